#pragma once
// Central-difference check of an assembled OCP (objective gradient, constraint Jacobian, Lagrangian Hessian,
// lower-triangular sparsity) at a point z with multipliers lambda and objective factor sigma. Used by the jump
// and arm-flywheel derivative tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/ocp.hpp"

namespace centaur::test {

inline double nlpRelErr(double a, double b) {
  return std::abs(a - b) / std::max(1.0, std::max(std::abs(a), std::abs(b)));
}

inline void expectNlpMatchesCentralDifferences(const planner::Ocp& ocp, const Eigen::VectorXd& z,
                                               const Eigen::VectorXd& lambda, double sigma, const std::string& label,
                                               double h = 1e-6, double tol = 1e-6) {
  const int n = ocp.numVariables(), m = ocp.numConstraints();
  Eigen::VectorXd grad(n);
  ocp.gradient(z.data(), grad.data());
  std::vector<double> jac(ocp.jacobianNonzeros()), hess(ocp.hessianNonzeros());
  ocp.jacobian(z.data(), jac.data());
  ocp.hessian(z.data(), sigma, lambda.data(), hess.data());
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, n), H = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t k = 0; k < jac.size(); ++k) J(ocp.jacobianRows()[k], ocp.jacobianCols()[k]) += jac[k];
  for (std::size_t k = 0; k < hess.size(); ++k) {
    const int r = ocp.hessianRows()[k], c = ocp.hessianCols()[k];
    ASSERT_GE(r, c) << label << ": the Hessian must be lower triangular";
    H(r, c) += hess[k];
    if (r != c) H(c, r) += hess[k];
  }
  // Lagrangian gradient for the Hessian check: sigma grad f + J^T lambda.
  auto lagGrad = [&](const Eigen::VectorXd& zz) {
    Eigen::VectorXd g(n);
    ocp.gradient(zz.data(), g.data());
    std::vector<double> jv(ocp.jacobianNonzeros());
    ocp.jacobian(zz.data(), jv.data());
    Eigen::VectorXd out = sigma * g;
    for (std::size_t k = 0; k < jv.size(); ++k) out[ocp.jacobianCols()[k]] += jv[k] * lambda[ocp.jacobianRows()[k]];
    return out;
  };
  Eigen::VectorXd gp(m), gm(m);
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd zp = z, zm = z;
    zp[i] += h;
    zm[i] -= h;
    ASSERT_LT(nlpRelErr(grad[i], (ocp.objective(zp.data()) - ocp.objective(zm.data())) / (2 * h)), tol)
        << label << " grad " << i;
    ocp.constraints(zp.data(), gp.data());
    ocp.constraints(zm.data(), gm.data());
    const Eigen::VectorXd col = (gp - gm) / (2 * h);
    for (int j = 0; j < m; ++j) ASSERT_LT(nlpRelErr(J(j, i), col[j]), tol) << label << " J(" << j << "," << i << ")";
    const Eigen::VectorXd hcol = (lagGrad(zp) - lagGrad(zm)) / (2 * h);
    for (int r = 0; r < n; ++r) ASSERT_LT(nlpRelErr(H(r, i), hcol[r]), tol) << label << " H(" << r << "," << i << ")";
  }
}

}  // namespace centaur::test
