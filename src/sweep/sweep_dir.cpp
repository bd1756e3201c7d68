#include "sweep/sweep_dir.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace centaur::sweep {

namespace fs = std::filesystem;

namespace {

std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The first line where two texts differ, for the message.
std::string firstDifference(const std::string& a, const std::string& b) {
  std::size_t line = 1, start = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    if (a[i] != b[i]) break;
    if (a[i] == '\n') {
      ++line;
      start = i + 1;
    }
  }
  const std::size_t end = a.find('\n', start);
  return "line " + std::to_string(line) + ": '" + a.substr(start, end == std::string::npos ? end : end - start) + "'";
}

}  // namespace

bool checkSweepDir(const std::string& dir, const std::string& canonical_spec) {
  std::error_code ec;
  const fs::path d(dir);
  if (!fs::exists(d, ec)) return false;
  if (!fs::is_directory(d, ec)) throw InputError("--out " + dir + ": exists and is not a directory");
  const fs::path spec = d / "sweep.yaml";
  if (!fs::exists(spec, ec)) {
    if (fs::directory_iterator(d, ec) != fs::directory_iterator()) {
      throw InputError("--out " + dir + ": a non-empty directory that holds no sweep (no sweep.yaml); give a new or "
                       "empty directory");
    }
    return false;
  }
  const std::string old = readText(spec);
  if (old != canonical_spec) {
    throw InputError("--out " + dir + ": holds a different sweep (its sweep.yaml differs from this spec at " +
                     firstDifference(old, canonical_spec) +
                     "); give a new directory, or the same spec to resume it");
  }
  return true;
}

SweepDir::SweepDir(const std::string& dir, const std::string& canonical_spec) : dir_(dir) {
  resumed_ = checkSweepDir(dir, canonical_spec);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw RuntimeError("cannot create " + dir + ": " + ec.message());
  const std::string lock = path(".lock");
  lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) throw RuntimeError("cannot open " + lock + ": " + std::strerror(errno));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw InputError("--out " + dir + ": another sweep is running in this directory (" + lock + " is locked)");
  }
  // Temporaries of a killed sweep (an output being written, "<name>.tmp.<pid>"): no one else writes here now.
  for (const fs::path& d : {fs::path(dir), fs::path(dir) / "plans"}) {
    for (const auto& e : fs::directory_iterator(d, ec)) {
      if (e.path().filename().string().find(".tmp.") != std::string::npos) fs::remove(e.path(), ec);
    }
  }
  if (!resumed_) writeTextFileAtomic(path("sweep.yaml"), canonical_spec);
}

SweepDir::~SweepDir() {
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

std::string SweepDir::path(const std::string& name) const { return (fs::path(dir_) / name).string(); }

}  // namespace centaur::sweep
