// JumpProblem::toPrimitive: knots and the 1 kHz resampling of a solved jump.
#include <cmath>

#include "common/yaml_reader.hpp"
#include "planner/jump_problem.hpp"
#include "planner/template_elements.hpp"

namespace centaur::planner {

namespace {

constexpr int kNq = model::kTemplateNq;
constexpr int kNv = model::kTemplateNv;

// Exact step of the template kinematics over h with constant nu_dot: polynomial for positions/velocities,
// RK4 for the quaternion (the same integrator as the OCP's continuity constraint).
void step(const double* q, const double* nu, const double* nu_dot, double h, double* q_next, double* nu_next) {
  for (int a = 0; a < 3; ++a) q_next[a] = q[a] + nu[a] * h + 0.5 * nu_dot[a] * h * h;
  quaternionRk4(q + 3, nu + 3, nu_dot + 3, h, q_next + 3);
  for (int j = 0; j < 12; ++j) q_next[7 + j] = q[7 + j] + nu[6 + j] * h + 0.5 * nu_dot[6 + j] * h * h;
  for (int j = 0; j < kNv; ++j) nu_next[j] = nu[j] + nu_dot[j] * h;
}

}  // namespace

data::Primitive JumpProblem::toPrimitive(const SolveResult& result, double sample_dt) const {
  data::Primitive out;
  out.name = cfg_.primitive;
  out.solve = result.info;
  const Eigen::VectorXd& z = result.z;
  if (result.y.size() == ocp_.numConstraints() && result.z_l.size() == z.size() && result.z_u.size() == z.size() &&
      result.y.allFinite() && result.z_l.allFinite() && result.z_u.allFinite()) {
    out.mult_constraints = result.y;
    out.mult_lower = result.z_l.cwiseMax(0.0);
    out.mult_upper = result.z_u.cwiseMax(0.0);
  }
  fillKnots(z, out);
  const ResampleErrors errors = resample(sample_dt, out);
  fillMetadata(z, sample_dt, errors, out);
  return out;
}

// The knots: states on the nodes, controls and durations on the intervals, and the times of the nodes.
void JumpProblem::fillKnots(const Eigen::VectorXd& z, data::Primitive& out) const {
  const int nx = kNq + kNv, nu_c = ocp_.nu();
  out.knot_x.resize(N_ + 1, nx);
  out.knot_u.resize(N_, nu_c);
  out.knot_dt.resize(N_);
  out.knot_t.resize(N_ + 1);
  out.knot_t[0] = 0.0;
  for (int k = 0; k <= N_; ++k) {
    out.knot_x.row(k) = z.segment(ocp_.index("q", k, 0), nx).transpose();
    if (k < N_) {
      out.knot_u.row(k) = z.segment(ocp_.index("nu_dot", k, 0), nu_c).transpose();
      out.knot_dt[k] = z[ocp_.index("dt", k, 0)];
      out.knot_t[k + 1] = out.knot_t[k] + out.knot_dt[k];
    }
  }
}

// The samples every sample_dt from the knots (out.knot_*), integrated with the OCP's dynamics; the errors are the
// end state against the last knot and the largest under-actuation residual of the inverse dynamics.
JumpProblem::ResampleErrors JumpProblem::resample(double sample_dt, data::Primitive& out) const {
  const auto& P = cfg_.model;
  const double T = out.knot_t[N_];
  const int S = static_cast<int>(std::floor(T / sample_dt + 1e-9)) + 1;
  out.t.resize(S);
  out.q.resize(S, kNq);
  out.nu.resize(S, kNv);
  out.base_pos.resize(S, 3);
  out.base_quat.resize(S, 4);
  out.base_vel.resize(S, 3);
  out.base_omega.resize(S, 3);
  out.foot_pos.resize(S, 12);
  out.foot_pos_rel.resize(S, 12);
  out.foot_vel_rel.resize(S, 12);
  out.force.resize(S, 12);
  out.contact.resize(S, 4);
  out.tau.resize(S, 12);

  Eigen::Matrix<double, kNq, 1> q = out.knot_x.row(0).head(kNq).transpose();
  Eigen::Matrix<double, kNv, 1> nu = out.knot_x.row(0).tail(kNv).transpose();
  double t = 0.0;
  int k = 0;  // current interval
  ResampleErrors errors;
  auto control = [&](int kk, int offset, int n) { return out.knot_u.row(kk).segment(offset, n).transpose(); };

  auto integrateTo = [&](double target) {
    while (t < target - 1e-12) {
      while (k < N_ - 1 && t >= out.knot_t[k + 1] - 1e-12) ++k;
      const double h = std::min(target, out.knot_t[k + 1]) - t;
      const Eigen::Matrix<double, kNv, 1> a = control(k, 0, kNv);
      Eigen::Matrix<double, kNq, 1> qn;
      Eigen::Matrix<double, kNv, 1> nun;
      step(q.data(), nu.data(), a.data(), h, qn.data(), nun.data());
      q = qn;
      nu = nun;
      t += h;
      if (std::abs(t - out.knot_t[k + 1]) < 1e-12) t = out.knot_t[k + 1];
    }
  };

  for (int j = 0; j < S; ++j) {
    const double tj = j * sample_dt;
    integrateTo(tj);
    // The interval whose control acts from this sample on (the last interval at the final time).
    int kk = 0;
    while (kk < N_ - 1 && tj >= out.knot_t[kk + 1] - 1e-12) ++kk;
    const Eigen::Matrix<double, kNv, 1> a = control(kk, 0, kNv);
    const Eigen::Matrix<double, 12, 1> F = control(kk, kNv, 12);
    Eigen::Matrix<double, kNv, 1> tau_full;
    model::inverseDynamics(P, q.data(), nu.data(), a.data(), F.data(), tau_full.data());
    errors.max_residual = std::max(errors.max_residual, tau_full.head<6>().cwiseAbs().maxCoeff());

    const Eigen::Matrix3d R = model::quatToRotation(q.data() + 3);
    out.t[j] = tj;
    out.q.row(j) = q.transpose();
    out.nu.row(j) = nu.transpose();
    out.base_pos.row(j) = q.head<3>().transpose();
    out.base_quat.row(j) = q.segment<4>(3).transpose();
    out.base_vel.row(j) = nu.head<3>().transpose();
    out.base_omega.row(j) = nu.segment<3>(3).transpose();
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d rel = P.hip[i] + q.segment<3>(7 + 3 * i);
      out.foot_pos_rel.row(j).segment<3>(3 * i) = rel.transpose();
      out.foot_pos.row(j).segment<3>(3 * i) = (q.head<3>() + R * rel).transpose();
      out.foot_vel_rel.row(j).segment<3>(3 * i) = nu.segment<3>(6 + 3 * i).transpose();
      out.force.row(j).segment<3>(3 * i) = F.segment<3>(3 * i).transpose();
      out.contact(j, i) = schedule_[i][kk] >= 0 ? 1.0 : 0.0;
    }
    out.tau.row(j) = tau_full.tail<12>().transpose();
  }
  // End state of the resampled trajectory against the last knot.
  integrateTo(T);
  Eigen::VectorXd x_end(kNq + kNv);
  x_end << q, nu;
  errors.end_error = (x_end - out.knot_x.row(N_).transpose()).cwiseAbs().maxCoeff();
  return errors;
}

