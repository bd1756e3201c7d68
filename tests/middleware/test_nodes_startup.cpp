// ctest-labels: middleware integration
// How `centaur control` starts against a robot: this test process plays the robot (joint states, IMU, robot
// status on DDS) so that it controls the order and the timing of what the controller sees.
//   - The controller's first tick waits for the robot's status: only the status says whether the robot is in
//     lockstep (slow periods are allowed, lockstep_stale_time) or realtime (stale_time). A lockstep robot whose
//     status is matched after its first state must not be judged by the realtime stale time: before this rule, a
//     busy machine could put the controller in safe mode during a lockstep run, and the DDS run no longer equaled
//     the in-process one.
//   - A robot that publishes no status at all is served after a grace time and judged by the strict stale time.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "controller/robot_interface.hpp"
#include "middleware/dds.hpp"
#include "middleware/messages.hpp"
#include "middleware/state_codec.hpp"
#include "support/dds_peer.hpp"
#include "support/node_pair.hpp"

using namespace centaur_test;
namespace mw = centaur::middleware;
using Clock = std::chrono::steady_clock;

namespace {

/// The robot's side of the protocol, played by the test.
class FakeRobot {
 public:
  explicit FakeRobot(int domain)
      : participant_(onDomain(domain)),
        joints_(participant_, mw::kJointStates),
        imu_(participant_, mw::kImu),
        status_(participant_, mw::kRobotStatus),
        commands_(participant_, mw::kJointCommand),
        controller_status_(participant_, mw::kControllerStatus),
        encoder_(centauroJointNames(), "imu_link") {
    const auto n = static_cast<Eigen::Index>(centauroJointNames().size());
    state_.resize(n);
    state_.q.setZero();
    state_.qd.setZero();
    state_.tau.setZero();
    state_.imu_quat.setIdentity();
    state_.imu_omega.setZero();
    state_.imu_acc = Eigen::Vector3d(0.0, 0.0, 9.81);
  }

  /// True once the controller's state readers are matched (discovery done).
  bool waitForController(double timeout_s) {
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
    while (Clock::now() < deadline) {
      if (joints_.matched() > 0 && imu_.matched() > 0 && status_.matched() > 0 && commands_.matched() > 0 &&
          controller_status_.matched() > 0) {
        return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  }

  void publishState(std::int64_t t_ns) {
    state_.t = centaur::secondsFromNanoseconds(t_ns);
    encoder_.encode(state_);
    ASSERT_TRUE(joints_.write(encoder_.jointState()));
    ASSERT_TRUE(imu_.write(encoder_.imu()));
  }

  void publishStatus(std::int64_t t_ns, bool lockstep) {
    mw::RobotStatusMsg s{};
    s.header.stamp = mw::timeFromNanoseconds(t_ns);
    s.header.frame_id = empty_;
    s.mode = mw::kModeRunning;
    s.lockstep = lockstep;
    s.reason = empty_;
    ASSERT_TRUE(status_.write(s));
  }

  /// Waits up to timeout_s for a command answering the state at t_ns (the state is republished every 100 ms,
  /// as the robot node does); also records whether any controller status said stale or safe mode.
  bool waitForAnswer(std::int64_t t_ns, double timeout_s) {
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
    auto republish = Clock::now() + std::chrono::milliseconds(100);
    bool answered = false;
    while (!answered && Clock::now() < deadline) {
      commands_.take([&](const mw::JointCommandMsg& m, const dds_sample_info_t&) {
        answered = answered || mw::nanosecondsFromTime(m.state_stamp) == t_ns;
      });
      takeControllerStatus();
      if (Clock::now() >= republish) {
        publishState(t_ns);
        republish = Clock::now() + std::chrono::milliseconds(100);
      }
      if (!answered) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return answered;
  }

  void takeControllerStatus() {
    controller_status_.take([&](const mw::ControllerStatusMsg& s, const dds_sample_info_t&) {
      stale_seen_ = stale_seen_ || s.stale;
      safe_seen_ = safe_seen_ || s.safe_mode;
    });
  }

  bool staleSeen() const { return stale_seen_; }
  bool safeSeen() const { return safe_seen_; }

 private:
  mw::Participant participant_;
  mw::Writer<mw::JointStateMsg> joints_;
  mw::Writer<mw::ImuMsg> imu_;
  mw::Writer<mw::RobotStatusMsg> status_;
  mw::Reader<mw::JointCommandMsg> commands_;
  mw::Reader<mw::ControllerStatusMsg> controller_status_;
  mw::StateEncoder encoder_;
  centaur::RobotState state_;
  char empty_[1] = {'\0'};
  bool stale_seen_ = false, safe_seen_ = false;
};

constexpr std::int64_t kMs = 1000000;  // one control period [ns]

}  // namespace

TEST(NodesStartup, TheControllerWaitsForTheRobotsStatusSoASlowLockstepRobotIsNeverStale) {
  const TempDir dir("startup-status");
  constexpr int kDomain = 35;
  FakeRobot robot(kDomain);
  auto control = startControl(dir, "stand", kDomain, {});
  ASSERT_TRUE(robot.waitForController(60.0)) << control->output();
  // The first state arrives before any status: the controller does not answer yet (its grace is 1 s).
  robot.publishState(0);
  EXPECT_FALSE(robot.waitForAnswer(0, 0.5)) << "the controller ticked before it knew the robot's mode";
  // The status says lockstep: now it answers.
  robot.publishStatus(0, true);
  ASSERT_TRUE(robot.waitForAnswer(0, 20.0)) << control->output();
  // Periods of 300 ms wall time: far above stale_time (50 ms), below lockstep_stale_time (2 s).
  for (int k = 1; k <= 4; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    robot.publishState(k * kMs);
    ASSERT_TRUE(robot.waitForAnswer(k * kMs, 20.0)) << "period " << k << "\n" << control->output();
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  robot.takeControllerStatus();
  EXPECT_FALSE(robot.staleSeen()) << "a slow lockstep robot was judged by the realtime stale time";
  EXPECT_FALSE(robot.safeSeen());
  control->signal(SIGTERM);
  ASSERT_TRUE(control->wait(20.0));
  const nlohmann::json c = summaryOf(*control);
  ASSERT_TRUE(c.contains("stale_events")) << control->output();
  EXPECT_EQ(c["stale_events"], 0);
  EXPECT_EQ(c["ticks"], 5);
}

TEST(NodesStartup, ARobotWithoutStatusIsServedAfterTheGraceAndJudgedByTheStrictStaleTime) {
  const TempDir dir("startup-nostatus");
  constexpr int kDomain = 36;
  FakeRobot robot(kDomain);
  auto control = startControl(dir, "stand", kDomain, {});
  ASSERT_TRUE(robot.waitForController(60.0)) << control->output();
  const auto first = Clock::now();
  robot.publishState(0);
  ASSERT_TRUE(robot.waitForAnswer(0, 20.0)) << control->output();
  const double waited = std::chrono::duration<double>(Clock::now() - first).count();
  EXPECT_GE(waited, 1.0) << "answered before its grace time without knowing the robot's mode";
  // Unknown mode: the strict stale time (50 ms) applies, so a 300 ms pause is a stale state.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  robot.publishState(kMs);
  ASSERT_TRUE(robot.waitForAnswer(kMs, 20.0)) << control->output();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  robot.takeControllerStatus();
  EXPECT_TRUE(robot.staleSeen());
  control->signal(SIGTERM);
  ASSERT_TRUE(control->wait(20.0));
  EXPECT_GE(summaryOf(*control)["stale_events"].get<int>(), 1);
}
