#include "cli/plot_primitive.hpp"

#include <array>
#include <cstdio>
#include <sstream>

#include "cli/gnuplot.hpp"
#include "common/error.hpp"
#include "common/excerpt.hpp"
#include "data/primitive_summary.hpp"

namespace centaur::cli {
namespace {

// Per-foot colours (FL, FR, RL, RR), waist x/y/z colours, and phase shading.
const std::array<const char*, 4> kFootColour = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728"};
const std::array<const char*, 3> kAxisColour = {"#d62728", "#2ca02c", "#1f77b4"};
const char* const kFlightShade = "#c9d6e8";
const char* const kPartialShade = "#fbefc5";

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

/// Columns of the data file (1-based, gnuplot's numbering).
int forceCol(int foot, int axis) { return 2 + 3 * foot + axis; }
int footCol(int foot, int axis) { return 14 + 3 * foot + axis; }
int baseCol(int axis) { return 26 + axis; }

const char* const kDash = "dt (8,5)";

/// Plot clauses for the four feet of the data columns col(foot, axis): z solid, x dashed. Left and right feet
/// of a symmetric motion coincide, so the right feet (FR, RR) are drawn first with wide lines and the left
/// feet (FL, RL) on top with narrow ones: coinciding curves show as a narrow line with a coloured rim.
std::string footCurves(const std::string& data, int (*col)(int, int)) {
  std::ostringstream g;
  const int order[4] = {1, 3, 0, 2};
  bool first = true;
  for (int axis : {2, 0}) {
    for (int f : order) {
      const bool right = f == 1 || f == 3;
      g << (first ? "" : ", ") << data << " u 1:" << col(f, axis) << " w l lw " << (right ? "4.5" : "1.8")
        << (axis == 0 ? std::string(" ") + kDash : std::string()) << " lc rgb '"
        << kFootColour[static_cast<std::size_t>(f)] << "' notitle";
      first = false;
    }
  }
  for (int f = 0; f < 4; ++f) {  // legend in storage order
    const bool right = f == 1 || f == 3;
    g << ", keyentry w l lw " << (right ? "4.5" : "1.8") << " lc rgb '" << kFootColour[static_cast<std::size_t>(f)]
      << "' t '" << data::kFootNames[static_cast<std::size_t>(f)] << "'";
  }
  return g.str();
}

/// The data file of the plot (its name in the script: kDataFile).
const char* const kDataFile = "primitive.dat";

std::string plotData(const data::Primitive& p) {
  std::ostringstream out;
  out << "# t force(FL,FR,RL,RR x,y,z) foot_pos(FL,FR,RL,RR x,y,z) base_pos(x,y,z)\n";
  char buf[32];
  for (Eigen::Index i = 0; i < p.t.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.9g", p.t(i));
    out << buf;
    for (Eigen::Index c = 0; c < 12; ++c) {
      std::snprintf(buf, sizeof buf, " %.9g", p.force(i, c));
      out << buf;
    }
    for (Eigen::Index c = 0; c < 12; ++c) {
      std::snprintf(buf, sizeof buf, " %.9g", p.foot_pos(i, c));
      out << buf;
    }
    for (Eigen::Index c = 0; c < 3; ++c) {
      std::snprintf(buf, sizeof buf, " %.9g", p.base_pos(i, c));
      out << buf;
    }
    out << '\n';
  }
  return out.str();
}

std::string fmtApex(double z) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "z = %.3f m", z);
  return buf;
}

// "name: planned primitive (status, iterations) - flight, apex" of a primitive without a title of its own.
std::string defaultTitle(const data::Primitive& p, const data::PrimitiveSummary& s) {
  std::ostringstream t;
  t << excerpt(p.name, 60) << ": planned primitive (" << excerpt(p.solve.status, 40) << ", " << p.solve.iterations
    << " iterations)";
  if (!s.flight.empty()) {
    char buf[160];
    std::snprintf(buf, sizeof buf, " - flight %.3f s, apex +%.3f m at %.3f s", s.flight_time, s.apex_gain,
                  s.apex_time);
    t << buf;
  }
  return t.str();
}

// The terminal, axes and key settings, and the shaded flight and partial-support intervals behind every panel.
void writeSetupAndShades(std::ostringstream& g, const data::Primitive& p, const PlotOptions& o,
                         const data::PrimitiveSummary& s, const std::vector<data::TimeInterval>& partial_iv) {
  const Eigen::Index n = p.t.size();
  g << "set terminal pngcairo size " << o.width_px << "," << o.height_px << " enhanced font 'Sans,11'\n"
    << "set output " << gnuplotQuote(kGnuplotPng) << "\n"
    << "set datafile commentschars '#'\n"
    << "set xrange [" << num(p.t(0)) << ":" << num(p.t(n - 1)) << "]\n"
    << "set grid xtics ytics lc rgb '#dddddd' lw 1 dt 1\n"
    << "set border lw 1\n"
    << "set offsets 0, 0, graph 0.06, graph 0.06\n"
    << "set key outside right top vertical Left reverse samplen 3.5 spacing 1.15 font ',10' box lc rgb '#bbbbbb'\n"
    << "set lmargin at screen 0.085\nset rmargin at screen 0.80\n";
  int obj = 1;
  for (const auto& iv : s.flight) {
    g << "set object " << obj++ << " rect from first " << num(iv.start) << ", graph 0 to first " << num(iv.end)
      << ", graph 1 behind fc rgb '" << kFlightShade << "' fs solid 1.0 noborder\n";
  }
  for (const auto& iv : partial_iv) {
    g << "set object " << obj++ << " rect from first " << num(iv.start) << ", graph 0 to first " << num(iv.end)
      << ", graph 1 behind fc rgb '" << kPartialShade << "' fs solid 1.0 noborder\n";
  }
}

