// ctest-labels: physics integration
// The planned primitives, checked at every 1 kHz sample of the resampled trajectory (which is integrated from
// the knots with the same dynamics, not interpolated): contacts, friction, flight, torques, Newton's law.
#include <gtest/gtest.h>

#include <cmath>

#include "model/template_model.hpp"
#include "planner/jump_problem.hpp"

using namespace centaur;
using namespace centaur::planner;
using namespace centaur::data;

namespace {

struct Solved {
  JumpConfig cfg;
  Primitive prim;
};

const Solved& solved(const std::string& primitive) {
  static std::map<std::string, Solved> cache;
  auto it = cache.find(primitive);
  if (it == cache.end()) {
    Solved s;
    s.cfg = loadJumpConfig(primitive, "", {});
    const JumpProblem problem(s.cfg);
    s.prim = problem.toPrimitive(problem.solve(false));
    it = cache.emplace(primitive, std::move(s)).first;
  }
  return it->second;
}

Eigen::Vector3d row3(const RowMatrix& m, Eigen::Index j, int i) { return m.row(j).segment<3>(3 * i).transpose(); }

// Every contact sample: on its surface, not slipping since the phase began, force inside the friction cone.
void checkContacts(const Solved& s, double wall_x) {
  const Primitive& p = s.prim;
  const double r = s.cfg.wheel_radius;
  for (int i = 0; i < 4; ++i) {
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
    bool in_phase = false;
    double worst_surface = 0.0, worst_slip = 0.0, worst_cone = 0.0, worst_flight_force = 0.0;
    for (Eigen::Index j = 0; j < p.samples(); ++j) {
      const Eigen::Vector3d pf = row3(p.foot_pos, j, i), F = row3(p.force, j, i);
      if (p.contact(j, i) < 0.5) {
        in_phase = false;
        worst_flight_force = std::max(worst_flight_force, F.norm());
        continue;
      }
      if (!in_phase) anchor = pf, in_phase = true;
      // Which surface: the wall when the foot is at the wall plane, else the ground.
      const bool on_wall = wall_x > -1e9 && i >= 2 && std::abs(pf.x() - (wall_x + r)) < 0.01;
      const Eigen::Vector3d n = on_wall ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
      const double dist = on_wall ? pf.x() - (wall_x + r) : pf.z() - r;
      const double mu = on_wall ? s.cfg.contact.mu_wall : s.cfg.contact.mu;
      worst_surface = std::max(worst_surface, std::abs(dist));
      worst_slip = std::max(worst_slip, (pf - anchor).norm());
      const double fn = F.dot(n);
      const double ft = (F - fn * n).norm();
      worst_cone = std::max(worst_cone, std::max(-fn, ft - mu * fn));
    }
    EXPECT_LT(worst_surface, 1e-3) << "foot " << i << " leaves its surface in stance";
    EXPECT_LT(worst_slip, 1e-3) << "foot " << i << " slips in stance";
    EXPECT_LE(worst_cone, 1e-3) << "foot " << i << " force outside the friction cone (N, beyond the solver tolerance)";
    EXPECT_EQ(worst_flight_force, 0.0) << "foot " << i << " has a force while not in contact";
  }
}

// Newton's law for the whole system: d/dt (sum m_b v_b) = sum F + m g, from the sampled states.
void checkNewton(const Solved& s) {
  const Primitive& p = s.prim;
  const auto& P = s.cfg.model;
  const double mg = P.totalMass() * P.gravity, h = p.t[1] - p.t[0];
  auto momentum = [&](Eigen::Index j) {
    const model::VectorQ q = p.q.row(j).transpose();
    const model::VectorV v = p.nu.row(j).transpose();
    return model::linearMomentum(P, q, v);
  };
  double worst = 0.0;
  int checked = 0;
  for (Eigen::Index j = 1; j + 1 < p.samples(); ++j) {
    // Skip samples next to a knot, where the piecewise-constant forces jump.
    bool near_knot = false;
    for (Eigen::Index k = 0; k < p.knot_t.size(); ++k) near_knot = near_knot || std::abs(p.t[j] - p.knot_t[k]) <= 1.5 * h;
    if (near_knot) continue;
    const Eigen::Vector3d dp = (momentum(j + 1) - momentum(j - 1)) / (2 * h);
    Eigen::Vector3d f(0, 0, -mg);
    for (int i = 0; i < 4; ++i) f += row3(p.force, j, i);
    worst = std::max(worst, (dp - f).norm() / mg);
    ++checked;
  }
  EXPECT_GT(checked, p.samples() / 2);
  EXPECT_LT(worst, 0.01) << "Newton's law violated by " << 100 * worst << " % of the weight";
}

void checkTorques(const Solved& s) {
  const double lim = s.cfg.limits.leg_force;
  const double worst = s.prim.tau.cwiseAbs().maxCoeff();
  EXPECT_LE(worst, lim * 1.01) << "prismatic leg force beyond its bound at some 1 kHz sample";
  // At the knots the bound holds exactly (it is a constraint there).
  for (Eigen::Index k = 0; k + 1 < s.prim.knot_t.size(); ++k) {
    const Eigen::Index j = static_cast<Eigen::Index>(std::llround(s.prim.knot_t[k] / 1e-3));
    if (j < s.prim.samples() && std::abs(s.prim.t[j] - s.prim.knot_t[k]) < 1e-9) {
      EXPECT_LE(s.prim.tau.row(j).cwiseAbs().maxCoeff(), lim * (1 + 1e-6));
    }
  }
}

}  // namespace

