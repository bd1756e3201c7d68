// Cost per control tick of the contact force distribution (4 stance wheels, and the relaxed fallback when
// the hard floating-base rows are infeasible) and of one contact-detector step, on a RobotModel already
// updated by the caller (RobotModel::update() is measured in bench_robot_model).
#include <benchmark/benchmark.h>

#include <string>

#include "controller/contact_detector.hpp"
#include "controller/force_distribution.hpp"
#include "model/robot_model.hpp"

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

void homeState(centaur::RobotModel& model) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.nq());
  q[2] = 0.71885;
  q[3] = 1.0;
  q.tail(model.numJoints()) = model.homeJoints();
  model.update(q, Eigen::VectorXd::Constant(model.nv(), 0.05));
}

// forward_acc: desired base acceleration along x [m/s^2] (10 -> infeasible with mu = 0.6 -> relaxed QP).
void runDistribution(benchmark::State& st, double forward_acc, int stance_wheels) {
  centaur::RobotModel model(kModel);
  homeState(model);
  centaur::ForceDistribution fd;
  fd.init(model);
  Eigen::VectorXd vdot = Eigen::VectorXd::Zero(model.nv());
  vdot[0] = forward_acc;
  centaur::ForceDistribution::Forces Fd = centaur::ForceDistribution::Forces::Zero();
  Fd.row(2).setConstant(model.totalMass() * 9.81 / stance_wheels);
  centaur::WheelContacts c;
  for (int k = stance_wheels; k < 4; ++k) c.stance[k] = false;
  int bad = 0;
  for (auto _ : st) {
    Fd(2, 0) += 1e-9;  // defeat any caching
    const auto s = fd.compute(model, vdot, Fd, c);
    bad += s == centaur::ForceDistributionStatus::kFailed;
    benchmark::DoNotOptimize(fd.tauFeedforward().data());
  }
  st.counters["failed"] = bad;
  st.counters["qp_iterations"] = fd.iterations();
}

void BM_ForceDistribution4Stance(benchmark::State& st) { runDistribution(st, 0.0, 4); }
BENCHMARK(BM_ForceDistribution4Stance);
void BM_ForceDistribution3Stance(benchmark::State& st) { runDistribution(st, 0.0, 3); }
BENCHMARK(BM_ForceDistribution3Stance);
void BM_ForceDistribution4StanceRelaxed(benchmark::State& st) { runDistribution(st, 10.0, 4); }
BENCHMARK(BM_ForceDistribution4StanceRelaxed);

// Worst case for the warm start: every call alternates the stance set (4 / 3 wheels) and a desired force
// that is inside / outside the friction pyramids, so the active set changes at every call.
void BM_ForceDistributionAlternating(benchmark::State& st) {
  centaur::RobotModel model(kModel);
  homeState(model);
  centaur::ForceDistribution fd;
  fd.init(model);
  const Eigen::VectorXd vdot = Eigen::VectorXd::Zero(model.nv());
  centaur::ForceDistribution::Forces Fd[2];
  Fd[0].setZero();
  Fd[0].row(2).setConstant(model.totalMass() * 9.81 / 4);
  Fd[1] = Fd[0];
  Fd[1].row(0) << 200.0, 200.0, -200.0, -200.0;  // squeeze: consistent, beyond mu * normal at the rear
  centaur::WheelContacts c[2];
  c[1].stance[3] = false;
  int bad = 0, i = 0, iterations = 0;
  for (auto _ : st) {
    const auto s = fd.compute(model, vdot, Fd[i & 1], c[(i >> 1) & 1]);
    bad += s == centaur::ForceDistributionStatus::kFailed;
    iterations += fd.iterations();
    ++i;
    benchmark::DoNotOptimize(fd.tauFeedforward().data());
  }
  st.counters["failed"] = bad;
  st.counters["qp_iterations_mean"] = i > 0 ? static_cast<double>(iterations) / i : 0.0;
}
BENCHMARK(BM_ForceDistributionAlternating);

void BM_ContactDetectorUpdate(benchmark::State& st) {
  centaur::RobotModel model(kModel);
  homeState(model);
  centaur::ContactDetector det;
  det.init(model);
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(model.numJoints());
  for (auto _ : st) {
    tau[0] += 1e-9;
    benchmark::DoNotOptimize(det.update(model, tau, 0.001));
  }
}
BENCHMARK(BM_ContactDetectorUpdate);

}  // namespace

BENCHMARK_MAIN();
