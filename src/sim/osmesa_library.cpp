#include "sim/osmesa_library.hpp"

#include <dlfcn.h>

#include <string>

#include "common/error.hpp"

namespace centaur::sim {

namespace {

// Debian 12's run-time name first, then the development link the build found (CMake: CENTAUR_OSMESA_LIBRARY).
constexpr const char* kCandidates[] = {"libOSMesa.so.8", CENTAUR_OSMESA_PATH};

template <class F>
F symbol(void* lib, const char* name, const std::string& from) {
  void* p = ::dlsym(lib, name);
  if (p == nullptr) throw RuntimeError("offscreen rendering: " + from + " has no " + name);
  return reinterpret_cast<F>(p);
}

OsMesaLibrary load() {
  void* lib = nullptr;
  std::string tried, from;
  for (const char* name : kCandidates) {
    lib = ::dlopen(name, RTLD_NOW | RTLD_GLOBAL);
    if (lib != nullptr) {
      from = name;
      break;
    }
    const char* why = ::dlerror();
    tried += std::string(tried.empty() ? "" : "; ") + (why ? why : name);
  }
  if (lib == nullptr) {
    throw RuntimeError("offscreen rendering needs libOSMesa (Debian package libosmesa6): " + tried);
  }
  OsMesaLibrary api;  // the library stays loaded for the life of the process
  api.createContextExt = symbol<decltype(api.createContextExt)>(lib, "OSMesaCreateContextExt", from);
  api.makeCurrent = symbol<decltype(api.makeCurrent)>(lib, "OSMesaMakeCurrent", from);
  api.destroyContext = symbol<decltype(api.destroyContext)>(lib, "OSMesaDestroyContext", from);
  return api;
}

}  // namespace

const OsMesaLibrary& osMesaLibrary() {
  static const OsMesaLibrary api = load();  // a failed load throws and is tried again at the next call
  return api;
}

}  // namespace centaur::sim
