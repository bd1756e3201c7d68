#include "controller/force_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"

namespace centaur {

Eigen::Vector3d wheelContactPoint(const Eigen::Isometry3d& w_T_centre, double radius, const Eigen::Vector3d& n) {
  const Eigen::Vector3d a = w_T_centre.linear().col(2);
  Eigen::Vector3d d = n - n.dot(a) * a;  // normal, perpendicular to the axis
  const double len = d.norm();
  d = len > 1e-6 ? Eigen::Vector3d(d / len) : n;
  return w_T_centre.translation() - radius * d;
}

const char* toString(ForceDistributionStatus status) {
  switch (status) {
    case ForceDistributionStatus::kOk: return "ok";
    case ForceDistributionStatus::kRelaxed: return "relaxed";
    case ForceDistributionStatus::kFailed: return "failed";
  }
  return "unknown";
}

const char* ForceDistributionParams::defaultsYaml() {
  return R"(force_distribution:
  friction: 0.6            # [-] mu, half-width of the linearized friction pyramid, [0.01, 5]
  wheel_radius: 0.078      # [m] contact point = wheel centre - radius along the surface normal, [0.01, 0.5]
  min_normal_force: 0.0    # [N] lower bound of every stance wheel's normal force, [0, 1e4]
  max_normal_force: 1.0e4  # [N] upper bound, [min_normal_force, 1e5]
  tracking_weight: 1.0     # [1/N^2] weight of ||F - F_d||^2, [0, 1e6]
  regularization: 1.0e-8   # [1/N^2] weight of ||F||^2, [1e-12, 1]; tracking_weight + regularization >= 1e-7 x dynamics_weight
  dynamics_weight: 1.0e4   # [1/N^2] weight of the floating-base rows when they must be relaxed, [1, 1e9]
)";
}

void ForceDistributionParams::read(YamlReader& r) {
  r.get("friction", friction, 0.01, 5.0);
  r.get("wheel_radius", wheel_radius, 0.01, 0.5);
  r.get("min_normal_force", min_normal_force, 0.0, 1e4);
  r.get("max_normal_force", max_normal_force, min_normal_force, 1e5);
  r.get("tracking_weight", tracking_weight, 0.0, 1e6);
  r.get("regularization", regularization, 1e-12, 1.0);
  r.get("dynamics_weight", dynamics_weight, 1.0, 1e9);
  if (!conditioned()) r.fail("regularization", conditioningRule());
}

bool ForceDistributionParams::conditioned() const {
  return tracking_weight + regularization >= kMinRegularisationRatio * dynamics_weight;
}

std::string ForceDistributionParams::conditioningRule() const {
  // The relaxed QP's Hessian is (tracking_weight + regularization) I + dynamics_weight J_u J_u': its relative
  // regularisation must stay in the QP solver's direct, accurate range (docs/qp.md).
  std::ostringstream msg;
  msg << "value " << regularization << " too small: tracking_weight + regularization must be >= "
      << kMinRegularisationRatio << " x dynamics_weight (here: regularization in ["
      << std::max(1e-12, kMinRegularisationRatio * dynamics_weight - tracking_weight)
      << ", 1]), or the relaxed QP is too ill-conditioned for the solver (docs/controller.md)";
  return msg.str();
}

namespace {
void check(bool ok, const std::string& what) {
  if (!ok) throw InputError("force distribution: " + what);
}
bool finite(const Eigen::Ref<const Eigen::MatrixXd>& m) { return m.allFinite(); }
}  // namespace

void ForceDistribution::init(const RobotModel& model, const ForceDistributionParams& params) {
  const auto& p = params;
  check(p.friction >= 0.01 && p.friction <= 5.0, "friction must be in [0.01, 5]");
  check(p.wheel_radius > 0.0 && p.wheel_radius <= 0.5, "wheel_radius must be in (0, 0.5]");
  check(p.min_normal_force >= 0.0 && p.max_normal_force >= p.min_normal_force,
        "need 0 <= min_normal_force <= max_normal_force");
  check(p.tracking_weight >= 0.0 && p.regularization > 0.0 && p.dynamics_weight > 0.0,
        "weights: tracking >= 0, regularization > 0, dynamics > 0");
  check(p.conditioned(), "regularization: " + p.conditioningRule());
  params_ = params;
  nv_ = model.nv();
  n_ = model.numJoints();
  for (int k = 0; k < kWheels; ++k) {
    body_[k] = model.frameId(p.wheel_bodies[k]);
    centre_[k] = model.frameId(p.wheel_centres[k]);
    check(body_[k] >= 0, "frame '" + p.wheel_bodies[k] + "' not found in the model");
    check(centre_[k] >= 0, "frame '" + p.wheel_centres[k] + "' not found in the model");
    J_[k].setZero(3, nv_);
    w_contact_[k].setZero();
  }
  M_.setZero(nv_, nv_);
  b_.setZero(nv_);
  Mvb_.setZero(nv_);
  constexpr int nx = 3 * kWheels, neq = 6, nin = 5 * kWheels;
  H_.setZero(nx, nx);
  Aeq_.setZero(neq, nx);
  C_.setZero(nin, nx);
  g_.setZero(nx);
  beq_.setZero(neq);
  clo_.setZero(nin);
  cup_.setZero(nin);
  empty_.resize(0);
  hard_.resize(nx, neq, nin);
  relaxed_.resize(nx, 0, nin);
  F_.setZero();
  tau_ff_.setZero(n_);
  residual_ = 0.0;
  iterations_ = 0;
  status_ = ForceDistributionStatus::kFailed;
  initialized_ = true;
}

