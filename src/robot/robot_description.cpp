#include "robot/robot_description.hpp"

#include <fnmatch.h>
#include <sys/stat.h>

#include <cmath>

#include "common/error.hpp"
#include "common/excerpt.hpp"
#include "common/input_file.hpp"
#include "common/yaml_reader.hpp"

namespace centaur::robot {

namespace {

constexpr std::size_t kMaxMjcfBytes = 64u << 20;  // a robot MJCF without meshes is < 1 MiB; meshes are separate

bool isDirectory(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

std::string folderOf(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

bool validName(const std::string& s) {
  if (s.empty() || s.size() > 64) return false;
  for (char c : s) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-')) return false;
  }
  return true;
}

// A required, non-empty string key.
std::string requireString(YamlReader& r, const std::string& key) {
  if (!r.has(key)) r.fail(key, "is required");
  std::string v;
  r.get(key, v);
  if (v.empty()) r.fail(key, "must not be empty");
  return v;
}

// A list of names (possibly empty); `max` bounds its length.
std::vector<std::string> readNames(YamlReader& r, const std::string& key, bool required, std::size_t max) {
  if (!r.has(key)) {
    if (required) r.fail(key, "is required");
    return {};
  }
  const YAML::Node n = r.raw(key);
  if (!n.IsSequence()) r.fail(key, "expected a list of names");
  if (n.size() > max) r.fail(key, "at most " + std::to_string(max) + " names (has " + std::to_string(n.size()) + ")");
  std::vector<std::string> out;
  for (const auto& item : n) {
    if (!item.IsScalar() || item.Scalar().empty()) r.fail(key, "every item must be a non-empty name");
    for (const auto& seen : out) {
      if (seen == item.Scalar()) r.fail(key, "name '" + excerpt(seen) + "' appears twice");
    }
    out.push_back(item.Scalar());
  }
  return out;
}

FootSpec readFoot(YamlReader f, const std::string& name) {
  FootSpec s;
  s.name = name;
  s.root = requireString(f, "root");
  s.contact = requireString(f, "contact");
  s.centre = requireString(f, "centre");
  std::string type = "wheel";
  if (!f.has("type")) f.fail("type", "is required (wheel or point)");
  f.get("type", type, {"wheel", "point"});
  s.type = type == "wheel" ? FootType::kWheel : FootType::kPoint;
  if (f.has("wheel_joint")) {
    if (s.type != FootType::kWheel) f.fail("wheel_joint", "only a foot of type wheel has a wheel joint");
    s.wheel_joint = requireString(f, "wheel_joint");
  }
  if (f.has("radius")) {
    const YAML::Node n = f.raw("radius");
    if (!(n.IsScalar() && n.Scalar() == "auto")) {
      double r = -1.0;
      try {
        r = n.as<double>();
      } catch (const YAML::Exception&) {
        f.fail("radius", "expected auto or a number in [0.001, 1] (m)");
      }
      if (!(r >= 0.001 && r <= 1.0)) f.fail("radius", "expected auto or a number in [0.001, 1] (m)");
      s.radius = r;
    }
  }
  f.finish();
  return s;
}

void readFeet(YamlReader& r, RobotDescription& d) {
  if (!r.has("feet")) r.fail("feet", "is required: FL, FR, RL, RR");
  YamlReader feet = r.child("feet");
  for (std::size_t k = 0; k < kFootNames.size(); ++k) {
    if (!feet.has(kFootNames[k])) {
      feet.fail(kFootNames[k], "is missing: a robot has exactly four feet, FL, FR, RL, RR (the template's order)");
    }
    d.feet[k] = readFoot(feet.child(kFootNames[k]), kFootNames[k]);
  }
  feet.finish();
}

ArmSpec readArm(YamlReader a) {
  ArmSpec s;
  s.name = requireString(a, "name");
  s.joints = readNames(a, "joints", true, 1000);
  if (s.joints.empty() || static_cast<int>(s.joints.size()) > kMaxArmJoints) {
    a.fail("joints", "an arm has 1 to " + std::to_string(kMaxArmJoints) + " joints (has " +
                         std::to_string(s.joints.size()) + ")");
  }
  s.end_effector = requireString(a, "end_effector");
  if (a.has("mirrors")) s.mirrors = requireString(a, "mirrors");
  a.finish();
  return s;
}

void readUpperBody(YamlReader u, RobotDescription& d) {
  d.torso_joints = readNames(u, "torso_joints", false, 16);
  if (u.has("arms")) {
    const YAML::Node arms = u.raw("arms");
    if (!arms.IsSequence()) u.fail("arms", "expected a list of arms");
    if (arms.size() > static_cast<std::size_t>(kMaxArms)) {
      u.fail("arms", "at most " + std::to_string(kMaxArms) + " arms (has " + std::to_string(arms.size()) + ")");
    }
    for (std::size_t i = 0; i < arms.size(); ++i) {
      if (!arms[i].IsMap()) u.fail("arms", "every arm is a mapping {name, joints, end_effector[, mirrors]}");
      d.arms.push_back(readArm(YamlReader(arms[i], u.file(), u.full("arms[" + std::to_string(i) + "]"))));
    }
  }
  u.finish();
  for (std::size_t i = 0; i < d.arms.size(); ++i) {
    const std::string key = "upper_body.arms[" + std::to_string(i) + "]";
    for (std::size_t j = 0; j < i; ++j) {
      if (d.arms[j].name == d.arms[i].name) throw InputError(d.yaml_path, key + ".name", "two arms are called '" + excerpt(d.arms[i].name) + "'");
    }
    const std::string& m = d.arms[i].mirrors;
    if (m.empty()) continue;
    const int k = d.armIndex(m);
    if (k < 0 || k == static_cast<int>(i)) throw InputError(d.yaml_path, key + ".mirrors", "names no other arm: '" + excerpt(m) + "'");
    if (d.arms[k].joints.size() != d.arms[i].joints.size()) {
      throw InputError(d.yaml_path, key + ".mirrors", "arm '" + excerpt(m) + "' has another number of joints");
    }
  }
}

void readGains(YamlReader& r, RobotDescription& d) {
  if (!r.has("gains")) r.fail("gains", "is required: a list of {group, joints, kp, kd}");
  const YAML::Node g = r.raw("gains");
  if (!g.IsSequence() || g.size() == 0) r.fail("gains", "expected a non-empty list of {group, joints, kp, kd}");
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (!g[i].IsMap()) r.fail("gains", "every item is a mapping {group, joints, kp, kd}");
    YamlReader item(g[i], r.file(), "gains[" + std::to_string(i) + "]");
    GainGroup gg;
    gg.group = requireString(item, "group");
    gg.patterns = readNames(item, "joints", true, 1000);
    if (gg.patterns.empty()) item.fail("joints", "must list at least one joint-name pattern");
    if (!item.has("kp")) item.fail("kp", "is required, in [0, 1e5] Nm/rad");
    if (!item.has("kd")) item.fail("kd", "is required, in [0, 1e3] Nm s/rad");
    item.get("kp", gg.kp, 0.0, 1e5);
    item.get("kd", gg.kd, 0.0, 1e3);
    item.finish();
    for (const auto& other : d.gains) {
      if (other.group == gg.group) item.fail("group", "group '" + excerpt(gg.group) + "' appears twice");
    }
    d.gains.push_back(std::move(gg));
  }
}

void readLimits(YamlReader& r, RobotDescription& d) {
  if (!r.has("limits")) return;
  const YAML::Node l = r.raw("limits");
  if (!(l.IsMap() || l.IsNull())) r.fail("limits", "expected a mapping {JOINT: {q_min, q_max, qd_max, tau_max}}");
  YamlReader limits(l, r.file(), "limits");
  for (const auto& kv : l) {
    const std::string joint = kv.first.as<std::string>();
    YamlReader j = limits.child(joint);
    LimitOverride o;
    o.joint = joint;
    j.get("q_min", o.q_min, -100.0, 100.0);
    j.get("q_max", o.q_max, -100.0, 100.0);
    j.get("qd_max", o.qd_max, 1e-3, 1e4);
    j.get("tau_max", o.tau_max, 1e-3, 1e5);
    j.finish();
    if (std::isfinite(o.q_min) && std::isfinite(o.q_max) && !(o.q_min < o.q_max)) {
      j.fail("q_max", "must be above q_min");
    }
    d.limits.push_back(o);
  }
  limits.finish();
}

}  // namespace

const char* footTypeName(FootType t) { return t == FootType::kWheel ? "wheel" : "point"; }

std::uint64_t fnv1a64(const std::string& bytes, std::uint64_t h) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

const GainGroup* RobotDescription::gainsFor(const std::string& joint) const {
  for (const auto& g : gains) {
    for (const auto& p : g.patterns) {
      if (::fnmatch(p.c_str(), joint.c_str(), 0) == 0) return &g;
    }
  }
  return nullptr;
}

int RobotDescription::armIndex(const std::string& arm) const {
  for (std::size_t i = 0; i < arms.size(); ++i) {
    if (arms[i].name == arm) return static_cast<int>(i);
  }
  return -1;
}

RobotDescription readRobotDescription(const std::string& path) {
  RobotDescription d;
  d.yaml_path = isDirectory(path) ? path + "/robot.yaml" : path;
  const std::string text = readSmallFile(d.yaml_path, YamlLimits::kMaxBytes, "a robot description (robot.yaml)");
  YamlReader r(loadYamlString(text, d.yaml_path), d.yaml_path);
  d.name = requireString(r, "name");
  if (!validName(d.name)) r.fail("name", "1 to 64 characters of a-z, 0-9, _ and - (is '" + excerpt(d.name) + "')");
  const std::string mjcf = requireString(r, "mjcf");
  d.mjcf_path = mjcf.front() == '/' ? mjcf : folderOf(d.yaml_path) + "/" + mjcf;
  d.base = requireString(r, "base");
  d.home = requireString(r, "home");
  std::string scene = "centaur";
  r.get("scene", scene, {"centaur", "mjcf"});
  d.scene_in_mjcf = scene == "mjcf";
  if (!r.has("imu")) r.fail("imu", "is required: {site, orientation, gyro, accelerometer}");
  {
    YamlReader imu = r.child("imu");
    d.imu.site = requireString(imu, "site");
    d.imu.orientation = requireString(imu, "orientation");
    d.imu.gyro = requireString(imu, "gyro");
    d.imu.accelerometer = requireString(imu, "accelerometer");
    imu.finish();
  }
  readFeet(r, d);
  readUpperBody(r.child("upper_body"), d);
  {
    YamlReader s = r.child("stabilizers");
    d.raibert_joints = readNames(s, "raibert", false, 16);
    d.angmom_joints = readNames(s, "angmom", false, 16);
    s.finish();
  }
  readGains(r, d);
  readLimits(r, d);
  r.finish();
  const std::string mjcf_bytes = readSmallFile(d.mjcf_path, kMaxMjcfBytes, "the MJCF named by key 'mjcf' of " + d.yaml_path);
  static const char* kHex = "0123456789abcdef";
  std::uint64_t h = fnv1a64(mjcf_bytes, fnv1a64(text));
  d.hash.assign(16, '0');
  for (int i = 15; i >= 0; --i, h >>= 4) d.hash[i] = kHex[h & 0xF];
  return d;
}

}  // namespace centaur::robot
