// deriveFacts(): the template's parameters and the stabilizers' facts from the MJCF at its home keyframe.
//
// Waist: every body that is not in a leg's subtree (base, torso, arms, head, ...), lumped: total mass, CoM and
// inertia about that CoM, in B. Feet: each leg's subtree mass (the template has one foot mass: their mean).
// Hips: the leg roots' origins. Arm mirror signs: a joint of the mirroring arm turns the sagittal mirror image
// of its counterpart when its axis is the reflected pseudo-vector, a_this = -M a_other with M = diag(1, -1, 1):
// sign = -a_this . (M a_other) (+1 or -1 for a mirror-symmetric model). Pitch authority: the column of the
// centroidal momentum matrix for the joint's rate, angular row y (kg m^2/s per rad/s), and its ratio to the
// robot's own pitch inertia about its CoM (how much body pitch rate a unit joint rate cancels).
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/excerpt.hpp"
#include "model/robot_model.hpp"
#include "robot/mjcf_view.hpp"

namespace centaur::robot::detail {

namespace {

using Vec3C = Eigen::Map<const Eigen::Vector3d>;
using Mat3C = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>;

constexpr double kMirrorTolerance = 0.05;  // [-] on a sign, [m] on a joint anchor's mirror position
constexpr double kGroundTolerance = 0.005;  // [m] a foot's contact point above or below z = 0 at home
constexpr double kLegMassSpread = 0.02;     // [-] legs heavier or lighter than their mean by more: warned

// Body b's inertia about its own CoM in B axes (B = W here).
Eigen::Matrix3d bodyInertia(const mjModel* m, const mjData* d, int b) {
  const Mat3C R(d->ximat + 9 * b);
  return R * Vec3C(m->body_inertia + 3 * b).asDiagonal() * R.transpose();
}

void lumpWaist(const mjModel* m, const mjData* d, const MjcfView& v, model::TemplateParams& P) {
  double mass = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (int b = 1; b < m->nbody; ++b) {
    if (v.leg_of_body[b] >= 0) continue;
    mass += m->body_mass[b];
    first += m->body_mass[b] * Vec3C(d->xipos + 3 * b);
  }
  const Eigen::Vector3d com = first / mass;
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  for (int b = 1; b < m->nbody; ++b) {
    if (v.leg_of_body[b] >= 0) continue;
    const Eigen::Vector3d r = Vec3C(d->xipos + 3 * b) - com;
    I += bodyInertia(m, d, b) + m->body_mass[b] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  P.waist_mass = mass;
  P.waist_com = com;
  P.waist_inertia = 0.5 * (I + I.transpose());
}

// Home keyframe with the base at the origin and upright, kinematics computed; the keyframe's own base height
// and whether each foot touches the ground are read first.
void homeKinematics(const RobotDescription& d, const MjcfView& v, RobotFacts& f, std::vector<Finding>& problems) {
  const mjModel* m = v.m;
  mjData* dd = v.d;
  mj_resetDataKeyframe(m, dd, v.home_key);
  mj_kinematics(m, dd);
  f.home_base_height = dd->qpos[2];
  for (int k = 0; k < 4; ++k) {
    const double z = dd->site_xpos[3 * v.centre[k] + 2] - v.radius[k];
    if (std::abs(z) > kGroundTolerance) {
      problems.push_back({d.yaml_path, "home", "at keyframe '" + excerpt(d.home) + "' foot " + kFootNames[k] +
                                                   " touches z = " + std::to_string(z) +
                                                   " m, not the ground (z = 0 within 5 mm): centaur starts there"});
    }
  }
  f.home_joints = Eigen::Map<const Eigen::VectorXd>(dd->qpos + 7, m->nq - 7);
  for (int i = 0; i < 7; ++i) dd->qpos[i] = i == 3 ? 1.0 : 0.0;
  mj_kinematics(m, dd);
  mj_comPos(m, dd);
}

void armMirrors(const RobotDescription& d, const MjcfView& v, RobotFacts& f, std::vector<Finding>& problems) {
  const Eigen::Vector3d M(1.0, -1.0, 1.0);
  for (std::size_t a = 0; a < d.arms.size(); ++a) {
    const int other = d.arms[a].mirrors.empty() ? -1 : d.armIndex(d.arms[a].mirrors);
    if (other < 0) continue;
    const std::string key = "upper_body.arms[" + std::to_string(a) + "].mirrors";
    for (std::size_t i = 0; i < v.arm_joints[a].size(); ++i) {
      const int j = v.arm_joints[a][i], o = v.arm_joints[other][i];
      const Eigen::Vector3d axis(Vec3C(v.d->xaxis + 3 * j)), axis_o(Vec3C(v.d->xaxis + 3 * o));
      const Eigen::Vector3d anchor(Vec3C(v.d->xanchor + 3 * j)), anchor_o(Vec3C(v.d->xanchor + 3 * o));
      const double s = -axis.dot(M.cwiseProduct(axis_o));
      if (std::abs(std::abs(s) - 1.0) > kMirrorTolerance || (anchor - M.cwiseProduct(anchor_o)).norm() > kMirrorTolerance) {
        problems.push_back({d.yaml_path, key, "joint '" + d.arms[a].joints[i] + "' is not the sagittal mirror image of '" +
                                                  d.arms[other].joints[i] + "' at home (axis or position)"});
      }
      f.arms[a].mirror_signs.push_back(s > 0.0 ? 1.0 : -1.0);
    }
  }
}

void pitchAuthority(const RobotDescription& d, const MjcfView& v, RobotFacts& f, std::vector<Finding>& warnings) {
  RobotModel model(d.mjcf_path);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.nq());
  q[3] = 1.0;
  q.tail(model.numJoints()) = f.home_joints;
  model.update(q, Eigen::VectorXd::Zero(model.nv()), RobotModel::Detail::kMomentum);
  RowMatrixXd A(6, model.nv());
  model.centroidalMomentumMatrix(A);
  f.pitch_inertia = A(4, 4);  // base angular rate about y (base frame = world here)
  f.limits = model.limits();
  for (std::size_t a = 0; a < d.arms.size(); ++a) {
    for (int j : v.arm_joints[a]) {
      const double h = A(4, v.m->jnt_dofadr[j]);
      f.arms[a].pitch_authority.push_back(h);
      f.arms[a].pitch_ratio.push_back(h / f.pitch_inertia);
    }
  }
  for (const auto& jn : d.raibert_joints) {
    const int j = mj_name2id(v.m, mjOBJ_JOINT, jn.c_str());
    const double h = A(4, v.m->jnt_dofadr[j]);
    f.raibert_directions.push_back(h >= 0.0 ? 1.0 : -1.0);
  }
  // A stabilizer is as strong as its strongest joint: warn when even that one barely moves the robot's pitch.
  for (const auto* list : {&d.raibert_joints, &d.angmom_joints}) {
    double best = 0.0;
    std::string best_joint;
    for (const auto& jn : *list) {
      const int j = mj_name2id(v.m, mjOBJ_JOINT, jn.c_str());
      const double ratio = std::abs(A(4, v.m->jnt_dofadr[j]) / f.pitch_inertia);
      if (ratio > best) best = ratio, best_joint = jn;
    }
    if (!list->empty() && best < kLowPitchAuthority) {
      char pct[32];
      std::snprintf(pct, sizeof pct, "%.2f %%", 100.0 * best);
      warnings.push_back({d.yaml_path, list == &d.raibert_joints ? "stabilizers.raibert" : "stabilizers.angmom",
                          "low pitch authority: its strongest joint '" + best_joint + "' gives " + pct +
                              " of the robot's pitch inertia per rad/s at home (below 1 %): the stabilizer can "
                              "do little"});
    }
  }
}

void applyOverrides(const RobotDescription& d, RobotFacts& f) {
  for (const auto& o : d.limits) {
    const auto it = std::find(f.joint_names.begin(), f.joint_names.end(), o.joint);
    const auto k = it - f.joint_names.begin();
    if (std::isfinite(o.q_min)) f.limits.q_min[k] = o.q_min;
    if (std::isfinite(o.q_max)) f.limits.q_max[k] = o.q_max;
    if (std::isfinite(o.qd_max)) f.limits.qd_max[k] = o.qd_max;
    if (std::isfinite(o.tau_max)) f.limits.tau_max[k] = o.tau_max;
  }
}

}  // namespace

RobotFacts deriveFacts(const RobotDescription& d, const MjcfView& v, std::vector<Finding>& problems,
                       std::vector<Finding>& warnings) {
  const mjModel* m = v.m;
  RobotFacts f;
  f.total_mass = m->body_subtreemass[v.base];
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] != mjJNT_HINGE) continue;
    f.joint_names.emplace_back(mj_id2name(m, mjOBJ_JOINT, j));
    const int leg = v.leg_of_body[m->jnt_bodyid[j]];
    if (leg >= 0) f.leg_joints[leg].push_back(f.joint_names.back());
  }
  homeKinematics(d, v, f, problems);
  model::TemplateParams& P = f.template_params;
  P.preset = "derived";
  P.gravity = -m->opt.gravity[2];
  lumpWaist(m, v.d, v, P);
  double legs = 0.0;
  for (int k = 0; k < 4; ++k) {
    f.leg_mass[k] = m->body_subtreemass[v.root[k]];
    legs += f.leg_mass[k];
    P.hip[k] = Vec3C(v.d->xpos + 3 * v.root[k]);
    f.b_p_foot[k] = Vec3C(v.d->site_xpos + 3 * v.centre[k]);
    const Mat3C R(v.d->xmat + 9 * v.contact[k]);
    f.centre_in_contact[k] = R.transpose() * (f.b_p_foot[k] - Vec3C(v.d->xpos + 3 * v.contact[k]));
    if (f.centre_in_contact[k].norm() < 1e-9) f.centre_in_contact[k].setZero();  // a site at the origin: exactly
    f.foot_radius[k] = v.radius[k];
  }
  P.foot_mass = legs / 4.0;
  for (int k = 0; k < 4; ++k) {
    if (std::abs(f.leg_mass[k] - P.foot_mass) > kLegMassSpread * P.foot_mass) {
      warnings.push_back({d.yaml_path, std::string("feet.") + kFootNames[k],
                          "leg mass " + std::to_string(f.leg_mass[k]) + " kg differs from the legs' mean " +
                              std::to_string(P.foot_mass) + " kg by more than 2 %: the template uses the mean"});
    }
  }
  f.arms.resize(d.arms.size());
  armMirrors(d, v, f, problems);
  pitchAuthority(d, v, f, warnings);
  applyOverrides(d, f);
  for (const auto& jn : f.joint_names) f.gain_group.push_back(d.gainsFor(jn)->group);
  return f;
}

}  // namespace centaur::robot::detail
