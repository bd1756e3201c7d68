#pragma once
// A batch of independent simulation runs (scenario + options + outputs), executed in-process on a small
// thread pool: what `centaur compare` uses to run every (jump, stabilizer) pair.
//
// Thread safety: every run builds its own SimConfig, MujocoRobot (own mjModel/mjData) and controller through
// runScenario(); the scenario registry is only read. Nothing in sim/controller/qp/model holds mutable global
// state (the planner's reverse-mode AD tape is thread_local), HDF5 is Debian's thread-safe build
// (libhdf5.settings: Threadsafety yes), and MuJoCo is thread-safe per mjData; its XML loader keeps the last
// parsed model in a global for mj_saveLastXML, guarded by a mutex in 2.x (libmujoco 2.2.2 links
// pthread_mutex_lock; tests/sim/test_compare_runner.cpp and tests/cli/test_compare_cli.cpp load models
// concurrently and compare with serial runs). What is NOT thread-safe is Ipopt with MUMPS (Fortran SAVE state):
// runs that may solve an OCP while they run share an exclusive_group, and runs of the same group never overlap.
#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "sim/sim_runner.hpp"

namespace centaur::sim {

/// One run of the batch.
struct BatchRun {
  std::string label;                           ///< for messages, e.g. "squat-jump/raibert"
  std::string scenario;                        ///< a registered scenario name (findScenario)
  std::map<std::string, std::string> options;  ///< scenario options (as `--<name> VALUE` of simulate)
  std::vector<std::string> overrides;          ///< configuration overrides "key=value" (as `--set`)
  std::string config_file;                     ///< scenario configuration file; "" = defaults
  RunOutputs outputs;                          ///< log/video/snapshot of this run ("" = none)
  std::string exclusive_group;                 ///< runs sharing a non-empty group never run at the same time
};

/// What became of one run.
struct BatchResult {
  enum class Status {
    NotRun,          ///< never started
    Completed,       ///< ran to its end (a fall is an outcome in summary.outcome, not a failure)
    BadInput,        ///< InputError (unknown scenario, bad option/override, unreadable primitive, ...)
    RuntimeFailure,  ///< RuntimeError or any other exception (I/O, simulator)
  };
  Status status = Status::NotRun;
  std::string error;        ///< the exception's message when not Completed
  RunSummary summary;       ///< valid when Completed
  double elapsed_s = 0.0;   ///< [s] wall time of the whole run (setup, loop and writing outputs)
};

/// Called (serialised: never concurrently, from the worker threads) when run `index` starts / ends; must not throw.
struct BatchCallbacks {
  std::function<void(std::size_t index)> started;
  std::function<void(std::size_t index, const BatchResult& result, std::size_t done, std::size_t total)> finished;
};

/// Worker threads to use for `runs` runs when `jobs` were asked for (jobs <= 0: hardware concurrency);
/// at least 1, at most max(runs, 1).
int batchThreads(int jobs, std::size_t runs);

/// Run every run of `runs` on batchThreads(jobs, runs.size()) threads, in list order as threads free up.
/// Never throws for a failing run: its status and message are in its result (results[i] belongs to runs[i]).
std::vector<BatchResult> runBatch(const std::vector<BatchRun>& runs, int jobs, const BatchCallbacks& callbacks = {});

}  // namespace centaur::sim
