#pragma once
// One run of a sweep, in-process: exactly `centaur simulate <jump> --primitive DB --primitive-group <point's
// group> --stabilizer <mode> [--flywheel F] --set <simulation.set> --set <sampled values> --set sensors.seed=<s>`
// (sim::runScenario; its own configuration, MuJoCo model, robot and controller, so runs may go to threads), and
// the command that replays it alone.
#include <string>
#include <vector>

#include "data/primitive_database.hpp"
#include "sweep/run_record.hpp"
#include "sweep/sweep_spec.hpp"

namespace centaur::sweep {

/// What every run of a sweep needs (read-only; shared by the threads of a process).
struct RunContext {
  const SweepSpec* spec = nullptr;
  std::string primitives;          ///< the database file (primitives.h5, or a rank's local copy)
  std::string flywheel;            ///< arm-flywheel file for mode ocp ("" if no ocp mode)
  data::DatabaseIndex index;       ///< its grid points (group, plan status), in point order
};

/// Runs `run` and returns its record; never throws (a failure is the record's outcome "error").
RunRecord executeRun(const RunContext& ctx, std::size_t run);

/// The command line that replays `run` alone (`centaur simulate ...`, arguments shell-quoted), with the paths of
/// the database and the arm-flywheel file as given.
std::string replayCommand(const RunContext& ctx, std::size_t run);

}  // namespace centaur::sweep
