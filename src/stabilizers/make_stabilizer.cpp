#include "stabilizers/make_stabilizer.hpp"

#include <sstream>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "stabilizers/angmom_stabilizer.hpp"
#include "stabilizers/no_stabilizer.hpp"
#include "stabilizers/ocp_posture_stabilizer.hpp"
#include "stabilizers/raibert_stabilizer.hpp"

namespace centaur {

namespace {
std::string indent(const std::string& text) {
  std::istringstream in(text);
  std::string line, out;
  while (std::getline(in, line)) out += "  " + line + "\n";
  return out;
}
}  // namespace

std::string stabilizerDefaultsYaml() {
  return indent(RaibertParams::defaultsYaml()) + indent(AngmomParams::defaultsYaml()) +
         indent(OcpPostureParams::defaultsYaml());
}

std::unique_ptr<Stabilizer> makeStabilizer(const std::string& mode, YamlReader& r, const std::string& flywheel_file,
                                           const FlywheelSource& fallback) {
  RaibertParams raibert;
  AngmomParams angmom;
  OcpPostureParams ocp;
  {
    auto c = r.child("ocp");
    ocp.read(c);
    c.finish();
  }
  if (!flywheel_file.empty()) ocp.flywheel_file = flywheel_file;
  {
    auto c = r.child("raibert");
    raibert.read(c);
    c.finish();
  }
  {
    auto c = r.child("angmom");
    angmom.read(c);
    c.finish();
  }
  if (mode == "none") return std::make_unique<NoStabilizer>();
  if (mode == "raibert") return std::make_unique<RaibertStabilizer>(raibert);
  if (mode == "angmom") return std::make_unique<AngmomStabilizer>(angmom);
  if (mode == "ocp") {
    if (ocp.flywheel_file.empty() && fallback) return std::make_unique<OcpPostureStabilizer>(ocp, fallback());
    return std::make_unique<OcpPostureStabilizer>(ocp);
  }
  throw InputError("stabilizer '" + mode + "' is not available (none, raibert, angmom, ocp)");
}

}  // namespace centaur
