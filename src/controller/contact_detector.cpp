#include "controller/contact_detector.hpp"

#include <cmath>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "controller/force_distribution.hpp"  // wheelContactPoint

namespace centaur {

const char* ContactDetectorParams::defaultsYaml() {
  return R"(contact_detector:
  observer_gain: 500.0  # [1/s] momentum-observer gain K (time constant 1/K; K * control period < 1), [1, 1e4]
  on_threshold: 60.0    # [N] touchdown when the normal force exceeds this, (off_threshold, 1e4]
  off_threshold: 30.0   # [N] lift-off when the normal force falls below this, [0, on_threshold)
  on_debounce: 2        # [control periods] consecutive samples above on_threshold, [1, 100]
  off_debounce: 2       # [control periods] consecutive samples below off_threshold, [1, 100]
  wheel_radius: 0.078   # [m] contact point = wheel centre - radius along the surface normal, [0.01, 0.5]
)";
}

void ContactDetectorParams::read(YamlReader& r) {
  r.get("observer_gain", observer_gain, 1.0, 1e4);
  r.get("off_threshold", off_threshold, 0.0, 1e4);
  r.get("on_threshold", on_threshold, off_threshold, 1e4);
  r.get("on_debounce", on_debounce, 1, 100);
  r.get("off_debounce", off_debounce, 1, 100);
  r.get("wheel_radius", wheel_radius, 0.01, 0.5);
}

namespace {
void check(bool ok, const std::string& what) {
  if (!ok) throw InputError("contact detector: " + what);
}
}  // namespace

void ContactDetector::init(const RobotModel& model, const ContactDetectorParams& params) {
  const auto& p = params;
  check(p.observer_gain >= 1.0 && p.observer_gain <= 1e4, "observer_gain must be in [1, 1e4]");
  check(p.off_threshold >= 0.0 && p.on_threshold > p.off_threshold, "need 0 <= off_threshold < on_threshold");
  check(p.on_debounce >= 1 && p.off_debounce >= 1, "debounce counts must be >= 1");
  check(p.wheel_radius > 0.0 && p.wheel_radius <= 0.5, "wheel_radius must be in (0, 0.5]");
  params_ = params;
  nv_ = model.nv();
  n_ = model.numJoints();
  int max_leg = 0;
  for (int k = 0; k < kWheels; ++k) {
    body_[k] = model.frameId(p.wheel_bodies[k]);
    centre_[k] = model.frameId(p.wheel_centres[k]);
    check(body_[k] >= 0, "frame '" + p.wheel_bodies[k] + "' not found in the model");
    check(centre_[k] >= 0, "frame '" + p.wheel_centres[k] + "' not found in the model");
    dofs_[k].clear();
    for (const auto& name : p.leg_joints[k]) {
      const int j = model.jointIndex(name);
      check(j >= 0, "leg joint '" + name + "' not found in the model");
      dofs_[k].push_back(6 + j);
    }
    check(dofs_[k].size() >= 3, "wheel " + std::to_string(k + 1) + " needs at least 3 leg joints");
    max_leg = std::max(max_leg, static_cast<int>(dofs_[k].size()));
    normal_[k] = Eigen::Vector3d::UnitZ();
  }
  M_.setZero(nv_, nv_);
  M_prev_.setZero(nv_, nv_);
  J_.setZero(3, nv_);
  b_.setZero(nv_);
  p0_.setZero(nv_);
  I_.setZero(nv_);
  r_.setZero(nv_);
  tmp_.setZero(nv_);
  Jleg_.setZero(3, max_leg);
  rleg_.setZero(max_leg);
  initialized_ = true;
  reset();
}

void ContactDetector::reset(const std::array<bool, kWheels>& in_contact, bool quasi_static_start) {
  started_ = false;
  quasi_static_start_ = quasi_static_start;
  contact_ = in_contact;
  count_.fill(0);
  fn_.fill(0.0);
  F_.setZero();
}

void ContactDetector::setNormal(int k, const Eigen::Vector3d& n) {
  if (k >= 0 && k < kWheels && n.norm() > 1e-9) normal_[k] = n.normalized();
}

bool ContactDetector::update(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& tau,
                             double dt) noexcept {
  if (!initialized_ || model.nv() != nv_ || tau.size() != n_ || !tau.allFinite()) return false;
  if (started_ && !(dt > 0.0 && std::isfinite(dt))) return false;
  const Eigen::VectorXd& v = model.v();
  if (!v.allFinite()) return false;
  const double K = params_.observer_gain;
  model.massMatrix(M_);
  model.biasForces(b_);
  if (!started_) {
    // Quasi-static start: r_0 = b_0 - S' tau_0 (else r_0 = 0); I_0 such that K (p_0 - p_0 - I_0) = r_0.
    p0_.noalias() = M_ * v;
    if (quasi_static_start_) {
      r_ = b_;
      r_.tail(n_) -= tau;
    } else {
      r_.setZero();
    }
    I_ = -r_ / K;
    started_ = true;
  } else {
    // I += dt (S' tau - b + r) + (M_k - M_{k-1}) v_k
    tmp_ = r_ - b_;
    tmp_.tail(n_) += tau;
    I_ += dt * tmp_;
    tmp_.noalias() = M_ * v;  // p_k
    I_ += tmp_;
    I_.noalias() -= M_prev_ * v;
    r_ = K * (tmp_ - p0_ - I_);
  }
  M_prev_.swap(M_);  // M_ is overwritten by the next update (no copy, no allocation: same size)

  for (int k = 0; k < kWheels; ++k) {
    const Eigen::Vector3d w_c = wheelContactPoint(model.framePose(centre_[k]), params_.wheel_radius, normal_[k]);
    model.worldPointJacobian(body_[k], w_c, J_);
    const int m = static_cast<int>(dofs_[k].size());
    for (int j = 0; j < m; ++j) {
      Jleg_.col(j) = J_.col(dofs_[k][static_cast<std::size_t>(j)]);
      rleg_[j] = r_[dofs_[k][static_cast<std::size_t>(j)]];
    }
    const Eigen::Matrix3d A = Jleg_.leftCols(m) * Jleg_.leftCols(m).transpose();
    const Eigen::Vector3d rhs = Jleg_.leftCols(m) * rleg_.head(m);
    ldlt_.compute(A);
    F_.col(k) = ldlt_.solve(rhs);
    const double fn = normal_[k].dot(F_.col(k));
    fn_[k] = fn;
    if (contact_[k]) {
      if (fn < params_.off_threshold) {
        if (++count_[k] >= params_.off_debounce) {
          contact_[k] = false;
          count_[k] = 0;
        }
      } else {
        count_[k] = 0;
      }
    } else {
      if (fn > params_.on_threshold) {
        if (++count_[k] >= params_.on_debounce) {
          contact_[k] = true;
          count_[k] = 0;
        }
      } else {
        count_[k] = 0;
      }
    }
  }
  return true;
}

}  // namespace centaur
