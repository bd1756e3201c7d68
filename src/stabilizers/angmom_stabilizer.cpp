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

std::string AngmomStabilizer::stackYaml(const RobotFrames& frames) const { return angmomStackYaml(frames); }

void AngmomStabilizer::start(const std::vector<std::string>&, const Eigen::VectorXd& q_home) {
  q_home_ = q_home;
}

unsigned AngmomStabilizer::references() const {
  return WholeBodyReferences::kPosture | WholeBodyReferences::kPelvisAngularVelocity | WholeBodyReferences::kAngularMomentum;
}

void AngmomStabilizer::update(const RobotState& state, double, bool, WholeBodyReferences& out) noexcept {
  out.q_posture = q_home_;
  out.set = WholeBodyReferences::kPosture | WholeBodyReferences::kAngularMomentum;
  const Eigen::Vector3d w_omega = state.imu_quat * state.imu_omega;
  if (w_omega.allFinite()) {  // a non-finite measurement keeps the last pelvis reference
    out.w_omega_pelvis = -params_.gain * w_omega;
    out.set |= WholeBodyReferences::kPelvisAngularVelocity;
  }
  out.h_angular.setZero();
}

}  // namespace centaur
