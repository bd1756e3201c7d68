#pragma once
// The heatmaps of a sweep: success rate over two planner axes, one panel per (jump, mode), each cell coloured
// red (0) to green (1) and labelled successes/runs; cells whose plans did not converge are grey ("no plan").
// Drawn by gnuplot from a copy of the data file in a private temporary directory: the script holds only our own
// text (axis keys and values, checked by the spec to be [A-Za-z0-9_.-]; jump and mode names), never a path or a
// string from the user. The PNG is written to a temporary sibling and renamed.
#include <string>

#include "sweep/summary.hpp"

namespace centaur::cli {

/// Draws `h` (data as written by sweep::heatmapData to `data_path`) into `png_path`. RuntimeError on failure.
void plotHeatmap(const sweep::Heatmap& h, const std::string& data_path, const std::string& png_path);

}  // namespace centaur::cli
