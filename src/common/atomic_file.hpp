#pragma once
// Outputs are never half-written: write to a temporary sibling, then rename over the target.
#include <string>
#include <vector>

#include "common/cleanup.hpp"

namespace centaur {

/// A temporary path next to `target` (same directory, so rename is atomic): `<target>.tmp.<pid>`. It is
/// registered with common/cleanup.hpp, so it is removed if the process exits or is stopped by a signal before
/// commitFile() or removeFileIfExists() releases it.
std::string temporaryPathFor(const std::string& target);

/// Rename `tmp` to `target`; throws RuntimeError on failure (and removes `tmp`).
void commitFile(const std::string& tmp, const std::string& target);

/// Remove a file if it exists (no error if it does not); releases its cleanup registration.
void removeFileIfExists(const std::string& path);

/// Write `text` to `path` atomically.
void writeTextFileAtomic(const std::string& path, const std::string& text);

/// Create the parent directory of `path` if missing.
void ensureParentDirectory(const std::string& path);

/// The outputs of one command that appear together or not at all (e.g. the files of `compare --out DIR`): each
/// is written into a private staging directory `DIR/.tmp.<pid>` (registered with common/cleanup.hpp, so a
/// signal removes it) and commit() moves every file it holds into DIR. Without commit() (bad input, an
/// exception) the staging directory is removed with its contents, and DIR too if it was created for it and is
/// empty: nothing is written.
class StagedOutputs {
 public:
  explicit StagedOutputs(std::string dir);
  ~StagedOutputs();
  StagedOutputs(const StagedOutputs&) = delete;
  StagedOutputs& operator=(const StagedOutputs&) = delete;

  const std::string& dir() const { return dir_; }
  /// Where to write the output named `name` (a file name inside DIR) now.
  std::string path(const std::string& name) const;
  /// The path of the output `name` once committed: DIR/name.
  std::string finalPath(const std::string& name) const;
  /// Move every file of the staging directory into DIR (each one atomically, by rename) and remove the
  /// staging directory; returns the final paths. RuntimeError if a move fails.
  std::vector<std::string> commit();

 private:
  std::string dir_, staging_;
  bool created_dir_ = false, committed_ = false;
  cleanup::Registration dir_registration_, staging_registration_;
};

}  // namespace centaur
