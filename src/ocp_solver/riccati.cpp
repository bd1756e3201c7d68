#include "ocp_solver/riccati.hpp"

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
  s.lu.compute(s.Cs.rightCols(nu), opt_.rank_tol);
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
  Eigen::MatrixXd& X = s.X;
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

// The cost part of one stage, after its row part and given Qp: the reduced Hessian on the free directions, its
// factor, the cost-to-go P. Adds the stage's inertia (rows and dynamics first). False on an indefinite reduced
// Hessian (unless full_inertia).
bool RiccatiSolver::eliminateCost(Stage& s) {
  const int nx = s.nx, r = s.rank, nv = s.nv, w = nx + nv;
  inertia_.positive += s.dyn_pairs + r;
  inertia_.negative += s.dyn_pairs + r;
  inertia_.zero += s.dependent;

  // Reduced Hessian Qh = T' Qp T with T = [I; E]: Qp_WW + E' F + F' E, F = Qp_BW + 1/2 Qp_BB E (lower
  // triangle only, then mirrored).
  s.F = s.Qp.block(w, 0, r, w);
  s.F.noalias() += 0.5 * s.Qp.bottomRightCorner(r, r) * s.E;
  s.Qh = s.Qp.topLeftCorner(w, w);
  if (r > 0 && w > 0) {
    s.Qh.triangularView<Eigen::Lower>() += s.E.transpose() * s.F;
    s.Qh.triangularView<Eigen::Lower>() += s.F.transpose() * s.E;
    s.Qh.triangularView<Eigen::StrictlyUpper>() = s.Qh.transpose();
  }
  s.use_eig = false;
  s.K.resize(nv, nx);
  if (nv > 0) {
    s.llt.compute(s.Qh.bottomRightCorner(nv, nv));
    if (s.llt.info() == Eigen::Success) {
      inertia_.positive += nv;
      s.K = s.Qh.bottomLeftCorner(nv, nx);
      solveInPlaceUnlessEmpty(s.llt.matrixL(), s.K);
    } else {
      if (!opt_.full_inertia) return false;
      s.use_eig = true;
      s.eig.compute(s.Qh.bottomRightCorner(nv, nv));
      const Eigen::VectorXd& d = s.eig.eigenvalues();
      const double scale = std::max(1.0, d.cwiseAbs().maxCoeff());
      for (int i = 0; i < nv; ++i) {
        if (std::abs(d[i]) <= 1e-14 * scale) ++inertia_.zero;
        else if (d[i] > 0) ++inertia_.positive;
        else ++inertia_.negative;
      }
    }
  }
  s.P = s.Qh.topLeftCorner(nx, nx);
  if (nv > 0 && nx > 0) {
    if (!s.use_eig) {
      s.P.selfadjointView<Eigen::Lower>().rankUpdate(s.K.transpose(), -1.0);
    } else {
      Eigen::MatrixXd t = s.Qh.bottomLeftCorner(nv, nx);
      s.solveNN(t);
      s.P.triangularView<Eigen::Lower>() -= s.Qh.topRightCorner(nx, nv) * t;
    }
    s.P.triangularView<Eigen::StrictlyUpper>() = s.P.transpose();
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
    sparseColumns(d.A, d.B, next->nx, s.Msp);
    if (npend > 0) denseTimesSparse(next->Gamma, s.Msp, s.Cs.bottomRows(npend), false);
  }
  eliminateRows(s);
}

// Cost part of stage k (after its row part and the cost part of stage k+1): Qp = H + M' P_{k+1} M in the elimination
// order (H permuted, then M's columns taken in the same order: the same sums as permuting H + M' P M), then
// eliminateCost.
bool RiccatiSolver::stageCost(const std::vector<StageQp>& qp, int k) {
  const int N = static_cast<int>(qp.size()) - 1;
  Stage& s = st_[k];
  const int n = qp[k].nx + qp[k].nu;
  permuteSymmetric(qp[k].H, s.perm, s.nx, s.Qp);
  if (k < N) {
    const Stage& next = st_[k + 1];
    s.PM.resize(next.nx, n);
    denseTimesSparse(next.P, s.Msp, s.PM, false, &s.perm);
    s.PMt = s.PM.transpose();
    denseTimesSparse(s.PMt, s.Msp, s.Qp, true, &s.perm);
  }
  return eliminateCost(s);
}

