#include "data/hdf5_table.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "common/error.hpp"

namespace centaur::data::h5 {

// ---- Table -------------------------------------------------------------------------------------------

Table::Table(std::vector<Column> columns) : columns_(std::move(columns)) {
  f64.resize(columns_.size());
  i64.resize(columns_.size());
  str.resize(columns_.size());
}

std::size_t Table::find(const std::string& name) const {
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (columns_[c].name == name) return c;
  }
  return npos;
}

std::size_t Table::addRow() {
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    switch (columns_[c].type) {
      case Column::Type::kFloat64: f64[c].push_back(0.0); break;
      case Column::Type::kInt64: i64[c].push_back(0); break;
      case Column::Type::kString: str[c].emplace_back(); break;
    }
  }
  return rows_++;
}

void Table::set(std::size_t row, std::size_t column, double value) {
  if (columns_.at(column).type == Column::Type::kInt64) {
    i64[column].at(row) = static_cast<std::int64_t>(value);
  } else {
    f64[column].at(row) = value;
  }
}

void Table::set(std::size_t row, std::size_t column, std::int64_t value) {
  if (columns_.at(column).type == Column::Type::kFloat64) {
    f64[column].at(row) = static_cast<double>(value);
  } else {
    i64[column].at(row) = value;
  }
}

void Table::set(std::size_t row, std::size_t column, const std::string& value) { str[column].at(row) = value; }

double Table::number(std::size_t row, std::size_t column) const {
  if (columns_.at(column).type == Column::Type::kInt64) return static_cast<double>(i64[column].at(row));
  return f64[column].at(row);
}

std::int64_t Table::integer(std::size_t row, std::size_t column) const {
  if (columns_.at(column).type == Column::Type::kFloat64) return static_cast<std::int64_t>(f64[column].at(row));
  return i64[column].at(row);
}

const std::string& Table::text(std::size_t row, std::size_t column) const { return str[column].at(row); }

Table Table::slice(std::size_t first, std::size_t count) const {
  Table out(columns_);
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    auto take = [&](const auto& from, auto& to) {
      if (!from.empty()) to.assign(from.begin() + static_cast<std::ptrdiff_t>(first),
                                   from.begin() + static_cast<std::ptrdiff_t>(first + count));
    };
    take(f64[c], out.f64[c]);
    take(i64[c], out.i64[c]);
    take(str[c], out.str[c]);
  }
  out.rows_ = count;
  return out;
}

void Table::append(const Table& other) {
  if (other.columns_.size() != columns_.size()) throw std::invalid_argument("tables with different columns");
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (other.columns_[c].name != columns_[c].name || other.columns_[c].type != columns_[c].type) {
      throw std::invalid_argument("tables with different columns ('" + columns_[c].name + "')");
    }
    f64[c].insert(f64[c].end(), other.f64[c].begin(), other.f64[c].end());
    i64[c].insert(i64[c].end(), other.i64[c].begin(), other.i64[c].end());
    str[c].insert(str[c].end(), other.str[c].begin(), other.str[c].end());
  }
  rows_ += other.rows_;
}

// ---- HDF5 types and row buffers ---------------------------------------------------------------------

namespace {

constexpr std::size_t kCell = 8;  // every field is 8 bytes in memory: double, int64_t or char*
static_assert(sizeof(double) == kCell && sizeof(std::int64_t) == kCell && sizeof(char*) == kCell,
              "the row layout assumes 8-byte cells");

Id stringType() {
  Id t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t.get(), H5T_VARIABLE);
  H5Tset_cset(t.get(), H5T_CSET_UTF8);
  return t;
}

/// The compound type of `columns`: file (little endian) or native memory layout; both 8 bytes per field.
Id compoundType(const Writer& w, const std::vector<Column>& columns, bool file) {
  Id t(w.check(H5Tcreate(H5T_COMPOUND, kCell * columns.size()), "compound type"), H5Tclose);
  const Id s = stringType();
  for (std::size_t c = 0; c < columns.size(); ++c) {
    hid_t member = s.get();
    if (columns[c].type == Column::Type::kFloat64) member = file ? H5T_IEEE_F64LE : H5T_NATIVE_DOUBLE;
    if (columns[c].type == Column::Type::kInt64) member = file ? H5T_STD_I64LE : H5T_NATIVE_INT64;
    w.ok(H5Tinsert(t.get(), columns[c].name.c_str(), kCell * c, member), "column '" + columns[c].name + "'");
  }
  return t;
}

