// SPDX-License-Identifier: GPL-3.0-or-later
// The meshed domain of a regional run (see domain.hpp).
#include "mask/domain.hpp"

#include <fmt/format.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "core/error.hpp"
#include "core/types.hpp"
#include "mask/lattice_coords.hpp"

namespace aq::mask {

namespace {

using config::DomainKind;

std::int64_t mod(std::int64_t a, std::int64_t n) { return ((a % n) + n) % n; }

// Sets bits [x0, x1) of a row, a word at a time.
void quadtree_free_set_range(std::uint64_t* row, std::int64_t x0, std::int64_t x1) {
  while (x0 < x1) {
    const std::int64_t w = x0 >> 6, b = x0 & 63, n = std::min<std::int64_t>(64 - b, x1 - x0);
    const std::uint64_t bits = n == 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << n) - 1) << b;
    row[w] |= bits;
    x0 += n;
  }
}

using Ring = PolygonRing;

void add_rings(OGRGeometryH g, std::vector<Ring>& rings) {
  if (g == nullptr) return;
  const OGRwkbGeometryType t = wkbFlatten(OGR_G_GetGeometryType(g));
  if (t == wkbPolygon) {
    for (int r = 0; r < OGR_G_GetGeometryCount(g); ++r) {
      OGRGeometryH ring = OGR_G_GetGeometryRef(g, r);
      Ring out;
      for (int k = 0; k < OGR_G_GetPointCount(ring); ++k) {
        out.lon.push_back(OGR_G_GetX(ring, k));
        out.lat.push_back(OGR_G_GetY(ring, k));
      }
      if (out.lon.size() >= 3) rings.push_back(std::move(out));
    }
  } else if (t == wkbMultiPolygon || t == wkbGeometryCollection) {
    for (int k = 0; k < OGR_G_GetGeometryCount(g); ++k) add_rings(OGR_G_GetGeometryRef(g, k), rings);
  }
}

