// importUrdf(): the URDF checked and pre-processed with tinyxml2, compiled by MuJoCo's URDF compiler, saved as
// MJCF, then completed (free joint, motors, velocity limits, sites, sensors, keyframe) and written with robot.yaml.
#include "robot/urdf_import.hpp"

#include <mujoco/mujoco.h>
#include <tinyxml2.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/cleanup.hpp"
#include "common/error.hpp"
#include "common/excerpt.hpp"
#include "common/input_file.hpp"
#include "common/number_text.hpp"

namespace centaur::robot {

namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;
using detail::RobotGuess;
using detail::UrdfJoint;
using detail::UrdfJoints;

constexpr std::size_t kMaxUrdfBytes = 64u << 20;  // xacro output of a large robot is a few MiB; meshes are separate
constexpr const char* kTimestep = "0.0005";        // 2 kHz, what centaur's simulator runs

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
  void operator()(mjVFS* v) const {
    mj_deleteVFS(v);
    delete v;
  }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;

// mj_saveLastXML saves MuJoCo's process-wide "last loaded XML": loading and saving must not interleave.
std::mutex& lastXmlMutex() {
  static std::mutex m;
  return m;
}

std::string inQuotes(const std::string& s) { return "'" + excerpt(s) + "'"; }

std::string attr(const XMLElement* e, const char* name) {
  const char* v = e ? e->Attribute(name) : nullptr;
  return v ? v : "";
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// ---------------------------------------------------------------------------------------------------------------
// The URDF: parsed, checked, pre-processed for MuJoCo.

struct Urdf {
  XMLDocument doc;
  std::string name;  // sanitized
  UrdfJoints joints;
};

UrdfJoint readJoint(const std::string& path, const XMLElement* j, int& floating) {
  UrdfJoint out;
  out.type = attr(j, "type");
  const std::string name = attr(j, "name");
  if (out.type != "revolute" && out.type != "continuous" && out.type != "fixed" && out.type != "floating") {
    throw InputError(excerpt(path, 4 * kMaxExcerpt) + ": joint " + inQuotes(name) + " is of type " + inQuotes(out.type) +
                     ": centaur imports revolute, continuous, fixed and floating joints only");
  }
  if (out.type == "floating" && ++floating > 1) {
    throw InputError(excerpt(path, 4 * kMaxExcerpt) + ": joint " + inQuotes(name) +
                     " is a second floating joint: centaur needs one floating base");
  }
  if (const XMLElement* limit = j->FirstChildElement("limit")) {
    limit->QueryDoubleAttribute("effort", &out.effort);
    limit->QueryDoubleAttribute("velocity", &out.velocity);
  }
  return out;
}

void parseUrdf(const std::string& path, Urdf& u) {
  const std::string text = readSmallFile(path, kMaxUrdfBytes, "a URDF robot description");
  const std::string where = excerpt(path, 4 * kMaxExcerpt);
  if (u.doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    throw InputError(where + ": not a URDF: not XML (" + excerpt(u.doc.ErrorStr(), 200) + ")");
  }
  const XMLElement* robot = u.doc.RootElement();
  if (!robot || std::strcmp(robot->Name(), "robot") != 0) {
    throw InputError(where + ": not a URDF: the root element is <" + excerpt(robot ? robot->Name() : "") +
                     ">, not <robot>");
  }
  if (!robot->FirstChildElement("link")) throw InputError(where + ": the URDF has no <link>");
  u.name = sanitizeRobotName(attr(robot, "name"));
  int floating = 0;
  for (const XMLElement* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    u.joints[attr(j, "name")] = readJoint(path, j, floating);
  }
}

// The file a URDF <mesh filename> names, absolute; "" if it cannot be found. `package://pkg/rest` is looked
// for as <urdf dir>/../rest (a ROS package: pkg/urdf/robot.urdf next to pkg/meshes) and <urdf dir>/rest.
std::string resolveMesh(std::string name, const fs::path& urdf_dir) {
  std::vector<fs::path> candidates;
  if (name.rfind("file://", 0) == 0) name = name.substr(7);
  if (name.rfind("package://", 0) == 0) {
    const std::string rest = name.substr(10);
    const std::size_t slash = rest.find('/');
    if (slash == std::string::npos) return "";
    candidates = {urdf_dir / ".." / rest.substr(slash + 1), urdf_dir / rest.substr(slash + 1)};
  } else if (!name.empty()) {
    candidates = {fs::path(name).is_absolute() ? fs::path(name) : urdf_dir / name};
  }
  for (const fs::path& c : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(c, ec)) return c.lexically_normal().string();
  }
  return "";
}

// Drops every <visual>/<collision> of `link` whose mesh cannot be found or read by MuJoCo 2.2.2 (STL, OBJ and
// MSH only); the others get the mesh's absolute path, so the saved MJCF finds it from any directory.
void fixMeshes(XMLElement* link, const fs::path& urdf_dir, std::vector<std::string>& warnings) {
  const std::string link_name = attr(link, "name");
  for (const char* tag : {"visual", "collision"}) {
    for (XMLElement *e = link->FirstChildElement(tag), *next = nullptr; e; e = next) {
      next = e->NextSiblingElement(tag);
      XMLElement* geometry = e->FirstChildElement("geometry");
      XMLElement* mesh = geometry ? geometry->FirstChildElement("mesh") : nullptr;
      if (!mesh) continue;
      const std::string file = attr(mesh, "filename");
      const std::string found = resolveMesh(file, urdf_dir);
      const std::string ext = lower(fs::path(found).extension().string());
      const std::string head = "link " + inQuotes(link_name) + ": mesh " + inQuotes(file);
      if (found.empty()) {
        warnings.push_back(head + " not found, dropped");
      } else if (ext != ".stl" && ext != ".obj" && ext != ".msh") {
        warnings.push_back(head + " is not STL, OBJ or MSH (all MuJoCo 2.2.2 reads), dropped");
      } else {
        mesh->SetAttribute("filename", found.c_str());
        continue;
      }
      link->DeleteChild(e);
    }
  }
}

// The URDF as MuJoCo is to compile it: meshes fixed, links without inertia warned about, and the compiler options
// that keep every fixed link a body (IMU link, wheel centres, tips: centaur's sites go there) and take the
// inertia from <inertial> only.
std::string preprocess(const std::string& path, Urdf& u, std::vector<std::string>& warnings) {
  std::error_code ec;
  const fs::path urdf_dir = fs::absolute(fs::path(path), ec).parent_path();
  XMLElement* robot = u.doc.RootElement();
  for (XMLElement* link = robot->FirstChildElement("link"); link; link = link->NextSiblingElement("link")) {
    fixMeshes(link, urdf_dir, warnings);
    const std::string name = attr(link, "name");
    if (name != "world" && !link->FirstChildElement("inertial")) {
      warnings.push_back("link " + inQuotes(name) + ": no <inertial>, massless");
    }
  }
  XMLElement* mujoco = robot->FirstChildElement("mujoco");
  if (!mujoco) mujoco = robot->InsertFirstChild(u.doc.NewElement("mujoco"))->ToElement();
  XMLElement* compiler = mujoco->FirstChildElement("compiler");
  if (!compiler) compiler = mujoco->InsertFirstChild(u.doc.NewElement("compiler"))->ToElement();
  compiler->SetAttribute("fusestatic", "false");
  compiler->SetAttribute("discardvisual", "false");
  compiler->SetAttribute("balanceinertia", "true");
  compiler->SetAttribute("strippath", "false");
  compiler->SetAttribute("inertiafromgeom", "false");
  tinyxml2::XMLPrinter printer;
  u.doc.Print(&printer);
  return printer.CStr();
}

// ---------------------------------------------------------------------------------------------------------------
// MuJoCo: compile from text (a virtual file under the file's own name, so nothing is written), save as MJCF.

std::string oneLine(const char* error) {
  std::string why(error);
  while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
  for (char& c : why) c = c == '\n' ? ' ' : c;
  return excerpt(why, 400);
}

// Compiles `text` as if it were the file `path`; nullptr with `error` set if MuJoCo refuses it.
ModelPtr compileText(const std::string& path, const std::string& text, std::string& error) {
  std::unique_ptr<mjVFS, ModelDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  const std::string name = fs::path(path).filename().string();
  if (mj_makeEmptyFileVFS(vfs.get(), name.c_str(), static_cast<int>(text.size())) != 0) {
    throw RuntimeError("MuJoCo cannot hold " + excerpt(path) + " in memory");
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name.c_str())], text.data(), text.size());
  char err[1000] = "";
  ModelPtr m(mj_loadXML(path.c_str(), vfs.get(), err, sizeof err));
  if (!m) error = oneLine(err);
  return m;
}

