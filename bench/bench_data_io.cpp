// Reading the data formats with their validation (data/hdf5.hpp): what the checks of every dataset (finite values,
// time axis, quaternions, knots) cost next to the HDF5 read itself; and writing a primitive (compression included).
//   ./build/bench/bench_data_io --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

#include "data/hdf5.hpp"
#include "data/primitive_io.hpp"
#include "../tests/support/synthetic_primitive.hpp"

namespace {

/// The synthetic jump (1001 samples) written once to a temporary file.
const std::string& primitiveFile() {
  static const std::string path = [] {
    const std::string p = (std::filesystem::temp_directory_path() / ("bench-data-io-" + std::to_string(getpid()) + ".h5")).string();
    centaur::data::writePrimitive(p, centaur::test::makeSyntheticJump("squat-jump"));
    return p;
  }();
  return path;
}

void BM_ReadPrimitive(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(centaur::data::readPrimitive(primitiveFile(), "squat-jump"));
}
BENCHMARK(BM_ReadPrimitive)->Unit(benchmark::kMicrosecond);

// Writing the same primitive to a new file (through a temporary and a rename, as every output), deflate included.
void BM_WritePrimitive(benchmark::State& state) {
  const centaur::data::Primitive p = centaur::test::makeSyntheticJump("squat-jump");
  const std::string path =
      (std::filesystem::temp_directory_path() / ("bench-data-io-w-" + std::to_string(getpid()) + ".h5")).string();
  for (auto _ : state) centaur::data::writePrimitive(path, p);
  state.counters["file_bytes"] = static_cast<double>(std::filesystem::file_size(path));
  std::filesystem::remove(path);
}
BENCHMARK(BM_WritePrimitive)->Unit(benchmark::kMicrosecond);

// The checks alone, on the same arrays: every matrix finite, the time axis, the quaternions.
void BM_ValidatePrimitiveArrays(benchmark::State& state) {
  const centaur::data::Primitive p = centaur::data::readPrimitive(primitiveFile(), "squat-jump");
  const centaur::data::h5::Reader r(primitiveFile(), "bench");
  for (auto _ : state) {
    r.requireTimeAxis("t", p.t, centaur::data::h5::TimeAxisRules{});
    for (const auto* m : {&p.q, &p.nu, &p.base_pos, &p.base_quat, &p.base_vel, &p.base_omega, &p.foot_pos,
                          &p.foot_pos_rel, &p.foot_vel_rel, &p.force, &p.tau, &p.knot_x, &p.knot_u}) {
      r.requireFinite("m", *m);
    }
    r.requireUnitQuaternions("base_quat", p.base_quat);
  }
}
BENCHMARK(BM_ValidatePrimitiveArrays)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
