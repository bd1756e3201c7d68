#include "planner/jump_problem.hpp"

#include <cmath>
#include <memory>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "planner/solve_ocp.hpp"
#include "planner/template_elements.hpp"

namespace centaur::planner {

namespace {

constexpr int kNq = model::kTemplateNq;
constexpr int kNv = model::kTemplateNv;
constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<int> cat(std::initializer_list<std::vector<int>> parts) {
  std::vector<int> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

Eigen::VectorXd constant(int n, double v) { return Eigen::VectorXd::Constant(n, v); }

}  // namespace

JumpProblem::JumpProblem(const JumpConfig& config)
    : cfg_(config), ocp_(config.horizon.intervals), N_(config.horizon.intervals) {
  force_scale_ = cfg_.model.totalMass() * std::max(cfg_.model.gravity, 1.0);
  const double r = cfg_.wheel_radius;
  surfaces_.push_back({"ground", Eigen::Vector3d::UnitZ(), -r, cfg_.contact.mu});
  // Schedules. Squat jump: all feet on the ground on [0, N_T] and [N_L, N-1]. Half-squat jump: front feet on the
  // ground throughout; rear feet on the ground on [0, N_T], on the wall (normal +x, behind the robot) on [N_L, N-1].
  schedule_.assign(4, std::vector<int>(N_, -1));
  const int NT = cfg_.horizon.takeoff, NL = cfg_.horizon.landing;
  if (cfg_.primitive == "half-squat-jump") {
    const double wall_plane = cfg_.wallX() + r;  // foot-point plane
    surfaces_.push_back({"wall", Eigen::Vector3d::UnitX(), -wall_plane, cfg_.contact.mu_wall});
    for (int k = 0; k < N_; ++k) {
      schedule_[0][k] = schedule_[1][k] = 0;
      schedule_[2][k] = schedule_[3][k] = (k <= NT) ? 0 : (k >= NL ? 1 : -1);
    }
  } else {
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < N_; ++k) schedule_[i][k] = (k <= NT || k >= NL) ? 0 : -1;
  }
  buildVariables();
  buildDynamics();
  buildContacts();
  buildCosts();
  buildGuess();
  ocp_.finalize();
}

std::vector<int> JumpProblem::idx(const char* var, int k, int first, int count) const {
  std::vector<int> out(count);
  for (int j = 0; j < count; ++j) out[j] = ocp_.index(var, k, first + j);
  return out;
}

void JumpProblem::buildVariables() {
  ocp_.addState("q", kNq);
  ocp_.addState("nu", kNv);
  ocp_.addControl("nu_dot", kNv);
  ocp_.addControl("F", 12);
  ocp_.addControl("dt", 1);

  // Initial state (fixed by bounds): waist above the origin, level, feet at their stance points, at rest.
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(kNq);
  q0[2] = cfg_.initialWaistHeight();
  q0[3] = 1.0;
  for (int i = 0; i < 4; ++i) q0.segment<3>(7 + 3 * i) = cfg_.feet[i] - cfg_.model.hip[i];
  ocp_.setBounds("q", 0, q0, q0);
  ocp_.setBounds("nu", 0, constant(kNv, 0.0), constant(kNv, 0.0));

  // Workspace: the foot point in the waist frame is hip_i + q_C,i; a box per foot.
  Eigen::VectorXd qlo = constant(kNq, -kInf), qhi = constant(kNq, kInf);
  const auto& W = cfg_.workspace;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d& x = (i < 2) ? W.front_x : W.rear_x;
    const Eigen::Vector2d& y = (i % 2 == 0) ? W.left_y : W.right_y;
    const Eigen::Vector3d lo(x[0], y[0], W.z[0]), hi(x[1], y[1], W.z[1]);
    qlo.segment<3>(7 + 3 * i) = lo - cfg_.model.hip[i];
    qhi.segment<3>(7 + 3 * i) = hi - cfg_.model.hip[i];
  }
  if (W.reach > 0.0) {  // leg reach: |hip -> foot| <= reach at every node (the box alone lets a stretched leg
                        // with its foot far forward ask for more than the robot's leg reaches)
    auto reach = std::make_shared<LegReachElement>();
    for (int k = 1; k <= N_; ++k) {
      for (int i = 0; i < 4; ++i) {
        ocp_.addTerm(ocp_.addConstraint("leg_reach", k, constant(1, 0.0), constant(1, W.reach * W.reach)), reach,
                     idx("q", k, 7 + 3 * i, 3));
      }
    }
  }
  const double vmax = cfg_.limits.velocity, amax = cfg_.limits.acceleration;
  for (int k = 1; k <= N_; ++k) {
    ocp_.setBounds("q", k, qlo, qhi);
    Eigen::VectorXd vlo = constant(kNv, -vmax), vhi = constant(kNv, vmax);
    if (k == N_) vlo.head<6>().setZero(), vhi.head<6>().setZero();  // final state: the waist at rest
    ocp_.setBounds("nu", k, vlo, vhi);
  }
  for (int k = 0; k < N_; ++k) {
    ocp_.setBounds("nu_dot", k, constant(kNv, -amax), constant(kNv, amax));
    ocp_.setBounds("dt", k, constant(1, cfg_.horizon.dt_min), constant(1, cfg_.horizon.dt_max));
    ocp_.setBounds("F", k, constant(12, -cfg_.contact.force_max), constant(12, cfg_.contact.force_max));
  }
  ocp_.setScale("nu_dot", constant(kNv, 10.0));
  ocp_.setScale("F", constant(12, 0.25 * force_scale_));
  ocp_.setScale("dt", constant(1, 0.1));
}

