// Shared by the netCDF readers and writers (xygrid, ROMS grid, nesting): status checks that
// throw with the path and nc_strerror, and an open-file handle closed on scope exit.
#pragma once

#include <fmt/format.h>
#include <netcdf.h>

#include <filesystem>
#include <string>

namespace aq::io {

/// Throws E("<path>: netCDF <what>: <nc_strerror>") unless status is NC_NOERR.
template <typename E>
void nc_check(int status, const std::filesystem::path& path, const std::string& what) {
  if (status != NC_NOERR) throw E(fmt::format("{}: netCDF {}: {}", path.string(), what, nc_strerror(status)));
}

/// An open netCDF file id, closed on scope exit (errors of that close are ignored: it only runs
/// when another error is already propagating, or after an explicit close()).
class NcFile {
 public:
  NcFile() = default;
  NcFile(const NcFile&) = delete;
  NcFile& operator=(const NcFile&) = delete;
  ~NcFile() {
    if (id_ >= 0) nc_close(id_);
  }
  /// Where nc_create/nc_open store the id.
  int* out() { return &id_; }
  [[nodiscard]] int id() const { return id_; }
  /// Closes and returns nc_close's status (data are flushed here).
  int close() {
    const int status = nc_close(id_);
    id_ = -1;
    return status;
  }

 private:
  int id_ = -1;
};

}  // namespace aq::io
