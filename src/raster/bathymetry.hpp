// SPDX-License-Identifier: GPL-3.0-or-later
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
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "config/kinds.hpp"
#include "core/log.hpp"
#include "raster/elevation_edits.hpp"

namespace aq::raster {

/// input.interpolation (config/kinds.hpp): the seed's bilinear rule or a C2 bicubic spline.
using config::Interpolation;

struct OpenOptions {
  std::string path;
  std::string variable;        ///< netCDF variable / subdataset; empty = the first / the file itself
  int band = 1;                ///< 1-based band
  bool positive_down = false;  ///< file stores depth positive down: values are negated
  /// Values (after scale, offset and sign) beyond ±this many metres are no-data: a sentinel
  /// such as -1e29 or a wrong scale is not an elevation (Earth: -10 994 m .. 8 849 m).
  double max_abs_elevation_m = 12000.0;
  Interpolation interpolation = Interpolation::kBilinear;
  std::int64_t max_memory_bytes = 0;  ///< refuse if the raster would not fit; 0 = 80% of RAM
  /// The caller can use a streamed raster (unrotated vertex-rule lattice, bilinear): see
  /// `Streaming` and ARCHITECTURE §4.1 / README "Big rasters". False: the raster is held whole.
  bool allow_streaming = false;
  /// Latitude window [lat_min, lat_max] (degrees, NaN = whole raster): only the raster rows
  /// covering it (+2 rows) are read and held; outside them sampling gives NaN. Regional runs.
  double lat_min = std::numeric_limits<double>::quiet_NaN();
  double lat_max = std::numeric_limits<double>::quiet_NaN();
  /// Longitude window [lon_min, lon_max] (degrees, lon_min < lon_max, either may be past ±180;
  /// NaN = all longitudes; bilinear only): only the columns covering it (+3 each side) are read
  /// and held, in two pieces across the seam of a global raster; outside them sampling gives NaN
  /// like outside any regional raster. Regional runs (README "Regional FE meshes").
  double lon_min = std::numeric_limits<double>::quiet_NaN();
  double lon_max = std::numeric_limits<double>::quiet_NaN();

  // Hidden knobs for tests and benchmarks (not configuration keys).
  enum class Streaming { kAuto, kAlways, kNever };
  /// kAuto: stream when allow_streaming and the raster as float32 is above kStreamAboveBytes or
  /// above the memory limit; kAlways/kNever force a path (kAlways still needs allow_streaming).
  Streaming streaming = Streaming::kAuto;
  std::int64_t band_rows = 0;  ///< stored rows per band read; 0 = whole blocks, about 64 MB
  /// A streamed raster GDAL can map into memory (an uncompressed file in the machine's byte
  /// order, one block per row or a strip layout: GeoTIFF, ENVI, EHdr) is read through the map
  /// (RasterInfo::mapped); false: through GDAL reads always (tests compare the two).
  bool map_file = true;
  /// Warn that a raster not covering 360° leaves the rest of the lattice dry (off for a source
  /// above another one, whose uncovered part the sources below fill).
  bool warn_partial_coverage = true;
  /// Read in tiles on demand (RasterInfo::tiled) when the values held would take more than this
  /// many bytes as float32 and the raster is not streamed; 0 = never (the forest engine sets it, so
  /// that a stack of fine tiles over a whole coast is read only where it is sampled).
  std::int64_t tiles_above_bytes = 0;
  /// Tiled: the most bytes of tiles kept at once (the least recently used go first).
  std::int64_t tile_cache_bytes = std::int64_t{256} << 20;
};

/// Tiles of a tiled raster are kTileCells × kTileCells values.
constexpr std::int64_t kTileCells = 128;

/// A raster larger than this (as float32) is streamed when the caller allows it (1 GiB: ETOPO5
/// 37 MB and a 1' raster 0.9 GB are held whole, 30" 3.7 GB and 15" 15 GB are streamed).
constexpr std::int64_t kStreamAboveBytes = std::int64_t{1} << 30;

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
  std::int64_t implausible_count = 0;  ///< values beyond ±max_abs_elevation_m made no-data
  double max_abs_elevation_m = 12000.0;
  std::int64_t memory_bytes = 0;  ///< bytes held for the values (streamed: the band buffers)
  bool streamed = false;          ///< values are read in bands of rows on each pass, never held whole
  std::int64_t block_rows = 0;    ///< the file's block height (rows)
  std::int64_t band_rows = 0;     ///< streamed: stored rows per band read
  std::int64_t passes = 0;        ///< streamed: full or partial passes over the file so far
  bool tiled = false;             ///< values read in tiles on demand and cached (OpenOptions::tiles_above_bytes)
  std::int64_t tile_cache_bytes = 0;    ///< tiled: the cache's bound
  mutable std::int64_t tiles_read = 0;  ///< tiled: tiles read so far (with repeats after eviction)
  /// Streamed through GDAL's memory map of the file (OpenOptions::map_file): the threads read the
  /// rows where they lie instead of copying them through a read buffer; the same values.
  bool mapped = false;
  /// Held whole: the window read (OpenOptions lat/lon window), in normalised columns and rows;
  /// the whole raster when no window was asked (held_cols = ncols, held_rows = nrows).
  std::int64_t held_cols = 0, held_rows = 0;
  std::int64_t held_col_first = 0, held_row_first = 0;  ///< first normalised column (wraps) and row
};

