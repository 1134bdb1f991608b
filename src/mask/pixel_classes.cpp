// SPDX-License-Identifier: GPL-3.0-or-later
// Pixel classes (seed 002 §2; ARCHITECTURE §4.2): vertex sampling row by row into a wet-vertex
// bitmap, the 4-vertex rule by word arithmetic, and the optional area rule.
#include "mask/pixel_classes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/cancel.hpp"
#include "core/error.hpp"
#include "core/row_progress.hpp"
#include "mask/bit_rows.hpp"
#include "mask/lattice_coords.hpp"
#include "raster/value_bounds.hpp"

namespace aq::mask {

namespace {

// Lattices with fewer samples than this are classified by one thread.
constexpr std::int64_t kParallelMinSamples = std::int64_t{1} << 16;

// The rotated vertex rule works on units of vertices [I0, I1) × [J0, J1) within one bitmap word
// (I1 - I0 <= 64): a unit whose image lies where every raster value is on one side of the
// threshold is decided without sampling; an undecided one is split, and sampled vertex by vertex
// at the last level. Sizes per level (columns × rows): 64 × 32, 16 × 8. (A third level of 4 × 4
// decided only a quarter of its units on the 1' run and cost more than it saved.)
constexpr std::array<std::int64_t, 2> kUnitCols = {64, 16};
constexpr std::array<std::int64_t, 2> kUnitRows = {32, 8};

struct RotatedSampler {
  const raster::Bathymetry& bathy;
  const Lattice& lattice;
  const PoleRotation& rot;
  const LatticeRowMapper& mapper;
  const raster::ValueBounds& bounds;
  double threshold;
  Bitmap& wv;

  // +1 every vertex of the unit samples wet, -1 dry, 0 undecided. The unit is a λ′–φ′ rectangle
  // of the rotated frame; it lies in the cap around its centre whose radius is the largest
  // distance to a corner (a rotation keeps distances), and the cap's geographic box bounds it.
  [[nodiscard]] int side(std::int64_t I0, std::int64_t I1, std::int64_t J0, std::int64_t J1) const {
    if (!bounds.available()) return 0;
    const LonLat a = vertex_lattice_deg(lattice, I0, J0), b = vertex_lattice_deg(lattice, I1 - 1, J1 - 1);
    const LonLat c{0.5 * (a.lon_deg + b.lon_deg), 0.5 * (a.lat_deg + b.lat_deg)};
    double r = 0.0;
    for (const LonLat q : {a, b, LonLat{a.lon_deg, b.lat_deg}, LonLat{b.lon_deg, a.lat_deg}})
      r = std::max(r, angular_distance_deg(c, q));
    r += 1e-9;
    const LonLat g = lattice_to_geographic(rot, c);
    if (std::abs(g.lat_deg) + r >= 89.0) return 0;  // the cap reaches a pole: no λ box
    const double half = std::asin(std::min(1.0, std::sin(r * kDegToRad) / std::cos(g.lat_deg * kDegToRad))) * kRadToDeg;
    if (!bathy.info().global_lon && (g.lon_deg - half < -180.0 || g.lon_deg + half > 180.0)) return 0;
    return raster::side_of_threshold(bounds.in_box(g.lon_deg - half, g.lon_deg + half, g.lat_deg - r, g.lat_deg + r),
                                     threshold);
  }

