// SPDX-License-Identifier: GPL-3.0-or-later
// The quadtree's leaves as a p4est forest (see mesh_forest.hpp).
#include "forest/mesh_forest.hpp"

#include <fmt/format.h>
#include <p4est_algorithms.h>
#include <p4est_bits.h>
#include <p4est_communication.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/error.hpp"
#include "core/types.hpp"
#include "quadtree/nodes.hpp"

namespace aq::forest {

namespace {

struct RefineContext {
  const LatticeBrick* brick;
  const ForestPyramid* pyramid;
  int levels;
};

int refine_from_pyramid(p4est_t* p, p4est_topidx_t t, p4est_quadrant_t* q) {
  const auto* c = static_cast<const RefineContext*>(p->user_pointer);
  if (q->level >= c->levels) return 0;
  const Square s = c->brick->square(t, *q);
  return !c->pyramid->omega(s.level, s.a, s.b) && c->pyramid->any(s.level, s.a, s.b) ? 1 : 0;
}

std::uint8_t& flag(p4est_quadrant_t* q) { return *static_cast<std::uint8_t*>(q->p.user_data); }
std::uint8_t flag(const p4est_quadrant_t* q) { return *static_cast<const std::uint8_t*>(q->p.user_data); }

// Split quadrants keep their parent's flag (filled or land).
void copy_flag(p4est_t*, p4est_topidx_t, int num_outgoing, p4est_quadrant_t* outgoing[], int num_incoming,
               p4est_quadrant_t* incoming[]) {
  if (num_outgoing != 1) return;
  for (int k = 0; k < num_incoming; ++k) flag(incoming[k]) = static_cast<std::uint8_t>(flag(outgoing[0]) & 1);
}

const p4est_quadrant_t* quadrant_at(const sc_array_t& a, std::size_t k) {
  return static_cast<const p4est_quadrant_t*>(sc_array_index(const_cast<sc_array_t*>(&a), k));
}

// The quadrant of [first, last) of a sorted array that contains q (a level-L pixel), or -1.
std::int64_t containing(const sc_array_t& a, std::size_t first, std::size_t last, const p4est_quadrant_t& q) {
  std::size_t lo = first, hi = last;  // the first quadrant after q
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (p4est_quadrant_compare(quadrant_at(a, mid), &q) <= 0)
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo == first) return -1;
  const p4est_quadrant_t* c = quadrant_at(a, lo - 1);
  return (p4est_quadrant_is_equal(c, &q) != 0 || p4est_quadrant_is_ancestor(c, &q) != 0)
             ? static_cast<std::int64_t>(lo - 1)
             : -1;
}

// The leaf holding a pixel, among this rank's leaves and the ghost layer.
class Lookup {
 public:
  Lookup(p4est_t* f, const LatticeBrick& brick) : f_(f), brick_(brick) {
    ghost_.reset(p4est_ghost_new(f, P4EST_CONNECT_FULL));
    flags_.resize(ghost_->ghosts.elem_count);
    p4est_ghost_exchange_data(f, ghost_.get(), flags_.data());
  }
  struct Found {
    bool local = false;
    std::int64_t index = -1;  // local quadrant number, or ghost number
    const p4est_quadrant_t* q = nullptr;
    std::uint8_t filled = 0;
    std::int64_t tree = -1;
  };
  // Pixel (i, j) with 0 <= i < nx, 0 <= j < ny.
  [[nodiscard]] Found find(std::int64_t i, std::int64_t j) const {
    const int L = brick_.lattice().levels;
    Found out;
    const std::int64_t t = brick_.tree(i >> L, j >> L);
    p4est_quadrant_t q;
    std::int64_t tt = 0;
    brick_.quadrant(Square{L, i, j}, tt, q);
    out.tree = t;
    if (t >= f_->first_local_tree && t <= f_->last_local_tree) {
      const auto* tree = static_cast<const p4est_tree_t*>(sc_array_index(f_->trees, static_cast<size_t>(t)));
      const std::int64_t k = containing(tree->quadrants, 0, tree->quadrants.elem_count, q);
      if (k >= 0) {
        out.local = true;
        out.index = tree->quadrants_offset + k;
        out.q = quadrant_at(tree->quadrants, static_cast<std::size_t>(k));
        out.filled = static_cast<std::uint8_t>(flag(out.q) & 1);
      }
      return out;
    }
    const auto first = static_cast<std::size_t>(ghost_->tree_offsets[t]);
    const auto last = static_cast<std::size_t>(ghost_->tree_offsets[t + 1]);
    const std::int64_t g = containing(ghost_->ghosts, first, last, q);
    if (g >= 0) {
      out.index = g;
      out.q = quadrant_at(ghost_->ghosts, static_cast<std::size_t>(g));
      out.filled = static_cast<std::uint8_t>(flags_[static_cast<std::size_t>(g)] & 1);
    }
    return out;
  }
  [[nodiscard]] int owner(std::int64_t ghost_index, int ranks) const {
    int r = 0;
    while (r + 1 < ranks && ghost_->proc_offsets[r + 1] <= ghost_index) ++r;
    return r;
  }

