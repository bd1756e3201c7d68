#include "cli/sweep_plots.hpp"

#include <algorithm>
#include <sstream>

#include "cli/gnuplot.hpp"

namespace centaur::cli {

namespace {

/// The data file's name in gnuplot's private directory.
constexpr const char* kData = "data.dat";

std::string tics(const std::vector<std::string>& labels) {
  std::string s = "(";
  for (std::size_t i = 0; i < labels.size(); ++i) s += (i ? ", " : "") + gnuplotQuote(labels[i]) + " " + std::to_string(i);
  return s + ")";
}

std::string heatmapScript(const sweep::Heatmap& h) {
  const std::size_t cols = h.panels.empty() ? 1 : std::min<std::size_t>(h.panels.size(), 4);
  const std::size_t rows = (h.panels.size() + cols - 1) / cols;
  std::ostringstream g;
  g << "set terminal pngcairo size " << 380 * cols << "," << 60 + 330 * rows << " noenhanced font 'Sans,10'\n"
    << "set output " << gnuplotQuote(kGnuplotPng) << "\n"
    << "set multiplot layout " << rows << "," << cols << " title " << gnuplotQuote("success rate over " + h.x + " x " + h.y)
    << " font ',13'\n"
    << "set palette defined (0 '#d62728', 0.5 '#f2c14e', 1 '#2ca02c')\nset cbrange [0:1]\nset cbtics 0.25\n"
    << "set xrange [-0.5:" << h.x_values.size() - 0.5 << "]\nset yrange [-0.5:" << h.y_values.size() - 0.5 << "]\n"
    << "set xtics " << tics(h.x_values) << " rotate by 45 right\nset ytics " << tics(h.y_values) << "\n"
    << "set xlabel " << gnuplotQuote(h.x) << "\nset ylabel " << gnuplotQuote(h.y) << "\nset tics nomirror\nunset key\n"
    << "set style fill solid 1.0 noborder\n";
  for (std::size_t p = 0; p < h.panels.size(); ++p) {
    g << "set title " << gnuplotQuote(h.panels[p].jump + " / " + h.panels[p].mode) << "\n"
      << "plot " << gnuplotQuote(kData) << " index " << p
      << " using 1:2:($1-0.5):($1+0.5):($2-0.5):($2+0.5):3 with boxxyerror fc palette, \\\n"
      << "     '' index " << p << " using ($6 == 0 ? $1 : NaN):2:($1-0.5):($1+0.5):($2-0.5):($2+0.5) with boxxyerror "
      << "fc rgb '#bbbbbb', \\\n"
      << "     '' index " << p
      << " using 1:2:($4 > 0 ? sprintf('%d/%d', $5, $4) : ($6 == 0 ? 'no plan' : '')) with labels font ',9'\n";
  }
  g << "unset multiplot\nunset output\n";
  return g.str();
}

std::string histogramScript(const sweep::PitchHistogram& h) {
  const std::size_t modes = h.panels.empty() ? 1 : static_cast<std::size_t>(std::count_if(
      h.panels.begin(), h.panels.end(), [&](const auto& p) { return p.jump == h.panels.front().jump; }));
  const std::size_t rows = (h.panels.size() + modes - 1) / modes;
  std::ostringstream g;
  g << "set terminal pngcairo size " << 330 * modes << "," << 60 + 280 * rows << " noenhanced font 'Sans,10'\n"
    << "set output " << gnuplotQuote(kGnuplotPng) << "\n"
    << "set multiplot layout " << rows << "," << modes << " title "
    << gnuplotQuote("peak pitch of the runs (green: success, red: the others)") << " font ',13'\n"
    << "set style fill solid 0.9 noborder\nset boxwidth " << h.bin_deg << " absolute\nset xrange [0:"
    << h.bins * h.bin_deg << "]\nset yrange [0:*]\nset xlabel 'peak pitch [deg]'\nset ylabel 'runs'\n"
    << "set tics nomirror\nunset key\n";
  for (std::size_t p = 0; p < h.panels.size(); ++p) {
    g << "set title " << gnuplotQuote(h.panels[p].jump + " / " + h.panels[p].mode) << "\n"
      << "plot " << gnuplotQuote(kData) << " index " << p << " using ($1+" << 0.5 * h.bin_deg
      << "):($2+$3) with boxes fc rgb '#d62728', '' index " << p << " using ($1+" << 0.5 * h.bin_deg
      << "):2 with boxes fc rgb '#2ca02c'\n";
  }
  g << "unset multiplot\nunset output\n";
  return g.str();
}

}  // namespace

void plotHeatmap(const sweep::Heatmap& h, const std::string& data_path, const std::string& png_path) {
  renderPng(heatmapScript(h), {GnuplotFile{kData, "", data_path}}, png_path);
}

void plotPitchHistogram(const sweep::PitchHistogram& h, const std::string& data_path, const std::string& png_path) {
  renderPng(histogramScript(h), {GnuplotFile{kData, "", data_path}}, png_path);
}

}  // namespace centaur::cli