void JumpProblem::buildDynamics() {
  auto pos = std::make_shared<PositionStep>();
  auto vel = std::make_shared<VelocityStep>();
  auto quat = std::make_shared<QuaternionStep>();
  auto waist = std::make_shared<WaistDynamicsElement>(cfg_.model, force_scale_);
  std::vector<std::shared_ptr<FootDynamicsElement>> feet;
  for (int i = 0; i < 4; ++i) feet.push_back(std::make_shared<FootDynamicsElement>(cfg_.model, i, force_scale_));

  Eigen::VectorXd dyn_lo = constant(kNv, 0.0), dyn_hi = constant(kNv, 0.0);
  dyn_lo.tail<12>().setConstant(-cfg_.limits.leg_force / force_scale_);
  dyn_hi.tail<12>().setConstant(cfg_.limits.leg_force / force_scale_);

  for (int k = 0; k < N_; ++k) {
    const auto dt = idx("dt", k, 0, 1);
    const auto& cont = ocp_.addConstraint("continuity", k, constant(kNq + kNv, 0.0), constant(kNq + kNv, 0.0));
    // Base position (rows 0-2) and leg coordinates (rows 7-18): exact constant-acceleration steps.
    for (int a = 0; a < 3; ++a) {
      ocp_.addTerm(cont, pos, cat({idx("q", k, a, 1), idx("nu", k, a, 1), idx("nu_dot", k, a, 1), dt, idx("q", k + 1, a, 1)}), {a});
    }
    ocp_.addTerm(cont, quat, cat({idx("q", k, 3, 4), idx("nu", k, 3, 3), idx("nu_dot", k, 3, 3), dt, idx("q", k + 1, 3, 4)}),
                 {3, 4, 5, 6});
    for (int j = 0; j < 12; ++j) {
      ocp_.addTerm(cont, pos,
                   cat({idx("q", k, 7 + j, 1), idx("nu", k, 6 + j, 1), idx("nu_dot", k, 6 + j, 1), dt, idx("q", k + 1, 7 + j, 1)}),
                   {7 + j});
    }
    for (int j = 0; j < kNv; ++j) {
      ocp_.addTerm(cont, vel, cat({idx("nu", k, j, 1), idx("nu_dot", k, j, 1), dt, idx("nu", k + 1, j, 1)}), {kNq + j});
    }
    // Under-actuation (rows 0-5 == 0) and torque bounds (rows 6-17), scaled by 1 / (m g).
    const auto& dyn = ocp_.addConstraint("dynamics", k, dyn_lo, dyn_hi);
    ocp_.addTerm(dyn, waist, cat({idx("q", k, 3, 4), idx("nu", k, 3, 3), idx("nu_dot", k, 0, 3), idx("nu_dot", k, 3, 3)}),
                 {0, 1, 2, 3, 4, 5});
    for (int i = 0; i < 4; ++i) {
      ocp_.addTerm(dyn, feet[i],
                   cat({idx("q", k, 3, 4), idx("nu", k, 3, 3), idx("q", k, 7 + 3 * i, 3), idx("nu", k, 6 + 3 * i, 3),
                        idx("nu_dot", k, 0, 3), idx("nu_dot", k, 3, 3), idx("nu_dot", k, 6 + 3 * i, 3), idx("F", k, 3 * i, 3)}),
                   {0, 1, 2, 3, 4, 5, 6 + 3 * i, 7 + 3 * i, 8 + 3 * i});
    }
  }
}

