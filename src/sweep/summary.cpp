#include "sweep/summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <tuple>

#include "common/number_text.hpp"
#include "common/stats.hpp"
#include "sweep/run_plan.hpp"

namespace centaur::sweep {

namespace {

using nlohmann::json;

/// Counts of one group of runs.
struct Tally {
  std::size_t n = 0, k = 0;  ///< simulated runs, successes
  std::map<std::string, std::size_t> outcomes;
  std::vector<double> peak_pitch;
  void add(const RunRecord& r) {
    ++outcomes[r.outcome];
    if (!r.simulated()) return;
    ++n;
    k += r.success() ? 1 : 0;
    peak_pitch.push_back(r.metric("peak_pitch_deg"));
  }
};

json rateJson(const Tally& t) {
  const Interval ci = wilson(t.k, t.n);
  json j;
  j["runs"] = t.n;
  j["successes"] = t.k;
  j["rate"] = t.n > 0 ? json(static_cast<double>(t.k) / t.n) : json(nullptr);
  j["ci95"] = {ci.lo, ci.hi};
  j["outcomes"] = t.outcomes;
  return j;
}

json distributionJson(const std::vector<double>& v) {
  if (v.empty()) return nullptr;
  double sum = 0.0;
  for (double x : v) sum += x;
  return {{"min", *std::min_element(v.begin(), v.end())}, {"p05", percentile(v, 0.05)}, {"p25", percentile(v, 0.25)},
          {"median", median(v)}, {"p75", percentile(v, 0.75)}, {"p95", percentile(v, 0.95)},
          {"max", *std::max_element(v.begin(), v.end())}, {"mean", sum / static_cast<double>(v.size())}};
}

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string rateText(const Tally& t) {
  if (t.n == 0) return "- | -";
  const Interval ci = wilson(t.k, t.n);
  return fmt("%.1f %%", 100.0 * t.k / t.n) + " | [" + fmt("%.1f", 100.0 * ci.lo) + ", " + fmt("%.1f", 100.0 * ci.hi) + "]";
}

std::string outcomeText(const Tally& t) {
  std::string s;
  for (const auto& [o, c] : t.outcomes) s += (s.empty() ? "" : ", ") + o + " " + std::to_string(c);
  return s;
}

/// Per point: the index of its value on every axis.
std::vector<std::vector<std::size_t>> valueIndices(const SweepSpec& spec, const data::DatabaseIndex& index) {
  std::vector<std::vector<std::size_t>> out;
  for (const data::GridEntry& e : index.points) {
    std::vector<std::size_t> at;
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
      const auto& vs = spec.axes[a].values;
      std::size_t i = 0;
      while (i < vs.size() && vs[i].yaml() != e.values[a].yaml()) ++i;
      at.push_back(i);
    }
    out.push_back(at);
  }
  return out;
}

Heatmap makeHeatmap(const RunContext& ctx, const std::vector<RunRecord>& records,
                    const std::vector<std::vector<std::size_t>>& at, const std::pair<std::string, std::string>& axes) {
  const SweepSpec& spec = *ctx.spec;
  auto axisIndex = [&](const std::string& k) {
    std::size_t a = 0;
    while (spec.axes[a].key != k) ++a;
    return a;
  };
  const std::size_t ax = axisIndex(axes.first), ay = axisIndex(axes.second);
  Heatmap h;
  h.x = axes.first;
  h.y = axes.second;
  for (const auto& v : spec.axes[ax].values) h.x_values.push_back(v.yaml());
  for (const auto& v : spec.axes[ay].values) h.y_values.push_back(v.yaml());
  const std::size_t cells = h.x_values.size() * h.y_values.size();
  for (const std::string& jump : spec.jumps) {
    for (const std::string& mode : spec.modes) {
      h.panels.push_back({jump, mode, std::vector<std::size_t>(cells, 0), std::vector<std::size_t>(cells, 0),
                          std::vector<bool>(cells, false)});
    }
  }
  auto panelOf = [&](const std::string& jump, std::size_t mode) {
    const std::size_t j = static_cast<std::size_t>(std::find(spec.jumps.begin(), spec.jumps.end(), jump) - spec.jumps.begin());
    return j * spec.modes.size() + mode;
  };
  for (const data::GridEntry& e : ctx.index.points) {
    if (e.solve_status != "solved") continue;
    const std::size_t cell = at[e.point][ax] * h.y_values.size() + at[e.point][ay];
    for (std::size_t m = 0; m < spec.modes.size(); ++m) h.panels[panelOf(e.jump, m)].planned[cell] = true;
  }
  for (const RunRecord& r : records) {
    if (!r.simulated()) continue;
    const RunId id = runId(spec, static_cast<std::size_t>(r.run));
    const std::size_t cell = at[id.point][ax] * h.y_values.size() + at[id.point][ay];
    Heatmap::Panel& p = h.panels[panelOf(ctx.index.points[id.point].jump, id.mode)];
    ++p.n[cell];
    p.k[cell] += r.success() ? 1 : 0;
  }
  return h;
}

PitchHistogram makePitchHistogram(const RunContext& ctx, const std::vector<RunRecord>& records) {
  const SweepSpec& spec = *ctx.spec;
  PitchHistogram h;
  double top = 1.0;
  for (const RunRecord& r : records) {
    if (r.simulated()) top = std::max(top, r.metric("peak_pitch_deg"));
  }
  h.bins = static_cast<std::size_t>(std::ceil(std::min(top, 60.0) / h.bin_deg)) + (top > 60.0 ? 1 : 0);
  for (const std::string& jump : spec.jumps) {
    for (const std::string& mode : spec.modes) {
      h.panels.push_back({jump, mode, std::vector<std::size_t>(h.bins, 0), std::vector<std::size_t>(h.bins, 0)});
    }
  }
  for (const RunRecord& r : records) {
    if (!r.simulated()) continue;
    const RunId id = runId(spec, static_cast<std::size_t>(r.run));
    const std::size_t j = static_cast<std::size_t>(
        std::find(spec.jumps.begin(), spec.jumps.end(), ctx.index.points[id.point].jump) - spec.jumps.begin());
    PitchHistogram::Panel& p = h.panels[j * spec.modes.size() + id.mode];
    const double x = r.metric("peak_pitch_deg");
    const std::size_t bin = std::min(h.bins - 1, static_cast<std::size_t>(std::max(0.0, x) / h.bin_deg));
    ++(r.success() ? p.successes : p.others)[bin];
  }
  return h;
}

}  // namespace

