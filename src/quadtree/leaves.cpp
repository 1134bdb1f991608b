// SPDX-License-Identifier: GPL-3.0-or-later
// Level pyramid, coastal band, refinement rules and leaf extraction (see leaves.hpp).
#include "quadtree/leaves.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/error.hpp"
#include "core/types.hpp"
#include "quadtree/bits.hpp"
#include "quadtree/parallel.hpp"
#include "raster/bathymetry.hpp"

namespace aq::quadtree {

namespace {

using Words = std::vector<std::uint64_t>;

void check_shape(const Bitmap& filled, const Lattice& lat) {
  if (filled.nx() != lat.nx || filled.ny() != lat.ny) {
    throw InternalError(fmt::format("quadtree: filled set is {}×{} pixels but the lattice is {}×{}", filled.nx(),
                                    filled.ny(), lat.nx, lat.ny));
  }
}

/// H[j] = row j of the coast pixels dilated by r along the (periodic) row: the pixels not in
/// `filled` and not `open` (the water beyond a regional domain's edge, mask/coast.hpp; null: none).
Bitmap dry_dilation(const Bitmap& filled, std::int64_t r, const Bitmap* open = nullptr) {
  Bitmap h(filled.nx(), filled.ny());
  const std::int64_t nx = filled.nx();
  const std::int64_t ny = filled.ny();
  const std::int64_t words = filled.words_per_row();
  const std::uint64_t last = bits::last_word_mask(nx);
#pragma omp parallel default(none) if (quadtree::parallel_worth(ny * words * 8)) \
    shared(filled, open, h, nx, ny, words, last, r)
  {
    Words comp(static_cast<std::size_t>(words)), tmp(static_cast<std::size_t>(words));
#pragma omp for schedule(static)
    for (std::int64_t j = 0; j < ny; ++j) {
      const std::uint64_t* src = filled.row(j);
      const std::uint64_t* beyond = open != nullptr ? open->row(j) : nullptr;
      for (std::int64_t w = 0; w < words; ++w)
        comp[static_cast<std::size_t>(w)] = ~src[w] & (beyond != nullptr ? ~beyond[w] : ~std::uint64_t{0});
      comp[static_cast<std::size_t>(words - 1)] &= last;
      bits::dilate_row(comp.data(), h.row(j), tmp.data(), nx, r);
    }
  }
  return h;
}

/// The row dilations of the coast for the band of radius r (mask/coast.hpp): `h` of the edge of
/// the filled set, and with a sea at the datum (a floodplain run) `h_sea` of the shoreline.
struct CoastDilation {
  Bitmap h, h_sea;
  const Bitmap* sea = nullptr;
};

CoastDilation coast_dilation(const Bitmap& filled, std::int64_t r, const mask::CoastSources& coast) {
  CoastDilation d;
  d.h = dry_dilation(filled, r, coast.open);
  if (coast.sea != nullptr) {
    d.h_sea = dry_dilation(*coast.sea, r, coast.open);
    d.sea = coast.sea;
  }
  return d;
}

/// out = filled row j with the coastal band removed: band = filled & OR of h rows j-r .. j+r, and
/// with a sea also sea & OR of h_sea rows j-r .. j+r (the sea side of the shoreline at the datum).
void interior_row(const Bitmap& filled, const CoastDilation& d, std::int64_t j, std::int64_t r, std::uint64_t* out) {
  const std::int64_t words = filled.words_per_row();
  const std::int64_t j0 = std::max<std::int64_t>(0, j - r);
  const std::int64_t j1 = std::min<std::int64_t>(filled.ny() - 1, j + r);
  const std::uint64_t* f = filled.row(j);
  const std::uint64_t* sea = d.sea != nullptr ? d.sea->row(j) : nullptr;
  for (std::int64_t w = 0; w < words; ++w) {
    std::uint64_t v = 0, vs = 0;
    for (std::int64_t k = j0; k <= j1; ++k) v |= d.h.row(k)[w];
    if (sea != nullptr)
      for (std::int64_t k = j0; k <= j1; ++k) vs |= d.h_sea.row(k)[w];
    out[w] = f[w] & ~v & ~(sea != nullptr ? sea[w] & vs : std::uint64_t{0});
  }
}

bool in_box(const config::BoxRule& r, double lon, double lat) {
  if (lat < r.lat_min_deg || lat > r.lat_max_deg) return false;
  const double hi = r.lon_max_deg < r.lon_min_deg ? r.lon_max_deg + 360.0 : r.lon_max_deg;
  return wrap_lon_deg(lon, r.lon_min_deg) <= hi;
}

// Whether rule `r` asks to split a level-l square of size `size_km` whose centre is in its range:
// the level form on the level-(level-1) grid only, the size form wherever the square is too large.
// The size form (size_km > 0) is a term of the size field (size/size_field.hpp), not a rule here.
template <typename Rule>
bool asks_split(const Rule& r, int l, double /*size_km*/) {
  return !(r.size_km > 0.0) && r.level == l + 1;
}

void collect_leaves(const LevelMasks& m, int levels, int l, std::int64_t a, std::int64_t b, std::vector<Leaf>& out) {
  if (m.omega[static_cast<std::size_t>(l)].get(a, b)) {
    out.push_back(Leaf{l, a, b});
    return;
  }
  if (l == levels || !m.any_at(l).get(a, b)) return;
  for (std::int64_t c = 0; c < 4; ++c) collect_leaves(m, levels, l + 1, 2 * a + (c & 1), 2 * b + (c >> 1), out);
}

void check_leaf_range(const Leaf& f, const Lattice& lat) {
  const bool ok = f.level >= 0 && f.level <= lat.levels && f.a >= 0 && f.b >= 0 &&
                  f.a < (lat.nx >> (lat.levels - f.level)) && f.b < (lat.ny >> (lat.levels - f.level));
  if (!ok) {
    throw InternalError(fmt::format("quadtree: leaf (level {}, a {}, b {}) lies outside the {}×{} lattice of {} levels",
                                    f.level, f.a, f.b, lat.nx, lat.ny, lat.levels));
  }
}

}  // namespace

LeafKey pixel_key(const Lattice& lat, std::int64_t i, std::int64_t j) {
  const int sh = lat.levels;
  const std::int64_t mask = (std::int64_t{1} << sh) - 1;
  const std::int64_t nx0 = lat.nx >> sh;
  return LeafKey{static_cast<std::uint64_t>((j >> sh) * nx0 + (i >> sh)),
                 bits::morton(static_cast<std::uint64_t>(i & mask), static_cast<std::uint64_t>(j & mask))};
}

LeafKey leaf_key(const Lattice& lat, const Leaf& f) { return pixel_key(lat, leaf_i0(lat, f), leaf_j0(lat, f)); }

Bitmap coastal_band(const Bitmap& filled, int band, const mask::CoastSources& coast) {
  Bitmap out(filled.nx(), filled.ny());
  if (band <= 0) return out;
  const CoastDilation d = coast_dilation(filled, band, coast);
  const std::int64_t ny = filled.ny();
  const std::int64_t words = filled.words_per_row();
  const std::int64_t r = band;
#pragma omp parallel default(none) if (quadtree::parallel_worth(ny * words * (2 * r + 1))) \
    shared(filled, d, out, ny, words, r)
  {
    Words inner(static_cast<std::size_t>(words));
#pragma omp for schedule(static)
    for (std::int64_t j = 0; j < ny; ++j) {
      interior_row(filled, d, j, r, inner.data());
      const std::uint64_t* f = filled.row(j);
      std::uint64_t* o = out.row(j);
      for (std::int64_t w = 0; w < words; ++w) o[w] = f[w] & ~inner[static_cast<std::size_t>(w)];
    }
  }
  return out;
}

LevelMasks make_level_masks(const Bitmap& filled, const Lattice& lat, int coast_band, const mask::CoastSources& coast) {
  check_shape(filled, lat);
  for (const Bitmap* b : {coast.open, coast.sea})
    if (b != nullptr) check_shape(*b, lat);
  const int levels = lat.levels;
  LevelMasks m;
  m.coast = coast;
  m.omega.resize(static_cast<std::size_t>(levels) + 1);
  m.any.resize(static_cast<std::size_t>(levels) + 1);
  m.omega.back() = filled;
  if (levels > 0) {
    const auto top = static_cast<std::size_t>(levels - 1);
    m.any[top] = bits::reduce(filled, true);
    for (int l = levels - 2; l >= 0; --l) {
      m.any[static_cast<std::size_t>(l)] = bits::reduce(m.any[static_cast<std::size_t>(l) + 1], true);
    }
  }
  apply_coast_band(m, coast_band);
  return m;
}

void apply_coast_band(LevelMasks& m, int coast_band) {
  if (coast_band < 0) throw InternalError(fmt::format("apply_coast_band: band of {} pixels", coast_band));
  const int levels = m.levels();
  if (levels == 0) return;
  const Bitmap& filled = m.filled();
  const auto top = static_cast<std::size_t>(levels - 1);
  if (coast_band == 0) {
    m.omega[top] = bits::reduce(filled, false);
  } else {
    const std::int64_t r = coast_band;
    const CoastDilation d = coast_dilation(filled, r, m.coast);
    Bitmap& dst = m.omega[top];
    dst = Bitmap(filled.nx() / 2, filled.ny() / 2);
    const std::int64_t rows = dst.ny();
    const std::int64_t words = filled.words_per_row();
#pragma omp parallel default(none) if (quadtree::parallel_worth(rows * words * (4 * r + 2))) \
    shared(filled, d, dst, rows, words, r)
    {
      Words lo(static_cast<std::size_t>(words)), hi(static_cast<std::size_t>(words));
#pragma omp for schedule(static)
      for (std::int64_t b = 0; b < rows; ++b) {
        interior_row(filled, d, 2 * b, r, lo.data());
        interior_row(filled, d, 2 * b + 1, r, hi.data());
        bits::reduce_rows(lo.data(), hi.data(), words, dst.row(b), false);
      }
    }
  }
  for (int l = levels - 2; l >= 0; --l) {
    m.omega[static_cast<std::size_t>(l)] = bits::reduce(m.omega[static_cast<std::size_t>(l) + 1], false);
  }
}

void apply_refinement_rules(LevelMasks& masks, const Lattice& lat, const config::QuadtreeOptions& options,
                            const PoleRotation& rotation, const raster::Bathymetry* bathy) {
  if (options.depth_rules.empty() && options.box_rules.empty()) return;
  const int levels = lat.levels;
  const bool level_depth_rules = std::any_of(options.depth_rules.begin(), options.depth_rules.end(),
                                             [](const config::DepthRule& r) { return !(r.size_km > 0.0); });
  if (level_depth_rules && bathy == nullptr) {
    throw InternalError("quadtree: depth rules need the bathymetry raster");
  }
  const int top = rules_top_level(options, levels);
  for (int l = top; l >= 0; --l) {
    Bitmap& om = masks.omega[static_cast<std::size_t>(l)];
    if (l < top) {  // keep omega monotone after the finer level's splits
      const Bitmap fine = bits::reduce(masks.omega[static_cast<std::size_t>(l) + 1], false);
      for (std::size_t k = 0; k < om.words().size(); ++k) om.words()[k] &= fine.words()[k];
    }
    apply_rules_level(om, lat, options, rotation, bathy, l, 0, 0);
  }
}

int rules_top_level(const config::QuadtreeOptions& options, int levels) {
  // The finest level a rule may split: below its level (the size form asks none here).
  int max_level = 0;
  for (const config::DepthRule& r : options.depth_rules) max_level = std::max(max_level, r.level);
  for (const config::BoxRule& r : options.box_rules) max_level = std::max(max_level, r.level);
  return std::min(levels, max_level) - 1;
}

void apply_rules_level(Bitmap& om, const Lattice& lat, const config::QuadtreeOptions& options,
                       const PoleRotation& rotation, const raster::Bathymetry* bathy, int l, std::int64_t ax,
                       std::int64_t bx) {
  const std::vector<config::DepthRule>& depth_rules = options.depth_rules;
  const std::vector<config::BoxRule>& box_rules = options.box_rules;
  // Rules are sampled at the centres of the level-l squares.
  const double step = lat.step0_deg / static_cast<double>(std::int64_t{1} << l);
  const double lon0 = lat.lon0_deg;
  const std::int64_t a0 = lat.square_origin_i(l) + ax;  // a window lattice's first level-l column, and the piece's
  const std::int64_t rows = om.ny();
  const std::int64_t words = om.words_per_row();
#pragma omp parallel for default(none) if (quadtree::parallel_worth(rows * words * 64)) \
    shared(om, rows, words, step, lat, lon0, a0, bx, l, rotation, bathy, depth_rules, box_rules) schedule(dynamic, 16)
  for (std::int64_t r0 = 0; r0 < rows; ++r0) {
    const std::int64_t b = bx + r0;
    const double centre = square_centre_row(lat, l, b);
    const double size = square_size_km(lat, l, centre);
    bool need_box = false, need_depth = false;
    for (const config::BoxRule& r : box_rules) need_box = need_box || asks_split(r, l, size);
    for (const config::DepthRule& r : depth_rules) need_depth = need_depth || asks_split(r, l, size);
    if (!need_box && !need_depth) continue;
    const double rlat = lat.lat_of_row(centre);
    std::uint64_t* row = om.row(r0);
    for (std::int64_t w = 0; w < words; ++w) {
      std::uint64_t bitsleft = row[w];
      while (bitsleft != 0) {
        const int t = std::countr_zero(bitsleft);
        bitsleft &= bitsleft - 1;
        const std::int64_t a = 64 * w + t;
        double lon = 0.0, lat_deg = 0.0;
        rotation.to_geographic(lon0 + (static_cast<double>(a + a0) + 0.5) * step, rlat, lon, lat_deg);
        bool split = false;
        if (need_box) {
          for (const config::BoxRule& r : box_rules)
            split = split || (asks_split(r, l, size) && in_box(r, lon, lat_deg));
        }
        if (!split && need_depth) {
          const double depth = -bathy->sample(lon, lat_deg);
          for (const config::DepthRule& r : depth_rules) {
            split = split || (asks_split(r, l, size) && depth >= r.min_depth_m && depth < r.max_depth_m);
          }
        }
        if (split) row[w] &= ~(1ULL << t);
      }
    }
  }
}

double square_size_km(const Lattice& lat, int level, double row_centre) {
  const double side_rad = lat.step0_deg / static_cast<double>(std::int64_t{1} << level) * kDegToRad;
  return side_rad * kEarthRadiusKm * lat.size_scale(row_centre);
}

int level_for_size(const Lattice& lat, double target_km, double row) {
  int l = 0;
  while (l < lat.levels && exceeds_size_target(square_size_km(lat, l, row), target_km)) ++l;
  return l;
}

// The shortest edge (km) a triangle of a level-(l+1) child of a level-l square of row b may have:
// the child's shortest side at the parent's poleward edge (along the row: Δλ·cos φ′ there; along
// the column: the Mercator side or Δφ), halved when the child can hold hanging nodes (l+1 < L).
double child_min_edge_km(const Lattice& lat, int l, std::int64_t b) {
  const std::int64_t s = lat.pixels_per_square(l);
  const double y0 = static_cast<double>(b * s), y1 = static_cast<double>((b + 1) * s);
  const double pole = std::max(std::fabs(lat.lat_of_row(y0)), std::fabs(lat.lat_of_row(y1)));
  const double side_rad = lat.step0_deg / static_cast<double>(std::int64_t{1} << (l + 1)) * kDegToRad;
  const double along_row = kEarthRadiusKm * side_rad * std::cos(pole * kDegToRad);
  const double along_col =
      lat.mercator() ? along_row : kEarthRadiusKm * (lat.lat_of_row(y1) - lat.lat_of_row(y0)) / 2.0 * kDegToRad;
  const double side = std::min(along_row, along_col);
  return l + 1 < lat.levels ? side / 2.0 : side;
}

// Whether the CFL edge bound of `field` lets the level-l square (a, b) be split (its children's
// shortest possible edge, child_edge_km, is not below the bound anywhere over the square).
bool cfl_allows_split(const size::SizeField& field, int l, std::int64_t a, std::int64_t b, double child_edge_km) {
  return !field.has_cfl() || child_edge_km * (1.0 + 1e-9) >= field.cfl_edge_over_square(l, a, b);
}

void apply_size_field(LevelMasks& masks, const Lattice& lat, const size::SizeField& field) {
  const int levels = masks.levels();
  if (levels == 0 || !field.active()) return;
  const double band_km = field.band_km();
  // The coastal band's pyramid (any band pixel in the square), only when its term is on.
  std::vector<Bitmap> band;
  if (band_km > 0.0) {
    band.resize(static_cast<std::size_t>(levels));
    band[static_cast<std::size_t>(levels - 1)] =
        bits::reduce(coastal_band(masks.filled(), field.band_radius(), masks.coast), true);
    for (int l = levels - 2; l >= 0; --l)
      band[static_cast<std::size_t>(l)] = bits::reduce(band[static_cast<std::size_t>(l) + 1], true);
  }
  for (int l = levels - 1; l >= 0; --l) {
    Bitmap& om = masks.omega[static_cast<std::size_t>(l)];
    if (l + 1 < levels) {  // keep omega monotone after the finer level's splits
      const Bitmap fine = bits::reduce(masks.omega[static_cast<std::size_t>(l) + 1], false);
      for (std::size_t k = 0; k < om.words().size(); ++k) om.words()[k] &= fine.words()[k];
    }
    apply_size_field_level(om, band_km > 0.0 ? &band[static_cast<std::size_t>(l)] : nullptr, lat, field, l, 0, 0);
  }
}

void apply_size_field_level(Bitmap& om, const Bitmap* band, const Lattice& lat, const size::SizeField& field, int l,
                            std::int64_t a0, std::int64_t b0) {
  const double band_km = field.band_km();
  const bool grid = field.has_grid();
  const std::int64_t words = om.words_per_row();
  const std::int64_t rows = om.ny();
#pragma omp parallel for default(none) if (quadtree::parallel_worth(rows * words * 64)) \
    shared(om, band, field, lat, l, rows, words, band_km, grid, a0, b0) schedule(dynamic, 16)
  for (std::int64_t r = 0; r < rows; ++r) {
    const std::int64_t b = b0 + r;
    const double size = square_size_km(lat, l, square_centre_row(lat, l, b));
    const double child_edge = child_min_edge_km(lat, l, b);
    std::uint64_t* row = om.row(r);
    const bool band_splits = band != nullptr && band_km > 0.0 && exceeds_size_target(size, band_km);
    const std::uint64_t* in_band = band_splits ? band->row(r) : nullptr;
    for (std::int64_t w = 0; w < words; ++w) {
      std::uint64_t keep = row[w];
      std::uint64_t split = in_band != nullptr ? keep & in_band[w] : 0;
      if (grid) {
        std::uint64_t left = keep & ~split;
        while (left != 0) {
          const int t = std::countr_zero(left);
          left &= left - 1;
          if (exceeds_size_target(size, field.grid_min_over_square(l, a0 + 64 * w + t, b))) split |= 1ULL << t;
        }
      }
      if (field.has_cfl()) {  // the CFL bound is applied last: it refuses splits, never asks one
        std::uint64_t left = split;
        while (left != 0) {
          const int t = std::countr_zero(left);
          left &= left - 1;
          if (!cfl_allows_split(field, l, a0 + 64 * w + t, b, child_edge)) split &= ~(1ULL << t);
        }
      }
      row[w] = keep & ~split;
    }
  }
}

void grading_radii(const Lattice& lat, int v, double g, std::vector<std::int64_t>& rx, std::vector<std::int64_t>& ry) {
  // Radii (in level-v squares) per row: a run of n squares of side a spans n·dx along the row
  // and n·dy along the column; it keeps the grading when a/(√2·n·d) <= g.
  const std::int64_t n = lat.nx >> (lat.levels - v), rows = lat.ny >> (lat.levels - v);
  rx.assign(static_cast<std::size_t>(rows), 0);
  ry.assign(static_cast<std::size_t>(rows), 0);
  const double side_rad = lat.step0_deg / static_cast<double>(std::int64_t{1} << v) * kDegToRad;
  for (std::int64_t b = 0; b < rows; ++b) {
    // Conservative over the square's rows: its size at the equatorward edge, its sides at the
    // poleward one (the runs are measured at the rows they cross).
    const double p0 = lat.lat_of_row(static_cast<double>(b * lat.pixels_per_square(v)));
    const double p1 = lat.lat_of_row(static_cast<double>((b + 1) * lat.pixels_per_square(v)));
    const double eq = (p0 < 0.0) != (p1 < 0.0) ? 0.0 : std::min(std::fabs(p0), std::fabs(p1));
    const double pole = std::max(std::fabs(p0), std::fabs(p1));
    const double c_eq = std::cos(eq * kDegToRad);
    const double a_km = kEarthRadiusKm * side_rad * (lat.mercator() ? c_eq : std::sqrt(c_eq));
    const double dx = kEarthRadiusKm * side_rad * std::cos(pole * kDegToRad);
    const double dy = lat.mercator() ? dx : kEarthRadiusKm * side_rad;
    const auto radius = [&](double d, std::int64_t cap) {
      const double r = std::ceil(a_km / (std::sqrt(2.0) * g * std::max(d, 1e-9)) - 1e-9);
      return std::min<std::int64_t>(cap, std::max<std::int64_t>(1, static_cast<std::int64_t>(std::min(r, 1e12))));
    };
    rx[static_cast<std::size_t>(b)] = radius(dx, n);
    ry[static_cast<std::size_t>(b)] = radius(dy, rows);
  }
}

GradeStats grade_levels(LevelMasks& masks, const Lattice& lat, const size::SizeField& field) {
  GradeStats st;
  const int levels = masks.levels();
  const double g = field.gradation();
  if (levels < 2 || !field.has_grid() || !(g > 0.0)) return st;
  for (int v = levels - 1; v >= 1; --v) {
    const GradeStats s = grade_level(masks.omega, masks.any_at(v), lat, field, v);
    st.splits += s.splits;
    st.cfl_refused += s.cfl_refused;
    if (v == levels - 1) st.radius_at_equator = s.radius_at_equator;
  }
  return st;
}

GradeStats grade_level(std::vector<Bitmap>& omega, const Bitmap& any, const Lattice& lat, const size::SizeField& field,
                       int v) {
  GradeStats st;
  const double g = field.gradation();
  const Bitmap& om = omega[static_cast<std::size_t>(v)];
  const std::int64_t n = om.nx(), rows = om.ny(), words = om.words_per_row();
  std::vector<std::int64_t> rx, ry;
  grading_radii(lat, v, g, rx, ry);
  st.radius_at_equator = rx[static_cast<std::size_t>(rows / 2)];
  // Split squares of level v (holding finer leaves), row by row.
  Bitmap split(n, rows);
  for (std::int64_t b = 0; b < rows; ++b)
    for (std::int64_t w = 0; w < words; ++w) split.row(b)[w] = any.row(b)[w] & ~om.row(b)[w];
  // T: the split squares dilated by (rx, ry) of the target row.
  Bitmap near(n, rows);
#pragma omp parallel default(none) if (quadtree::parallel_worth(rows * words * 16)) shared(split, near, rx, ry, n, rows, words)
  {
    Words acc(static_cast<std::size_t>(words)), tmp(static_cast<std::size_t>(words));
#pragma omp for schedule(static)
    for (std::int64_t b = 0; b < rows; ++b) {
      std::fill(acc.begin(), acc.end(), 0ULL);
      const std::int64_t r = ry[static_cast<std::size_t>(b)];
      for (std::int64_t q = std::max<std::int64_t>(0, b - r); q <= std::min(rows - 1, b + r); ++q)
        for (std::int64_t w = 0; w < words; ++w) acc[static_cast<std::size_t>(w)] |= split.row(q)[w];
      bits::dilate_row(acc.data(), near.row(b), tmp.data(), n, rx[static_cast<std::size_t>(b)]);
    }
  }
  // Their parents (level v-1) are split, unless the CFL bound refuses it.
  const Bitmap parents = bits::reduce(near, true);
  Bitmap& up = omega[static_cast<std::size_t>(v) - 1];
  const std::int64_t prow = up.ny(), pwords = up.words_per_row();
  std::int64_t splits = 0, refused = 0;
#pragma omp parallel for default(none) if (quadtree::parallel_worth(prow * pwords * 16)) \
    shared(up, parents, field, lat, v, prow, pwords) reduction(+ : splits, refused) schedule(static)
  for (std::int64_t b = 0; b < prow; ++b) {
    const double child_edge = child_min_edge_km(lat, v - 1, b);
    std::uint64_t* row = up.row(b);
    for (std::int64_t w = 0; w < pwords; ++w) {
      std::uint64_t hit = row[w] & parents.row(b)[w];
      std::uint64_t left = hit;
      while (left != 0) {
        const int t = std::countr_zero(left);
        left &= left - 1;
        if (!cfl_allows_split(field, v - 1, 64 * w + t, b, child_edge)) {
          hit &= ~(1ULL << t);
          ++refused;
        }
      }
      splits += bits::popcount64(hit);
      row[w] &= ~hit;
    }
  }
  st.splits = splits;
  st.cfl_refused = refused;
  for (int l = v - 2; l >= 0; --l) {  // keep omega monotone
    Bitmap& o = omega[static_cast<std::size_t>(l)];
    const Bitmap fine = bits::reduce(omega[static_cast<std::size_t>(l) + 1], false);
    for (std::size_t k = 0; k < o.words().size(); ++k) o.words()[k] &= fine.words()[k];
  }
  return st;
}

std::vector<Leaf> extract_leaves(const LevelMasks& masks, const Lattice& lat) {
  const int levels = masks.levels();
  const std::int64_t nx0 = lat.nx >> lat.levels;
  const std::int64_t ny0 = lat.ny >> lat.levels;
  const std::int64_t roots = nx0 * ny0;
  const int blocks = block_count(roots, 16);
  std::vector<std::vector<Leaf>> parts(static_cast<std::size_t>(blocks));
  for_each_block(roots, blocks, [&](int t, std::int64_t begin, std::int64_t end) {
    std::vector<Leaf>& out = parts[static_cast<std::size_t>(t)];
    for (std::int64_t r = begin; r < end; ++r) collect_leaves(masks, levels, 0, r % nx0, r / nx0, out);
  });
  std::size_t total = 0;
  for (int t = 0; t < blocks; ++t) total += parts[static_cast<std::size_t>(t)].size();
  std::vector<Leaf> leaves;
  leaves.reserve(total);
  for (int t = 0; t < blocks; ++t) {
    std::vector<Leaf>& p = parts[static_cast<std::size_t>(t)];
    leaves.insert(leaves.end(), p.begin(), p.end());
    std::vector<Leaf>().swap(p);
  }
  return leaves;
}

std::vector<std::int64_t> count_leaves_per_level(const LevelMasks& masks) {
  const int levels = masks.levels();
  std::vector<std::int64_t> counts(static_cast<std::size_t>(levels) + 1, 0);
  counts[0] = masks.omega[0].count();
  for (int l = 1; l <= levels; ++l) {
    const Bitmap& om = masks.omega[static_cast<std::size_t>(l)];
    const Bitmap& parent = masks.omega[static_cast<std::size_t>(l) - 1];
    const std::int64_t rows = om.ny();
    const std::int64_t words = om.words_per_row();
    std::int64_t n = 0;
#pragma omp parallel default(none) if (quadtree::parallel_worth(rows * words * 2)) shared(om, parent, rows, words) reduction(+ : n)
    {
      Words up(static_cast<std::size_t>(words));
#pragma omp for schedule(static)
      for (std::int64_t b = 0; b < rows; ++b) {
        bits::expand_row(parent.row(b / 2), up.data(), words);
        const std::uint64_t* row = om.row(b);
        for (std::int64_t w = 0; w < words; ++w) n += bits::popcount64(row[w] & ~up[static_cast<std::size_t>(w)]);
      }
    }
    counts[static_cast<std::size_t>(l)] = n;
  }
  return counts;
}

bool leaves_sorted(const std::vector<Leaf>& leaves, const Lattice& lat) {
  const auto n = static_cast<std::int64_t>(leaves.size());
  const int blocks = block_count(n, 8);
  std::vector<char> ok(static_cast<std::size_t>(blocks), 1);
  for_each_block(n, blocks, [&](int t, std::int64_t begin, std::int64_t end) {
    if (begin >= end) return;
    const std::int64_t first = std::max<std::int64_t>(begin, 1);
    LeafKey prev = leaf_key(lat, leaves[static_cast<std::size_t>(first - 1)]);
    for (std::int64_t k = first; k < end; ++k) {
      const LeafKey key = leaf_key(lat, leaves[static_cast<std::size_t>(k)]);
      if (!(prev < key)) {
        ok[static_cast<std::size_t>(t)] = 0;
        return;
      }
      prev = key;
    }
  });
  return std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; });
}

