#include "planner/template_elements.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace centaur::planner {

FrictionPyramidElement::FrictionPyramidElement(const Eigen::Vector3d& normal, double mu, double threshold, double scale)
    : n(normal.normalized()), mu_inner(mu / std::sqrt(2.0)), thr(threshold), inv_scale(1.0 / scale) {
  // Any orthonormal tangent basis: start from the axis least aligned with n.
  Eigen::Vector3d a = Eigen::Vector3d::UnitX();
  if (std::abs(n.x()) > 0.9) a = Eigen::Vector3d::UnitY();
  t1 = (a - a.dot(n) * n).normalized();
  t2 = n.cross(t1);
}

void FootDynamicsElement::evalJacobian(const double* in, double* out, double* jac) const {
  compute(in, out);
  footDynamicsDerivatives(P, i, inv_scale, in, nullptr, jac, nullptr);
}

void FootDynamicsElement::evalHessian(const double* in, const double* w, double* hess) const {
  footDynamicsDerivatives(P, i, inv_scale, in, w, nullptr, hess);
}

void FootDynamicsElement::evalJacobianHessian(const double* in, const double* w, double* out, double* jac,
                                              double* hess) const {
  compute(in, out);
  footDynamicsDerivatives(P, i, inv_scale, in, w, jac, hess);
}

}  // namespace centaur::planner
