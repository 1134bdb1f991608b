// SPDX-License-Identifier: GPL-3.0-or-later
// The K-cursor fill on the forest (see fill.hpp).
#include "forest/fill.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "core/error.hpp"
#include "core/types.hpp"
#include "mask/lattice_coords.hpp"
#include "quadtree/bits.hpp"

namespace aq::forest {

namespace {

// Union-find over sparse 64-bit node ids; the root of a set is its smallest id.
class MinDsu {
 public:
  std::int64_t find(std::int64_t x) {
    auto it = parent_.find(x);
    if (it == parent_.end()) {
      parent_.emplace(x, x);
      return x;
    }
    std::int64_t r = x;
    while (true) {
      const std::int64_t p = parent_[r];
      if (p == r) break;
      r = p;
    }
    while (x != r) {  // path compression
      std::int64_t& p = parent_[x];
      const std::int64_t next = p;
      p = r;
      x = next;
    }
    return r;
  }
  void unite(std::int64_t a, std::int64_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a < b)
      parent_[b] = a;
    else
      parent_[a] = b;
  }
  [[nodiscard]] const std::unordered_map<std::int64_t, std::int64_t>& nodes() const { return parent_; }

 private:
  std::unordered_map<std::int64_t, std::int64_t> parent_;
};

enum class Kind : std::uint8_t { kNone = 0, kCore = 1, kMat = 2 };

// 4-connected labels of the set bits of a p × p bitmap (no wrap), -1 elsewhere; returns the count.
std::int32_t label_bits(const Bitmap& w, std::int64_t p, std::vector<std::int32_t>& lab) {
  lab.assign(static_cast<std::size_t>(p * p), -1);
  std::int32_t n = 0;
  std::vector<std::int64_t> stack;
  for (std::int64_t j = 0; j < p; ++j)
    for (std::int64_t i = 0; i < p; ++i) {
      if (!w.get(i, j) || lab[static_cast<std::size_t>(j * p + i)] >= 0) continue;
      lab[static_cast<std::size_t>(j * p + i)] = n;
      stack.assign(1, j * p + i);
      while (!stack.empty()) {
        const std::int64_t q = stack.back();
        stack.pop_back();
        const std::int64_t x = q % p, y = q / p;
        const std::int64_t nb[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
        for (const auto& c : nb) {
          if (c[0] < 0 || c[1] < 0 || c[0] >= p || c[1] >= p) continue;
          const auto s = static_cast<std::size_t>(c[1] * p + c[0]);
          if (lab[s] >= 0 || !w.get(c[0], c[1])) continue;
          lab[s] = n;
          stack.push_back(c[1] * p + c[0]);
        }
      }
      ++n;
    }
  return n;
}

// The all-wet K-windows of a patch and its components (see fill.hpp).
struct Windows {
  Kind kind = Kind::kNone;
  Bitmap w;  // kMat: the patch's windows
  std::int32_t comps = 0;
};

// The window components of a pixel set over all ranks.
class WindowComponents {
 public:
  WindowComponents(const PatchForest& pf, const std::vector<PatchBits>& set, int k) : pf_(pf), k_(k) {
    const PatchGrid& g = pf.grid();
    p_ = g.size;
    stride_ = p_ * p_ + 1;
    const std::vector<PatchBits> ghosts = pf.exchange(set);
    const auto n = pf.local_count();
    win_.resize(n);
    // Border ids of the materialised patches: west, east, south, north (p each), -1 where no
    // window; a core patch's are all its one node.
    std::vector<std::int32_t> lab;
    for (std::size_t l = 0; l < n; ++l) {
      const std::int64_t key = pf.key(l);
      Windows& w = win_[l];
      const PatchBits& s = set[l];
      if (s.state == Fill::kNone) continue;
      bool core = s.state == Fill::kAll;
      for (std::int64_t dy = -1; dy <= 1 && core; ++dy)
        for (std::int64_t dx = -1; dx <= 1 && core; ++dx) {
          const PatchBits* nb = pf.find(g.neighbour(g.gx(key), g.gy(key), dx, dy), set, ghosts);
          core = nb != nullptr && nb->state == Fill::kAll;
        }
      if (core) {
        w.kind = Kind::kCore;
        continue;
      }
      w.kind = Kind::kMat;
      const Bitmap big = mask::all_wet_windows(pf.assemble(l, set, ghosts, OutsideRule{false, false}), k);
      w.w = centre_of(big, p_);
      w.comps = label_bits(w.w, p_, lab);
      std::vector<std::int64_t>& ids = borders_[l];
      ids.assign(static_cast<std::size_t>(4 * p_), -1);
      const auto id = [&](std::int64_t i, std::int64_t j) {
        const std::int32_t c = lab[static_cast<std::size_t>(j * p_ + i)];
        return c < 0 ? std::int64_t{-1} : key * stride_ + c;
      };
      for (std::int64_t t = 0; t < p_; ++t) {
        ids[static_cast<std::size_t>(t)] = id(0, t);
        ids[static_cast<std::size_t>(p_ + t)] = id(p_ - 1, t);
        ids[static_cast<std::size_t>(2 * p_ + t)] = id(t, 0);
        ids[static_cast<std::size_t>(3 * p_ + t)] = id(t, p_ - 1);
      }
    }
    // The border records of the patches other ranks see (kind, then the 4p ids).
    const std::size_t rec = static_cast<std::size_t>(8 + 4 * p_ * 8);
    const std::vector<char> ghost_borders = pf.exchange_records(rec, [&](std::size_t l, char* out) {
      out[0] = static_cast<char>(win_[l].kind);
      auto* ids = reinterpret_cast<std::int64_t*>(out + 8);
      border_into(l, ids);
    });
    std::vector<std::int64_t> mine_buf(static_cast<std::size_t>(4 * p_)), theirs_buf(mine_buf.size());
    // The border ids of a local or ghost patch into `buf` (returns it), or null when neither.
    const auto border_of = [&](std::int64_t key, std::vector<std::int64_t>& buf) -> const std::int64_t* {
      if (const std::int64_t l = pf.local_index(key); l >= 0) {
        border_into(static_cast<std::size_t>(l), buf.data());
        return buf.data();
      }
      if (const std::int64_t gi = pf.ghost_index(key); gi >= 0)
        return reinterpret_cast<const std::int64_t*>(ghost_borders.data() + static_cast<std::size_t>(gi) * rec + 8);
      return nullptr;
    };
    // Local sets: every node, and the joins with the east and north neighbours.
    std::unordered_set<std::int64_t> ghost_nodes;
    for (std::size_t l = 0; l < n; ++l) {
      const Windows& w = win_[l];
      const std::int64_t key = pf.key(l);
      if (w.kind == Kind::kCore) dsu_.find(key * stride_);
      for (std::int32_t c = 0; c < w.comps; ++c) dsu_.find(key * stride_ + c);
      if (w.kind == Kind::kNone) continue;
      const std::int64_t* mine = border_of(key, mine_buf);
      for (const auto [dx, dy] : {std::array<std::int64_t, 2>{1, 0}, std::array<std::int64_t, 2>{0, 1}}) {
        const std::int64_t nk = g.neighbour(g.gx(key), g.gy(key), dx, dy);
        if (nk < 0) continue;
        const std::int64_t* theirs = border_of(nk, theirs_buf);
        if (theirs == nullptr) throw InternalError("forest fill: a neighbour patch is neither local nor a ghost");
        const bool local = pf.local_index(nk) >= 0;
        const std::int64_t* a = dx == 1 ? mine + p_ : mine + 3 * p_;  // my east / north
        const std::int64_t* b = dx == 1 ? theirs : theirs + 2 * p_;   // their west / south
        for (std::int64_t t = 0; t < p_; ++t) {
          if (a[t] < 0 || b[t] < 0) continue;
          dsu_.unite(a[t], b[t]);
          if (!local) ghost_nodes.insert(b[t]);
        }
      }
    }
    merge_ranks(ghost_nodes);
  }

  // The 4p border ids of local patch l (see the constructor).
  void border_into(std::size_t l, std::int64_t* ids) const {
    const Windows& w = win_[l];
    if (w.kind == Kind::kMat) {
      const std::vector<std::int64_t>& b = borders_.at(l);
      std::copy(b.begin(), b.end(), ids);
    } else {
      std::fill(ids, ids + 4 * p_, w.kind == Kind::kCore ? pf_.key(l) * stride_ : std::int64_t{-1});
    }
  }

  [[nodiscard]] std::int64_t root(std::int64_t id) {
    const std::int64_t r = dsu_.find(id);
    const auto it = merged_.find(r);
    return it == merged_.end() ? r : it->second;
  }
  [[nodiscard]] const Windows& windows(std::size_t l) const { return win_[l]; }
  [[nodiscard]] std::int64_t stride() const { return stride_; }
  [[nodiscard]] std::int64_t p() const { return p_; }
  /// Window w(i, j) of a local patch, its local labels recomputed.
  void labels(std::size_t l, std::vector<std::int32_t>& lab) const { label_bits(win_[l].w, p_, lab); }
  /// Whether window (i, j) (the lattice pixel of its lower-left) of a local patch is all-wet.
  [[nodiscard]] bool window_bit(std::int64_t i, std::int64_t j) const {
    const PatchGrid& g = pf_.grid();
    const std::int64_t l = pf_.local_index(g.key_at(i / p_, j / p_));
    if (l < 0) return false;
    const Windows& w = win_[static_cast<std::size_t>(l)];
    return w.kind == Kind::kCore || (w.kind == Kind::kMat && w.w.get(i % p_, j % p_));
  }
  /// The same, with the window's node.
  [[nodiscard]] bool window(std::int64_t i, std::int64_t j, std::int64_t& node) const {
    const PatchGrid& g = pf_.grid();
    const std::int64_t key = g.key_at(i / p_, j / p_);
    const std::int64_t l = pf_.local_index(key);
    if (l < 0) return false;
    const Windows& w = win_[static_cast<std::size_t>(l)];
    if (w.kind == Kind::kCore) {
      node = key * stride_;
      return true;
    }
    if (w.kind != Kind::kMat || !w.w.get(i % p_, j % p_)) return false;
    std::vector<std::int32_t> lab;
    label_bits(w.w, p_, lab);
    node = key * stride_ + lab[static_cast<std::size_t>((j % p_) * p_ + i % p_)];
    return true;
  }

 private:
  // Rank 0 joins the sets that cross ranks: every rank sends (node, local root) for the ghost
  // nodes it joined and for its own nodes in patches other ranks see as ghosts; the merged root
  // (smallest id) of every local root that crosses comes back to every rank.
  void merge_ranks(const std::unordered_set<std::int64_t>& ghost_nodes) {
    const Comm& comm = pf_.comm();
    if (comm.size() == 1) return;
    std::vector<std::int64_t> pairs;
    for (const std::int64_t x : ghost_nodes) {
      pairs.push_back(x);
      pairs.push_back(dsu_.find(x));
    }
    // Own nodes on the borders of patches next to another rank's patches.
    const PatchGrid& g = pf_.grid();
    for (std::size_t l = 0; l < win_.size(); ++l) {
      const Windows& w = win_[l];
      if (w.kind == Kind::kNone) continue;
      const std::int64_t key = pf_.key(l);
      bool edge = false;
      for (std::int64_t dy = -1; dy <= 1 && !edge; ++dy)
        for (std::int64_t dx = -1; dx <= 1 && !edge; ++dx) {
          const std::int64_t nk = g.neighbour(g.gx(key), g.gy(key), dx, dy);
          edge = nk >= 0 && pf_.local_index(nk) < 0;
        }
      if (!edge) continue;
      const std::int32_t count = w.kind == Kind::kCore ? 1 : w.comps;
      for (std::int32_t c = 0; c < count; ++c) {
        const std::int64_t id = key * stride_ + c;
        pairs.push_back(id);
        pairs.push_back(dsu_.find(id));
      }
    }
    std::vector<std::int64_t> all = comm.gatherv(pairs, 0);
    std::vector<std::int64_t> result;  // (local root, merged root) pairs
    if (comm.root()) {
      MinDsu d;
      for (std::size_t q = 0; q + 1 < all.size(); q += 2) d.unite(all[q], all[q + 1]);
      std::vector<std::int64_t> roots;
      for (std::size_t q = 1; q < all.size(); q += 2) roots.push_back(all[q]);
      std::sort(roots.begin(), roots.end());
      roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
      for (const std::int64_t r : roots) {
        const std::int64_t m = d.find(r);
        if (m != r) {
          result.push_back(r);
          result.push_back(m);
        }
      }
    }
    comm.bcast(result, 0);
    for (std::size_t q = 0; q + 1 < result.size(); q += 2) merged_[result[q]] = result[q + 1];
  }

  const PatchForest& pf_;
  int k_ = 1;
  std::int64_t p_ = 1, stride_ = 2;
  std::vector<Windows> win_;
  std::unordered_map<std::size_t, std::vector<std::int64_t>> borders_;  // materialised patches only
  MinDsu dsu_;
  std::unordered_map<std::int64_t, std::int64_t> merged_;
};

void check_cursor(int k, std::int64_t p) {
  if (k < 1 || k > 64) throw ConfigError(fmt::format("mask.cursor = {}: K must be between 1 and 64", k));
  if (k > p)
    throw ConfigError(
        fmt::format("mask.cursor = {}: the forest engine needs K <= {} pixels (its patches of 2^min(L, "
                    "7) pixels); more quadtree.levels, or quadtree.engine = \"dense\"",
                    k, p));
}

std::string seed_name(std::size_t n, const std::array<double, 2>& s) {
  return fmt::format("mask.seeds[{}] = ({}, {})", n, s[0], s[1]);
}

// The nearest all-wet window over all ranks: dist, then (j, i) (mask::place_seeds's Best).
struct Candidate {
  double dist = std::numeric_limits<double>::infinity();
  std::int64_t i = -1, j = -1;
  void offer(std::int64_t ci, std::int64_t cj, double d) {
    if (d < dist || (d == dist && (cj < j || (cj == j && ci < i)))) {
      dist = d;
      i = ci;
      j = cj;
    }
  }
  [[nodiscard]] bool found() const { return i >= 0; }
};

Candidate best_over_ranks(const Comm& comm, const Candidate& mine) {
  std::vector<Candidate> all = comm.allgatherv(std::vector<Candidate>{mine});
  Candidate b;
  for (const Candidate& c : all)
    if (c.found()) b.offer(c.i, c.j, c.dist);
  return b;
}

// mask::place_seeds on the forest's windows: the same choices and messages.
std::vector<mask::SeedInfo> place_seeds(const PatchForest& pf, WindowComponents& wc, int k, const PoleRotation& rot,
                                        const std::vector<std::array<double, 2>>& seeds, double radius_deg,
                                        const Logger& log) {
  if (seeds.empty()) throw ConfigError("mask.seeds = []: give at least one [lon, lat] point in the ocean");
  if (!std::isfinite(radius_deg) || radius_deg < 0.0)
    throw ConfigError(fmt::format("mask.seed_radius_deg = {}: must be a finite number >= 0", radius_deg));
  const Lattice& lattice = pf.grid().lat;
  const std::int64_t nx = lattice.nx, ny = lattice.ny, p = pf.grid().size;
  const double dpx = lattice.pixel_deg();
  std::vector<mask::SeedInfo> out;
  for (std::size_t n = 0; n < seeds.size(); ++n) {
    const auto& s = seeds[n];
    if (!std::isfinite(s[0]) || !std::isfinite(s[1]) || s[1] < -90.0 || s[1] > 90.0)
      throw ConfigError(
          fmt::format("{}: not a valid point (longitude, latitude in [-90, 90] degrees)", seed_name(n, s)));
    const mask::LonLat r = mask::geographic_to_lattice(rot, {s[0], s[1]});
    double x = 0.0, y = 0.0;
    mask::deg_to_lattice_xy(lattice, r, x, y);
    const auto px = std::min<std::int64_t>(static_cast<std::int64_t>(std::floor(x)), nx - 1);
    const auto py = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(y)), 0, ny - 1);
    const auto offer = [&](Candidate& best, std::int64_t i0, std::int64_t j0) {
      if (j0 < 0 || j0 > ny - k) return;
      const mask::PixelIJ w{wrap_index(i0, nx), j0};
      if (!wc.window_bit(w.i, w.j)) return;
      best.offer(w.i, w.j, mask::angular_distance_deg(r, mask::window_center_lattice_deg(lattice, w, k)));
    };
    Candidate mine;
    for (std::int64_t j0 = py - k + 1; j0 <= py; ++j0)
      for (std::int64_t i0 = px - k + 1; i0 <= px; ++i0) offer(mine, i0, j0);
    Candidate best = best_over_ranks(pf.comm(), mine);
    mask::SeedInfo info;
    info.index = static_cast<int>(n);
    info.requested = {s[0], s[1]};
    if (!best.found()) {
      const mask::SeedSearchBox box = mask::seed_search_box(lattice, r.lat_deg, x, radius_deg, k);
      const std::int64_t jlo = box.jlo, jhi = box.jhi, ilo = box.ilo, ihi = box.ihi;
      // This rank's patches in the box, nearest (by latitude, a lower bound of the distance) first;
      // a patch farther than the best so far cannot hold a nearer window.
      const std::int64_t j_from = std::max<std::int64_t>(jlo, 0), j_to = std::min(jhi, ny - k);
      struct Near {
        double lb;
        std::size_t l;
      };
      std::vector<Near> order;
      const PatchGrid& g = pf.grid();
      for (std::size_t l = 0; l < pf.local_count(); ++l) {
        const std::int64_t key = pf.key(l);
        const std::int64_t y0 = g.gy(key) * p, y1 = y0 + p - 1;
        if (y1 < j_from || y0 > j_to) continue;
        const double c0 = mask::window_center_lattice_deg(lattice, {0, y0}, k).lat_deg;
        const double c1 = mask::window_center_lattice_deg(lattice, {0, y1}, k).lat_deg;
        const double lb = r.lat_deg < c0 ? c0 - r.lat_deg : r.lat_deg > c1 ? r.lat_deg - c1 : 0.0;
        if (lb > radius_deg + 1e-9) continue;
        order.push_back({lb, l});
      }
      std::sort(order.begin(), order.end(),
                [](const Near& a, const Near& b) { return a.lb < b.lb || (a.lb == b.lb && a.l < b.l); });
      Candidate near;
      for (const Near& o : order) {
        if (near.found() && o.lb > near.dist + 1e-12) break;
        const std::int64_t key = pf.key(o.l);
        const std::int64_t x0 = g.gx(key) * p, y0 = g.gy(key) * p;
        for (std::int64_t j0 = std::max(y0, j_from); j0 <= std::min(y0 + p - 1, j_to); ++j0)
          for (std::int64_t i = x0; i < x0 + p; ++i) {
            // The box's columns: [ilo, ihi] taken modulo nx (or all).
            const bool in_cols = ihi - ilo + 1 >= nx || wrap_index(i - ilo, nx) <= ihi - ilo;
            if (in_cols) offer(near, i, j0);
          }
      }
      near = best_over_ranks(pf.comm(), near);
      if (!near.found() || near.dist > radius_deg) {
        throw ConfigError(fmt::format(
            "{}: no all-wet {}×{} pixel window (K = mask.cursor, pixels of {}°; wet means elevation <= "
            "-mask.min_depth_m) within mask.seed_radius_deg = {}° of the seed; put the seed in open water or "
            "increase mask.seed_radius_deg",
            seed_name(n, s), k, k, dpx, radius_deg));
      }
      best = near;
      info.moved = true;
      info.moved_deg = near.dist;
    }
    info.window = {best.i, best.j};
    info.window_center = mask::lattice_to_geographic(rot, mask::window_center_lattice_deg(lattice, info.window, k));
    if (info.moved) {
      log.warn("{}: not inside an all-wet {}×{} pixel window; moved {:.3f}° to ({:.4f}, {:.4f}) (window centre)",
               seed_name(n, s), k, k, info.moved_deg, info.window_center.lon_deg, info.window_center.lat_deg);
    }
    out.push_back(info);
  }
  return out;
}

