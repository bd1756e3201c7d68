// ctest-labels: unit data
// The primitive database (a sweep's primitives.h5): the index table round trip, the groups readable by every
// primitive reader (the index is a dataset, not a group), the grid attributes, the nearest-point rule of
// `--select` (normalised distance, ties, unconverged points skipped, string axes, unknown axis -> InputError), the
// extendible table of results (append = one write of all rows), and h5py reading the database (Debian's
// python3-h5py, the format promise to Python users).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/error.hpp"
#include "data/hdf5_table.hpp"
#include "data/primitive_database.hpp"
#include "data/primitive_io.hpp"
#include "support/synthetic_primitive.hpp"
#include "support/temp_dir.hpp"

using namespace centaur;
using namespace centaur::data;

namespace {

GridValue num(double x) {
  GridValue v;
  v.number = x;
  return v;
}

GridValue str(const std::string& s) {
  GridValue v;
  v.numeric = false;
  v.text = s;
  return v;
}

/// A 3 x 2 grid over (target.height, model.preset) of squat jumps plus one half-squat jump; point 4 unsolved.
DatabaseIndex sampleIndex() {
  DatabaseIndex index;
  index.axes = {"target.height", "model.preset"};
  index.numeric = {true, false};
  const double heights[] = {0.8, 0.85, 0.9};
  const char* presets[] = {"centauro", "centauro-authors"};
  int p = 0;
  for (double h : heights) {
    for (const char* pr : presets) {
      index.points.push_back({p, "squat-jump-" + std::to_string(p), "squat-jump", p == 4 ? "not_converged" : "solved",
                              {num(h), str(pr)}});
      ++p;
    }
  }
  index.points.push_back({p, "half-squat-jump-6", "half-squat-jump", "solved", {num(0.87), str("centauro")}});
  return index;
}

/// Writes the sample database (synthetic primitives, one file per point as a sweep's plans/) into `dir`.
std::string writeSample(const centaur_test::TempDir& dir, const DatabaseIndex& index) {
  std::vector<std::string> sources;
  for (const GridEntry& e : index.points) {
    Primitive p = test::makeSyntheticJump(e.group, 0.01 * e.point);
    gridAttributes(index, e, p);
    p.solve.status = e.solve_status;
    sources.push_back(dir.file(e.group + ".h5"));
    writePrimitive(sources.back(), p);
  }
  const std::string db = dir.file("primitives.h5");
  writeDatabase(db, index, sources, "jumps: [squat-jump]\n");
  return db;
}

std::size_t select(const DatabaseIndex& index, const std::string& jump, const std::vector<Selection>& s) {
  return selectGridPoint(index, jump, s, "db.h5");
}

}  // namespace

TEST(PrimitiveDatabase, IndexRoundTripAndEveryGroupIsAPrimitive) {
  const centaur_test::TempDir dir("db");
  const DatabaseIndex index = sampleIndex();
  const std::string db = writeSample(dir, index);
  ASSERT_TRUE(isDatabase(db));
  const DatabaseIndex back = readDatabaseIndex(db);
  EXPECT_EQ(back.axes, index.axes);
  EXPECT_EQ(back.numeric, index.numeric);
  ASSERT_EQ(back.points.size(), index.points.size());
  for (std::size_t i = 0; i < index.points.size(); ++i) {
    EXPECT_EQ(back.points[i].group, index.points[i].group);
    EXPECT_EQ(back.points[i].jump, index.points[i].jump);
    EXPECT_EQ(back.points[i].solve_status, index.points[i].solve_status);
    EXPECT_EQ(back.points[i].values[0].number, index.points[i].values[0].number);
    EXPECT_EQ(back.points[i].values[1].text, index.points[i].values[1].text);
  }
  // The primitive readers see exactly the grid points' groups, in creation order, bit for bit.
  const std::vector<std::string> names = listPrimitives(db);
  ASSERT_EQ(names.size(), index.points.size());
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(names[i], index.points[i].group);
  const Primitive p = readPrimitive(db, "squat-jump-3");
  const Primitive ref = test::makeSyntheticJump("squat-jump-3", 0.03);
  EXPECT_EQ(p.base_pos, ref.base_pos);
  EXPECT_EQ(p.scalars.at("grid.point"), 3.0);
  EXPECT_EQ(p.scalars.at("grid.target.height"), 0.85);
  EXPECT_EQ(p.strings.at("grid.model.preset"), "centauro-authors");
  EXPECT_EQ(readPrimitives(db).size(), index.points.size());
  // A plain primitive file is not a database.
  EXPECT_FALSE(isDatabase(dir.file("squat-jump-0.h5")));
  EXPECT_THROW(readDatabaseIndex(dir.file("squat-jump-0.h5")), InputError);
}

TEST(PrimitiveDatabase, WithoutAxes) {  // a sweep of the default plans only: one grid point per jump
  const centaur_test::TempDir dir("db-no-axes");
  DatabaseIndex index;
  index.points.push_back({0, "squat-jump-0000", "squat-jump", "solved", {}});
  const std::string db = writeSample(dir, index);
  const DatabaseIndex back = readDatabaseIndex(db);
  EXPECT_TRUE(back.axes.empty());
  ASSERT_EQ(back.points.size(), 1u);
  EXPECT_EQ(back.points[0].group, "squat-jump-0000");
  EXPECT_EQ(select(back, "squat-jump", {}), 0u);
}

