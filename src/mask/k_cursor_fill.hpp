// SPDX-License-Identifier: GPL-3.0-or-later
// K-cursor fill of seed 002 (Kireev & Pyataev 2009, §2 "K-заливка", Fig. 2) in the efficient
// form of ARCHITECTURE §4.3:
//   W(i, j) = the K×K window with lower-left pixel (i, j) is all wet  (separable running AND),
//   R       = windows reachable from the seed windows by 4-connected one-pixel steps through W
//             (periodic in i across the λ seam, no wrap over the poles),
//   Ω_L     = ∪ of the K×K windows of R                            (separable running OR).
// K = 1 is the ordinary 4-connected flood fill; K >= 2 never passes a channel narrower than K
// pixels, so no 1-pixel chains appear in Ω_L.
//
//        j+K  +---+---+                 window (i, j) for K = 2: pixels [i, i+2) × [j, j+2);
//             |   |   |                 windows near the seam wrap: (nx-1, j) holds pixel
//        j    +---+---+                 columns nx-1 and 0; windows (i, j) with j > ny-K do
//             i      i+K                not exist (they would cross a pole).
//
// The reachability step is a span (scanline) flood fill on the bitmap: a run of set bits is
// found and cleared with word operations (ctz), each run is visited once and the rows above
// and below are scanned word-wise over the run. The reached set is unique, so the result does
// not depend on the visiting order or on the number of threads; the erosion and dilation are
// OpenMP-parallel over rows.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/rotation.hpp"
#include "mask/lattice_coords.hpp"