void RiccatiSolver::setParallel(bool on) {
  if (on && !par_) par_ = std::make_unique<Parallel>();
  if (!on) par_.reset();
}

RiccatiSolver::Status RiccatiSolver::factor(const std::vector<StageQp>& qp,
                                            const std::function<void(int)>& before_stage) {
  const int N = static_cast<int>(qp.size()) - 1;
  st_.resize(N + 2);
  inertia_ = Inertia{};
  failed_stage_ = -1;
  factored_ = false;
  if (par_) {
    // The worker runs the row parts (and before_stage) of stages N..0 ahead of the cost parts. After an early stop
    // it still calls before_stage for every stage, as the sequential order would not (callers may rely on it).
    Parallel& pl = *par_;
    pl.rows_done.store(N + 1, std::memory_order_relaxed);
    pl.stop.store(false, std::memory_order_relaxed);
    pl.worker.run([this, &qp, &before_stage, &pl, N] {
      for (int k = N; k >= 0; --k) {
        if (before_stage) before_stage(k);
        if (!pl.stop.load(std::memory_order_relaxed)) stageRows(qp, k);
        pl.rows_done.store(k, std::memory_order_release);
      }
    });
  }
  bool ok = true;
  for (int k = N; k >= 0 && ok; --k) {
    if (par_) {
      while (par_->rows_done.load(std::memory_order_acquire) > k) std::this_thread::yield();
    } else {
      if (before_stage) before_stage(k);
      stageRows(qp, k);
    }
    ok = stageCost(qp, k);
    if (!ok) failed_stage_ = k;
  }
  if (par_) {
    par_->stop.store(true, std::memory_order_relaxed);
    par_->worker.wait();
  }
  if (!ok) return Status::kWrongInertia;
  // The initial state: a stage without state whose controls are x_0, cost P_0 and rows the pending ones of stage 0.
  Stage& v = st_[N + 1];
  v.nx = 0;
  v.nu = st_[0].nx;
  v.m_own = 0;
  v.m = static_cast<int>(st_[0].Gamma.rows());
  v.dyn_pairs = 0;
  v.Cs = st_[0].Gamma;
  eliminateRows(v);
  permuteSymmetric(st_[0].P, v.perm, 0, v.Qp);
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

void RiccatiSolver::backwardVectors(const std::vector<StageQp>& qp) {
  const int N = static_cast<int>(qp.size()) - 1;
  for (int step = 0; step <= N + 1; ++step) {
    const int k = step <= N ? N - step : N + 1;  // stages N..0, then the initial state
    Stage& s = st_[k];
    const int nx = s.nx, nu = s.nu, n = nx + nu, r = s.rank, nv = s.nv, w = nx + nv;
    if (k == N + 1) {
      s.q = st_[0].p;
      s.cs = st_[0].gamma;
    } else {
      const StageQp& d = qp[k];
      s.q = d.h;
      s.cs.resize(s.m);
      s.cs.head(s.m_own) = d.c;
      if (k < N) {
        const Stage& nx1 = st_[k + 1];
        Eigen::VectorXd wv = nx1.p;
        wv.noalias() += nx1.P * d.b;
        s.q.head(nx).noalias() += d.A.transpose() * wv;
        s.q.tail(nu).noalias() += d.B.transpose() * wv;
        s.cs.tail(s.m - s.m_own) = nx1.gamma;
        s.cs.tail(s.m - s.m_own).noalias() += nx1.Gamma * d.b;
      }
    }
    s.cs.array() *= s.row_scale.array();
    Eigen::VectorXd ct(s.m);
    for (int i = 0; i < s.m; ++i) ct[i] = s.cs[s.lu.rowPerm()[i]];
    s.lu.applyRowTransform(ct);
    s.gamma.resize(static_cast<int>(s.kept.size()));
    for (std::size_t j = 0; j < s.kept.size(); ++j) s.gamma[static_cast<int>(j)] = ct[r + s.kept[j]];
    s.e = -ct.head(r);
    solveInPlaceUnlessEmpty(s.lu.packed().topLeftCorner(r, r).triangularView<Eigen::Upper>(), s.e);
    s.qp.resize(n);
    for (int i = 0; i < n; ++i) s.qp[i] = s.q[s.perm[i]];
    s.g = s.qp;
    s.g.noalias() += s.Qp.rightCols(r) * s.e;
    s.qh = s.g.head(w);
    s.qh.noalias() += s.E.transpose() * s.g.tail(r);
    s.kff = -s.qh.tail(nv);
    s.solveNN(s.kff);
    s.p = s.qh.head(nx);
    s.p.noalias() += s.Qh.topRightCorner(nx, nv) * s.kff;
  }
}

void RiccatiSolver::stageForward(Stage& s, const Eigen::VectorXd& x, const Eigen::VectorXd& eta_pending,
                                 Eigen::VectorXd& z, Eigen::VectorXd& eta_stacked) {
  const int nx = s.nx, nu = s.nu, n = nx + nu, r = s.rank, nv = s.nv, w = nx + nv;
  s.zp.resize(n);
  s.zp.head(nx) = x;
  Eigen::VectorXd t = s.qh.tail(nv);
  t.noalias() += s.Qh.bottomLeftCorner(nv, nx) * x;
  s.solveNN(t);
  s.zp.segment(nx, nv) = -t;
  s.zp.tail(r) = s.e;
  s.zp.tail(r).noalias() += s.E * s.zp.head(w);
  z.resize(n);
  for (int i = 0; i < n; ++i) z[s.perm[i]] = s.zp[i];
  // Multipliers of the stacked rows: the fixed control directions give the independent ones, the pending
  // rows' multipliers come from the previous stage; then back to the original rows.
  Eigen::VectorXd gb = s.qp.tail(r);  // the gradient's u_B part: only it carries the multipliers
  gb.noalias() += s.Qp.bottomRows(r) * s.zp;
  s.eta_t.setZero(s.m);
  s.eta_t.head(r) = -gb;
  solveInPlaceUnlessEmpty(s.lu.packed().topLeftCorner(r, r).triangularView<Eigen::Upper>().transpose(),
                          s.eta_t.head(r));
  for (std::size_t j = 0; j < s.kept.size(); ++j) s.eta_t[r + s.kept[j]] = eta_pending[static_cast<int>(j)];
  s.lu.applyRowTransformTransposed(s.eta_t);
  eta_stacked.resize(s.m);
  for (int i = 0; i < s.m; ++i) eta_stacked[s.lu.rowPerm()[i]] = s.eta_t[i];
  eta_stacked.array() *= s.row_scale.array();
}

void RiccatiSolver::forward(const std::vector<StageQp>& qp, std::vector<StageSolution>& sol) {
  const int N = static_cast<int>(qp.size()) - 1;
  sol.resize(N + 1);
  Eigen::VectorXd x(0), z, eta_stacked, eta_pending(0);
  stageForward(st_[N + 1], x, eta_pending, z, eta_stacked);
  x = z;
  eta_pending = eta_stacked;
  for (int k = 0; k <= N; ++k) {
    Stage& s = st_[k];
    stageForward(s, x, eta_pending, z, eta_stacked);
    StageSolution& o = sol[k];
    o.x = z.head(s.nx);
    o.u = z.tail(s.nu);
    o.eta = eta_stacked.head(s.m_own);
    if (k == N) {
      o.lambda.resize(0);
      break;
    }
    const Stage& nx1 = st_[k + 1];
    eta_pending = eta_stacked.tail(s.m - s.m_own);
    x = qp[k].b;
    x.noalias() += qp[k].A * o.x;
    x.noalias() += qp[k].B * o.u;
    o.lambda = nx1.p;
    o.lambda.noalias() += nx1.P * x;
    o.lambda.noalias() += nx1.Gamma.transpose() * eta_pending;
  }
}

void RiccatiSolver::solve(const std::vector<StageQp>& qp, std::vector<StageSolution>& sol) {
  backwardVectors(qp);
  forward(qp, sol);
}

}  // namespace centaur::ocp_solver
