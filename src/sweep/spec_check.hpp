#pragma once
// The checks of a sweep spec against the planner's and the simulator's own configuration readers: every planner
// key and value of every grid point, every simulation override and the extreme values of every perturbation go
// through the same strict readers as `centaur plan` / `centaur simulate` (nothing is planned or simulated).
#include <string>
#include <vector>

#include "sweep/sweep_spec.hpp"

namespace centaur::sweep {

/// The shape of a simulation key's value, from the documented defaults of the jump scenarios.
struct SimKeyShape {
  int size = 1;          ///< 1: a scalar; n: a list of n numbers
  bool integer = false;  ///< an integer scalar (e.g. sensors.latency_periods)
};

/// InputError(spec.file, "simulation.perturb.<key>") if `key` has no documented default or is a section.
SimKeyShape simKeyShape(const SweepSpec& spec, const std::string& key);

/// The planner overrides of grid point `point` ("key=value", planner.set first, then the axes).
std::vector<std::string> plannerOverrides(const SweepSpec& spec, std::size_t point);
/// The grid point's jump and axis values.
const std::string& pointJump(const SweepSpec& spec, std::size_t point);
std::vector<data::GridValue> pointValues(const SweepSpec& spec, std::size_t point);

/// Every grid point's planner configuration parses (InputError naming planner.set / planner.axes.<key>).
void checkPlanner(const SweepSpec& spec);
/// The simulation overrides and every perturbation's extreme values parse for every jump scenario, the
/// controller section included (InputError naming simulation.set.<key> / simulation.perturb.<key>).
void checkSimulation(const SweepSpec& spec);

}  // namespace centaur::sweep