/// Row-major buffer of the table's cells (strings as pointers into `t`, valid while `t` lives).
std::vector<unsigned char> packRows(const Table& t) {
  const std::size_t n = t.columns().size();
  std::vector<unsigned char> buf(t.rows() * n * kCell);
  for (std::size_t r = 0; r < t.rows(); ++r) {
    for (std::size_t c = 0; c < n; ++c) {
      unsigned char* cell = buf.data() + (r * n + c) * kCell;
      switch (t.columns()[c].type) {
        case Column::Type::kFloat64: std::memcpy(cell, &t.f64[c][r], kCell); break;
        case Column::Type::kInt64: std::memcpy(cell, &t.i64[c][r], kCell); break;
        case Column::Type::kString: {
          const char* p = t.str[c][r].c_str();
          std::memcpy(cell, &p, kCell);
          break;
        }
      }
    }
  }
  return buf;
}

void columnAttributes(const Writer& w, hid_t ds, const std::vector<Column>& columns, const std::string& description) {
  std::vector<std::string> units, descriptions;
  for (const auto& c : columns) {
    units.push_back(c.units);
    descriptions.push_back(c.description);
  }
  w.stringAttribute(ds, "description", description);
  w.stringListAttribute(ds, "column_units", units);
  w.stringListAttribute(ds, "column_descriptions", descriptions);
}

}  // namespace

void writeTable(const Writer& w, hid_t loc, const std::string& name, const Table& table, const std::string& description,
                bool extendible, std::size_t chunk_rows) {
  const hsize_t rows = table.rows();
  const hsize_t max_rows = extendible ? H5S_UNLIMITED : rows;
  Id space(w.check(H5Screate_simple(1, &rows, &max_rows), "dataspace"), H5Sclose);
  Id dcpl(w.check(H5Pcreate(H5P_DATASET_CREATE), "property list"), H5Pclose);
  if (extendible || rows > 0) {
    const hsize_t chunk = extendible ? std::max<hsize_t>(chunk_rows, 1) : std::min<hsize_t>(rows, 1024);
    w.ok(H5Pset_chunk(dcpl.get(), 1, &chunk), "chunking");
    if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) w.ok(H5Pset_deflate(dcpl.get(), kDeflateLevel), "deflate filter");
  }
  const Id file_type = compoundType(w, table.columns(), true);
  const Id mem_type = compoundType(w, table.columns(), false);
  Id ds(w.check(H5Dcreate2(loc, name.c_str(), file_type.get(), space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                "dataset '" + name + "'"),
        H5Dclose);
  if (rows > 0) {
    const std::vector<unsigned char> buf = packRows(table);
    w.ok(H5Dwrite(ds.get(), mem_type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()), "dataset '" + name + "'");
  }
  columnAttributes(w, ds.get(), table.columns(), description);
}

void appendTable(const Writer& w, hid_t loc, const std::string& name, const Table& rows) {
  if (rows.rows() == 0) return;
  Id ds(w.check(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "dataset '" + name + "'"), H5Dclose);
  Id type(w.check(H5Dget_type(ds.get()), "type of '" + name + "'"), H5Tclose);
  const auto& columns = rows.columns();
  if (H5Tget_class(type.get()) != H5T_COMPOUND || H5Tget_nmembers(type.get()) != static_cast<int>(columns.size())) {
    w.fail("dataset '" + name + "' is not a table with " + std::to_string(columns.size()) + " columns");
  }
  for (std::size_t c = 0; c < columns.size(); ++c) {
    char* member = H5Tget_member_name(type.get(), static_cast<unsigned>(c));
    const bool same = member != nullptr && columns[c].name == member;
    H5free_memory(member);
    if (!same) w.fail("dataset '" + name + "': column " + std::to_string(c) + " is not '" + columns[c].name + "'");
  }
  Id space(w.check(H5Dget_space(ds.get()), "dataspace"), H5Sclose);
  hsize_t old_rows = 0;
  H5Sget_simple_extent_dims(space.get(), &old_rows, nullptr);
  const hsize_t add = rows.rows(), total = old_rows + add;
  w.ok(H5Dset_extent(ds.get(), &total), "extending '" + name + "'");
  Id file_space(w.check(H5Dget_space(ds.get()), "dataspace"), H5Sclose);
  w.ok(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &old_rows, nullptr, &add, nullptr), "selection");
  Id mem_space(w.check(H5Screate_simple(1, &add, nullptr), "dataspace"), H5Sclose);
  const Id mem_type = compoundType(w, columns, false);
  const std::vector<unsigned char> buf = packRows(rows);
  w.ok(H5Dwrite(ds.get(), mem_type.get(), mem_space.get(), file_space.get(), H5P_DEFAULT, buf.data()),
       "appending to '" + name + "'");
}

