// Whole-robot model on MuJoCo's kinematics/dynamics functions with a private mjModel/mjData.
//
// What update() computes (all preallocated):
//   mj_kinematics, mj_comPos (subtree CoM, com-based inertias cinert, motion subspaces cdof),
//   mj_crb (composite inertias crb and the sparse mass matrix qM), mj_comVel (body velocities cvel and
//   cdof_dot), mj_fullM (dense M), mj_rne(flg_acc = 0) (bias forces C v + g).
// Centroidal momentum matrix: MuJoCo's com-based quantities are all expressed about one point O, the
// CoM of the robot's kinematic tree (subtree_com of the root body), in world axes. Column j of A is the
// spatial momentum of the subtree moved by dof j: crb[body(j)] * cdof[j] (the composite inertia of the
// subtree times the unit motion), about O = the CoM, i.e. exactly the centroidal momentum matrix.
// CoM Jacobian = linear rows of A / total mass; gravity forces g = -m J_com^T gravity (uniform field).
// Bias accelerations Jdot v: per body, the spatial acceleration with vdot = 0, accumulated from the root
// as sum of cdof_dot * v (what MuJoCo's RNE does), then converted to classical point accelerations.
#include "model/robot_model.hpp"

#include <mujoco/mujoco.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/error.hpp"
#include "model/mjcf_load.hpp"

namespace centaur {

namespace {

// Spatial-inertia x motion-vector product, MuJoCo layouts: inertia i = [Ixx Iyy Izz Ixy Ixz Iyz, m c (3), m]
// about the com point, motion v = [omega; vel], result = [angular momentum; linear momentum].
inline void mulInertVec(double res[6], const double i[10], const double v[6]) {
  res[0] = i[0] * v[0] + i[3] * v[1] + i[4] * v[2] - i[8] * v[4] + i[7] * v[5];
  res[1] = i[3] * v[0] + i[1] * v[1] + i[5] * v[2] + i[8] * v[3] - i[6] * v[5];
  res[2] = i[4] * v[0] + i[5] * v[1] + i[2] * v[2] - i[7] * v[3] + i[6] * v[4];
  res[3] = i[8] * v[1] - i[7] * v[2] + i[9] * v[3];
  res[4] = i[6] * v[2] - i[8] * v[0] + i[9] * v[4];
  res[5] = i[7] * v[0] - i[6] * v[1] + i[9] * v[5];
}

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat3C = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>;
using Vec3C = Eigen::Map<const Eigen::Vector3d>;

// What is read from MuJoCo's model once: the description holds it, each workspace a copy for its queries.
struct ModelFacts {
  std::string path;
  int n = 0, nq = 0, nv = 0;
  int base_body = -1;
  double mass = 0.0;
  Eigen::Vector3d grav = Eigen::Vector3d::Zero();
  std::vector<std::string> joint_names;
  std::vector<std::string> frame_names;  // bodies, then sites
  JointLimits limits;
  Eigen::VectorXd home;
};

}  // namespace

// The const part: MuJoCo's model and its facts. Never written after loadRobotModel().
struct RobotModelDescription : ModelFacts {
  mjModel* m = nullptr;
  ~RobotModelDescription() {
    if (m) mj_deleteModel(m);
  }
};

struct RobotModel::Impl : ModelFacts {
  std::shared_ptr<const RobotModelDescription> desc;
  const mjModel* m = nullptr;
  mjData* d = nullptr;

  // results of update()
  Eigen::VectorXd q, v;
  RowMatrixXd M, A, Jcom;
  Eigen::VectorXd b, g;
  Eigen::Matrix<double, 6, Eigen::Dynamic> cacc;  // per body bias spatial acceleration about O, [ang; lin]
  Vec6 h = Vec6::Zero(), hbias = Vec6::Zero();
  bool has_momentum = false, has_bias_acc = false;  // what the last update() computed beyond kinematics
  // query scratch (queries are logically const)
  RowMatrixXd jacp, jacr;

  ~Impl() {
    if (d) mj_deleteData(d);
  }

