#pragma once
// Loading an MJCF file with MuJoCo, optionally without its visual-only geoms. Shared by the controller's models
// (model module) and the simulator (sim module); the only header of the model module that names a MuJoCo type,
// and only as an opaque pointer.
#include <string>

struct mjModel_;

namespace centaur {

/// Loads `path` (InputError naming the file if MuJoCo cannot). With `discard_visual`, geoms that collide with
/// nothing (contype = conaffinity = 0, i.e. the visual shapes) are dropped by MuJoCo's parser (compiler option
/// discardvisual). They cost time in every kinematics pass (pose of each geom) but play no part in the dynamics
/// or contacts. The result is checked: if any body's mass, inertia or CoM differs from the full load (a model
/// that derives inertia from those geoms), the full model is returned instead. The caller owns the model
/// (mj_deleteModel). A path that is not a regular file (a FIFO, a directory, a device) is refused before MuJoCo
/// opens it.
mjModel_* loadMjcf(const std::string& path, bool discard_visual);

/// The robot-alone MJCF `path` inside a scene: `scene_xml` is an MJCF that includes the robot by its file name
/// (<include file="NAME.xml"/>) and adds the world around it; it is read as a file in the robot's folder. Visual
/// geoms are kept. InputError naming the robot's file if MuJoCo cannot load the pair.
mjModel_* loadMjcfInScene(const std::string& path, const std::string& scene_xml);

/// MuJoCo's process-wide message handlers: warnings to stderr, errors as RuntimeError, never MUJOCO_LOG.TXT in the
/// working directory nor a prompt on stdin. loadMjcf() installs them; idempotent.
void installMujocoHandlers();

}  // namespace centaur
