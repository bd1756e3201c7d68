#pragma once
// Input files are regular files: a FIFO would block the command until some writer appears, a device could
// stream forever, a directory is a mistake. Every reader of a named input goes through these checks before it
// opens anything (InputError naming the file, CLI exit code 2).
#include <cstddef>
#include <string>

namespace centaur {

/// InputError unless `path` names an existing regular file (symlinks followed). `what` completes the message
/// of a missing file, e.g. "a YAML configuration".
void requireRegularFile(const std::string& path, const std::string& what);

/// The whole content of the regular file `path`, at most `max_bytes` long (InputError naming the file and the
/// limit otherwise). The file is opened non-blocking and checked through its descriptor, so a FIFO put in its
/// place after a check cannot block the read.
std::string readSmallFile(const std::string& path, std::size_t max_bytes, const std::string& what);

}  // namespace centaur
