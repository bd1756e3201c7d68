// ctest-labels: physics integration
// The two OCP backends (Ipopt + MUMPS, the reference; our interior point with the stage-wise KKT solver) on 21
// perturbed variants of the shipped problems: targets, wall distances, friction coefficients, both model presets,
// pyramid and cone friction, free touch-down, and the arm flywheel's period and momentum. For every variant both
// converge, and either
//   - they reach the same local optimum: objective within 1e-6 relative and the same 1 kHz primitive (positions
//     within 1 mm; durations within 3 ms and forces within 10 N, because the objective fixes the step sizes only
//     to ~1e-4 s at tol 1e-8 -- a flat valley along the phase durations -- so the sample grids shift by a few
//     samples and quickly changing forces differ there), or
//   - the variant is one where they stop at different points (named in the table below, docs/planner.md):
//     different local optima, or points of the flat valley at the same objective whose primitives differ beyond
//     these bounds; each point is a KKT point: the other backend, warm-started there, stays (objective within
//     1e-6 relative), except where the table says that riccati leaves Ipopt's point for a lower one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "planner/arm_flywheel_problem.hpp"
#include "planner/jump_problem.hpp"
#include "planner/solve_ocp.hpp"
#include "planner/solve_with.hpp"

using namespace centaur;
using namespace centaur::planner;
using centaur::test::solveWith;

