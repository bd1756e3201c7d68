#include "data/primitive_summary.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace centaur::data {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void requireRows(const Primitive& p, const RowMatrix& m, Eigen::Index cols, const char* field) {
  if (m.rows() != p.t.size() || m.cols() != cols) {
    throw std::invalid_argument("primitive '" + p.name + "': " + field + " is " + std::to_string(m.rows()) +
                                " x " + std::to_string(m.cols()) + ", expected " + std::to_string(p.t.size()) +
                                " x " + std::to_string(cols));
  }
}

// One foot's contact phases (marking the samples where it is in contact as not airborne) and its peak forces.
FootSummary footSummary(const Primitive& p, std::size_t f, std::vector<bool>& airborne) {
  const Eigen::Index n = p.t.size();
  FootSummary foot;
  foot.name = kFootNames[f];
  std::vector<bool> in_contact(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    const bool c = p.contact(i, static_cast<Eigen::Index>(f)) > 0.5;
    in_contact[static_cast<std::size_t>(i)] = c;
    if (c) airborne[static_cast<std::size_t>(i)] = false;
  }
  foot.stance = intervalsWhere(p.t, in_contact, true);
  foot.swing = intervalsWhere(p.t, in_contact, false);
  for (const TimeInterval& iv : foot.stance) foot.stance_time += iv.duration();
  foot.lift_off_time = foot.touch_down_time = kNaN;
  for (std::size_t k = 0; k < foot.stance.size(); ++k) {
    const bool followed_by_swing = k + 1 < foot.stance.size() || !in_contact.back();
    if (followed_by_swing) {
      foot.lift_off_time = foot.stance[k].end;
      if (k + 1 < foot.stance.size()) foot.touch_down_time = foot.stance[k + 1].start;
      break;
    }
  }
  // peak forces
  foot.peak_force_norm_time = foot.peak_force_z_time = p.t(0);
  foot.peak_force_z = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto c = static_cast<Eigen::Index>(3 * f);
    const double fx = p.force(i, c), fy = p.force(i, c + 1), fz = p.force(i, c + 2);
    const double norm = std::sqrt(fx * fx + fy * fy + fz * fz);
    if (norm > foot.peak_force_norm) {
      foot.peak_force_norm = norm;
      foot.peak_force_norm_time = p.t(i);
    }
    if (fz > foot.peak_force_z) {
      foot.peak_force_z = fz;
      foot.peak_force_z_time = p.t(i);
    }
  }
  return foot;
}

}  // namespace

std::vector<TimeInterval> intervalsWhere(const Eigen::VectorXd& t, const std::vector<bool>& flags, bool value) {
  std::vector<TimeInterval> out;
  const auto n = static_cast<Eigen::Index>(flags.size());
  Eigen::Index i = 0;
  while (i < n) {
    if (flags[static_cast<std::size_t>(i)] != value) {
      ++i;
      continue;
    }
    Eigen::Index j = i;
    while (j < n && flags[static_cast<std::size_t>(j)] == value) ++j;
    out.push_back({t(i), j < n ? t(j) : t(n - 1)});
    i = j;
  }
  return out;
}

PrimitiveSummary summarize(const Primitive& p) {
  const Eigen::Index n = p.t.size();
  requireRows(p, p.base_pos, 3, "base_pos");
  requireRows(p, p.force, 12, "force");
  requireRows(p, p.contact, 4, "contact");
  requireRows(p, p.tau, 12, "tau");

  PrimitiveSummary s;
  s.name = p.name;
  s.samples = n;
  s.solve = p.solve;
  s.shooting_intervals = static_cast<int>(p.knot_dt.size());
  s.take_off_time = s.touch_down_time = kNaN;
  if (n == 0) {
    s.start_height = s.apex_height = s.apex_time = s.apex_gain = s.end_height = kNaN;
    for (std::size_t f = 0; f < 4; ++f) s.feet[f].name = kFootNames[f];
    return s;
  }
  s.duration = p.t(n - 1) - p.t(0);

  // ---- contact phases ---------------------------------------------------------------------------
  std::vector<bool> airborne(static_cast<std::size_t>(n), true);
  for (std::size_t f = 0; f < 4; ++f) s.feet[f] = footSummary(p, f, airborne);
  s.flight = intervalsWhere(p.t, airborne, true);
  for (const TimeInterval& iv : s.flight) s.flight_time += iv.duration();
  if (!s.flight.empty()) {
    s.take_off_time = s.flight.front().start;
    if (!airborne.back() || s.flight.size() > 1) s.touch_down_time = s.flight.front().end;
  }

  // ---- apex -------------------------------------------------------------------------------------
  Eigen::Index apex = 0;
  p.base_pos.col(2).maxCoeff(&apex);
  s.start_height = p.base_pos(0, 2);
  s.apex_height = p.base_pos(apex, 2);
  s.apex_time = p.t(apex);
  s.apex_gain = s.apex_height - s.start_height;
  s.end_height = p.base_pos(n - 1, 2);

  // ---- torques ----------------------------------------------------------------------------------
  Eigen::Index row = 0, col = 0;
  s.peak_abs_tau = p.tau.cwiseAbs().maxCoeff(&row, &col);
  s.peak_abs_tau_joint = static_cast<int>(col);
  s.peak_abs_tau_time = p.t(row);
  return s;
}

}  // namespace centaur::data
