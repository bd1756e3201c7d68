#pragma once
// `centaur sweep SPEC.yaml --out DIR`: the whole sweep (docs/sweeps.md).
//   1. read and check the spec completely (InputError: exit 2, nothing written), check DIR (a different sweep:
//      exit 2), claim DIR (lock, sweep.yaml);
//   2. plan the database DIR/primitives.h5 (and DIR/arm-flywheel.h5 for mode ocp), resuming what a killed sweep
//      planned;
//   3. read the journal of finished runs, rebuild DIR/results.h5 from it, and run the others: on a pool of threads,
//      and under MPI on every rank (rank 0 dispatches dynamically and is the only writer); every batch of records
//      is appended to the journal (fdatasync) and to results.h5 (flushed) as it arrives;
//   4. DIR/summary.json, DIR/summary.md, the data of the heatmaps (DIR/heatmap-<x>-<y>.dat) and of the peak-pitch
//      histograms (DIR/peak-pitch.dat); the CLI draws them.
// Under MPI (the process was started by mpirun/srun) every rank calls runSweep: rank 0 reads the spec and writes
// DIR; the other ranks receive the spec and the plans from it (no shared file system needed).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sweep/summary.hpp"

namespace centaur::sweep {

struct SweepOptions {
  std::string spec;        ///< SPEC.yaml
  std::string out;         ///< DIR
  int jobs = 0;            ///< simulation threads per process; 0 = all cores without MPI, 1 per rank under MPI
  bool plan_only = false;  ///< stop after the database (and the arm-flywheel plan)
};

struct SweepReport {
  bool writer = true;          ///< false on MPI ranks other than 0 (they report nothing)
  int exit_code = 0;           ///< 0, or 4 if a run failed with an error
  std::string dir;
  std::size_t runs_total = 0, runs_before = 0, runs_now = 0;
  int ranks = 1, threads = 1;
  double wall_time_s = 0.0;        ///< the whole command
  double runs_wall_time_s = 0.0;   ///< the simulation phase
  double writer_time_s = 0.0;      ///< rank 0's time in the journal, results.h5 and progress lines
  std::vector<std::string> files;  ///< written (the heatmap PNGs are added by the CLI)
  Summary summary;
  std::vector<std::string> heatmap_data;   ///< DIR/heatmap-<x>-<y>.dat, one per summary.heatmaps entry
  std::string pitch_data;                  ///< DIR/peak-pitch.dat (summary.pitch)
};

/// Runs the sweep; see the header comment. Throws InputError (bad spec or DIR) and RuntimeError (I/O, MPI).
SweepReport runSweep(const SweepOptions& options);

}  // namespace centaur::sweep
