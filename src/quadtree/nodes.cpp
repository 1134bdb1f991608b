// SPDX-License-Identifier: GPL-3.0-or-later
// Node numbering, midside nodes, boundary loops and pinches of a balanced quadtree (see nodes.hpp).
#include "quadtree/nodes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <limits>

#include "core/error.hpp"
#include "quadtree/bits.hpp"
#include "quadtree/parallel.hpp"

namespace aq::quadtree {

namespace {

/// Row-major vertex bitmap (nx × (ny+1) vertices) with O(1) rank: the node id of a marked vertex.
class VertexRank {
 public:
  VertexRank(std::int64_t nx, std::int64_t ny) : vb_(nx, ny + 1) {}

  Bitmap& bitmap() { return vb_; }
  [[nodiscard]] const Bitmap& bitmap() const { return vb_; }

  /// Builds the rank tables; returns the number of marked vertices.
  std::int64_t build() {
    const std::int64_t rows = vb_.ny();
    const std::int64_t words = vb_.words_per_row();
    prefix_.assign(static_cast<std::size_t>(rows * words), 0U);
    row_base_.assign(static_cast<std::size_t>(rows), 0);
#pragma omp parallel for default(none) if (quadtree::parallel_worth(rows * words)) shared(rows, words) schedule(static)
    for (std::int64_t j = 0; j < rows; ++j) {
      const std::uint64_t* r = vb_.row(j);
      std::uint32_t run = 0;
      for (std::int64_t w = 0; w < words; ++w) {
        prefix_[static_cast<std::size_t>(j * words + w)] = run;
        run += static_cast<std::uint32_t>(bits::popcount64(r[w]));
      }
      row_base_[static_cast<std::size_t>(j)] = run;
    }
    return exclusive_scan_in_place(row_base_);
  }

  /// Node id of vertex (i, j) (i in [0, nx)); the vertex must be marked.
  [[nodiscard]] NodeId rank(std::int64_t i, std::int64_t j) const {
    const std::int64_t w = i >> 6;
    const std::uint64_t below = vb_.row(j)[w] & ((1ULL << (i & 63)) - 1ULL);
    return row_base_[static_cast<std::size_t>(j)] + prefix_[static_cast<std::size_t>(j * vb_.words_per_row() + w)] +
           bits::popcount64(below);
  }
  [[nodiscard]] std::int64_t row_base(std::int64_t j) const { return row_base_[static_cast<std::size_t>(j)]; }

