#include "model/template_params.hpp"

#include <Eigen/Eigenvalues>

namespace centaur::model {

Eigen::Matrix3d inertiaFromList(const Eigen::Matrix<double, 6, 1>& v) {
  Eigen::Matrix3d I;
  I << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
  return I;
}

std::vector<std::string> templatePresetNames() { return {"centauro", "centauro-authors"}; }

TemplateParams templatePreset(const std::string& name) {
  TemplateParams P;
  P.preset = name;
  if (name == "centauro") {
    P.waist_mass = 50.293;
    P.waist_com = Eigen::Vector3d(0.194, 0.0005, 0.224);
    Eigen::Matrix<double, 6, 1> I;
    I << 3.049, 3.177, 4.046, 0.0, -0.560, 0.0;
    P.waist_inertia = inertiaFromList(I);
    P.foot_mass = 10.705;
    P.foot_inertia = Eigen::Matrix3d::Identity() * 0.04;
    P.hip = {Eigen::Vector3d(0.25, 0.125, -0.0566), Eigen::Vector3d(0.25, -0.125, -0.0566),
             Eigen::Vector3d(-0.25, 0.125, -0.0566), Eigen::Vector3d(-0.25, -0.125, -0.0566)};
  } else if (name == "centauro-authors") {
    P.waist_mass = 69.0;
    P.waist_com = Eigen::Vector3d(0.16, 0.0, 0.0);
    P.waist_inertia = Eigen::Vector3d(1.0417, 1.875, 2.1667).asDiagonal();
    P.foot_mass = 10.0;
    P.foot_inertia = Eigen::Matrix3d::Identity() * 0.04;
    P.hip = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  } else {
    std::string list;
    for (const auto& n : templatePresetNames()) list += (list.empty() ? "" : ", ") + n;
    throw InputError("model preset '" + name + "' is unknown; allowed: " + list);
  }
  return P;
}

TemplateParams readTemplateParams(YamlReader r, const TemplateParams* derived) {
  std::string preset = "centauro";
  std::vector<std::string> allowed = templatePresetNames();
  if (derived) allowed.push_back("derived");
  r.get("preset", preset, allowed);
  TemplateParams P = preset == "derived" ? *derived : templatePreset(preset);
  P.preset = preset;
  r.get("waist_mass", P.waist_mass, 1e-3, 1000.0);
  Eigen::VectorXd com = P.waist_com;
  r.get("waist_com", com, -2.0, 2.0);
  P.waist_com = com;
  Eigen::VectorXd I(6);
  I << P.waist_inertia(0, 0), P.waist_inertia(1, 1), P.waist_inertia(2, 2), P.waist_inertia(0, 1),
      P.waist_inertia(0, 2), P.waist_inertia(1, 2);
  r.get("waist_inertia", I, -1000.0, 1000.0);
  P.waist_inertia = inertiaFromList(I);
  if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(P.waist_inertia).eigenvalues().minCoeff() <= 0.0) {
    r.fail("waist_inertia", "must be positive definite ([ixx, iyy, izz, ixy, ixz, iyz], kg m^2)");
  }
  r.get("foot_mass", P.foot_mass, 1e-3, 1000.0);
  Eigen::VectorXd If(6);
  If << P.foot_inertia(0, 0), P.foot_inertia(1, 1), P.foot_inertia(2, 2), P.foot_inertia(0, 1), P.foot_inertia(0, 2),
      P.foot_inertia(1, 2);
  r.get("foot_inertia", If, -1000.0, 1000.0);
  P.foot_inertia = inertiaFromList(If);
  if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(P.foot_inertia).eigenvalues().minCoeff() < 0.0) {
    r.fail("foot_inertia", "must be positive semi-definite ([ixx, iyy, izz, ixy, ixz, iyz], kg m^2)");
  }
  r.getPoints("hip_offsets", P.hip.data(), 4, -2.0, 2.0, "points in the waist frame (FL, FR, RL, RR), in m,");
  r.get("gravity", P.gravity, 0.0, 100.0);
  r.finish();
  return P;
}

}  // namespace centaur::model