std::vector<std::int64_t> root_row_starts(const std::vector<Leaf>& leaves, const Lattice& lat) {
  const std::int64_t ny0 = lat.ny >> lat.levels;
  std::vector<std::int64_t> start(static_cast<std::size_t>(ny0) + 1, static_cast<std::int64_t>(leaves.size()));
  std::int64_t next = 0;
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    const std::int64_t b0 = leaf_j0(lat, leaves[k]) >> lat.levels;
    while (next <= b0) start[static_cast<std::size_t>(next++)] = static_cast<std::int64_t>(k);
  }
  return start;
}

namespace {

/// Calls fn(leaf) for every leaf: in parallel by level-0 rows when the leaves are sorted (the
/// leaves of a level-0 row touch only the rows of their band at every level), else serially.
template <class Fn>
void for_leaves_by_band(const std::vector<Leaf>& leaves, const Lattice& lat, bool sorted, const Fn& fn) {
  if (!sorted) {
    for (const Leaf& f : leaves) fn(f);
    return;
  }
  const std::vector<std::int64_t> starts = root_row_starts(leaves, lat);
  const auto ny0 = static_cast<std::int64_t>(starts.size()) - 1;
  const int blocks = block_count(static_cast<std::int64_t>(leaves.size()), 4);
  for_each_block(ny0, blocks, [&](int, std::int64_t begin, std::int64_t end) {
    for (std::int64_t k = starts[static_cast<std::size_t>(begin)]; k < starts[static_cast<std::size_t>(end)]; ++k) {
      fn(leaves[static_cast<std::size_t>(k)]);
    }
  });
}

}  // namespace

