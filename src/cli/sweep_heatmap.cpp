#include "cli/sweep_heatmap.hpp"

#include <stdlib.h>

#include <cctype>
#include <filesystem>
#include <sstream>

#include "cli/plot_primitive.hpp"  // runGnuplot
#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace centaur::cli {

namespace {

namespace fs = std::filesystem;

/// Text that goes into the script: only [A-Za-z0-9_./+-] and spaces (the spec guarantees it for keys and values);
/// anything else is replaced, so nothing can end a gnuplot string.
std::string safe(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || std::string("_./+- ").find(c) != std::string::npos;
    out += ok ? c : '?';
  }
  return "'" + out + "'";
}

std::string tics(const std::vector<std::string>& labels) {
  std::string s = "(";
  for (std::size_t i = 0; i < labels.size(); ++i) s += (i ? ", " : "") + safe(labels[i]) + " " + std::to_string(i);
  return s + ")";
}

std::string buildScript(const sweep::Heatmap& h, const std::string& data, const std::string& png) {
  const std::size_t cols = h.panels.empty() ? 1 : std::min<std::size_t>(h.panels.size(), 4);
  const std::size_t rows = (h.panels.size() + cols - 1) / cols;
  std::ostringstream g;
  g << "set terminal pngcairo size " << 380 * cols << "," << 60 + 330 * rows << " noenhanced font 'Sans,10'\n"
    << "set output " << safe(png) << "\n"
    << "set multiplot layout " << rows << "," << cols << " title " << safe("success rate over " + h.x + " x " + h.y)
    << " font ',13'\n"
    << "set palette defined (0 '#d62728', 0.5 '#f2c14e', 1 '#2ca02c')\nset cbrange [0:1]\nset cbtics 0.25\n"
    << "set xrange [-0.5:" << h.x_values.size() - 0.5 << "]\nset yrange [-0.5:" << h.y_values.size() - 0.5 << "]\n"
    << "set xtics " << tics(h.x_values) << " rotate by 45 right\nset ytics " << tics(h.y_values) << "\n"
    << "set xlabel " << safe(h.x) << "\nset ylabel " << safe(h.y) << "\nset tics nomirror\nunset key\n"
    << "set style fill solid 1.0 noborder\n";
  for (std::size_t p = 0; p < h.panels.size(); ++p) {
    g << "set title " << safe(h.panels[p].jump + " / " + h.panels[p].mode) << "\n"
      << "plot " << safe(data) << " index " << p
      << " using 1:2:($1-0.5):($1+0.5):($2-0.5):($2+0.5):3 with boxxyerror fc palette, \\\n"
      << "     '' index " << p << " using ($6 == 0 ? $1 : NaN):2:($1-0.5):($1+0.5):($2-0.5):($2+0.5) with boxxyerror "
      << "fc rgb '#bbbbbb', \\\n"
      << "     '' index " << p
      << " using 1:2:($4 > 0 ? sprintf('%d/%d', $5, $4) : ($6 == 0 ? 'no plan' : '')) with labels font ',9'\n";
  }
  g << "unset multiplot\nunset output\n";
  return g.str();
}

/// A private directory whose path is plain text (falls back to /tmp if TMPDIR holds other characters).
fs::path privateDirectory() {
  std::error_code ec;
  fs::path base = fs::temp_directory_path(ec);
  if (ec || base.string().find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_./-") !=
                std::string::npos) {
    base = "/tmp";
  }
  std::string pattern = (base / "centaur-heatmap-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) throw RuntimeError("cannot create a temporary directory in " + base.string());
  return pattern;
}

}  // namespace

void plotHeatmap(const sweep::Heatmap& h, const std::string& data_path, const std::string& png_path) {
  const fs::path dir = privateDirectory();
  std::error_code ec;
  try {
    const fs::path data = dir / "heatmap.dat", png = dir / "heatmap.png";
    fs::copy_file(data_path, data, ec);
    if (ec) throw RuntimeError("cannot copy " + data_path + ": " + ec.message());
    runGnuplot(buildScript(h, data.string(), png.string()));
    if (!fs::exists(png, ec) || fs::file_size(png, ec) < 8) throw RuntimeError("gnuplot did not draw " + png_path);
    const std::string tmp = temporaryPathFor(png_path);
    fs::copy_file(png, tmp, fs::copy_options::overwrite_existing, ec);
    if (ec) throw RuntimeError("cannot write " + png_path + ": " + ec.message());
    commitFile(tmp, png_path);
  } catch (...) {
    fs::remove_all(dir, ec);
    throw;
  }
  fs::remove_all(dir, ec);
}

}  // namespace centaur::cli
