// SPDX-License-Identifier: GPL-3.0-or-later
// Initial grids of seed 004 Sec. 2 (digest B.3): TFI with normalised blending and internal sections,
// STAR with the polygon kernel as pole, and the boundary-crossing test; see initial_grids.hpp.
#include "curvilinear/elliptic/initial_grids.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace aq::curvilinear {

namespace {

// φ(t) = sin²(πt/2): φ(0) = 0, φ(1) = 1, φ'(0) = 0 (seed 004 Fig. 3a).
double phi(double t) {
  const double s = std::sin(0.5 * std::numbers::pi * t);
  return s * s;
}

PlanePoint node(const Grid2D& g, int i, int j) {
  const std::size_t k = g.at(i, j);
  return {g.x[k], g.y[k]};
}

void set_node(Grid2D& g, int i, int j, PlanePoint p) {
  const std::size_t k = g.at(i, j);
  g.x[k] = p.x;
  g.y[k] = p.y;
}

PlanePoint lerp(PlanePoint a, PlanePoint b, double t) { return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}; }

double orient(PlanePoint a, PlanePoint b, PlanePoint c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool proper_intersection(PlanePoint a, PlanePoint b, PlanePoint c, PlanePoint d) {
  const double d1 = orient(a, b, c), d2 = orient(a, b, d), d3 = orient(c, d, a), d4 = orient(c, d, b);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// Uniform Catmull–Rom curve through pts (end tangents by reflection), `per_piece` samples per piece.
std::vector<PlanePoint> catmull_rom(const std::vector<PlanePoint>& pts, int per_piece) {
  if (pts.size() == 2) return pts;
  std::vector<PlanePoint> out;
  const auto n = pts.size();
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const PlanePoint p1 = pts[k], p2 = pts[k + 1];
    const PlanePoint p0 = k > 0 ? pts[k - 1] : PlanePoint{2 * p1.x - p2.x, 2 * p1.y - p2.y};
    const PlanePoint p3 = k + 2 < n ? pts[k + 2] : PlanePoint{2 * p2.x - p1.x, 2 * p2.y - p1.y};
    for (int m = 0; m < per_piece; ++m) {
      const double t = static_cast<double>(m) / per_piece, t2 = t * t, t3 = t2 * t;
      const auto c = [&](double a0, double a1, double a2, double a3) {
        return 0.5 *
               (2 * a1 + (-a0 + a2) * t + (2 * a0 - 5 * a1 + 4 * a2 - a3) * t2 + (-a0 + 3 * a1 - 3 * a2 + a3) * t3);
      };
      out.push_back({c(p0.x, p1.x, p2.x, p3.x), c(p0.y, p1.y, p2.y, p3.y)});
    }
  }
  out.push_back(pts.back());
  return out;
}

}  // namespace

void raw_blending_weights(const std::vector<double>& q, double x, std::vector<double>& alpha) {
  const auto L = q.size();
  alpha.assign(L, 0.0);
  for (std::size_t l = 0; l < L; ++l) {
    double f = 0.0, b = 0.0;
    if (l == 0) {
      f = phi(1.0 - x);
    } else {
      f = x > q[l - 1] ? phi((x - q[l - 1]) / (q[l] - q[l - 1])) : 0.0;
    }
    if (l + 1 == L) {
      b = phi(x);
    } else {
      b = x < q[l + 1] ? phi((q[l + 1] - x) / (q[l + 1] - q[l])) : 0.0;
    }
    alpha[l] = f * b;
  }
}

void blending_weights(const std::vector<double>& q, double x, std::vector<double>& alpha) {
  raw_blending_weights(q, x, alpha);
  double sum = 0.0;
  for (const double a : alpha) sum += a;
  if (!(sum > 0.0)) throw InternalError(fmt::format("blending_weights: zero sum at q = {}", x));
  for (double& a : alpha) a /= sum;
}