// MuJoCo's MJCF of the model it compiled last (mj_saveLastXML), through a temporary file (registered for cleanup).
std::string saveLastXml(const mjModel* m) {
  static std::atomic<int> counter{0};
  const std::string tmp = (fs::temp_directory_path() / ("centaur-urdf-import." + std::to_string(::getpid()) + "." +
                                                         std::to_string(counter++) + ".xml")).string();
  cleanup::addFile(tmp);
  char err[1000] = "";
  const int ok = mj_saveLastXML(tmp.c_str(), m, err, sizeof err);
  std::ifstream in(tmp, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  removeFileIfExists(tmp);
  if (!ok || text.str().empty()) throw RuntimeError("MuJoCo cannot save the compiled URDF as MJCF: " + oneLine(err));
  return text.str();
}

// ---------------------------------------------------------------------------------------------------------------
// The saved MJCF completed for centaur.

// tinyxml2's printer with MuJoCo's two-space indentation.
class Printer : public tinyxml2::XMLPrinter {
 protected:
  void PrintSpace(int depth) override {
    for (int i = 0; i < depth; ++i) Write("  ");
  }
};

XMLElement* child(XMLDocument& doc, XMLElement* parent, const char* tag, XMLElement* after) {
  if (XMLElement* e = parent->FirstChildElement(tag)) return e;
  XMLElement* e = doc.NewElement(tag);
  return (after ? parent->InsertAfterChild(after, e) : parent->InsertFirstChild(e))->ToElement();
}

void indexBodies(XMLElement* parent, std::map<std::string, XMLElement*>& bodies,
                 std::map<std::string, XMLElement*>& joints) {
  for (XMLElement* e = parent->FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (std::strcmp(e->Name(), "body") == 0) {
      bodies[attr(e, "name")] = e;
      indexBodies(e, bodies, joints);
    } else if (std::strcmp(e->Name(), "joint") == 0) {
      joints[attr(e, "name")] = e;
    }
  }
}

struct MjcfEdit {
  XMLDocument doc;
  XMLElement* root = nullptr;
  std::map<std::string, XMLElement*> bodies, joints;

  void header(const std::string& name, const std::string& urdf_file);
  void freeJoint(const std::string& base);
  void site(const std::string& body, const std::string& name, const std::array<double, 3>& pos);
  void motorsAndLimits(const mjModel* m, const UrdfJoints& urdf, std::vector<std::string>& warnings);
  void sensorsAndKeyframe(const mjModel* m, double home_height);
};

void MjcfEdit::header(const std::string& name, const std::string& urdf_file) {
  doc.InsertFirstChild(doc.NewComment((" " + name + ": imported by `centaur model import` from " + urdf_file +
                                       " with MuJoCo's URDF compiler; free joint, motors, velocity limits (joint"
                                       " user), sites, IMU sensors and the home keyframe added ").c_str()));
  root->SetAttribute("model", name.c_str());
  XMLElement* compiler = child(doc, root, "compiler", nullptr);
  compiler->SetAttribute("angle", "radian");
  compiler->SetAttribute("autolimits", "true");  // MuJoCo 2.2.2 needs it explicitly for range without limited
  compiler->SetAttribute("inertiafromgeom", "false");
  XMLElement* option = child(doc, root, "option", compiler);
  option->SetAttribute("timestep", kTimestep);
  option->SetAttribute("integrator", "Euler");
  child(doc, root, "size", option)->SetAttribute("nuser_jnt", 1);  // jnt_user[0] = qd_max (model/robot_model.cpp)
}

// MuJoCo keeps a URDF's floating base only for a `floating` joint from a world link: otherwise the base gets a
// free joint here, as its first child, so that it is the first joint in qpos.
void MjcfEdit::freeJoint(const std::string& base) {
  XMLElement* body = bodies.at(base);
  for (XMLElement* j = body->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    if (attr(j, "type") == "free") return;
  }
  if (body->FirstChildElement("freejoint")) return;
  std::string name = "root";
  while (joints.count(name)) name += "_free";
  body->InsertFirstChild(doc.NewElement("freejoint"))->ToElement()->SetAttribute("name", name.c_str());
}

// A site on `body` at `pos` (its frame), before the body's child bodies.
void MjcfEdit::site(const std::string& body, const std::string& name, const std::array<double, 3>& pos) {
  XMLElement* b = bodies.at(body);
  XMLElement* s = doc.NewElement("site");
  s->SetAttribute("name", name.c_str());
  if (pos[0] != 0.0 || pos[1] != 0.0 || pos[2] != 0.0) {
    s->SetAttribute("pos", (exactNumber(pos[0]) + " " + exactNumber(pos[1]) + " " + exactNumber(pos[2])).c_str());
  }
  XMLElement* first_body = b->FirstChildElement("body");
  XMLElement* before = nullptr;  // last child element before the first child body
  for (XMLElement* e = b->FirstChildElement(); e && e != first_body; e = e->NextSiblingElement()) before = e;
  if (before) b->InsertAfterChild(before, s);
  else b->InsertFirstChild(s);
}

// One torque motor per hinge, in MuJoCo's joint order, limited to the URDF effort; the URDF velocity limit in
// the joint's user field.
void MjcfEdit::motorsAndLimits(const mjModel* m, const UrdfJoints& urdf, std::vector<std::string>& warnings) {
  XMLElement* actuator = doc.NewElement("actuator");
  root->InsertEndChild(actuator);
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] != mjJNT_HINGE) continue;
    const std::string name = mj_id2name(m, mjOBJ_JOINT, j);
    const auto it = urdf.find(name);
    const UrdfJoint info = it == urdf.end() ? UrdfJoint{} : it->second;
    std::string effort = exactNumber(info.effort);
    if (!(info.effort > 0.0)) {
      effort = "1";
      warnings.push_back("joint " + inQuotes(name) + ": no effort limit in the URDF, motor limited to 1 N m: set it");
    }
    if (info.velocity > 0.0) joints.at(name)->SetAttribute("user", exactNumber(info.velocity).c_str());
    else warnings.push_back("joint " + inQuotes(name) + ": no velocity limit in the URDF");
    XMLElement* motor = doc.NewElement("motor");
    motor->SetAttribute("name", name.c_str());
    motor->SetAttribute("joint", name.c_str());
    motor->SetAttribute("gear", "1");
    motor->SetAttribute("ctrllimited", "true");
    motor->SetAttribute("ctrlrange", ("-" + effort + " " + effort).c_str());
    actuator->InsertEndChild(motor);
  }
}

