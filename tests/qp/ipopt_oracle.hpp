#pragma once
// Test-only oracle: the same dense QP solved by Ipopt (interior point, TNLP interface, exact constant Hessian),
// with tight tolerances and no bound relaxation, used to check our active-set solver.
#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include <Eigen/Core>
#include <Eigen/QR>

#include <cmath>
#include <limits>
#include <vector>

namespace centaur::test {

struct DenseQp {
  Eigen::MatrixXd H, A_eq, C;
  Eigen::VectorXd g, b_eq, c_lo, c_up, x_lo, x_up;  // x_lo/x_up size 0: no box
  int n() const { return static_cast<int>(g.size()); }
  double objective(const Eigen::VectorXd& x) const { return 0.5 * x.dot(H * x) + g.dot(x); }
};

struct OracleResult {
  bool solved = false;
  bool infeasible = false;
  int status = -1;  // Ipopt::SolverReturn
  Eigen::VectorXd x;
  double objective = std::numeric_limits<double>::quiet_NaN();
};

class QpTnlp : public Ipopt::TNLP {
 public:
  QpTnlp(const DenseQp& qp, OracleResult& out) : qp_(qp), out_(out) {}
  using Index = Ipopt::Index;
  using Number = Ipopt::Number;

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = qp_.n();
    m = static_cast<Index>(qp_.A_eq.rows() + qp_.C.rows());
    nnz_jac_g = m * n;
    nnz_h_lag = n * (n + 1) / 2;
    style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index, Number* g_l, Number* g_u) override {
    const bool box = qp_.x_lo.size() > 0;
    for (Index j = 0; j < n; ++j) {
      x_l[j] = box ? clip(qp_.x_lo[j]) : -1e20;
      x_u[j] = box ? clip(qp_.x_up[j]) : 1e20;
    }
    Index k = 0;
    for (Index i = 0; i < qp_.A_eq.rows(); ++i, ++k) g_l[k] = g_u[k] = qp_.b_eq[i];
    for (Index i = 0; i < qp_.C.rows(); ++i, ++k) {
      g_l[k] = clip(qp_.c_lo[i]);
      g_u[k] = clip(qp_.c_up[i]);
    }
    return true;
  }
  bool get_starting_point(Index n, bool, Number* x, bool, Number*, Number*, Index, bool, Number*) override {
    for (Index j = 0; j < n; ++j) x[j] = 0.0;
    return true;
  }
  bool eval_f(Index n, const Number* x, bool, Number& f) override {
    f = qp_.objective(Eigen::Map<const Eigen::VectorXd>(x, n));
    return true;
  }
  bool eval_grad_f(Index n, const Number* x, bool, Number* grad) override {
    Eigen::Map<Eigen::VectorXd>(grad, n) = qp_.H * Eigen::Map<const Eigen::VectorXd>(x, n) + qp_.g;
    return true;
  }
  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    Eigen::Map<const Eigen::VectorXd> xv(x, n);
    Eigen::Map<Eigen::VectorXd> gv(g, m);
    gv.head(qp_.A_eq.rows()) = qp_.A_eq * xv;
    gv.tail(qp_.C.rows()) = qp_.C * xv;
    return true;
  }
  bool eval_jac_g(Index n, const Number*, bool, Index m, Index, Index* iRow, Index* jCol, Number* values) override {
    Index k = 0;
    for (Index i = 0; i < m; ++i)
      for (Index j = 0; j < n; ++j, ++k) {
        if (values == nullptr) {
          iRow[k] = i;
          jCol[k] = j;
        } else {
          values[k] = i < qp_.A_eq.rows() ? qp_.A_eq(i, j) : qp_.C(i - qp_.A_eq.rows(), j);
        }
      }
    return true;
  }
  bool eval_h(Index n, const Number*, bool, Number obj_factor, Index, const Number*, bool, Index, Index* iRow,
              Index* jCol, Number* values) override {
    Index k = 0;
    for (Index i = 0; i < n; ++i)
      for (Index j = 0; j <= i; ++j, ++k) {
        if (values == nullptr) {
          iRow[k] = i;
          jCol[k] = j;
        } else {
          values[k] = obj_factor * qp_.H(i, j);
        }
      }
    return true;
  }
  void finalize_solution(Ipopt::SolverReturn status, Index n, const Number* x, const Number*, const Number*, Index,
                         const Number*, const Number*, Number obj, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    out_.solved = status == Ipopt::SUCCESS;
    out_.status = static_cast<int>(status);
    out_.infeasible = status == Ipopt::LOCAL_INFEASIBILITY;
    out_.x = Eigen::Map<const Eigen::VectorXd>(x, n);
    out_.objective = obj;
  }

 private:
  static double clip(double v) { return std::isinf(v) ? (v > 0 ? 1e20 : -1e20) : v; }
  const DenseQp& qp_;
  OracleResult& out_;
};

/// Ipopt assumes linearly independent equality constraints (LICQ): with dependent (consistent) rows it may
/// report success at a non-optimal point. The oracle therefore keeps an independent subset of A_eq's rows
/// (rank-revealing QR of A_eq'), which describes the same affine set.
inline DenseQp withIndependentEqualities(const DenseQp& qp) {
  DenseQp out = qp;
  if (qp.A_eq.rows() == 0) return out;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(qp.A_eq.transpose());
  qr.setThreshold(1e-10);
  qr.compute(qp.A_eq.transpose());
  const int rank = static_cast<int>(qr.rank());
  out.A_eq.resize(rank, qp.n());
  out.b_eq.resize(rank);
  for (int k = 0; k < rank; ++k) {
    const int row = qr.colsPermutation().indices()[k];
    out.A_eq.row(k) = qp.A_eq.row(row);
    out.b_eq[k] = qp.b_eq[row];
  }
  return out;
}

