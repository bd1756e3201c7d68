#pragma once
// Offscreen rendering of a MuJoCo model (OSMesa software GL context; works headless), RGB frames
// top row first. One Renderer per thread; it owns the GL context.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim/mujoco_robot.hpp"

namespace centaur::sim {

class Renderer {
 public:
  /// `camera`: an MJCF camera name; empty or unknown -> a free camera tracking body `track_body`.
  /// `shadows` / `reflections` are the costly parts of software rendering (~5x slower with both on).
  Renderer(const mjModel* model, int width, int height, const std::string& camera = "side",
           const std::string& track_body = "pelvis", bool shadows = true, bool reflections = true);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Render the current state; returns width*height*3 bytes, RGB, top row first.
  const std::vector<std::uint8_t>& render(mjData* data);
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_, height_;
};

}  // namespace centaur::sim
