// SPDX-License-Identifier: GPL-3.0-or-later
// Private to src/raster: what every GDAL user of this folder shares. GDAL is set up once (drivers
// registered, its errors kept quiet: they become exceptions carrying GDAL's message, since
// nothing below app/ prints, and a small block cache), its last message is appended to ours, and
// an open dataset is closed on scope exit.
#pragma once

#include <cpl_conv.h>
#include <gdal_priv.h>

#include <memory>
#include <string>

namespace aq::raster {

/// Registers GDAL's drivers and sets its error handler and cache, once per process.
void gdal_init();

/// ": <GDAL's last error message>", or "" when there is none.
std::string gdal_message();

/// PAM (GDAL's .aux.xml sidecar files) off for this thread while the object lives: aquatoria's
/// GeoTIFFs are exactly the bytes it writes, with nothing beside them.
class NoSidecar {
 public:
  NoSidecar() { CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", "NO"); }
  ~NoSidecar() { CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", nullptr); }
  NoSidecar(const NoSidecar&) = delete;
  NoSidecar& operator=(const NoSidecar&) = delete;
};

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
/// An open GDAL dataset, closed when it goes out of scope.
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

}  // namespace aq::raster
