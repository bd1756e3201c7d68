#include "middleware/topics.hpp"

#include "middleware/messages.hpp"

namespace centaur::middleware {

const TopicSpec kJointStates = {"joint_states", "sensor_msgs/msg/JointState",
                                &sensor_msgs_msg_dds__JointState__desc, 1, 1, "1 kHz (one per control period)", "robot"};
const TopicSpec kImu = {"imu", "sensor_msgs/msg/Imu", &sensor_msgs_msg_dds__Imu__desc, 1, 1,
                        "1 kHz (one per control period)", "robot"};
const TopicSpec kJointCommand = {"joint_command", "centaur_msgs/msg/JointCommand",
                                 &centaur_msgs_msg_dds__JointCommand__desc, 1, 64, "1 kHz (one per joint state)",
                                 "controller"};
const TopicSpec kRobotStatus = {"robot_status", "centaur_msgs/msg/RobotStatus",
                                &centaur_msgs_msg_dds__RobotStatus__desc, 10, 10, "100 Hz and on every mode change",
                                "robot"};
const TopicSpec kControllerStatus = {"controller_status", "centaur_msgs/msg/ControllerStatus",
                                     &centaur_msgs_msg_dds__ControllerStatus__desc, 10, 10,
                                     "100 Hz and on every change of phase or safe mode", "controller"};
const TopicSpec kContactForces = {"debug/contact_forces", "centaur_msgs/msg/ContactForces",
                                  &centaur_msgs_msg_dds__ContactForces__desc, 1, 1, "1 kHz", "robot"};
const TopicSpec kRobotReset = {"robot/reset", "std_msgs/msg/Empty", &std_msgs_msg_dds__Empty__desc, 10, 10,
                               "on demand", "user"};
const TopicSpec kControllerReset = {"controller/reset", "std_msgs/msg/Empty", &std_msgs_msg_dds__Empty__desc, 10, 10,
                                    "on demand", "user"};
const TopicSpec kStart = {"start", "std_msgs/msg/Empty", &std_msgs_msg_dds__Empty__desc, 10, 10, "on demand", "user"};

const TopicSpec* const* allTopics(int& count) {
  static const TopicSpec* const all[] = {&kJointStates, &kImu,           &kJointCommand,
                                         &kRobotStatus, &kControllerStatus, &kContactForces,
                                         &kRobotReset,  &kControllerReset, &kStart};
  count = static_cast<int>(sizeof(all) / sizeof(all[0]));
  return all;
}

}  // namespace centaur::middleware
