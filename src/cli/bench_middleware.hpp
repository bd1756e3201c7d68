#pragma once
// centaur bench middleware [--primitives P.h5] [--realtime-priority N] [--json]: the robot node in this process, the controller node
// (centaur-control) as a child process on a private DDS domain over loopback:
//   1. lockstep stand, 5 s: state -> command round trip (publish the state ... apply the answer), p50/p99/max;
//   2. realtime stand, 10 s: control periods whose command arrived late (after robot_node.command_wait);
//   3. lockstep squat jump (raibert): the closed loop's real-time factor.
// realtime_priority > 0: both nodes under SCHED_FIFO at that priority (middleware.realtime_priority).
#include <nlohmann/json.hpp>

#include <string>

namespace centaur::cli {

nlohmann::json benchMiddleware(const std::string& primitives, int realtime_priority = 0);

}  // namespace centaur::cli
