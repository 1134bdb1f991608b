// SPDX-License-Identifier: GPL-3.0-or-later
// The level pyramid on the forest (see pyramid.hpp).
#include "forest/pyramid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/types.hpp"
#include "quadtree/bits.hpp"

namespace aq::forest {

namespace {

namespace qb = quadtree::bits;

void and_into(Bitmap& a, const Bitmap& b) {
  for (std::size_t k = 0; k < a.words().size(); ++k) a.words()[k] &= b.words()[k];
}

Bitmap ones(std::int64_t n) {
  Bitmap b(n, n);
  for (std::int64_t j = 0; j < n; ++j) qb::set_range(b.row(j), 0, n);
  return b;
}

bool any_bit(const Bitmap& b) {
  for (const std::uint64_t w : b.words())
    if (w != 0) return true;
  return false;
}

}  // namespace

ForestPyramid::ForestPyramid(const PatchForest& pf, const std::vector<PatchBits>& filled, int coast_band,
                             const std::vector<PatchBits>* open, const std::vector<PatchBits>* sea)
    : pf_(pf), filled_(filled), open_(open), sea_(sea) {
  const PatchGrid& g = pf.grid();
  L_ = g.lat.levels;
  lp_ = g.level;
  plog_ = g.plog;
  p_ = g.size;
  if (plog_ < 1)
    throw ConfigError("quadtree.levels = 0: the forest engine needs at least one level (quadtree.engine = \"dense\")");
  if (coast_band < 0) throw ConfigError(fmt::format("quadtree.coast_band = {}: must be >= 0 (pixels)", coast_band));
  if (coast_band > p_)
    throw ConfigError(
        fmt::format("quadtree.coast_band = {}: the forest engine needs at most {} pixels (its patches); "
                    "quadtree.engine = \"dense\"",
                    coast_band, p_));
  ghosts_ = pf.exchange(filled);
  if (open_ != nullptr) open_ghosts_ = pf.exchange(*open_);
  if (sea_ != nullptr) sea_ghosts_ = pf.exchange(*sea_);
  const std::size_t n = pf.local_count();
  fine_.resize(n);
  all_.assign(n, 0);
  for (std::size_t l = 0; l < n; ++l) {
    const PatchBits& f = filled[l];
    if (f.state == Fill::kNone) continue;
    Bitmap band;
    if (coast_band > 0) {
      band = band_bits(l, coast_band);
      if (!any_bit(band)) band = Bitmap();
    }
    if (f.state == Fill::kAll && band.words().empty()) {
      all_[l] = 1;
      continue;
    }
    auto fine = std::make_unique<Fine>();
    fine->omega.resize(static_cast<std::size_t>(plog_) + 1);
    fine->any.resize(static_cast<std::size_t>(plog_) + 1);
    const Bitmap px = f.dense(p_);
    fine->omega.back() = px;
    fine->any.back() = px;
    if (!band.words().empty()) {
      Bitmap interior = px;
      for (std::size_t k = 0; k < interior.words().size(); ++k) interior.words()[k] &= ~band.words()[k];
      fine->omega[static_cast<std::size_t>(plog_) - 1] = qb::reduce(interior, false);
    } else {
      fine->omega[static_cast<std::size_t>(plog_) - 1] = qb::reduce(px, false);
    }
    for (int d = plog_ - 2; d >= 0; --d)
      fine->omega[static_cast<std::size_t>(d)] = qb::reduce(fine->omega[static_cast<std::size_t>(d) + 1], false);
    for (int d = plog_ - 1; d >= 0; --d)
      fine->any[static_cast<std::size_t>(d)] = qb::reduce(fine->any[static_cast<std::size_t>(d) + 1], true);
    fine_[l] = std::move(fine);
  }
  // The coarse levels from the patches' own bits.
  omega_c_.resize(static_cast<std::size_t>(lp_) + 1);
  any_c_.resize(static_cast<std::size_t>(lp_) + 1);
  any_c_.back() = Bitmap(g.npx, g.npy);
  for (std::size_t l = 0; l < n; ++l) {
    const std::int64_t key = pf.key(l);
    const bool a = fine_[l] ? fine_[l]->any[0].get(0, 0) : all_[l] != 0;
    if (a) any_c_.back().set(g.gx(key), g.gy(key));
  }
  pf.comm().or_in_place(any_c_.back().words());
  for (int l = lp_ - 1; l >= 0; --l)
    any_c_[static_cast<std::size_t>(l)] = qb::reduce(any_c_[static_cast<std::size_t>(l) + 1], true);
  sync_coarse();
}

Bitmap ForestPyramid::band_bits(std::size_t l, int radius) const {
  // Unfilled pixels within Chebyshev `radius` of a filled one (rows beyond the poles are no coast,
  // columns beyond a window lattice are its unfilled padding, as in the dense engine's bitmaps),
  // and with a sea the sea pixels within `radius` of a pixel that is neither sea nor open water.
  const PatchGrid& g = pf_.grid();
  const std::int64_t key = pf_.key(l);
  // Whether `set` is all ones on the patch and its 8 neighbours (rows beyond the poles count).
  const auto all_around = [&](const std::vector<PatchBits>& set, const std::vector<PatchBits>& ghosts) {
    if (set[l].state != Fill::kAll) return false;
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        const std::int64_t nk = g.neighbour(g.gx(key), g.gy(key), dx, dy);
        if (nk < 0) {
          if (g.gy(key) + dy < 0 || g.gy(key) + dy >= g.npy) continue;
          return false;
        }
        const PatchBits* b = pf_.find(nk, set, ghosts);
        if (b == nullptr || b->state != Fill::kAll) return false;
      }
    return true;
  };
  const bool no_sea_band = sea_ == nullptr || (*sea_)[l].state == Fill::kNone || all_around(*sea_, sea_ghosts_);
  if (no_sea_band && all_around(filled_, ghosts_)) return Bitmap(p_, p_);
  const Bitmap window = pf_.assemble(l, filled_, ghosts_, OutsideRule{true, false});
  if (open_ == nullptr && sea_ == nullptr) return centre_of(quadtree::coastal_band(window, radius), p_);
  // A regional run: the water beyond the domain's edge is no coast (its copy beyond the lattice
  // never matters: the domain lies a level-0 square inside the window lattice). A floodplain: the
  // sea's rows beyond the poles are no coast either, its columns beyond a window are.
  Bitmap open, sea;
  if (open_ != nullptr) open = pf_.assemble(l, *open_, open_ghosts_, OutsideRule{false, false});
  if (sea_ != nullptr) sea = pf_.assemble(l, *sea_, sea_ghosts_, OutsideRule{true, false});
  return centre_of(
      quadtree::coastal_band(window, radius,
                             mask::CoastSources{open_ != nullptr ? &open : nullptr, sea_ != nullptr ? &sea : nullptr}),
      p_);
}

