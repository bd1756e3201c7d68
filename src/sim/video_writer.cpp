#include "sim/video_writer.hpp"

#include <csignal>
#include <filesystem>

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace centaur::sim {

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps)
    : path_(path), tmp_(temporaryPathFor(path)), width_(width), height_(height) {
  if (width % 2 || height % 2) {
    removeFileIfExists(tmp_);
    throw InputError(path + ": video width and height must be even (yuv420p)");
  }
  ensureParentDirectory(path);
  std::signal(SIGPIPE, SIG_IGN);  // a dying ffmpeg must give an error, not kill us
  // No shell: each argument reaches ffmpeg as it is. The output is an absolute path behind ffmpeg's `file:`
  // protocol, so a name that starts with '-' or looks like a URL ("http:...", "pipe:") is still a local file.
  ChildProcess::Options o;
  o.pipe_stdin = true;
  o.missing_hint = "ffmpeg is not installed (needed by --video): apt-get install ffmpeg";
  const std::string output = "file:" + std::filesystem::absolute(tmp_).string();
  try {
    ffmpeg_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{"ffmpeg", "-nostdin", "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt",
                                 "rgb24", "-s", std::to_string(width) + "x" + std::to_string(height), "-r",
                                 std::to_string(fps), "-i", "pipe:0", "-an", "-c:v", "libx264", "-preset", "veryfast",
                                 "-crf", "23", "-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4", output},
        o);
  } catch (...) {
    removeFileIfExists(tmp_);
    throw;
  }
}

VideoWriter::~VideoWriter() {
  if (ffmpeg_) {
    ffmpeg_.reset();  // kills and reaps a running ffmpeg
    removeFileIfExists(tmp_);
  }
}

void VideoWriter::addFrame(const std::vector<std::uint8_t>& rgb) {
  if (!ffmpeg_) throw RuntimeError("video " + path_ + " already closed");
  std::FILE* pipe = ffmpeg_->input();
  if (rgb.size() != static_cast<std::size_t>(width_) * height_ * 3 || pipe == nullptr ||
      std::fwrite(rgb.data(), 1, rgb.size(), pipe) != rgb.size()) {
    throw RuntimeError("cannot write a frame to ffmpeg for " + path_);
  }
  ++frames_;
}

void VideoWriter::close() {
  if (!ffmpeg_) return;
  const bool flushed = ffmpeg_->closeInput();
  const int status = ffmpeg_->wait();
  ffmpeg_.reset();
  if (!flushed || status != 0 || frames_ == 0) {
    removeFileIfExists(tmp_);
    throw RuntimeError("ffmpeg failed to encode " + path_);
  }
  commitFile(tmp_, path_);
}

}  // namespace centaur::sim
