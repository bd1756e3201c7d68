#pragma once
// The primitive database: lower-body primitives in one HDF5 file, one group per primitive.
// Schema, units, frames and reading examples: docs/primitive-format.md.
//
// Guarantees:
//   - Writing never leaves a half-written file: the whole file is written to a temporary sibling and renamed
//     over the target; on any error the temporary is removed and centaur::RuntimeError is thrown.
//   - Reading a missing, non-HDF5 or corrupt file, or a group missing a dataset / with a wrongly shaped
//     dataset, throws centaur::InputError naming the file and the dataset (CLI exit code 2). HDF5's own
//     error printing is silenced. Every dataset is validated as it is read (docs/primitive-format.md,
//     "Validation"): sample count, time axis, finite values, unit quaternions, contact flags, consistent knots
//     and metadata; a simulation log or another format is recognised and refused by its `format` attribute.
#include <string>
#include <vector>

#include "data/file_image.hpp"
#include "data/primitive.hpp"

namespace centaur::data {

enum class WriteMode {
  Replace,  ///< create a new file holding exactly `prims` (an existing file is replaced)
  Append,   ///< keep the groups of an existing file, add `prims`, replacing groups of the same name;
            ///< creates the file if it does not exist
};

/// Schema version written as the root attribute `format_version`.
inline constexpr int kPrimitiveFormatVersion = 1;

/// Write `prims` to `path` (parent directories are created). Names must be unique, non-empty and contain
/// no '/' or '.' as the whole name. Throws RuntimeError on I/O failure or an inconsistent primitive
/// (wrong column count, rows differing from t.size(), a metadata key colliding with a reserved attribute);
/// Append on an existing file that cannot be read throws InputError. The target is untouched on error.
void writePrimitives(const std::string& path, const std::vector<Primitive>& prims,
                     WriteMode mode = WriteMode::Replace);

/// Convenience: one primitive.
void writePrimitive(const std::string& path, const Primitive& prim, WriteMode mode = WriteMode::Replace);

/// Names of the primitives (groups) in the file, in the order they were written.
std::vector<std::string> listPrimitives(const std::string& path);
std::vector<std::string> listPrimitives(const FileImage& image);

/// Every primitive in the file, in the order of listPrimitives().
std::vector<Primitive> readPrimitives(const std::string& path);
std::vector<Primitive> readPrimitives(const FileImage& image);

/// One primitive by name; InputError naming the file and listing the available names if absent.
Primitive readPrimitive(const std::string& path, const std::string& name);

/// InputError naming both robots unless `p` was planned for `robot` (its string `robot`; a primitive written
/// before primitives recorded their robot has none and was planned for CENTAURO, the only robot then). `where`
/// names the primitive in the message (file and group).
void requirePlannedFor(const Primitive& p, const std::string& robot, const std::string& where);
Primitive readPrimitive(const FileImage& image, const std::string& name);

}  // namespace centaur::data
