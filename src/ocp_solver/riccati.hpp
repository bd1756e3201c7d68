#pragma once
// Structured factorization of the stage-wise KKT system of a StageQp (stage_qp.hpp): a generalized Riccati
// recursion for stage-wise equality constraints.
//
// Backward, stage by stage: the cost-to-go of stage k+1 (a quadratic in x_{k+1}, P_{k+1}) is pulled back through
// the dynamics; the stage rows plus the rows stage k+1 could not satisfy itself ("pending" rows on x_{k+1}) are
// stacked and factored with complete pivoting in the controls u_k: the independent ones fix as many control
// directions, the dependent ones become pending rows on x_k for stage k-1; the cost on the remaining control
// directions (the reduced Hessian) is factored by Cholesky and eliminated, which gives P_k. After stage 0 the
// initial state x_0 is eliminated the same way (it is a decision variable). Forward, the states, controls and
// every multiplier are recovered.
//
// Each stage has a row part (stacking, equilibrating and rank-splitting the rows, the pending rows for stage k-1)
// and a cost part (the pull-back, the reduced Hessian, P_k). The row parts read no cost, only the pending rows of
// the next stage, so they form a chain of their own, which setParallel runs on a second thread ahead of the cost
// parts.
//
// Inertia (Sylvester's law on the block elimination): every eliminated row pairs with one control direction
// (+1, -1), every dynamics row with one state (+1, -1), and the reduced Hessians add their own inertia. The KKT
// matrix has the inertia an interior-point method needs, (n, m, 0), exactly when every reduced Hessian is
// positive definite and no row was found dependent; rows that are combinations of others (a rank-deficient
// constraint Jacobian) are counted as zero eigenvalues and make the status kSingular.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <atomic>
#include <functional>
#include <memory>
#include <vector>

#include "common/worker_thread.hpp"

#include "ocp_solver/block_ops.hpp"
#include "ocp_solver/pivoted_lu.hpp"
#include "ocp_solver/stage_qp.hpp"

namespace centaur::ocp_solver {

/// The vectors of one solve with a RiccatiSolver's factors: per stage the pulled-back gradient and the stage's
/// feed-forward terms, and the forward pass's scratch. Kept between solves so that they do not allocate; solves
/// that run concurrently on the same factors need one each.
struct RiccatiVectors {
  struct Stage {
    Eigen::VectorXd q, qp, cs, e, qh, kff, p, gamma;
    Eigen::VectorXd zp, g, eta_t;
  };
  std::vector<Stage> st;  // stages 0..N, then the initial state
  Eigen::VectorXd wv, ct, t, gb, x, z, eta_stacked, eta_pending, dyn;
};

class RiccatiSolver {
 public:
  struct Options {
    double rank_tol = 1e-10;    ///< a row passed back whose state part is at most this is dependent (zero eigenvalue)
    bool full_inertia = false;  ///< keep going past an indefinite reduced Hessian to count the whole inertia
    /// Pivot threshold of the rank split by the controls, on the equilibrated rows (each row scaled to max |entry|
    /// 1): a row whose control part, after the elimination of the rows before it, is at most this is passed back
    /// to the previous stage as a row on the state, without that remainder. It bounds the growth of the
    /// elimination (|E| <~ 1 / pivot_tol) at the price of a solve error of the order of pivot_tol, which
    /// iterative refinement removes (StageKktSolver); with 1e-10 only rounding-level remainders are dropped.
    /// docs/planner.md, "The pivot threshold of the stage rows".
    double pivot_tol = 3e-4;
  };
  enum class Status { kOk, kWrongInertia, kSingular };

  RiccatiSolver() = default;
  explicit RiccatiSolver(const Options& o) : opt_(o) {}

