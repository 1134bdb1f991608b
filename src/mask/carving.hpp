// SPDX-License-Identifier: GPL-3.0-or-later
// Carving passages, channels and land blockages into the bathymetry before the fill (README
// "Passages, channels and rivers", ARCHITECTURE §4.13; MPAS/compass carve "critical passages" and
// block "critical land blockages" the same way). Not in seed 002: its K-fill closes every strait
// narrower than K pixels, and with it the seas behind (the Mediterranean behind Gibraltar on
// ETOPO5 at 7.5').
//
// The lines come from the built-in table (mask.passages_open: the strait's deepest path between
// its two sides), from mask.transects (user passages and blockages) and from mask.channels
// (channels and rivers). Each becomes a corridor edit of the elevation (raster/elevation_edits.hpp)
// that the caller installs on the Bathymetry (Bathymetry::set_edits) before the pixel classes are
// sampled, so the classification, the fill, the mesh nodes' depths and the size field all see the
// same carved bathymetry, whichever lattice engine samples it. The interface to an engine is the
// edited Bathymetry alone.
//
// Width (half-width r of the corridor, great-circle degrees at each arc). p = the longest side of
// a lattice pixel on the sphere there: Δ_L on the lon-lat lattice (its meridian side), Δ_L·cos φ′
// on the Mercator lattice (φ′ the rotated latitude); the larger of an arc's two ends.
//   channel, passage: r = ((K + 1)/√2 + 1/4)·p, or half the stated width when wider. Every K-window
//     of the 4-connected chain of windows whose centres follow the line (each centre within √2/2
//     pixel of it) has its vertices within (K + 1)/√2 pixels of the line: all of them are in the
//     corridor, so the fill passes along it (1/4 pixel for the line's curvature in the lattice plane).
//   blockage: r = (√2/2 + 1/4)·p: every pixel the line crosses has a vertex within √2/2 pixel of it,
//     so no 4-connected chain of wet pixels crosses the line.
// Depth (channels and passages; d positive down, the corridor's bottom at −d):
//   table passage: the raster's sill depth between the sides (the lowest elevation m such that
//     4-connected raster-resolution samples of the passage's box <= m join side A's centre to side
//     B's), when deeper than h; otherwise (the raster closes the strait) its nominal sill depth;
//   transect: its depth_m, else the sill of the deepest path inside its corridor from its first
//     to its last vertex when deeper than h, else mask.channel_depth_m;
//   channel line: its depth_m, else mask.channel_depth_m;
//   always at least max(h, 0) + 1 m, so every carved vertex is wet.
// Only samples that are not wet already (elevation above −h) take the corridor's bottom: the
// raster's own water in the corridor keeps its depth.
// Blockage: elevation max(height_m (default 10 m), −h + 1 m): land at every vertex of the line.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "config/options.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/report.hpp"
#include "core/rotation.hpp"
#include "mask/edit_lines.hpp"
#include "mask/lattice_coords.hpp"
#include "raster/bathymetry.hpp"
#include "raster/elevation_edits.hpp"

namespace aq::mask {

/// The carved depth is at least this far below max(h, 0) (metres).
inline constexpr double kCarveBelowThresholdM = 1.0;
/// A blockage's default height (metres above the datum), when the line states none.
inline constexpr double kBlockageHeightM = 10.0;

/// One carved (or blocked) line as planned, for the log and the report.
struct CarvedLine {
  std::string name;
  std::string source;  ///< "mask.passages_open", or the line's file/layer/feature
  LineKind kind = LineKind::kPassage;
  double depth_m = 0.0;    ///< channel/passage: depth of the corridor's bottom (m, positive down)
  double height_m = 0.0;   ///< blockage: elevation of its top (m)
  std::string depth_from;  ///< how depth_m was chosen (raster sill, table nominal, stated, key)
  double raster_sill_m =
      std::numeric_limits<double>::quiet_NaN();  ///< the raster's sill elevation found (m), NaN = not searched
  LonLat sill{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};  ///< where
  double half_width_km_min = 0.0, half_width_km_max = 0.0;  ///< corridor half-width on the sphere
  double length_km = 0.0;
  std::vector<double> lon_deg, lat_deg;  ///< the corridor's polyline
};

struct Carving {
  std::shared_ptr<const raster::ElevationEdits> edits;  ///< null when nothing is carved
  std::vector<CarvedLine> lines;
  std::vector<std::string> skipped;  ///< lines not carved and why (outside the raster's coverage)
};

/// Throws ConfigError naming mask.passages_open and the name when a name is not in the built-in
/// table (with the closest names and the list of names); call it before any data is read.
void check_passage_names(const config::MaskOptions& options);

/// Plans every line of `options` on `lattice` (K = options.cursor, h = options.min_depth_m),
/// reading the raster through `bathy` (which must not hold edits yet) and the line files through
/// GDAL/OGR. Throws what check_passage_names and read_edit_lines throw. Deterministic.
Carving plan_carving(const config::MaskOptions& options, const Lattice& lattice, const PoleRotation& rot,
                     const raster::Bathymetry& bathy);

/// The longest side of a lattice pixel on the sphere at geographic (lon, lat), in great-circle
/// degrees: Δ_L on the lon-lat lattice, Δ_L·cos φ′ on the Mercator lattice.
double pixel_arc_deg(const Lattice& lattice, const PoleRotation& rot, double lon_deg, double lat_deg);

/// The minimax path of a 4-connected grid (exposed for tests). z: nx × ny row-major elevations
/// (NaN = impassable). Returns the lowest m such that cells <= m join a source to a target
/// (+inf when none do) and, when `path` is given, the path (cell indices, a source first) through
/// cells <= m that minimises Σ length·w(z) over its steps, w = (D / (max(−z, 0) + D))², D =
/// max(−m, 0) + 10 m (it keeps to the deep middle of a channel); `dx` (per row) and `dy` are the
/// steps' lengths.
double minimax_path(const std::vector<double>& z, std::int64_t nx, std::int64_t ny,
                    const std::vector<std::int64_t>& sources, const std::vector<unsigned char>& is_target,
                    const std::vector<double>& dx, double dy, std::vector<std::int64_t>* path);

/// The report's "carving" array.
Json carving_json(const Carving& c);
/// One log line per carved line.
std::vector<std::string> describe_carving(const Carving& c);

}  // namespace aq::mask
