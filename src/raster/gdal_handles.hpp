// GDAL plumbing shared by the files of src/raster (the only stage that includes GDAL's raster
// headers): the drivers registered once, GDAL's last error message for an exception's text, and
// an owning dataset handle.
#pragma once

#include <cpl_error.h>
#include <gdal_priv.h>

#include <memory>
#include <mutex>
#include <string>

namespace aq::raster {

/// GDALAllRegister(), once per process.
inline void gdal_register() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

/// ": <message>" of GDAL's last error, or "" when there is none.
inline std::string last_gdal_error() {
  const char* m = CPLGetLastErrorMsg();
  return (m != nullptr && *m != '\0') ? std::string(": ") + m : std::string();
}

/// Closes a dataset (GDALClose) when its owner goes.
struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

}  // namespace aq::raster
