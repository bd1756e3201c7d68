// Serial-chain extraction from an MJCF with a private mjModel/mjData (see chain_from_mjcf.hpp).
#include "model/chain_from_mjcf.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <memory>

#include "common/error.hpp"
#include "model/mjcf_load.hpp"

namespace centaur::model {

namespace {

using Mat3R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>;
using Vec3C = Eigen::Map<const Eigen::Vector3d>;

struct MjDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
  void operator()(mjData* d) const { mj_deleteData(d); }
};

Eigen::Matrix3d quatToMat(const double* q) {  // MuJoCo order w, x, y, z
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

}  // namespace

ChainSpec centauroLeftArmSpec() {
  ChainSpec s;
  for (int i = 1; i <= 7; ++i) s.joints.push_back("j_arm1_" + std::to_string(i));
  s.ee_frame = "ball1_tip";
  return s;
}

std::string centauroMjcfPath() { return std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml"; }

namespace {

[[noreturn]] void chainFail(const std::string& path, const std::string& what, const std::string& msg) {
  throw InputError(path, what, msg);
}

// The link of joint `jn`, a hinge whose body is a child of `parent` (its body into `body`): its frame, axis,
// limits and home position.
ChainLink jointLink(const mjModel* m, const mjData* d, const std::string& path, const std::string& jn, int parent,
                    int& body) {
  const int j = mj_name2id(m, mjOBJ_JOINT, jn.c_str());
  if (j < 0) chainFail(path, jn, "no such joint");
  if (m->jnt_type[j] != mjJNT_HINGE) chainFail(path, jn, "not a hinge (revolute) joint");
  const int b = m->jnt_bodyid[j];
  if (m->body_jntnum[b] != 1) chainFail(path, jn, "its body carries more than one joint");
  if (m->body_parentid[b] != parent) {
    chainFail(path, jn, "its body is not a child of the previous link (or of the base)");
  }
  if (Vec3C(m->jnt_pos + 3 * j).norm() > 1e-12) chainFail(path, jn, "the joint anchor is not at the body origin");
  ChainLink L;
  L.joint = jn;
  L.body = mj_id2name(m, mjOBJ_BODY, b);
  L.parent_p = Vec3C(m->body_pos + 3 * b);
  L.parent_R = quatToMat(m->body_quat + 4 * b);
  L.axis = Vec3C(m->jnt_axis + 3 * j).normalized();
  L.armature = m->dof_armature[m->jnt_dofadr[j]];
  L.q_min = m->jnt_limited[j] ? m->jnt_range[2 * j] : -INFINITY;
  L.q_max = m->jnt_limited[j] ? m->jnt_range[2 * j + 1] : INFINITY;
  if (!(m->nuser_jnt >= 1 && m->jnt_user[m->nuser_jnt * j] > 0)) {
    chainFail(path, jn, "no velocity limit (joint user value)");
  }
  L.qd_max = m->jnt_user[m->nuser_jnt * j];
  L.tau_max = 0.0;
  for (int a = 0; a < m->nu; ++a) {
    if (m->actuator_trntype[a] == mjTRN_JOINT && m->actuator_trnid[2 * a] == j && m->actuator_ctrllimited[a]) {
      const double cr = std::max(std::abs(m->actuator_ctrlrange[2 * a]), std::abs(m->actuator_ctrlrange[2 * a + 1]));
      L.tau_max = std::abs(m->actuator_gear[6 * a]) * cr;
    }
  }
  if (!(L.tau_max > 0.0)) chainFail(path, jn, "no effort limit (a motor with ctrlrange on the joint)");
  L.q_home = d->qpos[m->jnt_qposadr[j]];
  body = b;
  return L;
}

// Mass, CoM and inertia of body b and every welded descendant (no joint on the path), in the link frame.
void weldedInertia(const mjModel* m, const mjData* d, const std::string& path, int b, ChainLink& L) {
  const Eigen::Matrix3d w_R_b = Mat3R(d->xmat + 9 * b);
  const Eigen::Vector3d w_p_b = Vec3C(d->xpos + 3 * b);
  std::vector<int> members{b};
  for (int k = b + 1; k < m->nbody; ++k) {  // MuJoCo numbers bodies depth-first: descendants follow b
    int a = k;
    bool welded = true;
    while (a != b && a > 0) {
      if (m->body_jntnum[a] != 0) welded = false;
      a = m->body_parentid[a];
    }
    if (a == b && welded) members.push_back(k);
  }
  double mass = 0.0;
  Eigen::Vector3d mc = Eigen::Vector3d::Zero();
  for (int k : members) {
    mass += m->body_mass[k];
    mc += m->body_mass[k] * (w_R_b.transpose() * (Vec3C(d->xipos + 3 * k) - w_p_b));
  }
  if (!(mass > 0.0)) chainFail(path, L.joint, "the link has no mass");
  L.mass = mass;
  L.com = mc / mass;
  L.inertia.setZero();
  for (int k : members) {
    const Eigen::Matrix3d b_R_i = w_R_b.transpose() * Mat3R(d->ximat + 9 * k);
    const Eigen::Vector3d r = w_R_b.transpose() * (Vec3C(d->xipos + 3 * k) - w_p_b) - L.com;
    const Eigen::Matrix3d Ic = b_R_i * Vec3C(m->body_inertia + 3 * k).asDiagonal() * b_R_i.transpose();
    L.inertia += Ic + m->body_mass[k] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
}

// The end-effector point `ee` (a site or a body welded to the last link's body `last`) in the last link's frame.
Eigen::Vector3d endEffectorOffset(const mjModel* m, const mjData* d, const std::string& path, const std::string& ee,
                                  int last) {
  Eigen::Vector3d w_p_ee = Eigen::Vector3d::Zero();
  int ee_body = -1;
  if (const int s = mj_name2id(m, mjOBJ_SITE, ee.c_str()); s >= 0) {
    w_p_ee = Vec3C(d->site_xpos + 3 * s);
    ee_body = m->site_bodyid[s];
  } else if (const int b = mj_name2id(m, mjOBJ_BODY, ee.c_str()); b >= 0) {
    w_p_ee = Vec3C(d->xpos + 3 * b);
    ee_body = b;
  } else {
    chainFail(path, ee, "no such site or body (end-effector)");
  }
  for (int a = ee_body; a != last; a = m->body_parentid[a]) {
    if (a <= 0 || m->body_jntnum[a] != 0) chainFail(path, ee, "the end-effector is not welded to the last link");
  }
  return Mat3R(d->xmat + 9 * last).transpose() * (w_p_ee - Vec3C(d->xpos + 3 * last));
}

}  // namespace

SerialChain chainFromMjcf(const std::string& path, const ChainSpec& spec) {
  std::unique_ptr<mjModel, MjDeleter> mp(loadMjcf(path, /*discard_visual=*/true));
  const mjModel* m = mp.get();
  std::unique_ptr<mjData, MjDeleter> dp(mj_makeData(m));
  mjData* d = dp.get();
  const int key = mj_name2id(m, mjOBJ_KEY, "home");
  if (key >= 0) {
    mj_resetDataKeyframe(m, d, key);
  } else {
    mj_resetData(m, d);
  }
  mj_kinematics(m, d);
  auto bodyId = [&](const std::string& name, const char* role) {
    const int b = mj_name2id(m, mjOBJ_BODY, name.c_str());
    if (b < 0) chainFail(path, name, std::string("no such body (") + role + ")");
    return b;
  };
  if (spec.joints.empty() || static_cast<int>(spec.joints.size()) > kMaxChainJoints) {
    chainFail(path, "joints", "a chain needs 1.." + std::to_string(kMaxChainJoints) + " joints");
  }

  SerialChain c;
  c.source = path;
  c.reference_body = spec.reference_body;
  c.base_body = spec.base_body;
  const int ref = bodyId(spec.reference_body, "reference");
  const int base = bodyId(spec.base_body, "base");
  const Eigen::Matrix3d w_R_ref = Mat3R(d->xmat + 9 * ref);
  const Eigen::Vector3d w_p_ref = Vec3C(d->xpos + 3 * ref);
  c.base_R = w_R_ref.transpose() * Mat3R(d->xmat + 9 * base);
  c.base_p = w_R_ref.transpose() * (Vec3C(d->xpos + 3 * base) - w_p_ref);
  c.gravity = w_R_ref.transpose() * Vec3C(m->opt.gravity);
  c.momentum_point = c.base_p;

  int parent = base;
  for (const std::string& jn : spec.joints) {
    int b = -1;
    ChainLink L = jointLink(m, d, path, jn, parent, b);
    weldedInertia(m, d, path, b, L);
    c.links.push_back(L);
    parent = b;
  }
  c.ee_name = spec.ee_frame;
  c.ee_offset = endEffectorOffset(m, d, path, spec.ee_frame, parent);
  return c;
}

}  // namespace centaur::model
