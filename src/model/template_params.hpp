#pragma once
// Template-model presets and their YAML form (section `model:` of a planner configuration).
//
//   model:
//     preset: centauro            # centauro | centauro-authors | derived (lumped from the robot's MJCF by
//                                 # robot/robot_facts.hpp); every other key overrides
//     waist_mass: 50.293          # [kg]            (0, 1000]
//     waist_com: [x, y, z]        # [m] in B        each in [-2, 2]
//     waist_inertia: [ixx, iyy, izz, ixy, ixz, iyz]  # [kg m^2] about the waist CoM; must be positive definite
//     foot_mass: 10.705           # [kg] each foot  (0, 1000]
//     foot_inertia: [ixx, iyy, izz, ixy, ixz, iyz]   # [kg m^2] about the foot point; positive semi-definite
//     hip_offsets: [[x, y, z] x4] # [m] leg origins in B, order FL, FR, RL, RR; each in [-2, 2]
//     gravity: 9.81               # [m/s^2]         [0, 100]
//
// Presets:
//   centauro          lumped from the 93.1 kg robot (reference MODEL.md, home posture): waist = pelvis + torso +
//                     arms (50.293 kg, CoM (0.194, 0.0005, 0.224), inertia about its CoM), each leg (10.705 kg)
//                     lumped at its wheel centre, legs attached at the hip-yaw joints (+-0.25, +-0.125, -0.0566).
//   centauro-authors  the paper authors' template: waist 69 kg with CoM x = +0.16 m, inertia
//                     diag(1.0417, 1.875, 2.1667), 10 kg feet with inertia 0.04 I, legs from the waist origin.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "common/yaml_reader.hpp"
#include "model/template_model.hpp"

namespace centaur::model {

/// Names of the shipped presets.
std::vector<std::string> templatePresetNames();
/// A preset by name; throws InputError for an unknown name.
TemplateParams templatePreset(const std::string& name);
/// Read `model:` (preset + overrides) with range checks; throws InputError naming file and key. Preset
/// `derived` is the robot's own template (robot/robot_facts.hpp), given as `derived` (nullptr: not allowed).
TemplateParams readTemplateParams(YamlReader reader, const TemplateParams* derived = nullptr);
/// Symmetric 3x3 from [ixx, iyy, izz, ixy, ixz, iyz].
Eigen::Matrix3d inertiaFromList(const Eigen::Matrix<double, 6, 1>& v);

}  // namespace centaur::model
