// The global pixel lattice (ARCHITECTURE §3): level-0 squares of side Δ0 (Δ0 divides 180°),
// L levels of halving, pixels = level-L squares. Lattice vertex (I, J) sits at
//   λ = lon0 + I·Δ_L,   φ = -90 + J·Δ_L,   0 <= I < nx (periodic: I = nx is I = 0), 0 <= J <= ny.
// Pixel (i, j) has lower-left vertex (i, j). Level-l square (a, b) covers pixels
// [a·2^(L-l), (a+1)·2^(L-l)) × [b·2^(L-l), (b+1)·2^(L-l)).
// With pole rotation the lattice lives in the rotated system; λ, φ above are rotated coordinates.
#pragma once

#include <cstdint>
#include <string>

namespace aq {

struct Lattice {
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
  /// Why `step0_deg` is not a valid Δ0 (one sentence without the key), or "" when it is.
  static std::string step_problem(double step0_deg);

  [[nodiscard]] double pixel_deg() const { return step0_deg / static_cast<double>(std::int64_t{1} << levels); }
  [[nodiscard]] double lon_of(std::int64_t i) const { return lon0_deg + static_cast<double>(i) * pixel_deg(); }
  [[nodiscard]] double lat_of(std::int64_t j) const { return -90.0 + static_cast<double>(j) * pixel_deg(); }
  /// Pixels per side of a level-l square: 2^(L-l).
  [[nodiscard]] std::int64_t pixels_per_square(int level) const { return std::int64_t{1} << (levels - level); }
  [[nodiscard]] std::int64_t pixel_count() const { return nx * ny; }
};

}  // namespace aq
