// SPDX-License-Identifier: GPL-3.0-or-later
// Several bathymetry sources behind one Bathymetry: priority with an optional blend at the
// sources' data edges (the rule and the distance field: raster/source_stack.hpp).
#include "raster/source_stack.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace aq::raster {

namespace {

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();
constexpr double kEarthRadiusKm = 6371.0088;  // mean radius (IUGG), as the size field's distances
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

// The value of source k (v), its weight w, and the value of the sources below (r).
inline double combine(double v, double w, double r) {
  if (std::isnan(v)) return r;
  if (w >= 1.0 || std::isnan(r)) return v;
  return w * v + (1.0 - w) * r;
}

// The lower envelope of parabolas (x − p_q)² + f_q over the points q with finite f, evaluated at
// the positions `at` (ascending): Felzenszwalb & Huttenlocher's 1-D squared distance transform.
// p ascending. out[i] = +inf when there is no point.
void envelope(const std::vector<double>& p, const std::vector<double>& f, const std::vector<double>& at,
              std::vector<double>& out, std::vector<std::size_t>& v, std::vector<double>& z) {
  out.assign(at.size(), std::numeric_limits<double>::infinity());
  v.clear();
  z.clear();
  for (std::size_t q = 0; q < p.size(); ++q) {
    if (!std::isfinite(f[q])) continue;
    double s = -std::numeric_limits<double>::infinity();
    while (!v.empty()) {
      const std::size_t u = v.back();
      s = ((f[q] + p[q] * p[q]) - (f[u] + p[u] * p[u])) / (2.0 * (p[q] - p[u]));
      if (s > z.back()) break;
      v.pop_back();
      z.pop_back();
      s = -std::numeric_limits<double>::infinity();
    }
    v.push_back(q);
    z.push_back(v.size() == 1 ? -std::numeric_limits<double>::infinity() : s);
  }
  if (v.empty()) return;
  std::size_t k = 0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    while (k + 1 < v.size() && z[k + 1] < at[i]) ++k;
    const double dx = at[i] - p[v[k]];
    out[i] = dx * dx + f[v[k]];
  }
}

}  // namespace

