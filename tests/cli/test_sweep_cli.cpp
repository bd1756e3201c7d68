// ctest-labels: integration cli sweep
// `centaur sweep`, end to end on a small sweep (2 x 2 squat-jump plans, 2 modes, 3 perturbed runs each, 0.7 s
// runs): the same results.h5 content (every column but the two wall-clock ones, bit for bit) on 1 thread, on 2
// threads and under `mpirun -n 2`; a sweep killed with SIGKILL in the middle (threads, and every process of an MPI
// job) and started again ends with the same content and skips what was done; a different spec on its DIR is
// refused; the replay command printed for a failed run reproduces it alone (`simulate --select`); bad specs exit 2
// naming the key and write nothing. The database is planned once (--plan-only) and copied for each variant.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <thread>

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"
#include "sweep/results_file.hpp"
#include "sweep/run_record.hpp"
#include "sweep/sweep_spec.hpp"

namespace fs = std::filesystem;
using centaur_test::CliRun;
using centaur_test::run;

namespace {

const char* kSpec = R"(jumps: [squat-jump]
modes: [none, raibert]
seeds: 3
seed: 5
planner:
  axes:
    target.height: [0.85, 0.87]
    contact.mu: [0.5, 0.6]
simulation:
  set: {duration: 0.7, sensors.noise.gyro: 0.01}
  perturb:
    robot.mass_scale: {uniform: [0.9, 1.1]}
    robot.com_offset: {uniform: [-0.02, 0.02]}
    world.friction: {uniform: [0.5, 1.0]}
    sensors.latency_periods: {choice: [0, 1]}
    push.impulse: {uniform: [0, 20]}
    push.start: {uniform: [0.1, 0.5]}
)";
constexpr std::size_t kRuns = 24;

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t lines(const std::string& path) {
  const std::string t = readFile(path);
  return static_cast<std::size_t>(std::count(t.begin(), t.end(), '\n'));
}

std::string mpirun() {
  // Loopback and shared memory only (a sandbox may have no usable network); 2 ranks on any number of cores.
  return std::string("env OMPI_MCA_btl=self,vader mpirun --oversubscribe ") + (::geteuid() == 0 ? "--allow-run-as-root " : "") +
         "-n 2 ";
}

/// Starts `cmd` (through sh, in its own session) and returns its pid.
pid_t spawn(const std::string& cmd) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setsid();
    ::execl("/bin/sh", "sh", "-c", ("exec " + cmd).c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

/// The pids whose parent is `parent` (from /proc).
std::vector<pid_t> children(pid_t parent) {
  std::vector<pid_t> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::istringstream stat(readFile((e.path() / "stat").string()));
    std::string pid, comm, state;
    long ppid = 0;
    if (stat >> pid >> comm >> state >> ppid && ppid == parent) out.push_back(std::stoi(pid));
  }
  return out;
}

/// SIGKILL to `pid` and all its children at once (a crashed node), then reap it.
void killAll(pid_t pid) {
  std::vector<pid_t> all = children(pid);
  all.push_back(pid);
  for (pid_t p : all) ::kill(p, SIGKILL);
  ::waitpid(pid, nullptr, 0);
}

