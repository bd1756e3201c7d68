#pragma once
// The crash-safe record of a sweep's finished runs: DIR/journal.jsonl, one JSON object per line (run_record.hpp),
// appended and fdatasync'ed per batch. A kill -9 can only tear the last line, which the next start cuts off; every
// earlier line is a finished run that a resume skips, and results.h5 is rebuilt from these lines on every start
// (the HDF5 file itself is not crash-safe while it is being appended to).
#include <string>
#include <vector>

#include "sweep/run_record.hpp"

namespace centaur::sweep {

class Journal {
 public:
  /// Opens (creates) `path`; reads its records (a torn last line is cut off); InputError naming the line if an
  /// earlier line is not a record, a run is out of [0, runs) or appears twice.
  Journal(const std::string& path, std::size_t runs);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  /// The records found when it was opened, in file order.
  const std::vector<RunRecord>& records() const { return records_; }
  /// Appends one line per record and waits until they are on disk (RuntimeError on failure).
  void append(const std::vector<RunRecord>& records);

 private:
  std::string path_;
  int fd_ = -1;
  std::vector<RunRecord> records_;
};

}  // namespace centaur::sweep