ForestPyramid::Fine& ForestPyramid::activate(std::size_t l) {
  if (!fine_[l]) {
    auto fine = std::make_unique<Fine>();
    fine->omega.resize(static_cast<std::size_t>(plog_) + 1);
    fine->any.resize(static_cast<std::size_t>(plog_) + 1);
    for (int d = 0; d <= plog_; ++d) {
      const std::int64_t side = std::int64_t{1} << d;
      fine->omega[static_cast<std::size_t>(d)] = all_[l] != 0 ? ones(side) : Bitmap(side, side);
      fine->any[static_cast<std::size_t>(d)] = fine->omega[static_cast<std::size_t>(d)];
    }
    fine_[l] = std::move(fine);
  }
  return *fine_[l];
}

void ForestPyramid::sync_coarse() {
  const PatchGrid& g = pf_.grid();
  Bitmap top(g.npx, g.npy);
  for (std::size_t l = 0; l < fine_.size(); ++l) {
    const std::int64_t key = pf_.key(l);
    const bool o = fine_[l] ? fine_[l]->omega[0].get(0, 0) : all_[l] != 0;
    if (o) top.set(g.gx(key), g.gy(key));
  }
  pf_.comm().or_in_place(top.words());
  omega_c_.back() = std::move(top);
  // Monotone coarse levels: a coarse square is in a leaf of its level or coarser only when all
  // four children are (bits only ever clear).
  for (int l = lp_ - 1; l >= 0; --l) {
    const Bitmap fine = qb::reduce(omega_c_[static_cast<std::size_t>(l) + 1], false);
    Bitmap& o = omega_c_[static_cast<std::size_t>(l)];
    if (o.words().empty())
      o = fine;
    else
      and_into(o, fine);
  }
}

