#pragma once
// DIR/results.h5: one row per finished run in the table `runs` (data/hdf5_table.hpp; schema in docs/sweeps.md):
// the run's identity (run, point, group, jump, mode, seed_index, seed), its grid point's parameters (one column per
// planner axis), its sampled perturbation (one column per value), its outcome and metrics (run_record.hpp) and the
// error message of a failed run. Rows are in the order the runs finished; `run` identifies them.
// Root attributes: kind = "sweep-results", format_version = 1, sweep_spec (the canonical spec).
#include <string>
#include <vector>

#include "data/hdf5.hpp"
#include "data/hdf5_table.hpp"
#include "data/primitive_database.hpp"
#include "sweep/run_record.hpp"
#include "sweep/sweep_spec.hpp"

namespace centaur::sweep {

inline constexpr int kResultsFormatVersion = 1;

/// The columns of the results table of `spec`.
std::vector<data::h5::Column> resultsColumns(const SweepSpec& spec);
/// The rows of `records` (grid point values from `index`, perturbations re-derived from the spec).
data::h5::Table resultsRows(const SweepSpec& spec, const data::DatabaseIndex& index,
                            const std::vector<RunRecord>& records);

class ResultsFile {
 public:
  /// Writes `path` afresh with `records` (temporary sibling, renamed), then keeps it open for appending.
  ResultsFile(const std::string& path, const SweepSpec& spec, const data::DatabaseIndex& index,
              const std::vector<RunRecord>& records);
  /// Appends one row per record and flushes the file (RuntimeError on failure).
  void append(const std::vector<RunRecord>& records);
  /// Flushes and closes (also done by the destructor, without throwing).
  void close();
  ~ResultsFile();
  ResultsFile(const ResultsFile&) = delete;
  ResultsFile& operator=(const ResultsFile&) = delete;

 private:
  std::string path_;
  const SweepSpec& spec_;
  const data::DatabaseIndex& index_;
  data::h5::Id file_;
};

/// The `runs` table of a results file (InputError naming the file if it is not one).
data::h5::Table readResults(const std::string& path);

}  // namespace centaur::sweep