 private:
  Bitmap vb_;
  std::vector<std::uint32_t> prefix_;   ///< set bits in the row before each word
  std::vector<std::int64_t> row_base_;  ///< set bits before each row
};

/// Leaf geometry in lattice units.
struct Box {
  std::int64_t i0, j0, s;
};
Box box_of(const Lattice& lat, const Leaf& f) { return Box{leaf_i0(lat, f), leaf_j0(lat, f), leaf_size(lat, f)}; }

/// Whether pixel (i mod nx, j) is filled; rows outside [0, ny) are not.
bool covered(const Bitmap& cov, std::int64_t i, std::int64_t j) {
  if (j < 0 || j >= cov.ny()) return false;
  return cov.get(wrap_index(i, cov.nx()), j);
}

/// The 8 "filled across" bits of a leaf (LeafNeighbourhood::covered) from a coverage bitmap.
std::uint8_t covered_bits(const Bitmap& cov, const Box& q) {
  const std::int64_t h = q.s / 2;
  const std::array<std::array<std::int64_t, 2>, 8> px{{{q.i0, q.j0 - 1},
                                                       {q.i0 + h, q.j0 - 1},
                                                       {q.i0 + q.s, q.j0},
                                                       {q.i0 + q.s, q.j0 + h},
                                                       {q.i0 + h, q.j0 + q.s},
                                                       {q.i0, q.j0 + q.s},
                                                       {q.i0 - 1, q.j0 + h},
                                                       {q.i0 - 1, q.j0}}};
  std::uint8_t bits = 0;
  for (std::size_t k = 0; k < 8; ++k)
    if (covered(cov, px[k][0], px[k][1])) bits = static_cast<std::uint8_t>(bits | (1U << k));
  return bits;
}

/// Boundary edges of one leaf, in side order S, E, N, W, from its "filled across" bits
/// (LeafNeighbourhood::covered); writes up to 8 edges, returns the count.
int leaf_boundary(std::uint8_t across, const std::array<NodeId, 4>& c, const std::array<NodeId, 4>& m,
                  std::array<NodeId, 2>* out) {
  int n = 0;
  auto emit = [&](NodeId a, NodeId b) { out[n++] = {a, b}; };
  const auto in = [across](int k) { return ((across >> k) & 1U) != 0; };
  // S: across is row j0 - 1; runs SW -> SE.
  if (m[0] < 0) {
    if (!in(0)) emit(c[0], c[1]);
  } else {
    if (!in(0)) emit(c[0], m[0]);
    if (!in(1)) emit(m[0], c[1]);
  }
  // E: across is column i0 + s; runs SE -> NE.
  if (m[1] < 0) {
    if (!in(2)) emit(c[1], c[2]);
  } else {
    if (!in(2)) emit(c[1], m[1]);
    if (!in(3)) emit(m[1], c[2]);
  }
  // N: across is row j0 + s; runs NE -> NW.
  if (m[2] < 0) {
    if (!in(5)) emit(c[2], c[3]);
  } else {
    if (!in(4)) emit(c[2], m[2]);
    if (!in(5)) emit(m[2], c[3]);
  }
  // W: across is column i0 - 1; runs NW -> SW.
  if (m[3] < 0) {
    if (!in(7)) emit(c[3], c[0]);
  } else {
    if (!in(6)) emit(c[3], m[3]);
    if (!in(7)) emit(m[3], c[0]);
  }
  return n;
}

int sign(std::int64_t v) { return (v > 0) - (v < 0); }

}  // namespace

std::vector<std::array<std::int64_t, 2>> find_pinches(const Bitmap& filled) {
  const std::int64_t nx = filled.nx();
  const std::int64_t ny = filled.ny();
  const std::int64_t words = filled.words_per_row();
  const std::int64_t rows = ny > 1 ? ny - 1 : 0;
  const int blocks = block_count(rows, 4 * words);
  std::vector<std::vector<std::array<std::int64_t, 2>>> parts(static_cast<std::size_t>(blocks));
  for_each_block(rows, blocks, [&](int t, std::int64_t begin, std::int64_t end) {
    std::vector<std::uint64_t> aw(static_cast<std::size_t>(words)), bw(static_cast<std::size_t>(words));
    std::vector<std::array<std::int64_t, 2>>& out = parts[static_cast<std::size_t>(t)];
    for (std::int64_t jj = begin; jj < end; ++jj) {
      const std::int64_t j = jj + 1;
      // Vertex (I, J): NE pixel (I, J), NW (I-1, J), SE (I, J-1), SW (I-1, J-1).
      const std::uint64_t* ne = filled.row(j);
      const std::uint64_t* se = filled.row(j - 1);
      bits::rotate_row(ne, aw.data(), nx, 1);
      bits::rotate_row(se, bw.data(), nx, 1);
      for (std::int64_t w = 0; w < words; ++w) {
        const std::size_t k = static_cast<std::size_t>(w);
        const std::uint64_t nw = aw[k], sw = bw[k];
        std::uint64_t p = (ne[w] & sw & ~nw & ~se[w]) | (nw & se[w] & ~ne[w] & ~sw);
        while (p != 0) {
          out.push_back({64 * w + std::countr_zero(p), j});
          p &= p - 1;
        }
      }
    }
  });
  std::vector<std::array<std::int64_t, 2>> all;
  for (int t = 0; t < blocks; ++t) {
    const auto& p = parts[static_cast<std::size_t>(t)];
    all.insert(all.end(), p.begin(), p.end());
  }
  return all;
}

// Steps 6 and 7 of the numbering: the boundary edges of every leaf (from its "filled across" bits),
// their node flags, and the loops they form (at a pinch a loop takes the left turn).
static void add_boundary(QuadNodes& out, const std::vector<std::uint8_t>& across, std::int64_t nx, std::int64_t ny) {
  const auto nleaves = static_cast<std::int64_t>(out.corners.size());
  const std::int64_t nnodes = out.node_count();
  std::vector<std::array<NodeId, 2>> edges;
  {
    const int blocks = block_count(nleaves, 8);
    std::vector<std::int64_t> block_edges(static_cast<std::size_t>(blocks), 0);
    std::vector<std::uint8_t> per_leaf(static_cast<std::size_t>(nleaves));
    for_each_block(nleaves, blocks, [&](int t, std::int64_t begin, std::int64_t end) {
      std::array<std::array<NodeId, 2>, 8> buf{};
      std::int64_t n = 0;
      for (std::int64_t f = begin; f < end; ++f) {
        const auto k = static_cast<std::size_t>(f);
        const int c = leaf_boundary(across[k], out.corners[k], out.midside[k], buf.data());
        per_leaf[k] = static_cast<std::uint8_t>(c);
        n += c;
      }
      block_edges[static_cast<std::size_t>(t)] = n;
    });
    const std::int64_t total = exclusive_scan_in_place(block_edges);
    edges.resize(static_cast<std::size_t>(total));
    for_each_block(nleaves, blocks, [&](int t, std::int64_t begin, std::int64_t end) {
      auto pos = static_cast<std::size_t>(block_edges[static_cast<std::size_t>(t)]);
      for (std::int64_t f = begin; f < end; ++f) {
        const auto k = static_cast<std::size_t>(f);
        if (per_leaf[k] == 0) continue;
        pos += static_cast<std::size_t>(leaf_boundary(across[k], out.corners[k], out.midside[k], &edges[pos]));
      }
    });
  }
  for (const auto& e : edges) {
    out.node_flags[static_cast<std::size_t>(e[0])] |= kBoundaryNode;
    out.node_flags[static_cast<std::size_t>(e[1])] |= kBoundaryNode;
  }

  // 7. Loops: follow each edge's successor; at a pinch take the left turn.
  const auto delta_i = [&](const std::array<NodeId, 2>& e) {  // seam-unwrapped I difference
    std::int64_t dx = out.node_i[static_cast<std::size_t>(e[1])] - out.node_i[static_cast<std::size_t>(e[0])];
    if (dx > nx / 2) dx -= nx;
    if (dx < -nx / 2) dx += nx;
    return dx;
  };
  const auto direction = [&](const std::array<NodeId, 2>& e) {
    const std::int64_t dy = out.node_j[static_cast<std::size_t>(e[1])] - out.node_j[static_cast<std::size_t>(e[0])];
    return std::array<int, 2>{sign(delta_i(e)), sign(dy)};
  };
  // Outgoing boundary edges of every node: one, or two at a pinch (kept in the order of their end node).
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  if (edges.size() >= kNone) throw InternalError("quadtree nodes: too many boundary edges");
  std::vector<std::uint32_t> out1(static_cast<std::size_t>(nnodes), kNone),
      out2(static_cast<std::size_t>(nnodes), kNone);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto a = static_cast<std::size_t>(edges[e][0]);
    if (out1[a] == kNone) {
      out1[a] = static_cast<std::uint32_t>(e);
    } else if (out2[a] == kNone) {
      out2[a] = static_cast<std::uint32_t>(e);
      if (edges[out2[a]][1] < edges[out1[a]][1]) std::swap(out1[a], out2[a]);
    } else {
      throw InternalError(fmt::format("quadtree nodes: node {} has more than two outgoing boundary edges", a));
    }
  }
  const auto successor = [&](std::size_t e) -> std::size_t {
    const auto b = static_cast<std::size_t>(edges[e][1]);
    if (out1[b] != kNone && out2[b] == kNone) return out1[b];
    if (out2[b] != kNone) {
      const std::array<int, 2> in = direction(edges[e]);
      const std::array<int, 2> left{-in[1], in[0]};
      if (direction(edges[out1[b]]) == left) return out1[b];
      if (direction(edges[out2[b]]) == left) return out2[b];
    }
    throw InternalError(
        fmt::format("quadtree nodes: boundary at node {} (I {}, J {}) has {} outgoing edges and no left turn (leaves "
                    "not balanced?)",
                    b, out.node_i[b], out.node_j[b], (out1[b] != kNone) + (out2[b] != kNone)));
  };
  // Loops start from the unused edge with the smallest (a, b).
  std::vector<std::uint32_t> order;
  order.reserve(edges.size());
  for (std::size_t v = 0; v < out1.size(); ++v) {
    if (out1[v] != kNone) order.push_back(out1[v]);
    if (out2[v] != kNone) order.push_back(out2[v]);
  }
  std::vector<std::uint8_t> used(edges.size(), 0);
  out.boundary_edges.reserve(edges.size());
  out.boundary_edge_loop.reserve(edges.size());
  struct Extent {
    std::int64_t area = 0, edges = 0;
  };
  std::vector<Extent> extents;
  for (const std::uint32_t first : order) {
    const std::size_t e0 = first;
    if (used[e0] != 0) continue;
    const auto id = static_cast<std::int32_t>(out.loops.size());
    LoopInfo info;
    info.first_edge = static_cast<std::int64_t>(out.boundary_edges.size());
    std::int64_t x = out.node_i[static_cast<std::size_t>(edges[e0][0])];
    const std::int64_t x_start = x;
    std::int64_t xmin = x, xmax = x;
    std::int64_t ymin = std::numeric_limits<std::int64_t>::max(), ymax = std::numeric_limits<std::int64_t>::min();
    bool all_south = true, all_north = true;
    std::size_t e = e0;
    do {
      if (used[e] != 0) {
        throw InternalError(fmt::format("quadtree nodes: boundary loop {} meets edge {} twice", id, e));
      }
      used[e] = 1;
      out.boundary_edges.push_back(edges[e]);
      out.boundary_edge_loop.push_back(id);
      const std::int64_t y = out.node_j[static_cast<std::size_t>(edges[e][0])];
      ymin = std::min(ymin, y);
      ymax = std::max(ymax, y);
      all_south = all_south && y == 0;
      all_north = all_north && y == ny;
      x += delta_i(edges[e]);
      xmin = std::min(xmin, x);
      xmax = std::max(xmax, x);
      e = successor(e);
    } while (e != e0);
    info.edge_count = static_cast<std::int64_t>(out.boundary_edges.size()) - info.first_edge;
    info.pole = all_south || all_north;
    const std::int64_t width = (x != x_start) ? nx : (xmax - xmin);
    extents.push_back(Extent{width * (ymax - ymin), info.edge_count});
    out.loops.push_back(info);
  }
  if (!out.loops.empty()) {
    std::size_t best = 0;
    for (std::size_t k = 1; k < extents.size(); ++k) {
      if (extents[k].area > extents[best].area ||
          (extents[k].area == extents[best].area && extents[k].edges > extents[best].edges)) {
        best = k;
      }
    }
    out.loops[best].outer = true;
  }
}

