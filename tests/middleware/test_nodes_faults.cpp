// ctest-labels: middleware integration
// Faults across the process boundary, injected for real:
//   - kill -9 of the controller in the middle of the squat jump: the robot enters damping mode within the
//     watchdog time plus one period (robot time), applies no NaN torque, and its log shows the switch;
//   - SIGSTOP of the robot: the controller reports stale state and enters its safe mode within its stale time;
//     after SIGCONT it stays in safe mode until a reset, then recovers;
//   - a rogue publisher sending NaN, wrong-size, wrong-name, out-of-limit and over-gain commands: every one is
//     rejected and counted, none is applied (the robot keeps standing on its controller's commands);
//   - the controller restarted: the new one reconnects and holds the posture.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>

#include "data/sim_log_file.hpp"
#include "controller/robot_interface.hpp"
#include "middleware/dds.hpp"
#include "middleware/messages.hpp"
#include "support/dds_peer.hpp"
#include "support/node_pair.hpp"

using namespace centaur_test;
namespace mw = centaur::middleware;
using Clock = std::chrono::steady_clock;

namespace {

/// Polls the controller status until pred(status) or the timeout; true if it held.
template <class Pred>
bool waitForControllerStatus(mw::Reader<mw::ControllerStatusMsg>& reader, double timeout_s, Pred pred) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  bool held = false;
  while (!held && Clock::now() < deadline) {
    reader.take([&](const mw::ControllerStatusMsg& s, const dds_sample_info_t&) { held = held || pred(s); });
    if (!held) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return held;
}

double seconds(const mw::TimeMsg& t) { return centaur::secondsFromNanoseconds(mw::nanosecondsFromTime(t)); }

}  // namespace

TEST(NodesFaults, KillingTheControllerMidJumpPutsTheRobotInDampingMode) {
  ASSERT_FALSE(bothJumps().empty());
  const TempDir dir("kill");
  constexpr int kDomain = 31;
  mw::Participant participant(onDomain(kDomain));
  mw::Reader<mw::ControllerStatusMsg> status(participant, mw::kControllerStatus);
  auto robot = startRobot(dir, "squat-jump", kDomain,
                          {"--lockstep", "--out", dir.file("log.h5"), "--set", "robot_node.lockstep_timeout=0.3",
                           "--set", "outcome.fall_height=0"});
  auto control = startControl(dir, "squat-jump", kDomain,
                              {"--primitive", bothJumps(), "--stabilizer", "raibert", "--start-after", "0.5"});
  // Mid jump: the primitive started at 0.5 s; take-off is about 1 s later.
  ASSERT_TRUE(waitForControllerStatus(status, 120.0, [](const mw::ControllerStatusMsg& s) {
    return seconds(s.header.stamp) >= 1.2 && std::strcmp(s.phase, "primitive") == 0;
  })) << control->output();
  control->signal(SIGKILL);
  ASSERT_TRUE(control->wait(10.0));
  ASSERT_TRUE(robot->wait(120.0)) << robot->output();
  const nlohmann::json r = summaryOf(*robot);
  ASSERT_TRUE(r.contains("watchdog_trips")) << robot->output();
  EXPECT_EQ(r["watchdog_trips"], 1);
  const double last = r["last_applied_time_s"], damping = r["first_damping_time_s"];
  EXPECT_GE(last, 1.2);
  EXPECT_LE(damping - last, 0.005 + 0.001 + 1e-9) << "watchdog time plus one period";
  // The log shows the switch: nominal gains up to it, then kp = 0 and the damping kd; never a NaN torque.
  const centaur::data::SimLogFile log(dir.file("log.h5"));
  const auto t = log.time();
  const auto kp = log.read("kp"), kd = log.read("kd"), tau = log.read("tau_applied"), tau_ff = log.read("tau_ff");
  EXPECT_TRUE(tau.allFinite());
  int switches = 0;
  for (Eigen::Index k = 1; k < t.size(); ++k) {
    const bool before = kp.row(k - 1).maxCoeff() > 0.0, now = kp.row(k).maxCoeff() > 0.0;
    if (before && !now) {
      ++switches;
      EXPECT_NEAR(t[k], damping, 1e-9);
    }
    if (t[k] >= damping) {
      ASSERT_EQ(kp.row(k).maxCoeff(), 0.0) << "t = " << t[k];
      EXPECT_GT(kd.row(k).minCoeff(), 0.0);
      EXPECT_EQ(tau_ff.row(k).cwiseAbs().maxCoeff(), 0.0) << "no feed-forward in damping mode";
    }
  }
  EXPECT_EQ(switches, 1);
}

