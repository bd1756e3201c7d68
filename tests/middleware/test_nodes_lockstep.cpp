// ctest-labels: middleware integration physics
// The online stage over DDS equals the in-process simulation: `centaur robot --lockstep` and `centaur control`
// as two processes on loopback run the same controller code on the same states, so their log equals the log of
// `centaur simulate` with the same settings (default configuration; the jump starts after the scenario's 0.5 s
// settle time: `--start-after 0.5`). Doubles travel unchanged and the robot clock counts nanoseconds on both
// paths, so the logs agree bit for bit; the stated tolerance is 1e-9. Stand 5 s; squat and half-squat jumps with
// the Raibert-like stabilizer and without one. Also a short realtime run: paced at 1x, it stands.
#include <gtest/gtest.h>

#include <cmath>

#include "data/sim_log_file.hpp"
#include "support/node_pair.hpp"

using namespace centaur_test;

namespace {

/// Largest |a - b| over every dataset of two simulation logs (infinity if their shapes differ).
double maxLogDifference(const std::string& a, const std::string& b) {
  const centaur::data::SimLogFile fa(a), fb(b);
  if (fa.header().samples != fb.header().samples) return INFINITY;
  double worst = 0.0;
  for (const auto& d : centaur::data::simLogDatasets()) {
    const centaur::data::RowMatrix ma = fa.read(d.name), mb = fb.read(d.name);
    if (ma.rows() != mb.rows() || ma.cols() != mb.cols()) return INFINITY;
    worst = std::max(worst, (ma - mb).cwiseAbs().maxCoeff());
  }
  return worst;
}

struct Pair {
  nlohmann::json robot, control, simulate;
  double log_difference = INFINITY;
  std::string robot_output, control_output;
};

Pair runBoth(const std::string& task, const std::string& stabilizer, int domain, const std::string& duration) {
  const TempDir dir("lockstep-" + task);
  Pair p;
  std::vector<std::string> control_args;
  std::string sim_args = "simulate " + task + " --json --out " + dir.file("sim.h5") + " --duration " + duration;
  if (task != "stand") {
    control_args = {"--primitive", bothJumps(), "--stabilizer", stabilizer, "--start-after", "0.5"};
    sim_args += " --primitive " + bothJumps() + " --stabilizer " + stabilizer;
  }
  auto robot = startRobot(dir, task, domain, {"--lockstep", "--duration", duration, "--out", dir.file("dds.h5")});
  auto control = startControl(dir, task, domain, control_args);
  const bool robot_done = robot->wait(240.0);
  const bool control_done = control->wait(20.0);
  p.robot_output = robot->output();
  p.control_output = control->output();
  EXPECT_TRUE(robot_done && robot->code() == 0) << p.robot_output;
  EXPECT_TRUE(control_done && control->code() == 0) << "the controller stops when the robot finishes\n"
                                                     << p.control_output;
  p.robot = summaryOf(*robot);
  p.control = summaryOf(*control);
  const CliRun sim = run(sim_args);
  EXPECT_EQ(sim.code, 0) << sim.out;
  p.simulate = nlohmann::json::parse(sim.last_line, nullptr, false);
  if (robot_done && robot->code() == 0 && sim.code == 0) p.log_difference = maxLogDifference(dir.file("dds.h5"), dir.file("sim.h5"));
  return p;
}

void expectSameRun(const Pair& p, const std::string& what) {
  ASSERT_TRUE(p.robot.contains("outcome")) << what << "\n" << p.robot_output;
  ASSERT_TRUE(p.simulate.contains("outcome")) << what;
  EXPECT_EQ(p.robot["outcome"], p.simulate["outcome"]) << what;
  EXPECT_EQ(p.robot["control_periods"], p.simulate["control_periods"]) << what;
  EXPECT_NEAR(p.robot["peak_pitch_deg"].get<double>(), p.simulate["peak_pitch_deg"].get<double>(), 1e-9) << what;
  EXPECT_LE(p.log_difference, 1e-9) << what << ": every logged value of the DDS run equals the in-process one";
  EXPECT_EQ(p.robot["commands_rejected"], 0) << what;
  EXPECT_EQ(p.robot["watchdog_trips"], 0) << what;
  EXPECT_EQ(p.robot["commands_applied"], p.robot["control_periods"]) << what << ": one command per period";
  EXPECT_EQ(p.control["ticks"], p.robot["control_periods"]) << what;
  EXPECT_EQ(p.control["stale_events"], 0) << what << ": a slow period of a lockstep robot is not a stale state";
}

}  // namespace

TEST(NodesLockstep, StandFiveSecondsEqualsSimulate) {
  const Pair p = runBoth("stand", "", 21, "5");
  expectSameRun(p, "stand");
  EXPECT_EQ(p.robot["outcome"], "success");
  EXPECT_LT(p.robot["pelvis_drift_m"].get<double>(), 0.01);
}

TEST(NodesLockstep, SquatJumpWithAndWithoutStabilizerEqualsSimulate) {
  ASSERT_FALSE(bothJumps().empty());
  for (const char* mode : {"raibert", "none"}) {
    const Pair p = runBoth("squat-jump", mode, 22, "5");
    expectSameRun(p, std::string("squat-jump ") + mode);
    EXPECT_EQ(p.robot["outcome"], "success") << mode;
  }
}

TEST(NodesLockstep, HalfSquatJumpWithAndWithoutStabilizerEqualsSimulate) {
  ASSERT_FALSE(bothJumps().empty());
  for (const char* mode : {"raibert", "none"}) {
    const Pair p = runBoth("half-squat-jump", mode, 23, "6.5");
    expectSameRun(p, std::string("half-squat-jump ") + mode);
    EXPECT_EQ(p.robot["outcome"], "success") << mode;
  }
}

TEST(NodesRealtime, StandsPacedToTheWallClock) {
  const TempDir dir("realtime");
  // A generous watchdog: this checks the pacing and the protocol, not the machine's scheduling under load.
  auto robot = startRobot(dir, "stand", 24,
                          {"--realtime", "--duration", "2", "--set", "safety.watchdog_timeout=0.5"});
  auto control = startControl(dir, "stand", 24, {});
  ASSERT_TRUE(robot->wait(60.0)) << robot->output();
  ASSERT_TRUE(control->wait(20.0)) << control->output();
  const nlohmann::json r = summaryOf(*robot);
  ASSERT_TRUE(r.contains("outcome")) << robot->output();
  EXPECT_EQ(r["outcome"], "success");
  EXPECT_EQ(r["mode"], "realtime");
  EXPECT_EQ(r["watchdog_trips"], 0);
  EXPECT_EQ(r["control_periods"], 2000);
  // Paced: 2 s of robot time took about 2 s (not much less).
  EXPECT_LT(r["real_time_factor"].get<double>(), 1.2);
  EXPECT_GT(r["commands_applied"].get<int>(), 1000);
}
