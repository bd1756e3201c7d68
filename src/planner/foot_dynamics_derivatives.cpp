// Derivation (all quantities in W; R = R(rho) the quadratic formula, dR_k = dR/drho_k, I = P.foot_inertia):
//   r = R r_b (r_b = hip + q_ci), rd = R qd, rdd = R qdd,
//   a = al x r + om x (om x r) + 2 om x rd + rdd + a_u + g e_z,   f = m a - F,
//   If = R I R^T,   n = If al + om x (If om) + r x f,   t = R^T f,   outputs s [f; n; t] (s = inv_scale).
// With the multipliers l = s w = (l_u, l_n, l_t) the weighted sum is
//   L = mu . f + E,   mu = l_u + R l_t + l_n x r,   E = l_n^T If al + om^T If v,   v = l_n x om
// (l_t . R^T f = (R l_t) . f, l_n . (r x f) = (l_n x r) . f, l_n . (om x If om) = (If om) . (l_n x om)), so
//   D2 L = f . D2 mu  +  (Dmu^T Df + Df^T Dmu)  +  mu . D2 f  +  D2 E.
// * f . D2 mu: f . R l_t + g . r with g = f x l_n; second derivatives only through R (rho-rho, rho-q).
// * Dmu^T Df + transpose: Dmu has rho and q columns only.
// * mu . D2 f = c . D2 a with c = m mu held fixed: a is multilinear in (al, om, r, rd, rdd); its Hessian is the
//   products of those (al-r, om-om, om-r, om-rd) mapped by their Jacobians, plus the adjoints of r, rd, rdd
//   (rbar = c x al + (c . om) om - |om|^2 c, rdbar = 2 c x om, rddbar = c) times their second derivatives, which
//   again come from R alone.
// * D2 E: If's first derivative dIf_k = dR_k I R^T + R I dR_k^T, its second one adds dR_k I dR_l^T + dR_l I dR_k^T.
// Every term a^T (d2R/drho_k drho_l) b collects into one 3 x 3 Z = sum a b^T (rotationHessianContract).
#include "planner/foot_dynamics_derivatives.hpp"

#include <Eigen/Geometry>

#include "planner/quaternion_rotation_derivatives.hpp"

