// SPDX-License-Identifier: GPL-3.0-or-later
// The global pixel lattice (ARCHITECTURE §3): level-0 squares of side Δ0 (Δ0 divides 180°),
// L levels of halving, pixels = level-L squares. Lattice vertex (I, J) sits at
//   λ = lon0 + I·Δ_L,   φ = -90 + J·Δ_L,   0 <= I < nx (periodic: I = nx is I = 0), 0 <= J <= ny.
// Pixel (i, j) has lower-left vertex (i, j). Level-l square (a, b) covers pixels
// [a·2^(L-l), (a+1)·2^(L-l)) × [b·2^(L-l), (b+1)·2^(L-l)).
// With pole rotation the lattice lives in the rotated system; λ, φ above are rotated coordinates.
//
// The Mercator lattice (quadtree.lattice = "mercator", issue 12) is the same integer grid with
// another row map: vertex row J sits at the Mercator ordinate y = y0 + J·Δ_L (degrees of
//   y = ln tan(π/4 + φ/2), in radians ·180/π) and at latitude φ = atan(sinh y); λ as above. One
// step in λ and in y makes every pixel a conformal square on the sphere (side Δ_L·cos φ). The
// rows cover |φ| <= φ_max: y0 = -m0·Δ0 with m0 level-0 squares per hemisphere, the fewest whose
// ordinate reaches φ_max (Δ0 = 4°, φ_max = 85°: m0 = 45, y = ±180°, φ = ±85.0511°). Everything
// that needs the latitude of a row goes through lat_of / lat_of_row / row_of_lat; lattice-plane
// pictures and files use plane_y (= φ on the lon-lat lattice, = y on the Mercator one).
//
// A window lattice (a regional run, README "Regional FE meshes") is a block of the global one:
// columns i_origin .. i_origin + nx, rows j_origin .. j_origin + ny of the global lattice, aligned
// to its level-0 squares. Its vertex (I, J) is the global vertex (I + i_origin, J + j_origin): λ,
// φ and every coordinate function below include the origin, so the same vertex has the same bits
// on both lattices. lon0_deg and y0_deg stay the global lattice's. The window's columns are
// contiguous (i_origin may be negative, or i_origin + nx may run past the global seam: λ then goes
// on past λ0 + 360); it is periodic in I only when it spans all longitudes (periodic()). The
// window is padded with at least one level-0 square outside the domain on every side that is not
// a pole, so the code that wraps I = nx to 0 or takes row 0 / row ny for a pole only ever touches
// padding, which is never meshed; pole_row() says whether a row really is a pole.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "core/enum_names.hpp"

namespace aq {

/// The lattice's rows (quadtree.lattice): equal steps of latitude (the seed's) or of the Mercator
/// ordinate (conformal squares).
enum class LatticeKind { kLonLat, kMercator };
inline constexpr std::array<EnumName<LatticeKind>, 2> kLatticeKindNames{{
    {LatticeKind::kLonLat, "lonlat", "the seed's longitude-latitude squares"},
    {LatticeKind::kMercator, "mercator", "x = lon', y = ln tan(pi/4 + lat'/2): conformal squares"},
}};
constexpr std::span<const EnumName<LatticeKind>> enum_names(LatticeKind) { return kLatticeKindNames; }

/// Mercator ordinate (degrees, y = ln tan(π/4 + φ/2)·180/π) of latitude φ (degrees, |φ| < 90).
[[nodiscard]] double mercator_y_deg(double lat_deg);
/// Latitude (degrees) of the Mercator ordinate y (degrees): φ = atan(sinh y).
[[nodiscard]] double mercator_lat_deg(double y_deg);

struct Lattice {
  LatticeKind kind = LatticeKind::kLonLat;
  double y0_deg = -90.0;     ///< plane ordinate of row 0: φ = -90 (lon-lat) or the Mercator y = -m0·Δ0
  double lon0_deg = -180.0;  ///< western edge of the lattice (the seam)
  double step0_deg = 4.0;    ///< Δ0, side of a level-0 square; 180/Δ0 is an integer
  int levels = 3;            ///< L >= 0
  std::int64_t n0 = 45;      ///< 180/Δ0: level-0 squares per meridian
  std::int64_t nx = 720;     ///< pixels along λ: 2·n0·2^L
  std::int64_t ny = 360;     ///< pixels along φ: n0·2^L
  std::int64_t i_origin = 0;      ///< window: global column of column 0 (0 on the global lattice)
  std::int64_t j_origin = 0;      ///< window: global row of row 0 (0 on the global lattice)
  std::int64_t nx_global = 720;   ///< the global lattice's nx
  std::int64_t ny_global = 360;   ///< the global lattice's ny