  int bodyOf(int frame) const { return frame < m->nbody ? frame : m->site_bodyid[frame - m->nbody]; }
  Eigen::Vector3d originOf(int frame) const {
    return frame < m->nbody ? Eigen::Vector3d(Vec3C(d->xpos + 3 * frame))
                            : Eigen::Vector3d(Vec3C(d->site_xpos + 3 * (frame - m->nbody)));
  }
  Eigen::Matrix3d rotOf(int frame) const {
    return frame < m->nbody ? Eigen::Matrix3d(Mat3C(d->xmat + 9 * frame))
                            : Eigen::Matrix3d(Mat3C(d->site_xmat + 9 * (frame - m->nbody)));
  }
  // Velocity [lin; ang] (W) of the material point of body bd at world position p.
  Vec6 pointVel(int bd, const Eigen::Vector3d& p) const {
    const Vec3C w(d->cvel + 6 * bd), vo(d->cvel + 6 * bd + 3);
    const Vec3C o(d->subtree_com + 3 * m->body_rootid[bd]);
    Vec6 r;
    r.head<3>() = vo + w.cross(p - o);
    r.tail<3>() = w;
    return r;
  }
  // Bias acceleration [classical lin; ang] (W) of the material point of body bd at world position p.
  Vec6 pointAcc(int bd, const Eigen::Vector3d& p) const {
    const Vec3C o(d->subtree_com + 3 * m->body_rootid[bd]);
    const Eigen::Vector3d alpha = cacc.col(bd).head<3>();
    const Vec6 vel = pointVel(bd, p);
    Vec6 r;
    r.head<3>() = cacc.col(bd).tail<3>() + alpha.cross(p - o) + vel.tail<3>().cross(vel.head<3>());
    r.tail<3>() = alpha;
    return r;
  }
  // Per body bias spatial accelerations (vdot = 0) from cdof_dot, and the centroidal momentum bias hbias.
  void biasAccelerations();
  void checkFrame(int frame) const {
    (void)frame;
    eigen_assert(frame >= 0 && frame < m->nbody + m->nsite);
  }
};

std::shared_ptr<const RobotModelDescription> loadRobotModel(const std::string& mjcf_path) {
  auto desc = std::make_shared<RobotModelDescription>();
  RobotModelDescription& I = *desc;
  I.path = mjcf_path;
  I.m = loadMjcf(mjcf_path, /*discard_visual=*/true);  // the controller never draws: no visual geoms to pose
  const mjModel* m = I.m;

  int free_joint = -1;
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] == mjJNT_FREE) {
      if (free_joint >= 0) throw InputError(mjcf_path + ": the model has more than one free joint");
      free_joint = j;
    } else if (m->jnt_type[j] != mjJNT_HINGE) {
      throw InputError(mjcf_path + ": joint '" + mj_id2name(m, mjOBJ_JOINT, j) +
                       "': only hinge joints are supported besides the floating base");
    }
  }
  if (free_joint < 0) throw InputError(mjcf_path + ": the model has no free joint (floating base)");
  if (m->jnt_qposadr[free_joint] != 0 || m->jnt_dofadr[free_joint] != 0)
    throw InputError(mjcf_path + ": the free joint must come first in qpos/qvel");
  I.base_body = m->jnt_bodyid[free_joint];
  I.nq = m->nq;
  I.nv = m->nv;
  I.n = m->njnt - 1;
  if (I.nq != 7 + I.n || I.nv != 6 + I.n)
    throw InputError(mjcf_path + ": unexpected nq/nv for a free joint plus hinges");
  I.mass = m->body_subtreemass[I.base_body];
  I.grav = Eigen::Vector3d(m->opt.gravity[0], m->opt.gravity[1], m->opt.gravity[2]);

  const double inf = std::numeric_limits<double>::infinity();
  I.limits.q_min.setConstant(I.n, -inf);
  I.limits.q_max.setConstant(I.n, inf);
  I.limits.qd_max.setConstant(I.n, inf);
  I.limits.tau_max.setConstant(I.n, inf);
  for (int j = 0, k = 0; j < m->njnt; ++j) {
    if (j == free_joint) continue;
    if (m->jnt_qposadr[j] != 7 + k || m->jnt_dofadr[j] != 6 + k)
      throw InputError(mjcf_path + ": joint order does not match qpos order");
    I.joint_names.emplace_back(mj_id2name(m, mjOBJ_JOINT, j));
    if (m->jnt_limited[j]) {
      I.limits.q_min[k] = m->jnt_range[2 * j];
      I.limits.q_max[k] = m->jnt_range[2 * j + 1];
    }
    if (m->nuser_jnt >= 1 && m->jnt_user[m->nuser_jnt * j] > 0) I.limits.qd_max[k] = m->jnt_user[m->nuser_jnt * j];
    for (int a = 0; a < m->nu; ++a) {
      if (m->actuator_trntype[a] == mjTRN_JOINT && m->actuator_trnid[2 * a] == j && m->actuator_ctrllimited[a]) {
        const double c = std::max(std::abs(m->actuator_ctrlrange[2 * a]), std::abs(m->actuator_ctrlrange[2 * a + 1]));
        I.limits.tau_max[k] = std::abs(m->actuator_gear[6 * a]) * c;
      }
    }
    ++k;
  }
  for (int b = 0; b < m->nbody; ++b) {
    const char* nm = mj_id2name(m, mjOBJ_BODY, b);
    I.frame_names.emplace_back(nm ? nm : "");
  }
  for (int s = 0; s < m->nsite; ++s) {
    const char* nm = mj_id2name(m, mjOBJ_SITE, s);
    I.frame_names.emplace_back(nm ? nm : "");
  }
  I.home.setZero(I.n);
  const int key = mj_name2id(m, mjOBJ_KEY, "home");
  if (key >= 0) I.home = Eigen::Map<const Eigen::VectorXd>(m->key_qpos + m->nq * key + 7, I.n);
  return desc;
}

