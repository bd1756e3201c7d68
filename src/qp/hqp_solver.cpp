#include "qp/hqp_solver.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace centaur {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
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
  e_.setZero(std::max(total_rows, 1));
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
  for (int k = 0; k < levels; ++k) {
    solvers_[k].resize(n, level_offset_[k], m_in_);
    solvers_[k].settings() = settings;
  }
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
    const int m_eq = level_offset_[k];
    QpSolver& qp = solvers_[k];
    const QpStatus status =
        has_box_ ? qp.solve(H_, g_, E_.topRows(m_eq), e_.head(m_eq), C_, c_lo_, c_up_, x_lo_, x_up_)
                 : qp.solve(H_, g_, E_.topRows(m_eq), e_.head(m_eq), C_, c_lo_, c_up_, none, none);
    if (status != QpStatus::kOptimal) {
      failed_level_ = k;
      if (k > 0) x = level_x_[k - 1];
      return status;
    }
    level_x_[k] = qp.x();
    // Clip to the box (a change within the QP tolerance) so that the equality rows handed to the next level
    // are met by a point that satisfies the bounds exactly: otherwise a level whose feasible set is a single
    // point on the boundary could be infeasible by 1e-11.
    if (has_box_) level_x_[k] = level_x_[k].cwiseMax(x_lo_).cwiseMin(x_up_);
    // Keep this level's optimal residual for the levels below.
    const int m = level_offset_[k + 1] - m_eq;
    e_.segment(m_eq, m).noalias() = E_.middleRows(m_eq, m) * level_x_[k];
  }
  x = level_x_[levels - 1];  // clipped: satisfies the box bounds (joint limits) exactly
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
