#pragma once
// Plot a lower-body primitive like the lower plots of the paper's Fig. 3: three stacked panels over time
// (contact forces, feet positions, waist position) with flight and partial-support phases shaded.
// Rendering is done by gnuplot (Debian package gnuplot-nox, terminal pngcairo) in a child process; the PNG
// is written to a temporary sibling and renamed, so a failed plot never leaves a half-written image.
#include <string>

#include "data/primitive.hpp"

namespace centaur::cli {

struct PlotOptions {
  int width_px = 1200;   ///< image width [px]
  int height_px = 1300;  ///< image height [px]
  std::string title;     ///< figure title; empty = "<name>: planned primitive (<status>, <iterations> it)"
};

/// True if a `gnuplot` executable is on PATH.
bool gnuplotAvailable();

/// Run gnuplot on `script` (text) in a fresh temporary directory; returns what gnuplot printed (stdout and
/// stderr). Throws RuntimeError if gnuplot is missing ("apt-get install gnuplot-nox") or exits non-zero.
std::string runGnuplot(const std::string& script);

/// Draw `p` into the PNG file `png_path` (parent directories created). Throws RuntimeError on failure.
void plotPrimitive(const data::Primitive& p, const std::string& png_path, const PlotOptions& options = {});

}  // namespace centaur::cli
