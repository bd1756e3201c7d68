#pragma once
// The paper's 5-mass template of the quadrupedal lower body (Sec. III-A/B): a floating waist and four point
// feet, each moved by three prismatic joints along the waist axes. Written once, templated on the scalar,
// so the same code gives values (double) and exact derivatives (Eigen AutoDiff scalars).
//
// Generalized coordinates (eq. 1), nq = 19:  q  = [p_u (3, W), rho_u (4: w, x, y, z), q_C (12)]
// Generalized velocities (eq. 2), nv = 18:   nu = [pdot_u (3, W), omega_u (3, W), qdot_C (12)]
// Foot i sits at  w_p_foot_i = p_u + w_R_b (hip_i + q_C,i),  i.e. q_C,i is the foot position relative to its
// hip point, in waist (B) axes. Foot order: 0 FL, 1 FR, 2 RL, 3 RR (the robot's wheel_1..wheel_4).
// Quaternion component order here is w, x, y, z (MuJoCo's). The paper writes rho = [eps; eta] (x, y, z, w).
#include <Eigen/Core>

#include <array>
#include <string>

namespace centaur::model {

constexpr int kTemplateNq = 19;
constexpr int kTemplateNv = 18;
constexpr int kNumFeet = 4;

/// Inertial and geometric parameters of the template (all SI, waist frame B).
struct TemplateParams {
  std::string preset = "centauro";
  double waist_mass = 50.293;                                    ///< [kg]
  Eigen::Vector3d waist_com = Eigen::Vector3d(0.194, 0.0005, 0.224);  ///< [m] in B
  Eigen::Matrix3d waist_inertia = Eigen::Matrix3d::Identity();  ///< [kg m^2] about the waist CoM, B axes
  double foot_mass = 10.705;                                     ///< [kg] each foot
  Eigen::Matrix3d foot_inertia = Eigen::Matrix3d::Identity() * 0.04;  ///< [kg m^2] about the foot point
  std::array<Eigen::Vector3d, kNumFeet> hip{};                   ///< [m] prismatic-leg origins in B
  double gravity = 9.81;                                         ///< [m/s^2], along -z of W

