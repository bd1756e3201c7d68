#include "qp/constraint.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace centaur {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

Constraint::Constraint(std::string name, int n, int rows)
    : name_(std::move(name)),
      x_lo_(Eigen::VectorXd::Constant(n, -kInf)),
      x_up_(Eigen::VectorXd::Constant(n, kInf)),
      C_(Eigen::MatrixXd::Zero(rows, n)),
      c_lo_(Eigen::VectorXd::Constant(rows, -kInf)),
      c_up_(Eigen::VectorXd::Constant(rows, kInf)) {
  if (n <= 0 || rows < 0) throw std::invalid_argument("constraint '" + name_ + "': bad sizes");
}

JointPositionLimits::JointPositionLimits(std::string name, int n, int offset, const Eigen::VectorXd& q_min,
                                         const Eigen::VectorXd& q_max, double dt, double scaling)
    : Constraint(std::move(name), n, 0),
      offset_(offset),
      q_min_(q_min),
      q_max_(q_max),
      q_(Eigen::VectorXd::Zero(q_min.size())),
      dt_(dt),
      scaling_(scaling) {
  if (q_min.size() != q_max.size() || offset < 0 || offset + q_min.size() > n)
    throw std::invalid_argument("constraint '" + name_ + "': joint range outside the decision vector");
  if (!(dt > 0.0) || !(scaling > 0.0 && scaling <= 1.0))
    throw std::invalid_argument("constraint '" + name_ + "': need dt > 0 and scaling in (0, 1]");
  for (Eigen::Index i = 0; i < q_min.size(); ++i)
    if (!(q_min[i] <= q_max[i])) throw std::invalid_argument("constraint '" + name_ + "': q_min > q_max");
  q_ = 0.5 * (q_min_ + q_max_);
  for (Eigen::Index i = 0; i < q_.size(); ++i)
    if (!std::isfinite(q_[i])) q_[i] = 0.0;
  update();
}

void JointPositionLimits::update() {
  const double k = scaling_ / dt_;
  const Eigen::Index nj = q_.size();
  x_lo_.segment(offset_, nj) = k * (q_min_ - q_);  // -inf stays -inf for continuous joints
  x_up_.segment(offset_, nj) = k * (q_max_ - q_);
}

JointVelocityLimits::JointVelocityLimits(std::string name, int n, int offset, const Eigen::VectorXd& qd_max)
    : Constraint(std::move(name), n, 0) {
  if (offset < 0 || offset + qd_max.size() > n)
    throw std::invalid_argument("constraint '" + name_ + "': joint range outside the decision vector");
  for (Eigen::Index i = 0; i < qd_max.size(); ++i)
    if (!(qd_max[i] > 0.0)) throw std::invalid_argument("constraint '" + name_ + "': qd_max must be > 0");
  x_lo_.segment(offset, qd_max.size()) = -qd_max;
  x_up_.segment(offset, qd_max.size()) = qd_max;
}

}  // namespace centaur
