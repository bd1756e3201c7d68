#pragma once
// The statistics of a sweep (DIR/summary.json, DIR/summary.md): success rates with Wilson 95 % score intervals
// per (jump, mode) and per (jump, axis value, mode), the outcomes, the peak-pitch distribution per (jump, mode),
// the plans that did not converge, and the replay command of every run that did not succeed. Rates count the
// runs that were simulated to their end; runs that failed (outcome error) or whose plan did not converge
// (not_planned) are counted apart. Plus the data of the heatmaps: success per (x value, y value) of two axes, per
// jump and mode, pooled over the other axes.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sweep/run_record.hpp"
#include "sweep/run_task.hpp"

namespace centaur::sweep {

/// Wilson score interval of k successes in n trials (z = 1.959964: 95 %); [0, 1] for n = 0.
struct Interval {
  double lo = 0.0, hi = 1.0;
};
Interval wilson(std::size_t k, std::size_t n, double z = 1.959963984540054);

/// One heatmap: per jump and mode, the successes and simulated runs of every (x value, y value) cell.
struct Heatmap {
  std::string x, y;                         ///< axis keys
  std::vector<std::string> x_values, y_values;  ///< tick labels, in the axis order
  struct Panel {
    std::string jump, mode;
    std::vector<std::size_t> k, n;          ///< per cell, index ix * y_values.size() + iy
    std::vector<bool> planned;              ///< per cell: at least one of its grid points' plans converged
  };
  std::vector<Panel> panels;
};

/// The peak pitch of the simulated runs per (jump, mode): counts per bin of `bin_deg` from 0, successes and the
/// others apart; the last bin also holds everything above it (falls reach 90 deg and more).
struct PitchHistogram {
  double bin_deg = 1.0;
  std::size_t bins = 0;
  struct Panel {
    std::string jump, mode;
    std::vector<std::size_t> successes, others;  ///< per bin
  };
  std::vector<Panel> panels;
};

struct Summary {
  nlohmann::json json;        ///< summary.json
  std::string markdown;       ///< summary.md
  std::vector<Heatmap> heatmaps;
  PitchHistogram pitch;
};

/// The summary of `records` (every finished run, any order) of the sweep `ctx` in DIR `dir` (named in the text).
Summary summarize(const RunContext& ctx, const std::vector<RunRecord>& records, const std::string& dir);

/// The histogram's data as text for gnuplot: one block per panel (two blank lines apart), lines "bin_start
/// successes others".
std::string pitchHistogramData(const PitchHistogram& h);

/// A heatmap's data as text for gnuplot: one block per panel (separated by two blank lines, gnuplot's `index`),
/// lines "ix iy rate n k" with rate NaN for a cell without simulated runs.
std::string heatmapData(const Heatmap& h);

}  // namespace centaur::sweep
