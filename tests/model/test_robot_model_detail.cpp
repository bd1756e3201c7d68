// ctest-labels: unit
// RobotModel::update with a partial Detail gives exactly the quantities of a full update that the level promises
// at a random state: kMomentum the kinematic and centroidal ones (frame poses, Jacobians, CoM, A, h, Jcom, g) and
// leaves the dynamics of the last full update untouched; kDynamics the kinematics, mass matrix and bias forces and
// leaves the momentum data untouched; kKinematics the frame poses, velocities, Jacobians and CoM position;
// kJacobians the frame poses, Jacobians and CoM position.
#include <gtest/gtest.h>

#include <random>

#include "model/robot_model.hpp"

using namespace centaur;

namespace {
const std::string path = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

void randomState(const RobotModel& model, Eigen::VectorXd& q, Eigen::VectorXd& v) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  q.resize(model.nq());
  v.resize(model.nv());
  for (int i = 0; i < q.size(); ++i) q[i] = u(rng);
  q.segment<4>(3).normalize();
  q.tail(model.numJoints()) += model.homeJoints();
  for (int i = 0; i < v.size(); ++i) v[i] = 2.0 * u(rng);
}

void expectSameKinematics(const RobotModel& full, const RobotModel& part, bool velocities = true) {
  RowMatrixXd J1(6, full.nv()), J2(6, full.nv());
  EXPECT_TRUE(full.com().isApprox(part.com(), 1e-12));
  for (const char* f : {"pelvis", "wheel_centre_1", "wheel_centre_4", "wheel_2"}) {
    const int id = full.frameId(f);
    EXPECT_TRUE(full.framePose(id).matrix().isApprox(part.framePose(id).matrix(), 1e-12)) << f;
    if (velocities) {
      EXPECT_TRUE(full.frameVelocity(id).isApprox(part.frameVelocity(id), 1e-12)) << f;
    }
    full.frameJacobian(id, J1);
    part.frameJacobian(id, J2);
    EXPECT_TRUE(J1.isApprox(J2, 1e-12)) << f;
  }
}

// Jacobian of the wheel's material point 7.8 cm below its centre (its ground contact point at rest)
void expectSameContactJacobian(const RobotModel& full, const RobotModel& part, const char* wheel_name) {
  RowMatrixXd J1(3, full.nv()), J2(3, full.nv());
  const int wheel = full.frameId(wheel_name);
  const Eigen::Vector3d contact = full.framePose(wheel).translation() - Eigen::Vector3d(0.0, 0.0, 0.078);
  full.worldPointJacobian(wheel, contact, J1);
  part.worldPointJacobian(wheel, contact, J2);
  EXPECT_TRUE(J1.isApprox(J2, 1e-12)) << wheel_name;
}
}  // namespace

TEST(RobotModelDetail, MomentumLevelMatchesTheFullUpdate) {
  RobotModel full(path), part(path);
  Eigen::VectorXd q, v;
  randomState(full, q, v);
  full.update(q, v);
  part.update(0.9 * q, v);  // a full update elsewhere first: its dynamics must stay
  const RowMatrixXd M_before = [&] { RowMatrixXd M(part.nv(), part.nv()); part.massMatrix(M); return M; }();
  part.update(q, v, RobotModel::Detail::kMomentum);

  RowMatrixXd A1(6, full.nv()), A2(6, full.nv()), J1(6, full.nv()), J2(6, full.nv());
  full.centroidalMomentumMatrix(A1);
  part.centroidalMomentumMatrix(A2);
  EXPECT_TRUE(A1.isApprox(A2, 1e-12));
  EXPECT_TRUE(full.com().isApprox(part.com(), 1e-12));
  EXPECT_TRUE(full.comVelocity().isApprox(part.comVelocity(), 1e-12));
  EXPECT_TRUE(full.centroidalMomentum().isApprox(part.centroidalMomentum(), 1e-12));
  for (const char* f : {"pelvis", "wheel_centre_1", "wheel_centre_4"}) {
    const int id = full.frameId(f);
    EXPECT_TRUE(full.framePose(id).matrix().isApprox(part.framePose(id).matrix(), 1e-12)) << f;
    full.frameJacobian(id, J1);
    part.frameJacobian(id, J2);
    EXPECT_TRUE(J1.isApprox(J2, 1e-12)) << f;
  }
  RowMatrixXd M_after(part.nv(), part.nv());
  part.massMatrix(M_after);
  EXPECT_TRUE(M_after.isApprox(M_before, 0.0));  // untouched by the partial update
}

TEST(RobotModelDetail, DynamicsLevelMatchesTheFullUpdateAndKeepsTheMomentumData) {
  RobotModel full(path), part(path);
  Eigen::VectorXd q, v;
  randomState(full, q, v);
  full.update(q, v);
  part.update(0.9 * q, v);
  const RobotModel::Vector6d h_before = part.centroidalMomentum();
  part.update(q, v, RobotModel::Detail::kDynamics);
  expectSameKinematics(full, part);
  RowMatrixXd M1(full.nv(), full.nv()), M2(full.nv(), full.nv());
  full.massMatrix(M1);
  part.massMatrix(M2);
  EXPECT_TRUE(M1.isApprox(M2, 1e-12));
  Eigen::VectorXd b1(full.nv()), b2(full.nv());
  full.biasForces(b1);
  part.biasForces(b2);
  EXPECT_TRUE(b1.isApprox(b2, 1e-12));
  EXPECT_TRUE(part.centroidalMomentum().isApprox(h_before, 0.0));  // not recomputed
}

TEST(RobotModelDetail, KinematicsLevelMatchesTheFullUpdate) {
  RobotModel full(path), part(path);
  Eigen::VectorXd q, v;
  randomState(full, q, v);
  full.update(q, v);
  part.update(q, v, RobotModel::Detail::kKinematics);
  expectSameKinematics(full, part);
  expectSameContactJacobian(full, part, "wheel_3");
}

TEST(RobotModelDetail, JacobiansLevelMatchesTheFullUpdateWithoutVelocities) {
  RobotModel full(path), part(path);
  Eigen::VectorXd q, v;
  randomState(full, q, v);
  full.update(q, v);
  part.update(q, v, RobotModel::Detail::kJacobians);
  expectSameKinematics(full, part, /*velocities=*/false);
  expectSameContactJacobian(full, part, "wheel_1");
}
