#include "sweep/sweep.hpp"

#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <thread>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/output_guard.hpp"
#include "sweep/dispatch.hpp"
#include "sweep/journal.hpp"
#include "sweep/planning.hpp"
#include "sweep/results_file.hpp"
#include "sweep/run_plan.hpp"
#include "sweep/sweep_dir.hpp"

namespace centaur::sweep {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

struct Prepared {
  SweepSpec spec;
  std::unique_ptr<SweepDir> dir;
  data::DatabaseIndex index;
  std::string flywheel;  ///< "" without mode ocp
};

std::string heatmapStem(const std::string& x, const std::string& y) { return "heatmap-" + x + "-" + y; }

/// Every file a sweep of `spec` may write into `out` (sweep.yaml only when the sweep is new: a resume only reads
/// it), for guardOutputs(): the spec must not be one of them.
std::vector<NamedPath> sweepOutputs(const SweepSpec& spec, const std::string& out, bool resume) {
  const fs::path d(out);
  std::vector<NamedPath> files;
  auto add = [&](const std::string& name) { files.push_back({"--out", (d / name).string()}); };
  if (!resume) add("sweep.yaml");
  for (const char* name : {"primitives.h5", "arm-flywheel.h5", "journal.jsonl", "results.h5", "summary.json",
                           "summary.md", "peak-pitch.dat", "peak-pitch.png", ".lock"}) {
    add(name);
  }
  for (const auto& [x, y] : spec.heatmaps) {
    add(heatmapStem(x, y) + ".dat");
    add(heatmapStem(x, y) + ".png");
  }
  return files;
}

/// Steps 1 and 2: spec, DIR, database, arm-flywheel plan.
Prepared prepare(const SweepOptions& o) {
  Prepared p;
  p.spec = loadSweepSpec(o.spec);
  const std::string canonical = p.spec.canonicalYaml();
  guardOutputs({{"the spec", o.spec}}, sweepOutputs(p.spec, o.out, checkSweepDir(o.out, canonical)));
  p.dir = std::make_unique<SweepDir>(o.out, canonical);
  std::fprintf(stderr, "sweep: %s %s: %zu grid points x %d seeds x %zu modes = %zu runs\n",
               p.dir->resumed() ? "resuming" : "starting", o.out.c_str(), p.spec.points(), p.spec.seeds,
               p.spec.modes.size(), p.spec.runs());
  p.index = planDatabase(p.spec, *p.dir);
  if (std::find(p.spec.modes.begin(), p.spec.modes.end(), "ocp") != p.spec.modes.end()) {
    p.flywheel = planFlywheel(*p.dir);
  }
  return p;
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RuntimeError("cannot read " + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  if (!out) throw RuntimeError("cannot write " + path);
}

void progress(const RunContext& ctx, const RunRecord& r, std::size_t done, std::size_t total) {
  const RunId id = runId(*ctx.spec, static_cast<std::size_t>(r.run));
  std::fprintf(stderr, "sweep: [%zu/%zu] run %lld %s %s seed %zu: %s", done, total, static_cast<long long>(r.run),
               ctx.index.points[id.point].group.c_str(), ctx.spec->modes[id.mode].c_str(), id.seed_index,
               r.outcome.c_str());
  if (r.simulated()) std::fprintf(stderr, ", peak pitch %.2f deg", r.metric("peak_pitch_deg"));
  if (!r.error.empty()) std::fprintf(stderr, ": %s", r.error.c_str());
  std::fprintf(stderr, " (%.2f s)\n", r.metric("run_time_s"));
}

/// Steps 3 and 4 on rank 0 (or the only process).
SweepReport runAndSummarize(Prepared& p, const MpiSession* mpi, int threads, Clock::time_point start) {
  SweepReport report;
  report.dir = p.dir->dir();
  report.ranks = mpi != nullptr ? mpi->size() : 1;
  report.threads = threads;
  report.runs_total = p.spec.runs();
  const RunContext ctx{&p.spec, p.dir->path("primitives.h5"), p.flywheel, p.index};
  Journal journal(p.dir->path("journal.jsonl"), p.spec.runs());
  std::vector<RunRecord> records = journal.records();
  ResultsFile results(p.dir->path("results.h5"), p.spec, p.index, records);
  std::vector<bool> done(p.spec.runs(), false);
  for (const RunRecord& r : records) done[static_cast<std::size_t>(r.run)] = true;
  std::vector<std::size_t> todo;
  for (std::size_t run = 0; run < done.size(); ++run) {
    if (!done[run]) todo.push_back(run);
  }
  report.runs_before = records.size();
  std::fprintf(stderr, "sweep: %zu runs to do (%zu finished before) on %d rank%s x %d thread%s\n", todo.size(),
               records.size(), report.ranks, report.ranks == 1 ? "" : "s", threads, threads == 1 ? "" : "s");
  const auto t_runs = Clock::now();
  {
    LocalPool pool(threads, [&ctx](std::size_t run) { return executeRun(ctx, run); });
    dispatchRuns(todo, pool, mpi, [&](std::vector<RunRecord>& batch) {
      const auto t0 = Clock::now();
      journal.append(batch);
      results.append(batch);
      for (RunRecord& r : batch) {
        progress(ctx, r, records.size() + 1, p.spec.runs());
        records.push_back(std::move(r));
      }
      report.writer_time_s += seconds(t0);
    });
  }
  report.runs_wall_time_s = seconds(t_runs);
  report.runs_now = records.size() - report.runs_before;
  results.close();

  report.summary = summarize(ctx, records, p.dir->dir());
  const std::string json_path = p.dir->path("summary.json"), md_path = p.dir->path("summary.md");
  writeTextFileAtomic(json_path, report.summary.json.dump(2) + "\n");
  writeTextFileAtomic(md_path, report.summary.markdown);
  report.files = {p.dir->path("sweep.yaml"), ctx.primitives};
  if (!p.flywheel.empty()) report.files.push_back(p.flywheel);
  report.files.insert(report.files.end(), {p.dir->path("journal.jsonl"), p.dir->path("results.h5"), json_path, md_path});
  for (const Heatmap& h : report.summary.heatmaps) {
    const std::string dat = p.dir->path(heatmapStem(h.x, h.y) + ".dat");
    writeTextFileAtomic(dat, heatmapData(h));
    report.heatmap_data.push_back(dat);
    report.files.push_back(dat);
  }
  report.pitch_data = p.dir->path("peak-pitch.dat");
  writeTextFileAtomic(report.pitch_data, pitchHistogramData(report.summary.pitch));
  report.files.push_back(report.pitch_data);
  for (const RunRecord& r : records) {
    if (r.outcome == kOutcomeError) report.exit_code = kExitRuntime;
  }
  report.wall_time_s = seconds(start);
  return report;
}

int defaultThreads(int jobs, bool mpi) {
  if (jobs > 0) return jobs;
  return mpi ? 1 : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

/// A worker rank: the spec and the plans from rank 0, into a private temporary directory, then runs.
SweepReport serveAsWorker(const MpiSession& mpi, int threads) {
  SweepReport report;
  report.writer = false;
  std::string text, primitives, flywheel;
  mpi.broadcast(text);
  mpi.broadcast(primitives);
  mpi.broadcast(flywheel);
  const SweepSpec spec = parseSweepSpec(text, "<the spec received from rank 0>");
  std::string pattern = (fs::temp_directory_path() / "centaur-sweep-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) throw RuntimeError("cannot create a temporary directory");
  const fs::path local(pattern);
  RunContext ctx{&spec, (local / "primitives.h5").string(), flywheel.empty() ? "" : (local / "arm-flywheel.h5").string(),
                 {}};
  writeBytes(ctx.primitives, primitives);
  if (!flywheel.empty()) writeBytes(ctx.flywheel, flywheel);
  ctx.index = data::readDatabaseIndex(ctx.primitives);
  {
    LocalPool pool(threads, [&ctx](std::size_t run) { return executeRun(ctx, run); });
    serveRuns(pool, mpi);
  }
  std::error_code ec;
  fs::remove_all(local, ec);
  return report;
}

/// Under MPI: rank 0 prepares and tells the others whether to go on (a bad spec ends every rank with exit 2).
SweepReport runWithMpi(const SweepOptions& o, Clock::time_point start) {
  MpiSession mpi;
  const int threads = defaultThreads(o.jobs, true);
  if (mpi.rank() != 0) {
    std::string status;
    mpi.broadcast(status);
    const json s = json::parse(status);
    if (s.at("code").get<int>() != 0 || !s.at("run").get<bool>()) {
      SweepReport r;
      r.writer = false;
      r.exit_code = s.at("code").get<int>();
      return r;
    }
    try {
      return serveAsWorker(mpi, threads);
    } catch (const std::exception& e) {
      std::cerr << "error: rank " << mpi.rank() << ": " << e.what() << std::endl;
      mpi.abort(kExitRuntime);
    }
  }
  Prepared p;
  std::string status = json{{"code", 0}, {"run", !o.plan_only}}.dump();
  try {
    p = prepare(o);
  } catch (const InputError& e) {
    status = json{{"code", kExitBadInput}, {"run", false}}.dump();
    mpi.broadcast(status);
    throw;
  } catch (const std::exception& e) {
    status = json{{"code", kExitRuntime}, {"run", false}}.dump();
    mpi.broadcast(status);
    throw;
  }
  mpi.broadcast(status);
  if (o.plan_only) {
    SweepReport r;
    r.dir = o.out;
    r.files = {p.dir->path("sweep.yaml"), p.dir->path("primitives.h5")};
    return r;
  }
  try {
    std::string text = p.spec.canonicalYaml(), primitives = readBytes(p.dir->path("primitives.h5"));
    std::string flywheel = p.flywheel.empty() ? std::string() : readBytes(p.flywheel);
    mpi.broadcast(text);
    mpi.broadcast(primitives);
    mpi.broadcast(flywheel);
    return runAndSummarize(p, &mpi, threads, start);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << std::endl;
    mpi.abort(dynamic_cast<const InputError*>(&e) != nullptr ? kExitBadInput : kExitRuntime);
  }
}

}  // namespace

SweepReport runSweep(const SweepOptions& o) {
  const auto start = Clock::now();
  if (MpiSession::launched()) return runWithMpi(o, start);
  Prepared p = prepare(o);
  if (o.plan_only) {
    SweepReport r;
    r.dir = o.out;
    r.files = {p.dir->path("sweep.yaml"), p.dir->path("primitives.h5")};
    if (!p.flywheel.empty()) r.files.push_back(p.flywheel);
    return r;
  }
  return runAndSummarize(p, nullptr, defaultThreads(o.jobs, false), start);
}

}  // namespace centaur::sweep