RobotModel::RobotModel(const std::string& mjcf_path) : RobotModel(loadRobotModel(mjcf_path)) {}

RobotModel::RobotModel(std::shared_ptr<const RobotModelDescription> description) : impl_(std::make_unique<Impl>()) {
  if (!description) throw std::invalid_argument("RobotModel: no description");
  Impl& I = *impl_;
  const RobotModelDescription& D = *description;
  static_cast<ModelFacts&>(I) = D;
  I.m = D.m;
  I.desc = std::move(description);
  const mjModel* m = I.m;
  I.d = mj_makeData(m);
  I.q.setZero(I.nq);
  I.q[3] = 1.0;
  I.v.setZero(I.nv);
  I.M.setZero(I.nv, I.nv);
  I.A.setZero(6, I.nv);
  I.Jcom.setZero(3, I.nv);
  I.b.setZero(I.nv);
  I.g.setZero(I.nv);
  I.cacc.setZero(6, m->nbody);
  I.jacp.setZero(3, I.nv);
  I.jacr.setZero(3, I.nv);
  update(I.q, I.v);
}

RobotModel::~RobotModel() = default;

const std::shared_ptr<const RobotModelDescription>& RobotModel::description() const { return impl_->desc; }
const std::string& RobotModel::path() const { return impl_->path; }

int RobotModel::nq() const { return impl_->nq; }
int RobotModel::nv() const { return impl_->nv; }
int RobotModel::numJoints() const { return impl_->n; }
const std::vector<std::string>& RobotModel::jointNames() const { return impl_->joint_names; }
int RobotModel::jointIndex(const std::string& name) const {
  for (int i = 0; i < impl_->n; ++i)
    if (impl_->joint_names[i] == name) return i;
  return -1;
}
const JointLimits& RobotModel::limits() const { return impl_->limits; }
double RobotModel::totalMass() const { return impl_->mass; }
int RobotModel::frameId(const std::string& name) const {
  if (name.empty()) return -1;
  const int n = static_cast<int>(impl_->frame_names.size());
  for (int f = 0; f < n; ++f)
    if (impl_->frame_names[f] == name) return f;
  return -1;
}
int RobotModel::numFrames() const { return static_cast<int>(impl_->frame_names.size()); }
const std::string& RobotModel::frameName(int frame) const { return impl_->frame_names.at(frame); }
Eigen::VectorXd RobotModel::homeJoints() const { return impl_->home; }
Eigen::Vector3d RobotModel::gravity() const { return impl_->grav; }
const Eigen::VectorXd& RobotModel::q() const { return impl_->q; }
const Eigen::VectorXd& RobotModel::v() const { return impl_->v; }

