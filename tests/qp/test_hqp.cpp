// ctest-labels: physics
// Hierarchical QP: strict priorities (a lower level never worsens a higher one), Math-of-Tasks expressions,
// closed-loop convergence with the task gain on a planar arm, joint limits at every tick over a long run.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "qp/hqp_solver.hpp"
#include "toy_arm.hpp"

using namespace centaur;
using centaur::test::PlanarArm;
using centaur::test::PostureTask;
using centaur::test::TipPositionTask;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

std::shared_ptr<LinearTask> randomTask(std::mt19937& rng, const std::string& name, int rows, int n) {
  std::normal_distribution<double> N(0.0, 1.0);
  MatrixXd A(rows, n);
  VectorXd b(rows);
  for (int i = 0; i < rows; ++i) {
    b[i] = N(rng);
    for (int j = 0; j < n; ++j) A(i, j) = N(rng);
  }
  if (rows >= 3) A.row(rows - 1) = A.row(0) + A.row(1);  // rank deficient rows, inconsistent targets
  return std::make_shared<LinearTask>(name, A, b);
}
}  // namespace

TEST(Hqp, TwoLevelAnalytic) {
  // Level 0: x0 + x1 = 1 (exactly achievable); level 1: x = (2, 0, 3).
  // Solution: x2 = 3 and the projection of (2, 0) on x0 + x1 = 1: (1.5, -0.5); eps shifts it by O(eps).
  auto a = std::make_shared<LinearTask>("a", (MatrixXd(1, 3) << 1, 1, 0).finished(), VectorXd::Ones(1));
  auto b = std::make_shared<LinearTask>("b", MatrixXd::Identity(3, 3), Eigen::Vector3d(2, 0, 3));
  Stack s = a / b;
  s.regularisation = 1e-10;
  HqpSolver hqp(s, 3);
  VectorXd x(3);
  ASSERT_EQ(hqp.solve(x), QpStatus::kOptimal);
  EXPECT_NEAR(x[0], 1.5, 1e-8);
  EXPECT_NEAR(x[1], -0.5, 1e-8);
  EXPECT_NEAR(x[2], 3.0, 1e-8);
  // With a box bound x1 >= 0 the first level still wins: x0 + x1 = 1, x1 = 0 closest to b's wish.
  auto box = std::make_shared<LinearConstraint>("box", 3, 0);
  box->lowerBounds()[1] = 0.0;
  HqpSolver hqp2(s << box, 3);
  ASSERT_EQ(hqp2.solve(x), QpStatus::kOptimal);
  EXPECT_NEAR(x[0], 1.0, 1e-8);
  EXPECT_NEAR(x[1], 0.0, 1e-8);
}

TEST(Hqp, MathOfTasksBuildsLevelsTermsAndConstraints) {
  std::mt19937 rng(1);
  auto feet = randomTask(rng, "feet", 6, 8), pelvis = randomTask(rng, "pelvis", 3, 8);
  auto ang = randomTask(rng, "ang_mom", 3, 8), posture = randomTask(rng, "posture", 8, 8);
  auto lim = std::make_shared<JointVelocityLimits>("qd", 8, 2, VectorXd::Ones(6));
  Stack s = (feet / (pelvis % Rows{0, 2})) / (ang + 0.1 * posture) << lim << lim;
  ASSERT_EQ(s.levels.size(), 3u);
  EXPECT_EQ(s.levels[0].size(), 6);
  EXPECT_EQ(s.levels[1].size(), 2);
  EXPECT_EQ(s.levels[1].terms[0].rows, (Rows{0, 2}));
  EXPECT_EQ(s.levels[2].terms.size(), 2u);
  EXPECT_DOUBLE_EQ(s.levels[2].terms[1].scale, 0.1);
  EXPECT_EQ(s.constraints.size(), 1u);  // the same constraint object is added once
  // Selecting from a selection picks among its rows; out of range rows are rejected.
  const Term t = (feet % Rows{1, 3, 5}) % Rows{2};
  EXPECT_EQ(t.rows, (Rows{5}));
  EXPECT_THROW(feet % Rows{6}, std::out_of_range);
  // Wrong sizes are rejected at configure time.
  auto wrong = randomTask(rng, "wrong", 2, 7);
  EXPECT_THROW(HqpSolver(feet / wrong, 8), std::invalid_argument);
}