std::vector<Ring> read_polygon(const config::DomainOptions& o) {
  GDALAllRegister();
  const std::string& path = o.polygon;
  struct Closer {
    void operator()(void* h) const { GDALClose(h); }
  };
  std::unique_ptr<void, Closer> ds(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  if (!ds) {
    throw InputError(fmt::format("domain.polygon = \"{}\": GDAL/OGR cannot open it as a vector file ({})", path,
                                 CPLGetLastErrorMsg()));
  }
  OGRLayerH layer = o.layer.empty() ? GDALDatasetGetLayer(ds.get(), 0)
                                    : GDALDatasetGetLayerByName(ds.get(), o.layer.c_str());
  if (layer == nullptr) {
    throw InputError(o.layer.empty() ? fmt::format("domain.polygon = \"{}\": the file has no layer", path)
                                     : fmt::format("domain.layer = \"{}\": no such layer in {}", o.layer, path));
  }
  if (OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(layer); srs != nullptr && OSRIsGeographic(srs) == 0) {
    throw InputError(fmt::format("domain.polygon = \"{}\": the layer is not in geographic lon/lat coordinates; "
                                 "reproject it (e.g. ogr2ogr -t_srs EPSG:4326)",
                                 path));
  }
  if (!o.where.empty() && OGR_L_SetAttributeFilter(layer, o.where.c_str()) != OGRERR_NONE) {
    throw ConfigError(fmt::format("domain.where = \"{}\": OGR refuses the filter on {} ({})", o.where, path,
                                  CPLGetLastErrorMsg()));
  }
  OGR_L_ResetReading(layer);
  std::vector<Ring> rings;
  int index = 0, features = 0;
  for (OGRFeatureH f = OGR_L_GetNextFeature(layer); f != nullptr; f = OGR_L_GetNextFeature(layer), ++index) {
    if (o.feature < 0 || o.feature == index) {
      add_rings(OGR_F_GetGeometryRef(f), rings);
      ++features;
    }
    OGR_F_Destroy(f);
  }
  if (o.feature >= 0 && features == 0) {
    throw ConfigError(fmt::format("domain.feature = {}: {} has only {} feature(s){}", o.feature, path, index,
                                  o.where.empty() ? "" : " matching domain.where"));
  }
  if (rings.empty()) {
    throw InputError(fmt::format("domain.polygon = \"{}\": no polygon in the selected feature(s) (layer \"{}\"{})", path,
                                 OGR_L_GetName(layer), o.where.empty() ? "" : ", where " + o.where));
  }
  for (const Ring& r : rings)
    for (std::size_t k = 0; k < r.lon.size(); ++k)
      if (!std::isfinite(r.lon[k]) || !std::isfinite(r.lat[k]) || std::abs(r.lat[k]) > 90.0)
        throw InputError(fmt::format("domain.polygon = \"{}\": vertex ({}, {}) is not a lon/lat point", path,
                                     r.lon[k], r.lat[k]));
  return rings;
}

// The box snapped outward to whole level-0 squares: columns [i0, i1) (contiguous, may run
// across the seam), rows [j0, j1) of `lat`.
struct SnappedBox {
  std::int64_t i0 = 0, i1 = 0, j0 = 0, j1 = 0;
};

SnappedBox snap_box(const config::DomainOptions& o, const Lattice& lat) {
  double width = o.box[1] - o.box[0];
  if (width < 0.0) width += 360.0;
  const double pix = lat.pixel_deg();
  const auto sq = lat.pixels_per_square(0);
  const double x_w = lat.windowed() ? lat.col_of_lon(o.box[0]) : (o.box[0] - lat.lon0_deg) / pix;
  const double x_e = x_w + width / pix;
  SnappedBox b;
  b.i0 = static_cast<std::int64_t>(std::floor(x_w / static_cast<double>(sq) + 1e-9)) * sq;
  b.i1 = static_cast<std::int64_t>(std::ceil(x_e / static_cast<double>(sq) - 1e-9)) * sq;
  const double y_s = lat.row_of_lat(std::max(o.box[2], -lat.lat_max_deg()));
  const double y_n = lat.row_of_lat(std::min(o.box[3], lat.lat_max_deg()));
  b.j0 = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(y_s / static_cast<double>(sq) + 1e-9)) * sq);
  b.j1 = std::min<std::int64_t>(lat.ny, static_cast<std::int64_t>(std::ceil(y_n / static_cast<double>(sq) - 1e-9)) * sq);
  if (b.i1 - b.i0 >= lat.nx_global)
    throw ConfigError(fmt::format("domain.box = [{}, {}, {}, {}]: snapped outward to {}° squares it covers all "
                                  "longitudes; use the global domain",
                                  o.box[0], o.box[1], o.box[2], o.box[3], lat.step0_deg));
  if (b.j1 <= b.j0)
    throw ConfigError(fmt::format("domain.box = [{}, {}, {}, {}]: no lattice row inside", o.box[0], o.box[1],
                                  o.box[2], o.box[3]));
  return b;
}

