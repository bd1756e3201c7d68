// ctest-labels: unit physics
// Whole-robot model against independent computations: Jacobians, CoM Jacobian and bias accelerations
// against central finite differences of forward kinematics (base perturbed on the quaternion manifold,
// base angular velocity in the BASE frame); centroidal momentum against the body-by-body sum of
// momenta; mass matrix against the kinetic energy; gravity and bias forces against MuJoCo's inverse
// dynamics on a separately created mjData.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <random>
#include <string>

#include "model/robot_model.hpp"

using centaur::RobotModel;
using centaur::RowMatrixXd;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

// q (+) h v on the configuration manifold: p += h v_lin (world), R <- R exp(h omega_base), joints += h qd.
VectorXd integrate(const VectorXd& q, const VectorXd& v, double h) {
  VectorXd r = q;
  r.head<3>() += h * v.head<3>();
  const Eigen::Quaterniond quat(q[3], q[4], q[5], q[6]);
  const Vector3d w = h * v.segment<3>(3);
  Eigen::Quaterniond dq = Eigen::Quaterniond::Identity();
  if (w.norm() > 0) dq = Eigen::Quaterniond(Eigen::AngleAxisd(w.norm(), w.normalized()));
  const Eigen::Quaterniond qn = (quat * dq).normalized();
  r[3] = qn.w();
  r[4] = qn.x();
  r[5] = qn.y();
  r[6] = qn.z();
  r.tail(q.size() - 7) += h * v.tail(v.size() - 6);
  return r;
}

// Angular velocity (world) from R(+h) and R(-h).
Vector3d omegaFd(const Matrix3d& Rp, const Matrix3d& Rm, double h) {
  const Eigen::AngleAxisd aa(Rp * Rm.transpose());
  return aa.axis() * aa.angle() / (2 * h);
}

struct Fixture : public ::testing::Test {
  RobotModel model{kModel};
  std::mt19937 rng{12345};
  VectorXd q, v;

  void randomState() {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int n = model.numJoints();
    q.resize(model.nq());
    v.resize(model.nv());
    q.head<3>() = Vector3d(u(rng), u(rng), 1.0 + u(rng));
    Eigen::Quaterniond quat(u(rng), u(rng), u(rng), u(rng));
    quat.normalize();
    q.segment<4>(3) << quat.w(), quat.x(), quat.y(), quat.z();
    const auto& L = model.limits();
    for (int i = 0; i < n; ++i) {
      const double lo = std::isinf(L.q_min[i]) ? -3.0 : L.q_min[i] + 0.05;
      const double hi = std::isinf(L.q_max[i]) ? 3.0 : L.q_max[i] - 0.05;
      q[7 + i] = lo + (hi - lo) * 0.5 * (1 + u(rng));
    }
    for (int i = 0; i < model.nv(); ++i) v[i] = 2.0 * u(rng);
  }
};

const char* kFrames[] = {"pelvis", "torso_2", "arm1_4", "ball1_tip", "ball2", "imu", "knee_2",
                         "wheel_1", "wheel_centre_3", "ankle2_4"};

}  // namespace

TEST_F(Fixture, FrameJacobiansMatchFiniteDifferences) {
  const double h = 1e-6;
  RowMatrixXd J(6, model.nv());
  for (int trial = 0; trial < 3; ++trial) {
    randomState();
    for (const char* name : kFrames) {
      const int f = model.frameId(name);
      ASSERT_GE(f, 0) << name;
      model.update(q, v);
      model.frameJacobian(f, J);
      const RobotModel::Vector6d vel = model.frameVelocity(f);
      for (int k = 0; k < model.nv(); ++k) {
        const VectorXd e = VectorXd::Unit(model.nv(), k);
        model.update(integrate(q, e, h), v);
        const Eigen::Isometry3d Tp = model.framePose(f);
        model.update(integrate(q, e, -h), v);
        const Eigen::Isometry3d Tm = model.framePose(f);
        const Vector3d lin = (Tp.translation() - Tm.translation()) / (2 * h);
        const Vector3d ang = omegaFd(Tp.linear(), Tm.linear(), h);
        EXPECT_LT((J.col(k).head<3>() - lin).norm(), 1e-6) << name << " col " << k;
        EXPECT_LT((J.col(k).tail<3>() - ang).norm(), 1e-6) << name << " col " << k;
      }
      EXPECT_LT((vel - J * v).norm(), 1e-9) << name;
    }
  }
}

