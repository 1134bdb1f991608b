// SPDX-License-Identifier: GPL-3.0-or-later
// The lattice's brick of trees (see lattice_forest.hpp).
#include "forest/lattice_forest.hpp"

#include <fmt/format.h>
#include <p4est_algorithms.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace aq::forest {

LatticeBrick::LatticeBrick(const Lattice& lat) : lat_(lat) {
  nx0_ = lat.nx >> lat.levels;
  ny0_ = lat.ny >> lat.levels;
  periodic_ = lat.periodic();
  if (nx0_ < 1 || ny0_ < 1 || (nx0_ << lat.levels) != lat.nx || (ny0_ << lat.levels) != lat.ny)
    throw InternalError(fmt::format("forest: the {} x {} lattice is not whole level-0 squares of {} pixels", lat.nx,
                                    lat.ny, lat.pixels_per_square(0)));
  if (nx0_ * ny0_ > std::numeric_limits<p4est_topidx_t>::max())
    throw ConfigError(
        fmt::format("quadtree.engine = \"forest\": {} x {} level-0 squares are more trees than p4est "
                    "numbers; a larger quadtree.step_deg",
                    nx0_, ny0_));
  conn_.reset(p4est_connectivity_new_brick(static_cast<int>(nx0_), static_cast<int>(ny0_), periodic_ ? 1 : 0, 0));
  // Tree t of the brick has its lower-left vertex at (a0, b0): the new index is b0·nx0 + a0.
  p4est_connectivity_t* c = conn_.get();
  const auto n = static_cast<std::size_t>(c->num_trees);
  sc_array_t* perm = sc_array_new_count(sizeof(size_t), n);
  std::vector<char> seen(n, 0);
  for (std::size_t t = 0; t < n; ++t) {
    const p4est_topidx_t v = c->tree_to_vertex[4 * t];
    const auto a0 = static_cast<std::int64_t>(std::llround(c->vertices[3 * v]));
    const auto b0 = static_cast<std::int64_t>(std::llround(c->vertices[3 * v + 1]));
    const auto to = static_cast<std::size_t>(b0 * nx0_ + a0);
    if (a0 < 0 || a0 >= nx0_ || b0 < 0 || b0 >= ny0_ || seen[to] != 0) {
      sc_array_destroy(perm);
      throw InternalError("forest: the brick's trees are not the level-0 squares");
    }
    seen[to] = 1;
    *static_cast<size_t*>(sc_array_index(perm, t)) = to;
  }
  p4est_connectivity_permute(c, perm, 1);
  sc_array_destroy(perm);
}

Square LatticeBrick::square(std::int64_t t, const p4est_quadrant_t& q) const {
  const int l = q.level;
  const int shift = P4EST_MAXLEVEL - l;
  return Square{l, (tree_a0(t) << l) + (static_cast<std::int64_t>(q.x) >> shift),
                (tree_b0(t) << l) + (static_cast<std::int64_t>(q.y) >> shift)};
}

void LatticeBrick::quadrant(const Square& s, std::int64_t& tree, p4est_quadrant_t& q) const {
  const int l = s.level;
  const std::int64_t a0 = s.a >> l, b0 = s.b >> l;
  tree = this->tree(a0, b0);
  const int shift = P4EST_MAXLEVEL - l;
  P4EST_QUADRANT_INIT(&q);
  q.level = static_cast<std::int8_t>(l);
  q.x = static_cast<p4est_qcoord_t>((s.a - (a0 << l)) << shift);
  q.y = static_cast<p4est_qcoord_t>((s.b - (b0 << l)) << shift);
}

ForestPtr uniform_forest(const LatticeBrick& brick, const Comm& comm, int level) {
  ForestPtr f(p4est_new_ext(comm.get(), brick.connectivity(), 0, level, 1, 0, nullptr, nullptr));
  const std::int64_t per_tree = std::int64_t{1} << (2 * level);
  partition_by_trees(f.get(), {}, std::vector<std::int64_t>(static_cast<std::size_t>(brick.trees()), per_tree));
  return f;
}

void partition_by_trees(p4est_t* forest, const std::vector<double>& tree_weight,
                        const std::vector<std::int64_t>& tree_quadrants) {
  const int size = forest->mpisize;
  const std::size_t trees = tree_quadrants.size();
  double total = 0.0;
  for (std::size_t t = 0; t < trees; ++t) total += tree_weight.empty() ? 1.0 : tree_weight[t];
  std::vector<p4est_locidx_t> counts(static_cast<std::size_t>(size), 0);
  double before = 0.0;
  for (std::size_t t = 0; t < trees; ++t) {
    const double w = tree_weight.empty() ? 1.0 : tree_weight[t];
    int r = total > 0.0 ? static_cast<int>(std::floor(before / total * size)) : 0;
    r = std::clamp(r, 0, size - 1);
    const std::int64_t c = counts[static_cast<std::size_t>(r)] + tree_quadrants[t];
    if (c > std::numeric_limits<p4est_locidx_t>::max())
      throw InternalError("forest: more quadrants on one rank than p4est numbers locally");
    counts[static_cast<std::size_t>(r)] = static_cast<p4est_locidx_t>(c);
    before += w;
  }
  p4est_partition_given(forest, counts.data());
}

std::vector<std::int64_t> quadrants_per_tree(p4est_t* forest, const Comm& comm) {
  std::vector<std::int64_t> n(static_cast<std::size_t>(forest->connectivity->num_trees), 0);
  for (p4est_topidx_t t = forest->first_local_tree; t <= forest->last_local_tree && t >= 0; ++t) {
    const auto* tree = static_cast<const p4est_tree_t*>(sc_array_index(forest->trees, static_cast<size_t>(t)));
    n[static_cast<std::size_t>(t)] = static_cast<std::int64_t>(tree->quadrants.elem_count);
  }
  comm.sum_in_place(n);
  return n;
}

void local_tree_range(const p4est_t* forest, std::int64_t& first, std::int64_t& last) {
  first = forest->first_local_tree;
  last = forest->last_local_tree + 1;
  if (forest->first_local_tree < 0) first = last = 0;
}

}  // namespace aq::forest
