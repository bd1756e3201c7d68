#include "sim/sim_config.hpp"

#include "sim/robot_setup.hpp"

namespace centaur::sim {

const char* const kSimConfigDefaults = R"(# centaur simulate: scenario configuration (defaults). Units SI; [lo, hi] = allowed range.
duration: 10.0            # [s] simulated time, [0.001, 3600]
model: ""                 # MJCF file; "" = the robot's (robot.name)
physics:
  timestep: 0.0005        # [s] physics step (2 kHz), [1e-5, 0.01]
  control_decimation: 2   # physics steps per controller call (2 -> 1 kHz), [1, 100]
  solver: newton          # MuJoCo contact solver: newton | cg | pgs | model (the MJCF's own option); all
                          # reach the MJCF's tolerance, so they agree to ~1e-6; speed differs (docs/benchmarks.md)
world:
  wall_x: -0.578          # [m] x of the wall's front face (normal +x, behind the robot), [-100, 100]
  friction: 1.0           # [-] wheel-ground sliding friction (set on ground and wheels), [0, 10]
sensors:
  latency_periods: 0      # [control periods] measurement delay, [0, 100]
  seed: 1                 # noise random seed, [0, 2147483647]
  noise:                  # Gaussian noise standard deviations; 0 = off
    q: 0.0                # [rad] joint positions, [0, 1]
    qd: 0.0               # [rad/s] joint velocities, [0, 10]
    tau: 0.0              # [Nm] measured joint torques, [0, 100]
    gyro: 0.0             # [rad/s] IMU angular velocity, [0, 10]
    acc: 0.0              # [m/s^2] IMU specific force, [0, 100]
    orientation: 0.0      # [rad] IMU orientation, [0, 1]
robot:                    # the simulated robot and its deviation from its model; the controller keeps the nominal model
  name: centauro          # a shipped robot (models/NAME/) or a robot.yaml (docs/robots.md); its layer comes first
  mass_scale: 1.0         # [-] every robot body's mass and inertia multiplied by this, [0.5, 2]
  com_offset: [0.0, 0.0, 0.0]  # [m] shift of the whole robot's CoM (pelvis frame), each in [-0.1, 0.1]
push:                     # an external push: a constant force at one body's CoM during a time window
  impulse: 0.0            # [N s] magnitude (force = impulse / duration), [0, 1000]; 0 = no push
  body: pelvis            # MJCF body pushed
  direction: [1.0, 0.0, 0.0]  # world frame (normalised), each in [-1, 1], not all zero
  start: 1.0              # [s] robot time the push starts, [0, 3600]
  duration: 0.1           # [s] length of the push, [0.0005, 10]
outcome:
  fall_height: 0.35       # [m] pelvis height below which the run is a fall, [0, 5]
  fall_tilt_deg: 45.0     # [deg] |roll| or |pitch| above which the run is a fall, [1, 180]
render:
  width: 640              # [px] video/snapshot width, [16, 4096]
  height: 480             # [px] video/snapshot height, [16, 4096]
  fps: 30.0               # [1/s] video frame rate, [1, 240]
  camera: side            # MJCF camera name; "" = free camera tracking the pelvis
  shadows: true           # render shadows (costly in software GL)
  reflections: false      # render floor reflections (costly in software GL)
log:
  decimation: 1           # log every N-th control period, [1, 1000]
controller: {}            # the scenario controller's own section (see docs/sim.md)
)";

SimConfig parseSimConfig(const YAML::Node& effective, const std::string& label,
                         const std::vector<std::string>& node_sections) {
  SimConfig c;
  c.effective = effective;
  c.label = label;
  YamlReader r(effective, label);
  r.get("duration", c.duration, 0.001, 3600.0);
  std::string model;
  r.get("model", model);
  c.robot.model_path = model;  // "": the robot's MJCF, filled in by loadSimConfig
  {
    auto p = r.child("physics");
    p.get("timestep", c.robot.timestep, 1e-5, 0.01);
    p.get("control_decimation", c.robot.control_decimation, 1, 100);
    p.get("solver", c.robot.solver, {"newton", "cg", "pgs", "model"});
    p.finish();
  }
  {
    auto w = r.child("world");
    w.get("wall_x", c.robot.wall_x, -100.0, 100.0);
    w.get("friction", c.robot.friction, 0.0, 10.0);
    w.finish();
  }
  {
    auto s = r.child("sensors");
    s.get("latency_periods", c.robot.latency_periods, 0, 100);
    int seed = 1;
    s.get("seed", seed, 0, 2147483647);
    c.robot.seed = static_cast<std::uint64_t>(seed);
    auto n = s.child("noise");
    n.get("q", c.robot.noise.q, 0.0, 1.0);
    n.get("qd", c.robot.noise.qd, 0.0, 10.0);
    n.get("tau", c.robot.noise.tau, 0.0, 100.0);
    n.get("gyro", c.robot.noise.gyro, 0.0, 10.0);
    n.get("acc", c.robot.noise.acc, 0.0, 100.0);
    n.get("orientation", c.robot.noise.orientation, 0.0, 1.0);
    n.finish();
    s.finish();
  }
  {
    auto b = r.child("robot");
    b.get("name", c.robot_name);
    b.get("mass_scale", c.robot.mass_scale, 0.5, 2.0);
    Eigen::VectorXd offset = c.robot.com_offset;
    b.get("com_offset", offset, -0.1, 0.1);
    c.robot.com_offset = offset;
    b.finish();
  }
  {
    auto p = r.child("push");
    PushSettings& push = c.robot.push;
    p.get("impulse", push.impulse, 0.0, 1000.0);
    p.get("body", push.body);
    Eigen::VectorXd direction = push.direction;
    p.get("direction", direction, -1.0, 1.0);
    if (!(direction.norm() > 0.0)) p.fail("direction", "must not be [0, 0, 0]");
    push.direction = direction.normalized();
    p.get("start", push.start, 0.0, 3600.0);
    p.get("duration", push.duration, 0.0005, 10.0);
    p.finish();
  }
  {
    auto o = r.child("outcome");
    o.get("fall_height", c.outcome.fall_height, 0.0, 5.0);
    o.get("fall_tilt_deg", c.outcome.fall_tilt_deg, 1.0, 180.0);
    o.finish();
  }
  {
    auto v = r.child("render");
    v.get("width", c.render.width, 16, 4096);
    v.get("height", c.render.height, 16, 4096);
    v.get("fps", c.render.fps, 1.0, 240.0);
    v.get("camera", c.render.camera);
    v.get("shadows", c.render.shadows);
    v.get("reflections", c.render.reflections);
    v.finish();
  }
  {
    auto l = r.child("log");
    l.get("decimation", c.log_decimation, 1, 1000);
    l.finish();
  }
  r.raw("controller");  // read by the scenario's controller (controllerSection)
  for (const std::string& section : node_sections) r.raw(section);  // read by the node that added them
  r.finish();
  return c;
}

