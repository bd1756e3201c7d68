// ctest-labels: unit
// The HDF5 primitive database: exact round trip, append/replace, atomic writes, clear errors on bad files.
#include <gtest/gtest.h>

#include "support/temp_dir.hpp"
#include <hdf5.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "common/error.hpp"
#include "data/primitive_io.hpp"
#include "support/synthetic_primitive.hpp"

namespace fs = std::filesystem;
using centaur::InputError;
using centaur::RuntimeError;
using centaur::data::Primitive;
using centaur::data::WriteMode;
namespace data = centaur::data;

namespace {

using centaur_test::TempDir;

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Exact equality of every field (datasets bit for bit, metadata exactly).
void expectSame(const Primitive& a, const Primitive& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_TRUE(a.t == b.t) << "t";
  EXPECT_TRUE(a.q == b.q) << "q";
  EXPECT_TRUE(a.nu == b.nu) << "nu";
  EXPECT_TRUE(a.base_pos == b.base_pos) << "base_pos";
  EXPECT_TRUE(a.base_quat == b.base_quat) << "base_quat";
  EXPECT_TRUE(a.base_vel == b.base_vel) << "base_vel";
  EXPECT_TRUE(a.base_omega == b.base_omega) << "base_omega";
  EXPECT_TRUE(a.foot_pos == b.foot_pos) << "foot_pos";
  EXPECT_TRUE(a.foot_pos_rel == b.foot_pos_rel) << "foot_pos_rel";
  EXPECT_TRUE(a.foot_vel_rel == b.foot_vel_rel) << "foot_vel_rel";
  EXPECT_TRUE(a.force == b.force) << "force";
  EXPECT_TRUE(a.contact == b.contact) << "contact";
  EXPECT_TRUE(a.tau == b.tau) << "tau";
  EXPECT_TRUE(a.knot_t == b.knot_t) << "knots/t";
  EXPECT_TRUE(a.knot_x == b.knot_x) << "knots/x";
  EXPECT_TRUE(a.knot_u == b.knot_u) << "knots/u";
  EXPECT_TRUE(a.knot_dt == b.knot_dt) << "knots/dt";
  EXPECT_EQ(a.solve.status, b.solve.status);
  EXPECT_EQ(a.solve.iterations, b.solve.iterations);
  EXPECT_EQ(a.solve.solve_time_s, b.solve.solve_time_s);
  EXPECT_EQ(a.solve.cost, b.solve.cost);
  EXPECT_EQ(a.solve.max_constraint_violation, b.solve.max_constraint_violation);
  EXPECT_EQ(a.solve.backend, b.solve.backend);
  EXPECT_EQ(a.config_yaml, b.config_yaml);
  EXPECT_EQ(a.scalars, b.scalars);
  EXPECT_EQ(a.vectors, b.vectors);
  EXPECT_EQ(a.strings, b.strings);
}

template <class F>
std::string inputErrorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("WRONG EXCEPTION TYPE: ") + e.what();
  }
  return "NO EXCEPTION";
}

/// Delete one link (dataset or group) of an existing file with the HDF5 API, to fabricate bad files.
void deleteLink(const std::string& path, const std::string& link) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_GE(H5Ldelete(f, link.c_str(), H5P_DEFAULT), 0);
  H5Fclose(f);
}

/// Replace dataset `link` by a double dataset of shape `dims`.
void replaceDataset(const std::string& path, const std::string& link, std::vector<hsize_t> dims) {
  deleteLink(path, link);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t ds = H5Dcreate2(f, link.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(ds, 0);
  H5Dclose(ds);
  H5Sclose(space);
  H5Fclose(f);
}

}  // namespace

TEST(PrimitiveIo, RoundTripPreservesEveryDatasetAndAttribute) {
  TempDir dir;
  const Primitive jump = centaur::test::makeSyntheticJump("squat-jump");
  const std::string path = dir.file("jump.h5");
  data::writePrimitives(path, {jump}, WriteMode::Replace);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"jump.h5"});  // no temporary left behind
  EXPECT_EQ(data::listPrimitives(path), std::vector<std::string>{"squat-jump"});
  const std::vector<Primitive> back = data::readPrimitives(path);
  ASSERT_EQ(back.size(), 1u);
  expectSame(jump, back[0]);
  expectSame(jump, data::readPrimitive(path, "squat-jump"));
}

