#include "cli/gnuplot.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/child_process.hpp"
#include "common/cleanup.hpp"
#include "common/error.hpp"

namespace centaur::cli {

namespace {

namespace fs = std::filesystem;

const char* const kInstallHint = "gnuplot is not installed (needed to draw plots): apt-get install gnuplot-nox";

/// gnuplot's private working directory, removed with its contents on destruction or by a signal.
class WorkDirectory {
 public:
  WorkDirectory() {
    std::error_code ec;
    fs::path base = fs::temp_directory_path(ec);
    if (ec) base = "/tmp";
    std::string pattern = (base / "centaur-gnuplot-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw RuntimeError("cannot create a temporary directory in " + base.string() + ": " + std::strerror(errno));
    }
    path_ = pattern;
    registration_ = cleanup::flatDirectory(path_.string());
  }
  WorkDirectory(const WorkDirectory&) = delete;
  WorkDirectory& operator=(const WorkDirectory&) = delete;
  ~WorkDirectory() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string path() const { return path_.string(); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
  cleanup::Registration registration_;
};

std::string readText(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw RuntimeError("cannot write " + path);
}

/// gnuplot on `script.gp` in `dir`, its output to `gnuplot.log` there: the exit status and the log.
int runIn(const WorkDirectory& dir, const std::string& script, std::string& log) {
  if (!gnuplotAvailable()) throw RuntimeError(kInstallHint);
  writeText(dir.file("script.gp"), script);
  ChildProcess::Options o;
  o.working_directory = dir.path();
  o.output_file = dir.file("gnuplot.log");
  o.missing_hint = kInstallHint;
  ChildProcess gnuplot({"gnuplot", "script.gp"}, o);
  const int status = gnuplot.wait();
  log = readText(dir.file("gnuplot.log"));
  return status;
}

}  // namespace

bool gnuplotAvailable() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) dir = ".";
    const std::string candidate = dir + "/gnuplot";
    std::error_code ec;
    if (::access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate, ec)) return true;
  }
  return false;
}

std::string gnuplotQuote(std::string_view text, bool enhanced) {
  std::string out = "'";
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      out += ' ';  // a newline would end the command and start another
    } else if (c == '\'') {
      out += "''";
    } else {
      if (enhanced && std::strchr("^_@&~{}\\", c) != nullptr) out += '\\';
      out += c;
    }
  }
  return out + "'";
}

void renderPng(const std::string& script, const std::vector<GnuplotFile>& files, const std::string& png_path) {
  if (!gnuplotAvailable()) throw RuntimeError(kInstallHint);
  WorkDirectory dir;
  for (const GnuplotFile& f : files) {
    if (f.source.empty()) {
      writeText(dir.file(f.name), f.text);
    } else {
      std::error_code ec;
      fs::copy_file(f.source, dir.file(f.name), ec);
      if (ec) throw RuntimeError("cannot copy " + f.source + " for gnuplot: " + ec.message());
    }
  }
  std::string log;
  const int status = runIn(dir, script, log);
  std::error_code ec;
  const auto size = fs::file_size(dir.file(kGnuplotPng), ec);
  if (status != 0 || ec || size < 8) {
    throw RuntimeError("gnuplot failed to draw " + png_path + " (exit status " + std::to_string(status) + "):\n" + log);
  }
  ensureParentDirectory(png_path);
  const std::string tmp = temporaryPathFor(png_path);
  fs::copy_file(dir.file(kGnuplotPng), tmp, fs::copy_options::overwrite_existing, ec);
  if (ec) {
    removeFileIfExists(tmp);
    throw RuntimeError("cannot write " + png_path + ": " + ec.message());
  }
  commitFile(tmp, png_path);
}

std::string runGnuplot(const std::string& script) {
  WorkDirectory dir;
  std::string log;
  const int status = runIn(dir, script, log);
  if (status != 0) throw RuntimeError("gnuplot failed (exit status " + std::to_string(status) + "):\n" + log);
  return log;
}

}  // namespace centaur::cli