namespace aq::mask {

/// W: bit (i, j) = the K×K window at (i, j) is all set in `wet` (nx × ny, same size as wet).
/// Rows j > ny - K are clear. k >= 1.
Bitmap all_wet_windows(const Bitmap& wet, int k);

/// Dilation by K: bit (i, j) = some window (i - a, j - b), 0 <= a, b < K, is set in `windows`
/// (i - a taken mod nx, j - b >= 0). k >= 1.
Bitmap dilate_windows(const Bitmap& windows, int k);

/// Counts of one flood fill.
struct FloodCount {
  std::int64_t cells = 0;       ///< cells newly reached
  std::int64_t probe_hits = 0;  ///< of those, cells set in the probe bitmap
};

/// 4-connected flood fill (periodic in i, bounded in j) in `remaining` from cell (i, j):
/// every reached cell is cleared in `remaining` and, when given, set in `reached`; hits of
/// `probe` are counted. A start cell that is clear in `remaining` gives a zero count.
FloodCount flood_consume(Bitmap& remaining, PixelIJ start, Bitmap* reached = nullptr, const Bitmap* probe = nullptr);

/// Like flood_consume, calling visit(j, a, b) for every run of cells [a, b) of row j it takes (a
/// run across the seam as its two pieces), in the fill's order; returns the cells taken.
using RunVisitor = std::function<void(std::int64_t j, std::int64_t a, std::int64_t b)>;
std::int64_t flood_consume_runs(Bitmap& remaining, PixelIJ start, const RunVisitor& visit);

/// The cells of `mask` 4-connected (periodic in i) to any of the start cells.
Bitmap flood_fill(const Bitmap& mask, std::span<const PixelIJ> starts);

/// 4-connected components of a bitmap (periodic in i).
struct ComponentStats {
  std::int64_t count = 0;                 ///< number of components
  std::int64_t largest = 0;               ///< cells in the largest component
  std::int64_t touching_probe = 0;        ///< components with at least one cell set in the probe
  std::int64_t cells_touching_probe = 0;  ///< cells of those components
};
/// `scratch`, when given, holds the working copy of `mask` (consumed by the floods; its contents
/// afterwards are unspecified): a bitmap of the same shape lends its storage, no new memory.
ComponentStats count_components(const Bitmap& mask, const Bitmap* probe = nullptr, Bitmap* scratch = nullptr);

/// K-fill on the lattice level: Ω_L from seed windows given by their lower-left pixels (each
/// must be set in all_wet_windows(wet, k), else it contributes nothing). When `reached_per_seed`
/// is given it receives, per seed in order, the number of windows newly reached from it (0 when
/// an earlier seed already reached its window).
Bitmap k_fill(const Bitmap& wet, int k, std::span<const PixelIJ> seed_windows,
              std::vector<std::int64_t>* reached_per_seed = nullptr);

/// Where a seed was put and what it filled.
struct SeedInfo {
  int index = 0;                     ///< position in mask.seeds
  LonLat requested;                  ///< the seed as configured (geographic degrees)
  bool moved = false;                ///< not inside an all-wet window: moved to the nearest one
  double moved_deg = 0.0;            ///< great-circle distance from the seed to the window centre
  PixelIJ window;                    ///< lower-left pixel of the seed window
  LonLat window_center;              ///< geographic centre of the seed window
  std::int64_t windows_reached = 0;  ///< windows newly reached from this seed
  int same_fill_as = -1;             ///< an earlier seed whose fill already held this window, or -1
};

/// The lattice box a seed's nearest all-wet K-window is searched in (window corners (i0, j0)):
/// rows jlo..jhi around latitude `lat_deg` ± `radius_deg` (great-circle degrees), columns ilo..ihi
/// around column `x` where the radius spans less than the globe, else every column (0..nx-1;
/// columns may run outside 0..nx-1 and wrap). Shared by the dense fill and the forest's.
struct SeedSearchBox {
  std::int64_t jlo = 0, jhi = 0, ilo = 0, ihi = 0;
};
SeedSearchBox seed_search_box(const Lattice& lattice, double lat_deg, double x, double radius_deg, std::int64_t k);

/// Places each geographic seed (lon, lat) on an all-wet K window of `windows` (= W). A seed whose
/// point lies in an all-wet window takes the one whose centre is nearest; otherwise it moves to
/// the all-wet window with the nearest centre within `radius_deg` (great-circle degrees) and a
/// warning names both positions. Ties go to the smaller (j, i). Throws ConfigError naming
/// mask.seeds[n] and its position when no all-wet window is within the radius. Preconditions (the
/// config validates mask.seeds and mask.seed_radius_deg at load; InternalError otherwise): at least
/// one seed, each a finite longitude and a latitude in [-90, 90]; a finite radius >= 0.
std::vector<SeedInfo> place_seeds(const Bitmap& windows, int k, const Lattice& lattice, const PoleRotation& rot,
                                  const std::vector<std::array<double, 2>>& seeds, double radius_deg,
                                  const Logger& log);

/// Statistics of the fill (report §4.3).
struct FillStats {
  int cursor = 1;                          ///< K
  std::int64_t wet_pixels = 0;             ///< wet pixels of the lattice
  std::int64_t all_wet_windows = 0;        ///< |W|
  std::int64_t reached_windows = 0;        ///< windows reached from the seeds
  std::int64_t filled_pixels = 0;          ///< |Ω_L|
  std::int64_t wet_left_out = 0;           ///< wet pixels not in Ω_L (lakes, Caspian, cut-off bays, narrows)
  std::int64_t wet_components = 0;         ///< 4-connected components of the wet pixels (K = 1 sense)
  std::int64_t wet_components_filled = 0;  ///< of those, components holding filled pixels
  std::int64_t largest_wet_component = 0;  ///< pixels of the largest wet component
};

struct KFillResult {
  Bitmap filled;  ///< Ω_L, nx × ny
  std::vector<SeedInfo> seeds;
  FillStats stats;
};

/// The whole K-cursor fill: W, seed placement, reachability, dilation and statistics.
/// `wet` is nx × ny of the lattice; 1 <= k <= 64 (mask.cursor, validated at load; InternalError
/// otherwise); seeds as in place_seeds.
KFillResult k_cursor_fill(const Bitmap& wet, const Lattice& lattice, const PoleRotation& rot, int k,
                          const std::vector<std::array<double, 2>>& seeds, double radius_deg, const Logger& log);

}  // namespace aq::mask