void MjcfEdit::sensorsAndKeyframe(const mjModel* m, double home_height) {
  XMLElement* sensor = doc.NewElement("sensor");
  root->InsertEndChild(sensor);
  XMLElement* quat = sensor->InsertEndChild(doc.NewElement("framequat"))->ToElement();
  quat->SetAttribute("name", "imu_quat");
  quat->SetAttribute("objtype", "site");
  quat->SetAttribute("objname", "imu");
  for (const auto& [tag, name] : {std::pair<const char*, const char*>{"gyro", "imu_gyro"}, {"accelerometer", "imu_acc"}}) {
    XMLElement* s = sensor->InsertEndChild(doc.NewElement(tag))->ToElement();
    s->SetAttribute("name", name);
    s->SetAttribute("site", "imu");
  }
  // The zero posture, base upright at `home_height`: free joint (7) then one value per hinge.
  std::string qpos = "0 0 " + exactNumber(home_height) + " 1 0 0 0";
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] == mjJNT_HINGE) qpos += " 0";
  }
  XMLElement* key = root->InsertEndChild(doc.NewElement("keyframe"))->InsertEndChild(doc.NewElement("key"))->ToElement();
  key->SetAttribute("name", "home");
  key->SetAttribute("qpos", qpos.c_str());
}

