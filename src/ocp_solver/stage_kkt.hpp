#pragma once
// The KKT system of an OCP transcribed by direct multiple shooting, solved stage-wise (riccati.hpp).
//
// From the sparsity alone it finds, for every stage k, the dynamics rows (one per component of x_{k+1}: a row
// with a single entry on x_{k+1}, the rest on stage k) and classifies the other rows and Hessian entries:
//   - local: everything on stage k (state or control) -> a stage row / a block of H_k;
//   - coupled to the next state (e.g. "the foot did not move since the last node": x_k and x_{k+1}): the
//     linearized dynamics are substituted for x_{k+1}, which makes it a row of stage k (a row operation on the
//     KKT system; multipliers are transformed back);
//   - anything else reaching back (a rate cost between u_k and u_{k+1}, a periodicity row between x_0 and x_N):
//     the earlier variables are carried forward as extra states (w_{k+1} = copy), so that the term becomes local
//     to the later stage.
// Fixed variables become unit rows. Inequality rows (d_c > 0) are penalties added to the stage Hessians; equality
// rows are exact, or penalties under a dual regularization (d_c > 0), except the dynamics, which stay exact.
// The structure is analysed once; factor() scatters the values into preallocated stage blocks.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "ocp_solver/kkt_system.hpp"
#include "ocp_solver/riccati.hpp"

namespace centaur::ocp_solver {

/// Which stage each variable belongs to (from the OCP's layout).
struct StageLayout {
  int num_stages = 0;           ///< N + 1 (stages 0..N)
  std::vector<int> stage;       ///< per variable
  std::vector<char> is_state;   ///< per variable: state of its stage (else a control)
};

/// The structure does not fit the stage-wise solver (e.g. a state without a dynamics row).
class StructureError : public std::runtime_error {
 public:
  explicit StructureError(const std::string& what) : std::runtime_error(what) {}
};

class StageKktSolver final : public KktSolver {
 public:
  /// fixed: per variable; equality: per row (lower bound == upper bound). Throws StructureError.
  StageKktSolver(const SparsePattern& pattern, const StageLayout& layout, const std::vector<char>& fixed,
                 const std::vector<char>& equality, RiccatiSolver::Options options = {});

  KktStatus factor(const double* hess, const double* jac, const Eigen::VectorXd& dx,
                   const Eigen::VectorXd& dc) override;
  /// Keeps the stage rows (C, the dynamics) and the recursion's row parts of the last factorization when the exact
  /// rows are the same (d_c == 0 on the same rows); the bits of factor().
  KktStatus refactor(const double* hess, const double* jac, const Eigen::VectorXd& dx,
                     const Eigen::VectorXd& dc) override;
  /// Solves, then refines on the residual of the whole system (at most `max_refinement` extra solves) until the
  /// relative residual is below 1e-12: rows whose controls were nearly dependent are passed to the previous
  /// stage by the recursion, which leaves an error of the size of the pivot threshold.
  void solve(const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, Eigen::VectorXd& dx, Eigen::VectorXd& dy) override;
  /// Pipelined (setPipelined): each solve with its refinement on its own thread. Otherwise the two recursions run
  /// in one pass over the factors (RiccatiSolver::solveTwo) and are refined one after the other. Either way the
  /// results are those of solve(a) and solve(b), bit for bit.
  void solveTwo(const KktSolve& a, const KktSolve& b) override;
  /// Fill the stage blocks and run the row part of each stage of the recursion on a second thread, ahead of the
  /// cost parts (RiccatiSolver::setParallel): the scattering of the sparse values and the rank splits of the rows
  /// then overlap the reduced Hessians. The results are bit-identical to the sequential ones.
  void setPipelined(bool on);
  /// Pipelined on a worker thread shared with the caller's other work (null: not pipelined). Each factorization and
  /// each pair of solves runs on it or on the calling thread alone as the worker's chooser decides
  /// (common::ParallelSection; the results are the same bits either way).
  void setPipelined(common::WorkerThread* shared);
  /// Relative residual of the last solve (after refinement; of b after solveTwo).
  double lastResidual() const { return last_residual_; }
  int max_refinement = 3;
  const std::vector<char>& alwaysExactRows() const override { return dynamics_row_; }
  Inertia inertia() const override { return riccati_.inertia(); }

  /// Sizes of the stage QP (augmented states) for reports: states, carried copies, controls of stage k.
  int stateSize(int k) const { return nx_[k]; }
  int carriedSize(int k) const { return static_cast<int>(carried_[k].size()); }
  int controlSize(int k) const { return nu_[k]; }

 private:
  enum class RowKind { kDynamics, kLocal, kCoupled };
  struct Entry {        // one Jacobian nonzero's destination
    int slot;           // index into the Jacobian values
    int col;            // column in the owner stage's z (augmented), or in x_{k+1} for `next`
    bool next;          // on x_{k+1} (coupled rows and the dynamics' diagonal)
  };
  struct Row {
    RowKind kind = RowKind::kLocal;
    int stage = 0;      // owner stage
    int comp = -1;      // dynamics: component of x_{k+1}
    std::vector<Entry> entries;
  };
  struct HessEntry {  // one Hessian nonzero's destination in its stage's H
    int slot, r, c;
  };

