#include "planner/quaternion_rotation_derivatives.hpp"

namespace centaur::planner {

RotationJacobian rotationJacobian(const double* rho) {
  const double w = rho[0], x = rho[1], y = rho[2], z = rho[3];
  // Entry by entry from quatToRotation, e.g. R(0, 1) = 2 (x y - w z): d/dw = -2 z, d/dx = 2 y, d/dy = 2 x, ...
  RotationJacobian d;
  d[0] << 0, -2 * z, 2 * y,  //
      2 * z, 0, -2 * x,      //
      -2 * y, 2 * x, 0;      // 2 [v]x
  d[1] << 0, 2 * y, 2 * z,   //
      2 * y, -4 * x, -2 * w, //
      2 * z, 2 * w, -4 * x;
  d[2] << -4 * y, 2 * x, 2 * w,  //
      2 * x, 0, 2 * z,           //
      -2 * w, 2 * z, -4 * y;
  d[3] << -4 * z, -2 * w, 2 * x,  //
      2 * w, -4 * z, 2 * y,       //
      2 * x, 2 * y, 0;
  return d;
}

Mat34 rotationJacobianTimes(const RotationJacobian& dR, const Eigen::Vector3d& b) {
  Mat34 out;
  for (int k = 0; k < 4; ++k) out.col(k) = dR[k] * b;
  return out;
}

Mat34 rotationJacobianTransposeTimes(const RotationJacobian& dR, const Eigen::Vector3d& a) {
  Mat34 out;
  for (int k = 0; k < 4; ++k) out.col(k) = dR[k].transpose() * a;
  return out;
}

Eigen::Matrix4d rotationHessianContract(const Eigen::Matrix3d& Z) {
  // d2R/drho_k drho_l has at most four nonzero entries (+-2 or -4), read off the derivatives above: e.g. the
  // x-derivative of dR/dw has -2 at (1, 2) and 2 at (2, 1); dR/dw does not depend on w.
  Eigen::Matrix4d H;
  H(0, 0) = 0.0;
  H(1, 1) = -4.0 * (Z(1, 1) + Z(2, 2));
  H(2, 2) = -4.0 * (Z(0, 0) + Z(2, 2));
  H(3, 3) = -4.0 * (Z(0, 0) + Z(1, 1));
  H(0, 1) = H(1, 0) = 2.0 * (Z(2, 1) - Z(1, 2));
  H(0, 2) = H(2, 0) = 2.0 * (Z(0, 2) - Z(2, 0));
  H(0, 3) = H(3, 0) = 2.0 * (Z(1, 0) - Z(0, 1));
  H(1, 2) = H(2, 1) = 2.0 * (Z(0, 1) + Z(1, 0));
  H(1, 3) = H(3, 1) = 2.0 * (Z(0, 2) + Z(2, 0));
  H(2, 3) = H(3, 2) = 2.0 * (Z(1, 2) + Z(2, 1));
  return H;
}

}  // namespace centaur::planner
