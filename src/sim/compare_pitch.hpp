#pragma once
// Pitch of an orientation, and the IMU pitch history of a simulation log (the quantity of the paper's Fig. 4).
//
// Convention: the pitch of w_R_imu is the middle angle of its ZYX (yaw-pitch-roll) Euler decomposition,
// w_R_imu = Rz(yaw) Ry(pitch) Rx(roll), pitch in [-90, 90] deg. From the quaternion (w, x, y, z) of w_R_imu:
//     pitch = asin(-R_20) = asin(2 (w y - x z) / |q|^2).
// Positive pitch = nose (IMU x axis) down: it equals minus the elevation angle of the IMU x axis above the
// horizontal plane, and does not depend on yaw. It is the same convention as the runner's peak_pitch_deg
// (which uses the ground-truth pelvis orientation instead of the IMU).
#include <string>
#include <vector>

namespace centaur::sim {

/// Pitch [rad] of the rotation given by the quaternion (w, x, y, z) (any non-zero norm; q and -q agree).
double pitchFromQuaternion(double w, double x, double y, double z);

/// A pitch history.
struct PitchSeries {
  std::vector<double> t;          ///< [s]
  std::vector<double> pitch_deg;  ///< [deg]
};

/// Read the datasets `t` (N) and `quat_dataset` (N x 4, order w, x, y, z; "imu_quat" or "base_quat") of a
/// simulation log (sim::SimLog's HDF5 file) and return the pitch of each sample. Throws InputError naming the
/// file and dataset if the file cannot be read or a dataset is missing or wrongly shaped.
PitchSeries readLogPitch(const std::string& log_path, const std::string& quat_dataset = "imu_quat");

}  // namespace centaur::sim
