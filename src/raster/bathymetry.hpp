// Bathymetry input (ARCHITECTURE §4.1): any GDAL raster in geographic coordinates, normalised to
// a south-up grid of sample points with a known longitude origin, and sampled bilinearly on the
// smallest cell of raster points containing the point (the seed's rule; longitude wraps on a
// global raster) or by a bicubic C2 spline (reference splines.md §4).
//
// Normalised layout: value (c, r) is at λ = lon_first + c·dlon, φ = lat_first + r·dlat with
// dlon, dlat > 0 (row 0 is the southernmost). A duplicated 360° column is dropped. Values are
// elevations in metres (negative below sea level) after scale/offset and positive_down; no-data
// is NaN. Sampling outside a regional raster's coverage gives NaN (treated as dry by callers).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/log.hpp"

namespace aq::raster {

enum class Interpolation { kBilinear, kBicubic };

struct OpenOptions {
  std::string path;
  std::string variable;        ///< netCDF variable / subdataset; empty = the first / the file itself
  int band = 1;                ///< 1-based band
  bool positive_down = false;  ///< file stores depth positive down: values are negated
  Interpolation interpolation = Interpolation::kBilinear;
  std::int64_t max_memory_bytes = 0;  ///< refuse if the raster would not fit; 0 = 80% of RAM
};

/// What `aquatoria info` prints about a raster, as found and as normalised.
struct RasterInfo {
  std::string path, driver, variable, crs_name, units;
  std::int64_t width = 0, height = 0;       ///< as stored in the file
  std::int64_t ncols = 0, nrows = 0;        ///< after dropping a duplicated column
  double dlon = 0.0, dlat = 0.0;            ///< degrees between sample points
  double lon_first_found = 0.0;             ///< λ of the first stored column's sample point
  double lon_first = 0.0, lat_first = 0.0;  ///< normalised origin (sample point of (0, 0))
  bool north_up = true;                     ///< rows stored north to south
  bool global_lon = false;                  ///< covers 360° (longitude wraps)
  bool duplicate_column = false;            ///< a 360° column was dropped
  std::string registration;                 ///< "grid" (points on whole multiples) or "pixel"
  std::string data_type;                    ///< GDAL type name of the band
  double scale = 1.0, offset = 0.0;
  bool has_nodata = false;
  double nodata = 0.0;
  double min_m = 0.0, max_m = 0.0, mean_m = 0.0;  ///< over valid values (after normalisation)
  std::int64_t valid_count = 0;
  std::int64_t memory_bytes = 0;  ///< bytes held for the values
};

class Bathymetry {
 public:
  /// Opens and reads the raster (band by band of rows through GDAL windows, with progress).
  /// Throws InputError naming the path: missing/unreadable, not a raster, projected CRS (named),
  /// band/variable not found, all no-data; throws InputError when it would not fit in memory.
  static Bathymetry open(const OpenOptions& options, const Logger& log = Logger::null());
  /// Builds from values in memory (tests and data tools): `values` row-major south-up,
  /// ncols×nrows, sample points at lon_first + c·dlon, lat_first + r·dlat; NaN = no data.
  static Bathymetry from_grid(std::vector<float> values, std::int64_t ncols, std::int64_t nrows, double lon_first,
                              double lat_first, double dlon, double dlat,
                              Interpolation interpolation = Interpolation::kBilinear);

  Bathymetry(Bathymetry&&) noexcept;
  Bathymetry& operator=(Bathymetry&&) noexcept;
  ~Bathymetry();

  [[nodiscard]] const RasterInfo& info() const;

  /// Elevation (m, negative below sea level) at (lon, lat) in degrees; NaN if no data or outside.
  /// Thread-safe.
  [[nodiscard]] double sample(double lon_deg, double lat_deg) const;
  /// Samples n points; thread-safe, parallel inside (OpenMP) when n is large.
  void sample_points(const double* lon_deg, const double* lat_deg, std::int64_t n, double* out) const;

  /// Fast separable sampling of a lattice row: out[k] = sample(lons[k], lat) for k < n, using
  /// precomputed column weights (`prepare_columns`). Thread-safe.
  struct Columns {
    std::vector<std::int64_t> c0, c1;  ///< bracketing raster columns
    std::vector<double> t;             ///< weight of c1
    std::vector<double> lon;           ///< the longitudes (for bicubic)
  };
  [[nodiscard]] Columns prepare_columns(const double* lons, std::int64_t n) const;
  void sample_row(const Columns& cols, double lat_deg, float* out) const;

  /// Raster value (c, r) in normalised layout (c wraps for global rasters); NaN if no data.
  [[nodiscard]] float value(std::int64_t c, std::int64_t r) const;

 private:
  struct Impl;
  explicit Bathymetry(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Estimated bytes `open` would hold for a raster of width×height (values as float32).
std::int64_t estimate_raster_bytes(std::int64_t width, std::int64_t height);

/// A coastline (or any iso-depth) polyline in lon/lat degrees, from GDAL's contour generator.
struct Polyline {
  std::vector<double> lon_deg, lat_deg;
};
/// Contours of elevation `level_m` inside [lon_min, lon_max] × [lat_min, lat_max]
/// (longitudes may extend past the raster's range on a global raster).
std::vector<Polyline> contour_lines(const Bathymetry& bathy, double level_m, double lon_min, double lon_max,
                                    double lat_min, double lat_max);

}  // namespace aq::raster
