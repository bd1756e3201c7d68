#include "sim/sim_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>

#include <nlohmann/json.hpp>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/excerpt.hpp"
#include "common/output_guard.hpp"
#include "common/stats.hpp"
#include "data/hdf5.hpp"
#include "data/sim_log_file.hpp"
#include "sim/png_writer.hpp"
#include "sim/renderer.hpp"
#include "sim/sim_log.hpp"
#include "sim/video_writer.hpp"

namespace centaur::sim {

namespace {
constexpr double kRadToDeg = 180.0 / M_PI;

/// Roll and pitch (ZYX convention) of w_R_b.
void rollPitch(const Eigen::Quaterniond& q, double& roll, double& pitch) {
  const Eigen::Matrix3d R = q.toRotationMatrix();
  pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  roll = std::atan2(R(2, 1), R(2, 2));
}

}  // namespace

nlohmann::json summaryJson(const RunSummary& s) {
  nlohmann::json j;
  j["outcome"] = s.outcome;
  j["duration_s"] = s.duration_s;
  j["fall_time_s"] = s.fall_time_s >= 0.0 ? nlohmann::json(s.fall_time_s) : nlohmann::json(nullptr);
  j["pelvis_drift_m"] = s.pelvis_drift_m;
  j["pelvis_drift_xy_m"] = s.pelvis_drift_xy_m;
  j["final_pelvis_height_m"] = s.final_pelvis_height_m;
  j["peak_pitch_deg"] = s.peak_pitch_deg;
  j["peak_roll_deg"] = s.peak_roll_deg;
  j["max_joint_limit_violation"] = s.max_joint_limit_violation;
  j["max_torque_ratio"] = s.max_torque_ratio;
  j["control_periods"] = s.control_periods;
  j["physics_steps"] = s.physics_steps;
  for (const auto& [name, value] : s.extra) j[name] = value;  // scenario-specific numbers
  return j;
}

std::string configPathFor(const std::string& output_path) {
  std::filesystem::path p(output_path);
  p.replace_extension(".config.yaml");
  return p.string();
}

std::vector<NamedPath> runOutputFiles(const RunOutputs& out) {
  std::vector<NamedPath> files;
  for (const auto& [role, path] : {std::pair<std::string, std::string>{"--out", out.log_path},
                                   {"--video", out.video_path},
                                   {"--snapshot", out.snapshot_path}}) {
    if (path.empty()) continue;
    files.push_back({role, path});
  }
  // Outputs with the same stem share one effective configuration (the same text): listed once.
  const std::size_t n = files.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::string config = configPathFor(files[i].path);
    bool listed = false;
    for (std::size_t j = n; j < files.size(); ++j) listed = listed || files[j].path == config;
    if (!listed) files.push_back({"the effective configuration of " + files[i].role, config});
  }
  return files;
}

