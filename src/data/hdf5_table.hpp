#pragma once
// Tables in HDF5: one compound dataset, one row per record, one named field per column (float64, int64 or
// variable-length UTF-8 string). h5py reads one as a structured array (`f["runs"][:]`, `f["runs"]["mode"]`),
// pandas as `pd.DataFrame(f["runs"][:])`. Each column's units and description are string-list attributes of the
// dataset (`column_units`, `column_descriptions`, in field order).
//
// An extendible table (unlimited rows, chunked) can be appended to in place (appendTable) and flushed, which is
// how a long batch records its results as they arrive. Writing goes through h5::Writer (RuntimeError naming the
// target), reading through h5::Reader (InputError naming the file and the dataset).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "data/hdf5.hpp"

namespace centaur::data::h5 {

struct Column {
  enum class Type { kFloat64, kInt64, kString };
  std::string name;
  Type type = Type::kFloat64;
  std::string units;        ///< "" where none applies
  std::string description;
};

/// Column-major table: the cells of column c are in f64[c], i64[c] or str[c] according to its type (the other
/// two vectors of that column stay empty).
class Table {
 public:
  Table() = default;
  explicit Table(std::vector<Column> columns);

  const std::vector<Column>& columns() const { return columns_; }
  std::size_t rows() const { return rows_; }
  /// Index of the column `name`, or npos.
  std::size_t find(const std::string& name) const;
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

  /// Appends a row of default cells (0, 0, ""); returns its index.
  std::size_t addRow();
  void set(std::size_t row, std::size_t column, double value);
  void set(std::size_t row, std::size_t column, std::int64_t value);
  void set(std::size_t row, std::size_t column, const std::string& value);

  double number(std::size_t row, std::size_t column) const;  ///< float64 or int64 cell as a double
  std::int64_t integer(std::size_t row, std::size_t column) const;
  const std::string& text(std::size_t row, std::size_t column) const;

  /// Rows [first, first + count) as a new table with the same columns.
  Table slice(std::size_t first, std::size_t count) const;
  /// Appends the rows of `other` (same columns, by name and type; std::invalid_argument otherwise).
  void append(const Table& other);

  // Raw column storage (for the HDF5 writer and reader).
  std::vector<std::vector<double>> f64;
  std::vector<std::vector<std::int64_t>> i64;
  std::vector<std::vector<std::string>> str;

 private:
  std::vector<Column> columns_;
  std::size_t rows_ = 0;
};

/// Writes `table` as the compound dataset `name` in `loc`. `extendible`: unlimited rows in chunks of
/// `chunk_rows` (appendTable may add rows later); otherwise exactly rows() rows, deflate-compressed.
void writeTable(const Writer& w, hid_t loc, const std::string& name, const Table& table, const std::string& description,
                bool extendible = false, std::size_t chunk_rows = 256);

/// Appends the rows of `rows` to the extendible table `name` of `loc` (same columns in the same order).
void appendTable(const Writer& w, hid_t loc, const std::string& name, const Table& rows);

/// Reads the compound dataset `name` of `loc` (any numeric field as float64 or int64 by its HDF5 class, string
/// fields of variable or fixed length). `key` names it in messages.
Table readTable(const Reader& r, hid_t loc, const std::string& key, const std::string& name);

}  // namespace centaur::data::h5
