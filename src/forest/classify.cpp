// SPDX-License-Identifier: GPL-3.0-or-later
// Pixel classes on the forest (see classify.hpp).
#include "forest/classify.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>

#include "core/error.hpp"
#include "core/types.hpp"
#include "mask/lattice_coords.hpp"
#include "quadtree/bits.hpp"

namespace aq::forest {

namespace {

// Which lattice vertices the run samples (mask::sample_wet_vertices: the window's vertex columns
// I0 .. I0 + ncv - 1, wrapping, and rows J0 .. J0 + nvr - 1; all when the window is the lattice).
struct VertexWindow {
  bool all_cols = true;
  std::int64_t I0 = 0, ncv = 0, J0 = 0, nvr = 0, nx = 0;
  VertexWindow(const Lattice& lat, const mask::PixelWindow& w) {
    const std::int64_t nv = lat.ny + 1;
    nx = lat.nx;
    all_cols = w.col_count < 0 || w.col_count + 1 >= nx;
    ncv = all_cols ? nx : w.col_count + 1;
    I0 = all_cols ? 0 : ((w.col_first % nx) + nx) % nx;
    J0 = w.row_count < 0 ? 0 : std::clamp<std::int64_t>(w.row_first, 0, nv - 1);
    nvr = w.row_count < 0 ? nv : std::min(w.row_count + 1, nv - J0);
  }
  [[nodiscard]] bool row(std::int64_t J) const { return J >= J0 && J < J0 + nvr; }
  [[nodiscard]] bool col(std::int64_t I) const { return all_cols || wrap_index(I - I0, nx) < ncv; }
  // Whether every vertex of the patch (columns I .. I + p, rows J .. J + p) is sampled.
  [[nodiscard]] bool holds(std::int64_t I, std::int64_t J, std::int64_t p) const {
    if (!row(J) || !row(J + p)) return false;
    if (all_cols) return true;
    for (std::int64_t k = 0; k <= p; ++k)
      if (!col(I + k)) return false;
    return true;
  }
  // Whether no vertex of the patch is sampled.
  [[nodiscard]] bool misses(std::int64_t I, std::int64_t J, std::int64_t p) const {
    if (J + p < J0 || J >= J0 + nvr) return true;
    if (all_cols) return false;
    for (std::int64_t k = 0; k <= p; ++k)
      if (col(I + k)) return false;
    return true;
  }
};

// The pixel classes of one patch from its (p + 1) × (p + 1) vertex bits; adds the counts.
struct PatchCounts {
  std::int64_t wet_vertices = 0, wet = 0, coastal = 0;
};

void pixels_from_vertices(const Bitmap& v, std::int64_t p, bool top_row, PatchBits& wet, PatchCounts& c) {
  wet.state = Fill::kMixed;
  wet.bits = Bitmap(p, p);
  for (std::int64_t J = 0; J < p + (top_row ? 1 : 0); ++J)
    for (std::int64_t I = 0; I < p; ++I) c.wet_vertices += v.get(I, J) ? 1 : 0;
  for (std::int64_t j = 0; j < p; ++j)
    for (std::int64_t i = 0; i < p; ++i) {
      const bool a = v.get(i, j), b = v.get(i + 1, j), d = v.get(i, j + 1), e = v.get(i + 1, j + 1);
      const bool all = a && b && d && e, any = a || b || d || e;
      if (all) {
        wet.bits.set(i, j);
        ++c.wet;
      } else if (any) {
        ++c.coastal;
      }
    }
  wet.normalise();
}

// Whole patch decided: all vertices wet (+1) or dry (-1).
void uniform(int s, std::int64_t p, bool top_row, PatchBits& wet, PatchCounts& c) {
  if (s > 0) {
    wet.state = Fill::kAll;
    c.wet_vertices += p * (p + (top_row ? 1 : 0));
    c.wet += p * p;
  } else {
    wet.state = Fill::kNone;
  }
}

// The rotated classification's bound on a block of vertices [I0, I1] × [J0, J1] (inclusive): the
// cap around its centre through its farthest corner, as mask::sample_rotated's units do; false
// when no box bounds it.
bool rotated_range(const StackBounds& bounds, const Lattice& lattice, const PoleRotation& rot, bool global_lon,
                   std::int64_t I0, std::int64_t I1, std::int64_t J0, std::int64_t J1, raster::ValueRange& range) {
  if (!bounds.available()) return false;
  const mask::LonLat a = mask::vertex_lattice_deg(lattice, I0, J0), b = mask::vertex_lattice_deg(lattice, I1, J1);
  const mask::LonLat c{0.5 * (a.lon_deg + b.lon_deg), 0.5 * (a.lat_deg + b.lat_deg)};
  double r = 0.0;
  for (const mask::LonLat q : {a, b, mask::LonLat{a.lon_deg, b.lat_deg}, mask::LonLat{b.lon_deg, a.lat_deg}})
    r = std::max(r, mask::angular_distance_deg(c, q));
  r += 1e-9;
  const mask::LonLat g = mask::lattice_to_geographic(rot, c);
  if (std::abs(g.lat_deg) + r >= 89.0) return false;
  const double half = std::asin(std::min(1.0, std::sin(r * kDegToRad) / std::cos(g.lat_deg * kDegToRad))) * kRadToDeg;
  if (!global_lon && (g.lon_deg - half < -180.0 || g.lon_deg + half > 180.0)) return false;
  range = bounds.in_box(g.lon_deg - half, g.lon_deg + half, g.lat_deg - r, g.lat_deg + r);
  return true;
}

}  // namespace

std::vector<PatchClasses> classify_patches_at(const PatchForest& pf, const raster::Bathymetry& bathy,
                                              const StackBounds& bounds, const PoleRotation& rot,
                                              const std::vector<double>& min_depths_m,
                                              const mask::PixelWindow& window) {
  const PatchGrid& g = pf.grid();
  const Lattice& lat = g.lat;
  const std::int64_t p = g.size, nx = lat.nx;
  const std::size_t nt = min_depths_m.size();
  if (nt < 1 || nt > 2) throw InternalError(fmt::format("classify: {} thresholds (1 or 2)", nt));
  std::vector<double> thresholds(nt);
  for (std::size_t t = 0; t < nt; ++t) thresholds[t] = -min_depths_m[t];
  const bool rotated = !rot.identity();
  const bool streamed = bathy.info().streamed;
  const bool global_lon = bathy.info().global_lon;
  if (streamed && rotated)
    throw ConfigError(
        fmt::format("{}: a streamed raster (not held whole) supports the unrotated vertex rule only; "
                    "rotation.enabled = true needs the raster whole",
                    bathy.info().path));
  const VertexWindow vw(lat, rotated ? mask::PixelWindow{} : window);
  std::vector<PatchClasses> out(nt);
  const auto n = static_cast<std::int64_t>(pf.local_count());
  for (PatchClasses& o : out) o.wet.resize(static_cast<std::size_t>(n));
  // Per threshold: wet vertices, wet, coastal, decided, sampled (this rank's).
  std::vector<std::int64_t> sums(5 * nt, 0);

  std::exception_ptr error;  // the first failure of this rank (sampling reads rasters)
  if (streamed) try {
      // A streamed raster is read band by band: the vertex rows of several tree rows at once, over
      // the columns of this rank's trees in them, thresholded into one buffer and cut into patches.
      const LatticeBrick& brick = pf.brick();
      const std::int64_t side0 = lat.pixels_per_square(0);
      const std::int64_t group =
          std::max<std::int64_t>(1, (4 * std::max<std::int64_t>(bathy.info().band_rows, 1) + side0 - 1) / side0);
      for (std::int64_t t0 = pf.first_tree(); t0 < pf.last_tree();) {
        const std::int64_t b_first = brick.tree_b0(t0);
        const std::int64_t b_last = std::min(brick.tree_b0(pf.last_tree() - 1), b_first + group - 1);
        const std::int64_t t_end = std::min(pf.last_tree(), brick.tree(0, b_last + 1));
        std::int64_t a_lo = 0, a_hi = brick.nx0() - 1;  // several tree rows: all columns
        if (b_first == b_last) {
          a_lo = brick.tree_a0(t0);
          a_hi = brick.tree_a0(t_end - 1);
        }
        const std::int64_t I_lo = a_lo * side0;
        const std::int64_t ncols = (a_hi + 1) * side0 - I_lo + 1;
        const std::int64_t J_lo = b_first * side0, nrows = (b_last - b_first + 1) * side0 + 1;
        std::vector<double> lons(static_cast<std::size_t>(ncols)), lats(static_cast<std::size_t>(nrows));
        for (std::int64_t k = 0; k < ncols; ++k)
          lons[static_cast<std::size_t>(k)] = lat.lon_of(wrap_index(I_lo + k, nx));
        for (std::int64_t k = 0; k < nrows; ++k) lats[static_cast<std::size_t>(k)] = lat.lat_of(J_lo + k);
        const raster::Bathymetry::Columns cols = bathy.prepare_columns(lons.data(), ncols);
        std::vector<Bitmap> v(nt, Bitmap(ncols, nrows));
        bathy.sample_rows(
            cols, lats.data(), nrows,
            [&v, &vw, &thresholds, nt, ncols, I_lo, J_lo](std::int64_t k, const float* values) {
              for (std::size_t t = 0; t < nt; ++t) {
                std::uint64_t* row = v[t].row(k);
                for (std::int64_t c = 0; c < ncols; ++c)
                  if (static_cast<double>(values[c]) <= thresholds[t] && vw.row(J_lo + k) && vw.col(I_lo + c))
                    row[c >> 6] |= std::uint64_t{1} << (c & 63);
              }
            });
        for (std::int64_t t = t0; t < t_end; ++t) {
          for (std::int64_t k = 0; k < g.per_tree * g.per_tree; ++k) {
            const std::int64_t local =
                pf.local_index(g.key(brick.tree_a0(t) * g.per_tree, brick.tree_b0(t) * g.per_tree)) + k;
            const std::int64_t key = pf.key(static_cast<std::size_t>(local));
            const std::int64_t I0 = g.gx(key) * p, J0 = g.gy(key) * p;
            for (std::size_t h = 0; h < nt; ++h) {
              Bitmap pv(p + 1, p + 1);
              for (std::int64_t r = 0; r <= p; ++r)
                for (std::int64_t c = 0; c <= p; ++c)
                  if (v[h].get(I0 - I_lo + c, J0 - J_lo + r)) pv.set(c, r);
              PatchCounts pc;
              pixels_from_vertices(pv, p, g.gy(key) == g.npy - 1, out[h].wet[static_cast<std::size_t>(local)], pc);
              sums[5 * h] += pc.wet_vertices;
              sums[5 * h + 1] += pc.wet;
              sums[5 * h + 2] += pc.coastal;
              sums[5 * h + 4] += 1;
            }
          }
        }
        t0 = t_end;
      }
    } catch (...) {
      error = std::current_exception();
    }
  else {
    std::vector<std::exception_ptr> errors(static_cast<std::size_t>(n));
    // The sums of the (at most two) thresholds as scalars, which OpenMP reduces.
    std::int64_t s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0, s5 = 0, s6 = 0, s7 = 0, s8 = 0, s9 = 0;
#pragma omp parallel default(none) shared(pf, g, lat, bathy, bounds, rot, vw, out, n, p, nx, thresholds, nt, rotated, \
                                              global_lon, errors) reduction(+ : s0, s1, s2, s3, s4, s5, s6, s7, s8, s9)
    {
      std::array<std::int64_t, 10> mine{};
      std::vector<double> lons(static_cast<std::size_t>(p + 1)), la(lons.size()), vals(lons.size());
      std::vector<float> fv(lons.size());
      std::vector<double> x(lons.size());
      std::vector<int> sides(nt, 0);
      std::vector<Bitmap> v(nt);
#pragma omp for schedule(dynamic, 4)
      for (std::int64_t l = 0; l < n; ++l) try {
          const std::int64_t key = pf.key(static_cast<std::size_t>(l));
          const std::int64_t I0 = g.gx(key) * p, J0 = g.gy(key) * p;
          const bool top = g.gy(key) == g.npy - 1;
          if (vw.misses(I0, J0, p)) {
            for (std::size_t h = 0; h < nt; ++h) {
              out[h].wet[static_cast<std::size_t>(l)].state = Fill::kNone;
              ++mine[5 * h + 3];
            }
            continue;
          }
          const bool whole = vw.holds(I0, J0, p);
          // The last vertex column of a window lattice (not periodic) wraps to column 0, as the
          // dense engine's vertex rule does (mask/pixel_classes.hpp): a box cannot bound it, so
          // the patches of the east edge are sampled.
          const bool wraps = !g.periodic && I0 + p >= nx;
          std::fill(sides.begin(), sides.end(), 0);
          if (whole && !wraps && bounds.available()) {
            raster::ValueRange range;
            bool bounded = true;
            if (rotated)
              bounded = rotated_range(bounds, lat, rot, global_lon, I0, I0 + p, J0, J0 + p, range);
            else
              range = bounds.in_box(lat.lon_of(I0), lat.lon_of(I0 + p), lat.lat_of(J0), lat.lat_of(J0 + p));
            if (bounded)
              for (std::size_t h = 0; h < nt; ++h) sides[h] = side(range, thresholds[h], !rotated);
          }
          // Sampled once for every threshold a bound leaves open (the same calls as the dense engine).
          const bool sample = std::any_of(sides.begin(), sides.end(), [](int q) { return q == 0; });
          if (sample) {
            for (std::size_t h = 0; h < nt; ++h) v[h] = sides[h] == 0 ? Bitmap(p + 1, p + 1) : Bitmap();
            const auto take = [&](std::int64_t r, std::int64_t c, double value) {
              for (std::size_t h = 0; h < nt; ++h)
                if (sides[h] == 0 && value <= thresholds[h] && vw.row(J0 + r) && vw.col(I0 + c)) v[h].set(c, r);
            };
            if (rotated) {
              for (std::int64_t k = 0; k <= p; ++k)
                x[static_cast<std::size_t>(k)] = static_cast<double>(wrap_index(I0 + k, nx));
              const mask::LatticeRowMapper mapper(lat, rot, x);
              for (std::int64_t r = 0; r <= p; ++r) {
                mapper.map_row(static_cast<double>(J0 + r), lons.data(), la.data());
                bathy.sample_points(lons.data(), la.data(), p + 1, vals.data());
                for (std::int64_t c = 0; c <= p; ++c) take(r, c, vals[static_cast<std::size_t>(c)]);
              }
            } else {
              for (std::int64_t k = 0; k <= p; ++k)
                lons[static_cast<std::size_t>(k)] = lat.lon_of(wrap_index(I0 + k, nx));
              const raster::Bathymetry::Columns cols = bathy.prepare_columns(lons.data(), p + 1);
              for (std::int64_t r = 0; r <= p; ++r) {
                bathy.sample_row(cols, lat.lat_of(J0 + r), fv.data());
                for (std::int64_t c = 0; c <= p; ++c) take(r, c, static_cast<double>(fv[static_cast<std::size_t>(c)]));
              }
            }
          }
          for (std::size_t h = 0; h < nt; ++h) {
            PatchBits& w = out[h].wet[static_cast<std::size_t>(l)];
            PatchCounts pc;
            if (sides[h] != 0) {
              uniform(sides[h], p, top, w, pc);
              ++mine[5 * h + 3];
            } else {
              pixels_from_vertices(v[h], p, top, w, pc);
              ++mine[5 * h + 4];
            }
            mine[5 * h] += pc.wet_vertices;
            mine[5 * h + 1] += pc.wet;
            mine[5 * h + 2] += pc.coastal;
          }
        } catch (...) {
          errors[static_cast<std::size_t>(l)] = std::current_exception();
        }
      s0 += mine[0], s1 += mine[1], s2 += mine[2], s3 += mine[3], s4 += mine[4];
      s5 += mine[5], s6 += mine[6], s7 += mine[7], s8 += mine[8], s9 += mine[9];
    }
    const std::array<std::int64_t, 10> all{s0, s1, s2, s3, s4, s5, s6, s7, s8, s9};
    for (std::size_t k = 0; k < sums.size(); ++k) sums[k] += all[k];
    for (const std::exception_ptr& e : errors)
      if (e && !error) error = e;
  }
  agree(pf.comm(), error);
  pf.comm().sum_in_place(sums);
  for (std::size_t h = 0; h < nt; ++h) {
    PatchClasses& o = out[h];
    o.counts.wet_vertices = sums[5 * h];
    o.counts.wet = sums[5 * h + 1];
    o.counts.coastal = sums[5 * h + 2];
    o.counts.dry = lat.pixel_count() - o.counts.wet - o.counts.coastal;
    o.decided = sums[5 * h + 3];
    o.sampled = sums[5 * h + 4];
  }
  return out;
}

PatchClasses classify_patches(const PatchForest& pf, const raster::Bathymetry& bathy, const StackBounds& bounds,
                              const PoleRotation& rot, double min_depth_m, const mask::PixelWindow& window) {
  return std::move(classify_patches_at(pf, bathy, bounds, rot, {min_depth_m}, window).front());
}

}  // namespace aq::forest
