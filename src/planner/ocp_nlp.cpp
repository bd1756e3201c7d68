#include "planner/ocp_nlp.hpp"

#include <algorithm>
#include <cmath>

namespace centaur::planner {

OcpNlp::OcpNlp(const Ocp& ocp, bool user_scaling, const Eigen::VectorXd* x0, int threads)
    : ocp_(ocp), user_scaling_(user_scaling), x0_(x0 ? *x0 : ocp.guess()) {
  pattern_.n = ocp.numVariables();
  pattern_.m = ocp.numConstraints();
  pattern_.jac_rows = ocp.jacobianRows();
  pattern_.jac_cols = ocp.jacobianCols();
  pattern_.hess_rows = ocp.hessianRows();
  pattern_.hess_cols = ocp.hessianCols();
  // The same split with one thread (the second list evaluated after the first): the derivatives, and so the
  // iterates and the primitive, do not depend on the number of cores.
  splitTerms();
  if (threads >= 2) {
    worker_ = std::make_unique<common::WorkerThread>();
    worker_->chooser().setMode(common::ParallelChooser::Mode::kAuto);
  }
  jac1_.resize(ocp.jacobianNonzeros());
  hess1_.resize(ocp.hessianNonzeros());
}

// The terms are split between the caller and the worker; each thread adds its terms, in its order, into its own
// buffers, and the caller then adds the worker's buffers to its own. The base split gives the worker the
// constraint terms after half of their estimated work and leaves the rest and every cost term to the caller (it
// differs from one sum over all terms only in the rounding of values both lists add to). To balance the work
// without changing any sum of the base split, the caller's list is walked backwards: a term moves to the end of the
// worker's list if that improves the balance and, for every value it adds to, it is the caller's last term there
// and either the caller's only one (c + W == W + c) or the worker has none (the caller's sum ends with it anyway).
void OcpNlp::splitTerms() {
  const Ocp& o = ocp_;
  const int nc = o.numConstraintTerms(), nj = o.jacobianNonzeros(), nh = o.hessianNonzeros();
  double total = 0.0, acc = 0.0;
  for (int c = 0; c < nc; ++c) total += o.termWork({false, c});
  int split = 0;
  while (split < nc && acc < 0.5 * total) acc += o.termWork({false, split++});
  // Values as one index space (Jacobian slots, Hessian slots, gradient entries), each listed once per term.
  const int nv = nj + nh + pattern_.n;
  Ocp::Footprint f;
  std::vector<int> v, mark(nv, -1);
  int stamp = 0;
  auto ids = [&](const Ocp::TermRef& t) -> const std::vector<int>& {
    o.footprint(t, f);
    v.clear();
    ++stamp;
    auto add = [&](int id) {
      if (mark[id] != stamp) mark[id] = stamp, v.push_back(id);
    };
    for (int j : f.jac) add(j);
    for (int h : f.hess) add(nj + h);
    for (int g : f.grad) add(nj + nh + g);
    return v;
  };
  std::vector<Ocp::TermRef> caller;
  for (int c = 0; c < split; ++c) caller.push_back({false, c});
  for (int k = 0; k < o.numCostTerms(); ++k) caller.push_back({true, k});
  // Every value a caller term adds to, in the caller's order ("occurrences"), linked to the previous occurrence of
  // the same value: top[id] is the caller's last term there, count[id] how many caller terms add to it.
  std::vector<int> occ_start(caller.size() + 1), occ_id, occ_prev, top(nv, -1), count(nv, 0), worker_count(nv, 0);
  occ_id.reserve(nv);
  occ_prev.reserve(nv);
  double work_caller = 0.0, work_worker = 0.0;
  for (std::size_t p = 0; p < caller.size(); ++p) {
    occ_start[p] = static_cast<int>(occ_id.size());
    for (int id : ids(caller[p])) {
      occ_prev.push_back(top[id]);
      top[id] = static_cast<int>(occ_id.size());
      occ_id.push_back(id);
      ++count[id];
    }
    work_caller += o.termWork(caller[p]);
  }
  occ_start[caller.size()] = static_cast<int>(occ_id.size());
  worker_terms_.clear();
  for (int c = split; c < nc; ++c) {
    worker_terms_.push_back({false, c});
    for (int id : ids({false, c})) ++worker_count[id];
    work_worker += o.termWork({false, c});
  }
  std::vector<char> moved(caller.size(), 0);
  for (int p = static_cast<int>(caller.size()) - 1; p >= 0; --p) {
    const double w = o.termWork(caller[p]);
    if (w <= 0.0 || work_worker + w > work_caller - w) continue;
    bool ok = true;
    for (int e = occ_start[p]; e < occ_start[p + 1] && ok; ++e) {
      const int id = occ_id[e];
      ok = top[id] == e && (count[id] == 1 || worker_count[id] == 0);
    }
    if (!ok) continue;
    for (int e = occ_start[p]; e < occ_start[p + 1]; ++e) {
      const int id = occ_id[e];
      top[id] = occ_prev[e];
      --count[id];
      ++worker_count[id];
    }
    moved[p] = 1;
    worker_terms_.push_back(caller[p]);
    work_caller -= w;
    work_worker += w;
  }
  caller_terms_.clear();
  for (std::size_t p = 0; p < caller.size(); ++p)
    if (!moved[p]) caller_terms_.push_back(caller[p]);
}

void OcpNlp::bounds(Eigen::VectorXd& x_l, Eigen::VectorXd& x_u, Eigen::VectorXd& g_l, Eigen::VectorXd& g_u) const {
  x_l = ocp_.lowerBounds();
  x_u = ocp_.upperBounds();
  g_l = ocp_.constraintLower();
  g_u = ocp_.constraintUpper();
}

Eigen::VectorXd OcpNlp::variableScale() const {
  return user_scaling_ ? ocp_.scale() : Eigen::VectorXd::Ones(pattern_.n);
}

bool OcpNlp::objective(const Eigen::VectorXd& x, double& f) {
  f = ocp_.objective(x.data());
  return std::isfinite(f);
}

bool OcpNlp::constraints(const Eigen::VectorXd& x, Eigen::VectorXd& g) {
  g.resize(pattern_.m);
  ocp_.constraints(x.data(), g.data());
  return true;
}

bool OcpNlp::derivatives(const Eigen::VectorXd& x, double obj_factor, const Eigen::VectorXd& y, Eigen::VectorXd& grad,
                         double* jac, double* hess) {
  const int nj = ocp_.jacobianNonzeros(), nh = ocp_.hessianNonzeros();
  auto second = [&] {  // the worker's list into its own buffers
    grad1_.setZero(pattern_.n);
    std::fill(jac1_.begin(), jac1_.end(), 0.0);
    std::fill(hess1_.begin(), hess1_.end(), 0.0);
    ocp_.addDerivatives(x.data(), obj_factor, y.data(), worker_terms_, scratch_[1], grad1_.data(), jac1_.data(),
                        hess1_.data());
  };
  const auto first = [&] {  // the caller's list into the outputs
    grad.setZero(pattern_.n);
    std::fill(jac, jac + nj, 0.0);
    std::fill(hess, hess + nh, 0.0);
    ocp_.addDerivatives(x.data(), obj_factor, y.data(), caller_terms_, scratch_[0], grad.data(), jac, hess);
  };
  {
    const common::ParallelSection section(worker_.get(), common::kSectionDerivatives);
    common::runAlongside(worker_.get(), first, second);
  }
  grad += grad1_;
  for (int k = 0; k < nj; ++k) jac[k] += jac1_[k];
  for (int k = 0; k < nh; ++k) hess[k] += hess1_[k];
  ocp_.addConstantDerivatives(obj_factor, jac, hess);
  return true;
}

ocp_solver::StageLayout OcpNlp::stageLayout() const {
  const int N = ocp_.numIntervals(), stride = ocp_.nx() + ocp_.nu();
  ocp_solver::StageLayout l;
  l.num_stages = N + 1;
  for (int i = 0; i < pattern_.n; ++i) {
    const int k = std::min(i / stride, N);
    l.stage.push_back(k);
    l.is_state.push_back(k == N || i % stride < ocp_.nx());
  }
  return l;
}

std::vector<char> OcpNlp::fixedVariables() const {
  std::vector<char> f(pattern_.n);
  for (int i = 0; i < pattern_.n; ++i) f[i] = ocp_.lowerBounds()[i] == ocp_.upperBounds()[i];
  return f;
}

std::vector<char> OcpNlp::equalityRows() const {
  std::vector<char> e(pattern_.m);
  for (int r = 0; r < pattern_.m; ++r) e[r] = ocp_.constraintLower()[r] == ocp_.constraintUpper()[r];
  return e;
}

}  // namespace centaur::planner
