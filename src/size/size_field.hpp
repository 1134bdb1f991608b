// SPDX-License-Identifier: GPL-3.0-or-later
// The target size field h(x) in km (ARCHITECTURE §4.10): the terms of a [size] section
// (size/terms.hpp), quadtree.size_km, the size form of quadtree.depth_rules / box_rules
// (a constant size on the cells whose centre is in the band or box) and a user raster of sizes combined by minimum on the
// field grid (size/field_grid.hpp), clamped to [h_min, h_max], gradient-limited (|∇h| <= g on
// the sphere, size/limit_gradient.hpp), and CFL-bounded last — OceanMesh2D's order. The coastal
// band's size (quadtree.coast_size_km) is a term at the pixel scale: a square holding a band pixel
// asks at most that size; with a gradient limit it is also put on the grid cells holding coast so
// the limit grades away from it.
//
// The quadtree reads the field through min_over_square: a square is split while it is larger
// than √2 × the field's minimum over it (quadtree/leaves.hpp apply_size_field).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "config/options.hpp"
#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/report.hpp"
#include "core/rotation.hpp"
#include "mask/coast.hpp"
#include "size/field_grid.hpp"

namespace aq::raster {
class Bathymetry;
}

namespace aq::size {

class SizeField {
 public:
  SizeField() = default;
  /// A field of grid values `h_km` (grid.cells() values, +inf = none), plus the coastal band
  /// term (band_km > 0: squares holding a pixel of the band of radius band_radius ask at most it).
  SizeField(FieldGrid grid, std::vector<float> h_km, double band_km, int band_radius);
  /// The band term alone, without a grid (band_km = 0: an inactive field).
  SizeField(double band_km, int band_radius) : band_km_(band_km), band_radius_(band_radius) {}

  /// Whether the field asks anything (a grid value or the band term).
  [[nodiscard]] bool active() const { return grid_.has_value() || band_km_ > 0.0; }
  [[nodiscard]] bool has_grid() const { return grid_.has_value(); }
  [[nodiscard]] const FieldGrid& grid() const { return *grid_; }
  [[nodiscard]] const std::vector<float>& values() const { return levels_.back(); }
  [[nodiscard]] double band_km() const { return band_km_; }
  [[nodiscard]] int band_radius() const { return band_radius_; }

  /// The grid's minimum (km) over the level-l square (a, b) (+inf without a grid): the min over
  /// its cells for l <= c, the value of the cell holding it for l > c. The band term is not in it.
  [[nodiscard]] double grid_min_over_square(int l, std::int64_t a, std::int64_t b) const;
  /// The grid value (km) at the lattice pixel (i, j) (+inf without a grid).
  [[nodiscard]] double at_pixel(std::int64_t i, std::int64_t j) const;

  /// The gradient limit g of the field (0: none); the quadtree keeps it in its levels
  /// (quadtree/leaves.hpp grade_levels).
  [[nodiscard]] double gradation() const { return gradation_; }
  void set_gradation(double g) { gradation_ = g; }
  /// The CFL edge bound: per grid cell the shortest edge (km) a triangle there may have at
  /// size.cfl.dt_s, (√(g·H) + u)·Δt/Cr_max with H the deepest value of the raster at the cell's
  /// pixel corners (where mesh nodes sit); 0 where there is no water. Empty: no CFL bound.
  void set_cfl_edges(std::vector<float> edge_km);
  [[nodiscard]] bool has_cfl() const { return !cfl_levels_.empty(); }
  /// The largest CFL edge bound (km) over the level-l square (a, b) (0 without a bound): the max
  /// over its cells for l <= c, the value of the cell holding it for l > c.
  [[nodiscard]] double cfl_edge_over_square(int l, std::int64_t a, std::int64_t b) const;

 private:
  std::optional<FieldGrid> grid_;
  std::vector<std::vector<float>> levels_;  ///< min pyramid: levels_[l] for l = 0..c
  double band_km_ = 0.0;
  int band_radius_ = 0;
  double gradation_ = 0.0;
  std::vector<std::vector<float>> cfl_levels_;  ///< max pyramid of the CFL edge bound, like levels_
};

/// Facts of the built field for the report and the log.
struct SizeFieldStats {
  int grid_level = -1;
  std::int64_t nx = 0, ny = 0;
  double cell_km_equator = 0.0;
  int sweeps = 0;
  double min_km = 0.0, median_km = 0.0, max_km = 0.0;  ///< over water cells, after every step
  Json terms = Json::object();                          ///< per term: min/median/max over water cells
};

/// Builds the field of `c.size` and the size rules of `c.quadtree` (size_km, coast_size_km) over
/// the filled set. An inactive field (no term set) when nothing asks a size. `bathy` is sampled at
/// the cell centres (mapped through `rotation`) when a depth or elevation term is on. Logs a
/// "size" stage line and writes the report's "size" section when `report` is given. `c` is as
/// validated at load (config/global_config.cpp: ranges, h_min <= h_max). Throws InputError for a
/// size raster that cannot be read or holds a value <= 0.
///
/// `coast` (mask/coast.hpp) says where the coast is: a cell is a coast cell when it holds a pixel
/// that is not filled (not sea, with a floodplain) and not open water beyond a regional domain's
/// edge. The coast and feature terms measure from those cells; with a floodplain (coast.sea) they,
/// and the wavelength and slope terms, size the cells holding sea, and the floodplain terms (size.inland: distance
/// inland from the nearest cell holding sea; size.elevation: the elevation at the cell centre, at least 0) size the
/// cells holding floodplain pixels (filled, not sea).
SizeField build_size_field(const Bitmap& filled, const Lattice& lat, const config::GlobalConfig& c,
                           const PoleRotation& rotation, const raster::Bathymetry* bathy, const Logger& log,
                           Report* report, const mask::CoastSources& coast = {});

/// What the field takes of the filled set on its grid (the forest engine sums them over its
/// patches and ranks): per cell, the filled pixels (FieldGrid::filled_counts), whether it is a
/// coast cell (see above: size/terms.hpp coast_cells or shore_cells) and, with a floodplain only,
/// its sea pixels (empty otherwise).
struct FieldCells {
  std::vector<std::int32_t> filled;
  std::vector<std::uint8_t> coast;
  std::vector<std::int32_t> sea;
};

/// The same with the filled set given as its cells on the field's grid.
SizeField build_size_field(const std::function<FieldCells(const FieldGrid&)>& field_cells, const Lattice& lat,
                           const config::GlobalConfig& c, const PoleRotation& rotation, const raster::Bathymetry* bathy,
                           const Logger& log, Report* report);

/// Whether `q` has depth or box rules in the size form (size_km > 0): terms of the field.
[[nodiscard]] bool has_size_rules(const config::QuadtreeOptions& q);
/// Whether `c` asks for a field grid (any [size] term or quadtree.size_km); the band term alone needs none.
/// The floodplain terms (size.inland, size.elevation) count only with a floodplain (mask.min_depth_m < 0).
[[nodiscard]] bool needs_grid(const config::GlobalConfig& c);
/// Whether `c` needs depths on the field grid (wavelength, slope, CFL; not the elevation term).
[[nodiscard]] bool needs_depth(const config::SizeOptions& s);

}  // namespace aq::size