// Files written before the solver backend was recorded have no solve_backend attribute: they read as unknown.
TEST(PrimitiveIo, AFileWithoutTheSolverBackendReadsItAsUnknown) {
  TempDir dir;
  Primitive jump = centaur::test::makeSyntheticJump("squat-jump");
  ASSERT_EQ(jump.solve.backend, "riccati");
  const std::string path = dir.file("jump.h5");
  data::writePrimitives(path, {jump}, WriteMode::Replace);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_GE(H5Adelete_by_name(f, "squat-jump", "solve_backend", H5P_DEFAULT), 0);
  H5Fclose(f);
  const Primitive back = data::readPrimitive(path, "squat-jump");
  EXPECT_EQ(back.solve.backend, "");
  jump.solve.backend.clear();
  expectSame(jump, back);
}

TEST(PrimitiveIo, EmptyKnotsAndLargeConfigRoundTrip) {
  TempDir dir;
  Primitive p = centaur::test::makeSyntheticJump("bare");
  p.knot_t.resize(0);
  p.knot_x.resize(0, 37);
  p.knot_u.resize(0, 31);
  p.knot_dt.resize(0);
  p.vectors["empty"] = {};
  p.vectors["long"] = std::vector<double>(20000, 0.25);  // larger than an object header message (64 kB)
  std::ostringstream yaml;  // larger than HDF5's 64 kB compact attribute limit
  for (int i = 0; i < 5000; ++i) yaml << "key_" << i << ": " << 0.001 * i << "  # ünïcode\n";
  p.config_yaml = yaml.str();
  ASSERT_GT(p.config_yaml.size(), 100000u);
  const std::string path = dir.file("bare.h5");
  data::writePrimitive(path, p);
  expectSame(p, data::readPrimitive(path, "bare"));

  // Empty knots are empty throughout: with no node in knots/t, a knots dataset that declares values (here 10^8,
  // unallocated: a small file) is refused by its shape, before any value is read or allocated.
  for (const char* dataset : {"bare/knots/x", "bare/knots/u", "bare/knots/dt"}) {
    data::writePrimitive(path, p);
    replaceDataset(path, dataset, std::string(dataset).back() == 't' ? std::vector<hsize_t>{100000000}
                                                                     : std::vector<hsize_t>{1000000, 100});
    const std::string msg = inputErrorOf([&] { data::readPrimitive(path, "bare"); });
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find(dataset), std::string::npos) << msg;
    EXPECT_NE(msg.find("knots/t has no nodes"), std::string::npos) << msg;
  }
}

TEST(PrimitiveIo, AppendAddsGroupsKeepsOthersAndReplacesSameName) {
  TempDir dir;
  const std::string path = dir.file("db.h5");
  const Primitive a = centaur::test::makeSyntheticJump("squat-jump");
  const Primitive b = centaur::test::makeSyntheticJump("half-squat-jump", 1.0);
  // Append to a missing file creates it.
  data::writePrimitives(path, {a}, WriteMode::Append);
  data::writePrimitives(path, {b}, WriteMode::Append);
  EXPECT_EQ(data::listPrimitives(path), (std::vector<std::string>{"squat-jump", "half-squat-jump"}));
  expectSame(a, data::readPrimitive(path, "squat-jump"));
  expectSame(b, data::readPrimitive(path, "half-squat-jump"));

  // Replace the first group in place: same position, new content, the other group untouched.
  Primitive a2 = centaur::test::makeSyntheticJump("squat-jump", 2.0);
  a2.solve.status = "not_converged";
  a2.scalars["target_height"] = 0.3;
  data::writePrimitives(path, {a2}, WriteMode::Append);
  EXPECT_EQ(data::listPrimitives(path), (std::vector<std::string>{"squat-jump", "half-squat-jump"}));
  expectSame(a2, data::readPrimitive(path, "squat-jump"));
  expectSame(b, data::readPrimitive(path, "half-squat-jump"));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"db.h5"});

  // Replace mode drops everything else.
  data::writePrimitives(path, {b}, WriteMode::Replace);
  EXPECT_EQ(data::listPrimitives(path), std::vector<std::string>{"half-squat-jump"});
}