Bitmap leaf_coverage(const std::vector<Leaf>& leaves, const Lattice& lat, bool* sorted_out) {
  Bitmap cov(lat.nx, lat.ny);
  std::int64_t area = 0;
  for (const Leaf& f : leaves) {
    check_leaf_range(f, lat);
    area += leaf_size(lat, f) * leaf_size(lat, f);
  }
  const bool sorted = leaves_sorted(leaves, lat);
  if (sorted_out != nullptr) *sorted_out = sorted;
  for_leaves_by_band(leaves, lat, sorted, [&](const Leaf& f) {
    const std::int64_t s = leaf_size(lat, f);
    const std::int64_t i0 = leaf_i0(lat, f);
    const std::int64_t j0 = leaf_j0(lat, f);
    for (std::int64_t j = j0; j < j0 + s; ++j) bits::set_range(cov.row(j), i0, i0 + s);
  });
  const std::int64_t covered = cov.count();
  if (covered != area) {
    throw InternalError(fmt::format("quadtree: leaves overlap ({} pixels in leaves, {} covered)", area, covered));
  }
  return cov;
}

LevelMasks masks_from_leaves(const std::vector<Leaf>& leaves, const Lattice& lat) {
  const int levels = lat.levels;
  LevelMasks m;
  m.omega.resize(static_cast<std::size_t>(levels) + 1);
  m.any.resize(static_cast<std::size_t>(levels) + 1);
  bool sorted = false;
  m.omega.back() = leaf_coverage(leaves, lat, &sorted);
  for (int l = 0; l < levels; ++l) {
    m.omega[static_cast<std::size_t>(l)] = Bitmap(lat.nx >> (levels - l), lat.ny >> (levels - l));
  }
  for_leaves_by_band(leaves, lat, sorted, [&](const Leaf& f) {
    for (int l = f.level; l < levels; ++l) {
      Bitmap& om = m.omega[static_cast<std::size_t>(l)];
      const int k = l - f.level;
      for (std::int64_t b = f.b << k; b < (f.b + 1) << k; ++b) bits::set_range(om.row(b), f.a << k, (f.a + 1) << k);
    }
  });
  for (int l = levels - 1; l >= 0; --l) {
    m.any[static_cast<std::size_t>(l)] = bits::reduce(m.any_at(l + 1), true);
  }
  return m;
}