 private:
  p4est_t* f_;
  const LatticeBrick& brick_;
  GhostPtr ghost_;
  std::vector<std::uint8_t> flags_;
};

}  // namespace

MeshForest::MeshForest(const LatticeBrick& brick, const Comm& comm, const ForestPyramid& pyramid)
    : brick_(brick), comm_(comm) {
  const int levels = brick.lattice().levels;
  forest_.reset(p4est_new_ext(comm.get(), brick.connectivity(), 0, 0, 1, sizeof(std::uint8_t), nullptr, nullptr));
  partition_by_trees(forest_.get(), {}, std::vector<std::int64_t>(static_cast<std::size_t>(brick.trees()), 1));
  RefineContext ctx{&brick, &pyramid, levels};
  forest_->user_pointer = &ctx;
  p4est_refine_ext(forest_.get(), 1, levels, refine_from_pyramid, nullptr, nullptr);
  forest_->user_pointer = nullptr;
  // Flags: a leaf of the pyramid is filled exactly when it is in omega (else it holds no filled pixel).
  p4est_t* f = forest_.get();
  for (p4est_topidx_t t = f->first_local_tree; t <= f->last_local_tree && t >= 0; ++t) {
    auto* tree = static_cast<p4est_tree_t*>(sc_array_index(f->trees, static_cast<size_t>(t)));
    for (size_t k = 0; k < tree->quadrants.elem_count; ++k) {
      auto* q = static_cast<p4est_quadrant_t*>(sc_array_index(&tree->quadrants, k));
      const Square s = brick.square(t, *q);
      flag(q) = pyramid.omega(s.level, s.a, s.b) ? 1 : 0;
    }
  }
}

