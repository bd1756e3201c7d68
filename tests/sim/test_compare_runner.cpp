// ctest-labels: sim integration
// sim::runBatch, the thread pool behind `centaur compare`: runs on 2 threads give bitwise the same logs as
// one after the other (nothing shared between runs), runs of one exclusive group never overlap, a failing run
// is reported with its status and message without stopping the others.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include "common/error.hpp"
#include "sim/compare_runner.hpp"
#include "sim/scenario.hpp"
#include "support/temp_dir.hpp"
#include "noisy_hold.hpp"

using namespace centaur;
using namespace centaur::sim;

namespace {

const std::string kTestModel = std::string(CENTAUR_SOURCE_DIR) + "/tests/testdata/sim_test_robot.xml";

// How many controller factories run at the same time, per group label ("" = ungrouped), and the maximum seen.
std::atomic<int> g_active[2];
std::atomic<int> g_max_active[2];


const ScenarioRegistrar kRegistrar{Scenario{
    "batch-test", "a scenario for the batch runner test",
    "duration: 0.3\nmodel: " + kTestModel +
        "\nsensors: {noise: {q: 0.001, gyro: 0.01, orientation: 0.002}, latency_periods: 1, seed: 3}\n"
        "controller: {gain: 1.0, hold_s: 0.0, slot: 0}\n",
    {{"mode", "changes the gain", "a", {"a", "b", "c"}, false}},
    [](ScenarioContext& ctx) -> std::unique_ptr<Controller> {
      double gain = 1.0, hold = 0.0;
      int slot = 0;
      ctx.controller_config.get("gain", gain, 0.1, 10.0);
      ctx.controller_config.get("hold_s", hold, 0.0, 1.0);
      ctx.controller_config.get("slot", slot, 0, 1);
      ctx.controller_config.finish();
      if (hold > 0.0) {  // stay inside the factory a while, counting who else is in one
        const int now = ++g_active[slot];
        int seen = g_max_active[slot].load();
        while (now > seen && !g_max_active[slot].compare_exchange_weak(seen, now)) {
        }
        std::this_thread::sleep_for(std::chrono::duration<double>(hold));
        --g_active[slot];
      }
      const std::string& mode = ctx.options.at("mode");
      return std::make_unique<centaur::test::NoisyHold>(gain * (mode == "a" ? 1.0 : mode == "b" ? 1.5 : 2.0));
    }}};

std::vector<double> readDataset(const std::string& file, const std::string& name) {
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  hid_t ds = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(ds, 0) << name;
  hid_t sp = H5Dget_space(ds);
  const hssize_t n = H5Sget_simple_extent_npoints(sp);
  std::vector<double> out(static_cast<std::size_t>(n));
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  H5Sclose(sp);
  H5Dclose(ds);
  H5Fclose(f);
  return out;
}

std::vector<BatchRun> sixRuns(const centaur_test::TempDir& dir, const std::string& tag) {
  std::vector<BatchRun> runs;
  for (const std::string mode : {"a", "b", "c"}) {
    for (const std::string seed : {"3", "4"}) {
      BatchRun r;
      r.label = mode + seed;
      r.scenario = "batch-test";
      r.options = {{"mode", mode}};
      r.overrides = {"sensors.seed=" + seed};
      r.outputs.log_path = dir.file(tag + "-" + r.label + ".h5");
      runs.push_back(r);
    }
  }
  return runs;
}

}  // namespace

TEST(CompareRunner, ThreadCount) {
  EXPECT_EQ(batchThreads(4, 2), 2);
  EXPECT_EQ(batchThreads(1, 8), 1);
  EXPECT_EQ(batchThreads(3, 0), 1);
  const int hw = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  EXPECT_EQ(batchThreads(0, 100), std::min(hw, 100));
}