bool ForestPyramid::fine_bit(int l, std::int64_t a, std::int64_t b, bool omega) const {
  const int d = l - lp_;
  const std::int64_t key = pf_.grid().key(a >> d, b >> d);
  const std::int64_t li = pf_.local_index(key);
  if (li < 0) throw InternalError(fmt::format("forest: square ({}, {}, {}) is not in a local patch", l, a, b));
  const auto s = static_cast<std::size_t>(li);
  if (!fine_[s]) return all_[s] != 0;
  const std::int64_t m = (std::int64_t{1} << d) - 1;
  return (omega ? fine_[s]->omega : fine_[s]->any)[static_cast<std::size_t>(d)].get(a & m, b & m);
}

bool ForestPyramid::omega(int l, std::int64_t a, std::int64_t b) const {
  return l <= lp_ ? omega_c_[static_cast<std::size_t>(l)].get(a, b) : fine_bit(l, a, b, true);
}

bool ForestPyramid::any(int l, std::int64_t a, std::int64_t b) const {
  return l <= lp_ ? any_c_[static_cast<std::size_t>(l)].get(a, b) : fine_bit(l, a, b, false);
}

void ForestPyramid::apply_rules(const config::QuadtreeOptions& options, const PoleRotation& rotation,
                                const raster::Bathymetry* bathy) {
  if (options.depth_rules.empty() && options.box_rules.empty()) return;
  // The rules' levels and ranges are checked at load (config/global_config.cpp).
  const bool level_depth_rules = std::any_of(options.depth_rules.begin(), options.depth_rules.end(),
                                             [](const config::DepthRule& r) { return !(r.size_km > 0.0); });
  if (level_depth_rules && bathy == nullptr) throw InternalError("quadtree: depth rules need the bathymetry raster");
  const int top = quadtree::rules_top_level(options, L_);
  if (top < 0) return;
  const Lattice& lat = pf_.grid().lat;
  // Fine levels, patch by patch (a patch inside a coarse leaf is tried as all ones and kept
  // inactive when no rule touches it).
  for (std::size_t l = 0; l < fine_.size(); ++l) {
    if (!fine_[l] && all_[l] == 0) continue;
    const std::int64_t key = pf_.key(l), gx = pf_.grid().gx(key), gy = pf_.grid().gy(key);
    Fine trial;
    Fine& f = fine_[l] ? *fine_[l] : trial;
    if (!fine_[l]) {
      trial.omega.resize(static_cast<std::size_t>(plog_) + 1);
      for (int d = 0; d <= plog_; ++d) trial.omega[static_cast<std::size_t>(d)] = ones(std::int64_t{1} << d);
    }
    bool changed = false;
    for (int lev = std::min(top, L_ - 1); lev >= lp_; --lev) {
      const int d = lev - lp_;
      Bitmap& om = f.omega[static_cast<std::size_t>(d)];
      if (lev < top) and_into(om, qb::reduce(f.omega[static_cast<std::size_t>(d) + 1], false));
      const std::int64_t before = om.count();
      quadtree::apply_rules_level(om, lat, options, rotation, bathy, lev, gx << d, gy << d);
      changed = changed || om.count() != before;
    }
    if (!fine_[l] && changed) {
      Fine& a = activate(l);
      a.omega = std::move(trial.omega);
    }
  }
  sync_coarse();
  for (int lev = std::min(top, lp_ - 1); lev >= 0; --lev) {
    Bitmap& om = omega_c_[static_cast<std::size_t>(lev)];
    and_into(om, qb::reduce(omega_c_[static_cast<std::size_t>(lev) + 1], false));
    quadtree::apply_rules_level(om, lat, options, rotation, bathy, lev, 0, 0);
  }
}

bool ForestPyramid::would_split(std::size_t l, const size::SizeField& field) const {
  // An inactive patch inside a coarse leaf: every square of every fine level is in omega until one
  // splits, and a square's test depends only on its row (size, shortest child edge) and on the
  // field cell holding it when it is finer than the field's grid. So one test per (level, row,
  // cell) finds whether the dense loop would split any square of it.
  if (!field.has_grid()) return false;
  const Lattice& lat = pf_.grid().lat;
  const int c = field.grid().level();
  const std::int64_t key = pf_.key(l), gx = pf_.grid().gx(key), gy = pf_.grid().gy(key);
  for (int lev = L_ - 1; lev >= lp_; --lev) {
    const int d = lev - lp_;
    const std::int64_t side = std::int64_t{1} << d, a0 = gx << d;
    for (std::int64_t j = 0; j < side; ++j) {
      const std::int64_t b = (gy << d) + j;
      const double size = quadtree::square_size_km(lat, lev, quadtree::square_centre_row(lat, lev, b));
      const double child_edge = quadtree::child_min_edge_km(lat, lev, b);
      std::int64_t i = 0;
      while (i < side) {
        const std::int64_t a = a0 + i;
        if (quadtree::exceeds_size_target(size, field.grid_min_over_square(lev, a, b)) &&
            (!field.has_cfl() || quadtree::cfl_allows_split(field, lev, a, b, child_edge)))
          return true;
        if (lev > c) {
          const int sh = lev - c;
          i = (((a >> sh) + 1) << sh) - a0;  // the next field cell
        } else {
          ++i;
        }
      }
    }
  }
  return false;
}

