// SPDX-License-Identifier: GPL-3.0-or-later
// Quadtree leaves from the filled set Ω_L (seed 002, §"дискретный аналог акватории": the sets
// Ω_l and D_l; ARCHITECTURE §4.4). The quadtree lives in a pyramid of bitmaps, one per level,
// built in O(N) with word tricks (bits.hpp):
//
//   omega[l](a, b)  square (l, a, b) lies inside a leaf of level <= l        (the seed's Ω_l)
//   any[l](a, b)    square (l, a, b) holds at least one filled pixel
//
// omega[L] is the filled set Ω_L itself. A leaf of level l is a square with omega[l] set and
// omega[l-1] clear on its parent (level 0: omega[0] set) — for the bare rule these are exactly
// the seed's D_l = {Q^l ⊆ Ω_L, Q^l ⊄ Ω_{l-1}}. Refinement only ever clears omega bits (splits),
// and omega stays monotone: omega[l] set implies omega[l+1] set on all four children.
//
// Squares, children and order (level l has nx_l = nx·2^(l-L) by ny_l = ny·2^(l-L) squares;
// square (l, a, b) covers pixels [a·2^(L-l), (a+1)·2^(L-l)) × [b·2^(L-l), (b+1)·2^(L-l))):
//
//        +-----+-----+        children of (l, a, b) at level l+1, in Morton (z) order:
//        |  2  |  3  |          0 SW (2a, 2b)     1 SE (2a+1, 2b)
//        | NW  | NE  |          2 NW (2a, 2b+1)   3 NE (2a+1, 2b+1)
//        +-----+-----+
//        |  0  |  1  |        Leaves are ordered by their level-0 square (row-major: b0 first,
//        | SW  | SE  |        then a0) and, inside it, by the Morton key of their SW pixel.
//        +-----+-----+
//
// Refinement rules applied before smoothing (all of them split, never merge):
//  * coastal band (`QuadtreeOptions::coast_band` = r): a filled pixel is in the band when an
//    unfilled pixel lies within Chebyshev distance r (columns wrap at the seam; rows beyond the
//    poles do not exist, so the lattice edge at φ = ±90° is not coast). Every leaf holding a band
//    pixel is split, recursively, until the band pixels are leaves of level L. With coast sources
//    (mask/coast.hpp) an unfilled pixel beyond a regional domain's edge in water is no coast (the
//    open boundary follows the other rules), and in a floodplain run a sea pixel (wet at the
//    datum) is also in the band when a pixel that is neither sea nor open lies within r of it
//    (the sea side of the shoreline at 0 m).
//  * depth rules (`DepthRule`) and box rules (`BoxRule`) asking level m >= 1 are sampled on the
//    level-(m-1) grid: every level-(m-1) square whose centre is in the rule's range is split,
//    together with every coarser square containing it, so the leaves there get level >= m.
//    A depth rule's range is depth (positive down, = -elevation) in [min_depth_m, max_depth_m),
//    sampled from the raster at the centre (NaN: not in range). A box rule's range is
//    lat_min <= φ <= lat_max and λ in [lon_min, lon_max] modulo 360 (lon_max < lon_min means the
//    box crosses the antimeridian). Centres are taken in the lattice (rotated) system and mapped
//    to geographic (λ, φ) through the PoleRotation. Where several rules apply the finest level
//    wins; level 0 asks nothing.
//  * a depth or box rule may ask a size instead of a level (`size_km` > 0, issue 12): that form is
//    a term of the target size field (size/size_field.hpp, issue 19), applied by apply_size_field
//    with every other size; apply_refinement_rules applies the level form only.
#pragma once

#include <compare>
#include <cstdint>
#include <numbers>
#include <vector>

#include "config/options.hpp"
#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/rotation.hpp"
#include "mask/coast.hpp"
#include "size/size_field.hpp"

namespace aq::raster {
class Bathymetry;
}

