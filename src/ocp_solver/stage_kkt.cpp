#include "ocp_solver/stage_kkt.hpp"

#include <algorithm>
#include <map>
#include <set>

namespace centaur::ocp_solver {

StageKktSolver::StageKktSolver(const SparsePattern& p, const StageLayout& layout, const std::vector<char>& fixed,
                               const std::vector<char>& equality, RiccatiSolver::Options options)
    : n_(p.n), m_(p.m), N_(layout.num_stages - 1), layout_(layout), fixed_(fixed), equality_(equality),
      pattern_(p), riccati_(options) {
  if (N_ < 0 || static_cast<int>(layout.stage.size()) != n_ || static_cast<int>(layout.is_state.size()) != n_ ||
      static_cast<int>(fixed.size()) != n_ || static_cast<int>(equality.size()) != m_) {
    throw StructureError("StageKktSolver: layout sizes do not match the pattern");
  }
  nx_.assign(N_ + 1, 0);
  nu_.assign(N_ + 1, 0);
  local_.resize(n_);
  for (int v = 0; v < n_; ++v) {
    const int s = layout.stage[v];
    if (s < 0 || s > N_) throw StructureError("StageKktSolver: variable " + std::to_string(v) + " outside the stages");
    local_[v] = layout.is_state[v] ? nx_[s]++ : nu_[s]++;
  }
  if (nu_[N_] != 0) throw StructureError("StageKktSolver: the last stage has controls");
  analyzeRows(p, equality);
  analyzeCarried(p);
  analyzeDynamics();
  diag_.setZero(m_);
}

// Where each stage's dynamics [A B] can be nonzero: the entries of its dynamics rows and the copies of the carried
// variables, by column, then row.
void StageKktSolver::analyzeDynamics() {
  dyn_pattern_.assign(N_ + 1, {});
  for (int k = 0; k < N_; ++k) {
    std::vector<std::pair<int, int>>& pat = dyn_pattern_[k];
    for (int j = 0; j < nx_[k + 1]; ++j)
      for (const Entry& e : rows_[dyn_rows_[k][j]].entries)
        if (!e.next) pat.emplace_back(e.col, j);
    for (std::size_t c = 0; c < carried_[k + 1].size(); ++c)
      pat.emplace_back(carry_src_[k + 1][c], nx_[k + 1] + static_cast<int>(c));
    std::sort(pat.begin(), pat.end());
    pat.erase(std::unique(pat.begin(), pat.end()), pat.end());
  }
}

// Size the row blocks of stage k and zero what fillRows accumulates into. A and B keep their size from one
// factorization to the next and are only ever written where the dynamics can be nonzero, so only those entries
// are reset; C's rows are all written by fillRows.
void StageKktSolver::resetRows(int k, int nxa, int m, int nxn) {
  StageQp& q = qp_[k];
  const int n = nxa + nu_[k];
  q.nx = nxa;
  q.nu = nu_[k];
  q.h.setZero(n);
  q.b.setZero(nxn);
  q.c.setZero(m);
  q.C.resize(m, n);
  if (q.A.rows() != nxn || q.A.cols() != nxa || q.B.cols() != nu_[k]) {
    q.A.setZero(nxn, nxa);
    q.B.setZero(nxn, nu_[k]);
  } else {
    for (const auto& [col, row] : dyn_pattern_[k]) (col < nxa ? q.A(row, col) : q.B(row, col - nxa)) = 0.0;
  }
}

// [A B] of stage k by sparse columns from its possible nonzeros (the entries sparseColumns() would keep).
void StageKktSolver::sparseDynamics(int k) {
  StageQp& q = qp_[k];
  SparseColumns& M = q.M;
  const int cols = q.nx + q.nu;
  M.rows = static_cast<int>(q.A.rows());
  M.cols = cols;
  M.start.assign(cols + 1, 0);
  M.row.clear();
  M.value.clear();
  for (const auto& [col, row] : dyn_pattern_[k]) {
    const double v = col < q.nx ? q.A(row, col) : q.B(row, col - q.nx);
    if (v == 0.0) continue;
    M.row.push_back(row);
    M.value.push_back(v);
    ++M.start[col + 1];
  }
  for (int j = 0; j < cols; ++j) M.start[j + 1] += M.start[j];
}

// Dynamics rows first (one per component of every x_{k+1}), then every other row's owner stage and kind.
void StageKktSolver::analyzeRows(const SparsePattern& p, const std::vector<char>& equality) {
  std::vector<std::vector<std::pair<int, int>>> by_row(m_);  // (slot, var)
  for (std::size_t t = 0; t < p.jac_rows.size(); ++t) by_row[p.jac_rows[t]].push_back({static_cast<int>(t), p.jac_cols[t]});
  rows_.assign(m_, Row{});
  dynamics_row_.assign(m_, 0);
  dyn_rows_.assign(N_, {});
  for (int k = 0; k < N_; ++k) dyn_rows_[k].assign(nx_[k + 1], -1);
  std::vector<int> smin(m_, N_ + 1), smax(m_, -1), next_states(m_, 0);
  std::vector<char> next_only_states(m_, 1);
  for (int r = 0; r < m_; ++r) {
    for (const auto& [slot, v] : by_row[r]) {
      smin[r] = std::min(smin[r], layout_.stage[v]);
      smax[r] = std::max(smax[r], layout_.stage[v]);
    }
    for (const auto& [slot, v] : by_row[r]) {
      if (layout_.stage[v] != smax[r]) continue;
      if (layout_.is_state[v]) ++next_states[r];
      else next_only_states[r] = 0;
    }
  }
  for (int r = 0; r < m_; ++r) {  // dynamics: one entry on x_{k+1}, the others on stage k
    if (!equality[r] || smax[r] != smin[r] + 1 || !next_only_states[r] || next_states[r] != 1) continue;
    const int k = smin[r];
    for (const auto& [slot, v] : by_row[r]) {
      if (layout_.stage[v] != k + 1) continue;
      int& d = dyn_rows_[k][local_[v]];
      if (d < 0) {
        d = r;
        dynamics_row_[r] = 1;
        rows_[r].kind = RowKind::kDynamics;
        rows_[r].stage = k;
        rows_[r].comp = local_[v];
      }
    }
  }
  for (int k = 0; k < N_; ++k)
    for (int j = 0; j < nx_[k + 1]; ++j)
      if (dyn_rows_[k][j] < 0)
        throw StructureError("StageKktSolver: state " + std::to_string(j) + " of stage " + std::to_string(k + 1) +
                             " has no dynamics row (x_{k+1} with a single entry, the rest on stage k)");
  for (int r = 0; r < m_; ++r) {
    if (by_row[r].empty()) throw StructureError("StageKktSolver: constraint row " + std::to_string(r) + " is empty");
    Row& row = rows_[r];
    if (row.kind == RowKind::kDynamics) continue;
    if (smax[r] == smin[r] + 1 && next_only_states[r]) {
      row.kind = RowKind::kCoupled;
      row.stage = smin[r];
    } else {
      row.kind = RowKind::kLocal;  // earlier variables, if any, are carried into the last stage
      row.stage = smax[r];
    }
  }
  // Entries (columns are set after the carried variables are known).
  for (int r = 0; r < m_; ++r)
    for (const auto& [slot, v] : by_row[r]) rows_[r].entries.push_back(Entry{slot, v, false});
}

void StageKktSolver::analyzeCarried(const SparsePattern& p) {
  std::vector<std::set<int>> carry(N_ + 1);
  auto need = [&](int var, int stage) {
    for (int s = layout_.stage[var] + 1; s <= stage; ++s) carry[s].insert(var);
  };
  for (const Row& row : rows_) {
    if (row.kind != RowKind::kLocal) continue;
    for (const Entry& e : row.entries)
      if (layout_.stage[e.col] < row.stage) need(e.col, row.stage);  // e.col still holds the variable here
  }
  for (std::size_t t = 0; t < p.hess_rows.size(); ++t) {
    const int a = p.hess_rows[t], b = p.hess_cols[t];
    const int sa = layout_.stage[a], sb = layout_.stage[b];
    if (sa < sb) need(a, sb);
    if (sb < sa) need(b, sa);
  }
  carried_.assign(N_ + 1, {});
  for (int s = 0; s <= N_; ++s) carried_[s].assign(carry[s].begin(), carry[s].end());
  carry_src_.assign(N_ + 1, {});
  for (int s = 1; s <= N_; ++s)
    for (int v : carried_[s]) carry_src_[s].push_back(colOf(s - 1, v));

  stage_rows_.assign(N_ + 1, {});
  for (int r = 0; r < m_; ++r) {
    Row& row = rows_[r];
    for (Entry& e : row.entries) {
      const int v = e.col;
      if (row.kind != RowKind::kLocal && layout_.stage[v] == row.stage + 1) {
        e.next = true;
        e.col = local_[v];
      } else {
        e.col = colOf(row.stage, v);
      }
    }
    if (row.kind != RowKind::kDynamics) stage_rows_[row.stage].push_back(r);
  }
  hess_entries_.assign(N_ + 1, {});
  for (std::size_t t = 0; t < p.hess_rows.size(); ++t) {
    const int a = p.hess_rows[t], b = p.hess_cols[t];
    const int s = std::max(layout_.stage[a], layout_.stage[b]);
    hess_entries_[s].push_back(HessEntry{static_cast<int>(t), colOf(s, a), colOf(s, b)});
  }
  stage_vars_.assign(N_ + 1, {});
  for (int v = 0; v < n_; ++v) stage_vars_[layout_.stage[v]].push_back(v);
  fixed_cols_.assign(N_ + 1, {});
  for (int v = 0; v < n_; ++v)
    if (fixed_[v]) fixed_cols_[layout_.stage[v]].push_back(colOf(layout_.stage[v], v));
  qp_.resize(N_ + 1);
  exact_rows_.assign(N_ + 1, {});
  penalty_rows_.assign(N_ + 1, {});
}

// A row of stage k as a dense vector over z_k; a coupled row gets the dynamics substituted for x_{k+1}
// (rhs_shift: its constant J_next b, which the caller adds to the row's right-hand side; computed when b is given).
void StageKktSolver::rowVector(const Row& row, const double* jac, const Eigen::VectorXd* b, Eigen::VectorXd& a,
                               double& rhs_shift) const {
  const StageQp& q = qp_[row.stage];
  a.setZero(q.nx + q.nu);
  rhs_shift = 0.0;
  for (const Entry& e : row.entries) {
    const double v = jac[e.slot];
    if (!e.next) {
      a[e.col] += v;
    } else {
      a.head(q.nx).noalias() += v * q.A.row(e.col).transpose();
      a.tail(q.nu).noalias() += v * q.B.row(e.col).transpose();
      if (b) rhs_shift += v * (*b)[e.col];
    }
  }
}

void StageKktSolver::setPipelined(bool on) { riccati_.setParallel(on); }
void StageKktSolver::setPipelined(common::WorkerThread* shared) { riccati_.setParallel(shared); }

// The blocks of stage k that depend on the Jacobian only: which rows are exact, the dynamics [A B] (and the scale
// of each dynamics row), C.
void StageKktSolver::fillRows(int k) {
  StageQp& q = qp_[k];
  Eigen::VectorXd& a = fill_a_;
  exact_rows_[k].clear();
  penalty_rows_[k].clear();
  for (int r : stage_rows_[k]) (dc_[r] > 0.0 ? penalty_rows_[k] : exact_rows_[k]).push_back(r);
  const int m = static_cast<int>(fixed_cols_[k].size() + exact_rows_[k].size());
  const int nxa = nx_[k] + static_cast<int>(carried_[k].size());
  const int nxn = k < N_ ? nx_[k + 1] + static_cast<int>(carried_[k + 1].size()) : 0;
  resetRows(k, nxa, m, nxn);
  // Dynamics x_{k+1} = A z_k + b, scaled by the entry d on x_{k+1}; carried variables are copied.
  if (k < N_) {
    for (int j = 0; j < nx_[k + 1]; ++j) {
      const Row& row = rows_[dyn_rows_[k][j]];
      double d = 0.0;
      for (const Entry& e : row.entries)
        if (e.next) d += jac_[e.slot];
      diag_[dyn_rows_[k][j]] = d;
      for (const Entry& e : row.entries) {
        if (e.next) continue;
        if (e.col < q.nx) q.A(j, e.col) -= jac_[e.slot] / d;
        else q.B(j, e.col - q.nx) -= jac_[e.slot] / d;
      }
    }
    for (std::size_t c = 0; c < carried_[k + 1].size(); ++c) {
      const int src = carry_src_[k + 1][c], dst = nx_[k + 1] + static_cast<int>(c);
      if (src < q.nx) q.A(dst, src) = 1.0;
      else q.B(dst, src - q.nx) = 1.0;
    }
    sparseDynamics(k);
  }
  double shift = 0.0;
  int i = 0;
  for (int c : fixed_cols_[k]) {
    q.C.row(i).setZero();
    q.C(i++, c) = 1.0;
  }
  for (int r : exact_rows_[k]) {
    rowVector(rows_[r], jac_, nullptr, a, shift);
    q.C.row(i++) = a.transpose();
  }
  rows_filled_[k] = 1;
}

// H of stage k (after fillRows): the Hessian entries, the diagonal, the penalty rows.
void StageKktSolver::fillCost(int k, int thread) {
  StageQp& q = qp_[k];
  Eigen::VectorXd& a = cost_fill_[thread].a;
  std::vector<int>& nz = cost_fill_[thread].nz;
  const int n = q.nx + q.nu;
  q.H.setZero(n, n);
  for (const HessEntry& h : hess_entries_[k]) {
    q.H(h.r, h.c) += hess_[h.slot];
    if (h.r != h.c) q.H(h.c, h.r) += hess_[h.slot];
  }
  for (int v : stage_vars_[k]) {
    const int c = colOf(k, v);
    q.H(c, c) += fixed_[v] ? 1.0 : dx_diag_[v];
  }
  double shift = 0.0;
  for (int r : penalty_rows_[k]) {
    const Row& row = rows_[r];
    const double w = 1.0 / dc_[r];
    if (row.kind == RowKind::kLocal) {  // sparse outer product
      for (const Entry& e1 : row.entries)
        for (const Entry& e2 : row.entries) q.H(e1.col, e2.col) += w * jac_[e1.slot] * jac_[e2.slot];
    } else {  // the row after substituting the dynamics: sparse too (a few states and controls)
      rowVector(row, jac_, nullptr, a, shift);
      nz.clear();
      for (int j = 0; j < a.size(); ++j)
        if (a[j] != 0.0) nz.push_back(j);
      for (int c : nz)
        for (int r2 : nz) q.H(r2, c) += w * a[r2] * a[c];
    }
  }
}

KktStatus StageKktSolver::factor(const double* hess, const double* jac, const Eigen::VectorXd& dx,
                                 const Eigen::VectorXd& dc) {
  jac_ = jac;
  hess_ = hess;
  dx_diag_ = dx;
  dc_ = dc;
  rows_filled_.assign(N_ + 1, 0);
  return run(false);
}

// The exact rows are those with d_c == 0 (the dynamics always): the same as in the last factorization, the row
// blocks and the recursion's row parts are kept.
KktStatus StageKktSolver::refactor(const double* hess, const double* jac, const Eigen::VectorXd& dx,
                                   const Eigen::VectorXd& dc) {
  bool same = hess == hess_ && jac == jac_ && dc.size() == dc_.size() && !rows_filled_.empty();
  for (int r = 0; same && r < m_; ++r) same = dynamics_row_[r] || (dc[r] > 0.0) == (dc_[r] > 0.0);
  if (!same) return factor(hess, jac, dx, dc);
  dx_diag_ = dx;
  dc_ = dc;
  return run(true);
}

KktStatus StageKktSolver::run(bool same_rows) {
  kmax_ = -1.0;
  // When pipelined, each stage's rows are filled on the second thread just before its row part, and its H by
  // whichever thread is free first. Stages the recursion did not reach after an early stop are filled by the next
  // factorization.
  const auto fill_rows = [this](int k) {
    if (!rows_filled_[k]) fillRows(k);
  };
  const auto fill_cost = [this](int k, int thread) { fillCost(k, thread); };
  // Timed per stage whose cost part ran (a failed trial stops early), first trials and retries apart.
  common::ParallelSection section(riccati_.worker(),
                                  same_rows ? common::kSectionRefactor : common::kSectionFactor);
  const RiccatiSolver::Status status = riccati_.factor(qp_, fill_rows, same_rows, fill_cost);
  const int failed = riccati_.failedStage();
  section.setWork(failed < 0 || failed > N_ ? N_ + 2 : N_ + 1 - failed);
  switch (status) {
    case RiccatiSolver::Status::kOk: return KktStatus::kOk;
    case RiccatiSolver::Status::kSingular: return KktStatus::kSingular;
    default: return KktStatus::kWrongInertia;
  }
}

}  // namespace centaur::ocp_solver
