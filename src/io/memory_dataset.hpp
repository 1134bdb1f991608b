// SPDX-License-Identifier: GPL-3.0-or-later
// A dataset kept in memory (see dataset.hpp): what a writer would put into its netCDF file, as
// flat arrays with their dimensions and attributes, for callers that want the file's contents
// without a file (the Python package's to_xarray). Values are stored in the variable's own type
// (a long long put into an NC_INT variable becomes int), as netCDF stores them.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/dataset.hpp"

namespace aq::io {

class MemoryDataset final : public DatasetSink {
 public:
  struct Dimension {
    std::string name;
    std::int64_t length = 0;
  };
  struct Attribute {
    std::string name;
    bool is_text = false;
    std::string text;                   ///< is_text
    DataType type = DataType::kDouble;  ///< otherwise: the numbers and their type
    std::vector<double> values;
  };
  struct Variable {
    std::string name;
    DataType type = DataType::kDouble;
    std::vector<int> dims;              ///< dimension ids, slowest first
    std::vector<Attribute> attributes;  ///< in definition order
    std::vector<unsigned char> data;    ///< row-major values of `type` (sized by end_definitions)
  };

  void start(bool large_indices) override { large_indices_ = large_indices; }
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

  [[nodiscard]] const std::vector<Dimension>& dimensions() const { return dims_; }
  [[nodiscard]] const std::vector<Variable>& variables() const { return vars_; }
  [[nodiscard]] std::vector<Variable>& variables() { return vars_; }
  [[nodiscard]] const std::vector<Attribute>& global_attributes() const { return global_; }
  [[nodiscard]] bool large_indices() const { return large_indices_; }

 private:
  std::vector<Attribute>& attributes_of(int var);
  template <typename T>
  void put_values(int var, std::int64_t row, std::int64_t rows, const T* values);

  std::vector<Dimension> dims_;
  std::vector<Variable> vars_;
  std::vector<Attribute> global_;
  bool defined_ = false;
  bool large_indices_ = false;
};

}  // namespace aq::io
