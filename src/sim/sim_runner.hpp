#pragma once
// Runs a closed loop (MujocoRobot + Controller) for a configured duration, logs it, renders it, and
// summarises the outcome. Outputs are written atomically at the end, each with the effective
// configuration saved next to it (<output stem>.config.yaml).
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/output_guard.hpp"
#include "controller/robot_interface.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_config.hpp"

namespace centaur::sim {

struct RunOutputs {
  std::string log_path;        ///< HDF5 log; "" = none
  std::string video_path;      ///< mp4; "" = none
  std::string snapshot_path;   ///< PNG; "" = none
  double snapshot_time = 0.0;  ///< [s] robot time of the snapshot
};

struct RunSummary {
  std::string outcome = "success";       ///< "success" or "fall"
  double duration_s = 0.0;               ///< [s] simulated time run
  double fall_time_s = -1.0;             ///< [s] first time the fall criterion held (-1: never)
  double pelvis_drift_m = 0.0;           ///< [m] max |w_p_base(t) - w_p_base(0)| over the run
  double pelvis_drift_xy_m = 0.0;        ///< [m] same, horizontal only
  double final_pelvis_height_m = 0.0;    ///< [m]
  double peak_pitch_deg = 0.0;           ///< [deg] max |pitch| of the pelvis (ground truth)
  double peak_roll_deg = 0.0;            ///< [deg] max |roll|
  double max_joint_limit_violation = 0.0;  ///< [rad] max over time and joints of the distance beyond a limit
  double max_torque_ratio = 0.0;         ///< [-] max |applied torque| / effort limit (1 = saturated)
  double wall_time_s = 0.0;              ///< [s] wall time of the loop (physics + impedance + controller)
  double real_time_factor = 0.0;         ///< simulated time / wall_time_s
  double period_time_us_median = 0.0;    ///< [us] median wall time of a control period (physics + controller)
  double tick_time_us_median = 0.0;      ///< [us] median wall time of the controller's tick() alone
  double tick_time_us_p99 = 0.0;         ///< [us] 99th percentile of the same
  double control_period_us = 0.0;        ///< [us] the control period the tick must fit in (1000 at 1 kHz)
  long ticks_over_period = 0;            ///< ticks that took longer than the control period
  /// The controller cannot keep its rate on this machine: its median tick exceeds the control period.
  bool tickOverBudget() const { return control_period_us > 0.0 && tick_time_us_median > control_period_us; }
  long control_periods = 0;
  long physics_steps = 0;
  int video_frames = 0;
  std::vector<std::string> files;        ///< files written
  std::map<std::string, double> extra;   ///< the scenario observer's numbers (RunObserver::summary)
};

/// The numbers of a run that depend only on the simulation (outcome, times, drift, pitch, torque ratio, counts and
/// the scenario observer's numbers; no wall times, no file names): part of `simulate --json`, and recorded in the
/// log (attribute `summary`) so that identical runs still write identical logs.
nlohmann::json summaryJson(const RunSummary& summary);

/// Run `controller` on `robot` (already reset) for config.duration seconds. controller.start() is called
/// first. Throws InputError for bad outputs (e.g. snapshot time beyond the duration) BEFORE running, and
/// RuntimeError for I/O failures (no half-written file is left).
RunSummary runSimulation(MujocoRobot& robot, Controller& controller, const SimConfig& config,
                         const RunOutputs& outputs, const std::string& scenario_name,
                         RunObserver* observer = nullptr);

/// The whole scenario: load the configuration (defaults <- file <- overrides), refuse outputs that would
/// overwrite an input (the configuration file, the model, the scenario's input-file options; guardOutputs),
/// build the robot and the scenario's controller, run. `options` are the scenario options given on the command
/// line.
RunSummary runScenario(const Scenario& scenario, const std::string& config_file,
                       const std::vector<std::string>& overrides, const std::map<std::string, std::string>& options,
                       const RunOutputs& outputs);

/// Where the effective configuration of an output goes: <dir>/<stem>.config.yaml.
std::string configPathFor(const std::string& output_path);

/// Every file a run with these outputs writes (each output and its effective configuration), for guardOutputs().
std::vector<NamedPath> runOutputFiles(const RunOutputs& outputs);

}  // namespace centaur::sim
