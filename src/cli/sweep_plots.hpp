#pragma once
// The figures of a sweep. Heatmaps: success rate over two planner axes, one panel per (jump, mode), each cell coloured
// red (0) to green (1) and labelled successes/runs; cells whose plans did not converge are grey ("no plan").
// Drawn by gnuplot from a private copy of the data file (cli/gnuplot.hpp, renderPng): the script names only that
// copy and the PNG, and every label it shows goes through gnuplotQuote.
#include <string>

#include "sweep/summary.hpp"

namespace centaur::cli {

/// Draws `h` (data as written by sweep::heatmapData to `data_path`) into `png_path`. RuntimeError on failure.
void plotHeatmap(const sweep::Heatmap& h, const std::string& data_path, const std::string& png_path);

/// Draws the peak-pitch histograms `h` (data as written by sweep::pitchHistogramData): one panel per (jump,
/// mode), successes green and the other runs red, stacked.
void plotPitchHistogram(const sweep::PitchHistogram& h, const std::string& data_path, const std::string& png_path);

}  // namespace centaur::cli