// The component (merged root) of each seed window, known on every rank.
std::vector<std::int64_t> seed_roots(const PatchForest& pf, WindowComponents& wc,
                                     const std::vector<mask::PixelIJ>& windows) {
  std::vector<std::int64_t> roots(windows.size(), -1);
  for (std::size_t n = 0; n < windows.size(); ++n) {
    std::int64_t node = 0;
    if (wc.window(windows[n].i, windows[n].j, node)) roots[n] = wc.root(node);
  }
  pf.comm().max_in_place(roots);
  return roots;
}

// Ω_L: the windows whose component is in `reached`, dilated by K.
std::vector<PatchBits> dilate_reached(const PatchForest& pf, WindowComponents& wc, int k,
                                      const std::unordered_set<std::int64_t>& reached) {
  const std::int64_t p = wc.p();
  const auto n = pf.local_count();
  std::vector<PatchBits> r(n);
  std::vector<std::int32_t> lab;
  for (std::size_t l = 0; l < n; ++l) {
    const Windows& w = wc.windows(l);
    const std::int64_t key = pf.key(l);
    if (w.kind == Kind::kCore) {
      r[l].state = reached.count(wc.root(key * wc.stride())) != 0 ? Fill::kAll : Fill::kNone;
    } else if (w.kind == Kind::kMat && w.comps > 0) {
      std::vector<char> in(static_cast<std::size_t>(w.comps), 0);
      bool any = false;
      for (std::int32_t c = 0; c < w.comps; ++c) {
        in[static_cast<std::size_t>(c)] = reached.count(wc.root(key * wc.stride() + c)) != 0 ? 1 : 0;
        any = any || in[static_cast<std::size_t>(c)] != 0;
      }
      if (!any) continue;
      wc.labels(l, lab);
      r[l].state = Fill::kMixed;
      r[l].bits = Bitmap(p, p);
      for (std::int64_t j = 0; j < p; ++j)
        for (std::int64_t i = 0; i < p; ++i) {
          const std::int32_t c = lab[static_cast<std::size_t>(j * p + i)];
          if (c >= 0 && in[static_cast<std::size_t>(c)] != 0) r[l].bits.set(i, j);
        }
    }
  }
  const std::vector<PatchBits> ghosts = pf.exchange(r);
  std::vector<PatchBits> filled(n);
  for (std::size_t l = 0; l < n; ++l) {
    const Windows& w = wc.windows(l);
    if (w.kind == Kind::kCore) {
      filled[l].state = r[l].state;
      continue;
    }
    if (w.kind == Kind::kNone && r[l].state == Fill::kNone) {
      // Windows of the neighbours to the west and south may reach into a patch without windows.
      bool near = false;
      const PatchGrid& g = pf.grid();
      for (std::int64_t dy = -1; dy <= 0 && !near; ++dy)
        for (std::int64_t dx = -1; dx <= 0 && !near; ++dx) {
          const PatchBits* b = pf.find(g.neighbour(g.gx(pf.key(l)), g.gy(pf.key(l)), dx, dy), r, ghosts);
          near = b != nullptr && b->state != Fill::kNone;
        }
      if (!near) continue;
    }
    const Bitmap big = mask::dilate_windows(pf.assemble(l, r, ghosts, OutsideRule{false, false}), k);
    filled[l].state = Fill::kMixed;
    filled[l].bits = centre_of(big, p);
    filled[l].normalise();
  }
  return filled;
}