void box_domain(Domain& d, const config::DomainOptions& o, const Lattice& lat, const PoleRotation& rot) {
  d.box = o.box;
  if (rot.identity()) {
    const SnappedBox b = snap_box(o, lat);
    const std::int64_t i0 = b.i0, i1 = b.i1, j0 = b.j0, j1 = b.j1;
    if (!lat.periodic() && (i0 < 0 || i1 > lat.nx))
      throw InternalError(fmt::format("domain.box: columns {}..{} outside the window lattice's {}", i0, i1, lat.nx));
    d.i0 = mod(i0, lat.nx);
    d.j0 = j0;
    d.ni = i1 - i0;
    d.nj = j1 - j0;
    d.lon_min = lat.lon_of(i0);
    d.lon_max = lat.lon_of(i1);
    d.lat_min = lat.lat_of(j0);
    d.lat_max = lat.lat_of(j1);
    const std::int64_t g0 = i0 + lat.i_origin, g1 = i1 + lat.i_origin;
    d.description = fmt::format("box [{}, {}, {}, {}] snapped outward to {}° squares: {:.6g}..{:.6g}°E, "
                                "{:.6g}..{:.6g}°N ({} x {} pixels{})",
                                o.box[0], o.box[1], o.box[2], o.box[3], lat.step0_deg, d.lon_min, d.lon_max,
                                d.lat_min, d.lat_max, d.ni, d.nj,
                                (g0 < 0 || g1 > lat.nx_global) ? ", across the seam" : "");
    return;
  }
  // Rotated lattice: pixel centres tested in geographic coordinates.
  double width = o.box[1] - o.box[0];
  if (width < 0.0) width += 360.0;
  d.lon_min = o.box[0];
  d.lon_max = o.box[0] + width;
  d.lat_min = o.box[2];
  d.lat_max = o.box[3];
  d.description = fmt::format("box [{}, {}, {}, {}] (rotated lattice: pixels whose centre is in the box)", o.box[0],
                              o.box[1], o.box[2], o.box[3]);
}

// Even-odd over the rings: whether (lon, la) is inside, lon shifted into [lo, lo + 360). The
// crossing rule is the scanline's of polygon_domain (a centre on a crossing's longitude is on
// the side east of it).
bool inside_rings(const std::vector<Ring>& rings, double lo, double lon, double la) {
  double x = std::fmod(lon - lo, 360.0);
  if (x < 0.0) x += 360.0;
  x += lo;
  bool in = false;
  for (const Ring& r : rings) {
    const std::size_t n = r.lon.size();
    for (std::size_t k = 0; k < n; ++k) {
      const double ax = r.lon[k], ay = r.lat[k], bx = r.lon[(k + 1) % n], by = r.lat[(k + 1) % n];
      if ((ay <= la) == (by <= la)) continue;
      if (ax + (la - ay) * (bx - ax) / (by - ay) > x) in = !in;
    }
  }
  return in;
}

void polygon_domain(Domain& d, const config::DomainOptions& o, const Lattice& lat, const PoleRotation& rot) {
  std::vector<Ring> rings = read_polygon(o);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, so = lo, no = -lo;
  std::size_t vertices = 0;
  for (const Ring& r : rings) {
    vertices += r.lon.size();
    for (std::size_t k = 0; k < r.lon.size(); ++k) {
      lo = std::min(lo, r.lon[k]);
      hi = std::max(hi, r.lon[k]);
      so = std::min(so, r.lat[k]);
      no = std::max(no, r.lat[k]);
    }
  }
  if (hi - lo >= 360.0)
    throw InputError(
        fmt::format("domain.polygon = \"{}\": the polygon spans {}° of longitude (360° or more)", o.polygon, hi - lo));
  // On a window lattice: the column offset of the polygon's copy of the longitudes that lies on it.
  double shift = 0.0;
  if (lat.windowed()) {
    const double x_lo = (lo - lat.lon0_deg) / lat.pixel_deg();
    shift = lat.col_of_lon(lo) - x_lo;
  }
  d.poly_lon_lo = lo;
  d.poly_lat_lo = so;
  d.poly_lat_hi = no;
  d.poly_shift = shift;
  d.lon_min = lo;
  d.lon_max = hi;
  d.lat_min = so;
  d.lat_max = no;
  d.description = fmt::format("polygon {} ({} ring(s), {} vertices; {:.6g}..{:.6g}°E, {:.6g}..{:.6g}°N{})", o.polygon,
                              rings.size(), vertices, lo, hi, so, no,
                              rot.identity() ? "" : "; rotated lattice: pixels whose centre is in the polygon");
  d.rings = std::move(rings);
}