LeafLocator::LeafLocator(const std::vector<Leaf>& leaves, const Lattice& lat) : leaves_(leaves), lat_(lat) {
  keys_.resize(leaves.size());
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    keys_[k] = leaf_key(lat, leaves[k]);
    if (k > 0 && !(keys_[k - 1] < keys_[k])) {
      throw InternalError(fmt::format("quadtree: leaves {} and {} are not in the deterministic order", k - 1, k));
    }
  }
}

std::int64_t LeafLocator::find(std::int64_t i, std::int64_t j) const {
  if (j < 0 || j >= lat_.ny) return -1;
  const std::int64_t iw = wrap_index(i, lat_.nx);
  const LeafKey key = pixel_key(lat_, iw, j);
  const auto it = std::upper_bound(keys_.begin(), keys_.end(), key);
  if (it == keys_.begin()) return -1;
  const auto k = static_cast<std::int64_t>(it - keys_.begin()) - 1;
  const Leaf& f = leaves_[static_cast<std::size_t>(k)];
  const std::int64_t s = leaf_size(lat_, f);
  const std::int64_t i0 = leaf_i0(lat_, f);
  const std::int64_t j0 = leaf_j0(lat_, f);
  return (iw >= i0 && iw < i0 + s && j >= j0 && j < j0 + s) ? k : -1;
}

}  // namespace aq::quadtree
