// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh statistics and checks (see statistics.hpp).
#include "mesh/statistics.hpp"

#include <fmt/format.h>
#include <GeographicLib/Ellipsoid.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/Math.hpp>
#include <GeographicLib/PolygonArea.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <utility>

#include "core/cancel.hpp"
#include "core/error.hpp"
#include "core/finite.hpp"
#include "core/rotation.hpp"
#include "core/types.hpp"
#include "mesh/buckets.hpp"
#include "quadtree/parallel.hpp"

namespace aq::mesh {

namespace {

/// Root of x in the union–find forest `parent` (parent[r] == r at a root, parent[x] < x elsewhere),
/// halving the path on the way. Safe while other threads run union_faces on the same forest.
std::int32_t find_root(std::int32_t* parent, std::int32_t x) {
  for (;;) {
    std::int32_t p = std::atomic_ref<std::int32_t>(parent[x]).load(std::memory_order_relaxed);
    if (p == x) return x;
    const std::int32_t g = std::atomic_ref<std::int32_t>(parent[p]).load(std::memory_order_relaxed);
    // g is an ancestor of x: replacing p by g only shortens the path (if no other thread did).
    if (g != p) std::atomic_ref<std::int32_t>(parent[x]).compare_exchange_weak(p, g, std::memory_order_relaxed);
    x = g;
  }
}

/// Joins the sets of faces a and b: the larger root goes under the smaller, by compare-and-swap so
/// that several threads may join at once (a root that another thread linked meanwhile is looked up
/// again). Parents only decrease, so no cycle forms; the final sets, and so the number of roots,
/// do not depend on the order of the calls.
void union_faces(std::int32_t* parent, std::int32_t a, std::int32_t b) {
  for (;;) {
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a == b) return;
    if (a < b) std::swap(a, b);
    std::int32_t expected = a;
    if (std::atomic_ref<std::int32_t>(parent[a]).compare_exchange_strong(expected, b, std::memory_order_relaxed))
      return;
  }
}

/// The smallest i in [0, n) with bad(i), or n when there is none (searched in parallel: the same
/// answer, and so the same error message, for any thread count).
template <class Bad>
std::int64_t first_where(std::int64_t n, const Bad& bad) {
  std::int64_t first = n;
#pragma omp parallel for default(none) shared(n, bad) reduction(min : first) if (quadtree::parallel_worth(n))
  for (std::int64_t i = 0; i < n; ++i)
    if (bad(i)) first = std::min(first, i);
  return first;
}

/// Whether every value of v is finite, checked in parallel: FiniteChecks::values, a serial scan
/// that finds and describes the first non-finite value, then runs only when it has one to report.
bool all_finite(std::span<const double> v) {
  const auto n = static_cast<std::int64_t>(v.size());
  const double* p = v.data();
  std::int64_t bad = 0;
#pragma omp parallel for default(none) if (quadtree::parallel_worth(n)) shared(n, p) schedule(static) reduction(+ : bad)
  for (std::int64_t i = 0; i < n; ++i) bad += std::isfinite(p[i]) ? 0 : 1;
  return bad == 0;
}

/// The values of the faces (or edges) by level, when most of them are entries of a memo table:
/// per table cell the number of faces of the cell's level that take its value, the others' values
/// one by one. Filled by the blocks of a parallel loop (add, one block per thread), then read.
class LevelValues {
 public:
  /// For values from `table` (which must outlive this), levels 0 .. nlevels − 1, `blocks` blocks.
  void reset(const std::vector<double>& table, std::int64_t nlevels, int blocks) {
    table_ = &table;
    nlevels_ = nlevels;
    counts_.assign(static_cast<std::size_t>(blocks), std::vector<std::int32_t>(table.size(), 0));
    loose_.assign(static_cast<std::size_t>(blocks * nlevels), {});
  }
  [[nodiscard]] int blocks() const { return static_cast<int>(counts_.size()); }
  /// Value v of a face of `level` (none outside 0 .. nlevels − 1) in block b: table[cell] when the
  /// cell is of that level, else cell = −1.
  void add(int b, int level, std::int64_t cell, double v) {
    if (level < 0 || level >= nlevels_) return;
    if (cell >= 0)
      ++counts_[static_cast<std::size_t>(b)][static_cast<std::size_t>(cell)];
    else
      loose_[static_cast<std::size_t>(b * nlevels_ + level)].push_back(v);
  }
  /// The (value, count) multiset of every level; cell c is of level cell_level(c).
  template <class CellLevel>
  [[nodiscard]] std::vector<std::vector<std::pair<double, std::int64_t>>> by_level(const CellLevel& cell_level) const {
    std::vector<std::vector<std::pair<double, std::int64_t>>> out(static_cast<std::size_t>(nlevels_));
    if (table_ == nullptr) return out;
    for (std::size_t c = 0; c < table_->size(); ++c) {
      std::int64_t count = 0;
      for (const auto& block : counts_) count += block[c];
      if (count > 0) out[static_cast<std::size_t>(cell_level(c))].emplace_back((*table_)[c], count);
    }
    for (std::size_t k = 0; k < loose_.size(); ++k)
      for (const double v : loose_[k]) out[k % static_cast<std::size_t>(nlevels_)].emplace_back(v, 1);
    return out;
  }

 private:
  const std::vector<double>* table_ = nullptr;
  std::int64_t nlevels_ = 0;
  std::vector<std::vector<std::int32_t>> counts_;  ///< per block, per cell
  std::vector<std::vector<double>> loose_;         ///< per block and level
};

/// Geodesic area (m², signed: anticlockwise positive) of a polygon of n <= 8 vertices given in
/// lattice coordinates.
double polygon_area_m2(const Lattice& lat, const PoleRotation& rot, const std::array<double, 8>& ui,
                       const std::array<double, 8>& uj, int n) {
  GeographicLib::PolygonArea poly(GeographicLib::Geodesic::WGS84());
  for (int v = 0; v < n; ++v) {
    double lon = 0.0, la = 0.0;
    rot.to_geographic(lat.lon_at(ui[static_cast<std::size_t>(v)]), lat.lat_of_row(uj[static_cast<std::size_t>(v)]), lon,
                      la);
    poly.AddPoint(la, lon);
  }
  double perimeter = 0.0, area = 0.0;
  poly.Compute(false, true, perimeter, area);
  return area;
}

/// +1/-1 when the edge lon1 -> lon2 crosses the prime meridian eastward/westward, as
/// GeographicLib::PolygonArea counts it (its transit(), which is private).
int polygon_transit(double lon1, double lon2) {
  // Both in (-180, 180) (where AngNormalize is the identity) and on one side of the prime
  // meridian: no crossing (the general test below gives 0 too).
  if (std::abs(lon1) < 180.0 && std::abs(lon2) < 180.0 && ((lon1 > 0.0 && lon2 > 0.0) || (lon1 < 0.0 && lon2 < 0.0)))
    return 0;
  const double lon12 = GeographicLib::Math::AngDiff(lon1, lon2);
  lon1 = GeographicLib::Math::AngNormalize(lon1);
  lon2 = GeographicLib::Math::AngNormalize(lon2);
  return lon12 > 0 && ((lon1 < 0 && lon2 >= 0) || (lon1 > 0 && lon2 == 0)) ? 1
         : (lon12 < 0 && lon1 >= 0 && lon2 < 0)                            ? -1
                                                                           : 0;
}

/// Signed (anticlockwise positive) polygon area from the sum of its edges' S12 and its prime
/// meridian crossings, reduced as GeographicLib::PolygonArea::Compute(false, true) does.
double polygon_area_reduce(double sum, double area0, int crossings) {
  double area = std::abs(sum) < 0.5 * area0 ? sum : std::remainder(sum, area0);  // remainder is exact there
  if ((crossings & 1) != 0) area += (area < 0 ? 1 : -1) * area0 / 2;
  area = -area;
  if (area > area0 / 2)
    area -= area0;
  else if (area <= -area0 / 2)
    area += area0;
  return area;
}

/// Geodesic distance (m) between two nodes given by geographic coordinates.
double distance_m(double lat1, double lon1, double lat2, double lon2) {
  double s12 = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(lat1, lon1, lat2, lon2, s12);
  return s12;
}

}  // namespace

// (statistics.hpp)
std::array<double, 3> min_median_max(std::span<double> v) {
  if (v.empty()) return {0.0, 0.0, 0.0};
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  const double mn = *lo, mx = *hi;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>((v.size() - 1) / 2);
  std::nth_element(v.begin(), mid, v.end());
  return {mn, *mid, mx};
}

