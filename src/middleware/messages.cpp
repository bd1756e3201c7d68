#include "middleware/messages.hpp"

namespace centaur::middleware {

TimeMsg timeFromNanoseconds(std::int64_t ns) {
  if (ns < 0) ns = 0;
  TimeMsg t;
  t.sec = static_cast<std::int32_t>(ns / 1000000000);
  t.nanosec = static_cast<std::uint32_t>(ns % 1000000000);
  return t;
}

std::int64_t nanosecondsFromTime(const TimeMsg& t) {
  if (t.sec < 0 || t.nanosec >= 1000000000u) return -1;
  return static_cast<std::int64_t>(t.sec) * 1000000000 + static_cast<std::int64_t>(t.nanosec);
}

}  // namespace centaur::middleware
