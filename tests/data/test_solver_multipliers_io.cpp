// ctest-labels: unit
// The optional solver multipliers of a primitive (`knots/multipliers`): an exact round trip, absent when the
// solver returned none, and bad files (negative bound multipliers, NaN, bound vectors of unequal length) refused
// with the dataset named; an inconsistent primitive is not written and leaves the target untouched.
#include <gtest/gtest.h>

#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include "common/error.hpp"
#include "data/primitive_io.hpp"
#include "support/synthetic_primitive.hpp"
#include "support/temp_dir.hpp"

namespace data = centaur::data;
using centaur::InputError;
using centaur::RuntimeError;
using centaur_test::TempDir;

namespace {

data::Primitive jumpWithMultipliers() {
  data::Primitive p = centaur::test::makeSyntheticJump("squat-jump");
  p.mult_constraints = Eigen::VectorXd::LinSpaced(7, -3.0, 3.0);
  p.mult_lower = Eigen::VectorXd::LinSpaced(5, 0.0, 2.0);
  p.mult_upper = Eigen::VectorXd::LinSpaced(5, 1e-9, 4.0);
  return p;
}

/// Replace dataset `link` of an existing file by a double vector holding `values`.
void rewrite(const std::string& path, const std::string& link, const std::vector<double>& values) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_GE(H5Ldelete(f, link.c_str(), H5P_DEFAULT), 0);
  const hsize_t n = values.size();
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t ds = H5Dcreate2(f, link.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(ds, 0);
  EXPECT_GE(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  H5Dclose(ds);
  H5Sclose(space);
  H5Fclose(f);
}

std::string inputErrorOf(const std::string& path) {
  try {
    data::readPrimitive(path, "squat-jump");
  } catch (const InputError& e) {
    return e.what();
  }
  return "NO INPUT ERROR";
}

}  // namespace

TEST(SolverMultipliersIo, RoundTripIsExactAndAbsentMultipliersStayAbsent) {
  TempDir dir;
  const std::string path = dir.file("jump.h5");
  const data::Primitive p = jumpWithMultipliers();
  data::writePrimitive(path, p);
  const data::Primitive back = data::readPrimitive(path, "squat-jump");
  EXPECT_TRUE(back.mult_constraints == p.mult_constraints);
  EXPECT_TRUE(back.mult_lower == p.mult_lower);
  EXPECT_TRUE(back.mult_upper == p.mult_upper);
  EXPECT_TRUE(back.knot_x == p.knot_x);

  data::writePrimitive(path, centaur::test::makeSyntheticJump("squat-jump"));
  const data::Primitive plain = data::readPrimitive(path, "squat-jump");
  EXPECT_EQ(plain.mult_constraints.size(), 0);
  EXPECT_EQ(plain.mult_lower.size(), 0);
  EXPECT_EQ(plain.mult_upper.size(), 0);
}

TEST(SolverMultipliersIo, BadMultipliersAreRefusedNamingTheDataset) {
  TempDir dir;
  const std::string path = dir.file("jump.h5");
  const std::string k = "squat-jump/knots/multipliers/";

  data::writePrimitive(path, jumpWithMultipliers());
  rewrite(path, k + "lower_bounds", {0.0, 1.0, -1e-3, 2.0, 0.5});
  std::string msg = inputErrorOf(path);
  EXPECT_NE(msg.find(k + "lower_bounds"), std::string::npos) << msg;
  EXPECT_NE(msg.find("entry 2 is negative"), std::string::npos) << msg;

  data::writePrimitive(path, jumpWithMultipliers());
  rewrite(path, k + "upper_bounds", {1.0, 1.0, 1.0, 1.0});  // one short of lower_bounds
  msg = inputErrorOf(path);
  EXPECT_NE(msg.find(k + "upper_bounds"), std::string::npos) << msg;

  data::writePrimitive(path, jumpWithMultipliers());
  rewrite(path, k + "constraints", {1.0, std::numeric_limits<double>::quiet_NaN()});
  msg = inputErrorOf(path);
  EXPECT_NE(msg.find(k + "constraints"), std::string::npos) << msg;
}

TEST(SolverMultipliersIo, AnIncompleteSetIsNotWrittenAndTheTargetIsKept) {
  TempDir dir;
  const std::string path = dir.file("jump.h5");
  data::writePrimitive(path, jumpWithMultipliers());
  const auto before = std::filesystem::last_write_time(path);
  data::Primitive p = jumpWithMultipliers();
  p.mult_upper.resize(0);  // lower bounds without upper ones
  EXPECT_THROW(data::writePrimitive(path, p), RuntimeError);
  EXPECT_EQ(std::filesystem::last_write_time(path), before);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"jump.h5"});
  EXPECT_EQ(data::readPrimitive(path, "squat-jump").mult_upper.size(), 5);
}
