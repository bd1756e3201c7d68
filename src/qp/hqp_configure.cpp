// HqpSolver's setup: the stack checked, its tasks and constraints collected, and every workspace sized.
#include "qp/hqp_solver.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace centaur {

void HqpSolver::configure(const Stack& stack, int n, const QpSettings& settings) {
  const int max_term_rows = checkStack(stack, n);
  sizeWorkspaces(max_term_rows, settings);
}

// The stack is checked and its distinct tasks and constraints collected; returns the most rows of any term.
int HqpSolver::checkStack(const Stack& stack, int n) {
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
  return max_term_rows;
}

// Every workspace of solve() sized once, so that solve() does not allocate.
void HqpSolver::sizeWorkspaces(int max_term_rows, const QpSettings& settings) {
  const int n = n_;
  const int levels = numLevels();
  const int total_rows = level_offset_.back();
  H_.setZero(n, n);
  g_.setZero(n);
  bE_.setZero(std::max(total_rows, 1));
  E_.setZero(std::max(total_rows, 1), n);
  WAs_.setZero(max_term_rows, n);
  Wsel_.setZero(max_term_rows, max_term_rows);
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
  int max_level_rows = 1;
  for (int k = 0; k < levels; ++k) max_level_rows = std::max(max_level_rows, level_offset_[k + 1] - level_offset_[k]);
  null_space_.reserve(max_level_rows, n);
  B_.setZero(max_level_rows, n);
  Ad_.setZero(max_level_rows, n);
  Cd_.setZero(m_in_, n);
  xd_.setZero(n);
  blo_.setZero(n);
  bup_.setZero(n);
  dense_.assign(n, 0);
  nz_idx_.assign(n, 0);
  kept_.assign(n, 0);
  block_root_.assign(n, 0);
  block_cols_.assign(n, 0);
  block_rows_.assign(std::max(max_level_rows, 1), 0);
  row_block_.assign(std::max(max_level_rows, 1), 0);
  Ab_.setZero(max_level_rows, n);
  sep_.assign(n, 0);
  Hc_.setZero(n, n);
  gc_.setZero(n);
  blc_.setZero(n);
  buc_.setZero(n);
  ysol_.setZero(n);
  nz_val_.setZero(n);
  w_.setZero(max_term_rows);
  free_.assign(n, 0);
  touched_.assign(n, 0);
  const int m_rows = m_in_ + (has_box_ ? n : 0);  // reduced levels: constraint rows and box rows
  for (int k = 0; k < levels; ++k) {
    // level 0: the full problem with box bounds; levels >= 1: the reduced problem (<= n variables, rows only)
    solvers_[k].resize(n, 0, k == 0 ? m_in_ : m_rows);
    solvers_[k].settings() = settings;
  }
  Z_[0].setZero(n, n);
  Z_[1].setZero(n, n);
  Hy_.setZero(n, n);
  HZ_.setZero(max_term_rows, n);
  Cy_.setZero(std::max(m_rows, 1), n);
  Cc_.setZero(std::max(m_rows, 1), n);
  gy_.setZero(n);
  ylo_.setZero(std::max(m_rows, 1));
  yup_.setZero(std::max(m_rows, 1));
  tmp_.setZero(std::max(m_rows, 1));
  used_.assign(n, 0);
  n_used_ = n;
  failed_level_ = -1;
}

}  // namespace centaur
