#pragma once
// A constraint of the hierarchical QP, imposed at every priority level: box bounds on x and/or two-sided
// inequality rows  c_lo <= C x <= c_up  (any bound may be +-inf; c_lo == c_up makes an equality row).
// Like a Task, a constraint has fixed sizes and an update() that runs once per tick (no allocation, no throw).
#include <Eigen/Core>

#include <memory>
#include <string>

namespace centaur {

class Constraint {
 public:
  /// n variables, `rows` inequality rows; bounds start at -inf/+inf, C at zero.
  Constraint(std::string name, int n, int rows);
  virtual ~Constraint() = default;
  Constraint(const Constraint&) = delete;
  Constraint& operator=(const Constraint&) = delete;

  virtual void update() {}

  const std::string& name() const { return name_; }
  int cols() const { return static_cast<int>(x_lo_.size()); }
  int rows() const { return static_cast<int>(C_.rows()); }

  const Eigen::VectorXd& lowerBounds() const { return x_lo_; }  ///< n
  const Eigen::VectorXd& upperBounds() const { return x_up_; }  ///< n
  const Eigen::MatrixXd& C() const { return C_; }
  const Eigen::VectorXd& cLower() const { return c_lo_; }
  const Eigen::VectorXd& cUpper() const { return c_up_; }
  Eigen::VectorXd& lowerBounds() { return x_lo_; }
  Eigen::VectorXd& upperBounds() { return x_up_; }
  Eigen::MatrixXd& C() { return C_; }
  Eigen::VectorXd& cLower() { return c_lo_; }
  Eigen::VectorXd& cUpper() { return c_up_; }

 protected:
  std::string name_;
  Eigen::VectorXd x_lo_, x_up_;
  Eigen::MatrixXd C_;
  Eigen::VectorXd c_lo_, c_up_;
};

/// Joint position limits as velocity bounds over one tick:
///   scaling (q_min - q) / dt <= qd <= scaling (q_max - q) / dt,   qd = x.segment(offset, nj).
/// scaling in (0, 1] (1: the limit can be reached in one tick). Set q with setJointPositions() before update().
/// If q lies outside [q_min, q_max], the bounds push it back (a bound of the wrong sign); HqpSolver resolves a
/// conflict with the velocity limits in favour of the velocity limit (see HqpSolver::solve).
class JointPositionLimits : public Constraint {
 public:
  JointPositionLimits(std::string name, int n, int offset, const Eigen::VectorXd& q_min, const Eigen::VectorXd& q_max,
                      double dt, double scaling = 1.0);
  void setJointPositions(const Eigen::Ref<const Eigen::VectorXd>& q) { q_ = q; }
  const Eigen::VectorXd& jointPositions() const { return q_; }
  void update() override;

 protected:
  int offset_;
  Eigen::VectorXd q_min_, q_max_, q_;
  double dt_, scaling_;
};

/// Joint velocity limits  -qd_max <= x.segment(offset, nj) <= qd_max  (constant; qd_max > 0).
class JointVelocityLimits : public Constraint {
 public:
  JointVelocityLimits(std::string name, int n, int offset, const Eigen::VectorXd& qd_max);
};

/// Constant bounds and rows set by the owner.
class LinearConstraint : public Constraint {
 public:
  LinearConstraint(std::string name, int n, int rows) : Constraint(std::move(name), n, rows) {}
};

using ConstraintPtr = std::shared_ptr<Constraint>;

}  // namespace centaur
