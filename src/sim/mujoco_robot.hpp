#pragma once
// The simulated robot: a MuJoCo model behind the RobotInterface.
//
// Timing (defaults): physics at 2 kHz (model timestep 0.0005 s), the joint impedance law
//   tau = tau_ff + kp (q_ref - q) + kd (qd_ref - qd),   saturated at +-tau_max (actuator ctrlrange x gear)
// evaluated at EVERY physics step from the true joint state (the drives' own encoders), and the controller
// called every `control_decimation` physics steps (2 -> 1 kHz). The law uses the last JointCommand written.
//
// Measurements (RobotState): sampled at the start of each control period, after mj_step1 (positions and
// velocities of that instant); the accelerometer is the one of the last physics step (it needs the applied
// torques). RobotState::tau ("measured torque") is the actuator torque applied during the last physics step
// (after saturation), i.e. what an ideal joint torque sensor would read. Optional Gaussian noise (seeded) and
// a measurement delay of `latency_periods` control periods; both off by default.
//
// Joint order: the model's joint order, as RobotModel::jointNames(); each joint's motor is the actuator that acts
// on it, whatever the actuators' order in the MJCF. Every actuator must be a torque motor on a hinge/slide joint.
//
// Perturbations (sweeps; all off by default, and then the model is used exactly as loaded): every robot body's
// mass and inertia scaled, the whole robot's CoM shifted (by moving the floating-base body's CoM), and a push
// (a constant force at one body's CoM during a time window). Only the simulated robot changes: a controller
// builds its own model from the MJCF and keeps the nominal masses.
//
// Deterministic: the same settings and the same controller give bitwise-identical trajectories.
// Model/Data split: everything is allocated in the constructor; the loop never allocates.
#include <mujoco/mujoco.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "controller/robot_interface.hpp"

namespace centaur::sim {

/// Standard deviations of additive Gaussian measurement noise (0 = off).
struct SensorNoise {
  double q = 0.0;            ///< [rad] joint positions
  double qd = 0.0;           ///< [rad/s] joint velocities
  double tau = 0.0;          ///< [Nm] measured joint torques
  double gyro = 0.0;         ///< [rad/s] IMU angular velocity
  double acc = 0.0;          ///< [m/s^2] IMU specific force
  double orientation = 0.0;  ///< [rad] IMU orientation (random rotation vector per sample)
};

/// An external push: a constant force on one body (at its CoM) during [start, start + duration) robot time.
struct PushSettings {
  double impulse = 0.0;                          ///< [N s] magnitude; 0 = no push (the default)
  std::string body = "pelvis";                   ///< MJCF body pushed
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< world frame, unit
  double start = 1.0;                            ///< [s] robot time
  double duration = 0.1;                         ///< [s]; force = impulse / duration * direction
};

struct SimSettings {
  std::string model_path;          ///< MJCF file
  std::string scene_xml;           ///< "" = the MJCF carries its world; else the scene that includes it (sim/robot_setup.hpp)
  std::string imu_orientation = "imu_quat", imu_gyro = "imu_gyro", imu_accelerometer = "imu_acc";  ///< IMU sensors
  double timestep = 0.0005;        ///< [s] physics step (overrides the MJCF's)
  int control_decimation = 2;      ///< physics steps per controller call (2 -> 1 kHz at 2 kHz physics)
  std::string solver = "model";    ///< contact solver: newton, cg, pgs, or model (keep the MJCF's)
  double wall_x = -0.578;          ///< [m] x of the wall's front face (normal +x; body/geom `wall`), if any
  double friction = 1.0;           ///< [-] sliding friction of the ground and the contact bodies' geoms
  SensorNoise noise;               ///< measurement noise (off)
  int latency_periods = 0;         ///< measurement delay [control periods] (off)
  std::uint64_t seed = 1;          ///< noise random seed
  // The simulated robot's deviation from its model (the controller keeps the nominal model). Defaults: none,
  // and then the loaded model is not touched at all.
  double mass_scale = 1.0;         ///< [-] every robot body's mass and rotational inertia multiplied by this
  Eigen::Vector3d com_offset = Eigen::Vector3d::Zero();  ///< [m] whole-robot CoM shift, floating-base frame
                                   ///< (realised by moving the floating-base body's CoM)
  PushSettings push;               ///< external push (off)
  std::string keyframe = "home";   ///< initial state (keyframe name; "" or missing -> the model's qpos0)
  /// Bodies whose contact forces are reported (ground truth), e.g. the four wheels.
  std::vector<std::string> contact_bodies = {"wheel_1", "wheel_2", "wheel_3", "wheel_4"};
  /// Keep the visual-only geoms (contype = conaffinity = 0). Needed to render; without them every physics step
  /// skips posing ~80 shapes (same dynamics and contacts; see model/mjcf_load.hpp).
  bool visual_geoms = true;
};

class MujocoRobot final : public RobotInterface {
 public:
  /// Loads the MJCF (InputError naming the file if it cannot), applies the settings and resets.
  explicit MujocoRobot(const SimSettings& settings);
  ~MujocoRobot() override;
  MujocoRobot(const MujocoRobot&) = delete;
  MujocoRobot& operator=(const MujocoRobot&) = delete;