// (statistics.hpp)
std::optional<std::array<double, 3>> weighted_min_median_max(std::vector<std::pair<double, std::int64_t>>& v,
                                                             std::int64_t& n) {
  n = 0;
  for (const auto& [value, count] : v) n += count;
  if (n == 0) return std::array<double, 3>{0.0, 0.0, 0.0};
  std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [value, count] : v)
    if (std::signbit(value) || !std::isfinite(value)) return std::nullopt;
  std::int64_t rank = (n - 1) / 2;
  double median = v.back().first;
  for (const auto& [value, count] : v) {
    if (rank < count) {
      median = value;
      break;
    }
    rank -= count;
  }
  return std::array<double, 3>{v.front().first, median, v.back().first};
}

std::vector<std::string> MeshStatistics::failed_checks() const {
  std::vector<std::string> f = non_finite;
  if (euler != euler_expected)
    f.push_back(fmt::format("Euler: V - E + F = {} but 2c - b - p = {}", euler, euler_expected));
  if (bad_edges != 0)
    f.push_back(fmt::format("{} edges not shared by exactly two oppositely oriented triangles", bad_edges));
  if (boundary_mismatch != 0)
    f.push_back(fmt::format("{} boundary edges differ from the triangles' boundary", boundary_mismatch));
  if (used_nodes != nodes) f.push_back(fmt::format("{} nodes are in no triangle", nodes - used_nodes));
  if (not_right_isosceles != 0)
    f.push_back(fmt::format("{} triangles are not right isosceles of a similarity class", not_right_isosceles));
  if (clockwise != 0) f.push_back(fmt::format("{} triangles are clockwise or degenerate", clockwise));
  if (twice_triangle_area_px2 != 2 * filled_pixels) {
    f.push_back(fmt::format("triangle area {} px² differs from the filled area {} px²",
                            static_cast<double>(twice_triangle_area_px2) / 2.0, filled_pixels));
  }
  if (geodesic && edges > 0 && !finite_at_most(area_relative_difference, area_tolerance)) {
    f.push_back(fmt::format(
        "triangle area {:.1f} km² differs from the filled area {:.1f} km² by {:.2e} (> {:.2e}, twice the bound of the "
        "lenses between the boundary edges' geodesics and the lattice lines: third order in the pixel size per edge)",
        triangle_area_km2, filled_area_km2, area_relative_difference, area_tolerance));
  }
  return f;
}

