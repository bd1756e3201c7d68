#pragma once
// No command overwrites one of its inputs. Every command declares what it reads and what it will write (derived
// outputs included: sidecar configurations, per-primitive plots, the files of an output directory) and calls
// guardOutputs() before it writes anything:
//
//   guardOutputs({{"--config", a.config}, {"--primitive", a.primitive}},
//                {{"--out", a.out}, {"the effective configuration", sidecar}});
#include <string>
#include <vector>

namespace centaur {

/// A path a command reads or writes; `role` names it in messages ("--config", "--out", ...). Empty paths are
/// skipped (an option not given).
struct NamedPath {
  std::string role;
  std::string path;
};

/// InputError (CLI exit code 2) if an output is the same file as an input: the same device and inode (a
/// symlink or a hard link to the input counts), or the same absolute path once the symlinks of its existing
/// parent directories are resolved; and if two outputs are the same path.
void guardOutputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

}  // namespace centaur
