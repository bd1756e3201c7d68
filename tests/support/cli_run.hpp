#pragma once
// Run the `centaur` command in a test: `run("plan squat-jump --out F.h5")` -> exit code, output, last line.
// The including test target defines CENTAUR_BIN (the executable's path; see tests/cli/CMakeLists.txt).
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace centaur_test {

struct CliRun {
  int code = 0;
  std::string out;        ///< stdout (+ stderr when merged)
  std::string last_line;  ///< the last line of out (trailing newlines dropped)
};

/// Runs `CENTAUR_BIN args`; stderr goes into out (merge_stderr) or to /dev/null. With `timeout_s` > 0 the command
/// is stopped after that many seconds (exit code 124: it hung).
inline CliRun run(const std::string& args, bool merge_stderr = true, int timeout_s = 0) {
  const std::string prefix = timeout_s > 0 ? "timeout " + std::to_string(timeout_s) + " " : std::string();
  const std::string cmd = prefix + std::string(CENTAUR_BIN) + " " + args + (merge_stderr ? " 2>&1" : " 2>/dev/null");
  FILE* p = popen(cmd.c_str(), "r");
  CliRun r;
  if (p == nullptr) {
    r.code = -1;
    return r;
  }
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), p)) r.out += buf.data();
  // The last line from the whole output: a line longer than the read buffer (a JSON summary) arrives in pieces.
  std::string::size_type end = r.out.size();
  while (end > 0 && r.out[end - 1] == '\n') --end;
  const std::string::size_type begin = r.out.rfind('\n', end == 0 ? 0 : end - 1);
  r.last_line = r.out.substr(begin == std::string::npos ? 0 : begin + 1);
  const int status = pclose(p);
  r.code = WEXITSTATUS(status);
  return r;
}

}  // namespace centaur_test