std::int64_t MeshForest::violations(quadtree::BalanceMode mode, bool mark, std::vector<char>* marks) const {
  p4est_t* f = forest_.get();
  const Lookup lookup(f, brick_);
  const Lattice& lat = brick_.lattice();
  const bool corner = mode == quadtree::BalanceMode::kCorner;
  std::int64_t count = 0;
  std::vector<std::vector<std::int64_t>> requests(static_cast<std::size_t>(comm_.size()));
  const auto find = [&lookup](std::int64_t i, std::int64_t j) { return lookup.find(i, j); };
  for (p4est_topidx_t t = f->first_local_tree; t <= f->last_local_tree && t >= 0; ++t) {
    const auto* tree = static_cast<const p4est_tree_t*>(sc_array_index(f->trees, static_cast<size_t>(t)));
    for (size_t k = 0; k < tree->quadrants.elem_count; ++k) {
      const p4est_quadrant_t* q = quadrant_at(tree->quadrants, k);
      if ((flag(q) & 1) == 0 || q->level < 2) continue;
      const Square s = brick_.square(t, *q);
      const std::int64_t size = lat.pixels_per_square(s.level);
      const std::int64_t i0 = s.a * size, j0 = s.b * size;
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || (!corner && dx != 0 && dy != 0)) continue;
          const std::int64_t j = j0 + dy * size;
          std::int64_t i = i0 + dx * size;
          if (j < 0 || j >= lat.ny) continue;
          if (i < 0 || i >= lat.nx) {
            if (!brick_.periodic()) continue;
            i = wrap_index(i, lat.nx);
          }
          const Lookup::Found c = find(i, j);
          // A leaf neither local nor a ghost does not touch this leaf: it is finer than the
          // neighbour square (a coarser or equal one would touch), so no violation.
          if (c.q == nullptr) continue;
          if (c.filled == 0 || c.q->level > s.level - 2) continue;
          ++count;
          if (!mark) continue;
          if (c.local) {
            (*marks)[static_cast<std::size_t>(c.index)] = 1;
          } else {
            auto& r = requests[static_cast<std::size_t>(lookup.owner(c.index, comm_.size()))];
            r.push_back(c.tree);
            r.push_back(c.q->x);
            r.push_back(c.q->y);
            r.push_back(c.q->level);
          }
        }
    }
  }
  if (mark) {
    const auto got = comm_.alltoallv(requests);
    for (const auto& r : got)
      for (std::size_t m = 0; m + 3 < r.size(); m += 4) {
        const auto t = static_cast<p4est_topidx_t>(r[m]);
        p4est_quadrant_t q;
        P4EST_QUADRANT_INIT(&q);
        q.x = static_cast<p4est_qcoord_t>(r[m + 1]);
        q.y = static_cast<p4est_qcoord_t>(r[m + 2]);
        q.level = static_cast<std::int8_t>(r[m + 3]);
        const auto* tree = static_cast<const p4est_tree_t*>(sc_array_index(f->trees, static_cast<size_t>(t)));
        const std::int64_t k = containing(tree->quadrants, 0, tree->quadrants.elem_count, q);
        if (k < 0 || quadrant_at(tree->quadrants, static_cast<std::size_t>(k))->level != q.level)
          throw InternalError("forest balance: a split request names no local leaf");
        (*marks)[static_cast<std::size_t>(tree->quadrants_offset + k)] = 1;
      }
  }
  return count;
}

MeshForest::BalanceResult MeshForest::balance(quadtree::BalanceMode mode, bool p4est_equivalent) {
  BalanceResult r;
  p4est_t* f = forest_.get();
  if (p4est_equivalent) {
    r.used_p4est = true;
    const p4est_gloidx_t before = f->global_num_quadrants;
    p4est_balance_ext(f, mode == quadtree::BalanceMode::kCorner ? P4EST_CONNECT_FULL : P4EST_CONNECT_FACE, nullptr,
                      copy_flag);
    r.forced_splits = static_cast<std::int64_t>((f->global_num_quadrants - before) / 3);
    r.rounds = 1;
    return r;
  }
  while (true) {
    std::vector<char> marks(static_cast<std::size_t>(f->local_num_quadrants), 0);
    violations(mode, true, &marks);
    std::int64_t marked = 0;
    for (const char m : marks) marked += m;
    marked = comm_.sum(marked);
    if (marked == 0) break;
    r.forced_splits += marked;
    ++r.rounds;
    // Split the marked leaves once (bit 2 of the flag; their children keep bit 1, filled).
    std::int64_t k = 0;
    for (p4est_topidx_t t = f->first_local_tree; t <= f->last_local_tree && t >= 0; ++t) {
      auto* tree = static_cast<p4est_tree_t*>(sc_array_index(f->trees, static_cast<size_t>(t)));
      for (size_t m = 0; m < tree->quadrants.elem_count; ++m, ++k) {
        auto* q = static_cast<p4est_quadrant_t*>(sc_array_index(&tree->quadrants, m));
        if (marks[static_cast<std::size_t>(k)] != 0) flag(q) |= 2;
      }
    }
    p4est_refine_ext(
        f, 0, -1, [](p4est_t*, p4est_topidx_t, p4est_quadrant_t* q) -> int { return (flag(q) & 2) != 0 ? 1 : 0; },
        nullptr, copy_flag);
  }
  return r;
}

std::int64_t MeshForest::count_violations(quadtree::BalanceMode mode) const {
  return comm_.sum(violations(mode, false, nullptr));
}

