#include "robot/robot_registry.hpp"

#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>

#include "common/error.hpp"
#include "common/excerpt.hpp"

namespace centaur::robot {

namespace {
bool exists(const std::string& path, bool directory) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && (directory ? S_ISDIR(st.st_mode) : S_ISREG(st.st_mode));
}
}  // namespace

std::string modelsDirectory() { return std::string(CENTAUR_SOURCE_DIR) + "/models"; }

std::vector<std::string> robotNames() {
  std::vector<std::string> names;
  std::unique_ptr<DIR, int (*)(DIR*)> dir(::opendir(modelsDirectory().c_str()), ::closedir);
  if (!dir) return names;
  while (const dirent* e = ::readdir(dir.get())) {
    const std::string name = e->d_name;
    if (name.empty() || name[0] == '.') continue;
    if (exists(modelsDirectory() + "/" + name + "/robot.yaml", false)) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string robotYamlPath(const std::string& name_or_path) {
  const auto names = robotNames();
  if (std::find(names.begin(), names.end(), name_or_path) != names.end()) {
    return modelsDirectory() + "/" + name_or_path + "/robot.yaml";
  }
  if (exists(name_or_path, true) && exists(name_or_path + "/robot.yaml", false)) return name_or_path + "/robot.yaml";
  if (exists(name_or_path, false)) return name_or_path;
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  throw InputError("--robot '" + excerpt(name_or_path) + "' is neither a shipped robot (" + list +
                   ") nor a robot.yaml or a folder holding one");
}

RobotDescription loadRobot(const std::string& name_or_path) { return readRobotDescription(robotYamlPath(name_or_path)); }

LoadedRobot loadRobotWithFacts(const std::string& name_or_path) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const RobotFacts>> cache;  // yaml path + hash -> facts
  LoadedRobot r{loadRobot(name_or_path), nullptr};
  const std::string key = r.description.yaml_path + "#" + r.description.hash;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[key];
  if (!slot) slot = std::make_shared<const RobotFacts>(robotFacts(r.description));
  r.facts = slot;
  return r;
}

}  // namespace centaur::robot
