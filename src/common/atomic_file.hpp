#pragma once
// Outputs are never half-written: write to a temporary sibling, then rename over the target.
#include <string>

namespace centaur {

/// A temporary path next to `target` (same directory, so rename is atomic).
std::string temporaryPathFor(const std::string& target);

/// Rename `tmp` to `target`; throws RuntimeError on failure (and removes `tmp`).
void commitFile(const std::string& tmp, const std::string& target);

/// Remove a file if it exists (no error if it does not).
void removeFileIfExists(const std::string& path);

/// Write `text` to `path` atomically.
void writeTextFileAtomic(const std::string& path, const std::string& text);

/// Create the parent directory of `path` if missing.
void ensureParentDirectory(const std::string& path);

}  // namespace centaur