  int colOf(int stage, int var) const;  // column of a variable in a stage's augmented z (-1 if absent)
  void analyzeRows(const SparsePattern& p, const std::vector<char>& equality);
  void analyzeCarried(const SparsePattern& p);
  void analyzeDynamics();
  void resetRows(int k, int nxa, int m, int nxn);
  void sparseDynamics(int k);
  /// The vectors of one solve (right-hand sides, solution, refinement): one for each solve of solveTwo().
  struct SolveWork {
    std::vector<StageRhs> rhs;
    std::vector<StageSolution> sol;
    RiccatiVectors vec;
    Eigen::VectorXd res_x, res_c, ddx, ddy, a, z;
    double residual = 0.0;
  };
  /// b: the right-hand sides of the dynamics of the row's stage, for rhs_shift (nullptr: not needed).
  void rowVector(const Row& row, const double* jac, const Eigen::VectorXd* b, Eigen::VectorXd& a,
                 double& rhs_shift) const;
  /// Scatter the values of stage k into qp_[k] (and the dynamics scales of its rows); touches no other stage.
  /// fillRows: what depends on the Jacobian and the set of exact rows only; fillCost: H (after fillRows(k), with
  /// the scratch of `thread`, 0 or 1: the two threads of a pipelined factorization fill different stages at once).
  void fillRows(int k);
  void fillCost(int k, int thread);
  KktStatus run(bool same_rows);
  /// Solve and refine (reads the factorization, writes w and the step only).
  void solveWith(SolveWork& w, const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, Eigen::VectorXd& dx,
                 Eigen::VectorXd& dy) const;
  void solveOnce(SolveWork& w, const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, Eigen::VectorXd& dx,
                 Eigen::VectorXd& dy) const;
  /// Iterative refinement of (dx, dy) on the residual of the whole system; sets w.residual.
  void refine(SolveWork& w, const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, Eigen::VectorXd& dx,
              Eigen::VectorXd& dy) const;
  void stageRhs(SolveWork& w, const Eigen::VectorXd& rx, const Eigen::VectorXd& rc) const;
  void recoverStep(SolveWork& w, const Eigen::VectorXd& rc, Eigen::VectorXd& dx, Eigen::VectorXd& dy) const;
  double largestEntry() const;
  /// r = rhs - K [dx; dy]; returns the scale max(|rhs|, |K| |[dx; dy]|) for the relative residual.
  double residual(const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, const Eigen::VectorXd& dx,
                  const Eigen::VectorXd& dy, Eigen::VectorXd& res_x, Eigen::VectorXd& res_c) const;

  int n_ = 0, m_ = 0, N_ = 0;
  StageLayout layout_;
  std::vector<int> local_;                 // index of a variable within x_k or u_k
  std::vector<char> fixed_;
  std::vector<char> equality_;
  std::vector<char> dynamics_row_;         // per NLP row
  std::vector<int> nx_, nu_;               // original sizes per stage
  std::vector<std::vector<int>> carried_;  // per stage: variables carried as extra states
  std::vector<std::vector<int>> carry_src_;  // per stage k+1: column in z_k of each carried variable
  std::vector<Row> rows_;
  std::vector<std::vector<int>> dyn_rows_;   // per stage k < N: NLP row of each x_{k+1} component
  std::vector<std::vector<int>> stage_rows_; // per stage: local and coupled NLP rows owned by it
  std::vector<std::vector<HessEntry>> hess_entries_;  // per stage, in the order of the Hessian's nonzeros
  std::vector<std::vector<int>> stage_vars_;           // per stage: its variables
  std::vector<std::vector<int>> fixed_cols_; // per stage: columns of fixed variables (unit rows)
  std::vector<std::vector<std::pair<int, int>>> dyn_pattern_;  // per stage k < N: (column, row) of [A B] that can
                                                               // be nonzero, sorted

  // values of the last factor()
  const SparsePattern pattern_;
  const double* jac_ = nullptr;
  const double* hess_ = nullptr;
  Eigen::VectorXd dx_diag_, dc_;
  double last_residual_ = 0.0;
  double kmax_ = -1.0;  // largest entry of the factored matrix (-1: not computed since the last factor())
  SolveWork work_[2];
  std::vector<std::vector<int>> exact_rows_;  // per stage: NLP rows kept as rows of C_k
  std::vector<std::vector<int>> penalty_rows_;
  std::vector<StageQp> qp_;
  RiccatiSolver riccati_;
  Eigen::VectorXd diag_;                      // dynamics row scale d (entry on x_{k+1})
  Eigen::VectorXd fill_a_;                    // row scratch of fillRows()
  struct alignas(64) CostFillScratch {  // a cache line each: both threads write theirs at once
    Eigen::VectorXd a;    // a substituted row
    std::vector<int> nz;  // its nonzero columns
  };
  CostFillScratch cost_fill_[2];              // of fillCost(), per thread
  std::vector<char> rows_filled_;             // per stage: fillRows() ran since the last factor()
};

// In the header: the solves (stage_kkt_solve.cpp) call it once per variable and right-hand side.
inline int StageKktSolver::colOf(int stage, int var) const {
  const int s = layout_.stage[var];
  const int nc = static_cast<int>(carried_[stage].size());
  if (s == stage) return layout_.is_state[var] ? local_[var] : nx_[stage] + nc + local_[var];
  const auto& c = carried_[stage];
  const auto it = std::lower_bound(c.begin(), c.end(), var);
  return (it != c.end() && *it == var) ? nx_[stage] + static_cast<int>(it - c.begin()) : -1;
}

}  // namespace centaur::ocp_solver