void RobotModel::update(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& v,
                        Detail detail) {
  Impl& I = *impl_;
  const mjModel* m = I.m;
  mjData* d = I.d;
  eigen_assert(q.size() == I.nq && v.size() == I.nv);
  I.q = q;
  I.v = v;
  for (int i = 0; i < I.nq; ++i) d->qpos[i] = q[i];
  for (int i = 0; i < I.nv; ++i) d->qvel[i] = v[i];

  const bool full = detail == Detail::kFull;
  const bool momentum = full || detail == Detail::kMomentum;
  const bool dynamics = full || detail == Detail::kDynamics;
  I.has_momentum = momentum;
  I.has_bias_acc = false;
  mj_kinematics(m, d);
  mj_comPos(m, d);
  if (dynamics) {
    mj_crb(m, d);  // composite inertias crb and the mass matrix qM
  } else if (momentum) {
    // composite inertias only (the CMM needs no qM): cinert are all about the same point, so a subtree's
    // composite inertia is the plain sum of its bodies', accumulated leaves to root (what mj_crb does first)
    mju_copy(d->crb, d->cinert, 10 * m->nbody);
    for (int bd = m->nbody - 1; bd > 0; --bd) {
      const int parent = m->body_parentid[bd];
      if (parent > 0) mju_addTo(d->crb + 10 * parent, d->crb + 10 * bd, 10);
    }
  }
  const bool velocities = full || dynamics || detail == Detail::kKinematics;
  if (velocities) mj_comVel(m, d);  // frame velocities (cvel, cdof_dot)
  if (dynamics) {
    mj_fullM(m, I.M.data(), d->qM);  // row-major nv x nv, same layout as RowMatrixXd
    mj_rne(m, d, 0, I.b.data());
  }
  if (!momentum) return;

  // Centroidal momentum matrix: column j = crb[body(j)] * cdof[j], about the tree's CoM.
  double res[6];
  for (int j = 0; j < I.nv; ++j) {
    mulInertVec(res, d->crb + 10 * m->dof_bodyid[j], d->cdof + 6 * j);
    for (int r = 0; r < 3; ++r) {
      I.A(r, j) = res[3 + r];
      I.A(3 + r, j) = res[r];
    }
  }
  I.Jcom = I.A.topRows<3>() / I.mass;
  I.g.noalias() = -I.mass * (I.Jcom.transpose() * I.grav);
  I.h.noalias() = I.A * I.v;
  if (!full) return;

  I.biasAccelerations();
}

void RobotModel::Impl::biasAccelerations() {
  has_bias_acc = true;
  // Bias spatial accelerations (vdot = 0, no gravity), root to leaves; body ids are topologically sorted.
  cacc.col(0).setZero();
  for (int bd = 1; bd < m->nbody; ++bd) {
    cacc.col(bd) = cacc.col(m->body_parentid[bd]);
    const int a0 = m->body_dofadr[bd];
    for (int j = 0; j < m->body_dofnum[bd]; ++j)
      cacc.col(bd) += Eigen::Map<const Vec6>(d->cdof_dot + 6 * (a0 + j)) * d->qvel[a0 + j];
  }
  // Centroidal momentum bias: sum over the tree of d/dt(I v) = I a + v x* (I v), about the (fixed) point O.
  Vec6 f = Vec6::Zero();
  const int root = m->body_rootid[base_body];
  for (int bd = 1; bd < m->nbody; ++bd) {
    if (m->body_rootid[bd] != root) continue;
    const double* in = d->cinert + 10 * bd;
    const double* cv = d->cvel + 6 * bd;
    double ia[6], iv[6];
    mulInertVec(ia, in, cacc.col(bd).data());
    mulInertVec(iv, in, cv);
    const Vec3C w(cv), vl(cv + 3), n(iv), l(iv + 3);
    const Eigen::Vector3d ang = w.cross(n) + vl.cross(l);
    const Eigen::Vector3d lin = w.cross(l);
    for (int r = 0; r < 3; ++r) {
      f[r] += ia[r] + ang[r];
      f[3 + r] += ia[3 + r] + lin[r];
    }
  }
  hbias.head<3>() = f.tail<3>();
  hbias.tail<3>() = f.head<3>();
}

void RobotModel::shiftBase(const Eigen::Vector3d& dp, const Eigen::Vector3d& dv) noexcept {
  // A rigid translation of the whole tree by dp and a uniform velocity dv added to every body: world positions
  // move by dp, linear velocities (cvel, about the moving tree CoM) by dv; orientations, the com-based
  // inertias and motion subspaces (cinert, cdof, crb), the mass matrix, the centroidal momentum matrix and the
  // bias forces (Galilean invariance: C(q, v) v does not change with a uniform velocity) do not change.
  Impl& I = *impl_;
  const mjModel* m = I.m;
  mjData* d = I.d;
  const int root = m->body_rootid[I.base_body];
  auto add3 = [](double* x, const Eigen::Vector3d& a) {
    x[0] += a[0];
    x[1] += a[1];
    x[2] += a[2];
  };
  add3(d->qpos, dp);  // the free joint comes first in qpos and qvel (checked at construction)
  add3(d->qvel, dv);
  I.q.head<3>() += dp;
  I.v.head<3>() += dv;
  for (int bd = 1; bd < m->nbody; ++bd) {
    if (m->body_rootid[bd] != root) continue;
    add3(d->xpos + 3 * bd, dp);
    add3(d->xipos + 3 * bd, dp);
    add3(d->subtree_com + 3 * bd, dp);
    add3(d->cvel + 6 * bd + 3, dv);
  }
  for (int j = 0; j < m->njnt; ++j)
    if (m->body_rootid[m->jnt_bodyid[j]] == root) add3(d->xanchor + 3 * j, dp);
  for (int g = 0; g < m->ngeom; ++g)
    if (m->body_rootid[m->geom_bodyid[g]] == root) add3(d->geom_xpos + 3 * g, dp);
  for (int s = 0; s < m->nsite; ++s)
    if (m->body_rootid[m->site_bodyid[s]] == root) add3(d->site_xpos + 3 * s, dp);
  // cdof_dot = cvel x cdof (motion cross product): its linear part gains dv x (angular part of cdof).
  for (int j = 0; j < m->nv; ++j) {
    if (m->body_rootid[m->dof_bodyid[j]] != root) continue;
    const Vec3C w(d->cdof + 6 * j);
    add3(d->cdof_dot + 6 * j + 3, dv.cross(w));
  }
  if (I.has_momentum) I.h.noalias() = I.A * I.v;
  if (I.has_bias_acc) I.biasAccelerations();
}