void ForestPyramid::apply_size_field(const size::SizeField& field) {
  if (!field.active()) return;
  const Lattice& lat = pf_.grid().lat;
  const double band_km = field.band_km();
  const PatchGrid& g = pf_.grid();
  std::vector<Bitmap> band_c;
  if (band_km > 0.0) band_c.assign(static_cast<std::size_t>(lp_) + 1, Bitmap());
  if (band_km > 0.0) band_c.back() = Bitmap(g.npx, g.npy);
  for (std::size_t l = 0; l < fine_.size(); ++l) {
    if (!fine_[l] && all_[l] == 0) continue;
    const std::int64_t key = pf_.key(l), gx = g.gx(key), gy = g.gy(key);
    std::vector<Bitmap> band;  // the band pyramid of the patch, levels lp .. L-1
    if (band_km > 0.0) {
      Bitmap px = band_bits(l, field.band_radius());
      if (any_bit(px)) {
        band.resize(static_cast<std::size_t>(plog_));
        band[static_cast<std::size_t>(plog_) - 1] = qb::reduce(px, true);
        for (int d = plog_ - 2; d >= 0; --d)
          band[static_cast<std::size_t>(d)] = qb::reduce(band[static_cast<std::size_t>(d) + 1], true);
        band_c.back().set(gx, gy);
      }
    }
    if (!fine_[l] && band.empty() && !would_split(l, field)) continue;
    Fine& f = activate(l);
    for (int d = plog_ - 1; d >= 0; --d) {
      Bitmap& om = f.omega[static_cast<std::size_t>(d)];
      if (d + 1 < plog_) and_into(om, qb::reduce(f.omega[static_cast<std::size_t>(d) + 1], false));
      quadtree::apply_size_field_level(om, band.empty() ? nullptr : &band[static_cast<std::size_t>(d)], lat, field,
                                       lp_ + d, gx << d, gy << d);
    }
  }
  sync_coarse();
  if (band_km > 0.0) {
    pf_.comm().or_in_place(band_c.back().words());
    for (int lev = lp_ - 1; lev >= 0; --lev)
      band_c[static_cast<std::size_t>(lev)] = qb::reduce(band_c[static_cast<std::size_t>(lev) + 1], true);
  }
  for (int lev = lp_ - 1; lev >= 0; --lev) {
    Bitmap& om = omega_c_[static_cast<std::size_t>(lev)];
    and_into(om, qb::reduce(omega_c_[static_cast<std::size_t>(lev) + 1], false));
    quadtree::apply_size_field_level(om, band_km > 0.0 ? &band_c[static_cast<std::size_t>(lev)] : nullptr, lat, field,
                                     lev, 0, 0);
  }
}

