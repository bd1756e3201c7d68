// ctest-labels: unit
// RobotModel::update() and every query run without heap allocation (counted by a replaced global
// operator new).
#include <gtest/gtest.h>

#include "support/allocation_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>

#include "model/robot_model.hpp"

namespace {
}


TEST(RobotModelAllocation, UpdateAndQueriesDoNotAllocate) {
  centaur::RobotModel model(std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml");
  const int nv = model.nv();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.nq()), v = Eigen::VectorXd::Constant(nv, 0.3);
  q[2] = 0.72;
  q[3] = 1.0;
  q.tail(model.numJoints()) = model.homeJoints();
  centaur::RowMatrixXd J(6, nv), Jp(3, nv), Jc(3, nv), A(6, nv), M(nv, nv);
  Eigen::VectorXd b(nv), g(nv);
  const int f = model.frameId("wheel_1"), s = model.frameId("imu");
  ASSERT_GE(f, 0);
  ASSERT_GE(s, 0);
  double sink = 0;
  const long before = centaur_test::heapAllocations();
  for (int k = 0; k < 3; ++k) {
    q[7] += 0.01;
    model.update(q, v);
    sink += model.framePose(f).translation().x();
    model.frameJacobian(f, J);
    model.frameJacobian(s, J);
    model.pointJacobian(f, Eigen::Vector3d(0, 0, 0.01), Jp);
    model.worldPointJacobian(f, Eigen::Vector3d(0.3, 0.3, 0.0), Jp);
    sink += model.com().z();
    model.comJacobian(Jc);
    model.centroidalMomentumMatrix(A);
    model.massMatrix(M);
    model.biasForces(b);
    model.gravityForces(g);
    sink += model.frameVelocity(f)[0] + model.frameBiasAcceleration(s)[1];
    sink += model.pointBiasAcceleration(f, Eigen::Vector3d(0, 0, 0.01))[2];
    sink += model.worldPointBiasAcceleration(f, Eigen::Vector3d(0.3, 0.3, 0.0))[2];
    sink += model.comVelocity()[0] + model.comBiasAcceleration()[0];
    sink += model.centroidalMomentum()[0] + model.centroidalMomentumBias()[0];
  }
  const long after = centaur_test::heapAllocations();
  EXPECT_EQ(after - before, 0);
  EXPECT_TRUE(std::isfinite(sink));
  // sanity: the counter does count
  double* volatile probe = new double[4];
  delete[] probe;
  EXPECT_GT(centaur_test::heapAllocations(), after);
}
