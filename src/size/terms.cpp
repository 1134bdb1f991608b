// SPDX-License-Identifier: GPL-3.0-or-later
// The physical terms of the size field (see terms.hpp).
#include "size/terms.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/types.hpp"
#include "size/limit_gradient.hpp"

namespace aq::size {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

std::vector<std::uint8_t> coast_cells(const FieldGrid& grid, const std::vector<std::int32_t>& filled_count) {
  const std::int64_t s = grid.pixels_per_cell();
  const auto full = static_cast<std::int32_t>(s * s);
  std::vector<std::uint8_t> c(filled_count.size());
  for (std::size_t k = 0; k < c.size(); ++k) c[k] = filled_count[k] < full ? 1 : 0;
  return c;
}

std::vector<std::uint8_t> shore_cells(const FieldGrid& grid, const Bitmap& filled, const mask::CoastSources& coast) {
  // The coast pixels: neither water at the datum inside the mesh nor open water beyond it.
  const Bitmap& water = coast.sea != nullptr ? *coast.sea : filled;
  Bitmap land(water.nx(), water.ny());
  const auto& w = water.words();
  auto& out = land.words();
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = ~w[k] & (coast.open != nullptr ? ~coast.open->words()[k] : ~std::uint64_t{0});
  const int tail = static_cast<int>(land.nx() & 63);  // padding bits stay clear
  if (tail != 0)
    for (std::int64_t j = 0; j < land.ny(); ++j)
      land.row(j)[land.words_per_row() - 1] &= (std::uint64_t{1} << tail) - 1;
  const std::vector<std::int32_t> count = grid.filled_counts(land);
  std::vector<std::uint8_t> c(count.size());
  for (std::size_t k = 0; k < c.size(); ++k) c[k] = count[k] > 0 ? 1 : 0;
  return c;
}

std::vector<double> coast_term(const FieldGrid& grid, const std::vector<std::uint8_t>& coast, double h0_km,
                               double alpha) {
  return coast_term(distance_to(grid, coast), h0_km, alpha);
}

std::vector<double> coast_term(std::vector<double> d, double h0_km, double alpha) {
  for (double& x : d) x = h0_km + alpha * x;
  return d;
}

std::vector<std::uint8_t> medial_axis(const FieldGrid& grid, const std::vector<double>& d,
                                      const std::vector<std::int32_t>& nearest, const std::vector<std::uint8_t>& water) {
  const std::int64_t nx = grid.nx(), ny = grid.ny();
  std::vector<std::uint8_t> ma(d.size(), 0);
  const auto opposite = [&](std::int64_t a, std::int64_t b, double cell_km) {
    const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
    if (water[ua] == 0 || water[ub] == 0 || nearest[ua] < 0 || nearest[ub] < 0) return false;
    if (d[ua] <= 0.0 && d[ub] <= 0.0) return false;
    const double sep = grid.distance_km(nearest[ua], nearest[ub]);
    return sep > std::max(2.0 * cell_km, 0.8 * (d[ua] + d[ub]));
  };
  for (std::int64_t j = 0; j < ny; ++j) {
    for (std::int64_t i = 0; i < nx; ++i) {
      const std::int64_t k = j * nx + i;
      const std::int64_t r = j * nx + (i + 1) % nx;
      if (opposite(k, r, grid.dx_km(j))) {  // the cell nearer the axis (farther from the coast) marks it
        ma[static_cast<std::size_t>(d[static_cast<std::size_t>(k)] >= d[static_cast<std::size_t>(r)] ? k : r)] = 1;
      }
      if (j + 1 < ny) {
        const std::int64_t u = k + nx;
        if (opposite(k, u, grid.dy_km(j)))
          ma[static_cast<std::size_t>(d[static_cast<std::size_t>(k)] >= d[static_cast<std::size_t>(u)] ? k : u)] = 1;
      }
    }
  }
  return ma;
}

std::vector<double> feature_term(const FieldGrid& grid, const std::vector<std::uint8_t>& coast,
                                 const std::vector<std::uint8_t>& water, double r) {
  std::vector<std::int32_t> nearest;
  const std::vector<double> d = distance_to(grid, coast, &nearest);
  return feature_term(grid, d, nearest, water, r);
}

std::vector<double> feature_term(const FieldGrid& grid, const std::vector<double>& d,
                                 const std::vector<std::int32_t>& nearest, const std::vector<std::uint8_t>& water,
                                 double r) {
  const std::vector<std::uint8_t> ma = medial_axis(grid, d, nearest, water);
  const std::vector<double> dma = distance_to(grid, ma);
  std::vector<double> h(d.size(), kInf);
  for (std::size_t k = 0; k < h.size(); ++k)
    if (water[k] != 0 && std::isfinite(d[k]) && std::isfinite(dma[k])) h[k] = 2.0 * (dma[k] + d[k]) / r;
  return h;
}

std::vector<double> wavelength_term(const std::vector<double>& depth_m, double period_h, double wl) {
  std::vector<double> h(depth_m.size(), kInf);
  for (std::size_t k = 0; k < h.size(); ++k)
    if (depth_m[k] > 0.0) h[k] = period_h * 3600.0 * std::sqrt(kGravity * depth_m[k]) / wl / 1000.0;
  return h;
}

std::vector<double> box_mean(const FieldGrid& grid, const std::vector<double>& v, const std::vector<double>& radius_km) {
  // A summed-area table over the values with a finite value (and a count of them), the columns
  // extended by the widest reach on both sides so the box wraps round the seam.
  const std::int64_t nx = grid.nx(), ny = grid.ny();
  std::int64_t reach = 0;
  for (std::int64_t j = 0; j < ny; ++j) {
    double rmax = 0.0;
    for (std::int64_t i = 0; i < nx; ++i) rmax = std::max(rmax, radius_km[static_cast<std::size_t>(j * nx + i)]);
    reach = std::max(reach, static_cast<std::int64_t>(std::ceil(rmax / grid.dx_km(j))));
  }
  reach = std::min(reach, nx);
  const std::int64_t w = nx + 2 * reach + 1;
  std::vector<double> sum(static_cast<std::size_t>(w * (ny + 1)), 0.0), cnt(sum.size(), 0.0);
  for (std::int64_t j = 0; j < ny; ++j) {
    double rs = 0.0, rc = 0.0;
    for (std::int64_t c = 1; c < w; ++c) {
      const std::int64_t i = wrap_index(c - 1 - reach, nx);
      const double x = v[static_cast<std::size_t>(j * nx + i)];
      if (std::isfinite(x)) {
        rs += x;
        rc += 1.0;
      }
      const auto at = static_cast<std::size_t>((j + 1) * w + c), up = static_cast<std::size_t>(j * w + c);
      sum[at] = sum[up] + rs;
      cnt[at] = cnt[up] + rc;
    }
  }
  std::vector<double> out(v.size());
#pragma omp parallel for default(none) shared(grid, v, radius_km, sum, cnt, out, nx, ny, reach, w) schedule(static)
  for (std::int64_t j = 0; j < ny; ++j) {
    for (std::int64_t i = 0; i < nx; ++i) {
      const auto k = static_cast<std::size_t>(j * nx + i);
      const std::int64_t rx = std::min(reach, static_cast<std::int64_t>(std::floor(radius_km[k] / grid.dx_km(j) + 0.5)));
      const auto ry = static_cast<std::int64_t>(std::floor(radius_km[k] / grid.dy_km(j) + 0.5));
      const std::int64_t j0 = std::max<std::int64_t>(0, j - ry), j1 = std::min(ny, j + ry + 1);
      const std::int64_t c0 = i + reach - rx, c1 = i + reach + rx + 1;  // columns of the extended table
      const auto at = [&](std::int64_t jj, std::int64_t cc) { return static_cast<std::size_t>(jj * w + cc); };
      const double s = sum[at(j1, c1)] - sum[at(j0, c1)] - sum[at(j1, c0)] + sum[at(j0, c0)];
      const double n = cnt[at(j1, c1)] - cnt[at(j0, c1)] - cnt[at(j1, c0)] + cnt[at(j0, c0)];
      out[k] = std::isfinite(v[k]) && n > 0.0 ? s / n : v[k];
    }
  }
  return out;
}

std::vector<double> rossby_filter(const FieldGrid& grid, const std::vector<double>& depth_m,
                                  const std::vector<double>& geo_lat_deg, double filter, double max_km) {
  if (filter <= 0.0) return depth_m;
  std::vector<double> radius(depth_m.size(), 0.0);
  for (std::size_t k = 0; k < radius.size(); ++k) {
    if (!(depth_m[k] > 0.0)) continue;
    const double f = std::fabs(2.0 * kEarthOmega * std::sin(geo_lat_deg[k] * kDegToRad));
    const double rossby_km = f > 0.0 ? std::sqrt(kGravity * depth_m[k]) / f / 1000.0 : kInf;
    radius[k] = std::min(filter * rossby_km, max_km);
  }
  return box_mean(grid, depth_m, radius);
}

std::vector<double> slope_term(const FieldGrid& grid, const std::vector<double>& depth_m, double slp) {
  const std::int64_t nx = grid.nx(), ny = grid.ny();
  std::vector<double> h(depth_m.size(), kInf);
  const double factor = 2.0 * std::numbers::pi / slp;
#pragma omp parallel for default(none) shared(grid, depth_m, h, nx, ny, factor) schedule(static)
  for (std::int64_t j = 0; j < ny; ++j) {
    for (std::int64_t i = 0; i < nx; ++i) {
      const auto at = [&](std::int64_t ii, std::int64_t jj) {
        return depth_m[static_cast<std::size_t>(jj * nx + wrap_index(ii, nx))];
      };
      const double c = at(i, j);
      if (!(c > 0.0)) continue;
      const double e = at(i + 1, j), w = at(i - 1, j);
      const double n = j + 1 < ny ? at(i, j + 1) : c, s = j > 0 ? at(i, j - 1) : c;
      if (!std::isfinite(e) || !std::isfinite(w) || !std::isfinite(n) || !std::isfinite(s)) continue;
      const double span_y = (j + 1 < ny ? 1.0 : 0.0) + (j > 0 ? 1.0 : 0.0);
      const double gx = (e - w) / (2.0 * grid.dx_km(j));
      const double gy = span_y > 0.0 ? (n - s) / (span_y * grid.dy_km(j)) : 0.0;
      const double grad = std::sqrt(gx * gx + gy * gy);  // m per km
      if (grad > 0.0) h[static_cast<std::size_t>(j * nx + i)] = factor * c / grad;
    }
  }
  return h;
}

std::vector<double> cfl_bound(const std::vector<double>& depth_m, double dt_s, double courant_max, double u_ms) {
  std::vector<double> h(depth_m.size(), 0.0);
  for (std::size_t k = 0; k < h.size(); ++k)
    if (depth_m[k] > 0.0) h[k] = (std::sqrt(kGravity * depth_m[k]) + u_ms) * dt_s / courant_max / 1000.0;
  return h;
}

}  // namespace aq::size
