#pragma once
// The Ocp as the NLP of our interior-point method (ocp_solver/nlp.hpp), and the stage of each decision
// variable (z = [x_0, u_0, x_1, ..., x_N]) for the stage-wise KKT solver.
#include <memory>
#include <vector>

#include "ocp_solver/nlp.hpp"
#include "ocp_solver/stage_kkt.hpp"
#include "planner/ocp.hpp"
#include "common/worker_thread.hpp"

namespace centaur::planner {

class OcpNlp final : public ocp_solver::Nlp {
 public:
  /// x0: the initial point (the OCP's guess if null); user_scaling: use Ocp::scale() as variable scale;
  /// threads: 1 or 2. The terms are split into two lists by estimated work; with 2 threads the second list runs
  /// on a worker thread, with 1 after the first. The derivatives are the same bit for bit either way. The worker's
  /// chooser starts in auto mode (common/parallel_chooser.hpp): each call runs on both threads only while that pays.
  OcpNlp(const Ocp& ocp, bool user_scaling, const Eigen::VectorXd* x0, int threads = 1);

  const ocp_solver::SparsePattern& pattern() const override { return pattern_; }
  void bounds(Eigen::VectorXd& x_l, Eigen::VectorXd& x_u, Eigen::VectorXd& g_l, Eigen::VectorXd& g_u) const override;
  Eigen::VectorXd initialPoint() const override { return x0_; }
  Eigen::VectorXd variableScale() const override;
  bool objective(const Eigen::VectorXd& x, double& f) override;
  bool constraints(const Eigen::VectorXd& x, Eigen::VectorXd& g) override;
  bool derivatives(const Eigen::VectorXd& x, double obj_factor, const Eigen::VectorXd& y, Eigen::VectorXd& grad,
                   double* jac, double* hess) override;

  /// The two lists of terms, each in the order it is evaluated (the second on the worker thread, if any).
  const std::vector<Ocp::TermRef>& callerTerms() const { return caller_terms_; }
  const std::vector<Ocp::TermRef>& workerTerms() const { return worker_terms_; }

  /// The thread the second list runs on (null with one thread); the KKT solver may share it (the derivatives and
  /// the factorization never run at the same time).
  common::WorkerThread* worker() const { return worker_.get(); }

  ocp_solver::StageLayout stageLayout() const;
  std::vector<char> fixedVariables() const;
  std::vector<char> equalityRows() const;

 private:
  const Ocp& ocp_;
  bool user_scaling_;
  Eigen::VectorXd x0_;
  ocp_solver::SparsePattern pattern_;
  std::unique_ptr<common::WorkerThread> worker_;
  void splitTerms();
  std::vector<Ocp::TermRef> caller_terms_, worker_terms_;  // each thread's terms, in the order it adds them
  Ocp::Scratch scratch_[2];
  Eigen::VectorXd grad1_;
  std::vector<double> jac1_, hess1_;
};

}  // namespace centaur::planner