void set_section_column(Grid2D& grid, const Section& section, const ControlFunction& w) {
  const int L = grid.nx_pts, M = grid.ny_pts;
  if (section.column <= 0 || section.column >= L - 1)
    throw InternalError(fmt::format("set_section_column: column {} outside 1..{}", section.column, L - 2));
  std::vector<PlanePoint> ctrl;
  ctrl.push_back(node(grid, section.column, 0));
  ctrl.insert(ctrl.end(), section.points.begin(), section.points.end());
  ctrl.push_back(node(grid, section.column, M - 1));
  const ArcPolyline line(catmull_rom(ctrl, 64));
  const std::vector<PlanePoint> pts = equidistributed_points(line, M, w);
  for (int j = 1; j < M - 1; ++j) set_node(grid, section.column, j, pts[static_cast<std::size_t>(j)]);
}

Grid2D transposed(const Grid2D& grid) {
  Grid2D t(grid.ny_pts, grid.nx_pts);
  for (int j = 0; j < grid.ny_pts; ++j)
    for (int i = 0; i < grid.nx_pts; ++i) {
      t.x[t.at(j, i)] = grid.x[grid.at(i, j)];
      t.y[t.at(j, i)] = grid.y[grid.at(i, j)];
    }
  return t;
}

void tfi_with_sections(Grid2D& grid, const std::vector<Section>& sections, SectionLines lines,
                       const ControlFunction& w) {
  Grid2D work = lines == SectionLines::kRows ? transposed(grid) : std::move(grid);
  std::vector<int> cols;
  for (const Section& s : sections) {
    set_section_column(work, s, w);
    cols.push_back(s.column);
  }
  tfi_fill(work, cols);
  grid = lines == SectionLines::kRows ? transposed(work) : std::move(work);
}

void tfi_fill(Grid2D& grid, const std::vector<int>& section_columns) {
  const int L = grid.nx_pts, M = grid.ny_pts;
  std::vector<int> cols{0};
  for (const int c : section_columns) {
    if (c <= cols.back() || c >= L - 1) throw InternalError("tfi_fill: section columns must increase inside 1..L-2");
    cols.push_back(c);
  }
  cols.push_back(L - 1);
  std::vector<double> qs(cols.size());
  for (std::size_t l = 0; l < cols.size(); ++l) qs[l] = static_cast<double>(cols[l]) / (L - 1);
  // Blending weights per column i (linear for classic TFI).
  const auto nl = cols.size();
  std::vector<double> alpha(static_cast<std::size_t>(L) * nl), a;
  for (int i = 0; i < L; ++i) {
    const double q1 = static_cast<double>(i) / (L - 1);
    if (nl == 2) {
      a = {1.0 - q1, q1};
    } else {
      blending_weights(qs, q1, a);
    }
    std::copy(a.begin(), a.end(), alpha.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(i) * nl));
  }
  const auto F = [&](int i, int j) {
    PlanePoint s{0.0, 0.0};
    for (std::size_t l = 0; l < nl; ++l) {
      const double al = alpha[static_cast<std::size_t>(i) * nl + l];
      const PlanePoint p = node(grid, cols[l], j);
      s.x += al * p.x;
      s.y += al * p.y;
    }
    return s;
  };
  std::vector<PlanePoint> south_gap(static_cast<std::size_t>(L)), north_gap(static_cast<std::size_t>(L));
  for (int i = 0; i < L; ++i) {
    const PlanePoint fs = F(i, 0), fn = F(i, M - 1), xs = node(grid, i, 0), xn = node(grid, i, M - 1);
    south_gap[static_cast<std::size_t>(i)] = {xs.x - fs.x, xs.y - fs.y};
    north_gap[static_cast<std::size_t>(i)] = {xn.x - fn.x, xn.y - fn.y};
  }
  std::vector<char> is_section(static_cast<std::size_t>(L), 0);
  for (const int c : cols) is_section[static_cast<std::size_t>(c)] = 1;
  for (int j = 1; j < M - 1; ++j) {
    const double q2 = static_cast<double>(j) / (M - 1);
    for (int i = 1; i < L - 1; ++i) {
      if (is_section[static_cast<std::size_t>(i)] != 0) continue;
      const PlanePoint f = F(i, j);
      const PlanePoint gs = south_gap[static_cast<std::size_t>(i)], gn = north_gap[static_cast<std::size_t>(i)];
      set_node(grid, i, j, {f.x + (1 - q2) * gs.x + q2 * gn.x, f.y + (1 - q2) * gs.y + q2 * gn.y});
    }
  }
}

