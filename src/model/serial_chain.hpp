#pragma once
// A fixed-base serial chain of revolute joints (e.g. one CENTAURO arm on its torso held still), written once
// for any scalar type so the same code gives values (double) and exact derivatives (Eigen AutoDiff scalars,
// the planner's reverse-mode TapeVar). The numbers come from the MJCF (model/chain_from_mjcf.hpp); nothing is
// typed in here.
//
// Frames: every result is expressed in the REFERENCE frame R (the body the chain is described in, e.g. the
// pelvis), which is inertial for this model: the base body (e.g. torso_2) is fixed at R_T_base.
// Link i is the body moved by joint i (with every body welded to it merged in); its frame sits at the joint
// anchor, parent_T_i(q_i) = [parent_R_i0 Rot(axis_i, q_i), parent_p_i].
//
// Functions (q, qd, qdd: dof() scalars each):
//   chainPoint(c, q, i, i_p)             a point given in link i's frame, in R
//   chainEndEffector(c, q)               the end-effector point (ee_offset in the last link), in R
//   chainInverseDynamics(c, q, qd, qdd)  joint torques (recursive Newton-Euler, gravity, rotor armature)
//   chainAngularMomentum(c, q, qd)       angular momentum of all links about momentum_point (R axes)
//   chainCom(c, q)                       centre of mass of all links, in R
// All work on fixed-size stack arrays (at most kMaxChainJoints joints): no heap allocation.
#include <Eigen/Core>

#include <string>
#include <vector>

namespace centaur::model {

constexpr int kMaxChainJoints = 8;

/// One revolute joint and the rigid body it moves.
struct ChainLink {
  std::string joint;               ///< joint name in the MJCF
  std::string body;                ///< body name (the link frame)
  Eigen::Vector3d parent_p = Eigen::Vector3d::Zero();      ///< [m] link origin in the parent link's frame
  Eigen::Matrix3d parent_R = Eigen::Matrix3d::Identity();  ///< parent_R_link at q = 0
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();         ///< joint axis in the link frame (unit)
  double mass = 0.0;                                       ///< [kg] body + welded descendants
  Eigen::Vector3d com = Eigen::Vector3d::Zero();           ///< [m] centre of mass in the link frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();       ///< [kg m^2] about the CoM, link axes
  double armature = 0.0;                                   ///< [kg m^2] rotor inertia added to tau (as MuJoCo)
  double q_min = 0.0, q_max = 0.0;                         ///< [rad] position range
  double qd_max = 0.0;                                     ///< [rad/s] velocity limit
  double tau_max = 0.0;                                    ///< [Nm] effort limit
  double q_home = 0.0;                                     ///< [rad] the home keyframe's value
};

struct SerialChain {
  std::string source;                 ///< where the description came from (file), for messages
  std::string reference_body;         ///< frame R, e.g. "pelvis"
  std::string base_body;              ///< the fixed body the chain hangs from, e.g. "torso_2"
  Eigen::Vector3d base_p = Eigen::Vector3d::Zero();      ///< [m] R_p_base
  Eigen::Matrix3d base_R = Eigen::Matrix3d::Identity();  ///< R_R_base
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};              ///< [m/s^2] in R
  std::string ee_name;                                   ///< body or site the end-effector point is taken from
  Eigen::Vector3d ee_offset = Eigen::Vector3d::Zero();   ///< [m] end-effector point in the last link's frame
  Eigen::Vector3d momentum_point = Eigen::Vector3d::Zero();  ///< [m] in R (default: the base origin)
  std::vector<ChainLink> links;

  int dof() const { return static_cast<int>(links.size()); }
  Eigen::VectorXd homePosture() const {
    Eigen::VectorXd q(dof());
    for (int i = 0; i < dof(); ++i) q[i] = links[i].q_home;
    return q;
  }
};

// ---------------------------------------------------------------------------------------------------------
// Templated kinematics and dynamics.

namespace chain_detail {

template <class S>
using V3 = Eigen::Matrix<S, 3, 1>;
template <class S>
using M3 = Eigen::Matrix<S, 3, 3>;

template <class S>
V3<S> cross(const V3<S>& a, const V3<S>& b) {
  return V3<S>(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

template <class S>
M3<S> mulConst(const M3<S>& A, const Eigen::Matrix3d& B) {
  M3<S> r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      S s = S(0);
      for (int k = 0; k < 3; ++k) {
        if (B(k, j) != 0.0) s += A(i, k) * S(B(k, j));
      }
      r(i, j) = s;
    }
  }
  return r;
}

/// A * b with b constant (double).
template <class S>
V3<S> mulConst(const M3<S>& A, const Eigen::Vector3d& b) {
  V3<S> r = V3<S>::Zero();
  for (int k = 0; k < 3; ++k) {
    if (b[k] != 0.0) r += A.col(k) * S(b[k]);
  }
  return r;
}

template <class S>
S dot(const V3<S>& a, const V3<S>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// R I R^T for a constant inertia I.
template <class S>
M3<S> rotateInertia(const M3<S>& R, const Eigen::Matrix3d& I) {
  return mulConst<S>(R, I) * R.transpose();
}

/// Rotation by angle q about the unit axis a (Rodrigues): I + sin q [a]x + (1 - cos q) [a]x^2.
template <class S>
M3<S> axisRotation(const Eigen::Vector3d& a, const S& q) {
  Eigen::Matrix3d K;
  K << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  const Eigen::Matrix3d K2 = K * K;
  using std::cos;
  using std::sin;
  const S s = sin(q);
  const S omc = S(1) - cos(q);
  M3<S> R;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      S e = S(i == j ? 1.0 : 0.0);
      if (K(i, j) != 0.0) e += S(K(i, j)) * s;
      if (K2(i, j) != 0.0) e += S(K2(i, j)) * omc;
      R(i, j) = e;
    }
  }
  return R;
}

