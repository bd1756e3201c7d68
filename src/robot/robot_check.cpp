// checkRobot(): robot.yaml's names against the MJCF, MuJoCo 2.2.2's limits, then the derivation.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <regex>

#include "common/error.hpp"
#include "common/excerpt.hpp"
#include "common/input_file.hpp"
#include "model/mjcf_load.hpp"
#include "robot/mjcf_view.hpp"

namespace centaur::robot {

std::string Finding::text() const {
  return key.empty() ? file + ": " + message : file + ": key '" + key + "': " + message;
}

namespace detail {
bool inSubtree(const mjModel* m, int b, int ancestor) {
  for (; b > 0; b = m->body_parentid[b]) {
    if (b == ancestor) return true;
  }
  return b == ancestor;
}
}  // namespace detail

namespace {

using detail::inSubtree;
using detail::MjcfView;

// MJCF features that Debian's MuJoCo 2.2.2 refuses, with what to do instead (measured: docs/robots.md).
struct Unsupported {
  const char* pattern;
  const char* advice;
};
const Unsupported kUnsupported[] = {
    {R"(\bactuatorfrcrange\s*=)", "joint attribute actuatorfrcrange: give the motor a ctrlrange instead"},
    {R"(\bactuatorgravcomp\s*=)", "attribute actuatorgravcomp: remove it (centaur compensates gravity itself)"},
    {R"(\binheritrange\s*=)", "attribute inheritrange: centaur needs torque motors (<motor ctrlrange=...>)"},
    {R"(<position\b[^>]*\bkv\s*=)", "<position kv=...>: centaur needs torque motors (<motor ctrlrange=...>)"},
    {R"(\bellipsoidinertia\b)", "<global ellipsoidinertia>: remove it"},
    {R"(\bimplicitfast\b)", "integrator implicitfast: use Euler (what centaur's simulator sets)"},
    {R"(<frame\b)", "the <frame> element: fold its pose into the children"},
    {R"(<replicate\b)", "the <replicate> element: write the copies out"},
    {R"(<jointactuatorfrc\b)", "the <jointactuatorfrc> sensor: remove it (centaur logs the torques itself)"},
};

int lineOf(const std::string& text, std::size_t pos) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
}

void scanUnsupported(const RobotDescription& d, std::vector<Finding>& problems) {
  std::string text;
  try {
    text = readSmallFile(d.mjcf_path, 64u << 20, "an MJCF model");
  } catch (const InputError& e) {
    problems.push_back({d.yaml_path, "mjcf", e.what()});
    return;
  }
  for (const auto& u : kUnsupported) {
    std::smatch match;
    if (std::regex_search(text, match, std::regex(u.pattern))) {
      problems.push_back({d.mjcf_path, "", "line " + std::to_string(lineOf(text, match.position(0))) +
                                               ": MuJoCo 2.2.2 does not load " + u.advice});
    }
  }
}

struct Checker {
  const RobotDescription& d;
  MjcfView& v;
  std::vector<Finding>& problems;
  const mjModel* m() const { return v.m; }

  void fail(const std::string& key, const std::string& msg) { problems.push_back({d.yaml_path, key, msg}); }
  void failModel(const std::string& msg) { problems.push_back({d.mjcf_path, "", msg}); }
  int id(int type, const std::string& key, const std::string& name, const char* what) {
    const int i = mj_name2id(m(), type, name.c_str());
    if (i < 0) fail(key, std::string("no ") + what + " '" + excerpt(name) + "' in " + d.mjcf_path);
    return i;
  }
  const char* jointName(int j) const { return mj_id2name(m(), mjOBJ_JOINT, j); }
  int hinge(const std::string& key, const std::string& name) {
    const int j = id(mjOBJ_JOINT, key, name, "joint");
    if (j >= 0 && m()->jnt_type[j] != mjJNT_HINGE) fail(key, "joint '" + excerpt(name) + "' is not a hinge");
    return j >= 0 && m()->jnt_type[j] == mjJNT_HINGE ? j : -1;
  }

