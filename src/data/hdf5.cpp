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

// ---- Id ----------------------------------------------------------------------------------------------

Id::Id(Id&& o) noexcept : id_(std::exchange(o.id_, -1)), closer_(o.closer_) {}

Id& Id::operator=(Id&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = std::exchange(o.id_, -1);
    closer_ = o.closer_;
  }
  return *this;
}

bool Id::close() {
  const herr_t rc = id_ >= 0 && closer_ != nullptr ? closer_(id_) : 0;
  id_ = -1;
  return rc >= 0;
}

void Id::reset() {
  if (id_ >= 0 && closer_ != nullptr) closer_(id_);
  id_ = -1;
}

// ---- errors ------------------------------------------------------------------------------------------

QuietErrors::QuietErrors() {
  H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

QuietErrors::~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }

namespace {
herr_t innermostError(unsigned n, const H5E_error2_t* err, void* data) {
  if (n == 0 && err != nullptr && err->desc != nullptr) *static_cast<std::string*>(data) = err->desc;
  return 0;
}
}  // namespace

namespace {
herr_t truncationError(unsigned /*n*/, const H5E_error2_t* err, void* data) {
  auto* msg = static_cast<std::string*>(data);
  if (msg->empty() && err != nullptr && err->desc != nullptr && std::strstr(err->desc, "truncated file") != nullptr) {
    *msg = err->desc;
  }
  return 0;
}
}  // namespace

std::string truncationMessage() {
  std::string msg;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, truncationError, &msg);
  return msg;
}

std::string errorStackMessage() {
  std::string msg;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, innermostError, &msg);
  return msg.empty() ? std::string() : " (HDF5: " + msg + ")";
}

std::string shapeText(const std::vector<hsize_t>& dims) {
  std::ostringstream s;
  s << "(";
  for (std::size_t i = 0; i < dims.size(); ++i) s << (i ? ", " : "") << dims[i];
  s << ")";
  return s.str();
}

// ---- Writer ------------------------------------------------------------------------------------------

namespace {
constexpr hsize_t kChunkRows = 1024;
constexpr unsigned kMaxCompactAttributes = 4096;
}  // namespace

void Writer::fail(const std::string& what) const {
  throw RuntimeError("cannot write " + target_ + ": " + what + errorStackMessage());
}

hid_t Writer::check(hid_t id, const std::string& what) const {
  if (id < 0) fail(what);
  return id;
}

void Writer::ok(herr_t rc, const std::string& what) const {
  if (rc < 0) fail(what);
}

Id Writer::createFile(const std::string& path) const {
  Id fcpl(check(H5Pcreate(H5P_FILE_CREATE), "property list"), H5Pclose);
  ok(H5Pset_link_creation_order(fcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), "creation order");
  Id fapl(check(H5Pcreate(H5P_FILE_ACCESS), "property list"), H5Pclose);
  // The 1.8 format stays readable by older tools (h5py on HDF5 1.8, MATLAB).
  ok(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V18), "format version");
  return Id(check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), "cannot create " + path),
            H5Fclose);
}

Id Writer::openFile(const std::string& path) const {
  return Id(check(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "cannot open " + path), H5Fclose);
}

Id Writer::createGroup(hid_t loc, const std::string& name) const {
  Id gcpl(check(H5Pcreate(H5P_GROUP_CREATE), "property list"), H5Pclose);
  ok(H5Pset_attr_phase_change(gcpl.get(), kMaxCompactAttributes, 0), "attribute storage");
  return Id(check(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), "group '" + name + "'"),
            H5Gclose);
}

