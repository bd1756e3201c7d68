#pragma once
// External programs (gnuplot, ffmpeg) run WITHOUT a shell: the arguments go to the program as they are, so no
// file name or value can be read as shell syntax. The child is registered with common/cleanup.hpp: a signal
// that stops the command kills and reaps it before the temporaries it writes are removed.
#include <sys/types.h>

#include <cstdio>
#include <string>
#include <vector>

#include "common/cleanup.hpp"

namespace centaur {

class ChildProcess {
 public:
  struct Options {
    std::string working_directory;  ///< "" = the current one
    bool pipe_stdin = false;        ///< true: write to the child through input(); false: stdin is /dev/null
    std::string output_file;        ///< stdout and stderr go to this file; "" = inherited
    std::string missing_hint;       ///< the message when the program is not installed
  };

  /// Starts argv[0] (looked up on PATH) with the arguments argv[1..]. RuntimeError if it cannot start.
  ChildProcess(const std::vector<std::string>& argv, const Options& options);
  /// Kills (SIGKILL) and reaps a child that is still running.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  /// The pipe to the child's stdin (Options::pipe_stdin), nullptr once closed.
  std::FILE* input() { return input_; }
  /// Close the pipe (the child sees end of file); false if flushing failed.
  bool closeInput();
  /// Wait for the child to end: its exit status, or 128 + the signal that ended it.
  int wait();

 private:
  pid_t pid_ = -1;
  std::FILE* input_ = nullptr;
  cleanup::Registration registration_;
};

}  // namespace centaur
