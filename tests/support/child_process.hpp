#pragma once
// A program started in the background by a test (fork + execv), its stdout and stderr in a file, with
// kill/stop/continue and a bounded wait. The destructor kills what is still running (no process outlives the
// test).
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace centaur_test {

class ChildProcess {
 public:
  /// Starts `program` with `args` in `working_directory` ("" = the test's); its output goes to `log_path`. SIGINT
  /// and SIGTERM have their default actions in the child (a shell's background job would ignore SIGINT).
  ChildProcess(const std::string& program, const std::vector<std::string>& args, std::string log_path,
               const std::string& working_directory = "")
      : log_path_(std::move(log_path)) {
    std::vector<std::string> storage{program};
    storage.insert(storage.end(), args.begin(), args.end());
    pid_ = ::fork();
    if (pid_ == 0) {
      ::signal(SIGINT, SIG_DFL);
      ::signal(SIGTERM, SIG_DFL);
      if (!working_directory.empty() && ::chdir(working_directory.c_str()) != 0) ::_exit(127);
      const int fd = ::open(log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd >= 0) {
        ::dup2(fd, 1);
        ::dup2(fd, 2);
        ::close(fd);
      }
      std::vector<char*> argv;
      for (std::string& s : storage) argv.push_back(s.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
  }
  ~ChildProcess() {
    if (running()) {
      ::kill(pid_, SIGCONT);
      ::kill(pid_, SIGKILL);
      wait(10.0);
    }
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  bool running() const { return pid_ > 0 && !exited_; }
  void signal(int sig) const {
    if (running()) ::kill(pid_, sig);
  }

  /// Waits up to `timeout_s` for the exit; true if it exited (code() is then valid: the exit status, or 128 + the
  /// signal that ended it).
  bool wait(double timeout_s) {
    if (!running()) return exited_;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    for (;;) {
      int status = 0;
      const pid_t r = ::waitpid(pid_, &status, WNOHANG);
      if (r == pid_) {
        exited_ = true;
        code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        return true;
      }
      if (std::chrono::steady_clock::now() >= deadline) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  int code() const { return code_; }
  std::string output() const {
    std::ifstream in(log_path_);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  /// The last non-empty line of the output (the --json summary).
  std::string lastLine() const {
    std::istringstream in(output());
    std::string line, last;
    while (std::getline(in, line)) {
      if (!line.empty()) last = line;
    }
    return last;
  }

 private:
  std::string log_path_;
  pid_t pid_ = -1;
  bool exited_ = false;
  int code_ = -1;
};

}  // namespace centaur_test
