// ctest-labels: sim integration
// The runner end to end: determinism of logs, the HDF5 log format, strict configuration (bad input ->
// InputError naming file/key/range, no output left), rendered snapshots that are not blank.
#include <gtest/gtest.h>

#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "sim/png_writer.hpp"
#include "sim/renderer.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_runner.hpp"
#include "noisy_hold.hpp"

using namespace centaur;
using namespace centaur::sim;
namespace fs = std::filesystem;

namespace {

const std::string kTestModel = std::string(CENTAUR_SOURCE_DIR) + "/tests/testdata/sim_test_robot.xml";

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("centaur_sim_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::vector<double> readDataset(const std::string& file, const std::string& name, std::vector<hsize_t>* dims = nullptr) {
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  hid_t ds = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(ds, 0) << name;
  hid_t sp = H5Dget_space(ds);
  const int rank = H5Sget_simple_extent_ndims(sp);
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(sp, d.data(), nullptr);
  hsize_t total = 1;
  for (auto x : d) total *= x;
  std::vector<double> out(total);
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  if (dims) *dims = d;
  H5Sclose(sp);
  H5Dclose(ds);
  H5Fclose(f);
  return out;
}

std::string readStringAttribute(const std::string& file, const std::string& name) {
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t a = H5Aopen(f, name.c_str(), H5P_DEFAULT);
  hid_t t = H5Aget_type(a);
  std::string s(H5Tget_size(t), '\0');
  hid_t mem = H5Tcopy(H5T_C_S1);
  H5Tset_size(mem, s.size());
  H5Aread(a, mem, s.data());
  H5Tclose(mem);
  H5Tclose(t);
  H5Aclose(a);
  H5Fclose(f);
  return s.c_str();
}


}  // namespace

TEST(SimRunner, IdenticalRunsGiveBitwiseIdenticalLogsEvenWithNoiseAndLatency) {
  const fs::path dir = tempDir("determinism");
  std::vector<std::vector<double>> runs[2];
  const std::vector<std::string> names = {"t", "q", "qd", "tau_cmd", "tau_meas", "imu_quat", "imu_omega", "imu_acc",
                                          "base_pos", "base_quat", "wheel_force", "q_ref", "tau_ff", "kp", "kd"};
  for (int r = 0; r < 2; ++r) {
    SimConfig cfg = loadSimConfig("", "", {"model=" + kTestModel, "duration=0.5", "sensors.noise.q=0.001",
                                           "sensors.noise.gyro=0.01", "sensors.noise.orientation=0.002",
                                           "sensors.latency_periods=2", "sensors.seed=7"});
    MujocoRobot robot(cfg.robot);
    centaur::test::NoisyHold ctrl;
    RunOutputs out;
    out.log_path = (dir / ("run" + std::to_string(r) + ".h5")).string();
    const RunSummary s = runSimulation(robot, ctrl, cfg, out, "test");
    EXPECT_EQ(s.control_periods, 500);
    EXPECT_EQ(s.physics_steps, 1000);
    for (const auto& n : names) runs[r].push_back(readDataset(out.log_path, n));
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    ASSERT_FALSE(runs[0][i].empty()) << names[i];
    EXPECT_TRUE(runs[0][i] == runs[1][i]) << names[i] << " differs between identical runs";
  }
  fs::remove_all(dir);
}

TEST(SimRunner, LogHasDocumentedShapesUnitsAndConfig) {
  const fs::path dir = tempDir("format");
  SimConfig cfg = loadSimConfig("", "", {"model=" + kTestModel, "duration=0.2"});
  MujocoRobot robot(cfg.robot);
  centaur::test::NoisyHold ctrl;
  RunOutputs out;
  out.log_path = (dir / "log.h5").string();
  runSimulation(robot, ctrl, cfg, out, "test");
  std::vector<hsize_t> dims;
  const auto t = readDataset(out.log_path, "t", &dims);
  ASSERT_EQ(dims.size(), 1u);
  ASSERT_EQ(dims[0], 200u);
  for (std::size_t k = 0; k < t.size(); ++k) EXPECT_NEAR(t[k], 0.001 * static_cast<double>(k), 1e-12);
  readDataset(out.log_path, "q", &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{200, 2}));
  readDataset(out.log_path, "wheel_force", &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{200, 4, 3}));
  const auto quat = readDataset(out.log_path, "imu_quat", &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{200, 4}));
  EXPECT_NEAR(quat[0], 1.0, 1e-6);  // w first: the test robot starts level
  // The wheel forces carry the robot's weight (14 kg) once it has settled.
  const auto wf = readDataset(out.log_path, "wheel_force");
  double fz = 0.0;
  for (int k = 0; k < 4; ++k) fz += wf[(199 * 4 + k) * 3 + 2];
  EXPECT_NEAR(fz, 14.0 * 9.81, 0.05 * 14.0 * 9.81);
  const std::string config = readStringAttribute(out.log_path, "config");
  EXPECT_NE(config.find("control_decimation: 2"), std::string::npos) << config;
  EXPECT_TRUE(fs::exists(configPathFor(out.log_path)));
  fs::remove_all(dir);
}

