// The HDF5 layer's handles, error messages, writer and attribute reading (the reader is in hdf5_reader.cpp).
#include "data/hdf5.hpp"

#include <algorithm>
#include <sstream>
#include <utility>

#include "common/error.hpp"

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

}  // namespace centaur::data::h5
