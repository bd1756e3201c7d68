#pragma once
// The YAML form of a stack (in the spirit of CartesI/O) and the registry of task / constraint types.
//
//   stack:                       # priority levels, highest first; each level is a list of task names
//     - [feet]                   #   (a plain name is a one-task level)
//     - [pelvis]
//     - [ang_mom, posture]       # soft priority inside a level
//   constraints: [joint_limits, velocity_limits]   # imposed at every level (optional)
//   regularisation: 1.0e-6       # eps ||x||^2 at every level (optional, [1e-7 x max scale x weight, 1])
//   feet:                        # one mapping per task / constraint named above
//     type: Cartesian            # a type registered in the TaskRegistry (required)
//     lambda: 0.5                # gain (optional, [0, 1e6], default: the type's)
//     weight: 1.0                # scalar, or a list with one entry per task row (optional, >= 0)
//     indices: [0, 1, 2]         # sub-task rows (optional)
//     scale: 1.0                 # multiplies the cost inside its level (optional, >= 0)
//     ...                        # the type's own keys (frames, gains, joints, ...), read by its maker
//   joint_limits:
//     type: JointPositionLimits  # a registered constraint type; its own keys follow
//
// Every key must be known: the common keys are read by loadStack(), the others by the type's maker;
// anything left unread is an InputError naming the file and key, as is a name without a definition.
//
// Robot-specific types register a maker that captures what it needs (a model, a time step) by value or
// reference, without any change here:
//   registry.addTask("Cartesian", [&model](const std::string& name, YamlReader& r) -> TaskPtr {
//     std::string base = "pelvis", distal;  r.get("base_link", base);  r.get("distal_link", distal);
//     return std::make_shared<CartesianTask>(name, model, base, distal);
//   });
#include <yaml-cpp/yaml.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/yaml_reader.hpp"
#include "qp/stack.hpp"

namespace centaur {

/// Builds a task from its YAML mapping (the common keys are handled by loadStack). Throw InputError (via
/// reader.fail) for bad values.
using TaskMaker = std::function<TaskPtr(const std::string& name, YamlReader& reader)>;
using ConstraintMaker = std::function<ConstraintPtr(const std::string& name, YamlReader& reader)>;

class TaskRegistry {
 public:
  /// Register a type; throws std::invalid_argument if the type is already registered.
  void addTask(const std::string& type, TaskMaker maker);
  void addConstraint(const std::string& type, ConstraintMaker maker);
  bool hasTask(const std::string& type) const { return tasks_.count(type) > 0; }
  bool hasConstraint(const std::string& type) const { return constraints_.count(type) > 0; }
  std::vector<std::string> taskTypes() const;
  std::vector<std::string> constraintTypes() const;
  const TaskMaker& task(const std::string& type) const { return tasks_.at(type); }
  const ConstraintMaker& constraint(const std::string& type) const { return constraints_.at(type); }

 private:
  std::map<std::string, TaskMaker> tasks_;
  std::map<std::string, ConstraintMaker> constraints_;
};

/// The stack and the named objects it was built from (to set references, read costs, ...).
struct LoadedStack {
  Stack stack;
  std::map<std::string, TaskPtr> tasks;
  std::map<std::string, ConstraintPtr> constraints;
};

/// Build a stack from its YAML form (see above). `file` only labels messages. Throws InputError.
LoadedStack loadStack(const YAML::Node& root, const std::string& file, const TaskRegistry& registry);

}  // namespace centaur
