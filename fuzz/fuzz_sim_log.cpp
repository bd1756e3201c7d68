// Fuzz target: the simulation-log reader (data/sim_log_file.hpp) on HDF5 file images in memory (raw, or built from the input: fuzz/h5_builder.hpp): open, read every
// dataset of the format, and the IMU pitch `centaur compare` derives from a log.
#include "data/sim_log_file.hpp"
#include "fuzz_support.hpp"
#include "h5_builder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes = centaur_fuzz::imageOf(data, size, centaur_fuzz::simLogImage);
  const centaur::data::FileImage image{bytes.data(), bytes.size(), "<fuzz.h5>"};
  centaur_fuzz::expectOnlyInputErrors([&] {
    const centaur::data::SimLogFile log(image);
    log.time();
    for (const centaur::data::LogDataset& d : centaur::data::simLogDatasets()) log.read(d.name);
  });
  return 0;
}
