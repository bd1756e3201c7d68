#pragma once
// Exact first and second derivatives of the foot's inverse-dynamics element (FootDynamicsElement: the
// 6 unactuated rows and the 3 actuated rows of model::footDynamics, scaled), written out by hand. The generic AD
// of element.hpp gives the same numbers (to rounding) at several times the cost; this element is evaluated four
// times per stage and iteration, the largest of the OCP. The derivation is in foot_dynamics_derivatives.cpp.
#include "model/template_model.hpp"

namespace centaur::planner {

/// Derivatives of FootDynamicsElement(P, foot, 1 / inv_scale) at `in` (25 inputs: rho, omega, q_ci, qd_ci, a_u,
/// alpha, qdd_ci, F_i). jac: the 9 x 25 Jacobian, row-major (null: not computed). hess: the full symmetric
/// 25 x 25 Hessian of sum_j w_j out_j, row-major (null: not computed, w unread). Values are not computed (the
/// element's eval gives them). P.foot_inertia must be symmetric (as every inertia is).
void footDynamicsDerivatives(const model::TemplateParams& P, int foot, double inv_scale, const double* in,
                             const double* w, double* jac, double* hess);

}  // namespace centaur::planner