  void joints();
  void imu();
  void feet();
  void arms();
  void lists();
  void actuators();
};

void Checker::joints() {
  int free_joint = -1;
  for (int j = 0; j < m()->njnt; ++j) {
    if (m()->jnt_type[j] == mjJNT_FREE) {
      if (free_joint >= 0) failModel("more than one free joint: centaur needs one floating base");
      free_joint = j;
    } else if (m()->jnt_type[j] != mjJNT_HINGE) {
      failModel(std::string("joint '") + jointName(j) + "' is not a hinge: only hinges besides the free joint");
    }
  }
  v.base = id(mjOBJ_BODY, "base", d.base, "body");
  if (free_joint < 0) {
    failModel("no free joint: the base needs <freejoint/> (a URDF import drops the floating base)");
  } else if (m()->jnt_qposadr[free_joint] != 0 || (v.base >= 0 && m()->jnt_bodyid[free_joint] != v.base)) {
    fail("base", "the free joint must be the first joint and sit on body '" + excerpt(d.base) + "'");
  }
  v.home_key = id(mjOBJ_KEY, "home", d.home, "keyframe");
  for (int b = 1; b < m()->nbody; ++b) {
    if (m()->body_jntnum[b] > 0 && !(m()->body_mass[b] > mjMINVAL && m()->body_inertia[3 * b] > 0.0)) {
      failModel(std::string("body '") + mj_id2name(m(), mjOBJ_BODY, b) + "' moves but has no mass or inertia");
    }
  }
}

void Checker::imu() {
  v.imu_site = id(mjOBJ_SITE, "imu.site", d.imu.site, "site");
  const std::pair<const std::string*, int> sensors[] = {{&d.imu.orientation, mjSENS_FRAMEQUAT},
                                                         {&d.imu.gyro, mjSENS_GYRO},
                                                         {&d.imu.accelerometer, mjSENS_ACCELEROMETER}};
  const char* keys[] = {"imu.orientation", "imu.gyro", "imu.accelerometer"};
  const char* kinds[] = {"a framequat", "a gyro", "an accelerometer"};
  for (int k = 0; k < 3; ++k) {
    const int s = id(mjOBJ_SENSOR, keys[k], *sensors[k].first, "sensor");
    if (s < 0) continue;
    if (m()->sensor_type[s] != sensors[k].second) fail(keys[k], std::string("sensor '") + *sensors[k].first + "' is not " + kinds[k] + " sensor");
    if (m()->sensor_objtype[s] != mjOBJ_SITE || m()->sensor_objid[s] != v.imu_site) {
      fail(keys[k], "sensor '" + excerpt(*sensors[k].first) + "' is not attached to site '" + excerpt(d.imu.site) + "'");
    }
  }
}

// The contact geom's radius (sphere, capsule, cylinder, ellipsoid: size[0]); -1 if the body has none.
double contactRadius(const mjModel* m, int body) {
  for (int g = m->body_geomadr[body]; g >= 0 && g < m->body_geomadr[body] + m->body_geomnum[body]; ++g) {
    if (m->geom_contype[g] == 0 && m->geom_conaffinity[g] == 0) continue;
    const int t = m->geom_type[g];
    if (t == mjGEOM_SPHERE || t == mjGEOM_CAPSULE || t == mjGEOM_CYLINDER || t == mjGEOM_ELLIPSOID) return m->geom_size[3 * g];
  }
  return -1.0;
}

void Checker::feet() {
  v.leg_of_body.assign(m()->nbody, -1);
  for (int k = 0; k < 4; ++k) {
    const FootSpec& f = d.feet[k];
    const std::string key = std::string("feet.") + f.name;
    v.root[k] = id(mjOBJ_BODY, key + ".root", f.root, "body");
    v.contact[k] = id(mjOBJ_BODY, key + ".contact", f.contact, "body");
    v.centre[k] = id(mjOBJ_SITE, key + ".centre", f.centre, "site");
    v.wheel_joint[k] = f.wheel_joint.empty() ? -1 : hinge(key + ".wheel_joint", f.wheel_joint);
    if (v.root[k] < 0 || v.contact[k] < 0) continue;
    if (v.root[k] == v.base || v.root[k] == 0) fail(key + ".root", "the leg's root must be a body below the base");
    if (!inSubtree(m(), v.contact[k], v.root[k])) fail(key + ".contact", "body '" + excerpt(f.contact) + "' is not in the leg of '" + excerpt(f.root) + "'");
    if (v.centre[k] >= 0 && !inSubtree(m(), m()->site_bodyid[v.centre[k]], v.root[k])) {
      fail(key + ".centre", "site '" + excerpt(f.centre) + "' is not in the leg of '" + excerpt(f.root) + "'");
    }
    if (v.wheel_joint[k] >= 0 && m()->jnt_bodyid[v.wheel_joint[k]] != v.contact[k]) {
      fail(key + ".wheel_joint", "joint '" + excerpt(f.wheel_joint) + "' does not turn the contact body");
    }
    v.radius[k] = f.radius > 0.0 ? f.radius : contactRadius(m(), v.contact[k]);
    if (v.radius[k] <= 0.0) fail(key + ".radius", "auto: body '" + excerpt(f.contact) + "' has no colliding sphere, capsule or cylinder; give the radius");
    for (int b = 1; b < m()->nbody; ++b) {
      if (!inSubtree(m(), b, v.root[k])) continue;
      if (v.leg_of_body[b] >= 0) fail(key + ".root", "its leg overlaps the leg of foot " + std::string(kFootNames[v.leg_of_body[b]]));
      v.leg_of_body[b] = k;
    }
  }
}

void Checker::arms() {
  for (std::size_t a = 0; a < d.arms.size(); ++a) {
    const ArmSpec& arm = d.arms[a];
    const std::string key = "upper_body.arms[" + std::to_string(a) + "]";
    std::vector<int> ids;
    int previous = v.base;
    for (const auto& jn : arm.joints) {
      const int j = hinge(key + ".joints", jn);
      ids.push_back(j);
      if (j < 0) continue;
      const int b = m()->jnt_bodyid[j];
      if (!v.leg_of_body.empty() && v.leg_of_body[b] >= 0) fail(key + ".joints", "joint '" + excerpt(jn) + "' is in a leg");
      if (previous >= 0 && (b == previous || !inSubtree(m(), b, previous))) {
        fail(key + ".joints", "joint '" + excerpt(jn) + "' does not follow the previous one down the chain");
      }
      previous = b;
    }
    int tip = mj_name2id(m(), mjOBJ_SITE, arm.end_effector.c_str());
    tip = tip >= 0 ? m()->site_bodyid[tip] : mj_name2id(m(), mjOBJ_BODY, arm.end_effector.c_str());
    if (tip < 0) fail(key + ".end_effector", "no site or body '" + excerpt(arm.end_effector) + "' in " + d.mjcf_path);
    else if (previous >= 0 && !inSubtree(m(), tip, previous)) fail(key + ".end_effector", "is not below the arm's last joint");
    v.arm_joints.push_back(ids);
    v.arm_tip_body.push_back(tip);
  }
}

void Checker::lists() {
  for (const auto& t : d.torso_joints) hinge("upper_body.torso_joints", t);
  auto armJoint = [&](const std::string& j) {
    for (const auto& a : d.arms) {
      if (std::find(a.joints.begin(), a.joints.end(), j) != a.joints.end()) return true;
    }
    return false;
  };
  for (const auto& [key, list] : {std::pair<const char*, const std::vector<std::string>*>{"stabilizers.raibert", &d.raibert_joints},
                                  {"stabilizers.angmom", &d.angmom_joints}}) {
    for (const auto& j : *list) {
      if (!armJoint(j)) fail(key, "joint '" + excerpt(j) + "' is not a joint of an arm (upper_body.arms)");
    }
  }
  for (const auto& o : d.limits) {
    if (mj_name2id(m(), mjOBJ_JOINT, o.joint.c_str()) < 0) fail("limits." + o.joint, "no such joint in " + d.mjcf_path);
  }
  for (int j = 0; j < m()->njnt; ++j) {
    if (m()->jnt_type[j] != mjJNT_HINGE) continue;
    if (!d.gainsFor(jointName(j))) fail("gains", std::string("joint '") + jointName(j) + "' matches no group's pattern (end with {group: other, joints: [\"*\"]})");
    const bool wheel = std::find(v.wheel_joint.begin(), v.wheel_joint.end(), j) != v.wheel_joint.end();
    if (!m()->jnt_limited[j] && !wheel) {
      failModel(std::string("joint '") + jointName(j) + "' has no range (limits): only a foot's wheel_joint may turn freely");
    }
  }
}

void Checker::actuators() {
  std::vector<int> motors(m()->njnt, 0);
  for (int a = 0; a < m()->nu; ++a) {
    const char* nm = mj_id2name(m(), mjOBJ_ACTUATOR, a);
    const std::string name = nm ? nm : "#" + std::to_string(a);
    const bool torque = m()->actuator_trntype[a] == mjTRN_JOINT && m()->actuator_dyntype[a] == mjDYN_NONE &&
                        m()->actuator_gaintype[a] == mjGAIN_FIXED && m()->actuator_biastype[a] == mjBIAS_NONE;
    if (!torque) {
      failModel("actuator '" + name + "' is not a torque motor (a servo or muscle): centaur commands joint torques (<motor>)");
    } else if (!m()->actuator_ctrllimited[a]) {
      failModel("motor '" + name + "' has no ctrlrange: centaur reads the effort limit from it");
    }
    if (m()->actuator_trntype[a] == mjTRN_JOINT) ++motors[m()->actuator_trnid[2 * a]];
  }
  for (int j = 0; j < m()->njnt; ++j) {
    if (m()->jnt_type[j] != mjJNT_HINGE) continue;
    if (motors[j] != 1) failModel(std::string("joint '") + jointName(j) + "' has " + std::to_string(motors[j]) + " motors (needs exactly one)");
  }
}

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
  void operator()(mjData* d) const { mj_deleteData(d); }
};

}  // namespace

