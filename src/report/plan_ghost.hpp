#pragma once
// A lower-body primitive as the viewer's translucent ghost (the planned 5-mass template: waist box, four feet at
// the wheel centres, template legs from the waist origin to the feet, planned contact-force arrows), on the
// robot's clock: the primitive's t = 0 is robot time `start` (the log's controller.settle_time); before it the
// first sample holds, after its end the last one, as in the online replay.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "data/primitive.hpp"

namespace centaur::report {

/// {"t0", "rate", "t": float32 base64 (robot time of each ghost frame), "pose": int16 channels (per frame:
/// waist position 3, waist quaternion w,x,y,z 4, feet positions 4 x 3, forces on the feet 4 x 3, all W),
/// "contact": uint8 base64 (frames x 4), "waist_half_extents", "foot_radius"}.
nlohmann::json planGhost(const data::Primitive& p, double start, double rate_hz,
                         const std::vector<double>& waist_half_extents);

/// Row of `p` for robot time t when the primitive starts at `start` (clamped to the first and last row).
Eigen::Index planRow(const data::Primitive& p, double start, double t);

/// Metadata of the plan: file, name, solver status, iterations, cost, solve time, constraint violation,
/// duration, flight time, apex height.
nlohmann::json planInfo(const data::Primitive& p, const std::string& file);

/// Where the wall's front face stands for a plan: behind the feet the plan puts on a wall (a planned contact more
/// than 5 cm above the ground), else far away (x = -20 m, as the squat-jump simulation puts it).
double planWallX(const data::Primitive& p);

/// Pitch [rad] of the rotation with quaternion (w, x, y, z): the middle angle of its ZYX decomposition,
/// asin(2 (w y - x z) / |q|^2), positive nose down (the convention of the paper's Fig. 4 and of compare).
double pitchOf(double w, double x, double y, double z);

}  // namespace centaur::report