  /// Factor the matrix part (H, A, B, C) of `qp`. kWrongInertia as soon as a reduced Hessian is not positive
  /// definite (unless full_inertia); kSingular if rows are dependent (the counts are still computed).
  /// before_stage(k), if given, is called before stage k's blocks are first read (stages N..0, in this order; on
  /// the second thread when parallel). After an early kWrongInertia the stages not reached yet may be skipped.
  /// same_rows: C, A and B (and the stage sizes) are those of the previous factor(), only H changed (a retry of an
  /// inertia correction): the row parts already computed are kept, which gives the bits of a full factorization.
  /// fill_cost(k, thread), if given, is called once for each stage whose cost part runs, after before_stage(k) and
  /// before the cost part reads H; it must write nothing but stage k's H, which no row part reads. When parallel it
  /// runs on whichever thread gets to it first (thread 0: the calling one, 1: the second), possibly while the other
  /// runs stage k's row part and later stages' before_stage: the one that would otherwise wait does it.
  Status factor(const std::vector<StageQp>& qp, const std::function<void(int)>& before_stage = {},
                bool same_rows = false, const std::function<void(int, int)>& fill_cost = {});
  /// Run each stage's row part (the rank split of its rows, which needs no cost) on a second thread, ahead of the
  /// cost parts (the reduced Hessians and the cost-to-go) on the calling one. The factors are bit-identical.
  void setParallel(bool on);
  /// The same on a worker thread shared with other work of the caller (which must not use it while this solver
  /// does; it must outlive the solver or a later setParallel).
  void setParallel(common::WorkerThread* shared);
  /// Whether the next factor() and runPair() use the second thread: set, and the worker not inline.
  bool parallel() const { return par_ != nullptr && !par_->worker.isInline(); }
  /// The second thread (null unless setParallel), e.g. for a ParallelSection around factor() or runPair().
  common::WorkerThread* worker() const { return par_ ? &par_->worker : nullptr; }
  /// Run `mine` on the calling thread and `other` on the second one (when parallel; otherwise one after the
  /// other), and return when both have finished. For work between factorizations, e.g. two solves.
  void runPair(const std::function<void()>& mine, const std::function<void()>& other) const;
  /// Solve with the right-hand sides (h, b, c) of `qp` (same matrices as the last factor()). Allowed after
  /// kOk or kSingular (dependent rows get zero multipliers) and after kWrongInertia with full_inertia.
  void solve(const std::vector<StageQp>& qp, std::vector<StageSolution>& sol);
  /// The same with the right-hand sides `rhs` (the vectors of `qp` are not read) and the caller's vectors. It
  /// reads the factors only, so solves with different `ws` may run concurrently.
  void solve(const std::vector<StageQp>& qp, const std::vector<StageRhs>& rhs, std::vector<StageSolution>& sol,
             RiccatiVectors& ws) const;
  /// One solve's right-hand sides, solution and vectors.
  struct Rhs {
    const std::vector<StageRhs>& rhs;
    std::vector<StageSolution>& sol;
    RiccatiVectors& ws;
  };
  /// Two solves in one pass over the factors, stage by stage one after the other, so that each stage's factors are
  /// still in cache for the second. The results are those of solve(), bit for bit.
  void solveTwo(const std::vector<StageQp>& qp, const Rhs& a, const Rhs& b) const;

  const Inertia& inertia() const { return inertia_; }
  /// The stage whose reduced Hessian was found indefinite first (-1: none; N + 1: the initial state).
  int failedStage() const { return failed_stage_; }
  const Options& options() const { return opt_; }

 private:
  struct Stage;
  struct Parallel {
    explicit Parallel(common::WorkerThread* shared)
        : own(shared ? nullptr : std::make_unique<common::WorkerThread>()), worker(shared ? *shared : *own) {}
    std::unique_ptr<common::WorkerThread> own;  // unless the thread is shared
    common::WorkerThread& worker;
    std::atomic<int> filled{0};     // before_stage has run for stages filled..N
    std::atomic<int> rows_done{0};  // the row parts of stages rows_done..N are done
    std::atomic<bool> stop{false};  // the cost parts stopped early: skip the remaining row parts
    std::unique_ptr<std::atomic<int>[]> cost_filled;  // per stage: 0 free, 1 being filled, 2 filled (fill_cost)
    int stages = 0;                                    // the size of cost_filled
    /// fill_cost(k, thread) unless the other thread has taken stage k.
    void claimCostFill(const std::function<void(int, int)>& fill_cost, int k, int thread) {
      int expected = 0;
      if (!cost_filled[k].compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) return;
      fill_cost(k, thread);
      cost_filled[k].store(2, std::memory_order_release);
    }
  };
  void startRowParts(const std::vector<StageQp>& qp, const std::function<void(int)>& before_stage,
                     const std::function<void(int, int)>& fill_cost);
  void awaitStage(int k, const std::function<void(int, int)>& fill_cost);
  void stageRows(const std::vector<StageQp>& qp, int k);
  bool stageCost(const std::vector<StageQp>& qp, int k);
  void eliminateRows(Stage& s);
  bool eliminateCost(Stage& s);
  void backwardStage(const std::vector<StageQp>& qp, const std::vector<StageRhs>& rhs, int k,
                     RiccatiVectors& ws) const;
  void forwardStage(const std::vector<StageQp>& qp, const std::vector<StageRhs>& rhs, int k,
                    std::vector<StageSolution>& sol, RiccatiVectors& ws) const;
  void stageForward(const Stage& s, RiccatiVectors::Stage& v, RiccatiVectors& ws) const;

