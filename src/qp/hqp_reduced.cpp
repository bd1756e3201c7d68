// HqpSolver's levels k >= 1: each solved in the null space of the rows of the levels above it.
#include "qp/hqp_solver.hpp"

#include "qp/product.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace centaur {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNullRowTol = 1e-9;  // relative norm of a constraint row after projection on null(E)
}  // namespace

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

}  // namespace centaur