TEST_F(Fixture, PointJacobiansAndComJacobianMatchFiniteDifferences) {
  const double h = 1e-6;
  RowMatrixXd Jp(3, model.nv()), Jw(3, model.nv()), Jc(3, model.nv());
  randomState();
  const int f = model.frameId("wheel_2");
  const Vector3d f_point(0.01, -0.078, 0.02);
  model.update(q, v);
  model.pointJacobian(f, f_point, Jp);
  const Vector3d w_point = model.framePose(f) * f_point;
  model.worldPointJacobian(f, w_point, Jw);
  model.comJacobian(Jc);
  EXPECT_LT((Jp - Jw).norm(), 1e-12);
  EXPECT_LT((model.comVelocity() - Jc * v).norm(), 1e-9);
  for (int k = 0; k < model.nv(); ++k) {
    const VectorXd e = VectorXd::Unit(model.nv(), k);
    model.update(integrate(q, e, h), v);
    const Vector3d pp = model.framePose(f) * f_point, cp = model.com();
    model.update(integrate(q, e, -h), v);
    const Vector3d pm = model.framePose(f) * f_point, cm = model.com();
    EXPECT_LT((Jp.col(k) - (pp - pm) / (2 * h)).norm(), 1e-6) << k;
    EXPECT_LT((Jc.col(k) - (cp - cm) / (2 * h)).norm(), 1e-6) << k;
  }
}

TEST_F(Fixture, BiasAccelerationsMatchFiniteDifferencesOfJv) {
  // Jdot v = d/dt (J(q(t)) v) along q(t) = q (+) t v with v constant.
  const double h = 1e-6;
  RowMatrixXd J(6, model.nv()), A(6, model.nv()), Jc(3, model.nv());
  for (int trial = 0; trial < 2; ++trial) {
    randomState();
    for (const char* name : kFrames) {
      const int f = model.frameId(name);
      model.update(q, v);
      const RobotModel::Vector6d a = model.frameBiasAcceleration(f);
      model.update(integrate(q, v, h), v);
      const RobotModel::Vector6d vp = model.frameVelocity(f);
      model.update(integrate(q, v, -h), v);
      const RobotModel::Vector6d vm = model.frameVelocity(f);
      EXPECT_LT((a - (vp - vm) / (2 * h)).norm(), 2e-5 * (1 + a.norm())) << name;
    }
    // a material point off the frame origin, given in frame and in world coordinates
    const int f = model.frameId("wheel_4");
    const Vector3d f_point(0.0, 0.078, 0.01);
    model.update(q, v);
    const Vector3d ap = model.pointBiasAcceleration(f, f_point);
    const Vector3d aw = model.worldPointBiasAcceleration(f, model.framePose(f) * f_point);
    EXPECT_LT((ap - aw).norm(), 1e-12);
    RowMatrixXd Jp(3, model.nv());
    model.update(integrate(q, v, h), v);
    model.pointJacobian(f, f_point, Jp);
    const Vector3d vp = Jp * v;
    model.update(integrate(q, v, -h), v);
    model.pointJacobian(f, f_point, Jp);
    const Vector3d vm = Jp * v;
    EXPECT_LT((ap - (vp - vm) / (2 * h)).norm(), 2e-5 * (1 + ap.norm()));
    // CoM and centroidal momentum
    model.update(q, v);
    const Vector3d ac = model.comBiasAcceleration();
    const RobotModel::Vector6d hb = model.centroidalMomentumBias();
    model.update(integrate(q, v, h), v);
    model.centroidalMomentumMatrix(A);
    const RobotModel::Vector6d hp = A * v;
    const Vector3d cvp = model.comVelocity();
    model.update(integrate(q, v, -h), v);
    model.centroidalMomentumMatrix(A);
    const RobotModel::Vector6d hm = A * v;
    const Vector3d cvm = model.comVelocity();
    EXPECT_LT((ac - (cvp - cvm) / (2 * h)).norm(), 2e-5 * (1 + ac.norm()));
    EXPECT_LT((hb - (hp - hm) / (2 * h)).norm(), 2e-5 * (1 + hb.norm())) << hb.transpose() << "\n"
                                                                        << ((hp - hm) / (2 * h)).transpose();
  }
}

