#include "sim/sim_log.hpp"

#include <map>

#include "data/sim_log_file.hpp"
#include "sim/mujoco_robot.hpp"

namespace centaur::sim {

SimLog::SimLog(std::vector<std::string> joint_names, std::vector<std::string> contact_bodies, std::size_t capacity)
    : joint_names_(std::move(joint_names)),
      contact_bodies_(std::move(contact_bodies)),
      n_(joint_names_.size()),
      nc_(contact_bodies_.size()),
      force_buffer_(3, static_cast<Eigen::Index>(contact_bodies_.size())) {
  t_.reserve(capacity);
  for (auto* v : {&q_, &qd_, &tau_cmd_, &tau_meas_, &tau_applied_, &q_ref_, &qd_ref_, &tau_ff_, &kp_, &kd_}) {
    v->reserve(capacity * n_);
  }
  imu_quat_.reserve(4 * capacity);
  imu_omega_.reserve(3 * capacity);
  imu_acc_.reserve(3 * capacity);
  base_pos_.reserve(3 * capacity);
  base_quat_.reserve(4 * capacity);
  base_vel_.reserve(6 * capacity);
  wheel_force_.reserve(3 * nc_ * capacity);
}

namespace {
void push(std::vector<double>& v, const Eigen::Ref<const Eigen::VectorXd>& x) {
  for (Eigen::Index i = 0; i < x.size(); ++i) v.push_back(x[i]);
}
}  // namespace

void SimLog::appendTruth(const MujocoRobot& robot) {
  push(base_pos_, robot.basePosition());
  const Eigen::Quaterniond bq = robot.baseOrientation();
  base_quat_.insert(base_quat_.end(), {bq.w(), bq.x(), bq.y(), bq.z()});
  push(base_vel_, robot.baseVelocity());
  robot.contactForces(force_buffer_);
  for (Eigen::Index k = 0; k < force_buffer_.cols(); ++k) push(wheel_force_, force_buffer_.col(k));
}

void SimLog::appendLoop(const MujocoRobot& robot, const RobotState& s, const JointCommand& c) {
  t_.push_back(s.t);
  push(q_, s.q);
  push(qd_, s.qd);
  push(tau_cmd_, robot.commandedTorque());
  push(tau_meas_, s.tau);
  push(tau_applied_, robot.appliedTorque());
  push(q_ref_, c.q_ref);
  push(qd_ref_, c.qd_ref);
  push(tau_ff_, c.tau_ff);
  push(kp_, c.kp);
  push(kd_, c.kd);
  imu_quat_.insert(imu_quat_.end(), {s.imu_quat.w(), s.imu_quat.x(), s.imu_quat.y(), s.imu_quat.z()});
  push(imu_omega_, s.imu_omega);
  push(imu_acc_, s.imu_acc);
}

void SimLog::writeHdf5(const std::string& path, const std::string& config_yaml, const std::string& scenario,
                       const std::string& summary_json) const {
  data::SimLogHeader header;
  header.joint_names = joint_names_;
  header.contact_bodies = contact_bodies_;
  header.config_yaml = config_yaml;
  header.scenario = scenario;
  header.summary_json = summary_json;
  header.samples = t_.size();
  const std::map<std::string, const std::vector<double>*> data = {
      {"t", &t_},
      {"q", &q_},
      {"qd", &qd_},
      {"tau_cmd", &tau_cmd_},
      {"tau_meas", &tau_meas_},
      {"tau_applied", &tau_applied_},
      {"q_ref", &q_ref_},
      {"qd_ref", &qd_ref_},
      {"tau_ff", &tau_ff_},
      {"kp", &kp_},
      {"kd", &kd_},
      {"imu_quat", &imu_quat_},
      {"imu_omega", &imu_omega_},
      {"imu_acc", &imu_acc_},
      {"base_pos", &base_pos_},
      {"base_quat", &base_quat_},
      {"base_vel", &base_vel_},
      {"wheel_force", &wheel_force_},
  };
  data::writeSimLog(path, header, data);
}

}  // namespace centaur::sim
