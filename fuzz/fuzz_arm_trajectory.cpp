// Fuzz target: the arm-trajectory reader (data/arm_trajectory_io.hpp) on HDF5 file images in memory (raw, or built from the input: fuzz/h5_builder.hpp).
#include "data/arm_trajectory_io.hpp"
#include "fuzz_support.hpp"
#include "h5_builder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes = centaur_fuzz::imageOf(data, size, centaur_fuzz::armImage);
  const centaur::data::FileImage image{bytes.data(), bytes.size(), "<fuzz.h5>"};
  centaur_fuzz::expectOnlyInputErrors([&] { centaur::data::readArmTrajectory(image); });
  return 0;
}
