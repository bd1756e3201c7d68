#include "common/atomic_file.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/error.hpp"

namespace centaur {

std::string temporaryPathFor(const std::string& target) {
  return target + ".tmp." + std::to_string(::getpid());
}

void commitFile(const std::string& tmp, const std::string& target) {
  std::error_code ec;
  std::filesystem::rename(tmp, target, ec);
  if (ec) {
    removeFileIfExists(tmp);
    throw RuntimeError("cannot write " + target + ": " + ec.message());
  }
}

void removeFileIfExists(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
}

void ensureParentDirectory(const std::string& path) {
  const auto parent = std::filesystem::path(path).parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) throw RuntimeError("cannot create directory " + parent.string() + ": " + ec.message());
}

void writeTextFileAtomic(const std::string& path, const std::string& text) {
  ensureParentDirectory(path);
  const std::string tmp = temporaryPathFor(path);
  {
    std::ofstream out(tmp);
    if (!out) throw RuntimeError("cannot write " + path);
    out << text;
    if (!out) {
      removeFileIfExists(tmp);
      throw RuntimeError("cannot write " + path);
    }
  }
  commitFile(tmp, path);
}

}  // namespace centaur