Table readTable(const Reader& r, hid_t loc, const std::string& key, const std::string& name) {
  const std::vector<hsize_t> dims = r.shape(loc, key, name);
  if (dims.size() != 1) r.fail(key, "a table must be one-dimensional, found shape " + shapeText(dims));
  Id ds(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  Id type(H5Dget_type(ds.get()), H5Tclose);
  if (!type.valid() || H5Tget_class(type.get()) != H5T_COMPOUND) r.fail(key, "not a table (compound dataset)");
  const int n = H5Tget_nmembers(type.get());
  if (n <= 0) r.fail(key, "table without columns");
  std::vector<Column> columns(static_cast<std::size_t>(n));
  for (int c = 0; c < n; ++c) {
    char* member = H5Tget_member_name(type.get(), static_cast<unsigned>(c));
    columns[c].name = member != nullptr ? member : "";
    H5free_memory(member);
    const H5T_class_t cls = H5Tget_member_class(type.get(), static_cast<unsigned>(c));
    if (cls == H5T_FLOAT) {
      columns[c].type = Column::Type::kFloat64;
    } else if (cls == H5T_INTEGER) {
      columns[c].type = Column::Type::kInt64;
    } else if (cls == H5T_STRING) {
      Id mt(H5Tget_member_type(type.get(), static_cast<unsigned>(c)), H5Tclose);
      if (H5Tis_variable_str(mt.get()) <= 0) r.fail(key, "column '" + columns[c].name + "': fixed-length strings are not supported");
      columns[c].type = Column::Type::kString;
    } else {
      r.fail(key, "column '" + columns[c].name + "' is neither a number nor a string");
    }
  }
  const hsize_t rows = dims[0];
  if (rows > (hsize_t(1) << 31) / (kCell * static_cast<hsize_t>(n))) r.fail(key, "table too large to read");
  if (r.hasAttribute(ds.get(), "column_units")) {
    const std::vector<std::string> units = r.textList(ds.get(), key + "@column_units", "column_units");
    for (std::size_t c = 0; c < columns.size() && c < units.size(); ++c) columns[c].units = units[c];
  }
  if (r.hasAttribute(ds.get(), "column_descriptions")) {
    const std::vector<std::string> d = r.textList(ds.get(), key + "@column_descriptions", "column_descriptions");
    for (std::size_t c = 0; c < columns.size() && c < d.size(); ++c) columns[c].description = d[c];
  }
  Table table(columns);
  if (rows == 0) return table;
  const Writer w(r.path());
  const Id mem_type = compoundType(w, columns, false);
  std::vector<unsigned char> buf(static_cast<std::size_t>(rows) * columns.size() * kCell);
  if (H5Dread(ds.get(), mem_type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0) {
    r.fail(key, "cannot read the table (corrupt?)" + errorStackMessage());
  }
  for (hsize_t i = 0; i < rows; ++i) {
    const std::size_t row = table.addRow();
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const unsigned char* cell = buf.data() + (row * columns.size() + c) * kCell;
      if (columns[c].type == Column::Type::kFloat64) {
        std::memcpy(&table.f64[c][row], cell, kCell);
      } else if (columns[c].type == Column::Type::kInt64) {
        std::memcpy(&table.i64[c][row], cell, kCell);
      } else {
        const char* p = nullptr;
        std::memcpy(&p, cell, kCell);
        table.str[c][row] = p != nullptr ? p : "";
      }
    }
  }
  Id space(H5Dget_space(ds.get()), H5Sclose);
  H5Dvlen_reclaim(mem_type.get(), space.get(), H5P_DEFAULT, buf.data());
  return table;
}

}  // namespace centaur::data::h5
