// SPDX-License-Identifier: GPL-3.0-or-later
// Consistent masks and depths of a refinement grid and its parent (see nested_bathymetry.hpp).
#include "handoff/nested_bathymetry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "handoff/contact_points.hpp"
#include "mask/regional_mask.hpp"

namespace aq::handoff {

namespace {

int floor_divide(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

std::size_t idx(int i, int j, int ni) {
  return static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i);
}

void check_box(const curvilinear::RefineBox& box, int parent_L, int parent_M) {
  if (const std::string bad = refinement_box_problem(box, parent_L, parent_M); !bad.empty()) throw ConfigError(bad);
}

template <typename T>
void check_size(const std::vector<T>& v, std::size_t n, const char* what) {
  if (v.size() != n)
    throw InternalError(fmt::format("nested bathymetry: {} has {} values, expected {}", what, v.size(), n));
}

// The footprint cells, J outer and I inner, with their blocks.
template <typename Visit>
void for_each_block(const curvilinear::RefineBox& b, Visit visit) {
  std::size_t n = 0;
  for (int J = b.j_bottom; J < b.j_top; ++J)
    for (int I = b.i_left; I < b.i_right; ++I)
      visit(n++, I, J, (I - b.i_left) * b.factor + 1, (J - b.j_bottom) * b.factor + 1);
}

}  // namespace

NestedMaskStats nest_masks(const curvilinear::RefineBox& box, int pL, int pM, std::vector<std::uint8_t>& parent_rho,
                           std::vector<std::uint8_t>& parent_u, std::vector<std::uint8_t>& parent_v,
                           std::vector<std::uint8_t>& parent_psi, std::vector<std::uint8_t>& child_rho,
                           std::vector<std::uint8_t>& child_u, std::vector<std::uint8_t>& child_v,
                           std::vector<std::uint8_t>& child_psi) {
  check_box(box, pL, pM);
  const int pni = pL + 1, pnj = pM + 1, ni = box.L() + 1, nj = box.M() + 1, r = box.factor;
  check_size(parent_rho, idx(0, pnj, pni), "the parent's mask_rho");
  check_size(parent_u, idx(0, pnj, pL), "the parent's mask_u");
  check_size(parent_v, idx(0, pM, pni), "the parent's mask_v");
  if (!parent_psi.empty()) check_size(parent_psi, idx(0, pM, pL), "the parent's mask_psi");
  check_size(child_rho, idx(0, nj, ni), "the child's mask_rho");
  NestedMaskStats st;

  // Parent footprint cells take their block centre's mask.
  const int centre = (r + 1) / 2;
  const auto prho = [&](int i, int j) { return parent_rho[idx(i, j, pni)] != 0; };
  const auto both = [](bool a, bool b) { return static_cast<std::uint8_t>(a && b ? 1 : 0); };
  for_each_block(box, [&](std::size_t, int I, int J, int i0, int j0) {
    const std::uint8_t want = child_rho[idx(i0 + centre - 1, j0 + centre - 1, ni)];
    if (parent_rho[idx(I, J, pni)] == want) return;
    parent_rho[idx(I, J, pni)] = want;
    ++st.parent_rho_changed;
    // The faces and corners around it (all inside the parent: the footprint keeps off its edge).
    for (int k = I - 1; k <= I; ++k) parent_u[idx(k, J, pL)] = both(prho(k, J), prho(k + 1, J));
    for (int l = J - 1; l <= J; ++l) parent_v[idx(I, l, pni)] = both(prho(I, l), prho(I, l + 1));
    if (!parent_psi.empty())
      for (int l = J - 1; l <= J; ++l)
        for (int k = I - 1; k <= I; ++k)
          parent_psi[idx(k, l, pL)] = both(prho(k, l) && prho(k + 1, l), prho(k, l + 1) && prho(k + 1, l + 1));
  });

  // Child ring points take the mask of the parent cell holding them (ρ(i) at ξ = Io + (i − ½)/r).
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      if (i != 0 && i != ni - 1 && j != 0 && j != nj - 1) continue;
      const int I = box.i_left + floor_divide(2 * i - 1, 2 * r), J = box.j_bottom + floor_divide(2 * j - 1, 2 * r);
      const std::uint8_t want = parent_rho[idx(I, J, pni)];
      if (child_rho[idx(i, j, ni)] == want) continue;
      child_rho[idx(i, j, ni)] = want;
      ++st.child_ring_changed;
    }
  mask::derive_staggered_masks(child_rho, ni, nj, child_u, child_v, child_psi);
  return st;
}

