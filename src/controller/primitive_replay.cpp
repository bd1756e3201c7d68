#include "controller/primitive_replay.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "common/error.hpp"

namespace centaur {

namespace {
double scalarOr(const data::Primitive& p, const char* key, double fallback) {
  auto it = p.scalars.find(key);
  return it == p.scalars.end() ? fallback : it->second;
}
void requireShape(const data::Primitive& p, const data::RowMatrix& m, long cols, const char* what) {
  if (m.rows() != p.t.size() || m.cols() != cols) {
    throw InputError("primitive '" + p.name + "': dataset " + what + " must be " + std::to_string(p.t.size()) +
                     " x " + std::to_string(cols) + ", it is " + std::to_string(m.rows()) + " x " +
                     std::to_string(m.cols()));
  }
}
}  // namespace

PrimitiveReplay::PrimitiveReplay(const data::Primitive& p) : name_(p.name) {
  n_ = p.t.size();
  if (n_ < 2) throw InputError("primitive '" + p.name + "': needs at least 2 samples, it has " + std::to_string(n_));
  requireShape(p, p.foot_pos_rel, 12, "foot_pos_rel");
  requireShape(p, p.foot_vel_rel, 12, "foot_vel_rel");
  requireShape(p, p.force, 12, "force");
  requireShape(p, p.contact, 4, "contact");
  requireShape(p, p.base_pos, 3, "base_pos");
  requireShape(p, p.base_quat, 4, "base_quat");
  requireShape(p, p.foot_pos, 12, "foot_pos");
  dt_ = p.t[1] - p.t[0];
  if (!(dt_ > 0.0)) throw InputError("primitive '" + p.name + "': t must increase");
  duration_ = p.t[n_ - 1] - p.t[0];
  foot_rel_ = p.foot_pos_rel;
  foot_vel_rel_ = p.foot_vel_rel;
  force_ = p.force;
  contact_ = p.contact;
  base_pos_ = p.base_pos;
  base_quat_ = p.base_quat;
  knot_t_ = p.knot_t;
  knot_u_ = p.knot_u;
  if (knot_u_.rows() > 0 && (knot_u_.cols() < 6 || knot_t_.size() != knot_u_.rows() + 1)) {
    throw InputError("primitive '" + p.name + "': knot_u must have N_s rows and knot_t N_s + 1 entries");
  }

  // Surfaces: each contact interval of each foot, classified by where the foot is.
  const double r = scalarOr(p, "wheel_radius", 0.078);
  const double ground_z = scalarOr(p, "ground_z", 0.0);
  const bool has_wall = p.scalars.count("wall_x") > 0;
  const double wall_x = scalarOr(p, "wall_x", 0.0);
  normals_.assign(static_cast<std::size_t>(n_), {});
  for (int k = 0; k < 4; ++k) {
    Eigen::Vector3d next = Eigen::Vector3d::UnitZ();  // normal of the next contact (filled backwards)
    long i = n_ - 1;
    while (i >= 0) {
      if (p.contact(i, k) > 0.5) {
        long j = i;  // interval [j, i]
        while (j > 0 && p.contact(j - 1, k) > 0.5) --j;
        const long mid = (i + j) / 2;
        const double fx = p.foot_pos(mid, 3 * k), fz = p.foot_pos(mid, 3 * k + 2);
        if (std::abs(fz - (ground_z + r)) < 0.02) {
          next = Eigen::Vector3d::UnitZ();
        } else if (has_wall && std::abs(fx - (wall_x + r)) < 0.02) {
          next = Eigen::Vector3d::UnitX();
        } else {
          throw InputError("primitive '" + p.name + "': foot " + std::to_string(k) + " is in contact at t = " +
                           std::to_string(p.t[mid]) + " s but on neither the ground nor the wall");
        }
        for (long s = j; s <= i; ++s) normals_[static_cast<std::size_t>(s)][k] = next;
        if (j > 0) touch_downs_[k].insert(touch_downs_[k].begin(), p.t[j] - p.t[0]);
        if (i < n_ - 1) lift_offs_[k].insert(lift_offs_[k].begin(), p.t[i + 1] - p.t[0]);
        i = j - 1;
      } else {
        normals_[static_cast<std::size_t>(i)][k] = next;
        --i;
      }
    }
  }
}

void PrimitiveReplay::sample(double t, ReplaySample& out) const noexcept {
  long i = 0;
  out.running = t >= 0.0 && t < duration_;
  if (t > 0.0) {
    // Clamped as a double: a time far beyond the end (or +inf) must not overflow the conversion to an index.
    i = static_cast<long>(std::min(static_cast<double>(n_ - 1), std::floor(t / dt_ + 1e-9)));
  }
  out.index = i;
  for (int k = 0; k < 4; ++k) {
    out.b_p_wheel.col(k) = foot_rel_.row(i).segment<3>(3 * k).transpose();
    if (out.running) {
      out.b_v_wheel.col(k) = foot_vel_rel_.row(i).segment<3>(3 * k).transpose();
    } else {
      out.b_v_wheel.col(k).setZero();
    }
    out.w_F.col(k) = force_.row(i).segment<3>(3 * k).transpose();
    out.contact[k] = contact_(i, k) > 0.5;
    out.w_normal[k] = normals_[static_cast<std::size_t>(i)][k];
  }
  out.w_p_base = base_pos_.row(i).transpose();
  out.base_quat_wxyz = base_quat_.row(i).transpose();
  out.vdot_base.setZero();
  if (out.running && knot_u_.rows() > 0) {
    // interval of the piecewise-constant control containing t
    const long N = knot_u_.rows();
    long m = static_cast<long>(std::upper_bound(knot_t_.data(), knot_t_.data() + N + 1, t + knot_t_[0]) -
                               knot_t_.data()) - 1;
    m = std::clamp(m, 0L, N - 1);
    const Eigen::Quaterniond w_q_b(out.base_quat_wxyz[0], out.base_quat_wxyz[1], out.base_quat_wxyz[2],
                                   out.base_quat_wxyz[3]);
    out.vdot_base.head<3>() = knot_u_.row(m).segment<3>(0).transpose();
    out.vdot_base.tail<3>() = w_q_b.conjugate() * Eigen::Vector3d(knot_u_.row(m).segment<3>(3).transpose());
  }
}

}  // namespace centaur
