// centaur model check NAME|PATH [--json]
// Validates a robot description (robot.yaml + its MJCF, docs/robots.md) and prints what centaur derives from
// it: the template's parameters, the feet, the limits, each arm joint's pitch authority, with the warnings;
// or every problem found (exit 2). With --json the last stdout line is one object (SI units, see factsJson).
// centaur model import ROBOT.urdf --out DIR [--json]
// A URDF becomes DIR/<name>.xml (MuJoCo's URDF compiler, plus a free joint, torque motors, sites, sensors and a
// home keyframe) and DIR/robot.yaml with every guess marked; then the pair is checked as by `model check`.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/command.hpp"
#include "common/error.hpp"
#include "robot/robot_facts.hpp"
#include "robot/robot_registry.hpp"
#include "robot/urdf_import.hpp"
#include "model/mjcf_load.hpp"

namespace centaur::cli {
namespace {

struct ModelArgs {
  std::string action, path, out;
  bool json = false;
};

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
nlohmann::json finiteOrNull(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json findings(const std::vector<robot::Finding>& list) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& f : list) j.push_back({{"file", f.file}, {"key", f.key}, {"message", f.message}});
  return j;
}

nlohmann::json factsJson(const robot::RobotDescription& d, const robot::RobotFacts& f) {
  const auto& P = f.template_params;
  const Eigen::Matrix3d& I = P.waist_inertia;
  nlohmann::json feet = nlohmann::json::array();
  for (int k = 0; k < 4; ++k) {
    feet.push_back({{"name", robot::kFootNames[k]}, {"type", robot::footTypeName(d.feet[k].type)},
                    {"leg_mass_kg", f.leg_mass[k]}, {"hip_m", vec(P.hip[k])}, {"centre_home_m", vec(f.b_p_foot[k])},
                    {"radius_m", f.foot_radius[k]}});
  }
  nlohmann::json arms = nlohmann::json::array();
  for (std::size_t a = 0; a < d.arms.size(); ++a) {
    nlohmann::json joints = nlohmann::json::array();
    for (std::size_t i = 0; i < d.arms[a].joints.size(); ++i) {
      joints.push_back({{"name", d.arms[a].joints[i]},
                        {"pitch_authority", f.arms[a].pitch_authority[i]},
                        {"pitch_ratio", f.arms[a].pitch_ratio[i]},
                        {"mirror_sign", f.arms[a].mirror_signs.empty() ? nlohmann::json(nullptr)
                                                                        : nlohmann::json(f.arms[a].mirror_signs[i])}});
    }
    arms.push_back({{"name", d.arms[a].name}, {"mirrors", d.arms[a].mirrors}, {"joints", joints}});
  }
  nlohmann::json limits = nlohmann::json::array();
  for (std::size_t j = 0; j < f.joint_names.size(); ++j) {
    limits.push_back({{"joint", f.joint_names[j]}, {"gain_group", f.gain_group[j]},
                      {"q_min", finiteOrNull(f.limits.q_min[j])}, {"q_max", finiteOrNull(f.limits.q_max[j])},
                      {"qd_max", finiteOrNull(f.limits.qd_max[j])}, {"tau_max", finiteOrNull(f.limits.tau_max[j])}});
  }
  return {{"total_mass_kg", f.total_mass},
          {"joints", f.joint_names.size()},
          {"home_base_height_m", f.home_base_height},
          {"pitch_inertia_kg_m2", f.pitch_inertia},
          {"template", {{"waist_mass", P.waist_mass}, {"waist_com", vec(P.waist_com)},
                        {"waist_inertia", {I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)}},
                        {"foot_mass", P.foot_mass}, {"gravity", P.gravity}}},
          {"feet", feet},
          {"arms", arms},
          {"raibert_directions", f.raibert_directions},
          {"limits", limits}};
}

