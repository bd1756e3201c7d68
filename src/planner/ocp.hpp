#pragma once
// A small declarative optimal-control layer in the spirit of Horizon/ifopt.
//
//   Ocp ocp(N);                                  // N shooting intervals, nodes 0..N
//   ocp.addState("q", 19); ocp.addState("nu", 18);          // x_k, k = 0..N
//   ocp.addControl("nu_dot", 18); ocp.addControl("F", 12); ocp.addControl("dt", 1);   // u_k, k = 0..N-1
//   ocp.setBounds("dt", ocp.controlNodes(), lb, ub);
//   auto& c = ocp.addConstraint("dynamics", k, 18, lb, ub);  // rows of one node
//   ocp.addTerm(c, element, inputs, rows);       // element outputs added into those rows
//   ocp.addCost("smooth", element, inputs, weight);
//   ocp.finalize();                              // sparsity of the Jacobian and the Lagrangian Hessian
//
// Decision vector layout: z = [x_0, u_0, x_1, u_1, ..., x_{N-1}, u_{N-1}, x_N] (banded KKT system).
// Every constraint and cost is a sum of Element contributions; derivatives are exact (element AD) and
// assembled into the sparse structures Ipopt asks for. Structural zeros are detected once at finalize().
#include <Eigen/Core>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "planner/element.hpp"

namespace centaur::planner {

class Ocp {
 public:
  explicit Ocp(int num_intervals);

  // ---- variables ----
  void addState(const std::string& name, int size);
  void addControl(const std::string& name, int size);
  int numIntervals() const { return N_; }
  int nx() const { return nx_; }
  int nu() const { return nu_; }
  int numVariables() const { return N_ * (nx_ + nu_) + nx_; }
  bool isState(const std::string& name) const;
  int size(const std::string& name) const;
  /// Global index of element j of variable `name` at node k.
  int index(const std::string& name, int k, int j = 0) const;
  /// Global indices of the whole variable at node k.
  std::vector<int> indices(const std::string& name, int k) const;
  std::vector<int> stateNodes() const;    ///< 0..N
  std::vector<int> controlNodes() const;  ///< 0..N-1

  void setBounds(const std::string& name, int k, const Eigen::VectorXd& lb, const Eigen::VectorXd& ub);
  void setBounds(const std::string& name, const std::vector<int>& nodes, const Eigen::VectorXd& lb,
                 const Eigen::VectorXd& ub);
  void setGuess(const std::string& name, int k, const Eigen::VectorXd& value);
  /// Typical magnitude of each element of a variable (used for Ipopt's user scaling).
  void setScale(const std::string& name, const Eigen::VectorXd& scale);

  // ---- constraints and costs ----
  struct ConstraintBlock {
    std::string name;
    int node = 0;
    int first_row = 0;
    int rows = 0;
  };
  /// Reserve `rows` constraint rows for node `k` with bounds lb <= g <= ub. Returns the block.
  const ConstraintBlock& addConstraint(const std::string& name, int k, const Eigen::VectorXd& lb,
                                       const Eigen::VectorXd& ub);
  /// Add element outputs into rows of a block: out[j] goes to row `rows[j]` of the block (default 0..NO-1).
  void addTerm(const ConstraintBlock& block, std::shared_ptr<const Element> element, const std::vector<int>& inputs,
               std::vector<int> rows = {});
  /// Add weight * (sum of element outputs) to the objective (elements with one output are the usual case).
  void addCost(const std::string& name, std::shared_ptr<const Element> element, const std::vector<int>& inputs,
               double weight);

  void finalize();
  bool finalized() const { return finalized_; }

  // ---- NLP evaluation (after finalize) ----
  int numConstraints() const { return m_; }
  const Eigen::VectorXd& lowerBounds() const { return z_lb_; }
  const Eigen::VectorXd& upperBounds() const { return z_ub_; }
  const Eigen::VectorXd& guess() const { return z0_; }
  const Eigen::VectorXd& scale() const { return z_scale_; }
  const Eigen::VectorXd& constraintLower() const { return g_lb_; }
  const Eigen::VectorXd& constraintUpper() const { return g_ub_; }
  int jacobianNonzeros() const { return static_cast<int>(jac_rows_.size()); }
  int hessianNonzeros() const { return static_cast<int>(hess_rows_.size()); }
  const std::vector<int>& jacobianRows() const { return jac_rows_; }
  const std::vector<int>& jacobianCols() const { return jac_cols_; }
  const std::vector<int>& hessianRows() const { return hess_rows_; }  ///< lower triangle (row >= col)
  const std::vector<int>& hessianCols() const { return hess_cols_; }

