// The HDF5 reader: files opened or mapped, checked against the expected format, datasets and attributes read
// with their shapes and limits checked.
#include "data/hdf5.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <new>
#include <sstream>
#include <utility>

#include "common/error.hpp"
#include "common/excerpt.hpp"
#include "common/input_file.hpp"

namespace centaur::data::h5 {

// ---- Reader ------------------------------------------------------------------------------------------

namespace {

std::uint64_t littleEndian(const unsigned char* p, unsigned n) {
  std::uint64_t v = 0;
  for (unsigned i = n; i-- > 0;) v = (v << 8) | p[i];
  return v;
}

}  // namespace

std::string globalHeapDefect(const unsigned char* bytes, std::size_t size) {
  // "Size of Lengths" from the superblock (signature at 0, or 512, 1024, ... after a user block): byte 14 of a
  // version 0/1 superblock, byte 10 of a version 2/3 one.
  unsigned lengths = 8;
  static const unsigned char kSignature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  for (std::size_t base = 0; base + 16 <= size; base = base == 0 ? 512 : 2 * base) {
    if (std::memcmp(bytes + base, kSignature, 8) != 0) continue;
    const unsigned v = bytes[base + 8];
    const unsigned l = v <= 1 ? bytes[base + 14] : bytes[base + 10];
    if (l == 2 || l == 4 || l == 8) lengths = l;
    break;
  }
  const unsigned char* end = bytes + size;
  for (const unsigned char* p = bytes; p + 8 + lengths <= end;) {
    const void* hit = memmem(p, static_cast<std::size_t>(end - p), "GCOL", 4);
    if (hit == nullptr) break;
    const unsigned char* c = static_cast<const unsigned char*>(hit);
    p = c + 4;
    if (c + 8 + lengths > end || c[4] != 1) continue;  // not a collection HDF5 would accept
    const std::uint64_t collection = littleEndian(c + 8, lengths);
    const auto offset = std::to_string(c - bytes);
    if (collection > static_cast<std::uint64_t>(end - c)) {
      return "global heap collection at byte " + offset + " declares " + std::to_string(collection) +
             " bytes, beyond the end of the file";
    }
    // The objects as libhdf5 walks them when it loads the collection: object 0 is free space whose size counts
    // its own header (libhdf5 advances by that size: 0 would loop forever); others advance by header + size.
    const std::uint64_t header = 8 + lengths;
    for (std::uint64_t at = header; at + header <= collection;) {  // byte offsets within the collection
      const std::uint64_t index = littleEndian(c + at, 2), object = littleEndian(c + at + 8, lengths);
      const std::uint64_t room = collection - at;
      if (index == 0 && (object < header || object > room)) {
        return "global heap collection at byte " + offset + ": its free space declares " + std::to_string(object) +
               " bytes, not between its header (" + std::to_string(header) + ") and what is left (" +
               std::to_string(room) + ")";
      }
      if (index != 0 && object > room - header) {
        return "global heap collection at byte " + offset + ": object " + std::to_string(index) + " declares " +
               std::to_string(object) + " bytes, more than its collection holds";
      }
      at += index == 0 ? object : header + ((object + 7) / 8) * 8;
    }
  }
  return "";
}

Reader::Reader(std::string path, const std::string& expected) : path_(std::move(path)) {
  requireRegularFile(path_, expected);
  const std::string shown = excerpt(path_, 4 * kMaxExcerpt);
  if (H5Fis_hdf5(path_.c_str()) <= 0) throw InputError(shown + ": not an HDF5 file (expected " + expected + ")");
  {  // libhdf5 1.10 trusts the sizes of global heaps (variable-length strings): checked before it reads them
    const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    struct stat st {};
    if (fd >= 0 && ::fstat(fd, &st) == 0 && st.st_size > 0) {
      void* map = ::mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
      if (map != MAP_FAILED) {
        const std::string defect = globalHeapDefect(static_cast<const unsigned char*>(map), static_cast<std::size_t>(st.st_size));
        ::munmap(map, static_cast<std::size_t>(st.st_size));
        if (!defect.empty()) {
          ::close(fd);
          throw InputError(shown + ": corrupt HDF5 file: " + defect);
        }
      }
    }
    if (fd >= 0) ::close(fd);
  }
  file_ = Id(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file_.valid()) {
    const std::string truncated = truncationMessage();
    if (!truncated.empty()) {
      throw InputError(shown + ": truncated HDF5 file, shorter than its header says (an interrupted write or copy?): " +
                       truncated);
    }
    throw InputError(shown + ": corrupt HDF5 file, cannot open it" + errorStackMessage());
  }
  path_ = shown;  // messages quote the path as a bounded excerpt
}

Reader::Reader(const FileImage& image, const std::string& expected) : path_(excerpt(image.label, 4 * kMaxExcerpt)) {
  if (image.data == nullptr || image.size < 8) throw InputError(path_ + ": not an HDF5 file (expected " + expected + ")");
  const std::string defect = globalHeapDefect(static_cast<const unsigned char*>(image.data), image.size);
  if (!defect.empty()) throw InputError(path_ + ": corrupt HDF5 file: " + defect);
  Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (!fapl.valid() || H5Pset_fapl_core(fapl.get(), 1 << 16, 0) < 0 ||
      H5Pset_file_image(fapl.get(), const_cast<void*>(image.data), image.size) < 0) {
    throw RuntimeError(path_ + ": cannot set up reading an HDF5 image" + errorStackMessage());
  }
  file_ = Id(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);
  if (!file_.valid()) throw InputError(path_ + ": not an HDF5 file or corrupt (expected " + expected + ")" + errorStackMessage());
}

void Reader::fail(const std::string& key, const std::string& message) const {
  throw InputError(path_, excerpt(key), message);
}

bool Reader::exists(hid_t loc, const std::string& name) const {
  return H5Lexists(loc, name.c_str(), H5P_DEFAULT) > 0;
}

Id Reader::openGroup(hid_t loc, const std::string& key, const std::string& name) const {
  if (!exists(loc, name)) fail(key, "missing group");
  Id g(H5Gopen2(loc, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail(key, "cannot open the group (not a group, or corrupt)" + errorStackMessage());
  return g;
}

namespace {
herr_t collectGroup(hid_t loc, const char* name, const H5L_info_t* /*info*/, void* data) {
  Id obj(H5Oopen(loc, name, H5P_DEFAULT), H5Oclose);
  if (obj.valid() && H5Iget_type(obj.get()) == H5I_GROUP) {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  }
  return 0;
}
}  // namespace

std::vector<std::string> Reader::childGroups(hid_t loc) const {
  std::vector<std::string> names;
  hsize_t idx = 0;
  herr_t rc = H5Literate(loc, H5_INDEX_CRT_ORDER, H5_ITER_INC, &idx, collectGroup, &names);
  if (rc < 0) {  // files written without a creation-order index (e.g. by other tools): alphabetical
    names.clear();
    idx = 0;
    rc = H5Literate(loc, H5_INDEX_NAME, H5_ITER_INC, &idx, collectGroup, &names);
  }
  if (rc < 0) throw InputError(path_ + ": cannot list the groups (corrupt file?)" + errorStackMessage());
  return names;
}

std::vector<hsize_t> Reader::shape(hid_t loc, const std::string& key, const std::string& name) const {
  if (!exists(loc, name)) fail(key, "missing dataset");
  Id ds(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) fail(key, "cannot open the dataset (not a dataset, or corrupt)" + errorStackMessage());
  Id space(H5Dget_space(ds.get()), H5Sclose);
  const int rank = space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
  if (rank < 0) fail(key, "cannot read the dataspace (corrupt?)" + errorStackMessage());
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank), 0);
  if (rank > 0 && H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0) {
    fail(key, "cannot read the dataspace (corrupt?)" + errorStackMessage());
  }
  return dims;
}

std::vector<double> Reader::doubles(hid_t loc, const std::string& key, const std::string& name,
                                    const std::vector<hsize_t>& want, std::vector<hsize_t>& dims) const {
  dims = shape(loc, key, name);
  bool ok = dims.size() == want.size();
  for (std::size_t i = 0; ok && i < want.size(); ++i) ok = want[i] == 0 || want[i] == dims[i];
  if (!ok) {
    std::ostringstream s;
    s << "dataset has shape " << shapeText(dims) << ", expected (";
    for (std::size_t i = 0; i < want.size(); ++i) {
      s << (i ? ", " : "") << (want[i] == 0 ? std::string(i == 0 ? "N" : "any") : std::to_string(want[i]));
    }
    s << ")";
    fail(key, s.str());
  }
  hsize_t total = 1;
  for (hsize_t d : dims) {
    if (d != 0 && total > ReadLimits::kMaxElements / d) total = ReadLimits::kMaxElements + 1;  // no overflow
    else total *= d;
  }
  if (total > ReadLimits::kMaxElements) {
    fail(key, "dataset declares shape " + shapeText(dims) + ": more than the limit of " +
                  std::to_string(ReadLimits::kMaxElements) + " values (a defective or hostile file)");
  }
  Id ds(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  Id type(H5Dget_type(ds.get()), H5Tclose);
  const H5T_class_t cls = type.valid() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) fail(key, "dataset is not numeric");
  // A corrupt chunk index can declare more stored bytes than the whole file holds; libhdf5 would allocate a read
  // buffer of that size. Refused first.
  hsize_t file_bytes = 0;
  const hsize_t stored = H5Dget_storage_size(ds.get());
  if (H5Fget_filesize(file_.get(), &file_bytes) >= 0 && stored > file_bytes) {
    fail(key, "dataset declares " + std::to_string(stored) + " bytes of storage, more than the whole file (" +
                  std::to_string(file_bytes) + " bytes): corrupt");
  }
  std::vector<double> out;
  try {
    out.resize(static_cast<std::size_t>(total));
  } catch (const std::bad_alloc&) {
    fail(key, "not enough memory for the " + std::to_string(total) + " values the dataset declares");
  }
  if (total > 0 && H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    fail(key, "cannot read the dataset (corrupt?)" + errorStackMessage());
  }
  return out;
}

RowMatrix Reader::matrix(hid_t loc, const std::string& key, const std::string& name,
                         const std::vector<hsize_t>& want) const {
  std::vector<hsize_t> dims;
  const std::vector<double> data = doubles(loc, key, name, want, dims);
  const auto rows = static_cast<Eigen::Index>(dims.empty() ? 1 : dims[0]);
  Eigen::Index cols = 1;
  for (std::size_t i = 1; i < dims.size(); ++i) cols *= static_cast<Eigen::Index>(dims[i]);
  RowMatrix m(rows, cols);
  if (!data.empty()) std::copy(data.begin(), data.end(), m.data());
  return m;
}

Eigen::VectorXd Reader::vector(hid_t loc, const std::string& key, const std::string& name, hsize_t want) const {
  std::vector<hsize_t> dims;
  const std::vector<double> data = doubles(loc, key, name, {want}, dims);
  Eigen::VectorXd v(static_cast<Eigen::Index>(data.size()));
  if (!data.empty()) std::copy(data.begin(), data.end(), v.data());
  return v;
}

bool Reader::hasAttribute(hid_t loc, const std::string& name) const { return H5Aexists(loc, name.c_str()) > 0; }

AttributeValue Reader::attribute(hid_t loc, const std::string& key, const std::string& name) const {
  if (!hasAttribute(loc, name)) fail(key, "missing attribute");
  Id a(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!a.valid()) fail(key, "cannot open the attribute (corrupt?)" + errorStackMessage());
  return readAttribute(a.get());
}

std::string Reader::text(hid_t loc, const std::string& key, const std::string& name) const {
  const AttributeValue v = attribute(loc, key, name);
  if (v.kind != AttributeValue::kString) fail(key, "attribute is not a string");
  return v.text;
}

std::vector<std::string> Reader::textList(hid_t loc, const std::string& key, const std::string& name) const {
  const AttributeValue v = attribute(loc, key, name);
  if (v.kind == AttributeValue::kString) return {v.text};
  if (v.kind != AttributeValue::kStringList) fail(key, "attribute is not a list of strings");
  return v.texts;
}

std::vector<double> Reader::numbers(hid_t loc, const std::string& key, const std::string& name,
                                    std::size_t n) const {
  const AttributeValue v = attribute(loc, key, name);
  if (v.kind != AttributeValue::kScalar && v.kind != AttributeValue::kVector) fail(key, "attribute is not numeric");
  if (n > 0 && v.numbers.size() != n) {
    fail(key, "attribute has " + std::to_string(v.numbers.size()) + " values, expected " + std::to_string(n));
  }
  return v.numbers;
}

hsize_t Reader::length(hid_t loc, const std::string& key, const std::string& name, hsize_t min, hsize_t max) const {
  const std::vector<hsize_t> dims = shape(loc, key, name);
  if (dims.size() != 1) fail(key, "dataset has shape " + shapeText(dims) + ", expected (N)");
  if (dims[0] < min || dims[0] > max) {
    fail(key, "dataset has " + std::to_string(dims[0]) + " samples, allowed [" + std::to_string(min) + ", " +
                  std::to_string(max) + "]");
  }
  return dims[0];
}

void Reader::requireFinite(const std::string& key, const double* data, Eigen::Index rows, Eigen::Index cols) const {
  const Eigen::Index n = rows * cols;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (std::isfinite(data[i])) continue;
    std::ostringstream s;
    s << "holds " << data[i] << " at row " << i / cols;
    if (cols > 1) s << ", column " << i % cols;
    s << ": every value must be a finite number";
    fail(key, s.str());
  }
}

