// SPDX-License-Identifier: GPL-3.0-or-later
// The mesh stage (seed 002: square mesh of Fig. 5, triangulation by the templates of Fig. 4,
// geographic coordinates and depths of the nodes, pole rotation of Fig. 8; ARCHITECTURE §4.5–4.7):
// balanced quadtree leaves -> aq::mesh::Mesh (mesh/mesh.hpp), which every writer consumes.
//
// Numbering. All nodes — leaf corners, and the centre nodes the templates add — are lattice
// vertices (a centre is added only to leaves with a midside node, whose side is >= 2 pixels), so
// ALL nodes, centres included, are numbered together by (J, I) (quadtree/nodes.hpp). Squares
// follow the leaf order (level-0 square row-major, Morton inside); triangles follow their square
// and, inside it, the template order (mesh/templates.hpp). Nothing depends on the thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "config/options.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/report.hpp"
#include "core/rotation.hpp"
#include "mesh/mesh.hpp"
#include "mesh/templates.hpp"
#include "quadtree/leaves.hpp"
#include "quadtree/nodes.hpp"

namespace aq::raster {
class Bathymetry;
}

namespace aq::mesh {

/// Builds the mesh of balanced leaves (quadtree::build_leaves).
///
/// Fills every field of Mesh: nodes (lattice (I, J); rotated = lattice-system λ', φ'; geographic
/// λ, φ through `rotation`, λ wrapped into [lon0, lon0 + 360); depth sampled from `bathy` at the
/// geographic position, NaN where the raster has no data; NodeFlag bits), squares with their
/// midside nodes (always), triangles by the templates with level and source square (when
/// options.elements is "triangles" or "both"; without triangles no centre nodes are made),
/// boundary edges and loops (wet on the left; one loop `outer`; the φ = ±90° loop flagged `pole`)
/// and pinch nodes. Logs one stage line; fills the report's "mesh" section when `report` is given.
///
/// Throws ConfigError for a bad mesh.elements / mesh.diagonal, InternalError when `leaves` are
/// not sorted, overlap or are not face-balanced.
Mesh build_mesh(const std::vector<quadtree::Leaf>& leaves, const Lattice& lat, const PoleRotation& rotation,
                const raster::Bathymetry& bathy, const config::MeshOptions& options, const Logger& log, Report* report);

/// Whether mesh.elements asks for triangles (whose templates need the centre nodes).
bool mesh_needs_centres(const config::MeshOptions& options);

/// The same from nodes numbered elsewhere (quadtree::build_nodes_from_neighbourhoods: the forest
/// engine), `nodes_s` the seconds that took; `stage` is the caller's "mesh" stage, whose line this
/// writes.
Mesh build_mesh(const std::vector<quadtree::Leaf>& leaves, quadtree::QuadNodes nodes, double nodes_s,
                const Lattice& lat, const PoleRotation& rotation, const raster::Bathymetry& bathy,
                const config::MeshOptions& options, const Logger& log, Report* report, StageScope& stage);

/// Appends the template triangles of every square to mesh.triangles / triangle_level /
/// triangle_square, from mesh.squares and mesh.square_midside, the squares' midside `codes`
/// (bit per side S, E, N, W) and `centres` (node or -1; needed for every code != 0), and the
/// leaves (for the level and the diagonal's parity). Parallel with per-thread counts and prefix
/// sums; the order is the serial one. Throws InternalError when a centre is missing.
void emit_triangles(const std::vector<quadtree::Leaf>& leaves, const std::vector<std::uint8_t>& codes,
                    const std::vector<NodeId>& centres, Diagonal diagonal, Mesh& mesh);

}  // namespace aq::mesh