CheckResult checkRobot(const RobotDescription& d) {
  CheckResult out;
  scanUnsupported(d, out.problems);
  std::unique_ptr<mjModel, ModelDeleter> model;
  try {
    model.reset(loadMjcf(d.mjcf_path, /*discard_visual=*/false));
  } catch (const std::exception& e) {
    out.problems.push_back({d.yaml_path, "mjcf", e.what()});
    return out;
  }
  std::unique_ptr<mjData, ModelDeleter> data(mj_makeData(model.get()));
  MjcfView v;
  v.m = model.get();
  v.d = data.get();
  Checker c{d, v, out.problems};
  c.joints();
  c.imu();
  c.feet();
  c.arms();
  c.lists();
  c.actuators();
  if (!out.problems.empty()) return out;
  RobotFacts facts = detail::deriveFacts(d, v, out.problems, out.warnings);
  if (out.problems.empty()) out.facts = std::move(facts);
  return out;
}

RobotFacts robotFacts(const RobotDescription& d) {
  CheckResult r = checkRobot(d);
  if (!r.problems.empty()) {
    std::string msg = d.yaml_path + ": the robot description has " + std::to_string(r.problems.size()) + " problem(s):";
    for (const auto& p : r.problems) msg += "\n  " + p.text();
    throw InputError(msg);
  }
  return *r.facts;
}

}  // namespace centaur::robot