inline OracleResult solveWithIpopt(const DenseQp& qp_in) {
  OracleResult out;
  const DenseQp qp = withIndependentEqualities(qp_in);
  Ipopt::SmartPtr<Ipopt::TNLP> nlp = new QpTnlp(qp, out);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetStringValue("sb", "yes");
  app->Options()->SetNumericValue("tol", 1e-12);
  app->Options()->SetNumericValue("constr_viol_tol", 1e-12);
  app->Options()->SetNumericValue("dual_inf_tol", 1e-10);
  app->Options()->SetNumericValue("compl_inf_tol", 1e-12);
  app->Options()->SetNumericValue("bound_relax_factor", 0.0);
  app->Options()->SetStringValue("honor_original_bounds", "yes");
  app->Options()->SetStringValue("hessian_constant", "yes");
  app->Options()->SetStringValue("jac_c_constant", "yes");
  app->Options()->SetStringValue("jac_d_constant", "yes");
  app->Options()->SetStringValue("mu_strategy", "adaptive");
  app->Options()->SetIntegerValue("max_iter", 3000);
  if (app->Initialize() != Ipopt::Solve_Succeeded) return out;
  app->OptimizeTNLP(nlp);
  return out;
}

/// Polish an (approximate) solution: take the constraints active within `active_tol` at x as equalities and
/// solve the KKT system [H N'; N 0] by a complete orthogonal decomposition (dependent rows allowed). Returns
/// true and the polished point if it is feasible (within feas_tol) and the multipliers have the right signs,
/// i.e. the polished point is a certified optimum of the convex QP.
inline bool polishOnActiveSet(const DenseQp& qp, const Eigen::VectorXd& x, Eigen::VectorXd& x_polished,
                              double active_tol = 1e-6, double feas_tol = 1e-9) {
  const int n = qp.n();
  const bool box = qp.x_lo.size() > 0;
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> rhs;
  std::vector<int> sign;  // +1 lower side (multiplier >= 0), -1 upper side (<= 0), 0 equality
  for (int i = 0; i < qp.A_eq.rows(); ++i) {
    rows.push_back(qp.A_eq.row(i).transpose());
    rhs.push_back(qp.b_eq[i]);
    sign.push_back(0);
  }
  auto consider = [&](const Eigen::VectorXd& a, double v, double lo, double up) {
    const bool at_lo = std::isfinite(lo) && std::abs(v - lo) <= active_tol * (1.0 + std::abs(lo));
    const bool at_up = std::isfinite(up) && std::abs(v - up) <= active_tol * (1.0 + std::abs(up));
    if (at_lo && at_up) {
      rows.push_back(a);
      rhs.push_back(lo == up ? lo : 0.5 * (lo + up));
      sign.push_back(0);
    } else if (at_lo || at_up) {
      rows.push_back(a);
      rhs.push_back(at_lo ? lo : up);
      sign.push_back(at_lo ? 1 : -1);
    }
  };
  for (int i = 0; i < qp.C.rows(); ++i) consider(qp.C.row(i).transpose(), qp.C.row(i).dot(x), qp.c_lo[i], qp.c_up[i]);
  if (box)
    for (int j = 0; j < n; ++j) consider(Eigen::VectorXd::Unit(n, j), x[j], qp.x_lo[j], qp.x_up[j]);
  const int m = static_cast<int>(rows.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m, n + m);
  Eigen::VectorXd r(n + m);
  K.topLeftCorner(n, n) = qp.H;
  r.head(n) = -qp.g;
  for (int k = 0; k < m; ++k) {
    K.block(0, n + k, n, 1) = -rows[k];
    K.block(n + k, 0, 1, n) = rows[k].transpose();
    r[n + k] = rhs[k];
  }
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(K);
  const Eigen::VectorXd sol = cod.solve(r);
  x_polished = sol.head(n);
  // Certificate: stationarity holds by construction; check feasibility and multiplier signs.
  if ((K * sol - r).cwiseAbs().maxCoeff() > 1e-8 * (1.0 + r.cwiseAbs().maxCoeff())) return false;
  for (int k = 0; k < m; ++k)
    if (sign[k] * sol[n + k] < -1e-9) return false;
  const Eigen::VectorXd& xp = x_polished;
  for (int i = 0; i < qp.A_eq.rows(); ++i)
    if (std::abs(qp.A_eq.row(i).dot(xp) - qp.b_eq[i]) > feas_tol * (1.0 + std::abs(qp.b_eq[i]))) return false;
  for (int i = 0; i < qp.C.rows(); ++i) {
    const double v = qp.C.row(i).dot(xp);
    if (v < qp.c_lo[i] - feas_tol * (1.0 + std::abs(qp.c_lo[i]))) return false;
    if (v > qp.c_up[i] + feas_tol * (1.0 + std::abs(qp.c_up[i]))) return false;
  }
  if (box)
    for (int j = 0; j < n; ++j)
      if (xp[j] < qp.x_lo[j] - feas_tol * (1.0 + std::abs(qp.x_lo[j])) ||
          xp[j] > qp.x_up[j] + feas_tol * (1.0 + std::abs(qp.x_up[j])))
        return false;
  return true;
}

}  // namespace centaur::test