void Writer::stringAttribute(hid_t loc, const std::string& name, const std::string& value,
                             bool fixed_length) const {
  Id type(check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
  if (fixed_length) {
    ok(H5Tset_size(type.get(), value.size() + 1), "string type");
    ok(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "string type");
  } else {
    ok(H5Tset_size(type.get(), H5T_VARIABLE), "string type");
    ok(H5Tset_cset(type.get(), H5T_CSET_UTF8), "string type");
  }
  Id space(check(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
  Id attr(check(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                "attribute '" + name + "'"),
          H5Aclose);
  const char* data = value.c_str();
  ok(fixed_length ? H5Awrite(attr.get(), type.get(), data) : H5Awrite(attr.get(), type.get(), &data),
     "attribute '" + name + "'");
}

void Writer::stringListAttribute(hid_t loc, const std::string& name, const std::vector<std::string>& values) const {
  std::vector<const char*> ptrs;
  for (const auto& v : values) ptrs.push_back(v.c_str());
  Id type(check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
  ok(H5Tset_size(type.get(), H5T_VARIABLE), "string type");
  ok(H5Tset_cset(type.get(), H5T_CSET_UTF8), "string type");
  const hsize_t n = values.size();
  Id space(check(H5Screate_simple(1, &n, nullptr), "dataspace"), H5Sclose);
  Id attr(check(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                "attribute '" + name + "'"),
          H5Aclose);
  if (n > 0) ok(H5Awrite(attr.get(), type.get(), ptrs.data()), "attribute '" + name + "'");
}

void Writer::doubleAttribute(hid_t loc, const std::string& name, double value) const {
  Id space(check(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
  Id attr(check(H5Acreate2(loc, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                "attribute '" + name + "'"),
          H5Aclose);
  ok(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, &value), "attribute '" + name + "'");
}

void Writer::intAttribute(hid_t loc, const std::string& name, int value) const {
  Id space(check(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
  Id attr(check(H5Acreate2(loc, name.c_str(), H5T_STD_I32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                "attribute '" + name + "'"),
          H5Aclose);
  ok(H5Awrite(attr.get(), H5T_NATIVE_INT, &value), "attribute '" + name + "'");
}

void Writer::vectorAttribute(hid_t loc, const std::string& name, const double* values, std::size_t n) const {
  const hsize_t dims = n;
  Id space(check(H5Screate_simple(1, &dims, nullptr), "dataspace"), H5Sclose);
  Id attr(check(H5Acreate2(loc, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                "attribute '" + name + "'"),
          H5Aclose);
  if (n > 0) ok(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, values), "attribute '" + name + "'");
}

void Writer::dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, hid_t file_type,
                     hid_t mem_type, const void* data, const DatasetMeta& meta, bool compress) const {
  Id space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "dataspace"), H5Sclose);
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  Id dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "property list"), H5Pclose);
  if (compress && total > 0 && !dims.empty() && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    std::vector<hsize_t> chunk = dims;
    chunk[0] = std::min<hsize_t>(dims[0], kChunkRows);
    ok(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), "chunking");
    ok(H5Pset_shuffle(dcpl.get()), "shuffle filter");
    ok(H5Pset_deflate(dcpl.get(), kDeflateLevel), "deflate filter");
  }
  Id ds(check(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
              "dataset '" + name + "'"),
        H5Dclose);
  if (total > 0) ok(H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "dataset '" + name + "'");
  stringAttribute(ds.get(), "units", meta.units, meta.fixed_length_strings);
  if (meta.frame != nullptr) stringAttribute(ds.get(), "frame", meta.frame, meta.fixed_length_strings);
  stringAttribute(ds.get(), "description", meta.description, meta.fixed_length_strings);
}

// ---- attributes --------------------------------------------------------------------------------------

namespace {

/// One string of a string-typed attribute held in `type` (variable- or fixed-length).
bool readStrings(hid_t attr, hid_t type, hsize_t n, std::vector<std::string>& out) {
  out.clear();
  if (n == 0) return true;  // an empty list (HDF5 refuses to read zero elements into no buffer)
  if (H5Tis_variable_str(type) > 0) {
    Id mem(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(mem.get(), H5T_VARIABLE);
    H5Tset_cset(mem.get(), H5Tget_cset(type));
    std::vector<char*> buf(static_cast<std::size_t>(n), nullptr);
    if (H5Aread(attr, mem.get(), buf.data()) < 0) return false;
    bool ok = true;
    for (char* s : buf) {
      const std::size_t len = s != nullptr ? strnlen(s, ReadLimits::kMaxStringBytes + 1) : 0;
      ok = ok && len <= ReadLimits::kMaxStringBytes;
      if (ok) out.emplace_back(s != nullptr ? s : "", len);
      H5free_memory(s);
    }
    return ok;
  }
  const std::size_t size = H5Tget_size(type);
  if (size == 0 || size > ReadLimits::kMaxStringBytes / std::max<hsize_t>(n, 1)) return false;
  std::vector<char> buf(size * static_cast<std::size_t>(n) + 1, '\0');
  if (H5Aread(attr, type, buf.data()) < 0) return false;
  for (hsize_t i = 0; i < n; ++i) {
    const char* s = buf.data() + i * size;
    out.emplace_back(s, strnlen(s, size));
  }
  return true;
}

}  // namespace

AttributeValue readAttribute(hid_t attr) {
  AttributeValue v;
  Id type(H5Aget_type(attr), H5Tclose);
  Id space(H5Aget_space(attr), H5Sclose);
  if (!type.valid() || !space.valid()) return v;
  const H5S_class_t sclass = H5Sget_simple_extent_type(space.get());
  const H5T_class_t tclass = H5Tget_class(type.get());
  const bool one_d = sclass == H5S_SIMPLE && H5Sget_simple_extent_ndims(space.get()) == 1;
  if (sclass != H5S_SCALAR && sclass != H5S_NULL && !one_d) return v;
  const hssize_t points = sclass == H5S_NULL ? 0 : H5Sget_simple_extent_npoints(space.get());
  // Attributes are small by nature; a huge declared extent is a defective file, not data.
  if (points < 0 || points > (1 << 20)) return v;
  const auto n = static_cast<hsize_t>(points);
  if (tclass == H5T_STRING) {
    if (!readStrings(attr, type.get(), n, v.texts)) return v;
    if (sclass == H5S_SCALAR) {
      v.kind = AttributeValue::kString;
      v.text = v.texts.empty() ? std::string() : v.texts.front();
      v.texts.clear();
    } else {
      v.kind = AttributeValue::kStringList;
    }
    return v;
  }
  if (tclass != H5T_FLOAT && tclass != H5T_INTEGER) return v;
  v.numbers.resize(static_cast<std::size_t>(n));
  if (n > 0 && H5Aread(attr, H5T_NATIVE_DOUBLE, v.numbers.data()) < 0) return AttributeValue{};
  v.kind = sclass == H5S_SCALAR ? AttributeValue::kScalar : AttributeValue::kVector;
  return v;
}

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
