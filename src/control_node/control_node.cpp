#include "control_node/control_node.hpp"

#include <chrono>
#include <cstdio>
#include <random>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "control_node/controller_link.hpp"
#include "data/primitive_io.hpp"
#include "stabilizers/online_stage.hpp"

namespace centaur::control_node {

std::string controlNodeDefaultsYaml(const std::string& task) {
  const std::string node = std::string(R"(model: ""                     # MJCF of the controller's robot model ("" = models/centauro/centauro.xml)
control_period: 0.001         # [s] the robot's control period (physics.timestep x control_decimation), [1e-4, 0.1]
control_node:                 # the controller node (docs/middleware.md)
  stale_time: 0.05            # [s] wall time without a new robot state -> safe mode, [0.002, 60]
  lockstep_stale_time: 2.0    # [s] the same when the robot reports lockstep (slow is not dead), [0.002, 600]
  connect_timeout: 60.0       # [s] wall time waiting for the first robot state, [0.1, 3600]
  status_decimation: 10       # controller status every N ticks (and on every change), [1, 10000]
)") + middleware::MiddlewareConfig::defaultsYaml();
  YAML::Node merged = mergeYaml(loadYamlString(node, "<control node defaults>"),
                                loadYamlString(controllerDefaultsYaml(task), task));
  // A jump over the middleware waits for its start trigger unless --start-after says otherwise.
  if (isJumpTask(task)) merged = mergeYaml(merged, loadYamlString("controller: {start: trigger}\n", task));
  return toYamlString(merged);
}

namespace {

struct NodeConfig {
  std::string model_path;
  double control_period = 0.001;
  ControlNodeSettings settings;
  middleware::MiddlewareConfig mw;
  std::unique_ptr<SupervisedController> controller;
};

NodeConfig loadNode(const ControlNodeArgs& a) {
  const auto& tasks = onlineTasks();
  if (std::find(tasks.begin(), tasks.end(), a.task) == tasks.end()) {
    throw InputError("control: task '" + a.task + "' is not available (stand, squat-jump, half-squat-jump)");
  }
  std::vector<std::string> overrides = a.overrides;
  if (a.start_after >= 0.0) {
    if (!isJumpTask(a.task)) throw InputError("control " + a.task + ": --start-after is for the jumps only");
    char buf[64];
    std::snprintf(buf, sizeof buf, "controller.settle_time=%.17g", a.start_after);
    overrides.push_back(buf);
    overrides.push_back("controller.start=settle");
  }
  std::string label;
  const YAML::Node root = loadLayered(loadYamlString(controlNodeDefaultsYaml(a.task), "<defaults>"), a.config_file,
                                      overrides, label);
  NodeConfig c;
  YamlReader r(root, label);
  std::string model;
  r.get("model", model);
  c.model_path = model.empty() ? std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml" : model;
  r.get("control_period", c.control_period, 1e-4, 0.1);
  {
    YamlReader n = r.child("control_node");
    n.get("stale_time", c.settings.stale_time, 0.002, 60.0);
    n.get("lockstep_stale_time", c.settings.lockstep_stale_time, 0.002, 600.0);
    n.get("connect_timeout", c.settings.connect_timeout, 0.1, 3600.0);
    n.get("status_decimation", c.settings.status_decimation, 1, 10000);
    n.finish();
  }
  {
    YamlReader m = r.child("middleware");
    c.mw.read(m);
  }
  OnlineStageInputs in;
  in.model_path = c.model_path;
  in.dt = c.control_period;
  in.stabilizer = a.stabilizer;
  in.flywheel_file = a.flywheel_file;
  const std::string file = a.primitive_file, task = a.task;
  in.primitive = [file, task] {
    if (file.empty()) throw InputError("control " + task + ": --primitive F.h5 is required (the node never plans)");
    return data::readPrimitive(file, task);
  };
  YamlReader section = r.child("controller");
  c.controller = makeOnlineController(a.task, section, in);
  r.finish();
  return c;
}

}  // namespace

ControlNodeReport runControlNode(const ControlNodeArgs& args, const std::atomic<bool>& stop) {
  NodeConfig c = loadNode(args);
  std::random_device rd;
  const std::uint64_t session = (static_cast<std::uint64_t>(rd()) << 32) ^ rd() ^
                                static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  ControllerLink link(*c.controller, c.mw, c.settings, args.task, isJumpTask(args.task) ? args.stabilizer : "",
                      session == 0 ? 1 : session);
  return link.run(stop);
}

}  // namespace centaur::control_node
