#pragma once
// The output directory of a sweep and its claim on it. DIR/sweep.yaml holds the canonical spec: a DIR whose
// sweep.yaml differs from the spec is refused (another sweep), one whose sweep.yaml matches is resumed. A DIR that
// is a file, or a non-empty directory without sweep.yaml, is refused too. While a sweep runs it holds an exclusive
// lock on DIR/.lock (flock: released by the kernel when the process dies, so a killed sweep never blocks its
// restart); a second sweep on the same DIR is refused.
#include <string>

namespace centaur::sweep {

/// InputError (CLI exit 2) if `dir` cannot hold the sweep `canonical_spec`; checks only, writes nothing.
/// Returns true if `dir` already holds this sweep (a resume).
bool checkSweepDir(const std::string& dir, const std::string& canonical_spec);

class SweepDir {
 public:
  /// checkSweepDir, then creates DIR, takes the lock (InputError if another sweep holds it), removes the
  /// temporaries a killed sweep left ("*.tmp.*") and writes DIR/sweep.yaml (atomically) if new.
  SweepDir(const std::string& dir, const std::string& canonical_spec);
  ~SweepDir();
  SweepDir(const SweepDir&) = delete;
  SweepDir& operator=(const SweepDir&) = delete;

  const std::string& dir() const { return dir_; }
  std::string path(const std::string& name) const;
  bool resumed() const { return resumed_; }

 private:
  std::string dir_;
  bool resumed_ = false;
  int lock_fd_ = -1;
};

}  // namespace centaur::sweep