std::vector<PlanePoint> boundary_ring(const Grid2D& g) {
  const int L = g.nx_pts, M = g.ny_pts;
  std::vector<PlanePoint> ring;
  ring.reserve(static_cast<std::size_t>(2 * (L + M)));
  for (int i = 0; i < L - 1; ++i) ring.push_back(node(g, i, 0));
  for (int j = 0; j < M - 1; ++j) ring.push_back(node(g, L - 1, j));
  for (int i = L - 1; i > 0; --i) ring.push_back(node(g, i, M - 1));
  for (int j = M - 1; j > 0; --j) ring.push_back(node(g, 0, j));
  return ring;
}

std::vector<PlanePoint> polygon_kernel(const std::vector<PlanePoint>& polygon) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& p : polygon) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  std::vector<PlanePoint> k{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, next;
  const auto n = polygon.size();
  for (std::size_t e = 0; e < n && !k.empty(); ++e) {
    const PlanePoint a = polygon[e], b = polygon[(e + 1) % n];
    if (a.x == b.x && a.y == b.y) continue;
    next.clear();
    for (std::size_t m = 0; m < k.size(); ++m) {
      const PlanePoint p = k[m], q = k[(m + 1) % k.size()];
      const double dp = orient(a, b, p), dq = orient(a, b, q);
      if (dp >= 0) next.push_back(p);
      if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0)) next.push_back(lerp(p, q, dp / (dp - dq)));
    }
    k.swap(next);
  }
  double area = 0.0;
  for (std::size_t m = 0; m < k.size(); ++m) area += orient({0, 0}, k[m], k[(m + 1) % k.size()]);
  if (k.size() < 3 || !(area > 1e-12 * (x1 - x0) * (y1 - y0))) k.clear();
  return k;
}

PlanePoint star_fill(Grid2D& grid, const ControlFunction& w) {
  const int L = grid.nx_pts, M = grid.ny_pts;
  if (L < 2 || M < 3) throw InternalError("star_fill: need at least 2 x 3 points");
  const std::vector<PlanePoint> kernel = polygon_kernel(boundary_ring(grid));
  if (kernel.empty())
    throw InputError(
        "STAR: the domain is not star-shaped (no point sees the whole boundary: the kernel of the boundary-node "
        "polygon is empty); use method tfi, ed2 or best");
  // Pole: area centroid of the kernel.
  double a = 0.0, cx = 0.0, cy = 0.0;
  for (std::size_t m = 0; m < kernel.size(); ++m) {
    const PlanePoint p = kernel[m], q = kernel[(m + 1) % kernel.size()];
    const double c = p.x * q.y - q.x * p.y;
    a += c;
    cx += (p.x + q.x) * c;
    cy += (p.y + q.y) * c;
  }
  const PlanePoint pole{cx / (3.0 * a), cy / (3.0 * a)};
  const int jm = (M - 1) / 2;
  const auto fill_row = [&](int j, const std::vector<PlanePoint>& support) {
    const std::vector<PlanePoint> pts = equidistributed_points(ArcPolyline(support), L, w);
    for (int i = 1; i < L - 1; ++i) set_node(grid, i, j, pts[static_cast<std::size_t>(i)]);
  };
  fill_row(jm, {node(grid, 0, jm), pole, node(grid, L - 1, jm)});
  // Rows at distance d from the south (dir = +1) or north (dir = −1) side, the middle at distance dm.
  std::vector<PlanePoint> support;
  for (const int dir : {+1, -1}) {
    const int side_row = dir > 0 ? 0 : M - 1;
    const int dm = dir > 0 ? jm : M - 1 - jm;
    const auto row_of = [&](int d) { return side_row + dir * d; };
    for (int d = 1; d < dm; ++d) {
      support.clear();
      for (int d2 = d; d2 >= 1; --d2)
        support.push_back(lerp(node(grid, 0, row_of(d2)), pole, static_cast<double>(d - d2) / (dm - d2)));
      for (int i = 0; i < L; ++i) support.push_back(lerp(node(grid, i, side_row), pole, static_cast<double>(d) / dm));
      for (int d2 = 1; d2 <= d; ++d2)
        support.push_back(lerp(node(grid, L - 1, row_of(d2)), pole, static_cast<double>(d - d2) / (dm - d2)));
      fill_row(row_of(d), support);
    }
  }
  return pole;
}