TEST(Hqp, LowerPriorityNeverWorsensHigher) {
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> rows_d(1, 6);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 4 + trial % 9;
    const int levels = 2 + trial % 3;
    std::vector<Level> lv;
    for (int k = 0; k < levels; ++k) {
      Level l = randomTask(rng, "t" + std::to_string(k), rows_d(rng), n);
      if (U(rng) < 0.5) l = l + Level(U(rng) * Term(randomTask(rng, "s" + std::to_string(k), rows_d(rng), n)));
      lv.push_back(l);
    }
    // Box bounds that contain 0 (so every level is feasible) plus a random inequality row.
    auto box = std::make_shared<LinearConstraint>("box", n, 1);
    for (int j = 0; j < n; ++j) {
      box->lowerBounds()[j] = -0.2 - U(rng);
      box->upperBounds()[j] = U(rng) < 0.2 ? kInf : 0.2 + U(rng);
    }
    for (int j = 0; j < n; ++j) box->C()(0, j) = U(rng);
    box->cLower()[0] = -kInf;
    box->cUpper()[0] = 0.3;
    Stack full = lv[0];
    for (int k = 1; k < levels; ++k) full = full / lv[k];
    full = full << box;
    full.regularisation = 1e-9;
    HqpSolver hqp(full, n);
    VectorXd x(n);
    ASSERT_EQ(hqp.solve(x), QpStatus::kOptimal) << trial;
    for (int j = 0; j < levels - 1; ++j) {
      // The stack truncated after level j: its optimum of level j is the best level j can do.
      Stack upto = lv[0];
      for (int k = 1; k <= j; ++k) upto = upto / lv[k];
      upto = upto << box;
      upto.regularisation = 1e-9;
      HqpSolver alone(upto, n);
      VectorXd xa(n);
      ASSERT_EQ(alone.solve(xa), QpStatus::kOptimal);
      const double best = alone.levelCost(j, xa);
      const double got = hqp.levelCost(j, x);
      EXPECT_LE(got, best + 1e-7 * (1.0 + best)) << "trial " << trial << " level " << j;
    }
    // The last level is optimal given the levels above: no feasible direction improves it. Check against a
    // perturbation that keeps higher-level rows fixed: the null space of the stacked higher rows.
    EXPECT_LE(x.maxCoeff(), 10.0);  // sanity: bounded by the box and the regularisation
  }
}

TEST(Hqp, FeasibleStackConvergesWithTheTaskGain) {
  // 3-link arm, tip task above posture; the tip target is reachable and the limits are far, so the tip error
  // obeys e' = -lambda e: e(t) = e0 exp(-lambda t) (to first order in dt).
  PlanarArm arm(3);
  arm.q << 0.3, 0.6, 0.4;
  auto tip = std::make_shared<TipPositionTask>("tip", arm);
  auto posture = std::make_shared<PostureTask>("posture", arm);
  posture->q_ref = arm.q;
  tip->target = Eigen::Vector2d(0.3, 0.55);
  const double lambda = 5.0, dt = 1e-3;
  tip->setLambda(lambda);
  posture->setLambda(1.0);
  auto vel = std::make_shared<JointVelocityLimits>("qd", 3, 0, VectorXd::Constant(3, 10.0));
  HqpSolver hqp(tip / posture << vel, 3);
  VectorXd qd(3);
  hqp.update();
  const double e0 = tip->b().norm();
  for (int k = 1; k <= 3000; ++k) {
    hqp.update();
    ASSERT_EQ(hqp.solve(qd), QpStatus::kOptimal);
    arm.q += dt * qd;
    if (k == 200) {  // t = 0.2 s = 1 / lambda
      hqp.update();
      EXPECT_NEAR(tip->b().norm() / e0, std::exp(-lambda * 0.2), 0.01);
    }
  }
  hqp.update();
  EXPECT_LT(tip->b().norm(), 1e-4 * e0);
  EXPECT_LT((arm.tip() - tip->target).norm(), 1e-5);
}

