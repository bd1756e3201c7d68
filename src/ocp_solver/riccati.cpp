#include "ocp_solver/riccati.hpp"

#include <chrono>
#include <cmath>
#include <thread>

#include "common/eigen_empty.hpp"
#include "ocp_solver/block_ops.hpp"

namespace centaur::ocp_solver {


void RiccatiSolver::Stage::solveNN(Eigen::Ref<Eigen::MatrixXd> rhs) const {
  if (nv == 0) return;
  if (!use_eig) {
    solveInPlaceUnlessEmpty(llt, rhs);
    return;
  }
  const Eigen::VectorXd& d = eig.eigenvalues();
  Eigen::MatrixXd t = eig.eigenvectors().transpose() * rhs;
  const double scale = std::max(1.0, d.cwiseAbs().maxCoeff());
  for (int i = 0; i < nv; ++i) t.row(i) *= (std::abs(d[i]) > 1e-14 * scale) ? 1.0 / d[i] : 0.0;
  rhs.noalias() = eig.eigenvectors() * t;
}

// The row part of one stage, given the stacked rows Cs (filled by the caller): their equilibration, the rank split
// by the controls, the pending rows Gamma for the previous stage and E. It reads no cost, so it can run ahead of
// the cost part. Its inertia contributions are kept in the stage (added by eliminateCost, in stage order).
void RiccatiSolver::eliminateRows(Stage& s) {
  const int nx = s.nx, nu = s.nu, n = nx + nu, m = s.m;
  equilibrateRows(s.Cs, s.row_scale);
  s.lu.compute(s.Cs.rightCols(nu), opt_.pivot_tol);
  const int r = s.lu.rank();
  s.rank = r;
  s.nv = nu - r;
  const int nv = s.nv, w = nx + nv;
  const std::vector<int>& rp = s.lu.rowPerm();
  const std::vector<int>& cp = s.lu.colPerm();
  s.perm.resize(n);
  for (int i = 0; i < nx; ++i) s.perm[i] = i;
  for (int j = 0; j < nv; ++j) s.perm[nx + j] = nx + cp[r + j];
  for (int j = 0; j < r; ++j) s.perm[w + j] = nx + cp[j];

  // State part of the rows, in pivot order, with the row transformation applied: the dependent rows become
  // rows on x alone (pending) or vanish (dependent rows of the whole KKT matrix: zero eigenvalues).
  Eigen::MatrixXd& X = row_scratch_.X;
  gatherRows(s.Cs, rp, nx, X);
  s.lu.applyRowTransform(X);
  s.kept.clear();
  s.dependent = 0;
  for (int i = r; i < m; ++i) {
    if (nx > 0 && X.row(i).cwiseAbs().maxCoeff() > opt_.rank_tol) {
      s.kept.push_back(i - r);
    } else {
      ++s.dependent;
    }
  }
  s.Gamma.resize(static_cast<int>(s.kept.size()), nx);
  for (std::size_t j = 0; j < s.kept.size(); ++j) s.Gamma.row(static_cast<int>(j)) = X.row(r + s.kept[j]);

  // u_B = E [x; u_N] + e with E = -U1^{-1} [X_I, U2].
  s.E.resize(r, w);
  s.E.leftCols(nx) = -X.topRows(r);
  s.E.rightCols(nv) = -s.lu.packed().block(0, r, r, nv);
  solveInPlaceUnlessEmpty(s.lu.packed().topLeftCorner(r, r).triangularView<Eigen::Upper>(), s.E);
}

// The cost part of one stage, after its row part and given Qp (in the cost scratch): the reduced Hessian on the
// free directions, its factor, the cost-to-go P. Adds the stage's inertia (rows and dynamics first). False on an
// indefinite reduced Hessian (unless full_inertia).
bool RiccatiSolver::eliminateCost(Stage& s) {
  const int nx = s.nx, r = s.rank, nv = s.nv, w = nx + nv;
  inertia_.positive += s.dyn_pairs + r;
  inertia_.negative += s.dyn_pairs + r;
  inertia_.zero += s.dependent;

  // Reduced Hessian Qh = T' Qp T with T = [I; E]: Qp_WW + E' F + F' E, F = Qp_BW + 1/2 Qp_BB E (lower
  // triangle only).
  Eigen::MatrixXd& F = cost_scratch_.F;
  Eigen::MatrixXd& K = cost_scratch_.K;
  Eigen::MatrixXd& Qp = cost_scratch_.Qp;
  F = Qp.block(w, 0, r, w);
  F.noalias() += 0.5 * Qp.bottomRightCorner(r, r) * s.E;
  // Where rows were eliminated Qh is formed in place of Qp_WW, which nothing else reads afterwards (the solves'
  // copies below are of u_B's rows and columns); otherwise Qh is Qp itself (w = n) or empty (w = 0).
  const bool formed = s.lowerOnlyCols() > 0;  // r > 0 and w > 0; Qp's upper part of these columns was not formed
  const auto Qh = Qp.topLeftCorner(w, w);
  if (formed) {
    Qp.topLeftCorner(w, w).triangularView<Eigen::Lower>() += s.E.transpose() * F;
    Qp.topLeftCorner(w, w).triangularView<Eigen::Lower>() += F.transpose() * s.E;
  }
  // The solves read only the blocks of x and u_N; above the diagonal that block is the mirror of the one below when
  // Qh was formed in its lower triangle.
  s.Qp_zB = Qp.rightCols(r);
  s.Qp_Bz = Qp.bottomRows(r);
  s.Qh_Nx = Qh.bottomLeftCorner(nv, nx);
  if (formed) s.Qh_xN = s.Qh_Nx.transpose();
  else s.Qh_xN = Qh.topRightCorner(nx, nv);
  s.use_eig = false;
  K.resize(nv, nx);
  if (nv > 0) {
    s.llt.compute(Qh.bottomRightCorner(nv, nv));
    if (s.llt.info() == Eigen::Success) {
      inertia_.positive += nv;
      K = s.Qh_Nx;
      solveInPlaceUnlessEmpty(s.llt.matrixL(), K);
    } else {
      if (!opt_.full_inertia) return false;
      s.use_eig = true;
      s.eig.compute(Qh.bottomRightCorner(nv, nv));
      const Eigen::VectorXd& d = s.eig.eigenvalues();
      const double scale = std::max(1.0, d.cwiseAbs().maxCoeff());
      for (int i = 0; i < nv; ++i) {
        if (std::abs(d[i]) <= 1e-14 * scale) ++inertia_.zero;
        else if (d[i] > 0) ++inertia_.positive;
        else ++inertia_.negative;
      }
    }
  }
  // P from Qh's lower triangle, mirrored. Where no rows were eliminated and no controls are left to eliminate, P is
  // Qh's x block as formed: Qp is formed in full there, and P keeps both of its triangles (they may differ in
  // rounding; mirroring would change the factors' bits).
  if ((nv > 0 && nx > 0) || formed) {
    s.P.resize(nx, nx);
    s.P.triangularView<Eigen::Lower>() = Qh.topLeftCorner(nx, nx);
    if (nv > 0 && nx > 0) {
      if (!s.use_eig) {
        s.P.selfadjointView<Eigen::Lower>().rankUpdate(K.transpose(), -1.0);
      } else {
        Eigen::MatrixXd t = s.Qh_Nx;
        s.solveNN(t);
        s.P.triangularView<Eigen::Lower>() -= s.Qh_xN * t;
      }
    }
    s.P.triangularView<Eigen::StrictlyUpper>() = s.P.transpose();
  } else {
    s.P = Qh.topLeftCorner(nx, nx);
  }
  return true;
}

// Row part of stage k: its dimensions, the stacked rows [C; Gamma_{k+1} M] and the sparse dynamics M = [A B]
// (continuity Jacobians are mostly identity and diagonal blocks), then eliminateRows.
void RiccatiSolver::stageRows(const std::vector<StageQp>& qp, int k) {
  const int N = static_cast<int>(qp.size()) - 1;
  Stage& s = st_[k];
  const StageQp& d = qp[k];
  s.nx = d.nx;
  s.nu = d.nu;
  const int n = d.nx + d.nu;
  const Stage* next = k < N ? &st_[k + 1] : nullptr;
  const int npend = next ? static_cast<int>(next->Gamma.rows()) : 0;
  s.m_own = static_cast<int>(d.C.rows());
  s.m = s.m_own + npend;
  s.dyn_pairs = next ? next->nx : 0;
  s.Cs.resize(s.m, n);
  s.Cs.topRows(s.m_own) = d.C;
  if (next) {
    if (d.M.cols == n && d.M.rows == next->nx) {
      s.M = &d.M;
    } else {
      sparseColumns(d.A, d.B, next->nx, s.Msp);
      s.M = &s.Msp;
    }
    if (npend > 0) denseTimesSparse(next->Gamma, *s.M, s.Cs.bottomRows(npend), false);
  }
  eliminateRows(s);
}

// Cost part of stage k (after its row part and the cost part of stage k+1): Qp = H + M' P_{k+1} M in the elimination
// order (H permuted, then M's columns taken in the same order: the same sums as permuting H + M' P M), then
// eliminateCost. The entries of Qp above the diagonal that eliminateCost and the solves never read are skipped.
bool RiccatiSolver::stageCost(const std::vector<StageQp>& qp, int k) {
  const int N = static_cast<int>(qp.size()) - 1;
  Stage& s = st_[k];
  const int n = qp[k].nx + qp[k].nu;
  const int lower = s.lowerOnlyCols();
  Eigen::MatrixXd& Qp = cost_scratch_.Qp;
  permuteSymmetric(qp[k].H, s.perm, s.nx, Qp, lower);
  if (k < N) {
    const Stage& next = st_[k + 1];
    Eigen::MatrixXd &PM = cost_scratch_.PM, &PMt = cost_scratch_.PMt;
    PM.resize(next.nx, n);
    denseTimesSparse(next.P, *s.M, PM, false, &s.perm);
    PMt = PM.transpose();
    denseTimesSparse(PMt, *s.M, Qp, true, &s.perm, lower);
  }
  return eliminateCost(s);
}

void RiccatiSolver::setParallel(bool on) {
  if (on && !par_) par_ = std::make_unique<Parallel>(nullptr);
  if (!on) par_.reset();
}

void RiccatiSolver::setParallel(common::WorkerThread* shared) {
  par_.reset();
  if (shared) par_ = std::make_unique<Parallel>(shared);
}

void RiccatiSolver::runPair(const std::function<void()>& mine, const std::function<void()>& other) const {
  common::runAlongside(par_ ? &par_->worker : nullptr, mine, other);
}

// The second thread runs before_stage and the row parts of stages N..0 ahead of the cost parts, until they stop
// early; after each row part it fills that stage's H unless the calling thread has taken it.
void RiccatiSolver::startRowParts(const std::vector<StageQp>& qp, const std::function<void(int)>& before_stage,
                                  const std::function<void(int, int)>& fill_cost) {
  const int N = static_cast<int>(qp.size()) - 1;
  Parallel& pl = *par_;
  if (fill_cost && pl.stages < N + 1) {
    pl.cost_filled.reset(new std::atomic<int>[N + 1]);
    pl.stages = N + 1;
  }
  if (fill_cost)
    for (int k = 0; k <= N; ++k) pl.cost_filled[k].store(0, std::memory_order_relaxed);
  pl.filled.store(N + 1, std::memory_order_relaxed);
  pl.rows_done.store(N + 1, std::memory_order_relaxed);
  pl.stop.store(false, std::memory_order_relaxed);
  pl.worker.run([this, &qp, &before_stage, &fill_cost, &pl, N] {
    for (int k = N; k >= 0 && !pl.stop.load(std::memory_order_relaxed); --k) {
      if (before_stage) before_stage(k);
      pl.filled.store(k, std::memory_order_release);
      if (!row_part_valid_[k]) stageRows(qp, k);
      row_part_valid_[k] = 1;
      pl.rows_done.store(k, std::memory_order_release);
      if (fill_cost) pl.claimCostFill(fill_cost, k, 1);
    }
  });
}

// The calling thread before stage k's cost part (parallel): it fills H itself when the second thread has filled
// the stage's blocks but not taken H yet (it would wait for the row part otherwise), then waits for both.
void RiccatiSolver::awaitStage(int k, const std::function<void(int, int)>& fill_cost) {
  Parallel& pl = *par_;
  // Yield until `done`; the time it took counts as waiting for the worker (ParallelSection).
  const auto until = [&pl](const auto& done) {
    if (done()) return;
    const auto t0 = std::chrono::steady_clock::now();
    while (!done()) std::this_thread::yield();
    pl.worker.addWaited(std::chrono::steady_clock::now() - t0);
  };
  if (fill_cost) {
    until([&] { return pl.filled.load(std::memory_order_acquire) <= k; });
    pl.claimCostFill(fill_cost, k, 0);
  }
  until([&] { return pl.rows_done.load(std::memory_order_acquire) <= k; });
  if (fill_cost) until([&] { return pl.cost_filled[k].load(std::memory_order_acquire) == 2; });
}

RiccatiSolver::Status RiccatiSolver::factor(const std::vector<StageQp>& qp,
                                            const std::function<void(int)>& before_stage, bool same_rows,
                                            const std::function<void(int, int)>& fill_cost) {
  const int N = static_cast<int>(qp.size()) - 1;
  if (static_cast<int>(st_.size()) != N + 2) same_rows = false;
  st_.resize(N + 2);
  // A row part is kept only if it was computed from the same rows; they are computed from stage N down, so the kept
  // ones are always stages N..j (and the initial state only after all of them).
  if (!same_rows) row_part_valid_.assign(N + 2, 0);
  inertia_ = Inertia{};
  failed_stage_ = -1;
  factored_ = false;
  const bool par = parallel();
  if (par) startRowParts(qp, before_stage, fill_cost);
  bool ok = true;
  for (int k = N; k >= 0 && ok; --k) {
    if (par) {
      awaitStage(k, fill_cost);
    } else {
      if (before_stage) before_stage(k);
      if (!row_part_valid_[k]) stageRows(qp, k);
      row_part_valid_[k] = 1;
      if (fill_cost) fill_cost(k, 0);
    }
    ok = stageCost(qp, k);
    if (!ok) failed_stage_ = k;
  }
  if (par) {
    par_->stop.store(true, std::memory_order_relaxed);
    par_->worker.wait();
  }
  if (!ok) return Status::kWrongInertia;
  // The initial state: a stage without state whose controls are x_0, cost P_0 and rows the pending ones of stage 0.
  Stage& v = st_[N + 1];
  if (!row_part_valid_[N + 1]) {
    v.nx = 0;
    v.nu = st_[0].nx;
    v.m_own = 0;
    v.m = static_cast<int>(st_[0].Gamma.rows());
    v.dyn_pairs = 0;
    v.Cs = st_[0].Gamma;
    eliminateRows(v);
    row_part_valid_[N + 1] = 1;
  }
  permuteSymmetric(st_[0].P, v.perm, 0, cost_scratch_.Qp);
  if (!eliminateCost(v)) {
    failed_stage_ = N + 1;
    return Status::kWrongInertia;
  }
  factored_ = true;
  if (failed_stage_ < 0) {
    for (int k = 0; k <= N + 1; ++k) {
      if (st_[k].use_eig) {
        failed_stage_ = k;
        break;
      }
    }
  }
  if (failed_stage_ >= 0) return Status::kWrongInertia;
  return inertia_.zero > 0 ? Status::kSingular : Status::kOk;
}

// One step of the backward pass over the vectors: stage k (N..0, then N + 1, the initial state).
void RiccatiSolver::backwardStage(const std::vector<StageQp>& qp, const std::vector<StageRhs>& rhs, int k,
                                  RiccatiVectors& ws) const {
  const int N = static_cast<int>(qp.size()) - 1;
  const Stage& s = st_[k];
  RiccatiVectors::Stage& v = ws.st[k];
  const int nx = s.nx, nu = s.nu, n = nx + nu, r = s.rank, nv = s.nv, w = nx + nv;
  if (k == N + 1) {
    v.q = ws.st[0].p;
    v.cs = ws.st[0].gamma;
  } else {
    const StageRhs& dr = rhs[k];
    v.q = dr.h;
    v.cs.resize(s.m);
    v.cs.head(s.m_own) = dr.c;
    if (k < N) {
      const Stage& nx1 = st_[k + 1];
      const RiccatiVectors::Stage& v1 = ws.st[k + 1];
      ws.wv = v1.p;
      ws.wv.noalias() += nx1.P * dr.b;
      sparseColsTransposedTimesAdd(*s.M, 0, nx, ws.wv, v.q.data());  // A' w and B' w, the bits of the dense ones
      sparseColsTransposedTimesAdd(*s.M, nx, nu, ws.wv, v.q.data() + nx);
      v.cs.tail(s.m - s.m_own) = v1.gamma;
      v.cs.tail(s.m - s.m_own).noalias() += nx1.Gamma * dr.b;
    }
  }
  v.cs.array() *= s.row_scale.array();
  ws.ct.resize(s.m);
  for (int i = 0; i < s.m; ++i) ws.ct[i] = v.cs[s.lu.rowPerm()[i]];
  s.lu.applyRowTransform(ws.ct);
  v.gamma.resize(static_cast<int>(s.kept.size()));
  for (std::size_t j = 0; j < s.kept.size(); ++j) v.gamma[static_cast<int>(j)] = ws.ct[r + s.kept[j]];
  v.e = -ws.ct.head(r);
  solveInPlaceUnlessEmpty(s.lu.packed().topLeftCorner(r, r).triangularView<Eigen::Upper>(), v.e);
  v.qp.resize(n);
  for (int i = 0; i < n; ++i) v.qp[i] = v.q[s.perm[i]];
  v.g = v.qp;
  v.g.noalias() += s.Qp_zB * v.e;
  v.qh = v.g.head(w);
  v.qh.noalias() += s.E.transpose() * v.g.tail(r);
  v.kff = -v.qh.tail(nv);
  s.solveNN(v.kff);
  v.p = v.qh.head(nx);
  v.p.noalias() += s.Qh_xN * v.kff;
}

// One stage of the forward pass: from the state ws.x and the multipliers of the rows this stage passed to the
// previous one (ws.eta_pending), the stage's z (ws.z) and the multipliers of its stacked rows (ws.eta_stacked).
void RiccatiSolver::stageForward(const Stage& s, RiccatiVectors::Stage& v, RiccatiVectors& ws) const {
  const int nx = s.nx, nu = s.nu, n = nx + nu, r = s.rank, nv = s.nv, w = nx + nv;
  v.zp.resize(n);
  v.zp.head(nx) = ws.x;
  ws.t = v.qh.tail(nv);
  ws.t.noalias() += s.Qh_Nx * ws.x;
  s.solveNN(ws.t);
  v.zp.segment(nx, nv) = -ws.t;
  v.zp.tail(r) = v.e;
  v.zp.tail(r).noalias() += s.E * v.zp.head(w);
  ws.z.resize(n);
  for (int i = 0; i < n; ++i) ws.z[s.perm[i]] = v.zp[i];
  // Multipliers of the stacked rows: the fixed control directions give the independent ones, the pending
  // rows' multipliers come from the previous stage; then back to the original rows.
  ws.gb = v.qp.tail(r);  // the gradient's u_B part: only it carries the multipliers
  ws.gb.noalias() += s.Qp_Bz * v.zp;
  v.eta_t.setZero(s.m);
  v.eta_t.head(r) = -ws.gb;
  solveInPlaceUnlessEmpty(s.lu.packed().topLeftCorner(r, r).triangularView<Eigen::Upper>().transpose(),
                          v.eta_t.head(r));
  for (std::size_t j = 0; j < s.kept.size(); ++j) v.eta_t[r + s.kept[j]] = ws.eta_pending[static_cast<int>(j)];
  s.lu.applyRowTransformTransposed(v.eta_t);
  ws.eta_stacked.resize(s.m);
  for (int i = 0; i < s.m; ++i) ws.eta_stacked[s.lu.rowPerm()[i]] = v.eta_t[i];
  ws.eta_stacked.array() *= s.row_scale.array();
}

// One step of the forward pass: the initial state (k = N + 1) first, then stages 0..N.
void RiccatiSolver::forwardStage(const std::vector<StageQp>& qp, const std::vector<StageRhs>& rhs, int k,
                                 std::vector<StageSolution>& sol, RiccatiVectors& ws) const {
  const int N = static_cast<int>(qp.size()) - 1;
  if (k == N + 1) {
    ws.x.resize(0);
    ws.eta_pending.resize(0);
    stageForward(st_[N + 1], ws.st[N + 1], ws);
    ws.x = ws.z;
    ws.eta_pending = ws.eta_stacked;
    return;
  }
  const Stage& s = st_[k];
  stageForward(s, ws.st[k], ws);
  StageSolution& o = sol[k];
  o.x = ws.z.head(s.nx);
  o.u = ws.z.tail(s.nu);
  o.eta = ws.eta_stacked.head(s.m_own);
  if (k == N) {
    o.lambda.resize(0);
    return;
  }
  const Stage& nx1 = st_[k + 1];
  ws.eta_pending = ws.eta_stacked.tail(s.m - s.m_own);
  ws.x = rhs[k].b;
  sparseColsTimesAdd(*s.M, 0, o.x, ws.dyn, ws.x.data());  // A x, then B u: the bits of the dense products
  sparseColsTimesAdd(*s.M, s.nx, o.u, ws.dyn, ws.x.data());
  o.lambda = ws.st[k + 1].p;
  o.lambda.noalias() += nx1.P * ws.x;
  o.lambda.noalias() += nx1.Gamma.transpose() * ws.eta_pending;
}

void RiccatiSolver::solve(const std::vector<StageQp>& qp, std::vector<StageSolution>& sol) {
  rhs_.resize(qp.size());
  for (std::size_t k = 0; k < qp.size(); ++k) {
    rhs_[k].h = qp[k].h;
    rhs_[k].b = qp[k].b;
    rhs_[k].c = qp[k].c;
  }
  solve(qp, rhs_, sol, ws_);
}

void RiccatiSolver::solve(const std::vector<StageQp>& qp, const std::vector<StageRhs>& rhs,
                          std::vector<StageSolution>& sol, RiccatiVectors& ws) const {
  const int N = static_cast<int>(qp.size()) - 1;
  ws.st.resize(N + 2);
  sol.resize(N + 1);
  for (int k = N; k >= 0; --k) backwardStage(qp, rhs, k, ws);
  backwardStage(qp, rhs, N + 1, ws);
  forwardStage(qp, rhs, N + 1, sol, ws);
  for (int k = 0; k <= N; ++k) forwardStage(qp, rhs, k, sol, ws);
}

void RiccatiSolver::solveTwo(const std::vector<StageQp>& qp, const Rhs& a, const Rhs& b) const {
  const int N = static_cast<int>(qp.size()) - 1;
  for (const Rhs* r : {&a, &b}) {
    r->ws.st.resize(N + 2);
    r->sol.resize(N + 1);
  }
  for (int k = N; k >= 0; --k) {
    backwardStage(qp, a.rhs, k, a.ws);
    backwardStage(qp, b.rhs, k, b.ws);
  }
  backwardStage(qp, a.rhs, N + 1, a.ws);
  backwardStage(qp, b.rhs, N + 1, b.ws);
  forwardStage(qp, a.rhs, N + 1, a.sol, a.ws);
  forwardStage(qp, b.rhs, N + 1, b.sol, b.ws);
  for (int k = 0; k <= N; ++k) {
    forwardStage(qp, a.rhs, k, a.sol, a.ws);
    forwardStage(qp, b.rhs, k, b.sol, b.ws);
  }
}

}  // namespace centaur::ocp_solver