std::int64_t count_set(const std::vector<PatchBits>& v, std::int64_t p) {
  std::int64_t n = 0;
  for (const PatchBits& b : v) n += b.state == Fill::kAll ? p * p : b.state == Fill::kMixed ? b.bits.count() : 0;
  return n;
}

// Windows per merged component, summed over the ranks for the components in `which`.
std::vector<std::int64_t> component_sizes(const PatchForest& pf, WindowComponents& wc,
                                          const std::vector<std::int64_t>& which) {
  std::unordered_map<std::int64_t, std::size_t> index;
  for (std::size_t q = 0; q < which.size(); ++q) index.emplace(which[q], q);
  std::vector<std::int64_t> size(which.size(), 0);
  std::vector<std::int32_t> lab;
  const std::int64_t p = wc.p();
  for (std::size_t l = 0; l < pf.local_count(); ++l) {
    const Windows& w = wc.windows(l);
    const std::int64_t key = pf.key(l);
    if (w.kind == Kind::kCore) {
      const auto it = index.find(wc.root(key * wc.stride()));
      if (it != index.end()) size[it->second] += p * p;
    } else if (w.kind == Kind::kMat && w.comps > 0) {
      std::vector<std::int64_t> per(static_cast<std::size_t>(w.comps), 0);
      wc.labels(l, lab);
      for (const std::int32_t c : lab)
        if (c >= 0) ++per[static_cast<std::size_t>(c)];
      for (std::int32_t c = 0; c < w.comps; ++c) {
        const auto it = index.find(wc.root(key * wc.stride() + c));
        if (it != index.end()) size[it->second] += per[static_cast<std::size_t>(c)];
      }
    }
  }
  pf.comm().sum_in_place(size);
  return size;
}

}  // namespace

