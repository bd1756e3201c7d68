#include "common/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "common/error.hpp"
#include "common/excerpt.hpp"

namespace centaur {

namespace {

/// The message for a path that exists but is not a regular file, "" for a regular file.
std::string kindProblem(const struct stat& st) {
  if (S_ISREG(st.st_mode)) return "";
  if (S_ISDIR(st.st_mode)) return "is a directory, not a file";
  if (S_ISFIFO(st.st_mode)) return "is a FIFO (named pipe), not a regular file";
  if (S_ISSOCK(st.st_mode)) return "is a socket, not a regular file";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "is a device, not a regular file";
  return "is not a regular file";
}

std::string label(const std::string& path) { return excerpt(path, 4 * kMaxExcerpt); }

}  // namespace

void requireRegularFile(const std::string& path, const std::string& what) {
  struct stat st {};
  if (path.empty()) throw InputError("empty file name (expected " + what + ")");
  if (::stat(path.c_str(), &st) != 0) {
    throw InputError(label(path) + ": " + (errno == ENOENT ? std::string("no such file") : std::strerror(errno)) +
                     " (expected " + what + ")");
  }
  const std::string problem = kindProblem(st);
  if (!problem.empty()) throw InputError(label(path) + ": " + problem + " (expected " + what + ")");
}

std::string readSmallFile(const std::string& path, std::size_t max_bytes, const std::string& what) {
  requireRegularFile(path, what);
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw InputError(label(path) + ": cannot open the file: " + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw InputError(label(path) + ": cannot stat the file: " + std::strerror(errno));
  const std::string problem = kindProblem(st);
  if (!problem.empty()) throw InputError(label(path) + ": " + problem + " (expected " + what + ")");
  if (static_cast<unsigned long long>(st.st_size) > max_bytes) {
    throw InputError(label(path) + ": " + std::to_string(st.st_size) + " bytes, more than the limit of " +
                     std::to_string(max_bytes) + " bytes for " + what);
  }
  // Read to the end (a file may grow after the stat), never more than the limit plus one byte.
  std::string text;
  std::size_t got = 0;
  for (;;) {
    if (text.size() < got + 65536) text.resize(std::min(got + 65536, max_bytes + 1));
    if (got >= text.size()) break;
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(label(path) + ": cannot read the file: " + std::strerror(errno));
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  if (got > max_bytes) {
    throw InputError(label(path) + ": more than the limit of " + std::to_string(max_bytes) + " bytes for " + what);
  }
  text.resize(got);
  return text;
}

}  // namespace centaur
