#pragma once
// A task of the hierarchical QP: the cost  || A x - lambda b ||^2_W  on the decision vector x (n), with
// A (m x n), b (m), a symmetric positive semi-definite weight W (m x m, default identity) and a gain lambda >= 0.
// For velocity IK, x = generalized velocities, A a Jacobian, b an error (so lambda is a gain in 1/s).
//
// Robot-specific tasks derive from Task and override update(), which recomputes A and b from whatever the
// task captured at construction (a model, a reference). update() runs once per tick, must not allocate
// and must not throw. Sizes are fixed at construction (Model/Data split).
#include <Eigen/Core>

#include <memory>
#include <string>

namespace centaur {

class Task {
 public:
  /// Allocates A (rows x cols, zero), b (zero), W (identity).
  Task(std::string name, int rows, int cols);
  virtual ~Task() = default;
  Task(const Task&) = delete;
  Task& operator=(const Task&) = delete;

  /// Recompute A and b (e.g. from the current model state). Default: a constant task. No allocation, no throw.
  virtual void update() {}

  const std::string& name() const { return name_; }
  int rows() const { return static_cast<int>(A_.rows()); }
  int cols() const { return static_cast<int>(A_.cols()); }

  const Eigen::MatrixXd& A() const { return A_; }
  const Eigen::VectorXd& b() const { return b_; }
  /// Writable A and b (fixed size) for tasks set from outside, e.g. a reference.
  Eigen::MatrixXd& A() { return A_; }
  Eigen::VectorXd& b() { return b_; }

  const Eigen::MatrixXd& weight() const { return W_; }
  bool diagonalWeight() const { return diagonal_weight_; }
  /// W = w I, w >= 0. Throws std::invalid_argument otherwise (configuration time).
  void setWeight(double w);
  /// W = diag(w), w_i >= 0, w.size() == rows().
  void setWeightDiagonal(const Eigen::VectorXd& w);
  /// Full symmetric PSD W (rows x rows); symmetry is checked, not definiteness.
  void setWeight(const Eigen::MatrixXd& W);

  double lambda() const { return lambda_; }
  /// lambda >= 0 (throws std::invalid_argument otherwise).
  void setLambda(double lambda);

  /// || A x - lambda b ||^2_W for a given x (no allocation when `residual` has rows() entries).
  double cost(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> residual) const;

 protected:
  std::string name_;
  Eigen::MatrixXd A_;
  Eigen::VectorXd b_;
  Eigen::MatrixXd W_;
  bool diagonal_weight_ = true;
  double lambda_ = 1.0;
};

/// The simplest task: A and b set by the owner (or once from YAML); update() does nothing.
class LinearTask : public Task {
 public:
  LinearTask(std::string name, const Eigen::MatrixXd& A, const Eigen::VectorXd& b);
};

using TaskPtr = std::shared_ptr<Task>;

}  // namespace centaur
