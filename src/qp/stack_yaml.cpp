#include "qp/stack_yaml.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "qp/qp_solver.hpp"

namespace centaur {

namespace {
std::string joinTypes(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "(none registered)" : s;
}

std::vector<std::string> namesOf(const YAML::Node& node, const YamlReader& root, const std::string& key) {
  std::vector<std::string> names;
  if (node.IsScalar()) {
    names.push_back(node.as<std::string>());
  } else if (node.IsSequence() && node.size() > 0) {
    for (const auto& item : node) {
      if (!item.IsScalar()) root.fail(key, "expected a list of names");
      names.push_back(item.as<std::string>());
    }
  } else {
    root.fail(key, "expected a name or a non-empty list of names");
  }
  return names;
}

void readWeight(YamlReader& r, Task& task) {
  if (!r.has("weight")) return;
  const YAML::Node w = r.raw("weight");
  try {
    if (w.IsScalar()) {
      const double v = w.as<double>();
      if (!(v >= 0.0 && v <= 1e12)) r.fail("weight", "must be in [0, 1e12]");
      task.setWeight(v);
    } else if (w.IsSequence()) {
      if (static_cast<int>(w.size()) != task.rows())
        r.fail("weight", "expected " + std::to_string(task.rows()) + " entries (one per task row)");
      Eigen::VectorXd d(task.rows());
      for (int i = 0; i < task.rows(); ++i) {
        d[i] = w[i].as<double>();
        if (!(d[i] >= 0.0 && d[i] <= 1e12)) r.fail("weight", "entries must be in [0, 1e12]");
      }
      task.setWeightDiagonal(d);
    } else {
      r.fail("weight", "expected a number or a list of numbers");
    }
  } catch (const YAML::Exception&) {
    r.fail("weight", "expected a number or a list of numbers");
  }
}
// The regularisation must dominate the heaviest weighted term enough for the QP solver to stay in its direct,
// accurate range (kMinRegularisationRatio, docs/qp.md): eps >= ratio * max over terms of scale * largest weight.
void checkRegularisation(const YamlReader& root, const LoadedStack& out) {
  double heaviest = 0.0;
  std::string name;
  for (const Level& level : out.stack.levels)
    for (const Term& t : level.terms) {
      double w = 0.0;
      for (int r = 0; r < t.size(); ++r) w = std::max(w, t.task->weight()(t.taskRow(r), t.taskRow(r)));
      if (t.scale * w > heaviest) {
        heaviest = t.scale * w;
        name = t.task->name();
      }
    }
  const double eps = out.stack.regularisation;
  if (eps >= kMinRegularisationRatio * heaviest) return;
  std::ostringstream msg;
  msg << "value " << eps << " is too small for the task weights: it must be in [" << kMinRegularisationRatio * heaviest
      << ", 1], i.e. at least " << kMinRegularisationRatio << " x the largest scale x weight of a task ('" << name
      << "': " << heaviest << "); below, the QP Hessians are too ill-conditioned for the solver's direct method "
      << "(docs/qp.md). Raise regularisation or lower the weights";
  root.fail("regularisation", msg.str());
}
// The task or constraint (kind) that the maker registered for the definition's `type` builds from the definition.
template <class Made, class MakerOf>
Made makeFromType(YamlReader& r, const std::string& name, const std::string& kind,
                  const std::vector<std::string>& types, const MakerOf& makerOf) {
  std::string type;
  r.get("type", type);
  if (type.empty()) r.fail("type", "required; registered " + kind + " types: " + joinTypes(types));
  if (std::find(types.begin(), types.end(), type) == types.end())
    r.fail("type", "unknown " + kind + " type '" + type + "'; registered: " + joinTypes(types));
  Made made;
  try {
    made = makerOf(type)(name, r);
  } catch (const std::invalid_argument& e) {
    r.fail("type", e.what());
  }
  if (!made) r.fail("type", "the maker of type '" + type + "' returned no " + kind);
  return made;
}

// The task `name` of the stack (its definition under the key `name`) as a term: type, lambda, weight, the rows
// selected by `indices` and the scale. The task goes into out.tasks.
Term readTerm(YamlReader& root, const std::string& name, const TaskRegistry& registry, LoadedStack& out) {
  if (name == "stack" || name == "constraints" || name == "regularisation")
    root.fail("stack", "'" + name + "' is a reserved key, not a task name");
  if (!root.has(name)) root.fail(name, "task named in 'stack' has no definition");
  YamlReader r = root.child(name);
  const TaskPtr task = makeFromType<TaskPtr>(r, name, "task", registry.taskTypes(),
                                             [&](const std::string& type) { return registry.task(type); });
  double lambda = task->lambda();
  r.get("lambda", lambda, 0.0, 1e6);
  task->setLambda(lambda);
  readWeight(r, *task);
  Term t(task);
  if (r.has("indices")) {
    const YAML::Node idx = r.raw("indices");
    Rows rows;
    try {
      if (!idx.IsSequence() || idx.size() == 0) throw YAML::Exception(YAML::Mark(), "");
      for (const auto& i : idx) rows.push_back(i.as<int>());
    } catch (const YAML::Exception&) {
      r.fail("indices", "expected a non-empty list of row indices");
    }
    try {
      t = t % rows;
    } catch (const std::out_of_range&) {
      r.fail("indices", "row indices must be in [0, " + std::to_string(task->rows() - 1) + "]");
    }
  }
  double scale = 1.0;
  r.get("scale", scale, 0.0, 1e12);
  t.scale = scale;
  r.finish();
  out.tasks[name] = task;
  return t;
}

// The constraints named in `constraints` (each once), from their definitions.
void readConstraints(YamlReader& root, const TaskRegistry& registry, LoadedStack& out) {
  if (!root.has("constraints")) return;
  const YAML::Node list = root.raw("constraints");
  if (list.IsSequence() && list.size() == 0) return;
  for (const std::string& name : namesOf(list, root, "constraints")) {
    if (out.constraints.count(name)) continue;
    if (!root.has(name)) root.fail(name, "constraint named in 'constraints' has no definition");
    YamlReader r = root.child(name);
    const ConstraintPtr c = makeFromType<ConstraintPtr>(r, name, "constraint", registry.constraintTypes(),
                                                        [&](const std::string& t) { return registry.constraint(t); });
    r.finish();
    out.constraints[name] = c;
    out.stack.constraints.push_back(c);
  }
}

}  // namespace

void TaskRegistry::addTask(const std::string& type, TaskMaker maker) {
  if (!tasks_.emplace(type, std::move(maker)).second)
    throw std::invalid_argument("task type '" + type + "' is already registered");
}

void TaskRegistry::addConstraint(const std::string& type, ConstraintMaker maker) {
  if (!constraints_.emplace(type, std::move(maker)).second)
    throw std::invalid_argument("constraint type '" + type + "' is already registered");
}

std::vector<std::string> TaskRegistry::taskTypes() const {
  std::vector<std::string> v;
  for (const auto& kv : tasks_) v.push_back(kv.first);
  return v;
}

std::vector<std::string> TaskRegistry::constraintTypes() const {
  std::vector<std::string> v;
  for (const auto& kv : constraints_) v.push_back(kv.first);
  return v;
}

LoadedStack loadStack(const YAML::Node& node, const std::string& file, const TaskRegistry& registry) {
  YamlReader root(node, file);
  LoadedStack out;
  if (!root.has("stack")) root.fail("stack", "required: a list of priority levels, e.g. [[feet], [posture]]");
  const YAML::Node levels = root.raw("stack");
  if (!levels.IsSequence() || levels.size() == 0) root.fail("stack", "expected a non-empty list of levels");
  root.get("regularisation", out.stack.regularisation, 1e-12, 1.0);

  std::map<std::string, Term> terms;  // a task named in several levels is read once
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const std::string key = "stack[" + std::to_string(k) + "]";
    Level level;
    for (const std::string& name : namesOf(levels[k], root, key)) {
      auto it = terms.find(name);
      if (it == terms.end()) it = terms.emplace(name, readTerm(root, name, registry, out)).first;
      level.terms.push_back(it->second);
    }
    out.stack.levels.push_back(std::move(level));
  }
  readConstraints(root, registry, out);
  checkRegularisation(root, out);
  root.finish();
  return out;
}

}  // namespace centaur
