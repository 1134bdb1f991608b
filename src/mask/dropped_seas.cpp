// SPDX-License-Identifier: GPL-3.0-or-later
// Dropped wet components: measured, named and explained (see dropped_seas.hpp).
#include "mask/dropped_seas.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "core/types.hpp"
#include "mask/bit_rows.hpp"
#include "mask/k_cursor_fill.hpp"
#include "mask/passages.hpp"

namespace aq::mask {

namespace {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

// WGS84 and its authalic sphere.
constexpr double kA = 6378137.0, kF = 1.0 / 298.257223563;
constexpr double kE2 = kF * (2.0 - kF);

// q(φ) of the authalic latitude: sin ξ = q(φ) / q(90°).
double authalic_q(double lat_deg) {
  const double e = std::sqrt(kE2), s = std::sin(lat_deg * kDegToRad);
  return (1.0 - kE2) * (s / (1.0 - kE2 * s * s) - std::log((1.0 - e * s) / (1.0 + e * s)) / (2.0 * e));
}

struct Probe {
  std::int64_t i = 0, j = 0;
  int passage = 0, side = 0;  ///< side 0 = A, 1 = B
};

// The pixels under five points of each side of each passage (its centre and its quarters' centres).
std::vector<Probe> side_probes(const Lattice& lat, const PoleRotation& rot) {
  std::vector<Probe> out;
  const auto passages = critical_passages();
  for (std::size_t p = 0; p < passages.size(); ++p)
    for (int s = 0; s < 2; ++s) {
      const GeoBox& b = s == 0 ? passages[p].side_a : passages[p].side_b;
      const double w = b.lon_max_deg - b.lon_min_deg, h = b.lat_max_deg - b.lat_min_deg;
      for (const auto& [fx, fy] : {std::pair{0.5, 0.5}, {0.25, 0.25}, {0.75, 0.25}, {0.25, 0.75}, {0.75, 0.75}}) {
        const LonLat r = geographic_to_lattice(rot, {b.lon_min_deg + fx * w, b.lat_min_deg + fy * h});
        double x = 0.0, y = 0.0;
        deg_to_lattice_xy(lat, r, x, y);
        if (!on_lattice(lat, x, y)) continue;
        const auto j = static_cast<std::int64_t>(std::floor(y));
        if (j < 0 || j >= lat.ny) continue;
        auto i = static_cast<std::int64_t>(std::floor(x));
        i = lat.periodic() ? wrap_index(i, lat.nx) : i;
        if (i < 0 || i >= lat.nx) continue;
        out.push_back({i, j, static_cast<int>(p), s});
      }
    }
  std::sort(out.begin(), out.end(), [](const Probe& a, const Probe& b) { return a.j != b.j ? a.j < b.j : a.i < b.i; });
  return out;
}

struct RowRun {
  std::int64_t j = 0, a = 0, b = 0;
};

// Inland waters below sea level (or with beds below it) that a fill from the ocean leaves out,
// named where no passage names them: a point in each (in its deepest part).
struct Basin {
  const char* name;
  double lon, lat;
};
constexpr std::array<Basin, 22> kBasins{{
    {"Caspian Sea", 51.0, 42.0},       {"Caspian Sea", 51.5, 38.5},        {"Lake Ladoga", 31.3, 61.0},
    {"Lake Onega", 35.5, 61.7},        {"Qattara Depression", 27.2, 29.7}, {"Dead Sea", 35.5, 31.5},
    {"Lake Baikal", 108.3, 53.5},      {"Lake Tanganyika", 29.7, -6.5},    {"Lake Malawi", 34.5, -12.0},
    {"Lake Superior", -87.5, 47.6},    {"Lake Michigan", -87.0, 44.0},     {"Lake Huron", -82.3, 44.8},
    {"Lake Ontario", -77.8, 43.6},     {"Great Slave Lake", -114.0, 61.7}, {"Great Bear Lake", -121.0, 66.0},
    {"Lake Vanern", 13.5, 58.9},       {"Lake Vattern", 14.6, 58.3},       {"Lake Eyre", 137.3, -28.4},
    {"Turpan Depression", 89.3, 42.7}, {"Danakil Depression", 40.3, 14.2}, {"Lake Titicaca", -69.4, -15.9},
    {"Issyk-Kul", 77.3, 42.4},
}};

// The pixel under a geographic point, or (-1, -1) off the lattice.
PixelIJ pixel_under(const Lattice& lat, const PoleRotation& rot, double lon, double la) {
  double x = 0.0, y = 0.0;
  deg_to_lattice_xy(lat, geographic_to_lattice(rot, {lon, la}), x, y);
  if (!on_lattice(lat, x, y)) return {-1, -1};
  const auto j = static_cast<std::int64_t>(std::floor(y));
  auto i = static_cast<std::int64_t>(std::floor(x));
  if (lat.periodic()) i = wrap_index(i, lat.nx);
  if (j < 0 || j >= lat.ny || i < 0 || i >= lat.nx) return {-1, -1};
  return {i, j};
}

// One component while it is flooded.
struct Component {
  std::int64_t pixels = 0;
  double area = 0.0;
  std::array<double, 3> sum{};  ///< area-weighted unit vectors, lattice frame
  std::vector<RowRun> runs;
  std::vector<std::size_t> probes;  ///< indices into the probe list
  std::int64_t contacts = 0;
  PixelIJ contact{-1, -1};
  bool edge = false;
  PixelIJ first{-1, -1};
};

LonLat centre_of(const Lattice& lat, const PoleRotation& rot, PixelIJ p) {
  return lattice_to_geographic(rot, pixel_center_lattice_deg(lat, p));
}

// dst |= the 4-neighbours of src (periodic in i when the lattice is; bounded in j).
void dilate4(const Bitmap& src, Bitmap& dst, bool periodic) {
  const std::int64_t nx = src.nx(), ny = src.ny(), nw = src.words_per_row();
  dst = src;
#pragma omp parallel default(none) shared(src, dst, nx, ny, nw, periodic) if (ny * nw >= bits::kParallelMinWords)
  {
    std::vector<std::uint64_t> tmp(static_cast<std::size_t>(nw));
#pragma omp for schedule(static)
    for (std::int64_t j = 0; j < ny; ++j) {
      std::uint64_t* d = dst.row(j);
      const std::uint64_t* s = src.row(j);
      std::fill(tmp.begin(), tmp.end(), 0ULL);
      bits::rotate_row(s, tmp.data(), nx, 1, bits::Combine::kOr);   // from the east neighbour
      bits::rotate_row(s, tmp.data(), nx, -1, bits::Combine::kOr);  // from the west neighbour
      if (!periodic && nx > 1) {  // no wrap: the end columns take only their inner neighbour
        const bool e0 = ((s[0] >> 1) & 1ULL) != 0;
        const bool w1 = ((s[(nx - 2) >> 6] >> ((nx - 2) & 63)) & 1ULL) != 0;
        tmp[0] = (tmp[0] & ~1ULL) | (e0 ? 1ULL : 0ULL);
        const std::uint64_t bit = 1ULL << ((nx - 1) & 63);
        tmp[static_cast<std::size_t>((nx - 1) >> 6)] =
            (tmp[static_cast<std::size_t>((nx - 1) >> 6)] & ~bit) | (w1 ? bit : 0ULL);
      }
      for (std::int64_t w = 0; w < nw; ++w) {
        std::uint64_t v = tmp[static_cast<std::size_t>(w)];
        if (j > 0) v |= src.row(j - 1)[w];
        if (j + 1 < ny) v |= src.row(j + 1)[w];
        d[w] |= v;
      }
    }
  }
}

// The first pixel of the component's runs set in `m`, or (-1, -1).
PixelIJ first_hit(const std::vector<RowRun>& runs, const Bitmap& m) {
  for (const RowRun& r : runs) {
    const std::int64_t p = bits::find_first_set(m.row(r.j), r.a, r.b);
    if (p < r.b) return {p, r.j};
  }
  return {-1, -1};
}

std::string lonlat_text(LonLat p) {
  return fmt::format("{:.2f}°{} {:.2f}°{}", std::abs(p.lon_deg), p.lon_deg < 0 ? "W" : "E", std::abs(p.lat_deg),
                     p.lat_deg < 0 ? "S" : "N");
}

std::string quoted_list(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += fmt::format("{}\"{}\"", s.empty() ? "" : ", ", x);
  return s;
}

}  // namespace

double pixel_area_km2(const Lattice& lattice, bool rotated, std::int64_t j) {
  const double qp = authalic_q(90.0);
  const double rq2 = kA * kA * qp / 2.0;
  const double dl = lattice.pixel_deg() * kDegToRad;
  const double p1 = lattice.lat_of(j), p2 = lattice.lat_of(j + 1);
  const double ds =
      rotated ? std::sin(p2 * kDegToRad) - std::sin(p1 * kDegToRad) : (authalic_q(p2) - authalic_q(p1)) / qp;
  return rq2 * dl * ds / 1e6;
}

DroppedSeas find_dropped_seas(const Bitmap& wet, const Bitmap& filled, const Lattice& lattice, const PoleRotation& rot,
                              int cursor, double threshold_km2, const std::vector<std::string>& carved,
                              const Domain* domain) {
  DroppedSeas out;
  out.threshold_km2 = threshold_km2;
  const std::int64_t nx = lattice.nx, ny = lattice.ny;
  const bool regional = domain != nullptr && domain->regional();
  const bool periodic = lattice.periodic();
  // The fill's wet pixels, and the dropped ones.
  // The dropped pixels: one bitmap (the fill's wet pixels are `wet`, or wet ∩ domain, recomputed
  // for the rare K >= 3 fills below rather than held).
  Bitmap rem = wet;
  for (std::size_t k = 0; k < rem.words().size(); ++k)
    rem.words()[k] &= ~filled.words()[k] & (regional ? domain->inside.words()[k] : ~std::uint64_t{0});
  Bitmap outside_wet;
  if (regional) {
    outside_wet = wet;
    for (std::size_t k = 0; k < outside_wet.words().size(); ++k) outside_wet.words()[k] &= ~domain->inside.words()[k];
  }
  std::vector<double> row_area(static_cast<std::size_t>(ny)), row_sin(row_area.size()), row_cos(row_area.size());
  for (std::int64_t j = 0; j < ny; ++j) {
    row_area[static_cast<std::size_t>(j)] = pixel_area_km2(lattice, !rot.identity(), j);
    const double phi = lattice.lat_of_row(static_cast<double>(j) + 0.5) * kDegToRad;
    row_sin[static_cast<std::size_t>(j)] = std::sin(phi);
    row_cos[static_cast<std::size_t>(j)] = std::cos(phi);
  }
  const double dl = lattice.pixel_deg() * kDegToRad;
  const std::vector<Probe> probes = side_probes(lattice, rot);
  const auto passages = critical_passages();

  std::vector<Component> large;
  std::vector<std::int64_t> large_id;  // component number of each large one
  // The component of each probe's pixel: its number, kFilledComponent, or -1 (dry, not wet).
  constexpr std::int64_t kFilledComponent = -2;
  std::vector<std::int64_t> probe_comp(probes.size(), -1);
  for (std::size_t k = 0; k < probes.size(); ++k)
    if (filled.get(probes[k].i, probes[k].j)) probe_comp[k] = kFilledComponent;
  Component cur;
  const auto filled_at = [&](std::int64_t i, std::int64_t j) {
    if (j < 0 || j >= ny) return false;
    if (i < 0 || i >= nx) {
      if (!periodic) return false;
      i = wrap_index(i, nx);
    }
    return filled.get(i, j);
  };
  const auto outside_at = [&](std::int64_t i, std::int64_t j) {
    if (!regional || j < 0 || j >= ny) return false;
    if (i < 0 || i >= nx) {
      if (!periodic) return false;
      i = wrap_index(i, nx);
    }
    return outside_wet.get(i, j);
  };
  const RunVisitor visit = [&](std::int64_t j, std::int64_t a, std::int64_t b) {
    const std::int64_t n = b - a;
    const auto u = static_cast<std::size_t>(j);
    cur.pixels += n;
    cur.area += row_area[u] * static_cast<double>(n);
    // Σ over the run of the unit vectors of the pixel centres (closed form along the row).
    const double l0 = lattice.lon_at(static_cast<double>(a) + 0.5) * kDegToRad;
    const double half = 0.5 * dl;
    const double f = std::abs(std::sin(half)) > 1e-300 ? std::sin(static_cast<double>(n) * half) / std::sin(half)
                                                       : static_cast<double>(n);
    const double mid = l0 + static_cast<double>(n - 1) * half;
    const double w = row_area[u];
    cur.sum[0] += w * row_cos[u] * f * std::cos(mid);
    cur.sum[1] += w * row_cos[u] * f * std::sin(mid);
    cur.sum[2] += w * row_sin[u] * static_cast<double>(n);
    cur.runs.push_back({j, a, b});
    if (cur.first.i < 0 || j < cur.first.j || (j == cur.first.j && a < cur.first.i)) cur.first = {a, j};
    // Contact with the filled set: the ends' neighbours, the rows above and below.
    const auto contact = [&](PixelIJ p) {
      ++cur.contacts;
      if (cur.contact.i < 0) cur.contact = p;
    };
    if (filled_at(a - 1, j)) contact({a, j});
    if (filled_at(b, j)) contact({b - 1, j});
    for (const std::int64_t jj : {j - 1, j + 1}) {
      if (jj < 0 || jj >= ny) continue;
      const std::int64_t c = bits::count_range(filled.row(jj), a, b);
      if (c > 0) {
        cur.contacts += c - 1;
        contact({bits::find_first_set(filled.row(jj), a, b), j});
      }
      if (regional && !cur.edge) cur.edge = bits::count_range(outside_wet.row(jj), a, b) > 0;
    }
    if (regional && !cur.edge) cur.edge = outside_at(a - 1, j) || outside_at(b, j);
    // Passage sides in this run.
    auto it =
        std::lower_bound(probes.begin(), probes.end(), j, [](const Probe& p, std::int64_t jj) { return p.j < jj; });
    for (; it != probes.end() && it->j == j; ++it)
      if (it->i >= a && it->i < b) cur.probes.push_back(static_cast<std::size_t>(it - probes.begin()));
  };
  for (std::int64_t j = 0; j < ny; ++j) {
    std::int64_t i = bits::find_first_set(rem.row(j), 0, nx);
    while (i < nx) {
      cur = Component{};
      flood_consume_runs(rem, {i, j}, visit);
      ++out.components;
      out.pixels += cur.pixels;
      out.area_km2 += cur.area;
      for (const std::size_t k : cur.probes) probe_comp[k] = out.components - 1;
      if (cur.area > threshold_km2) {
        large.push_back(std::move(cur));
        large_id.push_back(out.components - 1);
      }
      i = bits::find_first_set(rem.row(j), i + 1, nx);
    }
  }
  rem = Bitmap();
  {
    std::vector<std::size_t> order(large.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return large[a].area > large[b].area; });
    std::vector<Component> l2;
    std::vector<std::int64_t> id2;
    for (const std::size_t k : order) {
      l2.push_back(std::move(large[k]));
      id2.push_back(large_id[k]);
    }
    large = std::move(l2);
    large_id = std::move(id2);
  }
  // The passages as edges between components (a side's probes in one, the other side's in
  // another, or in the filled set), and from the filled set outward, breadth first: for each
  // component the chain of passages (nearest the component first) that would join it to the
  // ocean when all are open.
  struct Edge {
    std::int64_t a, b;
    std::size_t passage;
    int side_a;  // the side of the passage in component a
  };
  std::vector<Edge> edges;
  for (std::size_t p = 0; p < passages.size(); ++p) {
    std::vector<std::int64_t> sa, sb;
    for (std::size_t k = 0; k < probes.size(); ++k) {
      if (static_cast<std::size_t>(probes[k].passage) != p || probe_comp[k] == -1) continue;
      auto& v = probes[k].side == 0 ? sa : sb;
      if (std::find(v.begin(), v.end(), probe_comp[k]) == v.end()) v.push_back(probe_comp[k]);
    }
    for (const std::int64_t x : sa)
      for (const std::int64_t y : sb)
        if (x != y) {
          edges.push_back({x, y, p, 0});
          edges.push_back({y, x, p, 1});
        }
  }
  std::map<std::int64_t, std::pair<std::int64_t, std::size_t>> via;  // component -> (next toward the ocean, passage)
  {
    std::vector<std::int64_t> frontier{kFilledComponent};
    std::map<std::int64_t, bool> seen{{kFilledComponent, true}};
    while (!frontier.empty()) {
      std::vector<std::int64_t> next;
      for (const std::int64_t f : frontier)
        for (const Edge& e : edges)  // table order: deterministic
          if (e.b == f && !seen[e.a]) {
            seen[e.a] = true;
            via[e.a] = {f, e.passage};
            next.push_back(e.a);
          }
      frontier = std::move(next);
    }
  }

