// ctest-labels: unit
// Every constraint and cost derivative is exact: element Jacobians and weighted Hessians, and the assembled
// NLP gradient, constraint Jacobian and Lagrangian Hessian, against central finite differences.
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "model/template_params.hpp"
#include "planner/jump_problem.hpp"
#include "planner/template_elements.hpp"
#include "planner/nlp_fd_check.hpp"
#include "planner/ocp_nlp.hpp"

using namespace centaur;
using namespace centaur::planner;

namespace {

double relErr(double a, double b) { return std::abs(a - b) / std::max(1.0, std::max(std::abs(a), std::abs(b))); }

// The OCP's guess perturbed by 5 % of each variable's scale, and multipliers in [-1, 1].
void perturbedPoint(const Ocp& ocp, unsigned seed, Eigen::VectorXd& z, Eigen::VectorXd& y) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  z = ocp.guess();
  y.resize(ocp.numConstraints());
  for (int i = 0; i < z.size(); ++i) z[i] += 0.05 * U(rng) * ocp.scale()[i];
  for (int j = 0; j < y.size(); ++j) y[j] = U(rng);
}

// Jacobian of e at x by central differences of eval().
std::vector<double> fdJacobian(const Element& e, std::vector<double> x, double h) {
  const int ni = e.numInputs(), no = e.numOutputs();
  std::vector<double> J(no * ni), fp(no), fm(no);
  for (int i = 0; i < ni; ++i) {
    const double xi = x[i];
    x[i] = xi + h;
    e.eval(x.data(), fp.data());
    x[i] = xi - h;
    e.eval(x.data(), fm.data());
    x[i] = xi;
    for (int j = 0; j < no; ++j) J[j * ni + i] = (fp[j] - fm[j]) / (2 * h);
  }
  return J;
}

// Hessian of w^T e at x by central differences of the exact (AD) gradient w^T J.
std::vector<double> fdHessian(const Element& e, std::vector<double> x, const std::vector<double>& w, double h) {
  const int ni = e.numInputs(), no = e.numOutputs();
  std::vector<double> H(ni * ni), Jp(no * ni), Jm(no * ni), f(no);
  for (int i = 0; i < ni; ++i) {
    const double xi = x[i];
    x[i] = xi + h;
    e.evalJacobian(x.data(), f.data(), Jp.data());
    x[i] = xi - h;
    e.evalJacobian(x.data(), f.data(), Jm.data());
    x[i] = xi;
    for (int b = 0; b < ni; ++b) {
      double d = 0.0;
      for (int j = 0; j < no; ++j) d += w[j] * (Jp[j * ni + b] - Jm[j * ni + b]);
      H[i * ni + b] = d / (2 * h);
    }
  }
  return H;
}

void checkElement(const Element& e, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const int ni = e.numInputs(), no = e.numOutputs();
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> x(ni), w(no), f(no), J(no * ni), H(ni * ni);
    for (auto& v : x) v = U(rng);
    for (auto& v : w) v = U(rng);
    e.evalJacobian(x.data(), f.data(), J.data());
    std::vector<double> f2(no);
    e.eval(x.data(), f2.data());
    for (int j = 0; j < no; ++j) EXPECT_LT(relErr(f[j], f2[j]), 1e-13) << e.name();
    const auto Jfd = fdJacobian(e, x, 1e-6);
    for (int k = 0; k < no * ni; ++k) EXPECT_LT(relErr(J[k], Jfd[k]), 1e-6) << e.name() << " J[" << k << "]";
    e.evalHessian(x.data(), w.data(), H.data());
    const auto Hfd = fdHessian(e, x, w, 1e-6);
    for (int k = 0; k < ni * ni; ++k) EXPECT_LT(relErr(H[k], Hfd[k]), 1e-6) << e.name() << " H[" << k << "]";
    for (int a = 0; a < ni; ++a)
      for (int b = 0; b < ni; ++b) EXPECT_LT(relErr(H[a * ni + b], H[b * ni + a]), 1e-12) << e.name();
    // Both from one evaluation (what the planner's derivatives call): the same values, Jacobian and Hessian, to
    // rounding (two summation orders: up to ~2e-14 where the compiler contracts products into FMAs, an AVX2 build).
    std::vector<double> f3(no, -7.0), J3(no * ni, -7.0), H3(ni * ni, -7.0);
    e.evalJacobianHessian(x.data(), w.data(), f3.data(), J3.data(), H3.data());
    for (int j = 0; j < no; ++j) EXPECT_LT(relErr(f3[j], f[j]), 1e-13) << e.name();
    for (int k = 0; k < no * ni; ++k) EXPECT_LT(relErr(J3[k], J[k]), 1e-13) << e.name() << " J[" << k << "]";
    for (int k = 0; k < ni * ni; ++k) EXPECT_LT(relErr(H3[k], H[k]), 1e-13) << e.name() << " H[" << k << "]";
    // Declared constant derivatives are constant (the Ocp evaluates them once).
    std::vector<double> x2(ni), J2(no * ni), H2(ni * ni);
    for (auto& v : x2) v = 2.0 * U(rng);
    if (e.jacobianIsConstant()) {
      e.evalJacobian(x2.data(), f2.data(), J2.data());
      for (int k = 0; k < no * ni; ++k) EXPECT_EQ(J2[k], J[k]) << e.name() << " declares a constant Jacobian";
    }
    if (e.hessianIsConstant()) {
      e.evalHessian(x2.data(), w.data(), H2.data());
      for (int k = 0; k < ni * ni; ++k) EXPECT_LT(relErr(H2[k], H[k]), 1e-14) << e.name() << " declares a constant Hessian";
    }
  }
}