TEST(PrimitiveDatabase, NearestGridPointRule) {
  const DatabaseIndex index = sampleIndex();
  // Exact values select their point; the string axis must match.
  EXPECT_EQ(select(index, "squat-jump", {{"target.height", "0.85"}, {"model.preset", "centauro"}}), 2u);
  // Nearest by the normalised distance: 0.86 is nearest to 0.85.
  EXPECT_EQ(select(index, "squat-jump", {{"target.height", "0.86"}, {"model.preset", "centauro"}}), 2u);
  // Unselected axes do not count; ties go to the first point listed (0.85/centauro before 0.85/authors).
  EXPECT_EQ(select(index, "squat-jump", {{"target.height", "0.85"}}), 2u);
  // An unconverged point is skipped: 0.9/authors (point 5) is nearest to 0.95/authors after 0.9/centauro (4) fails.
  EXPECT_EQ(select(index, "squat-jump", {{"target.height", "0.95"}, {"model.preset", "centauro"}}), 2u)
      << "0.9/centauro did not converge: the nearest converged centauro point is 0.85";
  EXPECT_EQ(select(index, "squat-jump", {{"target.height", "0.95"}, {"model.preset", "centauro-authors"}}), 5u);
  // Only the scenario's jump.
  EXPECT_EQ(select(index, "half-squat-jump", {{"target.height", "0.8"}}), 6u);
  // Bad selections name the file and the key.
  for (const auto& [sel, expect] : std::vector<std::pair<Selection, std::string>>{
           {{"target.wall_height", "0.1"}, "no such axis"},
           {{"target.height", "tall"}, "not a number"},
           {{"model.preset", "robonaut"}, "no grid point"}}) {
    try {
      select(index, "squat-jump", {sel});
      ADD_FAILURE() << sel.key << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("db.h5"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  }
}

TEST(PrimitiveDatabase, NormalisedDistanceWeighsAxesBySpan) {
  DatabaseIndex index;
  index.axes = {"a", "b"};
  index.numeric = {true, true};
  // a spans [0, 1], b spans [0, 100]: (0.4, 0) is 0.4 away from (0, 0) in a, and (0, 30) 0.3 in b.
  index.points = {{0, "g0", "squat-jump", "solved", {num(1.0), num(0.0)}},
                  {1, "g1", "squat-jump", "solved", {num(0.0), num(100.0)}},
                  {2, "g2", "squat-jump", "solved", {num(0.4), num(0.0)}},
                  {3, "g3", "squat-jump", "solved", {num(0.0), num(30.0)}}};
  EXPECT_EQ(select(index, "squat-jump", {{"a", "0"}, {"b", "0"}}), 3u);
}

TEST(HdfTable, AppendedRowsEqualOneWrite) {
  const centaur_test::TempDir dir("table");
  using h5::Column;
  const std::vector<Column> columns = {{"run", Column::Type::kInt64, "", "index"},
                                       {"x", Column::Type::kFloat64, "m", "a length"},
                                       {"mode", Column::Type::kString, "", "a name"}};
  h5::Table all(columns);
  for (int i = 0; i < 7; ++i) {
    const std::size_t r = all.addRow();
    all.set(r, 0, static_cast<std::int64_t>(i));
    all.set(r, 1, i == 3 ? std::nan("") : 0.1 * i);
    all.set(r, 2, std::string(i % 2 ? "raibert" : "none"));
  }
  const std::string path = dir.file("t.h5");
  {
    const h5::Writer w(path);
    h5::Id f = w.createFile(path);
    h5::writeTable(w, f.get(), "runs", all.slice(0, 2), "test", true, 2);
    h5::appendTable(w, f.get(), "runs", all.slice(2, 4));
    h5::appendTable(w, f.get(), "runs", all.slice(6, 1));
  }
  const h5::Reader r(path, "a test table");
  const h5::Table back = h5::readTable(r, r.file(), "runs", "runs");
  ASSERT_EQ(back.rows(), 7u);
  EXPECT_EQ(back.i64[0], all.i64[0]);
  EXPECT_EQ(back.str[2], all.str[2]);
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(std::memcmp(&back.f64[1][i], &all.f64[1][i], sizeof(double)), 0) << i;  // NaN included, bitwise
  }
  EXPECT_EQ(back.columns()[1].units, "m");
  EXPECT_EQ(back.columns()[2].description, "a name");
}

TEST(PrimitiveDatabase, ReadableByH5py) {
  const char* python = "/usr/bin/python3";  // Debian's, with python3-h5py (Makefile DEBS)
  ASSERT_TRUE(std::filesystem::exists(python)) << "python3 is missing (apt-get install python3-h5py)";
  const centaur_test::TempDir dir("db-h5py");
  const std::string db = writeSample(dir, sampleIndex());
  const std::string script = dir.file("check.py");
  std::ofstream(script) << "import sys, h5py\n"
                           "f = h5py.File(sys.argv[1], 'r')\n"
                           "idx = f['index'][:]\n"
                           "assert f.attrs['kind'] == 'primitive-database', f.attrs['kind']\n"
                           "assert list(f.attrs['axes']) == ['target.height', 'model.preset']\n"
                           "assert len(idx) == 7 and idx['point'][3] == 3\n"
                           "g = idx['group'][3]\n"
                           "g = g.decode() if isinstance(g, bytes) else g\n"
                           "assert abs(idx['target.height'][3] - 0.85) == 0.0\n"
                           "assert f[g].attrs['grid.target.height'] == 0.85\n"
                           "assert f[g]['base_pos'].shape == (1001, 3)\n"
                           "print('ok', g)\n";
  const std::string cmd = std::string(python) + " " + script + " " + db + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  char buf[4096];
  std::string out;
  while (fgets(buf, sizeof buf, p)) out += buf;
  EXPECT_EQ(pclose(p), 0) << out;
  EXPECT_EQ(out, "ok squat-jump-3\n");
}