MeshStatistics compute_statistics(const Mesh& m, const StatisticsOptions& options) {
  MeshStatistics s;
  const Lattice& lat = m.lattice;
  const std::int64_t nx = lat.nx;
  const int levels = lat.levels;
  s.nodes = m.node_count();
  s.triangles = m.triangle_count();
  s.boundary_loops = static_cast<std::int64_t>(m.loops.size());
  s.pinch_nodes = static_cast<std::int64_t>(m.pinch_nodes.size());
  if (s.nodes >= (std::int64_t{1} << 32)) throw InternalError("mesh statistics: 2^32 nodes or more");
  {
    std::int64_t filled = 0;
    const auto nsq = m.square_count();
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nsq)) shared(m, lat, nsq) schedule(static) \
    reduction(+ : filled)
    for (std::int64_t q = 0; q < nsq; ++q) {
      const std::int64_t side = lat.pixels_per_square(m.square_level[static_cast<std::size_t>(q)]);
      filled += side * side;
    }
    s.filled_pixels = filled;
  }
  const std::int64_t ntri = s.triangles;
  const bool have_squares = static_cast<std::int64_t>(m.triangle_square.size()) == ntri &&
                            static_cast<std::int64_t>(m.triangle_level.size()) == ntri;
  if (!have_squares) throw InternalError("mesh statistics: triangle_level / triangle_square missing");
  const std::int64_t nodes = s.nodes;
  const auto node_of = [&](std::int64_t k) { return m.triangles[static_cast<std::size_t>(k / 3)][k % 3]; };
  const std::int64_t bad_node =
      first_where(3 * ntri, [&](std::int64_t k) { return node_of(k) < 0 || node_of(k) >= nodes; });
  if (bad_node < 3 * ntri)
    throw InternalError(fmt::format("mesh statistics: node id {} out of range", node_of(bad_node)));
  const std::int64_t bad_square = first_where(ntri, [&](std::int64_t t) {
    const ElementId q = m.triangle_square[static_cast<std::size_t>(t)];
    return q < 0 || q >= m.square_count();
  });
  if (bad_square < ntri) {
    throw InternalError(fmt::format("mesh statistics: square id {} out of range",
                                    m.triangle_square[static_cast<std::size_t>(bad_square)]));
  }

  // Faces: the triangles; or, for a mesh of squares only (mesh.elements = "squares"), the squares
  // as polygons through their corners and midside nodes (SW, S, SE, E, NE, N, NW, W), so that
  // conformity, Euler, orientation and the areas are checked on the elements that are written.
  const bool square_faces = ntri == 0 && !m.squares.empty();
  std::vector<std::int64_t> poly_start{0};
  std::vector<NodeId> poly_nodes;
  if (square_faces) {
    for (std::size_t q = 0; q < m.squares.size(); ++q) {
      for (std::size_t c = 0; c < 4; ++c) {
        poly_nodes.push_back(m.squares[q][c]);
        const NodeId mid = q < m.square_midside.size() ? m.square_midside[q][c] : -1;
        if (mid >= 0) poly_nodes.push_back(mid);
      }
      poly_start.push_back(static_cast<std::int64_t>(poly_nodes.size()));
    }
    for (const NodeId v : poly_nodes)
      if (v < 0 || v >= s.nodes) throw InternalError(fmt::format("mesh statistics: node id {} out of range", v));
  }
  const std::int64_t nfaces = square_faces ? m.square_count() : ntri;
  const auto face_size = [&](std::int64_t f) {
    return square_faces
               ? static_cast<int>(poly_start[static_cast<std::size_t>(f) + 1] - poly_start[static_cast<std::size_t>(f)])
               : 3;
  };
  const auto face_node = [&](std::int64_t f, int k) {
    return square_faces ? poly_nodes[static_cast<std::size_t>(poly_start[static_cast<std::size_t>(f)] + k)]
                        : m.triangles[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)];
  };
  const auto face_level = [&](std::int64_t f) {
    return square_faces ? m.square_level[static_cast<std::size_t>(f)] : m.triangle_level[static_cast<std::size_t>(f)];
  };
  // First half-edge slot of face f (slot face_first(f) + k: from node k to node k + 1).
  const auto face_first = [&](std::int64_t f) {
    return square_faces ? poly_start[static_cast<std::size_t>(f)] : 3 * f;
  };
  const auto face_square = [&](std::int64_t f) {
    return static_cast<std::size_t>(square_faces ? f : m.triangle_square[static_cast<std::size_t>(f)]);
  };

  // Unwrapped lattice coordinates of a face's vertices: I below its square's SW corner wrapped.
  const auto vertex_ij = [&](std::int64_t t, int v, std::int64_t& i, std::int64_t& j) {
    const auto n = static_cast<std::size_t>(face_node(t, v));
    const auto sq = face_square(t);
    const std::int64_t i0 = m.node_i[static_cast<std::size_t>(m.squares[sq][0])];
    i = m.node_i[n];
    if (i < i0) i += nx;
    j = m.node_j[n];
  };

  // Geometry in lattice units. shape[t] = p0·81 + p1·9 + p2 with p the vertex positions inside
  // the triangle's square in half sides (row·3 + column, 0..8), -1 if not on that grid.
  s.similarity.assign(static_cast<std::size_t>(2 * levels) + 1, 0);
  std::vector<std::int16_t> shape(static_cast<std::size_t>(ntri));
  {
    const int nt = quadtree::block_count(ntri, 16);
    std::vector<std::vector<std::int64_t>> sim(static_cast<std::size_t>(nt), s.similarity);
    std::vector<std::array<std::int64_t, 3>> sums(static_cast<std::size_t>(nt), {0, 0, 0});
    quadtree::for_each_block(ntri, nt, [&](int th, std::int64_t begin, std::int64_t end) {
      // Counted in locals and stored once: the blocks' slots share cache lines.
      std::array<std::int64_t, 3> acc{0, 0, 0};
      std::vector<std::int64_t> hist(s.similarity.size(), 0);
      for (std::int64_t t = begin; t < end; ++t) {
        std::array<std::int64_t, 3> x{}, y{};
        for (int v = 0; v < 3; ++v) vertex_ij(t, v, x[static_cast<std::size_t>(v)], y[static_cast<std::size_t>(v)]);
        {
          const auto sq = static_cast<std::size_t>(m.triangle_square[static_cast<std::size_t>(t)]);
          const std::int64_t side = lat.pixels_per_square(m.square_level[sq]);
          const std::int64_t i0 = m.node_i[static_cast<std::size_t>(m.squares[sq][0])];
          const std::int64_t j0 = m.node_j[static_cast<std::size_t>(m.squares[sq][0])];
          // side is a power of two: multiples by mask, quotients by shift (no integer division).
          const std::int64_t mask = side - 1;
          const int shift = std::countr_zero(static_cast<std::uint64_t>(side));
          int code = 0;
          for (std::size_t v = 0; v < 3 && code >= 0; ++v) {
            const std::int64_t px = 2 * (x[v] - i0), py = 2 * (y[v] - j0);
            const bool on =
                (px & mask) == 0 && (py & mask) == 0 && px >= 0 && py >= 0 && px <= 2 * side && py <= 2 * side;
            code = on ? code * 9 + static_cast<int>((py >> shift) * 3 + (px >> shift)) : -1;
          }
          shape[static_cast<std::size_t>(t)] = static_cast<std::int16_t>(code);
        }
        const std::int64_t cross = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        acc[0] += cross;
        if (cross <= 0) ++acc[1];
        std::array<std::int64_t, 3> d2{};
        for (int e = 0; e < 3; ++e) {
          const auto a = static_cast<std::size_t>(e), b = static_cast<std::size_t>((e + 1) % 3);
          d2[a] = (x[b] - x[a]) * (x[b] - x[a]) + (y[b] - y[a]) * (y[b] - y[a]);
        }
        std::sort(d2.begin(), d2.end());
        const std::int64_t leg2 = d2[0];
        bool ok =
            leg2 > 0 && d2[1] == leg2 && d2[2] == 2 * leg2 && std::has_single_bit(static_cast<std::uint64_t>(leg2));
        if (ok) {
          const int k = 2 * levels - std::countr_zero(static_cast<std::uint64_t>(leg2));
          ok = k >= 0 && k <= 2 * levels;
          if (ok) ++hist[static_cast<std::size_t>(k)];
        }
        if (!ok) ++acc[2];
      }
      sums[static_cast<std::size_t>(th)] = acc;
      sim[static_cast<std::size_t>(th)] = std::move(hist);
    });
    for (int th = 0; th < nt; ++th) {
      s.twice_triangle_area_px2 += sums[static_cast<std::size_t>(th)][0];
      s.clockwise += sums[static_cast<std::size_t>(th)][1];
      s.not_right_isosceles += sums[static_cast<std::size_t>(th)][2];
      for (std::size_t k = 0; k < s.similarity.size(); ++k) s.similarity[k] += sim[static_cast<std::size_t>(th)][k];
    }
  }

  if (square_faces) {  // squares: twice the area by the shoelace formula, exact in lattice units
    for (std::int64_t f = 0; f < nfaces; ++f) {
      const int n = face_size(f);
      std::int64_t cross = 0;
      for (int v = 0; v < n; ++v) {
        std::int64_t xa = 0, ya = 0, xb = 0, yb = 0;
        vertex_ij(f, v, xa, ya);
        vertex_ij(f, (v + 1) % n, xb, yb);
        cross += xa * yb - xb * ya;
      }
      s.twice_triangle_area_px2 += cross;
      const std::int64_t side = lat.pixels_per_square(m.square_level[static_cast<std::size_t>(f)]);
      if (cross != 2 * side * side) ++s.clockwise;  // clockwise, degenerate or not the square's area
    }
  }

  throw_if_cancelled();  // between the passes (core/cancel.hpp)
  // Edges: half-edges bucketed by their smaller node (stable counting sort, mesh/buckets.hpp), each
  // bucket sorted by the other node; a group of 1 is a boundary edge, of 2 (opposite directions) an
  // interior one. Edges are numbered by (smaller node, larger node).
  if (nfaces >= (std::int64_t{1} << 31)) throw InternalError("mesh statistics: 2^31 elements or more");
  const auto nn = static_cast<std::size_t>(s.nodes);
  // rec = other node << 32 | face << 1 | (half-edge runs from the larger node to the smaller).
  Buckets<std::uint64_t> half =
      stable_buckets<std::uint64_t>(nfaces, s.nodes, 16, [&](std::int64_t f, const auto& emit) {
        const int n = face_size(f);
        for (int e = 0; e < n; ++e) {
          const NodeId a = face_node(f, e), b = face_node(f, (e + 1) % n);
          emit(std::min(a, b), static_cast<std::uint64_t>(std::max(a, b)) << 32 | static_cast<std::uint64_t>(f) << 1 |
                                   (a > b ? 1U : 0U));
        }
      });
  const std::int64_t* start = half.start.data();
  std::uint64_t* rec = half.values.data();
  const auto nbuckets = static_cast<std::int64_t>(nn);
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nbuckets * 4)) shared(rec, start, nbuckets) \
    schedule(static)
  for (std::int64_t v = 0; v < nbuckets; ++v) std::sort(rec + start[v], rec + start[v + 1]);
  // edge_first[v]: the first edge of bucket v (its runs of equal other node are its edges).
  FillVector<std::int64_t> edge_first(nn + 1);  // first touched in the parallel loop
  std::int64_t* first = edge_first.data();
  first[0] = 0;
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nbuckets * 4)) shared(rec, start, first, nbuckets) \
    schedule(static)
  for (std::int64_t v = 0; v < nbuckets; ++v) {
    std::int64_t runs = 0;
    for (std::int64_t k = start[v]; k < start[v + 1]; ++k)
      runs += k == start[v] || (rec[k] >> 32) != (rec[k - 1] >> 32);
    first[v + 1] = runs;
  }
  for (std::size_t v = 0; v < nn; ++v) edge_first[v + 1] += edge_first[v];
  s.edges = edge_first[nn];
  const auto ne = static_cast<std::size_t>(s.edges);
  // Rotated frame or squares: the faces' areas are sums over their edges (below).
  const bool per_edge_areas = m.rotation.enabled || square_faces;
  FillVector<std::uint32_t> edge_a(ne), edge_b(ne);              // nodes a < b
  FillVector<std::uint32_t> edge_t(per_edge_areas ? 0 : ne);     // a face of the edge (for the memo)
  FillVector<std::uint8_t> edge_level(ne);                       // finest level of the edge's faces
  FillVector<std::uint8_t> edge_inner(per_edge_areas ? ne : 0);  // 1 = two faces, opposite directions
  // per_edge_areas: face_edge[face_first(f) + k] = the edge of the face's half-edge k, ~edge when it
  // runs from the larger node to the smaller.
  if (per_edge_areas && s.edges >= (std::int64_t{1} << 31)) throw InternalError("mesh statistics: 2^31 edges or more");
  FillVector<std::int32_t> face_edge(per_edge_areas ? half.values.size() : 0);
  throw_if_cancelled();  // between the passes (core/cancel.hpp)
  // Components of the faces joined by interior edges: union–find, the larger root linked under the
  // smaller by compare-and-swap (parents only decrease, so no cycles form), so that the buckets can
  // be walked in parallel; the number of roots does not depend on the order of the unions.
  FillVector<std::int32_t> parent(static_cast<std::size_t>(nfaces));
  std::int32_t* par = parent.data();
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nfaces)) shared(par, nfaces) schedule(static)
  for (std::int64_t f = 0; f < nfaces; ++f) par[f] = static_cast<std::int32_t>(f);
  std::int64_t boundary = 0, interior = 0, bad = 0;
  {
    std::uint32_t *ea = edge_a.data(), *eb = edge_b.data(), *et = edge_t.data();
    std::uint8_t *el = edge_level.data(), *ei = edge_inner.data();
    std::int32_t* fe = face_edge.data();
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nbuckets * 16))                                 \
    shared(rec, start, first, nbuckets, ea, eb, et, el, ei, fe, par, per_edge_areas, face_level, face_size, face_node, \
               face_first) schedule(static) reduction(+ : boundary, interior, bad)
    for (std::int64_t v = 0; v < nbuckets; ++v) {
      std::int64_t edge = first[v];
      const std::int64_t end = start[v + 1];
      for (std::int64_t k = start[v]; k < end; ++edge) {
        std::int64_t e = k + 1;
        while (e < end && (rec[e] >> 32) == (rec[k] >> 32)) ++e;
        const auto t0 = static_cast<std::int32_t>((rec[k] & 0xffffffffULL) >> 1);
        const bool inner = e - k == 2 && ((rec[k] ^ rec[k + 1]) & 1U) != 0;
        const auto x = static_cast<std::size_t>(edge);
        ea[x] = static_cast<std::uint32_t>(v);
        eb[x] = static_cast<std::uint32_t>(rec[k] >> 32);
        std::uint8_t level = face_level(t0);
        if (!per_edge_areas) {
          et[x] = static_cast<std::uint32_t>(t0);
        } else {
          ei[x] = inner ? 1 : 0;
          // The slot of each half-edge in its face; a face with the same directed edge twice (a
          // broken mesh) has that many equal records, the j-th taking its j-th such slot.
          for (std::int64_t h = k; h < e; ++h) {
            const std::int64_t t = static_cast<std::int64_t>((rec[h] & 0xffffffffULL) >> 1);
            const NodeId hi = static_cast<NodeId>(rec[h] >> 32);
            const NodeId from = (rec[h] & 1U) != 0 ? hi : v, to = (rec[h] & 1U) != 0 ? v : hi;
            std::int64_t skip = 0;
            for (std::int64_t g = h; g > k && rec[g - 1] == rec[h]; --g) ++skip;
            const int n = face_size(t);
            for (int c = 0; c < n; ++c) {
              if (face_node(t, c) != from || face_node(t, (c + 1) % n) != to || skip-- > 0) continue;
              fe[face_first(t) + c] = static_cast<std::int32_t>(from < to ? edge : ~edge);
              break;
            }
          }
        }
        if (e - k == 1) {
          ++boundary;
        } else if (inner) {
          ++interior;
          const auto t1 = static_cast<std::int32_t>((rec[k + 1] & 0xffffffffULL) >> 1);
          level = std::max(level, face_level(t1));
          union_faces(par, t0, t1);
        } else {
          ++bad;
        }
        el[x] = level;
        k = e;
      }
    }
  }
  s.boundary_edges = boundary;
  s.interior_edges = interior;
  s.bad_edges = bad;
  std::int64_t components = 0, used_nodes = 0;
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nfaces)) shared(par, nfaces) schedule(static) \
    reduction(+ : components)
  for (std::int64_t f = 0; f < nfaces; ++f) components += par[f] == f;
  s.components = components;
  FillVector<std::int32_t>().swap(parent);
  std::vector<std::uint8_t> used(nn, 0);
  std::uint8_t* use = used.data();
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nfaces * 4)) \
    shared(use, nfaces, face_size, face_node) schedule(static)
  for (std::int64_t f = 0; f < nfaces; ++f)
    for (int k = 0; k < face_size(f); ++k)
      std::atomic_ref<std::uint8_t>(use[face_node(f, k)]).store(1, std::memory_order_relaxed);
  for (const std::uint8_t u : used) used_nodes += u;
  s.used_nodes = used_nodes;
  if (nfaces > 0) {
    // Every Mesh boundary edge a -> b must be a face edge used once, in the same direction.
    std::int64_t matched = 0;
    const auto nbe = static_cast<std::int64_t>(m.boundary_edges.size());
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nbe * 8)) shared(m, rec, start, nbe, nodes) \
    schedule(static) reduction(+ : matched)
    for (std::int64_t i = 0; i < nbe; ++i) {
      const auto& be = m.boundary_edges[static_cast<std::size_t>(i)];
      if (be[0] < 0 || be[1] < 0 || be[0] >= nodes || be[1] >= nodes || be[0] == be[1]) continue;
      const auto lo = std::min(be[0], be[1]);
      const auto hi = static_cast<std::uint64_t>(std::max(be[0], be[1]));
      const std::uint64_t dir = be[0] > be[1] ? 1U : 0U;
      std::int64_t count = 0;
      bool same_direction = false;
      for (std::int64_t k = start[lo]; k < start[lo + 1]; ++k) {
        if ((rec[k] >> 32) != hi) continue;
        ++count;
        same_direction = (rec[k] & 1U) == dir;
      }
      matched += (count == 1 && same_direction);
    }
    s.boundary_mismatch =
        std::abs(s.boundary_edges - matched) + (static_cast<std::int64_t>(m.boundary_edges.size()) - matched);
    s.euler = s.used_nodes - s.edges + nfaces;
    s.euler_expected = 2 * s.components - s.boundary_loops - s.pinch_nodes;
  }
  half = Buckets<std::uint64_t>();

  FiniteChecks finite;
  const auto node_where = [&](std::int64_t k) {
    const auto n = static_cast<std::size_t>(k);
    return fmt::format("node {} (lattice I = {}, J = {}; λ = {}°, φ = {}°)", k, m.node_i[n], m.node_j[n], m.lon_deg[n],
                       m.lat_deg[n]);
  };
  if (m.lon_deg.size() == nn && m.lat_deg.size() == nn) {
    if (!all_finite(m.lon_deg)) finite.values("node longitude", m.lon_deg, node_where);
    if (!all_finite(m.lat_deg)) finite.values("node latitude", m.lat_deg, node_where);
    if (m.depth_m.size() == nn && !all_finite(m.depth_m)) finite.values("node depth", m.depth_m, node_where);
  }
  s.non_finite = finite.failures();
  if (!options.geodesic) return s;
  s.geodesic = true;

  throw_if_cancelled();  // between the passes (core/cancel.hpp)
  // Filled area of the squares on WGS84. Without rotation a lattice cell between geodetic
  // latitudes φ1, φ2 has the exact area Rq²·Δλ·(sin ξ2 − sin ξ1), ξ the authalic latitude and Rq
  // the authalic radius. With rotation the cell lies between parallels and meridians of the
  // rotated frame; its area is Rq² ∫ g(φ) dΩ over the cell, dΩ = dλ' d(sin φ') the unit-sphere
  // measure (invariant under the rotation) and
  //   g(φ) = a²(1 − e²) / (Rq² (1 − e² sin²φ)²)   (0.9966 at the equator .. 1.0034 at the poles)
  // the ellipsoid's area per unit-sphere area at the geodetic latitude φ of the point, taken by
  // 3×3 Gauss–Legendre in (λ', sin φ') per square. (The rotated cells used to be taken with g ≡ 1,
  // on the authalic sphere: a model error of up to ±0.34% per cell that does not shrink with the
  // pixel size, 4.85e-4 of the total for the h = 200 ocean, which failed the area check.)
  const GeographicLib::Ellipsoid& ell = GeographicLib::Ellipsoid::WGS84();
  const double rq2 = ell.Area() / (4.0 * kPi);
  const double e2 = ell.EccentricitySq();
  const double pixel_rad = lat.pixel_deg() * kDegToRad;
  const PoleRotation rot =
      m.rotation.enabled ? PoleRotation(m.rotation.pole_lon_deg, m.rotation.pole_lat_deg) : PoleRotation();
  std::vector<double> sin_xi(static_cast<std::size_t>(lat.ny) + 1);
  for (std::int64_t j = 0; j <= lat.ny; ++j) {
    const double phi = lat.lat_of(j);
    sin_xi[static_cast<std::size_t>(j)] = std::sin((m.rotation.enabled ? phi : ell.AuthalicLatitude(phi)) * kDegToRad);
  }
  finite.values("lattice row sine of latitude (cell areas)", sin_xi, [&](std::int64_t j) {
    return fmt::format("lattice row J = {} (φ = {:.17g}° in the lattice frame)", j, lat.lat_of(j));
  });
  const auto nsquares = static_cast<std::int64_t>(m.squares.size());
  FillVector<double> square_m2(static_cast<std::size_t>(nsquares));
  const double density_scale = ell.EquatorialRadius() * ell.EquatorialRadius() * (1.0 - e2);
  FillVector<double> quadrature_error(m.rotation.enabled ? static_cast<std::size_t>(nsquares) : 0);
  // Rotated: 3×3 Gauss–Legendre; |3×3 − 2×2| bounds the error (the 2×2 rule's error, far above the
  // 3×3's). The density needs only sin φ = z of the geographic unit vector: a dot product of the
  // rotation's last row with (cos φ' cos λ', cos φ' sin λ', sin φ'), where sin φ' is the quadrature
  // coordinate itself and cos φ' = √(1 − sin² φ'). The quadrature nodes u (across the columns) and
  // v (across the rows) take the 5 values of kNode (the 2×2 rule's, then the 3×3 rule's), and the
  // squares of a level sit on a grid of their side, so cos/sin λ' of the columns and sin/cos φ' of
  // the rows are tabled once per level (grid_cos_sin below) instead of once per square.
  constexpr double kG2 = 0.57735026918962576, kG3 = 0.7745966692414834;  // 1/√3, √(3/5)
  constexpr std::array<double, 5> kNode{-kG2, kG2, -kG3, 0.0, kG3};
  constexpr std::array<double, 3> kW3{5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  // cos/sin λ' of node u (-1..1) across the square of `side` pixels whose west side is at I = i0.
  const auto column = [&](std::int64_t i0, std::int64_t side, double u, double& c, double& sn) {
    const double rlon =
        lat.lon0_deg +
        (static_cast<double>(i0 + lat.i_origin) + 0.5 * static_cast<double>(side) * (1.0 + u)) * lat.pixel_deg();
    c = std::cos(rlon * kDegToRad);
    sn = std::sin(rlon * kDegToRad);
  };
  // sin/cos φ' of node v (-1..1) across the square of `side` pixels whose south side is at J = j0.
  const auto row = [&](std::int64_t j0, std::int64_t side, double v, double& sr, double& cr) {
    const double s0 = sin_xi[static_cast<std::size_t>(j0)], s1 = sin_xi[static_cast<std::size_t>(j0 + side)];
    sr = std::clamp(0.5 * (s0 + s1) + 0.5 * (s1 - s0) * v, -1.0, 1.0);
    cr = std::sqrt((1.0 - sr) * (1.0 + sr));
  };
  // grid_cos_sin[(grid_first[l] + n) · 5 + k]: column n of level l (I = n·side) at node k, then
  // row n (J = n·side) after all the columns: {cos λ', sin λ'} and {sin φ', cos φ'}.
  std::vector<std::int64_t> grid_first(2 * static_cast<std::size_t>(levels + 1) + 1, 0);
  std::vector<std::array<double, 2>> grid_cos_sin;
  if (m.rotation.enabled) {
    for (int axis = 0; axis < 2; ++axis) {
      for (int l = 0; l <= levels; ++l) {
        const auto k = static_cast<std::size_t>(axis * (levels + 1) + l);
        grid_first[k + 1] = grid_first[k] + (axis == 0 ? lat.nx : lat.ny) / lat.pixels_per_square(l);
      }
    }
    grid_cos_sin.resize(static_cast<std::size_t>(grid_first.back()) * kNode.size());
    const std::int64_t cells = grid_first.back();
#pragma omp parallel for default(none) if (quadtree::parallel_worth(cells * 64)) \
    shared(grid_first, grid_cos_sin, cells, levels, lat, kNode, column, row) schedule(static)
    for (std::int64_t c = 0; c < cells; ++c) {
      int k = 0;
      while (grid_first[static_cast<std::size_t>(k) + 1] <= c) ++k;
      const int axis = k / (levels + 1), l = k % (levels + 1);
      const std::int64_t side = lat.pixels_per_square(l), at = (c - grid_first[static_cast<std::size_t>(k)]) * side;
      for (std::size_t n = 0; n < kNode.size(); ++n) {
        auto& cs = grid_cos_sin[static_cast<std::size_t>(c) * kNode.size() + n];
        if (axis == 0)
          column(at, side, kNode[n], cs[0], cs[1]);
        else
          row(at, side, kNode[n], cs[0], cs[1]);
      }
    }
  }
  const auto square_area = [&](std::int64_t q) {
    const auto qq = static_cast<std::size_t>(q);
    const int level = m.square_level[qq];
    const std::int64_t side = lat.pixels_per_square(level);
    const std::int64_t j0 = m.node_j[static_cast<std::size_t>(m.squares[qq][0])];
    const double s0 = sin_xi[static_cast<std::size_t>(j0)], s1 = sin_xi[static_cast<std::size_t>(j0 + side)];
    const double dlam = static_cast<double>(side) * pixel_rad;
    if (!m.rotation.enabled) {
      square_m2[qq] = rq2 * dlam * (s1 - s0);
      return;
    }
    const std::int64_t i0 = m.node_i[static_cast<std::size_t>(m.squares[qq][0])];
    std::array<std::array<double, 2>, 5> lon{}, phi{};  // cos/sin λ', sin/cos φ' at the nodes
    const auto col_k = static_cast<std::size_t>(level), row_k = static_cast<std::size_t>(levels + 1 + level);
    if (i0 % side == 0 && j0 % side == 0 && level <= levels && grid_first[col_k] + i0 / side < grid_first[col_k + 1] &&
        grid_first[row_k] + j0 / side < grid_first[row_k + 1]) {
      const auto* c = &grid_cos_sin[static_cast<std::size_t>(grid_first[col_k] + i0 / side) * kNode.size()];
      const auto* r = &grid_cos_sin[static_cast<std::size_t>(grid_first[row_k] + j0 / side) * kNode.size()];
      std::copy(c, c + kNode.size(), lon.begin());
      std::copy(r, r + kNode.size(), phi.begin());
    } else {  // not on its level's grid (not a quadtree leaf): directly
      for (std::size_t n = 0; n < kNode.size(); ++n) {
        column(i0, side, kNode[n], lon[n][0], lon[n][1]);
        row(j0, side, kNode[n], phi[n][0], phi[n][1]);
      }
    }
    const auto density = [&](std::size_t u, std::size_t v) {  // at nodes kNode[u], kNode[v]
      const double sp = rot.geographic_sin_lat(lon[u][0], lon[u][1], phi[v][1], phi[v][0]);
      const double d = 1.0 - e2 * sp * sp;
      return density_scale / (d * d);
    };
    double q2 = 0.0, q3 = 0.0;
    for (std::size_t u = 0; u < 2; ++u)
      for (std::size_t v = 0; v < 2; ++v) q2 += density(u, v);
    for (std::size_t a = 0; a < 3; ++a)
      for (std::size_t b = 0; b < 3; ++b) q3 += kW3[a] * kW3[b] * density(2 + a, 2 + b);
    const double cell = 0.25 * dlam * (s1 - s0);
    square_m2[qq] = q3 * cell;
    quadrature_error[qq] = std::fabs(q3 - q2) * cell;
  };
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nsquares * (m.rotation.enabled ? 64 : 4))) \
    shared(nsquares, square_area) schedule(static)
  for (std::int64_t q = 0; q < nsquares; ++q) square_area(q);
  double filled_m2 = 0.0;
  for (const double a : square_m2) filled_m2 += a;  // serial: the same sum for any thread count
  s.filled_area_km2 = filled_m2 * 1e-6;

  throw_if_cancelled();  // between the passes (core/cancel.hpp)
  // The tolerance of |triangle area − filled area|, from the error it bounds. Interior edges are
  // one geodesic for both neighbouring triangles and cancel, and the squares tile the filled set
  // exactly, so the two areas differ by the lenses between each boundary edge's geodesic and the
  // lattice line it stands for:
  //  * an edge along a lattice parallel φ' spanning Δλ (rad): the great circle bulges poleward by
  //    Δλ² |sin φ'| cos φ' / 8, a lens of a² Δλ³ |sin φ'| cos² φ' / 12 (a: equatorial radius);
  //  * the ellipsoid's geodesics leave the sphere's great circles by a relative curvature of order
  //    e² (so, with rotation, also along lattice meridians): at most e² a² s³ / 4 per boundary edge
  //    of angular length s;
  //  * the rotated cells' quadrature: |3×3 − 2×2 Gauss–Legendre| per square (O(side⁴ e²));
  //  * rounding: 8 ε per summed term.
  // Each lens is third order in the pixel size and there are O(1/pixel) boundary edges, so the
  // tolerance scales as the pixel size squared (and grows with a rugged coast), without a constant
  // fitted to a run. It is twice the sum of these bounds, relative to the filled area.
  double bound_m2 = 0.0;
  {
    // Per boundary edge the two lenses (0 where one does not apply: the terms are never negative,
    // so adding +0 changes nothing), in parallel; summed below in edge order.
    const double a2 = ell.EquatorialRadius() * ell.EquatorialRadius();
    const auto nbe = static_cast<std::int64_t>(m.boundary_edges.size());
    // cos/sin of each row's lattice latitude, once per row (a Mercator row's latitude is not cheap).
    const std::int64_t rows = lat.ny + 1;
    std::vector<std::array<double, 2>> row_cos_sin(static_cast<std::size_t>(rows));
#pragma omp parallel for default(none) if (quadtree::parallel_worth(rows * 64)) shared(lat, row_cos_sin, rows) \
    schedule(static)
    for (std::int64_t j = 0; j < rows; ++j) {
      const double phi = lat.lat_of(j) * kDegToRad;
      row_cos_sin[static_cast<std::size_t>(j)] = {std::cos(phi), std::sin(phi)};
    }
    const auto cos_sin_row = [&](std::int64_t j) {
      if (j >= 0 && j < rows) return row_cos_sin[static_cast<std::size_t>(j)];
      const double phi = lat.lat_of(j) * kDegToRad;  // not a lattice row (a broken mesh)
      return std::array<double, 2>{std::cos(phi), std::sin(phi)};
    };
    FillVector<std::array<double, 2>> lens(static_cast<std::size_t>(nbe));
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nbe * 16)) \
    shared(m, lens, nbe, nodes, nx, pixel_rad, a2, e2, cos_sin_row) schedule(static)
    for (std::int64_t k = 0; k < nbe; ++k) {
      const auto& be = m.boundary_edges[static_cast<std::size_t>(k)];
      auto& term = lens[static_cast<std::size_t>(k)];
      term = {0.0, 0.0};
      if (be[0] < 0 || be[1] < 0 || be[0] >= nodes || be[1] >= nodes) continue;
      const auto na = static_cast<std::size_t>(be[0]), nb = static_cast<std::size_t>(be[1]);
      std::int64_t di = std::abs(m.node_i[nb] - m.node_i[na]);
      di = std::min(di, nx - di);
      const std::int64_t dj = std::abs(m.node_j[nb] - m.node_j[na]);
      const auto [cos_phi, sin_phi] = cos_sin_row(m.node_j[na]);
      const double dlam = static_cast<double>(di) * pixel_rad;
      const double len = std::max(dlam * cos_phi, static_cast<double>(dj) * pixel_rad);
      if (dj == 0) term[0] = a2 * dlam * dlam * dlam * std::fabs(sin_phi) * cos_phi * cos_phi / 12.0;
      term[1] = e2 * a2 * len * len * len / 4.0;
    }
    for (const auto& term : lens) {  // serial: the same sum for any thread count
      bound_m2 += term[0];
      bound_m2 += term[1];
    }
    for (const double e : quadrature_error) bound_m2 += e;
    bound_m2 +=
        8.0 * std::numeric_limits<double>::epsilon() * static_cast<double>(nsquares + ntri) * std::fabs(filled_m2);
  }
  s.area_tolerance =
      options.area_tolerance > 0.0 ? options.area_tolerance : (filled_m2 > 0.0 ? 2.0 * bound_m2 / filled_m2 : 0.0);

  // Position (0..8) of vertex v of triangle t inside its square, from shape[t]; -1 if unknown.
  const auto local_pos = [&](std::int64_t t, int v) {
    const int code = shape[static_cast<std::size_t>(t)];
    if (code < 0) return -1;
    return v == 0 ? code / 81 : v == 1 ? (code / 9) % 9 : code % 9;
  };
  // Row offsets of the (level, row) memo tables.
  std::vector<std::int64_t> row_offset(static_cast<std::size_t>(levels) + 2, 0);
  for (int l = 0; l <= levels; ++l) {
    row_offset[static_cast<std::size_t>(l) + 1] = row_offset[static_cast<std::size_t>(l)] + (lat.ny >> (levels - l));
  }
  const bool memo = !per_edge_areas;
  const auto row_of = [&](std::int64_t t) {
    const auto sq = static_cast<std::size_t>(m.triangle_square[static_cast<std::size_t>(t)]);
    const int l = m.square_level[sq];
    return row_offset[static_cast<std::size_t>(l)] +
           m.node_j[static_cast<std::size_t>(m.squares[sq][0])] / lat.pixels_per_square(l);
  };
  const auto lattice_area = [&](std::int64_t t) {
    std::array<double, 8> ui{}, uj{};
    const int n = face_size(t);
    for (int v = 0; v < n; ++v) {
      std::int64_t i = 0, j = 0;
      vertex_ij(t, v, i, j);
      ui[static_cast<std::size_t>(v)] = static_cast<double>(i);
      uj[static_cast<std::size_t>(v)] = static_cast<double>(j);
    }
    return polygon_area_m2(lat, rot, ui, uj, n);
  };

  throw_if_cancelled();  // between the passes (core/cancel.hpp)
  // Without rotation the per-level statistics at the end are taken from the memo tables: each
  // table cell's value with the number of faces (edges) of the cell's level that take it, plus
  // the values of the others one by one (level_values below), instead of gathering 8 bytes per
  // face and edge by level and selecting among them.
  const std::int64_t nlevels = levels + 1;
  std::vector<std::uint8_t> row_level(memo ? static_cast<std::size_t>(row_offset.back()) : 0);
  for (std::int64_t l = 0; l < nlevels && memo; ++l)
    std::fill(row_level.begin() + row_offset[static_cast<std::size_t>(l)],
              row_level.begin() + row_offset[static_cast<std::size_t>(l) + 1], static_cast<std::uint8_t>(l));
  LevelValues area_values, length_values;
  std::vector<double> area_table, length_table;  // the memo tables (kept for the LevelValues)
  std::int64_t area_nshapes = 1;

  // Element areas.
  FillVector<double> edge_s12, edge_S12;  // per edge, when not memoised (below)
  FillVector<double> area(static_cast<std::size_t>(nfaces));
  if (memo) {
    std::vector<std::int32_t> shape_id(729, -1);
    std::vector<std::int32_t> shapes;
    for (const std::int16_t c : shape) {
      if (c >= 0 && shape_id[static_cast<std::size_t>(c)] < 0) {
        shape_id[static_cast<std::size_t>(c)] = static_cast<std::int32_t>(shapes.size());
        shapes.push_back(c);
      }
    }
    const auto nshapes = static_cast<std::int64_t>(shapes.size());
    area_nshapes = std::max<std::int64_t>(1, nshapes);
    const std::int64_t cells = row_offset.back() * nshapes;
    std::vector<double>& table = area_table;
    table.assign(static_cast<std::size_t>(cells), std::numeric_limits<double>::quiet_NaN());
    std::vector<std::int64_t> example(static_cast<std::size_t>(cells), -1);
    for (std::int64_t t = 0; t < ntri; ++t) {
      const std::int32_t c = shape[static_cast<std::size_t>(t)];
      if (c < 0) continue;
      const std::int64_t cell = row_of(t) * nshapes + shape_id[static_cast<std::size_t>(c)];
      if (example[static_cast<std::size_t>(cell)] < 0) example[static_cast<std::size_t>(cell)] = t;
    }
#pragma omp parallel for default(none) if (quadtree::parallel_worth(cells * 64)) \
    shared(table, example, cells, lattice_area) schedule(dynamic, 64)
    for (std::int64_t cell = 0; cell < cells; ++cell) {
      const std::int64_t t = example[static_cast<std::size_t>(cell)];
      if (t >= 0) table[static_cast<std::size_t>(cell)] = lattice_area(t);
    }
    std::vector<std::int64_t>().swap(example);  // its memory for the counts
    area_values.reset(table, nlevels, quadtree::block_count(ntri, 4));
    quadtree::for_each_block(ntri, area_values.blocks(), [&](int b, std::int64_t begin, std::int64_t end) {
      for (std::int64_t t = begin; t < end; ++t) {
        const std::int32_t c = shape[static_cast<std::size_t>(t)];
        const std::int64_t cell = c < 0 ? -1 : row_of(t) * nshapes + shape_id[static_cast<std::size_t>(c)];
        const double a = cell < 0 ? lattice_area(t) : table[static_cast<std::size_t>(cell)];
        area[static_cast<std::size_t>(t)] = a;
        const int l = face_level(t);
        area_values.add(b, l, cell >= 0 && row_level[static_cast<std::size_t>(cell / nshapes)] == l ? cell : -1, a);
      }
    });
  } else {
    // Rotated frame or squares: no two cells are alike, so each edge's geodesic is solved once, for
    // its length s12 and its area S12 (between the geodesic and the equator), and a face's area is
    // the sum of ±S12 over its edges reduced as GeographicLib::PolygonArea does (which solved
    // every interior edge twice, once per face, and then a third time for the length).
    //
    // Interior edges shorter than kShortEdgeM (45 km: every interior edge of a lattice with
    // pixels of 6' or less) take closed forms, about ten times cheaper than a geodesic:
    //  * S12 of the arc between their authalic-sphere images (c² · 2 atan(tan(Δλ/2)(t1 + t2) /
    //    (1 + t1 t2)), t = tan(β/2), β the authalic latitude): the authalic map keeps areas and maps
    //    meridians and the equator to themselves, so this is the area between the arc's preimage and
    //    the equator. Each interior edge enters its two faces with opposite signs, so the total area
    //    is unchanged; a face's area is that of the region its edges bound, which differs from the
    //    all-geodesic face by lenses of order e²·s³/R (a relative e²·s/R: below 1e-6 at 1', and
    //    within 3e-6 for edges up to 45 km in the unit test that compares every level);
    //  * the length from the ECEF chord d and the normal-section radius ρ along it,
    //    s = d (1 + d² / (24 ρ²)) (within 1e-9 relative of the geodesic in the same test).
    // Boundary edges, which the total area and its check rest on, and longer edges are geodesics.
    const GeographicLib::Geodesic& geod = GeographicLib::Geodesic::WGS84();
    edge_s12.resize(static_cast<std::size_t>(s.edges));  // every edge written below
    edge_S12.resize(static_cast<std::size_t>(s.edges));
    [[maybe_unused]] const std::int64_t nedges_all = s.edges;  // in the OpenMP clause only
    constexpr double kShortEdgeM = 45000.0;
    const double a_eq = ell.EquatorialRadius(), ecc = std::sqrt(e2);
    const double c2 = rq2;  // the authalic radius squared
    const auto q_of = [ecc, e2](double sn) {
      return (1.0 - e2) * (sn / (1.0 - e2 * sn * sn) + std::atanh(ecc * sn) / ecc);
    };
    const double qp = q_of(1.0);
    // Per node: tan(β/2) and the ECEF position.
    const auto nnodes = static_cast<std::int64_t>(nn);
    FillVector<double> tb(nn), ecef(3 * nn);
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nnodes * 16)) \
    shared(m, tb, ecef, nnodes, q_of, qp, a_eq, e2) schedule(static)
    for (std::int64_t v = 0; v < nnodes; ++v) {
      const auto k = static_cast<std::size_t>(v);
      const double phi = m.lat_deg[k] * kDegToRad, lam = m.lon_deg[k] * kDegToRad;
      const double sp = std::sin(phi), cp = std::cos(phi);
      const double sb = std::clamp(q_of(sp) / qp, -1.0, 1.0);
      tb[k] = sb / (1.0 + std::sqrt((1.0 - sb) * (1.0 + sb)));
      const double n = a_eq / std::sqrt(1.0 - e2 * sp * sp);
      ecef[3 * k] = n * cp * std::cos(lam);
      ecef[3 * k + 1] = n * cp * std::sin(lam);
      ecef[3 * k + 2] = n * (1.0 - e2) * sp;
    }
    // The edges of node a (the smaller node) are edge_first[a] .. edge_first[a + 1]: the frame at a
    // is set up once for all of them.
    const std::int64_t* first_edge = edge_first.data();
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nedges_all * 64)) shared( \
    m, geod, edge_b, edge_inner, edge_s12, edge_S12, first_edge, nnodes, tb, ecef, c2, a_eq, e2) schedule(dynamic, 64)
    for (std::int64_t node = 0; node < nnodes; ++node) {
      const auto a = static_cast<std::size_t>(node);
      // The local frame at node a from its ECEF position (geocentric: the direction and the
      // latitude enter only the small curvature term).
      const double x = ecef[3 * a], y = ecef[3 * a + 1], z = ecef[3 * a + 2];
      const double p2 = x * x + y * y, p = std::sqrt(p2), r = std::sqrt(p2 + z * z);
      const double sp = z / r;
      const double w2 = 1.0 - e2 * sp * sp;
      const double inv_m = w2 * std::sqrt(w2) / (a_eq * (1.0 - e2)), inv_n = std::sqrt(w2) / a_eq;
      for (std::int64_t e = first_edge[node]; e < first_edge[node + 1]; ++e) {
        const auto k = static_cast<std::size_t>(e);
        const auto b = static_cast<std::size_t>(edge_b[k]);
        if (edge_inner[k] != 0) {
          const double dx = ecef[3 * b] - x, dy = ecef[3 * b + 1] - y, dz = ecef[3 * b + 2] - z;
          const double d2 = dx * dx + dy * dy + dz * dz;
          if (d2 < kShortEdgeM * kShortEdgeM) {
            const double east = p > 0.0 ? (-y * dx + x * dy) / p : dx;
            const double north = p > 0.0 ? (-z * (x * dx + y * dy) / p + p * dz) / r : dy;
            const double h2 = east * east + north * north;
            const double inv_rho = h2 > 0.0 ? (north * north * inv_m + east * east * inv_n) / h2 : inv_n;
            edge_s12[k] = std::sqrt(d2) * (1.0 + d2 * inv_rho * inv_rho / 24.0);
            double dlam = m.lon_deg[b] - m.lon_deg[a];
            dlam = (dlam > 180.0 ? dlam - 360.0 : dlam <= -180.0 ? dlam + 360.0 : dlam) * kDegToRad;
            edge_S12[k] = c2 * 2.0 * std::atan2(std::tan(0.5 * dlam) * (tb[a] + tb[b]), 1.0 + tb[a] * tb[b]);
            continue;
          }
        }
        double azi1 = 0.0, azi2 = 0.0, m12 = 0.0, mm12 = 0.0, mm21 = 0.0;
        geod.GenInverse(m.lat_deg[a], m.lon_deg[a], m.lat_deg[b], m.lon_deg[b],
                        GeographicLib::Geodesic::DISTANCE | GeographicLib::Geodesic::AREA, edge_s12[k], azi1, azi2, m12,
                        mm12, mm21, edge_S12[k]);
      }
    }
    const double area0 = geod.EllipsoidArea();
    const auto face_area = [&](std::int64_t t) {
      const int n = face_size(t);
      double sum = 0.0;
      int crossings = 0;
      for (int v = 0; v < n; ++v) {
        const NodeId a = face_node(t, v), b = face_node(t, (v + 1) % n);
        const std::int64_t e = face_edge[static_cast<std::size_t>(face_first(t) + v)];
        sum += e >= 0 ? edge_S12[static_cast<std::size_t>(e)] : -edge_S12[static_cast<std::size_t>(~e)];
        crossings += polygon_transit(m.lon_deg[static_cast<std::size_t>(a)], m.lon_deg[static_cast<std::size_t>(b)]);
      }
      return polygon_area_reduce(sum, area0, crossings);
    };
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nfaces * 16)) shared(area, nfaces, face_area) \
    schedule(static)
    for (std::int64_t t = 0; t < nfaces; ++t) area[static_cast<std::size_t>(t)] = face_area(t);
  }
  FillVector<std::int64_t>().swap(edge_first);
  const auto face_where = [&](std::int64_t t) {
    std::string w = fmt::format("{} {} (level {}), nodes", square_faces ? "square" : "triangle", t, face_level(t));
    for (int k = 0; k < face_size(t); ++k) {
      const NodeId v = face_node(t, k);
      const auto n = static_cast<std::size_t>(v);
      w += fmt::format(" {} (λ = {}°, φ = {}°; lattice I = {}, J = {})", v, m.lon_deg[n], m.lat_deg[n], m.node_i[n],
                       m.node_j[n]);
    }
    return w;
  };
  double total_m2 = 0.0;
  bool areas_finite = true;
  for (const double a : area) {  // serial: the same sum for any thread count
    total_m2 += a;
    areas_finite = areas_finite && std::isfinite(a);
  }
  if (!areas_finite)
    finite.values(square_faces ? "geodesic square area (m²)" : "geodesic triangle area (m²)", area, face_where);
  s.triangle_area_km2 = total_m2 * 1e-6;
  finite.scalar("total triangle area (km²)", s.triangle_area_km2, "the sum over all triangles");
  finite.scalar("filled area of the lattice cells (km²)", s.filled_area_km2, "the sum over all squares");
  // No triangles: nothing to compare. Otherwise a filled area that is not positive and finite
  // makes the difference NaN, which fails the check (finite_at_most) instead of passing as 0.
  s.area_relative_difference =
      nfaces == 0 ? 0.0
                  : (s.filled_area_km2 > 0.0 ? std::abs(s.triangle_area_km2 - s.filled_area_km2) / s.filled_area_km2
                                             : std::numeric_limits<double>::quiet_NaN());

  // Edge lengths, memoised by (level, row, shape) of a triangle holding the edge.
  const auto nedges = s.edges;
  FillVector<double> length;
  const auto direct_length = [&](std::int64_t e) {
    const auto a = static_cast<std::size_t>(edge_a[static_cast<std::size_t>(e)]);
    const auto b = static_cast<std::size_t>(edge_b[static_cast<std::size_t>(e)]);
    return distance_m(m.lat_deg[a], m.lon_deg[a], m.lat_deg[b], m.lon_deg[b]);
  };
  if (memo) {
    length.resize(static_cast<std::size_t>(nedges));  // every edge written below
    const std::int64_t cells = row_offset.back() * 81;
    std::vector<double>& table = length_table;
    table.assign(static_cast<std::size_t>(cells), std::numeric_limits<double>::quiet_NaN());
    std::vector<std::int64_t> example(static_cast<std::size_t>(cells), -1);
    std::vector<std::int64_t> cell_of(static_cast<std::size_t>(nedges), -1);
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nedges * 8)) \
    shared(m, edge_a, edge_b, edge_t, cell_of, nedges, local_pos, row_of) schedule(static)
    for (std::int64_t e = 0; e < nedges; ++e) {
      const auto k = static_cast<std::size_t>(e);
      const std::int64_t t = edge_t[k];
      const auto& tr = m.triangles[static_cast<std::size_t>(t)];
      int v0 = 0, v1 = 0;
      for (int v = 0; v < 3; ++v) {
        if (tr[static_cast<std::size_t>(v)] == static_cast<NodeId>(edge_a[k])) v0 = v;
        if (tr[static_cast<std::size_t>(v)] == static_cast<NodeId>(edge_b[k])) v1 = v;
      }
      const int p0 = local_pos(t, v0), p1 = local_pos(t, v1);
      if (p0 >= 0 && p1 >= 0) cell_of[k] = row_of(t) * 81 + std::min(p0, p1) * 9 + std::max(p0, p1);
    }
    for (std::int64_t e = 0; e < nedges; ++e) {
      const std::int64_t cell = cell_of[static_cast<std::size_t>(e)];
      if (cell >= 0 && example[static_cast<std::size_t>(cell)] < 0) example[static_cast<std::size_t>(cell)] = e;
    }
