#include "qp/hqp_solver.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace centaur {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNullRowTol = 1e-9;  // relative norm of a constraint row after projection on null(E)
}

void HqpSolver::configure(const Stack& stack, int n, const QpSettings& settings) {
  if (n <= 0) throw std::invalid_argument("hierarchical QP: n must be positive");
  if (stack.levels.empty()) throw std::invalid_argument("hierarchical QP: the stack has no level");
  if (!(stack.regularisation > 0.0)) throw std::invalid_argument("hierarchical QP: regularisation must be > 0");
  stack_ = stack;
  n_ = n;
  tasks_.clear();
  constraints_.clear();
  level_offset_.assign(1, 0);
  int max_term_rows = 1;
  for (std::size_t k = 0; k < stack_.levels.size(); ++k) {
    const Level& level = stack_.levels[k];
    if (level.terms.empty()) throw std::invalid_argument("hierarchical QP: level " + std::to_string(k) + " is empty");
    for (const Term& t : level.terms) {
      if (!t.task) throw std::invalid_argument("hierarchical QP: null task in level " + std::to_string(k));
      if (t.task->cols() != n)
        throw std::invalid_argument("task '" + t.task->name() + "' has " + std::to_string(t.task->cols()) +
                                    " columns, the decision vector has " + std::to_string(n));
      for (int r : t.rows)
        if (r < 0 || r >= t.task->rows())
          throw std::invalid_argument("task '" + t.task->name() + "': selected row " + std::to_string(r) +
                                      " out of range");
      if (std::find(tasks_.begin(), tasks_.end(), t.task.get()) == tasks_.end()) tasks_.push_back(t.task.get());
      max_term_rows = std::max(max_term_rows, t.size());
    }
    level_offset_.push_back(level_offset_.back() + level.size());
  }
  m_in_ = 0;
  for (const ConstraintPtr& c : stack_.constraints) {
    if (!c) throw std::invalid_argument("hierarchical QP: null constraint");
    if (c->cols() != n)
      throw std::invalid_argument("constraint '" + c->name() + "' has " + std::to_string(c->cols()) +
                                  " columns, the decision vector has " + std::to_string(n));
    if (std::find(constraints_.begin(), constraints_.end(), c.get()) != constraints_.end()) continue;
    constraints_.push_back(c.get());
    m_in_ += c->rows();
  }
  has_box_ = !constraints_.empty();

  const int levels = numLevels();
  const int total_rows = level_offset_.back();
  H_.setZero(n, n);
  g_.setZero(n);
  E_.setZero(std::max(total_rows, 1), n);
  As_.setZero(max_term_rows, n);
  WAs_.setZero(max_term_rows, n);
  Wsel_.setZero(max_term_rows, max_term_rows);
  bs_.setZero(max_term_rows);
  res_.setZero(max_term_rows);
  C_.setZero(m_in_, n);
  c_lo_.setZero(m_in_);
  c_up_.setZero(m_in_);
  x_lo_.setZero(has_box_ ? n : 0);
  x_up_.setZero(has_box_ ? n : 0);
  solvers_.clear();
  solvers_.resize(levels);  // default-constructed in place, then sized
  level_x_.assign(levels, Eigen::VectorXd::Zero(n));
  level_rank_.assign(levels, 0);
  qr_.clear();
  qr_.reserve(levels);
  const int m_rows = m_in_ + (has_box_ ? n : 0);  // reduced levels: constraint rows and box rows
  for (int k = 0; k < levels; ++k) {
    // level 0: the full problem with box bounds; levels >= 1: the reduced problem (<= n variables, rows only)
    solvers_[k].resize(n, 0, k == 0 ? m_in_ : m_rows);
    solvers_[k].settings() = settings;
    qr_.emplace_back(n, std::max(level_offset_[k], 1));
    qr_.back().setThreshold(rank_threshold_);
  }
  Z_.setZero(n, n);
  HZ_.setZero(n, n);
  Hy_.setZero(n, n);
  Cy_.setZero(std::max(m_rows, 1), n);
  gy_.setZero(n);
  ylo_.setZero(std::max(m_rows, 1));
  yup_.setZero(std::max(m_rows, 1));
  work_.setZero(n);
  tmp_.setZero(std::max(m_in_, n));
  failed_level_ = -1;
}

