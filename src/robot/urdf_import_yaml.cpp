// The robot's structure guessed from a compiled URDF (feet, arms, IMU body, home height) and robot.yaml from it.
//
// Vocabulary: a body's subtree is a *chain* when the hinges in it lie on one path (every body of it has at most
// one child whose subtree holds a hinge; hinge-free side branches such as sensor frames are allowed). Legs: the
// four heaviest chains hanging from the first body (root first, depth first) that has at least four. Arms: the
// other maximal chains (their parent is no chain) with a hinge, the two heaviest. A chain's tip: follow the hinges
// down, then the deepest body below the last one (ties: the farthest from it at the zero posture).
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cctype>
#include <memory>

#include "common/excerpt.hpp"
#include "common/number_text.hpp"
#include "robot/robot_description.hpp"
#include "robot/urdf_import.hpp"

namespace centaur::robot::detail {

namespace {

constexpr double kAxisY = 0.8;               // |axis . y| above (within 37 deg of y): a pitch joint
constexpr double kMirrorTolerance = 0.05;    // as robot_facts.cpp: on axis signs and anchor positions [m]
constexpr double kLegGains[2] = {300.0, 3.0};  // conservative joint impedance [Nm/rad, Nm s/rad]
constexpr double kArmGains[2] = {100.0, 1.0};
constexpr double kOtherGains[2] = {100.0, 1.0};

using Vec3 = std::array<double, 3>;

struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

// The kinematic tree of the compiled model at its zero posture, positions and axes in the base frame.
struct Tree {
  const mjModel* m;
  int base = 1;
  std::vector<std::vector<int>> children;
  std::vector<int> hinges, depth;  // hinges in the subtree; depth below the world
  std::vector<bool> chain;
  std::vector<Vec3> pos;           // body origins
  std::vector<std::array<double, 9>> rot;  // body orientations (row major)
  std::vector<Vec3> axis, anchor;  // per joint

  explicit Tree(const mjModel* model);
  std::string name(int b) const { return mj_id2name(m, mjOBJ_BODY, b); }
  std::string joint(int j) const { return mj_id2name(m, mjOBJ_JOINT, j); }
  int hingeChild(int b) const {
    for (int c : children[b]) {
      if (hinges[c] > 0) return c;
    }
    return -1;
  }
  std::vector<int> chainJoints(int c) const;
  int tip(int c) const;
  double mass(int b) const { return m->body_subtreemass[b]; }
};

Tree::Tree(const mjModel* model) : m(model), children(m->nbody), hinges(m->nbody, 0), depth(m->nbody, 0),
                                   chain(m->nbody, true), pos(m->nbody), rot(m->nbody), axis(m->njnt), anchor(m->njnt) {
  for (int b = 1; b < m->nbody; ++b) {
    children[m->body_parentid[b]].push_back(b);
    depth[b] = depth[m->body_parentid[b]] + 1;
  }
  for (int j = 0; j < m->njnt; ++j) hinges[m->jnt_bodyid[j]] += m->jnt_type[j] == mjJNT_HINGE;
  for (int b = m->nbody - 1; b > 0; --b) {  // children have larger ids than their parent
    int with_hinges = 0;
    for (int c : children[b]) {
      with_hinges += hinges[c] > 0;
      chain[b] = chain[b] && chain[c];
    }
    chain[b] = chain[b] && with_hinges <= 1;
    hinges[m->body_parentid[b]] += hinges[b];
  }
  for (int c : children[0]) {  // the base: the heaviest tree hanging from the world
    if (m->body_subtreemass[c] > m->body_subtreemass[base]) base = c;
  }
  std::unique_ptr<mjData, DataDeleter> d(mj_makeData(m));
  mj_kinematics(m, d.get());  // qpos0: every hinge at zero
  const double* R = d->xmat + 9 * base;
  const double* o = d->xpos + 3 * base;
  auto toBase = [&](const double* v, bool point) {
    Vec3 out{};
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) out[r] += R[3 * k + r] * (v[k] - (point ? o[k] : 0.0));
    }
    return out;
  };
  for (int b = 0; b < m->nbody; ++b) {
    pos[b] = toBase(d->xpos + 3 * b, true);
    for (int r = 0; r < 3; ++r) {  // R_base^T R_b
      for (int c = 0; c < 3; ++c) {
        double v = 0.0;
        for (int k = 0; k < 3; ++k) v += R[3 * k + r] * d->xmat[9 * b + 3 * k + c];
        rot[b][3 * r + c] = v;
      }
    }
  }
  for (int j = 0; j < m->njnt; ++j) {
    axis[j] = toBase(d->xaxis + 3 * j, false);
    anchor[j] = toBase(d->xanchor + 3 * j, true);
  }
}