ForceDistributionStatus ForceDistribution::compute(const RobotModel& model,
                                                   const Eigen::Ref<const Eigen::VectorXd>& vdot_d,
                                                   const Forces& F_d, const WheelContacts& contacts) noexcept {
  iterations_ = 0;
  status_ = ForceDistributionStatus::kFailed;
  if (!initialized_ || model.nv() != nv_ || vdot_d.size() != nv_ || !vdot_d.allFinite()) return status_;

  // Dynamics terms: Mvb = M vdot_d + b.
  model.biasForces(b_);
  Mvb_ = b_;
  if (!vdot_d.isZero(0.0)) {  // the default vdot_d = 0 needs no mass matrix
    model.massMatrix(M_);
    Mvb_.noalias() += M_ * vdot_d;
  }
  if (!Mvb_.allFinite()) return status_;

  // Stance wheels: contact points, Jacobians, variable slots, constraint rows.
  const double mu = params_.friction;
  int ns = 0;
  for (int k = 0; k < kWheels; ++k) {
    slot_[k] = -1;
    if (!contacts.stance[k]) continue;
    const double len = contacts.normal[k].norm();
    if (!(len > 0.5 && len < 2.0) || !F_d.col(k).allFinite()) return status_;
    const Eigen::Vector3d n = contacts.normal[k] / len;
    w_contact_[k] = wheelContactPoint(model.framePose(centre_[k]), params_.wheel_radius, n);
    model.worldPointJacobian(body_[k], w_contact_[k], J_[k]);
    const Eigen::Vector3d a = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d t1 = (a - a.dot(n) * n).normalized();
    const Eigen::Vector3d t2 = n.cross(t1);
    const int c = 3 * ns, r = 5 * ns;
    slot_[k] = c;
    Aeq_.block<6, 3>(0, c) = J_[k].leftCols<6>().transpose();
    C_.block(r, 0, 5, 3 * kWheels).setZero();
    C_.block<1, 3>(r, c) = n.transpose();
    clo_[r] = params_.min_normal_force;
    cup_[r] = params_.max_normal_force;
    C_.block<1, 3>(r + 1, c) = (t1 - mu * n).transpose();  // t1'F <= mu n'F
    C_.block<1, 3>(r + 2, c) = (t1 + mu * n).transpose();  // t1'F >= -mu n'F
    C_.block<1, 3>(r + 3, c) = (t2 - mu * n).transpose();
    C_.block<1, 3>(r + 4, c) = (t2 + mu * n).transpose();
    for (int j = 1; j <= 4; ++j) {
      clo_[r + j] = (j % 2 == 1) ? -std::numeric_limits<double>::infinity() : 0.0;
      cup_[r + j] = (j % 2 == 1) ? 0.0 : std::numeric_limits<double>::infinity();
    }
    ++ns;
  }
  const int nx = 3 * ns, nin = 5 * ns;
  beq_ = Mvb_.head<6>();
  if (!finite(Aeq_.leftCols(nx))) return status_;

  ForceDistributionStatus result = ForceDistributionStatus::kOk;
  if (ns > 0) {
    // Hard problem: H = (w + eps) I, g = -w F_d.
    H_.topLeftCorner(nx, nx).setIdentity();
    H_.topLeftCorner(nx, nx) *= params_.tracking_weight + params_.regularization;
    for (int k = 0; k < kWheels; ++k) {
      if (slot_[k] >= 0) g_.segment<3>(slot_[k]) = -params_.tracking_weight * F_d.col(k);
    }
    QpStatus qs = hard_.solve(H_.topLeftCorner(nx, nx), g_.head(nx), Aeq_.leftCols(nx), beq_,
                              C_.topLeftCorner(nin, nx), clo_.head(nin), cup_.head(nin), empty_, empty_);
    iterations_ += hard_.iterations();
    const QpSolver* solved = &hard_;
    if (qs == QpStatus::kInfeasible) {
      // Relaxed problem: the floating-base rows as a weighted least-squares term.
      const double w = params_.dynamics_weight;
      H_.topLeftCorner(nx, nx).noalias() += w * Aeq_.leftCols(nx).transpose() * Aeq_.leftCols(nx);
      g_.head(nx).noalias() -= w * Aeq_.leftCols(nx).transpose() * beq_;
      qs = relaxed_.solve(H_.topLeftCorner(nx, nx), g_.head(nx), Aeq_.topLeftCorner(0, nx), beq_.head(0),
                          C_.topLeftCorner(nin, nx), clo_.head(nin), cup_.head(nin), empty_, empty_);
      iterations_ += relaxed_.iterations();
      solved = &relaxed_;
      result = ForceDistributionStatus::kRelaxed;
    }
    if (qs != QpStatus::kOptimal) return status_;  // kFailed, outputs keep the last good values
    F_.setZero();
    for (int k = 0; k < kWheels; ++k) {
      if (slot_[k] >= 0) F_.col(k) = solved->x().segment<3>(slot_[k]);
    }
  } else {
    F_.setZero();
  }

  // Residual of the floating-base rows and the actuated rows' torques.
  wrench_ = beq_;
  tau_ff_ = Mvb_.tail(n_);
  for (int k = 0; k < kWheels; ++k) {
    if (slot_[k] < 0) continue;
    wrench_.noalias() -= J_[k].leftCols<6>().transpose() * F_.col(k);
    tau_ff_.noalias() -= J_[k].rightCols(n_).transpose() * F_.col(k);
  }
  residual_ = wrench_.norm();
  if (ns == 0 && residual_ > 1e-6 * (1.0 + beq_.norm())) result = ForceDistributionStatus::kRelaxed;
  status_ = result;
  return status_;
}

}  // namespace centaur
