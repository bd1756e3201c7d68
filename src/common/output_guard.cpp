#include "common/output_guard.hpp"

#include <sys/stat.h>

#include <filesystem>

#include "common/error.hpp"
#include "common/excerpt.hpp"

namespace centaur {

namespace {

struct Identity {
  bool exists = false;
  dev_t dev = 0;
  ino_t ino = 0;
  std::string canonical;  // absolute, symlinks of the existing part resolved
};

Identity identify(const std::string& path) {
  Identity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.dev = st.st_dev;
    id.ino = st.st_ino;
  }
  std::error_code ec;
  const std::filesystem::path abs = std::filesystem::absolute(path, ec);
  id.canonical = ec ? path : std::filesystem::weakly_canonical(abs, ec).string();
  if (ec) id.canonical = abs.lexically_normal().string();
  return id;
}

bool same(const Identity& a, const Identity& b) {
  if (a.exists && b.exists && a.dev == b.dev && a.ino == b.ino) return true;
  return a.canonical == b.canonical;
}

std::string name(const NamedPath& p) { return p.role + " " + excerpt(p.path, 4 * kMaxExcerpt); }

}  // namespace

void guardOutputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  std::vector<std::pair<const NamedPath*, Identity>> in, out;
  for (const NamedPath& p : inputs) {
    if (!p.path.empty()) in.emplace_back(&p, identify(p.path));
  }
  for (const NamedPath& p : outputs) {
    if (p.path.empty()) continue;
    Identity id = identify(p.path);
    for (const auto& [input, input_id] : in) {
      if (same(id, input_id)) {
        throw InputError(name(p) + ": is the same file as the input " + name(*input) +
                         "; an output must not overwrite an input (choose another output path)");
      }
    }
    for (const auto& [other, other_id] : out) {
      if (same(id, other_id)) {
        throw InputError(name(p) + ": is the same file as the output " + name(*other) +
                         "; one would overwrite the other (choose distinct output paths)");
      }
    }
    out.emplace_back(&p, std::move(id));
  }
}

}  // namespace centaur
