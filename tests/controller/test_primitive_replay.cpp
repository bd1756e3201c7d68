// ctest-labels: unit
// PrimitiveReplay: the 1 kHz samples of a primitive turned into whole-body references, checked on the analytic
// synthetic jump (tests/planner/synthetic_primitive.hpp): sample selection and holding outside the primitive,
// planned contact events, surface normals (ground / wall / neither), base acceleration from the knots'
// piecewise-constant control, no allocation.
#include <gtest/gtest.h>

#include <limits>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "controller/primitive_replay.hpp"
#include "support/synthetic_primitive.hpp"
#include "support/allocation_counter.hpp"

using namespace centaur;
using centaur::test::makeSyntheticJump;
using centaur::test::SyntheticJump;

namespace {
data::Primitive jump() {
  data::Primitive p = makeSyntheticJump("squat-jump");
  p.scalars["wheel_radius"] = SyntheticJump::wheel_radius;
  p.scalars["ground_z"] = 0.0;
  return p;
}
}  // namespace

TEST(PrimitiveReplay, SamplesTheRowAtOrBeforeTAndHoldsTheEnds) {
  const data::Primitive p = jump();
  const PrimitiveReplay replay(p);
  EXPECT_NEAR(replay.duration(), 1.0, 1e-12);
  ReplaySample s;
  replay.sample(0.2505, s);
  EXPECT_EQ(s.index, 250);
  EXPECT_TRUE(s.running);
  for (int k = 0; k < 4; ++k) {
    EXPECT_TRUE(s.b_p_wheel.col(k).isApprox(p.foot_pos_rel.row(250).segment<3>(3 * k).transpose()));
    EXPECT_TRUE(s.b_v_wheel.col(k).isApprox(p.foot_vel_rel.row(250).segment<3>(3 * k).transpose()));
    EXPECT_TRUE(s.w_F.col(k).isApprox(p.force.row(250).segment<3>(3 * k).transpose()));
  }
  replay.sample(-0.3, s);  // before the start: first sample, at rest
  EXPECT_EQ(s.index, 0);
  EXPECT_FALSE(s.running);
  EXPECT_EQ(s.b_v_wheel.norm(), 0.0);
  EXPECT_EQ(s.vdot_base.norm(), 0.0);
  replay.sample(7.0, s);  // after the end: last sample, at rest
  EXPECT_EQ(s.index, 1000);
  EXPECT_FALSE(s.running);
  EXPECT_EQ(s.b_v_wheel.norm(), 0.0);
  // Far beyond the end (t / dt beyond any integer type) and non-finite times: an end sample, never an index
  // computed from an overflowed conversion.
  for (double t : {1e300, std::numeric_limits<double>::infinity()}) {
    replay.sample(t, s);
    EXPECT_EQ(s.index, 1000) << t;
    EXPECT_FALSE(s.running) << t;
  }
  for (double t : {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    replay.sample(t, s);
    EXPECT_EQ(s.index, 0) << t;
    EXPECT_FALSE(s.running) << t;
  }
}

TEST(PrimitiveReplay, ContactEventsAndFlagsFollowThePlan) {
  const PrimitiveReplay replay(jump());
  ReplaySample s;
  replay.sample(0.295, s);  // front feet lifted, rear feet still down
  EXPECT_FALSE(s.contact[0]);
  EXPECT_FALSE(s.contact[1]);
  EXPECT_TRUE(s.contact[2]);
  EXPECT_TRUE(s.contact[3]);
  for (int k = 0; k < 4; ++k) {
    ASSERT_EQ(replay.liftOffs(k).size(), 1u);
    ASSERT_EQ(replay.touchDowns(k).size(), 1u);
    EXPECT_NEAR(replay.liftOffs(k)[0], k < 2 ? 0.29 : 0.30, 1e-9);
    EXPECT_NEAR(replay.touchDowns(k)[0], 0.60, 1e-9);
    // every contact is on the ground, and the flight samples carry the next contact's normal
    EXPECT_TRUE(replay.normalAt(450, k).isApprox(Eigen::Vector3d::UnitZ()));
  }
}

TEST(PrimitiveReplay, WallContactsGetTheWallNormalAndFloatingContactsAreRejected) {
  data::Primitive p = jump();
  const double wall_x = -2.0, r = SyntheticJump::wheel_radius;
  p.scalars["wall_x"] = wall_x;
  for (long i = 600; i < p.samples(); ++i) {  // the rear-left foot lands on the wall, 0.3 m up
    p.foot_pos(i, 6) = wall_x + r;
    p.foot_pos(i, 8) = 0.3;
  }
  const PrimitiveReplay replay(p);
  EXPECT_TRUE(replay.normalAt(800, 2).isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_TRUE(replay.normalAt(450, 2).isApprox(Eigen::Vector3d::UnitX()));  // the next contact's, in flight
  EXPECT_TRUE(replay.normalAt(100, 2).isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(replay.normalAt(800, 3).isApprox(Eigen::Vector3d::UnitZ()));
  p.scalars.erase("wall_x");  // no wall: the same contact floats in the air
  EXPECT_THROW(PrimitiveReplay{p}, InputError);
}

TEST(PrimitiveReplay, BaseAccelerationIsTheKnotControlInTheRobotLayout) {
  const data::Primitive p = jump();
  const PrimitiveReplay replay(p);
  ReplaySample s;
  replay.sample(0.2505, s);  // knot interval 2 = [0.2, 0.3)
  const Eigen::Quaterniond w_q_b(p.base_quat(250, 0), p.base_quat(250, 1), p.base_quat(250, 2), p.base_quat(250, 3));
  const Eigen::Vector3d w_alpha = p.knot_u.row(2).segment<3>(3).transpose();
  EXPECT_TRUE(s.vdot_base.head<3>().isApprox(p.knot_u.row(2).head<3>().transpose()));
  EXPECT_TRUE(s.vdot_base.tail<3>().isApprox(w_q_b.conjugate() * w_alpha));  // base frame, like RobotModel's v
}

TEST(PrimitiveReplay, BadShapesNameTheDataset) {
  data::Primitive p = jump();
  p.force.resize(10, 12);
  try {
    PrimitiveReplay replay(p);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("force"), std::string::npos) << e.what();
  }
}

TEST(PrimitiveReplay, SampleNeverAllocates) {
  const PrimitiveReplay replay(jump());
  ReplaySample s;
  const long before = centaur_test::heapAllocations();
  for (int i = -100; i < 1200; ++i) replay.sample(0.001 * i, s);
  EXPECT_EQ(centaur_test::heapAllocations() - before, 0);
}
