#pragma once
// Element functions of the lower-body jump OCP on the template model (Sec. III-C of the paper).
// Each is written once for any scalar type (values and exact derivatives by AD, see element.hpp).
// Variable layout (see jump_problem.hpp): x = [q (19), nu (18)], u = [nu_dot (18), F (12), dt (1)].
#include <Eigen/Core>

#include "model/template_model.hpp"
#include "planner/element.hpp"
#include "planner/foot_dynamics_derivatives.hpp"

namespace centaur::planner {

using model::TemplateParams;

// ---------------------------------------------------------------------------------------------
// Continuity (Direct Multiple Shooting, RK4 with one step per interval, piecewise-constant nu_dot).
// For a coordinate with constant second derivative RK4 is exact: x+ = x + v dt + a dt^2 / 2, v+ = v + a dt.

/// Inputs: x_k, v_k, a_k, dt, x_{k+1}. Output: x_{k+1} - (x_k + v_k dt + a_k dt^2 / 2).
struct PositionStep : AdElement<PositionStep, 5, 1> {
  const char* name() const override { return "continuity_position"; }
  template <class S>
  void compute(const S* in, S* out) const {
    out[0] = in[4] - (in[0] + in[1] * in[3] + S(0.5) * in[2] * in[3] * in[3]);
  }
};

/// Inputs: v_k, a_k, dt, v_{k+1}. Output: v_{k+1} - (v_k + a_k dt).
struct VelocityStep : AdElement<VelocityStep, 4, 1> {
  const char* name() const override { return "continuity_velocity"; }
  bool hessianIsConstant() const override { return true; }  // bilinear
  template <class S>
  void compute(const S* in, S* out) const {
    out[0] = in[3] - (in[0] + in[1] * in[2]);
  }
};

/// One RK4 step of the quaternion propagation (eq. 3) with omega(t) = omega_k + omega_dot t.
template <class S>
void quaternionRk4(const S* rho, const S* om0, const S* al, const S& h, S* rho_next) {
  S k1[4], k2[4], k3[4], k4[4], tmp[4], om[3];
  model::quatDerivative(rho, om0, k1);
  for (int a = 0; a < 3; ++a) om[a] = om0[a] + S(0.5) * h * al[a];
  for (int a = 0; a < 4; ++a) tmp[a] = rho[a] + S(0.5) * h * k1[a];
  model::quatDerivative(tmp, om, k2);
  for (int a = 0; a < 4; ++a) tmp[a] = rho[a] + S(0.5) * h * k2[a];
  model::quatDerivative(tmp, om, k3);
  for (int a = 0; a < 3; ++a) om[a] = om0[a] + h * al[a];
  for (int a = 0; a < 4; ++a) tmp[a] = rho[a] + h * k3[a];
  model::quatDerivative(tmp, om, k4);
  for (int a = 0; a < 4; ++a) rho_next[a] = rho[a] + h / S(6) * (k1[a] + S(2) * k2[a] + S(2) * k3[a] + k4[a]);
}

/// Inputs: rho_k (4), omega_k (3), omega_dot_k (3), dt, rho_{k+1} (4). Output (4): rho_{k+1} - RK4(...).
struct QuaternionStep : AdElement<QuaternionStep, 15, 4> {
  const char* name() const override { return "continuity_quaternion"; }
  template <class S>
  void compute(const S* in, S* out) const {
    S next[4];
    quaternionRk4(in, in + 4, in + 7, in[10], next);
    for (int a = 0; a < 4; ++a) out[a] = in[11 + a] - next[a];
  }
};

// ---------------------------------------------------------------------------------------------
// Inverse dynamics (eq. 4), one element per body; outputs are scaled by 1 / scale (e.g. m g) for conditioning.

/// Inputs: rho (4), omega (3), pddot_u (3), omega_dot (3). Outputs: 6 unactuated rows.
struct WaistDynamicsElement : AdElement<WaistDynamicsElement, 13, 6, 7> {
  WaistDynamicsElement(const TemplateParams& p, double s) : P(p), inv_scale(1.0 / s) {}
  const char* name() const override { return "dynamics_waist"; }
  template <class S>
  void compute(const S* in, S* out) const {
    model::waistDynamics(P, in, in + 4, in + 7, in + 10, out);
    for (int k = 0; k < 6; ++k) out[k] *= S(inv_scale);
  }
  TemplateParams P;
  double inv_scale;
};

/// Inputs: rho (4), omega (3), q_ci (3), qd_ci (3), pddot_u (3), omega_dot (3), qdd_ci (3), F_i (3).
/// Outputs: 6 unactuated rows, then the 3 actuated rows of foot i.
/// Its Jacobian and Hessian are written out by hand (foot_dynamics_derivatives.hpp, several times cheaper than the
/// AD's and equal to them to rounding); the AdElement base's versions stay callable by qualified name (tests).
struct FootDynamicsElement : AdElement<FootDynamicsElement, 25, 9, 13> {
  using Ad = AdElement<FootDynamicsElement, 25, 9, 13>;
  FootDynamicsElement(const TemplateParams& p, int foot, double s) : P(p), i(foot), inv_scale(1.0 / s) {}
  const char* name() const override { return "dynamics_foot"; }
  void evalJacobian(const double* in, double* out, double* jac) const override;
  void evalHessian(const double* in, const double* w, double* hess) const override;
  void evalJacobianHessian(const double* in, const double* w, double* out, double* jac, double* hess) const override;
  template <class S>
  void compute(const S* in, S* out) const {
    model::footDynamics(P, i, in, in + 4, in + 7, in + 10, in + 13, in + 16, in + 19, in + 22, out, out + 6);
    for (int k = 0; k < 9; ++k) out[k] *= S(inv_scale);
  }
  TemplateParams P;
  int i;
  double inv_scale;
};

// ---------------------------------------------------------------------------------------------
// Contact kinematics.

/// Inputs: p_u (3), rho (4), q_ci (3). Output: n . p_foot + d (surface, eq. climbing_surface).
struct FootSurfaceElement : AdElement<FootSurfaceElement, 10, 1> {
  FootSurfaceElement(const TemplateParams& p, int foot, const Eigen::Vector3d& normal, double offset)
      : P(p), i(foot), n(normal), d(offset) {}
  const char* name() const override { return "contact_surface"; }
  template <class S>
  void compute(const S* in, S* out) const {
    const model::Vec3<S> pf = model::footPosition(P, i, in, in + 3, in + 7);
    out[0] = S(n[0]) * pf[0] + S(n[1]) * pf[1] + S(n[2]) * pf[2] + S(d);
  }
  TemplateParams P;
  int i;
  Eigen::Vector3d n;
  double d;
};

/// Inputs: p_u (3), rho (4), q_ci (3). Outputs (3): p_foot - target (foot pinned at a known point).
struct FootPointElement : AdElement<FootPointElement, 10, 3> {
  FootPointElement(const TemplateParams& p, int foot, const Eigen::Vector3d& target) : P(p), i(foot), c(target) {}
  const char* name() const override { return "contact_point"; }
  template <class S>
  void compute(const S* in, S* out) const {
    const model::Vec3<S> pf = model::footPosition(P, i, in, in + 3, in + 7);
    for (int a = 0; a < 3; ++a) out[a] = pf[a] - S(c[a]);
  }
  TemplateParams P;
  int i;
  Eigen::Vector3d c;
};

/// Inputs: q_ci (3, hip -> foot in the waist frame). Output (1): |q_ci|^2 (leg reach, bounded above by r^2).
struct LegReachElement : AdElement<LegReachElement, 3, 1> {
  const char* name() const override { return "leg_reach"; }
  bool hessianIsConstant() const override { return true; }
  template <class S>
  void compute(const S* in, S* out) const {
    out[0] = in[0] * in[0] + in[1] * in[1] + in[2] * in[2];
  }
};

/// Inputs: [p_u, rho, q_ci] at node k (10) and at node k+1 (10). Outputs (3): p_foot(k+1) - p_foot(k).
struct FootDisplacementElement : AdElement<FootDisplacementElement, 20, 3> {
  FootDisplacementElement(const TemplateParams& p, int foot) : P(p), i(foot) {}
  const char* name() const override { return "contact_no_slip"; }
  template <class S>
  void compute(const S* in, S* out) const {
    const model::Vec3<S> a = model::footPosition(P, i, in, in + 3, in + 7);
    const model::Vec3<S> b = model::footPosition(P, i, in + 10, in + 13, in + 17);
    for (int k = 0; k < 3; ++k) out[k] = b[k] - a[k];
  }
  TemplateParams P;
  int i;
};

/// Inputs: rho (4), q_ci (3), v_u (3), omega (3), qd_ci (3). Outputs (3): foot velocity in W (no-slip, eq. no_slip).
struct FootVelocityElement : AdElement<FootVelocityElement, 16, 3> {
  FootVelocityElement(const TemplateParams& p, int foot) : P(p), i(foot) {}
  const char* name() const override { return "contact_velocity"; }
  template <class S>
  void compute(const S* in, S* out) const {
    const model::Vec3<S> v = model::footVelocity(P, i, in, in + 4, in + 7, in + 10, in + 13);
    for (int a = 0; a < 3; ++a) out[a] = v[a];
  }
  TemplateParams P;
  int i;
};

/// Inputs: as FootVelocityElement. Output: |foot velocity|^2 (a cost).
struct FootVelocitySquared : AdElement<FootVelocitySquared, 16, 1> {
  FootVelocitySquared(const TemplateParams& p, int foot) : P(p), i(foot) {}
  const char* name() const override { return "stance_foot_velocity"; }
  template <class S>
  void compute(const S* in, S* out) const {
    const model::Vec3<S> v = model::footVelocity(P, i, in, in + 4, in + 7, in + 10, in + 13);
    out[0] = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  }
  TemplateParams P;
  int i;
};

// ---------------------------------------------------------------------------------------------
// Friction (eq. friction_conic). The surface normal n points out of the surface, towards the robot.

/// Linearized (inner) pyramid, 5 rows, all >= 0: mu' Fn -+ F.t1, mu' Fn -+ F.t2 (mu' = mu / sqrt(2)), Fn - F_thr.
struct FrictionPyramidElement : AdElement<FrictionPyramidElement, 3, 5, 1> {
  FrictionPyramidElement(const Eigen::Vector3d& normal, double mu, double threshold, double scale);
  const char* name() const override { return "friction_pyramid"; }
  bool jacobianIsConstant() const override { return true; }
  template <class S>
  void compute(const S* F, S* out) const {
    const S fn = S(n[0]) * F[0] + S(n[1]) * F[1] + S(n[2]) * F[2];
    const S f1 = S(t1[0]) * F[0] + S(t1[1]) * F[1] + S(t1[2]) * F[2];
    const S f2 = S(t2[0]) * F[0] + S(t2[1]) * F[1] + S(t2[2]) * F[2];
    const S m = S(mu_inner) * fn;
    out[0] = (m - f1) * S(inv_scale);
    out[1] = (m + f1) * S(inv_scale);
    out[2] = (m - f2) * S(inv_scale);
    out[3] = (m + f2) * S(inv_scale);
    out[4] = (fn - S(thr)) * S(inv_scale);
  }
  Eigen::Vector3d n, t1, t2;
  double mu_inner, thr, inv_scale;
};

/// Second-order cone, 2 rows, both >= 0: mu^2 Fn^2 - |F_t|^2 (scaled), Fn - F_thr.
struct FrictionConeElement : AdElement<FrictionConeElement, 3, 2> {
  FrictionConeElement(const Eigen::Vector3d& normal, double mu, double threshold, double scale)
      : n(normal.normalized()), mu(mu), thr(threshold), inv_scale(1.0 / scale) {}
  const char* name() const override { return "friction_cone"; }
  bool hessianIsConstant() const override { return true; }
  template <class S>
  void compute(const S* F, S* out) const {
    const S fn = S(n[0]) * F[0] + S(n[1]) * F[1] + S(n[2]) * F[2];
    S ft2 = S(0);
    for (int a = 0; a < 3; ++a) {
      const S ft = F[a] - fn * S(n[a]);
      ft2 += ft * ft;
    }
    out[0] = (S(mu * mu) * fn * fn - ft2) * S(inv_scale * inv_scale);
    out[1] = (fn - S(thr)) * S(inv_scale);
  }
  Eigen::Vector3d n;
  double mu, thr, inv_scale;
};

// ---------------------------------------------------------------------------------------------
// Least-squares costs (the weights are applied by the Ocp).

/// Inputs: N values. Output: sum (in - ref)^2.
template <int N>
struct SquaredError : AdElement<SquaredError<N>, N, 1> {
  explicit SquaredError(const Eigen::Matrix<double, N, 1>& reference, const char* label = "squared_error")
      : ref(reference), label_(label) {}
  const char* name() const override { return label_; }
  bool hessianIsConstant() const override { return true; }
  template <class S>
  void compute(const S* in, S* out) const {
    S s = S(0);
    for (int a = 0; a < N; ++a) {
      const S e = in[a] - S(ref[a]);
      s += e * e;
    }
    out[0] = s;
  }
  Eigen::Matrix<double, N, 1> ref;
  const char* label_;
};

/// Inputs: N values. Output: offset + sum coef_a in_a (a cost of constant slope).
template <int N>
struct AffineSum : AdElement<AffineSum<N>, N, 1> {
  AffineSum(const Eigen::Matrix<double, N, 1>& coefficients, double offset, const char* label = "affine_sum")
      : coef(coefficients), off(offset), label_(label) {}
  const char* name() const override { return label_; }
  bool jacobianIsConstant() const override { return true; }
  bool hessianIsConstant() const override { return true; }
  template <class S>
  void compute(const S* in, S* out) const {
    S s = S(off);
    for (int a = 0; a < N; ++a) s += S(coef[a]) * in[a];
    out[0] = s;
  }
  Eigen::Matrix<double, N, 1> coef;
  double off;
  const char* label_;
};

/// Inputs: a (N), b (N). Output: sum (b - a)^2 (rates: force and acceleration smoothing).
template <int N>
struct SquaredDifference : AdElement<SquaredDifference<N>, 2 * N, 1> {
  const char* name() const override { return "squared_difference"; }
  bool hessianIsConstant() const override { return true; }
  template <class S>
  void compute(const S* in, S* out) const {
    S s = S(0);
    for (int a = 0; a < N; ++a) {
      const S e = in[N + a] - in[a];
      s += e * e;
    }
    out[0] = s;
  }
};

}  // namespace centaur::planner
