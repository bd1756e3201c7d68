#pragma once
// The HDF5 plumbing every centaur data format shares (primitives, arm trajectories, simulation logs):
//   - Id: owns one HDF5 identifier and closes it with the matching H5?close;
//   - QuietErrors: silences HDF5's own error printing on stderr for a scope, restoring the previous handler;
//   - Writer: every failure becomes RuntimeError("cannot write <target>: <what> (HDF5: <cause>)");
//   - Reader: every defect of a file becomes InputError("<file>: key '<dataset or attribute>': <message>")
//     (CLI exit code 2). Files must be regular files (a FIFO, a directory or a device is refused before
//     anything is opened) or file images in memory (FileImage); dataset shapes are checked against the
//     expectation and the size limits (ReadLimits) before any element is read or allocated; the checks every
//     format shares (finite values, a time axis, unit quaternions) are here, linear in the data.
// Strings are written as variable-length UTF-8; both variable- and fixed-length strings are read.
// Matrices are row-major in memory and in the file (dataset dims = [rows, trailing...]).
#include <hdf5.h>

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "data/file_image.hpp"
#include "data/row_matrix.hpp"

namespace centaur::data {
namespace h5 {

/// Owns an HDF5 identifier (move-only).
class Id {
 public:
  using Closer = herr_t (*)(hid_t);
  Id() = default;
  Id(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  Id(Id&& o) noexcept;
  Id& operator=(Id&& o) noexcept;
  ~Id() { reset(); }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Close now; false if closing failed (a file flushes on close).
  bool close();
  void reset();

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

/// While alive, HDF5 prints nothing on its own (errors are reported by the callers' exceptions).
class QuietErrors {
 public:
  QuietErrors();
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;
  ~QuietErrors();

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

/// " (HDF5: <innermost message of the error stack>)", or "" when the stack is empty.
std::string errorStackMessage();

/// HDF5's "truncated file: eof = ..., stored_eof = ..." message if the error stack holds one, else "".
std::string truncationMessage();

/// "(2, 4, 3)".
std::string shapeText(const std::vector<hsize_t>& dims);

/// Descriptive attributes of a dataset.
struct DatasetMeta {
  const char* units = "";
  const char* frame = nullptr;  ///< written as attribute `frame` when not null
  const char* description = "";
  bool fixed_length_strings = false;  ///< write units/frame/description as fixed-length strings
};

/// Deflate level of every compressed dataset (after the shuffle filter). Level 1: a planned primitive's file is ~1 %
/// larger than at level 4 and written in a fraction of the time, which a re-plan run as a process of its own pays
/// (docs/benchmarks.md, "Process start"). Any level reads back the same with every HDF5 reader.
constexpr unsigned kDeflateLevel = 1;

class Writer {
 public:
  explicit Writer(std::string target) : target_(std::move(target)) {}
  const std::string& target() const { return target_; }

  [[noreturn]] void fail(const std::string& what) const;
  hid_t check(hid_t id, const std::string& what) const;
  void ok(herr_t rc, const std::string& what) const;

  /// A new file at `path` (truncated) tracking link creation order, in the HDF5 1.8 format.
  Id createFile(const std::string& path) const;
  /// An existing file opened for writing.
  Id openFile(const std::string& path) const;
  /// A group whose attributes stay in compact storage (HDF5 1.10's H5Ocopy, used by h5copy and h5py's
  /// Group.copy, crashes on variable-length string attributes in dense storage).
  Id createGroup(hid_t loc, const std::string& name) const;

  /// Variable-length UTF-8 by default; `fixed_length`: a null-terminated fixed-length ASCII string (the
  /// simulation log's root attributes, kept as first written for readers that use the C API).
  void stringAttribute(hid_t loc, const std::string& name, const std::string& value, bool fixed_length = false) const;
  void stringListAttribute(hid_t loc, const std::string& name, const std::vector<std::string>& values) const;
  void doubleAttribute(hid_t loc, const std::string& name, double value) const;
  void intAttribute(hid_t loc, const std::string& name, int value) const;
  void vectorAttribute(hid_t loc, const std::string& name, const double* values, std::size_t n) const;
  void vectorAttribute(hid_t loc, const std::string& name, const std::vector<double>& values) const {
    vectorAttribute(loc, name, values.data(), values.size());
  }

  /// A dataset of shape `dims` from contiguous row-major memory; deflate-compressed in chunks of 1024 rows
  /// when `compress` (and the filter is available).
  void dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, hid_t file_type,
               hid_t mem_type, const void* data, const DatasetMeta& meta, bool compress = true) const;
  /// Doubles (IEEE 64-bit little endian in the file).
  void doubles(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const double* data,
               const DatasetMeta& meta, bool compress = true) const {
    dataset(loc, name, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data, meta, compress);
  }

 private:
  std::string target_;
};

/// What one attribute holds, once read.
struct AttributeValue {
  enum Kind { kString, kScalar, kVector, kStringList, kUnsupported } kind = kUnsupported;
  std::string text;
  std::vector<double> numbers;
  std::vector<std::string> texts;
};

/// Reads any scalar/1-D numeric, scalar string or 1-D string attribute; kUnsupported otherwise.
AttributeValue readAttribute(hid_t attr);

/// "" if every global heap collection (where HDF5 keeps variable-length strings) of the file `bytes` lies within
/// the file and holds its objects, else what is wrong. libhdf5 1.10 trusts these sizes (a corrupt collection
/// makes it copy past its buffer: found by fuzzing, docs/reliability.md); the Reader refuses such files first.
std::string globalHeapDefect(const unsigned char* bytes, std::size_t size);

/// What a reader allocates for one dataset or attribute at most; larger declared shapes are refused before
/// anything is allocated (a small file can declare a huge compressed or unallocated dataset).
struct ReadLimits {
  static constexpr hsize_t kMaxElements = hsize_t{1} << 27;   ///< values of one dataset (1 GiB of doubles)
  static constexpr std::size_t kMaxStringBytes = 16u << 20;   ///< one string attribute
};

/// What a time axis must satisfy (TimeAxis::check).
struct TimeAxisRules {
  hsize_t min_samples = 2;
  bool starts_at_zero = true;     ///< t[0] = 0 (within 1e-9 s)
  bool uniform = true;            ///< every step equal to the first within 1e-6 of it
  double min_step = 1e-4;         ///< [s] bounds of the (first) step
  double max_step = 0.1;          ///< [s]
};

class Reader {
 public:
  /// Opens `path` read-only. `expected` completes the message of a missing file ("an HDF5 primitive file
  /// written by `centaur plan`"). InputError if the path is missing, not a regular file, or not HDF5.
  Reader(std::string path, const std::string& expected);
  /// Opens an HDF5 file image held in memory (HDF5's core driver, no disk access); messages name image.label.
  Reader(const FileImage& image, const std::string& expected);

  hid_t file() const { return file_.get(); }
  const std::string& path() const { return path_; }

  /// InputError("<file>: key '<key>': <message>").
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

  bool exists(hid_t loc, const std::string& name) const;
  Id openGroup(hid_t loc, const std::string& key, const std::string& name) const;
  /// Child groups of `loc`, in creation order where the file tracks it, else alphabetically.
  std::vector<std::string> childGroups(hid_t loc) const;

  /// Shape of dataset `name` in `loc` without reading it; `key` names it in messages.
  std::vector<hsize_t> shape(hid_t loc, const std::string& key, const std::string& name) const;
  /// A numeric dataset as doubles, row-major. `want` is the expected shape (0 = any extent, the rank must
  /// match); the shape is checked before anything is allocated.
  std::vector<double> doubles(hid_t loc, const std::string& key, const std::string& name,
                              const std::vector<hsize_t>& want, std::vector<hsize_t>& dims) const;
  /// A dataset as a matrix: rows = first extent, columns = the product of the others.
  RowMatrix matrix(hid_t loc, const std::string& key, const std::string& name, const std::vector<hsize_t>& want) const;
  Eigen::VectorXd vector(hid_t loc, const std::string& key, const std::string& name, hsize_t want) const;
  /// The extent of the 1-D dataset `name` (read nothing), refused if outside [min, max].
  hsize_t length(hid_t loc, const std::string& key, const std::string& name, hsize_t min, hsize_t max) const;

  /// InputError naming `key` and the first element (row, column) that is NaN or infinite.
  void requireFinite(const std::string& key, const double* data, Eigen::Index rows, Eigen::Index cols) const;
  void requireFinite(const std::string& key, const RowMatrix& m) const {
    requireFinite(key, m.data(), m.rows(), m.cols());
  }
  void requireFinite(const std::string& key, const Eigen::VectorXd& v) const { requireFinite(key, v.data(), v.size(), 1); }
  /// A time axis: finite, strictly increasing, and the rules.
  void requireTimeAxis(const std::string& key, const Eigen::VectorXd& t, const TimeAxisRules& rules) const;
  /// Every row a unit quaternion (norm within `tolerance` of 1).
  void requireUnitQuaternions(const std::string& key, const RowMatrix& q, double tolerance = 1e-3) const;

  bool hasAttribute(hid_t loc, const std::string& name) const;
  /// A required attribute; `key` names it in messages (e.g. "squat-jump@solve_status").
  AttributeValue attribute(hid_t loc, const std::string& key, const std::string& name) const;
  std::string text(hid_t loc, const std::string& key, const std::string& name) const;
  std::vector<std::string> textList(hid_t loc, const std::string& key, const std::string& name) const;
  /// A numeric attribute with exactly `n` values (0 = any number; a scalar counts as 1).
  std::vector<double> numbers(hid_t loc, const std::string& key, const std::string& name, std::size_t n) const;

 private:
  std::string path_;
  QuietErrors quiet_;
  Id file_;
};

}  // namespace h5
}  // namespace centaur::data