  /// Builds the lattice. Preconditions (quadtree.step_deg, levels, lon0_deg are validated at load;
  /// InternalError otherwise): Δ0 divides 180° exactly in arc-seconds (step_problem() is ""),
  /// 0 <= L <= 20, λ0 finite. A step within rounding of a
  /// whole arc-second value (1e-6") becomes exactly that value: 0.2666666666666667 and
  /// 0.26666666666666666 give the same lattice (step0_deg = 960/3600), whose rows end at ±90°.
  static Lattice make(double step0_deg, int levels, double lon0_deg);
  /// The Mercator lattice of the same Δ0, L, λ0 whose rows reach at least ±`lat_max_deg` (in whole
  /// level-0 squares); 1 <= lat_max_deg <= 89.5 (quadtree.mercator_lat_max_deg, validated at load;
  /// InternalError otherwise).
  static Lattice make_mercator(double step0_deg, int levels, double lon0_deg, double lat_max_deg);
  /// Why `step0_deg` is not a valid Δ0 (one sentence without the key), or "" when it is.
  static std::string step_problem(double step0_deg);
  /// The window of the global lattice `g` with columns [i_first, i_first + nx) (contiguous; may
  /// start west of the seam or run past it; nx >= g.nx gives all columns, periodic) and rows
  /// [j_first, j_first + ny) clamped to the global rows. i_first, j_first, nx and ny are whole
  /// level-0 squares (InternalError otherwise).
  static Lattice window(const Lattice& g, std::int64_t i_first, std::int64_t nx, std::int64_t j_first,
                        std::int64_t ny);
  /// Whether this is a window of the global lattice (not all of it).
  [[nodiscard]] bool windowed() const { return nx != nx_global || ny != ny_global; }
  /// Whether column nx is column 0 (the lattice spans all longitudes).
  [[nodiscard]] bool periodic() const { return nx == nx_global; }
  /// Whether vertex row J is a pole row of the lon-lat lattice (J = 0 or ny of the global one).
  [[nodiscard]] bool pole_row(std::int64_t j) const {
    return !mercator() && (j + j_origin == 0 || j + j_origin == ny_global);
  }
  /// Global column of the first column of a level-l square column 0 (i_origin / 2^(L-l)).
  [[nodiscard]] std::int64_t square_origin_i(int level) const { return i_origin / pixels_per_square(level); }
  /// λ of the fractional column x (x in pixels from column 0 of this lattice).
  [[nodiscard]] double lon_at(double x) const {
    return lon0_deg + (i_origin == 0 ? x : x + static_cast<double>(i_origin)) * pixel_deg();
  }
  /// Fractional column of the longitude λ: in [0, nx) on a periodic lattice (λ wrapped as
  /// wrap_lon_deg does); on a window, the column of λ or λ ± 360 nearest the window (may be
  /// outside [0, nx)).
  [[nodiscard]] double col_of_lon(double lon_deg) const;

  [[nodiscard]] double pixel_deg() const { return step0_deg / static_cast<double>(std::int64_t{1} << levels); }
  [[nodiscard]] double lon_of(std::int64_t i) const {
    return lon0_deg + static_cast<double>(i + i_origin) * pixel_deg();
  }
  [[nodiscard]] bool mercator() const { return kind == LatticeKind::kMercator; }
  /// Plane ordinate (degrees) of the fractional row y: φ on the lon-lat lattice, the Mercator y.
  [[nodiscard]] double plane_y(double y) const {
    return y0_deg + (j_origin == 0 ? y : y + static_cast<double>(j_origin)) * pixel_deg();
  }
  /// Latitude (lattice frame, degrees) of the fractional row y.
  [[nodiscard]] double lat_of_row(double y) const {
    return mercator() ? mercator_lat_deg(plane_y(y))
                      : -90.0 + (j_origin == 0 ? y : y + static_cast<double>(j_origin)) * pixel_deg();
  }
  /// Fractional row of the latitude φ (lattice frame, degrees); inverse of lat_of_row.
  [[nodiscard]] double row_of_lat(double lat_deg) const {
    const double y = mercator() ? (mercator_y_deg(lat_deg) - y0_deg) / pixel_deg() : (lat_deg + 90.0) / pixel_deg();
    return j_origin == 0 ? y : y - static_cast<double>(j_origin);
  }
  [[nodiscard]] double lat_of(std::int64_t j) const { return lat_of_row(static_cast<double>(j)); }
  /// Plane ordinate of vertex row J (see plane_y).
  [[nodiscard]] double plane_y_of(std::int64_t j) const { return plane_y(static_cast<double>(j)); }
  /// Plane ordinate of a latitude (lattice frame): φ itself or its Mercator y.
  [[nodiscard]] double plane_y_of_lat(double lat_deg) const { return mercator() ? mercator_y_deg(lat_deg) : lat_deg; }
  /// Highest latitude of the global lattice's rows (90 on the lon-lat lattice).
  [[nodiscard]] double lat_max_deg() const { return lat_of(ny_global - j_origin); }
  /// Length on the sphere of one plane degree along row y, relative to a degree of the equator:
  /// 1 along φ on the lon-lat lattice is not a single number, so this is the Mercator scale cos φ
  /// (both directions) or, on the lon-lat lattice, the geometric mean √cos φ of the two sides.
  [[nodiscard]] double size_scale(double y) const;
  [[nodiscard]] const char* kind_name() const { return mercator() ? "mercator" : "lonlat"; }
  /// Pixels per side of a level-l square: 2^(L-l).
  [[nodiscard]] std::int64_t pixels_per_square(int level) const { return std::int64_t{1} << (levels - level); }
  [[nodiscard]] std::int64_t pixel_count() const { return nx * ny; }
};

}  // namespace aq
