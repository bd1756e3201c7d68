#include "qp/hqp_solver.hpp"

#include "qp/product.hpp"

#include <algorithm>
#include <cmath>
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

void HqpSolver::update() {
  for (Task* t : tasks_) t->update();
  for (Constraint* c : constraints_) c->update();
}

void HqpSolver::assembleFirst() {
  // The rows of level 0 (into E_, their targets into bE_), then the columns they or a constraint row touch.
  const int m0 = level_offset_[1];
  copyLevelRows(0);
  n_used_ = 0;
  for (int j = 0; j < n_; ++j) {
    const bool used = (m0 > 0 && E_.col(j).head(m0).cwiseAbs().maxCoeff() > 0.0) ||
                      (m_in_ > 0 && C_.col(j).cwiseAbs().maxCoeff() > 0.0);
    if (used) used_[n_used_++] = j;
  }
  // H = sum A' W A + eps I and g = -sum A' W b on the used columns (H_, g_ if all are used, else Hy_, gy_).
  const int nu = n_used_;
  const bool all = nu == n_;
  auto H = all ? H_.topLeftCorner(n_, n_) : Hy_.topLeftCorner(nu, nu);
  auto g = all ? g_.head(n_) : gy_.head(nu);
  H.setZero();
  g.setZero();
  int row = 0;
  for (const Term& t : stack_.levels[0].terms) {
    const int m = t.size();
    auto A = HZ_.topLeftCorner(m, nu);  // the term's rows on the used columns (E_'s own rows if all are used)
    if (!all)
      for (int b = 0; b < nu; ++b) A.col(b) = E_.col(used_[b]).segment(row, m);
    const Eigen::Ref<const Eigen::MatrixXd> At = all ? Eigen::Ref<const Eigen::MatrixXd>(E_.middleRows(row, m))
                                                     : Eigen::Ref<const Eigen::MatrixXd>(A);
    auto WA = WAs_.topLeftCorner(m, nu);
    weigh(t, At, WA);
    productNoAlloc(H, At.transpose(), WA, true);
    g.noalias() -= WA.transpose() * bE_.segment(row, m);
    row += m;
  }
  H.diagonal().array() += stack_.regularisation;
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
  // Crossed bounds (e.g. q beyond a position limit by more than one tick at the velocity limit: the position
  // bound asks to come back faster than the velocity bound allows) are resolved in favour of the bound of
  // smaller magnitude, i.e. move back as fast as allowed, instead of making every level infeasible.
  for (Eigen::Index j = 0; j < x_lo_.size(); ++j) {
    if (x_lo_[j] > x_up_[j]) {
      const double v = std::abs(x_lo_[j]) < std::abs(x_up_[j]) ? x_lo_[j] : x_up_[j];
      x_lo_[j] = x_up_[j] = v;
    }
  }
  const Eigen::Map<const Eigen::VectorXd> none(nullptr, 0);
  const int levels = numLevels();
  for (int k = 0; k < levels; ++k) {
    QpStatus status = QpStatus::kOptimal;
    if (k == 0) {
      assembleFirst();
      status = solveFirst();
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

QpStatus HqpSolver::solveFirst() {
  const Eigen::Map<const Eigen::VectorXd> none(nullptr, 0);
  QpSolver& qp = solvers_[0];
  if (n_used_ == n_) {
    const QpStatus status = has_box_ ? qp.solve(H_, g_, E_.topRows(0), bE_.head(0), C_, c_lo_, c_up_, x_lo_, x_up_)
                                     : qp.solve(H_, g_, E_.topRows(0), bE_.head(0), C_, c_lo_, c_up_, none, none);
    if (status == QpStatus::kOptimal) level_x_[0] = qp.x();
    return status;
  }
  // The QP on the used columns (H, g in the workspaces of the reduced levels, free at this point). An unused
  // column has H_jj = eps, g_j = 0 and no constraint row: x_j = argmin eps x_j^2 over its box = the box point
  // nearest 0.
  const int nu = n_used_;
  const auto H = Hy_.topLeftCorner(nu, nu);
  const auto g = gy_.head(nu);
  auto C = Cy_.topLeftCorner(m_in_, nu);
  for (int b = 0; b < nu; ++b) C.col(b) = C_.col(used_[b]);
  QpStatus status;
  if (has_box_) {
    auto lo = ylo_.head(nu), up = yup_.head(nu);
    for (int b = 0; b < nu; ++b) {
      lo[b] = x_lo_[used_[b]];
      up[b] = x_up_[used_[b]];
    }
    status = qp.solve(H, g, E_.topLeftCorner(0, nu), bE_.head(0), C, c_lo_, c_up_, lo, up);
  } else {
    status = qp.solve(H, g, E_.topLeftCorner(0, nu), bE_.head(0), C, c_lo_, c_up_, none, none);
  }
  if (status != QpStatus::kOptimal) return status;
  Eigen::VectorXd& x = level_x_[0];
  x.setZero();
  if (has_box_) x = x.cwiseMax(x_lo_).cwiseMin(x_up_);
  for (int b = 0; b < nu; ++b) x[used_[b]] = qp.x()[b];
  return status;
}

void HqpSolver::updateNullSpace(int k) {
  // Z_k = Z_{k-1} N, N a basis of null(A_{k-1} Z_{k-1}) (A_{k-1}: the rows of level k-1; Z_0 = I). Z is kept as
  // Zd (its rows on the dense variables) and unit columns for the free ones, which no row above touches.
  const int first = level_offset_[k - 1];
  const int m = level_offset_[k] - first;
  const int prev = cur_;
  cur_ = 1 - cur_;
  if (k == 1) {
    // Level 0's rows live on its used columns: they are the dense variables, the others are free.
    n_dense_ = n_free_ = 0;
    for (int j = 0; j < n_; ++j) {
      if (n_dense_ < n_used_ && used_[n_dense_] == j) {
        dense_[n_dense_++] = j;
      } else {
        free_[n_free_++] = j;
      }
    }
    dense_identity_ = n_dense_ == n_;
    firstNullSpace(denseColumns(E_.middleRows(first, m), B_));
  } else if (nzd_ > 0) {
    // The rows of level k-1 touch dense variables only (the free ones they touch joined after its solve).
    const Eigen::Ref<const Eigen::MatrixXd> Ad = denseColumns(E_.middleRows(first, m), Ad_);
    auto B = B_.topLeftCorner(m, nzd_);
    productNoAlloc(B, Ad, Z_[prev].topLeftCorner(n_dense_, nzd_), false);
    double scale = 0.0;  // rank threshold relative to the rows before projection
    for (int i = 0; i < m; ++i) scale = std::max(scale, E_.row(first + i).norm());
    null_space_.compute(B, rank_tol_, scale);
    const int nzd_new = nzd_ - null_space_.rank();
    productNoAlloc(Z_[cur_].topLeftCorner(n_dense_, nzd_new), Z_[prev].topLeftCorner(n_dense_, nzd_),
                   null_space_.basis(), false);
    nzd_ = nzd_new;
  }
  nz_ = nzd_ + n_free_;
}

void HqpSolver::firstNullSpace(const Eigen::Ref<const Eigen::MatrixXd>& B) {
  // Null space of level 0's rows B (m x nu) on its used columns, block by block: rows that share no column (the
  // feet: one leg each) form independent blocks, and the null space of a block-diagonal matrix is the
  // block-diagonal of theirs. The QR of a block is the QR of those rows within the whole (a Householder step on
  // one row touches only its columns), so the rank decisions are the same with the same scale (the largest row
  // norm of B); four 3 x 5 factorisations instead of one 12 x 20.
  const int m = static_cast<int>(B.rows()), nu = static_cast<int>(B.cols());
  auto root = [this](int c) {
    while (block_root_[c] != c) c = block_root_[c] = block_root_[block_root_[c]];
    return c;
  };
  for (int c = 0; c < nu; ++c) block_root_[c] = c;
  int blocks = nu;
  for (int r = 0; r < m && blocks > 1; ++r) {
    int first_col = -1;
    for (int c = 0; c < nu; ++c) {
      if (B(r, c) == 0.0) continue;
      if (first_col < 0) {
        first_col = c;
      } else {
        const int a = root(c), b = root(first_col);
        if (a != b) {
          block_root_[a] = b;
          --blocks;
        }
      }
    }
    row_block_[r] = first_col < 0 ? -1 : first_col;  // a column of the row's block (-1: an all-zero row)
  }
  if (blocks == 1) {  // one block (e.g. a dense row): the whole matrix at once
    null_space_.compute(B, rank_tol_);
    nzd_ = nu - null_space_.rank();
    Z_[cur_].topLeftCorner(nu, nzd_) = null_space_.basis();
    return;
  }
  double scale = 0.0;
  for (int r = 0; r < m; ++r) scale = std::max(scale, B.row(r).norm());
  auto Z = Z_[cur_].topLeftCorner(nu, nu);
  int nzd = 0;
  for (int c0 = 0; c0 < nu; ++c0) {
    if (root(c0) != c0) continue;  // one pass per block, at its root column
    int p = 0, mb = 0;
    for (int c = 0; c < nu; ++c)
      if (root(c) == c0) block_cols_[p++] = c;
    for (int r = 0; r < m; ++r)
      if (row_block_[r] >= 0 && root(row_block_[r]) == c0) block_rows_[mb++] = r;
    for (int j = 0; j < p; ++j) Z.col(nzd + j).setZero();
    if (mb == 0) {  // columns no row touches (a constraint row does): their unit vectors
      for (int j = 0; j < p; ++j) Z(block_cols_[j], nzd + j) = 1.0;
      nzd += p;
      continue;
    }
    auto Bb = Ab_.topLeftCorner(mb, p);
    for (int j = 0; j < p; ++j)
      for (int i = 0; i < mb; ++i) Bb(i, j) = B(block_rows_[i], block_cols_[j]);
    null_space_.compute(Bb, rank_tol_, scale);
    const auto N = null_space_.basis();
    for (int j = 0; j < N.cols(); ++j)
      for (int i = 0; i < p; ++i) Z(block_cols_[i], nzd + j) = N(i, j);
    nzd += static_cast<int>(N.cols());
  }
  nzd_ = nzd;
}

Eigen::Ref<const Eigen::MatrixXd> HqpSolver::denseColumns(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                                          Eigen::MatrixXd& work) const {
  if (dense_identity_) return M;  // every variable is dense, in order: M itself
  auto D = work.topLeftCorner(M.rows(), n_dense_);
  for (int b = 0; b < n_dense_; ++b) D.col(b) = M.col(dense_[b]);
  return D;
}

void HqpSolver::copyLevelRows(int k) {
  // Straight into E_ / bE_: a term that takes every row of its task as one block copy, a selection row by row.
  int row = level_offset_[k];
  for (const Term& t : stack_.levels[k].terms) {
    const Task& task = *t.task;
    const int m = t.size();
    if (t.rows.empty()) {
      E_.middleRows(row, m) = task.A();
      bE_.segment(row, m) = task.lambda() * task.b();
    } else {
      for (int r = 0; r < m; ++r) {
        const int tr = t.taskRow(r);
        E_.row(row + r) = task.A().row(tr);
        bE_[row + r] = task.lambda() * task.b()[tr];
      }
    }
    row += m;
  }
}

void HqpSolver::weigh(const Term& t, const Eigen::Ref<const Eigen::MatrixXd>& M, Eigen::Ref<Eigen::MatrixXd> WM) {
  const Task& task = *t.task;
  const int m = t.size();
  if (task.diagonalWeight()) {
    for (int r = 0; r < m; ++r) WM.row(r) = (t.scale * task.weight()(t.taskRow(r), t.taskRow(r))) * M.row(r);
  } else {
    auto W = Wsel_.topLeftCorner(m, m);
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < m; ++c) W(r, c) = t.scale * task.weight()(t.taskRow(r), t.taskRow(c));
    productNoAlloc(WM, W, M, false);
  }
}

QpStatus HqpSolver::solveReduced(int k) {
  const Eigen::VectorXd& xp = level_x_[k - 1];
  updateNullSpace(k);
  level_rank_[k] = n_ - nz_;
  if (nz_ == 0) {  // the levels above fix x completely (and every level below)
    level_x_[k] = xp;
    return QpStatus::kOptimal;
  }
  levelRows(k);
  // The QP in y = [yd; yt]: x = xp + Zd yd on the dense variables, xp + yt on the touched free ones.
  const int nd = n_dense_, nzd = nzd_, nt = n_touched_;
  reducedCost(k);
  const int rows = reducedRows(xp);
  const QpStatus status = solveReducedQp(k, rows);
  if (status != QpStatus::kOptimal) return status;
  const auto y = ysol_.head(nzd + nt);
  Eigen::VectorXd& x = level_x_[k];
  x = xp;
  if (nzd > 0) {
    auto xd = xd_.head(nd);
    xd.noalias() = Z_[cur_].topLeftCorner(nd, nzd) * y.head(nzd);
    for (int b = 0; b < nd; ++b) x[dense_[b]] += xd[b];
  }
  for (int i = 0; i < nt; ++i) x[touched_[i]] += y[nzd + i];
  // The touched free variables join the dense ones for the levels below: Zd <- [Zd 0; 0 I].
  if (nt > 0 && k + 1 < numLevels()) {
    Eigen::MatrixXd& Z = Z_[cur_];
    Z.block(0, nzd, nd, nt).setZero();
    Z.block(nd, 0, nt, nzd).setZero();
    Z.block(nd, nzd, nt, nt).setIdentity();
    for (int i = 0; i < nt; ++i) dense_[nd + i] = touched_[i];
    n_dense_ += nt;
    dense_identity_ = false;
    nzd_ += nt;
  }
  return QpStatus::kOptimal;
}

void HqpSolver::levelRows(int k) {
  // This level's rows (into E_, for the next level's null space) and the free variables they touch. The
  // untouched free variables keep their value: their only cost is eps x_j^2 and no row couples them, so they
  // stay where level 0 put them (0 clipped to the box).
  const int first = level_offset_[k];
  const int mk = level_offset_[k + 1] - first;
  copyLevelRows(k);
  n_touched_ = 0;
  int kept = 0;
  for (int i = 0; i < n_free_; ++i) {
    const int j = free_[i];
    if (E_.col(j).segment(first, mk).cwiseAbs().maxCoeff() > 0.0) {
      touched_[n_touched_++] = j;
    } else {
      free_[kept++] = j;
    }
  }
  n_free_ = kept;
}

void HqpSolver::reducedCost(int k) {
  // Reduced cost of level k, x = xp + Z y:  sum_t scale_t ||A_t Z y + (A_t xp - lambda_t b_t)||^2_W + eps ||xp + Z y||^2
  //   Hy = sum (A Z)' W (A Z) + eps I,   gy = sum (A Z)' W (A xp - lambda b) + eps Z' xp   (Z'Z = I).
  const Eigen::VectorXd& xp = level_x_[k - 1];
  const int nd = n_dense_, nzd = nzd_, nt = n_touched_, nq = nzd + nt;
  const auto Zd = Z_[cur_].topLeftCorner(nd, nzd);
  auto Hy = Hy_.topLeftCorner(nq, nq);
  auto gy = gy_.head(nq);
  auto xd = xd_.head(nd);
  for (int b = 0; b < nd; ++b) xd[b] = xp[dense_[b]];
  Hy.setZero();
  gy.head(nzd).noalias() = stack_.regularisation * (Zd.transpose() * xd);
  for (int i = 0; i < nt; ++i) gy[nzd + i] = stack_.regularisation * xp[touched_[i]];
  int row = level_offset_[k];
  for (const Term& t : stack_.levels[k].terms) {
    const int m = t.size();
    const auto A = E_.middleRows(row, m);
    const Eigen::Ref<const Eigen::MatrixXd> Ad = denseColumns(A, Ad_);
    auto res = res_.head(m);
    res.noalias() = A * xp;
    res -= bE_.segment(row, m);
    if (t.task->diagonalWeight()) {
      addDiagonalTerm(t, A, Ad, res, nzd, nt);
    } else {
      auto AZ = HZ_.topLeftCorner(m, nq);
      productNoAlloc(AZ.leftCols(nzd), Ad, Zd, false);
      for (int i = 0; i < nt; ++i) AZ.col(nzd + i) = A.col(touched_[i]);
      auto WAZ = WAs_.topLeftCorner(m, nq);
      weigh(t, AZ, WAZ);
      productNoAlloc(Hy, AZ.transpose(), WAZ, true);
      gy.noalias() += WAZ.transpose() * res;
    }
    row += m;
  }
  Hy.diagonal().array() += stack_.regularisation;
}

int HqpSolver::reducedRows(const Eigen::VectorXd& xp) {
  const int nd = n_dense_, nzd = nzd_, nt = n_touched_, nq = nzd + nt;
  const auto Zd = Z_[cur_].topLeftCorner(nd, nzd);
  // Rows: c_lo - C xp <= C Z y <= c_up - C xp (C touches dense variables only: they include level 0's used
  // columns); the box of a dense variable j is the row x_lo - xp <= Zd(j, :) yd <= x_up - xp, the box of a
  // touched free one a bound on its own yt.
  int rows = 0;
  if (m_in_ > 0) {
    const Eigen::Ref<const Eigen::MatrixXd> Cd = denseColumns(C_, Cd_);
    productNoAlloc(Cy_.topLeftCorner(m_in_, nzd), Cd, Zd, false);
    Cy_.block(0, nzd, m_in_, nt).setZero();
    auto cxp = tmp_.head(m_in_);
    cxp.noalias() = C_ * xp;
    ylo_.head(m_in_) = c_lo_ - cxp;
    yup_.head(m_in_) = c_up_ - cxp;
    rows = m_in_;
  }
  if (has_box_) {
    int nb = 0;  // the bounded dense variables (an unbounded one, e.g. the floating base, has no row)
    for (int b = 0; b < nd; ++b) {
      const int j = dense_[b];
      if (x_lo_[j] == -kInf && x_up_[j] == kInf) continue;
      nz_idx_[nb++] = b;
      ylo_[rows] = x_lo_[j] - xp[j];
      yup_[rows] = x_up_[j] - xp[j];
      ++rows;
    }
    auto Cb = Cy_.block(rows - nb, 0, nb, nq);  // their rows of Zd, column by column (contiguous)
    for (int c = 0; c < nzd; ++c)
      for (int i = 0; i < nb; ++i) Cb(i, c) = Zd(nz_idx_[i], c);
    Cb.rightCols(nt).setZero();
    blo_.head(nzd).setConstant(-kInf);
    bup_.head(nzd).setConstant(kInf);
    for (int i = 0; i < nt; ++i) {
      const int j = touched_[i];
      blo_[nzd + i] = x_lo_[j] - xp[j];
      bup_[nzd + i] = x_up_[j] - xp[j];
    }
  }
  // A row whose projection on the null space is negligible is fixed by the levels above (and met by xp):
  // it is dropped, since rounding noise in a near-zero row would read as a large normalised violation.
  auto row_sq = tmp_.head(rows);  // squared row norms, column by column
  row_sq.setZero();
  for (int c = 0; c < nq; ++c) row_sq += Cy_.col(c).head(rows).cwiseAbs2();
  for (int i = 0; i < rows; ++i) {
    const double original = i < m_in_ ? C_.row(i).norm() : 1.0;
    if (std::sqrt(row_sq[i]) <= kNullRowTol * original) {
      Cy_.row(i).head(nq).setZero();
      ylo_[i] = -kInf;
      yup_[i] = kInf;
    }
  }
  return rows;
}

QpStatus HqpSolver::solveReducedQp(int k, int rows) {
  const int nzd = nzd_, nt = n_touched_, nq = nzd + nt;
  const auto Hy = Hy_.topLeftCorner(nq, nq);
  const auto gy = gy_.head(nq);
  // A touched free variable with no off-diagonal entry of Hy is separable (it has no row either: its box is a
  // bound of its own, and the constraint and box rows are zero on it): y_i = argmin Hy_ii y^2 / 2 + gy_i y over
  // that bound, in closed form, e.g. a joint only a posture row touches. The QP keeps the other variables.
  int nk = 0, n_sep = 0;
  for (int i = 0; i < nzd; ++i) kept_[nk++] = i;
  for (int i = 0; i < nt; ++i) {
    const int c = nzd + i;
    bool separable = true;
    for (int r = 0; r < nq && separable; ++r) separable = r == c || Hy(r, c) == 0.0;
    if (separable) {
      sep_[n_sep++] = c;
    } else {
      kept_[nk++] = c;
    }
  }
  const Eigen::Map<const Eigen::VectorXd> none(nullptr, 0);
  QpSolver& qp = solvers_[k];
  auto y = ysol_.head(nq);
  QpStatus status;
  if (n_sep == 0) {
    const auto C = Cy_.topLeftCorner(rows, nq);
    status = has_box_ ? qp.solve(Hy, gy, Cy_.topLeftCorner(0, nq), ylo_.head(0), C, ylo_.head(rows),
                                 yup_.head(rows), blo_.head(nq), bup_.head(nq))
                      : qp.solve(Hy, gy, Cy_.topLeftCorner(0, nq), ylo_.head(0), C, ylo_.head(rows),
                                 yup_.head(rows), none, none);
    if (status == QpStatus::kOptimal) y = qp.x();
  } else {
    auto Hc = Hc_.topLeftCorner(nk, nk);
    auto gc = gc_.head(nk);
    for (int b = 0; b < nk; ++b) {
      gc[b] = gy[kept_[b]];
      for (int a = 0; a < nk; ++a) Hc(a, b) = Hy(kept_[a], kept_[b]);
    }
    auto Cc = Cc_.topLeftCorner(rows, nk);  // the kept touched columns of the rows are zero
    Cc.leftCols(nzd) = Cy_.topLeftCorner(rows, nzd);
    Cc.rightCols(nk - nzd).setZero();
    if (has_box_) {
      for (int a = 0; a < nk; ++a) {
        blc_[a] = blo_[kept_[a]];
        buc_[a] = bup_[kept_[a]];
      }
    }
    status = has_box_ ? qp.solve(Hc, gc, Cc_.topLeftCorner(0, nk), ylo_.head(0), Cc, ylo_.head(rows),
                                 yup_.head(rows), blc_.head(nk), buc_.head(nk))
                      : qp.solve(Hc, gc, Cc_.topLeftCorner(0, nk), ylo_.head(0), Cc, ylo_.head(rows),
                                 yup_.head(rows), none, none);
    if (status == QpStatus::kOptimal) {
      for (int a = 0; a < nk; ++a) y[kept_[a]] = qp.x()[a];
      for (int s = 0; s < n_sep; ++s) {
        const int c = sep_[s];
        double v = -gy[c] / Hy(c, c);
        if (has_box_) v = std::clamp(v, blo_[c], bup_[c]);
        y[c] = v;
      }
    }
  }
  return status;
}

void HqpSolver::addDiagonalTerm(const Term& t, const Eigen::Ref<const Eigen::MatrixXd>& A,
                                const Eigen::Ref<const Eigen::MatrixXd>& Ad, const Eigen::Ref<const Eigen::VectorXd>& res,
                                int nzd, int nt) {
  // A term with a diagonal weight w_r: Hy += (A Z)' diag(w) (A Z), gy += (A Z)' diag(w) res, with A Z = [Ad Zd, A_T].
  // The Zd block is dense; the touched free columns A_T are mostly empty (a posture row has one entry), so their
  // blocks are accumulated row by row over each row's nonzeros instead of as a dense product.
  const Task& task = *t.task;
  const int m = t.size();
  const int nd = static_cast<int>(Ad.cols());
  auto Hy = Hy_.topLeftCorner(nzd + nt, nzd + nt);
  auto gy = gy_.head(nzd + nt);
  auto w = w_.head(m);
  for (int r = 0; r < m; ++r) w[r] = t.scale * task.weight()(t.taskRow(r), t.taskRow(r));
  auto AZd = HZ_.topLeftCorner(m, nzd);
  auto WAZd = WAs_.topLeftCorner(m, nzd);
  if (nzd > 0) {
    productNoAlloc(AZd, Ad, Z_[cur_].topLeftCorner(nd, nzd), false);
    WAZd = w.asDiagonal() * AZd;
    productNoAlloc(Hy.topLeftCorner(nzd, nzd), AZd.transpose(), WAZd, true);
    gy.head(nzd).noalias() += WAZd.transpose() * res;
  }
  for (int r = 0; r < m; ++r) {
    int nnz = 0;
    for (int i = 0; i < nt; ++i) {
      const double a = A(r, touched_[i]);
      if (a != 0.0) {
        nz_idx_[nnz] = i;
        nz_val_[nnz++] = a;
      }
    }
    for (int p = 0; p < nnz; ++p) {
      const int ci = nzd + nz_idx_[p];
      const double wa = w[r] * nz_val_[p];
      gy[ci] += wa * res[r];
      if (nzd > 0) {
        Hy.col(ci).head(nzd) += nz_val_[p] * WAZd.row(r).transpose();
        Hy.row(ci).head(nzd) += nz_val_[p] * WAZd.row(r);
      }
      for (int q = 0; q < nnz; ++q) Hy(ci, nzd + nz_idx_[q]) += wa * nz_val_[q];
    }
  }
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