// The URDF's root link may not hang from the world by a hinge: centaur's base floats.
void requireFloatingBase(const std::string& path, const mjModel* m, int base) {
  for (int j = m->body_jntadr[base]; j >= 0 && j < m->body_jntadr[base] + m->body_jntnum[base]; ++j) {
    if (m->jnt_type[j] != mjJNT_FREE) {
      throw InputError(excerpt(path, 4 * kMaxExcerpt) + ": the base link '" + excerpt(mj_id2name(m, mjOBJ_BODY, base)) +
                       "' is attached to the world by joint '" + excerpt(mj_id2name(m, mjOBJ_JOINT, j)) +
                       "': centaur's base floats (a `floating` joint or none)");
    }
  }
}

std::string completeMjcf(const std::string& saved, const mjModel* m, const RobotGuess& g, const Urdf& u,
                         const std::string& urdf_file, std::vector<std::string>& warnings) {
  MjcfEdit e;
  if (e.doc.Parse(saved.data(), saved.size()) != tinyxml2::XML_SUCCESS || !(e.root = e.doc.RootElement())) {
    throw RuntimeError("cannot read the MJCF MuJoCo saved: " + excerpt(e.doc.ErrorStr(), 200));
  }
  if (XMLElement* world = e.root->FirstChildElement("worldbody")) indexBodies(world, e.bodies, e.joints);
  e.header(u.name, urdf_file);
  e.freeJoint(g.base);
  e.site(g.imu_body, "imu", {0.0, 0.0, 0.0});
  if (g.feet_found) {
    for (const auto& f : g.feet) e.site(f.contact, f.centre, f.centre_pos);
  }
  for (const auto& a : g.arms) e.site(a.tip_body, a.tip_site, {0.0, 0.0, 0.0});
  e.motorsAndLimits(m, u.joints, warnings);
  e.sensorsAndKeyframe(m, g.home_height);
  Printer printer;
  e.doc.Print(&printer);
  return printer.CStr();
}