  // Decides or samples the unit at `level` (see kUnitCols); its bits are in word I0 / 64 of
  // rows J0..J1-1, owned by the calling thread.
  void unit(std::size_t level, std::int64_t I0, std::int64_t I1, std::int64_t J0, std::int64_t J1,
            std::vector<double>& lon, std::vector<double>& lat, std::vector<double>& val) const {
    const int s = side(I0, I1, J0, J1);
    if (s < 0) return;  // all dry: the bits stay clear
    const std::int64_t w = I0 >> 6;
    if (s > 0) {
      const std::int64_t n = I1 - I0, shift = I0 & 63;
      const std::uint64_t bits = (n == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1) << shift;
      for (std::int64_t J = J0; J < J1; ++J) wv.row(J)[w] |= bits;
      return;
    }
    if (level + 1 < kUnitCols.size()) {
      const std::int64_t dc = kUnitCols[level + 1], dr = kUnitRows[level + 1];
      for (std::int64_t j = J0; j < J1; j += dr)
        for (std::int64_t i = I0; i < I1; i += dc)
          unit(level + 1, i, std::min(I1, i + dc), j, std::min(J1, j + dr), lon, lat, val);
      return;
    }
    const std::int64_t n = I1 - I0;
    for (std::int64_t J = J0; J < J1; ++J) {
      mapper.map_row(static_cast<double>(J), static_cast<std::size_t>(I0), static_cast<std::size_t>(I1), lon.data(),
                     lat.data());
      bathy.sample_points(lon.data(), lat.data(), n, val.data());
      std::uint64_t word = 0;
      bits::threshold_row(val.data(), n, threshold, &word);
      wv.row(J)[w] |= word << (I0 & 63);
    }
  }
};

// Vertex rule through the pole rotation, unit by unit (RotatedSampler): open ocean and inland,
// most of a fine lattice, are decided from the raster's value bounds without sampling; the rest
// is mapped (lattice -> geographic) and sampled vertex by vertex. The same bits as sampling every
// vertex: the bounds hold every bilinear sample, and without them (bicubic) every vertex is
// sampled.
void sample_rotated(const raster::Bathymetry& bathy, const Lattice& lattice, const PoleRotation& rot, double threshold,
                    const ProgressFn& progress, Bitmap& wv) {
  const std::int64_t nx = lattice.nx, nv = lattice.ny + 1;
  std::vector<double> xs(static_cast<std::size_t>(nx));
  for (std::int64_t I = 0; I < nx; ++I) xs[static_cast<std::size_t>(I)] = static_cast<double>(I);
  const LatticeRowMapper mapper(lattice, rot, xs);
  // Blocks of 4 raster cells when a lattice pixel is under 2 cells, 8 otherwise (the bounds'
  // coarser levels serve the large units): on the 1' run the 16 × 8 units decide 52 % instead of
  // 42 %, and 16 % fewer vertices are sampled.
  const auto& in = bathy.info();
  const double cells_per_pixel = lattice.pixel_deg() / std::min(in.dlon, in.dlat);
  const raster::ValueBounds bounds(bathy, cells_per_pixel < 2.0 ? 4 : 8);
  const RotatedSampler sampler{bathy, lattice, rot, mapper, bounds, threshold, wv};
  const std::int64_t ntx = bits::words_for(nx), rows0 = kUnitRows[0], nty = (nv + rows0 - 1) / rows0;
  RowProgress rp(progress, nty, "vertices");
#pragma omp parallel default(none) shared(sampler, rp, nx, nv, ntx, nty, rows0) if (nx * nv >= kParallelMinSamples)
  {
    std::vector<double> lon(64), lat(64), val(64);
#pragma omp for schedule(static, 1)
    for (std::int64_t ty = 0; ty < nty; ++ty) {
      if (cancel_requested()) continue;  // a stop request (core/cancel.hpp): the rest is skipped, thrown below
      const std::int64_t J0 = ty * rows0, J1 = std::min(nv, J0 + rows0);
      for (std::int64_t tx = 0; tx < ntx; ++tx)
        sampler.unit(0, tx * 64, std::min(nx, tx * 64 + 64), J0, J1, lon, lat, val);
      rp.row_done();
    }
  }
  throw_if_cancelled();
  rp.finish();
}

// Per-row accumulation of the area rule: has a point, all points wet, some point wet.
struct AreaFlags {
  std::vector<unsigned char> has, all_wet, any_wet;
  explicit AreaFlags(std::int64_t n) : has(static_cast<std::size_t>(n)), all_wet(has.size()), any_wet(has.size()) {}
  void reset() {
    std::fill(has.begin(), has.end(), 0);
    std::fill(all_wet.begin(), all_wet.end(), 1);
    std::fill(any_wet.begin(), any_wet.end(), 0);
  }
  void add(std::int64_t i, bool wet) {
    const auto s = static_cast<std::size_t>(i);
    has[s] = 1;
    all_wet[s] = static_cast<unsigned char>(all_wet[s] & static_cast<unsigned char>(wet));
    any_wet[s] = static_cast<unsigned char>(any_wet[s] | static_cast<unsigned char>(wet));
  }
  // Overwrites the vertex-rule classes of pixels that had points.
  void store(std::int64_t nx, std::uint64_t* wet_row, std::uint64_t* coastal_row) const {
    for (std::int64_t i = 0; i < nx; ++i) {
      const auto s = static_cast<std::size_t>(i);
      if (has[s] == 0) continue;
      const std::uint64_t bit = std::uint64_t{1} << (i & 63);
      const std::int64_t w = i >> 6;
      wet_row[w] = all_wet[s] != 0 ? (wet_row[w] | bit) : (wet_row[w] & ~bit);
      coastal_row[w] = (any_wet[s] != 0 && all_wet[s] == 0) ? (coastal_row[w] | bit) : (coastal_row[w] & ~bit);
    }
  }
};

// Area rule, lattice aligned with the raster axes: raster points inside each closed pixel.
void classify_area_aligned(const raster::Bathymetry& bathy, const Lattice& lattice, double threshold,
                           const ProgressFn& progress, Bitmap& wet, Bitmap& coastal) {
  const auto& in = bathy.info();
  const std::int64_t nx = lattice.nx, ny = lattice.ny;
  const double eps = 1e-9;
  const double d = lattice.pixel_deg();
  // Raster column range [c_lo, c_hi] (unwrapped) of each pixel column.
  std::vector<std::int64_t> c_lo(static_cast<std::size_t>(nx)), c_hi(c_lo.size());
  const double width = static_cast<double>(in.ncols) * in.dlon;
  const double west = in.global_lon ? in.lon_first : in.lon_first - 0.5 * (360.0 - width);
  for (std::int64_t i = 0; i < nx; ++i) {
    const double x = (wrap_lon_deg(lattice.lon_of(i), west) - in.lon_first) / in.dlon;
    auto lo = static_cast<std::int64_t>(std::ceil(x - eps));
    auto hi = static_cast<std::int64_t>(std::floor(x + d / in.dlon + eps));
    if (!in.global_lon) {
      lo = std::max<std::int64_t>(lo, 0);
      hi = std::min<std::int64_t>(hi, in.ncols - 1);
    }
    c_lo[static_cast<std::size_t>(i)] = lo;
    c_hi[static_cast<std::size_t>(i)] = hi;
  }
  RowProgress rp(progress, ny, "pixels (area)");
#pragma omp parallel default(none) shared(bathy, lattice, in, c_lo, c_hi, wet, coastal, rp, ny, nx, d, eps, \
                                          threshold) if (nx * ny >= kParallelMinSamples)
  {
    AreaFlags flags(nx);
#pragma omp for schedule(static)
    for (std::int64_t j = 0; j < ny; ++j) {
      flags.reset();
      const double y = (lattice.lat_of(j) - in.lat_first) / in.dlat;
      // The row's height in φ: Δ on the lon-lat lattice, φ(j+1) − φ(j) on the Mercator one.
      const double dy = lattice.mercator() ? (lattice.lat_of(j + 1) - lattice.lat_of(j)) / in.dlat : d / in.dlat;
      const auto r_lo = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil(y - eps)));
      const auto r_hi = std::min<std::int64_t>(in.nrows - 1, static_cast<std::int64_t>(std::floor(y + dy + eps)));
      for (std::int64_t r = r_lo; r <= r_hi; ++r) {
        for (std::int64_t i = 0; i < nx; ++i) {
          const auto s = static_cast<std::size_t>(i);
          for (std::int64_t c = c_lo[s]; c <= c_hi[s]; ++c)
            flags.add(i, static_cast<double>(bathy.value(c, r)) <= threshold);
        }
      }
      flags.store(nx, wet.row(j), coastal.row(j));
      rp.row_done();
    }
  }
  rp.finish();
}