namespace centaur::planner {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Rows3 = Eigen::Matrix<double, 3, 25>;                  // three rows of the Jacobian
using Hess = Eigen::Map<Eigen::Matrix<double, 25, 25, Eigen::RowMajor>>;  // the weighted Hessian, in place
using CVec3 = Eigen::Map<const Vec3>;

// Offsets of the input groups.
constexpr int kRho = 0, kOm = 4, kQ = 7, kQd = 10, kAu = 13, kAl = 16, kQdd = 19, kF = 22;

Mat3 skew(const Vec3& v) {
  Mat3 S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

/// The element's intermediate quantities at one point (unscaled), as footDynamics computes them.
struct FootPoint {
  Vec3 om, al, rb, qd, qdd;  // inputs (rb = hip + q_ci)
  double m;
  Mat3 I, R, RI, If;  // RI = R I; If = R I R^T
  RotationJacobian dR;
  Vec3 r, rd, f;
  Mat34 dr, drd, drdd;  // derivatives in rho of R rb, R qd, R qdd
};

FootPoint evaluate(const model::TemplateParams& P, int foot, const double* in) {
  FootPoint p;
  p.om = CVec3(in + kOm);
  p.al = CVec3(in + kAl);
  p.rb = P.hip[foot] + CVec3(in + kQ);
  p.qd = CVec3(in + kQd);
  p.qdd = CVec3(in + kQdd);
  p.m = P.foot_mass;
  p.I = P.foot_inertia;
  p.R = model::quatToRotation(in + kRho);
  p.RI = p.R * p.I;
  p.If = p.RI * p.R.transpose();
  p.dR = rotationJacobian(in + kRho);
  p.r = p.R * p.rb;
  p.rd = p.R * p.qd;
  Vec3 a = p.al.cross(p.r) + p.om.cross(p.om.cross(p.r)) + 2.0 * p.om.cross(p.rd) + p.R * p.qdd + CVec3(in + kAu);
  a.z() += P.gravity;
  p.f = p.m * a - CVec3(in + kF);
  p.dr = rotationJacobianTimes(p.dR, p.rb);
  p.drd = rotationJacobianTimes(p.dR, p.qd);
  p.drdd = rotationJacobianTimes(p.dR, p.qdd);
  return p;
}

/// Column k is dIf_k y = (dR_k I R^T + R I dR_k^T) y: the derivative in rho of If y (y fixed).
Mat34 inertiaJacobianTimes(const FootPoint& p, const Vec3& y) {
  return rotationJacobianTimes(p.dR, p.RI.transpose() * y) + p.RI * rotationJacobianTransposeTimes(p.dR, y);
}

// ---------------------------------------------------------------------------------------------------------------
// Jacobian.

/// df/din. With W = [om]x: da/dr = [al]x + W^2, da/dom = om r^T + (om . r) 1 - 2 r om^T - 2 [rd]x, da/drd = 2 W.
Rows3 forceJacobian(const FootPoint& p) {
  const Mat3 W = skew(p.om);
  const Mat3 Ma = skew(p.al) + W * W;
  Rows3 Df;
  Df.middleCols<4>(kRho) = p.m * (Ma * p.dr + 2.0 * W * p.drd + p.drdd);
  Df.middleCols<3>(kOm) = p.m * (p.om * p.r.transpose() + p.om.dot(p.r) * Mat3::Identity() -
                                 2.0 * p.r * p.om.transpose() - 2.0 * skew(p.rd));
  Df.middleCols<3>(kQ) = p.m * Ma * p.R;
  Df.middleCols<3>(kQd) = 2.0 * p.m * W * p.R;
  Df.middleCols<3>(kAu) = p.m * Mat3::Identity();
  Df.middleCols<3>(kAl) = -p.m * skew(p.r);
  Df.middleCols<3>(kQdd) = p.m * p.R;
  Df.middleCols<3>(kF) = -Mat3::Identity();
  return Df;
}

/// dn/din: r x df, plus If al + om x If om and r x f differentiated in rho, om, q and al.
Rows3 momentJacobian(const FootPoint& p, const Rows3& Df) {
  const Mat3 W = skew(p.om);
  Rows3 Dn = skew(p.r) * Df;
  Dn.middleCols<4>(kRho) += inertiaJacobianTimes(p, p.al) + W * inertiaJacobianTimes(p, p.om) - skew(p.f) * p.dr;
  Dn.middleCols<3>(kOm) += W * p.If - skew(p.If * p.om);
  Dn.middleCols<3>(kQ) -= skew(p.f) * p.R;
  Dn.middleCols<3>(kAl) += p.If;
  return Dn;
}

/// dt/din = R^T df + (dR_k^T f) in rho.
Rows3 actuatedJacobian(const FootPoint& p, const Rows3& Df) {
  Rows3 Dt = p.R.transpose() * Df;
  Dt.middleCols<4>(kRho) += rotationJacobianTransposeTimes(p.dR, p.f);
  return Dt;
}

// ---------------------------------------------------------------------------------------------------------------
// Hessian of L = mu . f + E (see the top of the file). Blocks are added as (rows, cols) = (a 3-input group, rho or
// another group) together with their transposes.

template <int R, int C>
void addSymmetric(Hess& H, int row, int col, const Eigen::Matrix<double, R, C>& M) {
  H.block<R, C>(row, col) += M;
  H.block<C, R>(col, row) += M.transpose();
}

/// The multipliers and the weights the Hessian's terms share.
struct Weights {
  Vec3 ln, lt;  // of n and t (scaled)
  Vec3 mu;      // l_u + R l_t + l_n x r: the weight of f
  Vec3 c;       // m mu: the weight of a
};

/// Dmu^T Df + Df^T Dmu, Dmu = [dR_k l_t + l_n x dr_k (rho), [l_n]x R (q)].
void addMultiplierCoupling(const FootPoint& p, const Weights& w, const Rows3& Df, Hess& H) {
  const Mat3 Ln = skew(w.ln);
  const Mat34 dmu_rho = rotationJacobianTimes(p.dR, w.lt) + Ln * p.dr;
  const Mat3 dmu_q = Ln * p.R;
  const Eigen::Matrix<double, 4, 25> Y4 = dmu_rho.transpose() * Df;
  const Eigen::Matrix<double, 3, 25> Y3 = dmu_q.transpose() * Df;
  H.middleRows<4>(kRho) += Y4;
  H.middleCols<4>(kRho) += Y4.transpose();
  H.middleRows<3>(kQ) += Y3;
  H.middleCols<3>(kQ) += Y3.transpose();
}

/// c . D2 a through the products of a's factors: c . (al x r) (al-r: -[c]x), c . (om x (om x r)) =
/// (c . om)(om . r) - |om|^2 (c . r) (om-om, om-r) and 2 c . (om x rd) (om-rd: -2 [c]x); r and rd map to rho, q, qd.
void addAccelerationProducts(const FootPoint& p, const Weights& w, Hess& H) {
  const Vec3& c = w.c;
  const Mat3 C = skew(c);
  const Mat3 Mor = c * p.om.transpose() + c.dot(p.om) * Mat3::Identity() - 2.0 * p.om * c.transpose();
  H.block<3, 3>(kOm, kOm) += c * p.r.transpose() + p.r * c.transpose() - 2.0 * c.dot(p.r) * Mat3::Identity();
  addSymmetric<3, 4>(H, kOm, kRho, Mor * p.dr - 2.0 * C * p.drd);
  addSymmetric<3, 3>(H, kOm, kQ, Mor * p.R);
  addSymmetric<3, 3>(H, kOm, kQd, -2.0 * C * p.R);
  addSymmetric<3, 4>(H, kAl, kRho, -C * p.dr);
  addSymmetric<3, 3>(H, kAl, kQ, -C * p.R);
}

/// The second derivatives of R-products weighted by their adjoints: f . R l_t + g . R r_b (from f . mu, g = f x l_n)
/// and rbar . R r_b + rdbar . R qd + c . R qdd (from c . a). Cross terms rho-q, rho-qd, rho-qdd; the rho-rho terms
/// are added to Z.
void addRotationCurvature(const FootPoint& p, const Weights& w, Hess& H, Mat3& Z) {
  const Vec3& c = w.c;
  const Vec3 g = p.f.cross(w.ln);
  const Vec3 rbar = c.cross(p.al) + c.dot(p.om) * p.om - p.om.squaredNorm() * c;
  const Vec3 rdbar = 2.0 * c.cross(p.om);
  addSymmetric<3, 4>(H, kQ, kRho, rotationJacobianTransposeTimes(p.dR, g + rbar));
  addSymmetric<3, 4>(H, kQd, kRho, rotationJacobianTransposeTimes(p.dR, rdbar));
  addSymmetric<3, 4>(H, kQdd, kRho, rotationJacobianTransposeTimes(p.dR, c));
  Z += p.f * w.lt.transpose() + (g + rbar) * p.rb.transpose() + rdbar * p.qd.transpose() + c * p.qdd.transpose();
}

/// D2 E, E = l_n^T If al + om^T If v (v = l_n x om; If symmetric): rho-rho (the dR I dR^T terms here, the d2R
/// terms into Z), rho-al (dIf_k l_n), rho-om (dIf_k v - l_n x dIf_k om), om-om (If [l_n]x - [l_n]x If).
void addInertiaCurvature(const FootPoint& p, const Weights& w, Hess& H, Mat3& Z) {
  const Vec3& ln = w.ln;
  const Vec3 v = ln.cross(p.om);
  const Mat34 Lk = rotationJacobianTransposeTimes(p.dR, ln), Ak = rotationJacobianTransposeTimes(p.dR, p.al);
  const Mat34 Ok = rotationJacobianTransposeTimes(p.dR, p.om), Vk = rotationJacobianTransposeTimes(p.dR, v);
  const Eigen::Matrix4d X = Lk.transpose() * p.I * Ak + Ok.transpose() * p.I * Vk;
  H.block<4, 4>(kRho, kRho) += X + X.transpose();
  const Mat3 IRt = p.RI.transpose();
  Z += ln * (IRt * p.al).transpose() + p.al * (IRt * ln).transpose() + p.om * (IRt * v).transpose() +
       v * (IRt * p.om).transpose();
  // dIf_k y = dR_k (I R^T y) + R I (dR_k^T y), with dR_k^T y already at hand for y = l_n, om, v.
  const Mat34 dIf_ln = rotationJacobianTimes(p.dR, IRt * ln) + p.RI * Lk;
  const Mat34 dIf_om = rotationJacobianTimes(p.dR, IRt * p.om) + p.RI * Ok;
  const Mat34 dIf_v = rotationJacobianTimes(p.dR, IRt * v) + p.RI * Vk;
  const Mat3 Ln = skew(ln);
  addSymmetric<3, 4>(H, kAl, kRho, dIf_ln);
  addSymmetric<3, 4>(H, kOm, kRho, dIf_v - Ln * dIf_om);
  const Mat3 A = p.If * Ln;  // If [l_n]x - [l_n]x If = A + A^T, so written: symmetric to the last bit
  H.block<3, 3>(kOm, kOm) += A + A.transpose();
}

void lagrangianHessian(const FootPoint& p, const Rows3& Df, const Vec3& lu, const Vec3& ln, const Vec3& lt,
                       Hess& H) {
  Weights w;
  w.ln = ln;
  w.lt = lt;
  w.mu = lu + p.R * lt + ln.cross(p.r);
  w.c = p.m * w.mu;
  H.setZero();
  Mat3 Z = Mat3::Zero();
  addMultiplierCoupling(p, w, Df, H);
  addAccelerationProducts(p, w, H);
  addRotationCurvature(p, w, H, Z);
  addInertiaCurvature(p, w, H, Z);
  H.block<4, 4>(kRho, kRho) += rotationHessianContract(Z);
}

}  // namespace

void footDynamicsDerivatives(const model::TemplateParams& P, int foot, double inv_scale, const double* in,
                             const double* w, double* jac, double* hess) {
  const FootPoint p = evaluate(P, foot, in);
  const Rows3 Df = forceJacobian(p);
  if (jac != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 9, 25, Eigen::RowMajor>> J(jac);
    J.topRows<3>() = inv_scale * Df;
    J.middleRows<3>(3) = inv_scale * momentJacobian(p, Df);
    J.bottomRows<3>() = inv_scale * actuatedJacobian(p, Df);
  }
  if (hess != nullptr) {
    // The scale folds into the multipliers: sum_j w_j s out_j = L(s w).
    const Vec3 lu = inv_scale * CVec3(w), ln = inv_scale * CVec3(w + 3), lt = inv_scale * CVec3(w + 6);
    Hess H(hess);
    lagrangianHessian(p, Df, lu, ln, lt, H);
  }
}

}  // namespace centaur::planner