TEST(Hqp, JointLimitsHoldAtEveryTickWithRandomTargets) {
  PlanarArm arm(4);
  arm.q << 0.2, 0.3, -0.2, 0.1;
  const VectorXd q_min = (VectorXd(4) << -0.5, -0.2, -1.0, -0.3).finished();
  const VectorXd q_max = (VectorXd(4) << 1.0, 1.5, 0.2, 0.8).finished();
  const VectorXd qd_max = (VectorXd(4) << 1.0, 2.0, 1.5, 3.0).finished();
  const double dt = 1e-3;
  auto tip = std::make_shared<TipPositionTask>("tip", arm);
  auto posture = std::make_shared<PostureTask>("posture", arm);
  auto pos = std::make_shared<JointPositionLimits>("q", 4, 0, q_min, q_max, dt);
  auto vel = std::make_shared<JointVelocityLimits>("qd", 4, 0, qd_max);
  tip->setLambda(20.0);
  posture->setLambda(2.0);
  HqpSolver hqp(tip / (0.01 * posture) << pos << vel, 4);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1.2, 1.2);
  VectorXd qd(4);
  int at_limit_ticks = 0;
  for (int k = 0; k < 20000; ++k) {
    if (k % 500 == 0) tip->target = Eigen::Vector2d(U(rng), U(rng));  // many unreachable within the limits
    pos->setJointPositions(arm.q);
    hqp.update();
    ASSERT_EQ(hqp.solve(qd), QpStatus::kOptimal) << "tick " << k;
    for (int j = 0; j < 4; ++j) ASSERT_LE(std::abs(qd[j]), qd_max[j]) << "tick " << k;
    arm.q += dt * qd;
    for (int j = 0; j < 4; ++j) {
      // q + dt (q_max - q) / dt may round one ulp past the limit
      ASSERT_GE(arm.q[j], q_min[j] - 1e-15) << "tick " << k << " joint " << j;
      ASSERT_LE(arm.q[j], q_max[j] + 1e-15) << "tick " << k << " joint " << j;
      if (arm.q[j] <= q_min[j] + 1e-9 || arm.q[j] >= q_max[j] - 1e-9) ++at_limit_ticks;
    }
  }
  EXPECT_GT(at_limit_ticks, 1000);  // the limits were actually exercised
}

TEST(Hqp, InfeasibleConstraintsAreReportedWithTheLevel) {
  auto a = std::make_shared<LinearTask>("a", MatrixXd::Identity(2, 2), VectorXd::Ones(2));
  // x0 + x1 >= 1 and x0 + x1 <= 0 (rows; crossed box bounds would be resolved, rows are not).
  auto c = std::make_shared<LinearConstraint>("c", 2, 2);
  c->C().setOnes();
  c->cLower()[0] = 1.0;
  c->cUpper()[1] = 0.0;
  HqpSolver hqp(Stack(a) << c, 2);
  VectorXd x = VectorXd::Constant(2, 7.0);
  EXPECT_EQ(hqp.solve(x), QpStatus::kInfeasible);
  EXPECT_EQ(hqp.failedLevel(), 0);
  EXPECT_EQ(x[0], 7.0);  // untouched
  a->b()[1] = std::numeric_limits<double>::quiet_NaN();
  c->cUpper()[1] = 2.0;
  EXPECT_EQ(hqp.solve(x), QpStatus::kInvalidInput);
}

