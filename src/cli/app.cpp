#include "cli/app.hpp"

#include <cstdio>
#include <iostream>

#include "cli/command.hpp"

namespace centaur::cli {

std::vector<Command>& commands() {
  static std::vector<Command> registry;
  return registry;
}

void printJsonLine(const std::string& json) {
  std::fflush(stderr);
  std::cout << json << std::endl;
}

void printJsonLine(const nlohmann::json& json) {
  printJsonLine(json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

CliApp::CliApp() : app_("centaur: agile actions for a centaur-type humanoid (plan offline, replay online at 1 kHz)") {
  app_.require_subcommand(1);
  app_.set_version_flag("--version", "centaur 0.1.0");
  for (auto& c : commands()) {
    CLI::App* sub = app_.add_subcommand(c.name, c.help);
    actions_.emplace_back(sub, c.setup(*sub));
  }
}

std::function<int()> CliApp::parse(int argc, const char* const* argv) {
  app_.parse(argc, argv);
  for (auto& [sub, action] : actions_) {
    if (sub->parsed()) return action;
  }
  throw CLI::RequiredError("a command");
}

}  // namespace centaur::cli