  std::vector<DroppedSea> seas(large.size());
  for (std::size_t q = 0; q < large.size(); ++q) {
    const Component& c = large[q];
    DroppedSea& s = seas[q];
    s.pixels = c.pixels;
    s.area_km2 = c.area;
    const double len = std::sqrt(c.sum[0] * c.sum[0] + c.sum[1] * c.sum[1] + c.sum[2] * c.sum[2]);
    const LonLat lc = len > 0.0 ? LonLat{std::atan2(c.sum[1], c.sum[0]) * kRadToDeg,
                                         std::asin(std::clamp(c.sum[2] / len, -1.0, 1.0)) * kRadToDeg}
                                : pixel_center_lattice_deg(lattice, c.first);
    s.centre = lattice_to_geographic(rot, lc);
    s.reaches_domain_edge = c.edge;
    s.contact_pixels = c.contacts;
    if (c.contacts > 0) {
      s.connecting_cursor = 1;
      s.contact = centre_of(lattice, rot, c.contact);
    }
    // The chain of passages to the ocean, else the passages with a side in it (table order).
    const std::int64_t id = large_id[q];
    std::vector<std::size_t> chain;
    for (std::int64_t x = id; via.count(x) != 0; x = via[x].first) chain.push_back(via[x].second);
    s.cut = !chain.empty() && via[id].first == kFilledComponent;
    std::vector<std::size_t> named;  // a passage the chain crosses twice (its sides split between pieces) named once
    for (const std::size_t p : chain)
      if (std::find(named.begin(), named.end(), p) == named.end()) named.push_back(p);
    if (named.empty())
      for (const Edge& e : edges)
        if (e.a == id && std::find(named.begin(), named.end(), e.passage) == named.end()) named.push_back(e.passage);
    s.joined_by_chain = !chain.empty();
    if (chain.empty())
      for (const Edge& e : edges)
        if (e.a == id) {
          const char* far = e.side_a == 0 ? passages[e.passage].side_b_name : passages[e.passage].side_a_name;
          if (s.far_sides.find(far) == std::string::npos)
            s.far_sides += (s.far_sides.empty() ? "" : ", ") + std::string(far);
        }
    for (const std::size_t p : named) {
      s.passages.push_back(passages[p].name);
      for (const std::string& n : carved)
        if (find_passage(n) == &passages[p]) {
          s.passages_carved.push_back(passages[p].name);
          break;
        }
    }
    if (named.empty() && c.probes.empty())  // no passage side in it: an inland basin of the list?
      for (const Basin& bs : kBasins) {
        const PixelIJ p = pixel_under(lattice, rot, bs.lon, bs.lat);
        const bool in = p.i >= 0 && std::any_of(c.runs.begin(), c.runs.end(),
                                                [&p](const RowRun& r) { return r.j == p.j && p.i >= r.a && p.i < r.b; });
        if (in) {
          s.name = bs.name;
          s.inland = true;
          break;
        }
      }
    if (!named.empty()) {
      int side = 0;
      for (const Edge& e : edges)
        if (e.a == id && e.passage == named.front()) {
          side = e.side_a;
          break;
        }
      s.name = side == 0 ? passages[named.front()].side_a_name : passages[named.front()].side_b_name;
    } else {
      for (const std::size_t k : c.probes) {  // a side inside, both sides of one passage in it
        s.name = probes[k].side == 0 ? passages[static_cast<std::size_t>(probes[k].passage)].side_a_name
                                     : passages[static_cast<std::size_t>(probes[k].passage)].side_b_name;
        break;
      }
    }
  }
  // The widest narrower cursor that reaches a touching component (K >= 3 only: K' = 1 is the touch).
  for (int kk = cursor - 1; kk >= 2; --kk) {
    bool need = false;
    for (const DroppedSea& s : seas) need = need || (s.connecting_cursor == 1);
    if (!need) break;
    Bitmap wet_in = wet;
    if (regional)
      for (std::size_t k = 0; k < wet_in.words().size(); ++k) wet_in.words()[k] &= domain->inside.words()[k];
    const Bitmap windows = all_wet_windows(wet_in, kk);
    const Bitmap starts = all_wet_windows(filled, kk);
    Bitmap left = windows, reached(nx, ny);
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = bits::find_first_set(starts.row(j), 0, nx); i < nx;
           i = bits::find_first_set(starts.row(j), i + 1, nx))
        if (left.get(i, j)) (void)flood_consume(left, {i, j}, &reached);
    const Bitmap px = dilate_windows(reached, kk);
    for (std::size_t q = 0; q < seas.size(); ++q)
      if (seas[q].connecting_cursor == 1 && first_hit(large[q].runs, px).i >= 0) seas[q].connecting_cursor = kk;
  }
  // The land gap of each component that does not touch: 4-dilations of the filled set, on the
  // band of rows that the component and kMaxLandGapPixels + 1 rows around it span (nothing
  // farther can reach it in as many steps), so a fine lattice holds two band bitmaps, not two
  // whole ones.
  constexpr int kSteps = kMaxLandGapPixels + 1;
  for (std::size_t q = 0; q < seas.size(); ++q) {
    DroppedSea& s = seas[q];
    if (s.contact_pixels > 0) continue;
    std::int64_t jmin = ny, jmax = -1;
    for (const RowRun& r : large[q].runs) {
      jmin = std::min(jmin, r.j);
      jmax = std::max(jmax, r.j);
    }
    const std::int64_t j0 = std::max<std::int64_t>(0, jmin - kSteps), j1 = std::min(ny - 1, jmax + kSteps);
    Bitmap d(nx, j1 - j0 + 1), next;
    for (std::int64_t j = j0; j <= j1; ++j) std::copy_n(filled.row(j), filled.words_per_row(), d.row(j - j0));
    std::vector<RowRun> runs = large[q].runs;
    for (RowRun& r : runs) r.j -= j0;
    for (int step = 1; step <= kSteps; ++step) {
      dilate4(d, next, periodic);
      std::swap(d, next);
      PixelIJ hit = first_hit(runs, d);
      if (hit.i < 0) continue;
      hit.j += j0;
      s.land_gap_pixels = step - 1;
      s.gap_at = centre_of(lattice, rot, hit);
      const LonLat r = pixel_center_lattice_deg(lattice, hit);
      const double side =
          lattice.pixel_deg() * kDegToRad * (lattice.mercator() ? std::cos(r.lat_deg * kDegToRad) : 1.0);
      s.land_gap_km = static_cast<double>(s.land_gap_pixels) * side * 6371.0088;
      break;
    }
  }
  // How to keep each one.
  for (DroppedSea& s : seas) {
    if (s.inland) {
      s.keep = "it is inland water: a seed in it (mask.seeds) meshes it apart, with its own coast all round";
      continue;
    }
    std::vector<std::string> open;
    for (const std::string& p : s.passages)
      if (std::find(s.passages_carved.begin(), s.passages_carved.end(), p) == s.passages_carved.end())
        open.push_back(p);
    std::vector<std::string> keys;
    if (s.joined_by_chain && !open.empty())
      keys.push_back(fmt::format("mask.passages_open = [{}] (add to the list)", quoted_list(open)));
    else if (!open.empty())
      keys.push_back(
          fmt::format("mask.passages_open = [{}] together with what keeps the water on {} other side ({}, "
                      "left out too)",
                      quoted_list(open), open.size() == 1 ? "its" : "their", s.far_sides));
    else if (s.joined_by_chain)
      keys.push_back(
          "finer pixels (quadtree.levels) or mask.cursor = 1: the carved channel is there, the water beyond "
          "it is narrower than the cursor");
    if (s.connecting_cursor > 0)
      keys.push_back(
          fmt::format("mask.cursor = {} (every channel that narrow then stays), or a line through {} in "
                      "mask.transects",
                      s.connecting_cursor, lonlat_text(s.contact)));
    else if (!s.joined_by_chain && s.land_gap_pixels >= 0)
      keys.push_back(fmt::format("a line in mask.transects across the land gap at {}", lonlat_text(s.gap_at)));
    else if (!s.joined_by_chain)
      keys.push_back("a line in mask.transects joining it to the ocean");
    if (s.reaches_domain_edge)
      keys.push_back("a seed in it (mask.seeds) meshes it with its own open boundary, or a larger domain joins it");
    else if (s.connecting_cursor == 0 && !s.joined_by_chain)
      keys.push_back("a seed in it (mask.seeds) meshes it apart");
    for (std::size_t k = 0; k < keys.size(); ++k) s.keep += (k == 0 ? "" : "; or ") + keys[k];
  }
  out.large = std::move(seas);
  return out;
}

