#pragma once
// The robot and its world as the viewer draws them, stored once per page: every geom of the MJCF (boxes,
// capsules, cylinders, spheres, ellipsoids, planes, meshes) with its body slot, local pose, size and colour.
// Body slots: movingBodies() first (their poses come per frame), then staticBodies() (one pose per run, e.g. the
// wall moved by world.wall_x).
#include <nlohmann/json.hpp>

#include "report/kinematic_model.hpp"

namespace centaur::report {

/// {"file", "bodies": [names by slot], "moving": count of moving slots, "geoms": [{"slot", "type", "size",
/// "pos", "quat" (w,x,y,z), "rgba", "mesh"}], "meshes": [{"vertices": float32 base64, "faces": int32 base64}]}.
/// Sizes follow MuJoCo: box half-extents, capsule/cylinder (radius, half-length along local z), sphere
/// radius, ellipsoid radii, plane half-extents.
nlohmann::json sceneGeometry(const KinematicModel& model);

}  // namespace centaur::report
