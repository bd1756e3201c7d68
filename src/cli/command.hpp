#pragma once
// The `centaur` command line: each verb lives in its own cmd_<verb>.cpp and registers itself here.
// A command's run() returns the process exit code (see common/error.hpp); it may throw InputError
// (-> exit 2) or RuntimeError (-> exit 4), which main() reports on stderr.
#include <CLI/CLI.hpp>

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

}  // namespace centaur::cli