// Area rule through the pole rotation: (n+1)×(n+1) bilinear samples per pixel. Each thread
// handles whole pixel rows, one sample row (nx·n points, periodic) at a time.
void classify_area_rotated(const raster::Bathymetry& bathy, const Lattice& lattice, const PoleRotation& rot,
                           double threshold, const ProgressFn& progress, Bitmap& wet, Bitmap& coastal) {
  const auto& in = bathy.info();
  const std::int64_t nx = lattice.nx, ny = lattice.ny;
  const auto n = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(std::ceil(lattice.pixel_deg() / std::min(in.dlon, in.dlat) - 1e-9)));
  const std::int64_t cols = nx * n;  // sample columns along the row (periodic)
  const auto dn = static_cast<double>(n);
  // Sample (a, b) of pixel row j sits at fractional pixel coordinates (a/n, j + b/n).
  std::vector<double> xs(static_cast<std::size_t>(cols));
  for (std::int64_t a = 0; a < cols; ++a) xs[static_cast<std::size_t>(a)] = static_cast<double>(a) / dn;
  const LatticeRowMapper mapper(lattice, rot, xs);
  RowProgress rp(progress, ny, "pixels (area)");
#pragma omp parallel default(none) \
    shared(bathy, mapper, wet, coastal, rp, nx, ny, n, dn, cols, threshold) if (nx * ny >= kParallelMinSamples)
  {
    std::vector<double> lon(static_cast<std::size_t>(cols)), lat(lon.size()), val(lon.size());
    AreaFlags flags(nx);
#pragma omp for schedule(static)
    for (std::int64_t j = 0; j < ny; ++j) {
      flags.reset();
      for (std::int64_t b = 0; b <= n; ++b) {
        mapper.map_row(static_cast<double>(j * n + b) / dn, lon.data(), lat.data());
        bathy.sample_points(lon.data(), lat.data(), cols, val.data());
        for (std::int64_t i = 0; i < nx; ++i)
          for (std::int64_t a = i * n; a <= (i + 1) * n; ++a)
            flags.add(i, val[static_cast<std::size_t>(a < cols ? a : a - cols)] <= threshold);
      }
      flags.store(nx, wet.row(j), coastal.row(j));
      rp.row_done();
    }
  }
  rp.finish();
}

}  // namespace