  double totalMass() const { return waist_mass + kNumFeet * foot_mass; }
};

// ------------------------------------------------------------------------------------------------------
// Small templated helpers (quaternion w, x, y, z stored in 4 consecutive scalars).

template <class S>
using Vec3 = Eigen::Matrix<S, 3, 1>;
template <class S>
using Mat3 = Eigen::Matrix<S, 3, 3>;

/// Rotation matrix w_R_b of a unit quaternion (w, x, y, z): R = I + 2 w [v]x + 2 [v]x^2.
template <class S>
Mat3<S> quatToRotation(const S* rho) {
  const S w = rho[0], x = rho[1], y = rho[2], z = rho[3];
  Mat3<S> R;
  R(0, 0) = S(1) - S(2) * (y * y + z * z);
  R(0, 1) = S(2) * (x * y - w * z);
  R(0, 2) = S(2) * (x * z + w * y);
  R(1, 0) = S(2) * (x * y + w * z);
  R(1, 1) = S(1) - S(2) * (x * x + z * z);
  R(1, 2) = S(2) * (y * z - w * x);
  R(2, 0) = S(2) * (x * z - w * y);
  R(2, 1) = S(2) * (y * z + w * x);
  R(2, 2) = S(1) - S(2) * (x * x + y * y);
  return R;
}

/// Quaternion propagation (eq. 3) with the angular velocity in W: rho_dot = 1/2 [omega, 0] o rho.
template <class S>
void quatDerivative(const S* rho, const S* w_omega, S* rho_dot) {
  const S w = rho[0], x = rho[1], y = rho[2], z = rho[3];
  const S ox = w_omega[0], oy = w_omega[1], oz = w_omega[2];
  rho_dot[0] = S(-0.5) * (ox * x + oy * y + oz * z);
  rho_dot[1] = S(0.5) * (ox * w + oy * z - oz * y);
  rho_dot[2] = S(0.5) * (oy * w + oz * x - ox * z);
  rho_dot[3] = S(0.5) * (oz * w + ox * y - oy * x);
}

template <class S>
Vec3<S> cross(const Vec3<S>& a, const Vec3<S>& b) {
  return Vec3<S>(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

/// Foot position in W: p_u + R (hip_i + q_C,i).
template <class S>
Vec3<S> footPosition(const TemplateParams& P, int i, const S* p_u, const S* rho, const S* q_ci) {
  const Mat3<S> R = quatToRotation(rho);
  Vec3<S> r;
  for (int a = 0; a < 3; ++a) r[a] = S(P.hip[i][a]) + q_ci[a];
  Vec3<S> out = R * r;
  for (int a = 0; a < 3; ++a) out[a] += p_u[a];
  return out;
}

/// Foot velocity in W: pdot_u + omega x R r_i + R qdot_C,i.
template <class S>
Vec3<S> footVelocity(const TemplateParams& P, int i, const S* rho, const S* q_ci, const S* v_u, const S* w_omega,
                     const S* qd_ci) {
  const Mat3<S> R = quatToRotation(rho);
  Vec3<S> r;
  for (int a = 0; a < 3; ++a) r[a] = S(P.hip[i][a]) + q_ci[a];
  const Vec3<S> Rr = R * r;
  const Vec3<S> om(w_omega[0], w_omega[1], w_omega[2]);
  const Vec3<S> qd(qd_ci[0], qd_ci[1], qd_ci[2]);
  Vec3<S> out = cross(om, Rr) + R * qd;
  for (int a = 0; a < 3; ++a) out[a] += v_u[a];
  return out;
}

// ------------------------------------------------------------------------------------------------------
// Inverse dynamics, split in elements so that derivatives stay small (one element per body).
//
// tau_full = B(q) nu_dot + h(q, nu) - J_C^T F_C   (18 rows: 6 unactuated, 12 actuated; eq. 4)
// Kane's method: every body's (m a - f_ext) and (I alpha + omega x I omega) mapped by its partial velocities.
// Moments of the unactuated angular rows are about the waist origin p_u, in W.

/// Waist contribution to the 6 unactuated rows. Inputs: rho (4), omega (3, W), pddot_u (3, W), omega_dot (3, W).
template <class S>
void waistDynamics(const TemplateParams& P, const S* rho, const S* w_omega, const S* a_u, const S* w_alpha,
                   S* tau_u /*6*/) {
  const Mat3<S> R = quatToRotation(rho);
  const Vec3<S> om(w_omega[0], w_omega[1], w_omega[2]);
  const Vec3<S> al(w_alpha[0], w_alpha[1], w_alpha[2]);
  const Vec3<S> c = R * P.waist_com.cast<S>();
  Vec3<S> a = cross(al, c) + cross(om, cross(om, c));
  for (int k = 0; k < 3; ++k) a[k] += a_u[k];
  a[2] += S(P.gravity);  // a - g, with g = (0, 0, -gravity)
  const Vec3<S> f = S(P.waist_mass) * a;
  const Mat3<S> Iw = R * P.waist_inertia.cast<S>() * R.transpose();
  const Vec3<S> n = Iw * al + cross(om, Vec3<S>(Iw * om)) + cross(c, f);
  for (int k = 0; k < 3; ++k) {
    tau_u[k] = f[k];
    tau_u[3 + k] = n[k];
  }
}

/// Foot i contribution: 6 unactuated rows and its own 3 actuated rows.
/// Inputs: rho (4), omega (3, W), q_ci (3), qd_ci (3), pddot_u (3), omega_dot (3), qdd_ci (3), F_i (3, W).
template <class S>
void footDynamics(const TemplateParams& P, int i, const S* rho, const S* w_omega, const S* q_ci, const S* qd_ci,
                  const S* a_u, const S* w_alpha, const S* qdd_ci, const S* F_i, S* tau_u /*6*/, S* tau_a /*3*/) {
  const Mat3<S> R = quatToRotation(rho);
  const Vec3<S> om(w_omega[0], w_omega[1], w_omega[2]);
  const Vec3<S> al(w_alpha[0], w_alpha[1], w_alpha[2]);
  Vec3<S> r_b;
  for (int a = 0; a < 3; ++a) r_b[a] = S(P.hip[i][a]) + q_ci[a];
  const Vec3<S> r = R * r_b;
  const Vec3<S> rd = R * Vec3<S>(qd_ci[0], qd_ci[1], qd_ci[2]);
  const Vec3<S> rdd = R * Vec3<S>(qdd_ci[0], qdd_ci[1], qdd_ci[2]);
  Vec3<S> a = cross(al, r) + cross(om, cross(om, r)) + S(2) * cross(om, rd) + rdd;
  for (int k = 0; k < 3; ++k) a[k] += a_u[k];
  a[2] += S(P.gravity);
  Vec3<S> f = S(P.foot_mass) * a;
  for (int k = 0; k < 3; ++k) f[k] -= F_i[k];
  const Mat3<S> If = R * P.foot_inertia.cast<S>() * R.transpose();
  const Vec3<S> n = If * al + cross(om, Vec3<S>(If * om)) + cross(r, f);
  const Vec3<S> t = R.transpose() * f;
  for (int k = 0; k < 3; ++k) {
    tau_u[k] = f[k];
    tau_u[3 + k] = n[k];
    tau_a[k] = t[k];
  }
}

/// Full inverse dynamics: tau_full (18) = B nu_dot + h - J^T F. `F` is 12 (W). Rows 0-5 must vanish (eq. 4a).
template <class S>
void inverseDynamics(const TemplateParams& P, const S* q, const S* nu, const S* nu_dot, const S* F, S* tau_full) {
  const S* rho = q + 3;
  const S* om = nu + 3;
  const S* a_u = nu_dot;
  const S* al = nu_dot + 3;
  S tu[6];
  waistDynamics(P, rho, om, a_u, al, tu);
  for (int k = 0; k < 6; ++k) tau_full[k] = tu[k];
  for (int i = 0; i < kNumFeet; ++i) {
    S ta[3];
    footDynamics(P, i, rho, om, q + 7 + 3 * i, nu + 6 + 3 * i, a_u, al, nu_dot + 6 + 3 * i, F + 3 * i, tu, ta);
    for (int k = 0; k < 6; ++k) tau_full[k] += tu[k];
    for (int k = 0; k < 3; ++k) tau_full[6 + 3 * i + k] = ta[k];
  }
}

// ------------------------------------------------------------------------------------------------------
// Double-valued conveniences (model queries, tests, resampling).

using VectorQ = Eigen::Matrix<double, kTemplateNq, 1>;
using VectorV = Eigen::Matrix<double, kTemplateNv, 1>;
using MatrixV = Eigen::Matrix<double, kTemplateNv, kTemplateNv>;
using VectorF = Eigen::Matrix<double, 3 * kNumFeet, 1>;

/// Joint-space inertia matrix B(q) (18 x 18), from the inverse dynamics with zero velocity and gravity.
MatrixV massMatrix(const TemplateParams& P, const VectorQ& q);
/// Nonlinear terms h(q, nu) (gravity, centrifugal, Coriolis).
VectorV nonlinearTerms(const TemplateParams& P, const VectorQ& q, const VectorV& nu);
/// Contact Jacobian of foot i (3 x 18): w_pdot_foot_i = J_i nu.
Eigen::Matrix<double, 3, kTemplateNv> footJacobian(const TemplateParams& P, const VectorQ& q, int i);
/// Forward dynamics: nu_dot = B^-1 (S tau + J^T F - h), tau 12 (prismatic forces), F 12 (W).
VectorV forwardDynamics(const TemplateParams& P, const VectorQ& q, const VectorV& nu,
                        const Eigen::Matrix<double, 12, 1>& tau, const VectorF& F);
/// qdot from nu (quaternion propagation, eq. 3).
VectorQ configurationRate(const VectorQ& q, const VectorV& nu);
/// Kinetic energy 1/2 nu^T B nu and potential energy (gravity) of the whole template.
double kineticEnergy(const TemplateParams& P, const VectorQ& q, const VectorV& nu);
double potentialEnergy(const TemplateParams& P, const VectorQ& q);
/// Whole-body CoM in W, linear momentum, and angular momentum about the CoM (W).
Eigen::Vector3d centerOfMass(const TemplateParams& P, const VectorQ& q);
Eigen::Vector3d linearMomentum(const TemplateParams& P, const VectorQ& q, const VectorV& nu);
Eigen::Vector3d angularMomentumAboutCom(const TemplateParams& P, const VectorQ& q, const VectorV& nu);

}  // namespace centaur::model
