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
#pragma once

#include <cstdint>
#include <string>

namespace aq {

enum class LatticeKind { kLonLat, kMercator };

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

  /// Builds and validates; throws ConfigError (naming `key_prefix`.step_deg / levels) when Δ0 does
  /// not divide 180° exactly in arc-seconds or L is outside 0..20. A step within rounding of a
  /// whole arc-second value (1e-6") becomes exactly that value: 0.2666666666666667 and
  /// 0.26666666666666666 give the same lattice (step0_deg = 960/3600), whose rows end at ±90°.
  static Lattice make(double step0_deg, int levels, double lon0_deg);
  /// The Mercator lattice of the same Δ0, L, λ0 whose rows reach at least ±`lat_max_deg` (in whole
  /// level-0 squares); throws ConfigError naming quadtree.mercator_lat_max_deg unless
  /// 1 <= lat_max_deg <= 89.5.
  static Lattice make_mercator(double step0_deg, int levels, double lon0_deg, double lat_max_deg);
  /// Why `step0_deg` is not a valid Δ0 (one sentence without the key), or "" when it is.
  static std::string step_problem(double step0_deg);

  [[nodiscard]] double pixel_deg() const { return step0_deg / static_cast<double>(std::int64_t{1} << levels); }
  [[nodiscard]] double lon_of(std::int64_t i) const { return lon0_deg + static_cast<double>(i) * pixel_deg(); }
  [[nodiscard]] bool mercator() const { return kind == LatticeKind::kMercator; }
  /// Plane ordinate (degrees) of the fractional row y: φ on the lon-lat lattice, the Mercator y.
  [[nodiscard]] double plane_y(double y) const { return y0_deg + y * pixel_deg(); }
  /// Latitude (lattice frame, degrees) of the fractional row y.
  [[nodiscard]] double lat_of_row(double y) const {
    return mercator() ? mercator_lat_deg(plane_y(y)) : -90.0 + y * pixel_deg();
  }
  /// Fractional row of the latitude φ (lattice frame, degrees); inverse of lat_of_row.
  [[nodiscard]] double row_of_lat(double lat_deg) const {
    return mercator() ? (mercator_y_deg(lat_deg) - y0_deg) / pixel_deg() : (lat_deg + 90.0) / pixel_deg();
  }
  [[nodiscard]] double lat_of(std::int64_t j) const { return lat_of_row(static_cast<double>(j)); }
  /// Plane ordinate of vertex row J (see plane_y).
  [[nodiscard]] double plane_y_of(std::int64_t j) const { return plane_y(static_cast<double>(j)); }
  /// Plane ordinate of a latitude (lattice frame): φ itself or its Mercator y.
  [[nodiscard]] double plane_y_of_lat(double lat_deg) const { return mercator() ? mercator_y_deg(lat_deg) : lat_deg; }
  /// Highest latitude of the rows (90 on the lon-lat lattice).
  [[nodiscard]] double lat_max_deg() const { return lat_of(ny); }
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
