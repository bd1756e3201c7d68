#include "data/primitive_database.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/number_text.hpp"
#include "data/hdf5.hpp"
#include "data/hdf5_table.hpp"
#include "data/primitive_io.hpp"

namespace centaur::data {

namespace {

using h5::Column;
using h5::Id;

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

h5::Table indexTable(const DatabaseIndex& index) {
  std::vector<Column> columns = {
      {"point", Column::Type::kInt64, "", "grid point index (the spec's order: the last axis varies fastest)"},
      {"group", Column::Type::kString, "", "HDF5 group of the grid point's primitive"},
      {"jump", Column::Type::kString, "", "jump primitive (squat-jump | half-squat-jump)"},
      {"solve_status", Column::Type::kString, "", "the planner's outcome: solved or the failure"}};
  for (std::size_t a = 0; a < index.axes.size(); ++a) {
    columns.push_back({index.axes[a], index.numeric[a] ? Column::Type::kFloat64 : Column::Type::kString,
                       index.numeric[a] ? "SI (the planner key's unit)" : "", "planner key swept by the grid"});
  }
  h5::Table t(columns);
  for (const GridEntry& e : index.points) {
    const std::size_t r = t.addRow();
    t.set(r, 0, static_cast<std::int64_t>(e.point));
    t.set(r, 1, e.group);
    t.set(r, 2, e.jump);
    t.set(r, 3, e.solve_status);
    for (std::size_t a = 0; a < index.axes.size(); ++a) {
      if (index.numeric[a]) {
        t.set(r, 4 + a, e.values.at(a).number);
      } else {
        t.set(r, 4 + a, e.values.at(a).text);
      }
    }
  }
  return t;
}

void copyGroup(const h5::Writer& w, const std::string& source, const std::string& group, hid_t dst) {
  Id src(w.check(H5Fopen(source.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "cannot open " + source), H5Fclose);
  w.ok(H5Ocopy(src.get(), group.c_str(), dst, group.c_str(), H5P_DEFAULT, H5P_DEFAULT),
       "copying group '" + group + "' from " + source);
}

}  // namespace

std::string GridValue::yaml() const { return numeric ? exactNumber(number) : text; }

void gridAttributes(const DatabaseIndex& index, const GridEntry& entry, Primitive& prim) {
  prim.scalars["grid.point"] = entry.point;
  for (std::size_t a = 0; a < index.axes.size(); ++a) {
    const std::string key = "grid." + index.axes[a];
    if (index.numeric[a]) {
      prim.scalars[key] = entry.values.at(a).number;
    } else {
      prim.strings[key] = entry.values.at(a).text;
    }
  }
}

void writeDatabase(const std::string& path, const DatabaseIndex& index, const std::vector<std::string>& sources,
                   const std::string& spec_yaml) {
  if (sources.size() != index.points.size()) {
    throw RuntimeError("cannot write " + path + ": " + std::to_string(sources.size()) + " sources for " +
                       std::to_string(index.points.size()) + " grid points");
  }
  const h5::QuietErrors quiet;
  ensureParentDirectory(path);
  const std::string tmp = temporaryPathFor(path);
  try {
    writePrimitives(tmp, {}, WriteMode::Replace);  // the root attributes of a primitive file
    const h5::Writer w(path);
    Id file = w.openFile(tmp);
    for (std::size_t i = 0; i < sources.size(); ++i) copyGroup(w, sources[i], index.points[i].group, file.get());
    h5::writeTable(w, file.get(), "index", indexTable(index),
                   "grid points of the database: parameters -> group (docs/sweeps.md)");
    w.stringAttribute(file.get(), "kind", kDatabaseKind);
    w.stringListAttribute(file.get(), "axes", index.axes);
    w.stringAttribute(file.get(), "sweep_spec", spec_yaml);
    if (!file.close()) w.fail("closing (flushing) the file failed");
  } catch (...) {
    removeFileIfExists(tmp);
    throw;
  }
  commitFile(tmp, path);
}

bool isDatabase(const std::string& path) {
  try {
    const h5::Reader r(path, "a primitive database");
    return r.hasAttribute(r.file(), "kind") && r.text(r.file(), "@kind", "kind") == kDatabaseKind;
  } catch (const InputError&) {
    return false;
  }
}

DatabaseIndex readDatabaseIndex(const std::string& path) {
  const h5::Reader r(path, "a primitive database written by `centaur sweep`");
  if (!r.hasAttribute(r.file(), "kind") || r.text(r.file(), "@kind", "kind") != kDatabaseKind) {
    r.fail("@kind", "not a primitive database (written by `centaur sweep`): it has no grid index");
  }
  DatabaseIndex index;
  index.axes = r.textList(r.file(), "@axes", "axes");
  const h5::Table t = h5::readTable(r, r.file(), "index", "index");
  const char* fixed[] = {"point", "group", "jump", "solve_status"};
  std::vector<std::size_t> at;
  for (const char* name : fixed) {
    at.push_back(t.find(name));
    if (at.back() == h5::Table::npos) r.fail("index", std::string("missing column '") + name + "'");
  }
  std::vector<std::size_t> axis_at;
  for (const std::string& a : index.axes) {
    axis_at.push_back(t.find(a));
    if (axis_at.back() == h5::Table::npos) r.fail("index", "missing the column of axis '" + a + "'");
    index.numeric.push_back(t.columns()[axis_at.back()].type != Column::Type::kString);
  }
  for (std::size_t row = 0; row < t.rows(); ++row) {
    GridEntry e;
    e.point = static_cast<int>(t.integer(row, at[0]));
    e.group = t.text(row, at[1]);
    e.jump = t.text(row, at[2]);
    e.solve_status = t.text(row, at[3]);
    for (std::size_t a = 0; a < index.axes.size(); ++a) {
      GridValue v;
      v.numeric = index.numeric[a];
      if (v.numeric) {
        v.number = t.number(row, axis_at[a]);
      } else {
        v.text = t.text(row, axis_at[a]);
      }
      e.values.push_back(v);
    }
    index.points.push_back(std::move(e));
  }
  return index;
}

std::size_t selectGridPoint(const DatabaseIndex& index, const std::string& jump, const std::vector<Selection>& selections,
                            const std::string& file) {
  std::vector<std::size_t> axis;
  std::vector<double> wanted;
  for (const Selection& s : selections) {
    const auto it = std::find(index.axes.begin(), index.axes.end(), s.key);
    if (it == index.axes.end()) {
      throw InputError(file, s.key, "the database has no such axis (its axes: " +
                                        (index.axes.empty() ? std::string("none") : join(index.axes)) + ")");
    }
    const std::size_t a = static_cast<std::size_t>(it - index.axes.begin());
    double x = std::numeric_limits<double>::quiet_NaN();
    if (index.numeric[a]) {
      char* end = nullptr;
      x = std::strtod(s.value.c_str(), &end);
      if (s.value.empty() || end == nullptr || *end != '\0' || !std::isfinite(x)) {
        throw InputError(file, s.key, "'" + s.value + "' is not a number (a numeric axis)");
      }
    }
    axis.push_back(a);
    wanted.push_back(x);
  }
  // Spans of the numeric axes over the jump's grid points.
  std::vector<double> lo(index.axes.size(), std::numeric_limits<double>::infinity());
  std::vector<double> hi(index.axes.size(), -std::numeric_limits<double>::infinity());
  for (const GridEntry& e : index.points) {
    if (e.jump != jump) continue;
    for (std::size_t a = 0; a < index.axes.size(); ++a) {
      if (!index.numeric[a]) continue;
      lo[a] = std::min(lo[a], e.values[a].number);
      hi[a] = std::max(hi[a], e.values[a].number);
    }
  }
  std::size_t best = index.points.size();
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < index.points.size(); ++i) {
    const GridEntry& e = index.points[i];
    if (e.jump != jump || e.solve_status != "solved") continue;
    double d2 = 0.0;
    bool match = true;
    for (std::size_t k = 0; k < axis.size(); ++k) {
      const std::size_t a = axis[k];
      if (!index.numeric[a]) {
        match = match && e.values[a].text == selections[k].value;
        continue;
      }
      const double span = hi[a] > lo[a] ? hi[a] - lo[a] : 1.0;
      const double u = (wanted[k] - e.values[a].number) / span;
      d2 += u * u;
    }
    if (match && (best == index.points.size() || d2 < best_d)) {
      best = i;
      best_d = d2;
    }
  }
  if (best == index.points.size()) {
    std::string what;
    for (const Selection& s : selections) what += (what.empty() ? "" : ", ") + s.key + "=" + s.value;
    throw InputError(file + ": no grid point of " + jump + " whose plan converged matches " +
                     (what.empty() ? std::string("(no selection)") : what));
  }
  return best;
}

}  // namespace centaur::data
