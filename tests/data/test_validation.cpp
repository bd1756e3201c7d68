// ctest-labels: unit
// Every dataset a reader accepts is validated (data/hdf5.hpp, primitive_io, arm_trajectory_io, sim_log_file):
// the same answers from a file and from its image in memory; sim logs and arm trajectories refused for NaN,
// time axes, quaternions, bounds and periods, naming the file and the dataset; shapes beyond the limits
// refused before anything is allocated.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <functional>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <tuple>

#include "common/error.hpp"
#include "data/arm_trajectory_io.hpp"
#include "data/hdf5.hpp"
#include "data/primitive_io.hpp"
#include "data/sim_log_file.hpp"
#include "support/synthetic_primitive.hpp"
#include "support/temp_dir.hpp"

using namespace centaur::data;
using centaur::InputError;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The message of `f`'s InputError, "" if it does not throw one.
template <class F>
std::string refusal(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

ArmTrajectory arm() {
  ArmTrajectory tr;
  const int n = 101;
  tr.joint_names = {"j1", "j2", "j3", "j4", "j5", "j6", "j7"};
  tr.period = 1.0;
  tr.t = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
  tr.q = RowMatrix::Zero(n, 7), tr.qd = RowMatrix::Zero(n, 7), tr.qdd = RowMatrix::Zero(n, 7);
  tr.tau = RowMatrix::Zero(n, 7), tr.h_ang = RowMatrix::Zero(n, 3), tr.ee_pos = RowMatrix::Zero(n, 3);
  tr.knot_t = Eigen::VectorXd::LinSpaced(5, 0.0, 1.0);
  tr.knot_x = RowMatrix::Zero(5, 14);
  tr.knot_u = RowMatrix::Zero(4, 7);
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(7);
  tr.q_min = -one, tr.q_max = one, tr.qd_max = one, tr.tau_max = one;
  tr.q_min_model = -one, tr.q_max_model = one, tr.qd_max_model = one, tr.tau_max_model = one;
  tr.solve.status = "solved";
  return tr;
}

/// A log of `n` samples and 2 joints; `edit` may change any column before writing.
void writeLog(const std::string& path, std::size_t n,
              const std::function<void(std::map<std::string, std::vector<double>>&)>& edit = {}) {
  SimLogHeader h;
  h.joint_names = {"a", "b"};
  h.contact_bodies = {"w"};
  h.scenario = "stand";
  h.samples = n;
  std::map<std::string, std::vector<double>> cols;
  for (const LogDataset& d : simLogDatasets()) {
    std::size_t size = 1;
    for (auto e : logDatasetDims(d, h)) size *= e;
    auto& v = cols[d.name];
    v.assign(size, 0.0);
    if (std::string(d.name) == "t") {
      for (std::size_t i = 0; i < n; ++i) v[i] = 0.001 * static_cast<double>(i);
    }
    if (std::string(d.name).find("quat") != std::string::npos) {
      for (std::size_t i = 0; i < size; i += 4) v[i] = 1.0;
    }
  }
  if (edit) edit(cols);
  std::map<std::string, const std::vector<double>*> data;
  for (auto& [k, v] : cols) data[k] = &v;
  writeSimLog(path, h, data);
}

}  // namespace

TEST(Validation, AFileAndItsImageInMemoryReadTheSame) {
  centaur_test::TempDir dir;
  const std::string path = dir.file("p.h5");
  writePrimitive(path, centaur::test::makeSyntheticJump("squat-jump"));
  const std::string image = bytes(path);
  const Primitive a = readPrimitive(path, "squat-jump");
  const Primitive b = readPrimitive(FileImage{image.data(), image.size(), "image.h5"}, "squat-jump");
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.force, b.force);
  EXPECT_EQ(a.solve.status, b.solve.status);
  const std::string bad = image.substr(0, image.size() / 3);
  EXPECT_NE(refusal([&] { readPrimitives(FileImage{bad.data(), bad.size(), "cut.h5"}); }).find("cut.h5"),
            std::string::npos);
  EXPECT_NE(refusal([&] { readPrimitives(FileImage{"junk", 4, "junk.h5"}); }).find("junk.h5"), std::string::npos);
}

