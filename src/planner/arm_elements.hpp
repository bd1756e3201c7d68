#pragma once
// Element functions of the arm-flywheel OCP (paper Sec. "OCP Postural Task") on a fixed-base 7-DoF arm
// (model/serial_chain.hpp), each written once for any scalar (exact derivatives by AD, see element.hpp).
// Variable layout (arm_flywheel_problem.hpp): x = [q (7), qd (7)], u = [qdd (7)].
#include <Eigen/Core>

#include "model/serial_chain.hpp"
#include "planner/element.hpp"

namespace centaur::planner {

constexpr int kArmDof = 7;

/// Direct multiple shooting continuity of one joint with the control qdd constant over the interval (a fixed
/// step h). RK4 on the double integrator [q, qd]' = [qd, qdd] is exact, so one RK4 step gives
///   q+ = q + qd h + qdd h^2 / 2,  qd+ = qd + qdd h.
/// Inputs: q_k, qd_k, qdd_k, q_{k+1}, qd_{k+1}. Outputs (2): the defects (linear).
struct ArmContinuityElement : AdElement<ArmContinuityElement, 5, 2, 1> {
  explicit ArmContinuityElement(double step) : h(step) {}
  const char* name() const override { return "arm_continuity"; }
  bool jacobianIsConstant() const override { return true; }
  template <class S>
  void compute(const S* in, S* out) const {
    out[0] = in[3] - (in[0] + in[1] * S(h) + in[2] * S(0.5 * h * h));
    out[1] = in[4] - (in[1] + in[2] * S(h));
  }
  double h;
};

/// Inputs: a (N), b (N). Outputs (N): b - a (periodicity x_N - x_0).
template <int N>
struct DifferenceElement : AdElement<DifferenceElement<N>, 2 * N, N, 1> {
  const char* name() const override { return "periodicity"; }
  bool jacobianIsConstant() const override { return true; }
  template <class S>
  void compute(const S* in, S* out) const {
    for (int a = 0; a < N; ++a) out[a] = in[N + a] - in[a];
  }
};

/// Inputs: q (7), qd (7), qdd (7). Outputs (7): tau_i / tau_max_i (inverse dynamics, gravity, armature).
struct ArmTorqueElement : AdElement<ArmTorqueElement, 3 * kArmDof, kArmDof, 2 * kArmDof> {
  explicit ArmTorqueElement(const model::SerialChain& c) : chain(c) {}
  const char* name() const override { return "arm_torque"; }
  template <class S>
  void compute(const S* in, S* out) const {
    model::chainInverseDynamics(chain, in, in + kArmDof, in + 2 * kArmDof, out);
    for (int i = 0; i < kArmDof; ++i) out[i] *= S(1.0 / chain.links[i].tau_max);
  }
  model::SerialChain chain;
};

/// Inputs: q (7). Outputs (3): the end-effector point in the reference frame [m].
struct ArmEndEffectorElement : AdElement<ArmEndEffectorElement, kArmDof, 3> {
  explicit ArmEndEffectorElement(const model::SerialChain& c) : chain(c) {}
  const char* name() const override { return "arm_workspace"; }
  template <class S>
  void compute(const S* in, S* out) const {
    const Eigen::Matrix<S, 3, 1> p = model::chainEndEffector(chain, in);
    for (int a = 0; a < 3; ++a) out[a] = p[a];
  }
  model::SerialChain chain;
};

/// Inputs: q (7). Outputs (3): the arm's centre of mass in the reference frame [m].
struct ArmComElement : AdElement<ArmComElement, kArmDof, 3> {
  explicit ArmComElement(const model::SerialChain& c) : chain(c) {}
  const char* name() const override { return "arm_com"; }
  template <class S>
  void compute(const S* in, S* out) const {
    const Eigen::Matrix<S, 3, 1> p = model::chainCom(chain, in);
    for (int a = 0; a < 3; ++a) out[a] = p[a];
  }
  model::SerialChain chain;
};

/// Inputs: q (7), qd (7). Output: the momentum cost of eq. (cost_function_posture_oc) on the axis e (unit,
/// reference frame): linear mode  -(e . h) (maximise);  tracking mode  (e . h - h_d)^2.
struct ArmMomentumCostElement : AdElement<ArmMomentumCostElement, 2 * kArmDof, 1> {
  ArmMomentumCostElement(const model::SerialChain& c, const Eigen::Vector3d& axis, bool tracking, double target)
      : chain(c), e(axis), track(tracking), h_d(target) {}
  const char* name() const override { return "arm_momentum"; }
  template <class S>
  void compute(const S* in, S* out) const {
    const Eigen::Matrix<S, 3, 1> h = model::chainAngularMomentum(chain, in, in + kArmDof);
    S he = S(0);
    for (int a = 0; a < 3; ++a) {
      if (e[a] != 0.0) he += S(e[a]) * h[a];
    }
    if (track) {
      const S d = he - S(h_d);
      out[0] = d * d;
    } else {
      out[0] = -he;
    }
  }
  model::SerialChain chain;
  Eigen::Vector3d e;
  bool track;
  double h_d;
};

/// Inputs: N values. Output: sum in^2.
template <int N>
struct SquaredNorm : AdElement<SquaredNorm<N>, N, 1> {
  explicit SquaredNorm(const char* label) : label_(label) {}
  const char* name() const override { return label_; }
  bool hessianIsConstant() const override { return true; }
  template <class S>
  void compute(const S* in, S* out) const {
    S s = S(0);
    for (int a = 0; a < N; ++a) s += in[a] * in[a];
    out[0] = s;
  }
  const char* label_;
};

}  // namespace centaur::planner
