// SPDX-License-Identifier: GPL-3.0-or-later
// A netCDF-like dataset as a writer describes it: dimensions, typed variables with attributes,
// then every variable's values in blocks of rows. A writer that describes its file through this
// interface does it once for two destinations: NetcdfDataset (io/netcdf_dataset.hpp) puts it into a
// netCDF file, MemoryDataset (io/memory_dataset.hpp) keeps it in memory, where the Python package
// makes an xarray.Dataset of it that equals the file variable by variable (the UGRID writer,
// mesh_files/ugrid_writer.hpp, is such a writer).
//
// Calls come in netCDF's order: start(), then dim()/var() and attributes, end_definitions(), then
// put() (rows of a variable in any order; a scalar variable holds 0 from end_definitions()).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace aq::io {

/// A variable's or attribute's type: netCDF's NC_BYTE, NC_SHORT, NC_INT, NC_INT64, NC_DOUBLE.
enum class DataType : std::uint8_t { kByte, kShort, kInt, kInt64, kDouble };

/// Bytes of one value of `t`.
std::size_t data_type_size(DataType t);

class DatasetSink {
 public:
  /// The variable id of the dataset's own (global) attributes.
  static constexpr int kGlobal = -1;

  virtual ~DatasetSink() = default;

  /// Before the first definition: whether some index needs 64 bits (the file then needs the
  /// netCDF-4 format even when uncompressed).
  virtual void start(bool large_indices) = 0;
  /// A dimension; returns its id.
  virtual int dim(const std::string& name, std::int64_t length) = 0;
  /// A variable over `dims` (ids, slowest first; none: a scalar); returns its id.
  virtual int var(const std::string& name, DataType type, const std::vector<int>& dims) = 0;
  /// Attributes of variable `var` (or kGlobal): text, or numbers of the given type.
  virtual void text(int var, const std::string& name, std::string_view value) = 0;
  virtual void numbers(int var, const std::string& name, DataType type, const std::vector<double>& values) = 0;
  /// Ends the definitions; every scalar variable holds 0 afterwards.
  virtual void end_definitions() = 0;
  /// Rows [row, row + rows) of `var` (along its first dimension, each row the product of the
  /// other dimensions' lengths), converted to the variable's type.
  virtual void put(int var, std::int64_t row, std::int64_t rows, const double* values) = 0;
  virtual void put(int var, std::int64_t row, std::int64_t rows, const long long* values) = 0;
  virtual void put(int var, std::int64_t row, std::int64_t rows, const int* values) = 0;
  virtual void put(int var, std::int64_t row, std::int64_t rows, const short* values) = 0;
  virtual void put(int var, std::int64_t row, std::int64_t rows, const signed char* values) = 0;

  /// One number attribute.
  void number(int var, const std::string& name, DataType type, double value) { numbers(var, name, type, {value}); }
};

}  // namespace aq::io
