// SPDX-License-Identifier: GPL-3.0-or-later
// A dataset written into a netCDF file (see dataset.hpp), with the netCDF-C API. deflate 1..9:
// netCDF-4 (HDF5) with every array chunked (65536 rows of the first dimension, whole rows) and
// compressed (shuffle + deflate at that level); 0: the classic 64-bit-offset format, uncompressed
// (netCDF-4 when start() is told of 64-bit indices). No fill values are written (NC_NOFILL), so
// every value must be put; scalar variables get 0 at end_definitions(). Every call is checked and a
// failure throws OutputError naming the file (with write_failure_note: a full disk says so). The
// destructor aborts, and so deletes, a file that was not closed.
//
// With deflate, the chunks of each put that starts on a chunk boundary are compressed ahead on the
// OpenMP team (io/deflate_ahead.hpp: the same bytes, HDF5 still writes them in its own order), so
// a writer that wants the time saved puts whole chunks' worth of rows at a time, each variable's
// rows made just before its put. 64-bit indices put into an NC_INT variable are narrowed here
// once (a plain copy, not netCDF's checked conversion of every value; also what the cache must
// see: the values in the file's type).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/dataset.hpp"
#include "io/deflate_ahead.hpp"

namespace aq::io {

class NetcdfDataset final : public DatasetSink {
 public:
  /// Throws ConfigError naming output.ugrid_deflate when `deflate` is outside 0..9. The file is
  /// created by start().
  NetcdfDataset(std::filesystem::path path, int deflate);
  ~NetcdfDataset() override;
  NetcdfDataset(const NetcdfDataset&) = delete;
  NetcdfDataset& operator=(const NetcdfDataset&) = delete;

  void start(bool large_indices) override;
  int dim(const std::string& name, std::int64_t length) override;
  int var(const std::string& name, DataType type, const std::vector<int>& dims) override;
  void text(int var, const std::string& name, std::string_view value) override;
  void numbers(int var, const std::string& name, DataType type, const std::vector<double>& values) override;
  void end_definitions() override;
  void put(int var, std::int64_t row, std::int64_t rows, const double* values) override;
  void put(int var, std::int64_t row, std::int64_t rows, const long long* values) override;
  void put(int var, std::int64_t row, std::int64_t rows, const int* values) override;
  void put(int var, std::int64_t row, std::int64_t rows, const short* values) override;
  void put(int var, std::int64_t row, std::int64_t rows, const signed char* values) override;

  /// Closes the file (its data are flushed here). Throws OutputError naming it.
  void close();

 private:
  void check(int status, const std::string& what) const;
  // start[] and count[] of rows [row, row + rows) of `var`.
  void extent(int var, std::int64_t row, std::int64_t rows, std::vector<std::size_t>& start,
              std::vector<std::size_t>& count) const;
  // Rows [row, row + rows) of `var` from `values`, compressed ahead first where they start a chunk.
  template <typename T>
  void put_rows(int var, std::int64_t row, std::int64_t rows, const T* values);

  static constexpr std::size_t kChunkRows = std::size_t{1} << 16;
  std::filesystem::path path_;
  int deflate_ = 0;
  int id_ = -1;
  std::vector<std::size_t> dim_len_;        ///< length of each defined dimension, by id
  std::vector<std::vector<int>> var_dims_;  ///< dimensions of each defined variable, by id
  std::vector<std::string> var_names_;      ///< and its name
  std::vector<int> scalars_;                ///< variables without dimensions (topology, grid mappings)
  std::vector<DataType> var_types_;         ///< type of each defined variable, by id
  std::vector<std::size_t> chunk_rows_;     ///< by variable: rows per chunk of a compressed one, else 0
  std::vector<int> narrow_;                 ///< put's int copy of 64-bit indices for an NC_INT variable
  // With deflate: the chunks of each put compressed ahead on the OpenMP team; alive until after
  // nc_close / nc_abort (declared last: destroyed first, after the destructor's nc_abort).
  std::optional<DeflateAhead> ahead_;
};

}  // namespace aq::io