  double objective(const double* z) const;
  void gradient(const double* z, double* grad) const;
  void constraints(const double* z, double* g) const;
  void jacobian(const double* z, double* values) const;
  /// Lower triangle of sigma * Hess(f) + sum_i lambda_i Hess(g_i).
  void hessian(const double* z, double sigma, const double* lambda, double* values) const;

  // ---- the same derivatives in parts, for parallel evaluation (OcpNlp) ----
  /// Buffers of one evaluating thread.
  struct Scratch {
    std::vector<double> in, out, jac, hess, w;
  };
  int numConstraintTerms() const { return static_cast<int>(constraint_terms_.size()); }
  int numCostTerms() const { return static_cast<int>(cost_terms_.size()); }
  /// One term: a constraint term or a cost term, by its index among those.
  struct TermRef {
    bool cost = false;
    int index = 0;
  };
  /// Relative work of a term's derivatives (for splitting the terms between threads).
  double termWork(TermRef t) const;
  /// What a term's derivatives add to at every call (a constant Jacobian or cost Hessian is added once, by
  /// addConstantDerivatives): Jacobian slots, Hessian slots and gradient entries. A value may be listed twice when
  /// a term takes the same variable twice. `f` is overwritten (its storage reused).
  struct Footprint {
    std::vector<int> jac, hess, grad;
  };
  void footprint(TermRef t, Footprint& f) const;
  /// grad, jac, hess += the derivatives that depend on z of the listed terms, in that order. jac and hess are in
  /// the Jacobian / Hessian structure; nothing is zeroed.
  void addDerivatives(const double* z, double sigma, const double* lambda, const std::vector<TermRef>& terms,
                      Scratch& s, double* grad, double* jac, double* hess) const;
  /// jac += the constant Jacobian entries (linear terms), hess += sigma * the constant cost Hessian (quadratic costs).
  void addConstantDerivatives(double sigma, double* jac, double* hess) const;

  /// Per-term costs at z (name -> value), for reporting.
  std::map<std::string, double> costBreakdown(const double* z) const;
  /// Constraint block names and rows, for reporting the largest violation.
  const std::vector<ConstraintBlock>& blocks() const { return blocks_; }

 private:
  struct Var {
    std::string name;
    bool state;
    int offset;
    int size;
  };
  struct Instance {
    std::shared_ptr<const Element> element;
    std::vector<int> in;        // global variable indices
    std::vector<int> out_rows;  // global constraint rows (constraints), empty for costs
    double weight = 1.0;        // costs
    std::string cost_name;
    std::vector<int> jac_slot;   // NO x NI (row-major), -1 if structurally zero
    std::vector<int> hess_slot;  // NI x NI (row-major), -1 if zero or upper triangle duplicate
    bool has_hessian = false;
    std::vector<std::pair<int, int>> jac_nz, hess_nz;  // (entry of the element's dense block, slot), nonzeros only
    bool const_jac = false;       // constraint: Jacobian evaluated once (const_jac_)
    bool const_hess = false;      // cost: Hessian evaluated once (const_cost_hess_)
  };
  void cacheConstantDerivatives();
  void scatterHessian(const Instance& t, const double* h, double scale, double* values) const;
  void addConstraintTerm(const Instance& t, const double* z, const double* lambda, Scratch& s, double* jac,
                         double* hess) const;
  void addCostTerm(const Instance& t, const double* z, double sigma, Scratch& s, double* grad, double* hess) const;
  std::vector<double> const_jac_, const_cost_hess_;
  const Var& var(const std::string& name) const;
  void checkNode(const Var& v, int k) const;
  struct Pattern {
    std::vector<char> jnz, hnz;  // structurally nonzero Jacobian (NO x NI) and Hessian (NI x NI) entries
  };
  static const Pattern& pattern(const Element& e, std::map<const Element*, Pattern>& cache);
  void analyze(Instance& inst, const Pattern& p, std::map<std::pair<int, int>, int>& jac_map,
               std::map<std::pair<int, int>, int>& hess_map, bool constraint);

  int N_;
  int nx_ = 0;
  int nu_ = 0;
  std::vector<Var> vars_;
  Eigen::VectorXd z_lb_, z_ub_, z0_, z_scale_;
  bool vectors_sized_ = false;
  void sizeVectors();

  std::vector<ConstraintBlock> blocks_;
  int m_ = 0;
  Eigen::VectorXd g_lb_, g_ub_;
  std::vector<Instance> constraint_terms_;
  std::vector<Instance> cost_terms_;

  bool finalized_ = false;
  std::vector<int> jac_rows_, jac_cols_, hess_rows_, hess_cols_;
  mutable std::vector<double> buf_in_, buf_out_, buf_jac_, buf_hess_, buf_w_;  // evaluation scratch (sized once)
  std::size_t max_in_ = 1, max_out_ = 1;
};

}  // namespace centaur::planner