Bitmap sample_wet_vertices(const raster::Bathymetry& bathy, const Lattice& lattice, const PoleRotation& rot,
                           double min_depth_m, const ProgressFn& progress, const PixelWindow& window) {
  const double threshold = -min_depth_m;  // wet: d <= -h (at h = 0 exactly 0 m is wet)
  const std::int64_t nx = lattice.nx, nv = lattice.ny + 1;
  Bitmap wv(nx, nv);
  if (!rot.identity()) {
    sample_rotated(bathy, lattice, rot, threshold, progress, wv);
    return wv;
  }
  // A window (regional runs): the vertex columns I0 .. I0 + ncv - 1 (wrapping) and rows J0 ..
  // J0 + nvr - 1 of its pixels; the same values as the whole lattice's there.
  const bool all_cols = window.col_count < 0 || window.col_count + 1 >= nx;
  const std::int64_t ncv = all_cols ? nx : window.col_count + 1;
  const std::int64_t I0 = all_cols ? 0 : ((window.col_first % nx) + nx) % nx;
  const std::int64_t J0 = window.row_count < 0 ? 0 : std::clamp<std::int64_t>(window.row_first, 0, nv - 1);
  const std::int64_t nvr = window.row_count < 0 ? nv : std::min(window.row_count + 1, nv - J0);
  std::vector<double> lons(static_cast<std::size_t>(ncv));
  for (std::int64_t k = 0; k < ncv; ++k)
    lons[static_cast<std::size_t>(k)] = vertex_lattice_deg(lattice, (I0 + k) % nx, 0).lon_deg;
  const raster::Bathymetry::Columns cols = bathy.prepare_columns(lons.data(), ncv);
  std::vector<double> lats(static_cast<std::size_t>(nvr));
  for (std::int64_t k = 0; k < nvr; ++k)
    lats[static_cast<std::size_t>(k)] = vertex_lattice_deg(lattice, 0, J0 + k).lat_deg;
  // Row by row (a streamed raster: band by band of raster rows, each read once); each vertex row
  // is thresholded straight into its bitmap row.
  bathy.sample_rows(
      cols, lats.data(), nvr,
      [&wv, nx, ncv, I0, J0, all_cols, threshold](std::int64_t k, const float* values) {
        if (all_cols) {
          bits::threshold_row(values, nx, threshold, wv.row(J0 + k));
          return;
        }
        for (std::int64_t c = 0; c < ncv; ++c)
          if (static_cast<double>(values[c]) <= threshold) wv.set((I0 + c) % nx, J0 + k);
      },
      progress);
  return wv;
}

