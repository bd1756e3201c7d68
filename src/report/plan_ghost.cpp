#include "report/plan_ghost.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "data/primitive_summary.hpp"
#include "report/channel_codec.hpp"

namespace centaur::report {

double pitchOf(double w, double x, double y, double z) {
  const double n2 = w * w + x * x + y * y + z * z;
  if (!(n2 > 0.0)) return 0.0;
  return std::asin(std::clamp(2.0 * (w * y - x * z) / n2, -1.0, 1.0));
}

double planWallX(const data::Primitive& p) {
  const auto r = p.scalars.find("wheel_radius");
  const double radius = r != p.scalars.end() ? r->second : 0.078;
  const auto g = p.scalars.find("ground_z");
  const double ground = g != p.scalars.end() ? g->second : 0.0;
  double wall = INFINITY;
  for (Eigen::Index i = 0; i < p.samples(); ++i) {
    for (int k = 0; k < 4; ++k) {
      if (p.contact(i, k) != 0.0 && p.foot_pos(i, 3 * k + 2) > ground + radius + 0.05) {
        wall = std::min(wall, p.foot_pos(i, 3 * k) - radius);
      }
    }
  }
  return std::isfinite(wall) ? wall : -20.0;
}

Eigen::Index planRow(const data::Primitive& p, double start, double t) {
  const Eigen::Index n = p.samples();
  if (n == 0) return 0;
  const double t_rel = t - start;
  // the first sample at or after t_rel - 1 ns (sample times are uniform but need not be exactly k * dt)
  const double* begin = p.t.data();
  const Eigen::Index i = std::lower_bound(begin, begin + n, t_rel - 1e-9) - begin;
  return std::clamp<Eigen::Index>(i, 0, n - 1);
}

nlohmann::json planGhost(const data::Primitive& p, double start, double rate_hz,
                         const std::vector<double>& waist_half_extents) {
  const Eigen::Index n = p.samples();
  const double duration = n > 0 ? p.t[n - 1] - p.t[0] : 0.0;
  const auto frames = static_cast<Eigen::Index>(std::floor(duration * rate_hz + 1e-9)) + 1;
  std::vector<double> t, pose;
  std::vector<std::uint8_t> contact;
  for (Eigen::Index k = 0; k < frames && n > 0; ++k) {
    const Eigen::Index i = planRow(p, 0.0, p.t[0] + static_cast<double>(k) / rate_hz);
    t.push_back(start + p.t[i]);
    for (int c = 0; c < 3; ++c) pose.push_back(p.base_pos(i, c));
    for (int c = 0; c < 4; ++c) pose.push_back(p.base_quat(i, c));
    for (int c = 0; c < 12; ++c) pose.push_back(p.foot_pos(i, c));
    for (int c = 0; c < 12; ++c) pose.push_back(p.force(i, c));
    for (int c = 0; c < 4; ++c) contact.push_back(p.contact(i, c) != 0.0 ? 1 : 0);
  }
  const auto radius = p.scalars.find("wheel_radius");
  return {{"name", p.name},
          {"t0", start},
          {"rate", rate_hz},
          {"t", encodeFloat32(t)},
          {"pose", encodeInt16Channels(pose, 31)},
          {"frames", t.size()},
          {"contact", encodeBytes(contact)},
          {"waist_half_extents", waist_half_extents},
          {"foot_radius", radius != p.scalars.end() ? radius->second : 0.078}};
}

nlohmann::json planInfo(const data::Primitive& p, const std::string& file) {
  const data::PrimitiveSummary s = data::summarize(p);
  auto orNull = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  return {{"file", file},
          {"name", p.name},
          {"solve_status", p.solve.status},
          {"solve_iterations", p.solve.iterations},
          {"solve_time_s", p.solve.solve_time_s},
          {"final_cost", p.solve.cost},
          {"max_constraint_violation", p.solve.max_constraint_violation},
          {"duration_s", s.duration},
          {"flight_time_s", s.flight_time},
          {"take_off_s", orNull(s.take_off_time)},
          {"apex_height_m", orNull(s.apex_height)},
          {"config_yaml", p.config_yaml}};
}

}  // namespace centaur::report
