// ctest-labels: unit
// RobotModel::update with Detail::kMomentum gives exactly the kinematic and centroidal quantities of a full
// update (frame poses, Jacobians, CoM, A, h, Jcom, g) at a random state, and leaves the dynamics of the last
// full update untouched.
#include <gtest/gtest.h>

#include <random>

#include "model/robot_model.hpp"

using namespace centaur;

TEST(RobotModelDetail, MomentumLevelMatchesTheFullUpdate) {
  const std::string path = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";
  RobotModel full(path), part(path);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  Eigen::VectorXd q(full.nq()), v(full.nv());
  for (int i = 0; i < q.size(); ++i) q[i] = u(rng);
  q.segment<4>(3).normalize();
  q.tail(full.numJoints()) += full.homeJoints();
  for (int i = 0; i < v.size(); ++i) v[i] = 2.0 * u(rng);
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