#pragma omp parallel for default(none) if (quadtree::parallel_worth(cells * 64)) \
    shared(table, example, cells, direct_length) schedule(dynamic, 64)
    for (std::int64_t cell = 0; cell < cells; ++cell) {
      const std::int64_t e = example[static_cast<std::size_t>(cell)];
      if (e >= 0) table[static_cast<std::size_t>(cell)] = direct_length(e);
    }
    std::vector<std::int64_t>().swap(example);  // its memory for the counts
    length_values.reset(table, nlevels, quadtree::block_count(nedges, 2));
    quadtree::for_each_block(nedges, length_values.blocks(), [&](int b, std::int64_t begin, std::int64_t end) {
      for (std::int64_t e = begin; e < end; ++e) {
        const std::int64_t cell = cell_of[static_cast<std::size_t>(e)];
        const double len = cell < 0 ? direct_length(e) : table[static_cast<std::size_t>(cell)];
        length[static_cast<std::size_t>(e)] = len;
        const int l = edge_level[static_cast<std::size_t>(e)];
        length_values.add(b, l, cell >= 0 && row_level[static_cast<std::size_t>(cell / 81)] == l ? cell : -1, len);
      }
    });
  } else {
    length = std::move(edge_s12);  // solved with the areas above
  }

  const bool lengths_finite = all_finite(length);
  if (!lengths_finite) {
    finite.values("geodesic edge length (m)", length, [&](std::int64_t e) {
      const auto k = static_cast<std::size_t>(e);
      return fmt::format("edge {} between {} and {}", e, node_where(edge_a[k]), node_where(edge_b[k]));
    });
  }
  s.non_finite = finite.failures();

  // Per level: the min, median and max of the areas and of the lengths (levels outside 0..L are
  // not counted) and their numbers. Group g: level L − g/2, areas for even g, lengths for odd g.
  const std::int64_t groups = 2 * nlevels;
  std::vector<std::array<double, 3>> extremes(static_cast<std::size_t>(groups));
  std::vector<std::int64_t> group_size(static_cast<std::size_t>(groups), 0);
  bool from_memo = memo && areas_finite && lengths_finite;
  if (from_memo) {  // from the memo tables' counts (LevelValues)
    auto area_groups =
        area_values.by_level([&](std::size_t c) { return row_level[c / static_cast<std::size_t>(area_nshapes)]; });
    auto length_groups = length_values.by_level([&](std::size_t c) { return row_level[c / 81]; });
    for (std::int64_t g = 0; g < groups && from_memo; ++g) {
      auto& values = (g % 2 == 0 ? area_groups : length_groups)[static_cast<std::size_t>(levels - g / 2)];
      const auto r = weighted_min_median_max(values, group_size[static_cast<std::size_t>(g)]);
      from_memo = r.has_value();
      if (r) extremes[static_cast<std::size_t>(g)] = *r;
    }
  }
  if (!from_memo) {
    // The areas and lengths grouped by level in face and edge order, then the min, median and max
    // of each group, the groups in parallel (the finest, largest groups first).
    Buckets<double> area_of = stable_buckets<double>(nfaces, nlevels, 2, [&](std::int64_t t, const auto& emit) {
      const int l = face_level(t);
      if (l <= levels) emit(l, area[static_cast<std::size_t>(t)]);
    });
    Buckets<double> length_of = stable_buckets<double>(nedges, nlevels, 2, [&](std::int64_t e, const auto& emit) {
      const int l = edge_level[static_cast<std::size_t>(e)];
      if (l <= levels) emit(l, length[static_cast<std::size_t>(e)]);
    });
#pragma omp parallel for default(none) if (quadtree::parallel_worth(nfaces + nedges)) \
    shared(area_of, length_of, extremes, group_size, groups, levels) schedule(dynamic, 1)
    for (std::int64_t g = 0; g < groups; ++g) {
      Buckets<double>& b = g % 2 == 0 ? area_of : length_of;  // each group reordered in place by one thread
      const auto l = static_cast<std::size_t>(levels - g / 2);
      group_size[static_cast<std::size_t>(g)] = b.start[l + 1] - b.start[l];
      extremes[static_cast<std::size_t>(g)] = min_median_max(
          std::span<double>(b.values.data() + b.start[l], static_cast<std::size_t>(b.start[l + 1] - b.start[l])));
    }
  }
  for (int l = 0; l <= levels; ++l) {
    if (group_size[static_cast<std::size_t>(2 * (levels - l))] == 0) continue;
    const auto& am = extremes[static_cast<std::size_t>(2 * (levels - l))];
    const auto& lm = extremes[static_cast<std::size_t>(2 * (levels - l) + 1)];
    LevelStatistics ls;
    ls.level = l;
    ls.triangles = group_size[static_cast<std::size_t>(2 * (levels - l))];
    ls.edges = group_size[static_cast<std::size_t>(2 * (levels - l) + 1)];
    ls.area_min_m2 = am[0];
    ls.area_median_m2 = am[1];
    ls.area_max_m2 = am[2];
    ls.edge_min_m = lm[0];
    ls.edge_median_m = lm[1];
    ls.edge_max_m = lm[2];
    s.levels.push_back(ls);
  }
  return s;
}

