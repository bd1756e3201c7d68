// Fuzz target: the HQP stack loader (qp/stack_yaml.hpp) with CENTAURO's robot tasks registered
// (controller/robot_tasks.hpp), as `centaur bench tick --stack F` and the whole-body controller load a stack file.
#include <memory>

#include "common/yaml_reader.hpp"
#include "controller/robot_tasks.hpp"
#include "fuzz_support.hpp"
#include "model/robot_model.hpp"
#include "qp/stack_yaml.hpp"

namespace {

struct World {
  World() : model(std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml") {
    centaur::registerRobotTasks(registry, model, 0.001);
  }
  centaur::RobotModel model;
  centaur::TaskRegistry registry;
};

World& world() {
  static World w;
  return w;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  World& w = world();
  const std::string file = centaur_fuzz::scratchFile(std::string(reinterpret_cast<const char*>(data), size), ".yaml");
  centaur_fuzz::expectOnlyInputErrors([&] { centaur::loadStack(centaur::loadYamlFile(file), file, w.registry); });
  return 0;
}
