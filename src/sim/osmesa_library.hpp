#pragma once
// The OSMesa entry points the offscreen renderer needs, from libOSMesa loaded at the first use. OSMesa pulls in
// libLLVM, whose relocations cost every process that links it ~0.1 s at start; loaded on demand, only a process
// that renders pays them.
#include <GL/osmesa.h>

namespace centaur::sim {

struct OsMesaLibrary {
  decltype(&OSMesaCreateContextExt) createContextExt = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
};

/// The loaded library (global symbols, so that MuJoCo's GL loader finds the GL functions). Thread-safe; throws
/// RuntimeError naming the library and the loader's message when it cannot be loaded.
const OsMesaLibrary& osMesaLibrary();

}  // namespace centaur::sim