QuadNodes build_nodes(const std::vector<Leaf>& leaves, const Lattice& lat, const NodeOptions& options) {
  bool sorted = false;
  const Bitmap cov = leaf_coverage(leaves, lat, &sorted);
  if (!sorted) throw InternalError("quadtree nodes: leaves are not in the deterministic order");
  const std::int64_t nx = lat.nx;
  const std::int64_t ny = lat.ny;
  const auto nleaves = static_cast<std::int64_t>(leaves.size());
  const std::vector<std::int64_t> starts = root_row_starts(leaves, lat);
  const std::int64_t ny0 = static_cast<std::int64_t>(starts.size()) - 1;

  // 1. Corners. Leaves of level-0 row b0 touch vertex rows b0·S0 .. (b0+1)·S0: even rows of
  //    level-0 squares first, then odd ones, so no two threads write the same word.
  VertexRank vr(nx, ny);
  Bitmap& vb = vr.bitmap();
  for (std::int64_t phase = 0; phase < 2; ++phase) {
    const std::int64_t count = (ny0 - phase + 1) / 2;
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nleaves * 4)) \
    shared(leaves, lat, vb, starts, phase, count, nx) schedule(dynamic, 1)
    for (std::int64_t k = 0; k < count; ++k) {
      const std::int64_t b0 = 2 * k + phase;
      for (std::int64_t f = starts[static_cast<std::size_t>(b0)]; f < starts[static_cast<std::size_t>(b0) + 1]; ++f) {
        const Box q = box_of(lat, leaves[static_cast<std::size_t>(f)]);
        const std::int64_t i1 = wrap_index(q.i0 + q.s, nx);
        vb.set(q.i0, q.j0);
        vb.set(i1, q.j0);
        vb.set(i1, q.j0 + q.s);
        vb.set(q.i0, q.j0 + q.s);
      }
    }
  }

  // 2. Midside codes: the midpoint of a side is a node exactly when a finer neighbour has a corner there.
  QuadNodes out;
  out.midside_code.assign(static_cast<std::size_t>(nleaves), 0);
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nleaves * 4)) \
    shared(leaves, lat, vb, out, nleaves, nx) schedule(static)
  for (std::int64_t f = 0; f < nleaves; ++f) {
    const Box q = box_of(lat, leaves[static_cast<std::size_t>(f)]);
    if (q.s < 2) continue;
    const std::int64_t h = q.s / 2;
    std::uint8_t code = 0;
    if (vb.get(q.i0 + h, q.j0)) code |= kSideS;
    if (vb.get(wrap_index(q.i0 + q.s, nx), q.j0 + h)) code |= kSideE;
    if (vb.get(q.i0 + h, q.j0 + q.s)) code |= kSideN;
    if (vb.get(q.i0, q.j0 + h)) code |= kSideW;
    out.midside_code[static_cast<std::size_t>(f)] = code;
  }

  // 3. Centres (strictly inside their leaf, so inside their level-0 row: no write conflicts).
  if (options.centres) {
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nleaves)) \
    shared(leaves, lat, vb, out, starts, ny0) schedule(dynamic, 1)
    for (std::int64_t b0 = 0; b0 < ny0; ++b0) {
      for (std::int64_t f = starts[static_cast<std::size_t>(b0)]; f < starts[static_cast<std::size_t>(b0) + 1]; ++f) {
        if (out.midside_code[static_cast<std::size_t>(f)] == 0) continue;
        const Box q = box_of(lat, leaves[static_cast<std::size_t>(f)]);
        vb.set(q.i0 + q.s / 2, q.j0 + q.s / 2);
      }
    }
  }

  // 4. Numbering by (J, I) = rank in the vertex bitmap.
  const std::int64_t nnodes = vr.build();
  out.node_i.resize(static_cast<std::size_t>(nnodes));
  out.node_j.resize(static_cast<std::size_t>(nnodes));
  out.node_flags.resize(static_cast<std::size_t>(nnodes));
  const std::int64_t vrows = ny + 1;
  const std::int64_t vwords = vb.words_per_row();
