#include "sim/video_writer.hpp"

#include <sys/wait.h>

#include <csignal>

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace centaur::sim {

namespace {
std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}
}  // namespace

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps)
    : path_(path), tmp_(temporaryPathFor(path)), width_(width), height_(height) {
  if (width % 2 || height % 2) throw InputError(path + ": video width and height must be even (yuv420p)");
  ensureParentDirectory(path);
  std::signal(SIGPIPE, SIG_IGN);  // a dying ffmpeg must give an error, not kill us
  const std::string cmd = "ffmpeg -nostdin -y -loglevel error -f rawvideo -pix_fmt rgb24 -s " + std::to_string(width) +
                          "x" + std::to_string(height) + " -r " + std::to_string(fps) +
                          " -i - -an -c:v libx264 -preset veryfast -crf 23 -pix_fmt yuv420p -movflags +faststart -f mp4 " +
                          shellQuote(tmp_);
  pipe_ = ::popen(cmd.c_str(), "w");
  if (!pipe_) throw RuntimeError("cannot start ffmpeg (Debian package ffmpeg) to write " + path);
}

VideoWriter::~VideoWriter() {
  if (pipe_) {
    ::pclose(pipe_);
    removeFileIfExists(tmp_);
  }
}

void VideoWriter::addFrame(const std::vector<std::uint8_t>& rgb) {
  if (!pipe_) throw RuntimeError("video " + path_ + " already closed");
  if (rgb.size() != static_cast<std::size_t>(width_) * height_ * 3 ||
      std::fwrite(rgb.data(), 1, rgb.size(), pipe_) != rgb.size()) {
    throw RuntimeError("cannot write a frame to ffmpeg for " + path_);
  }
  ++frames_;
}

void VideoWriter::close() {
  if (!pipe_) return;
  const int status = ::pclose(pipe_);
  pipe_ = nullptr;
  if (status != 0 || frames_ == 0) {
    removeFileIfExists(tmp_);
    throw RuntimeError("ffmpeg failed to encode " + path_);
  }
  commitFile(tmp_, path_);
}

}  // namespace centaur::sim
