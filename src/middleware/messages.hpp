#pragma once
// The generated message types (idlc, from src/middleware/idl/*.idl): C structs named
// <pkg>_msg_dds__<Type>_ with descriptors <pkg>_msg_dds__<Type>__desc. Sequences are
// {_maximum, _length, _buffer, _release}; strings are char*.
#include <cstdint>

#include "builtin_interfaces.h"
#include "centaur_msgs.h"
#include "geometry_msgs.h"
#include "sensor_msgs.h"
#include "std_msgs.h"

namespace centaur::middleware {

using TimeMsg = builtin_interfaces_msg_dds__Time_;
using EmptyMsg = std_msgs_msg_dds__Empty_;
using JointStateMsg = sensor_msgs_msg_dds__JointState_;
using ImuMsg = sensor_msgs_msg_dds__Imu_;
using JointCommandMsg = centaur_msgs_msg_dds__JointCommand_;
using RobotStatusMsg = centaur_msgs_msg_dds__RobotStatus_;
using ControllerStatusMsg = centaur_msgs_msg_dds__ControllerStatus_;
using ContactForcesMsg = centaur_msgs_msg_dds__ContactForces_;
using Vector3Msg = geometry_msgs_msg_dds__Vector3_;

/// Robot time [ns] <-> builtin_interfaces/Time (sec, nanosec in [0, 1e9)). Negative times clamp to 0.
TimeMsg timeFromNanoseconds(std::int64_t ns);
/// -1 if the message is not a valid time (nanosec >= 1e9 or negative seconds).
std::int64_t nanosecondsFromTime(const TimeMsg& t);

/// Robot modes on RobotStatus.mode.
enum RobotMode : std::uint8_t { kModeWaiting = 0, kModeRunning = 1, kModeDamping = 2, kModeFinished = 3 };

}  // namespace centaur::middleware