// Independent body-by-body momentum and kinetic energy from MuJoCo's body poses (a separate mjData),
// velocities by finite differences of those poses.
TEST_F(Fixture, CentroidalMomentumAndMassMatrixMatchBodyByBodySums) {
  char err[1000] = "";
  mjModel* m = mj_loadXML(kModel.c_str(), nullptr, err, sizeof(err));
  ASSERT_NE(m, nullptr) << err;
  mjData* d = mj_makeData(m);
  const double h = 1e-6;
  RowMatrixXd A(6, model.nv()), M(model.nv(), model.nv());
  for (int trial = 0; trial < 3; ++trial) {
    randomState();
    auto poses = [&](const VectorXd& qq, std::vector<Vector3d>& c, std::vector<Matrix3d>& R) {
      for (int i = 0; i < m->nq; ++i) d->qpos[i] = qq[i];
      mj_kinematics(m, d);
      c.resize(m->nbody);
      R.resize(m->nbody);
      for (int b = 0; b < m->nbody; ++b) {
        c[b] = Vector3d(d->xipos[3 * b], d->xipos[3 * b + 1], d->xipos[3 * b + 2]);
        R[b] = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->ximat + 9 * b);
      }
    };
    std::vector<Vector3d> c0, cp, cm;
    std::vector<Matrix3d> R0, Rp, Rm;
    poses(q, c0, R0);
    poses(integrate(q, v, h), cp, Rp);
    poses(integrate(q, v, -h), cm, Rm);
    double mass = 0;
    Vector3d com = Vector3d::Zero();
    for (int b = 1; b < m->nbody; ++b) {
      mass += m->body_mass[b];
      com += m->body_mass[b] * c0[b];
    }
    com /= mass;
    Vector3d lin = Vector3d::Zero(), ang = Vector3d::Zero();
    double kinetic = 0;
    for (int b = 1; b < m->nbody; ++b) {
      const Vector3d vc = (cp[b] - cm[b]) / (2 * h);
      const Vector3d w = omegaFd(Rp[b], Rm[b], h);
      const Matrix3d I = R0[b] * Vector3d(m->body_inertia[3 * b], m->body_inertia[3 * b + 1],
                                          m->body_inertia[3 * b + 2]).asDiagonal() * R0[b].transpose();
      lin += m->body_mass[b] * vc;
      ang += m->body_mass[b] * (c0[b] - com).cross(vc) + I * w;
      kinetic += 0.5 * m->body_mass[b] * vc.squaredNorm() + 0.5 * w.dot(I * w);
    }
    for (int j = 0; j < m->nv; ++j) kinetic += 0.5 * m->dof_armature[j] * v[j] * v[j];  // rotor inertia

    model.update(q, v);
    model.centroidalMomentumMatrix(A);
    const RobotModel::Vector6d hm = A * v;
    EXPECT_LT((hm.head<3>() - lin).norm(), 1e-6 * (1 + lin.norm())) << hm.transpose() << " vs " << lin.transpose();
    EXPECT_LT((hm.tail<3>() - ang).norm(), 1e-6 * (1 + ang.norm())) << hm.transpose() << " vs " << ang.transpose();
    EXPECT_LT((model.centroidalMomentum() - hm).norm(), 1e-9);
    EXPECT_LT((model.com() - com).norm(), 1e-12);
    EXPECT_NEAR(mass, model.totalMass(), 1e-9);

    model.massMatrix(M);
    EXPECT_LT((M - M.transpose()).norm(), 1e-12);
    Eigen::LLT<Eigen::MatrixXd> llt(M);
    EXPECT_EQ(llt.info(), Eigen::Success);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().minCoeff(), 0.0);
    EXPECT_NEAR(0.5 * v.dot(M * v), kinetic, 1e-6 * kinetic);
    // the base block of M is the whole robot's mass
    EXPECT_NEAR(M(0, 0), mass, 1e-9);
    EXPECT_NEAR(M(2, 2), mass, 1e-9);
  }
  mj_deleteData(d);
  mj_deleteModel(m);
}

TEST_F(Fixture, GravityAndBiasMatchMujocoInverseDynamics) {
  char err[1000] = "";
  mjModel* m = mj_loadXML(kModel.c_str(), nullptr, err, sizeof(err));
  ASSERT_NE(m, nullptr) << err;
  mjData* d = mj_makeData(m);
  VectorXd g(model.nv()), b(model.nv());
  for (int trial = 0; trial < 3; ++trial) {
    randomState();
    q[2] = 5.0;  // in the air: no contacts; q within joint limits: no limit constraints
    model.update(q, v);
    model.gravityForces(g);
    model.biasForces(b);
    for (int i = 0; i < m->nq; ++i) d->qpos[i] = q[i];
    for (int i = 0; i < m->nv; ++i) {
      d->qvel[i] = 0;
      d->qacc[i] = 0;
    }
    mj_inverse(m, d);
    EXPECT_EQ(d->nefc, 0);
    const VectorXd g_mj = Eigen::Map<const VectorXd>(d->qfrc_inverse, m->nv);
    EXPECT_LT((g - g_mj).norm(), 1e-9 * (1 + g_mj.norm()));
    for (int i = 0; i < m->nv; ++i) d->qvel[i] = v[i];
    mj_inverse(m, d);
    const VectorXd b_mj = Eigen::Map<const VectorXd>(d->qfrc_inverse, m->nv);
    EXPECT_LT((b - b_mj).norm(), 1e-9 * (1 + b_mj.norm()));
    // analytic facts: the base force of g is the weight, -m * gravity
    EXPECT_LT((g.head<3>() + model.totalMass() * model.gravity()).norm(), 1e-9);
  }
  mj_deleteData(d);
  mj_deleteModel(m);
}