void JumpProblem::buildContacts() {
  const auto& P = cfg_.model;
  auto footKin = [&](int k, int i) { return cat({idx("q", k, 0, 3), idx("q", k, 3, 4), idx("q", k, 7 + 3 * i, 3)}); };
  auto footVelIn = [&](int k, int i) {
    return cat({idx("q", k, 3, 4), idx("q", k, 7 + 3 * i, 3), idx("nu", k, 0, 3), idx("nu", k, 3, 3), idx("nu", k, 6 + 3 * i, 3)});
  };
  for (int i = 0; i < 4; ++i) {
    std::vector<char> pinned(N_ + 1, 0);
    int k = 0;
    while (k < N_) {
      const int s = schedule_[i][k];
      if (s < 0) {
        Eigen::VectorXd lo = ocp_.lowerBounds().segment(ocp_.index("F", k, 0), 12);
        Eigen::VectorXd hi = ocp_.upperBounds().segment(ocp_.index("F", k, 0), 12);
        lo.segment<3>(3 * i).setZero();
        hi.segment<3>(3 * i).setZero();
        ocp_.setBounds("F", k, lo, hi);
        ++k;
        continue;
      }
      int e = k;
      while (e + 1 < N_ && schedule_[i][e + 1] == s) ++e;
      const Surface& S = surfaces_[s];
      // Friction on every contact interval of the phase.
      for (int j = k; j <= e; ++j) {
        const auto& fb = (cfg_.contact.friction == "cone")
                             ? ocp_.addConstraint("friction", j, constant(2, 0.0), constant(2, kInf))
                             : ocp_.addConstraint("friction", j, constant(5, 0.0), constant(5, kInf));
        std::shared_ptr<const Element> fe;
        if (cfg_.contact.friction == "cone") {
          fe = std::make_shared<FrictionConeElement>(S.normal, S.mu, cfg_.contact.force_threshold, force_scale_);
        } else {
          fe = std::make_shared<FrictionPyramidElement>(S.normal, S.mu, cfg_.contact.force_threshold, force_scale_);
        }
        ocp_.addTerm(fb, fe, idx("F", j, 3 * i, 3));
      }
      // Position: pinned at every node of the phase.
      const bool from_start = (k == 0);
      const bool back_to_start = (!from_start && s == 0 && schedule_[i][0] == 0 && cfg_.contact.touchdown == "same_position");
      if (from_start || back_to_start) {
        auto pe = std::make_shared<FootPointElement>(P, i, cfg_.initialFootWorld(i));
        for (int n = (from_start ? 1 : k); n <= e + 1; ++n) {
          ocp_.addTerm(ocp_.addConstraint("contact_point", n, constant(3, 0.0), constant(3, 0.0)), pe, footKin(n, i));
        }
      } else {
        auto se = std::make_shared<FootSurfaceElement>(P, i, S.normal, S.offset);
        ocp_.addTerm(ocp_.addConstraint("contact_surface", k, constant(1, 0.0), constant(1, 0.0)), se, footKin(k, i));
        auto de = std::make_shared<FootDisplacementElement>(P, i);
        for (int n = k + 1; n <= e + 1; ++n) {
          ocp_.addTerm(ocp_.addConstraint("contact_no_slip", n, constant(3, 0.0), constant(3, 0.0)), de,
                       cat({footKin(n - 1, i), footKin(n, i)}));
        }
      }
      if (!from_start) {  // touch-down: the foot arrives at rest (eq. no_slip)
        auto ve = std::make_shared<FootVelocityElement>(P, i);
        ocp_.addTerm(ocp_.addConstraint("contact_velocity", k, constant(3, 0.0), constant(3, 0.0)), ve, footVelIn(k, i));
      }
      if (S.name == "wall" && cfg_.wall_height > 0.0) {  // target.wall_height: touch-down height on the wall
        auto he = std::make_shared<FootSurfaceElement>(P, i, Eigen::Vector3d::UnitZ(), -cfg_.wall_height);
        ocp_.addTerm(ocp_.addConstraint("wall_height", k, constant(1, 0.0), constant(1, 0.0)), he, footKin(k, i));
      }
      for (int n = k; n <= e + 1; ++n) pinned[n] = 1;
      if (cfg_.cost.stance_foot_velocity > 0) {
        auto ve = std::make_shared<FootVelocitySquared>(P, i);
        for (int n = (from_start ? 1 : k + 1); n <= e + 1; ++n) {
          ocp_.addCost("stance_foot_velocity", ve, footVelIn(n, i), cfg_.cost.stance_foot_velocity);
        }
      }
      k = e + 1;
    }
    // Swing nodes stay on the free side of every surface.
    for (int n = 1; n <= N_; ++n) {
      if (pinned[n]) continue;
      for (const auto& S : surfaces_) {
        auto se = std::make_shared<FootSurfaceElement>(P, i, S.normal, S.offset);
        ocp_.addTerm(ocp_.addConstraint("clearance_" + S.name, n, constant(1, 0.0), constant(1, kInf)), se, footKin(n, i));
      }
    }
  }
}