ForestFill forest_fill(const PatchForest& pf, const std::vector<PatchBits>& wet, const PoleRotation& rot, int k,
                       const std::vector<std::array<double, 2>>& seeds, double radius_deg, const Logger& log) {
  const std::int64_t p = pf.grid().size;
  check_cursor(k, p);
  ForestFill out;
  WindowComponents wc(pf, wet, k);
  out.stats.cursor = k;
  std::int64_t windows = 0;
  for (std::size_t l = 0; l < pf.local_count(); ++l) {
    const Windows& w = wc.windows(l);
    windows += w.kind == Kind::kCore ? p * p : w.kind == Kind::kMat ? w.w.count() : 0;
  }
  out.stats.all_wet_windows = pf.comm().sum(windows);
  out.seeds = place_seeds(pf, wc, k, rot, seeds, radius_deg, log);
  std::vector<mask::PixelIJ> seed_windows;
  for (const mask::SeedInfo& s : out.seeds) seed_windows.push_back(s.window);
  const std::vector<std::int64_t> roots = seed_roots(pf, wc, seed_windows);
  const std::vector<std::int64_t> sizes = component_sizes(pf, wc, roots);
  std::unordered_set<std::int64_t> reached;
  for (std::size_t n = 0; n < out.seeds.size(); ++n) {
    mask::SeedInfo& si = out.seeds[n];
    const std::int64_t r = roots[n];
    const bool fresh = r >= 0 && reached.count(r) == 0;
    si.windows_reached = fresh ? sizes[n] : 0;
    if (fresh) {
      reached.insert(r);
      out.stats.reached_windows += sizes[n];
      for (std::size_t m = n + 1; m < out.seeds.size(); ++m)
        if (out.seeds[m].same_fill_as < 0 && sizes[n] > 0 && roots[m] == r)
          out.seeds[m].same_fill_as = static_cast<int>(n);
    }
  }
  out.filled = dilate_reached(pf, wc, k, reached);
  out.stats.wet_pixels = pf.comm().sum(count_set(wet, p));
  out.stats.filled_pixels = pf.comm().sum(count_set(out.filled, p));
  out.stats.wet_left_out = out.stats.wet_pixels - out.stats.filled_pixels;
  const mask::ComponentStats cs = forest_components(pf, wet, out.filled);
  out.stats.wet_components = cs.count;
  out.stats.wet_components_filled = cs.touching_probe;
  out.stats.largest_wet_component = cs.largest;
  return out;
}