void classify_from_vertices(const Bitmap& wet_vertices, Bitmap& wet, Bitmap& coastal) {
  const std::int64_t nx = wet_vertices.nx(), ny = wet_vertices.ny() - 1;
  wet = Bitmap(nx, std::max<std::int64_t>(ny, 0));
  coastal = Bitmap(nx, std::max<std::int64_t>(ny, 0));
  const std::int64_t nw = wet_vertices.words_per_row();
#pragma omp parallel default(none) \
    shared(wet_vertices, wet, coastal, nx, ny, nw) if (ny * nw >= bits::kParallelMinWords)
  {
    // east0/east1: vertex rows J and J+1 shifted so that bit i holds vertex i+1 (periodic).
    std::vector<std::uint64_t> east0(static_cast<std::size_t>(nw)), east1(east0.size());
#pragma omp for schedule(static)
    for (std::int64_t j = 0; j < ny; ++j) {
      const std::uint64_t* v0 = wet_vertices.row(j);
      const std::uint64_t* v1 = wet_vertices.row(j + 1);
      // Two vertex rows without a wet vertex (most rows of a regional run): the pixel row is dry.
      bool any_wet = false;
      for (std::int64_t k = 0; k < nw && !any_wet; ++k) any_wet = (v0[k] | v1[k]) != 0;
      if (!any_wet) continue;
      bits::rotate_row(v0, east0.data(), nx, 1, bits::Combine::kCopy);
      bits::rotate_row(v1, east1.data(), nx, 1, bits::Combine::kCopy);
      std::uint64_t* w = wet.row(j);
      std::uint64_t* c = coastal.row(j);
      for (std::int64_t k = 0; k < nw; ++k) {
        const auto s = static_cast<std::size_t>(k);
        const std::uint64_t all = v0[k] & east0[s] & v1[k] & east1[s];
        const std::uint64_t any = v0[k] | east0[s] | v1[k] | east1[s];
        w[k] = all;
        c[k] = any & ~all;
      }
    }
  }
}