std::string buildScript(const data::Primitive& p, const PlotOptions& o) {
  const data::PrimitiveSummary s = data::summarize(p);
  const Eigen::Index n = p.t.size();

  // Phases: flight = all feet off; partial support = some feet off, some on.
  std::vector<bool> partial(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    const double on = p.contact.row(i).sum();
    partial[static_cast<std::size_t>(i)] = on > 0.5 && on < 3.5;
  }
  const auto partial_iv = data::intervalsWhere(p.t, partial, true);

  const std::string title = o.title.empty() ? defaultTitle(p, s) : o.title;

  std::ostringstream g;
  writeSetupAndShades(g, p, o, s, partial_iv);
  auto shadeKeys = [&]() {
    std::string k;
    if (!s.flight.empty()) {
      k += ", keyentry w boxes fs solid 1.0 fc rgb '" + std::string(kFlightShade) + "' t 'flight (all feet off)'";
    }
    if (!partial_iv.empty()) {
      k += ", keyentry w boxes fs solid 1.0 fc rgb '" + std::string(kPartialShade) + "' t 'some feet off'";
    }
    return k;
  };
  const std::string d = gnuplotQuote(kDataFile);
  g << "set multiplot title " << gnuplotQuote(title, true) << " font ',14'\n";

  // ---- panel 1: contact forces -----------------------------------------------------------------
  g << "set tmargin at screen 0.935\nset bmargin at screen 0.665\n"
    << "set title 'Contact forces on the robot (world frame)' font ',12'\n"
    << "set ylabel 'force [N]'\nunset xlabel\nset format x ''\n"
    << "plot ";
  g << footCurves(d, forceCol) << ", keyentry w l lw 2 lc rgb 'black' t 'F_z (solid)', keyentry w l lw 2 "
    << kDash << " lc rgb 'black' t 'F_x (dashed)'" << shadeKeys() << "\n";

  // ---- panel 2: feet positions -----------------------------------------------------------------
  g << "set tmargin at screen 0.615\nset bmargin at screen 0.345\n"
    << "set title 'Feet (wheel centres), world frame' font ',12'\n"
    << "set ylabel 'position [m]'\n"
    << "plot ";
  g << footCurves(d, footCol) << ", keyentry w l lw 2 lc rgb 'black' t 'z (solid)', keyentry w l lw 2 " << kDash
    << " lc rgb 'black' t 'x (dashed)'" << shadeKeys() << "\n";

  // ---- panel 3: waist position -----------------------------------------------------------------
  g << "set tmargin at screen 0.295\nset bmargin at screen 0.06\n"
    << "set title 'Waist (base) position, world frame' font ',12'\n"
    << "set ylabel 'position [m]'\nset xlabel 'time [s]'\nset format x '%g'\n"
    << "set offsets 0, 0, graph 0.16, graph 0.06\n"
    << "set label 1 " << gnuplotQuote("apex " + fmtApex(s.apex_height), true) << " at first " << num(s.apex_time) << ", first "
    << num(s.apex_height) << " center point pt 7 ps 1.2 lc rgb '#1f77b4' offset 0,1.1\n"
    << "plot ";
  const char* axis[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    g << (a ? ", " : "") << d << " u 1:" << baseCol(a) << " w l lw 2 lc rgb '" << kAxisColour[a] << "' t '"
      << axis[a] << "'";
  }
  g << shadeKeys() << "\n";
  g << "unset multiplot\nunset output\n";
  return g.str();
}

}  // namespace

void plotPrimitive(const data::Primitive& p, const std::string& png_path, const PlotOptions& options) {
  if (p.t.size() < 2) throw InputError("primitive '" + excerpt(p.name) + "' has fewer than 2 samples: nothing to plot");
  if (p.force.rows() != p.t.size() || p.foot_pos.rows() != p.t.size() || p.base_pos.rows() != p.t.size() ||
      p.contact.rows() != p.t.size() || p.force.cols() != 12 || p.foot_pos.cols() != 12 ||
      p.base_pos.cols() != 3 || p.contact.cols() != 4) {
    throw InputError("primitive '" + excerpt(p.name) + "': force/foot_pos/base_pos/contact do not match t in size");
  }
  renderPng(buildScript(p, options), {{kDataFile, plotData(p), ""}}, png_path);
}

}  // namespace centaur::cli
