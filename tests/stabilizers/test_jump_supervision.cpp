// ctest-labels: unit
// What a node supervises in the jump controller (SupervisedController): the start trigger (the primitive starts
// at max(trigger, start + settle_time), the first sample is held before), the phase it reports, and the safe
// mode asked for from outside (latched until resume(), the whole-body controller's safe command meanwhile).
#include <gtest/gtest.h>

#include <cstring>

#include "stabilizers/jump_controller.hpp"
#include "stabilizers/no_stabilizer.hpp"
#include "support/synthetic_primitive.hpp"

using namespace centaur;

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

std::unique_ptr<JumpController> makeController(const std::string& start) {
  JumpControllerParams p;
  p.settle_time = 0.5;
  p.start = start;
  data::Primitive jump = test::makeSyntheticJump("squat-jump");
  jump.scalars["wheel_radius"] = test::SyntheticJump::wheel_radius;  // its ground: z = wheel radius
  return std::make_unique<JumpController>(kModel, jump, std::make_unique<NoStabilizer>(), p);
}

/// The robot at its home posture, level, at rest, at robot time t.
RobotState standingAt(const JumpController& c, double t) {
  RobotState s;
  s.resize(static_cast<Eigen::Index>(c.jointNames().size()));
  s.q = c.wholeBody().homePosture();
  s.imu_acc = Eigen::Vector3d(0.0, 0.0, 9.81);
  s.t = t;
  return s;
}

}  // namespace

TEST(JumpSupervision, TheTriggerStartsThePrimitiveButNotBeforeTheSettleTime) {
  for (const double trigger : {1.2, 0.2}) {
    auto c = makeController("trigger");
    JointCommand cmd;
    c->start(standingAt(*c, 0.0), cmd);
    for (int k = 0; k < 130; ++k) {
      c->tick(standingAt(*c, 0.01 * k), cmd);
      if (0.01 * k + 1e-9 < trigger) {
        EXPECT_STREQ(c->report().phase, "waiting") << "t = " << 0.01 * k;
      }
      if (k == static_cast<int>(std::lround(trigger / 0.01))) c->triggerStart(0.01 * k);
    }
    const double expected = std::max(trigger, 0.5);
    EXPECT_DOUBLE_EQ(c->primitiveStart(), expected) << trigger;
    c->tick(standingAt(*c, 1.3), cmd);
    EXPECT_NEAR(c->primitiveTime(), 1.3 - expected, 1e-12) << trigger;
    EXPECT_STREQ(c->report().phase, "primitive");
    c->triggerStart(2.0);  // a second trigger changes nothing
    EXPECT_DOUBLE_EQ(c->primitiveStart(), expected);
  }
}

TEST(JumpSupervision, WithoutTheTriggerThePrimitiveStartsAfterSettling) {
  auto c = makeController("settle");
  JointCommand cmd;
  c->start(standingAt(*c, 0.25), cmd);
  c->tick(standingAt(*c, 0.3), cmd);
  EXPECT_STREQ(c->report().phase, "settle");
  c->triggerStart(0.3);  // ignored: this controller starts on its own
  EXPECT_DOUBLE_EQ(c->primitiveStart(), 0.75);
  c->tick(standingAt(*c, 0.8), cmd);
  EXPECT_STREQ(c->report().phase, "primitive");
  EXPECT_NEAR(c->primitiveTime(), 0.05, 1e-12);
  c->tick(standingAt(*c, 2.0), cmd);
  EXPECT_STREQ(c->report().phase, "end");  // the synthetic primitive lasts 1 s, no recovery configured
}

TEST(JumpSupervision, RequestedSafeModeIsLatchedUntilResume) {
  auto c = makeController("settle");
  JointCommand cmd;
  c->start(standingAt(*c, 0.0), cmd);
  c->tick(standingAt(*c, 0.001), cmd);
  ASSERT_FALSE(c->report().safe_mode);
  const Eigen::VectorXd kd_nominal = cmd.kd;
  c->requestSafeMode();
  for (int k = 2; k < 10; ++k) {
    c->tick(standingAt(*c, 0.001 * k), cmd);
    ASSERT_TRUE(c->report().safe_mode);
    EXPECT_STREQ(c->report().safe_reason, "safe_requested");
    EXPECT_TRUE(cmd.qd_ref.isZero());
    EXPECT_TRUE(cmd.kd.isApprox(3.0 * kd_nominal)) << "the whole-body controller's safe command";
  }
  c->resume();
  c->tick(standingAt(*c, 0.011), cmd);
  EXPECT_FALSE(c->report().safe_mode);
  EXPECT_TRUE(cmd.kd.isApprox(kd_nominal));
}