void JumpProblem::buildCosts() {
  const auto& C = cfg_.cost;
  const int NT = cfg_.horizon.takeoff, NL = cfg_.horizon.landing;
  const double z0 = cfg_.initialWaistHeight();
  if (C.base_height > 0) {
    auto e = std::make_shared<SquaredError<1>>(Eigen::Matrix<double, 1, 1>(cfg_.target_height), "base_height");
    for (int k = NT + 1; k <= NL; ++k) ocp_.addCost("base_height", e, idx("q", k, 2, 1), C.base_height);
  }
  if (C.base_velocity > 0) {
    auto e = std::make_shared<SquaredError<kNv>>(Eigen::Matrix<double, kNv, 1>::Zero(), "base_velocity");
    for (int k = NT + 1; k <= NL; ++k) ocp_.addCost("base_velocity", e, idx("nu", k, 0, kNv), C.base_velocity);
  }
  if (C.joint_velocity > 0) {
    auto e = std::make_shared<SquaredError<12>>(Eigen::Matrix<double, 12, 1>::Zero(), "joint_velocity");
    for (int k = NT + 1; k <= N_; ++k) ocp_.addCost("joint_velocity", e, idx("nu", k, 6, 12), C.joint_velocity);
  }
  if (C.force_rate > 0) {  // forces measured in units of the per-foot static load m g / 4
    auto e = std::make_shared<SquaredDifference<12>>();
    for (int k = NL + 1; k <= N_ - 2; ++k) ocp_.addCost("force_rate", e, cat({idx("F", k, 0, 12), idx("F", k + 1, 0, 12)}), C.force_rate / (0.0625 * force_scale_ * force_scale_));
  }
  if (C.acceleration_rate > 0) {
    auto e = std::make_shared<SquaredDifference<kNv>>();
    for (int k = 0; k <= N_ - 2; ++k)
      ocp_.addCost("acceleration_rate", e, cat({idx("nu_dot", k, 0, kNv), idx("nu_dot", k + 1, 0, kNv)}), C.acceleration_rate);
  }
  if (C.velocity_regularization > 0) {
    auto e = std::make_shared<SquaredError<kNv>>(Eigen::Matrix<double, kNv, 1>::Zero(), "velocity_regularization");
    for (int k = 1; k <= N_; ++k) ocp_.addCost("velocity_regularization", e, idx("nu", k, 0, kNv), C.velocity_regularization);
  }
  if (C.base_angular_velocity > 0) {
    auto e = std::make_shared<SquaredError<3>>(Eigen::Vector3d::Zero(), "base_angular_velocity");
    for (int k = 1; k <= N_; ++k) ocp_.addCost("base_angular_velocity", e, idx("nu", k, 3, 3), C.base_angular_velocity);
  }
  if (C.last_interval > 0) {  // the last interval's step size, which nothing else fixes once the robot is at rest
    auto e = std::make_shared<SquaredError<1>>(Eigen::Matrix<double, 1, 1>::Zero(), "last_interval");
    ocp_.addCost("last_interval", e, idx("dt", N_ - 1, 0, 1), C.last_interval);
  }
  if (C.landing_steps > 0) {  // from the landing on the robot comes to rest: little else fixes those steps' lengths
    auto e = std::make_shared<AffineSum<1>>(Eigen::Matrix<double, 1, 1>::Constant(-1.0), cfg_.horizon.dt_max,
                                            "landing_steps");
    for (int k = NL; k <= N_ - 1; ++k) ocp_.addCost("landing_steps", e, idx("dt", k, 0, 1), C.landing_steps);
  }
  const Eigen::Vector4d rho0(1, 0, 0, 0);
  if (C.base_orientation > 0) {
    auto e = std::make_shared<SquaredError<4>>(rho0, "base_orientation");
    for (int k = 1; k <= N_; ++k) ocp_.addCost("base_orientation", e, idx("q", k, 3, 4), C.base_orientation);
  }
  if (C.base_pose > 0) {
    auto ep = std::make_shared<SquaredError<3>>(Eigen::Vector3d(0, 0, z0), "base_position");
    auto eo = std::make_shared<SquaredError<4>>(rho0, "base_orientation");
    for (int k = NT + 1; k <= N_; ++k) {
      ocp_.addCost("base_pose", ep, idx("q", k, 0, 3), C.base_pose);
      ocp_.addCost("base_pose", eo, idx("q", k, 3, 4), C.base_pose);
    }
  }
}

