#include "report/log_settings.hpp"

#include <yaml-cpp/yaml.h>

#include "common/error.hpp"

namespace centaur::report {

LogSettings readLogSettings(const data::SimLogFile& log) {
  LogSettings s;
  try {
    const YAML::Node c = YAML::Load(log.header().config_yaml);
    if (c["model"]) s.model = c["model"].as<std::string>();
    if (c["world"] && c["world"]["wall_x"]) s.wall_x = c["world"]["wall_x"].as<double>();
    if (c["controller"] && c["controller"]["settle_time"]) {
      s.primitive_start = c["controller"]["settle_time"].as<double>();
    }
  } catch (const YAML::Exception& e) {
    throw InputError(log.path(), "config", std::string("not a valid configuration: ") + e.what());
  }
  return s;
}

}  // namespace centaur::report
