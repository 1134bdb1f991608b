// SPDX-License-Identifier: GPL-3.0-or-later
// Regional (ROMS) masks from the global Ω_L; the rules are drawn in regional_mask.hpp.
#include "mask/regional_mask.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace aq::mask {

namespace {

std::size_t cells(int ni, int nj) {
  return static_cast<std::size_t>(std::max(ni, 0)) * static_cast<std::size_t>(std::max(nj, 0));
}

}  // namespace

PixelIJ pixel_of_point(const Lattice& lattice, const PoleRotation& rot, double lon_deg, double lat_deg, bool* on_rows) {
  const LonLat q = rot.identity() ? LonLat{lon_deg, lat_deg} : geographic_to_lattice(rot, {lon_deg, lat_deg});
  double x = 0.0, y = 0.0;
  deg_to_lattice_xy(lattice, q, x, y);
  if (on_rows != nullptr) *on_rows = on_lattice_rows(lattice, y);
  PixelIJ p;
  p.i = std::clamp(static_cast<std::int64_t>(std::floor(x)), std::int64_t{0}, lattice.nx - 1);
  p.j = std::clamp(static_cast<std::int64_t>(std::floor(y)), std::int64_t{0}, lattice.ny - 1);
  return p;
}

std::vector<double> sample_elevations(const raster::Bathymetry& bathy, const double* lon_deg, const double* lat_deg,
                                      std::size_t n) {
  std::vector<double> d(n, 0.0);
  if (n == 0) return d;
  bathy.sample_points(lon_deg, lat_deg, static_cast<std::int64_t>(n), d.data());
  std::size_t missing = 0, first = n;
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isnan(d[k])) continue;
    if (missing++ == 0) first = k;
  }
  if (missing > 0) {
    const auto& ri = bathy.info();
    const double lon_last = ri.lon_first + static_cast<double>(ri.ncols - 1) * ri.dlon;
    const double lat_last = ri.lat_first + static_cast<double>(ri.nrows - 1) * ri.dlat;
    throw InputError(fmt::format(
        "{}: no depth at {} of the {} ρ points of the regional grid (the first at lon {:.4f}, lat {:.4f}): the grid "
        "leaves the raster's coverage (lon {:.4f}..{:.4f}{}, lat {:.4f}..{:.4f}) or meets no-data cells; use a raster "
        "covering the whole grid (input.path of roms.global_config) or a smaller contour",
        ri.path.empty() ? std::string("bathymetry") : ri.path, missing, n, lon_deg[first], lat_deg[first], ri.lon_first,
        lon_last, ri.global_lon ? ", global" : "", ri.lat_first, lat_last));
  }
  return d;
}

std::vector<std::uint8_t> rho_mask_from_filled(const Bitmap& filled, const Lattice& lattice, const PoleRotation& rot,
                                               const double* lon_deg, const double* lat_deg, const double* elevation_m,
                                               double threshold_m, std::size_t n, RegionalMaskStats* stats,
                                               const Bitmap* wet_pixels) {
  for (const Bitmap* b : {&filled, wet_pixels})
    if (b != nullptr && (b->nx() != lattice.nx || b->ny() != lattice.ny))
      throw InternalError(fmt::format("regional mask: pixel set {} x {} for a {} x {} lattice", b->nx(), b->ny(),
                                      lattice.nx, lattice.ny));
  std::vector<std::uint8_t> m(n, 0);
  RegionalMaskStats s;
  s.rho_points = static_cast<std::int64_t>(n);
  for (std::size_t k = 0; k < n; ++k) {
    bool on_rows = true;
    const PixelIJ p = pixel_of_point(lattice, rot, lon_deg[k], lat_deg[k], &on_rows);
    const bool in = on_rows && filled.get(p.i, p.j);
    const bool deep = elevation_m == nullptr || elevation_m[k] <= -threshold_m;
    s.in_filled += in ? 1 : 0;
    s.deep_enough += deep ? 1 : 0;
    if (deep && !in) {
      const bool wet_pixel = wet_pixels == nullptr || (on_rows && wet_pixels->get(p.i, p.j));
      s.lake_points += wet_pixel ? 1 : 0;
      s.coastal_points += wet_pixel ? 0 : 1;
    }
    s.shallow_in_filled += (in && !deep) ? 1 : 0;
    m[k] = (in && deep) ? 1 : 0;
  }
  if (stats != nullptr) {
    stats->rho_points = s.rho_points;
    stats->in_filled = s.in_filled;
    stats->deep_enough = s.deep_enough;
    stats->lake_points = s.lake_points;
    stats->coastal_points = s.coastal_points;
    stats->shallow_in_filled = s.shallow_in_filled;
  }
  return m;
}