void JumpProblem::buildGuess() {
  Eigen::VectorXd q0 = ocp_.lowerBounds().segment(ocp_.index("q", 0, 0), kNq);
  for (int k = 0; k <= N_; ++k) {
    ocp_.setGuess("q", k, q0);
    ocp_.setGuess("nu", k, constant(kNv, 0.0));
  }
  const double mg = cfg_.model.totalMass() * cfg_.model.gravity;
  for (int k = 0; k < N_; ++k) {
    int on_ground = 0;
    for (int i = 0; i < 4; ++i) on_ground += (schedule_[i][k] == 0);
    Eigen::VectorXd F = Eigen::VectorXd::Zero(12);
    for (int i = 0; i < 4; ++i) {
      const int s = schedule_[i][k];
      if (s < 0) continue;
      F.segment<3>(3 * i) = (s == 0 && on_ground > 0 ? mg / on_ground : 0.05 * mg) * surfaces_[s].normal;
    }
    ocp_.setGuess("F", k, F);
    ocp_.setGuess("nu_dot", k, constant(kNv, 0.0));
    ocp_.setGuess("dt", k, constant(1, cfg_.horizon.dt_init));
  }
}

SolveResult JumpProblem::solve(bool progress, const Eigen::VectorXd* x0) const {
  SolverSettings s = cfg_.solver;
  s.progress = progress;
  return solveOcp(ocp_, s, x0);
}

SolveResult JumpProblem::solve(bool progress, const WarmStartPoint& warm) const {
  SolverSettings s = cfg_.solver;
  s.progress = progress;
  return solveOcp(ocp_, s, warm);
}

WarmStartPoint JumpProblem::warmStart(const data::Primitive& p, const std::string& source) const {
  WarmStartPoint w;
  w.z = decisionVector(p, source);
  if (p.mult_constraints.size() == ocp_.numConstraints() && p.mult_lower.size() == w.z.size() &&
      p.mult_upper.size() == w.z.size()) {
    w.y = p.mult_constraints;
    w.z_l = p.mult_lower;
    w.z_u = p.mult_upper;
  }
  return w;
}

Eigen::VectorXd JumpProblem::decisionVector(const data::Primitive& p, const std::string& source) const {
  const int nx = ocp_.nx(), nu = ocp_.nu();
  if (p.knot_x.rows() != N_ + 1 || p.knot_x.cols() != nx || p.knot_u.rows() != N_ || p.knot_u.cols() != nu) {
    throw InputError(source + ": primitive '" + p.name + "' has " + std::to_string(p.knot_x.rows() - 1) +
                     " intervals of " + std::to_string(p.knot_x.cols()) + " states and " +
                     std::to_string(p.knot_u.cols()) + " controls; this problem has " + std::to_string(N_) + ", " +
                     std::to_string(nx) + " and " + std::to_string(nu) + " (plan the neighbour with the same horizon)");
  }
  Eigen::VectorXd z = ocp_.guess();
  for (int k = 0; k <= N_; ++k) {
    z.segment(ocp_.index("q", k, 0), nx) = p.knot_x.row(k).transpose();
    if (k < N_) z.segment(ocp_.index("nu_dot", k, 0), nu) = p.knot_u.row(k).transpose();
  }
  if (!z.allFinite()) throw InputError(source + ": primitive '" + p.name + "' has non-finite knots");
  return z;
}

}  // namespace centaur::planner
