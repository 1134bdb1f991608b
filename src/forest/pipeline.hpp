// SPDX-License-Identifier: GPL-3.0-or-later
// The forest engine's stages of the global run (README "The forest engine"; ARCHITECTURE §4.12):
// pixel classes, K-cursor fill, pinches and passages, the size field, the quadtree's refinement and
// 2:1 balance — on the patches and the p4est forest of every rank — and, on rank 0, the leaves
// and their neighbourhoods from which the mesh stage numbers nodes and emits the templates
// (quadtree::build_nodes_from_neighbourhoods, mesh::build_mesh). Every collective step either
// succeeds on every rank or fails on every rank with the same message (forest/comm.hpp).
#pragma once

#include <memory>
#include <vector>

#include "config/options.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/report.hpp"
#include "core/rotation.hpp"
#include "mask/domain.hpp"
#include "mask/wet_area.hpp"
#include "quadtree/leaves.hpp"
#include "quadtree/nodes.hpp"
#include "raster/bathymetry.hpp"
#include "size/size_field.hpp"

namespace aq::forest {

/// What the stages keep for later collective questions (the open boundary of a regional run).
struct ForestState;

/// One rank's memory once the leaves are known, before rank 0 gathers them and builds the mesh
/// (app/global_run.cpp turns these into the estimate per rank printed then).
struct RankMemory {
  std::int64_t peak_bytes = 0;  ///< the rank's peak so far (the classification, the fill, the pyramids)
  std::int64_t leaves = 0;      ///< its filled leaves (the gather sends them with their neighbourhoods)
  std::int64_t elements = 0;    ///< the triangles their templates make (mesh/templates.hpp; squares x 2 for quads)
};

/// The dropped seas (mask::find_dropped_seas) are found on rank 0 from the wet and filled pixels
/// gathered there on lattices up to this many pixels (two bitmaps of 256 MB); on larger ones
/// the forest counts the dropped components over its ranks and names none. (The hidden test knob
/// AQ_FOREST_DROPPED_MAX_PIXELS sets another limit.)
inline constexpr std::int64_t kDroppedSeasMaxPixels = std::int64_t{1} << 31;

/// What the forest's stages made. On rank 0 `leaves` and `neighbourhoods` hold every filled leaf
/// in the dense engine's order; on the other ranks they are empty.
struct ForestLeaves {
  /// Counts, seeds, pinches and passages (lists on rank 0); on rank 0, when the lattice has at
  /// most kDroppedSeasMaxPixels pixels, the bitmaps `wet` and `filled` (for the dropped seas),
  /// else no bitmap.
  mask::WetArea area;
  std::int64_t dropped_components = -1;  ///< above kDroppedSeasMaxPixels: the dropped components (else -1)
  std::int64_t dropped_pixels = 0;       ///< and their pixels
  size::SizeField size_field;
  std::vector<quadtree::Leaf> leaves;
  std::vector<quadtree::LeafNeighbourhood> neighbourhoods;
  std::int64_t area_domain_pixels = 0;  ///< a regional run: the domain's pixels, over all ranks
  std::vector<RankMemory> rank_memory;  ///< every rank's, in rank order, on every rank
  std::shared_ptr<ForestState> state;
};

/// Runs classify -> fill -> pinches -> passages -> size -> quadtree on the forest, on every rank of
/// MPI_COMM_WORLD (MPI must be running: start_mpi). Logs the stage lines (pass Logger::null() on
/// ranks other than 0) and writes the report's "mask", "quadtree" and "forest" sections. Throws the
/// dense engine's errors for the same inputs, on every rank.
ForestLeaves run_forest_leaves(const config::GlobalConfig& c, const Lattice& lat, const PoleRotation& rot,
                               const raster::Bathymetry& bathy, const mask::Domain& domain, const Logger& log,
                               Report* report);

/// For the open boundary of a regional run: whether each pixel of `queries` (given on rank 0) is wet
/// and outside the domain; the answers on rank 0 (empty elsewhere). Collective.
std::vector<char> wet_outside_domain(const ForestState& state, const mask::Domain& domain,
                                     const std::vector<mask::PixelIJ>& queries);

}  // namespace aq::forest