/// Waits until `n` runs are in the journal of `dir` (false after 300 s).
bool waitForRuns(const std::string& dir, std::size_t n) {
  for (int i = 0; i < 6000; ++i) {
    if (fs::exists(dir + "/journal.jsonl") && lines(dir + "/journal.jsonl") >= n) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

/// Waits until no process holds the lock of `dir` (the ranks of a killed MPI job may take a moment to go).
bool waitForUnlock(const std::string& dir) {
  for (int i = 0; i < 600; ++i) {
    const int fd = ::open((dir + "/.lock").c_str(), O_RDWR);
    const bool free = fd >= 0 && ::flock(fd, LOCK_EX | LOCK_NB) == 0;
    if (fd >= 0) ::close(fd);
    if (free) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

void copyDir(const std::string& from, const std::string& to) {
  fs::copy(from, to, fs::copy_options::recursive);
}

/// Every column but the wall-clock ones, rows sorted by run, bit for bit.
void expectSameResults(const std::string& a, const std::string& b) {
  using centaur::data::h5::Column;
  const auto ta = centaur::sweep::readResults(a + "/results.h5"), tb = centaur::sweep::readResults(b + "/results.h5");
  ASSERT_EQ(ta.rows(), kRuns) << a;
  ASSERT_EQ(tb.rows(), kRuns) << b;
  ASSERT_EQ(ta.columns().size(), tb.columns().size());
  auto order = [](const centaur::data::h5::Table& t) {
    std::vector<std::size_t> idx(t.rows());
    std::iota(idx.begin(), idx.end(), 0);
    const std::size_t run = t.find("run");
    std::sort(idx.begin(), idx.end(), [&](std::size_t x, std::size_t y) { return t.integer(x, run) < t.integer(y, run); });
    return idx;
  };
  const std::vector<std::size_t> oa = order(ta), ob = order(tb);
  std::size_t compared = 0;
  for (std::size_t c = 0; c < ta.columns().size(); ++c) {
    const std::string& name = ta.columns()[c].name;
    ASSERT_EQ(name, tb.columns()[c].name);
    if (name == "run_time_s" || name == "real_time_factor") continue;  // machine-dependent by nature
    for (std::size_t r = 0; r < kRuns; ++r) {
      const std::size_t i = oa[r], j = ob[r];
      switch (ta.columns()[c].type) {
        case Column::Type::kFloat64:
          EXPECT_EQ(std::memcmp(&ta.f64[c][i], &tb.f64[c][j], sizeof(double)), 0)
              << name << " of run " << r << ": " << ta.f64[c][i] << " vs " << tb.f64[c][j] << " (" << a << ", " << b << ")";
          break;
        case Column::Type::kInt64: EXPECT_EQ(ta.i64[c][i], tb.i64[c][j]) << name << " of run " << r; break;
        case Column::Type::kString: EXPECT_EQ(ta.str[c][i], tb.str[c][j]) << name << " of run " << r; break;
      }
      ++compared;
    }
  }
  EXPECT_GT(compared, kRuns * 20);
}

/// Runs a shell command line (stderr dropped); the last line of stdout is the JSON of --json.
CliRun shell(const std::string& cmd) {
  CliRun r;
  FILE* p = popen((cmd + " 2>/dev/null").c_str(), "r");
  if (p == nullptr) return r;
  char buf[4096];
  while (fgets(buf, sizeof buf, p)) r.out += buf;
  r.code = WEXITSTATUS(pclose(p));
  const auto nl = r.out.rfind('\n', r.out.empty() ? 0 : r.out.size() - 2);
  r.last_line = r.out.substr(nl == std::string::npos ? 0 : nl + 1);
  while (!r.last_line.empty() && r.last_line.back() == '\n') r.last_line.pop_back();
  return r;
}

/// `centaur sweep ARGS`, under mpirun -n 2 if `mpi`.
CliRun sweep(const std::string& args, bool mpi) {
  return shell((mpi ? mpirun() : std::string()) + CENTAUR_BIN + " sweep " + args);
}

nlohmann::json lastJson(const CliRun& r) {
  try {
    return nlohmann::json::parse(r.last_line);
  } catch (const std::exception&) {
    ADD_FAILURE() << "no JSON last line:\n" << r.out;
    return nlohmann::json::object();
  }
}

}  // namespace

TEST(SweepCli, SameResultsOnThreadsAndMpiAndAfterKill9) {
  const centaur_test::TempDir dir("sweep-cli");
  const std::string spec = dir.file("spec.yaml"), plans = dir.file("plans");
  std::ofstream(spec) << kSpec;
  // The sweeps' temporary files (an MPI worker's private copy of the plans) go under the test's directory: a
  // killed worker cannot remove its own, and the directory is removed with the test.
  const std::string tmp = dir.file("tmp");
  fs::create_directories(tmp);
  ::setenv("TMPDIR", tmp.c_str(), 1);
  CliRun r = run("sweep " + spec + " --out " + plans + " --plan-only", false);
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_TRUE(fs::exists(plans + "/primitives.h5"));
  EXPECT_FALSE(fs::exists(plans + "/journal.jsonl"));

  // 1 thread, 2 threads, 2 MPI ranks.
  const std::string a = dir.file("one-thread"), b = dir.file("two-threads"), c = dir.file("mpi");
  for (const auto& d : {a, b, c}) copyDir(plans, d);
  r = sweep(spec + " --out " + a + " --jobs 1 --json", false);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(lastJson(r)["runs_now"], kRuns);
  r = sweep(spec + " --out " + b + " --jobs 2 --json", false);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(lastJson(r)["threads"], 2);
  r = sweep(spec + " --out " + c + " --json", true);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(lastJson(r)["ranks"], 2);
  EXPECT_EQ(lastJson(r)["runs_now"], kRuns);
  expectSameResults(a, b);
  expectSameResults(a, c);
  for (const auto& e : fs::directory_iterator(tmp)) {
    EXPECT_EQ(e.path().filename().string().rfind("centaur-sweep-", 0), std::string::npos)
        << "a worker left its temporary copy: " << e.path();
  }

  // Killed in the middle, then started again: threads, then every process of an MPI job.
  const std::string d = dir.file("killed-threads"), e = dir.file("killed-mpi");
  copyDir(plans, d);
  copyDir(plans, e);
  for (const auto& [out, mpi] : {std::pair<std::string, bool>{d, false}, {e, true}}) {
    const std::string args = spec + " --out " + out + (mpi ? "" : " --jobs 2");
    const pid_t pid = spawn((mpi ? mpirun() : std::string()) + CENTAUR_BIN + " sweep " + args + " > " + out + ".log 2>&1");
    ASSERT_TRUE(waitForRuns(out, 4)) << readFile(out + ".log");
    killAll(pid);
    ASSERT_TRUE(waitForUnlock(out)) << "a process of the killed sweep is still running";
    const std::size_t done = lines(out + "/journal.jsonl");
    EXPECT_LT(done, kRuns) << "the sweep finished before it was killed: the test proves nothing";
    r = sweep(args + " --json", mpi);
    ASSERT_EQ(r.code, 0) << r.out;
    const nlohmann::json j = lastJson(r);
    EXPECT_GE(j["runs_before"].get<std::size_t>(), done) << "runs finished before the kill were run again";
    EXPECT_EQ(j["runs_before"].get<std::size_t>() + j["runs_now"].get<std::size_t>(), kRuns);
    expectSameResults(a, out);
  }

  // A different spec on an existing sweep's DIR: exit 2, nothing touched.
  const std::string journal = readFile(a + "/journal.jsonl");
  const std::string other = dir.file("other.yaml");
  std::string text = kSpec;
  text.replace(text.find("seed: 5"), 7, "seed: 6");
  std::ofstream(other) << text;
  r = run("sweep " + other + " --out " + a);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("different sweep"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("seed"), std::string::npos) << r.out;
  EXPECT_EQ(readFile(a + "/journal.jsonl"), journal);

  // Every run failed (0.7 s: no flight yet): its printed command replays it alone, to the last bit.
  const nlohmann::json summary = nlohmann::json::parse(readFile(a + "/summary.json"));
  ASSERT_EQ(summary["failed_runs"].size(), kRuns);
  const nlohmann::json failed = summary["failed_runs"][7];
  std::string replay = failed["command"].get<std::string>();
  ASSERT_EQ(replay.rfind("centaur simulate squat-jump --primitive ", 0), 0u) << replay;
  EXPECT_NE(replay.find("--select target.height="), std::string::npos) << replay;
  r = run(replay.substr(std::string("centaur ").size()) + " --json", false);
  ASSERT_EQ(r.code, 0) << replay << "\n" << r.out;
  const nlohmann::json alone = lastJson(r);
  const auto table = centaur::sweep::readResults(a + "/results.h5");
  std::size_t row = 0;
  while (table.integer(row, table.find("run")) != failed["run"].get<std::int64_t>()) ++row;
  for (const char* metric : {"peak_pitch_deg", "pitch_rms_deg", "max_torque_ratio", "apex_height_m"}) {
    EXPECT_EQ(alone[metric].get<double>(), table.number(row, table.find(metric))) << metric << "\n" << replay;
  }
  EXPECT_EQ(alone["outcome"], table.text(row, table.find("outcome")));
  EXPECT_EQ(alone["grid_point"]["group"], table.text(row, table.find("group")));

  // --select needs an axis of the database.
  r = run("simulate squat-jump --primitive " + a + "/primitives.h5 --select target.wall_height=0.2 --duration 0.1");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("target.wall_height"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("target.height, contact.mu"), std::string::npos) << r.out;  // the axes it has
  r = run("simulate squat-jump --select target.height=0.85 --duration 0.1");
  EXPECT_EQ(r.code, 2) << r.out;
  r = run("simulate squat-jump --primitive " + a + "/primitives.h5 --duration 0.1");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--select"), std::string::npos) << r.out;

  // results.h5 for Python users.
  const std::string py = "/usr/bin/python3 -c \"import h5py; t = h5py.File('" + a +
                         "/results.h5', 'r')['runs'][:]; print(len(t), sorted(set(t['mode'].astype(str))))\"";
  FILE* p = popen(py.c_str(), "r");
  ASSERT_NE(p, nullptr);
  char buf[256] = {0};
  const std::string got = fgets(buf, sizeof buf, p) ? buf : "";
  EXPECT_EQ(pclose(p), 0);
  EXPECT_EQ(got, "24 ['none', 'raibert']\n");
}

TEST(SweepCli, BadSpecsExit2NamingTheKeyAndWriteNothing) {
  const centaur_test::TempDir dir("sweep-cli-bad");
  const std::string out = dir.file("out");
  const std::string base = "jumps: [squat-jump]\nmodes: [none]\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {base + "planner: {axes: {target.height: [0.85]}}\nextra: 1\n", "extra"},
      {base + "planner: {axes: {target.height: []}}\n", "planner.axes.target.height"},
      {base + "planner: {axes: {contact.mu: {from: 0.6, to: 0.5, steps: 2}}}\n", "reversed range"},
      {"jumps: [squat-jump]\nmodes: [none, rabbit]\n", "rabbit"},
      {base + "seeds: -1\n", "seeds"},
      {base + "planner: {axes: {target.heigth: [0.85]}}\n", "target.heigth"},
      {base + "simulation: {perturb: {robot.mass_scale: {uniform: [0.1, 1.0]}}}\n", "robot.mass_scale"},
      {"jumps: [squat-jump\n", "malformed"},
  };
  int i = 0;
  for (const auto& [text, expect] : cases) {
    const std::string spec = dir.file("bad" + std::to_string(i++) + ".yaml");
    std::ofstream(spec) << text;
    const CliRun r = run("sweep " + spec + " --out " + out);
    EXPECT_EQ(r.code, 2) << text << "\n" << r.out;
    EXPECT_NE(r.out.find(expect), std::string::npos) << text << "\n" << r.out;
    EXPECT_NE(r.out.find(spec), std::string::npos) << "the message does not name the file:\n" << r.out;
    EXPECT_FALSE(fs::exists(out)) << text;
  }
  // A non-empty directory that holds no sweep is not taken over.
  fs::create_directories(out);
  std::ofstream(out + "/notes.txt") << "mine\n";
  const std::string good = dir.file("good.yaml");
  std::ofstream(good) << base;
  const CliRun r = run("sweep " + good + " --out " + out);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("holds no sweep"), std::string::npos) << r.out;
  EXPECT_EQ(fs::directory_iterator(out)->path().filename(), "notes.txt");

  // The spec is never one of the files the sweep writes: here a copy of the spec named like the summary, in a
  // DIR that holds this sweep. Resuming from DIR/sweep.yaml itself is allowed (a resume does not write it).
  const std::string held = dir.file("held");
  fs::create_directories(held);
  const std::string canonical = centaur::sweep::loadSweepSpec(good).canonicalYaml();
  std::ofstream(held + "/sweep.yaml") << canonical;
  std::ofstream(held + "/summary.md") << canonical;
  const CliRun clobber = run("sweep " + held + "/summary.md --out " + held);
  EXPECT_EQ(clobber.code, 2) << clobber.out;
  EXPECT_NE(clobber.out.find("is the same file as the input the spec"), std::string::npos) << clobber.out;
  EXPECT_EQ(readFile(held + "/summary.md"), canonical);
  EXPECT_FALSE(fs::exists(held + "/primitives.h5"));
  const CliRun resume = run("sweep " + held + "/sweep.yaml --out " + held + " --plan-only");
  EXPECT_EQ(resume.code, 0) << resume.out;
  EXPECT_EQ(readFile(held + "/sweep.yaml"), canonical);
}