double Bathymetry::blend_weight(double d_km, double blend_km) {
  if (!(blend_km > 0.0)) return 1.0;
  if (std::isnan(d_km)) return 0.0;
  const double s = std::clamp(d_km / blend_km, 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

Bathymetry edge_distance_field(const Bathymetry& source, double cap_km) {
  const RasterInfo& in = source.info();
  const std::int64_t nc = in.ncols, nr = in.nrows;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  source.values(0, nc, 0, nr, v.data());
  const bool wrap = in.global_lon;
  const bool south_edge = in.lat_first - 0.5 * in.dlat > -90.0 + 1e-9;
  const bool north_edge = in.lat_first + (static_cast<double>(nr) - 0.5) * in.dlat < 90.0 - 1e-9;
  const auto at = [&](std::int64_t c, std::int64_t r) { return static_cast<std::size_t>(r * nc + c); };

  // Edge points: no-data, a no-data neighbour (of 8), the outermost rows/columns of the extent.
  std::vector<unsigned char> edge(v.size(), 0);
#pragma omp parallel for schedule(static) default(none) shared(v, edge, at, nc, nr, wrap, south_edge, north_edge)
  for (std::int64_t r = 0; r < nr; ++r) {
    for (std::int64_t c = 0; c < nc; ++c) {
      bool e = std::isnan(v[at(c, r)]) || (!wrap && (c == 0 || c == nc - 1)) || (south_edge && r == 0) ||
               (north_edge && r == nr - 1);
      for (std::int64_t dr = -1; dr <= 1 && !e; ++dr)
        for (std::int64_t dc = -1; dc <= 1 && !e; ++dc) {
          const std::int64_t rr = r + dr;
          std::int64_t cc = c + dc;
          if (rr < 0 || rr >= nr) continue;
          if (wrap) cc = (cc + nc) % nc;
          if (cc < 0 || cc >= nc) continue;
          e = std::isnan(v[at(cc, rr)]);
        }
      edge[at(c, r)] = e ? 1 : 0;
    }
  }
  v = {};

  // Along columns: g = distance (km) to the nearest edge point of the same column (+inf: none).
  const double dy_km = kEarthRadiusKm * in.dlat * kDegToRad;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> g(edge.size(), inf);
#pragma omp parallel for schedule(static) default(none) shared(edge, g, at, nc, nr, dy_km, inf)
  for (std::int64_t c = 0; c < nc; ++c) {
    double last = -inf;
    for (std::int64_t r = 0; r < nr; ++r) {
      if (edge[at(c, r)] != 0) last = static_cast<double>(r);
      g[at(c, r)] = (static_cast<double>(r) - last) * dy_km;
    }
    last = inf;
    for (std::int64_t r = nr - 1; r >= 0; --r) {
      if (edge[at(c, r)] != 0) last = static_cast<double>(r);
      g[at(c, r)] = std::min(g[at(c, r)], (last - static_cast<double>(r)) * dy_km);
    }
  }
  edge = {};

  // Along rows, on the row's plane (Δx = R cos φ Δλ): d² = min over columns q of (x − x_q)² + g_q².
  // Columns with g_q >= cap cannot bring d under the cap and are left out; a global raster's row
  // is extended by the columns within the cap on each side (at most one turn).
  std::vector<float> d(g.size());
  const double lat_first = in.lat_first, dlat = in.dlat, dlon = in.dlon;
#pragma omp parallel default(none) shared(g, d, at, nc, nr, wrap, cap_km, lat_first, dlat, dlon)
  {
    std::vector<double> p, f, pos, out, z;
    std::vector<std::size_t> stack;
#pragma omp for schedule(static)
    for (std::int64_t r = 0; r < nr; ++r) {
      const double phi = lat_first + static_cast<double>(r) * dlat;
      const double dx_km = std::max(1e-9, kEarthRadiusKm * std::cos(phi * kDegToRad) * dlon * kDegToRad);
      std::int64_t m = 0;
      if (wrap) m = std::min<std::int64_t>(nc, static_cast<std::int64_t>(std::ceil(cap_km / dx_km)) + 1);
      p.clear();
      f.clear();
      pos.resize(static_cast<std::size_t>(nc));
      for (std::int64_t q = -m; q < nc + m; ++q) {
        const std::int64_t cq = wrap ? ((q % nc) + nc) % nc : q;
        const double gq = g[at(cq, r)];
        if (!(gq < cap_km)) continue;
        p.push_back(static_cast<double>(q) * dx_km);
        f.push_back(gq * gq);
      }
      for (std::int64_t c = 0; c < nc; ++c) pos[static_cast<std::size_t>(c)] = static_cast<double>(c) * dx_km;
      envelope(p, f, pos, out, stack, z);
      for (std::int64_t c = 0; c < nc; ++c)
        d[at(c, r)] = static_cast<float>(std::min(cap_km, std::sqrt(out[static_cast<std::size_t>(c)])));
    }
  }
  return Bathymetry::from_grid(std::move(d), nc, nr, in.lon_first, in.lat_first, in.dlon, in.dlat);
}

double Bathymetry::Stack::sample(double lon_deg, double lat_deg) const { return sample_from(0, lon_deg, lat_deg); }

double Bathymetry::Stack::sample_from(std::size_t k, double lon_deg, double lat_deg) const {
  const double v = sources[k].sample(lon_deg, lat_deg);
  if (k + 1 == sources.size()) return v;
  if (std::isnan(v)) return sample_from(k + 1, lon_deg, lat_deg);
  if (!(blend_km > 0.0)) return v;
  const double w = blend_weight(distances[k].sample(lon_deg, lat_deg), blend_km);
  if (w >= 1.0) return v;
  return combine(v, w, sample_from(k + 1, lon_deg, lat_deg));
}

void Bathymetry::Stack::sample_points(const double* lon_deg, const double* lat_deg, std::int64_t n, double* out,
                                      int* code) const {
  points_from(0, lon_deg, lat_deg, n, out, code);
}

void Bathymetry::Stack::points_from(std::size_t k, const double* lon_deg, const double* lat_deg, std::int64_t n,
                                    double* out, int* code) const {
  sources[k].sample_points(lon_deg, lat_deg, n, out);
  const bool last = k + 1 == sources.size();
  std::vector<double> w;
  if (!last && blend_km > 0.0) {
    w.resize(static_cast<std::size_t>(n));
    distances[k].sample_points(lon_deg, lat_deg, n, w.data());
    for (double& x : w) x = blend_weight(x, blend_km);
  }
  const auto weight = [&w](std::int64_t i) { return w.empty() ? 1.0 : w[static_cast<std::size_t>(i)]; };
  std::vector<std::int64_t> below;  // points that need the sources below
  for (std::int64_t i = 0; i < n; ++i) {
    const bool has = !std::isnan(out[i]);
    if (code != nullptr) code[i] = has ? static_cast<int>(k) : kNoSource;
    if (!last && (!has || weight(i) < 1.0)) below.push_back(i);
  }
  if (below.empty()) return;
  const auto m = static_cast<std::int64_t>(below.size());
  std::vector<double> lon(below.size()), lat(below.size()), r(below.size());
  std::vector<int> rc(code != nullptr ? below.size() : 0);
  for (std::size_t j = 0; j < below.size(); ++j) {
    lon[j] = lon_deg[below[j]];
    lat[j] = lat_deg[below[j]];
  }
  points_from(k + 1, lon.data(), lat.data(), m, r.data(), code != nullptr ? rc.data() : nullptr);
  for (std::size_t j = 0; j < below.size(); ++j) {
    const std::int64_t i = below[j];
    const bool has = !std::isnan(out[i]);
    if (code != nullptr)
      code[i] = !has ? rc[j] : std::isnan(r[j]) ? static_cast<int>(k) : kBlended + static_cast<int>(k);
    out[i] = combine(out[i], weight(i), r[j]);
  }
}

Bathymetry::Columns Bathymetry::Stack::prepare_columns(const double* lons, std::int64_t n, bool skip_tiled) const {
  Columns c;
  c.lon.assign(lons, lons + n);
  c.skip_tiled = skip_tiled;
  for (const Bathymetry& s : sources) c.sources.push_back(s.prepare_columns(lons, n, skip_tiled));
  for (const Bathymetry& d : distances) c.distances.push_back(d.prepare_columns(lons, n));
  return c;
}

void Bathymetry::Stack::sample_row(const Columns& cols, double lat_deg, float* out) const {
  row_from(0, cols, lat_deg, out);
}

void Bathymetry::Stack::row_from(std::size_t k, const Columns& cols, double lat_deg, float* out) const {
  sources[k].sample_row(cols.sources[k], lat_deg, out);
  if (k + 1 == sources.size()) return;
  const auto n = static_cast<std::int64_t>(cols.lon.size());
  std::vector<float> d;
  if (blend_km > 0.0) {
    d.resize(static_cast<std::size_t>(n));
    distances[k].sample_row(cols.distances[k], lat_deg, d.data());
  }
  bool need = false;
  for (std::int64_t i = 0; i < n && !need; ++i)
    need = std::isnan(out[i]) || (!d.empty() && blend_weight(d[static_cast<std::size_t>(i)], blend_km) < 1.0);
  if (!need) return;
  std::vector<float> r(static_cast<std::size_t>(n));
  row_from(k + 1, cols, lat_deg, r.data());
  for (std::int64_t i = 0; i < n; ++i) {
    const auto s = static_cast<std::size_t>(i);
    const double w = d.empty() ? 1.0 : blend_weight(d[s], blend_km);
    out[i] = static_cast<float>(combine(out[i], w, r[s]));
  }
}

void Bathymetry::Stack::sample_rows(const Columns& cols, const double* lats, std::int64_t n, const RowSink& sink,
                                    const ProgressFn& progress) const {
  // In chunks of rows (16 MB of float), each source sampled only on the rows that the sources
  // above leave (partly) open, straight into the chunk where a source above has nothing in a row.
  const auto nc = static_cast<std::int64_t>(cols.lon.size());
  const std::int64_t chunk = std::max<std::int64_t>(1, (std::int64_t{1} << 22) / std::max<std::int64_t>(1, nc));
  std::vector<float> buf;
  std::vector<float*> rows;
  for (std::int64_t k0 = 0; k0 < n; k0 += chunk) {
    const std::int64_t m = std::min(chunk, n - k0);
    buf.resize(static_cast<std::size_t>(m * nc));
    rows.resize(static_cast<std::size_t>(m));
    for (std::int64_t q = 0; q < m; ++q) rows[static_cast<std::size_t>(q)] = buf.data() + q * nc;
    block_from(0, cols, lats + k0, m, rows.data());
    const float* b = buf.data();
#pragma omp parallel for schedule(static) default(none) \
    shared(sink, b, k0, m, nc) if (m * nc >= (std::int64_t{1} << 16))
    for (std::int64_t q = 0; q < m; ++q) sink(k0 + q, b + q * nc);
    if (progress) progress(static_cast<double>(k0 + m) / static_cast<double>(n), "rows");
  }
  if (n == 0)  // a pass without rows still reads the streamed sources' statistics
    for (const Bathymetry& s : sources) s.ensure_statistics();
}

void Bathymetry::Stack::block_from(std::size_t k, const Columns& cols, const double* lats, std::int64_t n,
                                   float* const* out) const {
  const auto nc = static_cast<std::int64_t>(cols.lon.size());
  sources[k].sample_rows(cols.sources[k], lats, n,
                         [out, nc](std::int64_t q, const float* v) { std::copy(v, v + nc, out[q]); });
  if (k + 1 == sources.size()) return;
  // Rows where this source has nothing go to the sources below as they are (written in place);
  // rows where it has something need them where it is NaN or within the blend.
  std::vector<std::int64_t> empty, partial;
  for (std::int64_t q = 0; q < n; ++q) {
    const float* o = out[q];
    (std::all_of(o, o + nc, [](float x) { return std::isnan(x); }) ? empty : partial).push_back(q);
  }
  const auto np = static_cast<std::int64_t>(partial.size());
  std::vector<double> sub;
  for (const std::int64_t q : partial) sub.push_back(lats[q]);
  std::vector<float> d;
  if (blend_km > 0.0 && np > 0) {
    d.resize(static_cast<std::size_t>(np * nc));
    float* dd = d.data();
    distances[k].sample_rows(cols.distances[k], sub.data(), np,
                             [dd, nc](std::int64_t q, const float* v) { std::copy(v, v + nc, dd + q * nc); });
  }
  const double cap = blend_km;
  std::vector<std::int64_t> open;  // indices into partial
  for (std::int64_t j = 0; j < np; ++j) {
    const float* o = out[partial[static_cast<std::size_t>(j)]];
    bool need = false;
    for (std::int64_t i = 0; i < nc && !need; ++i)
      need = std::isnan(o[i]) || (!d.empty() && blend_weight(d[static_cast<std::size_t>(j * nc + i)], cap) < 1.0);
    if (need) open.push_back(j);
  }
  if (empty.empty() && open.empty()) return;
  const auto no = static_cast<std::int64_t>(open.size());
  std::vector<float> r(static_cast<std::size_t>(no * nc));
  std::vector<double> below_lats;
  std::vector<float*> below_rows;
  for (const std::int64_t q : empty) {
    below_lats.push_back(lats[q]);
    below_rows.push_back(out[q]);
  }
  for (std::int64_t j = 0; j < no; ++j) {
    below_lats.push_back(sub[static_cast<std::size_t>(open[static_cast<std::size_t>(j)])]);
    below_rows.push_back(r.data() + j * nc);
  }
  block_from(k + 1, cols, below_lats.data(), static_cast<std::int64_t>(below_lats.size()), below_rows.data());
  const float* rr = r.data();
  const float* dd = d.empty() ? nullptr : d.data();
#pragma omp parallel for schedule(static) default(none) \
    shared(open, partial, rr, dd, out, no, nc, cap) if (no * nc >= (std::int64_t{1} << 16))
  for (std::int64_t jj = 0; jj < no; ++jj) {
    const std::int64_t j = open[static_cast<std::size_t>(jj)];
    float* o = out[partial[static_cast<std::size_t>(j)]];
    const float* lower = rr + jj * nc;
    for (std::int64_t i = 0; i < nc; ++i) {
      if (std::isnan(o[i])) {
        o[i] = lower[i];
        continue;
      }
      const double w = dd == nullptr ? 1.0 : blend_weight(dd[j * nc + i], cap);
      o[i] = static_cast<float>(combine(o[i], w, lower[i]));
    }
  }
}

void Bathymetry::Stack::ensure_statistics(const ProgressFn& progress) const {
  for (const Bathymetry& s : sources) s.ensure_statistics(progress);
}

Bathymetry Bathymetry::open_sources(const std::vector<OpenOptions>& sources, double blend_km, const Logger& log) {
  if (sources.empty()) throw InputError("no bathymetry source given (input.path or input.paths)");
  if (sources.size() == 1) return open(sources.front(), log);
  std::vector<Bathymetry> open_ones;
  for (std::size_t k = 0; k < sources.size(); ++k) {
    OpenOptions o = sources[k];
    o.warn_partial_coverage = o.warn_partial_coverage && k + 1 == sources.size();
    open_ones.push_back(open(o, log));
    if (blend_km > 0.0 && k + 1 < sources.size() && (open_ones.back().info().streamed || open_ones.back().info().tiled))
      throw InputError(fmt::format(
          "{}: input.blend_km = {} needs the distance to this raster's data edge, held whole beside it, but the "
          "raster is {} (too large to hold); blend only below a smaller source, or set input.blend_km = 0",
          sources[k].path, blend_km, open_ones.back().info().streamed ? "streamed" : "read in tiles"));
  }
  return stack(std::move(open_ones), blend_km);
}

std::size_t Bathymetry::source_count() const { return stack_ ? stack_->sources.size() : 1; }

const Bathymetry& Bathymetry::source(std::size_t k) const {
  if (!stack_) {
    if (k != 0) throw InternalError(fmt::format("Bathymetry::source({}) of a single raster", k));
    return *this;
  }
  return stack_->sources.at(k);
}

void Bathymetry::supplying_sources(const double* lon_deg, const double* lat_deg, std::int64_t n, int* out) const {
  if (stack_) {
    std::vector<double> v(static_cast<std::size_t>(n));
    stack_->sample_points(lon_deg, lat_deg, n, v.data(), out);
    return;
  }
  std::vector<double> v(static_cast<std::size_t>(n));
  sample_points(lon_deg, lat_deg, n, v.data());
  for (std::int64_t i = 0; i < n; ++i) out[i] = std::isnan(v[static_cast<std::size_t>(i)]) ? kNoSource : 0;
}

}  // namespace aq::raster
