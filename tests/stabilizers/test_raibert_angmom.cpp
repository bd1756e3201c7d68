// ctest-labels: unit
// The Raibert-like and angular-momentum stabilizers against the whole-robot model: the default Raibert
// directions make the arms swing "in the direction of falling" (a positive pitch rate yields positive
// centroidal angular momentum about y from the arm motion), the Raibert posture offset integrates the pitch
// rate exactly (gain * direction * angle, leak off), the angmom stabilizer commands omega_fb,d = -gain *
// w_R_imu * omega_imu and h_d = 0, and neither allocates in update().
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <memory>

#include "common/yaml_reader.hpp"
#include "controller/whole_body_controller.hpp"
#include "stabilizers/angmom_stabilizer.hpp"
#include "stabilizers/raibert_stabilizer.hpp"
#include "support/allocation_counter.hpp"

using namespace centaur;

namespace {
const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

Eigen::VectorXd homeQ(const RobotModel& m) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m.nq());
  q[2] = 0.71885;
  q[3] = 1.0;
  q.tail(m.numJoints()) = m.homeJoints();
  return q;
}

/// `stab` started on the model's joints at home, and a whole-body controller with its stack.
std::unique_ptr<WholeBodyController> controllerFor(Stabilizer& stab, const RobotModel& m) {
  stab.start(m.jointNames(), m.homeJoints());
  WholeBodyParams wp;
  wp.stack_yaml = stab.stackYaml(RobotFrames());
  return std::make_unique<WholeBodyController>(kModel, wp);
}
}  // namespace

TEST(Raibert, DefaultDirectionsSwingTheArmsInTheDirectionOfFalling) {
  RobotModel m(kModel);
  m.update(homeQ(m), Eigen::VectorXd::Zero(m.nv()));
  RowMatrixXd A(6, m.nv());
  m.centroidalMomentumMatrix(A);
  const RaibertParams p;
  double h_y = 0.0;
  for (std::size_t s = 0; s < p.joints.size(); ++s) {
    const int i = m.jointIndex(p.joints[s]);
    ASSERT_GE(i, 0) << p.joints[s];
    const double contrib = A(4, 6 + i) * p.directions[s];
    EXPECT_GT(contrib, 0.0) << p.joints[s] << ": direction must give +y momentum";
    h_y += contrib * p.gains[s];
  }
  // with omega_y = 1 rad/s the default gains ask the arms for this much momentum about +y [kg m^2/s]
  EXPECT_GT(h_y, 3.0);
}

TEST(Raibert, PostureOffsetIsTheIntegratedPitchRate) {
  RaibertParams p;
  p.leak_rate = 0.0;
  RaibertStabilizer stab(p);
  RobotModel m(kModel);
  const auto wbc = controllerFor(stab, m);
  RobotState state;
  state.resize(m.numJoints());
  WholeBodyReferences refs;
  refs.resize(m.numJoints());
  const double dt = 0.001;
  state.imu_omega = Eigen::Vector3d(0.3, 0.5, -0.2);  // only the pitch rate counts
  for (int k = 0; k < 200; ++k) stab.update(state, dt, true, refs);  // 0.1 rad of pitch
  state.imu_omega.y() = -0.25;
  for (int k = 0; k < 200; ++k) stab.update(state, dt, true, refs);  // -0.05 rad: 0.05 rad in total
  for (std::size_t s = 0; s < p.joints.size(); ++s) {
    const int i = m.jointIndex(p.joints[s]);
    EXPECT_NEAR(stab.postureReference()[i] - m.homeJoints()[i], p.gains[s] * p.directions[s] * 0.05, 1e-9);
  }
  // the velocity feed-forward is the law's rate: gain * direction * omega_y (leak off, not clamped)
  for (std::size_t s = 0; s < p.joints.size(); ++s) {
    const int i = m.jointIndex(p.joints[s]);
    EXPECT_NEAR(stab.postureVelocity()[i], p.gains[s] * p.directions[s] * -0.25, 1e-9);
  }
  // clamped at max_offset
  state.imu_omega.y() = 100.0;
  for (int k = 0; k < 1000; ++k) stab.update(state, dt, true, refs);
  const int e = m.jointIndex("j_arm1_4");
  EXPECT_NEAR(stab.postureReference()[e] - m.homeJoints()[e], p.max_offset, 1e-12);
}

TEST(Angmom, PelvisReferenceIsMinusTheWorldImuRate) {
  AngmomParams p;
  p.gain = 0.5;
  AngmomStabilizer stab(p);
  RobotModel m(kModel);
  const auto wbc = controllerFor(stab, m);
  RobotState state;
  state.resize(m.numJoints());
  WholeBodyReferences refs;
  refs.resize(m.numJoints());
  state.imu_quat = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
  state.imu_omega = Eigen::Vector3d(0.1, 0.7, 0.0);
  stab.update(state, 0.001, true, refs);
  EXPECT_TRUE(refs.set & WholeBodyReferences::kPelvisAngularVelocity);
  wbc->setReferences(refs);
  const auto& pelvis = wbc->stack().tasks.at("pelvis");
  pelvis->update();  // b = omega_fb,d (lambda 1) on the model's last update
  const Eigen::Vector3d expected = -0.5 * (state.imu_quat * state.imu_omega);
  EXPECT_TRUE(pelvis->b().head<3>().isApprox(expected, 1e-12)) << pelvis->b().transpose();
}

TEST(Stabilizers, UpdateNeverAllocates) {
  RobotModel m(kModel);
  RaibertStabilizer raibert{RaibertParams{}};
  AngmomStabilizer angmom{AngmomParams{}};
  raibert.start(m.jointNames(), m.homeJoints());
  const auto wbc = controllerFor(angmom, m);
  RobotState state;
  state.resize(m.numJoints());
  WholeBodyReferences refs;
  refs.resize(m.numJoints());
  state.imu_omega = Eigen::Vector3d(0.1, 0.7, 0.0);
  const long before = centaur_test::heapAllocations();
  for (int k = 0; k < 1000; ++k) {
    raibert.update(state, 0.001, true, refs);
    wbc->setReferences(refs);
    angmom.update(state, 0.001, true, refs);
    wbc->setReferences(refs);
  }
  EXPECT_EQ(centaur_test::heapAllocations() - before, 0);
}

TEST(Stabilizers, AReferenceWithoutItsTaskIsAnError) {
  // The angular-momentum stabilizer sets the pelvis angular velocity and the momentum: a posture-only stack has
  // neither task, and the references would be dropped without a word.
  RobotModel m(kModel);
  AngmomStabilizer angmom{AngmomParams{}};
  RaibertStabilizer raibert{RaibertParams{}};
  WholeBodyParams wp;
  wp.stack_yaml = raibert.stackYaml(RobotFrames());
  WholeBodyController wbc(kModel, wp);
  EXPECT_NO_THROW(wbc.requireTasks(raibert.references(), "raibert"));
  try {
    wbc.requireTasks(angmom.references(), "stabilizer 'angmom'");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("stabilizer 'angmom' sets the pelvis angular velocity"), std::string::npos) << e.what();
  }
}