TEST(CompareRunner, ParallelRunsGiveBitwiseTheSameLogsAsSerialRuns) {
  const centaur_test::TempDir dir("compare-runner");
  const std::vector<BatchRun> serial = sixRuns(dir, "serial"), parallel = sixRuns(dir, "parallel");
  const auto rs = runBatch(serial, 1);
  std::size_t last_done = 0;
  BatchCallbacks cb;
  std::vector<int> started(parallel.size(), 0);
  cb.started = [&](std::size_t i) { ++started[i]; };
  cb.finished = [&](std::size_t, const BatchResult&, std::size_t done, std::size_t total) {
    EXPECT_EQ(done, last_done + 1);
    EXPECT_EQ(total, parallel.size());
    last_done = done;
  };
  const auto rp = runBatch(parallel, 2, cb);
  EXPECT_EQ(last_done, parallel.size());
  for (int s : started) EXPECT_EQ(s, 1);
  ASSERT_EQ(rs.size(), serial.size());
  ASSERT_EQ(rp.size(), parallel.size());
  for (std::size_t i = 0; i < serial.size(); ++i) {
    ASSERT_EQ(rs[i].status, BatchResult::Status::Completed) << rs[i].error;
    ASSERT_EQ(rp[i].status, BatchResult::Status::Completed) << rp[i].error;
    EXPECT_EQ(rp[i].summary.control_periods, 300);
    EXPECT_EQ(rp[i].summary.max_torque_ratio, rs[i].summary.max_torque_ratio) << serial[i].label;
    for (const std::string name : {"q", "qd", "tau_applied", "imu_quat", "imu_omega", "base_pos"}) {
      const auto a = readDataset(serial[i].outputs.log_path, name);
      const auto b = readDataset(parallel[i].outputs.log_path, name);
      ASSERT_FALSE(a.empty());
      EXPECT_TRUE(a == b) << serial[i].label << ": " << name << " differs between the serial and the parallel run";
    }
  }
  // The runs differ from each other (mode and seed matter), so the comparison above is not vacuous.
  EXPECT_NE(readDataset(serial[0].outputs.log_path, "q"), readDataset(serial[1].outputs.log_path, "q"));
  EXPECT_NE(readDataset(serial[0].outputs.log_path, "q"), readDataset(serial[2].outputs.log_path, "q"));
}

TEST(CompareRunner, RunsOfOneExclusiveGroupNeverOverlap) {
  g_active[0] = g_active[1] = 0;
  g_max_active[0] = g_max_active[1] = 0;
  // The same four runs twice on 2 threads: slot 0 without a group (they overlap: the pool runs in parallel),
  // slot 1 in the exclusive group "solver" (they must not).
  for (int slot = 0; slot < 2; ++slot) {
    std::vector<BatchRun> runs(4);
    for (auto& r : runs) {
      r.scenario = "batch-test";
      r.overrides = {"duration=0.01", "controller.hold_s=0.15", "controller.slot=" + std::to_string(slot)};
      if (slot == 1) r.exclusive_group = "solver";
    }
    const auto results = runBatch(runs, 2);
    for (const auto& r : results) ASSERT_EQ(r.status, BatchResult::Status::Completed) << r.error;
  }
  EXPECT_EQ(g_max_active[0].load(), 2) << "ungrouped runs never overlapped: the pool did not run in parallel";
  EXPECT_EQ(g_max_active[1].load(), 1) << "two runs of the exclusive group were inside their factory at once";
}

TEST(CompareRunner, FailingRunsAreReportedAndDoNotStopTheOthers) {
  const centaur_test::TempDir dir("compare-runner-fail");
  std::vector<BatchRun> runs(4);
  runs[0].scenario = "no-such-scenario";
  runs[1].scenario = "batch-test";
  runs[1].overrides = {"controller.gian=2"};  // typo: unknown key
  runs[2].scenario = "batch-test";
  std::filesystem::create_directories(dir.file("taken.h5"));  // the log path is a directory: I/O failure
  runs[2].outputs.log_path = dir.file("taken.h5");
  runs[3].scenario = "batch-test";
  runs[3].outputs.log_path = dir.file("ok.h5");
  const auto r = runBatch(runs, 2);
  EXPECT_EQ(r[0].status, BatchResult::Status::BadInput);
  EXPECT_NE(r[0].error.find("no-such-scenario"), std::string::npos) << r[0].error;
  EXPECT_NE(r[0].error.find("batch-test"), std::string::npos) << "the message lists the registered scenarios";
  EXPECT_EQ(r[1].status, BatchResult::Status::BadInput);
  EXPECT_NE(r[1].error.find("gian"), std::string::npos) << r[1].error;
  EXPECT_EQ(r[2].status, BatchResult::Status::RuntimeFailure) << r[2].error;
  EXPECT_FALSE(r[2].error.empty());
  EXPECT_EQ(r[3].status, BatchResult::Status::Completed) << r[3].error;
  EXPECT_TRUE(std::filesystem::exists(dir.file("ok.h5")));
}