std::vector<double> child_block_averages(const std::vector<double>& child, const std::vector<std::uint8_t>& mask,
                                         const std::vector<double>& area, const curvilinear::RefineBox& box) {
  const int ni = box.L() + 1, nj = box.M() + 1, r = box.factor;
  check_size(child, idx(0, nj, ni), "the child field");
  check_size(mask, idx(0, nj, ni), "the child's mask_rho");
  check_size(area, idx(0, nj, ni), "the child's cell areas");
  std::vector<double> out(static_cast<std::size_t>(box.i_right - box.i_left) *
                          static_cast<std::size_t>(box.j_top - box.j_bottom));
  for_each_block(box, [&](std::size_t n, int, int, int i0, int j0) {
    double sw = 0.0, swh = 0.0, sa = 0.0, sah = 0.0;
    for (int j = j0; j < j0 + r; ++j)
      for (int i = i0; i < i0 + r; ++i) {
        const std::size_t k = idx(i, j, ni);
        sa += area[k];
        sah += area[k] * child[k];
        if (mask[k] == 0) continue;
        sw += area[k];
        swh += area[k] * child[k];
      }
    out[n] = sw > 0.0 ? swh / sw : sah / sa;
  });
  return out;
}

NestedDepthResult nested_depth(const NestedDepthInput& in) {
  const curvilinear::RefineBox& box = in.box;
  check_box(box, in.parent_L, in.parent_M);
  const int pni = in.parent_L + 1, pnj = in.parent_M + 1, ni = box.L() + 1, nj = box.M() + 1, r = box.factor;
  check_size(in.parent_h, idx(0, pnj, pni), "the parent's h");
  check_size(in.parent_mask, idx(0, pnj, pni), "the parent's mask_rho");
  check_size(in.child_hraw, idx(0, nj, ni), "the child's hraw");
  check_size(in.child_mask, idx(0, nj, ni), "the child's mask_rho");
  check_size(in.child_area, idx(0, nj, ni), "the child's cell areas");
  if (in.blend_cells < 0) throw InternalError(fmt::format("nested_depth: blend_cells = {}", in.blend_cells));
  const double hmin = in.child_options.hmin_m;
  if (!(hmin > 0.0) || !std::isfinite(hmin))  // roms.hmin_m, validated at load
    throw InternalError(fmt::format("nested_depth: hmin = {} m", hmin));

  // Blend weights: 1 − d/B at d rows from the outer ring, d < B.
  std::vector<double> w(idx(0, nj, ni), 0.0);
  if (in.blend_cells > 0)
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) {
        const int d = std::min({i, ni - 1 - i, j, nj - 1 - j});
        if (d < in.blend_cells) w[idx(i, j, ni)] = 1.0 - static_cast<double>(d) / in.blend_cells;
      }

  NestedDepthResult res;
  std::vector<double> P = in.parent_h;
  const std::size_t nblocks =
      static_cast<std::size_t>(box.i_right - box.i_left) * static_cast<std::size_t>(box.j_top - box.j_bottom);
  std::vector<double> raise(nblocks, 0.0), A;
  curvilinear::DepthResult child;
  for (res.rounds = 1; res.rounds <= in.max_rounds; ++res.rounds) {
    // 1. The child from the parent (and the blocks' accumulated deepening).
    const std::vector<double> hp = parent_rho_on_fine(P, in.parent_L, in.parent_M, box);
    std::vector<double> T = in.child_hraw;
    res.blend_max_change_m = 0.0;
    for (std::size_t k = 0; k < T.size(); ++k) {
      if (w[k] > 0.0) {
        T[k] = w[k] * hp[k] + (1.0 - w[k]) * in.child_hraw[k];
        res.blend_max_change_m = std::max(res.blend_max_change_m, std::abs(T[k] - in.child_hraw[k]));
      }
      T[k] = std::max(T[k], hmin);
    }
    for_each_block(box, [&](std::size_t n, int, int, int i0, int j0) {
      if (raise[n] == 0.0) return;
      for (int j = j0; j < j0 + r; ++j)
        for (int i = i0; i < i0 + r; ++i) T[idx(i, j, ni)] += raise[n];
    });
    child = curvilinear::roms_depth(T, in.child_mask, ni, nj, in.child_options);
    // 2. The parent from the child.
    A = child_block_averages(child.h, in.child_mask, in.child_area, box);
    std::vector<double> Pn = P;
    for_each_block(box, [&](std::size_t n, int I, int J, int, int) { Pn[idx(I, J, pni)] = A[n]; });
    // 3. Parent smoothing.
    curvilinear::smooth_r_factor(Pn, in.parent_mask, pni, pnj, in.parent_rmax);
    double short_by = 0.0, change = 0.0;
    for_each_block(
        box, [&](std::size_t n, int I, int J, int, int) { short_by = std::max(short_by, Pn[idx(I, J, pni)] - A[n]); });
    for (std::size_t k = 0; k < P.size(); ++k) change = std::max(change, std::abs(Pn[k] - P[k]));
    P = std::move(Pn);
    res.last_round_change_m = change;
    if (short_by == 0.0 && change <= in.tolerance_m) {
      res.settled = true;
      break;
    }
    // 4. Deepen the blocks by what the smoothing added.
    for_each_block(box, [&](std::size_t n, int I, int J, int, int) { raise[n] += P[idx(I, J, pni)] - A[n]; });
  }
  res.rounds = std::min(res.rounds, in.max_rounds);
  res.child_h = std::move(child.h);
  child.h.clear();
  if (!res.settled) {
    // Add the remaining differences and take the averages again: the equality holds exactly.
    for_each_block(box, [&](std::size_t n, int I, int J, int i0, int j0) {
      const double d = P[idx(I, J, pni)] - A[n];
      raise[n] += d;
      for (int j = j0; j < j0 + r; ++j)
        for (int i = i0; i < i0 + r; ++i) res.child_h[idx(i, j, ni)] += d;
    });
    A = child_block_averages(res.child_h, in.child_mask, in.child_area, box);
    for_each_block(box, [&](std::size_t n, int I, int J, int, int) { P[idx(I, J, pni)] = A[n]; });
  }
  res.child_depth = std::move(child);
  res.parent_h = std::move(P);

  // What changed, and the invariant.
  for (const double d : raise) {
    res.block_raise_max_m = std::max(res.block_raise_max_m, d);
    if (d > 0.0) ++res.blocks_raised;
  }
  std::vector<std::uint8_t> in_footprint(res.parent_h.size(), 0);
  double sum_wet = 0.0;
  std::int64_t n_wet = 0;
  const std::vector<double> check = child_block_averages(res.child_h, in.child_mask, in.child_area, box);
  for_each_block(box, [&](std::size_t n, int I, int J, int, int) {
    const std::size_t k = idx(I, J, pni);
    in_footprint[k] = 1;
    res.invariant_residual_m = std::max(res.invariant_residual_m, std::abs(res.parent_h[k] - check[n]));
    if (in.parent_mask[k] != 0) {
      sum_wet += res.parent_h[k] - in.parent_h[k];
      ++n_wet;
    }
  });
  for (std::size_t k = 0; k < res.parent_h.size(); ++k) {
    const double d = std::abs(res.parent_h[k] - in.parent_h[k]);
    if (d == 0.0) continue;
    ++res.parent_points_changed;
    if (in_footprint[k] == 0) ++res.parent_outside_changed;
    res.parent_max_change_m = std::max(res.parent_max_change_m, d);
  }
  res.parent_mean_change_wet_m = n_wet > 0 ? sum_wet / static_cast<double>(n_wet) : 0.0;
  res.child_rx0 = curvilinear::max_r_factor(res.child_h, in.child_mask, ni, nj);
  res.parent_rx0 = curvilinear::max_r_factor(res.parent_h, in.parent_mask, pni, pnj);
  return res;
}

}  // namespace aq::handoff