std::vector<int> Tree::chainJoints(int c) const {
  std::vector<int> out;
  for (int b = c; b >= 0; b = hingeChild(b)) {
    for (int j = m->body_jntadr[b]; j >= 0 && j < m->body_jntadr[b] + m->body_jntnum[b]; ++j) {
      if (m->jnt_type[j] == mjJNT_HINGE) out.push_back(j);
    }
  }
  return out;
}

double distance(const Vec3& a, const Vec3& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

int Tree::tip(int c) const {
  int last = c;
  while (hingeChild(last) >= 0) last = hingeChild(last);
  int best = last;
  for (int b = last + 1; b < m->nbody; ++b) {  // the subtree of `last`: the ids after it, while deeper
    if (depth[b] <= depth[last]) break;
    const bool deeper = depth[b] > depth[best];
    if (deeper || (depth[b] == depth[best] && distance(pos[b], pos[last]) > distance(pos[best], pos[last]) + 1e-9)) best = b;
  }
  return best;
}

// The first colliding sphere, capsule, cylinder or ellipsoid of `body` (what robot_check.cpp takes for the
// radius), -1 if none.
int contactGeom(const mjModel* m, int body) {
  for (int g = m->body_geomadr[body]; g >= 0 && g < m->body_geomadr[body] + m->body_geomnum[body]; ++g) {
    if (m->geom_contype[g] == 0 && m->geom_conaffinity[g] == 0) continue;
    const int t = m->geom_type[g];
    if (t == mjGEOM_SPHERE || t == mjGEOM_CAPSULE || t == mjGEOM_CYLINDER || t == mjGEOM_ELLIPSOID) return g;
  }
  return -1;
}

FootGuess makeFoot(const Tree& t, int root, const UrdfJoints& urdf) {
  const mjModel* m = t.m;
  FootGuess f;
  const int contact = t.tip(root);
  f.root = t.name(root);
  f.contact = t.name(contact);
  f.centre = f.contact + "_centre";
  for (int j : t.chainJoints(root)) f.joints.push_back(t.joint(j));
  const int g = contactGeom(m, contact);
  bool continuous = false;
  int hinge = -1;
  for (int j = m->body_jntadr[contact]; j >= 0 && j < m->body_jntadr[contact] + m->body_jntnum[contact]; ++j) {
    if (m->jnt_type[j] != mjJNT_HINGE) continue;
    hinge = j;
    const auto it = urdf.find(t.joint(j));
    continuous = it != urdf.end() && it->second.type == "continuous";
  }
  f.wheel = continuous || (g >= 0 && m->geom_type[g] == mjGEOM_CYLINDER);
  if (f.wheel && hinge >= 0) f.wheel_joint = t.joint(hinge);
  // The centre site: at the contact geom's centre (a wheel's axle, a point foot's sphere), else the body origin.
  if (g >= 0) {
    f.radius = m->geom_size[3 * g];
    for (int k = 0; k < 3; ++k) f.centre_pos[k] = m->geom_pos[3 * g + k];
  }
  const double* R = t.rot[contact].data();
  f.centre_z = t.pos[contact][2] + R[6] * f.centre_pos[0] + R[7] * f.centre_pos[1] + R[8] * f.centre_pos[2];
  return f;
}

// Legs in FL, FR, RL, RR order: the two front feet have the largest x, the left one of a pair the larger y.
void orderFeet(const Tree& t, std::vector<int>& roots) {
  auto x = [&](int r) { return t.pos[t.tip(r)][0]; };
  auto y = [&](int r) { return t.pos[t.tip(r)][1]; };
  std::stable_sort(roots.begin(), roots.end(), [&](int a, int b) { return x(a) > x(b); });
  if (y(roots[1]) > y(roots[0])) std::swap(roots[0], roots[1]);
  if (y(roots[3]) > y(roots[2])) std::swap(roots[2], roots[3]);
}

// The four leg roots, or none.
std::vector<int> findLegs(const Tree& t) {
  for (int b = t.base; b < t.m->nbody && (b == t.base || t.depth[b] > t.depth[t.base]); ++b) {
    std::vector<int> limbs;
    for (int c : t.children[b]) {
      if (t.hinges[c] > 0 && t.chain[c]) limbs.push_back(c);
    }
    if (limbs.size() < 4) continue;
    std::stable_sort(limbs.begin(), limbs.end(), [&](int a, int c) { return t.mass(a) > t.mass(c); });
    limbs.resize(4);
    orderFeet(t, limbs);
    return limbs;
  }
  return {};
}

bool mirrorImages(const Tree& t, const std::vector<int>& a, const std::vector<int>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Vec3 &ax = t.axis[a[i]], &bx = t.axis[b[i]], &ap = t.anchor[a[i]], &bp = t.anchor[b[i]];
    const double s = -(ax[0] * bx[0] - ax[1] * bx[1] + ax[2] * bx[2]);  // -a . (M b), M = diag(1, -1, 1)
    if (std::abs(std::abs(s) - 1.0) > kMirrorTolerance) return false;
    if (distance(ap, {bp[0], -bp[1], bp[2]}) > kMirrorTolerance) return false;
  }
  return true;
}

