#pragma once
// Numbers as text that reads back to the same double (for command lines, YAML and file names).
#include <cstdio>
#include <cstdlib>
#include <string>

namespace centaur {

/// The shortest "%.{15,16,17}g" form of `x` that parses back to exactly `x` (0.15 -> "0.15", not
/// "0.14999999999999999"); "nan", "inf" and "-inf" for the non-finite values.
inline std::string exactNumber(double x) {
  char buf[40];
  for (int precision = 15; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, x);
    if (std::strtod(buf, nullptr) == x) break;
  }
  return buf;
}

}  // namespace centaur