// ---------------------------------------------------------------------------------------------------------------
// Output: both files written as temporaries, then renamed, so that they appear together or not at all.

std::string writeTemporary(const std::string& target, const std::string& text) {
  ensureParentDirectory(target);
  const std::string tmp = temporaryPathFor(target);
  std::ofstream out(tmp, std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    removeFileIfExists(tmp);
    throw RuntimeError("cannot write " + target);
  }
  return tmp;
}

void writeOutputs(const std::string& mjcf_path, const std::string& mjcf, const std::string& yaml_path,
                  const std::string& yaml) {
  const std::string mjcf_tmp = writeTemporary(mjcf_path, mjcf);
  std::string yaml_tmp;
  try {
    yaml_tmp = writeTemporary(yaml_path, yaml);
  } catch (...) {
    removeFileIfExists(mjcf_tmp);
    throw;
  }
  commitFile(mjcf_tmp, mjcf_path);
  commitFile(yaml_tmp, yaml_path);
}

}  // namespace

std::string sanitizeRobotName(const std::string& urdf_name) {
  std::string out;
  for (char c : urdf_name) {
    const char l = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool ok = (l >= 'a' && l <= 'z') || (l >= '0' && l <= '9') || l == '_' || l == '-';
    if (out.size() < 64) out += ok ? l : '_';
  }
  return out.empty() ? "robot" : out;
}

UrdfImportReport importUrdf(const std::string& urdf_path, const std::string& out_dir) {
  UrdfImportReport report;
  Urdf u;
  parseUrdf(urdf_path, u);
  const std::string text = preprocess(urdf_path, u, report.warnings);
  const std::string where = excerpt(urdf_path, 4 * kMaxExcerpt);
  const std::string urdf_file = fs::path(urdf_path).filename().string();
  report.name = u.name;
  report.mjcf_path = (fs::path(out_dir) / (u.name + ".xml")).string();
  report.yaml_path = (fs::path(out_dir) / "robot.yaml").string();
  std::string mjcf, yaml;
  {
    std::lock_guard<std::mutex> lock(lastXmlMutex());
    std::string error;
    ModelPtr m = compileText(urdf_path, text, error);
    if (!m) {
      if (error.find("mjMINVAL") != std::string::npos) error += " (a link that a joint moves needs an <inertial> with mass)";
      throw InputError(where + ": MuJoCo's URDF compiler refuses it: " + error);
    }
    if (m->nbody < 2) throw InputError(where + ": the URDF has no link besides the world");
    const std::string saved = saveLastXml(m.get());
    mj_freeLastXML();
    const RobotGuess guess = detail::guessStructure(m.get(), u.joints, report.warnings);
    requireFloatingBase(urdf_path, m.get(), mj_name2id(m.get(), mjOBJ_BODY, guess.base.c_str()));
    mjcf = completeMjcf(saved, m.get(), guess, u, urdf_file, report.warnings);
    yaml = detail::robotYaml(u.name, u.name + ".xml", urdf_file, guess);
    // The result must load as centaur loads it: free joint first.
    const ModelPtr result = compileText(report.mjcf_path, mjcf, error);
    mj_freeLastXML();
    if (!result) throw InputError(where + ": the imported MJCF does not compile: " + error);
    if (result->njnt == 0 || result->jnt_type[0] != mjJNT_FREE || result->jnt_qposadr[0] != 0) {
      throw InputError(where + ": the floating base is not the first joint (a second tree hangs from the world)");
    }
    report.hinge_joints = result->nu;
    report.total_mass = mj_getTotalmass(result.get());
  }
  writeOutputs(report.mjcf_path, mjcf, report.yaml_path, yaml);
  return report;
}

}  // namespace centaur::robot
