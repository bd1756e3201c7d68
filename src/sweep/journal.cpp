#include "sweep/journal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <set>

#include "common/error.hpp"

namespace centaur::sweep {

namespace {

std::string readAll(int fd, const std::string& path) {
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw RuntimeError("cannot read " + path + ": " + std::strerror(errno));
    if (n == 0) break;
    text.append(buf, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace

Journal::Journal(const std::string& path, std::size_t runs) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw RuntimeError("cannot open " + path + ": " + std::strerror(errno));
  const std::string text = readAll(fd_, path);
  const std::size_t complete = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
  std::set<std::int64_t> seen;
  std::size_t line = 0;
  for (std::size_t begin = 0; begin < complete;) {
    const std::size_t end = text.find('\n', begin);
    ++line;
    const std::string where = path + " line " + std::to_string(line);
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(text.substr(begin, end - begin));
    } catch (const nlohmann::json::exception&) {
      throw InputError(where + ": not JSON (the journal was edited?)");
    }
    RunRecord r = recordFromJson(j, where);
    if (r.run < 0 || static_cast<std::size_t>(r.run) >= runs) {
      throw InputError(where + ": run " + std::to_string(r.run) + " is not a run of this sweep");
    }
    if (!seen.insert(r.run).second) throw InputError(where + ": run " + std::to_string(r.run) + " appears twice");
    records_.push_back(std::move(r));
    begin = end + 1;
  }
  // A torn last line (killed while writing): cut it off; appending continues after the last whole record.
  if (complete < text.size() && ::ftruncate(fd_, static_cast<off_t>(complete)) != 0) {
    throw RuntimeError("cannot truncate " + path + ": " + std::strerror(errno));
  }
  if (::lseek(fd_, static_cast<off_t>(complete), SEEK_SET) < 0) {
    throw RuntimeError("cannot seek in " + path + ": " + std::strerror(errno));
  }
}

Journal::~Journal() {
  if (fd_ >= 0) ::close(fd_);
}

void Journal::append(const std::vector<RunRecord>& records) {
  if (records.empty()) return;
  std::string text;
  for (const RunRecord& r : records) text += toJson(r).dump() + "\n";
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw RuntimeError("cannot write " + path_ + ": " + std::strerror(errno));
    done += static_cast<std::size_t>(n);
  }
  if (::fdatasync(fd_) != 0) throw RuntimeError("cannot flush " + path_ + ": " + std::strerror(errno));
}

}  // namespace centaur::sweep
