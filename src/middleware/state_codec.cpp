#include "middleware/state_codec.hpp"

#include <cmath>
#include <cstring>

namespace centaur::middleware {

namespace {

template <class Seq, class T>
void bind(Seq& seq, std::vector<T>& storage) {
  seq._buffer = storage.data();
  seq._length = seq._maximum = static_cast<std::uint32_t>(storage.size());
  seq._release = false;
}

void bindNames(dds_sequence_string& seq, std::vector<std::string>& names, std::vector<char*>& ptrs) {
  ptrs.clear();
  for (std::string& n : names) ptrs.push_back(n.data());
  bind(seq, ptrs);
}

void copyTo(std::vector<double>& dst, const Eigen::VectorXd& src) {
  for (std::size_t i = 0; i < dst.size(); ++i) dst[i] = src[static_cast<Eigen::Index>(i)];
}

}  // namespace

// ---- StateEncoder --------------------------------------------------------------------------------------

StateEncoder::StateEncoder(const std::vector<std::string>& joint_names, const std::string& imu_frame)
    : names_(joint_names), imu_frame_(imu_frame), q_(joint_names.size()), qd_(joint_names.size()),
      tau_(joint_names.size()) {
  joints_.header.frame_id = empty_;
  bindNames(joints_.name, names_, name_ptrs_);
  bind(joints_.position, q_);
  bind(joints_.velocity, qd_);
  bind(joints_.effort, tau_);
  imu_.header.frame_id = imu_frame_.data();
  setImuVariances(0.0, 0.0, 0.0);
}

void StateEncoder::setImuVariances(double orientation, double gyro, double acc) {
  for (int i = 0; i < 9; ++i) {
    const bool diag = i % 4 == 0;
    imu_.orientation_covariance[i] = diag ? orientation : 0.0;
    imu_.angular_velocity_covariance[i] = diag ? gyro : 0.0;
    imu_.linear_acceleration_covariance[i] = diag ? acc : 0.0;
  }
}

void StateEncoder::encode(const RobotState& s) {
  const TimeMsg stamp = timeFromNanoseconds(nanosecondsFromSeconds(s.t));
  joints_.header.stamp = stamp;
  copyTo(q_, s.q);
  copyTo(qd_, s.qd);
  copyTo(tau_, s.tau);
  imu_.header.stamp = stamp;
  imu_.orientation.x = s.imu_quat.x();
  imu_.orientation.y = s.imu_quat.y();
  imu_.orientation.z = s.imu_quat.z();
  imu_.orientation.w = s.imu_quat.w();
  imu_.angular_velocity = {s.imu_omega.x(), s.imu_omega.y(), s.imu_omega.z()};
  imu_.linear_acceleration = {s.imu_acc.x(), s.imu_acc.y(), s.imu_acc.z()};
}

// ---- StateDecoder --------------------------------------------------------------------------------------

StateDecoder::StateDecoder(const std::vector<std::string>& joint_names) : names_(joint_names) {
  joints_.resize(static_cast<Eigen::Index>(names_.size()));
  imu_.resize(0);
  index_.assign(names_.size(), -1);
}

bool StateDecoder::mapNames(const JointStateMsg& msg) {
  // The same order as the last message: nothing to do (a string compare per joint, no allocation).
  bool same = last_order_.size() == msg.name._length;
  for (std::uint32_t i = 0; same && i < msg.name._length; ++i) {
    same = msg.name._buffer[i] != nullptr && last_order_[i] == msg.name._buffer[i];
  }
  if (same) return true;
  // A new order (the first message, or a robot restarted with another order): map by name, once.
  std::vector<int> index(names_.size(), -1);
  for (std::uint32_t i = 0; i < msg.name._length; ++i) {
    const char* n = msg.name._buffer[i];
    if (n == nullptr) return false;
    for (std::size_t j = 0; j < names_.size(); ++j) {
      if (names_[j] != n) continue;
      if (index[j] >= 0) return false;  // a joint named twice
      index[j] = static_cast<int>(i);
    }
  }
  for (int k : index) {
    if (k < 0) return false;  // one of our joints is missing
  }
  index_ = std::move(index);
  last_order_.assign(msg.name._buffer, msg.name._buffer + msg.name._length);
  return true;
}

bool StateDecoder::acceptJoints(const JointStateMsg& msg) {
  const std::uint32_t n = msg.name._length;
  if (n != names_.size() || msg.position._length != n || msg.velocity._length != n || msg.effort._length != n) {
    return false;
  }
  const std::int64_t ns = nanosecondsFromTime(msg.header.stamp);
  if (ns < 0 || !mapNames(msg)) return false;
  for (std::size_t j = 0; j < names_.size(); ++j) {
    const auto i = static_cast<std::uint32_t>(index_[j]);
    const auto k = static_cast<Eigen::Index>(j);
    joints_.q[k] = msg.position._buffer[i];
    joints_.qd[k] = msg.velocity._buffer[i];
    joints_.tau[k] = msg.effort._buffer[i];
  }
  joints_ns_ = ns;
  return true;
}

bool StateDecoder::acceptImu(const ImuMsg& msg) {
  const std::int64_t ns = nanosecondsFromTime(msg.header.stamp);
  const auto& o = msg.orientation;
  const double norm = std::sqrt(o.x * o.x + o.y * o.y + o.z * o.z + o.w * o.w);
  if (ns < 0 || !(std::abs(norm - 1.0) <= 1e-6)) return false;
  imu_.imu_quat = Eigen::Quaterniond(o.w, o.x, o.y, o.z);  // the bits as sent: no renormalisation
  imu_.imu_omega = Eigen::Vector3d(msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z);
  imu_.imu_acc = Eigen::Vector3d(msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z);
  imu_ns_ = ns;
  return true;
}

bool StateDecoder::complete() const { return joints_ns_ >= 0 && joints_ns_ == imu_ns_ && joints_ns_ > taken_ns_; }

std::int64_t StateDecoder::take(RobotState& state) {
  state.t = secondsFromNanoseconds(joints_ns_);
  state.q = joints_.q;
  state.qd = joints_.qd;
  state.tau = joints_.tau;
  state.imu_quat = imu_.imu_quat;
  state.imu_omega = imu_.imu_omega;
  state.imu_acc = imu_.imu_acc;
  taken_ns_ = joints_ns_;
  return taken_ns_;
}

// ---- CommandEncoder ------------------------------------------------------------------------------------

CommandEncoder::CommandEncoder(const std::vector<std::string>& joint_names, std::uint64_t session)
    : names_(joint_names), q_ref_(names_.size()), qd_ref_(names_.size()), tau_ff_(names_.size()),
      kp_(names_.size()), kd_(names_.size()), session_(session) {
  msg_.header.frame_id = empty_;
  msg_.session = session_;
  bindNames(msg_.name, names_, name_ptrs_);
  bind(msg_.q_ref, q_ref_);
  bind(msg_.qd_ref, qd_ref_);
  bind(msg_.tau_ff, tau_ff_);
  bind(msg_.kp, kp_);
  bind(msg_.kd, kd_);
}

void CommandEncoder::encode(const JointCommand& c, std::int64_t state_ns) {
  msg_.header.stamp = timeFromNanoseconds(state_ns);
  msg_.state_stamp = msg_.header.stamp;
  msg_.seq = ++seq_;
  copyTo(q_ref_, c.q_ref);
  copyTo(qd_ref_, c.qd_ref);
  copyTo(tau_ff_, c.tau_ff);
  copyTo(kp_, c.kp);
  copyTo(kd_, c.kd);
}

}  // namespace centaur::middleware