void printFacts(const robot::RobotDescription& d, const robot::RobotFacts& f) {
  const auto& P = f.template_params;
  const Eigen::Matrix3d& I = P.waist_inertia;
  std::printf("robot %s (%s), hash %s\n", d.name.c_str(), d.mjcf_path.c_str(), d.hash.c_str());
  std::printf("  %.3f kg, %zu joints, base %.4f m high at home, pitch inertia %.3f kg m^2\n", f.total_mass,
              f.joint_names.size(), f.home_base_height, f.pitch_inertia);
  std::printf("template (derived)\n  waist %.3f kg, CoM (%.4f, %.4f, %.4f) m\n", P.waist_mass, P.waist_com.x(),
              P.waist_com.y(), P.waist_com.z());
  std::printf("  inertia Ixx Iyy Izz %.3f %.3f %.3f, Ixy Ixz Iyz %.3f %.3f %.3f kg m^2\n", I(0, 0), I(1, 1), I(2, 2),
              I(0, 1), I(0, 2), I(1, 2));
  std::printf("  feet %.3f kg (mean of the legs)\n", P.foot_mass);
  for (int k = 0; k < 4; ++k) {
    std::printf("  %s %-5s leg %.3f kg, hip (%.4f, %.4f, %.4f), centre at home (%.4f, %.4f, %.4f), radius %.4f m\n",
                robot::kFootNames[k], robot::footTypeName(d.feet[k].type), f.leg_mass[k], P.hip[k].x(), P.hip[k].y(),
                P.hip[k].z(), f.b_p_foot[k].x(), f.b_p_foot[k].y(), f.b_p_foot[k].z(), f.foot_radius[k]);
  }
  for (std::size_t a = 0; a < d.arms.size(); ++a) {
    std::printf("arm %s (%zu joints%s%s): pitch authority [kg m^2/s per rad/s] (%% of the pitch inertia)\n",
                d.arms[a].name.c_str(), d.arms[a].joints.size(), d.arms[a].mirrors.empty() ? "" : ", mirrors ",
                d.arms[a].mirrors.c_str());
    for (std::size_t i = 0; i < d.arms[a].joints.size(); ++i) {
      std::printf("  %-16s %+8.4f (%5.2f %%)%s\n", d.arms[a].joints[i].c_str(), f.arms[a].pitch_authority[i],
                  100.0 * std::abs(f.arms[a].pitch_ratio[i]),
                  f.arms[a].mirror_signs.empty() ? "" : (f.arms[a].mirror_signs[i] > 0 ? "  mirror +1" : "  mirror -1"));
    }
  }
}

int runCheck(const ModelArgs& a) {
  const robot::RobotDescription d = robot::loadRobot(a.path);
  const robot::CheckResult r = robot::checkRobot(d);
  for (const auto& w : r.warnings) std::cerr << "warning: " << w.text() << "\n";
  for (const auto& p : r.problems) std::cerr << "error: " << p.text() << "\n";
  if (!a.json && r.facts) printFacts(d, *r.facts);
  if (!a.json && !r.problems.empty()) std::printf("%zu problem(s): the description is not usable\n", r.problems.size());
  if (a.json) {
    nlohmann::json j = {{"robot", d.name}, {"file", d.yaml_path}, {"mjcf", d.mjcf_path}, {"hash", d.hash},
                        {"ok", r.problems.empty()}, {"problems", findings(r.problems)},
                        {"warnings", findings(r.warnings)}};
    if (r.facts) j["derived"] = factsJson(d, *r.facts);
    printJsonLine(j);
  }
  return r.problems.empty() ? kExitOk : kExitBadInput;
}

int runImport(const ModelArgs& a) {
  if (a.out.empty()) throw InputError("model import: --out DIR is required (where <name>.xml and robot.yaml go)");
  installMujocoHandlers();
  const robot::UrdfImportReport rep = robot::importUrdf(a.path, a.out);
  for (const auto& w : rep.warnings) std::cerr << "warning: " << w << "\n";
  const robot::RobotDescription d = robot::readRobotDescription(rep.yaml_path);
  const robot::CheckResult r = robot::checkRobot(d);
  for (const auto& w : r.warnings) std::cerr << "warning: " << w.text() << "\n";
  for (const auto& p : r.problems) std::cerr << "to fix: " << p.text() << "\n";
  if (!a.json) {
    std::printf("%s: %d joints, %.3f kg -> %s, %s (%zu import warnings; confirm every '# GUESS' in robot.yaml)\n",
                a.path.c_str(), rep.hinge_joints, rep.total_mass, rep.mjcf_path.c_str(), rep.yaml_path.c_str(),
                rep.warnings.size());
    if (!r.problems.empty()) std::printf("%zu problem(s) left for `centaur model check` (listed above)\n", r.problems.size());
  } else {
    printJsonLine(nlohmann::json{{"robot", rep.name}, {"mjcf", rep.mjcf_path}, {"robot_yaml", rep.yaml_path},
                                 {"joints", rep.hinge_joints}, {"total_mass_kg", rep.total_mass},
                                 {"import_warnings", rep.warnings}, {"ok", r.problems.empty()},
                                 {"problems", findings(r.problems)}, {"warnings", findings(r.warnings)}});
  }
  return kExitOk;
}

const Registrar registrar{Command{
    "model", "Check a robot description (robot.yaml + MJCF) and print what centaur derives from it; import a URDF",
    [](CLI::App& sub) -> std::function<int()> {
      auto a = std::make_shared<ModelArgs>();
      sub.add_option("action", a->action, "check: validate a robot; import: a URDF into a robot folder")
          ->required()
          ->check(CLI::IsMember({"check", "import"}));
      sub.add_option("robot", a->path, "check: a shipped robot's name (models/NAME/), a robot.yaml or its folder; "
                                       "import: the URDF")
          ->required();
      sub.add_option("--out", a->out, "import: the folder to write <name>.xml and robot.yaml into");
      sub.add_flag("--json", a->json, "print one JSON object last on stdout (check: {robot, ok, problems, warnings, "
                                      "derived}; import: {robot, mjcf, robot_yaml, joints, total_mass_kg, ...})");
      return [a]() { return a->action == "import" ? runImport(*a) : runCheck(*a); };
    }}};

}  // namespace
}  // namespace centaur::cli
