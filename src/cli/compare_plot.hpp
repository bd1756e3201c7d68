#pragma once
// Plot of pitch histories like the paper's Fig. 4: one panel per jump, one curve per stabilizer mode, drawn by
// gnuplot (pngcairo) straight from the CSV that `centaur compare` writes (sim::pitchCsv: column 1 = time [s],
// then one column per run, "nan" where a run has no sample). The PNG is written to a temporary sibling and
// renamed, so a failed plot never leaves a half-written image.
#include <string>
#include <vector>

namespace centaur::cli {

struct PitchCurve {
  int column = 2;      ///< 1-based CSV column of the curve's values (column 1 is time)
  std::string label;   ///< legend entry, e.g. "raibert (success)"
  std::string colour;  ///< "#rrggbb"
};

struct PitchPanel {
  std::string title;  ///< e.g. "squat-jump"
  std::vector<PitchCurve> curves;
  double t_min = 0.0, t_max = 0.0;  ///< [s] time axis; t_max <= t_min = autoscale
};

struct PitchPlotOptions {
  int width_px = 1100;
  int panel_height_px = 420;  ///< per panel
  std::string title = "IMU pitch (ZYX Euler pitch of w_R_imu)";
};

/// The colour of a stabilizer mode (none, raibert, angmom, ocp; others grey).
std::string modeColour(const std::string& mode);

/// Draw `panels` (stacked vertically, shared time axis label) from `csv_path` into `png_path` (parent
/// directories created). Throws InputError for no panels, RuntimeError if gnuplot is missing or fails.
void plotPitchPanels(const std::string& csv_path, const std::vector<PitchPanel>& panels, const std::string& png_path,
                     const PitchPlotOptions& options = {});

}  // namespace centaur::cli
