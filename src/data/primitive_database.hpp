#pragma once
// A primitive database: the primitives planned over a grid of planner parameters (`centaur sweep`), in one
// primitive file (docs/primitive-format.md, format_version 1, so `inspect`, `plot` and every primitive reader
// work on it unchanged) with, in addition:
//   /index            table (data/hdf5_table.hpp), one row per grid point: `point` (int64, 0-based), `group`,
//                     `jump`, `solve_status`, then one column per axis named by its planner key (float64 for a
//                     numeric axis, string otherwise), e.g. `target.wall_distance`;
//   root attributes   kind = "primitive-database", axes (the axis keys, string list), sweep_spec (YAML);
//   every group       its grid point's parameters as attributes "grid.<key>" and "grid.point" (written with the
//                     primitive, see gridAttributes), besides the usual primitive attributes.
// Selecting a grid point by parameters (`simulate --primitive DB --select key=value`): selectGridPoint.
#include <string>
#include <vector>

#include "data/primitive.hpp"

namespace centaur::data {

inline constexpr const char* kDatabaseKind = "primitive-database";

/// One axis value of a grid point: a number or a string (e.g. model.preset).
struct GridValue {
  bool numeric = true;
  double number = 0.0;
  std::string text;
  /// The value as YAML text: a number with 17 significant digits (exact round trip), or the string.
  std::string yaml() const;
};

struct GridEntry {
  int point = 0;             ///< index in the grid (spec order)
  std::string group;         ///< HDF5 group of its primitive
  std::string jump;          ///< squat-jump | half-squat-jump
  std::string solve_status;  ///< the planner's outcome ("solved", ...)
  std::vector<GridValue> values;  ///< one per axis
};

struct DatabaseIndex {
  std::vector<std::string> axes;  ///< planner keys, in the spec's order
  std::vector<bool> numeric;      ///< per axis
  std::vector<GridEntry> points;
};

/// Adds the grid attributes of `entry` ("grid.point", "grid.<axis>") to `prim`'s metadata.
void gridAttributes(const DatabaseIndex& index, const GridEntry& entry, Primitive& prim);

/// Writes the database `path` atomically (temporary sibling, renamed): the root attributes of a primitive file,
/// every grid point's group copied from `sources[i]` (a primitive file holding the group index.points[i].group),
/// the /index table and the root attributes above. RuntimeError (nothing written) on failure.
void writeDatabase(const std::string& path, const DatabaseIndex& index, const std::vector<std::string>& sources,
                   const std::string& spec_yaml);

/// True if `path` is a primitive database (root attribute kind = "primitive-database").
bool isDatabase(const std::string& path);
/// The index of a database; InputError naming the file if it is not one, or if the index is malformed.
DatabaseIndex readDatabaseIndex(const std::string& path);

/// `key=value` of `--select`.
struct Selection {
  std::string key;
  std::string value;
};

/// The grid point of `jump` nearest to the selections, among the points whose plan converged. Distance: the
/// Euclidean norm over the selected numeric axes of (value - grid value) / (the axis' span over the jump's grid
/// points; 1 if they all share one value); a selected string axis must match exactly. Axes not selected do not
/// count. Ties (exactly equal distances) go to the point listed first in the index. InputError naming `file`
/// and the key if an axis is not in the database (listing its axes), a value is not a number on a numeric axis,
/// or no converged point of `jump` matches. Returns the index into index.points.
std::size_t selectGridPoint(const DatabaseIndex& index, const std::string& jump, const std::vector<Selection>& selections,
                            const std::string& file);

}  // namespace centaur::data
