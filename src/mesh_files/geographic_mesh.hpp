// SPDX-License-Identifier: GPL-3.0-or-later
// The mesh as written in geographic (or 3-D) coordinates: no element of zero area on the Earth
// and no two nodes at one point (ARCHITECTURE §4.5, §4.8; issue 11).
//
// The lattice mesh (mesh/build_mesh.hpp) is a mesh of the (λ, φ) rectangle. Where the filled
// ocean reaches a pole of the lattice system (the Arctic of every unrotated run), the row
// φ = ±90° is a row of distinct lattice nodes that are one point on the Earth, and the triangles
// with two nodes on it have zero area. Every writer whose coordinates are geographic (UGRID,
// fort.14, plain text, MSH on the sphere, VTU) writes the mesh this class makes instead:
//
//  * cap (triangle output, the default): when the whole level-0 row next to the pole and the
//    pixel row below it are filled, every element of that row is replaced by the pole cap of
//    mesh/pole_cap.hpp: rings of nearly equilateral triangles (valence ≤ 8 in the default run)
//    round a small polar island, with the row's far edge (a full lattice row of existing nodes)
//    kept, so the rest of the mesh is untouched and conforming. The island (radius about one
//    cap element, 1.2° in the default run, 0.01% of the ocean) keeps every node off the pole:
//    at a node on the pole the λ–φ metric factors (1/cos φ) are infinite, and ADCIRC (ICS = 22)
//    blew up at the first step on a cap with a pole node. It is a boundary loop of its own (an
//    island in fort.14). New nodes get their depth from the raster like every other node (they
//    are new points of the ocean; interpolating the replaced nodes would only smooth the same
//    raster). The polar boundary loop (φ = 90°, a line of length zero) goes.
//    Why not the pole on land by rotation: the unrotated run is the seed's reference run, and
//    models need the Arctic. Why not a merged pole node: its valence (135 in the default run)
//    made ADCIRC 3.7× slower, and it is a node on the pole.
//  * merge (fallback): when the polar row is not all ocean (a coast crosses it) the cap cannot be
//    attached to a full ring; the pole-row nodes are merged into their lowest-numbered one
//    (io/pole_merge.hpp) and the triangles that become degenerate are dropped.
//  * squares or both (mesh.elements): a cap of triangles cannot replace the squares, so every
//    pole row is merged as in the fallback; a square on the pole row keeps its corner slots with
//    the pole node twice (a triangle on the Earth; its polygon, square_polygon, lists it once),
//    and a degenerate triangle of "both" is dropped. The squares keep their ids, so
//    triangle_square stays valid. The 3-D writers' own merge (VTU, MSH on the sphere) then finds
//    nothing left to merge.
//
// Node ids: the kept lattice nodes in their order, then the new cap nodes (South cap, North cap;
// rings from the outside in). New nodes have node_i = node_j = -1 and the flag kNodeCap. The
// island loops follow the kept loops. Cap triangles have level 0; the capped mesh has no squares.
// A mesh for triangle writers has no triangle_square (empty: no squares to point to; it was
// 8 bytes of -1 per triangle); with squares it keeps the lattice mesh's. The result depends only
// on the mesh (no threads, no clock).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "core/report.hpp"
#include "mesh/mesh.hpp"
#include "mesh/sphere_geometry.hpp"
#include "mesh_files/element_kinds.hpp"

namespace aq::io {

/// How a pole row became geographic (the report's "method").
enum class PoleMethod { kCap, kMerge };
inline constexpr std::array<EnumName<PoleMethod>, 2> kPoleMethodNames{{
    {PoleMethod::kCap, "cap", "rings of triangles round a small polar island"},
    {PoleMethod::kMerge, "merge", "the pole row merged into one node"},
}};
constexpr std::span<const EnumName<PoleMethod>> enum_names(PoleMethod) { return kPoleMethodNames; }
/// Radius (km) of WGS84's authalic sphere (the sphere of the same area): sizes and areas on the
/// unit sphere in km.
inline constexpr double kAuthalicRadiusKm = 6371.0072;

/// What was done at one pole.
struct PoleChange {
  bool north = true;
  PoleMethod method = PoleMethod::kCap;
  std::string reason;              ///< why kMerge (empty for kCap)
  double ring_lat_deg = 0.0;       ///< cap: lattice latitude of ring 0
  std::int64_t ring_nodes = 0;     ///< cap: nodes of ring 0 (kept)
  std::int64_t removed_nodes = 0;  ///< lattice nodes no longer written (pole row included)
  std::int64_t removed_triangles = 0;
  std::int64_t added_nodes = 0;  ///< cap nodes (the pole included)
  std::int64_t added_triangles = 0;
  int rings = 0;                    ///< cap: inner rings
  int max_valence = 0;              ///< cap: most triangles around a node of the cap or ring 0
  double min_angle_deg = 0.0;       ///< cap: smallest angle of a cap triangle on the sphere
  double max_angle_deg = 0.0;       ///< cap: largest angle of a cap triangle on the sphere
  std::int64_t island_nodes = 0;    ///< cap: nodes of the polar island's loop (the last ring)
  double island_radius_deg = 0.0;   ///< cap: distance of the island's loop from the pole
  double island_area_km2 = 0.0;     ///< cap: area of the island (authalic sphere), no longer ocean
  double area_relative_change = 0;  ///< cap: |cap + island − area replaced| / area replaced (sphere)
};

/// Depths (elevation, m, negative below sea level) at geographic points, like build_mesh samples
/// every node: fn(lon_deg, lat_deg, elevation_m) with elevation_m sized like lon_deg.
using ElevationSampler =
    std::function<void(const std::vector<double>& lon_deg, const std::vector<double>& lat_deg, std::vector<double>&)>;

class GeographicMesh {
 public:
  /// Builds the geographic mesh of `lattice_mesh` for writers of `kinds` (see the top of this
  /// file). `lattice_mesh` must outlive this object. Throws InternalError when the cap fails its
  /// own checks (a cap triangle not anticlockwise on the sphere, or the area of the cap differing
  /// from the area it replaces by more than 1e-9).
  GeographicMesh(const mesh::Mesh& lattice_mesh, ElementKinds kinds, const ElevationSampler& elevation);

  [[nodiscard]] const mesh::Mesh& mesh() const { return owned_ ? *owned_ : lattice_; }
  [[nodiscard]] bool changed() const { return owned_.has_value(); }
  [[nodiscard]] const std::vector<PoleChange>& poles() const { return poles_; }
  /// Lattice-mesh triangle each triangle of mesh() comes from, -1 for a cap triangle; empty when
  /// the mesh is unchanged (then triangle k is lattice triangle k).
  [[nodiscard]] const std::vector<ElementId>& source_triangle() const { return source_triangle_; }

  /// One line per changed pole, for the log.
  [[nodiscard]] std::vector<std::string> describe() const;
  /// The "geographic_mesh" report section: written counts and what was done at each pole.
  [[nodiscard]] Json json() const;

 private:
  const mesh::Mesh& lattice_;
  std::optional<mesh::Mesh> owned_;
  std::vector<PoleChange> poles_;
  std::vector<ElementId> source_triangle_;
};

// The sphere's geometry, where it lives now (mesh/sphere_geometry.hpp).
using mesh::spherical_angles_deg;
using mesh::spherical_triangle_area;
using mesh::unit_vector_deg;

}  // namespace aq::io
