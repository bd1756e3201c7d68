#include "planner/arm_flywheel_config.hpp"

#include "common/yaml_reader.hpp"

namespace centaur::planner {

namespace {

const char* kArmFlywheelDefaults = R"(primitive: arm-flywheel
model:
  mjcf: ""
horizon:
  intervals: 40
  period: 1.0
limits:
  position_margin: 0.05
  velocity_scale: 0.9
  torque_scale: 0.8
workspace:
  x: [0.40, 1.00]
  y: [0.10, 0.70]
  z: [0.15, 1.10]
  com_x_offset: 2.0
cost:
  momentum_mode: tracking
  momentum: 1.0
  momentum_target: 5.0
  joint_velocity: 0.02
  joint_acceleration: 1.0e-4
phase_anchor: false
sample_dt: 0.001
solver:
  backend: ipopt
  tol: 1.0e-8
  constr_viol_tol: 1.0e-6
  max_iter: 1000
  max_cpu_time: 60.0
  hessian: exact
  mu_strategy: adaptive
  user_scaling: true
  print_level: 0
  threads: auto
)";


}  // namespace

std::string defaultArmFlywheelYaml() { return kArmFlywheelDefaults; }

ArmFlywheelConfig parseArmFlywheelConfig(const YAML::Node& root, const std::string& label) {
  ArmFlywheelConfig c;
  c.source = label;
  c.effective = YAML::Clone(root);
  YamlReader r(root, label);
  r.get("primitive", c.primitive, {"arm-flywheel"});
  auto m = r.child("model");
  m.get("mjcf", c.mjcf);
  m.finish();
  auto h = r.child("horizon");
  h.get("intervals", c.intervals, 8, 400);
  h.get("period", c.period, 0.1, 10.0);
  h.finish();
  auto l = r.child("limits");
  l.get("position_margin", c.position_margin, 0.0, 0.5);
  l.get("velocity_scale", c.velocity_scale, 0.05, 1.0);
  l.get("torque_scale", c.torque_scale, 0.05, 1.0);
  l.finish();
  auto w = r.child("workspace");
  w.getInterval("x", c.ws_x, -2.0, 2.0);
  w.getInterval("y", c.ws_y, -2.0, 2.0);
  w.getInterval("z", c.ws_z, -2.0, 2.0);
  w.get("com_x_offset", c.com_x_offset, 0.0, 2.0);
  w.finish();
  auto k = r.child("cost");
  k.get("momentum_mode", c.momentum_mode, {"linear", "tracking"});
  k.get("momentum", c.gamma_h, 0.0, 1e6);
  k.get("momentum_target", c.h_d, -1e3, 1e3);
  k.get("joint_velocity", c.gamma_qd, 0.0, 1e6);
  k.get("joint_acceleration", c.gamma_qdd, 0.0, 1e6);
  k.finish();
  r.get("phase_anchor", c.phase_anchor);
  r.get("sample_dt", c.sample_dt, 1e-4, 0.1);
  auto s = r.child("solver");
  readSolverSettings(s, c.solver);
  r.finish();
  if (c.momentum_mode == "linear" && c.gamma_qd <= 0.0) {
    throw InputError(label, "cost.joint_velocity",
                     "must be > 0 in linear momentum mode (it bounds the otherwise unbounded -gamma_h h_y)");
  }
  return c;
}

ArmFlywheelConfig loadArmFlywheelConfig(const std::string& file, const std::vector<std::string>& overrides) {
  std::string label;
  const YAML::Node root = loadLayered(loadYamlString(kArmFlywheelDefaults, "<defaults>"), file, overrides, label);
  return parseArmFlywheelConfig(root, label);
}

}  // namespace centaur::planner
