#include "cli/bench_middleware.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "common/error.hpp"
#include "common/stats.hpp"
#include "data/primitive_io.hpp"
#include "planner/jump_problem.hpp"
#include "robot_node/robot_node.hpp"

namespace centaur::cli {

namespace {

/// centaur-control as a child process (output discarded); killed if still running when destroyed.
class ControlChild {
 public:
  explicit ControlChild(std::vector<std::string> args) {
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    args.insert(args.begin(), (self.parent_path() / "centaur-control").string());
    pid_ = ::fork();
    if (pid_ == 0) {
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, 1);
      ::dup2(null, 2);
      std::vector<char*> argv;
      for (std::string& s : args) argv.push_back(s.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    if (pid_ < 0) throw RuntimeError("bench middleware: cannot start centaur-control");
  }
  ~ControlChild() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
  ControlChild(const ControlChild&) = delete;
  ControlChild& operator=(const ControlChild&) = delete;

 private:
  pid_t pid_ = -1;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(std::min<double>(static_cast<double>(v.size()) - 1, p * static_cast<double>(v.size())));
  return v[k];
}

/// Where both nodes run: a private DDS domain and a scheduling priority (0 = normal).
struct PairSetup {
  int domain = 0;
  int realtime_priority = 0;
};

robot_node::RobotNodeResult runPair(const std::string& task, bool lockstep, double duration, const PairSetup& setup,
                                    std::vector<std::string> control_args, std::size_t record) {
  const std::string dom = "middleware.domain=" + std::to_string(setup.domain);
  const std::string prio = "middleware.realtime_priority=" + std::to_string(setup.realtime_priority);
  control_args.insert(control_args.begin(), {task, "--set", dom, "--set", prio});
  ControlChild control(control_args);
  robot_node::RobotNodeArgs a;
  a.task = task;
  a.lockstep = lockstep;
  a.overrides = {"duration=" + std::to_string(duration), dom, prio};
  a.record_round_trips = record;
  return robot_node::runRobotNode(a);
}

std::string jumpsFile(const std::string& given, std::string& tmp) {
  if (!given.empty()) return given;
  std::fprintf(stderr, "  planning the squat jump with the defaults (give --primitives P.h5 to reuse one) ...\n");
  const planner::JumpProblem problem(planner::loadJumpConfig("squat-jump", "", {}));
  tmp = (std::filesystem::temp_directory_path() / ("centaur-bench-" + std::to_string(::getpid()) + ".h5")).string();
  data::writePrimitive(tmp, problem.toPrimitive(problem.solve(false)));
  return tmp;
}

}  // namespace

nlohmann::json benchMiddleware(const std::string& primitives, int realtime_priority) {
  PairSetup setup;
  setup.domain = 200 + static_cast<int>(::getpid() % 30);  // a private domain, away from the default 0
  setup.realtime_priority = realtime_priority;
  nlohmann::json out;
  out["realtime_priority"] = realtime_priority;
  std::fprintf(stderr, "bench middleware: lockstep stand 5 s (round trips) ...\n");
  const auto rt = runPair("stand", true, 5.0, setup, {}, 10000);
  const std::vector<double>& v = rt.remote.round_trip_us;
  out["round_trip_us"] = {{"samples", v.size()},          {"p50", percentile(v, 0.5)},
                          {"p99", percentile(v, 0.99)},   {"max", v.empty() ? 0.0 : *std::max_element(v.begin(), v.end())}};
  out["lockstep_stand_real_time_factor"] = rt.summary.real_time_factor;
  std::fprintf(stderr, "  round trip p50 %.1f us, p99 %.1f us, max %.1f us (%zu samples)\n",
               out["round_trip_us"]["p50"].get<double>(), out["round_trip_us"]["p99"].get<double>(),
               out["round_trip_us"]["max"].get<double>(), v.size());
  std::fprintf(stderr, "bench middleware: realtime stand 10 s ...\n");
  const auto live = runPair("stand", false, 10.0, setup, {}, 0);
  out["realtime_stand"] = {{"control_periods", live.summary.control_periods},
                           {"late_periods", live.remote.late_periods},
                           {"watchdog_trips", live.remote.watchdog_trips},
                           {"outcome", live.summary.outcome}};
  std::fprintf(stderr, "  %ld periods, %llu late, %llu watchdog trips\n", live.summary.control_periods,
               static_cast<unsigned long long>(live.remote.late_periods),
               static_cast<unsigned long long>(live.remote.watchdog_trips));
  std::string tmp;
  const std::string file = jumpsFile(primitives, tmp);
  std::fprintf(stderr, "bench middleware: lockstep squat jump (raibert) ...\n");
  const auto jump = runPair("squat-jump", true, 5.0, setup,
                            {"--primitive", file, "--stabilizer", "raibert", "--start-after", "0.5"}, 0);
  if (!tmp.empty()) std::filesystem::remove(tmp);
  out["lockstep_squat_jump"] = {{"outcome", jump.summary.outcome},
                                {"real_time_factor", jump.summary.real_time_factor},
                                {"peak_pitch_deg", jump.summary.peak_pitch_deg}};
  std::fprintf(stderr, "  %s, real-time factor %.2f\n", jump.summary.outcome.c_str(), jump.summary.real_time_factor);
  return out;
}

}  // namespace centaur::cli