TEST(Hqp, ALevelThatFailsTheKktCheckIsReportedWithTheLevel) {
  // A lower level whose QP answer fails the KKT check (a tolerance no answer can meet) is a failure of that
  // level: the cascade stops there, failedLevel() names it, x holds the level above's solution.
  std::mt19937 rng(8);
  auto t0 = randomTask(rng, "t0", 2, 5), t1 = randomTask(rng, "t1", 5, 5);
  auto box = std::make_shared<LinearConstraint>("box", 5, 1);
  box->lowerBounds().setConstant(-0.3);  // active at the optimum of level 1: the dual method runs
  box->upperBounds().setConstant(0.3);
  HqpSolver hqp(t0 / t1 << box, 5);
  VectorXd x(5);
  ASSERT_EQ(hqp.solve(x), QpStatus::kOptimal);
  const VectorXd good = x;
  ASSERT_GT(hqp.levelSolver(1).numActive(), 0);
  hqp.levelSolver(1).settings().kkt_tol = 1e-30;
  EXPECT_EQ(hqp.solve(x), QpStatus::kInaccurate);
  EXPECT_EQ(hqp.failedLevel(), 1);
  EXPECT_EQ((x - hqp.levelSolution(0)).norm(), 0.0);
  EXPECT_GT((x - good).norm(), 1e-6);  // the level above's solution, not the last good answer
  hqp.levelSolver(1).settings().kkt_tol = 1e-9;
  ASSERT_EQ(hqp.solve(x), QpStatus::kOptimal);
  EXPECT_LT((x - good).norm(), 1e-12);
}

