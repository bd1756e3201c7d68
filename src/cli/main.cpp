// centaur: plan, inspect, plot, simulate, compare and benchmark agile actions of CENTAURO.
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/command.hpp"
#include "common/error.hpp"

namespace centaur::cli {

std::vector<Command>& commands() {
  static std::vector<Command> registry;
  return registry;
}

void printJsonLine(const std::string& json) {
  std::fflush(stderr);
  std::cout << json << std::endl;
}

}  // namespace centaur::cli

int main(int argc, char** argv) {
  using namespace centaur;
  CLI::App app{"centaur: agile actions for a centaur-type humanoid (plan offline, replay online at 1 kHz)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "centaur 0.1.0");
  std::vector<std::pair<CLI::App*, std::function<int()>>> actions;
  std::vector<std::shared_ptr<std::function<int()>>> slots;
  for (auto& c : cli::commands()) {
    CLI::App* sub = app.add_subcommand(c.name, c.help);
    auto slot = std::make_shared<std::function<int()>>(c.setup(*sub));
    actions.emplace_back(sub, *slot);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : kExitBadInput;
  }
  try {
    for (auto& [sub, action] : actions) {
      if (sub->parsed()) return action();
    }
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << std::endl;
    return kExitBadInput;
  } catch (const RuntimeError& e) {
    std::cerr << "error: " << e.what() << std::endl;
    return kExitRuntime;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << std::endl;
    return kExitRuntime;
  }
  return kExitFailure;
}
