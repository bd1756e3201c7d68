#include "controller/robot_tasks.hpp"

#include <memory>

#include "controller/model_joint_limits.hpp"
#include "controller/task_angular_momentum.hpp"
#include "controller/task_cartesian.hpp"
#include "controller/task_com.hpp"
#include "controller/task_pelvis_angular_velocity.hpp"
#include "controller/task_postural.hpp"

namespace centaur {

namespace {
void checkFrame(const RobotModel& model, YamlReader& r, const std::string& key, const std::string& frame,
                bool allow_world) {
  if (allow_world && frame == "world") return;
  if (model.frameId(frame) < 0) r.fail(key, "unknown frame '" + frame + "'");
}
// Optional `joints:` list of joint names -> indices (empty if the key is absent).
std::vector<int> readJointList(const RobotModel& model, YamlReader& r) {
  std::vector<int> joints;
  if (!r.has("joints")) return joints;
  const YAML::Node list = r.raw("joints");
  if (!list.IsSequence() || list.size() == 0) r.fail("joints", "a non-empty list of joint names");
  for (const auto& j : list) {
    const std::string jn = j.as<std::string>();
    const int idx = model.jointIndex(jn);
    if (idx < 0) r.fail("joints", "unknown joint '" + jn + "'");
    joints.push_back(idx);
  }
  return joints;
}
}  // namespace

void registerRobotTasks(TaskRegistry& reg, const RobotModel& model, double dt) {
  reg.addTask("Cartesian", [&model](const std::string& name, YamlReader& r) -> TaskPtr {
    std::string base = "pelvis", distal;
    bool orientation = false;
    r.get("base_link", base);
    r.get("distal_link", distal);
    r.get("orientation", orientation);
    if (distal.empty()) r.fail("distal_link", "required (a frame of the model)");
    checkFrame(model, r, "base_link", base, true);
    checkFrame(model, r, "distal_link", distal, false);
    return std::make_shared<CartesianTask>(name, model, base, distal, orientation);
  });
  reg.addTask("PelvisAngularVelocity", [&model](const std::string& name, YamlReader& r) -> TaskPtr {
    std::string base = "pelvis";
    r.get("base_link", base);
    checkFrame(model, r, "base_link", base, false);
    return std::make_shared<PelvisAngularVelocityTask>(name, model, base);
  });
  reg.addTask("Postural", [&model](const std::string& name, YamlReader& r) -> TaskPtr {
    return std::make_shared<PosturalTask>(name, model, readJointList(model, r));
  });
  reg.addTask("AngularMomentum", [&model](const std::string& name, YamlReader& r) -> TaskPtr {
    return std::make_shared<AngularMomentumTask>(name, model, readJointList(model, r));
  });
  reg.addTask("Com", [&model](const std::string& name, YamlReader&) -> TaskPtr {
    return std::make_shared<ComTask>(name, model);
  });
  reg.addConstraint("JointPositionLimits", [&model, dt](const std::string& name, YamlReader& r) -> ConstraintPtr {
    double scaling = 1.0;
    r.get("scaling", scaling, 1e-3, 1.0);
    return std::make_shared<ModelJointPositionLimits>(name, model, dt, scaling);
  });
  reg.addConstraint("JointVelocityLimits", [&model](const std::string& name, YamlReader& r) -> ConstraintPtr {
    double scaling = 1.0;
    r.get("scaling", scaling, 1e-3, 1.0);
    return std::make_shared<JointVelocityLimits>(name, model.nv(), 6, scaling * model.limits().qd_max);
  });
}

}  // namespace centaur
