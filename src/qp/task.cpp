#include "qp/task.hpp"

#include <cmath>
#include <stdexcept>

namespace centaur {

Task::Task(std::string name, int rows, int cols)
    : name_(std::move(name)),
      A_(Eigen::MatrixXd::Zero(rows, cols)),
      b_(Eigen::VectorXd::Zero(rows)),
      W_(Eigen::MatrixXd::Identity(rows, rows)) {
  if (rows <= 0 || cols <= 0) throw std::invalid_argument("task '" + name_ + "': sizes must be positive");
}

void Task::setWeight(double w) {
  if (!(w >= 0.0) || !std::isfinite(w)) throw std::invalid_argument("task '" + name_ + "': weight must be >= 0");
  W_ = w * Eigen::MatrixXd::Identity(rows(), rows());
  diagonal_weight_ = true;
}

void Task::setWeightDiagonal(const Eigen::VectorXd& w) {
  if (w.size() != rows()) throw std::invalid_argument("task '" + name_ + "': weight needs one entry per row");
  for (Eigen::Index i = 0; i < w.size(); ++i)
    if (!(w[i] >= 0.0) || !std::isfinite(w[i]))
      throw std::invalid_argument("task '" + name_ + "': weights must be >= 0");
  W_ = w.asDiagonal();
  diagonal_weight_ = true;
}

void Task::setWeight(const Eigen::MatrixXd& W) {
  if (W.rows() != rows() || W.cols() != rows() || !W.allFinite() || !W.isApprox(W.transpose(), 1e-12))
    throw std::invalid_argument("task '" + name_ + "': weight must be a finite symmetric rows x rows matrix");
  W_ = W;
  diagonal_weight_ = W.isDiagonal(0.0);
}

void Task::setLambda(double lambda) {
  if (!(lambda >= 0.0) || !std::isfinite(lambda))
    throw std::invalid_argument("task '" + name_ + "': lambda must be >= 0");
  lambda_ = lambda;
}

double Task::cost(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> residual) const {
  residual.noalias() = A_ * x;
  residual -= lambda_ * b_;
  if (diagonal_weight_) return residual.dot(W_.diagonal().cwiseProduct(residual));
  double c = 0.0;
  for (int i = 0; i < rows(); ++i) c += residual[i] * W_.row(i).dot(residual);
  return c;
}

LinearTask::LinearTask(std::string name, const Eigen::MatrixXd& A, const Eigen::VectorXd& b)
    : Task(std::move(name), static_cast<int>(A.rows()), static_cast<int>(A.cols())) {
  if (b.size() != A.rows()) throw std::invalid_argument("task '" + name_ + "': b needs one entry per row of A");
  A_ = A;
  b_ = b;
}

}  // namespace centaur
