// SPDX-License-Identifier: GPL-3.0-or-later
// A compact lon/lat byte raster as GeoTIFF (issue 9, "the global run as a file"): several byte
// bands, deflate-compressed at level 1 (the masks still compress ~100×; level 6 was ~2 s slower
// on the 1′ lattice for a 1.5× smaller file) in 512 × 512 tiles, EPSG:4326 georeferencing (north-up: row 0 is the
// northernmost), band descriptions and key = value metadata that GDAL, QGIS and our reader see.
// Only this folder includes GDAL; the caller supplies rows and reads rows back.
//
// Bytes are deterministic: no timestamps, tiles compressed by GDAL's worker threads but written
// in tile order, no .aux.xml sidecar (PAM off while writing).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace aq::raster {

struct ByteGeoTiffLayout {
  std::int64_t width = 0, height = 0;  ///< pixels
  double west_deg = -180.0;            ///< longitude of the western edge of column 0
  double north_deg = 90.0;             ///< latitude (Mercator: plane ordinate) of the northern edge of row 0
  double pixel_deg = 1.0;              ///< pixel side, degrees (Mercator: plane units of the same size)
  /// Rows equally spaced in the Mercator ordinate y = ln tan(π/4 + φ/2) in degrees (the Mercator
  /// lattice): the file is in a spherical Mercator (authalic radius R, metres = plane degrees ×
  /// R·π/180), so GDAL maps every row to its latitude (the frame's) exactly.
  bool mercator = false;
  std::vector<std::string> band_names;                        ///< one per band
  std::vector<std::pair<std::string, std::string>> metadata;  ///< dataset metadata, default domain
  int no_data = -1;                                           ///< no-data value of every band; < 0 = none
};

/// Fills rows [row0, row0 + rows) (north-up) of every band: bands[b][r·width + c].
using ByteRowsSource =
    std::function<void(std::int64_t row0, std::int64_t rows, std::vector<std::vector<std::uint8_t>>& bands)>;

/// Writes `path` (GTiff; any extension). Throws OutputError naming the file on failure (a partly
/// written file is removed).
void write_byte_geotiff(const std::filesystem::path& path, const ByteGeoTiffLayout& layout, const ByteRowsSource& rows);

/// A byte GeoTIFF opened for reading.
class ByteGeoTiff {
 public:
  /// Opens `path`; throws InputError naming the file when it is missing or not a byte raster.
  explicit ByteGeoTiff(const std::filesystem::path& path);
  ~ByteGeoTiff();
  ByteGeoTiff(const ByteGeoTiff&) = delete;
  ByteGeoTiff& operator=(const ByteGeoTiff&) = delete;

  /// Size, georeferencing (north-up assumed), band names and metadata as stored.
  [[nodiscard]] const ByteGeoTiffLayout& layout() const { return layout_; }
  /// Value of a metadata item; "" when absent.
  [[nodiscard]] std::string metadata(const std::string& key) const;
  /// Reads rows [row0, row0 + rows) of 1-based `band` into out (rows·width bytes).
  void read_rows(int band, std::int64_t row0, std::int64_t rows, std::uint8_t* out) const;

 private:
  std::filesystem::path path_;
  ByteGeoTiffLayout layout_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aq::raster
