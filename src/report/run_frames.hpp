#pragma once
// The replay of a simulated run: the log's rows sampled at the pose rate, each turned into world poses of the
// robot's moving bodies (forward kinematics from the logged base pose and joint positions) and the ground-truth
// contact force on each contact body.
//
// Joint angles are the log's `q` (the measurement given to the controller: equal to the truth unless the run
// had sensor noise or latency); the base pose is the simulator's truth (`base_pos`, `base_quat`).
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "data/sim_log_file.hpp"
#include "report/kinematic_model.hpp"

namespace centaur::report {

/// Rows of `t` one per 1/rate_hz seconds (the first row at or after each tick t[0] + k / rate_hz; every row when
/// the log is sparser), the last row always included.
std::vector<Eigen::Index> frameRows(const Eigen::VectorXd& t, double rate_hz);

/// {"rate", "frames", "t": float32 base64 (robot time of each frame), "pose": int16 channels (per frame and
/// moving body slot: position 3, quaternion w,x,y,z 4; W), "force": int16 channels (per frame and contact body: force on the body 3, W),
/// "force_slots": [body slot of each contact body], "force_radius": [its tyre radius]}.
/// InputError naming the log and `joint_names` / `contact_bodies` if the model lacks one of them.
nlohmann::json runFrames(const data::SimLogFile& log, KinematicModel& model, double rate_hz);

}  // namespace centaur::report
