// SPDX-License-Identifier: GPL-3.0-or-later
// Shared by the netCDF readers and writers (xygrid, ROMS grid, nesting, contact): status checks
// that throw with the path and nc_strerror, the attribute writer, and an open-file handle closed
// on scope exit.
#pragma once

#include <fmt/format.h>
#include <netcdf.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <type_traits>
#include <variant>

#include "core/error.hpp"
#include "io/attribute_value.hpp"

namespace aq::io {

/// What a failed write to `path` most likely ran into, for a message: ": No space left on device
/// (ENOSPC)" when errno says so or the file system of `path` has (almost) no free block left,
/// the errno text for EFBIG/EDQUOT/EIO, else "". libnetcdf and HDF5 report a full disk only as
/// "HDF error" or "I/O failure"; this names it.
std::string write_failure_note(const std::filesystem::path& path);

/// Throws E("<path>: netCDF <what>: <nc_strerror>") unless status is NC_NOERR; an OutputError
/// also gets write_failure_note().
template <typename E>
void nc_check(int status, const std::filesystem::path& path, const std::string& what) {
  if (status == NC_NOERR) return;
  std::string note;
  if constexpr (std::is_same_v<E, OutputError>) note = write_failure_note(path);
  throw E(fmt::format("{}: netCDF {}: {}{}", path.string(), what, nc_strerror(status), note));
}

/// Writes a text attribute; OutputError naming the path and attribute on failure.
inline void put_text(int nc, int var, const char* name, const std::string& text, const std::filesystem::path& path) {
  nc_check<OutputError>(nc_put_att_text(nc, var, name, text.size(), text.c_str()), path,
                        fmt::format("attribute {}", name));
}

/// Writes attribute `name` of `var` (NC_GLOBAL for a global one): text as NC_CHAR, a real number
/// as one NC_DOUBLE, an integer as NC_INT64 in a file that has 64-bit integers (netCDF-4, CDF-5)
/// and otherwise (classic files) as NC_INT when it fits in 32 bits, else as NC_DOUBLE. The one
/// rule of every writer (the ROMS, xygrid, nesting and contact files). OutputError naming the path
/// and the attribute on failure.
void put_attribute(int nc, int var, const std::string& name, const AttributeValue& value,
                   const std::filesystem::path& path);

/// put_attribute() for every (name, value) of `attributes` in their order (a map's or a list's).
template <typename Attributes>
void put_attributes(int nc, int var, const Attributes& attributes, const std::filesystem::path& path) {
  for (const auto& [name, value] : attributes) put_attribute(nc, var, name, value, path);
}

/// A global text attribute, or "" when it is missing or not text (trailing NULs removed).
inline std::string global_text(int nc, const char* name) {
  nc_type type = NC_NAT;
  std::size_t len = 0;
  if (nc_inq_att(nc, NC_GLOBAL, name, &type, &len) != NC_NOERR || type != NC_CHAR) return {};
  std::string text(len, '\0');
  if (len > 0 && nc_get_att_text(nc, NC_GLOBAL, name, text.data()) != NC_NOERR) return {};
  while (!text.empty() && text.back() == '\0') text.pop_back();
  return text;
}

/// A numeric global attribute of one value, or NaN when it is missing or not numeric.
inline double global_number(int nc, const char* name) {
  nc_type type = NC_NAT;
  std::size_t len = 0;
  if (nc_inq_att(nc, NC_GLOBAL, name, &type, &len) != NC_NOERR || len != 1 || type == NC_CHAR || type == NC_STRING)
    return std::numeric_limits<double>::quiet_NaN();
  double v = 0.0;
  if (nc_get_att_double(nc, NC_GLOBAL, name, &v) != NC_NOERR) return std::numeric_limits<double>::quiet_NaN();
  return v;
}

/// An open netCDF file id, aborted on scope exit (only when another error is already propagating:
/// nc_abort releases the file in libnetcdf and HDF5 without flushing, so a file left behind by a
/// failed write, a full disk, is not flushed again by HDF5's exit handler, which crashed).
class NcFile {
 public:
  NcFile() = default;
  NcFile(const NcFile&) = delete;
  NcFile& operator=(const NcFile&) = delete;
  ~NcFile() {
    if (id_ >= 0) nc_abort(id_);
  }
  /// Where nc_create/nc_open store the id.
  int* out() { return &id_; }
  [[nodiscard]] int id() const { return id_; }
  /// Closes and returns nc_close's status (data are flushed here); aborts the file when the
  /// close fails, so nothing of it stays open.
  int close() {
    const int status = nc_close(id_);
    if (status != NC_NOERR) nc_abort(id_);
    id_ = -1;
    return status;
  }

 private:
  int id_ = -1;
};

/// Checks a classic netCDF file's header (CDF-1/2/5; io/netcdf_header.cpp): every count within
/// the file and every variable's data inside it. Other files (netCDF-4) pass unchecked. Throws
/// InputError naming the path and what is damaged.
void check_netcdf_header(const std::filesystem::path& path);

/// Refuses (InputError naming the path) a file whose declared dimensions would need more than
/// 80 % of this machine's memory to hold `values` doubles: a netCDF-4 file can declare
/// 100000 x 100000 nodes in a few bytes. Computed in floating point (no overflow).
void check_declared_size(const std::filesystem::path& path, double values, const std::string& what);

/// check_netcdf_header() then nc_open for reading into `nc`; InputError naming the path.
void open_for_reading(const std::filesystem::path& path, NcFile& nc);

}  // namespace aq::io