Json statistics_json(const MeshStatistics& s) {
  Json j;
  j["nodes"] = s.nodes;
  j["triangles"] = s.triangles;
  j["edges"] = s.edges;
  j["interior_edges"] = s.interior_edges;
  j["boundary_edges"] = s.boundary_edges;
  j["boundary_loops"] = s.boundary_loops;
  j["pinch_nodes"] = s.pinch_nodes;
  j["components"] = s.components;
  j["euler"] = Json{{"v_minus_e_plus_f", s.euler},
                    {"expected_2c_minus_b_minus_p", s.euler_expected},
                    {"ok", s.euler == s.euler_expected}};
  j["conforming"] = Json{{"bad_edges", s.bad_edges},
                         {"boundary_mismatch", s.boundary_mismatch},
                         {"unused_nodes", s.nodes - s.used_nodes},
                         {"ok", s.bad_edges == 0 && s.boundary_mismatch == 0 && s.nodes == s.used_nodes}};
  j["right_isosceles"] = Json{{"not_right_isosceles", s.not_right_isosceles},
                              {"clockwise_or_degenerate", s.clockwise},
                              {"min_angle_deg", s.not_right_isosceles == 0 ? 45.0 : 0.0}};
  Json sim = Json::array();
  for (std::size_t k = 0; k < s.similarity.size(); ++k) {
    if (s.similarity[k] == 0) continue;
    sim.push_back(
        Json{{"k", k}, {"ratio", std::pow(std::sqrt(0.5), static_cast<double>(k))}, {"triangles", s.similarity[k]}});
  }
  j["similarity"] = sim;
  j["area"] = Json{{"triangles_px2", static_cast<double>(s.twice_triangle_area_px2) / 2.0},
                   {"filled_px2", s.filled_pixels},
                   {"lattice_ok", s.twice_triangle_area_px2 == 2 * s.filled_pixels}};
  if (s.geodesic) {
    j["area"]["triangles_km2"] = s.triangle_area_km2;
    j["area"]["filled_km2"] = s.filled_area_km2;
    j["area"]["relative_difference"] = s.area_relative_difference;
    j["area"]["tolerance"] = s.area_tolerance;
    j["total_wet_area_km2"] = s.triangle_area_km2;
    Json lv = Json::array();
    for (const LevelStatistics& l : s.levels) {
      lv.push_back(Json{{"level", l.level},
                        {"triangles", l.triangles},
                        {"area_m2", Json{{"min", l.area_min_m2}, {"median", l.area_median_m2}, {"max", l.area_max_m2}}},
                        {"edges", l.edges},
                        {"edge_m", Json{{"min", l.edge_min_m}, {"median", l.edge_median_m}, {"max", l.edge_max_m}}}});
    }
    j["levels"] = lv;
  }
  const std::vector<std::string> failed = s.failed_checks();
  j["ok"] = failed.empty();
  j["failed_checks"] = failed;
  j["non_finite"] = s.non_finite;
  return j;
}

}  // namespace aq::mesh
