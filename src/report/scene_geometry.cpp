#include "report/scene_geometry.hpp"

#include <mujoco/mujoco.h>

#include <cstdint>
#include <vector>

#include "report/channel_codec.hpp"

namespace centaur::report {

namespace {

const char* typeName(int type) {
  switch (type) {
    case mjGEOM_PLANE: return "plane";
    case mjGEOM_SPHERE: return "sphere";
    case mjGEOM_CAPSULE: return "capsule";
    case mjGEOM_ELLIPSOID: return "ellipsoid";
    case mjGEOM_CYLINDER: return "cylinder";
    case mjGEOM_BOX: return "box";
    case mjGEOM_MESH: return "mesh";
    default: return nullptr;  // height fields and others: not drawn
  }
}

std::vector<double> span(const mjtNum* p, int n) { return std::vector<double>(p, p + n); }

nlohmann::json meshJson(const mjModel* m, int id) {
  const int v0 = m->mesh_vertadr[id], nv = m->mesh_vertnum[id];
  const int f0 = m->mesh_faceadr[id], nf = m->mesh_facenum[id];
  const std::vector<double> verts(m->mesh_vert + 3 * v0, m->mesh_vert + 3 * (v0 + nv));
  const std::vector<std::int32_t> faces(m->mesh_face + 3 * f0, m->mesh_face + 3 * (f0 + nf));
  return {{"vertices", encodeFloat32(verts)}, {"faces", encodeInt32(faces)}};
}

}  // namespace

nlohmann::json sceneGeometry(const KinematicModel& km) {
  const mjModel* m = km.model();
  std::vector<int> slots = km.movingBodies();
  slots.insert(slots.end(), km.staticBodies().begin(), km.staticBodies().end());
  nlohmann::json bodies = nlohmann::json::array(), geoms = nlohmann::json::array(), meshes = nlohmann::json::array();
  std::vector<int> mesh_slot(static_cast<std::size_t>(m->nmesh), -1);
  for (std::size_t s = 0; s < slots.size(); ++s) {
    const int b = slots[s];
    bodies.push_back(km.bodyName(b));
    for (int g = m->body_geomadr[b]; g < m->body_geomadr[b] + m->body_geomnum[b]; ++g) {
      const char* type = typeName(m->geom_type[g]);
      if (type == nullptr || m->geom_rgba[4 * g + 3] == 0.0f) continue;
      const int mat = m->geom_matid[g];
      const float* rgba = mat >= 0 ? m->mat_rgba + 4 * mat : m->geom_rgba + 4 * g;
      nlohmann::json j = {{"slot", s},
                          {"type", type},
                          {"size", span(m->geom_size + 3 * g, 3)},
                          {"pos", span(m->geom_pos + 3 * g, 3)},
                          {"quat", span(m->geom_quat + 4 * g, 4)},
                          {"rgba", std::vector<double>(rgba, rgba + 4)}};
      const char* name = mj_id2name(m, mjOBJ_GEOM, g);
      if (name != nullptr) j["name"] = name;
      const int mesh = m->geom_dataid[g];
      if (m->geom_type[g] == mjGEOM_MESH && mesh >= 0) {
        if (mesh_slot[mesh] < 0) {
          mesh_slot[mesh] = static_cast<int>(meshes.size());
          meshes.push_back(meshJson(m, mesh));
        }
        j["mesh"] = mesh_slot[mesh];
      }
      geoms.push_back(std::move(j));
    }
  }
  return {{"file", km.path()},
          {"bodies", bodies},
          {"moving", km.movingBodies().size()},
          {"geoms", geoms},
          {"meshes", meshes}};
}

}  // namespace centaur::report
