#include "model/mjcf_load.hpp"

#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>

#include "common/error.hpp"
#include "common/excerpt.hpp"
#include "common/input_file.hpp"

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

// `text` served to MuJoCo from a virtual file system as the file `path` (its folder still resolves relative
// includes and assets from the disk); the parser's message in `err`.
ModelPtr loadText(const std::string& path, const std::string& text, char* err, int err_size) {
  const std::size_t slash = path.find_last_of('/');
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), name.c_str(), static_cast<int>(text.size())) != 0) return nullptr;
  const int i = mj_findFileVFS(vfs.get(), name.c_str());
  if (i < 0) return nullptr;
  std::memcpy(vfs->filedata[i], text.data(), text.size());
  return ModelPtr(mj_loadXML(path.c_str(), vfs.get(), err, err_size));
}

// The same file with <compiler discardvisual="true"/> as the first child of <mujoco>.
ModelPtr loadWithoutVisuals(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  const std::size_t tag = text.find("<mujoco");
  const std::size_t end = tag == std::string::npos ? tag : text.find('>', tag);
  if (end == std::string::npos || text[end - 1] == '/') return nullptr;
  text.insert(end + 1, "<compiler discardvisual=\"true\"/>");
  char err[1000] = "";
  return loadText(path, text, err, sizeof(err));
}

std::string oneLine(std::string why) {
  while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
  for (char& c : why) c = c == '\n' ? ' ' : c;
  return why;
}

// MuJoCo's default handlers append to MUJOCO_LOG.TXT in the working directory, and its default error handler
// waits for Enter on stdin before exit(1). Ours print warnings to stderr and turn errors into RuntimeError
// (exit code 4): nothing is written to the working directory, nothing waits.
void warningToStderr(const char* msg) { std::fprintf(stderr, "MuJoCo warning: %s\n", msg); }
void errorToException(const char* msg) { throw RuntimeError(std::string("MuJoCo error: ") + msg); }

}  // namespace

void installMujocoHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_warning = warningToStderr;
    mju_user_error = errorToException;
  });
}

mjModel_* loadMjcf(const std::string& path, bool discard_visual) {
  installMujocoHandlers();
  requireRegularFile(path, "an MJCF model (MuJoCo XML)");
  char err[1000] = "";
  ModelPtr full(mj_loadXML(path.c_str(), nullptr, err, sizeof(err)));
  if (!full) {
    throw InputError(excerpt(path, 4 * kMaxExcerpt) + ": cannot load the MJCF model: " + excerpt(oneLine(err), 400));
  }
  if (!discard_visual) return full.release();
  ModelPtr lean = loadWithoutVisuals(path);
  if (!lean || !sameInertia(lean.get(), full.get())) return full.release();
  return lean.release();
}

mjModel_* loadMjcfInScene(const std::string& path, const std::string& scene_xml) {
  installMujocoHandlers();
  requireRegularFile(path, "an MJCF model (MuJoCo XML)");
  const std::size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? std::string(".") : path.substr(0, slash);
  char err[1000] = "";
  ModelPtr m = loadText(folder + "/centaur-scene.xml", scene_xml, err, sizeof(err));
  if (!m) {
    throw InputError(excerpt(path, 4 * kMaxExcerpt) + ": cannot load the MJCF model in centaur's scene: " +
                     excerpt(oneLine(err), 400));
  }
  return m.release();
}

}  // namespace centaur