void check_mercator_caps(const raster::Bathymetry& bathy, const Lattice& lattice, const PoleRotation& rot,
                         double min_depth_m) {
  if (!lattice.mercator()) return;
  const auto& in = bathy.info();
  const double phi_max = lattice.lat_max_deg();
  const double step = std::min({in.dlon, in.dlat, lattice.pixel_deg()});  // along φ′
  const auto rows = static_cast<std::int64_t>(std::ceil((90.0 - phi_max) / step));
  const double cos_max = std::cos(phi_max * kDegToRad);
  const auto cols = std::max<std::int64_t>(8, static_cast<std::int64_t>(std::ceil(360.0 * cos_max / step)));
  for (const double side : {1.0, -1.0}) {
    std::int64_t wet = 0;
    LonLat first_geo, first_rot;
    for (std::int64_t r = 0; r < rows; ++r) {  // the last row (the pole itself) is left out: one point
      const double rlat = side * (phi_max + static_cast<double>(r) * step);
      for (std::int64_t c = 0; c < cols; ++c) {
        const LonLat rp{lattice.lon0_deg + 360.0 * static_cast<double>(c) / static_cast<double>(cols), rlat};
        const LonLat g = lattice_to_geographic(rot, rp);
        if (bathy.sample(g.lon_deg, g.lat_deg) <= -min_depth_m) {
          if (wet++ == 0) {
            first_geo = g;
            first_rot = rp;
          }
        }
      }
    }
    const LonLat pole = lattice_to_geographic(rot, {0.0, side * 90.0});
    if (bathy.sample(pole.lon_deg, pole.lat_deg) <= -min_depth_m && wet++ == 0) {
      first_geo = pole;
      first_rot = {0.0, side * 90.0};
    }
    if (wet == 0) continue;
    throw ConfigError(fmt::format(
        "quadtree.lattice = \"mercator\": the lattice rows end at |φ′| = {:.4f}° (quadtree.mercator_lat_max_deg "
        "rounded up to whole level-0 squares), but {} points of the {} cap beyond are wet (elevation <= "
        "-mask.min_depth_m = {:g} m), the first at "
        "geographic ({:.4f}, {:.4f}) = lattice frame ({:.4f}, {:.4f}); put that pole on land with a rotation "
        "(rotation.enabled = true: the default pole in Greenland puts the other one in East Antarctica), move it "
        "(rotation.pole_lon_deg, rotation.pole_lat_deg) or raise quadtree.mercator_lat_max_deg",
        phi_max, wet, side > 0 ? "north" : "south", min_depth_m, first_geo.lon_deg, first_geo.lat_deg,
        first_rot.lon_deg, first_rot.lat_deg));
  }
}

PixelClasses classify_pixels(const raster::Bathymetry& bathy, const Lattice& lattice, const PoleRotation& rot,
                             const ClassifyOptions& options) {
  PixelClasses pc;
  const bool area = options.sampling == Sampling::kArea;
  if (bathy.info().streamed && (area || !rot.identity())) {
    throw ConfigError(fmt::format(
        "{}: a streamed raster (not held whole) supports the unrotated vertex rule only; {} needs the raster whole",
        bathy.info().path, area ? "mask.sampling = \"area\"" : "rotation.enabled = true"));
  }
  ProgressFn vertex_progress;
  if (options.progress) {
    const ProgressFn& p = options.progress;
    vertex_progress = [&p, area](double f, std::string_view label) { p(area ? 0.3 * f : f, label); };
  }
  pc.wet_vertices =
      sample_wet_vertices(bathy, lattice, rot, options.min_depth_m, vertex_progress, area ? PixelWindow{} : options.window);
  classify_from_vertices(pc.wet_vertices, pc.wet, pc.coastal);
  if (area) {
    ProgressFn area_progress;
    if (options.progress) {
      const ProgressFn& p = options.progress;
      area_progress = [&p](double f, std::string_view label) { p(0.3 + 0.7 * f, label); };
    }
    if (rot.identity())
      classify_area_aligned(bathy, lattice, -options.min_depth_m, area_progress, pc.wet, pc.coastal);
    else
      classify_area_rotated(bathy, lattice, rot, -options.min_depth_m, area_progress, pc.wet, pc.coastal);
  }
  pc.wet_vertex_count = pc.wet_vertices.count();
  pc.wet_count = pc.wet.count();
  pc.coastal_count = pc.coastal.count();
  pc.dry_count = lattice.pixel_count() - pc.wet_count - pc.coastal_count;
  return pc;
}

}  // namespace aq::mask
