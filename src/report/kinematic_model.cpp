#include "report/kinematic_model.hpp"

#include <mujoco/mujoco.h>

#include <cmath>
#include <limits>

#include "common/error.hpp"
#include "model/mjcf_load.hpp"

namespace centaur::report {

KinematicModel::KinematicModel(const std::string& mjcf_path) : path_(mjcf_path) {
  model_ = loadMjcf(mjcf_path, false);  // InputError naming the file
  data_ = mj_makeData(model_);
  for (int j = 0; j < model_->njnt; ++j) {
    if (model_->jnt_type[j] == mjJNT_FREE) {
      free_qpos_ = model_->jnt_qposadr[j];
      moving_.push_back(model_->jnt_bodyid[j]);
      break;
    }
  }
  if (free_qpos_ < 0) {
    mj_deleteData(data_);
    mj_deleteModel(model_);
    throw InputError(mjcf_path + ": the model has no free joint (a report replays a floating-base robot)");
  }
  for (int b = 0; b < model_->nbody; ++b) {  // the world body's own geoms (ground plane) are static too
    if (model_->body_geomnum[b] == 0 || b == moving_.front()) continue;
    (model_->body_weldid[b] == 0 ? static_ : moving_).push_back(b);
  }
}

KinematicModel::~KinematicModel() {
  mj_deleteData(data_);
  mj_deleteModel(model_);
}

std::string KinematicModel::bodyName(int body) const {
  const char* n = mj_id2name(model_, mjOBJ_BODY, body);
  return n != nullptr ? n : "body_" + std::to_string(body);
}

int KinematicModel::bodyId(const std::string& name) const { return mj_name2id(model_, mjOBJ_BODY, name.c_str()); }

std::vector<int> KinematicModel::jointAddresses(const std::vector<std::string>& names, const std::string& file,
                                                const std::string& key) const {
  std::vector<int> out;
  for (const std::string& n : names) {
    const int j = mj_name2id(model_, mjOBJ_JOINT, n.c_str());
    if (j < 0) throw InputError(file, key, "joint '" + n + "' is not a joint of the model " + path_);
    if (model_->jnt_type[j] != mjJNT_HINGE && model_->jnt_type[j] != mjJNT_SLIDE) {
      throw InputError(file, key, "joint '" + n + "' of the model " + path_ + " is not a hinge or slide joint");
    }
    out.push_back(model_->jnt_qposadr[j]);
  }
  return out;
}

std::vector<double> KinematicModel::effortLimits(const std::vector<std::string>& names) const {
  std::vector<double> out(names.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < names.size(); ++i) {
    const int j = mj_name2id(model_, mjOBJ_JOINT, names[i].c_str());
    for (int a = 0; j >= 0 && a < model_->nu; ++a) {
      if (model_->actuator_trntype[a] != mjTRN_JOINT || model_->actuator_trnid[2 * a] != j) continue;
      if (!model_->actuator_ctrllimited[a]) continue;
      const double range = std::max(std::abs(model_->actuator_ctrlrange[2 * a]),
                                    std::abs(model_->actuator_ctrlrange[2 * a + 1]));
      out[i] = range * std::abs(model_->actuator_gear[6 * a]);
    }
  }
  return out;
}

double KinematicModel::contactRadius(int body) const {
  for (int g = model_->body_geomadr[body]; g < model_->body_geomadr[body] + model_->body_geomnum[body]; ++g) {
    if (model_->geom_contype[g] != 0 || model_->geom_conaffinity[g] != 0) return model_->geom_size[3 * g];
  }
  return 0.0;
}

std::vector<double> KinematicModel::boxHalfExtents(int body) const {
  for (int g = model_->body_geomadr[body]; g < model_->body_geomadr[body] + model_->body_geomnum[body]; ++g) {
    if (model_->geom_type[g] == mjGEOM_BOX) return {model_->geom_size + 3 * g, model_->geom_size + 3 * g + 3};
  }
  return {0.0, 0.0, 0.0};
}

void KinematicModel::placeWall(double wall_x) {
  const int wall = mj_name2id(model_, mjOBJ_BODY, "wall");
  if (wall > 0) model_->body_pos[3 * wall] = wall_x;
}

void KinematicModel::bodyPoses(const double* w_p_base, const double* w_quat_base, const double* q,
                               const std::vector<int>& addresses, std::vector<double>& out) {
  for (int i = 0; i < model_->nq; ++i) data_->qpos[i] = model_->qpos0[i];
  for (int k = 0; k < 3; ++k) data_->qpos[free_qpos_ + k] = w_p_base[k];
  double norm = 0.0;
  for (int k = 0; k < 4; ++k) norm += w_quat_base[k] * w_quat_base[k];
  norm = std::sqrt(norm);
  const bool valid = std::isfinite(norm) && norm > 0.0;  // a zero or NaN quaternion: drawn unrotated
  for (int k = 0; k < 4; ++k) data_->qpos[free_qpos_ + 3 + k] = valid ? w_quat_base[k] / norm : (k == 0 ? 1.0 : 0.0);
  for (std::size_t i = 0; i < addresses.size(); ++i) data_->qpos[addresses[i]] = q[i];
  mj_kinematics(model_, data_);
  for (int b : moving_) {
    out.insert(out.end(), data_->xpos + 3 * b, data_->xpos + 3 * b + 3);
    out.insert(out.end(), data_->xquat + 4 * b, data_->xquat + 4 * b + 4);
  }
}

std::vector<double> KinematicModel::staticPoses() {
  for (int i = 0; i < model_->nq; ++i) data_->qpos[i] = model_->qpos0[i];
  mj_kinematics(model_, data_);
  std::vector<double> out;
  for (int b : static_) {
    out.insert(out.end(), data_->xpos + 3 * b, data_->xpos + 3 * b + 3);
    out.insert(out.end(), data_->xquat + 4 * b, data_->xquat + 4 * b + 4);
  }
  return out;
}

}  // namespace centaur::report