std::vector<ArmGuess> findArms(const Tree& t, const std::vector<int>& legs, std::vector<std::string>& warnings) {
  std::vector<int> roots;
  for (int c = 1; c < t.m->nbody; ++c) {
    const int parent = t.m->body_parentid[c];
    if (c == t.base || parent == 0 || t.hinges[c] == 0 || !t.chain[c] || t.chain[parent]) continue;
    if (std::find(legs.begin(), legs.end(), c) != legs.end()) continue;
    if (static_cast<int>(t.chainJoints(c).size()) > kMaxArmJoints) {
      warnings.push_back("chain from body '" + excerpt(t.name(c)) + "' has more than " + std::to_string(kMaxArmJoints) +
                         " hinges: not listed as an arm");
      continue;
    }
    roots.push_back(c);
  }
  std::stable_sort(roots.begin(), roots.end(), [&](int a, int b) { return t.mass(a) > t.mass(b); });
  for (std::size_t i = kMaxArms; i < roots.size(); ++i) {
    warnings.push_back("chain from body '" + excerpt(t.name(roots[i])) + "' is not listed as an arm (at most " +
                       std::to_string(kMaxArms) + ", the heaviest)");
  }
  if (roots.size() > static_cast<std::size_t>(kMaxArms)) roots.resize(kMaxArms);
  if (roots.size() == 2 && t.pos[t.tip(roots[1])][1] > t.pos[t.tip(roots[0])][1]) std::swap(roots[0], roots[1]);
  std::vector<ArmGuess> arms;
  for (std::size_t i = 0; i < roots.size(); ++i) {
    ArmGuess a;
    a.name = roots.size() == 1 ? "arm" : (i == 0 ? "left" : "right");
    a.tip_body = t.name(t.tip(roots[i]));
    a.tip_site = a.tip_body + "_tip";
    for (int j : t.chainJoints(roots[i])) a.joints.push_back(t.joint(j));
    arms.push_back(a);
  }
  if (roots.size() == 2 && mirrorImages(t, t.chainJoints(roots[1]), t.chainJoints(roots[0]))) arms[1].mirrors = "left";
  return arms;
}

