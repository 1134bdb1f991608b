// SPDX-License-Identifier: GPL-3.0-or-later
// Consistent land masks and depths of a refinement grid ("child") and its parent for ROMS two-way
// nesting. ROMS's fine-to-coarse feedback (nesting.F, fine2coarse) replaces the parent's zeta, T,
// S, u and v inside the child's footprint by averages of the child's values, level by level with
// no vertical interpolation, and copies the parent's values (interpolated) onto the child's outer
// ring and beyond. So the parent's h in the footprint must be the child's h averaged per parent
// cell, or every parent level receives water from another depth (a two-way run then blows up).
//
// Index spaces as in contact_points.hpp: the parent's ψ box Io..Ie × Jo..Je split r × r; parent ρ
// cell (I, J), I = Io..Ie−1, J = Jo..Je−1 (the "footprint", ROMS's region-2 ρ points), holds the
// r × r child ρ points i = (I−Io)·r + 1 .. (I−Io+1)·r, j likewise (its "block"), and the block's
// centre point i = (I−Io)·r + (r+1)/2 lies exactly on the parent ρ point. The child's outer ρ
// ring (i = 0, L or j = 0, M) lies outside the footprint, in the parent cells around it. Arrays
// are ρ arrays, row-major with ξ fastest.
//
// Masks (nest_masks):
//   * a parent cell of the footprint is water iff the child ρ point at its block centre is water
//     (both masks come from the same global ocean at the same point, so this normally changes
//     nothing; it guarantees that every wet parent cell has wet child points to average, which
//     ROMS's feedback needs: with none it would write 0 into the parent's T and S);
//   * a child ρ point on the outer ring is water iff the parent cell holding it is (what ROMS
//     copies there from the contact file, and what guarantees a wet parent donor for every wet
//     ring point);
//   * u, v and ψ masks are the products of their ρ neighbours (the child's all, the parent's
//     where a ρ value changed).
//
// Depths (nested_depth), given both masks:
//   1. child from the parent: within blend_cells rows of the outer ring the child's raw depth
//      blends linearly into the parent's h interpolated bilinearly (weight 1 on the ring), then
//      the child is clipped to hmin and r-factor smoothed (curvilinear/roms_depth.hpp);
//   2. parent from the child: each footprint cell's h becomes the area-weighted mean of its
//      block, weights 1/(pm·pn) of the child's wet points (all points when the block is dry);
//   3. parent smoothing: the parent is r-factor smoothed (only deepening) with parent_rmax. A
//      block average can be steeper than the parent allows (the child resolves a slope in r
//      cells that the parent crosses in one), so this can deepen footprint cells, breaking 2;
//   4. each block is then deepened by its cell's difference (added to all its child points, which
//      keeps the child's r-factor inside the block) and 1–3 repeat, the additions accumulated,
//      until step 3 changes nothing and the parent's footprint moves by less than the tolerance
//      between two rounds (step 1 depends on the parent's new values near the ring: a
//      contraction, the change halving per round). Then the parent's footprint is exactly the
//      child's block averages (step 2 of the last round) and both bounds hold exactly.
// If the rounds do not settle in max_rounds, the remaining differences are added to the blocks
// and the averages recomputed: the equality holds, the bounds within the reported residual.
#pragma once

#include <cstdint>
#include <vector>

#include "curvilinear/common/refine.hpp"
#include "curvilinear/common/roms_depth.hpp"

namespace aq::handoff {

struct NestedMaskStats {
  std::int64_t parent_rho_changed = 0;  ///< footprint cells whose mask took the block centre's
  std::int64_t child_ring_changed = 0;  ///< ring points whose mask took the parent cell's
};

/// Applies the mask rules above in place. `parent_rho` is (parent_L+1) × (parent_M+1), the
/// parent's u, v, ψ masks (parent_L × (parent_M+1), (parent_L+1) × parent_M, parent_L × parent_M;
/// ψ may be empty: not kept) are updated around changed ρ points; `child_rho` is
/// (box.L()+1) × (box.M()+1) and the child's u, v, ψ are recomputed from it. Throws ConfigError
/// for a box outside the parent, InternalError for sizes that do not fit.
NestedMaskStats nest_masks(const curvilinear::RefineBox& box, int parent_L, int parent_M,
                           std::vector<std::uint8_t>& parent_rho, std::vector<std::uint8_t>& parent_u,
                           std::vector<std::uint8_t>& parent_v, std::vector<std::uint8_t>& parent_psi,
                           std::vector<std::uint8_t>& child_rho, std::vector<std::uint8_t>& child_u,
                           std::vector<std::uint8_t>& child_v, std::vector<std::uint8_t>& child_psi);

/// Area-weighted block averages of a child ρ field: one value per footprint cell, J outer, I
/// inner ((Ie−Io)·(Je−Jo) values); weights `area` (1/(pm·pn)) of the block's wet points, or of all
/// its points when none is wet.
std::vector<double> child_block_averages(const std::vector<double>& child, const std::vector<std::uint8_t>& child_mask,
                                         const std::vector<double>& area, const curvilinear::RefineBox& box);

struct NestedDepthInput {
  curvilinear::RefineBox box;
  int parent_L = 0, parent_M = 0;           ///< parent ρ points (parent_L+1) × (parent_M+1)
  std::vector<double> parent_h;             ///< the parent file's h
  std::vector<std::uint8_t> parent_mask;    ///< after nest_masks
  double parent_rmax = 0.0;                 ///< the parent's r-factor bound (0 = no smoothing)
  std::vector<double> child_hraw;           ///< the child's raw depth (m, positive down)
  std::vector<std::uint8_t> child_mask;     ///< after nest_masks
  std::vector<double> child_area;           ///< 1/(pm·pn) at the child's ρ points
  curvilinear::DepthOptions child_options;  ///< hmin and the child's rmax
  int blend_cells = 6;                      ///< rows of the blend (0 = none)
  double tolerance_m = 1e-6;                ///< footprint change between rounds that ends them
  int max_rounds = 500;
};

struct NestedDepthResult {
  std::vector<double> child_h, parent_h;
  curvilinear::DepthResult child_depth;  ///< clip/smoothing counts of the child's last round (h: empty)
  int rounds = 0;
  bool settled = false;                      ///< the rounds ended by the rule above, not by max_rounds
  double last_round_change_m = 0.0;          ///< largest footprint change of the last round
  double blend_max_change_m = 0.0;           ///< largest |blended − raw| of the child (last round)
  double block_raise_max_m = 0.0;            ///< largest accumulated deepening of a block (step 4)
  std::int64_t blocks_raised = 0;            ///< blocks deepened by step 4
  double child_rx0 = 0.0, parent_rx0 = 0.0;  ///< final r-factors over wet faces
  std::int64_t parent_points_changed = 0;    ///< parent ρ points whose h changed (any mask)
  std::int64_t parent_outside_changed = 0;   ///< of these, outside the footprint (smoothing)
  double parent_max_change_m = 0.0;          ///< largest |new − old| of the parent's h
  double parent_mean_change_wet_m = 0.0;     ///< mean new − old over the wet footprint cells
  double invariant_residual_m = 0.0;         ///< max |parent h − block average| over the footprint
};

/// Steps 1–4 above. Throws ConfigError (roms.hmin_m, roms.rmax, a box outside the parent),
/// InternalError for sizes that do not fit.
NestedDepthResult nested_depth(const NestedDepthInput& in);

}  // namespace aq::handoff