/// What `open` would do with a raster, found from its header only (nothing is read).
struct RasterPlan {
  std::int64_t width = 0, height = 0;  ///< as stored
  bool streamed = false;
  std::int64_t block_rows = 0, band_rows = 0;
  std::int64_t bytes = 0;  ///< held values (whole) or band buffers (streamed)
};
/// "N value(s) beyond ±M m treated as no-data (input.max_abs_elevation_m)" when a pass found
/// any, else "" (streamed rasters: after their first pass).
std::string implausible_note(const RasterInfo& info);

/// Opens the header of `options.path` and decides whole or streamed with the rule of `open`;
/// throws what `open` throws for a missing or unusable file (not the memory refusal).
RasterPlan plan_raster(const OpenOptions& options);

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

  /// Several rasters, highest priority first (README "Several bathymetry sources"), each opened
  /// as `open` opens one (`sources[k]` its options; the same validation and normalisation). At
  /// every point the first source whose sample is not NaN wins; with `blend_km` > 0, within
  /// blend_km of a source's data edge (its extent or a no-data value) the value is
  /// w·v_k + (1 − w)·v_rest with w = s²(3 − 2s), s = min(1, d/blend_km), d the distance (km) from
  /// the point to that edge (see `blend_weight`). One source: the same as `open`. Throws what
  /// `open` throws, naming the source; InputError when blend_km > 0 and a source other than the
  /// last would be streamed (its distance field is held whole beside it).
  static Bathymetry open_sources(const std::vector<OpenOptions>& sources, double blend_km,
                                 const Logger& log = Logger::null());
  /// The same over rasters already open (tests and tools; `sources` are moved in).
  static Bathymetry stack(std::vector<Bathymetry> sources, double blend_km);

  /// Number of sources (1 for a single raster) and source k (the raster itself when there is one).
  [[nodiscard]] std::size_t source_count() const;
  [[nodiscard]] const Bathymetry& source(std::size_t k) const;
  /// The blend weight of the source above at distance d_km inside its data edge: s²(3 − 2s) with
  /// s = clamp(d_km / blend_km, 0, 1) (1 when blend_km is 0).
  static double blend_weight(double d_km, double blend_km);

  /// Which source supplies each point's `sample`: k (0-based) when source k alone gives the value,
  /// kBlended + k when it is a blend of source k with the sources below it, kNoSource when no
  /// source has data. Thread-safe; the same rule as `sample_points`.
  static constexpr int kNoSource = -1;
  static constexpr int kBlended = 1000;
  void supplying_sources(const double* lon_deg, const double* lat_deg, std::int64_t n, int* out) const;

  Bathymetry(Bathymetry&&) noexcept;
  Bathymetry& operator=(Bathymetry&&) noexcept;
  ~Bathymetry();

  /// Several sources: a summary (paths joined by " + ", the finest steps, streamed when any is,
  /// global when any is, memory and valid counts summed); each source's own is source(k).info().
  [[nodiscard]] const RasterInfo& info() const;
  /// True when the raster itself is sampled bilinearly (every raw value is a convex combination
  /// of the four surrounding raster values, or NaN); false for the bicubic spline and for several
  /// sources (no one raster grid holds the values). Edits (set_edits) apply on top of it.
  [[nodiscard]] bool samples_bilinear() const;

  /// Installs corridor edits (raster/elevation_edits.hpp) applied to every value this object
  /// returns from now on: sample, sample_points, sample_row(s), value(s) (at the raster points'
  /// positions). Null or empty removes them. Not thread-safe against concurrent sampling: call it
  /// between stages (the mask stage's carving does, before the classification).
  void set_edits(std::shared_ptr<const ElevationEdits> edits);
  /// The installed edits, or null.
  [[nodiscard]] const ElevationEdits* edits() const { return edits_.get(); }
  [[nodiscard]] std::shared_ptr<const ElevationEdits> shared_edits() const { return edits_; }

  /// Elevation (m, negative below sea level) at (lon, lat) in degrees; NaN if no data or outside.
  /// Thread-safe.
  [[nodiscard]] double sample(double lon_deg, double lat_deg) const;
  /// Samples n points; thread-safe, parallel inside (OpenMP) when n is large. Streamed: one
  /// banded pass over the rows the points need (points grouped by row), same values bit for bit.
  void sample_points(const double* lon_deg, const double* lat_deg, std::int64_t n, double* out,
                     const ProgressFn& progress = {}) const;

  /// Fast separable sampling of a lattice row: out[k] = sample(lons[k], lat) for k < n, using
  /// precomputed column weights (`prepare_columns`). Thread-safe.
  struct Columns {
    std::vector<std::int64_t> c0, c1;  ///< bracketing raster columns
    std::vector<double> t;             ///< weight of c1
    std::vector<double> lon;           ///< the longitudes (for bicubic)
    /// Several sources: the columns of each source and of each blend-distance field.
    std::vector<Columns> sources, distances;
    /// A source read in tiles gives NaN on these columns (the sources below it answer): for a
    /// picture, whose sparse samples would read a tile each.
    bool skip_tiled = false;
  };
  [[nodiscard]] Columns prepare_columns(const double* lons, std::int64_t n, bool skip_tiled = false) const;
  void sample_row(const Columns& cols, double lat_deg, float* out) const;

  /// Many rows at once: for k < n, sink(k, values) where values[0..cols) = sample_row(cols,
  /// lats[k]). The sink is called once per row, from several threads at once (distinct k), in no
  /// particular order; values are the same as sample_row's bit for bit. A streamed raster is read
  /// once in bands of rows (the next band is read while this one is sampled); the first such pass
  /// also fills the statistics of info() and throws InputError when every value is no-data.
  using RowSink = std::function<void(std::int64_t k, const float* values)>;
  void sample_rows(const Columns& cols, const double* lats, std::int64_t n, const RowSink& sink,
                   const ProgressFn& progress = {}) const;

  /// Fills the statistics of info() (min, max, mean, valid count) of a streamed raster with one
  /// banded pass when no pass has yet (a raster held whole has them from `open`); throws what
  /// sample_rows throws.
  void ensure_statistics(const ProgressFn& progress = {}) const;

  /// Raster value (c, r) in normalised layout (c wraps for global rasters); NaN if no data.
  /// Several sources: there is no one grid; `value` and `values` throw InternalError.
  /// Streamed: one small read per call (use `values` for blocks).
  [[nodiscard]] float value(std::int64_t c, std::int64_t r) const;
  /// Values of columns c_lo..c_lo+nc-1 (wrapping on a global raster) and rows r_lo..r_lo+nr-1
  /// into out (row-major, row r_lo first); NaN outside. Streamed: one read of those rows.
  void values(std::int64_t c_lo, std::int64_t nc, std::int64_t r_lo, std::int64_t nr, float* out) const;

  /// Whether a source has no data at all in the normalised cells [c_lo, c_hi] × [r_lo, r_hi] (both
  /// inclusive, columns unwrapped: they wrap on a global raster), as GDAL's data coverage knows it
  /// without reading (a VRT's tiles: its sources' footprints); false when it cannot tell.
  [[nodiscard]] bool surely_empty(std::int64_t c_lo, std::int64_t c_hi, std::int64_t r_lo, std::int64_t r_hi) const;

 private:
  struct Impl;
  struct Stack;  // several sources (raster/source_stack.hpp); null for one raster
  explicit Bathymetry(std::unique_ptr<Impl> impl);
  static std::unique_ptr<Impl> open_header(const OpenOptions& o);
  friend RasterPlan plan_raster(const OpenOptions& options);
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<Stack> stack_;
  std::shared_ptr<const ElevationEdits> edits_;  ///< null = the raster's values as they are
  // The raster's values without the edits (the public functions apply them on top).
  void raw_points(const double* lon_deg, const double* lat_deg, std::int64_t n, double* out,
                  const ProgressFn& progress) const;
  void raw_row(const Columns& cols, double lat_deg, float* out) const;
  void raw_rows(const Columns& cols, const double* lats, std::int64_t n, const RowSink& sink,
                const ProgressFn& progress) const;
  /// Normalised raster point (c, r)'s position (degrees), for edits of value / values.
  void point_lonlat(std::int64_t c, std::int64_t r, double& lon_deg, double& lat_deg) const;
};

/// The files GDAL reads for the raster at `path`: the file itself, a VRT's source tiles, sidecar
/// files, as GDAL's GetFileList names them; empty when GDAL cannot open it as a raster.
std::vector<std::string> raster_files(const std::string& path);

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
