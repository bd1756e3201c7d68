// ctest-labels: unit
// The interior-point method on small NLPs with known solutions (dense KKT solver): Hock-Schittkowski 71
// (Ipopt's example), a bound-constrained problem whose solution sits on bounds, an equality-constrained
// nonconvex problem that needs the inertia correction, and failures reported as statuses: an infeasible
// problem (restoration fails), an iteration limit, and a line search that fails at an acceptable iterate.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "dense_kkt.hpp"
#include "ocp_solver/interior_point.hpp"

using namespace centaur::ocp_solver;
using centaur_test::DenseKktSolver;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// An NLP from lambdas with dense derivatives (pattern: every Jacobian entry, the whole lower triangle).
struct LambdaNlp : Nlp {
  int n, m;
  Eigen::VectorXd xl, xu, gl, gu, x0;
  std::function<double(const Eigen::VectorXd&)> f;
  std::function<Eigen::VectorXd(const Eigen::VectorXd&)> g, grad;
  std::function<Eigen::MatrixXd(const Eigen::VectorXd&)> jac;
  std::function<Eigen::MatrixXd(const Eigen::VectorXd&, double, const Eigen::VectorXd&)> hess;
  SparsePattern p;
  int evaluations = 0;
  void finalize() {
    p.n = n;
    p.m = m;
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < n; ++c) p.jac_rows.push_back(r), p.jac_cols.push_back(c);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c <= r; ++c) p.hess_rows.push_back(r), p.hess_cols.push_back(c);
  }
  const SparsePattern& pattern() const override { return p; }
  void bounds(Eigen::VectorXd& a, Eigen::VectorXd& b, Eigen::VectorXd& c, Eigen::VectorXd& d) const override {
    a = xl, b = xu, c = gl, d = gu;
  }
  Eigen::VectorXd initialPoint() const override { return x0; }
  bool objective(const Eigen::VectorXd& x, double& v) override {
    v = f(x);
    return true;
  }
  bool constraints(const Eigen::VectorXd& x, Eigen::VectorXd& v) override {
    v = g(x);
    return true;
  }
  bool derivatives(const Eigen::VectorXd& x, double s, const Eigen::VectorXd& y, Eigen::VectorXd& gr, double* J,
                   double* H) override {
    ++evaluations;
    gr = grad(x);
    const Eigen::MatrixXd Jm = jac(x), Hm = hess(x, s, y);
    int k = 0;
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < n; ++c) J[k++] = Jm(r, c);
    k = 0;
    for (int r = 0; r < n; ++r)
      for (int c = 0; c <= r; ++c) H[k++] = Hm(r, c);
    return true;
  }
};

IpmResult solve(LambdaNlp& nlp, IpmOptions opt = {}, const WarmStart* warm = nullptr) {
  std::vector<char> fixed(nlp.n);
  for (int i = 0; i < nlp.n; ++i) fixed[i] = nlp.xl[i] == nlp.xu[i];
  DenseKktSolver kkt(nlp.p, fixed);
  return solveInteriorPoint(nlp, kkt, opt, warm);
}