TEST(Hqp, RedundantLevelsAndFullyDeterminedLevels) {
  // A task repeated at a lower level (all its rows dependent on the level above) changes nothing, and a level
  // below a full-rank level is fixed (null space of dimension 0).
  std::mt19937 rng(8);
  const int n = 7;
  auto a = randomTask(rng, "a", 4, n), b = randomTask(rng, "b", 3, n);
  auto full = std::make_shared<LinearTask>("full", MatrixXd::Identity(n, n) + 0.1 * MatrixXd::Ones(n, n),
                                           VectorXd::Ones(n));
  auto box = std::make_shared<LinearConstraint>("box", n, 0);
  box->lowerBounds().setConstant(-0.5);
  box->upperBounds().setConstant(0.5);
  HqpSolver ab(a / b << box, n), aab(a / a / b << box, n);
  VectorXd x1(n), x2(n);
  ASSERT_EQ(ab.solve(x1), QpStatus::kOptimal);
  ASSERT_EQ(aab.solve(x2), QpStatus::kOptimal);
  EXPECT_LT((x1 - x2).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(aab.levelRank(2), ab.levelRank(1));
  HqpSolver fixed(Stack(full) / b, n);
  ASSERT_EQ(fixed.solve(x1), QpStatus::kOptimal);
  EXPECT_EQ(fixed.levelRank(1), n);
  EXPECT_LT((x1 - fixed.levelSolution(0)).norm(), 1e-15);
}

TEST(Hqp, JointBeyondItsLimitIsBroughtBackAtTheVelocityLimit) {
  // q is 0.1 rad beyond q_max: the position bound asks for -100 rad/s over one tick, the velocity limit allows
  // -2 rad/s; the solver must not report infeasible but move back at -2 rad/s, and converge into the range.
  PlanarArm arm(3);
  arm.q << 0.2, 1.1, 0.0;
  const double dt = 1e-3;
  auto posture = std::make_shared<PostureTask>("posture", arm);
  posture->q_ref << 0.2, 2.0, 0.0;  // wants to go further out
  auto pos = std::make_shared<JointPositionLimits>("q", 3, 0, VectorXd::Constant(3, -1.0), VectorXd::Constant(3, 1.0),
                                                   dt);
  auto vel = std::make_shared<JointVelocityLimits>("qd", 3, 0, VectorXd::Constant(3, 2.0));
  HqpSolver hqp(Stack(posture) << pos << vel, 3);
  VectorXd qd(3);
  pos->setJointPositions(arm.q);
  hqp.update();
  ASSERT_EQ(hqp.solve(qd), QpStatus::kOptimal);
  EXPECT_DOUBLE_EQ(qd[1], -2.0);
  for (int k = 0; k < 100; ++k) {
    arm.q += dt * qd;
    pos->setJointPositions(arm.q);
    hqp.update();
    ASSERT_EQ(hqp.solve(qd), QpStatus::kOptimal);
  }
  EXPECT_LE(arm.q[1], 1.0 + 1e-12);
}

TEST(Hqp, WarmStartNeverChangesTheAnswer) {
  // Closed loop with limits being hit: a persistent (warm) solver and one made cold at every tick agree.
  PlanarArm arm(5);
  arm.q << 0.1, 0.4, -0.3, 0.2, 0.5;
  const double dt = 1e-3;
  auto tip = std::make_shared<TipPositionTask>("tip", arm);
  auto posture = std::make_shared<PostureTask>("posture", arm);
  auto extra = std::make_shared<LinearTask>("extra", MatrixXd::Ones(1, 5), VectorXd::Zero(1));
  auto pos = std::make_shared<JointPositionLimits>("q", 5, 0, VectorXd::Constant(5, -0.6), VectorXd::Constant(5, 0.6),
                                                   dt);
  auto vel = std::make_shared<JointVelocityLimits>("qd", 5, 0, VectorXd::Constant(5, 1.5));
  tip->setLambda(30.0);
  const Stack s = tip / extra / posture << pos << vel;
  HqpSolver warm(s, 5), cold(s, 5);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  VectorXd xw(5), xc(5);
  for (int k = 0; k < 3000; ++k) {
    if (k % 300 == 0) tip->target = Eigen::Vector2d(U(rng), U(rng));
    pos->setJointPositions(arm.q);
    warm.update();
    for (int l = 0; l < cold.numLevels(); ++l) cold.levelSolver(l).resetWarmStart();
    ASSERT_EQ(warm.solve(xw), QpStatus::kOptimal) << k;
    ASSERT_EQ(cold.solve(xc), QpStatus::kOptimal) << k;
    ASSERT_LT((xw - xc).cwiseAbs().maxCoeff(), 1e-9) << "tick " << k;
    arm.q += dt * xw;
  }
}

TEST(Hqp, FirstLevelOnItsOwnColumnsEqualsTheFullProblem) {
  // Level 0 touches only some columns (as the feet of a whole-body stack touch only the legs): the solver leaves
  // the others out of the first QP and its null space. Reference: the same stack plus an inequality row with
  // infinite bounds that touches every column, which keeps every column in the first QP (the full-size path)
  // without changing the problem. Both must give the same solution of every level, including columns whose box
  // excludes 0 (the first level puts them at the bound nearest 0).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 6 + trial % 7;
    auto first = randomTask(rng, "first", 1 + trial % 4, n);
    std::vector<int> unused;
    for (int j = 0; j < n; ++j)
      if (U(rng) < 0.5) unused.push_back(j);
    for (int j : unused) first->A().col(j).setZero();
    auto second = randomTask(rng, "second", 2 + trial % 3, n);
    auto third = randomTask(rng, "third", n, n);
    auto box = std::make_shared<LinearConstraint>("box", n, 0);
    for (int j = 0; j < n; ++j) {
      box->lowerBounds()[j] = -0.3 - U(rng);
      box->upperBounds()[j] = 0.3 + U(rng);
    }
    if (!unused.empty()) box->lowerBounds()[unused[0]] = 0.1;  // excludes 0
    auto everywhere = std::make_shared<LinearConstraint>("everywhere", n, 1);
    everywhere->C().setOnes();
    everywhere->cLower()[0] = -kInf;
    everywhere->cUpper()[0] = kInf;
    const Stack s = first / second / third << box;
    HqpSolver reduced(s, n), full(s << everywhere, n);
    VectorXd xr(n), xf(n);
    ASSERT_EQ(reduced.solve(xr), QpStatus::kOptimal) << trial;
    ASSERT_EQ(full.solve(xf), QpStatus::kOptimal) << trial;
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT((reduced.levelSolution(k) - full.levelSolution(k)).cwiseAbs().maxCoeff(), 1e-7)
          << "trial " << trial << " level " << k;
      EXPECT_EQ(reduced.levelRank(k), full.levelRank(k));
    }
    if (!unused.empty()) {
      EXPECT_DOUBLE_EQ(reduced.levelSolution(0)[unused[0]], 0.1);
    }
  }
}

