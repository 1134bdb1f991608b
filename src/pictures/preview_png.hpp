// SPDX-License-Identifier: GPL-3.0-or-later
// Preview pictures of a global mesh (PNG through Cairo): an equirectangular map of the lattice
// plane λ ∈ [λ0, λ0+360], φ ∈ [-90, 90] (the rotated system's λ', φ' when the pole is rotated).
//
//   +------------------------------------------------------------+
//   | title: counts                                              |  title band
//   +------------------------------------------------------------+
//   | background: the Bathymetry sampled at every pixel centre   |
//   |   (sea shaded light -> dark blue with depth, land          |  map, width x width/2
//   |   grey-green, no data light grey)                          |  (zoom: the box's aspect)
//   | squares filled by level (translucent, one colour a level)  |
//   | mesh edges thin dark grey; coast (boundary edges) black;   |
//   | the zoom box (if any) outlined in red                      |
//   | outlines (blocks) in magenta with their labels             |
//   +------------------------------------------------------------+
//   | legend: level colours with element counts, sea/land        |  legend band
//   +------------------------------------------------------------+
//
// Elements across the seam are drawn with their nodes unwrapped (I = 0 drawn at I = nx), so the
// map shows them at its east edge. The zoom picture shows a box [lon_min, lon_max] × [lat_min,
// lat_max] of the same plane at the same width; the box may extend past λ0 + 360 (elements are
// drawn shifted by ±360° where they fall into it).
// The bytes are deterministic (no time stamps; fixed drawing order; rows of the background in
// parallel, each band of rows computed independently).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "io/write_stats.hpp"
#include "mesh/mesh.hpp"
#include "mesh_files/element_kinds.hpp"
#include "raster/bathymetry.hpp"

namespace aq::io {

/// A closed polygon drawn on the map (e.g. a regional block), with a label at its first point.
/// Points are (λ', φ') in degrees of the lattice system (as the zoom box), drawn at the plane
/// ordinate of φ' (Lattice::plane_y_of_lat: the Mercator ordinate on the Mercator lattice, so an
/// outline along lattice rows lies on them, φ' clamped to the rows); also shifted by ±360°.
struct PreviewOutline {
  std::vector<std::array<double, 2>> points;
  std::string label;
};

/// What fills the elements (output.png_color): the quadtree level, translucent over the
/// bathymetry ("level"), or opaque per triangle in classes with counts in the legend: its smallest
/// angle on the sphere ("angle": < 10°, 10–20°, …, ≥ 50°, dark red to green) or its size in km
/// ("size": classes 1–2–5–10… km wide on a log scale, spanning the values, fine = yellow), or the
/// target size field at its centre ("target", the same classes). With value_range_km the classes
/// span that range instead, so "size" and "target" pictures of one run share a scale. "elevation":
/// its mean node elevation in fixed classes, sea by depth in blues and land above the datum (the
/// floodplain of a surge mesh) in 0-1, 1-2, 2-5, 5-10, > 10 m classes in yellow to brown.
using config::PreviewColour;

struct PreviewOptions {
  int width_px = 2400;  ///< picture width, 200..20000
  ElementKinds elements = ElementKinds::kTriangles;
  PreviewColour colour = PreviewColour::kLevel;
  /// kAngle / kSize / kTarget / kElevation: one value per triangle of the mesh drawn (degrees / km / m); NaN leaves a
  /// triangle unfilled (the pole cap rows, which the geographic files hold instead).
  std::vector<float> triangle_values;
  std::vector<double> value_range_km;  ///< kSize / kTarget: [lo, hi] the classes span; empty = the values'
  std::vector<double> zoom;  ///< empty, or [lon_min, lon_max, lat_min, lat_max] in map degrees
  std::string title = "aquatoria mesh";
  std::vector<PreviewOutline> outlines;  ///< drawn in magenta over the mesh, labels in black on white
  /// Hidden knob for tests and benchmarks (not a configuration key): a rotated map's background
  /// with atan2, asin and Bathymetry::sample at every pixel (RotatedMapSampler::sample_rows_exact)
  /// instead of RotatedMapSampler::sample_rows.
  bool exact_background = false;
};

/// The preconditions of the writers below (output.png_width and output.png_zoom are validated at
/// load; InternalError otherwise): width 200..20000; zoom empty or 4 finite numbers with
/// lon_min < lon_max <= lon_min + 360 and -90 <= lat_min < lat_max <= 90.
void check_preview_options(const PreviewOptions& options);

/// Draws the whole map (with the zoom box outlined) to `path`. Throws OutputError naming the
/// path on any Cairo or write failure. WriteStats::elements counts the elements drawn.
WriteStats write_preview_png(const mesh::Mesh& mesh, const raster::Bathymetry& bathy, const std::filesystem::path& path,
                             const PreviewOptions& options);

/// Draws the zoom box (options.zoom must be set) to `path`.
WriteStats write_preview_zoom_png(const mesh::Mesh& mesh, const raster::Bathymetry& bathy,
                                  const std::filesystem::path& path, const PreviewOptions& options);

}  // namespace aq::io
