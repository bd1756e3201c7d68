#include "planner/jump_config.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "common/excerpt.hpp"
#include "common/yaml_reader.hpp"
#include "model/template_params.hpp"
#include "robot/robot_registry.hpp"

namespace centaur::planner {

namespace {

// The embedded defaults. config/<primitive>.yaml ships the same text with comments.
const char* kSquatJumpDefaults = R"(primitive: squat-jump
robot: centauro
model:
  preset: centauro
horizon:
  intervals: 30
  takeoff: 10
  landing: 20
  dt_min: 0.03
  dt_max: 0.25
  dt_init: 0.08
feet: [[0.35, 0.35, -0.6408], [0.35, -0.35, -0.6408], [-0.35, 0.35, -0.6408], [-0.35, -0.35, -0.6408]]
wheel_radius: 0.078
workspace:
  front_x: [0.1, 0.6]
  rear_x: [-0.6, -0.1]
  left_y: [0.1, 0.5]
  right_y: [-0.5, -0.1]
  z: [-0.76, -0.46]
  reach: 0.0
contact:
  friction: pyramid
  mu: 0.5
  mu_wall: 1.0
  force_threshold: 0.0
  force_max: 10000.0
  touchdown: same_position
limits:
  leg_force: 1500.0
  velocity: 100.0
  acceleration: 100.0
target:
  height: 0.87
  wall_distance: 0.15
  wall_height: 0.0
cost:
  base_height: 50.0
  base_velocity: 0.0
  joint_velocity: 1.0
  force_rate: 1.0
  acceleration_rate: 1.0e-3
  base_orientation: 0.0
  base_pose: 0.0
  stance_foot_velocity: 100.0
  velocity_regularization: 0.0
  base_angular_velocity: 1000.0
  last_interval: 1.0e-3
  landing_steps: 0.0
solver:
  backend: ipopt
  tol: 1.0e-8
  constr_viol_tol: 1.0e-4
  max_iter: 3000
  max_cpu_time: 600.0
  hessian: exact
  mu_strategy: adaptive
  user_scaling: true
  print_level: 0
  threads: auto
)";

const char* kHalfSquatOverrides = R"(primitive: half-squat-jump
contact:
  mu: 1.0
cost:
  base_height: 0.0
  base_pose: 50.0
  last_interval: 0.0
)";


std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

/// Consistency of the contact-force settings that Ipopt would otherwise take minutes to find infeasible.
void checkContactForces(const JumpConfig& c, const std::string& label) {
  const double f_thr = c.contact.force_threshold;
  if (f_thr > c.contact.force_max) {
    throw InputError(label, "contact.force_threshold",
                     num(f_thr) + " N exceeds contact.force_max " + num(c.contact.force_max) +
                         " N: no contact force can satisfy both");
  }
  // Both jumps start with all four feet pinned in contact on intervals 0..N_T, each pressing with at least F_thr,
  // from rest. If 4 F_thr exceeds the weight, the centre of mass accelerates upwards by at least
  // a = 4 F_thr / m - g for the whole stance (at least (N_T + 1) dt_min long), so the waist rises by at least
  // a T^2 / 2 above feet that do not move. The waist can be at most r (the farthest corner of the workspace box)
  // above or below a foot, whatever its orientation: a rise beyond 2 r is impossible.
  const double m = c.model.totalMass(), g = c.model.gravity;
  const double a = 4.0 * f_thr / m - g;
  if (a <= 0.0) return;
  const double T = (c.horizon.takeoff + 1) * c.horizon.dt_min;
  double r = 0.0;
  for (double x : {c.workspace.front_x[0], c.workspace.front_x[1], c.workspace.rear_x[0], c.workspace.rear_x[1]}) {
    for (double y : {c.workspace.left_y[0], c.workspace.left_y[1], c.workspace.right_y[0], c.workspace.right_y[1]}) {
      for (double z : {c.workspace.z[0], c.workspace.z[1]}) r = std::max(r, std::sqrt(x * x + y * y + z * z));
    }
  }
  const double rise = 0.5 * a * T * T;
  if (rise > 2.0 * r) {
    throw InputError(label, "contact.force_threshold",
                     num(f_thr) + " N on each of the four feet lifts the " + num(m) +
                         " kg robot at >= " + num(a) + " m/s^2 for the >= " + num(T) +
                         " s of the initial stance: the waist would rise >= " + num(rise) +
                         " m above its pinned feet, beyond the legs' reach (" + num(2.0 * r) +
                         " m); lower the threshold (e.g. below the weight share " + num(m * g / 4.0) +
                         " N) or raise horizon.dt_min / horizon.takeoff");
  }
}

