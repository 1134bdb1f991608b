// SPDX-License-Identifier: GPL-3.0-or-later
// The quadtree stage (seed 002 §"дискретный аналог акватории", Fig. 1; ARCHITECTURE §4.4): from
// the filled set Ω_L to balanced leaves, in the order Ω_l/D_l -> coastal band -> depth/box rules
// -> 2:1 smoothing -> leaves -> checkers (partition of Ω_L, balance).
#pragma once

#include <vector>

#include "config/options.hpp"
#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/report.hpp"
#include "core/rotation.hpp"
#include "quadtree/leaves.hpp"
#include "size/size_field.hpp"

namespace aq::raster {
class Bathymetry;
}

namespace aq::quadtree {

/// Builds the balanced leaves of the filled set.
///
/// `filled` is Ω_L on the lattice (lat.nx × lat.ny pixels). `rotation` maps lattice coordinates
/// to geographic ones (identity without pole rotation); `bathy` is needed only for depth rules
/// (may be null otherwise). `field` is the target size field (size/size_field.hpp); null: the
/// field of quadtree.size_km / coast_size_km alone (size::build_size_field), the level rules only when both are 0. Logs
/// one stage line and, when `report` is given, writes the "quadtree" section: leaves per level for the bare D_l rule,
/// after the coastal band and rules, and after smoothing, plus sub-stage timings. `coast` (mask/coast.hpp; bitmaps
/// lat.nx × lat.ny) says what the coastal band and a field built here take for the coast: the open water beyond a
/// regional domain is none, the shoreline at the datum of a floodplain run is.
///
/// Throws ConfigError for bad quadtree options (coast_band < 0, balance not "face"/"corner", bad
/// rules) and InternalError when a checker fails (leaves not partitioning Ω_L, or balance
/// violations left).
std::vector<Leaf> build_leaves(const Bitmap& filled, const Lattice& lat, const config::QuadtreeOptions& options,
                               const PoleRotation& rotation, const raster::Bathymetry* bathy, const Logger& log,
                               Report* report, const size::SizeField* field = nullptr,
                               const mask::CoastSources& coast = {});

/// Leaves per level after each step of the stage: the bare D_l rule, the coastal band, the rules
/// and size field, the balance (both engines; the report's leaves_per_level_*).
struct LeafSteps {
  std::vector<std::int64_t> bare, banded, refined, balanced;
};

/// Throws InternalError unless the leaves of every step hold the `filled_pixels` pixels of Ω_L.
void check_leaf_steps(const LeafSteps& steps, int levels, std::int64_t filled_pixels);

/// Throws InternalError unless `leaves` hold per_level[l] leaves of each level l (the counts of
/// the pyramid they were extracted from).
void check_leaves_per_level(const std::vector<Leaf>& leaves, const std::vector<std::int64_t>& per_level);

/// The "quadtree" report entries of both engines: the lattice, the options, the steps' leaf counts
/// and the balance violations left (none).
void leaf_steps_json(Json& q, const Lattice& lat, const config::QuadtreeOptions& options, std::int64_t filled_pixels,
                     const LeafSteps& steps, std::int64_t violations);

}  // namespace aq::quadtree