// The domain's pixels [i0, i0 + w) of row j into `out` (bit k = pixel i0 + k): the box's columns,
// the polygon's scanline spans (a centre on a crossing's longitude is on the side east of it) or,
// on a rotated lattice, the pixels whose centre's geographic position is inside.
void row_bits(const Domain& d, std::int64_t j, std::int64_t i0, std::int64_t w, std::uint64_t* out) {
  const Lattice& lat = d.lattice;
  const auto set = [&](std::int64_t i) {  // i any column: taken modulo nx
    const std::int64_t x = mod(i, lat.nx) - i0;
    if (x >= 0 && x < w) out[x >> 6] |= std::uint64_t{1} << (x & 63);
  };
  if (!d.rotation.identity()) {
    for (std::int64_t x = 0; x < w; ++x) {
      const LonLat c = pixel_center_lattice_deg(lat, {i0 + x, j});
      double lon = 0.0, la = 0.0;
      d.rotation.to_geographic(c.lon_deg, c.lat_deg, lon, la);
      bool in = false;
      if (d.kind == config::DomainKind::kBox) {
        double width = d.box[1] - d.box[0];
        if (width < 0.0) width += 360.0;
        double dl = std::fmod(lon - d.box[0], 360.0);
        if (dl < 0.0) dl += 360.0;
        in = dl < width && la >= d.box[2] && la <= d.box[3];
      } else {
        in = la >= d.poly_lat_lo && la <= d.poly_lat_hi && inside_rings(d.rings, d.poly_lon_lo, lon, la);
      }
      if (in) out[x >> 6] |= std::uint64_t{1} << (x & 63);
    }
    return;
  }
  if (d.kind == config::DomainKind::kBox) {
    if (j < d.j0 || j >= d.j0 + d.nj) return;
    // Columns d.i0 .. d.i0 + ni - 1, modulo nx: the unwrapped pieces [d.i0 + t·nx, ... + ni) that
    // meet [i0, i0 + w) (0 <= i0, i0 + w <= nx).
    for (std::int64_t t = -1; t <= 1; ++t) {
      const std::int64_t a = std::max(d.i0 + t * lat.nx, i0), b = std::min(d.i0 + t * lat.nx + d.ni, i0 + w);
      if (a < b) quadtree_free_set_range(out, a - i0, b - i0);
    }
    return;
  }
  const double la = lat.lat_of_row(static_cast<double>(j) + 0.5);
  if (la < d.poly_lat_lo || la > d.poly_lat_hi) return;
  const double pix = lat.pixel_deg();
  std::vector<double> xs;
  for (const Ring& r : d.rings) {
    const std::size_t n = r.lon.size();
    for (std::size_t k = 0; k < n; ++k) {
      const double ax = r.lon[k], ay = r.lat[k], bx = r.lon[(k + 1) % n], by = r.lat[(k + 1) % n];
      if ((ay <= la) == (by <= la)) continue;
      xs.push_back(ax + (la - ay) * (bx - ax) / (by - ay));
    }
  }
  std::sort(xs.begin(), xs.end());
  for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
    auto a = static_cast<std::int64_t>(std::ceil((xs[k] - lat.lon0_deg) / pix - 0.5));
    auto b = static_cast<std::int64_t>(std::ceil((xs[k + 1] - lat.lon0_deg) / pix - 0.5));
    if (!lat.periodic()) {  // the window holds the polygon's bounding box and a level-0 square more
      const auto sh = static_cast<std::int64_t>(std::llround(d.poly_shift));
      a = std::max<std::int64_t>(0, a + sh);
      b = std::min<std::int64_t>(lat.nx, b + sh);
    }
    for (std::int64_t i = a; i < b && i < a + lat.nx; ++i) set(i);
  }
}

}  // namespace

