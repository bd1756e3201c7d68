#pragma once
// Test-only toy kinematic model: a planar serial arm (revolute joints, analytic forward kinematics and
// Jacobian), and tasks on it of the kind the robot will have (end-effector position, posture).
#include <Eigen/Core>

#include <cmath>
#include <string>

#include "qp/task.hpp"

namespace centaur::test {

struct PlanarArm {
  Eigen::VectorXd lengths;  // [m]
  Eigen::VectorXd q;        // [rad]

  explicit PlanarArm(int n) : lengths(Eigen::VectorXd::Constant(n, 1.0 / n)), q(Eigen::VectorXd::Zero(n)) {}
  int dof() const { return static_cast<int>(q.size()); }

  Eigen::Vector2d tip() const {
    Eigen::Vector2d p = Eigen::Vector2d::Zero();
    double th = 0.0;
    for (int i = 0; i < dof(); ++i) {
      th += q[i];
      p += lengths[i] * Eigen::Vector2d(std::cos(th), std::sin(th));
    }
    return p;
  }
  /// d tip / d q (2 x n), analytic; J must be pre-sized.
  template <class M>
  void jacobian(M& J) const {
    double th = 0.0;
    J.setZero();
    for (int i = 0; i < dof(); ++i) {
      th += q[i];
      const Eigen::Vector2d dp(-lengths[i] * std::sin(th), lengths[i] * std::cos(th));
      for (int j = 0; j <= i; ++j) J.col(j).template head<2>() += dp;  // link i moves with every joint j <= i
    }
  }
};

/// Tip position: A = J(q), b = target - tip(q) (so lambda is the error-decay rate, 1/s).
class TipPositionTask : public Task {
 public:
  TipPositionTask(std::string name, const PlanarArm& arm)
      : Task(std::move(name), 2, arm.dof()), arm_(arm), target(Eigen::Vector2d::Zero()) {}
  void update() override {
    arm_.jacobian(A_);
    b_.head<2>() = target - arm_.tip();
  }
  const PlanarArm& arm_;
  Eigen::Vector2d target;
};

/// Posture: A = I, b = q_ref - q.
class PostureTask : public Task {
 public:
  PostureTask(std::string name, const PlanarArm& arm)
      : Task(std::move(name), arm.dof(), arm.dof()), arm_(arm), q_ref(Eigen::VectorXd::Zero(arm.dof())) {
    A_.setIdentity();
  }
  void update() override { b_ = q_ref - arm_.q; }
  const PlanarArm& arm_;
  Eigen::VectorXd q_ref;
};

}  // namespace centaur::test
