// SPDX-License-Identifier: GPL-3.0-or-later
// A dataset written into a netCDF file (see netcdf_dataset.hpp).
#include "io/netcdf_dataset.hpp"

#include <fmt/format.h>
#include <netcdf.h>

#include <algorithm>

#include "core/error.hpp"
#include "io/netcdf_file.hpp"

namespace aq::io {

namespace {

nc_type nc_type_of(DataType t) {
  switch (t) {
    case DataType::kByte:
      return NC_BYTE;
    case DataType::kShort:
      return NC_SHORT;
    case DataType::kInt:
      return NC_INT;
    case DataType::kInt64:
      return NC_INT64;
    case DataType::kDouble:
      return NC_DOUBLE;
  }
  return NC_DOUBLE;
}

int nc_var_of(int var) { return var == DatasetSink::kGlobal ? NC_GLOBAL : var; }

// netCDF's typed nc_put_vara for each value type of DatasetSink::put.
int put_vara(int id, int v, const std::size_t* s, const std::size_t* c, const double* d) {
  return nc_put_vara_double(id, v, s, c, d);
}
int put_vara(int id, int v, const std::size_t* s, const std::size_t* c, const long long* d) {
  return nc_put_vara_longlong(id, v, s, c, d);
}
int put_vara(int id, int v, const std::size_t* s, const std::size_t* c, const int* d) {
  return nc_put_vara_int(id, v, s, c, d);
}
int put_vara(int id, int v, const std::size_t* s, const std::size_t* c, const short* d) {
  return nc_put_vara_short(id, v, s, c, d);
}
int put_vara(int id, int v, const std::size_t* s, const std::size_t* c, const signed char* d) {
  return nc_put_vara_schar(id, v, s, c, d);
}

}  // namespace

NetcdfDataset::NetcdfDataset(std::filesystem::path path, int deflate) : path_(std::move(path)), deflate_(deflate) {
  if (deflate_ < 0 || deflate_ > 9)  // output.ugrid_deflate is validated at load
    throw InternalError(fmt::format("{}: deflate level {} is outside 0..9", path_.string(), deflate_));
}

NetcdfDataset::~NetcdfDataset() {
  if (id_ >= 0) nc_abort(id_);
}

void NetcdfDataset::check(int status, const std::string& what) const {
  if (status != NC_NOERR) {
    throw OutputError(
        fmt::format("{}: netCDF {}: {}{}", path_.string(), what, nc_strerror(status), write_failure_note(path_)));
  }
}

void NetcdfDataset::start(bool large_indices) {
  const int mode = NC_CLOBBER | (large_indices || deflate_ > 0 ? NC_NETCDF4 : NC_64BIT_OFFSET);
  check(nc_create(path_.c_str(), mode, &id_), "cannot create");
  int old = 0;
  check(nc_set_fill(id_, NC_NOFILL, &old), "nc_set_fill");
  if (deflate_ > 0) ahead_.emplace();
}

int NetcdfDataset::dim(const std::string& name, std::int64_t length) {
  int d = -1;
  check(nc_def_dim(id_, name.c_str(), static_cast<std::size_t>(length), &d), "define dimension " + name);
  if (static_cast<std::size_t>(d) >= dim_len_.size()) dim_len_.resize(static_cast<std::size_t>(d) + 1, 0);
  dim_len_[static_cast<std::size_t>(d)] = static_cast<std::size_t>(length);
  return d;
}

int NetcdfDataset::var(const std::string& name, DataType type, const std::vector<int>& dims) {
  int v = -1;
  check(nc_def_var(id_, name.c_str(), nc_type_of(type), static_cast<int>(dims.size()), dims.data(), &v),
        "define variable " + name);
  const auto uv = static_cast<std::size_t>(v);
  if (uv >= var_dims_.size()) {
    var_dims_.resize(uv + 1);
    var_names_.resize(uv + 1);
    var_types_.resize(uv + 1, DataType::kDouble);
    chunk_rows_.resize(uv + 1, 0);
  }
  var_dims_[uv] = dims;
  var_names_[uv] = name;
  var_types_[uv] = type;
  if (dims.empty()) scalars_.push_back(v);
  if (deflate_ > 0 && !dims.empty()) {
    std::vector<std::size_t> chunk;
    for (const int k : dims) chunk.push_back(dim_len_[static_cast<std::size_t>(k)]);
    chunk[0] = std::max<std::size_t>(1, std::min(chunk[0], kChunkRows));
    check(nc_def_var_chunking(id_, v, NC_CHUNKED, chunk.data()), "chunking of " + name);
    check(nc_def_var_deflate(id_, v, 1, 1, deflate_), "compression of " + name);
    chunk_rows_[uv] = chunk[0];
  }
  return v;
}

void NetcdfDataset::text(int var, const std::string& name, std::string_view value) {
  check(nc_put_att_text(id_, nc_var_of(var), name.c_str(), value.size(), value.data()), "attribute " + name);
}

void NetcdfDataset::numbers(int var, const std::string& name, DataType type, const std::vector<double>& values) {
  const int v = nc_var_of(var);
  const std::size_t n = values.size();
  int status = NC_NOERR;
  switch (type) {
    case DataType::kDouble:
      status = nc_put_att_double(id_, v, name.c_str(), NC_DOUBLE, n, values.data());
      break;
    case DataType::kInt: {
      const std::vector<int> x(values.begin(), values.end());
      status = nc_put_att_int(id_, v, name.c_str(), NC_INT, n, x.data());
      break;
    }
    case DataType::kInt64: {
      const std::vector<long long> x(values.begin(), values.end());
      status = nc_put_att_longlong(id_, v, name.c_str(), NC_INT64, n, x.data());
      break;
    }
    case DataType::kShort: {
      const std::vector<short> x(values.begin(), values.end());
      status = nc_put_att_short(id_, v, name.c_str(), NC_SHORT, n, x.data());
      break;
    }
    case DataType::kByte: {
      const std::vector<signed char> x(values.begin(), values.end());
      status = nc_put_att_schar(id_, v, name.c_str(), NC_BYTE, n, x.data());
      break;
    }
  }
  check(status, "attribute " + name);
}

void NetcdfDataset::end_definitions() {
  check(nc_enddef(id_), "end of definitions");
  // With NC_NOFILL an unwritten netCDF-4 scalar would hold whatever the memory held, and the
  // bytes would vary.
  const int zero = 0;
  for (const int v : scalars_) check(nc_put_var_int(id_, v, &zero), "write a scalar variable");
}

void NetcdfDataset::extent(int var, std::int64_t row, std::int64_t rows, std::vector<std::size_t>& start,
                           std::vector<std::size_t>& count) const {
  const std::vector<int>& dims = var_dims_.at(static_cast<std::size_t>(var));
  start.assign(dims.size(), 0);
  count.resize(dims.size());
  for (std::size_t k = 0; k < dims.size(); ++k) count[k] = dim_len_[static_cast<std::size_t>(dims[k])];
  if (!dims.empty()) {
    start[0] = static_cast<std::size_t>(row);
    count[0] = static_cast<std::size_t>(rows);
  }
}

template <typename T>
void NetcdfDataset::put_rows(int var, std::int64_t row, std::int64_t rows, const T* values) {
  const auto uv = static_cast<std::size_t>(var);
  std::vector<std::size_t> s, c;
  extent(var, row, rows, s, c);
  const std::size_t chunk_rows = chunk_rows_.at(uv);
  if (ahead_ && ahead_->active() && chunk_rows > 0 && static_cast<std::size_t>(row) % chunk_rows == 0) {
    std::size_t row_bytes = sizeof(T);
    for (std::size_t k = 1; k < c.size(); ++k) row_bytes *= c[k];
    ahead_->prepare(values, static_cast<std::size_t>(rows) * row_bytes, chunk_rows * row_bytes, sizeof(T), true,
                    deflate_);
  }
  check(put_vara(id_, var, s.data(), c.data(), values), "write " + var_names_[uv]);
}

void NetcdfDataset::put(int var, std::int64_t row, std::int64_t rows, const double* values) {
  put_rows(var, row, rows, values);
}
void NetcdfDataset::put(int var, std::int64_t row, std::int64_t rows, const long long* values) {
  if (var_types_.at(static_cast<std::size_t>(var)) == DataType::kInt) {
    std::size_t n = static_cast<std::size_t>(rows);
    const std::vector<int>& dims = var_dims_[static_cast<std::size_t>(var)];
    for (std::size_t k = 1; k < dims.size(); ++k) n *= dim_len_[static_cast<std::size_t>(dims[k])];
    narrow_.resize(n);  // kept: one allocation for every block
    for (std::size_t k = 0; k < n; ++k) narrow_[k] = static_cast<int>(values[k]);
    put_rows(var, row, rows, narrow_.data());
    return;
  }
  put_rows(var, row, rows, values);
}
void NetcdfDataset::put(int var, std::int64_t row, std::int64_t rows, const int* values) {
  put_rows(var, row, rows, values);
}
void NetcdfDataset::put(int var, std::int64_t row, std::int64_t rows, const short* values) {
  put_rows(var, row, rows, values);
}
void NetcdfDataset::put(int var, std::int64_t row, std::int64_t rows, const signed char* values) {
  put_rows(var, row, rows, values);
}

void NetcdfDataset::close() {
  const int id = id_;
  id_ = -1;
  const int status = nc_close(id);
  if (status != NC_NOERR) nc_abort(id);  // nothing of the file stays open for HDF5's exit handler
  check(status, "close");
}

}  // namespace aq::io
