#include "sim/png_writer.hpp"

#include <stb/stb_image_write.h>  // Debian libstb: implementation in libstb.so

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace centaur::sim {

void writePng(const std::string& path, const std::vector<std::uint8_t>& rgb, int width, int height) {
  if (rgb.size() != static_cast<std::size_t>(width) * height * 3) throw RuntimeError("writePng: bad frame size");
  ensureParentDirectory(path);
  const std::string tmp = temporaryPathFor(path);
  if (!stbi_write_png(tmp.c_str(), width, height, 3, rgb.data(), width * 3)) {
    removeFileIfExists(tmp);
    throw RuntimeError("cannot write " + path);
  }
  commitFile(tmp, path);
}

}  // namespace centaur::sim