std::vector<quadtree::Leaf> MeshForest::local_leaves() const {
  std::vector<quadtree::Leaf> out;
  p4est_t* f = forest_.get();
  for (p4est_topidx_t t = f->first_local_tree; t <= f->last_local_tree && t >= 0; ++t) {
    const auto* tree = static_cast<const p4est_tree_t*>(sc_array_index(f->trees, static_cast<size_t>(t)));
    for (size_t k = 0; k < tree->quadrants.elem_count; ++k) {
      const p4est_quadrant_t* q = quadrant_at(tree->quadrants, k);
      if ((flag(q) & 1) == 0) continue;
      const Square s = brick_.square(t, *q);
      out.push_back(quadtree::Leaf{s.level, s.a, s.b});
    }
  }
  return out;
}

std::vector<quadtree::LeafNeighbourhood> MeshForest::local_neighbourhoods() const {
  p4est_t* f = forest_.get();
  const Lookup lookup(f, brick_);
  const Lattice& lat = brick_.lattice();
  const std::int64_t nx = lat.nx, ny = lat.ny;
  const bool periodic = brick_.periodic();
  // The filled local leaves in order.
  std::vector<Square> sq;
  for (p4est_topidx_t t = f->first_local_tree; t <= f->last_local_tree && t >= 0; ++t) {
    const auto* tree = static_cast<const p4est_tree_t*>(sc_array_index(f->trees, static_cast<size_t>(t)));
    for (size_t k = 0; k < tree->quadrants.elem_count; ++k) {
      const p4est_quadrant_t* q = quadrant_at(tree->quadrants, k);
      if ((flag(q) & 1) != 0) sq.push_back(brick_.square(t, *q));
    }
  }
  std::vector<quadtree::LeafNeighbourhood> out(sq.size());
  // The leaf holding pixel (i, j) (columns wrapped on a periodic lattice); null outside the lattice
  // and beyond a window lattice's columns (its padding: never filled, as the dense bitmaps wrap onto).
  const auto leaf_at = [&](std::int64_t i, std::int64_t j, Square& s) {
    if (j < 0 || j >= ny) return false;
    if (i < 0 || i >= nx) {
      if (!periodic) return false;
      i = wrap_index(i, nx);
    }
    const Lookup::Found c = lookup.find(i, j);
    if (c.q == nullptr) throw InternalError("forest nodes: a neighbour leaf is neither local nor a ghost");
    if (c.filled == 0) return false;
    s = brick_.square(c.tree, *c.q);
    return true;
  };
  const auto filled = [&](std::int64_t i, std::int64_t j) {
    Square s;
    return leaf_at(i, j, s);
  };
  // Whether square `s` has its corner `c` (0 SW, 1 SE, 2 NE, 3 NW) at vertex (I, J).
  const auto has_corner = [&](const Square& s, int c, std::int64_t I, std::int64_t J) {
    const std::int64_t z = lat.pixels_per_square(s.level);
    const std::int64_t x = s.a * z + ((c == 1 || c == 2) ? z : 0), y = s.b * z + (c >= 2 ? z : 0);
    return wrap_index(x, nx) == wrap_index(I, nx) && y == J;
  };
  const auto corner_at = [&](std::int64_t i, std::int64_t j, int c, std::int64_t I, std::int64_t J) {
    Square s;
    return leaf_at(i, j, s) && has_corner(s, c, I, J);
  };
  // Every answer is the one of looking up each pixel the rules name (quadtree::leaf_neighbourhoods),
  // with fewer lookups (binary searches over the quadrants, most of this stage's time): the 8
  // neighbour pixels are looked up once and reused; a side whose outer midside pixel lies in a
  // filled leaf as large as this one or larger has no hanging node (that leaf spans the whole side,
  // and its corners are multiples of its size, which the side's midpoint is not); at each corner,
  // one of the 4 pixels is this leaf's own (filled), so a pinch needs the 2 next to it unfilled,
  // and those are asked first.
  const auto n = static_cast<std::int64_t>(sq.size());
#pragma omp parallel for default(none) shared(sq, out, lat, n, ny, filled, corner_at, has_corner, leaf_at) \
    schedule(dynamic, 256)
  for (std::int64_t k = 0; k < n; ++k) {
    const Square& s = sq[static_cast<std::size_t>(k)];
    const std::int64_t z = lat.pixels_per_square(s.level), i0 = s.a * z, j0 = s.b * z, h = z / 2;
    quadtree::LeafNeighbourhood& nb = out[static_cast<std::size_t>(k)];
    const std::int64_t px[8][2] = {{i0, j0 - 1},     {i0 + h, j0 - 1}, {i0 + z, j0},     {i0 + z, j0 + h},
                                   {i0 + h, j0 + z}, {i0, j0 + z},     {i0 - 1, j0 + h}, {i0 - 1, j0}};
    std::array<Square, 8> ns{};
    std::array<bool, 8> cov{};
    for (int b = 0; b < 8; ++b) {
      cov[static_cast<std::size_t>(b)] = leaf_at(px[b][0], px[b][1], ns[static_cast<std::size_t>(b)]);
      if (cov[static_cast<std::size_t>(b)]) nb.covered = static_cast<std::uint8_t>(nb.covered | (1U << b));
    }
    if (z >= 2) {
      // side: its outer midside pixel px[m], the corner `cm` of that pixel's leaf at the midpoint
      // (I, J), and the pixel beside px[m] whose leaf's corner `cb` would be there instead.
      struct Side {
        int m, cm, cb;
        std::int64_t bi, bj, I, J;
        std::uint8_t bit;
      };
      const std::array<Side, 4> sides{{{1, 3, 2, i0 + h - 1, j0 - 1, i0 + h, j0, quadtree::kSideS},
                                       {3, 0, 3, i0 + z, j0 + h - 1, i0 + z, j0 + h, quadtree::kSideE},
                                       {4, 0, 1, i0 + h - 1, j0 + z, i0 + h, j0 + z, quadtree::kSideN},
                                       {6, 1, 2, i0 - 1, j0 + h - 1, i0, j0 + h, quadtree::kSideW}}};
      for (const Side& d : sides) {
        const auto m = static_cast<std::size_t>(d.m);
        const bool coarse = cov[m] && ns[m].level <= s.level;
        if ((cov[m] && has_corner(ns[m], d.cm, d.I, d.J)) || (!coarse && corner_at(d.bi, d.bj, d.cb, d.I, d.J)))
          nb.midside |= d.bit;
      }
    }
    // Corner c's pinch: the 2 pixels beside this leaf's own unfilled, the one across filled.
    if (j0 > 0) {
      if (!cov[7] && !cov[0] && filled(i0 - 1, j0 - 1)) nb.pinch |= 1U;                      // SW
      if (!cov[2] && !filled(i0 + z - 1, j0 - 1) && filled(i0 + z, j0 - 1)) nb.pinch |= 2U;  // SE
    }
    if (j0 + z < ny) {
      if (!filled(i0 + z - 1, j0 + z) && !filled(i0 + z, j0 + z - 1) && filled(i0 + z, j0 + z)) nb.pinch |= 4U;  // NE
      if (!cov[5] && !filled(i0 - 1, j0 + z - 1) && filled(i0 - 1, j0 + z)) nb.pinch |= 8U;                      // NW
    }
  }
  return out;
}

std::vector<std::int64_t> MeshForest::leaves_per_level() const {
  std::vector<std::int64_t> n(static_cast<std::size_t>(brick_.lattice().levels) + 1, 0);
  p4est_t* f = forest_.get();
  for (p4est_topidx_t t = f->first_local_tree; t <= f->last_local_tree && t >= 0; ++t) {
    const auto* tree = static_cast<const p4est_tree_t*>(sc_array_index(f->trees, static_cast<size_t>(t)));
    for (size_t k = 0; k < tree->quadrants.elem_count; ++k) {
      const p4est_quadrant_t* q = quadrant_at(tree->quadrants, k);
      if ((flag(q) & 1) != 0) ++n[static_cast<std::size_t>(q->level)];
    }
  }
  comm_.sum_in_place(n);
  return n;
}

std::int64_t MeshForest::quadrants() const { return static_cast<std::int64_t>(forest_->global_num_quadrants); }

std::int64_t MeshForest::memory_bytes() const { return static_cast<std::int64_t>(p4est_memory_used(forest_.get())); }

}  // namespace aq::forest
