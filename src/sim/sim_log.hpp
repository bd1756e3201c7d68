#pragma once
// The log of a simulation run, sampled once per control period (or every log.decimation periods), and its
// HDF5 writer. Format (documented in docs/sim.md): one dataset per signal, first dimension = samples,
// each with attributes `units` and `description`; root attributes joint_names, contact_bodies, config (the
// effective YAML), scenario, format.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controller/robot_interface.hpp"

namespace centaur::sim {

class MujocoRobot;

class SimLog {
 public:
  /// Reserve room for `capacity` samples (no reallocation below that).
  SimLog(std::vector<std::string> joint_names, std::vector<std::string> contact_bodies, std::size_t capacity);

  /// Sample k, part 1, at the START of control period k (time t_k): the simulator's ground truth
  /// (base pose/velocity at t_k; wheel forces of the last physics step before t_k).
  void appendTruth(const MujocoRobot& robot);
  /// Sample k, part 2, right AFTER control period k: the measurement the controller saw (time t_k), its
  /// command, and the impedance torques of the period's last physics step.
  void appendLoop(const MujocoRobot& robot, const RobotState& measured, const JointCommand& command);

  std::size_t size() const { return t_.size(); }
  const std::vector<std::string>& jointNames() const { return joint_names_; }

  /// Write the HDF5 file atomically (temporary file, then rename). Throws RuntimeError on I/O failure.
  /// `summary_json`: the run's outcome and metrics (root attribute `summary`; "" = none).
  void writeHdf5(const std::string& path, const std::string& config_yaml, const std::string& scenario,
                 const std::string& summary_json = "") const;

 private:
  std::vector<std::string> joint_names_, contact_bodies_;
  std::size_t n_, nc_;
  std::vector<double> t_, q_, qd_, tau_cmd_, tau_meas_, tau_applied_, q_ref_, qd_ref_, tau_ff_, kp_, kd_;
  std::vector<double> imu_quat_, imu_omega_, imu_acc_, base_pos_, base_quat_, base_vel_, wheel_force_;
  Eigen::Matrix3Xd force_buffer_;
};

}  // namespace centaur::sim