RunSummary runSimulation(MujocoRobot& robot, Controller& controller, const SimConfig& config,
                         const RunOutputs& out, const std::string& scenario_name, RunObserver* observer) {
  RunSummary sum;
  const double dt = robot.controlPeriodSeconds();
  const long periods = std::lround(config.duration / dt);
  if (!out.snapshot_path.empty() && !(out.snapshot_time >= 0.0 && out.snapshot_time <= config.duration + 1e-9)) {
    throw InputError("--at " + std::to_string(out.snapshot_time) + ": snapshot time must be in [0, duration = " +
                     std::to_string(config.duration) + "] s");
  }
  const std::string config_yaml = toYamlString(config.effective);
  const Eigen::Index n = robot.numJoints();

  RobotState state;
  state.resize(n);
  JointCommand command;
  command.resize(n);

  std::unique_ptr<SimLog> log;
  if (!out.log_path.empty()) {  // a log larger than the readers accept is refused before the run
    const auto rows = static_cast<unsigned long long>(periods / config.log_decimation + 2);
    const auto width = static_cast<unsigned long long>(std::max<Eigen::Index>(n, 6));
    if (rows > data::kMaxLogSamples || rows * width > data::h5::ReadLimits::kMaxElements) {
      throw InputError(config.label, "log.decimation",
                       "the log would hold " + std::to_string(rows) + " samples of " + std::to_string(n) +
                           " joints, more than a log may (" + std::to_string(data::kMaxLogSamples) +
                           " samples); raise log.decimation or shorten duration");
    }
    log = std::make_unique<SimLog>(robot.jointNames(), robot.settings().contact_bodies,
                                   static_cast<std::size_t>(periods / config.log_decimation + 2));
  }
  std::unique_ptr<Renderer> renderer;
  std::unique_ptr<VideoWriter> video;
  if (!out.video_path.empty() || !out.snapshot_path.empty()) {
    const std::string& camera = config.render.camera;
    if (!camera.empty() && mj_name2id(robot.model(), mjOBJ_CAMERA, camera.c_str()) < 0) {
      std::string names;
      for (int i = 0; i < robot.model()->ncam; ++i) {
        const char* name = mj_id2name(robot.model(), mjOBJ_CAMERA, i);
        if (name != nullptr) names += std::string(names.empty() ? "" : ", ") + name;
      }
      throw InputError(config.label, "render.camera",
                       "no camera '" + excerpt(camera) + "' in the model (its cameras: " +
                           (names.empty() ? std::string("none") : names) + "; \"\" = a free camera following the pelvis)");
    }
    renderer = std::make_unique<Renderer>(robot.model(), config.render.width, config.render.height,
                                          config.render.camera, "pelvis", config.render.shadows,
                                          config.render.reflections);
  }
  if (!out.video_path.empty()) {
    video = std::make_unique<VideoWriter>(out.video_path, config.render.width, config.render.height, config.render.fps);
  }
  bool snapshot_done = out.snapshot_path.empty();
  double next_frame_t = 0.0;

  const Eigen::Vector3d p0 = robot.basePosition();
  Eigen::VectorXd q(n);
  const double fall_tilt = config.outcome.fall_tilt_deg / kRadToDeg;
  const double fall_extra = 1.0;  // [s] keep simulating after a fall (for the video), then stop
  double wall = 0.0;
  std::vector<double> period_s, tick_s;  // per control period, for the medians
  period_s.reserve(static_cast<std::size_t>(periods));
  tick_s.reserve(static_cast<std::size_t>(periods));
  long k = 0;
  for (; k < periods; ++k) {
    const double t = robot.time();
    // --- ground-truth bookkeeping at the start of the period ---
    const Eigen::Vector3d p = robot.basePosition();
    sum.pelvis_drift_m = std::max(sum.pelvis_drift_m, (p - p0).norm());
    sum.pelvis_drift_xy_m = std::max(sum.pelvis_drift_xy_m, (p - p0).head<2>().norm());
    double roll = 0.0, pitch = 0.0;
    rollPitch(robot.baseOrientation(), roll, pitch);
    sum.peak_roll_deg = std::max(sum.peak_roll_deg, std::abs(roll) * kRadToDeg);
    sum.peak_pitch_deg = std::max(sum.peak_pitch_deg, std::abs(pitch) * kRadToDeg);
    robot.jointPositions(q);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double v = std::max(robot.positionLower()[i] - q[i], q[i] - robot.positionUpper()[i]);
      sum.max_joint_limit_violation = std::max(sum.max_joint_limit_violation, v);
      if (std::isfinite(robot.effortLimits()[i]) && robot.effortLimits()[i] > 0.0) {
        sum.max_torque_ratio = std::max(sum.max_torque_ratio, std::abs(robot.appliedTorque()[i]) / robot.effortLimits()[i]);
      }
    }
    const bool fallen = p.z() < config.outcome.fall_height || std::abs(roll) > fall_tilt || std::abs(pitch) > fall_tilt;
    if (fallen && sum.fall_time_s < 0.0) {
      sum.fall_time_s = t;
      sum.outcome = "fall";
    }
    if (sum.fall_time_s >= 0.0 && t > sum.fall_time_s + fall_extra) break;
    // --- pictures ---
    if (!snapshot_done && t + 0.5 * dt >= out.snapshot_time) {
      writePng(out.snapshot_path, renderer->render(robot.data()), renderer->width(), renderer->height());
      snapshot_done = true;
    }
    if (video && t + 0.5 * dt >= next_frame_t) {
      video->addFrame(renderer->render(robot.data()));
      next_frame_t += 1.0 / config.render.fps;
    }
    // --- one control period: measure, controller, impedance at 2 kHz ---
    const bool log_now = log && k % config.log_decimation == 0;
    if (log_now) log->appendTruth(robot);
    const auto w0 = std::chrono::steady_clock::now();
    double start_s = 0.0;  // controller.start() allocates: not part of the loop's timing
    if (k == 0) {  // the controller starts on the first period's measurement, then ticks on it (as a node does)
      robot.beginPeriod(state);
      controller.start(state, command);
      const auto t0 = std::chrono::steady_clock::now();
      start_s = std::chrono::duration<double>(t0 - w0).count();
      controller.tick(state, command);
      tick_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      robot.endPeriod(command);
    } else {
      robot.controlPeriod(controller, state, command);
      tick_s.push_back(robot.lastTickSeconds());
    }
    const double period = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count() - start_s;
    wall += period;
    period_s.push_back(period);
    if (log_now) log->appendLoop(robot, state, command);
    if (observer) observer->observe(robot, state, command);
  }
  sum.control_periods = k;
  sum.physics_steps = k * robot.settings().control_decimation;
  sum.duration_s = robot.time();
  sum.final_pelvis_height_m = robot.basePosition().z();
  sum.wall_time_s = wall;
  sum.real_time_factor = wall > 0.0 ? sum.duration_s / wall : 0.0;
  sum.period_time_us_median = 1e6 * median(period_s);
  sum.tick_time_us_median = 1e6 * median(tick_s);
  sum.tick_time_us_p99 = 1e6 * percentile(tick_s, 0.99);
  sum.control_period_us = 1e6 * dt;
  sum.ticks_over_period = std::count_if(tick_s.begin(), tick_s.end(), [dt](double x) { return x > dt; });
  if (observer) {
    sum.extra = observer->summary();
    const std::string o = observer->outcome();
    if (!o.empty() && sum.outcome != "fall") sum.outcome = o;  // a fall stays a fall
  }
  if (!snapshot_done) {  // snapshot at the very end (e.g. --at duration, or the run stopped early)
    writePng(out.snapshot_path, renderer->render(robot.data()), renderer->width(), renderer->height());
  }
  if (video) {
    sum.video_frames = video->frames();
    video->close();
    sum.files.push_back(out.video_path);
    writeTextFileAtomic(configPathFor(out.video_path), config_yaml);
  }
  if (!out.snapshot_path.empty()) {
    sum.files.push_back(out.snapshot_path);
    writeTextFileAtomic(configPathFor(out.snapshot_path), config_yaml);
  }
  if (log) {
    log->writeHdf5(out.log_path, config_yaml, scenario_name, summaryJson(sum).dump());
    sum.files.push_back(out.log_path);
    writeTextFileAtomic(configPathFor(out.log_path), config_yaml);
  }
  return sum;
}

