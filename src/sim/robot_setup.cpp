#include "sim/robot_setup.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace centaur::sim {

namespace {

// A number as YAML text with `digits` decimals: a derived value that equals a typed one gives its exact double.
std::string fixed(double x, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}

std::string fileName(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

SimRobot loadSimRobot(const std::string& name_or_path) {
  robot::LoadedRobot loaded = robot::loadRobotWithFacts(name_or_path);
  SimRobot r{std::move(loaded.description), std::move(loaded.facts), RobotFrames()};
  const robot::RobotDescription& d = r.description;
  RobotFrames& f = r.frames;
  f.base = d.base;
  f.imu = d.imu.site;
  f.wheel_joints.clear();
  for (int k = 0; k < 4; ++k) {
    f.contact_bodies[k] = d.feet[k].contact;
    f.foot_centres[k] = d.feet[k].centre;
    f.centre_offsets[k] = r.facts->centre_in_contact[k];
    f.foot_radius[k] = r.facts->foot_radius[k];
    f.leg_joints[k] = r.facts->leg_joints[k];
    if (!d.feet[k].wheel_joint.empty()) f.wheel_joints.push_back(d.feet[k].wheel_joint);
  }
  for (const auto& g : d.gains) f.gain_patterns.push_back({g.group, g.patterns});
  f.angmom_joints = d.angmom_joints;
  return r;
}

std::string sceneXml(const robot::RobotDescription& d) {
  return "<mujoco model=\"" + d.name + " in centaur's scene\">\n"
         "  <include file=\"" + fileName(d.mjcf_path) + "\"/>\n"
         "  <visual><global offwidth=\"1280\" offheight=\"720\"/><quality shadowsize=\"4096\"/></visual>\n"
         "  <asset>\n"
         "    <texture name=\"centaur_grid\" type=\"2d\" builtin=\"checker\" rgb1=\"0.75 0.78 0.8\" rgb2=\"0.6 0.63 0.66\"\n"
         "             width=\"512\" height=\"512\"/>\n"
         "    <material name=\"centaur_grid\" texture=\"centaur_grid\" texrepeat=\"8 8\" reflectance=\"0.05\"/>\n"
         "  </asset>\n"
         "  <worldbody>\n"
         "    <light name=\"centaur_sun\" directional=\"true\" pos=\"0 0 5\" dir=\"-0.3 0.4 -1\" diffuse=\"0.7 0.7 0.7\"/>\n"
         "    <geom name=\"ground\" type=\"plane\" size=\"20 20 0.1\" contype=\"0\" conaffinity=\"1\" condim=\"3\"\n"
         "          friction=\"1.0 0.005 0.0001\" material=\"centaur_grid\"/>\n"
         "    <body name=\"wall\" pos=\"-5 0 0\">\n"
         "      <geom name=\"wall\" type=\"box\" size=\"0.05 1 1\" pos=\"-0.05 0 1\" contype=\"0\" conaffinity=\"1\"\n"
         "            condim=\"3\" friction=\"1.0 0.005 0.0001\" rgba=\"0.7 0.55 0.4 1\"/>\n"
         "    </body>\n"
         "    <camera name=\"side\" mode=\"trackcom\" pos=\"0.1 -3.2 0.9\" xyaxes=\"1 0 0 0 0.15 1\"/>\n"
         "  </worldbody>\n"
         "</mujoco>\n";
}

namespace {

// A key's value, or a null node (a default-constructed node is null, and null converts to true: test present()).
bool present(const YAML::Node& n) { return n.IsDefined() && !n.IsNull(); }
YAML::Node child(const YAML::Node& n, const std::string& key) {
  return present(n) && n.IsMap() && n[key] ? n[key] : YAML::Node();
}

// `value` at `path` of `layer`, unless `defaults` holds the same there (a layer of differences only: a robot whose
// derived values are the defaults' leaves the configuration as it is, text included). Reads go through const
// nodes: yaml-cpp's non-const operator[] inserts the keys it looks up.
void setIfDifferent(YAML::Node& layer, const YAML::Node& defaults, const std::vector<std::string>& path,
                    const std::string& value) {
  YAML::Node d = YAML::Clone(defaults);
  for (const auto& key : path) {
    const YAML::Node& cd = d;
    const YAML::Node next = present(cd) && cd.IsMap() && cd[key] ? YAML::Clone(cd[key]) : YAML::Node();
    d = next;
  }
  if (present(d) && d.IsScalar()) {
    try {
      if (d.as<double>() == std::stod(value)) return;
    } catch (const std::exception&) {
      if (d.Scalar() == value) return;
    }
  }
  YAML::Node n = layer;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) n.reset(n[path[i]]);
  n[path.back()] = value;
}

// The robot's impedance groups as a controller.gains mapping, or null when the defaults have exactly these.
YAML::Node gainsIfDifferent(const robot::RobotDescription& d, const YAML::Node& defaults) {
  YAML::Node gains(YAML::NodeType::Map);
  bool same = present(defaults) && defaults.IsMap() && defaults.size() == d.gains.size();
  for (const auto& g : d.gains) {
    gains[g.group]["kp"] = g.kp;
    gains[g.group]["kd"] = g.kd;
    const YAML::Node o = child(defaults, g.group);
    same = same && present(child(o, "kp")) && present(child(o, "kd")) && o["kp"].as<double>() == g.kp &&
           o["kd"].as<double>() == g.kd;
  }
  return same ? YAML::Node() : gains;
}

}  // namespace

YAML::Node simRobotLayer(const SimRobot& r, const YAML::Node& defaults) {
  const robot::RobotFacts& f = *r.facts;
  YAML::Node layer(YAML::NodeType::Map);
  setIfDifferent(layer, defaults, {"push", "body"}, r.description.base);
  setIfDifferent(layer, defaults, {"outcome", "fall_height"},
                 fixed(0.05 * std::floor(f.home_base_height / 2.0 / 0.05 + 1e-9), 2));
  const double rear_x = 0.5 * (f.b_p_foot[2].x() + f.b_p_foot[3].x());
  setIfDifferent(layer, defaults, {"world", "wall_x"}, fixed(rear_x - 0.15 - f.foot_radius[2], 4));
  const YAML::Node controller = child(defaults, "controller");
  if (present(child(controller, "wheel_radius"))) {
    setIfDifferent(layer, defaults, {"controller", "wheel_radius"}, fixed(f.foot_radius[0], 4));
  }
  if (present(child(controller, "gains"))) {
    const YAML::Node gains = gainsIfDifferent(r.description, controller["gains"]);
    if (present(gains)) layer["controller"]["gains"] = gains;
  }
  const YAML::Node raibert = child(controller, "raibert");
  if (present(child(raibert, "joints"))) {  // the robot's Raibert joints, their derived directions
    const auto& joints = r.description.raibert_joints;
    const YAML::Node gains = child(raibert, "gains");
    const bool same_count = present(gains) && gains.size() == joints.size();
    bool same = same_count && raibert["joints"].size() == joints.size() && present(child(raibert, "directions"));
    YAML::Node out(YAML::NodeType::Map);
    for (std::size_t i = 0; i < joints.size(); ++i) {
      out["joints"].push_back(joints[i]);
      out["directions"].push_back(f.raibert_directions[i]);
      out["gains"].push_back(same_count ? gains[i].as<double>() : 1.0);
      same = same && raibert["joints"][i].as<std::string>() == joints[i] &&
             raibert["directions"][i].as<double>() == f.raibert_directions[i];
    }
    if (!same) layer["controller"]["raibert"] = out;
  }
  return layer;
}

}  // namespace centaur::sim
