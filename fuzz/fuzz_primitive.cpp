// Fuzz target: the primitive reader (data/primitive_io.hpp) on HDF5 file images in memory (raw, or built from the input: fuzz/h5_builder.hpp), then what consumes a
// primitive that was accepted: `centaur inspect`'s summary and the online replay (controller/primitive_replay.hpp)
// sampled across and beyond its duration. An accepted primitive must never make them misbehave.
#include "controller/primitive_replay.hpp"
#include "data/primitive_io.hpp"
#include "data/primitive_summary.hpp"
#include "fuzz_support.hpp"
#include "h5_builder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes = centaur_fuzz::imageOf(data, size, centaur_fuzz::primitiveImage);
  const centaur::data::FileImage image{bytes.data(), bytes.size(), "<fuzz.h5>"};
  centaur_fuzz::expectOnlyInputErrors([&] {
    for (const centaur::data::Primitive& p : centaur::data::readPrimitives(image)) {
      centaur::data::summarize(p);
      const centaur::PrimitiveReplay replay(p);
      centaur::ReplaySample s;
      for (double t : {-1.0, 0.0, 1e-4, 0.5 * replay.duration(), replay.duration(), 2.0 * replay.duration() + 1.0, 1e300}) {
        replay.sample(t, s);
      }
    }
  });
  return 0;
}
