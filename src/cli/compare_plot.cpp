#include "cli/compare_plot.hpp"

#include <filesystem>
#include <sstream>

#include "cli/gnuplot.hpp"
#include "common/error.hpp"
#include "common/excerpt.hpp"

namespace centaur::cli {

namespace {

/// The data file of the plot in gnuplot's working directory.
const char* const kCsv = "pitch.csv";

/// Text shown in the figure (the terminal is noenhanced): bounded and escaped.
std::string quoted(const std::string& s) { return gnuplotQuote(excerpt(s, 120)); }

std::string buildScript(const std::vector<PitchPanel>& panels, const PitchPlotOptions& o) {
  const int n = static_cast<int>(panels.size());
  // Layout in pixels, converted to screen fractions: a band for the figure title, then per panel a band for
  // its title, the plot, and a band for the time axis label.
  const int title_px = 50, panel_title_px = 36, axis_px = 62;
  const int height_px = title_px + n * o.panel_height_px;
  auto screenY = [&](int px_from_top) { return 1.0 - static_cast<double>(px_from_top) / height_px; };
  std::ostringstream g;
  g << "set terminal pngcairo size " << o.width_px << "," << height_px << " noenhanced font 'Sans,11'\n"
    << "set output " << gnuplotQuote(kGnuplotPng) << "\n"
    << "set datafile separator comma\n"
    << "set grid xtics ytics lc rgb '#dddddd' lw 1 dt 1\n"
    << "set xzeroaxis lt -1 lw 1 lc rgb '#888888'\n"
    << "set key outside right top vertical Left reverse samplen 3 spacing 1.2 font ',10' box lc rgb '#bbbbbb'\n"
    << "set lmargin at screen 0.08\nset rmargin at screen 0.76\n"
    << "set ylabel 'pitch [deg]'\nset xlabel 'time [s]'\n"
    << "set multiplot title " << quoted(o.title) << " font ',14'\n";
  for (int p = 0; p < n; ++p) {
    const PitchPanel& panel = panels[static_cast<std::size_t>(p)];
    const int top = title_px + p * o.panel_height_px + panel_title_px;
    const int bottom = title_px + (p + 1) * o.panel_height_px - axis_px;
    g << "set tmargin at screen " << screenY(top) << "\nset bmargin at screen " << screenY(bottom) << "\n"
      << "set title " << quoted(panel.title) << " font ',12'\n";
    if (panel.t_max > panel.t_min) {
      g << "set xrange [" << panel.t_min << ":" << panel.t_max << "]\n";
    } else {
      g << "set autoscale x\n";
    }
    if (panel.curves.empty()) {
      g << "unset key\nset label 99 'no completed run' at graph 0.5, graph 0.5 center\n"
        << "plot [0:1] [-1:1] NaN notitle\nunset label 99\nset key\n";
      continue;
    }
    g << "plot ";
    for (std::size_t c = 0; c < panel.curves.size(); ++c) {
      const PitchCurve& cv = panel.curves[c];
      g << (c ? ", " : "") << gnuplotQuote(kCsv) << " skip 1 u 1:" << cv.column << " w l lw 2 lc rgb " << quoted(cv.colour)
        << " t " << quoted(cv.label);
    }
    g << "\n";
  }
  g << "unset multiplot\nunset output\n";
  return g.str();
}

}  // namespace

std::string modeColour(const std::string& mode) {
  if (mode == "none") return "#d62728";
  if (mode == "raibert") return "#1f77b4";
  if (mode == "angmom") return "#2ca02c";
  if (mode == "ocp") return "#ff7f0e";
  return "#7f7f7f";
}

void plotPitchPanels(const std::string& csv_path, const std::vector<PitchPanel>& panels, const std::string& png_path,
                     const PitchPlotOptions& options) {
  if (panels.empty()) throw InputError("pitch plot " + png_path + ": no panels to draw");
  for (const auto& p : panels) {
    for (const auto& c : p.curves) {
      if (c.column < 2) throw InputError("pitch plot " + png_path + ": curve '" + c.label + "' has column < 2");
    }
  }
  renderPng(buildScript(panels, options), {{kCsv, "", csv_path}}, png_path);
}

}  // namespace centaur::cli