TEST(Hqp, LevelsOnTheColumnsTheyTouchEqualTheFullProblem) {
  // Every level touches its own random subset of the columns (as a whole-body stack: feet on the legs, then the
  // pelvis, then the arms' momentum, then a posture on everything), so variables stay out of the reduced QPs
  // until a level first touches them. Reference: the same stack plus an always-inactive row touching every
  // column, which makes every variable dense from level 0 on. Every level's solution and rank must agree. Some
  // last levels are a posture (a row per column), whose late-joining variables the solver takes in closed form.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int late_touches = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 5 + trial % 9;
    std::vector<std::shared_ptr<LinearTask>> level;
    std::vector<bool> seen(n, false);
    for (int k = 0; k < 4; ++k) {
      const int rows = 1 + static_cast<int>(U(rng) * (k == 3 ? n : 4));
      auto t = randomTask(rng, "level" + std::to_string(k), rows, n);
      if (k == 3 && trial % 3 == 2) {  // a posture: one row per column, each on its own column only
        MatrixXd P = MatrixXd::Zero(n, n);
        for (int j = 0; j < n; ++j) P(j, j) = 0.5 + U(rng);
        t = std::make_shared<LinearTask>("posture", P, VectorXd::Random(n));
      }
      const double keep = k == 3 ? (trial % 3 == 2 ? 1.0 : 0.9) : 0.35;
      for (int j = 0; j < n; ++j) {
        if (U(rng) > keep) {
          t->A().col(j).setZero();
        } else {
          if (k > 0 && !seen[j]) ++late_touches;
          seen[j] = true;
        }
      }
      if (trial % 4 == 1 && k >= 1) {  // a full (non-diagonal) SPD weight on some trials: the dense path
        MatrixXd R = MatrixXd::Random(t->rows(), t->rows());
        t->setWeight(MatrixXd(R * R.transpose() + MatrixXd::Identity(t->rows(), t->rows())));
      } else if (trial % 4 == 2) {
        t->setWeight(0.5 + U(rng));  // a diagonal weight other than 1
      }
      level.push_back(t);
    }
    auto box = std::make_shared<LinearConstraint>("box", n, 1);
    for (int j = 0; j < n; ++j) {
      box->lowerBounds()[j] = -0.2 - U(rng);
      box->upperBounds()[j] = 0.2 + U(rng);
    }
    box->lowerBounds()[trial % n] = 0.05;  // excludes 0
    if (trial % 3 == 0) box->lowerBounds()[n - 1] = -kInf, box->upperBounds()[n - 1] = kInf;  // unbounded
    box->C().setZero();  // one inequality row on two columns, active in some trials
    box->C()(0, 0) = 1.0;
    box->C()(0, n / 2) = 1.0;
    box->cLower()[0] = -0.3 * U(rng);
    box->cUpper()[0] = 0.3 * U(rng);
    auto everywhere = std::make_shared<LinearConstraint>("everywhere", n, 1);
    everywhere->C().setOnes();
    everywhere->cLower()[0] = -kInf;
    everywhere->cUpper()[0] = kInf;
    const Stack s = level[0] / level[1] / level[2] / level[3] << box;
    HqpSolver reduced(s, n), full(s << everywhere, n);
    VectorXd xr(n), xf(n);
    ASSERT_EQ(reduced.solve(xr), QpStatus::kOptimal) << trial;
    ASSERT_EQ(full.solve(xf), QpStatus::kOptimal) << trial;
    for (int k = 0; k < 4; ++k) {
      // 1e-6: these random stacks are ill-conditioned enough that merely reversing the column order of the full
      // problem moves a level's solution by up to 1.2e-7 (measured over the same 200 trials).
      EXPECT_LT((reduced.levelSolution(k) - full.levelSolution(k)).cwiseAbs().maxCoeff(), 1e-6)
          << "trial " << trial << " level " << k;
      EXPECT_EQ(reduced.levelRank(k), full.levelRank(k)) << "trial " << trial << " level " << k;
    }
  }
  EXPECT_GT(late_touches, 200);  // the trials do exercise variables that join at a lower level
}