std::int64_t copy_boundary_from_interior(std::vector<std::uint8_t>& m, int ni, int nj) {
  if (ni < 3 || nj < 3 || m.size() != cells(ni, nj))
    throw InternalError(fmt::format("regional mask: boundary copy of a {} x {} mask with {} values", ni, nj, m.size()));
  const auto at = [ni](int i, int j) {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i);
  };
  std::int64_t changed = 0;
  const auto copy = [&](std::size_t dst, std::size_t src) {
    changed += m[dst] != m[src] ? 1 : 0;
    m[dst] = m[src];
  };
  for (int j = 1; j < nj - 1; ++j) {
    copy(at(0, j), at(1, j));
    copy(at(ni - 1, j), at(ni - 2, j));
  }
  for (int i = 0; i < ni; ++i) {
    copy(at(i, 0), at(i, 1));
    copy(at(i, nj - 1), at(i, nj - 2));
  }
  return changed;
}

void derive_staggered_masks(const std::vector<std::uint8_t>& r, int ni, int nj, std::vector<std::uint8_t>& mu,
                            std::vector<std::uint8_t>& mv, std::vector<std::uint8_t>& mp) {
  if (ni < 2 || nj < 2 || r.size() != cells(ni, nj))
    throw InternalError(
        fmt::format("regional mask: staggered masks of a {} x {} mask with {} values", ni, nj, r.size()));
  const auto at = [ni](int i, int j) {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i);
  };
  mu.assign(cells(ni - 1, nj), 0);
  mv.assign(cells(ni, nj - 1), 0);
  mp.assign(cells(ni - 1, nj - 1), 0);
  for (int j = 0; j < nj; ++j)
    for (int k = 0; k + 1 < ni; ++k)
      mu[static_cast<std::size_t>(j) * static_cast<std::size_t>(ni - 1) + static_cast<std::size_t>(k)] =
          static_cast<std::uint8_t>(r[at(k, j)] & r[at(k + 1, j)]);
  for (int l = 0; l + 1 < nj; ++l)
    for (int i = 0; i < ni; ++i) mv[at(i, l)] = static_cast<std::uint8_t>(r[at(i, l)] & r[at(i, l + 1)]);
  for (int l = 0; l + 1 < nj; ++l)
    for (int k = 0; k + 1 < ni; ++k)
      mp[static_cast<std::size_t>(l) * static_cast<std::size_t>(ni - 1) + static_cast<std::size_t>(k)] =
          static_cast<std::uint8_t>(r[at(k, l)] & r[at(k + 1, l)] & r[at(k, l + 1)] & r[at(k + 1, l + 1)]);
}

RomsMasks build_roms_masks(const Bitmap& filled, const Lattice& lattice, const PoleRotation& rot, const double* lon_deg,
                           const double* lat_deg, const double* elevation_m, double threshold_m, int ni, int nj,
                           const Bitmap* wet_pixels) {
  RomsMasks m;
  m.ni = ni;
  m.nj = nj;
  m.rho = rho_mask_from_filled(filled, lattice, rot, lon_deg, lat_deg, elevation_m, threshold_m, cells(ni, nj),
                               &m.stats, wet_pixels);
  m.stats.boundary_changed = copy_boundary_from_interior(m.rho, ni, nj);
  derive_staggered_masks(m.rho, ni, nj, m.u, m.v, m.psi);
  const auto count = [](const std::vector<std::uint8_t>& v) {
    std::int64_t c = 0;
    for (const auto x : v) c += x;
    return c;
  };
  m.stats.wet_rho = count(m.rho);
  m.stats.wet_u = count(m.u);
  m.stats.wet_v = count(m.v);
  m.stats.wet_psi = count(m.psi);
  for (int j = 1; j + 1 < nj; ++j)
    for (int i = 1; i + 1 < ni; ++i)
      m.stats.wet_rho_interior +=
          m.rho[static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i)];
  return m;
}

}  // namespace aq::mask