TEST(PrimitiveIo, GroupsOfAnotherKindAreNotPrimitives) {
  // An arm-flywheel trajectory (attribute kind = "arm-trajectory") may share the file: the jump readers skip it.
  TempDir dir;
  const std::string path = dir.file("db.h5");
  const Primitive a = centaur::test::makeSyntheticJump("squat-jump");
  data::writePrimitives(path, {a});
  {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    const hid_t g = H5Gcreate2(f, "arm-flywheel", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, 14);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(g, "kind", type, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attr, type, "arm-trajectory");
    H5Aclose(attr);
    H5Sclose(space);
    H5Tclose(type);
    H5Gclose(g);
    H5Fclose(f);
  }
  EXPECT_EQ(data::listPrimitives(path), std::vector<std::string>{"squat-jump"});
  ASSERT_EQ(data::readPrimitives(path).size(), 1u);
  EXPECT_THROW(data::readPrimitive(path, "arm-flywheel"), InputError);
}

TEST(PrimitiveIo, UnwritableLocationThrowsAndLeavesNothing) {
  TempDir dir;
  const std::string blocker = dir.file("not-a-directory");
  std::ofstream(blocker) << "a regular file";
  const Primitive p = centaur::test::makeSyntheticJump("squat-jump");
  EXPECT_THROW(data::writePrimitive(blocker + "/sub/out.h5", p), RuntimeError);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"not-a-directory"});

  if (::geteuid() != 0) {  // permissions do not stop root
    const std::string locked = dir.file("locked");
    fs::create_directory(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_THROW(data::writePrimitive(locked + "/out.h5", p), RuntimeError);
    fs::permissions(locked, fs::perms::owner_all);
    EXPECT_TRUE(fs::is_empty(locked));
  }
}

TEST(PrimitiveIo, FailureHalfwayRemovesTheTemporaryAndKeepsTheOldFile) {
  TempDir dir;
  const std::string path = dir.file("db.h5");
  const Primitive good = centaur::test::makeSyntheticJump("good");
  Primitive bad = centaur::test::makeSyntheticJump("bad");
  bad.force.conservativeResize(Eigen::NoChange, 11);  // detected while writing the second group

  // New file: nothing at all is left.
  try {
    data::writePrimitives(path, {good, bad});
    ADD_FAILURE() << "no exception";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("force"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_TRUE(dir.entries().empty());

  // Existing file: untouched, byte for byte, in both modes.
  data::writePrimitives(path, {good});
  const std::string before = readBytes(path);
  EXPECT_THROW(data::writePrimitives(path, {bad}, WriteMode::Append), RuntimeError);
  EXPECT_THROW(data::writePrimitives(path, {good, bad}, WriteMode::Replace), RuntimeError);
  Primitive odd_contact = good;
  odd_contact.contact(5, 2) = 0.5;
  EXPECT_THROW(data::writePrimitives(path, {odd_contact}), RuntimeError);
  Primitive reserved = good;
  reserved.scalars["solve_time_s"] = 1.0;
  EXPECT_THROW(data::writePrimitives(path, {reserved}), RuntimeError);
  EXPECT_THROW(data::writePrimitives(path, {good, good}), RuntimeError);  // duplicate name
  Primitive unnamed = good;
  unnamed.name = "a/b";
  EXPECT_THROW(data::writePrimitives(path, {unnamed}), RuntimeError);
  EXPECT_EQ(readBytes(path), before);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"db.h5"});
}

TEST(PrimitiveIo, FailedRenameRemovesTheTemporary) {
  TempDir dir;
  const std::string target = dir.file("occupied");
  fs::create_directory(target);
  std::ofstream(target + "/keep") << "x";  // a non-empty directory cannot be renamed over
  EXPECT_THROW(data::writePrimitive(target, centaur::test::makeSyntheticJump("j")), RuntimeError);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"occupied"});
}