// Hinges outside the chains (trunk, torso): the torso joints; and the arms' pitch joints (axis ~ y).
void torsoAndStabilizers(const Tree& t, RobotGuess& g, std::vector<std::string>& warnings) {
  for (int j = 0; j < t.m->njnt; ++j) {
    if (t.m->jnt_type[j] == mjJNT_HINGE && !t.chain[t.m->jnt_bodyid[j]]) g.torso_joints.push_back(t.joint(j));
  }
  for (const auto& a : g.arms) {
    for (const auto& jn : a.joints) {
      const int j = mj_name2id(t.m, mjOBJ_JOINT, jn.c_str());
      if (std::abs(t.axis[j][1]) > kAxisY) g.stabilizer_joints.push_back(jn);
    }
  }
  for (auto* list : {&g.torso_joints, &g.stabilizer_joints}) {
    if (list->size() > 16) {
      warnings.push_back("more than 16 " + std::string(list == &g.torso_joints ? "torso" : "stabilizer") +
                         " joints guessed: robot.yaml lists the first 16");
      list->resize(16);
    }
  }
}

// ---------------------------------------------------------------------------------------------------------------
// robot.yaml text, in the schema of models/centauro/robot.yaml (robot/robot_description.hpp).

const char* const kGuess = "  # GUESS: confirm";