DomainExtent domain_extent(const config::DomainOptions& options, const Lattice& lattice) {
  DomainExtent e;
  if (options.resolved == DomainKind::kBox) {
    const SnappedBox b = snap_box(options, lattice);
    e = {lattice.lon_of(b.i0), lattice.lon_of(b.i1), lattice.lat_of(b.j0), lattice.lat_of(b.j1)};
  } else {
    const std::vector<Ring> rings = read_polygon(options);
    e = {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
         std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const Ring& r : rings)
      for (std::size_t k = 0; k < r.lon.size(); ++k) {
        e.lon_min = std::min(e.lon_min, r.lon[k]);
        e.lon_max = std::max(e.lon_max, r.lon[k]);
        e.lat_min = std::min(e.lat_min, r.lat[k]);
        e.lat_max = std::max(e.lat_max, r.lat[k]);
      }
  }
  return e;
}

bool Domain::contains(std::int64_t i, std::int64_t j) const {
  if (!regional()) return true;
  if (j < 0 || j >= lattice.ny) return false;
  if (!periodic && (i < 0 || i >= lattice.nx)) return false;
  if (dense) return inside.get(mod(i, inside.nx()), j);
  std::uint64_t bit = 0;
  row_bits(*this, j, mod(i, lattice.nx), 1, &bit);
  return bit != 0;
}

Bitmap Domain::window(std::int64_t col0, std::int64_t row0, std::int64_t w, std::int64_t h) const {
  Bitmap out(w, h);
  if (!regional()) {
    for (std::int64_t y = 0; y < h; ++y) quadtree_free_set_range(out.row(y), 0, w);
    return out;
  }
  for (std::int64_t y = 0; y < h; ++y) {
    if (dense) {
      for (std::int64_t x = 0; x < w; ++x)
        if (inside.get(col0 + x, row0 + y)) out.set(x, y);
    } else {
      row_bits(*this, row0 + y, col0, w, out.row(y));
    }
  }
  return out;
}

Domain make_domain(const config::DomainOptions& options, const Lattice& lattice, const PoleRotation& rot, bool dense) {
  Domain d;
  d.kind = options.resolved;
  if (!d.regional()) return d;
  d.periodic = lattice.periodic();
  d.lattice = lattice;
  d.rotation = rot;
  d.dense = dense;
  if (d.kind == DomainKind::kBox) {
    box_domain(d, options, lattice, rot);
  } else {
    polygon_domain(d, options, lattice, rot);
  }
  if (dense) {
    d.inside = Bitmap(lattice.nx, lattice.ny);
    for (std::int64_t j = 0; j < lattice.ny; ++j) row_bits(d, j, 0, lattice.nx, d.inside.row(j));
    d.pixels = d.inside.count();
    if (d.pixels == 0)
      throw ConfigError(
          fmt::format("domain: the {} holds no pixel of the lattice ({}° pixels)", d.description, lattice.pixel_deg()));
  }
  return d;
}

std::vector<std::array<double, 2>> regional_seeds(const Domain& domain, const Bitmap& wet, const Lattice& lattice,
                                                  const PoleRotation& rot, const raster::Bathymetry& bathy,
                                                  const std::vector<std::array<double, 2>>& seeds, const Logger& log) {
  std::vector<std::array<double, 2>> out;
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    double rl = 0.0, rp = 0.0, x = 0.0, y = 0.0;
    rot.to_rotated(seeds[k][0], seeds[k][1], rl, rp);
    deg_to_lattice_xy(lattice, {rl, rp}, x, y);
    if (!on_lattice(lattice, x, y)) continue;
    const auto i = static_cast<std::int64_t>(std::floor(x)), j = static_cast<std::int64_t>(std::floor(y));
    if (domain.contains(i, std::min(j, lattice.ny - 1))) out.push_back(seeds[k]);
  }
  if (!out.empty()) {
    if (out.size() < seeds.size())
      log.info("domain: {} of the {} mask.seeds are inside the domain and seed the fill", out.size(), seeds.size());
    return out;
  }
  // The deepest wet pixel inside (pixel centre sampled from the raster).
  double best = std::numeric_limits<double>::infinity();
  std::int64_t bi = -1, bj = -1;
  for (std::int64_t j = 0; j < lattice.ny; ++j)
    for (std::int64_t i = 0; i < lattice.nx; ++i) {
      if (!domain.inside.get(i, j) || !wet.get(i, j)) continue;
      const LonLat c = pixel_center_lattice_deg(lattice, {i, j});
      double lon = c.lon_deg, la = c.lat_deg;
      if (!rot.identity()) rot.to_geographic(c.lon_deg, c.lat_deg, lon, la);
      const double z = bathy.sample(lon, la);
      if (std::isfinite(z) && z < best) {
        best = z;
        bi = i;
        bj = j;
      }
    }
  if (bi < 0) throw InputError(fmt::format("domain: no wet pixel inside the {}", domain.description));
  const LonLat c = pixel_center_lattice_deg(lattice, {bi, bj});
  double lon = c.lon_deg, la = c.lat_deg;
  if (!rot.identity()) rot.to_geographic(c.lon_deg, c.lat_deg, lon, la);
  log.info("domain: no mask.seeds point is inside the domain; the fill starts at the deepest wet pixel inside, "
           "{:.4f}°E {:.4f}°N ({:.0f} m)",
           lon, la, best);
  return {{lon, la}};
}

