// The solves of StageKktSolver: the stage right-hand sides, the recursion's solve, the recovery of the step in
// the OCP's variables, and iterative refinement on the whole system's residual.
#include <algorithm>
#include <cmath>

#include "ocp_solver/stage_kkt.hpp"

namespace centaur::ocp_solver {

// The largest entry of the matrix (the scale of the relative residual), once per factorization.
double StageKktSolver::largestEntry() const {
  double kmax = 0.0;
  for (std::size_t t = 0; t < pattern_.hess_rows.size(); ++t) kmax = std::max(kmax, std::abs(hess_[t]));
  for (int v = 0; v < n_; ++v) kmax = std::max(kmax, std::abs(dx_diag_[v]));
  for (std::size_t t = 0; t < pattern_.jac_rows.size(); ++t) kmax = std::max(kmax, std::abs(jac_[t]));
  return kmax;
}

double StageKktSolver::residual(const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, const Eigen::VectorXd& dx,
                                const Eigen::VectorXd& dy, Eigen::VectorXd& res_x, Eigen::VectorXd& res_c) const {
  res_x = rx;
  res_c = rc;
  // Each entry gets the subtractions of a plain loop over the triplets, in the same order; a run of triplets of one
  // row keeps that row's entry in a register instead of storing it after every triplet (the patterns list their
  // triplets by row; any order gives the same result).
  const int nh = static_cast<int>(pattern_.hess_rows.size()), nj = static_cast<int>(pattern_.jac_rows.size());
  const int* hr = pattern_.hess_rows.data();
  const int* hc = pattern_.hess_cols.data();
  for (int t = 0; t < nh;) {
    const int a = hr[t];
    const double dxa = dx[a];
    double ra = res_x[a];
    for (; t < nh && hr[t] == a; ++t) {
      const int b = hc[t];
      ra -= hess_[t] * dx[b];
      if (a != b) res_x[b] -= hess_[t] * dxa;
    }
    res_x[a] = ra;
  }
  for (int v = 0; v < n_; ++v) res_x[v] -= dx_diag_[v] * dx[v];
  const int* jr = pattern_.jac_rows.data();
  const int* jc = pattern_.jac_cols.data();
  for (int t = 0; t < nj;) {
    const int r = jr[t];
    const double dyr = dy[r];
    double rr = res_c[r];
    for (; t < nj && jr[t] == r; ++t) {
      const int c = jc[t];
      res_x[c] -= jac_[t] * dyr;
      rr -= jac_[t] * dx[c];
    }
    res_c[r] = rr;
  }
  for (int r = 0; r < m_; ++r)
    if (!dynamics_row_[r]) res_c[r] += dc_[r] * dy[r];
  for (int v = 0; v < n_; ++v)
    if (fixed_[v]) res_x[v] = 0.0;
  const double sol = std::max(dx.cwiseAbs().maxCoeff(), dy.size() ? dy.cwiseAbs().maxCoeff() : 0.0);
  return std::max({rx.cwiseAbs().maxCoeff(), rc.size() ? rc.cwiseAbs().maxCoeff() : 0.0, kmax_ * sol, 1e-300});
}

void StageKktSolver::solve(const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, Eigen::VectorXd& dx,
                           Eigen::VectorXd& dy) {
  if (kmax_ < 0.0) kmax_ = largestEntry();
  solveWith(work_[0], rx, rc, dx, dy);
  last_residual_ = work_[0].residual;
}

void StageKktSolver::solveTwo(const KktSolve& a, const KktSolve& b) {
  if (kmax_ < 0.0) kmax_ = largestEntry();
  SolveWork &wa = work_[0], &wb = work_[1];
  const common::ParallelSection section(riccati_.worker(), common::kSectionSolves);
  if (riccati_.parallel()) {
    riccati_.runPair([&] { solveWith(wa, a.rx, a.rc, a.dx, a.dy); }, [&] { solveWith(wb, b.rx, b.rc, b.dx, b.dy); });
    last_residual_ = wb.residual;
    return;
  }
  stageRhs(wa, a.rx, a.rc);
  stageRhs(wb, b.rx, b.rc);
  riccati_.solveTwo(qp_, {wa.rhs, wa.sol, wa.vec}, {wb.rhs, wb.sol, wb.vec});
  recoverStep(wa, a.rc, a.dx, a.dy);
  recoverStep(wb, b.rc, b.dx, b.dy);
  refine(wa, a.rx, a.rc, a.dx, a.dy);
  refine(wb, b.rx, b.rc, b.dx, b.dy);
  last_residual_ = wb.residual;
}

void StageKktSolver::solveWith(SolveWork& w, const Eigen::VectorXd& rx, const Eigen::VectorXd& rc,
                               Eigen::VectorXd& dx, Eigen::VectorXd& dy) const {
  solveOnce(w, rx, rc, dx, dy);
  refine(w, rx, rc, dx, dy);
}

void StageKktSolver::refine(SolveWork& w, const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, Eigen::VectorXd& dx,
                            Eigen::VectorXd& dy) const {
  for (int it = 0;; ++it) {
    const double scale = residual(rx, rc, dx, dy, w.res_x, w.res_c);
    const double r = std::max(w.res_x.cwiseAbs().maxCoeff(), m_ ? w.res_c.cwiseAbs().maxCoeff() : 0.0);
    w.residual = r / scale;
    if (w.residual <= 1e-12 || it >= max_refinement) break;
    solveOnce(w, w.res_x, w.res_c, w.ddx, w.ddy);
    dx += w.ddx;
    dy += w.ddy;
  }
}

void StageKktSolver::solveOnce(SolveWork& w, const Eigen::VectorXd& rx, const Eigen::VectorXd& rc,
                               Eigen::VectorXd& dx, Eigen::VectorXd& dy) const {
  stageRhs(w, rx, rc);
  riccati_.solve(qp_, w.rhs, w.sol, w.vec);
  recoverStep(w, rc, dx, dy);
}

// The stage right-hand sides of the system with right-hand side (rx, rc).
void StageKktSolver::stageRhs(SolveWork& w, const Eigen::VectorXd& rx, const Eigen::VectorXd& rc) const {
  w.rhs.resize(N_ + 1);
  for (int k = 0; k <= N_; ++k) {
    const StageQp& q = qp_[k];
    w.rhs[k].h.setZero(q.H.rows());
    w.rhs[k].b.setZero(q.A.rows());
    w.rhs[k].c.setZero(q.C.rows());
  }
  for (int v = 0; v < n_; ++v)
    if (!fixed_[v]) w.rhs[layout_.stage[v]].h[colOf(layout_.stage[v], v)] = -rx[v];
  for (int k = 0; k < N_; ++k) {
    StageRhs& q = w.rhs[k];
    for (int j = 0; j < nx_[k + 1]; ++j) q.b[j] = rc[dyn_rows_[k][j]] / diag_[dyn_rows_[k][j]];
  }
  Eigen::VectorXd& a = w.a;
  double shift = 0.0;
  for (int k = 0; k <= N_; ++k) {
    StageRhs& q = w.rhs[k];
    int i = static_cast<int>(fixed_cols_[k].size());
    for (int r : exact_rows_[k]) {
      const Row& row = rows_[r];
      shift = 0.0;
      for (const Entry& e : row.entries)
        if (e.next) shift += jac_[e.slot] * q.b[e.col];
      q.c[i++] = shift - rc[r];
    }
    for (int r : penalty_rows_[k]) {
      const Row& row = rows_[r];
      if (row.kind == RowKind::kLocal) {  // its few entries: the dense update below changes no other entry of h
        const double coef = rc[r] / dc_[r];
        for (const Entry& e : row.entries) q.h[e.col] -= coef * jac_[e.slot];
        continue;
      }
      rowVector(row, jac_, &q.b, a, shift);
      q.h.noalias() -= ((rc[r] - shift) / dc_[r]) * a;
    }
  }
}

// The step (dx, dy) of the NLP from the stage solution in w.
void StageKktSolver::recoverStep(SolveWork& w, const Eigen::VectorXd& rc, Eigen::VectorXd& dx,
                                 Eigen::VectorXd& dy) const {
  const std::vector<StageSolution>& sol = w.sol;
  Eigen::VectorXd& a = w.a;
  double shift = 0.0;
  dx.setZero(n_);
  for (int v = 0; v < n_; ++v) {
    if (fixed_[v]) continue;
    const StageSolution& s = sol[layout_.stage[v]];
    dx[v] = layout_.is_state[v] ? s.x[local_[v]] : s.u[local_[v]];
  }
  dy.setZero(m_);
  Eigen::VectorXd& z = w.z;
  for (int k = 0; k <= N_; ++k) {
    const StageSolution& s = sol[k];
    int i = static_cast<int>(fixed_cols_[k].size());
    for (int r : exact_rows_[k]) dy[r] = s.eta[i++];
    if (penalty_rows_[k].empty()) continue;
    z.resize(s.x.size() + s.u.size());
    z << s.x, s.u;
    for (int r : penalty_rows_[k]) {
      rowVector(rows_[r], jac_, &w.rhs[k].b, a, shift);
      dy[r] = (a.dot(z) + shift - rc[r]) / dc_[r];
    }
  }
  // Dynamics multipliers: from the Riccati co-states, then undo the substitution of the coupled rows.
  for (int k = 0; k < N_; ++k)
    for (int j = 0; j < nx_[k + 1]; ++j) {
      const int r = dyn_rows_[k][j];
      dy[r] = -sol[k].lambda[j] / diag_[r];
    }
  for (int k = 0; k < N_; ++k)
    for (int r : stage_rows_[k]) {
      const Row& row = rows_[r];
      if (row.kind != RowKind::kCoupled) continue;
      for (const Entry& e : row.entries) {
        if (!e.next) continue;
        const int dr = dyn_rows_[k][e.col];
        dy[dr] -= jac_[e.slot] / diag_[dr] * dy[r];
      }
    }
}

}  // namespace centaur::ocp_solver