// A YAML scalar: plain when it is made of name characters only and YAML would not read it as null or a boolean,
// else double-quoted.
std::string scalar(const std::string& s) {
  bool plain = !s.empty() && s.front() != '-';
  std::string low;
  for (char c : s) {
    plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == '/');
    low += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  for (const char* word : {"null", "true", "false", "yes", "no", "on", "off", "y", "n"}) plain = plain && low != word;
  if (plain) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string list(const std::vector<std::string>& names) {
  std::string out = "[";
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + scalar(names[i]);
  return out + "]";
}

// A joint name as an fnmatch(3) pattern that matches only itself.
std::string literalPattern(const std::string& name) {
  std::string out;
  for (char c : name) {
    if (c == '*' || c == '?' || c == '[' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

// One gain group over the joints `joints` (names; "*" for every other joint).
std::string gainLine(const std::string& group, const std::vector<std::string>& joints, const double* gains) {
  std::vector<std::string> patterns;
  for (const auto& j : joints) patterns.push_back(j == "*" ? j : literalPattern(j));
  return "  - {group: " + scalar(group) + ", joints: " + list(patterns) + ", kp: " + exactNumber(gains[0]) +
         ", kd: " + exactNumber(gains[1]) + "}  # GUESS: conservative gains, tune them\n";
}

std::string footLine(const char* name, const FootGuess& f) {
  std::string line = std::string("  ") + name + ": {root: " + scalar(f.root) + ", contact: " + scalar(f.contact) +
                     ", centre: " + scalar(f.centre) + ", type: " + (f.wheel ? "wheel" : "point");
  if (!f.wheel_joint.empty()) line += ", wheel_joint: " + scalar(f.wheel_joint);
  return line + ", radius: auto}" + kGuess + "\n";
}

std::string armLines(const ArmGuess& a) {
  std::string out = "    - name: " + scalar(a.name) + kGuess + "\n";
  out += "      joints: " + list(a.joints) + kGuess + "\n";
  out += "      end_effector: " + scalar(a.tip_site) + kGuess + "\n";
  if (!a.mirrors.empty()) out += "      mirrors: " + scalar(a.mirrors) + kGuess + "\n";
  return out;
}

}  // namespace

RobotGuess guessStructure(const mjModel* m, const UrdfJoints& joints, std::vector<std::string>& warnings) {
  const Tree t(m);
  RobotGuess g;
  g.base = t.name(t.base);
  for (int b = t.base; b < m->nbody && g.imu_body.empty(); ++b) {
    std::string n = t.name(b);
    std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (n.find("imu") != std::string::npos) g.imu_body = t.name(b);
  }
  if (g.imu_body.empty()) {
    g.imu_body = g.base;
    warnings.push_back("no body named like 'imu': the imu site is at the origin of the base '" + excerpt(g.base) + "'");
  }
  const std::vector<int> legs = findLegs(t);
  g.feet_found = legs.size() == 4;
  for (std::size_t k = 0; k < legs.size(); ++k) {
    g.feet[k] = makeFoot(t, legs[k], joints);
    if (g.feet[k].radius <= 0.0) {
      warnings.push_back(std::string("foot ") + kFootNames[k] + ": body '" + excerpt(g.feet[k].contact) +
                         "' has no colliding sphere, capsule or cylinder: give robot.yaml its radius");
    }
  }
  if (!g.feet_found) warnings.push_back("no body has four limbs (chains with a hinge): fill in robot.yaml's feet");
  g.arms = findArms(t, legs, warnings);
  torsoAndStabilizers(t, g, warnings);
  for (int j = 0; j < m->njnt; ++j) {
    const auto it = joints.find(t.joint(j));
    if (it == joints.end() || it->second.type != "continuous") continue;
    const bool wheel = std::any_of(g.feet.begin(), g.feet.end(), [&](const FootGuess& f) { return f.wheel_joint == t.joint(j); });
    if (!wheel) warnings.push_back("joint '" + excerpt(t.joint(j)) + "' is continuous but no wheel: give it a range");
  }
  // Home: the zero posture with the lowest foot centre at its contact radius above the ground (no feet: the
  // lowest body origin on the ground).
  double h = 0.0;
  if (g.feet_found) {
    const auto low = std::min_element(g.feet.begin(), g.feet.end(), [](const FootGuess& a, const FootGuess& b) { return a.centre_z < b.centre_z; });
    h = low->radius - low->centre_z;
  } else {
    for (int b = t.base; b < m->nbody; ++b) h = std::max(h, -t.pos[b][2]);
  }
  g.home_height = std::round(h * 1e6) / 1e6;
  return g;
}

std::string robotYaml(const std::string& name, const std::string& mjcf_file, const std::string& urdf_file,
                      const RobotGuess& g) {
  std::string y = "# " + name + ": the semantic layer of " + mjcf_file + ", imported by `centaur model import` from " +
                  urdf_file + ".\n# Every value marked GUESS was guessed from the URDF's kinematic tree: confirm or correct it, then check\n"
                  "# the robot with `centaur model check DIR`. Schema, defaults and ranges: docs/robots.md.\n";
  y += "name: " + scalar(name) + "\nmjcf: " + scalar(mjcf_file) + "\nbase: " + scalar(g.base) + "\n";
  y += "home: home  # GUESS: the home posture is the zero posture; set your robot's stand\n";
  y += "imu:\n  site: imu" + std::string(kGuess) + " (on body " + scalar(g.imu_body) + ")\n";
  y += "  orientation: imu_quat\n  gyro: imu_gyro\n  accelerometer: imu_acc\n";
  y += "feet:  # exactly FL, FR, RL, RR: the template's foot order\n";
  for (std::size_t k = 0; k < kFootNames.size(); ++k) {
    if (g.feet_found) {
      y += footLine(kFootNames[k], g.feet[k]);
    } else {
      y += std::string("  ") + kFootNames[k] + ": {root: TODO, contact: TODO, centre: TODO, type: point, radius: auto}" +
           "  # GUESS: no four legs found, fill in\n";
    }
  }
  y += "upper_body:\n  torso_joints: " + list(g.torso_joints) + kGuess + "\n";
  y += g.arms.empty() ? "  arms: []" + std::string(kGuess) + "\n" : "  arms:\n";
  for (const auto& a : g.arms) y += armLines(a);
  y += "stabilizers:  # the arm joints each upper-body stabilizer moves (guess: those turning about y)\n";
  y += "  raibert: " + list(g.stabilizer_joints) + kGuess + "\n";
  y += "  angmom: " + list(g.stabilizer_joints) + kGuess + "\n";
  y += "gains:  # joint impedance groups, the first whose pattern (fnmatch) matches a joint wins\n";
  if (g.feet_found) {
    for (std::size_t k = 0; k < kFootNames.size(); ++k) {
      std::string group = std::string("leg_") + kFootNames[k];
      std::transform(group.begin(), group.end(), group.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      y += gainLine(group, g.feet[k].joints, kLegGains);
    }
  }
  for (const auto& a : g.arms) y += gainLine("arm_" + a.name, a.joints, kArmGains);
  y += gainLine("other", {"*"}, kOtherGains);
  y += "limits: {}  # per joint overrides of the MJCF's: {JOINT: {q_min, q_max, qd_max, tau_max}}\n";
  return y;
}

}  // namespace centaur::robot::detail