std::vector<PatchBits> forest_refill(const PatchForest& pf, const std::vector<PatchBits>& filled, int k,
                                     const std::vector<mask::PixelIJ>& seed_windows) {
  WindowComponents wc(pf, filled, k);
  const std::vector<std::int64_t> roots = seed_roots(pf, wc, seed_windows);
  std::unordered_set<std::int64_t> reached;
  for (const std::int64_t r : roots)
    if (r >= 0) reached.insert(r);
  return dilate_reached(pf, wc, k, reached);
}

namespace {

// The 4-connected components of `set` over all ranks (labelled by their merged roots) with their
// pixels and whether a `probe` pixel is in them; `touching` (when given) receives on every rank
// the roots of the components a probe pixel is in, sorted.
mask::ComponentStats component_totals(const PatchForest& pf, WindowComponents& wc, const std::vector<PatchBits>& probe,
                                      std::vector<std::int64_t>* touching) {
  const std::int64_t p = wc.p();
  // Per merged component: pixels and whether a probe pixel is in it.
  std::unordered_map<std::int64_t, std::pair<std::int64_t, bool>> per;
  std::vector<std::int32_t> lab;
  for (std::size_t l = 0; l < pf.local_count(); ++l) {
    const Windows& w = wc.windows(l);
    const std::int64_t key = pf.key(l);
    const PatchBits& pr = probe[l];
    if (w.kind == Kind::kCore) {
      auto& e = per[wc.root(key * wc.stride())];
      e.first += p * p;
      e.second = e.second || pr.state != Fill::kNone;
    } else if (w.kind == Kind::kMat && w.comps > 0) {
      wc.labels(l, lab);
      std::vector<std::int64_t> cnt(static_cast<std::size_t>(w.comps), 0);
      std::vector<char> hit(static_cast<std::size_t>(w.comps), 0);
      for (std::int64_t j = 0; j < p; ++j)
        for (std::int64_t i = 0; i < p; ++i) {
          const std::int32_t c = lab[static_cast<std::size_t>(j * p + i)];
          if (c < 0) continue;
          ++cnt[static_cast<std::size_t>(c)];
          if (pr.get(i, j)) hit[static_cast<std::size_t>(c)] = 1;
        }
      for (std::int32_t c = 0; c < w.comps; ++c) {
        auto& e = per[wc.root(key * wc.stride() + c)];
        e.first += cnt[static_cast<std::size_t>(c)];
        e.second = e.second || hit[static_cast<std::size_t>(c)] != 0;
      }
    }
  }
  std::vector<std::int64_t> flat;
  flat.reserve(per.size() * 3);
  for (const auto& [root, e] : per) {
    flat.push_back(root);
    flat.push_back(e.first);
    flat.push_back(e.second ? 1 : 0);
  }
  const std::vector<std::int64_t> all = pf.comm().gatherv(flat, 0);
  std::vector<std::int64_t> stats(4, 0);
  std::vector<std::int64_t> hit_roots;
  if (pf.comm().root()) {
    std::unordered_map<std::int64_t, std::pair<std::int64_t, bool>> total;
    for (std::size_t q = 0; q + 2 < all.size(); q += 3) {
      auto& e = total[all[q]];
      e.first += all[q + 1];
      e.second = e.second || all[q + 2] != 0;
    }
    for (const auto& [root, e] : total) {
      ++stats[0];
      stats[1] = std::max(stats[1], e.first);
      if (e.second) {
        ++stats[2];
        stats[3] += e.first;
        if (touching != nullptr) hit_roots.push_back(root);
      }
    }
  }
  pf.comm().bcast(stats, 0);
  if (touching != nullptr) {
    std::sort(hit_roots.begin(), hit_roots.end());
    pf.comm().bcast(hit_roots, 0);
    *touching = std::move(hit_roots);
  }
  mask::ComponentStats cs;
  cs.count = stats[0];
  cs.largest = stats[1];
  cs.touching_probe = stats[2];
  cs.cells_touching_probe = stats[3];
  return cs;
}

}  // namespace

