// ctest-labels: physics
// The arm-flywheel plan (stabilizer 3) with the shipped defaults: converges; periodic (first = last state);
// within every bound at every 1 kHz sample (joint ranges of both arms, velocity and torque limits, hand box);
// the samples integrate the knots consistently; the mean angular momentum is about +y and dominates x and z;
// the HDF5 round trip is exact; append keeps other groups; bad files and configuration keys are refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "model/chain_from_mjcf.hpp"
#include "planner/arm_flywheel_problem.hpp"
#include "data/arm_trajectory_io.hpp"
#include "support/temp_dir.hpp"

using namespace centaur;
using namespace centaur::planner;
using namespace centaur::data;

namespace {

const ArmTrajectory& plan() {
  static const ArmTrajectory tr = planArmFlywheel(loadArmFlywheelConfig("", {}));
  return tr;
}

}  // namespace

TEST(ArmFlywheel, ConvergesToAPeriodicTrajectory) {
  const ArmTrajectory& tr = plan();
  ASSERT_TRUE(tr.solve.solved()) << tr.solve.status;
  ASSERT_EQ(tr.q.cols(), 7);
  const Eigen::Index N = tr.samples();
  ASSERT_EQ(N, 1001);  // 1 kHz over T = 1 s, both ends included
  EXPECT_NEAR(tr.t[N - 1], tr.period, 1e-12);
  EXPECT_LT((tr.q.row(0) - tr.q.row(N - 1)).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((tr.qd.row(0) - tr.qd.row(N - 1)).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((tr.knot_x.row(0) - tr.knot_x.row(tr.knot_x.rows() - 1)).cwiseAbs().maxCoeff(), 1e-6);
  // the samples are the exact integration of the knots: they pass through every knot
  const int Ns = static_cast<int>(tr.knot_u.rows());
  for (int k = 0; k <= Ns; ++k) {
    const Eigen::Index j = k * (N - 1) / Ns;
    EXPECT_LT((tr.q.row(j) - tr.knot_x.row(k).head(7)).cwiseAbs().maxCoeff(), 1e-6) << "knot " << k;
    EXPECT_LT((tr.qd.row(j) - tr.knot_x.row(k).tail(7)).cwiseAbs().maxCoeff(), 1e-6) << "knot " << k;
  }
  // velocities are the derivative of positions (central differences of the samples; exact for the piecewise
  // quadratic q except next to a knot, where qdd jumps: error <= |qdd| dt / 2)
  const double dt = tr.t[1] - tr.t[0];
  const double amax = tr.qdd.cwiseAbs().maxCoeff();
  for (Eigen::Index j = 1; j + 1 < N; ++j) {
    ASSERT_LT(((tr.q.row(j + 1) - tr.q.row(j - 1)) / (2 * dt) - tr.qd.row(j)).cwiseAbs().maxCoeff(), 0.5 * amax * dt + 1e-9);
  }
}

TEST(ArmFlywheel, EverySampleIsWithinEveryBound) {
  const ArmTrajectory& tr = plan();
  // the model limits of BOTH arms (the right arm replays the mirror image)
  const auto left = model::chainFromMjcf(model::centauroMjcfPath(), model::centauroLeftArmSpec());
  model::ChainSpec rs;
  for (int i = 1; i <= 7; ++i) rs.joints.push_back("j_arm2_" + std::to_string(i));
  rs.ee_frame = "ball2_tip";
  const auto right = model::chainFromMjcf(model::centauroMjcfPath(), rs);
  const auto s = armMirrorSigns();
  for (Eigen::Index k = 0; k < tr.samples(); ++k) {
    for (int j = 0; j < 7; ++j) {
      const double q = tr.q(k, j), qr = s[j] * q;
      ASSERT_GE(q, left.links[j].q_min) << "sample " << k << " joint " << j;
      ASSERT_LE(q, left.links[j].q_max) << "sample " << k << " joint " << j;
      ASSERT_GE(qr, right.links[j].q_min) << "sample " << k << " joint " << j << " (mirror)";
      ASSERT_LE(qr, right.links[j].q_max) << "sample " << k << " joint " << j << " (mirror)";
      ASSERT_LE(std::abs(tr.qd(k, j)), std::min(left.links[j].qd_max, right.links[j].qd_max));
      ASSERT_LE(std::abs(tr.tau(k, j)), std::min(left.links[j].tau_max, right.links[j].tau_max));
      // the OCP's own (tighter) bounds hold at the knots; between them within a small tolerance
      ASSERT_GE(q, tr.q_min[j] - 0.01);
      ASSERT_LE(q, tr.q_max[j] + 0.01);
      ASSERT_LE(std::abs(tr.qd(k, j)), tr.qd_max[j] + 1e-6);
      ASSERT_LE(std::abs(tr.tau(k, j)), 1.05 * tr.tau_max[j]);
    }
    for (int a = 0; a < 3; ++a) {  // hand box, 5 mm between knots
      ASSERT_GE(tr.ee_pos(k, a), tr.ee_box_min[a] - 0.005) << "sample " << k << " axis " << a;
      ASSERT_LE(tr.ee_pos(k, a), tr.ee_box_max[a] + 0.005) << "sample " << k << " axis " << a;
    }
  }
}

TEST(ArmFlywheel, MomentumIsAboutPlusYAndDominant) {
  const ArmTrajectory& tr = plan();
  const Eigen::Vector3d mean = tr.h_ang.colwise().mean();
  EXPECT_GT(mean.y(), 1.0);  // N m s, one arm over one period
  EXPECT_GT(mean.y(), 1.5 * std::abs(mean.x()));
  EXPECT_GT(mean.y(), 5.0 * std::abs(mean.z()));
  // the mean momentum of a periodic motion is a property of the loop, not of the reference point:
  // it equals the mean about any other fixed point (the mean linear momentum vanishes over a period)
  const auto chain = model::chainFromMjcf(model::centauroMjcfPath(), model::centauroLeftArmSpec());
  model::SerialChain shifted = chain;
  shifted.momentum_point += Eigen::Vector3d(0.3, -0.2, 0.5);
  double sum = 0.0;
  for (Eigen::Index k = 0; k + 1 < tr.samples(); ++k) {
    const Eigen::VectorXd q = tr.q.row(k).transpose(), qd = tr.qd.row(k).transpose();
    sum += model::chainAngularMomentum(shifted, q.data(), qd.data()).y();
  }
  const double mean_excl_last = tr.h_ang.col(1).head(tr.samples() - 1).mean();
  EXPECT_NEAR(sum / (tr.samples() - 1), mean_excl_last, 1e-3 * std::abs(mean_excl_last));
}

TEST(ArmFlywheel, OptionalCentreOfMassBoundHolds) {
  const ArmFlywheelConfig cfg = loadArmFlywheelConfig("", {"workspace.com_x_offset=0.1"});
  const ArmFlywheelProblem problem(cfg);
  const ArmTrajectory tr = problem.toTrajectory(problem.solve());
  ASSERT_TRUE(tr.solve.solved());
  const auto& chain = problem.chain();
  const double cx = model::chainCom(chain, chain.homePosture().data()).x();
  for (Eigen::Index k = 0; k < tr.samples(); ++k) {
    const Eigen::VectorXd q = tr.q.row(k).transpose();
    ASSERT_NEAR(model::chainCom(chain, q.data()).x(), cx, 0.1 + 0.002) << "sample " << k;
  }
  // a tighter posture costs momentum, but the arm still spins the same way
  const double h = tr.h_ang.col(1).mean();
  EXPECT_GT(h, 0.5);
  EXPECT_LT(h, plan().h_ang.col(1).mean());
}

TEST(ArmFlywheel, FileRoundTripAndAppend) {
  const ArmTrajectory& tr = plan();
  centaur_test::TempDir dir;
  const std::string f = dir.file("arm.h5");
  writeArmTrajectory(f, tr);
  const ArmTrajectory back = readArmTrajectory(f);
  EXPECT_EQ(back.joint_names, tr.joint_names);
  EXPECT_EQ(back.q, tr.q);
  EXPECT_EQ(back.tau, tr.tau);
  EXPECT_EQ(back.h_ang, tr.h_ang);
  EXPECT_EQ(back.knot_x, tr.knot_x);
  EXPECT_EQ(back.qd_max_model, tr.qd_max_model);
  EXPECT_EQ(back.solve.status, "solved");
  EXPECT_EQ(back.solve.iterations, tr.solve.iterations);
  EXPECT_EQ(back.solve.backend, "ipopt");  // the default backend, recorded as solve_backend
  EXPECT_EQ(back.config_yaml, tr.config_yaml);
  // append: a second group next to the first one, which stays
  ArmTrajectory other = tr;
  other.name = "arm-flywheel-slow";
  writeArmTrajectory(f, other, true);
  EXPECT_EQ(readArmTrajectory(f, "arm-flywheel").q, tr.q);
  EXPECT_EQ(readArmTrajectory(f, "arm-flywheel-slow").q, tr.q);
  // replace (no append): only the new group
  writeArmTrajectory(f, other, false);
  EXPECT_THROW(readArmTrajectory(f, "arm-flywheel"), InputError);
  // missing / not HDF5
  EXPECT_THROW(readArmTrajectory(dir.file("none.h5")), InputError);
  const std::string junk = dir.file("junk.h5");
  { std::ofstream(junk) << "not hdf5"; }
  EXPECT_THROW(readArmTrajectory(junk), InputError);
}

TEST(ArmFlywheel, ConfigurationIsValidated) {
  EXPECT_NO_THROW(loadArmFlywheelConfig(std::string(CENTAUR_SOURCE_DIR) + "/config/arm-flywheel.yaml", {}));
  // the shipped file equals the embedded defaults
  const YAML::Node shipped = loadYamlFile(std::string(CENTAUR_SOURCE_DIR) + "/config/arm-flywheel.yaml");
  EXPECT_EQ(toYamlString(shipped), toYamlString(loadYamlString(defaultArmFlywheelYaml(), "d")));
  EXPECT_THROW(loadArmFlywheelConfig("", {"cost.bogus=1"}), InputError);
  EXPECT_THROW(loadArmFlywheelConfig("", {"horizon.intervals=2"}), InputError);
  EXPECT_THROW(loadArmFlywheelConfig("", {"workspace.x=[1.0, 0.5]"}), InputError);
  EXPECT_THROW(loadArmFlywheelConfig("", {"cost.momentum_mode=linear", "cost.joint_velocity=0"}), InputError);
  try {
    loadArmFlywheelConfig("", {"horizon.period=50"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("horizon.period"), std::string::npos) << e.what();
  }
}