LambdaNlp hs071() {
  LambdaNlp q;
  q.n = 4;
  q.m = 2;
  q.xl = Eigen::VectorXd::Constant(4, 1.0);
  q.xu = Eigen::VectorXd::Constant(4, 5.0);
  q.gl = Eigen::Vector2d(25.0, 40.0);
  q.gu = Eigen::Vector2d(kInf, 40.0);
  q.x0 = Eigen::Vector4d(1.0, 5.0, 5.0, 1.0);
  q.f = [](const Eigen::VectorXd& x) { return x[0] * x[3] * (x[0] + x[1] + x[2]) + x[2]; };
  q.g = [](const Eigen::VectorXd& x) {
    return Eigen::Vector2d(x[0] * x[1] * x[2] * x[3], x.squaredNorm());
  };
  q.grad = [](const Eigen::VectorXd& x) {
    return Eigen::Vector4d(x[3] * (2 * x[0] + x[1] + x[2]), x[0] * x[3], x[0] * x[3] + 1, x[0] * (x[0] + x[1] + x[2]));
  };
  q.jac = [](const Eigen::VectorXd& x) {
    Eigen::MatrixXd J(2, 4);
    J << x[1] * x[2] * x[3], x[0] * x[2] * x[3], x[0] * x[1] * x[3], x[0] * x[1] * x[2], 2 * x[0], 2 * x[1], 2 * x[2],
        2 * x[3];
    return J;
  };
  q.hess = [](const Eigen::VectorXd& x, double s, const Eigen::VectorXd& y) {
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(4, 4);
    H(0, 0) = s * 2 * x[3];
    H(1, 0) = s * x[3];
    H(2, 0) = s * x[3];
    H(3, 0) = s * (2 * x[0] + x[1] + x[2]);
    H(3, 1) = s * x[0];
    H(3, 2) = s * x[0];
    H(1, 0) += y[0] * x[2] * x[3];
    H(2, 0) += y[0] * x[1] * x[3];
    H(3, 0) += y[0] * x[1] * x[2];
    H(2, 1) += y[0] * x[0] * x[3];
    H(3, 1) += y[0] * x[0] * x[2];
    H(3, 2) += y[0] * x[0] * x[1];
    for (int i = 0; i < 4; ++i) H(i, i) += 2 * y[1];
    return Eigen::MatrixXd(H.selfadjointView<Eigen::Lower>());
  };
  q.finalize();
  return q;
}

}  // namespace

TEST(InteriorPoint, Hs071ReachesTheKnownOptimum) {
  for (const char* mode : {"monotone", "adaptive"}) {
    LambdaNlp q = hs071();
    IpmOptions opt;
    opt.mu_strategy = mode;
    const IpmResult r = solve(q, opt);
    ASSERT_EQ(r.status, IpmStatus::kSolved) << mode;
    EXPECT_NEAR(r.objective, 17.0140173, 1e-6) << mode;
    EXPECT_NEAR(r.x[0], 1.0, 1e-6);
    EXPECT_NEAR(r.x[1], 4.7429994, 1e-6);
    EXPECT_NEAR(r.x[2], 3.8211503, 1e-6);
    EXPECT_NEAR(r.x[3], 1.3794082, 1e-6);
    // at most the bound relaxation (as Ipopt): bound_relax_factor * max(1, |25|)
    EXPECT_LT(r.constraint_violation, 1.01 * opt.bound_relax_factor * 25.0);
    EXPECT_LT(r.stats.iterations, 20) << mode;  // Ipopt: 8
  }
}

