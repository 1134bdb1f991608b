// SPDX-License-Identifier: GPL-3.0-or-later
// Private to src/raster: the one GeoTIFF writer of aquatoria, through GDAL. It writes the global
// run file (byte_geotiff.hpp: byte bands, tiled, deflated, lon/lat or spherical Mercator) and the
// Python interface's in-memory rasters (memory_raster.hpp: one band of the caller's type in
// /vsimem/). A file is created with its georeferencing, coordinate system, metadata, band names
// and no-data value, in that order; rows are written; close() finishes it. No .aux.xml sidecar.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "raster/gdal_common.hpp"

namespace aq::raster {

/// The pixel type of every band.
enum class GeoTiffType { kByte, kInt16, kInt32, kFloat32, kFloat64 };

struct GeoTiffSpec {
  std::int64_t width = 0, height = 0;  ///< pixels, > 0
  int bands = 1;                       ///< >= 1
  GeoTiffType type = GeoTiffType::kByte;
  /// GDAL's geotransform of a north-up raster: west edge, pixel width, 0, north edge, 0, -pixel
  /// height, in the units of the coordinate system.
  std::array<double, 6> geotransform{0.0, 1.0, 0.0, 0.0, 0.0, -1.0};
  std::string proj4;                                          ///< coordinate system; "" = EPSG:4326
  std::vector<std::string> creation_options;                  ///< GTiff creation options, "KEY=VALUE"
  std::vector<std::pair<std::string, std::string>> metadata;  ///< dataset metadata, default domain
  std::vector<std::string> band_names;                        ///< empty, or one per band
  std::optional<double> no_data;                              ///< of every band
};

/// A GeoTIFF being written. Every failure is an OutputError "<path>: GeoTIFF <what>: <GDAL's
/// message>", and the file is removed (also when the writer is destroyed before close()).
class GeoTiffWriter {
 public:
  GeoTiffWriter(std::string path, const GeoTiffSpec& spec);
  ~GeoTiffWriter();
  GeoTiffWriter(const GeoTiffWriter&) = delete;
  GeoTiffWriter& operator=(const GeoTiffWriter&) = delete;

  /// Writes rows [row0, row0 + rows) of 1-based `band` from `data`: rows × width values of the
  /// spec's type, row after row.
  void write_rows(int band, std::int64_t row0, std::int64_t rows, const void* data);
  /// Closes the file (GTiff writes its last tiles here).
  void close();

 private:
  [[noreturn]] void fail(const std::string& what);
  std::string path_;
  GeoTiffSpec spec_;
  DatasetPtr ds_;
};

}  // namespace aq::raster