quadtree::GradeStats ForestPyramid::grade(const size::SizeField& field) {
  quadtree::GradeStats st;
  const double gr = field.gradation();
  if (L_ < 2 || !field.has_grid() || !(gr > 0.0)) return st;
  const PatchGrid& g = pf_.grid();
  const Lattice& lat = g.lat;
  const Comm& comm = pf_.comm();
  std::int64_t splits = 0, refused = 0;
  for (int v = L_ - 1; v >= lp_ + 1; --v) {
    const int d = v - lp_;
    const std::int64_t side = std::int64_t{1} << d;
    const std::int64_t n_v = lat.nx >> (L_ - v), rows_v = lat.ny >> (L_ - v);
    // The split level-v squares of every rank, by row then column.
    std::vector<std::int64_t> mine;
    for (std::size_t l = 0; l < fine_.size(); ++l) {
      if (!fine_[l]) continue;
      const std::int64_t key = pf_.key(l), a0 = g.gx(key) << d, b0 = g.gy(key) << d;
      const Bitmap& om = fine_[l]->omega[static_cast<std::size_t>(d)];
      const Bitmap& an = fine_[l]->any[static_cast<std::size_t>(d)];
      for (std::int64_t j = 0; j < side; ++j)
        for (std::int64_t i = 0; i < side; ++i)
          if (an.get(i, j) && !om.get(i, j)) {
            mine.push_back(b0 + j);
            mine.push_back(a0 + i);
          }
    }
    std::vector<std::int64_t> flat = comm.allgatherv(mine);
    struct Sq {
      std::int64_t b, a;
    };
    std::vector<Sq> split(flat.size() / 2);
    for (std::size_t q = 0; q < split.size(); ++q) split[q] = {flat[2 * q], flat[2 * q + 1]};
    flat = {};
    std::sort(split.begin(), split.end(),
              [](const Sq& x, const Sq& y) { return x.b < y.b || (x.b == y.b && x.a < y.a); });
    if (v == L_ - 1) {
      std::vector<std::int64_t> rx, ry;
      quadtree::grading_radii(lat, v, gr, rx, ry);
      st.radius_at_equator = rx[static_cast<std::size_t>(rows_v / 2)];
    }
    if (split.empty()) continue;
    std::vector<std::int64_t> rx, ry;
    quadtree::grading_radii(lat, v, gr, rx, ry);
    const auto first_at = [&split](std::int64_t b, std::int64_t a) {
      return std::lower_bound(split.begin(), split.end(), Sq{b, a},
                              [](const Sq& x, const Sq& y) { return x.b < y.b || (x.b == y.b && x.a < y.a); });
    };
    // Calls f(unwrapped column) for the split squares of row q whose column lies in the periodic
    // range [lo, hi] (hi - lo + 1 < n_v), with the column taken into that range.
    const auto for_range = [&](std::int64_t q, std::int64_t lo, std::int64_t hi, const auto& f) {
      const std::int64_t w_lo = wrap_index(lo, n_v);
      const std::int64_t len = hi - lo + 1;
      const auto piece = [&](std::int64_t from, std::int64_t to, std::int64_t shift) {  // [from, to] in [0, n_v)
        for (auto it = first_at(q, from); it != split.end() && it->b == q && it->a <= to; ++it) f(it->a + shift);
      };
      if (w_lo + len <= n_v) {
        piece(w_lo, w_lo + len - 1, lo - w_lo);
      } else {
        piece(w_lo, n_v - 1, lo - w_lo);
        piece(0, w_lo + len - 1 - n_v, lo - w_lo + n_v);
      }
    };
    for (std::size_t l = 0; l < fine_.size(); ++l) {
      if (!fine_[l] && all_[l] == 0) continue;
      const std::int64_t key = pf_.key(l), a0 = g.gx(key) << d, b0 = g.gy(key) << d;
      // The near squares of the patch: split squares in the rows within ry of the target row and
      // the columns within rx (periodic, as bits::dilate_row's window).
      Bitmap near(side, side);
      bool any_near = false;
      for (std::int64_t j = 0; j < side; ++j) {
        const std::int64_t b = b0 + j;
        const std::int64_t r = ry[static_cast<std::size_t>(b)], c = rx[static_cast<std::size_t>(b)];
        const std::int64_t q_lo = std::max<std::int64_t>(0, b - r), q_hi = std::min(rows_v - 1, b + r);
        if (2 * c + 1 >= n_v || side + 2 * c >= n_v) {
          // The whole row (or more than it): every column is near any split square of the rows.
          const bool whole = 2 * c + 1 >= n_v;
          for (std::int64_t q = q_lo; q <= q_hi; ++q) {
            const auto it = first_at(q, 0);
            if (it == split.end() || it->b != q) continue;
            if (whole) {
              qb::set_range(near.row(j), 0, side);
              any_near = true;
              break;
            }
            for (auto jt = it; jt != split.end() && jt->b == q; ++jt)
              for (std::int64_t i = 0; i < side; ++i)
                if (wrap_index(a0 + i - jt->a + c, n_v) <= 2 * c) {
                  near.set(i, j);
                  any_near = true;
                }
          }
          continue;
        }
        for (std::int64_t q = q_lo; q <= q_hi; ++q)
          for_range(q, a0 - c, a0 + side - 1 + c, [&](std::int64_t a) {
            const std::int64_t i_lo = std::max<std::int64_t>(0, a - c - a0);
            const std::int64_t i_hi = std::min<std::int64_t>(side - 1, a + c - a0);
            if (i_lo <= i_hi) {
              qb::set_range(near.row(j), i_lo, i_hi + 1);
              any_near = true;
            }
          });
      }
      if (!any_near) continue;
      const Bitmap parents = qb::reduce(near, true);
      const int dp = d - 1;  // the parents' level v - 1 inside the patch
      const std::int64_t ps = std::int64_t{1} << dp;
      // omega[v-1] & parents, less what the CFL bound refuses.
      const bool active = static_cast<bool>(fine_[l]);
      std::vector<std::pair<std::int64_t, std::int64_t>> clear;
      for (std::int64_t j = 0; j < ps; ++j) {
        const std::int64_t b = (g.gy(key) << dp) + j;
        const double child_edge = quadtree::child_min_edge_km(lat, v - 1, b);
        for (std::int64_t i = 0; i < ps; ++i) {
          if (!parents.get(i, j)) continue;
          const bool set = active ? fine_[l]->omega[static_cast<std::size_t>(dp)].get(i, j) : true;
          if (!set) continue;
          if (!quadtree::cfl_allows_split(field, v - 1, (g.gx(key) << dp) + i, b, child_edge)) {
            ++refused;
            continue;
          }
          clear.emplace_back(i, j);
        }
      }
      if (clear.empty()) continue;
      Fine& f = activate(l);
      for (const auto& [i, j] : clear) f.omega[static_cast<std::size_t>(dp)].clear(i, j);
      splits += static_cast<std::int64_t>(clear.size());
      for (int dd = dp - 1; dd >= 0; --dd)
        and_into(f.omega[static_cast<std::size_t>(dd)], qb::reduce(f.omega[static_cast<std::size_t>(dd) + 1], false));
    }
  }
  sync_coarse();
  st.splits = comm.sum(splits);
  st.cfl_refused = comm.sum(refused);
  for (int v = lp_; v >= 1; --v) {
    const quadtree::GradeStats s = quadtree::grade_level(omega_c_, any_c_[static_cast<std::size_t>(v)], lat, field, v);
    st.splits += s.splits;
    st.cfl_refused += s.cfl_refused;
    if (v == L_ - 1) st.radius_at_equator = s.radius_at_equator;
  }
  return st;
}

