// SPDX-License-Identifier: GPL-3.0-or-later
// Model depth h of a ROMS grid from the raw depth hraw at ρ points (WikiROMS "Grid generation";
// the smoothing is Sikirić, Janeković & Kuzmić 2009, Ocean Modelling 29, "A new approach to
// bathymetry smoothing in sigma-coordinate ocean models", their positive rx0 method):
//
//   1. clip:   h = max(hraw, hmin) at every ρ point (land too: ROMS needs h > 0 everywhere);
//   2. smooth (rmax > 0): raise depths, never lower them, until every wet pair of ρ neighbours
//      (a u or v face with both ρ points wet) has the r-factor (Beckmann & Haidvogel 1993)
//          r = |h_a − h_b| / (h_a + h_b) ≤ rmax,   i.e.   h_shallow ≥ c·h_deep,  c = (1−rmax)/(1+rmax).
//      The update h_a ← max(h_a, c·h_b) over wet faces is repeated (forward then backward row-major
//      Gauss–Seidel sweeps) until nothing changes. Values only rise and the constraint set is
//      closed under pointwise minimum, so this converges to the unique smallest field ≥ the clipped
//      h that satisfies the bound: the result does not depend on sweep order (deterministic) and
//      every change is the least possible. Land points keep the clipped depth.
// Depths are metres, positive down. Arrays are ρ arrays of ni × nj (value (i, j) at j·ni + i).
#pragma once

#include <cstdint>
#include <vector>

namespace aq::curvilinear {

/// The vertical grid rx1 is measured on: ROMS's Vtransform = 2, Vstretching = 4 s-coordinate
/// (Shchepetkin & McWilliams 2009; WikiROMS "Vertical S-coordinate") with N levels. A grid file has
/// no vertical grid, so rx1 is reported for this reference one (a common ROMS set-up).
struct VerticalGrid {
  int n = 30;
  double theta_s = 7.0, theta_b = 2.0;
  double hc_m = 50.0;
};

/// Haney's hydrostatic inconsistency number rx1 = max over wet faces and levels k of
/// |z_a(k) − z_b(k) + z_a(k−1) − z_b(k−1)| / |z_a(k) + z_b(k) − z_a(k−1) − z_b(k−1)| on the w levels
/// z(k) of `v` (ζ = 0); 0 without a wet face.
double max_rx1(const std::vector<double>& h, const std::vector<std::uint8_t>& mask_rho, int ni, int nj,
               const VerticalGrid& v = {});

struct DepthOptions {
  /// Minimum depth, metres, > 0 (ROMS's hmin clip).
  double hmin_m = 10.0;
  /// r-factor bound in [0, 1); 0 = no smoothing.
  double rmax = 0.0;
};

struct DepthResult {
  std::vector<double> h;          ///< model depth, metres, ≥ hmin
  std::int64_t clipped = 0;       ///< points raised to hmin (land and water)
  std::int64_t clipped_wet = 0;   ///< wet points raised to hmin
  double rx0_before = 0.0;        ///< max r over wet faces after clipping, before smoothing
  double rx0_after = 0.0;         ///< the same after smoothing
  std::int64_t smoothed = 0;      ///< wet points the smoothing deepened
  double max_deepening_m = 0.0;   ///< largest change by the smoothing
  double volume_added_rel = 0.0;  ///< Σ(h_after − h_before)/Σh_before over wet points
  int sweeps = 0;                 ///< Gauss–Seidel sweeps until no change (0 when rmax = 0)
  double rx1_before = 0.0;        ///< max_rx1 (reference VerticalGrid) after clipping, before smoothing
  double rx1_after = 0.0;         ///< the same after smoothing
};

/// Clips and optionally smooths `hraw` (finite values; ni, nj ≥ 1; mask values 0/1).
/// Throws InternalError for roms.hmin_m / roms.rmax out of range (validated at load), inconsistent
/// sizes or a non-finite hraw.
DepthResult roms_depth(const std::vector<double>& hraw, const std::vector<std::uint8_t>& mask_rho, int ni, int nj,
                       const DepthOptions& options);

/// Step 2 alone on `h` in place: raises depths (never lowers them) to the least field ≥ h with
/// r ≤ rmax on every wet face; returns the number of Gauss–Seidel sweeps (0 when rmax = 0 or the
/// bound already holds). No clipping: a parent grid whose own hmin is unknown keeps its depths.
/// Throws InternalError for rmax outside [0, 1) (roms.rmax is validated at load) or inconsistent
/// sizes, NumericalError if it does not settle.
int smooth_r_factor(std::vector<double>& h, const std::vector<std::uint8_t>& mask_rho, int ni, int nj, double rmax);

/// Largest r-factor |h_a − h_b|/(h_a + h_b) over u and v faces whose two ρ points are wet.
double max_r_factor(const std::vector<double>& h, const std::vector<std::uint8_t>& mask_rho, int ni, int nj);

}  // namespace aq::curvilinear