void Reader::requireTimeAxis(const std::string& key, const Eigen::VectorXd& t, const TimeAxisRules& rules) const {
  const Eigen::Index n = t.size();
  if (static_cast<hsize_t>(n) < rules.min_samples) {
    fail(key, "has " + std::to_string(n) + " sample(s); at least " + std::to_string(rules.min_samples) + " needed");
  }
  requireFinite(key, t);
  if (rules.starts_at_zero && std::abs(t[0]) > 1e-9) {
    fail(key, "starts at " + std::to_string(t[0]) + " s; the time axis starts at 0");
  }
  for (Eigen::Index i = 1; i < n; ++i) {
    if (!(t[i] > t[i - 1])) {
      std::ostringstream s;
      s << "does not increase at sample " << i << " (" << t[i - 1] << " s, then " << t[i] << " s)";
      fail(key, s.str());
    }
  }
  if (n < 2) return;
  const double step = t[1] - t[0];
  if (!(step >= rules.min_step && step <= rules.max_step)) {
    std::ostringstream s;
    s << "sample period " << step << " s outside the allowed range [" << rules.min_step << ", " << rules.max_step
      << "] s";
    fail(key, s.str());
  }
  if (!rules.uniform) return;
  for (Eigen::Index i = 2; i < n; ++i) {
    const double d = t[i] - t[i - 1];
    if (std::abs(d - step) > 1e-6 * step) {
      std::ostringstream s;
      s << "is not uniformly sampled: step " << d << " s at sample " << i << ", first step " << step << " s";
      fail(key, s.str());
    }
  }
}

void Reader::requireUnitQuaternions(const std::string& key, const RowMatrix& q, double tolerance) const {
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const double norm = q.row(i).norm();
    if (!(std::abs(norm - 1.0) <= tolerance)) {
      std::ostringstream s;
      s << "row " << i << " is not a unit quaternion (norm " << norm << ")";
      fail(key, s.str());
    }
  }
}

}  // namespace centaur::data::h5