int self_intersecting_cells(const Grid2D& g) {
  int bad = 0;
  for (int j = 0; j + 1 < g.ny_pts; ++j)
    for (int i = 0; i + 1 < g.nx_pts; ++i) {
      const PlanePoint p1 = node(g, i, j), p2 = node(g, i + 1, j), p3 = node(g, i + 1, j + 1), p4 = node(g, i, j + 1);
      const double area = orient(p1, p2, p3) + orient(p1, p3, p4);
      if (!(area > 0.0) || proper_intersection(p1, p2, p3, p4) || proper_intersection(p2, p3, p4, p1)) ++bad;
    }
  return bad;
}

int boundary_crossings(const Grid2D& g) {
  const int L = g.nx_pts, M = g.ny_pts;
  const std::vector<PlanePoint> ring = boundary_ring(g);
  const auto n = ring.size();
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& p : ring) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  const int nb = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(n))));
  const double bw = std::max(x1 - x0, 1e-300) / nb, bh = std::max(y1 - y0, 1e-300) / nb;
  const auto bin_range = [&](double lo, double hi, double origin, double size) {
    return std::pair{std::clamp(static_cast<int>(std::floor((lo - origin) / size)), 0, nb - 1),
                     std::clamp(static_cast<int>(std::floor((hi - origin) / size)), 0, nb - 1)};
  };
  // Bins as CSR: count, prefix, fill (deterministic order).
  std::vector<int> start(static_cast<std::size_t>(nb * nb) + 1, 0), items;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t e = 0; e < n; ++e) {
      const PlanePoint a = ring[e], b = ring[(e + 1) % n];
      const auto [i0, i1] = bin_range(std::min(a.x, b.x), std::max(a.x, b.x), x0, bw);
      const auto [j0, j1] = bin_range(std::min(a.y, b.y), std::max(a.y, b.y), y0, bh);
      for (int bj = j0; bj <= j1; ++bj)
        for (int bi = i0; bi <= i1; ++bi) {
          const auto b_idx = static_cast<std::size_t>(bj * nb + bi);
          if (pass == 0) {
            ++start[b_idx + 1];
          } else {
            items[static_cast<std::size_t>(fill[b_idx]++)] = static_cast<int>(e);
          }
        }
    }
    if (pass == 0) {
      for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
      items.resize(static_cast<std::size_t>(start.back()));
    }
  }
  std::vector<int> stamp(n, -1);
  int crossings = 0, query = 0;
  const auto test = [&](PlanePoint a, PlanePoint b) {
    ++query;
    if (std::max(a.x, b.x) < x0 || std::min(a.x, b.x) > x1 || std::max(a.y, b.y) < y0 || std::min(a.y, b.y) > y1)
      return;
    const auto [i0, i1] = bin_range(std::min(a.x, b.x), std::max(a.x, b.x), x0, bw);
    const auto [j0, j1] = bin_range(std::min(a.y, b.y), std::max(a.y, b.y), y0, bh);
    for (int bj = j0; bj <= j1; ++bj)
      for (int bi = i0; bi <= i1; ++bi) {
        const auto b_idx = static_cast<std::size_t>(bj * nb + bi);
        for (int t = start[b_idx]; t < start[b_idx + 1]; ++t) {
          const auto e = static_cast<std::size_t>(items[static_cast<std::size_t>(t)]);
          if (stamp[e] == query) continue;
          stamp[e] = query;
          if (proper_intersection(a, b, ring[e], ring[(e + 1) % n])) {
            ++crossings;
            return;
          }
        }
      }
  };
  for (int j = 1; j < M - 1; ++j)
    for (int i = 0; i + 1 < L; ++i) test(node(g, i, j), node(g, i + 1, j));
  for (int i = 1; i < L - 1; ++i)
    for (int j = 0; j + 1 < M; ++j) test(node(g, i, j), node(g, i, j + 1));
  return crossings;
}

}  // namespace aq::curvilinear
