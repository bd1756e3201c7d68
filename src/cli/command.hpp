#pragma once
// The `centaur` command line: each verb lives in its own cmd_<verb>.cpp and registers itself here.
// A command's run() returns the process exit code (see common/error.hpp); it may throw InputError
// (-> exit 2) or RuntimeError (-> exit 4), which main() reports on stderr.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace centaur::cli {

struct Command {
  std::string name;
  std::string help;
  /// Declare options on `sub`; return the action to run if `sub` was selected.
  std::function<std::function<int()>(CLI::App& sub)> setup;
};

/// Registry of all verbs, filled by static registrars before main() runs.
std::vector<Command>& commands();

struct Registrar {
  explicit Registrar(Command c) { commands().push_back(std::move(c)); }
};

/// Print a JSON object as the last line of stdout (the --json contract).
void printJsonLine(const std::string& json);
/// The same from a JSON value; strings that are not valid UTF-8 (a name or path taken from an input) are
/// printed with U+FFFD instead of failing.
void printJsonLine(const nlohmann::json& json);

/// A finite number in [lo, hi]. CLI11's Range lets NaN through (every comparison with NaN is false) and reads
/// "inf"; use this for every floating-point option.
inline CLI::Validator finiteRange(double lo, double hi) {
  const std::string range = "[" + CLI::detail::to_string(lo) + ", " + CLI::detail::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        double v = 0.0;
        if (!CLI::detail::lexical_cast(text, v) || !(v >= lo && v <= hi)) {
          return "value " + text.substr(0, 40) + " is not a finite number in " + range;
        }
        return std::string();
      },
      "FINITE in " + range);
}

}  // namespace centaur::cli
