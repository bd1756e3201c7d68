#include "controller/base_estimator.hpp"

#include <cmath>

#include "common/error.hpp"

namespace centaur {

void BaseEstimator::init(const std::string& mjcf_path, const BaseEstimatorParams& params) {
  init(loadRobotModel(mjcf_path), params);
}

void BaseEstimator::init(std::shared_ptr<const RobotModelDescription> model, const BaseEstimatorParams& params) {
  if (!(params.wheel_radius > 0.0 && params.wheel_radius <= 0.5))
    throw InputError("base estimator: wheel_radius must be in (0, 0.5] m");
  params_ = params;
  model_ = std::make_unique<RobotModel>(std::move(model));
  const std::string& mjcf_path = model_->path();
  for (int k = 0; k < kWheels; ++k) {
    const std::string& wheel = params.wheel_bodies[k];
    const std::string& centre = params.wheel_centres[k];
    f_wheel_[k] = model_->frameId(wheel);
    f_centre_[k] = model_->frameId(centre);
    if (f_wheel_[k] < 0 || f_centre_[k] < 0)
      throw InputError(mjcf_path + ": base estimator needs body '" + wheel + "' and site '" + centre + "'");
    anchor_[k].setZero();
    prev_stance_[k] = false;
  }
  q_.setZero(model_->nq());
  q_[3] = 1.0;
  v_.setZero(model_->nv());
  q_tmp_ = q_;
  v_tmp_ = v_;
  Jc_.setZero(3, model_->nv());
  initialized_ = false;
  reset_pending_ = false;
  in_flight_ = false;
}

void BaseEstimator::reset(const Eigen::Vector3d& w_p_base, const Eigen::Vector3d& w_v_base) {
  reset_p_ = w_p_base;
  reset_v_ = w_v_base;
  reset_pending_ = true;
}

void BaseEstimator::update(const RobotState& state, const bool stance[kWheels]) noexcept {
  // In stance: wheel poses, velocities and Jacobians; in flight also the CoM velocity (from the momentum).
  estimate(state, stance, *model_, RobotModel::Detail::kKinematics, RobotModel::Detail::kMomentum);
}

void BaseEstimator::update(const RobotState& state, const bool stance[kWheels], RobotModel& model,
                           RobotModel::Detail detail) noexcept {
  using Detail = RobotModel::Detail;
  const bool dynamics = detail == Detail::kFull || detail == Detail::kDynamics;
  estimate(state, stance, model, detail, dynamics ? Detail::kFull : Detail::kMomentum);
  // the model was updated at the prediction q_tmp_, v_tmp_: move it to the estimate
  model.shiftBase(q_.head<3>() - q_tmp_.head<3>(), v_.head<3>() - v_tmp_.head<3>());
}

void BaseEstimator::estimate(const RobotState& state, const bool stance[kWheels], RobotModel& model,
                             RobotModel::Detail stance_detail, RobotModel::Detail flight_detail) noexcept {
  const int n = model.numJoints();
  const double r = params_.wheel_radius;

  bool first = !initialized_;
  const bool unknown_start = !initialized_ && !reset_pending_;
  Eigen::Vector3d p_prev = q_.head<3>(), v_prev = v_.head<3>();
  if (reset_pending_) {
    p_prev = reset_p_;
    v_prev = reset_v_;
    first = true;
    reset_pending_ = false;
  } else if (first) {
    p_prev.setZero();
    v_prev.setZero();
  }
  const double dt = first ? 0.0 : std::max(0.0, state.t - t_prev_);

  // Orientation, angular velocity and joints from the measurement; kinematics at the previous position.
  const Eigen::Quaterniond w_q = state.imu_quat.normalized();
  q_tmp_.head<3>() = p_prev;
  q_tmp_[3] = w_q.w();
  q_tmp_[4] = w_q.x();
  q_tmp_[5] = w_q.y();
  q_tmp_[6] = w_q.z();
  q_tmp_.tail(n) = state.q;
  v_tmp_.head<3>() = v_prev;
  v_tmp_.segment<3>(3) = state.imu_omega;
  v_tmp_.tail(n) = state.qd;
  int n_stance = 0;
  for (int k = 0; k < kWheels; ++k) n_stance += stance[k] ? 1 : 0;
  model.update(q_tmp_, v_tmp_, n_stance > 0 ? stance_detail : flight_detail);

  Eigen::Vector3d p_new = p_prev, v_new = v_prev;
  if (n_stance > 0) {
    // wheel centres and contact points (lowest rim point) for the stance wheels
    Eigen::Vector3d centre[kWheels], contact[kWheels];
    for (int k = 0; k < kWheels; ++k) {
      if (!stance[k]) continue;
      const Eigen::Isometry3d T = model.framePose(f_centre_[k]);
      centre[k] = T.translation();
      contact[k] = contactPoint(T, r);
    }
    if (unknown_start) {
      // no known start: x = y = 0, stance contact points on z = 0 on average (model base is at 0)
      double z = 0.0;
      for (int k = 0; k < kWheels; ++k)
        if (stance[k]) z -= contact[k].z();
      p_prev = Eigen::Vector3d(0.0, 0.0, z / n_stance);
    }
    p_new.setZero();
    v_new.setZero();
    for (int k = 0; k < kWheels; ++k) {
      if (!stance[k]) continue;
      const Eigen::Vector3d rel = centre[k] - q_tmp_.head<3>();  // pelvis-to-wheel-centre (W)
      if (first || !prev_stance_[k] || in_flight_) {
        anchor_[k] = p_prev + rel;  // touchdown: remember where the wheel is
      } else {
        // pure rolling: the centre moves with omega_wheel x (centre - contact)
        const Eigen::Vector3d w_wheel = model.frameVelocity(f_wheel_[k]).tail<3>();
        anchor_[k] += dt * w_wheel.cross(centre[k] - contact[k]);
      }
      p_new += anchor_[k] - rel;
      // contact point at rest: base velocity that cancels the rest of its velocity
      model.worldPointJacobian(f_wheel_[k], contact[k], Jc_);
      const Eigen::Vector3d u = Jc_ * v_tmp_;
      v_new += v_prev - u;
    }
    p_new /= n_stance;
    v_new /= n_stance;
    in_flight_ = false;
  } else {
    const Eigen::Vector3d com_rel = model.com() - q_tmp_.head<3>();
    const Eigen::Vector3d vcom_rel = model.comVelocity() - v_prev;
    if (!in_flight_) {
      in_flight_ = true;
      t_takeoff_ = first ? state.t : t_prev_;
      com0_ = p_prev + com_rel;
      vcom0_ = v_prev + vcom_rel;
    }
    const double tau = state.t - t_takeoff_;
    const Eigen::Vector3d g = model.gravity();
    const Eigen::Vector3d p_com = com0_ + vcom0_ * tau + 0.5 * g * tau * tau;
    const Eigen::Vector3d v_com = vcom0_ + g * tau;
    p_new = p_com - com_rel;
    v_new = v_com - vcom_rel;
  }

  q_ = q_tmp_;
  q_.head<3>() = p_new;
  v_ = v_tmp_;
  v_.head<3>() = v_new;
  for (int k = 0; k < kWheels; ++k) prev_stance_[k] = stance[k];
  t_prev_ = state.t;
  initialized_ = true;
}

}  // namespace centaur
