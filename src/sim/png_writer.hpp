#pragma once
// PNG output of rendered frames (stb_image_write from Debian's libstb).
#include <cstdint>
#include <string>
#include <vector>

namespace centaur::sim {

/// Write an RGB frame as PNG (atomically). Throws RuntimeError on failure.
void writePng(const std::string& path, const std::vector<std::uint8_t>& rgb, int width, int height);

}  // namespace centaur::sim