// A neighbour of HS071 (the product constraint >= 24 instead of 25, its optimum elsewhere) warm-starts HS071:
// from its x alone, and from its x and multipliers. Both reach HS071's optimum; the primal-dual start, already
// near the end of a central path with the right active bound (x0 = 1) and the right multiplier signs, needs
// fewer iterations. Started at HS071's own solution with its multipliers, it stays there.
TEST(InteriorPoint, PrimalDualWarmStartFromANeighbourReachesTheOptimumSooner) {
  LambdaNlp neighbour = hs071();
  neighbour.gl[0] = 24.0;
  const IpmResult rn = solve(neighbour);
  ASSERT_EQ(rn.status, IpmStatus::kSolved);
  ASSERT_GT(std::abs(rn.objective - 17.0140173), 1e-2);  // a different optimum

  WarmStart primal;
  primal.x = rn.x;
  WarmStart primal_dual = primal;
  primal_dual.y = rn.y, primal_dual.z_l = rn.z_l, primal_dual.z_u = rn.z_u;
  ASSERT_TRUE(primal_dual.hasMultipliers(4, 2));
  LambdaNlp q1 = hs071(), q2 = hs071();
  const IpmResult rp = solve(q1, {}, &primal), rpd = solve(q2, {}, &primal_dual);
  for (const IpmResult* r : {&rp, &rpd}) {
    ASSERT_EQ(r->status, IpmStatus::kSolved);
    EXPECT_NEAR(r->objective, 17.0140173, 1e-6);
    EXPECT_NEAR(r->x[1], 4.7429994, 1e-6);
    EXPECT_NEAR(r->x[3], 1.3794082, 1e-6);
  }
  // 7 and 4 iterations; without the neighbour's bound multipliers (mu 1e-8 and y alone) it takes 5.
  EXPECT_LT(rpd.stats.iterations, rp.stats.iterations);
  EXPECT_LE(rpd.stats.iterations, 4);

  LambdaNlp q3 = hs071(), q4 = hs071();
  const IpmResult cold = solve(q3);
  WarmStart at;
  at.x = cold.x, at.y = cold.y, at.z_l = cold.z_l, at.z_u = cold.z_u;
  const IpmResult again = solve(q4, {}, &at);
  ASSERT_EQ(again.status, IpmStatus::kSolved);
  EXPECT_LE(again.stats.iterations, 2);  // 3 without the bound multipliers
  EXPECT_LT((again.x - cold.x).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_NEAR(again.y[0], cold.y[0], 1e-5);
  EXPECT_NEAR(again.y[1], cold.y[1], 1e-5);
}

TEST(InteriorPoint, SolutionOnBoundsHasTheRightMultipliers) {
  // min (x0 - 2)^2 + (x1 + 1)^2 on [0, 1] x [0, 1]: x = (1, 0), z_u0 = 2, z_l1 = 2.
  LambdaNlp q;
  q.n = 2;
  q.m = 0;
  q.xl = Eigen::Vector2d(0, 0);
  q.xu = Eigen::Vector2d(1, 1);
  q.gl.resize(0), q.gu.resize(0);
  q.x0 = Eigen::Vector2d(0.5, 0.5);
  q.f = [](const Eigen::VectorXd& x) { return std::pow(x[0] - 2, 2) + std::pow(x[1] + 1, 2); };
  q.g = [](const Eigen::VectorXd&) { return Eigen::VectorXd(0); };
  q.grad = [](const Eigen::VectorXd& x) { return Eigen::Vector2d(2 * (x[0] - 2), 2 * (x[1] + 1)); };
  q.jac = [](const Eigen::VectorXd&) { return Eigen::MatrixXd(0, 2); };
  q.hess = [](const Eigen::VectorXd&, double s, const Eigen::VectorXd&) { return Eigen::MatrixXd(2 * s * Eigen::Matrix2d::Identity()); };
  q.finalize();
  const IpmResult r = solve(q);
  ASSERT_EQ(r.status, IpmStatus::kSolved);
  EXPECT_NEAR(r.x[0], 1.0, 1e-7);
  EXPECT_NEAR(r.x[1], 0.0, 1e-7);
  EXPECT_NEAR(r.z_u[0], 2.0, 1e-6);
  EXPECT_NEAR(r.z_l[1], 2.0, 1e-6);
}

TEST(InteriorPoint, NonconvexEqualityNeedsAndGetsInertiaCorrection) {
  // min -x0^2 - x1^2 + 2 x2  s.t. x0^2 + x1^2 = 1 + x2, x2 in [0, 10], x0, x1 in [-2, 2]; start at a saddle of
  // the Lagrangian. Optimum: objective -1 on the circle with x2 = 0.
  LambdaNlp q;
  q.n = 3;
  q.m = 1;
  q.xl = Eigen::Vector3d(-2, -2, 0);
  q.xu = Eigen::Vector3d(2, 2, 10);
  q.gl = Eigen::VectorXd::Zero(1);
  q.gu = Eigen::VectorXd::Zero(1);
  q.x0 = Eigen::Vector3d(0.1, 0.2, 1.0);
  q.f = [](const Eigen::VectorXd& x) { return -x[0] * x[0] - x[1] * x[1] + 2 * x[2]; };
  q.g = [](const Eigen::VectorXd& x) { return Eigen::VectorXd::Constant(1, x[0] * x[0] + x[1] * x[1] - 1 - x[2]); };
  q.grad = [](const Eigen::VectorXd& x) { return Eigen::Vector3d(-2 * x[0], -2 * x[1], 2); };
  q.jac = [](const Eigen::VectorXd& x) {
    Eigen::MatrixXd J(1, 3);
    J << 2 * x[0], 2 * x[1], -1;
    return J;
  };
  q.hess = [](const Eigen::VectorXd&, double s, const Eigen::VectorXd& y) {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    H(0, 0) = H(1, 1) = -2 * s + 2 * y[0];
    return Eigen::MatrixXd(H);
  };
  q.finalize();
  const IpmResult r = solve(q);
  ASSERT_EQ(r.status, IpmStatus::kSolved);
  EXPECT_NEAR(r.objective, -1.0, 1e-7);
  EXPECT_NEAR(r.x[2], 0.0, 1e-7);
  EXPECT_GT(r.stats.factorizations, r.stats.iterations + 1);  // some iterations were regularized
}

// A KKT solver that demands a primal regularization: the first factor() of each iteration and its retries report
// the wrong inertia until the diagonal of the unbounded variable 0 (which carries delta_w alone) reaches that
// iteration's requirement, then factor the matrix as it is. It records the delta_w of every trial. An iteration
// starts with an unregularized factor() (until the method skips it after three regularized iterations); other
// factorizations (the least-squares multiplier estimate, with a unit diagonal) pass through unrecorded.
class DemandingKktSolver final : public KktSolver {
 public:
  DemandingKktSolver(const SparsePattern& p, std::vector<double> needed) : dense_(p, std::vector<char>(p.n, 0)),
                                                                           needed_(std::move(needed)) {}
  KktStatus factor(const double* h, const double* j, const Eigen::VectorXd& dx, const Eigen::VectorXd& dc) override {
    if (dx[0] != 0.0) return dense_.factor(h, j, dx, dc);
    trials.emplace_back();
    return refactor(h, j, dx, dc);
  }
  KktStatus refactor(const double* h, const double* j, const Eigen::VectorXd& dx, const Eigen::VectorXd& dc) override {
    trials.back().push_back(dx[0]);
    const std::size_t it = trials.size() - 1;
    if (it < needed_.size() && dx[0] < needed_[it]) return KktStatus::kWrongInertia;
    return dense_.factor(h, j, dx, dc);
  }
  void solve(const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, Eigen::VectorXd& dx, Eigen::VectorXd& dy) override {
    dense_.solve(rx, rc, dx, dy);
  }
  const std::vector<char>& alwaysExactRows() const override { return dense_.alwaysExactRows(); }
  Inertia inertia() const override { return dense_.inertia(); }
  std::vector<std::vector<double>> trials;  // per iteration, the delta_w of each factorization

 private:
  DenseKktSolver dense_;
  std::vector<double> needed_;
};

TEST(InteriorPoint, ARegularizationFarAboveTheLastOneGrowsByAHundredAsIpopts) {
  // min (x0 - 1)^2 + (x1 - 2)^2 with both variables free: a convex problem whose KKT solver nonetheless asks for
  // delta_w >= 1e-3 in the first iteration and >= 1e6 in the second. First: 0, then Ipopt's first value 1e-4, then
  // x100 (no earlier delta_w): 1e-2. Second: 0, then a third of the last (3.3e-3), then x8 per trial while a trial
  // is at most 1e5 x the last (1e3), and x100 once it is beyond: ..., 874, 6991, 6.99e5, 6.99e7.
  LambdaNlp q;
  q.n = 2;
  q.m = 0;
  q.xl = Eigen::Vector2d(-kInf, -kInf);
  q.xu = Eigen::Vector2d(kInf, kInf);
  q.gl = q.gu = Eigen::VectorXd(0);
  q.x0 = Eigen::Vector2d(5.0, -3.0);
  q.f = [](const Eigen::VectorXd& x) { return (x[0] - 1) * (x[0] - 1) + (x[1] - 2) * (x[1] - 2); };
  q.g = [](const Eigen::VectorXd&) { return Eigen::VectorXd(0); };
  q.grad = [](const Eigen::VectorXd& x) { return Eigen::Vector2d(2 * (x[0] - 1), 2 * (x[1] - 2)); };
  q.jac = [](const Eigen::VectorXd&) { return Eigen::MatrixXd(0, 2); };
  q.hess = [](const Eigen::VectorXd&, double s, const Eigen::VectorXd&) {
    return Eigen::MatrixXd(2 * s * Eigen::Matrix2d::Identity());
  };
  q.finalize();
  DemandingKktSolver kkt(q.p, {1e-3, 1e6});
  IpmOptions o;
  o.max_iter = 2;
  solveInteriorPoint(q, kkt, o);
  ASSERT_GE(kkt.trials.size(), 2u);
  const std::vector<double>& first = kkt.trials[0];
  ASSERT_EQ(first.size(), 3u);
  EXPECT_EQ(first[0], 0.0);
  EXPECT_DOUBLE_EQ(first[1], 1e-4);
  EXPECT_DOUBLE_EQ(first[2], 1e-2);
  const std::vector<double>& second = kkt.trials[1];
  ASSERT_GE(second.size(), 3u);
  EXPECT_EQ(second[0], 0.0);
  EXPECT_DOUBLE_EQ(second[1], 1e-2 / 3.0);
  for (std::size_t t = 2; t < second.size(); ++t) {
    const double growth = second[t - 1] > 1e5 * 1e-2 ? 100.0 : 8.0;
    EXPECT_NEAR(second[t] / second[t - 1], growth, 1e-12 * growth) << "trial " << t;
  }
  EXPECT_GE(second.back(), 1e6);
  EXPECT_LT(second[second.size() - 2], 1e6);
  EXPECT_EQ(second.size(), 11u);  // only x8: 12 trials (..., 6991, 5.6e4, 4.5e5, 3.6e6)
}

TEST(InteriorPoint, FreeModeKeepsOnePercentOffTheBoundsWhileFarFromOptimal) {
  // min 1000 (x0 + x1)  s.t. x0 - x1 = 0, x >= 0, from (1, 1) with bound multipliers 1: the NLP error starts at
  // ~1000 (dual infeasibility), the affine-scaling step goes straight to the bounds and the quality function picks
  // the smallest barrier parameter it may (sigma 1e-6). As in Ipopt, the fraction to the boundary of the free mode
  // is max(0.99, 1 - NLP error), not 1 - mu: the first step keeps 1 % of the distance to the bounds (with 1 - mu it
  // went to 1e-6 of it).
  LambdaNlp q;
  q.n = 2;
  q.m = 1;
  q.xl = Eigen::Vector2d(0, 0);
  q.xu = Eigen::Vector2d(kInf, kInf);
  q.gl = Eigen::VectorXd::Zero(1);
  q.gu = Eigen::VectorXd::Zero(1);
  q.x0 = Eigen::Vector2d(1.0, 1.0);
  q.f = [](const Eigen::VectorXd& x) { return 1e3 * (x[0] + x[1]); };
  q.g = [](const Eigen::VectorXd& x) { return Eigen::VectorXd::Constant(1, x[0] - x[1]); };
  q.grad = [](const Eigen::VectorXd&) { return Eigen::Vector2d(1e3, 1e3); };
  q.jac = [](const Eigen::VectorXd&) {
    Eigen::MatrixXd J(1, 2);
    J << 1, -1;
    return J;
  };
  q.hess = [](const Eigen::VectorXd&, double, const Eigen::VectorXd&) { return Eigen::MatrixXd::Zero(2, 2).eval(); };
  std::vector<Eigen::VectorXd> points;  // where the derivatives were evaluated: the start, then every iterate
  auto grad = q.grad;
  q.grad = [&points, grad](const Eigen::VectorXd& x) {
    points.push_back(x);
    return grad(x);
  };
  q.finalize();
  IpmOptions o;
  o.max_iter = 2;
  const IpmResult r = solve(q, o);
  EXPECT_EQ(r.status, IpmStatus::kMaxIterations);
  std::size_t first = 0;  // the first iterate after the start
  while (first < points.size() && points[first] == q.x0) ++first;
  ASSERT_LT(first, points.size());
  for (int i = 0; i < 2; ++i) {
    EXPECT_GE(points[first][i], 0.01 * q.x0[i] - 1e-8) << "x" << i;  // the bounds are relaxed by 1e-8
    EXPECT_LT(points[first][i], 0.02 * q.x0[i]) << "x" << i;  // and it does go that far
  }
}

TEST(InteriorPoint, TheWatchdogTakesFullStepsAfterTenShortenedOnesAndReturnsWhenTheyFail) {
  // min (x - 20)^2 / 2 from x = 0, where the functions cannot be evaluated more than 1 beyond the last iterate (a
  // domain that grows as the method goes, NaN beyond it): the line search cuts every Newton step (to 20) to at
  // most 1. After ten such steps Ipopt's watchdog tries the full step from there; it cannot be evaluated, so the
  // method returns to the stored point and backtracks as before. It still reaches the minimum. A loose inequality
  // row (x in [-1e9, 1e9]) and a small fixed barrier parameter keep the barrier problem the same throughout.
  LambdaNlp q;
  q.n = 1;
  q.m = 1;
  q.xl = Eigen::VectorXd::Constant(1, -kInf);
  q.xu = Eigen::VectorXd::Constant(1, kInf);
  q.gl = Eigen::VectorXd::Constant(1, -1e9);
  q.gu = Eigen::VectorXd::Constant(1, 1e9);
  q.x0 = Eigen::VectorXd::Zero(1);
  double reach = 1.0;  // the domain: x <= reach, one beyond the last point whose derivatives were evaluated
  q.f = [&reach](const Eigen::VectorXd& x) {
    return x[0] <= reach ? 0.5 * (x[0] - 20.0) * (x[0] - 20.0) : std::numeric_limits<double>::quiet_NaN();
  };
  q.g = [](const Eigen::VectorXd& x) { return x; };
  q.grad = [&reach](const Eigen::VectorXd& x) {
    reach = x[0] + 1.0;
    return Eigen::VectorXd::Constant(1, x[0] - 20.0);
  };
  q.jac = [](const Eigen::VectorXd&) { return Eigen::MatrixXd::Ones(1, 1); };
  q.hess = [](const Eigen::VectorXd&, double s, const Eigen::VectorXd&) { return Eigen::MatrixXd::Constant(1, 1, s); };
  q.finalize();
  IpmOptions o;
  o.mu_strategy = "monotone";
  o.mu_init = 1e-3;
  const IpmResult r = solve(q, o);
  ASSERT_EQ(r.status, IpmStatus::kSolved);
  EXPECT_NEAR(r.x[0], 20.0, 1e-6);
  EXPECT_GE(r.stats.watchdog_starts, 1);
  EXPECT_GE(r.stats.watchdog_returns, 1);
}

TEST(InteriorPoint, ALineSearchThatFailsAtAnAcceptableIterateEndsThereSolvedAcceptable) {
  // min |x - (1, 1)|^2 / 2 s.t. x0 + x1 = 1, where the constraint cannot be evaluated within 1e-9 of feasibility
  // (NaN there): the line search halves the steps towards the constraint until the violation nears 1e-9, then
  // fails for good. The iterate is acceptable (violation and dual error ~1e-9, under 1e-6) but not optimal at
  // tol 1e-12, and too infeasible (1e-9 > 1e-2 tol) for the rule that takes back the last acceptable iterate of an
  // almost feasible point. Ipopt's rule before its restoration phase ends the solve there, `solved_acceptable`; a
  // restoration phase could only fail against the same wall.
  LambdaNlp q;
  q.n = 2;
  q.m = 1;
  q.xl = Eigen::Vector2d::Constant(-kInf);
  q.xu = Eigen::Vector2d::Constant(kInf);
  q.gl = Eigen::VectorXd::Zero(1);
  q.gu = Eigen::VectorXd::Zero(1);
  q.x0 = Eigen::Vector2d::Zero();
  q.f = [](const Eigen::VectorXd& x) { return 0.5 * (x - Eigen::Vector2d::Ones()).squaredNorm(); };
  q.g = [](const Eigen::VectorXd& x) {
    const double c = x[0] + x[1] - 1.0;
    return Eigen::VectorXd::Constant(1, std::abs(c) < 1e-9 ? std::numeric_limits<double>::quiet_NaN() : c);
  };
  q.grad = [](const Eigen::VectorXd& x) { return Eigen::VectorXd(x - Eigen::Vector2d::Ones()); };
  q.jac = [](const Eigen::VectorXd&) { return Eigen::MatrixXd::Ones(1, 2); };
  q.hess = [](const Eigen::VectorXd&, double s, const Eigen::VectorXd&) {
    return Eigen::MatrixXd(s * Eigen::Matrix2d::Identity());
  };
  q.finalize();
  IpmOptions o;
  o.tol = 1e-12;
  o.acceptable_iter = 100000;  // not by 15 acceptable iterations in a row
  o.max_iter = 1000;
  const IpmResult r = solve(q, o);
  ASSERT_EQ(r.status, IpmStatus::kAcceptable) << toString(r.status) << " after " << r.stats.iterations;
  EXPECT_LT(r.stats.iterations, o.max_iter);
  EXPECT_EQ(r.stats.restoration_iterations, 0);
  EXPECT_GE(r.constraint_violation, 1e-9);
  EXPECT_LT(r.constraint_violation, 1e-6);
  EXPECT_NEAR(r.x[0], 0.5, 1e-6);  // the minimiser on the line x0 + x1 = 1
  EXPECT_NEAR(r.x[1], 0.5, 1e-6);
}

TEST(InteriorPoint, InfeasibleProblemEndsAsAStatus) {
  // x0^2 + x1^2 = -1 has no solution.
  LambdaNlp q;
  q.n = 2;
  q.m = 1;
  q.xl = Eigen::Vector2d(-5, -5);
  q.xu = Eigen::Vector2d(5, 5);
  q.gl = Eigen::VectorXd::Constant(1, -1.0);
  q.gu = Eigen::VectorXd::Constant(1, -1.0);
  q.x0 = Eigen::Vector2d(1.0, 1.0);
  q.f = [](const Eigen::VectorXd& x) { return x[0] + x[1]; };
  q.g = [](const Eigen::VectorXd& x) { return Eigen::VectorXd::Constant(1, x.squaredNorm()); };
  q.grad = [](const Eigen::VectorXd&) { return Eigen::Vector2d(1, 1); };
  q.jac = [](const Eigen::VectorXd& x) {
    Eigen::MatrixXd J(1, 2);
    J << 2 * x[0], 2 * x[1];
    return J;
  };
  q.hess = [](const Eigen::VectorXd&, double, const Eigen::VectorXd& y) {
    return Eigen::MatrixXd(2 * y[0] * Eigen::Matrix2d::Identity());
  };
  q.finalize();
  IpmOptions opt;
  opt.max_iter = 200;
  const IpmResult r = solve(q, opt);
  EXPECT_NE(r.status, IpmStatus::kSolved);
  EXPECT_NE(r.status, IpmStatus::kAcceptable);
  EXPECT_GT(r.constraint_violation, 0.5);
}

TEST(InteriorPoint, IterationLimitIsAStatus) {
  LambdaNlp q = hs071();
  IpmOptions opt;
  opt.max_iter = 2;
  const IpmResult r = solve(q, opt);
  EXPECT_EQ(r.status, IpmStatus::kMaxIterations);
  EXPECT_EQ(r.stats.iterations, 2);
}