TEST(NodesFaults, AStoppedRobotMakesTheControllerStaleUntilAReset) {
  const TempDir dir("sigstop");
  constexpr int kDomain = 32;
  mw::Participant participant(onDomain(kDomain));
  mw::Reader<mw::ControllerStatusMsg> status(participant, mw::kControllerStatus);
  mw::Writer<mw::EmptyMsg> reset(participant, mw::kControllerReset);
  auto robot = startRobot(dir, "stand", kDomain, {"--lockstep", "--duration", "30"});
  auto control = startControl(dir, "stand", kDomain, {"--set", "control_node.lockstep_stale_time=0.05"});
  ASSERT_TRUE(waitForControllerStatus(status, 120.0, [](const auto& s) { return s.ticks > 200; }))
      << control->output();
  robot->signal(SIGSTOP);
  const auto stopped = Clock::now();
  ASSERT_TRUE(waitForControllerStatus(status, 10.0, [](const mw::ControllerStatusMsg& s) {
    return s.stale && s.safe_mode && std::strcmp(s.safe_reason, "stale_state") == 0;
  }));
  const double noticed = std::chrono::duration<double>(Clock::now() - stopped).count();
  std::printf("stale state reported %.0f ms after SIGSTOP (lockstep_stale_time 50 ms)\n", 1e3 * noticed);
  EXPECT_LT(noticed, 2.0) << "stale_time plus scheduling on a shared machine";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  robot->signal(SIGCONT);
  // States flow again: no longer stale, but still in safe mode (latched) ...
  ASSERT_TRUE(waitForControllerStatus(status, 10.0, [](const auto& s) { return !s.stale && s.safe_mode; }));
  // ... until the reset.
  const mw::EmptyMsg empty{0};
  ASSERT_TRUE(reset.write(empty));
  ASSERT_TRUE(waitForControllerStatus(status, 10.0, [](const auto& s) { return !s.stale && !s.safe_mode; }));
  control->signal(SIGTERM);  // the controller first: a robot gone first would make it stale once more
  EXPECT_TRUE(control->wait(10.0));
  robot->signal(SIGTERM);
  const nlohmann::json c = summaryOf(*control);
  EXPECT_EQ(c["stale_events"], 1);
  EXPECT_EQ(c["resets"], 1);
}