Interval wilson(std::size_t k, std::size_t n, double z) {
  if (n == 0) return {};
  const double nn = static_cast<double>(n), p = static_cast<double>(k) / nn, z2 = z * z;
  const double centre = (p + z2 / (2.0 * nn)) / (1.0 + z2 / nn);
  const double half = z / (1.0 + z2 / nn) * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

namespace {

using ModeKey = std::pair<std::string, std::size_t>;                                  // jump, mode
using ValueKey = std::tuple<std::size_t, std::size_t, std::string, std::size_t>;     // axis, value, jump, mode

void modesSection(const SweepSpec& spec, const std::map<ModeKey, Tally>& by_mode, json& j, std::ostringstream& md) {
  md << "## Success per jump and mode\n\n"
     << "| jump | mode | runs | successes | rate | 95 % interval | peak pitch [deg] median [p05, p95] (max) | outcomes |\n"
     << "|---|---|---:|---:|---:|---|---|---|\n";
  j["modes"] = json::array();
  for (const auto& [key, t] : by_mode) {
    json row = rateJson(t);
    row["jump"] = key.first;
    row["mode"] = spec.modes[key.second];
    row["peak_pitch_deg"] = distributionJson(t.peak_pitch);
    j["modes"].push_back(row);
    md << "| " << key.first << " | " << spec.modes[key.second] << " | " << t.n << " | " << t.k << " | " << rateText(t)
       << " | ";
    if (!t.peak_pitch.empty()) {
      md << fmt("%.2f", median(t.peak_pitch)) << " [" << fmt("%.2f", percentile(t.peak_pitch, 0.05)) << ", "
         << fmt("%.2f", percentile(t.peak_pitch, 0.95)) << "] ("
         << fmt("%.2f", *std::max_element(t.peak_pitch.begin(), t.peak_pitch.end())) << ")";
    } else {
      md << "-";
    }
    md << " | " << outcomeText(t) << " |\n";
  }
}

void axesSection(const SweepSpec& spec, const std::map<ValueKey, Tally>& by_value, json& j, std::ostringstream& md) {
  j["axes"] = json::array();
  if (spec.axes.empty()) return;
  md << "\n## Success per axis value (pooled over the other axes)\n\n"
     << "| axis | value | jump | mode | runs | successes | rate | 95 % interval |\n"
     << "|---|---:|---|---|---:|---:|---:|---|\n";
  for (const auto& [key, t] : by_value) {
    const auto& [a, v, jump, mode] = key;
    json row = rateJson(t);
    row["axis"] = spec.axes[a].key;
    row["value"] = spec.axes[a].values[v].yaml();
    row["jump"] = jump;
    row["mode"] = spec.modes[mode];
    j["axes"].push_back(row);
    md << "| " << spec.axes[a].key << " | " << spec.axes[a].values[v].yaml() << " | " << jump << " | "
       << spec.modes[mode] << " | " << t.n << " | " << t.k << " | " << rateText(t) << " |\n";
  }
}

void plansSection(const RunContext& ctx, json& j, std::ostringstream& md) {
  j["plans_not_converged"] = json::array();
  for (const data::GridEntry& e : ctx.index.points) {
    if (e.solve_status != "solved") j["plans_not_converged"].push_back({{"group", e.group}, {"status", e.solve_status}});
  }
  if (j["plans_not_converged"].empty()) return;
  md << "\n## Plans that did not converge (their runs are not simulated)\n\n";
  for (const auto& p : j["plans_not_converged"]) {
    md << "- " << p["group"].get<std::string>() << ": " << p["status"].get<std::string>() << "\n";
  }
}

/// Every run that did not succeed (and was simulated or failed), with the command that replays it alone.
void failuresSection(const RunContext& ctx, const std::vector<RunRecord>& records, json& j, std::ostringstream& md) {
  const SweepSpec& spec = *ctx.spec;
  j["failed_runs"] = json::array();
  std::ostringstream cmds;
  for (const RunRecord& r : records) {
    if (r.success() || r.outcome == kOutcomeNotPlanned) continue;
    const RunId id = runId(spec, static_cast<std::size_t>(r.run));
    const std::string& group = ctx.index.points[id.point].group;
    const std::string cmd = replayCommand(ctx, static_cast<std::size_t>(r.run));
    j["failed_runs"].push_back({{"run", r.run}, {"group", group}, {"mode", spec.modes[id.mode]},
                                {"outcome", r.outcome}, {"error", r.error}, {"command", cmd}});
    cmds << "# run " << r.run << " (" << group << ", " << spec.modes[id.mode] << ", seed " << id.seed_index
         << "): " << r.outcome << (r.error.empty() ? "" : ": " + r.error) << "\n" << cmd << "\n";
  }
  md << "\n## Runs that did not succeed (" << j["failed_runs"].size() << "), each replayed alone by its command\n\n";
  if (!j["failed_runs"].empty()) md << "```sh\n" << cmds.str() << "```\n";
}

}  // namespace

Summary summarize(const RunContext& ctx, const std::vector<RunRecord>& unsorted, const std::string& dir) {
  const SweepSpec& spec = *ctx.spec;
  std::vector<RunRecord> records = unsorted;
  std::sort(records.begin(), records.end(), [](const RunRecord& a, const RunRecord& b) { return a.run < b.run; });
  const std::vector<std::vector<std::size_t>> at = valueIndices(spec, ctx.index);
  std::map<ModeKey, Tally> by_mode;
  std::map<ValueKey, Tally> by_value;
  Tally all;
  for (const RunRecord& r : records) {
    const RunId id = runId(spec, static_cast<std::size_t>(r.run));
    const std::string& jump = ctx.index.points[id.point].jump;
    all.add(r);
    by_mode[{jump, id.mode}].add(r);
    for (std::size_t a = 0; a < spec.axes.size(); ++a) by_value[{a, at[id.point][a], jump, id.mode}].add(r);
  }
  Summary s;
  json& j = s.json;
  j["dir"] = dir;
  const std::size_t errors = all.outcomes[kOutcomeError], not_planned = all.outcomes[kOutcomeNotPlanned];
  j["runs"] = {{"total", spec.runs()}, {"finished", records.size()}, {"simulated", all.n}, {"successes", all.k},
               {"errors", errors}, {"not_planned", not_planned}};
  std::ostringstream md;
  md << "# centaur sweep: " << dir << "\n\n"
     << records.size() << " of " << spec.runs() << " runs finished; " << all.n << " simulated to their end, " << errors
     << " failed (error), " << not_planned
     << " not simulated because their grid point's plan did not converge. Spec: sweep.yaml. Rates: successes / runs "
        "simulated, with Wilson 95 % score intervals.\n\n";
  modesSection(spec, by_mode, j, md);
  axesSection(spec, by_value, j, md);
  plansSection(ctx, j, md);
  failuresSection(ctx, records, j, md);
  for (const auto& pair : spec.heatmaps) s.heatmaps.push_back(makeHeatmap(ctx, records, at, pair));
  s.pitch = makePitchHistogram(ctx, records);
  s.markdown = md.str();
  return s;
}

std::string pitchHistogramData(const PitchHistogram& h) {
  std::ostringstream s;
  s << "# centaur sweep: peak pitch of the simulated runs, bins of " << exactNumber(h.bin_deg)
    << " deg (the last bin holds everything above)\n";
  for (std::size_t p = 0; p < h.panels.size(); ++p) {
    if (p > 0) s << "\n\n";
    s << "# panel " << p << ": " << h.panels[p].jump << " " << h.panels[p].mode << "\n# bin_start_deg successes others\n";
    for (std::size_t b = 0; b < h.bins; ++b) {
      s << exactNumber(b * h.bin_deg) << " " << h.panels[p].successes[b] << " " << h.panels[p].others[b] << "\n";
    }
  }
  return s.str();
}

std::string heatmapData(const Heatmap& h) {
  std::ostringstream s;
  s << "# centaur sweep heatmap: success rate over " << h.x << " (ix) x " << h.y << " (iy)\n";
  for (std::size_t p = 0; p < h.panels.size(); ++p) {
    const Heatmap::Panel& panel = h.panels[p];
    if (p > 0) s << "\n\n";
    s << "# panel " << p << ": " << panel.jump << " " << panel.mode << "\n# ix iy rate runs successes planned\n";
    for (std::size_t ix = 0; ix < h.x_values.size(); ++ix) {
      for (std::size_t iy = 0; iy < h.y_values.size(); ++iy) {
        const std::size_t c = ix * h.y_values.size() + iy;
        const double rate = panel.n[c] > 0 ? static_cast<double>(panel.k[c]) / panel.n[c] : std::nan("");
        s << ix << " " << iy << " " << (std::isfinite(rate) ? exactNumber(rate) : "NaN") << " " << panel.n[c] << " "
          << panel.k[c] << " " << (panel.planned[c] ? 1 : 0) << "\n";
      }
    }
  }
  return s.str();
}

}  // namespace centaur::sweep