// Every elementary operation of the reverse-AD tape (reverse_ad.hpp), incl. repeated operands, constants on
// either side, and a linear tail (inputs 3, 4 enter linearly, so NN = 3).
struct TapeOpsElement : AdElement<TapeOpsElement, 5, 4, 3> {
  const char* name() const override { return "tape_ops"; }
  template <class S>
  void compute(const S* in, S* out) const {
    using std::cos;
    using std::sin;
    using std::sqrt;
    const S a = in[0], b = in[1], c = in[2];
    out[0] = a * a * b / (S(2.0) + c * c) - S(3.0) / (S(1.5) + b * b) + b / S(4.0) + in[3] * a;
    out[1] = sqrt(S(2.0) + a * a + b * c) * sin(c) - cos(a * b) + in[4] * cos(c);
    out[2] = (a - b) * (a - b) + a / a - (-c) * (S(1.0) - a) + in[3] - S(2.0) * in[4];
    out[3] = S(0.5) * in[4] + in[3] * (b + c) + (c + S(0.0)) * (c - S(0.0)) + S(0.0) * a + (S(0.0) + b) * S(0.0);
  }
};

// Zero constants record nothing (x + 0, x - 0, 0 + x are x, 0 * x the constant 0): the same tape, Jacobian and
// Hessian as the function written without them.
struct WithZeros : AdElement<WithZeros, 2, 1> {
  const char* name() const override { return "with_zeros"; }
  template <class S>
  void compute(const S* in, S* out) const {
    out[0] = (in[0] + S(0.0)) * (S(0.0) + in[1] - S(0.0)) + S(0.0) * in[0] * in[1] + in[0] * in[0];
  }
};
struct WithoutZeros : AdElement<WithoutZeros, 2, 1> {
  const char* name() const override { return "without_zeros"; }
  template <class S>
  void compute(const S* in, S* out) const {
    out[0] = in[0] * in[1] + in[0] * in[0];
  }
};

// Element Hessian by the tape (evalHessian) against nested forward AD (evalHessianForward): same numbers.
template <class E>
void checkTapeAgainstForward(const E& e, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  constexpr int ni = E::kInputs, no = E::kOutputs;
  std::vector<double> x(ni), w(no), H(ni * ni), Hf(ni * ni);
  for (auto& v : x) v = U(rng);
  for (auto& v : w) v = U(rng);
  e.evalHessian(x.data(), w.data(), H.data());
  e.evalHessianForward(x.data(), w.data(), Hf.data());
  for (int k = 0; k < ni * ni; ++k) EXPECT_LT(relErr(H[k], Hf[k]), 1e-12) << e.name() << " H[" << k << "]";
}

}  // namespace

TEST(Derivatives, ReverseTapeCoversEveryOperation) {
  checkElement(TapeOpsElement(), 80);
  checkElement(TapeOpsElement(), 81);
  checkTapeAgainstForward(TapeOpsElement(), 82);
}

TEST(Derivatives, ZeroConstantsRecordNothingOnTheTape) {
  const double x[2] = {0.7, -1.3}, w[1] = {2.5};
  double f[2], J[2][2], H[2][4];
  WithZeros().evalJacobianHessian(x, w, &f[0], J[0], H[0]);
  const int with_zeros = rad::activeTape().size();
  WithoutZeros().evalJacobianHessian(x, w, &f[1], J[1], H[1]);
  EXPECT_EQ(with_zeros, rad::activeTape().size());
  EXPECT_EQ(f[0], f[1]);
  for (int k = 0; k < 2; ++k) EXPECT_EQ(J[0][k], J[1][k]);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(H[0][k], H[1][k]);
  EXPECT_DOUBLE_EQ(H[0][1], 2.5);  // d2/dx0 dx1 of w x0 x1
  EXPECT_DOUBLE_EQ(H[0][0], 5.0);  // d2/dx0^2 of w x0^2
  checkElement(WithZeros(), 83);
}