std::string describe(const DroppedSea& s, int cursor) {
  const std::string area =
      s.area_km2 >= 1e6 ? fmt::format("{:.3g} million km²", s.area_km2 / 1e6) : fmt::format("{:.0f} km²", s.area_km2);
  std::string what = s.name.empty() ? fmt::format("wet area around {}", lonlat_text(s.centre))
                     : s.inland     ? fmt::format("{} (inland, centre {})", s.name, lonlat_text(s.centre))
                                    : fmt::format("{} (centre {})", s.name, lonlat_text(s.centre));
  std::string why;
  if (!s.passages.empty()) {
    std::string names;
    for (const std::string& p : s.passages) names += (names.empty() ? "" : ", ") + p;
    why = !s.joined_by_chain
              ? fmt::format("with a side of {} (closed) in it", names)
              : fmt::format(
                    "behind {} ({})", names,
                    s.passages_carved.size() == s.passages.size()
                        ? "carved, but the fill does not reach it: the water beyond holds no K-cursor path at this "
                          "lattice"
                        : "closed");
  }
  std::string how;
  if (s.connecting_cursor > 0)
    how = fmt::format(
        "wet pixels join it to the filled ocean at {} ({} pixel(s) touch), but no {}-pixel cursor passes; "
        "a {}-pixel cursor would",
        lonlat_text(s.contact), s.contact_pixels, cursor, s.connecting_cursor);
  else if (s.land_gap_pixels >= 0)
    how = fmt::format(
        "no wet path joins it to the filled ocean: {} pixel(s) (about {:.0f} km) of land or water "
        "shallower than h at {}",
        s.land_gap_pixels, s.land_gap_km, lonlat_text(s.gap_at));
  else
    how = fmt::format("no wet path joins it to the filled ocean (more than {} pixels of land between)",
                      kMaxLandGapPixels);
  if (s.reaches_domain_edge) how += "; it reaches the domain's edge";
  return fmt::format("{}, {}, left out by the fill{}: {}; to keep it: {}", what, area,
                     why.empty() ? std::string() : " " + why, how, s.keep);
}

Json dropped_json(const DroppedSeas& d) {
  Json list = Json::array();
  const auto ll = [](LonLat p) { return std::isnan(p.lon_deg) ? Json() : Json::array({p.lon_deg, p.lat_deg}); };
  for (const DroppedSea& s : d.large)
    list.push_back(Json{{"name", s.name},
                        {"area_km2", s.area_km2},
                        {"pixels", s.pixels},
                        {"centre", ll(s.centre)},
                        {"inland", s.inland},
                        {"passages", s.passages},
                        {"passages_carved", s.passages_carved},
                        {"cut_by_passage", s.cut},
                        {"connecting_cursor", s.connecting_cursor},
                        {"contact_pixels", s.contact_pixels},
                        {"contact", ll(s.contact)},
                        {"land_gap_pixels", s.land_gap_pixels},
                        {"land_gap_km", s.land_gap_km},
                        {"land_gap_at", ll(s.gap_at)},
                        {"reaches_domain_edge", s.reaches_domain_edge},
                        {"keep", s.keep}});
  return Json{{"threshold_km2", d.threshold_km2},
              {"components", d.components},
              {"pixels", d.pixels},
              {"area_km2", d.area_km2},
              {"above_threshold", list}};
}

}  // namespace aq::mask
