// SPDX-License-Identifier: GPL-3.0-or-later
// A dataset in memory (see memory_dataset.hpp).
#include "io/memory_dataset.hpp"

#include <fmt/format.h>

#include <cstring>

#include "core/error.hpp"

namespace aq::io {

std::size_t data_type_size(DataType t) {
  switch (t) {
    case DataType::kByte:
      return 1;
    case DataType::kShort:
      return 2;
    case DataType::kInt:
      return 4;
    case DataType::kInt64:
    case DataType::kDouble:
      return 8;
  }
  return 8;
}

int MemoryDataset::dim(const std::string& name, std::int64_t length) {
  if (defined_) throw InternalError(fmt::format("memory dataset: dimension {} after the definitions", name));
  dims_.push_back({name, length});
  return static_cast<int>(dims_.size()) - 1;
}

int MemoryDataset::var(const std::string& name, DataType type, const std::vector<int>& dims) {
  if (defined_) throw InternalError(fmt::format("memory dataset: variable {} after the definitions", name));
  for (const int d : dims)
    if (d < 0 || d >= static_cast<int>(dims_.size()))
      throw InternalError(fmt::format("memory dataset: variable {} over an unknown dimension", name));
  Variable v;
  v.name = name;
  v.type = type;
  v.dims = dims;
  vars_.push_back(std::move(v));
  return static_cast<int>(vars_.size()) - 1;
}

std::vector<MemoryDataset::Attribute>& MemoryDataset::attributes_of(int var) {
  if (var == kGlobal) return global_;
  if (var < 0 || var >= static_cast<int>(vars_.size()))
    throw InternalError(fmt::format("memory dataset: attribute of an unknown variable {}", var));
  return vars_[static_cast<std::size_t>(var)].attributes;
}

void MemoryDataset::text(int var, const std::string& name, std::string_view value) {
  Attribute a;
  a.name = name;
  a.is_text = true;
  a.text = std::string(value);
  attributes_of(var).push_back(std::move(a));
}

void MemoryDataset::numbers(int var, const std::string& name, DataType type, const std::vector<double>& values) {
  Attribute a;
  a.name = name;
  a.type = type;
  a.values = values;
  attributes_of(var).push_back(std::move(a));
}

void MemoryDataset::end_definitions() {
  defined_ = true;
  for (Variable& v : vars_) {
    std::int64_t n = 1;
    for (const int d : v.dims) n *= dims_[static_cast<std::size_t>(d)].length;
    // Zero-filled: a scalar (container) variable holds 0, as the file writer puts there.
    v.data.assign(static_cast<std::size_t>(n) * data_type_size(v.type), 0);
  }
}

template <typename T>
void MemoryDataset::put_values(int var, std::int64_t row, std::int64_t rows, const T* values) {
  if (!defined_ || var < 0 || var >= static_cast<int>(vars_.size()))
    throw InternalError("memory dataset: values before the definitions or of an unknown variable");
  Variable& v = vars_[static_cast<std::size_t>(var)];
  std::int64_t per_row = 1;
  for (std::size_t k = 1; k < v.dims.size(); ++k) per_row *= dims_[static_cast<std::size_t>(v.dims[k])].length;
  const std::int64_t first = v.dims.empty() ? 0 : row * per_row;
  const std::int64_t count = v.dims.empty() ? 1 : rows * per_row;
  const std::size_t size = data_type_size(v.type);
  if (row < 0 || rows < 0 || static_cast<std::size_t>(first + count) * size > v.data.size())
    throw InternalError(fmt::format("memory dataset: rows {}..{} of {} are out of range", row, row + rows, v.name));
  auto store = [&](auto tag) {
    using U = decltype(tag);
    unsigned char* out = v.data.data() + static_cast<std::size_t>(first) * sizeof(U);
    for (std::int64_t k = 0; k < count; ++k) {
      const U x = static_cast<U>(values[k]);
      std::memcpy(out + static_cast<std::size_t>(k) * sizeof(U), &x, sizeof(U));
    }
  };
  switch (v.type) {
    case DataType::kByte:
      store(static_cast<signed char>(0));
      break;
    case DataType::kShort:
      store(static_cast<short>(0));
      break;
    case DataType::kInt:
      store(0);
      break;
    case DataType::kInt64:
      store(static_cast<long long>(0));
      break;
    case DataType::kDouble:
      store(0.0);
      break;
  }
}

void MemoryDataset::put(int var, std::int64_t row, std::int64_t rows, const double* values) {
  put_values(var, row, rows, values);
}
void MemoryDataset::put(int var, std::int64_t row, std::int64_t rows, const long long* values) {
  put_values(var, row, rows, values);
}
void MemoryDataset::put(int var, std::int64_t row, std::int64_t rows, const int* values) {
  put_values(var, row, rows, values);
}
void MemoryDataset::put(int var, std::int64_t row, std::int64_t rows, const short* values) {
  put_values(var, row, rows, values);
}
void MemoryDataset::put(int var, std::int64_t row, std::int64_t rows, const signed char* values) {
  put_values(var, row, rows, values);
}

}  // namespace aq::io