// Variable-length strings live in global heap collections ("GCOL"), which libhdf5 1.10 walks trusting their
// sizes: a free-space block of 0 bytes makes it loop forever, an object larger than its collection makes it copy
// out of bounds. Such collections are refused before libhdf5 reads them, from a file and from an image.
TEST(Validation, CorruptGlobalHeapsAreRefusedBeforeLibhdf5WalksThem) {
  centaur_test::TempDir dir;
  const std::string path = dir.file("p.h5");
  writePrimitive(path, centaur::test::makeSyntheticJump("squat-jump"));
  const std::string good = bytes(path);
  EXPECT_EQ(h5::globalHeapDefect(reinterpret_cast<const unsigned char*>(good.data()), good.size()), "");
  const std::size_t gcol = good.find("GCOL");
  ASSERT_NE(gcol, std::string::npos);
  // Walk the objects (8-byte lengths, as our writer uses) to the free space, object index 0.
  std::size_t at = gcol + 16, free_at = 0;
  while (at + 16 <= good.size()) {
    const auto index = static_cast<unsigned char>(good[at]) | static_cast<unsigned char>(good[at + 1]) << 8;
    std::uint64_t size = 0;
    for (int b = 7; b >= 0; --b) size = size << 8 | static_cast<unsigned char>(good[at + 8 + b]);
    if (index == 0) {
      free_at = at;
      break;
    }
    at += 16 + (size + 7) / 8 * 8;
  }
  ASSERT_GT(free_at, gcol);
  auto corrupted = [&](std::size_t where, std::uint64_t size) {  // the object's declared size set to `size`
    std::string b = good;
    for (int i = 0; i < 8; ++i) b[where + 8 + i] = static_cast<char>(size >> (8 * i) & 0xff);
    std::ofstream(dir.file("bad.h5"), std::ios::binary | std::ios::trunc) << b;
    return b;
  };
  for (const auto& [where, value, what] : {std::tuple<std::size_t, std::uint64_t, const char*>{free_at, 0, "free space"},
                                           {free_at, 8, "free space"},
                                           {free_at, 1 << 20, "free space"},
                                           {gcol + 16, 1 << 20, "object 1 "}}) {
    const std::string bad = corrupted(where, value);
    const std::string from_file = refusal([&] { readPrimitives(dir.file("bad.h5")); });
    const std::string from_image = refusal([&] { readPrimitives(FileImage{bad.data(), bad.size(), "image.h5"}); });
    EXPECT_NE(from_file.find("bad.h5"), std::string::npos) << from_file;
    EXPECT_NE(from_file.find(what), std::string::npos) << from_file;
    EXPECT_NE(from_image.find("image.h5"), std::string::npos) << from_image;
    EXPECT_NE(from_image.find("global heap"), std::string::npos) << from_image;
  }
}

TEST(Validation, SimLogsAreCheckedOnOpenAndOnEveryRead) {
  centaur_test::TempDir dir;
  writeLog(dir.file("ok.h5"), 5);
  const SimLogFile ok(dir.file("ok.h5"));
  EXPECT_EQ(ok.time().size(), 5);
  EXPECT_EQ(ok.read("imu_quat").rows(), 5);
  writeLog(dir.file("nan.h5"), 5, [](auto& c) { c["tau_cmd"][7] = kNaN; });
  const SimLogFile nan(dir.file("nan.h5"));  // opening reads the header and t only
  const std::string m = refusal([&] { nan.read("tau_cmd"); });
  EXPECT_NE(m.find("nan.h5"), std::string::npos) << m;
  EXPECT_NE(m.find("tau_cmd"), std::string::npos) << m;
  EXPECT_NE(m.find("row 3, column 1"), std::string::npos) << m;
  writeLog(dir.file("back.h5"), 5, [](auto& c) { c["t"][3] = 0.0; });
  EXPECT_NE(refusal([&] { SimLogFile l(dir.file("back.h5")); }).find("does not increase"), std::string::npos);
  writeLog(dir.file("inf.h5"), 5, [](auto& c) { c["imu_quat"][8] = std::numeric_limits<double>::infinity(); });
  EXPECT_NE(refusal([&] { SimLogFile(dir.file("inf.h5")).read("imu_quat"); }).find("imu_quat"), std::string::npos);
  writeLog(dir.file("empty.h5"), 0);
  EXPECT_NE(refusal([&] { SimLogFile l(dir.file("empty.h5")); }).find("0 samples"), std::string::npos);
  const std::string image = bytes(dir.file("ok.h5"));
  EXPECT_EQ(SimLogFile(FileImage{image.data(), image.size(), "log"}).read("q").rows(), 5);
}