/// Per-link poses in R: R_i (orientation), p_i (origin), z_i (joint axis).
template <class S>
struct Poses {
  M3<S> R[kMaxChainJoints];
  V3<S> p[kMaxChainJoints];
  V3<S> z[kMaxChainJoints];
};

template <class S>
void poses(const SerialChain& c, const S* q, Poses<S>& out) {
  M3<S> Rprev = c.base_R.cast<S>();
  V3<S> pprev = c.base_p.cast<S>();
  for (int i = 0; i < c.dof(); ++i) {
    const ChainLink& L = c.links[i];
    const M3<S> R0 = mulConst<S>(Rprev, L.parent_R);  // R_R_link at q_i = 0
    out.p[i] = pprev + mulConst<S>(Rprev, L.parent_p);
    out.z[i] = mulConst<S>(R0, L.axis);
    out.R[i] = R0 * axisRotation<S>(L.axis, q[i]);
    Rprev = out.R[i];
    pprev = out.p[i];
  }
}

}  // namespace chain_detail

/// A point given in link i's frame, expressed in R.
template <class S>
Eigen::Matrix<S, 3, 1> chainPoint(const SerialChain& c, const S* q, int link, const Eigen::Vector3d& i_point) {
  chain_detail::Poses<S> P;
  chain_detail::poses(c, q, P);
  return P.p[link] + chain_detail::mulConst<S>(P.R[link], i_point);
}

/// The end-effector point (ee_offset in the last link), in R.
template <class S>
Eigen::Matrix<S, 3, 1> chainEndEffector(const SerialChain& c, const S* q) {
  return chainPoint(c, q, c.dof() - 1, c.ee_offset);
}

/// Joint torques tau (dof) = M(q) qdd + C(q, qd) qd + g(q) + armature .* qdd (recursive Newton-Euler in R).
template <class S>
void chainInverseDynamics(const SerialChain& c, const S* q, const S* qd, const S* qdd, S* tau) {
  using namespace chain_detail;
  const int n = c.dof();
  Poses<S> P;
  poses(c, q, P);
  V3<S> F[kMaxChainJoints], N[kMaxChainJoints], cw[kMaxChainJoints];
  V3<S> om = V3<S>::Zero(), al = V3<S>::Zero();
  V3<S> acc = (-c.gravity).cast<S>();  // base acceleration = -g: gravity enters as a fictitious lift
  V3<S> pprev = c.base_p.cast<S>();
  for (int i = 0; i < n; ++i) {
    const ChainLink& L = c.links[i];
    const V3<S> r = P.p[i] - pprev;
    acc = acc + cross(al, r) + cross(om, cross(om, r));  // origin of link i
    const V3<S> zq = P.z[i] * qd[i];
    al = al + P.z[i] * qdd[i] + cross(om, zq);
    om = om + zq;
    cw[i] = mulConst<S>(P.R[i], L.com);
    const V3<S> ac = acc + cross(al, cw[i]) + cross(om, cross(om, cw[i]));
    F[i] = ac * S(L.mass);
    const M3<S> Iw = rotateInertia<S>(P.R[i], L.inertia);
    N[i] = Iw * al + cross(om, V3<S>(Iw * om));
    pprev = P.p[i];
  }
  V3<S> f = V3<S>::Zero(), nn = V3<S>::Zero();
  for (int i = n - 1; i >= 0; --i) {
    // moment about the origin of link i of everything outboard of joint i
    V3<S> ni = N[i] + cross(cw[i], F[i]) + nn;
    if (i + 1 < n) ni = ni + cross(V3<S>(P.p[i + 1] - P.p[i]), f);
    f = F[i] + f;
    nn = ni;
    tau[i] = dot<S>(P.z[i], ni) + S(c.links[i].armature) * qdd[i];
  }
}

/// Centre of mass of all links, in R.
template <class S>
Eigen::Matrix<S, 3, 1> chainCom(const SerialChain& c, const S* q) {
  using namespace chain_detail;
  Poses<S> P;
  poses(c, q, P);
  V3<S> s = V3<S>::Zero();
  double m = 0.0;
  for (int i = 0; i < c.dof(); ++i) {
    s += (P.p[i] + mulConst<S>(P.R[i], c.links[i].com)) * S(c.links[i].mass);
    m += c.links[i].mass;
  }
  return s * S(1.0 / m);
}

/// Angular momentum of all links about c.momentum_point (fixed in R), R axes. Rotor armature excluded.
template <class S>
Eigen::Matrix<S, 3, 1> chainAngularMomentum(const SerialChain& c, const S* q, const S* qd) {
  using namespace chain_detail;
  Poses<S> P;
  poses(c, q, P);
  V3<S> om = V3<S>::Zero(), v = V3<S>::Zero(), h = V3<S>::Zero();
  V3<S> pprev = c.base_p.cast<S>();
  const V3<S> O = c.momentum_point.cast<S>();
  for (int i = 0; i < c.dof(); ++i) {
    const ChainLink& L = c.links[i];
    v = v + cross(om, V3<S>(P.p[i] - pprev));
    om = om + P.z[i] * qd[i];
    const V3<S> cw = mulConst<S>(P.R[i], L.com);
    const V3<S> vc = v + cross(om, cw);
    const M3<S> Iw = rotateInertia<S>(P.R[i], L.inertia);
    h = h + Iw * om + cross(V3<S>(P.p[i] + cw - O), vc) * S(L.mass);
    pprev = P.p[i];
  }
  return h;
}

}  // namespace centaur::model