#pragma omp parallel for default(none) if (quadtree::parallel_worth(vrows * vwords + nnodes)) \
    shared(vr, vb, out, vrows, vwords, ny) schedule(static)
  for (std::int64_t j = 0; j < vrows; ++j) {
    auto id = static_cast<std::size_t>(vr.row_base(j));
    const std::uint64_t* r = vb.row(j);
    for (std::int64_t w = 0; w < vwords; ++w) {
      std::uint64_t x = r[w];
      while (x != 0) {
        const std::int64_t i = 64 * w + std::countr_zero(x);
        x &= x - 1;
        out.node_i[id] = i;
        out.node_j[id] = j;
        out.node_flags[id] =
            static_cast<std::uint8_t>(((j == 0 || j == ny) ? kPoleNode : 0) | (i == 0 ? kSeamNode : 0));
        ++id;
      }
    }
  }

  // 5. Node ids per leaf.
  out.corners.resize(static_cast<std::size_t>(nleaves));
  out.midside.resize(static_cast<std::size_t>(nleaves));
  out.centre.resize(static_cast<std::size_t>(nleaves));
  const bool centres = options.centres;
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nleaves * 8)) \
    shared(leaves, lat, vr, out, nleaves, nx, centres) schedule(static)
  for (std::int64_t f = 0; f < nleaves; ++f) {
    const auto k = static_cast<std::size_t>(f);
    const Box q = box_of(lat, leaves[k]);
    const std::int64_t i1 = wrap_index(q.i0 + q.s, nx);
    const std::int64_t j1 = q.j0 + q.s;
    out.corners[k] = {vr.rank(q.i0, q.j0), vr.rank(i1, q.j0), vr.rank(i1, j1), vr.rank(q.i0, j1)};
    const std::uint8_t code = out.midside_code[k];
    const std::int64_t h = q.s / 2;
    out.midside[k] = {(code & kSideS) ? vr.rank(q.i0 + h, q.j0) : -1, (code & kSideE) ? vr.rank(i1, q.j0 + h) : -1,
                      (code & kSideN) ? vr.rank(q.i0 + h, j1) : -1, (code & kSideW) ? vr.rank(q.i0, q.j0 + h) : -1};
    out.centre[k] = (centres && code != 0) ? vr.rank(q.i0 + h, q.j0 + h) : -1;
  }
  for (std::int64_t f = 0; f < nleaves; ++f) {
    const auto k = static_cast<std::size_t>(f);
    for (const NodeId m : out.midside[k])
      if (m >= 0) out.node_flags[static_cast<std::size_t>(m)] |= kMidsideNode;
    if (out.centre[k] >= 0) out.node_flags[static_cast<std::size_t>(out.centre[k])] |= kCentreNode;
  }

  // 6. Boundary edges, and 7. their loops.
  {
    std::vector<std::uint8_t> across(static_cast<std::size_t>(nleaves));
    const int blocks = block_count(nleaves, 8);
    for_each_block(nleaves, blocks, [&](int, std::int64_t begin, std::int64_t end) {
      for (std::int64_t f = begin; f < end; ++f)
        across[static_cast<std::size_t>(f)] = covered_bits(cov, box_of(lat, leaves[static_cast<std::size_t>(f)]));
    });
    add_boundary(out, across, nx, ny);
  }

  // 8. Pinch vertices of the covered pixels.
  for (const auto& p : find_pinches(cov)) {
    if (!vb.get(p[0], p[1])) {
      throw InternalError(fmt::format("quadtree nodes: pinch vertex (I {}, J {}) is not a leaf corner", p[0], p[1]));
    }
    out.pinch_nodes.push_back(vr.rank(p[0], p[1]));
  }
  return out;
}

