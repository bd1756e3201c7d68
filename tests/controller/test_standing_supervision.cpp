// ctest-labels: unit
// The standing controller under supervision: a non-finite measurement or an outside request puts it in safe
// mode (home posture, 3x damping, the last good feed-forward: never a NaN in the command), latched until
// resume(); resume() takes effect only with a valid measurement.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "controller/standing_controller.hpp"

using namespace centaur;

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

RobotState home(const StandingController& c) {
  RobotState s;
  s.resize(c.model().numJoints());
  s.q = c.model().homeJoints();
  s.imu_acc = Eigen::Vector3d(0.0, 0.0, 9.81);
  return s;
}

bool finite(const JointCommand& c) {
  return c.q_ref.allFinite() && c.qd_ref.allFinite() && c.tau_ff.allFinite() && c.kp.allFinite() && c.kd.allFinite();
}

}  // namespace

TEST(StandingSupervision, InvalidInputAndRequestsLatchTheSafeModeUntilResume) {
  StandingController c(kModel, StandingParams{});
  JointCommand cmd;
  RobotState s = home(c);
  c.start(s, cmd);
  c.tick(s, cmd);
  ASSERT_FALSE(c.report().safe_mode);
  const Eigen::VectorXd kd = cmd.kd, tau_ff = cmd.tau_ff;
  ASSERT_GT(tau_ff.cwiseAbs().maxCoeff(), 1.0) << "gravity compensation is on";

  RobotState bad = s;
  bad.q[3] = std::nan("");
  c.tick(bad, cmd);
  EXPECT_TRUE(c.report().safe_mode);
  EXPECT_STREQ(c.report().safe_reason, "invalid_input");
  EXPECT_TRUE(finite(cmd));
  EXPECT_TRUE(cmd.kd.isApprox(3.0 * kd));
  EXPECT_EQ(cmd.tau_ff, tau_ff) << "the last good feed-forward";
  c.tick(s, cmd);
  EXPECT_TRUE(c.report().safe_mode) << "latched";
  c.resume();
  c.tick(bad, cmd);
  EXPECT_TRUE(c.report().safe_mode) << "resume needs a valid measurement";
  c.tick(s, cmd);
  EXPECT_FALSE(c.report().safe_mode);
  EXPECT_EQ(cmd.kd, kd);

  c.requestSafeMode();
  c.tick(s, cmd);
  EXPECT_TRUE(c.report().safe_mode);
  EXPECT_STREQ(c.report().safe_reason, "requested");
  c.resume();
  c.tick(s, cmd);
  EXPECT_FALSE(c.report().safe_mode);
}