TEST(PrimitiveIo, MissingOrForeignFilesGiveInputErrorsNamingThem) {
  TempDir dir;
  const std::string missing = dir.file("missing.h5");
  std::string msg = inputErrorOf([&] { data::readPrimitives(missing); });
  EXPECT_NE(msg.find(missing), std::string::npos) << msg;
  EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
  msg = inputErrorOf([&] { data::listPrimitives(missing); });
  EXPECT_NE(msg.find(missing), std::string::npos) << msg;

  const std::string text = dir.file("notes.h5");
  std::ofstream(text) << "this is not HDF5\n";
  msg = inputErrorOf([&] { data::readPrimitives(text); });
  EXPECT_NE(msg.find(text), std::string::npos) << msg;
  EXPECT_NE(msg.find("not an HDF5 file"), std::string::npos) << msg;

  // Append onto a foreign file refuses to clobber it.
  EXPECT_THROW(data::writePrimitive(text, centaur::test::makeSyntheticJump("j"), WriteMode::Append), InputError);
  EXPECT_EQ(readBytes(text), "this is not HDF5\n");

  // A truncated (corrupt) primitive file.
  const std::string good = dir.file("good.h5");
  data::writePrimitive(good, centaur::test::makeSyntheticJump("squat-jump"));
  const std::string bytes = readBytes(good);
  const std::string cut = dir.file("cut.h5");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  msg = inputErrorOf([&] { data::readPrimitives(cut); });
  EXPECT_NE(msg.find(cut), std::string::npos) << msg;
}

TEST(PrimitiveIo, MissingOrMisshapenDatasetGivesInputErrorNamingIt) {
  TempDir dir;
  const std::string path = dir.file("db.h5");
  data::writePrimitive(path, centaur::test::makeSyntheticJump("squat-jump"));

  deleteLink(path, "squat-jump/foot_pos");
  std::string msg = inputErrorOf([&] { data::readPrimitives(path); });
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("squat-jump/foot_pos"), std::string::npos) << msg;
  EXPECT_NE(msg.find("missing dataset"), std::string::npos) << msg;

  data::writePrimitive(path, centaur::test::makeSyntheticJump("squat-jump"));
  deleteLink(path, "squat-jump/knots/dt");
  msg = inputErrorOf([&] { data::readPrimitive(path, "squat-jump"); });
  EXPECT_NE(msg.find("squat-jump/knots/dt"), std::string::npos) << msg;

  data::writePrimitive(path, centaur::test::makeSyntheticJump("squat-jump"));
  replaceDataset(path, "squat-jump/tau", {1001, 11});
  msg = inputErrorOf([&] { data::readPrimitives(path); });
  EXPECT_NE(msg.find("squat-jump/tau"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(1001, 11)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected (1001, 12)"), std::string::npos) << msg;

  data::writePrimitive(path, centaur::test::makeSyntheticJump("squat-jump"));
  replaceDataset(path, "squat-jump/base_vel", {1000, 3});  // one row short of t
  msg = inputErrorOf([&] { data::readPrimitives(path); });
  EXPECT_NE(msg.find("squat-jump/base_vel"), std::string::npos) << msg;

  msg = inputErrorOf([&] { data::readPrimitive(path, "backflip"); });
  EXPECT_NE(msg.find("backflip"), std::string::npos) << msg;
  EXPECT_NE(msg.find("squat-jump"), std::string::npos) << msg;  // lists what is there
}

TEST(PrimitiveIo, GroupsCopyWithOtherToolsAndForeignFilesRead) {
  // h5copy / h5py's Group.copy use H5Ocopy, which in HDF5 1.10 crashes on string attributes in dense
  // storage: the writer keeps attributes compact. The copy (a file without a creation-order index, as other
  // tools write) must read back identically, listed by name.
  TempDir dir;
  const std::string src = dir.file("src.h5");
  const Primitive a = centaur::test::makeSyntheticJump("squat-jump");
  const Primitive b = centaur::test::makeSyntheticJump("half-squat-jump", 1.0);
  data::writePrimitives(src, {a, b});
  const std::string dst = dir.file("copy.h5");
  const hid_t in = H5Fopen(src.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t out = H5Fcreate(dst.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(in, 0);
  ASSERT_GE(out, 0);
  EXPECT_GE(H5Ocopy(in, "squat-jump", out, "squat-jump", H5P_DEFAULT, H5P_DEFAULT), 0);
  EXPECT_GE(H5Ocopy(in, "half-squat-jump", out, "half-squat-jump", H5P_DEFAULT, H5P_DEFAULT), 0);
  H5Fclose(out);
  H5Fclose(in);
  EXPECT_EQ(data::listPrimitives(dst), (std::vector<std::string>{"half-squat-jump", "squat-jump"}));
  expectSame(a, data::readPrimitive(dst, "squat-jump"));
  expectSame(b, data::readPrimitive(dst, "half-squat-jump"));
}