namespace aq::quadtree {

/// A quadtree leaf: the square (a, b) of level `level` (0 <= level <= L, 0 <= a < nx_l,
/// 0 <= b < ny_l). Plain data; the pixel extent follows from core/lattice.hpp.
struct Leaf {
  std::int32_t level = 0;
  std::int64_t a = 0;
  std::int64_t b = 0;
  friend bool operator==(const Leaf&, const Leaf&) = default;
};

/// Pixels per side of a leaf: 2^(L - level).
inline std::int64_t leaf_size(const Lattice& lat, const Leaf& f) { return lat.pixels_per_square(f.level); }
/// Column of the leaf's SW pixel (= I of its SW corner vertex).
inline std::int64_t leaf_i0(const Lattice& lat, const Leaf& f) { return f.a * leaf_size(lat, f); }
/// Row of the leaf's SW pixel (= J of its SW corner vertex).
inline std::int64_t leaf_j0(const Lattice& lat, const Leaf& f) { return f.b * leaf_size(lat, f); }

/// Fractional pixel row of the centre of the level-l squares of row b: (b + ½)·2^(L - level).
inline double square_centre_row(const Lattice& lat, int level, std::int64_t b) {
  return (static_cast<double>(b) + 0.5) * static_cast<double>(lat.pixels_per_square(level));
}
/// Fractional pixel row of the leaf's centre.
inline double leaf_centre_row(const Lattice& lat, const Leaf& f) { return square_centre_row(lat, f.level, f.b); }

/// Sort key of the deterministic leaf order: level-0 square row-major, then Morton of the SW
/// pixel inside it. Keys of non-overlapping leaves are distinct.
struct LeafKey {
  std::uint64_t root = 0;    ///< b0 · nx_0 + a0 of the level-0 square
  std::uint64_t morton = 0;  ///< Morton key of the pixel's offset inside the level-0 square
  auto operator<=>(const LeafKey&) const = default;
};
/// Key of pixel (i, j), 0 <= i < nx, 0 <= j < ny.
LeafKey pixel_key(const Lattice& lat, std::int64_t i, std::int64_t j);
/// Key of a leaf (the key of its SW pixel).
LeafKey leaf_key(const Lattice& lat, const Leaf& f);

/// The quadtree as a pyramid of bitmaps (see the file comment). omega has L+1 levels; any has
/// L+1 entries of which any[L] is left empty: use any_at(), which returns omega[L] for l = L.
struct LevelMasks {
  std::vector<Bitmap> omega;
  std::vector<Bitmap> any;
  /// What the coastal band takes for coast beyond the edge of the filled set (the bitmaps must
  /// outlive the masks); empty: every unfilled pixel.
  mask::CoastSources coast;
  [[nodiscard]] int levels() const { return static_cast<int>(omega.size()) - 1; }
  [[nodiscard]] const Bitmap& any_at(int l) const {
    return l == levels() ? omega.back() : any[static_cast<std::size_t>(l)];
  }
  [[nodiscard]] const Bitmap& filled() const { return omega.back(); }
};

/// Pixels of the coastal band of radius `band` >= 0 (see the file comment; `coast` the open water
/// and the sea at the datum, mask/coast.hpp); empty for band = 0.
/// Cost O((log band + 2·band + 1) · N / 64) word operations (twice that with a sea).
Bitmap coastal_band(const Bitmap& filled, int band, const mask::CoastSources& coast = {});

/// The pyramid of Ω_l (the bare D_l rule when coast_band = 0, else with the coastal band split
/// to level L). `filled` (and the bitmaps of `coast`, which must outlive the masks) must be
/// lat.nx × lat.ny and coast_band >= 0 (quadtree.coast_band, validated at load); InternalError
/// otherwise. O(N / 64) word operations, parallel.
LevelMasks make_level_masks(const Bitmap& filled, const Lattice& lat, int coast_band,
                            const mask::CoastSources& coast = {});

/// Recomputes omega[0..L-1] of `masks` from its filled set with the coastal band of radius
/// `coast_band` (and masks.coast) split to level L (0: the bare rule); the `any` pyramid is
/// unchanged. Undoes any earlier refinement. coast_band >= 0 (InternalError otherwise).
void apply_coast_band(LevelMasks& masks, int coast_band);

/// Applies the depth and box rules of `options` in place (see the file comment). `bathy` may be
/// null when there are no depth rules (InternalError otherwise). The rules are as validated at load
/// (config/global_config.cpp: one of level 0..L and size_km > 0, non-empty ranges).
void apply_refinement_rules(LevelMasks& masks, const Lattice& lat, const config::QuadtreeOptions& options,
                            const PoleRotation& rotation, const raster::Bathymetry* bathy);

/// The finest level apply_refinement_rules splits (the level form: one below the rule's level),
/// -1 when no rule asks a level.
[[nodiscard]] int rules_top_level(const config::QuadtreeOptions& options, int levels);
/// One level l of apply_refinement_rules on a piece of the lattice: `om` holds the level-l squares
/// [ax, ax + om.nx()) × [bx, bx + om.ny()) (omega already monotone from the finer level); clears
/// those whose centre a level rule of level l + 1 holds. Rules must have been validated.
void apply_rules_level(Bitmap& om, const Lattice& lat, const config::QuadtreeOptions& options,
                       const PoleRotation& rotation, const raster::Bathymetry* bathy, int l, std::int64_t ax,
                       std::int64_t bx);

/// Mean Earth radius (km) used for the physical size of lattice squares.
inline constexpr double kEarthRadiusKm = 6371.0088;

/// Physical size (km) of a level-l square whose rows are centred on the fractional pixel row
/// `row_centre`: its side Δ0/2^l in λ times the lattice's size scale there (Mercator: cos φ′ for
/// both sides; lon-lat: √cos φ′, the square root of its area), on a sphere of radius kEarthRadiusKm.
[[nodiscard]] double square_size_km(const Lattice& lat, int level, double row_centre);

/// Whether a square of `size_km` is split for the size target `target_km` (> 0): when it is
/// larger than √2·target, so that the squares left take the level whose size is nearest the
/// target (sizes halve from one level to the next). The one test of the size rules.
[[nodiscard]] inline bool exceeds_size_target(double size_km, double target_km) {
  return size_km > std::numbers::sqrt2 * target_km;
}

/// The level a size target `target_km` (> 0) asks at the fractional pixel row `row`: the coarsest
/// l in 0..L whose square_size_km(lat, l, row) does not exceed √2·target, and L when even the
/// pixels do. (The rules test each square at its own centre row; this is for logs and reports.)
[[nodiscard]] int level_for_size(const Lattice& lat, double target_km, double row);

/// Applies the target size field (size/size_field.hpp) in place after the coastal band and the
/// level rules and before smoothing: a level-l square (l < L) is split, with every coarser square
/// containing it, while its square_size_km exceeds √2 × the field's minimum over it — the grid's
/// minimum over the square, and the band term (band_km) when the square holds a pixel of the
/// coastal band of radius field.band_radius(). Each square so ends at the level whose size is
/// nearest the field (within √2) unless the filled set, a level rule or the 2:1 balance asks for a
/// finer one, or level 0 is already finer. quadtree.size_km is a constant term of the field and
/// quadtree.coast_size_km its band term, so those keys keep their meaning. No-op for an inactive field.
void apply_size_field(LevelMasks& masks, const Lattice& lat, const size::SizeField& field);

/// The shortest edge (km) a triangle of a level-(l+1) child of a level-l square of row b may have:
/// the child's shortest side at the parent's poleward edge (along the row: Δλ·cos φ′ there; along
/// the column: the Mercator side or Δφ), halved when the child can hold hanging nodes (l+1 < L).
[[nodiscard]] double child_min_edge_km(const Lattice& lat, int l, std::int64_t b);

/// Whether the CFL edge bound of `field` lets the level-l square (a, b) be split: its children's
/// shortest possible edge (child_min_edge_km) is not below the bound anywhere over the square.
[[nodiscard]] bool cfl_allows_split(const size::SizeField& field, int l, std::int64_t a, std::int64_t b,
                                    double child_edge_km);

/// The radii grade_levels keeps around a split level-v square, per row b of level-v squares:
/// rx[b] squares along the row (at most the row's length), ry[b] along the column (at most the
/// rows), for the gradation g > 0 (see grade_levels).
void grading_radii(const Lattice& lat, int v, double g, std::vector<std::int64_t>& rx, std::vector<std::int64_t>& ry);

/// One level of apply_size_field: `om` holds the level-l squares [a0, a0 + om.nx()) ×
/// [b0, b0 + om.ny()) of the lattice (omega already kept monotone from the finer level); splits
/// (clears) those the field asks, `band` the band pyramid's bits of the same squares (null: no
/// band term). The forest engine calls it on pieces of the lattice.
void apply_size_field_level(Bitmap& om, const Bitmap* band, const Lattice& lat, const size::SizeField& field, int l,
                            std::int64_t a0, std::int64_t b0);

/// What grade_levels did.
struct GradeStats {
  std::int64_t splits = 0;             ///< squares split to keep the grading
  std::int64_t cfl_refused = 0;        ///< splits the CFL edge bound refused (the grading yields there)
  std::int64_t radius_at_equator = 0;  ///< run length (squares) at level L-1 mid-lattice
};

/// Quantisation that keeps the field's grading g = field.gradation() (ARCHITECTURE §4.10), after
/// apply_size_field and before the 2:1 balance, when the field has a grid and g > 0 (a no-op
/// otherwise, so the seed's level-only mode is untouched). A level steps only after a run of
/// squares of one level long enough for the grading: for v = L-1 .. 1, every level-v square
/// within r squares of a split level-v square (one holding finer leaves) is kept out of a coarser
/// leaf (its level-(v-1) parent is split), r = ⌈a/(√2·g·d)⌉ per direction (a: the level-v
/// square's size at its equatorward edge, d: its side along the row or column at its poleward
/// edge; on the Mercator lattice ⌈1/(√2·g)⌉ = 4 for g = 0.2 except on coarse squares near the poles). So every run of level v between a finer and a coarser level spans at least r squares
/// and its grading a/(√2·D) is at most g, whatever asked the finer level (the D_l rule at the
/// coast, a level rule, the field). It implies the corner 2:1 balance. Only splits; one pass,
/// fine to coarse. A split the field's CFL edge bound refuses is not made (CFL last).
GradeStats grade_levels(LevelMasks& masks, const Lattice& lat, const size::SizeField& field);

/// One level v (1 <= v < omega.size()) of grade_levels: the level-v squares holding finer leaves
/// (`any` & ~omega[v]) split every omega[v-1] square within the grading radii (CFL permitting),
/// then omega stays monotone down to level 0. `omega` are the pyramid's levels 0..v (or more) of
/// the whole lattice. The forest engine runs it on its replicated coarse levels.
GradeStats grade_level(std::vector<Bitmap>& omega, const Bitmap& any, const Lattice& lat, const size::SizeField& field,
                       int v);

/// Leaves of the pyramid in the deterministic order. Parallel over level-0 squares.
std::vector<Leaf> extract_leaves(const LevelMasks& masks, const Lattice& lat);

/// Number of leaves per level (index = level, L+1 entries), counted on the bitmaps.
std::vector<std::int64_t> count_leaves_per_level(const LevelMasks& masks);

/// Whether `leaves` are in the deterministic order with strictly increasing keys.
bool leaves_sorted(const std::vector<Leaf>& leaves, const Lattice& lat);

/// Index of the first leaf of every level-0 row b0 (ny_0 + 1 entries, the last = leaves.size())
/// of leaves in the deterministic order.
std::vector<std::int64_t> root_row_starts(const std::vector<Leaf>& leaves, const Lattice& lat);

/// The filled pixels covered by `leaves` (any order; parallel when sorted). Throws InternalError when leaves overlap
/// (their pixel count differs from the covered count) or lie outside the lattice.
/// When `sorted` is given it receives leaves_sorted(leaves, lat).
Bitmap leaf_coverage(const std::vector<Leaf>& leaves, const Lattice& lat, bool* sorted = nullptr);

/// The pyramid of a leaf set (inverse of extract_leaves for non-overlapping leaves, any order;
/// parallel when sorted). Throws InternalError when the leaves overlap or lie outside the lattice.
LevelMasks masks_from_leaves(const std::vector<Leaf>& leaves, const Lattice& lat);

/// Finds the leaf holding a pixel by binary search on the leaf order, O(log n).
class LeafLocator {
 public:
  /// Keeps a reference to `leaves`, which must outlive the locator. Throws InternalError when
  /// the leaves are not in the deterministic order.
  LeafLocator(const std::vector<Leaf>& leaves, const Lattice& lat);
  /// Index of the leaf containing pixel (i mod nx, j), or -1 when the pixel is not covered or
  /// j is outside [0, ny).
  [[nodiscard]] std::int64_t find(std::int64_t i, std::int64_t j) const;

 private:
  const std::vector<Leaf>& leaves_;
  Lattice lat_;
  std::vector<LeafKey> keys_;
};

}  // namespace aq::quadtree
