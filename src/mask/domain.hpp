// SPDX-License-Identifier: GPL-3.0-or-later
// The meshed domain of a regional run (README "Regional FE meshes"): the pixels of the lattice
// inside a lon/lat box or a polygon. The K-cursor fill runs on wet ∩ domain, so water outside
// the domain is not meshed; a boundary edge of the mesh whose outside pixel is wet and outside
// the domain is an open boundary (mesh/boundaries.hpp).
//
// Box, no rotation: the box is snapped outward to whole level-0 squares of the lattice (its
// sides are lattice lines, so the open boundary is straight and the quadtree's squares fit it);
// lon_max < lon_min (or a range past lon0 + 360) crosses the seam: the columns wrap. With pole
// rotation a pixel is inside when its centre's geographic position is in the box (the box is not
// a lattice rectangle then). Polygon: a pixel is inside when its centre's geographic position
// is inside the polygon (even-odd over all rings of the selected features, edges straight in
// lon/lat), on a rotated lattice too.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "config/options.hpp"
#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/rotation.hpp"
#include "raster/bathymetry.hpp"

namespace aq::mask {

/// A ring of a domain polygon as read: geographic lon/lat vertices (continuous longitudes, e.g.
/// 170…190 across the seam), closed (the last vertex joins the first).
struct PolygonRing {
  std::vector<double> lon, lat;
};

struct Domain {
  config::DomainKind kind = config::DomainKind::kGlobal;
  Bitmap inside;                 ///< nx × ny: pixel inside the domain (empty for a global run, or when not `dense`)
  std::int64_t pixels = 0;       ///< |inside|
  std::int64_t i0 = 0, j0 = 0;   ///< box: first pixel column (may wrap) and row of the snapped box
  std::int64_t ni = 0, nj = 0;   ///< box: pixel columns and rows of the snapped box
  double lon_min = 0, lon_max = 0, lat_min = 0, lat_max = 0;  ///< lattice-frame extent of the region
  std::string description;       ///< one line for the log and the report
  std::vector<PolygonRing> rings;  ///< polygon: its rings (the open boundary is moved onto them)
  bool periodic = true;          ///< the lattice wraps in I (false on a window lattice: i outside [0, nx) is outside)

  bool dense = true;  ///< `inside` is held; otherwise pixels are tested from the shape
  // The shape (for a domain without its bitmap): the lattice, the rotation, the box as given and
  // the polygon's longitude origin and column shift on a window lattice.
  Lattice lattice;
  PoleRotation rotation;
  std::vector<double> box;
  double poly_lon_lo = 0.0, poly_lat_lo = 0.0, poly_lat_hi = 0.0, poly_shift = 0.0;

  [[nodiscard]] bool regional() const { return kind != config::DomainKind::kGlobal; }
  /// Whether pixel (i, j) is inside; i is taken modulo nx, rows outside [0, ny) are outside.
  [[nodiscard]] bool contains(std::int64_t i, std::int64_t j) const;
  /// The pixels [col0, col0 + w) × [row0, row0 + h) of the lattice (0 <= col0, col0 + w <= nx, rows in range)
  /// as a w × h bitmap: `inside` cut there, or the same bits computed from the shape.
  [[nodiscard]] Bitmap window(std::int64_t col0, std::int64_t row0, std::int64_t w, std::int64_t h) const;
};

/// The domain of `options` on `lattice`. Throws ConfigError naming domain.* (an empty region)
/// and InputError naming the polygon file (cannot be read, no layer,
/// no polygon feature, not lon/lat). `dense = false` (the forest engine) keeps no bitmap of the
/// lattice: `pixels` is then 0 (not counted) and every test works from the shape.
Domain make_domain(const config::DomainOptions& options, const Lattice& lattice, const PoleRotation& rot,
                   bool dense = true);

/// The lon/lat extent (lattice frame, lon_max > lon_min, continuous across the seam) that a
/// window lattice must hold for the domain of `options` on the global lattice `lattice`, without
/// any pixel bitmap: a box snapped outward to level-0 squares, a polygon's bounding box. Only
/// without pole rotation. Throws what make_domain throws for the box or the polygon file.
struct DomainExtent {
  double lon_min = 0, lon_max = 0, lat_min = 0, lat_max = 0;
};
DomainExtent domain_extent(const config::DomainOptions& options, const Lattice& lattice);

/// The geographic lon/lat window [lon_min, lon_max, lat_min, lat_max] of the raster a box domain
/// `box` ([lon_min, lon_max, lat_min, lat_max], geographic) needs on the rotated lattice `lat`: the
/// domain is the rotated pixels whose centre is in the box, the classification samples one
/// level-0 square around them and the regional picture shows the mesh's extent and 3 % more in
/// the rotated plane. So: the box's extent in the rotated frame (its edges densified), widened by
/// Δ0 + 2 pixels and 5 % of that extent, whose edges (densified) bound the window in geographic
/// lon/lat, 2 pixels wider. All NaN (read the raster whole) when that rectangle holds a pole or
/// spans half the globe.
std::array<double, 4> rotated_box_window(const std::vector<double>& box, const Lattice& lat, const PoleRotation& rot);

/// The seeds of the fill for a regional run: the configured seeds whose pixel is inside the
/// domain; when none is, the deepest wet pixel inside (ties: smallest (j, i)), logged. Throws
/// InputError when the domain holds no wet pixel.
std::vector<std::array<double, 2>> regional_seeds(const Domain& domain, const Bitmap& wet, const Lattice& lattice,
                                                  const PoleRotation& rot, const raster::Bathymetry& bathy,
                                                  const std::vector<std::array<double, 2>>& seeds, const Logger& log);

}  // namespace aq::mask