SimConfig loadSimConfig(const std::string& scenario_defaults, const std::string& file,
                        const std::vector<std::string>& overrides, const std::vector<std::string>& node_sections) {
  const YAML::Node sim_defaults = loadYamlString(kSimConfigDefaults, "<simulation defaults>");
  const YAML::Node scenario = scenario_defaults.empty() ? YAML::Node(YAML::NodeType::Map)
                                                        : loadYamlString(scenario_defaults, "<scenario defaults>");
  YAML::Node base = mergeYaml(sim_defaults, scenario);
  const YAML::Node user_file = file.empty() ? YAML::Node(YAML::NodeType::Map) : loadYamlFile(file);
  auto userLayers = [&](YAML::Node node) {
    node = mergeYaml(node, user_file);
    for (const auto& o : overrides) applyOverride(node, o);
    return node;
  };
  // The robot is a key of the configuration: read it from the user's layers, then put its layer between the
  // defaults and the user's layers (its impedance groups replace the defaults' controller.gains).
  const YAML::Node name = userLayers(YAML::Clone(base))["robot"]["name"];
  std::string label = file.empty() ? "<defaults>" : file;
  if (!overrides.empty()) label += (file.empty() ? " with --set" : " (with --set)");
  if (!name || !name.IsScalar() || name.Scalar().empty()) throw InputError(label, "robot.name", "expected a robot's name or path");
  SimRobot robot;
  try {
    robot = loadSimRobot(name.Scalar());
  } catch (const InputError& e) {
    throw InputError(label, "robot.name", e.what());
  }
  // The robot's world values (pushed body, fall height, wall) go under the scenario's own choices (a squat jump
  // moves the wall away); its controller values (radius, gains, Raibert joints) are facts of the robot and go over
  // them, its impedance groups replacing the scenario's.
  YAML::Node layer = simRobotLayer(robot, base);
  const YAML::Node& clayer = layer;  // const look-ups: yaml-cpp's non-const operator[] inserts the key
  YAML::Node controller = clayer["controller"] ? YAML::Clone(clayer["controller"]) : YAML::Node(YAML::NodeType::Map);
  layer.remove("controller");
  base = mergeYaml(mergeYaml(sim_defaults, layer), scenario);
  const YAML::Node& cbase = base;
  const YAML::Node& ccontroller = controller;
  if (ccontroller["gains"] && cbase["controller"]) base["controller"].remove("gains");
  if (controller.size() > 0) {
    YAML::Node over(YAML::NodeType::Map);
    over["controller"] = controller;
    base = mergeYaml(base, over);
  }
  SimConfig c = parseSimConfig(userLayers(base), label, node_sections);
  c.robot_name = robot.description.name;
  c.robot_hash = robot.description.hash;
  c.frames = robot.frames;
  if (c.robot.model_path.empty()) c.robot.model_path = robot.description.mjcf_path;
  if (!robot.description.scene_in_mjcf) c.robot.scene_xml = sceneXml(robot.description);
  c.robot.keyframe = robot.description.home;
  c.robot.imu_orientation = robot.description.imu.orientation;
  c.robot.imu_gyro = robot.description.imu.gyro;
  c.robot.imu_accelerometer = robot.description.imu.accelerometer;
  for (int k = 0; k < 4; ++k) c.robot.contact_bodies[k] = robot.description.feet[k].contact;
  return c;
}

YamlReader controllerSection(const SimConfig& config) {
  const YAML::Node& root = config.effective;
  const YAML::Node section = root["controller"];
  return YamlReader(section, config.label, "controller");
}

}  // namespace centaur::sim
