// SPDX-License-Identifier: GPL-3.0-or-later
// A block's regional projection and contour (ARCHITECTURE §6; the contour format of seed 000,
// digest izogrid.md §2–4): the conformal projection centred on the block and the control points
// of its outline in the projection's plane units, counter-clockwise from the SW corner with the
// 4 corners marked.
//
// Box coordinates. A block is a box [λ0, λ1] × [φ0, φ1] in its own spherical system (lattice or
// geographic, coastal_blocks.hpp). (s, t) ∈ [0, 1]² are the fractions along λ and φ:
//
//      t = 1  NW +--------- N --------+ NE       λ = λ0 + s (λ1 − λ0)
//                |                    |          φ = φ0 + t (φ1 − φ0)
//                W                    E          meridians and parallels of the box's system
//                |                    |          cross at right angles on the sphere, and the
//      t = 0  SW +--------- S --------+ SE       projection is conformal, so the box's corners
//             s = 0                 s = 1        are right angles in the plane too.
//
// A box with `mercator_rows` (a level-0 square of the Mercator lattice) runs t linearly in the
// Mercator ordinate instead: y(φ) = y(φ0) + t (y(φ1) − y(φ0)), y = ln tan(π/4 + φ/2), as its
// lattice rows do, so t = m/2^L is row m of the square and the (s, t) grid of shrink-to-wet has
// the same number of cells per pixel along both sides. Its outline is the same box.
//
// Projection choice: rotated Mercator (ME) centred on the box centre, with `rota` = the azimuth
// of the box's own meridian there (0 for geographic boxes and an unrotated lattice), so the box
// stands upright in the plane; stereographic (ST), same centre and rota, when the box reaches
// beyond 75° of geographic latitude (near the poles, where a box of meridians converges and the
// stereographic scale is the better behaved). `uscale` is 1, 2 or 5 × 10^k, the smallest making
// every contour coordinate |x|, |y| <= 100 (the seed's "graph paper" range). A box side on a
// pole of its system (φ = ±90°, a degenerate side) is moved to ±(90° − min(1°, height/4)).
//
// Shrink to wet (`shrink_to_wet`). Each side moves inward over land toward the wet area while
// staying smooth; corners stay right angles:
//   1. Sample Ω_L on an n × n grid of cell centres in (s, t) (n ≈ 2 cells per lattice pixel of
//      the box's longer side, box_extent_px, 32..1024). For side S, station k (s_k = (k + ½)/n) gets the raw inset
//      d_k = (number of consecutive non-filled cells from t = 0 upward) / n, capped at
//      `max_inset` (so opposite sides never meet); likewise E (from s = 1 leftward), N (from
//      t = 1 downward), W (from s = 0 rightward). At every station the strip between the old and
//      the raw side holds no wet cell (the guarantee is at the stations' resolution, half a
//      lattice pixel; step 4 carries it to the lines between control points, and the spline
//      through them may still bulge across less than a station).
//   2. Smooth by lowering only: e = min(d, ·) through the lower Lipschitz envelope
//      e_k = min_j (d_j + ½·|s_k − s_j|) (two sweeps), so a side turns at most atan ½ ≈ 26.6°
//      against the box edge and e <= d keeps the strip dry;
//   3. corner zones: the stations within `max_inset` (+ one cell) of either end of a side get
//      the zone's minimum, and 2–3 repeat until nothing changes (values only decrease). A side
//      is then straight (a coordinate line) near both its corners, and the corner where S
//      (inset b) meets W (inset a) is the point (a, b), where the straight pieces cross at a
//      right angle.
//   4. Control points: `points_per_side` (P) per side, evenly spaced in s (or t) between the new
//      corners. The contour interpolates between control points, not along the profile, so a
//      control point takes the profile's minimum over its two neighbouring intervals: the line
//      between two control points then lies on or outside the profile, and the strip a side
//      leaves behind stays dry between control points too (a control point on the profile itself
//      would let the side cut straight across a bay or estuary narrower than the spacing). The
//      corners take the minimum over the first and last `max_inset` + 1/P of the side (the
//      corner zone when P is large enough, so usually the zone's value).
// Without shrink the insets are 0 and the contour is the block's outline.
#pragma once

#include <array>
#include <vector>

#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/rotation.hpp"
#include "curvilinear/common/projection.hpp"
#include "handoff/coastal_blocks.hpp"

namespace aq::handoff {

/// Box coordinates (s, t) -> the box's system and geographic degrees (see the file comment).
class BoxFrame {
 public:
  /// `rotation` maps the lattice system to geographic (used when box.lattice_system).
  BoxFrame(const BlockBox& box, const PoleRotation& rotation);
  [[nodiscard]] const BlockBox& box() const { return box_; }
  /// Whether a side on a pole was moved off it.
  [[nodiscard]] bool trimmed() const { return trimmed_; }
  /// Whether the box's system differs from the geographic one (a box of a rotated lattice).
  [[nodiscard]] bool rotated() const { return rotate_; }
  /// λ, φ in the box's own system.
  [[nodiscard]] curvilinear::GeoPoint system(double s, double t) const;
  /// Geographic λ, φ (λ in (-180, 180] with rotation; as in the box's system without).
  [[nodiscard]] curvilinear::GeoPoint geographic(double s, double t) const;

 private:
  BlockBox box_;
  PoleRotation rotation_;
  bool rotate_ = false;
  bool trimmed_ = false;
  double y_min_deg_ = 0.0, y_max_deg_ = 0.0;  ///< Mercator ordinates of the box's φ range (mercator_rows)
};

/// Inset profiles of the sides S, E, N, W: `n` stations at (k + ½)/n along each side (S and N
/// west to east, E and W south to north), fractions of the block's width (E, W) or height (S, N).
struct SideInsets {
  int n = 0;
  double max_inset = 0.0;  ///< the cap the insets were made with (width of the corner zones)
  std::array<std::vector<double>, 4> e;
  /// Inset of `side` (0 S, 1 E, 2 N, 3 W) at fraction x ∈ [0, 1] along it (linear between
  /// stations, constant beyond the first and last); 0 when n = 0.
  [[nodiscard]] double at(int side, double x) const;
  /// Smallest inset of `side` over the fractions [a, b] along it (the profile of `at`).
  [[nodiscard]] double min_over(int side, double a, double b) const;
  /// Largest inset of a side.
  [[nodiscard]] double max(int side) const;
};

/// The insets of shrink-to-wet (steps 1–3 of the file comment). `filled` is Ω_L on `lat`;
/// `max_inset` in [0, 0.45]. Deterministic and serial.
SideInsets shrink_to_wet(const BoxFrame& frame, const Bitmap& filled, const Lattice& lat, const PoleRotation& rotation,
                         double max_inset);

/// The projection of the file comment, with uscale fitted to `frame`'s outline.
curvilinear::ProjectionParams choose_projection(const BoxFrame& frame);

struct BlockContour {
  curvilinear::ProjectionParams projection;
  std::vector<double> x, y;      ///< control points, plane units, counter-clockwise from SW
  std::array<int, 4> corners{};  ///< 0-based indices of SW, SE, NE, NW (0, P, 2P, 3P)
  SideInsets insets;             ///< n = 0 without shrink
  bool trimmed = false;          ///< a side on a pole was moved off it
};

/// The block's contour: `points_per_side` (>= 2) control points per side, on the outline or, with
/// `insets` of n > 0, on the shrunk sides. Throws InputError when a point falls on a singularity
/// of the projection (cannot happen for boxes under 180°; checked).
BlockContour block_contour(const BoxFrame& frame, const SideInsets& insets, int points_per_side);

}  // namespace aq::handoff
