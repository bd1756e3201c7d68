#pragma once
// Stabilizer 1, the Raibert-like postural task (paper eq. posture_raibert):
//   S_ub q_d,k+1 = S_ub q_d,k + Gamma omega_imu
// on the joints selected by S_ub (default: shoulder pitch j_arm*_1 and elbow pitch j_arm*_4 of both arms), with
// the stack of eq. (box_stack_Raibert) (feet / posture << limits). Gamma uses the pitch rate only (the column of
// omega_imu^[P] = imu_omega.y(), IMU frame = pelvis frame): per selected joint j,
//   q_d,j += gain_j * direction_j * omega_y * dt,
// so q_d,j - q_home,j = gain_j * direction_j * (pitch change) [rad per rad]. direction_j is the sign of the joint
// velocity that produces centroidal angular momentum about +y at the home posture (measured on our model:
// +1 for the elbows, -1 for the shoulders; tests/stabilizers/test_raibert_direction.cpp checks it), so the arms
// swing "in the direction of falling" (Raibert's flywheel). Each offset is clamped to +-max_offset and to the
// joint range. The law runs all the time (before, during and after the primitive); a slow leak (leak_rate)
// pulls q_d back to home so that a constant estimation bias cannot wind it up.
#include <string>
#include <vector>

#include "stabilizers/stabilizer.hpp"

namespace centaur {

class YamlReader;

struct RaibertParams {
  std::vector<std::string> joints = {"j_arm1_1", "j_arm2_1", "j_arm1_4", "j_arm2_4"};
  std::vector<double> gains = {1.0, 1.0, 3.0, 3.0};        ///< [rad/rad] per joint, [0, 50]
  std::vector<double> directions = {-1.0, -1.0, 1.0, 1.0};  ///< +-1 per joint
  double max_offset = 1.5;                                  ///< [rad] |q_d - q_home| per joint, [0, 3.2]
  double leak_rate = 0.2;                                   ///< [1/s] pull of q_d towards home, [0, 100]
  bool velocity_feedforward = false;                        ///< feed d q_d/dt to the posture task too
  static const char* defaultsYaml();                        ///< the `raibert:` section
  void read(YamlReader& r);
};

class RaibertStabilizer final : public Stabilizer {
 public:
  explicit RaibertStabilizer(RaibertParams params) : params_(std::move(params)) {}
  const char* name() const override { return "raibert"; }
  std::string stackYaml(const RobotFrames& frames) const override;
  /// Throws InputError for an unknown joint name.
  void start(const std::vector<std::string>& joint_names, const Eigen::VectorXd& q_home) override;
  unsigned references() const override;
  void update(const RobotState& state, double dt, bool active, WholeBodyReferences& out) noexcept override;
  const Eigen::VectorXd& postureReference() const { return q_d_; }
  /// d q_d / dt of the last update [rad/s] (fed to the posture task if velocity_feedforward).
  const Eigen::VectorXd& postureVelocity() const { return qd_d_; }

 private:
  RaibertParams params_;
  std::vector<int> idx_;
  Eigen::VectorXd q_home_, q_d_, qd_d_;  // qd_d_: d q_d / dt, the posture's velocity feed-forward
};

}  // namespace centaur