std::vector<std::int64_t> ForestPyramid::leaves_per_level() const {
  std::vector<std::int64_t> counts(static_cast<std::size_t>(L_) + 1, 0);
  // Coarse levels (the same on every rank).
  counts[0] = omega_c_[0].count();
  for (int l = 1; l <= lp_; ++l) {
    const Bitmap& om = omega_c_[static_cast<std::size_t>(l)];
    const Bitmap& parent = omega_c_[static_cast<std::size_t>(l) - 1];
    std::int64_t c = 0;
    for (std::int64_t b = 0; b < om.ny(); ++b)
      for (std::int64_t a = 0; a < om.nx(); ++a) c += (om.get(a, b) && !parent.get(a / 2, b / 2)) ? 1 : 0;
    counts[static_cast<std::size_t>(l)] = c;
  }
  std::vector<std::int64_t> fine(counts.size(), 0);
  for (const auto& f : fine_) {
    if (!f) continue;
    for (int d = 1; d <= plog_; ++d) {
      const Bitmap& om = f->omega[static_cast<std::size_t>(d)];
      const Bitmap& parent = f->omega[static_cast<std::size_t>(d) - 1];
      const std::int64_t side = std::int64_t{1} << d;
      for (std::int64_t j = 0; j < side; ++j)
        for (std::int64_t i = 0; i < side; ++i)
          fine[static_cast<std::size_t>(lp_ + d)] += (om.get(i, j) && !parent.get(i / 2, j / 2)) ? 1 : 0;
    }
  }
  pf_.comm().sum_in_place(fine);
  for (std::size_t l = 0; l < counts.size(); ++l) counts[l] += fine[l];
  return counts;
}

std::int64_t ForestPyramid::active_patches() const {
  std::int64_t n = 0;
  for (const auto& f : fine_) n += f ? 1 : 0;
  return n;
}

std::int64_t ForestPyramid::fine_bytes() const {
  std::int64_t b = 0;
  for (const auto& f : fine_)
    if (f)
      for (std::size_t d = 0; d < f->omega.size(); ++d)
        b += static_cast<std::int64_t>(f->omega[d].bytes() + f->any[d].bytes());
  return b;
}

}  // namespace aq::forest