TEST(Validation, ArmTrajectoriesAreChecked) {
  centaur_test::TempDir dir;
  writeArmTrajectory(dir.file("ok.h5"), arm());
  EXPECT_EQ(readArmTrajectory(dir.file("ok.h5")).q.rows(), 101);
  const std::vector<std::pair<std::function<void(ArmTrajectory&)>, std::string>> cases = {
      {[](ArmTrajectory& t) { t.q(50, 3) = kNaN; }, "arm-flywheel/q"},
      {[](ArmTrajectory& t) { t.period = 2.0; }, "arm-flywheel/t"},
      {[](ArmTrajectory& t) { t.t[10] = t.t[9]; }, "does not increase"},
      {[](ArmTrajectory& t) { t.q_min[2] = 5.0; }, "q_min"},
      {[](ArmTrajectory& t) { t.tau_max[0] = 0.0; }, "limits must be > 0"},
      {[](ArmTrajectory& t) { t.period = kNaN; }, "period"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    ArmTrajectory t = arm();
    cases[i].first(t);
    const std::string path = dir.file("bad" + std::to_string(i) + ".h5");
    writeArmTrajectory(path, t);
    const std::string m = refusal([&] { readArmTrajectory(path); });
    EXPECT_NE(m.find(path), std::string::npos) << i << ": " << m;
    EXPECT_NE(m.find(cases[i].second), std::string::npos) << i << ": " << m;
  }
}

TEST(Validation, ShapesBeyondTheLimitsAreRefusedBeforeAllocation) {
  centaur_test::TempDir dir;
  const std::string path = dir.file("huge.h5");
  // A dataset of 2^40 doubles (8 TiB) in a file of a few kB: chunked, never written.
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[2] = {hsize_t{1} << 20, hsize_t{1} << 20}, chunk[2] = {64, 64};
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, 2, chunk);
  const hid_t space = H5Screate_simple(2, dims, nullptr);
  H5Dclose(H5Dcreate2(f, "m", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT));
  H5Sclose(space), H5Pclose(dcpl), H5Fclose(f);
  const h5::Reader r(path, "a test file");
  const std::string m = refusal([&] { r.matrix(r.file(), "m", "m", {0, 0}); });
  EXPECT_NE(m.find("more than the limit"), std::string::npos) << m;
  EXPECT_NE(m.find("(1048576, 1048576)"), std::string::npos) << m;
}

TEST(Validation, TheFormatAttributeSaysWhatAFileIs) {
  centaur_test::TempDir dir;
  writeLog(dir.file("log.h5"), 3);
  EXPECT_NE(refusal([&] { readPrimitives(dir.file("log.h5")); }).find("simulation log"), std::string::npos);
  writePrimitive(dir.file("p.h5"), centaur::test::makeSyntheticJump("j"));
  const hid_t f = H5Fopen(dir.file("p.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const int version = 7;
  const hid_t a = H5Aopen(f, "format_version", H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_INT, &version);
  H5Aclose(a), H5Fclose(f);
  EXPECT_NE(refusal([&] { readPrimitives(dir.file("p.h5")); }).find("format_version"), std::string::npos);
}
