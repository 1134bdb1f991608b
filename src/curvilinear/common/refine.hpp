// SPDX-License-Identifier: GPL-3.0-or-later
// A refinement grid cut from a parent grid (ROMS refinement nesting; ROMS's coarse2fine.m lays its
// fine grid the same way): the parent's ψ cells I_left..I_right × J_bottom..J_top are split r × r
// (r odd), so every r-th fine ψ point on the perimeter is a parent ψ point and every parent cell
// inside is exactly r × r fine cells.
//
// Index spaces. The parent's (2Lp+1) × (2Mp+1) supergrid (cgrid.hpp: ρ(i) at supergrid 2i, u and
// ψ of ROMS index I at 2I − 1) is given in a conformal plane. ROMS's fractional coordinate ξ puts
// ψ(I) at ξ = I and ρ(i) at ξ = i + ½, i.e. supergrid s = 2ξ − 1. The fine grid has Lm = r·(I_right
// − I_left) interior ρ points, L = Lm + 1, and fine ROMS index i (ρ) or I (u, ψ) sits at parent
//   ξ(ρ i) = I_left + (i − ½)/r,   ξ(ψ I) = I_left + (I − 1)/r,
// so fine supergrid point S (ρ(0) at S = 0) is at parent supergrid s = 2·I_left − 1 + (S − 1)/r,
// and likewise in η. Fine points whose s and t are integers are parent supergrid points, copied
// exactly.
//
// Interpolation. Between parent supergrid points the map is interpolated by tensor-product cubic
// Hermite splines in (s, t), the node derivatives taken by fourth-order finite differences
// (centred five-point, one-sided five-point at the parent's edges): C¹, exact at the parent's
// points, fourth-order accurate for the smooth conformal map, so the fine grid keeps the parent's
// orthogonality to that order. A pass along s for every parent row, then along t for every fine
// column; each output depends only on its inputs, so the result does not depend on the thread count.
#pragma once

#include <array>

#include "curvilinear/common/grid2d.hpp"

namespace aq::curvilinear {

struct RefineBox {
  int i_left = 0, i_right = 0, j_bottom = 0, j_top = 0;  ///< parent ψ indices (ROMS, 1-based)
  int factor = 3;                                        ///< r, odd, ≥ 3

  [[nodiscard]] int L() const { return factor * (i_right - i_left) + 1; }  ///< fine ρ points − 1 along ξ
  [[nodiscard]] int M() const { return factor * (j_top - j_bottom) + 1; }  ///< fine ρ points − 1 along η
};

/// The fine supergrid of `box` in the parent's plane, `pad` fine cells wider on every side than
/// the fine grid itself: (2L + 1 + 4·pad) × (2M + 1 + 4·pad) points, the fine grid's ρ(0, 0) at
/// (2·pad, 2·pad). `parent` is the parent's full (2Lp+1) × (2Mp+1) supergrid. Throws ConfigError
/// when the padded fine grid leaves the parent (naming the box, the factor and the parent's ψ
/// range), InternalError for an even or non-positive factor or pad < 0.
Grid2D refine_supergrid(const Grid2D& parent, const RefineBox& box, int pad);

/// The (2L+1) × (2M+1) fine grid inside a padded supergrid from refine_supergrid.
Grid2D unpad_supergrid(const Grid2D& padded, int pad);

}  // namespace aq::curvilinear
