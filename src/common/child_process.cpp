#include "common/child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/error.hpp"

extern char** environ;

namespace centaur {

namespace {

/// posix_spawn_file_actions_t released on scope exit.
struct FileActions {
  posix_spawn_file_actions_t a;
  FileActions() { posix_spawn_file_actions_init(&a); }
  ~FileActions() { posix_spawn_file_actions_destroy(&a); }
};

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const Options& o) {
  if (argv.empty()) throw RuntimeError("ChildProcess: no program");
  FileActions fa;
  int pipe_fds[2] = {-1, -1};
  if (o.pipe_stdin) {
    if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw RuntimeError(std::string("cannot create a pipe: ") + std::strerror(errno));
    posix_spawn_file_actions_adddup2(&fa.a, pipe_fds[0], 0);  // dup2 clears close-on-exec on fd 0
  } else {
    posix_spawn_file_actions_addopen(&fa.a, 0, "/dev/null", O_RDONLY, 0);
  }
  if (!o.output_file.empty()) {
    posix_spawn_file_actions_addopen(&fa.a, 1, o.output_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&fa.a, 1, 2);
  }
  if (!o.working_directory.empty()) posix_spawn_file_actions_addchdir_np(&fa.a, o.working_directory.c_str());
  std::vector<std::string> args = argv;
  std::vector<char*> ptrs;
  for (std::string& s : args) ptrs.push_back(s.data());
  ptrs.push_back(nullptr);
  const int rc = posix_spawnp(&pid_, args[0].c_str(), &fa.a, nullptr, ptrs.data(), environ);
  if (o.pipe_stdin) ::close(pipe_fds[0]);
  if (rc != 0) {
    if (o.pipe_stdin) ::close(pipe_fds[1]);
    pid_ = -1;
    if (rc == ENOENT && !o.missing_hint.empty()) throw RuntimeError(o.missing_hint);
    throw RuntimeError("cannot start " + argv[0] + ": " + std::strerror(rc));
  }
  registration_ = cleanup::child(pid_);
  if (o.pipe_stdin) {
    input_ = ::fdopen(pipe_fds[1], "w");
    if (input_ == nullptr) {
      ::close(pipe_fds[1]);
      throw RuntimeError("cannot open the pipe to " + argv[0]);
    }
  }
}

ChildProcess::~ChildProcess() {
  if (input_ != nullptr) std::fclose(input_);
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
}

bool ChildProcess::closeInput() {
  if (input_ == nullptr) return true;
  const bool ok = std::fclose(input_) == 0;
  input_ = nullptr;
  return ok;
}

int ChildProcess::wait() {
  closeInput();
  if (pid_ <= 0) return -1;
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0) {
    if (errno == ECHILD) {  // already killed and reaped by the cleanup (common/cleanup.hpp)
      pid_ = -1;
      registration_.release();
      return 128 + SIGKILL;
    }
    if (errno != EINTR) throw RuntimeError(std::string("waiting for a child process failed: ") + std::strerror(errno));
  }
  pid_ = -1;
  registration_.release();
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

}  // namespace centaur