TEST(Derivatives, ReverseTapeHessianEqualsNestedForwardHessian) {
  const model::TemplateParams P = model::templatePreset("centauro");
  checkTapeAgainstForward(QuaternionStep(), 90);
  checkTapeAgainstForward(WaistDynamicsElement(P, 7.0), 91);
  for (int i = 0; i < 4; ++i) {
    // Its evalHessian is written out by hand (the tape's own: FootDynamicsDerivatives.*); against forward AD too.
    checkTapeAgainstForward(FootDynamicsElement(P, i, 7.0), 92 + i);
    checkTapeAgainstForward(FootDisplacementElement(P, i), 96 + i);
    checkTapeAgainstForward(FootVelocitySquared(P, i), 100 + i);
  }
  checkTapeAgainstForward(FrictionConeElement(Eigen::Vector3d(0.1, 0.2, 1.0), 0.5, 1.0, 10.0), 104);
}

TEST(Derivatives, EveryElementMatchesCentralDifferences) {
  for (const auto& preset : model::templatePresetNames()) {
    const model::TemplateParams P = model::templatePreset(preset);
    checkElement(PositionStep(), 1);
    checkElement(VelocityStep(), 2);
    checkElement(QuaternionStep(), 3);
    checkElement(WaistDynamicsElement(P, 1.0), 4);
    for (int i = 0; i < 4; ++i) {
      checkElement(FootDynamicsElement(P, i, 1.0), 10 + i);
      checkElement(FootSurfaceElement(P, i, Eigen::Vector3d(0.2, 0.1, 0.97).normalized(), -0.05), 20 + i);
      checkElement(FootPointElement(P, i, Eigen::Vector3d(0.3, -0.2, 0.1)), 30 + i);
      checkElement(FootDisplacementElement(P, i), 40 + i);
      checkElement(FootVelocityElement(P, i), 50 + i);
      checkElement(FootVelocitySquared(P, i), 60 + i);
    }
  }
  checkElement(FrictionPyramidElement(Eigen::Vector3d::UnitZ(), 0.7, 5.0, 10.0), 70);
  checkElement(FrictionPyramidElement(Eigen::Vector3d::UnitX(), 1.0, 0.0, 10.0), 71);
  checkElement(FrictionConeElement(Eigen::Vector3d(0.1, 0.2, 1.0), 0.5, 1.0, 10.0), 72);
  checkElement(SquaredError<4>(Eigen::Vector4d(1, 0, 0, 0)), 73);
  checkElement(SquaredDifference<3>(), 74);
  checkElement(AffineSum<3>(Eigen::Vector3d(-1.0, 0.5, 2.0), 0.25), 76);
  checkElement(LegReachElement(), 75);
}

TEST(Derivatives, AssembledNlpMatchesCentralDifferences) {
  // A short jump OCP (both primitives), evaluated at a perturbed initial guess.
  for (const std::string primitive : {"squat-jump", "half-squat-jump"}) {
    JumpConfig cfg = loadJumpConfig(primitive, "", {"horizon.intervals=6", "horizon.takeoff=1", "horizon.landing=4"});
    cfg.cost.base_orientation = 3.0;
    cfg.cost.velocity_regularization = 0.5;
    cfg.cost.landing_steps = 0.3;
    const JumpProblem problem(cfg);
    const Ocp& ocp = problem.ocp();
    const int n = ocp.numVariables(), m = ocp.numConstraints();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    Eigen::VectorXd z = ocp.guess();
    for (int i = 0; i < n; ++i) z[i] += 0.05 * U(rng) * ocp.scale()[i];
    Eigen::VectorXd lambda(m);
    for (int j = 0; j < m; ++j) lambda[j] = U(rng);
    centaur::test::expectNlpMatchesCentralDifferences(ocp, z, lambda, 0.7, primitive);
  }
}