TEST(SimRunner, UnknownKeyIsAnInputErrorNamingFileAndKeyAndNoOutputIsLeft) {
  const fs::path dir = tempDir("badkey");
  const std::string cfg = (dir / "bad.yaml").string();
  std::ofstream(cfg) << "duration: 0.1\nworld:\n  wal_x: 1.0\n";
  RunOutputs out;
  out.log_path = (dir / "log.h5").string();
  try {
    runScenario(*findScenario("stand"), cfg, {}, {}, out);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("bad.yaml"), std::string::npos) << msg;
    EXPECT_NE(msg.find("world.wal_x"), std::string::npos) << msg;
  }
  EXPECT_FALSE(fs::exists(out.log_path));
  EXPECT_FALSE(fs::exists(configPathFor(out.log_path)));
  fs::remove_all(dir);
}

TEST(SimRunner, OutOfRangeValueIsAnInputErrorNamingTheRange) {
  const fs::path dir = tempDir("range");
  const std::string cfg = (dir / "range.yaml").string();
  std::ofstream(cfg) << "physics:\n  timestep: 0.5\n";
  RunOutputs out;
  out.log_path = (dir / "log.h5").string();
  try {
    runScenario(*findScenario("stand"), cfg, {}, {}, out);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("range.yaml"), std::string::npos) << msg;
    EXPECT_NE(msg.find("physics.timestep"), std::string::npos) << msg;
    EXPECT_NE(msg.find("[1e-05, 0.01]"), std::string::npos) << msg;
  }
  // A bad controller key (scenario section) and a bad --set are caught the same way.
  EXPECT_THROW(runScenario(*findScenario("stand"), "", {"controller.gains.leg.kp=-1"}, {}, out), InputError);
  EXPECT_THROW(runScenario(*findScenario("stand"), "", {"controller.gainz=1"}, {}, out), InputError);
  EXPECT_FALSE(fs::exists(out.log_path));
  fs::remove_all(dir);
}

TEST(Renderer, SnapshotOfTheTestRobotIsNotBlank) {
  SimConfig cfg = loadSimConfig("", "", {"model=" + kTestModel});
  MujocoRobot robot(cfg.robot);
  Renderer renderer(robot.model(), 320, 240, "side");
  const auto& rgb = renderer.render(robot.data());
  ASSERT_EQ(rgb.size(), 320u * 240u * 3u);
  double mean = 0.0, mean2 = 0.0;
  for (auto v : rgb) {
    mean += v;
    mean2 += static_cast<double>(v) * v;
  }
  mean /= static_cast<double>(rgb.size());
  const double variance = mean2 / static_cast<double>(rgb.size()) - mean * mean;
  EXPECT_GT(variance, 100.0);
  // The robot's blue pelvis box is in view: pixels clearly bluer than red and green.
  int blue = 0;
  for (std::size_t p = 0; p < rgb.size(); p += 3) {
    if (rgb[p + 2] > rgb[p] + 40 && rgb[p + 2] > rgb[p + 1] + 40) ++blue;
  }
  EXPECT_GT(blue, 320 * 240 / 100) << "the pelvis should cover more than 1% of the image";
  const fs::path dir = tempDir("png");
  writePng((dir / "snap.png").string(), rgb, 320, 240);
  EXPECT_GT(fs::file_size(dir / "snap.png"), 1000u);
  fs::remove_all(dir);
}

TEST(SimConfig, ShippedStandConfigEqualsTheEmbeddedDefaults) {
  const std::string shipped = std::string(CENTAUR_SOURCE_DIR) + "/config/sim_stand.yaml";
  const Scenario* stand = findScenario("stand");
  ASSERT_NE(stand, nullptr);
  const SimConfig a = loadSimConfig(stand->defaults_yaml, shipped, {});
  const SimConfig b = loadSimConfig(stand->defaults_yaml, "", {});
  EXPECT_EQ(toYamlString(a.effective), toYamlString(b.effective));
  // and the shipped file alone (without the scenario defaults) already holds every controller key
  const SimConfig c = loadSimConfig("", shipped, {});
  EXPECT_EQ(toYamlString(c.effective), toYamlString(b.effective));
}
