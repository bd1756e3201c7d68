#pragma once
// Plot a lower-body primitive like the lower plots of the paper's Fig. 3: three stacked panels over time
// (contact forces, feet positions, waist position) with flight and partial-support phases shaded.
// Rendering is done by gnuplot (cli/gnuplot.hpp: data through a data file, text from the file escaped, no user
// path in the script); the PNG is written to a temporary sibling and renamed, so a failed plot never leaves a
// half-written image.
#include <string>

#include "cli/gnuplot.hpp"
#include "data/primitive.hpp"

namespace centaur::cli {

struct PlotOptions {
  int width_px = 1200;   ///< image width [px]
  int height_px = 1300;  ///< image height [px]
  std::string title;     ///< figure title; empty = "<name>: planned primitive (<status>, <iterations> it)"
};

/// Draw `p` into the PNG file `png_path` (parent directories created). Throws RuntimeError on failure.
void plotPrimitive(const data::Primitive& p, const std::string& png_path, const PlotOptions& options = {});

}  // namespace centaur::cli