void HqpSolver::update() {
  for (Task* t : tasks_) t->update();
  for (Constraint* c : constraints_) c->update();
}

void HqpSolver::assembleLevel(int k) {
  H_.setZero();
  g_.setZero();
  int row = level_offset_[k];
  for (const Term& t : stack_.levels[k].terms) {
    const Task& task = *t.task;
    const int m = t.size();
    auto As = As_.topRows(m);
    auto WAs = WAs_.topRows(m);
    auto bs = bs_.head(m);
    for (int r = 0; r < m; ++r) {
      const int tr = t.taskRow(r);
      As.row(r) = task.A().row(tr);
      bs[r] = task.lambda() * task.b()[tr];
    }
    if (task.diagonalWeight()) {
      for (int r = 0; r < m; ++r) WAs.row(r) = (t.scale * task.weight()(t.taskRow(r), t.taskRow(r))) * As.row(r);
    } else {
      auto W = Wsel_.topLeftCorner(m, m);
      for (int r = 0; r < m; ++r)
        for (int c = 0; c < m; ++c) W(r, c) = t.scale * task.weight()(t.taskRow(r), t.taskRow(c));
      WAs.noalias() = W * As;
    }
    H_.noalias() += As.transpose() * WAs;
    g_.noalias() -= WAs.transpose() * bs;
    E_.middleRows(row, m) = As;
    row += m;
  }
  H_.diagonal().array() += stack_.regularisation;
}

QpStatus HqpSolver::solve(Eigen::Ref<Eigen::VectorXd> x) {
  failed_level_ = -1;
  if (x.size() != n_ || solvers_.empty()) {
    failed_level_ = 0;
    return QpStatus::kInvalidInput;
  }
  // Constraints: intersection of the box bounds, stacked rows.
  if (has_box_) {
    x_lo_.setConstant(-kInf);
    x_up_.setConstant(kInf);
  }
  int row = 0;
  for (const Constraint* c : constraints_) {
    x_lo_ = x_lo_.cwiseMax(c->lowerBounds());
    x_up_ = x_up_.cwiseMin(c->upperBounds());
    const int m = c->rows();
    if (m > 0) {
      C_.middleRows(row, m) = c->C();
      c_lo_.segment(row, m) = c->cLower();
      c_up_.segment(row, m) = c->cUpper();
      row += m;
    }
  }
  const Eigen::Map<const Eigen::VectorXd> none(nullptr, 0);
  const int levels = numLevels();
  for (int k = 0; k < levels; ++k) {
    assembleLevel(k);
    QpSolver& qp = solvers_[k];
    QpStatus status = QpStatus::kOptimal;
    if (k == 0) {
      status = has_box_ ? qp.solve(H_, g_, E_.topRows(0), bs_.head(0), C_, c_lo_, c_up_, x_lo_, x_up_)
                        : qp.solve(H_, g_, E_.topRows(0), bs_.head(0), C_, c_lo_, c_up_, none, none);
      if (status == QpStatus::kOptimal) level_x_[k] = qp.x();
    } else {
      status = solveReduced(k);
    }
    if (status != QpStatus::kOptimal) {
      failed_level_ = k;
      if (k > 0) x = level_x_[k - 1];
      return status;
    }
    // Clip to the box (a change within the QP tolerance) so that the returned x and the point the next level
    // starts from satisfy the bounds (joint limits) exactly.
    if (has_box_) level_x_[k] = level_x_[k].cwiseMax(x_lo_).cwiseMin(x_up_);
  }
  x = level_x_[levels - 1];
  return QpStatus::kOptimal;
}

