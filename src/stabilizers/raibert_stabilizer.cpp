#include "stabilizers/raibert_stabilizer.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "controller/whole_body_controller.hpp"
#include "stabilizers/stabilizer_stacks.hpp"

namespace centaur {

const char* RaibertParams::defaultsYaml() {
  return R"(raibert:                      # Raibert-like postural task (docs/stabilizers.md)
  joints: [j_arm1_1, j_arm2_1, j_arm1_4, j_arm2_4]  # S_ub: shoulder pitch, elbow pitch
  gains: [1.0, 1.0, 3.0, 3.0]    # [rad/rad] Gamma / dt per joint, [0, 50]
  directions: [-1, -1, 1, 1]     # sign giving +y angular momentum per joint
  max_offset: 1.5                # [rad] |q_d - q_home|, [0, 3.2]
  leak_rate: 0.2                 # [1/s] pull of q_d back to home, [0, 100]
  velocity_feedforward: false    # also feed d q_d/dt to the posture task (docs/jumps.md: worse landings)
)";
}

void RaibertParams::read(YamlReader& r) {
  if (r.has("joints")) {
    joints.clear();
    for (const auto& j : r.raw("joints")) joints.push_back(j.as<std::string>());
  }
  if (r.has("gains")) {
    gains.clear();
    for (const auto& g : r.raw("gains")) gains.push_back(g.as<double>());
  }
  if (r.has("directions")) {
    directions.clear();
    for (const auto& d : r.raw("directions")) directions.push_back(d.as<double>());
  }
  r.get("max_offset", max_offset, 0.0, 3.2);
  r.get("leak_rate", leak_rate, 0.0, 100.0);
  r.get("velocity_feedforward", velocity_feedforward);
  if (gains.size() != joints.size()) r.fail("gains", "one gain per joint (" + std::to_string(joints.size()) + ")");
  if (directions.size() != joints.size()) r.fail("directions", "one direction per joint");
  for (double g : gains) {
    if (!(g >= 0.0 && g <= 50.0)) r.fail("gains", "every gain in [0, 50]");
  }
  for (double d : directions) {
    if (d != 1.0 && d != -1.0) r.fail("directions", "every direction is +1 or -1");
  }
}

std::string RaibertStabilizer::stackYaml(const RobotFrames& frames) const { return postureStackYaml(frames); }

void RaibertStabilizer::start(const std::vector<std::string>& names, const Eigen::VectorXd& q_home) {
  idx_.clear();
  for (const auto& j : params_.joints) {
    auto it = std::find(names.begin(), names.end(), j);
    if (it == names.end()) throw InputError("raibert stabilizer: unknown joint '" + j + "' (key raibert.joints)");
    idx_.push_back(static_cast<int>(it - names.begin()));
  }
  q_home_ = q_home;
  q_d_ = q_home;
  qd_d_.setZero(q_home.size());
}

unsigned RaibertStabilizer::references() const {
  return WholeBodyReferences::kPosture | (params_.velocity_feedforward ? WholeBodyReferences::kPostureVelocity : 0u);
}

void RaibertStabilizer::update(const RobotState& state, double dt, bool, WholeBodyReferences& out) noexcept {
  const double w = state.imu_omega.y();
  if (std::isfinite(w) && dt > 0.0) {
    for (std::size_t s = 0; s < idx_.size(); ++s) {
      const int i = idx_[s];
      double off = q_d_[i] - q_home_[i];
      off += params_.gains[s] * params_.directions[s] * w * dt - params_.leak_rate * dt * off;
      off = std::clamp(off, -params_.max_offset, params_.max_offset);
      qd_d_[i] = (q_home_[i] + off - q_d_[i]) / dt;  // what the law moved q_d by, per second
      q_d_[i] = q_home_[i] + off;
    }
  }
  out.q_posture = q_d_;
  out.qd_posture = qd_d_;
  out.set = references();
}

}  // namespace centaur
