#pragma once
// The offline stage of a sweep: one primitive per grid point (planned exactly as `centaur plan <jump> --set
// <planner.set> --set <the point's axis values>` would, cold-started: correctness first), collected into the
// database DIR/primitives.h5 (data/primitive_database.hpp), and the arm-flywheel trajectory of mode ocp.
// Resumable: every point is first written to DIR/plans/<group>.h5 (atomically), which a restart reuses; a database
// whose index already matches the grid is kept as it is. Ipopt (MUMPS) is not thread-safe: planning runs on the
// calling thread only (rank 0 under MPI), before any simulation.
#include <string>

#include "data/primitive_database.hpp"
#include "sweep/sweep_dir.hpp"
#include "sweep/sweep_spec.hpp"

namespace centaur::sweep {

/// The grid of `spec` as a database index (group names, axis values; solve_status "not_run").
data::DatabaseIndex gridIndex(const SweepSpec& spec);

/// Plans what is missing and writes DIR/primitives.h5; returns its index. Progress lines go to stderr.
data::DatabaseIndex planDatabase(const SweepSpec& spec, const SweepDir& dir);

/// DIR/arm-flywheel.h5 (planned with its defaults unless present); returns its path.
std::string planFlywheel(const SweepDir& dir);

}  // namespace centaur::sweep
