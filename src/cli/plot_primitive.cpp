#include "cli/plot_primitive.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "data/primitive_summary.hpp"

extern char** environ;

namespace centaur::cli {
namespace {

namespace fs = std::filesystem;

const char* const kInstallHint = "gnuplot is not installed (needed by `centaur plot`): apt-get install gnuplot-nox";

// Per-foot colours (FL, FR, RL, RR), waist x/y/z colours, and phase shading.
const std::array<const char*, 4> kFootColour = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728"};
const std::array<const char*, 3> kAxisColour = {"#d62728", "#2ca02c", "#1f77b4"};
const char* const kFlightShade = "#c9d6e8";
const char* const kPartialShade = "#fbefc5";

/// A private temporary directory, removed with its contents on destruction.
class TempDirectory {
 public:
  TempDirectory() {
    std::error_code ec;
    fs::path base = fs::temp_directory_path(ec);
    if (ec) base = "/tmp";
    std::string pattern = (base / "centaur-plot-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw RuntimeError("cannot create a temporary directory in " + base.string() + ": " + std::strerror(errno));
    }
    path_ = pattern;
  }
  TempDirectory(const TempDirectory&) = delete;
  TempDirectory& operator=(const TempDirectory&) = delete;
  ~TempDirectory() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

std::string readText(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw RuntimeError("cannot write " + path);
}

/// Run `gnuplot script_path` with stdout and stderr to `log_path`; returns the exit status.
int spawnGnuplot(const std::string& script_path, const std::string& log_path) {
  if (!gnuplotAvailable()) throw RuntimeError(kInstallHint);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::string arg0 = "gnuplot", arg1 = script_path;
  char* argv[] = {arg0.data(), arg1.data(), nullptr};
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc == ENOENT) throw RuntimeError(kInstallHint);
  if (rc != 0) throw RuntimeError(std::string("cannot start gnuplot: ") + std::strerror(rc));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw RuntimeError(std::string("waiting for gnuplot failed: ") + std::strerror(errno));
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

/// `s` as a gnuplot single-quoted string for enhanced text: quotes doubled, markup characters escaped.
std::string gpText(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out += "''";
    } else {
      if (std::strchr("^_@&~{}", c) != nullptr) out += '\\';
      out += c;
    }
  }
  return out + "'";
}

/// `s` as a gnuplot single-quoted literal (file names): only quotes doubled.
std::string gpPath(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

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

void writeData(const data::Primitive& p, const std::string& path) {
  std::ofstream out(path);
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
  if (!out) throw RuntimeError("cannot write plot data " + path);
}

std::string fmtApex(double z) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "z = %.3f m", z);
  return buf;
}

std::string buildScript(const data::Primitive& p, const std::string& data, const std::string& png,
                        const PlotOptions& o) {
  const data::PrimitiveSummary s = data::summarize(p);
  const Eigen::Index n = p.t.size();

  // Phases: flight = all feet off; partial support = some feet off, some on.
  std::vector<bool> partial(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    const double on = p.contact.row(i).sum();
    partial[static_cast<std::size_t>(i)] = on > 0.5 && on < 3.5;
  }
  const auto partial_iv = data::intervalsWhere(p.t, partial, true);

  std::string title = o.title;
  if (title.empty()) {
    std::ostringstream t;
    t << p.name << ": planned primitive (" << p.solve.status << ", " << p.solve.iterations << " iterations)";
    if (!s.flight.empty()) {
      char buf[160];
      std::snprintf(buf, sizeof buf, " - flight %.3f s, apex +%.3f m at %.3f s", s.flight_time, s.apex_gain,
                    s.apex_time);
      t << buf;
    }
    title = t.str();
  }

  std::ostringstream g;
  g << "set terminal pngcairo size " << o.width_px << "," << o.height_px << " enhanced font 'Sans,11'\n"
    << "set output " << gpPath(png) << "\n"
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
  const std::string d = gpPath(data);
  g << "set multiplot title " << gpText(title) << " font ',14'\n";

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
    << "set label 1 " << gpText("apex " + fmtApex(s.apex_height)) << " at first " << num(s.apex_time) << ", first "
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

bool gnuplotAvailable() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) dir = ".";
    const std::string candidate = dir + "/gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate)) return true;
  }
  return false;
}

std::string runGnuplot(const std::string& script) {
  TempDirectory tmp;
  const std::string script_path = tmp.file("script.gp");
  const std::string log_path = tmp.file("gnuplot.log");
  writeText(script_path, script);
  const int status = spawnGnuplot(script_path, log_path);
  const std::string log = readText(log_path);
  if (status != 0) throw RuntimeError("gnuplot failed (exit status " + std::to_string(status) + "):\n" + log);
  return log;
}

void plotPrimitive(const data::Primitive& p, const std::string& png_path, const PlotOptions& options) {
  if (p.t.size() < 2) throw InputError("primitive '" + p.name + "' has fewer than 2 samples: nothing to plot");
  if (p.force.rows() != p.t.size() || p.foot_pos.rows() != p.t.size() || p.base_pos.rows() != p.t.size() ||
      p.contact.rows() != p.t.size() || p.force.cols() != 12 || p.foot_pos.cols() != 12 ||
      p.base_pos.cols() != 3 || p.contact.cols() != 4) {
    throw InputError("primitive '" + p.name + "': force/foot_pos/base_pos/contact do not match t in size");
  }
  if (!gnuplotAvailable()) throw RuntimeError(kInstallHint);
  ensureParentDirectory(png_path);
  TempDirectory tmp;
  const std::string data = tmp.file("primitive.dat");
  const std::string script_path = tmp.file("plot.gp");
  const std::string log_path = tmp.file("gnuplot.log");
  const std::string png_tmp = temporaryPathFor(png_path);
  writeData(p, data);
  writeText(script_path, buildScript(p, data, png_tmp, options));
  int status = 0;
  try {
    status = spawnGnuplot(script_path, log_path);
  } catch (...) {
    removeFileIfExists(png_tmp);
    throw;
  }
  const std::string log = readText(log_path);
  std::error_code ec;
  const auto size = fs::file_size(png_tmp, ec);
  if (status != 0 || ec || size < 8) {
    removeFileIfExists(png_tmp);
    throw RuntimeError("gnuplot failed to draw " + png_path + " (exit status " + std::to_string(status) + "):\n" +
                       log);
  }
  commitFile(png_tmp, png_path);
}

}  // namespace centaur::cli
