#pragma once
// Derivatives of the rotation matrix R(rho) of model::quatToRotation with respect to the quaternion
// rho = (w, x, y, z), for hand-written element derivatives. quatToRotation is the quadratic formula
// R = I - 2 (|v|^2 I - v v^T) + 2 w [v]x (v = (x, y, z)) for ANY rho, unit or not, and the derivatives here are
// those of that formula: dR/drho_k is linear in rho, d2R/drho_k drho_l is a constant.
#include <Eigen/Core>

#include <array>

namespace centaur::planner {

using Mat34 = Eigen::Matrix<double, 3, 4>;
using RotationJacobian = std::array<Eigen::Matrix3d, 4>;

/// dR/drho_k, k = 0..3 (w, x, y, z).
RotationJacobian rotationJacobian(const double* rho);

/// Column k is (dR/drho_k) b: the derivative of R b with respect to rho (b fixed).
Mat34 rotationJacobianTimes(const RotationJacobian& dR, const Eigen::Vector3d& b);

/// Column k is (dR/drho_k)^T a: the derivative of R^T a with respect to rho (a fixed); also the gradient in rho of
/// a^T (dR/drho_k) b as a row over b.
Mat34 rotationJacobianTransposeTimes(const RotationJacobian& dR, const Eigen::Vector3d& a);

/// H_kl = <d2R/drho_k drho_l, Z> (Frobenius product): the Hessian in rho of <R(rho), Z> for a fixed Z, so that
/// every second-derivative term a^T (d2R) b of a function collects into one Z = sum a b^T (symmetric 4 x 4).
Eigen::Matrix4d rotationHessianContract(const Eigen::Matrix3d& Z);

}  // namespace centaur::planner