// horizon.*: the intervals, take-off and landing, the bounds and the first guess of the step sizes.
void readHorizon(YamlReader& r, JumpConfig& c) {
  auto h = r.child("horizon");
  h.get("intervals", c.horizon.intervals, 4, 200);
  h.get("takeoff", c.horizon.takeoff, 1, c.horizon.intervals - 3);
  h.get("landing", c.horizon.landing, c.horizon.takeoff + 2, c.horizon.intervals - 1);
  h.get("dt_min", c.horizon.dt_min, 1e-3, 1.0);
  h.get("dt_max", c.horizon.dt_max, 1e-3, 1.0);
  if (c.horizon.dt_min > c.horizon.dt_max) {
    h.fail("dt_min", "must not exceed horizon.dt_max (" + std::to_string(c.horizon.dt_max) + " s)");
  }
  c.horizon.dt_init = 0.5 * (c.horizon.dt_min + c.horizon.dt_max);
  h.get("dt_init", c.horizon.dt_init, c.horizon.dt_min, c.horizon.dt_max);
  h.finish();
}

// feet, wheel_radius and workspace.*; the initial stance must lie inside the workspace box.
void readStance(YamlReader& r, JumpConfig& c) {
  c.feet = {Eigen::Vector3d(0.35, 0.35, -0.6408), Eigen::Vector3d(0.35, -0.35, -0.6408),
              Eigen::Vector3d(-0.35, 0.35, -0.6408), Eigen::Vector3d(-0.35, -0.35, -0.6408)};
  r.getPoints("feet", c.feet.data(), 4, -2.0, 2.0, "foot points in the waist frame (FL, FR, RL, RR), in m,");
  r.get("wheel_radius", c.wheel_radius, 0.0, 1.0);

  auto w = r.child("workspace");
  w.getInterval("front_x", c.workspace.front_x, -2, 2);
  w.getInterval("rear_x", c.workspace.rear_x, -2, 2);
  w.getInterval("left_y", c.workspace.left_y, -2, 2);
  w.getInterval("right_y", c.workspace.right_y, -2, 2);
  w.getInterval("z", c.workspace.z, -2, 2);
  w.get("reach", c.workspace.reach, 0.0, 2.0);
  w.finish();
  for (int i = 0; i < 4; ++i) {
    const auto& x = (i < 2) ? c.workspace.front_x : c.workspace.rear_x;
    const auto& y = (i % 2 == 0) ? c.workspace.left_y : c.workspace.right_y;
    const Eigen::Vector3d& p = c.feet[i];
    if (p.x() < x[0] || p.x() > x[1] || p.y() < y[0] || p.y() > y[1] || p.z() < c.workspace.z[0] || p.z() > c.workspace.z[1]) {
      r.fail("feet", "initial foot " + std::to_string(i) + " lies outside the workspace box (workspace.*)");
    }
  }
}

// contact.*, limits.* and target.*.
void readContactLimitsTarget(YamlReader& r, JumpConfig& c) {
  auto ct = r.child("contact");
  ct.get("friction", c.contact.friction, {"pyramid", "cone"});
  ct.get("mu", c.contact.mu, 1e-3, 10.0);
  ct.get("mu_wall", c.contact.mu_wall, 1e-3, 10.0);
  ct.get("force_threshold", c.contact.force_threshold, 0.0, 1e4);
  ct.get("force_max", c.contact.force_max, 1.0, 1e6);
  ct.get("touchdown", c.contact.touchdown, {"same_position", "free"});
  ct.finish();

  auto l = r.child("limits");
  l.get("leg_force", c.limits.leg_force, 1.0, 1e6);
  l.get("velocity", c.limits.velocity, 0.1, 1e4);
  l.get("acceleration", c.limits.acceleration, 0.1, 1e5);
  l.finish();

  auto t = r.child("target");
  t.get("height", c.target_height, 0.0, 5.0);
  t.get("wall_distance", c.wall_distance, 0.0, 1.0);
  t.get("wall_height", c.wall_height, 0.0, 2.0);
  t.finish();
}