  Options opt_;
  std::vector<Stage> st_;  // stages 0..N, then the initial-state elimination at index N + 1
  std::vector<char> row_part_valid_;  // per entry of st_: its row part is that of the rows of the last factor()
  Inertia inertia_;
  int failed_stage_ = -1;
  bool factored_ = false;
  std::unique_ptr<Parallel> par_;
  std::vector<StageRhs> rhs_;  // solve(qp, sol): the right-hand sides copied from qp
  RiccatiVectors ws_;          // and its vectors
  // Scratch of the factorization that no later step reads, one set for all stages (the per-stage factors above are
  // what the solves need). The row parts run on one thread at a time and the cost parts on one thread at a time,
  // possibly a different one, so each part has its own.
  struct RowScratch {
    Eigen::MatrixXd X;  // the state part of the stacked rows in pivot order, row-transformed
  };
  struct CostScratch {
    Eigen::MatrixXd PM, PMt;  // P_{k+1} M and its transpose
    Eigen::MatrixXd F;        // Qp_BW + 1/2 Qp_BB E
    Eigen::MatrixXd Qp;  // the stage cost plus the pulled-back cost-to-go (H + M' P M), in elimination order; where
                         // rows were eliminated, its [x; u_N] block then becomes the reduced Hessian (lower triangle)
    Eigen::MatrixXd K;   // L^{-1} Qh_{N x}
  };
  RowScratch row_scratch_;
  CostScratch cost_scratch_;
};

/// The per-stage factors (public only so that the implementation file can define it).
struct RiccatiSolver::Stage {
  int nx = 0, nu = 0, m = 0, m_own = 0, rank = 0, nv = 0;
  int dependent = 0;          // rows dependent on the others (zero eigenvalues of the KKT matrix)
  int dyn_pairs = 0;          // dynamics rows into the next stage (one +1 and one -1 eigenvalue each)
  Eigen::MatrixXd Cs;         // stacked rows (own, then pending of the next stage), equilibrated
  Eigen::VectorXd row_scale;  // Cs = diag(row_scale) * [C; Gamma_next M]
  PivotedLu lu;               // of the control columns of Cs
  std::vector<int> perm;      // z order used below: [x, u_N (free directions), u_B (fixed by the rows)]
  Eigen::MatrixXd Qp_zB, Qp_Bz;  // the columns and the rows of u_B of Qp (CostScratch), which the solves read
  Eigen::MatrixXd E;          // u_B = E [x; u_N] + e
  Eigen::MatrixXd Qh_Nx, Qh_xN;  // the u_N-x and x-u_N blocks of the reduced Hessian Qh on [x; u_N]
  Eigen::LLT<Eigen::MatrixXd> llt;                          // of its u_N block
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig;       // fallback (full_inertia only)
  bool use_eig = false;
  Eigen::MatrixXd P;          // cost-to-go Hessian in x
  Eigen::MatrixXd Gamma;      // pending rows on x passed to the previous stage (kept ones)
  std::vector<int> kept;      // their positions among the dependent rows
  SparseColumns Msp;          // the dynamics M = [A B] (exact zeros dropped), unless the StageQp gives it
  const SparseColumns* M = nullptr;  // Msp or the StageQp's
  // helpers
  void solveNN(Eigen::Ref<Eigen::MatrixXd> rhs) const;  // Qh_NN^{-1} rhs
  /// The columns of Qp whose entries above the diagonal are never read: those of [x; u_N] when rows were
  /// eliminated, because Qh is then formed in its lower triangle (and its x-u_N block mirrored). 0 otherwise.
  int lowerOnlyCols() const { return rank > 0 && nx + nv > 0 ? nx + nv : 0; }
};

}  // namespace centaur::ocp_solver
