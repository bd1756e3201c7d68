// ctest-labels: unit physics
// Model/Data split: workspaces on one parsed description are independent and give, bit for bit, what a model
// parsed on its own gives, whatever the other workspaces do in between.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "model/robot_model.hpp"

using centaur::RobotModel;
using centaur::RowMatrixXd;

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

// A random configuration and velocity near home.
void randomState(const RobotModel& m, std::mt19937& rng, Eigen::VectorXd& q, Eigen::VectorXd& v) {
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  q.setZero(m.nq());
  v.setZero(m.nv());
  q.head<3>() << u(rng), u(rng), 0.7 + u(rng);
  Eigen::Quaterniond r(1.0, u(rng), u(rng), u(rng));
  r.normalize();
  q.segment<4>(3) << r.w(), r.x(), r.y(), r.z();
  for (int i = 0; i < m.numJoints(); ++i) q[7 + i] = m.homeJoints()[i] + u(rng);
  for (int i = 0; i < m.nv(); ++i) v[i] = 3.0 * u(rng);
}

// Everything a controller reads after an update.
Eigen::VectorXd outputs(const RobotModel& m) {
  RowMatrixXd M(m.nv(), m.nv()), A(6, m.nv()), J(6, m.nv());
  Eigen::VectorXd b(m.nv());
  m.massMatrix(M);
  m.centroidalMomentumMatrix(A);
  m.frameJacobian(m.frameId("wheel_3"), J);
  m.biasForces(b);
  Eigen::VectorXd out(M.size() + A.size() + J.size() + b.size() + 3 + 6);
  out << Eigen::Map<const Eigen::VectorXd>(M.data(), M.size()), Eigen::Map<const Eigen::VectorXd>(A.data(), A.size()),
      Eigen::Map<const Eigen::VectorXd>(J.data(), J.size()), b, m.com(), m.centroidalMomentumBias();
  return out;
}

TEST(RobotModelShared, WorkspacesOnOneDescriptionMatchSeparateParsesBitForBit) {
  const auto description = centaur::loadRobotModel(kModel);
  RobotModel a(description), b(description);
  RobotModel alone(kModel);
  EXPECT_EQ(a.description(), b.description());
  EXPECT_NE(alone.description(), a.description());
  EXPECT_EQ(a.jointNames(), alone.jointNames());
  std::mt19937 rng(7);
  Eigen::VectorXd q, v, q2, v2;
  for (int trial = 0; trial < 20; ++trial) {
    randomState(a, rng, q, v);
    randomState(a, rng, q2, v2);
    a.update(q, v);
    b.update(q2, v2);  // the other workspace moves in between
    alone.update(q, v);
    const Eigen::VectorXd oa = outputs(a), oalone = outputs(alone);
    ASSERT_EQ(oa.size(), oalone.size());
    for (Eigen::Index i = 0; i < oa.size(); ++i) ASSERT_EQ(oa[i], oalone[i]) << "trial " << trial << " entry " << i;
    EXPECT_EQ(b.q(), q2);
  }
}

TEST(RobotModelShared, DescriptionOutlivesTheFirstWorkspace) {
  auto first = std::make_unique<RobotModel>(kModel);
  RobotModel second(first->description());
  first.reset();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(second.nq()), v = Eigen::VectorXd::Zero(second.nv());
  q[2] = 0.7;
  q[3] = 1.0;
  q.tail(second.numJoints()) = second.homeJoints();
  second.update(q, v);
  RobotModel fresh(kModel);
  fresh.update(q, v);
  EXPECT_NEAR(second.totalMass(), 93.113, 1e-3);
  EXPECT_EQ(second.com(), fresh.com());
}

}  // namespace
