// SPDX-License-Identifier: GPL-3.0-or-later
// The attribute writer of every netCDF file aquatoria writes (see netcdf_file.hpp).
#include <fmt/format.h>
#include <netcdf.h>

#include "io/netcdf_file.hpp"

namespace aq::io {

void put_attribute(int nc, int var, const std::string& name, const AttributeValue& value,
                   const std::filesystem::path& path) {
  const std::string what = fmt::format("attribute {}", name);
  if (const auto* text = std::get_if<std::string>(&value)) {
    nc_check<OutputError>(nc_put_att_text(nc, var, name.c_str(), text->size(), text->c_str()), path, what);
    return;
  }
  if (const auto* real = std::get_if<double>(&value)) {
    nc_check<OutputError>(nc_put_att_double(nc, var, name.c_str(), NC_DOUBLE, 1, real), path, what);
    return;
  }
  const std::int64_t integer = std::get<std::int64_t>(value);
  int format = NC_FORMAT_CLASSIC;
  nc_check<OutputError>(nc_inq_format(nc, &format), path, "format");
  if (format == NC_FORMAT_NETCDF4 || format == NC_FORMAT_64BIT_DATA) {
    const long long v = integer;
    nc_check<OutputError>(nc_put_att_longlong(nc, var, name.c_str(), NC_INT64, 1, &v), path, what);
  } else if (integer >= -2147483647LL && integer <= 2147483647LL) {  // classic files have no 64-bit integers
    const int v = static_cast<int>(integer);
    nc_check<OutputError>(nc_put_att_int(nc, var, name.c_str(), NC_INT, 1, &v), path, what);
  } else {
    const double v = static_cast<double>(integer);
    nc_check<OutputError>(nc_put_att_double(nc, var, name.c_str(), NC_DOUBLE, 1, &v), path, what);
  }
}

}  // namespace aq::io
