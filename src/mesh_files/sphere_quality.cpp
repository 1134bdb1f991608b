// SPDX-License-Identifier: GPL-3.0-or-later
// Shape quality of a triangle mesh on the sphere (see sphere_quality.hpp).
#include "mesh_files/sphere_quality.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.hpp"
#include "core/types.hpp"
#include "mesh/buckets.hpp"
#include "mesh_files/geographic_mesh.hpp"
#include "quadtree/parallel.hpp"

namespace aq::io {

namespace {

using Vec3 = std::array<double, 3>;

// Loops over fewer items run on one thread: under load, waking the team costs more than the work.
constexpr std::int64_t kParallelMin = 200000;

// Great-circle distance (radians) between unit vectors: 2·asin(chord / 2).
double arc(const Vec3& a, const Vec3& b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return 2.0 * std::asin(std::min(1.0, 0.5 * std::sqrt(dx * dx + dy * dy + dz * dz)));
}

// Smallest and largest angle (degrees) between the great circles at the vertices of triangle
// a, b, c: the angles of spherical_angles_deg (geographic_mesh.hpp), through two trigonometric
// calls only. At vertex p with neighbours q, r the tangent directions are q − (p·q)p and
// r − (p·r)p; the smallest angle has the largest cosine, the largest the smallest.
std::array<double, 2> min_max_spherical_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto dot = [](const Vec3& u, const Vec3& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  auto tangent = [&](const Vec3& p, const Vec3& q) {
    const double d = dot(p, q);
    return Vec3{q[0] - d * p[0], q[1] - d * p[1], q[2] - d * p[2]};
  };
  const std::array<std::array<Vec3, 2>, 3> t{
      {{tangent(a, b), tangent(a, c)}, {tangent(b, c), tangent(b, a)}, {tangent(c, a), tangent(c, b)}}};
  std::size_t lo = 0, hi = 0;
  double lo_cos = -2.0, hi_cos = 2.0;
  for (std::size_t k = 0; k < 3; ++k) {
    const double den = std::sqrt(dot(t[k][0], t[k][0]) * dot(t[k][1], t[k][1]));
    const double cs = den > 0.0 ? dot(t[k][0], t[k][1]) / den : 1.0;  // a zero side: a zero angle
    if (cs > lo_cos) {
      lo_cos = cs;
      lo = k;
    }
    if (cs < hi_cos) {
      hi_cos = cs;
      hi = k;
    }
  }
  auto angle = [&](std::size_t k) {
    const Vec3 &u = t[k][0], &v = t[k][1];
    const Vec3 x{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return std::atan2(std::sqrt(dot(x, x)), dot(u, v)) * kRadToDeg;
  };
  return {angle(lo), angle(hi)};
}

int thread_count() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}
int thread_id() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

// Per-thread integer histograms, summed afterwards: the same for any thread count. Pass 1
// (prefixes empty) counts the high 16 bits of every value; pass 2 counts the low 16 bits of the
// values whose high bits equal prefixes[p], one histogram per prefix (equal prefixes share one:
// a value is looked up in a table of the high bits, not compared with every prefix).
std::vector<std::vector<std::int64_t>> digit_histograms(const std::vector<float>& v,
                                                        const std::vector<std::uint32_t>& prefixes) {
  constexpr std::size_t kBins = 1u << 16;
  // slot[high]: 1 + the histogram of values with these high bits, 0 for none (pass 2).
  std::vector<std::uint8_t> slot(prefixes.empty() ? 0 : kBins, 0);
  std::vector<std::size_t> of_prefix(prefixes.size());
  std::size_t nh = prefixes.empty() ? 1 : 0;
  for (std::size_t p = 0; p < prefixes.size(); ++p) {
    if (prefixes[p] >= kBins) throw InternalError("order_statistic: a prefix beyond 16 bits");
    std::uint8_t& s = slot[prefixes[p]];
    if (s == 0) {
      if (nh == 255) throw InternalError("order_statistic: more than 255 ranks at once");
      s = static_cast<std::uint8_t>(++nh);
    }
    of_prefix[p] = s - 1u;
  }
  const int nt = thread_count();
  std::vector<std::int64_t> per(static_cast<std::size_t>(nt) * nh * kBins, 0);
  const auto n = static_cast<std::int64_t>(v.size());
  const float* data = v.data();
  std::int64_t* counts = per.data();
  const std::uint8_t* slots = slot.data();
  const bool high = prefixes.empty();
#pragma omp parallel default(none) shared(n, data, counts, slots, high, nh) if (n >= kParallelMin)
  {
    std::int64_t* mine = counts + static_cast<std::size_t>(thread_id()) * nh * kBins;
    if (high) {
#pragma omp for schedule(static)
      for (std::int64_t k = 0; k < n; ++k) ++mine[std::bit_cast<std::uint32_t>(data[k]) >> 16];
    } else {
#pragma omp for schedule(static)
      for (std::int64_t k = 0; k < n; ++k) {
        const auto bits = std::bit_cast<std::uint32_t>(data[k]);
        if (const std::size_t s = slots[bits >> 16]; s != 0) ++mine[(s - 1) * kBins + (bits & 0xffffu)];
      }
    }
  }
  std::vector<std::vector<std::int64_t>> h(nh, std::vector<std::int64_t>(kBins, 0));
  for (int t = 0; t < nt; ++t)
    for (std::size_t p = 0; p < nh; ++p)
      for (std::size_t b = 0; b < kBins; ++b) h[p][b] += per[(static_cast<std::size_t>(t) * nh + p) * kBins + b];
  if (high) return h;
  std::vector<std::vector<std::int64_t>> by_prefix(prefixes.size());
  for (std::size_t p = 0; p < prefixes.size(); ++p) by_prefix[p] = h[of_prefix[p]];
  return by_prefix;
}

// The bin holding rank `rank` of a histogram, and the rank within it.
std::uint32_t find_bin(const std::vector<std::int64_t>& h, std::int64_t& rank) {
  for (std::size_t b = 0; b < h.size(); ++b) {
    if (rank < h[b]) return static_cast<std::uint32_t>(b);
    rank -= h[b];
  }
  throw InternalError("order_statistic: rank beyond the histogram");
}

// v rounded to `per_unit` steps per unit (100: to 0.01).
double round_to(double v, double per_unit) { return std::isfinite(v) ? std::round(v * per_unit) / per_unit : v; }

// JSON has no infinity: an infinite ratio (next to a zero-area triangle) is written as null.
Json finite_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

// Largest area ratio of each triangle of tri[0 .. nt) to its edge neighbours, 1 without neighbours
// (neighbour area ratio of sphere_quality.hpp); ar: the triangles' areas. The triangles round each
// node are listed in triangle order (mesh/buckets.hpp), numbered by Id.
template <class Id>
void neighbour_area_ratios(const std::array<NodeId, 3>* tri, std::int64_t nt, std::int64_t nn, const double* ar,
                           float* ratio) {
  const mesh::Buckets<Id> around = mesh::stable_buckets<Id>(nt, nn, 4, [tri](std::int64_t t, const auto& emit) {
    for (const NodeId v : tri[t]) emit(v, static_cast<Id>(t));
  });
  const std::int64_t* fp = around.start.data();
  const Id* ap = around.values.data();
#pragma omp parallel for schedule(static) default(none) shared(nt, tri, fp, ap, ar, ratio) if (nt >= kParallelMin)
  for (std::int64_t t = 0; t < nt; ++t) {
    const auto& v = tri[t];
    double worst = 1.0;
    // The edge neighbours are the other triangles with two of t's nodes: those round v0 with v1
    // or v2, and those round v1 with v2 (two lists instead of one per edge; a neighbour met twice
    // changes no maximum).
    const auto meet = [&](NodeId a, NodeId b, NodeId c) {
      for (std::int64_t k = fp[a]; k < fp[a + 1]; ++k) {
        const std::int64_t u = ap[k];
        if (u == t) continue;
        const auto& w = tri[u];
        if (w[0] != b && w[1] != b && w[2] != b && w[0] != c && w[1] != c && w[2] != c) continue;
        const double lo = std::min(ar[t], ar[u]), hi = std::max(ar[t], ar[u]);
        worst = std::max(worst, lo > 0.0 ? hi / lo : std::numeric_limits<double>::infinity());
      }
    };
    meet(v[0], v[1], v[2]);
    meet(v[1], v[2], v[2]);
    ratio[t] = static_cast<float>(worst);
  }
}

// The unit vector of every node of m: unit_vector_deg bit for bit, with cos φ and sin φ taken
// once per run of nodes of one latitude (the bits of lat_deg: −0 and +0 have sines of two signs)
// instead of once per node. The lattice's nodes are numbered by row (mesh.hpp), so without
// rotation this halves the trigonometric calls.
mesh::FillVector<Vec3> unit_vectors(const mesh::Mesh& m) {
  const auto nn = static_cast<std::int64_t>(m.lon_deg.size());
  mesh::FillVector<Vec3> p(static_cast<std::size_t>(nn));  // every node written below
  const double* lon = m.lon_deg.data();
  const double* lat = m.lat_deg.data();
  Vec3* pp = p.data();
  const int blocks = nn >= kParallelMin ? thread_count() : 1;
  quadtree::for_each_block(nn, blocks, [&](int, std::int64_t begin, std::int64_t end) {
    std::uint64_t row_bits = 0;
    double cos_lat = 0.0, sin_lat = 0.0;
    for (std::int64_t k = begin; k < end; ++k) {
      const auto bits = std::bit_cast<std::uint64_t>(lat[k]);
      if (k == begin || bits != row_bits) {
        const double la = lat[k] * kDegToRad;
        row_bits = bits;
        cos_lat = std::cos(la);
        sin_lat = std::sin(la);
      }
      const double lo = lon[k] * kDegToRad;
      pp[k] = Vec3{cos_lat * std::cos(lo), cos_lat * std::sin(lo), sin_lat};
    }
  });
  return p;
}

}  // namespace

std::vector<float> order_statistics(const std::vector<float>& values, const std::vector<double>& qs) {
  if (values.empty()) throw InternalError("order_statistic: no values");
  const auto n = static_cast<std::int64_t>(values.size());
  // Non-negative IEEE floats order like their bit patterns as unsigned integers.
  const auto high_histogram = digit_histograms(values, {})[0];
  std::vector<std::int64_t> rank(qs.size());
  std::vector<std::uint32_t> high(qs.size());
  for (std::size_t k = 0; k < qs.size(); ++k) {
    rank[k] = static_cast<std::int64_t>(std::floor(std::clamp(qs[k], 0.0, 1.0) * static_cast<double>(n - 1)));
    high[k] = find_bin(high_histogram, rank[k]);
  }
  const auto low_histograms = digit_histograms(values, high);
  std::vector<float> out(qs.size());
  for (std::size_t k = 0; k < qs.size(); ++k)
    out[k] = std::bit_cast<float>((high[k] << 16) | find_bin(low_histograms[k], rank[k]));
  return out;
}

float order_statistic(const std::vector<float>& values, double q) { return order_statistics(values, {q})[0]; }

TriangleShapes triangle_shapes(const mesh::Mesh& m) {
  const auto nn = static_cast<std::int64_t>(m.lon_deg.size());
  const auto nt = static_cast<std::int64_t>(m.triangles.size());
  const auto* tri = m.triangles.data();
  {  // the first node out of range in triangle order, searched in parallel
    std::int64_t bad = 3 * nt;
#pragma omp parallel for schedule(static) default(none) shared(nt, nn, tri) reduction(min : bad) if (nt >= kParallelMin)
    for (std::int64_t k = 0; k < 3 * nt; ++k) {
      const NodeId v = tri[k / 3][k % 3];
      if (v < 0 || v >= nn) bad = std::min(bad, k);
    }
    if (bad < 3 * nt) throw InternalError(fmt::format("triangle_shapes: node {} out of range", tri[bad / 3][bad % 3]));
  }

  // In three passes so that at most about 33 bytes per triangle and 24 per node are alive at
  // once (the five arrays, the areas, the unit vectors and the lists round the nodes together
  // were 45 per triangle: 1.3 GB at 15"): the areas, then the neighbour ratios (the lists round
  // the nodes take the unit vectors' place), then the other four from the unit vectors again.
  TriangleShapes s;
  const auto un = static_cast<std::size_t>(nt);
  mesh::FillVector<double> area(un);  // every triangle written below
  {
    const mesh::FillVector<Vec3> p = unit_vectors(m);
    const Vec3* pp = p.data();
    double* ar = area.data();
#pragma omp parallel for schedule(static) default(none) shared(nt, tri, pp, ar) if (nt >= kParallelMin)
    for (std::int64_t t = 0; t < nt; ++t) {
      const auto& v = tri[t];
      ar[t] = std::abs(spherical_triangle_area(pp[v[0]], pp[v[1]], pp[v[2]]));
    }
  }
  s.neighbour_area_ratio.resize(un);
  // Triangle numbers of 32 bits when they fit: half the memory of the lists round the nodes.
  if (nt < (std::int64_t{1} << 31))
    neighbour_area_ratios<std::int32_t>(tri, nt, nn, area.data(), s.neighbour_area_ratio.data());
  else
    neighbour_area_ratios<std::int64_t>(tri, nt, nn, area.data(), s.neighbour_area_ratio.data());
  mesh::FillVector<double>().swap(area);

  const mesh::FillVector<Vec3> p = unit_vectors(m);
  {  // resize zeroes the arrays (their first touch): the four spread over the threads
    const std::array<std::vector<float>*, 4> arrays{&s.min_angle_deg, &s.max_angle_deg, &s.edge_ratio, &s.size_km};
    const int blocks = std::min(4, nt >= kParallelMin ? thread_count() : 1);
    quadtree::for_each_block(4, blocks, [&](int, std::int64_t begin, std::int64_t end) {
      for (std::int64_t k = begin; k < end; ++k) arrays[static_cast<std::size_t>(k)]->resize(un);
    });
  }
  const Vec3* pp = p.data();
  float* min_angle = s.min_angle_deg.data();
  float* max_angle = s.max_angle_deg.data();
  float* edge_ratio = s.edge_ratio.data();
  float* size = s.size_km.data();
#pragma omp parallel for schedule(static) default(none) \
    shared(nt, tri, pp, min_angle, max_angle, edge_ratio, size) if (nt >= kParallelMin)
  for (std::int64_t t = 0; t < nt; ++t) {
    const auto& v = tri[t];
    const Vec3 &a = pp[v[0]], &b = pp[v[1]], &c = pp[v[2]];
    const auto angles = min_max_spherical_angle_deg(a, b, c);
    min_angle[t] = static_cast<float>(angles[0]);
    max_angle[t] = static_cast<float>(angles[1]);
    const double e0 = arc(a, b), e1 = arc(b, c), e2 = arc(c, a);
    const double lo = std::min({e0, e1, e2}), hi = std::max({e0, e1, e2});
    edge_ratio[t] = lo > 0.0 ? static_cast<float>(hi / lo) : std::numeric_limits<float>::infinity();
    size[t] = static_cast<float>((e0 + e1 + e2) / 3.0 * kAuthalicRadiusKm);
  }
  return s;
}

ObtuseTriangles obtuse_triangles(const mesh::Mesh& m, double threshold_deg) {
  ObtuseTriangles o;
  const auto nn = static_cast<NodeId>(m.lon_deg.size());
  for (const auto& t : m.triangles) {
    for (const NodeId v : t)
      if (v < 0 || v >= nn) throw InternalError(fmt::format("obtuse_triangles: node {} out of range", v));
    std::array<Vec3, 3> p{};
    for (std::size_t k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(t[k]);
      p[k] = unit_vector_deg(m.lon_deg[v], m.lat_deg[v]);
    }
    const double big = min_max_spherical_angle_deg(p[0], p[1], p[2])[1];
    o.max_angle_deg = std::max(o.max_angle_deg, big);
    if (!(big > threshold_deg)) continue;
    ++o.count;
    for (const NodeId v : t)
      o.from_lattice_lat_deg = std::min(o.from_lattice_lat_deg, std::abs(m.rlat_deg[static_cast<std::size_t>(v)]));
  }
  return o;
}

SphereQuality summarize_quality(const TriangleShapes& s) {
  SphereQuality q;
  q.triangles = static_cast<std::int64_t>(s.min_angle_deg.size());
  if (q.triangles == 0) return q;
  const auto a = order_statistics(s.min_angle_deg, {0.0, 0.01, 0.05, 0.5});
  q.min_angle_p0_deg = a[0];
  q.min_angle_p1_deg = a[1];
  q.min_angle_p5_deg = a[2];
  q.min_angle_p50_deg = a[3];
  const auto m = order_statistics(s.max_angle_deg, {0.5, 0.99, 1.0});
  q.max_angle_p50_deg = m[0];
  q.max_angle_p99_deg = m[1];
  q.max_angle_max_deg = m[2];
  std::int64_t below20 = 0, below30 = 0, above120 = 0;
  const float* angle = s.min_angle_deg.data();
  const float* big = s.max_angle_deg.data();
  const std::int64_t n = q.triangles;
#pragma omp parallel for schedule(static) default(none) shared(n, angle, big) \
    reduction(+ : below20, below30, above120) if (n >= kParallelMin)
  for (std::int64_t k = 0; k < n; ++k) {
    below20 += angle[k] < 20.0f ? 1 : 0;
    below30 += angle[k] < 30.0f ? 1 : 0;
    above120 += big[k] > 120.0f ? 1 : 0;
  }
  q.max_angle_above_120_deg = above120;
  q.below_20_deg_percent = 100.0 * static_cast<double>(below20) / static_cast<double>(n);
  q.below_30_deg_percent = 100.0 * static_cast<double>(below30) / static_cast<double>(n);
  const auto e = order_statistics(s.edge_ratio, {0.5, 0.99, 1.0});
  q.edge_ratio_p50 = e[0];
  q.edge_ratio_p99 = e[1];
  q.edge_ratio_max = e[2];
  const auto r = order_statistics(s.neighbour_area_ratio, {0.99, 1.0});
  q.neighbour_area_ratio_p99 = r[0];
  q.neighbour_area_ratio_max = r[1];
  q.size_p50_km = order_statistic(s.size_km, 0.5);
  return q;
}

Json SphereQuality::json() const {
  return Json{{"triangles", triangles},
              {"min_angle_deg", Json{{"p0", round_to(min_angle_p0_deg, 100)},
                                     {"p1", round_to(min_angle_p1_deg, 100)},
                                     {"p5", round_to(min_angle_p5_deg, 100)},
                                     {"p50", round_to(min_angle_p50_deg, 100)}}},
              {"max_angle_deg", Json{{"p50", round_to(max_angle_p50_deg, 100)},
                                     {"p99", round_to(max_angle_p99_deg, 100)},
                                     {"max", round_to(max_angle_max_deg, 100)}}},
              {"max_angle_above_120_deg_triangles", max_angle_above_120_deg},
              {"min_angle_below_20_deg_percent", round_to(below_20_deg_percent, 100)},
              {"min_angle_below_30_deg_percent", round_to(below_30_deg_percent, 100)},
              {"edge_ratio", Json{{"p50", round_to(edge_ratio_p50, 1e4)},
                                  {"p99", round_to(edge_ratio_p99, 1e4)},
                                  {"max", finite_or_null(round_to(edge_ratio_max, 1e4))}}},
              {"neighbour_area_ratio", Json{{"p99", finite_or_null(round_to(neighbour_area_ratio_p99, 1e4))},
                                            {"max", finite_or_null(round_to(neighbour_area_ratio_max, 1e4))}}},
              {"size_p50_km", round_to(size_p50_km, 1000)}};
}

std::string SphereQuality::describe() const {
  return fmt::format(
      "{} triangles on the sphere: min angle p0/p1/p5/median {:.1f}°/{:.1f}°/{:.1f}°/{:.1f}°, {:.1f}% < 20°, "
      "{:.1f}% < 30°; max angle median/p99/max {:.1f}°/{:.1f}°/{:.1f}°, {} triangles > 120°; edge ratio p50/p99/max "
      "{:.2f}/{:.2f}/{:.3g}; neighbour area ratio p99/max {:.2f}/{:.3g}",
      triangles, min_angle_p0_deg, min_angle_p1_deg, min_angle_p5_deg, min_angle_p50_deg, below_20_deg_percent,
      below_30_deg_percent, max_angle_p50_deg, max_angle_p99_deg, max_angle_max_deg, max_angle_above_120_deg,
      edge_ratio_p50, edge_ratio_p99, edge_ratio_max, neighbour_area_ratio_p99, neighbour_area_ratio_max);
}

}  // namespace aq::io