TEST(SquatJump, ConvergesAndObeysTheContactModelAtEverySample) {
  const Solved& s = solved("squat-jump");
  ASSERT_EQ(s.prim.solve.status, "solved");
  EXPECT_LT(s.prim.solve.max_constraint_violation, 1e-6);
  checkContacts(s, -1e10);
}

TEST(SquatJump, HasAFlightPhaseWithoutForcesAndReachesTheTarget) {
  const Solved& s = solved("squat-jump");
  const Primitive& p = s.prim;
  int flight = 0;
  double apex = -1e9;
  for (Eigen::Index j = 0; j < p.samples(); ++j) {
    if (p.contact.row(j).sum() == 0) {
      ++flight;
      EXPECT_EQ(p.force.row(j).norm(), 0.0);
    }
    apex = std::max(apex, p.base_pos(j, 2));
  }
  EXPECT_GT(flight, 100) << "at least 0.1 s of flight";
  EXPECT_GE(apex, s.cfg.target_height - 0.01) << "apex " << apex << " m, target " << s.cfg.target_height << " m";
  // Ballistic flight: the whole-body CoM follows g exactly between take-off and touch-down.
}

TEST(SquatJump, ObeysNewtonTorqueBoundsAndMatchesItsKnots) {
  const Solved& s = solved("squat-jump");
  checkNewton(s);
  checkTorques(s);
  EXPECT_LT(s.prim.scalars.at("resampled_end_state_error"), 1e-5);  // one RK4 step per interval vs 1 ms steps
  // The first sample is the initial knot, exactly.
  EXPECT_LT((s.prim.q.row(0) - s.prim.knot_x.row(0).head(model::kTemplateNq)).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(HalfSquatJump, RearFeetEndOnTheWallPushingAndFrontFeetNeverLeave) {
  const Solved& s = solved("half-squat-jump");
  const Primitive& p = s.prim;
  ASSERT_EQ(p.solve.status, "solved");
  const double wall_x = p.scalars.at("wall_x"), r = s.cfg.wheel_radius;
  checkContacts(s, wall_x);
  const Eigen::Index last = p.samples() - 1;
  for (int i = 2; i < 4; ++i) {
    EXPECT_EQ(p.contact(last, i), 1.0);
    EXPECT_NEAR(p.foot_pos(last, 3 * i + 0), wall_x + r, 1e-3) << "rear foot " << i << " not on the wall plane";
    EXPECT_GT(p.force(last, 3 * i + 0), 1.0) << "the wall must push the robot (normal force into the wall)";
  }
  for (Eigen::Index j = 0; j < p.samples(); ++j) {
    for (int i = 0; i < 2; ++i) {
      ASSERT_EQ(p.contact(j, i), 1.0);
      ASSERT_NEAR(p.foot_pos(j, 3 * i + 2), r, 1e-3) << "front foot " << i << " leaves the ground at " << p.t[j];
    }
  }
  checkNewton(s);
  checkTorques(s);
}

TEST(SquatJump, LegReachOptionBoundsEveryKnot) {
  // workspace.reach: |hip -> foot| <= reach at every node (a sphere per leg, on top of the box).
  const double reach = 0.74;
  const JumpConfig cfg = loadJumpConfig("squat-jump", "", {"workspace.reach=0.74"});
  const JumpProblem problem(cfg);
  const SolveResult r = problem.solve(false);
  ASSERT_TRUE(r.info.solved()) << r.info.status;
  const Primitive p = problem.toPrimitive(r);
  double worst = 0.0;
  for (Eigen::Index k = 1; k < p.knot_x.rows(); ++k) {
    for (int i = 0; i < 4; ++i) worst = std::max(worst, p.knot_x.row(k).segment<3>(7 + 3 * i).norm());
  }
  EXPECT_LE(worst, reach + 1e-6);
  EXPECT_GT(worst, reach - 0.01);  // it binds: the default plan stretches further (0.79 m)
}