// The configuration, the model's and the problem's parameters, the resampling's errors and the cost's terms.
void JumpProblem::fillMetadata(const Eigen::VectorXd& z, double sample_dt, const ResampleErrors& errors,
                               data::Primitive& out) const {
  const auto& P = cfg_.model;
  out.config_yaml = toYamlString(cfg_.effective);
  out.strings["model_preset"] = P.preset;
  out.strings["robot"] = cfg_.robot;  // the robot it was planned for (a simulation checks it) and its description's hash
  out.strings["robot_hash"] = cfg_.robot_hash;
  out.strings["foot_point"] = "wheel centre";
  out.strings["friction_model"] = cfg_.contact.friction;
  out.strings["config_source"] = cfg_.source;
  std::string surf;
  for (const auto& s : surfaces_) surf += (surf.empty() ? "" : ";") + s.name;
  out.strings["surfaces"] = surf;
  out.scalars["total_mass"] = P.totalMass();
  out.scalars["waist_mass"] = P.waist_mass;
  out.scalars["foot_mass"] = P.foot_mass;
  out.scalars["gravity"] = P.gravity;
  out.scalars["wheel_radius"] = cfg_.wheel_radius;
  out.scalars["ground_z"] = 0.0;
  out.scalars["sample_dt"] = sample_dt;
  out.scalars["duration"] = out.knot_t[N_];
  out.scalars["intervals"] = N_;
  out.scalars["takeoff_interval"] = cfg_.horizon.takeoff;
  out.scalars["landing_interval"] = cfg_.horizon.landing;
  out.scalars["mu"] = cfg_.contact.mu;
  out.scalars["leg_force_max"] = cfg_.limits.leg_force;
  out.scalars["resampled_end_state_error"] = errors.end_error;
  out.scalars["resampled_max_underactuation_residual"] = errors.max_residual;
  if (cfg_.primitive == "squat-jump") out.scalars["target_height"] = cfg_.target_height;
  if (cfg_.primitive == "half-squat-jump") {
    out.scalars["wall_x"] = cfg_.wallX();
    out.scalars["mu_wall"] = cfg_.contact.mu_wall;
  }
  out.vectors["waist_com"] = {P.waist_com.x(), P.waist_com.y(), P.waist_com.z()};
  out.vectors["waist_inertia"] = std::vector<double>(P.waist_inertia.data(), P.waist_inertia.data() + 9);
  out.vectors["foot_inertia"] = std::vector<double>(P.foot_inertia.data(), P.foot_inertia.data() + 9);
  std::vector<double> hips;
  for (const auto& h : P.hip) hips.insert(hips.end(), {h.x(), h.y(), h.z()});
  out.vectors["hip_offsets"] = hips;
  const auto costs = ocp_.costBreakdown(z.data());
  for (const auto& [name, v] : costs) out.scalars["cost_" + name] = v;
}

}  // namespace centaur::planner