TEST(NodesFaults, RogueCommandsAreRejectedCountedAndNeverApplied) {
  const TempDir dir("rogue");
  constexpr int kDomain = 33;
  mw::Participant participant(onDomain(kDomain));
  mw::Reader<mw::ControllerStatusMsg> status(participant, mw::kControllerStatus);
  mw::Writer<mw::JointCommandMsg> rogue(participant, mw::kJointCommand);
  auto robot = startRobot(dir, "stand", kDomain, {"--lockstep", "--duration", "4", "--out", dir.file("log.h5")});
  auto control = startControl(dir, "stand", kDomain, {});
  ASSERT_TRUE(waitForControllerStatus(status, 120.0, [](const auto& s) { return s.ticks > 100; }));
  // A valid-looking command of CENTAURO's 39 joints, then broken one way at a time.
  const std::vector<std::string>& names = centauroJointNames();
  struct Bad {
    const char* what;
    int drop = 0;          // joints dropped from the end
    int rename = -1;       // joint given a wrong name
    double q0 = 0.0, kp0 = 100.0, tau0 = 0.0;
  };
  const std::vector<Bad> bads = {{"nan", 0, -1, std::nan("")}, {"size", 1}, {"name", 0, 5},
                                 {"limit", 0, -1, 10.0},       {"gain", 0, -1, 0.0, 1e7}};
  const int kEach = 20;
  for (int rep = 0; rep < kEach; ++rep) {
    for (const Bad& b : bads) {
      std::vector<std::string> n = names;
      n.resize(n.size() - static_cast<std::size_t>(b.drop));
      if (b.rename >= 0) n[static_cast<std::size_t>(b.rename)] = "rogue_joint";
      std::vector<char*> ptrs;
      for (auto& s : n) ptrs.push_back(s.data());
      std::vector<double> q(n.size(), 0.0), zero(n.size(), 0.0), kp(n.size(), b.kp0), kd(n.size(), 1.0);
      q[0] = b.q0;
      char empty[1] = {'\0'};
      mw::JointCommandMsg m{};
      m.header.frame_id = empty;
      m.session = 0xbad;
      m.seq = static_cast<std::uint64_t>(rep + 1);
      m.state_stamp = mw::timeFromNanoseconds(1000000);  // an old state: rejected as stale if all else fits
      const auto u = static_cast<std::uint32_t>(n.size());
      m.name = {u, u, ptrs.data(), false};
      m.q_ref = {u, u, q.data(), false};
      m.qd_ref = {u, u, zero.data(), false};
      m.tau_ff = {u, u, zero.data(), false};
      m.kp = {u, u, kp.data(), false};
      m.kd = {u, u, kd.data(), false};
      ASSERT_TRUE(rogue.write(m));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(robot->wait(120.0)) << robot->output();
  ASSERT_TRUE(control->wait(20.0));
  const nlohmann::json r = summaryOf(*robot);
  ASSERT_TRUE(r.contains("rejected")) << robot->output();
  EXPECT_EQ(r["rejected"]["non_finite"], kEach);
  EXPECT_EQ(r["rejected"]["malformed"], 2 * kEach);
  EXPECT_EQ(r["rejected"]["limits"], kEach);
  EXPECT_EQ(r["rejected"]["gains"], kEach);
  EXPECT_EQ(r["commands_rejected"], 5 * kEach);
  EXPECT_EQ(r["commands_applied"], r["control_periods"]) << "exactly the controller's commands were applied";
  EXPECT_EQ(r["outcome"], "success");
  const centaur::data::SimLogFile log(dir.file("log.h5"));
  EXPECT_LT(log.read("kp").maxCoeff(), 1e4) << "no rogue gain reached the drives";
  EXPECT_LT(log.read("q_ref").col(0).cwiseAbs().maxCoeff(), 1.0) << "no rogue reference reached the drives";
}

TEST(NodesFaults, ARestartedControllerReconnectsAndHoldsThePosture) {
  const TempDir dir("restart");
  constexpr int kDomain = 34;
  mw::Participant participant(onDomain(kDomain));
  mw::Reader<mw::ControllerStatusMsg> status(participant, mw::kControllerStatus);
  // lockstep with a long answer timeout: while no controller answers, robot time stands still.
  auto robot = startRobot(dir, "stand", kDomain, {"--lockstep", "--duration", "3", "--set",
                                                  "robot_node.lockstep_timeout=60"});
  auto first = startControl(dir, "stand", kDomain, {}, "control-1");
  ASSERT_TRUE(waitForControllerStatus(status, 120.0, [](const auto& s) { return s.ticks > 500; }));
  first->signal(SIGKILL);
  ASSERT_TRUE(first->wait(10.0));
  auto second = startControl(dir, "stand", kDomain, {}, "control-2");
  ASSERT_TRUE(robot->wait(120.0)) << robot->output();
  ASSERT_TRUE(second->wait(20.0)) << second->output();
  const nlohmann::json r = summaryOf(*robot), c = summaryOf(*second);
  ASSERT_TRUE(r.contains("outcome")) << robot->output();
  EXPECT_EQ(r["watchdog_trips"], 0);
  EXPECT_EQ(r["outcome"], "success");
  EXPECT_LT(r["pelvis_drift_m"].get<double>(), 0.01) << "the posture was held across the restart";
  EXPECT_GT(c["ticks"].get<int>(), 500) << "the second controller ran the rest of the stand";
  EXPECT_EQ(r["commands_applied"], r["control_periods"]);
}