// cost.*: the weights of the cost's terms.
void readCost(YamlReader& r, JumpConfig& c) {
  auto k = r.child("cost");
  k.get("base_height", c.cost.base_height, 0.0, 1e6);
  k.get("base_velocity", c.cost.base_velocity, 0.0, 1e6);
  k.get("joint_velocity", c.cost.joint_velocity, 0.0, 1e6);
  k.get("force_rate", c.cost.force_rate, 0.0, 1e6);
  k.get("acceleration_rate", c.cost.acceleration_rate, 0.0, 1e6);
  k.get("base_orientation", c.cost.base_orientation, 0.0, 1e6);
  k.get("base_pose", c.cost.base_pose, 0.0, 1e6);
  k.get("stance_foot_velocity", c.cost.stance_foot_velocity, 0.0, 1e8);
  k.get("velocity_regularization", c.cost.velocity_regularization, 0.0, 1e6);
  k.get("base_angular_velocity", c.cost.base_angular_velocity, 0.0, 1e8);
  k.get("last_interval", c.cost.last_interval, 0.0, 1e6);
  k.get("landing_steps", c.cost.landing_steps, 0.0, 1e6);
  k.finish();
}

// A squat jump whose target is below the start, or unreachable by construction, is bad input.
void checkSquatTarget(const JumpConfig& c, const std::string& label) {
  const double z0 = c.initialWaistHeight();
  if (c.target_height <= z0) {
    throw InputError(label, "target.height", "target " + std::to_string(c.target_height) +
                                                 " m must be above the initial waist height " + std::to_string(z0) + " m");
  }
  // Optimistic upper bound of the reachable apex: take-off at full leg extension with the speed that the
  // leg forces can give over the whole extension stroke (work-energy), then a ballistic rise.
  const double m = c.model.totalMass(), g = c.model.gravity;
  const double stroke = c.workspace.z[1] - c.workspace.z[0];
  const double work = (4.0 * c.limits.leg_force - m * g) * stroke;
  const double v2 = work > 0 ? 2.0 * work / m : 0.0;
  const double apex_max = c.wheel_radius - c.workspace.z[0] + v2 / (2.0 * g);
  if (c.target_height > apex_max) {
    throw InputError(label, "target.height", "target " + std::to_string(c.target_height) +
                                                 " m is unreachable: with the workspace and leg-force limits the waist cannot rise above about " +
                                                 std::to_string(apex_max) + " m");
  }
}

}  // namespace

std::string defaultJumpYaml(const std::string& primitive) {
  if (primitive == "squat-jump") return kSquatJumpDefaults;
  if (primitive == "half-squat-jump") {
    return toYamlString(mergeYaml(loadYamlString(kSquatJumpDefaults, "<defaults>"),
                                  loadYamlString(kHalfSquatOverrides, "<defaults>")));
  }
  std::string list;
  for (const auto& n : jumpPrimitiveNames()) list += (list.empty() ? "" : ", ") + n;
  throw InputError("unknown primitive '" + primitive + "'; allowed: " + list);
}

double JumpConfig::initialWaistHeight() const {
  double z = 0.0;
  for (const auto& f : feet) z += f.z();
  return wheel_radius - z / 4.0;
}

Eigen::Vector3d JumpConfig::initialFootWorld(int i) const {
  return Eigen::Vector3d(0.0, 0.0, initialWaistHeight()) + feet[i];
}

double JumpConfig::wallX() const {
  const double rear_x = 0.5 * (feet[2].x() + feet[3].x());
  return rear_x - wall_distance - wheel_radius;
}

