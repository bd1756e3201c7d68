#pragma once
// mp4 output of rendered frames through an `ffmpeg` process (Debian package ffmpeg).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/child_process.hpp"

namespace centaur::sim {

/// Encodes RGB frames into an mp4 through an `ffmpeg` pipe (H.264, yuv420p); the file appears only at
/// close() (temporary file, then rename). Throws RuntimeError if ffmpeg cannot be started or fails.
/// ffmpeg runs without a shell; the command's cleanup (common/cleanup.hpp) kills it and removes the temporary
/// file if the process is interrupted.
class VideoWriter {
 public:
  VideoWriter(const std::string& path, int width, int height, double fps);
  ~VideoWriter();  ///< aborts (removes the temporary file) if close() was not called
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;
  void addFrame(const std::vector<std::uint8_t>& rgb);
  void close();
  int frames() const { return frames_; }

 private:
  std::string path_, tmp_;
  int width_, height_;
  std::unique_ptr<ChildProcess> ffmpeg_;
  int frames_ = 0;
};

}  // namespace centaur::sim