std::vector<LeafNeighbourhood> leaf_neighbourhoods(const std::vector<Leaf>& leaves, const Lattice& lat) {
  const Bitmap cov = leaf_coverage(leaves, lat);
  const std::int64_t nx = lat.nx, ny = lat.ny;
  Bitmap vb(nx, ny + 1);
  for (const Leaf& f : leaves) {
    const Box q = box_of(lat, f);
    const std::int64_t i1 = wrap_index(q.i0 + q.s, nx);
    vb.set(q.i0, q.j0);
    vb.set(i1, q.j0);
    vb.set(i1, q.j0 + q.s);
    vb.set(q.i0, q.j0 + q.s);
  }
  std::vector<LeafNeighbourhood> out(leaves.size());
  const auto pinch_at = [&](std::int64_t I, std::int64_t J) {
    if (J <= 0 || J >= ny) return false;
    const bool ne = covered(cov, I, J), nw = covered(cov, I - 1, J), se = covered(cov, I, J - 1),
               sw = covered(cov, I - 1, J - 1);
    return (ne && sw && !nw && !se) || (nw && se && !ne && !sw);
  };
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    const Box q = box_of(lat, leaves[k]);
    LeafNeighbourhood& n = out[k];
    if (q.s >= 2) {
      const std::int64_t h = q.s / 2;
      if (vb.get(q.i0 + h, q.j0)) n.midside |= kSideS;
      if (vb.get(wrap_index(q.i0 + q.s, nx), q.j0 + h)) n.midside |= kSideE;
      if (vb.get(q.i0 + h, q.j0 + q.s)) n.midside |= kSideN;
      if (vb.get(q.i0, q.j0 + h)) n.midside |= kSideW;
    }
    n.covered = covered_bits(cov, q);
    const std::array<std::array<std::int64_t, 2>, 4> c{
        {{q.i0, q.j0}, {q.i0 + q.s, q.j0}, {q.i0 + q.s, q.j0 + q.s}, {q.i0, q.j0 + q.s}}};
    for (std::size_t m = 0; m < 4; ++m)
      if (pinch_at(c[m][0], c[m][1])) n.pinch = static_cast<std::uint8_t>(n.pinch | (1U << m));
  }
  return out;
}

