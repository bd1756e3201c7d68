// centaur control <task> [--primitive F.h5] [--stabilizer MODE] [--flywheel F.h5] [--start-after S]
//                        [--config F.yaml] [--set key=value]... [--json]
// The controller node. It runs as the program centaur-control (built next to this one, linking neither Ipopt
// nor the simulator): this verb replaces the process with it, arguments unchanged (docs/middleware.md).
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "cli/command.hpp"
#include "common/error.hpp"

namespace centaur::cli {

namespace {

int execControlNode(const std::vector<std::string>& args) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path node = self.parent_path() / "centaur-control";
  if (ec || !std::filesystem::is_regular_file(node, ec)) {
    throw RuntimeError("control: the controller node program " + node.string() + " is missing (build it: make build)");
  }
  std::vector<std::string> storage;
  storage.push_back(node.string());
  storage.insert(storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  ::execv(argv[0], argv.data());
  throw RuntimeError("control: cannot run " + node.string() + ": " + std::strerror(errno));
}

const Registrar registrar{Command{
    "control",
    "the online stage as a DDS node (runs centaur-control): reads the robot's joint states and IMU, publishes "
    "joint commands; `centaur control --help` for its options",
    [](CLI::App& sub) -> std::function<int()> {
      sub.prefix_command();  // every argument goes to centaur-control, --help included
      sub.set_help_flag();
      return [&sub]() -> int { return execControlNode(sub.remaining()); };
    }}};

}  // namespace

}  // namespace centaur::cli