  // ---- RobotInterface ----
  Eigen::Index numJoints() const override { return n_; }
  /// The latest (possibly delayed, noisy) measurement.
  void read(RobotState& state) const override;
  /// Store the references used by the impedance law from the next physics step on (no allocation).
  void write(const JointCommand& command) override;

  // ---- loop ----
  /// Back to the keyframe, zero command (all gains zero), time 0, delay line filled with the first sample.
  void reset();
  /// One control period: beginPeriod(state), controller.tick(state, command), endPeriod(command). No allocation.
  void controlPeriod(Controller& controller, RobotState& state, JointCommand& command);
  /// First half of a control period: the positions/velocities of this instant and their sensors, sampled into
  /// the delay line; `state` receives the (possibly delayed, noisy) measurement the controller sees.
  void beginPeriod(RobotState& state);
  /// Second half: write(command), then `control_decimation` physics steps with the impedance law.
  void endPeriod(const JointCommand& command);
  /// One physics step with the current command (impedance law + mj_step). Measurements are not sampled.
  void physicsStep();
  /// [s] wall time of controller.tick() in the last controlPeriod().
  double lastTickSeconds() const { return last_tick_s_; }

  // ---- description ----
  const SimSettings& settings() const { return settings_; }
  const std::vector<std::string>& jointNames() const { return joint_names_; }
  const Eigen::VectorXd& effortLimits() const { return tau_max_; }  ///< [Nm]
  const Eigen::VectorXd& positionLower() const { return q_lo_; }   ///< [rad] (-inf if unlimited)
  const Eigen::VectorXd& positionUpper() const { return q_hi_; }   ///< [rad] (+inf if unlimited)
  double controlPeriodSeconds() const { return settings_.timestep * settings_.control_decimation; }
  int numContactBodies() const { return static_cast<int>(contact_body_ids_.size()); }

  // ---- ground truth (simulator state, for logs and tests; never for the controller) ----
  double time() const;
  Eigen::Vector3d basePosition() const;        ///< w_p_base [m]
  Eigen::Quaterniond baseOrientation() const;  ///< w_R_base
  Eigen::Matrix<double, 6, 1> baseVelocity() const;  ///< [w_v (world), b_omega (base frame)]
  void jointPositions(Eigen::Ref<Eigen::VectorXd> q) const;
  void jointVelocities(Eigen::Ref<Eigen::VectorXd> qd) const;
  /// Torques applied in the last physics step (after saturation) [Nm].
  const Eigen::VectorXd& appliedTorque() const { return tau_applied_; }
  /// Unsaturated impedance-law torque of the last physics step [Nm].
  const Eigen::VectorXd& commandedTorque() const { return tau_cmd_; }
  const JointCommand& command() const { return command_; }
  /// Total contact force on each contact body (sum over its contacts, force exerted ON the body by the
  /// other geom), world frame [N]; columns follow settings().contact_bodies. From the last physics step.
  void contactForces(Eigen::Ref<Eigen::Matrix3Xd> w_f) const;

  /// Raw MuJoCo access for rendering (const model; the renderer needs a non-const data pointer).
  const mjModel* model() const { return m_; }
  mjData* data() const { return d_; }

 private:
  void sampleMeasurement();
  void applyImpedance();
  // The constructor's steps (each deletes the model and data it was given before it throws on bad input).
  void configureModel();
  void readActuators();
  void findBaseAndSensors();
  void setContactsAndWall();
  void checkPush();
  /// Scales the robot's masses and shifts its CoM (SimSettings::mass_scale, com_offset), then mj_setConst.
  void applyModelError();
  /// The push force of the coming physics step (xfrc_applied of the pushed body), from the robot time.
  void applyPush();

  SimSettings settings_;
  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
  Eigen::Index n_ = 0;
  std::vector<std::string> joint_names_;
  std::vector<int> qpos_adr_, dof_adr_;
  std::vector<int> motor_;  // per joint (model order), its actuator's index
  Eigen::VectorXd gear_, tau_max_, q_lo_, q_hi_;
  int base_qpos_ = -1, base_dof_ = -1;  // free joint (-1 if fixed base)
  int push_body_ = -1;                   // body pushed (-1: no push)
  double last_tick_s_ = 0.0;
  int key_ = -1;
  int sensor_quat_ = -1, sensor_gyro_ = -1, sensor_acc_ = -1;
  std::vector<int> contact_body_ids_;

  JointCommand command_;
  Eigen::VectorXd tau_applied_, tau_cmd_;

  // delay line of measurements (latency_periods + 1 entries)
  std::vector<RobotState> delay_;
  std::size_t head_ = 0;

  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace centaur::sim
