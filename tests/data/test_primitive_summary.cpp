// ctest-labels: unit
// Summary of a primitive: phase times, flight, apex and peaks of an analytic jump with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "data/primitive_summary.hpp"
#include "support/synthetic_primitive.hpp"

using centaur::data::summarize;
using centaur::test::SyntheticJump;

namespace {
constexpr double kTimeTol = 1e-9;  // sample times are exact multiples of 1 ms up to rounding
}

TEST(PrimitiveSummary, PhaseTimesOfTheSyntheticJump) {
  const auto s = summarize(centaur::test::makeSyntheticJump("jump"));
  EXPECT_EQ(s.samples, 1001);
  EXPECT_NEAR(s.duration, 1.0, kTimeTol);
  EXPECT_EQ(s.shooting_intervals, 10);

  // Flight = all four feet off: from the rear feet's lift-off to the common touch-down.
  ASSERT_EQ(s.flight.size(), 1u);
  EXPECT_NEAR(s.take_off_time, SyntheticJump::t_take_off, kTimeTol);
  EXPECT_NEAR(s.touch_down_time, SyntheticJump::t_land, kTimeTol);
  EXPECT_NEAR(s.flight_time, SyntheticJump::t_land - SyntheticJump::t_take_off, kTimeTol);

  for (int f = 0; f < 4; ++f) {
    const auto& foot = s.feet[static_cast<std::size_t>(f)];
    const double lift = f < 2 ? SyntheticJump::t_front_lift : SyntheticJump::t_take_off;
    SCOPED_TRACE(foot.name);
    ASSERT_EQ(foot.stance.size(), 2u);
    ASSERT_EQ(foot.swing.size(), 1u);
    EXPECT_NEAR(foot.stance[0].start, 0.0, kTimeTol);
    EXPECT_NEAR(foot.stance[0].end, lift, kTimeTol);
    EXPECT_NEAR(foot.stance[1].start, SyntheticJump::t_land, kTimeTol);
    EXPECT_NEAR(foot.stance[1].end, SyntheticJump::t_end, kTimeTol);
    EXPECT_NEAR(foot.swing[0].start, lift, kTimeTol);
    EXPECT_NEAR(foot.swing[0].end, SyntheticJump::t_land, kTimeTol);
    EXPECT_NEAR(foot.lift_off_time, lift, kTimeTol);
    EXPECT_NEAR(foot.touch_down_time, SyntheticJump::t_land, kTimeTol);
    EXPECT_NEAR(foot.stance_time, lift + (SyntheticJump::t_end - SyntheticJump::t_land), kTimeTol);
  }
  EXPECT_EQ(s.feet[0].name, "FL");
  EXPECT_EQ(s.feet[3].name, "RR");
}

TEST(PrimitiveSummary, ApexIsTheBallisticApex) {
  const auto s = summarize(centaur::test::makeSyntheticJump("jump"));
  // Apex of the ballistic arc: t = t_to + v/g, gain = a t_to^2 / 2 + v^2 / (2 g) above the start.
  EXPECT_NEAR(s.apex_time, SyntheticJump::apexTime(), 1e-3);
  EXPECT_NEAR(s.apex_gain, SyntheticJump::apexGain(), 1e-6);
  EXPECT_NEAR(s.start_height, SyntheticJump::z0, 1e-12);
  EXPECT_NEAR(s.apex_height, SyntheticJump::z0 + SyntheticJump::apexGain(), 1e-6);
}

TEST(PrimitiveSummary, PeakForcesAndTorques) {
  const auto s = summarize(centaur::test::makeSyntheticJump("jump"));
  // Push-off: four feet share m (g + a_z) vertically and m a_x forward; in the last 10 ms before take-off
  // the two rear feet carry it alone.
  const double fz4 = SyntheticJump::pushForceZPerFoot();
  const double fx4 = SyntheticJump::mass * SyntheticJump::ax / 4.0;
  for (int f = 0; f < 2; ++f) {  // front
    const auto& foot = s.feet[static_cast<std::size_t>(f)];
    EXPECT_NEAR(foot.peak_force_z, fz4, 1e-9);
    EXPECT_NEAR(foot.peak_force_z_time, 0.0, kTimeTol);
    EXPECT_NEAR(foot.peak_force_norm, std::hypot(fz4, fx4), 1e-9);
  }
  for (int f = 2; f < 4; ++f) {  // rear
    const auto& foot = s.feet[static_cast<std::size_t>(f)];
    EXPECT_NEAR(foot.peak_force_z, 2.0 * fz4, 1e-9);
    EXPECT_NEAR(foot.peak_force_z_time, SyntheticJump::t_front_lift, kTimeTol);
    EXPECT_NEAR(foot.peak_force_norm, 2.0 * std::hypot(fz4, fx4), 1e-9);
  }
  // tau = -(force in the waist frame): its peak magnitude is the largest force norm component-wise,
  // reached by a rear foot in the last 10 ms of push-off.
  EXPECT_GT(s.peak_abs_tau, 1.9 * fz4);
  EXPECT_LE(s.peak_abs_tau, 2.0 * std::hypot(fz4, fx4) + 1e-9);
  EXPECT_GE(s.peak_abs_tau_joint, 6);
  EXPECT_GE(s.peak_abs_tau_time, SyntheticJump::t_front_lift - kTimeTol);
  EXPECT_LT(s.peak_abs_tau_time, SyntheticJump::t_take_off);
  EXPECT_EQ(s.solve.status, "solved");
  EXPECT_EQ(s.solve.iterations, 42);
}

TEST(PrimitiveSummary, NoFlightWhenAFootStaysDownAndOpenEndedFlight) {
  auto p = centaur::test::makeSyntheticJump("half");
  p.contact.col(0).setOnes();  // FL never lifts: no flight phase
  auto s = summarize(p);
  EXPECT_TRUE(s.flight.empty());
  EXPECT_TRUE(std::isnan(s.take_off_time));
  EXPECT_TRUE(std::isnan(s.touch_down_time));
  EXPECT_EQ(s.flight_time, 0.0);
  EXPECT_TRUE(std::isnan(s.feet[0].lift_off_time));
  EXPECT_NEAR(s.feet[1].lift_off_time, SyntheticJump::t_front_lift, kTimeTol);

  auto q = centaur::test::makeSyntheticJump("never-lands");
  q.contact.bottomRows(401).setZero();  // airborne from 0.6 to the end as well
  s = summarize(q);
  ASSERT_EQ(s.flight.size(), 1u);
  EXPECT_NEAR(s.take_off_time, SyntheticJump::t_take_off, kTimeTol);
  EXPECT_TRUE(std::isnan(s.touch_down_time));
  EXPECT_NEAR(s.flight_time, SyntheticJump::t_end - SyntheticJump::t_take_off, kTimeTol);
  EXPECT_TRUE(std::isnan(s.feet[2].touch_down_time));

  auto bad = centaur::test::makeSyntheticJump("bad");
  bad.force.conservativeResize(10, Eigen::NoChange);
  EXPECT_THROW(summarize(bad), std::invalid_argument);
}
