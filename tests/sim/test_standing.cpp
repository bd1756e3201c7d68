// ctest-labels: sim integration
// CENTAURO standing 10 s in MuJoCo with the standing controller (joint impedance + gravity-compensating
// feed-forward from static wheel forces): pelvis drift < 1 cm, pitch and roll < 0.5 deg, no joint beyond
// its limits. Plus a rendered snapshot of CENTAURO that is not blank.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "controller/standing_controller.hpp"
#include "sim/renderer.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_runner.hpp"

using namespace centaur;
using namespace centaur::sim;

TEST(Standing, CentauroStandsTenSecondsWithinOneCentimetreAndHalfADegree) {
  const Scenario* stand = findScenario("stand");
  ASSERT_NE(stand, nullptr);
  const RunSummary s = runScenario(*stand, "", {"duration=10"}, {}, RunOutputs{});
  EXPECT_EQ(s.outcome, "success");
  EXPECT_NEAR(s.duration_s, 10.0, 1e-6);
  EXPECT_EQ(s.control_periods, 10000);
  EXPECT_LT(s.pelvis_drift_m, 0.01);
  EXPECT_LT(s.peak_pitch_deg, 0.5);
  EXPECT_LT(s.peak_roll_deg, 0.5);
  EXPECT_LE(s.max_joint_limit_violation, 0.0);
  EXPECT_LT(s.max_torque_ratio, 1.0);  // never saturated
}

TEST(Standing, FeedforwardWheelForcesBalanceTheWeight) {
  // The static split must carry m g in total, push (not pull) on every wheel and put more load on the
  // front wheels (the whole-body CoM is 0.105 m ahead of the pelvis, between the wheels at x = +-0.35).
  SimConfig cfg = loadSimConfig("", "", {});
  MujocoRobot robot(cfg.robot);
  StandingController ctrl(cfg.robot.model_path, StandingParams{});
  RobotState state;
  state.resize(robot.numJoints());
  JointCommand command;
  robot.read(state);
  ctrl.start(state, command);
  const double weight = ctrl.model().totalMass() * 9.81;
  const Eigen::Matrix<double, 3, 4>& F = ctrl.wheelForces();
  EXPECT_NEAR(F.row(2).sum(), weight, 1e-6 * weight);
  EXPECT_NEAR(F.row(0).sum(), 0.0, 1e-6 * weight);
  EXPECT_NEAR(F.row(1).sum(), 0.0, 1e-6 * weight);
  for (int k = 0; k < 4; ++k) EXPECT_GT(F(2, k), 0.1 * weight) << "wheel " << k + 1;
  EXPECT_GT(F(2, 0) + F(2, 1), F(2, 2) + F(2, 3));  // wheel_1/2 are the front wheels
  // After settling in simulation, the simulator's wheel forces agree with the controller's split.
  for (int k = 0; k < 2000; ++k) robot.controlPeriod(ctrl, state, command);
  Eigen::Matrix3Xd sim_f(3, 4);
  robot.contactForces(sim_f);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(sim_f(2, k), ctrl.wheelForces()(2, k), 0.05 * weight) << "wheel " << k + 1;
  }
}

TEST(Standing, SnapshotOfCentauroIsNotBlank) {
  SimConfig cfg = loadSimConfig("", "", {});
  MujocoRobot robot(cfg.robot);
  Renderer renderer(robot.model(), 320, 240, "", "pelvis", false, false);  // tracking free camera
  const auto& rgb = renderer.render(robot.data());
  const std::size_t npx = rgb.size() / 3;
  double mean = 0.0, mean2 = 0.0;
  for (auto v : rgb) {
    mean += v;
    mean2 += static_cast<double>(v) * v;
  }
  mean /= static_cast<double>(rgb.size());
  EXPECT_GT(mean2 / static_cast<double>(rgb.size()) - mean * mean, 100.0);
  // The robot's dark joints and tyres (materials `dark`, `tyre`: < 60 per channel) are in view;
  // the floor, wall and sky are not that dark.
  std::size_t dark = 0, black_sky = 0;
  for (std::size_t p = 0; p < rgb.size(); p += 3) {
    const int r = rgb[p], g = rgb[p + 1], b = rgb[p + 2];
    if (r == 0 && g == 0 && b == 0) ++black_sky;
    else if (r < 60 && g < 60 && b < 60) ++dark;
  }
  EXPECT_GT(dark, npx / 200) << "robot not visible";
  EXPECT_LT(black_sky, npx * 9 / 10) << "nothing rendered";
}