mask::ComponentStats forest_components(const PatchForest& pf, const std::vector<PatchBits>& set,
                                       const std::vector<PatchBits>& probe) {
  WindowComponents wc(pf, set, 1);
  return component_totals(pf, wc, probe, nullptr);
}

Unreached forest_unreached(const PatchForest& pf, const std::vector<PatchBits>& set,
                           const std::vector<PatchBits>& probe) {
  WindowComponents wc(pf, set, 1);
  Unreached out;
  std::vector<std::int64_t> touching;
  out.stats = component_totals(pf, wc, probe, &touching);
  const auto hit = [&touching](std::int64_t root) {
    return std::binary_search(touching.begin(), touching.end(), root);
  };
  const std::int64_t p = wc.p();
  out.pixels.resize(pf.local_count());
  std::vector<std::int32_t> lab;
  for (std::size_t l = 0; l < pf.local_count(); ++l) {
    const Windows& w = wc.windows(l);
    const std::int64_t key = pf.key(l);
    PatchBits& o = out.pixels[l];
    if (w.kind == Kind::kCore) {
      o.state = hit(wc.root(key * wc.stride())) ? Fill::kNone : Fill::kAll;
    } else if (w.kind == Kind::kMat && w.comps > 0) {
      std::vector<char> keep(static_cast<std::size_t>(w.comps), 0);
      bool any = false;
      for (std::int32_t c = 0; c < w.comps; ++c) {
        keep[static_cast<std::size_t>(c)] = hit(wc.root(key * wc.stride() + c)) ? 0 : 1;
        any = any || keep[static_cast<std::size_t>(c)] != 0;
      }
      if (!any) continue;
      wc.labels(l, lab);
      o.state = Fill::kMixed;
      o.bits = Bitmap(p, p);
      for (std::int64_t j = 0; j < p; ++j)
        for (std::int64_t i = 0; i < p; ++i) {
          const std::int32_t c = lab[static_cast<std::size_t>(j * p + i)];
          if (c >= 0 && keep[static_cast<std::size_t>(c)] != 0) o.bits.set(i, j);
        }
      o.normalise();
    }
  }
  return out;
}

}  // namespace aq::forest