RunSummary runScenario(const Scenario& scenario, const std::string& config_file,
                       const std::vector<std::string>& overrides, const std::map<std::string, std::string>& given,
                       const RunOutputs& outputs) {
  std::map<std::string, std::string> options;
  for (const auto& o : scenario.options) {
    auto it = given.find(o.name);
    if (it == given.end() || it->second.empty()) {
      if (o.required) throw InputError("simulate " + scenario.name + ": option --" + o.name + " is required");
      options[o.name] = o.default_value;
      continue;
    }
    if (!o.allowed.empty()) {
      bool ok = false;
      std::string list;
      for (const auto& a : o.allowed) {
        ok = ok || a == it->second;
        list += (list.empty() ? "" : ", ") + a;
      }
      if (!ok) throw InputError("--" + o.name + " '" + it->second + "': must be one of " + list);
    }
    options[o.name] = it->second;
  }
  for (const auto& kv : given) {
    if (!options.count(kv.first)) throw InputError("simulate " + scenario.name + ": unknown option --" + kv.first);
  }
  const SimConfig config = loadSimConfig(scenario.defaults_yaml, config_file, overrides);
  std::vector<NamedPath> inputs{{"--config", config_file}, {"model", config.robot.model_path}};
  for (const auto& o : scenario.options) {
    if (o.input_file) inputs.push_back({"--" + o.name, options[o.name]});
  }
  guardOutputs(inputs, runOutputFiles(outputs));
  SimSettings settings = config.robot;
  settings.visual_geoms = !outputs.video_path.empty() || !outputs.snapshot_path.empty();  // only drawing needs them
  MujocoRobot robot(settings);
  YamlReader controller_config = controllerSection(config);
  ScenarioContext ctx{config, controller_config, options, robot};
  std::unique_ptr<Controller> controller = scenario.make_controller(ctx);
  std::unique_ptr<RunObserver> observer = scenario.make_observer ? scenario.make_observer(ctx) : nullptr;
  controller_config.finish();
  return runSimulation(robot, *controller, config, outputs, scenario.name, observer.get());
}

}  // namespace centaur::sim