std::array<double, 4> rotated_box_window(const std::vector<double>& b, const Lattice& lat, const PoleRotation& rot) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr int kSteps = 256;
  double width = b[1] - b[0];
  if (width < 0.0) width += 360.0;
  // Points along the edges of [x0, x0 + dx] x [y0, y0 + dy], mapped by f; longitudes unwrapped
  // against the first point.
  const auto outline = [&](double x0, double dx, double y0, double dy, auto f, std::array<double, 4>& box) {
    box = {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
           std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    double ref = kNaN;
    for (int e = 0; e < 4; ++e)
      for (int k = 0; k <= kSteps; ++k) {
        const double t = static_cast<double>(k) / kSteps;
        const double x = e < 2 ? x0 + t * dx : (e == 2 ? x0 : x0 + dx);
        const double y = e < 2 ? (e == 0 ? y0 : y0 + dy) : y0 + t * dy;
        double u = 0.0, v = 0.0;
        f(x, y, u, v);
        if (std::isnan(ref)) ref = u;
        u = ref + std::remainder(u - ref, 360.0);
        box = {std::min(box[0], u), std::max(box[1], u), std::min(box[2], v), std::max(box[3], v)};
      }
  };
  std::array<double, 4> r{};
  outline(
      b[0], width, b[2], b[3] - b[2], [&](double x, double y, double& u, double& v) { rot.to_rotated(x, y, u, v); }, r);
  const double mg = lat.step0_deg + 2.0 * lat.pixel_deg();
  const double mx = mg + 0.05 * (r[1] - r[0]), my = mg + 0.05 * (r[3] - r[2]);
  r = {r[0] - mx, r[1] + mx, r[2] - my, r[3] + my};
  if (r[1] - r[0] >= 180.0 || r[2] <= -89.0 || r[3] >= 89.0) return {kNaN, kNaN, kNaN, kNaN};
  std::array<double, 4> g{};
  outline(
      r[0], r[1] - r[0], r[2], r[3] - r[2],
      [&](double x, double y, double& u, double& v) { rot.to_geographic(x, y, u, v); }, g);
  // A geographic pole inside the rotated rectangle: the densified edges do not see it.
  for (const double pole : {-90.0, 90.0}) {
    double u = 0.0, v = 0.0;
    rot.to_rotated(0.0, pole, u, v);
    u = r[0] + std::fmod(std::fmod(u - r[0], 360.0) + 360.0, 360.0);
    if (u <= r[1] && v >= r[2] && v <= r[3]) return {kNaN, kNaN, kNaN, kNaN};
  }
  if (g[1] - g[0] >= 180.0) return {kNaN, kNaN, kNaN, kNaN};
  const double p = 2.0 * lat.pixel_deg();
  return {g[0] - p, g[1] + p, std::max(-90.0, g[2] - p), std::min(90.0, g[3] + p)};
}

}  // namespace aq::mask
