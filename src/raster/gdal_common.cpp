// SPDX-License-Identifier: GPL-3.0-or-later
// GDAL set-up shared by the raster folder (see gdal_common.hpp).
#include "raster/gdal_common.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>

#include <mutex>

namespace aq::raster {

void gdal_init() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);  // GDAL errors become exceptions with the message
    // A small block cache: rows are copied into our array once, so GDAL need not keep them too.
    if (CPLGetConfigOption("GDAL_CACHEMAX", nullptr) == nullptr) GDALSetCacheMax64(64LL << 20);
  });
}

std::string gdal_message() {
  const char* m = CPLGetLastErrorMsg();
  return (m != nullptr && *m != '\0') ? std::string(": ") + m : std::string();
}

}  // namespace aq::raster
