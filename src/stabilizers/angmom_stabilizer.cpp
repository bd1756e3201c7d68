#include "stabilizers/angmom_stabilizer.hpp"

#include "common/yaml_reader.hpp"
#include "controller/whole_body_controller.hpp"
#include "stabilizers/stabilizer_stacks.hpp"

namespace centaur {

const char* AngmomParams::defaultsYaml() {
  return R"(angmom:                       # angular momentum task (docs/stabilizers.md)
  gain: 0.3                      # [-] omega_fb,d = -gain * omega_imu, [0, 10]
)";
}

void AngmomParams::read(YamlReader& r) { r.get("gain", gain, 0.0, 10.0); }

std::string AngmomStabilizer::stackYaml() const { return angmomStackYaml(); }

void AngmomStabilizer::start(const std::vector<std::string>&, const Eigen::VectorXd& q_home) {
  q_home_ = q_home;
  sent_ = false;
}

void AngmomStabilizer::update(const RobotState& state, double, bool, WholeBodyController& wbc) noexcept {
  if (!sent_) wbc.setPostureReference(q_home_);
  sent_ = true;
  const Eigen::Vector3d w_omega = state.imu_quat * state.imu_omega;
  if (w_omega.allFinite()) wbc.setPelvisAngularVelocity(-params_.gain * w_omega);
  wbc.setAngularMomentum(Eigen::Vector3d::Zero());
}

}  // namespace centaur
