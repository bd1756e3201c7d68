// ctest-labels: unit
// The simulation log format: what writeSimLog writes SimLogFile reads back exactly; a file that is not a log
// (a primitive file, a log with a wrong shape, a FIFO, a directory) is an InputError naming the file and the
// dataset or attribute, refused before any dataset is read.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "data/hdf5.hpp"
#include "data/primitive_io.hpp"
#include "data/sim_log_file.hpp"
#include "support/synthetic_primitive.hpp"
#include "support/temp_dir.hpp"

namespace data = centaur::data;
using centaur::InputError;
using centaur::RuntimeError;

namespace {

/// A log of N samples, n joints, c contact bodies whose every value encodes (dataset, sample, column).
struct FakeLog {
  data::SimLogHeader header;
  std::map<std::string, std::vector<double>> values;
  std::map<std::string, const std::vector<double>*> pointers() const {
    std::map<std::string, const std::vector<double>*> out;
    for (const auto& [k, v] : values) out[k] = &v;
    return out;
  }
};

FakeLog fakeLog(std::size_t N, std::size_t n, std::size_t c) {
  FakeLog log;
  for (std::size_t j = 0; j < n; ++j) log.header.joint_names.push_back("joint_" + std::to_string(j));
  for (std::size_t k = 0; k < c; ++k) log.header.contact_bodies.push_back("wheel_" + std::to_string(k + 1));
  log.header.config_yaml = "duration: 0.1\n";
  log.header.scenario = "fake";
  log.header.samples = N;
  int tag = 0;
  for (const data::LogDataset& d : data::simLogDatasets()) {
    std::size_t count = 1;
    for (auto x : data::logDatasetDims(d, log.header)) count *= x;
    std::vector<double>& v = log.values[d.name];
    for (std::size_t i = 0; i < count; ++i) v.push_back(1000.0 * tag + 0.5 * static_cast<double>(i));
    ++tag;
  }
  return log;
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no InputError>";
}

}  // namespace

TEST(SimLogFile, RoundTripOfEveryDatasetAndTheHeader) {
  const centaur_test::TempDir dir("sim-log");
  const FakeLog log = fakeLog(7, 3, 4);
  const std::string path = dir.file("log.h5");
  data::writeSimLog(path, log.header, log.pointers());
  const data::SimLogFile f(path);
  EXPECT_EQ(f.header().joint_names, log.header.joint_names);
  EXPECT_EQ(f.header().contact_bodies, log.header.contact_bodies);
  EXPECT_EQ(f.header().config_yaml, log.header.config_yaml);
  EXPECT_EQ(f.header().scenario, "fake");
  EXPECT_EQ(f.header().samples, 7u);
  for (const data::LogDataset& d : data::simLogDatasets()) {
    const data::RowMatrix m = f.read(d.name);
    ASSERT_EQ(m.rows(), 7) << d.name;
    const std::vector<double>& want = log.values.at(d.name);
    ASSERT_EQ(static_cast<std::size_t>(m.size()), want.size()) << d.name;
    for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(m.data()[i], want[i]) << d.name << " " << i;
  }
  EXPECT_EQ(f.read("wheel_force").cols(), 12);  // c x 3, contact-major
  EXPECT_EQ(f.time().size(), 7);
  EXPECT_NE(messageOf([&] { (void)f.read("nonsense"); }).find("nonsense"), std::string::npos);
}

TEST(SimLogFile, MissingOrMisSizedDatasetIsNotWritten) {
  const centaur_test::TempDir dir("sim-log");
  FakeLog log = fakeLog(5, 2, 4);
  log.values["q"].pop_back();
  EXPECT_THROW(data::writeSimLog(dir.file("log.h5"), log.header, log.pointers()), RuntimeError);
  EXPECT_TRUE(dir.entries().empty()) << "no file and no temporary left behind";
}

