#include "sweep/results_file.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "sweep/run_plan.hpp"

namespace centaur::sweep {

namespace {

using data::h5::Column;
using Type = Column::Type;

const char* const kTable = "runs";

}  // namespace

std::vector<Column> resultsColumns(const SweepSpec& spec) {
  std::vector<Column> c = {
      {"run", Type::kInt64, "", "run index: (point * seeds + seed_index) * modes + mode index"},
      {"point", Type::kInt64, "", "grid point (row of primitives.h5 /index)"},
      {"group", Type::kString, "", "the grid point's group in primitives.h5"},
      {"jump", Type::kString, "", "squat-jump | half-squat-jump"},
      {"mode", Type::kString, "", "upper-body stabilizer: none | raibert | angmom | ocp"},
      {"seed_index", Type::kInt64, "", "index of the perturbation sample at this grid point (0 .. seeds-1)"},
      {"seed", Type::kInt64, "", "sensors.seed of the run (derived from the grid point and the seed index)"}};
  for (const Axis& a : spec.axes) {
    c.push_back({a.key, a.numeric() ? Type::kFloat64 : Type::kString, a.numeric() ? "SI" : "",
                 "planner axis: the grid point's value"});
  }
  for (const std::string& p : perturbationColumns(spec)) {
    c.push_back({p, Type::kFloat64, "SI", "simulation key sampled for this run"});
  }
  c.push_back({"outcome", Type::kString, "",
               "success | fall | no_flight | not_upright | no_wall_contact | error | not_planned"});
  c.push_back({"success", Type::kInt64, "", "1 if outcome is success"});
  for (const MetricInfo& m : metricInfo()) c.push_back({m.name, Type::kFloat64, m.unit, m.description});
  c.push_back({"error", Type::kString, "", "why the run failed (outcome error / not_planned), else empty"});
  return c;
}

data::h5::Table resultsRows(const SweepSpec& spec, const data::DatabaseIndex& index,
                            const std::vector<RunRecord>& records) {
  data::h5::Table t(resultsColumns(spec));
  for (const RunRecord& r : records) {
    const RunId id = runId(spec, static_cast<std::size_t>(r.run));
    const data::GridEntry& point = index.points.at(id.point);
    const std::uint64_t seed64 = runSeed(spec, id.point, id.seed_index);
    const std::size_t row = t.addRow();
    std::size_t c = 0;
    t.set(row, c++, static_cast<std::int64_t>(r.run));
    t.set(row, c++, static_cast<std::int64_t>(id.point));
    t.set(row, c++, point.group);
    t.set(row, c++, point.jump);
    t.set(row, c++, spec.modes[id.mode]);
    t.set(row, c++, static_cast<std::int64_t>(id.seed_index));
    t.set(row, c++, sensorSeed(seed64));
    for (std::size_t a = 0; a < spec.axes.size(); ++a, ++c) {
      if (point.values[a].numeric) {
        t.set(row, c, point.values[a].number);
      } else {
        t.set(row, c, point.values[a].text);
      }
    }
    for (const auto& sample : samplePerturbation(spec, seed64)) {
      for (double v : sample) t.set(row, c++, v);
    }
    t.set(row, c++, r.outcome);
    t.set(row, c++, static_cast<std::int64_t>(r.success() ? 1 : 0));
    for (double m : r.metrics) t.set(row, c++, m);
    t.set(row, c++, r.error);
  }
  return t;
}

ResultsFile::ResultsFile(const std::string& path, const SweepSpec& spec, const data::DatabaseIndex& index,
                         const std::vector<RunRecord>& records)
    : path_(path), spec_(spec), index_(index) {
  const data::h5::QuietErrors quiet;
  const data::h5::Writer w(path);
  const std::string tmp = temporaryPathFor(path);
  try {
    data::h5::Id file = w.createFile(tmp);
    w.stringAttribute(file.get(), "kind", "sweep-results");
    w.intAttribute(file.get(), "format_version", kResultsFormatVersion);
    w.stringAttribute(file.get(), "sweep_spec", spec.canonicalYaml());
    w.stringAttribute(file.get(), "description",
                      "one row per finished run of a centaur sweep, in the order they finished; schema in "
                      "docs/sweeps.md");
    data::h5::writeTable(w, file.get(), kTable, resultsRows(spec, index, records),
                         "one row per finished run (docs/sweeps.md)", true);
    if (!file.close()) w.fail("closing (flushing) the file failed");
  } catch (...) {
    removeFileIfExists(tmp);
    throw;
  }
  commitFile(tmp, path);
  file_ = w.openFile(path);
}

void ResultsFile::append(const std::vector<RunRecord>& records) {
  if (records.empty()) return;
  const data::h5::QuietErrors quiet;
  const data::h5::Writer w(path_);
  data::h5::appendTable(w, file_.get(), kTable, resultsRows(spec_, index_, records));
  w.ok(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flushing");
}

void ResultsFile::close() {
  if (!file_.valid()) return;
  const data::h5::QuietErrors quiet;
  if (!file_.close()) throw RuntimeError("cannot write " + path_ + ": closing (flushing) the file failed");
}

ResultsFile::~ResultsFile() { file_.reset(); }

data::h5::Table readResults(const std::string& path) {
  const data::h5::Reader r(path, "a results file written by `centaur sweep`");
  if (!r.hasAttribute(r.file(), "kind") || r.text(r.file(), "@kind", "kind") != "sweep-results") {
    r.fail("@kind", "not a sweep results file");
  }
  return data::h5::readTable(r, r.file(), kTable, kTable);
}

}  // namespace centaur::sweep