namespace {

enum class Expect {
  kSame,            // the same local optimum
  kBothStay,        // different KKT points (local optima, or points of a flat valley at the same objective whose
                    // primitives differ): each backend, warm-started at the other's point, stays there
  kRiccatiDescends, // Ipopt stays at riccati's point; riccati, warm-started at Ipopt's, leaves it for a lower one
};

struct Variant {
  std::string name;                   // test name
  std::string primitive;              // squat-jump | half-squat-jump | arm-flywheel
  std::vector<std::string> overrides; // --set key=value
  Expect expect;
};

std::ostream& operator<<(std::ostream& os, const Variant& v) { return os << v.name; }

double relDiff(double a, double b) { return std::abs(a - b) / std::max(1.0, std::abs(b)); }

void expectConverged(const SolveResult& r, const std::string& what, double constr_viol_tol) {
  EXPECT_EQ(r.info.status, "solved") << what;
  EXPECT_LT(r.info.max_constraint_violation, constr_viol_tol) << what;
}

double maxDiff(const data::RowMatrix& a, const data::RowMatrix& b) {
  const Eigen::Index n = std::min(a.rows(), b.rows());
  return (a.topRows(n) - b.topRows(n)).cwiseAbs().maxCoeff();
}

// The backends stopped at different points: check that each is a KKT point, by warm-starting the other backend
// there. Ipopt (the reference) must stay at riccati's point. Riccati must stay at Ipopt's point, or, where the
// variant says so, leave it for a point with a lower objective (never a higher one).
void expectKktPointsOfTheOther(const Ocp& ocp, const SolverSettings& s, const SolveResult& ip, const SolveResult& ri,
                               Expect expect) {
  const SolveResult ri_from_ip = solveWith(ocp, s, "riccati", &ip.z);
  const SolveResult ip_from_ri = solveWith(ocp, s, "ipopt", &ri.z);
  std::printf("  riccati from Ipopt's point %.10g (%d it), Ipopt from riccati's point %.10g (%d it)\n",
              ri_from_ip.info.cost, ri_from_ip.info.iterations, ip_from_ri.info.cost, ip_from_ri.info.iterations);
  if (ri_from_ip.info.status == "solved_acceptable") {
    // The descent from Ipopt's point may end at Ipopt's acceptable level (15 iterations within acceptable_tol), and
    // so may staying there: Ipopt's point depends on the BLAS kernels OpenBLAS picks for the CPU (MUMPS runs on
    // them; the build fixes them for the tests only on CPUs with AVX2 and FMA). With OpenBLAS's Cooperlake kernels
    // (AVX-512) Ipopt reaches the 0.85 m squat jump's optimum in 87 iterations instead of 75, and riccati's
    // knots-only start there stays within 1e-6 but at the acceptable level. The objective below decides.
    EXPECT_LT(ri_from_ip.info.max_constraint_violation, s.constr_viol_tol);
  } else {
    expectConverged(ri_from_ip, "riccati warm-started at Ipopt's optimum", s.constr_viol_tol);
  }
  expectConverged(ip_from_ri, "ipopt warm-started at riccati's optimum", s.constr_viol_tol);
  EXPECT_LT(relDiff(ip_from_ri.info.cost, ri.info.cost), 1e-6) << ip_from_ri.info.cost << " vs " << ri.info.cost;
  if (expect == Expect::kBothStay) {
    EXPECT_LT(relDiff(ri_from_ip.info.cost, ip.info.cost), 1e-6) << ri_from_ip.info.cost << " vs " << ip.info.cost;
  } else {
    EXPECT_LT(ri_from_ip.info.cost, ip.info.cost * (1.0 - 1e-6)) << "riccati was expected to find a lower point";
  }
}

struct Both {
  SolveResult ip, ri;
};

// Both backends from the default guess; both must converge. Prints the objectives (the table in docs/planner.md).
Both solveBoth(const Variant& v, const Ocp& ocp, const SolverSettings& s) {
  Both r{solveWith(ocp, s, "ipopt"), solveWith(ocp, s, "riccati")};
  std::printf("%s: ipopt %.10g (%d it), riccati %.10g (%d it), relative difference %.1e\n", v.name.c_str(),
              r.ip.info.cost, r.ip.info.iterations, r.ri.info.cost, r.ri.info.iterations,
              relDiff(r.ri.info.cost, r.ip.info.cost));
  expectConverged(r.ip, "ipopt", s.constr_viol_tol);
  expectConverged(r.ri, "riccati", s.constr_viol_tol);
  return r;
}

class BackendsAgreeVariant : public ::testing::TestWithParam<Variant> {};

TEST_P(BackendsAgreeVariant, SameOptimumOrBothKktPoints) {
  const Variant& v = GetParam();
  if (v.primitive == "arm-flywheel") {
    const ArmFlywheelProblem p(loadArmFlywheelConfig("", v.overrides));
    const SolverSettings& s = p.config().solver;
    const Both r = solveBoth(v, p.ocp(), s);
    if (v.expect != Expect::kSame) {
      expectKktPointsOfTheOther(p.ocp(), s, r.ip, r.ri, v.expect);
      return;
    }
    EXPECT_LT(relDiff(r.ri.info.cost, r.ip.info.cost), 1e-6) << "a different local optimum";
    const data::ArmTrajectory a = p.toTrajectory(r.ip), b = p.toTrajectory(r.ri);
    EXPECT_LT(maxDiff(a.q, b.q), 1e-3);    // [rad]
    EXPECT_LT(maxDiff(a.tau, b.tau), 1.0);  // [N m]
    return;
  }
  const JumpProblem p(loadJumpConfig(v.primitive, "", v.overrides));
  const SolverSettings& s = p.config().solver;
  const Both r = solveBoth(v, p.ocp(), s);
  if (v.expect != Expect::kSame) {
    expectKktPointsOfTheOther(p.ocp(), s, r.ip, r.ri, v.expect);
    return;
  }
  EXPECT_LT(relDiff(r.ri.info.cost, r.ip.info.cost), 1e-6) << "a different local optimum";
  const data::Primitive a = p.toPrimitive(r.ip), b = p.toPrimitive(r.ri);
  EXPECT_NEAR(a.t[a.samples() - 1], b.t[b.samples() - 1], 3e-3);  // [s]
  EXPECT_LT(maxDiff(a.base_pos, b.base_pos), 1e-3);                // [m]
  EXPECT_LT(maxDiff(a.foot_pos, b.foot_pos), 1e-3);
  EXPECT_LT(maxDiff(a.force, b.force), 10.0);                      // [N], of peaks of ~2 kN
}

// clang-format off
const std::vector<Variant> kVariants = {
  {"SquatHeight082", "squat-jump", {"target.height=0.82"}, Expect::kSame},
  {"SquatHeight085", "squat-jump", {"target.height=0.85"}, Expect::kBothStay},
  {"SquatHeight090", "squat-jump", {"target.height=0.90"}, Expect::kBothStay},
  {"SquatHeight092", "squat-jump", {"target.height=0.92"}, Expect::kBothStay},
  {"SquatCone", "squat-jump", {"contact.friction=cone"}, Expect::kRiccatiDescends},
  {"SquatAuthorsPreset", "squat-jump", {"model.preset=centauro-authors"}, Expect::kBothStay},
  {"SquatMu04", "squat-jump", {"contact.mu=0.4"}, Expect::kBothStay},
  {"SquatConeMu08", "squat-jump", {"contact.friction=cone", "contact.mu=0.8"}, Expect::kBothStay},
  {"HalfSquatWall012", "half-squat-jump", {"target.wall_distance=0.12"}, Expect::kBothStay},
  {"HalfSquatWall014", "half-squat-jump", {"target.wall_distance=0.14"}, Expect::kBothStay},
  {"HalfSquatWall016", "half-squat-jump", {"target.wall_distance=0.16"}, Expect::kBothStay},
  {"HalfSquatWall018", "half-squat-jump", {"target.wall_distance=0.18"}, Expect::kBothStay},
  {"HalfSquatCone", "half-squat-jump", {"contact.friction=cone"}, Expect::kSame},
  {"HalfSquatAuthorsPreset", "half-squat-jump", {"model.preset=centauro-authors"}, Expect::kBothStay},
  {"HalfSquatMuWall08", "half-squat-jump", {"contact.mu_wall=0.8"}, Expect::kBothStay},
  {"HalfSquatMu08", "half-squat-jump", {"contact.mu=0.8"}, Expect::kBothStay},
  {"HalfSquatAuthorsCone", "half-squat-jump", {"model.preset=centauro-authors", "contact.friction=cone"},
   Expect::kSame},
  // A point of docs/planner.md's half-squat-jump grid where riccati's KKT matrix had the wrong inertia for every
  // primal regularization in an early iteration (numerical_trouble before the dual regularization followed).
  {"HalfSquatAuthorsWall015Height010", "half-squat-jump",
   {"model.preset=centauro-authors", "target.wall_distance=0.15", "target.wall_height=0.1"}, Expect::kBothStay},
  {"ArmMomentum4", "arm-flywheel", {"phase_anchor=true", "cost.momentum_target=4.0"}, Expect::kSame},
  {"ArmPeriod08", "arm-flywheel", {"phase_anchor=true", "horizon.period=0.8"}, Expect::kBothStay},
  {"ArmPeriod12", "arm-flywheel", {"phase_anchor=true", "horizon.period=1.2"}, Expect::kSame},
};
// clang-format on

INSTANTIATE_TEST_SUITE_P(Variants, BackendsAgreeVariant, ::testing::ValuesIn(kVariants),
                         [](const ::testing::TestParamInfo<Variant>& i) { return i.param.name; });

}  // namespace
