#pragma once
// The `centaur` command line as an object: every registered verb (cli/command.hpp) as a sub-command. main()
// parses with it and runs the selected verb; the argument-parser fuzz target (fuzz/) parses with it only.
#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <vector>

namespace centaur::cli {

class CliApp {
 public:
  CliApp();
  /// Parse the arguments; returns the action of the selected verb. Throws CLI::ParseError (help, version and
  /// every parse error; CLI::App::exit() prints it).
  std::function<int()> parse(int argc, const char* const* argv);
  CLI::App& app() { return app_; }

 private:
  CLI::App app_;
  std::vector<std::pair<CLI::App*, std::function<int()>>> actions_;
};

}  // namespace centaur::cli
