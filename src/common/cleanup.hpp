#pragma once
// Temporaries that must not outlive a command. Files, directories and child processes registered here are
// removed (killed) when the process exits through exit() (main returning included) and when it is stopped by
// SIGINT, SIGTERM, SIGHUP or SIGQUIT: the handler kills and reaps the children, unlinks the files, removes the
// (then empty) directories, and re-raises the signal with its default action, so the caller still sees the
// signal. The handler is async-signal-safe: it only reads fixed-size slots filled before the temporaries exist
// and calls kill, waitpid, unlink and rmdir.
//
// common/atomic_file.hpp registers every temporary it names (temporaryPathFor) and releases it when the file is
// committed or removed, so a writer that uses it is covered without a call of its own; main() calls install().
#include <sys/types.h>

#include <string>

namespace centaur::cleanup {

/// Install the signal handlers and the exit hook (idempotent, thread-safe).
void install();

/// One registered temporary. Releasing (or destroying) the registration forgets it without touching it.
class Registration {
 public:
  Registration() = default;
  Registration(Registration&& o) noexcept : slot_(o.slot_) { o.slot_ = -1; }
  Registration& operator=(Registration&& o) noexcept;
  Registration(const Registration&) = delete;
  Registration& operator=(const Registration&) = delete;
  ~Registration() { release(); }
  void release();

 private:
  friend Registration file(const std::string&);
  friend Registration directory(const std::string&);
  friend Registration child(pid_t);
  friend Registration flatDirectory(const std::string&);
  explicit Registration(int slot) : slot_(slot) {}
  int slot_ = -1;
};

/// Unlink `path` if the process ends while registered. Register BEFORE creating the file.
Registration file(const std::string& path);
/// rmdir `path` (succeeds only once empty) if the process ends while registered.
Registration directory(const std::string& path);
/// Unlink every entry of the directory `path` (one level: a staging directory of files), then rmdir it.
Registration flatDirectory(const std::string& path);
/// SIGKILL and reap the child process `pid` if the process ends while registered.
Registration child(pid_t pid);

/// Path-keyed form for APIs that hand out names (atomic_file.hpp): register `path` as a file; forget it again.
void addFile(const std::string& path);
void forgetFile(const std::string& path);

/// Run the cleanup now (what the exit hook and the handler do); for tests.
void runNow();

}  // namespace centaur::cleanup
