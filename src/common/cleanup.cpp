#include "common/cleanup.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace centaur::cleanup {

namespace {

enum Kind : int { kFile = 0, kDirectory = 1, kChild = 2, kFlatDirectory = 3 };

// A slot is written only under the registry mutex; the signal handler reads it lock-free, guarded by the
// slot's sequence number (odd while being written): a slot that changes under the handler is skipped.
struct Slot {
  std::atomic<unsigned> sequence{0};
  std::atomic<bool> active{false};
  int kind = kFile;
  pid_t pid = 0;
};

constexpr int kSlots = 256;
// The paths apart from the slots: a pass over the slots (every exit sweeps them) then reads one page, not one
// page per slot (~7 us per first touch on a virtual machine).
Slot g_slots[kSlots];
char g_paths[kSlots][PATH_MAX];
std::mutex g_mutex;
std::atomic<bool> g_dying{false};
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

int claim(int kind, const std::string& path, pid_t pid) {
  if (path.size() >= PATH_MAX) return -1;  // the system refuses such a path anyway
  std::lock_guard<std::mutex> lock(g_mutex);
  if (g_dying.load()) return -1;
  for (int i = 0; i < kSlots; ++i) {
    Slot& s = g_slots[i];
    if (s.active.load(std::memory_order_relaxed)) continue;
    s.sequence.fetch_add(1, std::memory_order_acq_rel);  // odd: being written
    s.kind = kind;
    s.pid = pid;
    std::memcpy(g_paths[i], path.c_str(), path.size() + 1);
    s.active.store(true, std::memory_order_release);
    s.sequence.fetch_add(1, std::memory_order_acq_rel);  // even: stable
    return i;
  }
  return -1;  // full: the temporary is simply not tracked
}

void releaseSlot(int i) {
  if (i < 0) return;
  std::lock_guard<std::mutex> lock(g_mutex);
  Slot& s = g_slots[i];
  s.sequence.fetch_add(1, std::memory_order_acq_rel);
  s.active.store(false, std::memory_order_release);
  s.sequence.fetch_add(1, std::memory_order_acq_rel);
}

/// Unlink every entry of a directory, then the directory: raw getdents64, no allocation (signal-safe).
void removeFlatDirectory(const char* path) {
  const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  alignas(8) char buf[4096];
  for (;;) {
    const long n = ::syscall(SYS_getdents64, fd, buf, sizeof buf);
    if (n <= 0) break;
    for (long off = 0; off < n;) {
      const auto* d = reinterpret_cast<const struct dirent64*>(buf + off);
      const char* name = d->d_name;
      if (!(name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0')))) ::unlinkat(fd, name, 0);
      off += d->d_reclen;
    }
  }
  ::close(fd);
  ::rmdir(path);
}

/// One pass over the slots of `kind`: only async-signal-safe calls.
void sweep(int kind) {
  for (int i = 0; i < kSlots; ++i) {
    const Slot& s = g_slots[i];
    const unsigned before = s.sequence.load(std::memory_order_acquire);
    if ((before & 1U) != 0 || !s.active.load(std::memory_order_acquire) || s.kind != kind) continue;
    char path[PATH_MAX];
    std::memcpy(path, g_paths[i], sizeof path);
    path[PATH_MAX - 1] = '\0';
    const pid_t pid = s.pid;
    if (s.sequence.load(std::memory_order_acquire) != before) continue;  // changed while read
    if (kind == kChild && pid > 0) {
      ::kill(pid, SIGKILL);
      int status = 0;
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
    } else if (kind == kFile) {
      ::unlink(path);
    } else if (kind == kDirectory) {
      ::rmdir(path);
    } else if (kind == kFlatDirectory) {
      removeFlatDirectory(path);
    }
  }
}

void sweepAll() {
  sweep(kChild);  // first stop the writers
  sweep(kFile);
  sweep(kFlatDirectory);
  for (int pass = 0; pass < 4; ++pass) sweep(kDirectory);  // nested directories: innermost first
}

extern "C" void centaurCleanupOnSignal(int sig) {
  const int saved_errno = errno;
  g_dying.store(true);
  sweepAll();
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  errno = saved_errno;
  ::raise(sig);  // default action: the process ends with the signal, as without the handler
}

extern "C" void centaurCleanupOnExit() { runNow(); }

}  // namespace

Registration& Registration::operator=(Registration&& o) noexcept {
  if (this != &o) {
    release();
    slot_ = o.slot_;
    o.slot_ = -1;
  }
  return *this;
}

void Registration::release() {
  releaseSlot(slot_);
  slot_ = -1;
}

Registration file(const std::string& path) { return Registration(claim(kFile, path, 0)); }
Registration directory(const std::string& path) { return Registration(claim(kDirectory, path, 0)); }
Registration flatDirectory(const std::string& path) { return Registration(claim(kFlatDirectory, path, 0)); }
Registration child(pid_t pid) { return Registration(claim(kChild, std::to_string(pid), pid)); }

void addFile(const std::string& path) { claim(kFile, path, 0); }

void forgetFile(const std::string& path) {
  std::lock_guard<std::mutex> lock(g_mutex);
  for (int i = 0; i < kSlots; ++i) {
    Slot& s = g_slots[i];
    if (!s.active.load(std::memory_order_relaxed) || s.kind != kFile || path != g_paths[i]) continue;
    s.sequence.fetch_add(1, std::memory_order_acq_rel);
    s.active.store(false, std::memory_order_release);
    s.sequence.fetch_add(1, std::memory_order_acq_rel);
    return;
  }
}

void runNow() {
  std::lock_guard<std::mutex> lock(g_mutex);
  sweepAll();
  for (Slot& s : g_slots) {
    s.sequence.fetch_add(1, std::memory_order_acq_rel);
    s.active.store(false, std::memory_order_release);
    s.sequence.fetch_add(1, std::memory_order_acq_rel);
  }
}

void install() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : kSignals) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;  // keep an ignored signal ignored
      struct sigaction sa {};
      sa.sa_handler = centaurCleanupOnSignal;
      sigemptyset(&sa.sa_mask);
      for (int other : kSignals) sigaddset(&sa.sa_mask, other);  // one handler at a time
      ::sigaction(sig, &sa, nullptr);
    }
    std::atexit(centaurCleanupOnExit);
  });
}

}  // namespace centaur::cleanup