QuadNodes build_nodes_from_neighbourhoods(const std::vector<Leaf>& leaves, const std::vector<LeafNeighbourhood>& nb,
                                          const Lattice& lat, const NodeOptions& options) {
  if (nb.size() != leaves.size()) throw InternalError("quadtree nodes: one neighbourhood per leaf");
  if (!leaves_sorted(leaves, lat)) throw InternalError("quadtree nodes: leaves are not in the deterministic order");
  const std::int64_t nx = lat.nx, ny = lat.ny;
  const auto nleaves = static_cast<std::int64_t>(leaves.size());
  const auto key = [nx](std::int64_t i, std::int64_t j) { return j * nx + wrap_index(i, nx); };
  QuadNodes out;
  // 1-3. Corners, midside codes (given), centres; the vertex keys (J, I) sorted and unique.
  std::vector<std::int64_t> v;
  v.reserve(static_cast<std::size_t>(4 * nleaves));
  out.midside_code.resize(static_cast<std::size_t>(nleaves));
  for (std::int64_t f = 0; f < nleaves; ++f) {
    const auto k = static_cast<std::size_t>(f);
    const Box q = box_of(lat, leaves[k]);
    v.push_back(key(q.i0, q.j0));
    v.push_back(key(q.i0 + q.s, q.j0));
    v.push_back(key(q.i0 + q.s, q.j0 + q.s));
    v.push_back(key(q.i0, q.j0 + q.s));
    out.midside_code[k] = q.s >= 2 ? nb[k].midside : 0;
    if (options.centres && out.midside_code[k] != 0) v.push_back(key(q.i0 + q.s / 2, q.j0 + q.s / 2));
  }
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  // 4. Numbering by (J, I).
  const auto nnodes = static_cast<std::int64_t>(v.size());
  out.node_i.resize(v.size());
  out.node_j.resize(v.size());
  out.node_flags.resize(v.size());
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nnodes)) shared(v, out, nnodes, nx, ny) \
    schedule(static)
  for (std::int64_t n = 0; n < nnodes; ++n) {
    const auto p = static_cast<std::size_t>(n);
    const std::int64_t i = v[p] % nx, j = v[p] / nx;
    out.node_i[p] = i;
    out.node_j[p] = j;
    out.node_flags[p] = static_cast<std::uint8_t>(((j == 0 || j == ny) ? kPoleNode : 0) | (i == 0 ? kSeamNode : 0));
  }
  const auto id = [&v](std::int64_t k) {
    const auto it = std::lower_bound(v.begin(), v.end(), k);
    if (it == v.end() || *it != k) throw InternalError("quadtree nodes: a leaf vertex has no node");
    return static_cast<NodeId>(it - v.begin());
  };
  // 5. Node ids per leaf.
  out.corners.resize(static_cast<std::size_t>(nleaves));
  out.midside.resize(static_cast<std::size_t>(nleaves));
  out.centre.resize(static_cast<std::size_t>(nleaves));
  const bool centres = options.centres;
  const int blocks = block_count(nleaves, 16);
  for_each_block(nleaves, blocks, [&](int, std::int64_t begin, std::int64_t end) {
    for (std::int64_t f = begin; f < end; ++f) {
      const auto k = static_cast<std::size_t>(f);
      const Box q = box_of(lat, leaves[k]);
      const std::int64_t i1 = q.i0 + q.s, j1 = q.j0 + q.s, h = q.s / 2;
      out.corners[k] = {id(key(q.i0, q.j0)), id(key(i1, q.j0)), id(key(i1, j1)), id(key(q.i0, j1))};
      const std::uint8_t code = out.midside_code[k];
      out.midside[k] = {(code & kSideS) ? id(key(q.i0 + h, q.j0)) : -1, (code & kSideE) ? id(key(i1, q.j0 + h)) : -1,
                        (code & kSideN) ? id(key(q.i0 + h, j1)) : -1, (code & kSideW) ? id(key(q.i0, q.j0 + h)) : -1};
      out.centre[k] = (centres && code != 0) ? id(key(q.i0 + h, q.j0 + h)) : -1;
    }
  });
  for (std::int64_t f = 0; f < nleaves; ++f) {
    const auto k = static_cast<std::size_t>(f);
    for (const NodeId m : out.midside[k])
      if (m >= 0) out.node_flags[static_cast<std::size_t>(m)] |= kMidsideNode;
    if (out.centre[k] >= 0) out.node_flags[static_cast<std::size_t>(out.centre[k])] |= kCentreNode;
  }
  // 6-7. Boundary edges and loops.
  std::vector<std::uint8_t> across(static_cast<std::size_t>(nleaves));
  for (std::size_t k = 0; k < across.size(); ++k) across[k] = nb[k].covered;
  add_boundary(out, across, nx, ny);
  // 8. Pinch vertices, ascending (each is a corner of both of its filled pixels' leaves).
  for (std::size_t k = 0; k < nb.size(); ++k)
    for (std::size_t m = 0; m < 4; ++m)
      if (((nb[k].pinch >> m) & 1U) != 0) out.pinch_nodes.push_back(out.corners[k][m]);
  std::sort(out.pinch_nodes.begin(), out.pinch_nodes.end());
  out.pinch_nodes.erase(std::unique(out.pinch_nodes.begin(), out.pinch_nodes.end()), out.pinch_nodes.end());
  return out;
}

NodeId find_node(const QuadNodes& nodes, const Lattice& lat, std::int64_t i, std::int64_t j) {
  const std::int64_t iw = wrap_index(i, lat.nx);
  std::size_t lo = 0, hi = nodes.node_i.size();
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    const bool less = nodes.node_j[mid] < j || (nodes.node_j[mid] == j && nodes.node_i[mid] < iw);
    if (less) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return (lo < nodes.node_i.size() && nodes.node_j[lo] == j && nodes.node_i[lo] == iw) ? static_cast<NodeId>(lo) : -1;
}

}  // namespace aq::quadtree
