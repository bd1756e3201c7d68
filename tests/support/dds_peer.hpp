#pragma once
// Helpers of tests that take part in the DDS protocol themselves (a stand-in robot, a rogue publisher): a
// participant configuration on a test domain and CENTAURO's joint names in the robot's order.
#include <string>
#include <vector>

#include "middleware/middleware_config.hpp"

namespace centaur_test {

inline centaur::middleware::MiddlewareConfig onDomain(int domain) {
  centaur::middleware::MiddlewareConfig c;
  c.domain = domain;
  return c;
}

/// The 39 joints of models/centauro/centauro.xml in actuator order.
inline const std::vector<std::string>& centauroJointNames() {
  static const std::vector<std::string> names = {
      "torso_yaw",    "j_arm1_1",      "j_arm1_2",    "j_arm1_3",    "j_arm1_4",      "j_arm1_5",      "j_arm1_6",
      "j_arm1_7",     "j_arm2_1",      "j_arm2_2",    "j_arm2_3",    "j_arm2_4",      "j_arm2_5",      "j_arm2_6",
      "j_arm2_7",     "hip_yaw_1",     "hip_pitch_1", "knee_pitch_1", "ankle_pitch_1", "ankle_yaw_1",  "j_wheel_1",
      "hip_yaw_2",    "hip_pitch_2",   "knee_pitch_2", "ankle_pitch_2", "ankle_yaw_2", "j_wheel_2",    "hip_yaw_3",
      "hip_pitch_3",  "knee_pitch_3",  "ankle_pitch_3", "ankle_yaw_3", "j_wheel_3",    "hip_yaw_4",     "hip_pitch_4",
      "knee_pitch_4", "ankle_pitch_4", "ankle_yaw_4", "j_wheel_4"};
  return names;
}

}  // namespace centaur_test