TEST(SimLogFile, APrimitiveFileIsNotALog) {
  const centaur_test::TempDir dir("sim-log");
  const std::string path = dir.file("primitives.h5");
  data::writePrimitive(path, centaur::test::makeSyntheticJump("squat-jump"));
  const std::string msg = messageOf([&] { data::SimLogFile f(path); });
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("format"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not a centaur simulation log"), std::string::npos) << msg;
}

TEST(SimLogFile, AShapeThatDisagreesWithTheHeaderNamesTheDataset) {
  const centaur_test::TempDir dir("sim-log");
  FakeLog log = fakeLog(6, 2, 4);
  const std::string path = dir.file("log.h5");
  data::writeSimLog(path, log.header, log.pointers());
  // Rewrite the joint list with one more joint: every N x n dataset now disagrees with it.
  {
    const data::h5::QuietErrors quiet;
    const data::h5::Writer w(path);
    data::h5::Id file = w.openFile(path);
    ASSERT_GE(H5Adelete(file.get(), "joint_names"), 0);
    w.stringListAttribute(file.get(), "joint_names", {"a", "b", "c"});
  }
  const std::string msg = messageOf([&] { data::SimLogFile f(path); });
  EXPECT_NE(msg.find("key 'q'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(6, 2)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(6, 3)"), std::string::npos) << msg;
}

TEST(Hdf5Reader, RefusesDirectoriesFifosMissingAndForeignFilesAtOnce) {
  const centaur_test::TempDir dir("h5-reader");
  const std::string fifo = dir.file("fifo.h5");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // A FIFO with no writer would block an open(): the reader must refuse it before opening.
  EXPECT_NE(messageOf([&] { data::h5::Reader r(fifo, "x"); }).find("not a regular file"), std::string::npos);
  EXPECT_NE(messageOf([&] { data::h5::Reader r(dir.path().string(), "x"); }).find("is a directory"),
            std::string::npos);
  EXPECT_NE(messageOf([&] { data::h5::Reader r(dir.file("none.h5"), "a log"); }).find("no such file (expected a log)"),
            std::string::npos);
  centaur::writeTextFileAtomic(dir.file("text.h5"), "not hdf5\n");
  EXPECT_NE(messageOf([&] { data::h5::Reader r(dir.file("text.h5"), "x"); }).find("not an HDF5 file"),
            std::string::npos);
}

TEST(Hdf5Reader, ReadsFixedAndVariableLengthStringsAndChecksShapesFirst) {
  const centaur_test::TempDir dir("h5-reader");
  const std::string path = dir.file("f.h5");
  {
    const data::h5::QuietErrors quiet;
    const data::h5::Writer w(path);
    data::h5::Id file = w.createFile(path);
    w.stringAttribute(file.get(), "fixed", "fixed text", true);
    w.stringAttribute(file.get(), "variable", "variable text");
    w.stringListAttribute(file.get(), "list", {"a", "bc"});
    w.vectorAttribute(file.get(), "vec", std::vector<double>{1.0, 2.0, 3.0});
    const std::vector<double> m = {1, 2, 3, 4, 5, 6};
    w.doubles(file.get(), "m", {2, 3}, m.data(), {"m", nullptr, "a 2 x 3 matrix"});
  }
  const data::h5::Reader r(path, "x");
  EXPECT_EQ(r.text(r.file(), "fixed", "fixed"), "fixed text");
  EXPECT_EQ(r.text(r.file(), "variable", "variable"), "variable text");
  EXPECT_EQ(r.textList(r.file(), "list", "list"), (std::vector<std::string>{"a", "bc"}));
  EXPECT_EQ(r.numbers(r.file(), "vec", "vec", 3), (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_NE(messageOf([&] { r.numbers(r.file(), "vec", "vec", 2); }).find("has 3 values, expected 2"),
            std::string::npos);
  const data::RowMatrix m = r.matrix(r.file(), "m", "m", {2, 3});
  EXPECT_EQ(m(1, 2), 6.0);
  EXPECT_NE(messageOf([&] { r.matrix(r.file(), "m", "m", {3, 0}); }).find("shape (2, 3), expected (3, any)"),
            std::string::npos);
  EXPECT_NE(messageOf([&] { r.text(r.file(), "vec", "vec"); }).find("not a string"), std::string::npos);
}
