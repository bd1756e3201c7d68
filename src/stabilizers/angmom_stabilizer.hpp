#pragma once
// Stabilizer 2, the angular momentum task (paper eq. box_stack_angular_momentum):
//   (feet) / World->Pelvis: omega_fb,d = -omega_imu / (AngMom: h_ang,d = 0  +  Posture) << limits
// The pelvis task's reference is the measured IMU rate, negated and expressed in W (w_R_imu imu_omega); the
// momentum task acts on the shoulder and elbow joints (stackYaml()). So the IK asks the arms for the angular
// momentum that cancels the base's measured rotation: they spin in the direction of falling.
// `gain` scales the pelvis reference (1 = the paper's law).
#include "stabilizers/stabilizer.hpp"

namespace centaur {

class YamlReader;

struct AngmomParams {
  double gain = 0.3;  ///< [-] omega_fb,d = -gain * omega_imu, [0, 10] (docs/validation.md: 1 makes the arms flail)
  static const char* defaultsYaml();  ///< the `angmom:` section
  void read(YamlReader& r);
};

class AngmomStabilizer final : public Stabilizer {
 public:
  explicit AngmomStabilizer(AngmomParams params) : params_(params) {}
  const char* name() const override { return "angmom"; }
  std::string stackYaml(const RobotFrames& frames) const override;
  void start(const std::vector<std::string>& joint_names, const Eigen::VectorXd& q_home) override;
  unsigned references() const override;
  void update(const RobotState& state, double dt, bool active, WholeBodyReferences& out) noexcept override;

 private:
  AngmomParams params_;
  Eigen::VectorXd q_home_;
};

}  // namespace centaur
