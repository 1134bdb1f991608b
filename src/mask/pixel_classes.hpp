// SPDX-License-Identifier: GPL-3.0-or-later
// Pixel classes of seed 002 (Kireev & Pyataev 2009, §2 "мокрые/сухие/прибрежные пиксели"):
// a lattice vertex is wet when the elevation there is d <= -h (h = mask.min_depth_m, negative for
// a floodplain above the datum; NaN = no data = dry); a pixel is wet when its 4 vertices are wet,
// dry when its 4 vertices are dry, coastal otherwise (ARCHITECTURE §4.2).
//
//   vertex rows J+1:  (i,J+1) o-------o (i+1,J+1)      pixel (i, J) and its 4 vertices;
//                             | (i,J) |                vertex column i+1 wraps to 0 at the seam
//   vertex row  J:      (i,J) o-------o (i+1,J)
//
// The depth field is never stored: each lattice row of vertices is sampled (Bathymetry::
// sample_row, separable bilinear; or sample_points through the pole rotation) and thresholded
// straight into a bitmap of wet vertices.
//
// Optional area rule (mask.sampling = "area", for rasters much finer than a pixel):
//   let P = the raster sample points inside the closed pixel [λ_i, λ_i+Δ] × [φ_j, φ_j+Δ]
//   (a point on a pixel edge belongs to both pixels; positions are snapped to the raster grid
//   within 1e-9 of a cell). If P is empty (raster coarser than the pixel), P = the 4 vertices
//   (sampled as in the vertex rule). The pixel is wet when every value in P is <= -h (the
//   shallowest point is deep enough), dry when no value in P is <= -h, coastal otherwise.
//   With a pole rotation the rotated pixel is not aligned with the raster; P is then the
//   (n+1)×(n+1) grid of bilinear samples at the pixel's vertices and n-1 equally spaced
//   interior lines each way, n = ceil(Δ / min(raster dlon, dlat)), i.e. raster resolution.
//   The wet-vertex bitmap is always the vertex rule.
#pragma once

#include <cstdint>
#include <string>

#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/rotation.hpp"
#include "raster/bathymetry.hpp"

namespace aq::mask {

/// mask.sampling (config/kinds.hpp): the seed's vertex rule or the deepest raster cell.
using config::Sampling;

/// The pixels a regional run classifies (README "Regional FE meshes"): columns col_first ..
/// col_first + col_count - 1 (wrapping at the seam) and rows row_first .. row_first + row_count - 1;
/// a count < 0 (or the whole lattice) = all. Outside, no vertex is sampled: its vertices are not
/// wet and its pixels are dry.
struct PixelWindow {
  std::int64_t col_first = 0, col_count = -1, row_first = 0, row_count = -1;
};

struct ClassifyOptions {
  double min_depth_m = 0.0;  ///< h (metres; < 0: land up to -h above the datum); wet means elevation <= -h
  Sampling sampling = Sampling::kVertex;
  ProgressFn progress;  ///< optional; called from the calling thread, fraction in [0,1]
  /// Unrotated vertex rule only (else ignored): classify these pixels only.
  PixelWindow window;
};

/// The three pixel classes as bitmaps; dry = neither wet nor coastal.
struct PixelClasses {
  Bitmap wet_vertices;  ///< nx × (ny+1): bit (I, J) = vertex (I, J) is wet
  Bitmap wet;           ///< nx × ny
  Bitmap coastal;       ///< nx × ny
  std::int64_t wet_vertex_count = 0;
  std::int64_t wet_count = 0;
  std::int64_t coastal_count = 0;
  std::int64_t dry_count = 0;
};

/// The Mercator lattice's rows end at |φ′| = lattice.lat_max_deg(): the caps beyond (boundary
/// circle included) must be dry. Samples each cap on a λ′–φ′ grid no coarser than the raster or
/// the pixels and throws ConfigError naming quadtree.mercator_lat_max_deg, the number of wet
/// points and the first one (geographic and rotated), suggesting a rotation. No-op on the lon-lat
/// lattice.
void check_mercator_caps(const raster::Bathymetry& bathy, const Lattice& lattice, const PoleRotation& rot,
                         double min_depth_m);

/// Samples the bathymetry at every lattice vertex (rotated lattices through `rot`) and returns
/// the wet vertices and the pixel classes. OpenMP over rows; bit-identical for any thread count.
/// `min_depth_m` is mask.min_depth_m as validated at load (config/global_config.cpp; negative = a floodplain).
PixelClasses classify_pixels(const raster::Bathymetry& bathy, const Lattice& lattice, const PoleRotation& rot,
                             const ClassifyOptions& options);

/// Wet vertices only (vertex rule): nx × (ny+1) bitmap, bit (I, J) = d(vertex) <= -h.
/// Unrotated: only the vertices of the pixels in `window` are sampled (the others are not wet).
Bitmap sample_wet_vertices(const raster::Bathymetry& bathy, const Lattice& lattice, const PoleRotation& rot,
                           double min_depth_m, const ProgressFn& progress = {}, const PixelWindow& window = {});

/// Vertex rule on a bitmap of wet vertices (nx × (ny+1)): fills `wet` and `coastal` (nx × ny,
/// reallocated). Pure bitmap arithmetic, word-parallel, periodic in I.
void classify_from_vertices(const Bitmap& wet_vertices, Bitmap& wet, Bitmap& coastal);

}  // namespace aq::mask