TEST(Derivatives, SplitAndTwoThreadEvaluationEqualsTheSeparateCalls) {
  // OcpNlp::derivatives (constant parts cached, the terms optionally split over two threads) against
  // Ocp::gradient / jacobian / hessian, which the central-difference test above checks.
  for (const std::string primitive : {"squat-jump", "half-squat-jump"}) {
    const JumpProblem problem(loadJumpConfig(primitive, "", {}));
    const Ocp& ocp = problem.ocp();
    Eigen::VectorXd z, y;
    perturbedPoint(ocp, 11, z, y);
    Eigen::VectorXd g0(ocp.numVariables());
    std::vector<double> j0(ocp.jacobianNonzeros()), h0(ocp.hessianNonzeros());
    ocp.gradient(z.data(), g0.data());
    ocp.jacobian(z.data(), j0.data());
    ocp.hessian(z.data(), 0.7, y.data(), h0.data());
    for (int threads : {1, 2}) {
      OcpNlp nlp(ocp, true, nullptr, threads);
      Eigen::VectorXd g;
      std::vector<double> j(j0.size()), h(h0.size());
      ASSERT_TRUE(nlp.derivatives(z, 0.7, y, g, j.data(), h.data()));
      EXPECT_LT((g - g0).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + g0.cwiseAbs().maxCoeff())) << primitive << threads;
      for (std::size_t k = 0; k < j0.size(); ++k) ASSERT_LT(relErr(j[k], j0[k]), 1e-12) << primitive << " J " << k;
      for (std::size_t k = 0; k < h0.size(); ++k) ASSERT_LT(relErr(h[k], h0[k]), 1e-10) << primitive << " H " << k;
    }
  }
}

TEST(Derivatives, BalancedSplitSumsExactlyAsTheBaseSplitOnOneOrTwoThreads) {
  // The base split: the worker takes the constraint terms after half of their estimated work, the caller the rest
  // and every cost term; each sums its terms in order and the caller adds the worker's sums. The balanced split
  // moves terms to the worker only where no sum changes, so its derivatives must equal these bit for bit, and one
  // thread (the worker's list evaluated after the caller's) must give the same bits as two.
  for (const std::string primitive : {"squat-jump", "half-squat-jump"}) {
    const JumpProblem problem(loadJumpConfig(primitive, "", {}));
    const Ocp& ocp = problem.ocp();
    Eigen::VectorXd z, y;
    perturbedPoint(ocp, 5, z, y);
    const int nc = ocp.numConstraintTerms();
    double total = 0.0, acc = 0.0;
    for (int c = 0; c < nc; ++c) total += ocp.termWork({false, c});
    int split = 0;
    while (split < nc && acc < 0.5 * total) acc += ocp.termWork({false, split++});
    std::vector<Ocp::TermRef> caller, worker;
    for (int c = 0; c < nc; ++c) (c < split ? caller : worker).push_back({false, c});
    for (int k = 0; k < ocp.numCostTerms(); ++k) caller.push_back({true, k});
    const int n = ocp.numVariables(), nj = ocp.jacobianNonzeros(), nh = ocp.hessianNonzeros();
    std::vector<double> g0(n, 0.0), j0(nj, 0.0), h0(nh, 0.0), g1(n, 0.0), j1(nj, 0.0), h1(nh, 0.0);
    Ocp::Scratch s;
    ocp.addDerivatives(z.data(), 0.7, y.data(), caller, s, g0.data(), j0.data(), h0.data());
    ocp.addDerivatives(z.data(), 0.7, y.data(), worker, s, g1.data(), j1.data(), h1.data());
    for (int i = 0; i < n; ++i) g0[i] += g1[i];
    for (int k = 0; k < nj; ++k) j0[k] += j1[k];
    for (int k = 0; k < nh; ++k) h0[k] += h1[k];
    ocp.addConstantDerivatives(0.7, j0.data(), h0.data());

    for (int threads : {2, 1}) {
      OcpNlp nlp(ocp, true, nullptr, threads);
      int moved_costs = 0;
      double work_worker = 0.0, work_all = 0.0;
      for (const auto& t : nlp.workerTerms()) {
        moved_costs += t.cost;
        work_worker += ocp.termWork(t);
      }
      for (const auto& t : nlp.callerTerms()) work_all += ocp.termWork(t);
      work_all += work_worker;
      EXPECT_GT(moved_costs, 0) << primitive;  // the balancing did move terms
      EXPECT_GT(work_worker, 0.45 * work_all) << primitive;
      EXPECT_EQ(nlp.callerTerms().size() + nlp.workerTerms().size(), caller.size() + worker.size());
      Eigen::VectorXd g;
      std::vector<double> j(nj), h(nh);
      ASSERT_TRUE(nlp.derivatives(z, 0.7, y, g, j.data(), h.data()));
      for (int i = 0; i < n; ++i) ASSERT_EQ(g[i], g0[i]) << primitive << threads << " gradient " << i;
      for (int k = 0; k < nj; ++k) ASSERT_EQ(j[k], j0[k]) << primitive << threads << " J " << k;
      for (int k = 0; k < nh; ++k) ASSERT_EQ(h[k], h0[k]) << primitive << threads << " H " << k;
    }
  }
}
