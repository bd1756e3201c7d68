#include "model/template_model.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

namespace centaur::model {

namespace {
TemplateParams withoutGravity(const TemplateParams& P) {
  TemplateParams Q = P;
  Q.gravity = 0.0;
  return Q;
}
}  // namespace

MatrixV massMatrix(const TemplateParams& P, const VectorQ& q) {
  const TemplateParams Q = withoutGravity(P);
  MatrixV B;
  const VectorV zero = VectorV::Zero();
  const VectorF F = VectorF::Zero();
  for (int j = 0; j < kTemplateNv; ++j) {
    VectorV e = VectorV::Zero();
    e[j] = 1.0;
    VectorV col;
    inverseDynamics(Q, q.data(), zero.data(), e.data(), F.data(), col.data());
    B.col(j) = col;
  }
  return B;
}

VectorV nonlinearTerms(const TemplateParams& P, const VectorQ& q, const VectorV& nu) {
  VectorV h;
  const VectorV zero = VectorV::Zero();
  const VectorF F = VectorF::Zero();
  inverseDynamics(P, q.data(), nu.data(), zero.data(), F.data(), h.data());
  return h;
}

Eigen::Matrix<double, 3, kTemplateNv> footJacobian(const TemplateParams& P, const VectorQ& q, int i) {
  const Eigen::Matrix3d R = quatToRotation(q.data() + 3);
  const Eigen::Vector3d r = R * (P.hip[i] + q.segment<3>(7 + 3 * i));
  Eigen::Matrix<double, 3, kTemplateNv> J = Eigen::Matrix<double, 3, kTemplateNv>::Zero();
  J.block<3, 3>(0, 0).setIdentity();
  Eigen::Matrix3d rx;
  rx << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  J.block<3, 3>(0, 3) = -rx;
  J.block<3, 3>(0, 6 + 3 * i) = R;
  return J;
}

VectorV forwardDynamics(const TemplateParams& P, const VectorQ& q, const VectorV& nu,
                        const Eigen::Matrix<double, 12, 1>& tau, const VectorF& F) {
  const MatrixV B = massMatrix(P, q);
  VectorV rhs = -nonlinearTerms(P, q, nu);
  rhs.tail<12>() += tau;
  for (int i = 0; i < kNumFeet; ++i) rhs += footJacobian(P, q, i).transpose() * F.segment<3>(3 * i);
  return B.ldlt().solve(rhs);
}

VectorQ configurationRate(const VectorQ& q, const VectorV& nu) {
  VectorQ qd;
  qd.head<3>() = nu.head<3>();
  quatDerivative(q.data() + 3, nu.data() + 3, qd.data() + 3);
  qd.tail<12>() = nu.tail<12>();
  return qd;
}

double kineticEnergy(const TemplateParams& P, const VectorQ& q, const VectorV& nu) {
  return 0.5 * nu.dot(massMatrix(P, q) * nu);
}

double potentialEnergy(const TemplateParams& P, const VectorQ& q) {
  return P.totalMass() * P.gravity * centerOfMass(P, q).z();
}

Eigen::Vector3d centerOfMass(const TemplateParams& P, const VectorQ& q) {
  const Eigen::Matrix3d R = quatToRotation(q.data() + 3);
  Eigen::Vector3d c = P.waist_mass * (q.head<3>() + R * P.waist_com);
  for (int i = 0; i < kNumFeet; ++i) {
    c += P.foot_mass * footPosition(P, i, q.data(), q.data() + 3, q.data() + 7 + 3 * i);
  }
  return c / P.totalMass();
}

Eigen::Vector3d linearMomentum(const TemplateParams& P, const VectorQ& q, const VectorV& nu) {
  const Eigen::Matrix3d R = quatToRotation(q.data() + 3);
  const Eigen::Vector3d om = nu.segment<3>(3);
  Eigen::Vector3d l = P.waist_mass * (nu.head<3>() + om.cross(R * P.waist_com));
  for (int i = 0; i < kNumFeet; ++i) {
    l += P.foot_mass * footVelocity(P, i, q.data() + 3, q.data() + 7 + 3 * i, nu.data(), nu.data() + 3,
                                    nu.data() + 6 + 3 * i);
  }
  return l;
}

Eigen::Vector3d angularMomentumAboutCom(const TemplateParams& P, const VectorQ& q, const VectorV& nu) {
  const Eigen::Matrix3d R = quatToRotation(q.data() + 3);
  const Eigen::Vector3d om = nu.segment<3>(3);
  const Eigen::Vector3d c = centerOfMass(P, q);
  const Eigen::Vector3d pw = q.head<3>() + R * P.waist_com;
  const Eigen::Vector3d vw = nu.head<3>() + om.cross(R * P.waist_com);
  Eigen::Vector3d L = (pw - c).cross(P.waist_mass * vw) + R * P.waist_inertia * R.transpose() * om;
  for (int i = 0; i < kNumFeet; ++i) {
    const Eigen::Vector3d p = footPosition(P, i, q.data(), q.data() + 3, q.data() + 7 + 3 * i);
    const Eigen::Vector3d v = footVelocity(P, i, q.data() + 3, q.data() + 7 + 3 * i, nu.data(), nu.data() + 3,
                                           nu.data() + 6 + 3 * i);
    L += (p - c).cross(P.foot_mass * v) + R * P.foot_inertia * R.transpose() * om;
  }
  return L;
}

}  // namespace centaur::model
