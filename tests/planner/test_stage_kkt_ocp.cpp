// ctest-labels: unit
// The stage-wise KKT solver on the planner's own OCPs (short horizons, so that the dense reference stays
// small): squat jump (rate costs -> carried controls), half-squat jump (wall contact: rows coupling x_k and
// x_{k+1}), arm flywheel (periodicity x_N = x_0 -> the initial state carried to the end), with the Hessian and
// Jacobian at a perturbed guess, in the scaled variables the interior-point method works in. The structured
// solution satisfies the dense KKT system to 1e-10 (relative residual) and gives the same step.
#include <gtest/gtest.h>

#include <random>

#include "ocp_solver/dense_kkt.hpp"
#include "planner/arm_flywheel_problem.hpp"
#include "planner/jump_problem.hpp"
#include "planner/ocp_nlp.hpp"

using namespace centaur;
using namespace centaur::planner;
using centaur_test::DenseKkt;

namespace {

void compareWithDense(const Ocp& ocp, unsigned seed, double dxv = 50.0, double lam = 0.1, double pert = 0.02) {
  OcpNlp nlp(ocp, true, nullptr);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::VectorXd z = ocp.guess(), lambda(ocp.numConstraints());
  for (int i = 0; i < z.size(); ++i) z[i] += pert * U(rng) * ocp.scale()[i];
  for (int j = 0; j < lambda.size(); ++j) lambda[j] = lam * U(rng);
  std::vector<double> jac(ocp.jacobianNonzeros()), hess(ocp.hessianNonzeros());
  ocp.jacobian(z.data(), jac.data());
  ocp.hessian(z.data(), 1.0, lambda.data(), hess.data());
  const auto& pat = nlp.pattern();
  const Eigen::VectorXd D = ocp.scale();
  for (std::size_t t = 0; t < jac.size(); ++t) jac[t] *= D[pat.jac_cols[t]];
  for (std::size_t t = 0; t < hess.size(); ++t) hess[t] *= D[pat.hess_rows[t]] * D[pat.hess_cols[t]];
  const auto eq = nlp.equalityRows();
  Eigen::VectorXd dx(ocp.numVariables()), dc(ocp.numConstraints()), rx(ocp.numVariables()), rc(ocp.numConstraints());
  for (int i = 0; i < dx.size(); ++i) dx[i] = dxv * (1.0 + 0.2 * std::abs(U(rng))), rx[i] = U(rng);
  for (int r = 0; r < dc.size(); ++r) dc[r] = eq[r] ? 0.0 : 0.5 + std::abs(U(rng)), rc[r] = U(rng);
  ocp_solver::StageKktSolver s(nlp.pattern(), nlp.stageLayout(), nlp.fixedVariables(), eq);
  const DenseKkt d(nlp.pattern(), nlp.fixedVariables(), s.alwaysExactRows(), hess.data(), jac.data(), dx, dc);
  ASSERT_EQ(s.factor(hess.data(), jac.data(), dx, dc), ocp_solver::KktStatus::kOk);
  Eigen::VectorXd sx, sy, rxd, ryd;
  s.solve(rx, rc, sx, sy);
  d.solve(rx, rc, rxd, ryd);
  EXPECT_LT(s.lastResidual(), 1e-10);
  auto denseResidual = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
    const int nf = static_cast<int>(d.free_vars.size());
    Eigen::VectorXd v(nf + y.size()), rhs(nf + y.size());
    for (int i = 0; i < nf; ++i) v[i] = x[d.free_vars[i]], rhs[i] = rx[d.free_vars[i]];
    v.tail(y.size()) = y;
    rhs.tail(y.size()) = rc;
    return (d.K * v - rhs).cwiseAbs().maxCoeff() / (d.K.cwiseAbs().maxCoeff() * v.cwiseAbs().maxCoeff() + 1.0);
  };
  EXPECT_LT(denseResidual(sx, sy), 1e-10);
  EXPECT_LT(denseResidual(rxd, ryd), 1e-10);
  // The multipliers of these systems are ill-determined (the equality Jacobian's smallest singular values are
  // ~1e-6 of its largest at the guess), so they are checked through the residual; the step agrees.
  const double scale = 1.0 + rxd.cwiseAbs().maxCoeff();
  EXPECT_LT((sx - rxd).cwiseAbs().maxCoeff() / scale, 1e-6);
  // Filled on a second thread ahead of the recursion (as the planner runs it): the same step to the last bit.
  ocp_solver::StageKktSolver p(nlp.pattern(), nlp.stageLayout(), nlp.fixedVariables(), eq);
  p.setPipelined(true);
  ASSERT_EQ(p.factor(hess.data(), jac.data(), dx, dc), ocp_solver::KktStatus::kOk);
  Eigen::VectorXd px, py;
  p.solve(rx, rc, px, py);
  EXPECT_EQ(px, sx);
  EXPECT_EQ(py, sy);
  // Pipelined on the derivatives' worker thread (one second thread for both, as the planner runs), with derivative
  // evaluations on that thread before and between the factorizations: the same bits again, whichever way each
  // section runs (the worker's chooser in auto mode, as the planner runs it; then every section inline, then on both
  // threads), and the same derivatives each time.
  OcpNlp nlp2(ocp, true, nullptr, 2);
  ASSERT_NE(nlp2.worker(), nullptr);
  EXPECT_EQ(nlp2.worker()->chooser().mode(), common::ParallelChooser::Mode::kAuto);
  ocp_solver::StageKktSolver q(nlp2.pattern(), nlp2.stageLayout(), nlp2.fixedVariables(), eq);
  q.setPipelined(nlp2.worker());
  Eigen::VectorXd g2, g2_first;
  std::vector<double> jac2(jac.size()), hess2(hess.size()), jac2_first, hess2_first;
  for (int round = 0; round < 8; ++round) {
    if (round == 4) nlp2.worker()->chooser().setMode(common::ParallelChooser::Mode::kInline);
    if (round == 6) nlp2.worker()->chooser().setMode(common::ParallelChooser::Mode::kParallel);
    ASSERT_TRUE(nlp2.derivatives(z, 0.7, lambda, g2, jac2.data(), hess2.data()));
    if (round == 0) g2_first = g2, jac2_first = jac2, hess2_first = hess2;
    EXPECT_EQ(g2, g2_first);
    EXPECT_EQ(jac2, jac2_first);
    EXPECT_EQ(hess2, hess2_first);
    ASSERT_EQ(q.factor(hess.data(), jac.data(), dx, dc), ocp_solver::KktStatus::kOk);
    Eigen::VectorXd qx, qy;
    q.solve(rx, rc, qx, qy);
    EXPECT_EQ(qx, sx);
    EXPECT_EQ(qy, sy);
  }
  for (bool p : {true, false}) {  // each kind of section ran both ways
    EXPECT_GT(nlp2.worker()->chooser().calls(common::kSectionDerivatives, p), 0);
    EXPECT_GT(nlp2.worker()->chooser().calls(common::kSectionFactor, p), 0);
  }
  // Two right-hand sides in one pass over the factors (the interior point's affine and centring steps): the same
  // bits as one after the other.
  Eigen::VectorXd rx2 = rx, rc2 = rc, sx2, sy2, ax, ay, bx, by;
  for (int i = 0; i < rx2.size(); ++i) rx2[i] += U(rng);
  for (int r = 0; r < rc2.size(); ++r) rc2[r] *= 1.0 + U(rng);
  s.solve(rx2, rc2, sx2, sy2);
  p.solveTwo({rx, rc, ax, ay}, {rx2, rc2, bx, by});
  EXPECT_EQ(ax, sx);
  EXPECT_EQ(ay, sy);
  EXPECT_EQ(bx, sx2);
  EXPECT_EQ(by, sy2);
  EXPECT_NE(bx, sx);
  // The same pair on the planner's shared worker, inline and on both threads.
  for (const auto mode : {common::ParallelChooser::Mode::kInline, common::ParallelChooser::Mode::kParallel}) {
    nlp2.worker()->chooser().setMode(mode);
    Eigen::VectorXd cx, cy, ex, ey;
    q.solveTwo({rx, rc, cx, cy}, {rx2, rc2, ex, ey});
    EXPECT_EQ(cx, sx);
    EXPECT_EQ(cy, sy);
    EXPECT_EQ(ex, sx2);
    EXPECT_EQ(ey, sy2);
  }
}

std::vector<std::string> shortHorizon() {
  return {"horizon.intervals=10", "horizon.takeoff=3", "horizon.landing=7"};
}

}  // namespace

TEST(StageKktOcp, SquatJump) {
  const JumpProblem p(loadJumpConfig("squat-jump", "", shortHorizon()));
  ASSERT_NO_FATAL_FAILURE(compareWithDense(p.ocp(), 1));  // the helper asserts residuals and step
}

TEST(StageKktOcp, HalfSquatJumpWithWallContact) {
  const JumpProblem p(loadJumpConfig("half-squat-jump", "", shortHorizon()));
  ASSERT_NO_FATAL_FAILURE(compareWithDense(p.ocp(), 2));  // the helper asserts residuals and step
}

TEST(StageKktOcp, ArmFlywheelWithPeriodicity) {
  const ArmFlywheelProblem p(loadArmFlywheelConfig("", {"horizon.intervals=8"}));
  ASSERT_NO_FATAL_FAILURE(compareWithDense(p.ocp(), 3));  // the helper asserts residuals and step
}
