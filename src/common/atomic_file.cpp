#include "common/atomic_file.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/cleanup.hpp"
#include "common/error.hpp"

namespace centaur {

std::string temporaryPathFor(const std::string& target) {
  std::string tmp = target + ".tmp." + std::to_string(::getpid());
  cleanup::addFile(tmp);
  return tmp;
}

void commitFile(const std::string& tmp, const std::string& target) {
  std::error_code ec;
  std::filesystem::rename(tmp, target, ec);
  cleanup::forgetFile(tmp);
  if (ec) {
    removeFileIfExists(tmp);
    throw RuntimeError("cannot write " + target + ": " + ec.message());
  }
}

void removeFileIfExists(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
  cleanup::forgetFile(path);
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

StagedOutputs::StagedOutputs(std::string dir) : dir_(std::move(dir)) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(dir_, ec)) {
    dir_registration_ = cleanup::directory(dir_);
    fs::create_directories(dir_, ec);
    if (ec) throw RuntimeError("cannot create directory " + dir_ + ": " + ec.message());
    created_dir_ = true;
  }
  staging_ = (fs::path(dir_) / (".tmp." + std::to_string(::getpid()))).string();
  staging_registration_ = cleanup::flatDirectory(staging_);
  fs::create_directory(staging_, ec);
  if (ec) throw RuntimeError("cannot create directory " + staging_ + ": " + ec.message());
}

StagedOutputs::~StagedOutputs() {
  std::error_code ec;
  if (!committed_) {
    std::filesystem::remove_all(staging_, ec);
    if (created_dir_) std::filesystem::remove(dir_, ec);  // only if empty
  }
}

std::string StagedOutputs::path(const std::string& name) const {
  return (std::filesystem::path(staging_) / name).string();
}

std::string StagedOutputs::finalPath(const std::string& name) const {
  return (std::filesystem::path(dir_) / name).string();
}

std::vector<std::string> StagedOutputs::commit() {
  namespace fs = std::filesystem;
  std::vector<std::string> names, moved;
  std::error_code ec;
  for (fs::directory_iterator it(staging_, ec), end; !ec && it != end; it.increment(ec)) {
    names.push_back(it->path().filename().string());
  }
  if (ec) throw RuntimeError("cannot list " + staging_ + ": " + ec.message());
  for (const std::string& name : names) {
    fs::rename(fs::path(staging_) / name, fs::path(dir_) / name, ec);
    if (ec) throw RuntimeError("cannot write " + finalPath(name) + ": " + ec.message());
    moved.push_back(finalPath(name));
  }
  fs::remove(staging_, ec);
  committed_ = true;
  staging_registration_.release();
  dir_registration_.release();
  return moved;
}

}  // namespace centaur
