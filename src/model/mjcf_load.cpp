#include "model/mjcf_load.hpp"

#include <mujoco/mujoco.h>

#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

#include "common/error.hpp"

namespace centaur {

namespace {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;

struct VfsDeleter {
  void operator()(mjVFS* v) const {
    mj_deleteVFS(v);
    delete v;
  }
};

bool sameInertia(const mjModel* a, const mjModel* b) {
  if (a->nbody != b->nbody || a->nv != b->nv || a->nq != b->nq) return false;
  for (int i = 0; i < a->nbody; ++i) {
    if (a->body_mass[i] != b->body_mass[i]) return false;
    for (int k = 0; k < 3; ++k)
      if (a->body_inertia[3 * i + k] != b->body_inertia[3 * i + k] || a->body_ipos[3 * i + k] != b->body_ipos[3 * i + k])
        return false;
    for (int k = 0; k < 4; ++k)
      if (a->body_iquat[4 * i + k] != b->body_iquat[4 * i + k]) return false;
  }
  return true;
}

// The same file with <compiler discardvisual="true"/> as the first child of <mujoco>, served to MuJoCo from a
// virtual file system under the file's own name (so that relative includes and assets still resolve).
ModelPtr loadWithoutVisuals(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  const std::size_t tag = text.find("<mujoco");
  const std::size_t end = tag == std::string::npos ? tag : text.find('>', tag);
  if (end == std::string::npos || text[end - 1] == '/') return nullptr;
  text.insert(end + 1, "<compiler discardvisual=\"true\"/>");
  const std::size_t slash = path.find_last_of('/');
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), name.c_str(), static_cast<int>(text.size())) != 0) return nullptr;
  const int i = mj_findFileVFS(vfs.get(), name.c_str());
  if (i < 0) return nullptr;
  std::memcpy(vfs->filedata[i], text.data(), text.size());
  char err[1000] = "";
  return ModelPtr(mj_loadXML(path.c_str(), vfs.get(), err, sizeof(err)));
}

}  // namespace

mjModel_* loadMjcf(const std::string& path, bool discard_visual) {
  char err[1000] = "";
  ModelPtr full(mj_loadXML(path.c_str(), nullptr, err, sizeof(err)));
  if (!full) throw InputError(path + ": cannot load the MJCF model: " + err);
  if (!discard_visual) return full.release();
  ModelPtr lean = loadWithoutVisuals(path);
  if (!lean || !sameInertia(lean.get(), full.get())) return full.release();
  return lean.release();
}

}  // namespace centaur