QpStatus HqpSolver::solveReduced(int k) {
  const int n = n_;
  const int m = level_offset_[k];
  const Eigen::VectorXd& xp = level_x_[k - 1];
  // Null space of the rows of the levels above: E' P = Q R, Z = Q(:, rank:n).
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd>& qr = qr_[k];
  qr.compute(E_.topRows(m).transpose());
  const int rank = static_cast<int>(qr.rank());
  level_rank_[k] = rank;
  const int nz = n - rank;
  if (nz == 0) {  // the levels above fix x completely
    level_x_[k] = xp;
    return QpStatus::kOptimal;
  }
  auto Z = Z_.leftCols(nz);
  Z.setZero();
  Z.bottomRows(nz).setIdentity();
  const int reflectors = static_cast<int>(qr.hCoeffs().size());
  for (int i = reflectors - 1; i >= 0; --i) {
    auto rows = Z.bottomRows(n - i);
    rows.applyHouseholderOnTheLeft(qr.matrixQR().col(i).tail(n - i - 1), qr.hCoeffs()(i), work_.data());
  }
  // Reduced cost: 1/2 y' Z'HZ y + (Z'(H xp + g))' y.
  auto HZ = HZ_.leftCols(nz);
  HZ.noalias() = H_ * Z;
  auto Hy = Hy_.topLeftCorner(nz, nz);
  Hy.noalias() = Z.transpose() * HZ;
  auto t = tmp_.head(n);
  t = g_;
  t.noalias() += H_ * xp;
  auto gy = gy_.head(nz);
  gy.noalias() = Z.transpose() * t;
  // Rows: c_lo - C xp <= C Z y <= c_up - C xp ;  x_lo - xp <= Z y <= x_up - xp.
  int rows = 0;
  if (m_in_ > 0) {
    Cy_.topLeftCorner(m_in_, nz).noalias() = C_ * Z;
    auto cxp = tmp_.head(m_in_);
    cxp.noalias() = C_ * xp;
    ylo_.head(m_in_) = c_lo_ - cxp;
    yup_.head(m_in_) = c_up_ - cxp;
    rows = m_in_;
  }
  if (has_box_) {
    Cy_.block(rows, 0, n, nz) = Z;
    ylo_.segment(rows, n) = x_lo_ - xp;
    yup_.segment(rows, n) = x_up_ - xp;
    rows += n;
  }
  // A row whose projection on the null space is negligible is fixed by the levels above (and met by xp):
  // it is dropped, since rounding noise in a near-zero row would read as a large normalised violation.
  for (int i = 0; i < rows; ++i) {
    const double original = i < m_in_ ? C_.row(i).norm() : 1.0;
    if (Cy_.row(i).head(nz).norm() <= kNullRowTol * original) {
      Cy_.row(i).head(nz).setZero();
      ylo_[i] = -kInf;
      yup_[i] = kInf;
    }
  }
  const Eigen::Map<const Eigen::VectorXd> none(nullptr, 0);
  QpSolver& qp = solvers_[k];
  const QpStatus status = qp.solve(Hy, gy, Cy_.topLeftCorner(0, nz), ylo_.head(0), Cy_.topLeftCorner(rows, nz),
                                   ylo_.head(rows), yup_.head(rows), none, none);
  if (status != QpStatus::kOptimal) return status;
  level_x_[k] = xp;
  level_x_[k].noalias() += Z * qp.x();
  return QpStatus::kOptimal;
}

double HqpSolver::levelCost(int k, const Eigen::Ref<const Eigen::VectorXd>& x) {
  double cost = 0.0;
  for (const Term& t : stack_.levels[k].terms) {
    const Task& task = *t.task;
    const int m = t.size();
    auto res = res_.head(m);
    for (int r = 0; r < m; ++r) {
      const int tr = t.taskRow(r);
      res[r] = task.A().row(tr).dot(x) - task.lambda() * task.b()[tr];
    }
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < m; ++c) {
        if (task.diagonalWeight() && r != c) continue;
        cost += t.scale * res[r] * task.weight()(t.taskRow(r), t.taskRow(c)) * res[c];
      }
  }
  return cost;
}

}  // namespace centaur
