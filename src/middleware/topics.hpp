#pragma once
// Every topic the nodes use: ROS name (under the configured namespace, default /centaur), ROS type, DDS type
// (the generated descriptor), rate and QoS. ROS 2 wire conventions: DDS topic "rt" + ROS name, DDS type
// "<pkg>::msg::dds_::<Type>_". This table is the single source of truth; docs/middleware.md lists it.
//
// QoS: every writer and reader is RELIABLE with KEEP_LAST history of `depth` and VOLATILE durability; no
// deadline, lifespan or liveliness QoS (infinite: staleness is detected by the nodes' own watchdogs on the
// robot clock and the wall clock). A RELIABLE writer matches both RELIABLE and BEST_EFFORT ROS subscribers
// (`ros2 topic echo` with the default or the sensor-data profile).
#include <dds/dds.h>

namespace centaur::middleware {

struct TopicSpec {
  const char* name;       ///< relative ROS name, e.g. "joint_states" -> /centaur/joint_states
  const char* ros_type;   ///< e.g. "sensor_msgs/msg/JointState"
  const dds_topic_descriptor_t* descriptor;
  int depth;              ///< KEEP_LAST history depth of writers
  int reader_depth;       ///< KEEP_LAST history depth of our readers (joint_command: deep, so that a burst from
                          ///< another publisher cannot push a valid command out before the robot reads it)
  const char* rate;       ///< for the documentation, e.g. "1 kHz"
  const char* publisher;  ///< "robot", "controller" or "user"
};

/// The topics (defined in topics.cpp).
extern const TopicSpec kJointStates;      ///< robot -> controller: joint positions, velocities, torques
extern const TopicSpec kImu;              ///< robot -> controller: IMU orientation, angular velocity, acceleration
extern const TopicSpec kJointCommand;     ///< controller -> robot: references, feed-forward and gains per joint
extern const TopicSpec kRobotStatus;      ///< robot: mode and command counters
extern const TopicSpec kControllerStatus; ///< controller: tick time, safe mode, phase, contact flags
extern const TopicSpec kContactForces;    ///< robot (simulator ground truth, debug): force on each wheel
extern const TopicSpec kRobotReset;       ///< user -> robot: leave damping mode (std_msgs/Empty)
extern const TopicSpec kControllerReset;  ///< user -> controller: leave safe mode (std_msgs/Empty)
extern const TopicSpec kStart;            ///< user -> controller: start the jump (std_msgs/Empty)

/// All of them, in the documentation's order.
const TopicSpec* const* allTopics(int& count);

}  // namespace centaur::middleware
