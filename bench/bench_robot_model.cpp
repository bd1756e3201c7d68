// Cost of the whole-robot model per control tick: RobotModel::update() (kinematics, CoM, mass matrix,
// bias forces, centroidal momentum matrix, Jdot v data) and typical queries; and one base-estimator step.
#include <benchmark/benchmark.h>

#include <string>

#include "controller/base_estimator.hpp"
#include "model/robot_model.hpp"

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

void homeState(const centaur::RobotModel& model, Eigen::VectorXd& q, Eigen::VectorXd& v) {
  q = Eigen::VectorXd::Zero(model.nq());
  q[2] = 0.71885;
  q[3] = 1.0;
  q.tail(model.numJoints()) = model.homeJoints();
  v = Eigen::VectorXd::Constant(model.nv(), 0.1);
}

void BM_RobotModelUpdate(benchmark::State& st) {
  centaur::RobotModel model(kModel);
  Eigen::VectorXd q, v;
  homeState(model, q, v);
  for (auto _ : st) {
    q[10] += 1e-9;
    model.update(q, v);
    benchmark::DoNotOptimize(model.com());
  }
}
BENCHMARK(BM_RobotModelUpdate);

void BM_RobotModelUpdateAndQueries(benchmark::State& st) {
  centaur::RobotModel model(kModel);
  Eigen::VectorXd q, v;
  homeState(model, q, v);
  const int nv = model.nv();
  centaur::RowMatrixXd J(6, nv), Jc(3, nv), A(6, nv), M(nv, nv);
  Eigen::VectorXd b(nv), g(nv);
  int wheels[4];
  for (int k = 0; k < 4; ++k) wheels[k] = model.frameId("wheel_" + std::to_string(k + 1));
  for (auto _ : st) {
    q[10] += 1e-9;
    model.update(q, v);
    for (int k = 0; k < 4; ++k) {
      model.frameJacobian(wheels[k], J);
      benchmark::DoNotOptimize(model.frameBiasAcceleration(wheels[k]));
    }
    model.comJacobian(Jc);
    model.centroidalMomentumMatrix(A);
    model.massMatrix(M);
    model.biasForces(b);
    model.gravityForces(g);
    benchmark::DoNotOptimize(M.data());
  }
}
BENCHMARK(BM_RobotModelUpdateAndQueries);

void BM_BaseEstimatorUpdate(benchmark::State& st) {
  centaur::BaseEstimator est;
  est.init(kModel);
  centaur::RobotModel model(kModel);
  centaur::RobotState s;
  s.resize(model.numJoints());
  s.q = model.homeJoints();
  const bool stance[4] = {true, true, true, true};
  for (auto _ : st) {
    s.t += 0.001;
    est.update(s, stance);
    benchmark::DoNotOptimize(est.q().data());
  }
}
BENCHMARK(BM_BaseEstimatorUpdate);

}  // namespace

BENCHMARK_MAIN();
