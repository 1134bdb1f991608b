// A dataset written into a netCDF file (see dataset.hpp), with the netCDF-C API. deflate 1..9:
// netCDF-4 (HDF5) with every array chunked (65536 rows of the first dimension, whole rows) and
// compressed (shuffle + deflate at that level); 0: the classic 64-bit-offset format, uncompressed
// (netCDF-4 when start() is told of 64-bit indices). No fill values are written (NC_NOFILL), so
// every value must be put; scalar variables get 0 at end_definitions(). Every call is checked and a
// failure throws OutputError naming the file (with write_failure_note: a full disk says so). The
// destructor aborts, and so deletes, a file that was not closed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/dataset.hpp"

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

  static constexpr std::size_t kChunkRows = std::size_t{1} << 16;
  std::filesystem::path path_;
  int deflate_ = 0;
  int id_ = -1;
  std::vector<std::size_t> dim_len_;        ///< length of each defined dimension, by id
  std::vector<std::vector<int>> var_dims_;  ///< dimensions of each defined variable, by id
  std::vector<std::string> var_names_;      ///< and its name
  std::vector<int> scalars_;                ///< variables without dimensions (topology, grid mappings)
};

}  // namespace aq::io
