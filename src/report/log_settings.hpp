#pragma once
// What a report needs from a log's effective configuration (root attribute `config`): the MJCF it simulated,
// where the wall stood and when the primitive started.
#include <string>

#include "data/sim_log_file.hpp"

namespace centaur::report {

struct LogSettings {
  std::string model;             ///< `model`; "" = the shipped CENTAURO
  double wall_x = -0.578;        ///< [m] `world.wall_x`
  double primitive_start = 0.5;  ///< [s] `controller.settle_time` (robot time at which the primitive starts)
};

/// InputError("<log>: key 'config': ...") if the configuration is not YAML or a value has the wrong type.
LogSettings readLogSettings(const data::SimLogFile& log);

}  // namespace centaur::report