JumpConfig parseJumpConfig(const YAML::Node& root, const std::string& label, const model::TemplateParams* derived) {
  JumpConfig c;
  c.source = label;
  c.effective = YAML::Clone(root);
  YamlReader r(root, label);
  r.get("primitive", c.primitive, jumpPrimitiveNames());
  r.get("robot", c.robot);
  c.model = model::readTemplateParams(r.child("model"), derived);
  readHorizon(r, c);
  readStance(r, c);
  readContactLimitsTarget(r, c);
  readCost(r, c);
  auto s = r.child("solver");
  readSolverSettings(s, c.solver);
  r.finish();

  checkContactForces(c, label);
  if (c.primitive == "squat-jump") checkSquatTarget(c, label);
  return c;
}

std::vector<std::string> jumpPrimitiveNames() { return {"squat-jump", "half-squat-jump"}; }

YAML::Node robotPlannerLayer(const robot::RobotDescription& d, const robot::RobotFacts& f, const std::string& primitive) {
  YAML::Node layer(YAML::NodeType::Map);
  layer["model"]["preset"] = "derived";
  for (int k = 0; k < 4; ++k) {
    YAML::Node p(YAML::NodeType::Sequence);
    for (int i = 0; i < 3; ++i) p.push_back(f.b_p_foot[k][i]);
    layer["feet"].push_back(p);
  }
  layer["feet"].SetStyle(YAML::EmitterStyle::Flow);
  layer["wheel_radius"] = f.foot_radius[0];
  const std::string folder = d.yaml_path.substr(0, d.yaml_path.find_last_of('/') + 1);
  const std::string file = folder + "planner.yaml";
  if (!std::ifstream(file)) return layer;
  const YAML::Node own = loadYamlFile(file);
  std::vector<std::string> sections = jumpPrimitiveNames();
  sections.insert(sections.begin(), "all");
  for (const auto& kv : own) {
    const std::string key = kv.first.as<std::string>();
    if (std::find(sections.begin(), sections.end(), key) == sections.end()) {
      std::string list;
      for (const auto& n : sections) list += (list.empty() ? "" : ", ") + n;
      throw InputError(file, excerpt(key), "unknown section; allowed: " + list + " (each a planner configuration)");
    }
    if (!kv.second.IsMap()) throw InputError(file, excerpt(key), "expected a mapping of planner configuration keys");
  }
  if (own["all"]) layer = mergeYaml(layer, own["all"]);
  if (own[primitive]) layer = mergeYaml(layer, own[primitive]);
  return layer;
}

JumpConfig loadJumpConfig(const std::string& primitive, const std::string& file, const std::vector<std::string>& overrides) {
  std::string label;
  const YAML::Node defaults = loadYamlString(defaultJumpYaml(primitive), "<defaults>");
  // The robot is a key of the configuration itself: read it from the user's layers first, then put the robot's
  // layer (derived template, feet and radius, its planner.yaml) between the defaults and the user's layers.
  const YAML::Node user = loadLayered(defaults, file, overrides, label);
  const YAML::Node robot_key = user["robot"];
  if (!robot_key.IsScalar() || robot_key.Scalar().empty()) throw InputError(label, "robot", "expected a robot's name or path");
  robot::LoadedRobot robot;
  try {
    robot = robot::loadRobotWithFacts(robot_key.Scalar());
  } catch (const InputError& e) {
    throw InputError(label, "robot", e.what());
  }
  YAML::Node root = loadLayered(mergeYaml(defaults, robotPlannerLayer(robot.description, *robot.facts, primitive)),
                                file, overrides, label);
  const YAML::Node declared = root["primitive"];
  if (declared && (!declared.IsScalar() || declared.Scalar() != primitive)) {
    throw InputError(label, "primitive",
                     "is " + (declared.IsScalar() ? "'" + excerpt(declared.Scalar()) + "'" : std::string("not a name")) +
                         " but the command plans '" + primitive + "'");
  }
  JumpConfig c = parseJumpConfig(root, label, &robot.facts->template_params);
  c.robot = robot.description.name;
  c.robot_hash = robot.description.hash;
  return c;
}

}  // namespace centaur::planner
