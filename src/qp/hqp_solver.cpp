// HqpSolver's solve: level 0 on the columns its rows touch, the null spaces between the levels (the levels
// k >= 1 are in hqp_reduced.cpp, the setup in hqp_configure.cpp).
#include "qp/hqp_solver.hpp"

#include "qp/product.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace centaur {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

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
