#pragma once
// Helpers of the middleware node tests: the robot and controller nodes as child processes on one DDS domain,
// their JSON summaries, and the primitives they replay (planned once per test binary).
// The including test defines CENTAUR_BIN.
#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <sys/file.h>
#include <unistd.h>

#include <memory>
#include <string>
#include <vector>

#include "support/child_process.hpp"
#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

namespace centaur_test {

/// A primitives file with both jumps with the default settings, planned once per build tree (about 6 s) into
/// CENTAUR_TEST_CACHE; tests running in parallel wait for the one that plans (flock). "" if planning failed.
inline const std::string& bothJumps() {
  static const std::string path = [] {
    const std::string dir = CENTAUR_TEST_CACHE;
    const std::string p = dir + "/node-primitives.h5";
    const int lock = ::open((dir + "/node-primitives.lock").c_str(), O_RDWR | O_CREAT, 0644);
    if (lock < 0 || ::flock(lock, LOCK_EX) != 0) return std::string();
    std::string result = p;
    if (::access(p.c_str(), R_OK) != 0) {
      const std::string tmp = dir + "/node-primitives.tmp.h5";
      if (run("plan squat-jump --quiet --out " + tmp).code != 0 ||
          run("plan half-squat-jump --quiet --append --out " + tmp).code != 0 || ::rename(tmp.c_str(), p.c_str()) != 0) {
        result.clear();
      }
    }
    ::flock(lock, LOCK_UN);
    ::close(lock);
    return result;
  }();
  return path;
}

inline std::vector<std::string> domainSet(int domain) {
  return {"--set", "middleware.domain=" + std::to_string(domain)};
}

inline std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

/// `centaur robot <task> --lockstep --json` (plus `extra`) on `domain`, output in dir/robot.log.
inline std::unique_ptr<ChildProcess> startRobot(const TempDir& dir, const std::string& task, int domain,
                                                const std::vector<std::string>& extra, const std::string& name = "robot") {
  return std::make_unique<ChildProcess>(
      CENTAUR_BIN, concat(concat({"robot", task, "--json"}, domainSet(domain)), extra), dir.file(name + ".log"));
}

/// `centaur control <task> --json` (plus `extra`) on `domain`, output in dir/<name>.log.
inline std::unique_ptr<ChildProcess> startControl(const TempDir& dir, const std::string& task, int domain,
                                                  const std::vector<std::string>& extra,
                                                  const std::string& name = "control") {
  return std::make_unique<ChildProcess>(
      CENTAUR_BIN, concat(concat({"control", task, "--json"}, domainSet(domain)), extra), dir.file(name + ".log"));
}

/// The JSON summary line of a finished node (empty object if it has none).
inline nlohmann::json summaryOf(const ChildProcess& p) {
  const std::string last = p.lastLine();
  if (last.empty() || last.front() != '{') return nlohmann::json::object();
  return nlohmann::json::parse(last, nullptr, false);
}

}  // namespace centaur_test