Eigen::Isometry3d RobotModel::framePose(int frame) const {
  impl_->checkFrame(frame);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = impl_->rotOf(frame);
  T.translation() = impl_->originOf(frame);
  return T;
}

void RobotModel::frameJacobian(int frame, Eigen::Ref<RowMatrixXd> J) const {
  Impl& I = *impl_;
  I.checkFrame(frame);
  const Eigen::Vector3d p = I.originOf(frame);
  mj_jac(I.m, I.d, I.jacp.data(), I.jacr.data(), p.data(), I.bodyOf(frame));
  J.topRows<3>() = I.jacp;
  J.bottomRows<3>() = I.jacr;
}

void RobotModel::pointJacobian(int frame, const Eigen::Vector3d& f_point, Eigen::Ref<RowMatrixXd> J) const {
  Impl& I = *impl_;
  I.checkFrame(frame);
  const Eigen::Vector3d p = I.originOf(frame) + I.rotOf(frame) * f_point;
  mj_jac(I.m, I.d, I.jacp.data(), nullptr, p.data(), I.bodyOf(frame));
  J = I.jacp;
}

void RobotModel::worldPointJacobian(int frame, const Eigen::Vector3d& w_point, Eigen::Ref<RowMatrixXd> J) const {
  Impl& I = *impl_;
  I.checkFrame(frame);
  mj_jac(I.m, I.d, I.jacp.data(), nullptr, w_point.data(), I.bodyOf(frame));
  J = I.jacp;
}

Eigen::Vector3d RobotModel::com() const {
  return Vec3C(impl_->d->subtree_com + 3 * impl_->base_body);
}
void RobotModel::comJacobian(Eigen::Ref<RowMatrixXd> J) const { J = impl_->Jcom; }
void RobotModel::centroidalMomentumMatrix(Eigen::Ref<RowMatrixXd> A) const { A = impl_->A; }
void RobotModel::massMatrix(Eigen::Ref<RowMatrixXd> M) const { M = impl_->M; }
void RobotModel::biasForces(Eigen::Ref<Eigen::VectorXd> b) const { b = impl_->b; }
void RobotModel::gravityForces(Eigen::Ref<Eigen::VectorXd> g) const { g = impl_->g; }

RobotModel::Vector6d RobotModel::frameVelocity(int frame) const {
  impl_->checkFrame(frame);
  return impl_->pointVel(impl_->bodyOf(frame), impl_->originOf(frame));
}
RobotModel::Vector6d RobotModel::frameBiasAcceleration(int frame) const {
  impl_->checkFrame(frame);
  return impl_->pointAcc(impl_->bodyOf(frame), impl_->originOf(frame));
}
Eigen::Vector3d RobotModel::pointBiasAcceleration(int frame, const Eigen::Vector3d& f_point) const {
  impl_->checkFrame(frame);
  const Eigen::Vector3d p = impl_->originOf(frame) + impl_->rotOf(frame) * f_point;
  return impl_->pointAcc(impl_->bodyOf(frame), p).head<3>();
}
Eigen::Vector3d RobotModel::worldPointBiasAcceleration(int frame, const Eigen::Vector3d& w_point) const {
  impl_->checkFrame(frame);
  return impl_->pointAcc(impl_->bodyOf(frame), w_point).head<3>();
}
Eigen::Vector3d RobotModel::comVelocity() const { return impl_->h.head<3>() / impl_->mass; }
Eigen::Vector3d RobotModel::comBiasAcceleration() const { return impl_->hbias.head<3>() / impl_->mass; }
RobotModel::Vector6d RobotModel::centroidalMomentum() const { return impl_->h; }
RobotModel::Vector6d RobotModel::centroidalMomentumBias() const { return impl_->hbias; }

}  // namespace centaur
