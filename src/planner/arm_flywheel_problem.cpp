#include "planner/arm_flywheel_problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "planner/solve_ocp.hpp"
#include "model/chain_from_mjcf.hpp"
#include "planner/arm_elements.hpp"

namespace centaur::planner {

namespace {

std::vector<int> cat(std::initializer_list<std::vector<int>> parts) {
  std::vector<int> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

Eigen::VectorXd constant(int n, double v) { return Eigen::VectorXd::Constant(n, v); }
constexpr double kBig = std::numeric_limits<double>::infinity();  // no bound on that row

}  // namespace

ArmFlywheelProblem::ArmFlywheelProblem(const ArmFlywheelConfig& config) : cfg_(config), ocp_(config.intervals) {
  const std::string mjcf = cfg_.mjcf.empty() ? model::centauroMjcfPath() : cfg_.mjcf;
  chain_ = model::chainFromMjcf(mjcf, model::centauroLeftArmSpec());
  model::ChainSpec right;
  for (int i = 1; i <= 7; ++i) right.joints.push_back("j_arm2_" + std::to_string(i));
  right.ee_frame = "ball2_tip";
  const model::SerialChain rchain = model::chainFromMjcf(mjcf, right);
  if (chain_.dof() != kArmDof) throw InputError(mjcf + ": the arm must have 7 joints");
  buildLimits(rchain);
  buildVariables();
  buildGuess();
  buildConstraints();
  buildCosts();
  ocp_.finalize();
}

// The left arm's limits intersected with the mirrored right arm's (q_right = s q_left), then the configured
// margins and scales.
void ArmFlywheelProblem::buildLimits(const model::SerialChain& rchain) {
  const auto s = data::armMirrorSigns();
  const int n = kArmDof;
  q_lo_model_.resize(n), q_hi_model_.resize(n), qd_max_model_.resize(n), tau_max_model_.resize(n);
  q_lo_.resize(n), q_hi_.resize(n), qd_max_.resize(n), tau_max_.resize(n);
  for (int i = 0; i < n; ++i) {
    const auto& L = chain_.links[i];
    const auto& R = rchain.links[i];
    const double rlo = s[i] > 0 ? R.q_min : -R.q_max;
    const double rhi = s[i] > 0 ? R.q_max : -R.q_min;
    q_lo_model_[i] = std::max(L.q_min, rlo);
    q_hi_model_[i] = std::min(L.q_max, rhi);
    qd_max_model_[i] = std::min(L.qd_max, R.qd_max);
    tau_max_model_[i] = std::min(L.tau_max, R.tau_max);
    q_lo_[i] = q_lo_model_[i] + cfg_.position_margin;
    q_hi_[i] = q_hi_model_[i] - cfg_.position_margin;
    if (q_lo_[i] >= q_hi_[i]) {
      throw InputError(cfg_.source, "limits.position_margin", "leaves no range for joint " + L.joint);
    }
    qd_max_[i] = cfg_.velocity_scale * qd_max_model_[i];
    tau_max_[i] = cfg_.torque_scale * tau_max_model_[i];
  }
}

// The states q, qd on the nodes and the control qdd on the intervals: bounds and scales.
void ArmFlywheelProblem::buildVariables() {
  const int n = kArmDof;
  const int N = cfg_.intervals;
  const double h = cfg_.period / N;
  ocp_.addState("q", n);
  ocp_.addState("qd", n);
  ocp_.addControl("qdd", n);
  const double a_max = 4.0 * qd_max_.maxCoeff() / h;  // generous box on qdd (numerical safety only)
  for (int k = 0; k <= N; ++k) {
    ocp_.setBounds("q", k, q_lo_, q_hi_);
    ocp_.setBounds("qd", k, -qd_max_, qd_max_);
  }
  if (cfg_.phase_anchor) {
    Eigen::VectorXd lo = -qd_max_, hi = qd_max_;
    lo[0] = hi[0] = 0.0;
    ocp_.setBounds("qd", 0, lo, hi);
  }
  for (int k = 0; k < N; ++k) ocp_.setBounds("qdd", k, constant(n, -a_max), constant(n, a_max));
  ocp_.setScale("q", constant(n, 1.0));
  ocp_.setScale("qd", constant(n, 2.0));
  ocp_.setScale("qdd", constant(n, 10.0));
}

// Initial guess: a loop of shoulder pitch and elbow (a quarter period apart) around the home posture,
// clipped into the bounds. Its direction is arbitrary; the solver picks the one that maximises h_y.
void ArmFlywheelProblem::buildGuess() {
  const int n = kArmDof, N = cfg_.intervals;
  const Eigen::VectorXd qh = chain_.homePosture();
  for (int k = 0; k <= N; ++k) {
    const double ph = 2.0 * M_PI * k / N, w = 2.0 * M_PI / cfg_.period;
    Eigen::VectorXd q = qh, qd = constant(n, 0.0), qdd = constant(n, 0.0);
    q[0] += 0.3 * std::sin(ph), qd[0] = 0.3 * w * std::cos(ph), qdd[0] = -0.3 * w * w * std::sin(ph);
    q[3] += 0.2 * std::cos(ph) + 0.1, qd[3] = -0.2 * w * std::sin(ph), qdd[3] = -0.2 * w * w * std::cos(ph);
    q = q.cwiseMax(q_lo_).cwiseMin(q_hi_);
    ocp_.setGuess("q", k, q);
    ocp_.setGuess("qd", k, qd);
    if (k < N) ocp_.setGuess("qdd", k, qdd);
  }
}

// Continuity (DMS), periodicity x_N = x_0, torques, the workspace box and the arm's CoM.
void ArmFlywheelProblem::buildConstraints() {
  const int n = kArmDof, N = cfg_.intervals;
  const double h = cfg_.period / N;
  // The torque element normalises by the chain's tau_max: give it the effective bound.
  model::SerialChain tchain = chain_;
  for (int i = 0; i < n; ++i) tchain.links[i].tau_max = tau_max_[i];
  auto cont = std::make_shared<ArmContinuityElement>(h);
  for (int k = 0; k < N; ++k) {
    const auto& c = ocp_.addConstraint("continuity", k, constant(2 * n, 0.0), constant(2 * n, 0.0));
    for (int j = 0; j < n; ++j) {
      ocp_.addTerm(c, cont,
                   {ocp_.index("q", k, j), ocp_.index("qd", k, j), ocp_.index("qdd", k, j), ocp_.index("q", k + 1, j),
                    ocp_.index("qd", k + 1, j)},
                   {j, n + j});
    }
  }
  // Periodicity x_N = x_0.
  auto per = std::make_shared<DifferenceElement<2 * kArmDof>>();
  const auto& pc = ocp_.addConstraint("periodicity", N, constant(2 * n, 0.0), constant(2 * n, 0.0));
  ocp_.addTerm(pc, per, cat({ocp_.indices("q", 0), ocp_.indices("qd", 0), ocp_.indices("q", N), ocp_.indices("qd", N)}));
  // Torques (normalised by the effective bound) at every interval start; workspace box at every node.
  auto torque = std::make_shared<ArmTorqueElement>(tchain);
  auto ee = std::make_shared<ArmEndEffectorElement>(chain_);
  const Eigen::Vector3d box_lo(cfg_.ws_x[0], cfg_.ws_y[0], cfg_.ws_z[0]);
  const Eigen::Vector3d box_hi(cfg_.ws_x[1], cfg_.ws_y[1], cfg_.ws_z[1]);
  for (int k = 0; k < N; ++k) {
    const auto& tc = ocp_.addConstraint("torque", k, constant(n, -1.0), constant(n, 1.0));
    ocp_.addTerm(tc, torque, cat({ocp_.indices("q", k), ocp_.indices("qd", k), ocp_.indices("qdd", k)}));
  }
  for (int k = 0; k <= N; ++k) {
    const auto& wc = ocp_.addConstraint("workspace", k, box_lo, box_hi);
    ocp_.addTerm(wc, ee, ocp_.indices("q", k));
  }
  // Arm CoM x near its home value (the body's balance point moves less with the phase).
  if (cfg_.com_x_offset < 2.0) {
    auto com = std::make_shared<ArmComElement>(chain_);
    const double cx = model::chainCom(chain_, chain_.homePosture().data()).x();
    const Eigen::Vector3d lo(cx - cfg_.com_x_offset, -kBig, -kBig), hi(cx + cfg_.com_x_offset, kBig, kBig);
    for (int k = 0; k < N; ++k) {
      const auto& cc = ocp_.addConstraint("arm_com", k, lo, hi);
      ocp_.addTerm(cc, com, ocp_.indices("q", k));
    }
  }
}

// Cost (nodes 0..N-1): the momentum term, joint velocities and accelerations.
void ArmFlywheelProblem::buildCosts() {
  const int N = cfg_.intervals;
  auto mom = std::make_shared<ArmMomentumCostElement>(chain_, Eigen::Vector3d::UnitY(), cfg_.momentum_mode == "tracking",
                                                      cfg_.h_d);
  auto vel = std::make_shared<SquaredNorm<kArmDof>>("joint_velocity");
  auto acc = std::make_shared<SquaredNorm<kArmDof>>("joint_acceleration");
  for (int k = 0; k < N; ++k) {
    if (cfg_.gamma_h > 0) ocp_.addCost("momentum", mom, cat({ocp_.indices("q", k), ocp_.indices("qd", k)}), cfg_.gamma_h);
    if (cfg_.gamma_qd > 0) ocp_.addCost("joint_velocity", vel, ocp_.indices("qd", k), cfg_.gamma_qd);
    if (cfg_.gamma_qdd > 0) ocp_.addCost("joint_acceleration", acc, ocp_.indices("qdd", k), cfg_.gamma_qdd);
  }
}

SolveResult ArmFlywheelProblem::solve(bool progress) const {
  SolverSettings s = cfg_.solver;
  s.progress = progress;
  return solveOcp(ocp_, s);
}

data::ArmTrajectory ArmFlywheelProblem::toTrajectory(const SolveResult& result) const {
  const int n = kArmDof, N = cfg_.intervals;
  const double h = cfg_.period / N;
  data::ArmTrajectory tr;
  for (const auto& L : chain_.links) tr.joint_names.push_back(L.joint);
  tr.period = cfg_.period;
  tr.solve = result.info;
  tr.config_yaml = toYamlString(cfg_.effective);
  tr.q_min = q_lo_, tr.q_max = q_hi_, tr.qd_max = qd_max_, tr.tau_max = tau_max_;
  tr.q_min_model = q_lo_model_, tr.q_max_model = q_hi_model_, tr.qd_max_model = qd_max_model_;
  tr.tau_max_model = tau_max_model_;
  tr.ee_box_min = Eigen::Vector3d(cfg_.ws_x[0], cfg_.ws_y[0], cfg_.ws_z[0]);
  tr.ee_box_max = Eigen::Vector3d(cfg_.ws_x[1], cfg_.ws_y[1], cfg_.ws_z[1]);
  tr.momentum_point = chain_.momentum_point;
  tr.reference_frame = chain_.reference_body;
  tr.ee_frame = chain_.ee_name;

  const Eigen::VectorXd& z = result.z;
  auto get = [&](const std::string& var, int k) {
    Eigen::VectorXd v(n);
    for (int j = 0; j < n; ++j) v[j] = z[ocp_.index(var, k, j)];
    return v;
  };
  tr.knot_t.resize(N + 1);
  tr.knot_x.resize(N + 1, 2 * n);
  tr.knot_u.resize(N, n);
  for (int k = 0; k <= N; ++k) {
    tr.knot_t[k] = k * h;
    tr.knot_x.row(k).head(n) = get("q", k).transpose();
    tr.knot_x.row(k).tail(n) = get("qd", k).transpose();
    if (k < N) tr.knot_u.row(k) = get("qdd", k).transpose();
  }
  // Samples: exact integration of the piecewise-constant qdd from each knot (the continuity the OCP enforces).
  const int M = std::max(1, static_cast<int>(std::lround(cfg_.period / cfg_.sample_dt)));
  const double dts = cfg_.period / M;
  tr.t.resize(M + 1);
  tr.q.resize(M + 1, n), tr.qd.resize(M + 1, n), tr.qdd.resize(M + 1, n), tr.tau.resize(M + 1, n);
  tr.h_ang.resize(M + 1, 3), tr.ee_pos.resize(M + 1, 3);
  for (int j = 0; j <= M; ++j) {
    const double t = j * dts;
    int k = std::min(N - 1, static_cast<int>(std::floor(t / h + 1e-9)));
    const double s = t - k * h;
    Eigen::VectorXd q = tr.knot_x.row(k).head(n).transpose(), qd = tr.knot_x.row(k).tail(n).transpose();
    const Eigen::VectorXd a = tr.knot_u.row(k).transpose();
    q += qd * s + 0.5 * s * s * a;
    qd += a * s;
    Eigen::VectorXd tau(n);
    model::chainInverseDynamics(chain_, q.data(), qd.data(), a.data(), tau.data());
    tr.t[j] = t;
    tr.q.row(j) = q.transpose();
    tr.qd.row(j) = qd.transpose();
    tr.qdd.row(j) = a.transpose();
    tr.tau.row(j) = tau.transpose();
    tr.h_ang.block<1, 3>(j, 0) = model::chainAngularMomentum(chain_, q.data(), qd.data()).transpose();
    tr.ee_pos.block<1, 3>(j, 0) = model::chainEndEffector(chain_, q.data()).transpose();
  }
  return tr;
}

data::ArmTrajectory planArmFlywheel(const ArmFlywheelConfig& config, bool progress) {
  const ArmFlywheelProblem problem(config);
  return problem.toTrajectory(problem.solve(progress));
}

}  // namespace centaur::planner