TEST(Hqp, EveryLevelIsTheQpWithTheLevelsAboveAsEqualities) {
  // The definition of the cascade, solved directly: level k minimises its terms plus eps ||x||^2 subject to
  // A_j x = A_j x_j* for the levels j < k and the box, one plain QP in x with those equality rows (no null space,
  // no variable partition, no blocks). Random 3-level stacks whose first level is made of independent blocks of
  // rows (rows on disjoint columns, as the four feet), the others on random column subsets.
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const double eps = 1e-6;
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 8 + trial % 6;
    // level 0: blocks of 2 rows, each on its own 3 consecutive columns (the last columns stay free)
    const int blocks = 1 + trial % 3;
    MatrixXd A0 = MatrixXd::Zero(2 * blocks, n);
    for (int b = 0; b < blocks; ++b)
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 3; ++j) A0(2 * b + i, 3 * b + j) = U(rng) - 0.5;
    auto first = std::make_shared<LinearTask>("first", A0, VectorXd::Random(2 * blocks));
    auto second = randomTask(rng, "second", 1 + trial % 3, n);
    for (int j = 0; j < n; ++j)
      if (U(rng) < 0.5) second->A().col(j).setZero();
    auto third = randomTask(rng, "third", n, n);
    auto box = std::make_shared<LinearConstraint>("box", n, 0);
    for (int j = 0; j < n; ++j) {
      box->lowerBounds()[j] = -0.3 - U(rng);
      box->upperBounds()[j] = 0.3 + U(rng);
    }
    const Stack s = first / second / third << box;
    HqpSolver hqp(s, n);
    VectorXd x(n);
    ASSERT_EQ(hqp.solve(x), QpStatus::kOptimal) << trial;

    const std::shared_ptr<LinearTask> levels[3] = {first, second, third};
    MatrixXd Aeq(0, n);
    VectorXd beq(0);
    for (int k = 0; k < 3; ++k) {
      const LinearTask& t = *levels[k];
      const MatrixXd H = t.A().transpose() * t.A() + eps * MatrixXd::Identity(n, n);
      const VectorXd g = -t.A().transpose() * t.b();
      QpSolver qp(n, static_cast<int>(Aeq.rows()), 0);
      ASSERT_EQ(qp.solve(H, g, Aeq, beq, MatrixXd(0, n), VectorXd(0), VectorXd(0), box->lowerBounds(),
                         box->upperBounds()),
                QpStatus::kOptimal)
          << "trial " << trial << " level " << k;
      const VectorXd xk = qp.x();
      EXPECT_LT((hqp.levelSolution(k) - xk).cwiseAbs().maxCoeff(), 1e-6) << "trial " << trial << " level " << k;
      // the next levels keep this level's rows at their values
      MatrixXd A2(Aeq.rows() + t.A().rows(), n);
      A2 << Aeq, t.A();
      VectorXd b2(beq.size() + t.A().rows());
      b2 << beq, t.A() * xk;
      Aeq = A2;
      beq = b2;
    }
  }
}
