// SPDX-License-Identifier: GPL-3.0-or-later
// Edits of the sampled elevation (README "Passages, channels and rivers", ARCHITECTURE §4.13):
// corridors along polylines inside which every sample of the bathymetry is lowered (a channel:
// z -> elevation_m where z is above the corridor's keep_at_or_below_m, by default z -> min(z,
// elevation_m)) or raised (a land blockage, z -> max(z, elevation_m)).
//
// They are installed on a Bathymetry (Bathymetry::set_edits) and applied wherever it is sampled:
// the pixel classes and so the K-cursor fill, the mesh nodes' depths, the size field and the
// pictures all see one edited bathymetry, and any lattice engine that samples the raster (the
// dense one, the p4est forest) honours them without knowing about them. The corridors' widths
// are chosen by the caller (mask/carving.hpp: at least K lattice pixels of all-wet windows fit
// across a channel, every pixel a blockage crosses gets a dry vertex).
//
// A corridor is the set of points whose great-circle distance to its polyline (great-circle
// arcs between consecutive vertices, on the unit sphere) is at most the arc's half-width. A
// one-vertex polyline is a disc. All channels apply first, then all blockages (land wins where
// both apply). A no-data sample (NaN) counts as +inf under a channel (a channel drawn through
// no-data is water of its depth) and stays NaN under a blockage.
//
//        a ----------------- b        point p is inside the arc's corridor when
//       (   r  |               )      |n·p| <= sin r and p projects between a and b,
//        ------+--------------        or when p is within r of a or of b
//              p                      (n = a × b / |a × b|, unit vectors on the sphere)
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace aq::raster {

enum class EditKind : std::uint8_t {
  kChannel,   ///< z -> min(z, elevation_m): water at least elevation_m deep (elevation_m < 0 for sea)
  kBlockage,  ///< z -> max(z, elevation_m): land at least elevation_m high
};

/// One corridor along a geographic polyline.
struct Corridor {
  std::string name;  ///< for messages and the report
  EditKind kind = EditKind::kChannel;
  double elevation_m = 0.0;  ///< metres, negative below sea level (a channel's bottom, a blockage's top)
  /// Channels only: raster values at or below this elevation (metres) stay as they are (water the
  /// raster already has deep enough, e.g. the wet threshold −h); values above it, and no-data,
  /// become elevation_m. NaN = elevation_m itself (z -> min(z, elevation_m)).
  double keep_at_or_below_m = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> lon_deg, lat_deg;  ///< vertices (>= 1), geographic degrees, any longitude range
  /// Half-width (great-circle degrees, > 0) of each arc: lon_deg.size() - 1 values, or one value
  /// for a one-vertex disc.
  std::vector<double> half_width_deg;
};

/// A set of corridors with a spatial index; immutable once built, thread-safe to query.
class ElevationEdits {
 public:
  ElevationEdits() = default;
  /// Builds the index. Throws InputError naming the corridor when a vertex is not finite or has
  /// |lat| > 90, when half_width_deg has the wrong count or a value outside (0, 30], or when an
  /// arc joins two antipodal points. Arcs longer than 1° are split (the index bounds them).
  explicit ElevationEdits(std::vector<Corridor> corridors);

  [[nodiscard]] bool empty() const { return arcs_.empty(); }
  [[nodiscard]] const std::vector<Corridor>& corridors() const { return corridors_; }

  /// The edited elevation at (lon, lat) (degrees) of the raster's value z (metres, NaN = no data).
  [[nodiscard]] double apply(double lon_deg, double lat_deg, double z) const;
  /// out[k] = apply(lon_deg[k], lat_deg, out[k]) for k < n (one latitude: a lattice or raster row).
  void apply_row(const double* lon_deg, double lat_deg, float* out, std::int64_t n) const;
  /// The index (in corridors()) of the first corridor containing (lon, lat), or -1.
  [[nodiscard]] int corridor_at(double lon_deg, double lat_deg) const;
  /// Whether some corridor can reach latitude lat (so apply_row may change the row).
  [[nodiscard]] bool touches_lat(double lat_deg) const;

  /// The range of elevations the edits can set inside the box [lon_lo, lon_hi] × [lat_lo, lat_hi]
  /// (lon_lo <= lon_hi, any longitudes): the lowest channel elevation and the highest blockage
  /// elevation of the corridors whose index cells meet the box; +inf / -inf when none does.
  /// Callers widen their bounds of the raw values with it (raster/value_bounds.hpp).
  struct Reach {
    double channel_min_m = 0.0, blockage_max_m = 0.0;
    bool channel = false, blockage = false;
  };
  [[nodiscard]] Reach reach_in_box(double lon_lo, double lon_hi, double lat_lo, double lat_hi) const;

  /// 16 hex digits identifying the corridors (kind, elevation, vertices, widths, to the bit):
  /// the global run file records it among the mask stage's inputs.
  [[nodiscard]] std::string fingerprint() const;

 private:
  struct Arc {
    std::array<double, 3> a{}, b{}, n{};  ///< end points and unit normal of their great circle
    double sin_r = 0.0, cos_r = 1.0;      ///< of the half-width
    double keep = 0.0;                    ///< channel: values at or below stay (keep_at_or_below_m)
    bool point = false;                   ///< a disc around a (a == b)
    std::int32_t corridor = 0;
  };
  [[nodiscard]] bool inside(const Arc& arc, const std::array<double, 3>& p) const;
  [[nodiscard]] std::int64_t cell_of(double lon_deg, double lat_deg) const;

  std::vector<Corridor> corridors_;
  std::vector<Arc> arcs_;  ///< channels' arcs first, then blockages'
  // Index: cells of kCellDeg × kCellDeg; cell_start_[c] .. cell_start_[c + 1] index cell_arcs_.
  static constexpr double kCellDeg = 1.0;
  static constexpr std::int64_t kCols = 360, kRows = 180;
  std::vector<std::int32_t> cell_start_, cell_arcs_;
  std::vector<std::uint8_t> row_used_;  ///< per index row: some arc's cell is on it
};

}  // namespace aq::raster
