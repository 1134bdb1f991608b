// Bathymetry: GDAL raster input, normalisation (longitude origin, registration, duplicated
// column, orientation, no-data, scale/offset, positive-down) and sampling (ARCHITECTURE §4.1).
// Bilinear sampling on the smallest cell of raster points containing the point is the seed's
// rule (seed 002); the bicubic option is the C2 spline of reference splines.md §4 (periodic in
// longitude on a global raster, natural ends in latitude).
#include "raster/bathymetry.hpp"

#include <fmt/format.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>

#include "core/error.hpp"
#include "core/timer.hpp"
#include "raster/spline1d.hpp"

namespace aq::raster {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void gdal_init() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);  // GDAL errors become exceptions with the message
    // A small block cache: rows are copied into our array once, so GDAL need not keep them too.
    if (CPLGetConfigOption("GDAL_CACHEMAX", nullptr) == nullptr) GDALSetCacheMax64(64LL << 20);
  });
}

std::string gdal_message() {
  const char* m = CPLGetLastErrorMsg();
  return (m != nullptr && *m != '\0') ? std::string(": ") + m : std::string();
}

// Snaps x to the nearest multiple of q when within 1e-3·q (float32 coordinate noise).
double snap(double x, double q) {
  const double k = std::round(x / q);
  return std::abs(x / q - k) < 1e-3 ? k * q : x;
}

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

DatasetPtr open_dataset(const OpenOptions& o, std::string& used_name) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(o.path, ec)) throw InputError(fmt::format("{}: no such file", o.path));
  if (fs::is_directory(o.path, ec)) throw InputError(fmt::format("{}: is a directory, not a raster", o.path));
  DatasetPtr ds(static_cast<GDALDataset*>(
      GDALOpenEx(o.path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds) {
    FILE* f = std::fopen(o.path.c_str(), "rb");
    if (f == nullptr) throw InputError(fmt::format("{}: cannot read the file", o.path));
    std::fclose(f);
    throw InputError(fmt::format("{}: not a raster GDAL can read{}", o.path, gdal_message()));
  }
  used_name = o.path;
  char** subs = ds->GetMetadata("SUBDATASETS");
  std::vector<std::string> names;
  for (int k = 0; subs != nullptr && subs[k] != nullptr; ++k) {
    std::string kv = subs[k];
    const auto eq = kv.find('=');
    if (eq != std::string::npos && kv.find("_NAME=") != std::string::npos) names.push_back(kv.substr(eq + 1));
  }
  if (!o.variable.empty() || (ds->GetRasterCount() == 0 && !names.empty())) {
    std::string pick;
    if (o.variable.empty()) {
      pick = names.front();
    } else {
      for (const auto& n : names) {
        const auto c = n.rfind(':');
        if (c != std::string::npos && n.substr(c + 1) == o.variable) pick = n;
      }
      if (pick.empty() && ds->GetRasterCount() > 0) {
        // Single-variable netCDF: GDAL opens the variable directly; check its name.
        const char* vn = ds->GetRasterBand(1)->GetMetadataItem("NETCDF_VARNAME");
        if (vn != nullptr && o.variable == vn) return ds;
      }
      if (pick.empty()) {
        std::string avail;
        for (const auto& n : names) avail += " " + n.substr(n.rfind(':') + 1);
        if (avail.empty() && ds->GetRasterCount() > 0) {
          const char* vn = ds->GetRasterBand(1)->GetMetadataItem("NETCDF_VARNAME");
          avail = vn != nullptr ? std::string(" ") + vn : std::string(" (band 1 only)");
        }
        throw InputError(
            fmt::format("{}: variable '{}' not found (input.variable); the file has:{}", o.path, o.variable, avail));
      }
    }
    ds.reset(static_cast<GDALDataset*>(
        GDALOpenEx(pick.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
    if (!ds) throw InputError(fmt::format("{}: cannot open {}{}", o.path, pick, gdal_message()));
    used_name = pick;
  }
  if (ds->GetRasterCount() == 0) throw InputError(fmt::format("{}: not a raster (no bands)", o.path));
  return ds;
}

}  // namespace

struct Bathymetry::Impl {
  RasterInfo info;
  std::vector<float> v;            // ncols × nrows, south-up
  std::vector<float> fx, fy, fxy;  // bicubic: slopes per degree, only when bicubic
  Interpolation interp = Interpolation::kBilinear;
  bool global_lat = false;

  [[nodiscard]] std::size_t idx(std::int64_t c, std::int64_t r) const {
    return static_cast<std::size_t>(r * info.ncols + c);
  }

  // Column position: c0, t (c1 = next column, wrapped). Returns false outside coverage.
  bool col(double lon, std::int64_t& c0, std::int64_t& c1, double& t) const {
    const auto n = info.ncols;
    double x = (lon - info.lon_first) / info.dlon;
    if (info.global_lon) {
      x = std::fmod(x, static_cast<double>(n));
      if (x < 0.0) x += static_cast<double>(n);
    }
    const double xr = std::round(x);
    if (std::abs(x - xr) < 1e-9) x = xr;  // a point on a grid line takes the grid value exactly
    if (info.global_lon) {
      if (x >= static_cast<double>(n)) x -= static_cast<double>(n);
      c0 = static_cast<std::int64_t>(std::floor(x));
      t = x - static_cast<double>(c0);
      c1 = (c0 + 1 == n) ? 0 : c0 + 1;
      return true;
    }
    if (x < -0.5 || x > static_cast<double>(n) - 0.5) return false;
    x = std::clamp(x, 0.0, static_cast<double>(n - 1));
    c0 = std::min<std::int64_t>(static_cast<std::int64_t>(std::floor(x)), n - 1);
    t = x - static_cast<double>(c0);
    c1 = std::min<std::int64_t>(c0 + 1, n - 1);
    return true;
  }

  bool row(double lat, std::int64_t& r0, std::int64_t& r1, double& u) const {
    const auto n = info.nrows;
    double y = (lat - info.lat_first) / info.dlat;
    const double yr = std::round(y);
    if (std::abs(y - yr) < 1e-9) y = yr;
    if (!global_lat && (y < -0.5 || y > static_cast<double>(n) - 0.5)) return false;
    y = std::clamp(y, 0.0, static_cast<double>(n - 1));  // beyond the outermost row: nearest row
    r0 = std::min<std::int64_t>(static_cast<std::int64_t>(std::floor(y)), n - 1);
    u = y - static_cast<double>(r0);
    r1 = std::min<std::int64_t>(r0 + 1, n - 1);
    return true;
  }

  [[nodiscard]] double bilinear(std::int64_t c0, std::int64_t c1, double t, std::int64_t r0, std::int64_t r1,
                                double u) const {
    const double a = v[idx(c0, r0)], b = v[idx(c1, r0)], c = v[idx(c0, r1)], d = v[idx(c1, r1)];
    // Exact grid values where the weights vanish (no 0·NaN, no rounding).
    if (t == 0.0 && u == 0.0) return a;
    const double lo = (t == 0.0) ? a : (1.0 - t) * a + t * b;
    if (u == 0.0) return lo;
    const double hi = (t == 0.0) ? c : (1.0 - t) * c + t * d;
    return (1.0 - u) * lo + u * hi;
  }

  [[nodiscard]] double bicubic(std::int64_t c0, std::int64_t c1, double t, std::int64_t r0, std::int64_t r1,
                               double u) const {
    // Hermite basis on the unit cell; slopes stored per cell step.
    const auto h0 = [](double s) { return (1 + 2 * s) * (1 - s) * (1 - s); };
    const auto h1 = [](double s) { return s * s * (3 - 2 * s); };
    const auto g0 = [](double s) { return s * (1 - s) * (1 - s); };
    const auto g1 = [](double s) { return -s * s * (1 - s); };
    const std::size_t i00 = idx(c0, r0), i10 = idx(c1, r0), i01 = idx(c0, r1), i11 = idx(c1, r1);
    const double ax[4] = {h0(t), h1(t), g0(t), g1(t)};
    const double ay[4] = {h0(u), h1(u), g0(u), g1(u)};
    const double f[2][2] = {{v[i00], v[i01]}, {v[i10], v[i11]}};
    const double px[2][2] = {{fx[i00], fx[i01]}, {fx[i10], fx[i11]}};
    const double py[2][2] = {{fy[i00], fy[i01]}, {fy[i10], fy[i11]}};
    const double pxy[2][2] = {{fxy[i00], fxy[i01]}, {fxy[i10], fxy[i11]}};
    double s = 0.0;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        s += ax[a] * ay[b] * f[a][b] + ax[2 + a] * ay[b] * px[a][b] + ax[a] * ay[2 + b] * py[a][b] +
             ax[2 + a] * ay[2 + b] * pxy[a][b];
    return s;
  }

  [[nodiscard]] double sample(double lon, double lat) const {
    std::int64_t c0 = 0, c1 = 0, r0 = 0, r1 = 0;
    double t = 0.0, u = 0.0;
    if (!col(lon, c0, c1, t) || !row(lat, r0, r1, u)) return kNaN;
    if (interp == Interpolation::kBicubic && !fx.empty()) return bicubic(c0, c1, t, r0, r1, u);
    return bilinear(c0, c1, t, r0, r1, u);
  }

  void compute_stats() {
    double mn = std::numeric_limits<double>::infinity(), mx = -mn, sum = 0.0;
    std::int64_t count = 0;
    for (const float x : v) {
      if (std::isnan(x)) continue;
      mn = std::min(mn, static_cast<double>(x));
      mx = std::max(mx, static_cast<double>(x));
      sum += x;
      ++count;
    }
    info.valid_count = count;
    info.min_m = count > 0 ? mn : kNaN;
    info.max_m = count > 0 ? mx : kNaN;
    info.mean_m = count > 0 ? sum / static_cast<double>(count) : kNaN;
    info.memory_bytes = static_cast<std::int64_t>((v.size() + fx.size() + fy.size() + fxy.size()) * sizeof(float));
  }

  // Bicubic spline slopes (splines.md §4, 3-step algorithm): fx by rows, fy by columns, fxy by
  // columns of fx. Slopes are per cell step (h = 1).
  void build_spline() {
    const auto nc = info.ncols, nr = info.nrows;
    for (const float x : v)
      if (std::isnan(x))
        throw ConfigError(
            fmt::format("input.interpolation = \"bicubic\": {} has no-data cells; the spline needs "
                        "a complete raster (use \"bilinear\")",
                        info.path));
    fx.assign(v.size(), 0.0f);
    fy.assign(v.size(), 0.0f);
    fxy.assign(v.size(), 0.0f);
    const bool per = info.global_lon;
#pragma omp parallel default(none) shared(nc, nr, per)
    {
      const std::int64_t nmax = std::max(nc, nr);
      std::vector<double> f(static_cast<std::size_t>(nmax)), d(f.size()), w(2 * f.size());
#pragma omp for schedule(static)
      for (std::int64_t r = 0; r < nr; ++r) {
        for (std::int64_t c = 0; c < nc; ++c) f[static_cast<std::size_t>(c)] = v[idx(c, r)];
        spline_slopes(f.data(), d.data(), nc, 1.0, per, w.data());
        for (std::int64_t c = 0; c < nc; ++c) fx[idx(c, r)] = static_cast<float>(d[static_cast<std::size_t>(c)]);
      }
#pragma omp for schedule(static)
      for (std::int64_t c = 0; c < nc; ++c) {
        for (std::int64_t r = 0; r < nr; ++r) f[static_cast<std::size_t>(r)] = v[idx(c, r)];
        spline_slopes(f.data(), d.data(), nr, 1.0, false, w.data());
        for (std::int64_t r = 0; r < nr; ++r) fy[idx(c, r)] = static_cast<float>(d[static_cast<std::size_t>(r)]);
        for (std::int64_t r = 0; r < nr; ++r) f[static_cast<std::size_t>(r)] = fx[idx(c, r)];
        spline_slopes(f.data(), d.data(), nr, 1.0, false, w.data());
        for (std::int64_t r = 0; r < nr; ++r) fxy[idx(c, r)] = static_cast<float>(d[static_cast<std::size_t>(r)]);
      }
    }
  }
};

Bathymetry::Bathymetry(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Bathymetry::Bathymetry(Bathymetry&&) noexcept = default;
Bathymetry& Bathymetry::operator=(Bathymetry&&) noexcept = default;
Bathymetry::~Bathymetry() = default;

const RasterInfo& Bathymetry::info() const { return impl_->info; }
double Bathymetry::sample(double lon_deg, double lat_deg) const { return impl_->sample(lon_deg, lat_deg); }

float Bathymetry::value(std::int64_t c, std::int64_t r) const {
  const auto& i = impl_->info;
  if (i.global_lon) c = ((c % i.ncols) + i.ncols) % i.ncols;
  if (c < 0 || c >= i.ncols || r < 0 || r >= i.nrows) return std::numeric_limits<float>::quiet_NaN();
  return impl_->v[impl_->idx(c, r)];
}

void Bathymetry::sample_points(const double* lon_deg, const double* lat_deg, std::int64_t n, double* out) const {
  const Impl* im = impl_.get();
#pragma omp parallel for default(none) shared(im, lon_deg, lat_deg, n, out) schedule(static) if (n > 20000)
  for (std::int64_t k = 0; k < n; ++k) out[k] = im->sample(lon_deg[k], lat_deg[k]);
}

Bathymetry::Columns Bathymetry::prepare_columns(const double* lons, std::int64_t n) const {
  Columns c;
  c.c0.resize(static_cast<std::size_t>(n));
  c.c1.resize(c.c0.size());
  c.t.resize(c.c0.size());
  c.lon.assign(lons, lons + n);
  for (std::int64_t k = 0; k < n; ++k) {
    const auto s = static_cast<std::size_t>(k);
    if (!impl_->col(lons[k], c.c0[s], c.c1[s], c.t[s])) {
      c.c0[s] = -1;  // outside a regional raster
      c.c1[s] = -1;
      c.t[s] = 0.0;
    }
  }
  return c;
}

void Bathymetry::sample_row(const Columns& cols, double lat_deg, float* out) const {
  const Impl& im = *impl_;
  std::int64_t r0 = 0, r1 = 0;
  double u = 0.0;
  const auto n = static_cast<std::int64_t>(cols.c0.size());
  if (!im.row(lat_deg, r0, r1, u)) {
    std::fill(out, out + n, std::numeric_limits<float>::quiet_NaN());
    return;
  }
  const bool cubic = im.interp == Interpolation::kBicubic && !im.fx.empty();
  for (std::int64_t k = 0; k < n; ++k) {
    const auto s = static_cast<std::size_t>(k);
    if (cols.c0[s] < 0) {
      out[k] = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    const double val = cubic ? im.bicubic(cols.c0[s], cols.c1[s], cols.t[s], r0, r1, u)
                             : im.bilinear(cols.c0[s], cols.c1[s], cols.t[s], r0, r1, u);
    out[k] = static_cast<float>(val);
  }
}

std::int64_t estimate_raster_bytes(std::int64_t width, std::int64_t height) {
  return width * height * static_cast<std::int64_t>(sizeof(float));
}

Bathymetry Bathymetry::from_grid(std::vector<float> values, std::int64_t ncols, std::int64_t nrows, double lon_first,
                                 double lat_first, double dlon, double dlat, Interpolation interpolation) {
  if (ncols < 2 || nrows < 2 || static_cast<std::int64_t>(values.size()) != ncols * nrows || !(dlon > 0) ||
      !(dlat > 0)) {
    throw InputError("from_grid: values must be ncols×nrows (>= 2×2) with positive steps");
  }
  auto im = std::make_unique<Impl>();
  im->v = std::move(values);
  im->interp = interpolation;
  auto& i = im->info;
  i.path = "<memory>";
  i.driver = "memory";
  i.width = i.ncols = ncols;
  i.height = i.nrows = nrows;
  i.dlon = dlon;
  i.dlat = dlat;
  i.lon_first = i.lon_first_found = lon_first;
  i.lat_first = lat_first;
  i.north_up = false;
  i.global_lon = std::abs(static_cast<double>(ncols) * dlon - 360.0) < 1e-9 * 360.0;
  im->global_lat = static_cast<double>(nrows - 1) * dlat >= 180.0 - 1e-9 ||
                   std::abs(static_cast<double>(nrows) * dlat - 180.0) < 1e-9;
  i.registration = std::abs(lon_first / dlon - std::round(lon_first / dlon)) < 1e-6 ? "grid" : "pixel";
  i.data_type = "Float32";
  i.crs_name = "WGS 84 (assumed)";
  i.units = "m";
  if (interpolation == Interpolation::kBicubic) im->build_spline();
  im->compute_stats();
  return Bathymetry(std::move(im));
}

Bathymetry Bathymetry::open(const OpenOptions& o, const Logger& log) {
  gdal_init();
  std::string used;
  DatasetPtr ds = open_dataset(o, used);
  auto im = std::make_unique<Impl>();
  im->interp = o.interpolation;
  RasterInfo& info = im->info;
  info.path = o.path;
  info.driver = ds->GetDriver() != nullptr ? ds->GetDriver()->GetDescription() : "?";
  info.width = ds->GetRasterXSize();
  info.height = ds->GetRasterYSize();

  if (o.band < 1 || o.band > ds->GetRasterCount()) {
    throw InputError(fmt::format("{}: band {} not found (input.band); the raster has {} band(s)", o.path, o.band,
                                 ds->GetRasterCount()));
  }
  GDALRasterBand* band = ds->GetRasterBand(o.band);
  const char* vn = band->GetMetadataItem("NETCDF_VARNAME");
  info.variable = vn != nullptr ? vn : (o.variable.empty() ? fmt::format("band {}", o.band) : o.variable);
  const char* unit = band->GetUnitType();
  info.units = unit != nullptr ? unit : "";
  info.data_type = GDALGetDataTypeName(band->GetRasterDataType());

  // Coordinate reference system: geographic only.
  const OGRSpatialReference* srs = ds->GetSpatialRef();
  if (srs != nullptr && !srs->IsEmpty()) {
    const char* name = srs->GetName();
    info.crs_name = name != nullptr ? name : "unnamed";
    if (srs->IsProjected() || !srs->IsGeographic()) {
      throw InputError(
          fmt::format("{}: coordinate system '{}' is not geographic (lon/lat); reproject to "
                      "EPSG:4326 first (e.g. gdalwarp -t_srs EPSG:4326)",
                      o.path, info.crs_name));
    }
  } else {
    info.crs_name = "none in file; lon/lat on WGS 84 assumed";
  }

  double gt[6];
  if (ds->GetGeoTransform(gt) != CE_None) {
    throw InputError(fmt::format("{}: no georeferencing (geotransform) found{}", o.path, gdal_message()));
  }
  if (gt[2] != 0.0 || gt[4] != 0.0) throw InputError(fmt::format("{}: rotated rasters are not supported", o.path));
  const double rx = gt[1];
  const double ry = std::abs(gt[5]);
  if (!(rx > 0.0) || !(ry > 0.0)) throw InputError(fmt::format("{}: invalid pixel size {} × {}", o.path, gt[1], gt[5]));
  info.north_up = gt[5] < 0.0;
  const auto w = info.width, h = info.height;
  if (std::abs(static_cast<double>(w) * rx - 360.0) <= 0.25 * rx) {
    info.global_lon = true;
    info.dlon = 360.0 / static_cast<double>(w);
    info.ncols = w;
  } else if (w > 1 && std::abs(static_cast<double>(w - 1) * rx - 360.0) <= 0.25 * rx) {
    info.global_lon = true;
    info.duplicate_column = true;
    info.dlon = 360.0 / static_cast<double>(w - 1);
    info.ncols = w - 1;
  } else {
    info.dlon = rx;
    info.ncols = w;
  }
  if (std::abs(static_cast<double>(h) * ry - 180.0) <= 0.25 * ry) {
    im->global_lat = true;
    info.dlat = 180.0 / static_cast<double>(h);
  } else if (h > 1 && std::abs(static_cast<double>(h - 1) * ry - 180.0) <= 0.25 * ry) {
    im->global_lat = true;
    info.dlat = 180.0 / static_cast<double>(h - 1);
  } else {
    info.dlat = ry;
  }
  info.nrows = h;
  info.lon_first_found = snap(gt[0] + 0.5 * rx, info.dlon / 2.0);
  info.lon_first = info.lon_first_found;
  if (info.global_lon) {
    info.lon_first = std::fmod(info.lon_first + 180.0, 360.0);
    if (info.lon_first < 0) info.lon_first += 360.0;
    info.lon_first -= 180.0;
    info.lon_first = snap(info.lon_first, info.dlon / 2.0);
  }
  const double top_or_bottom = snap(gt[3] + 0.5 * gt[5], info.dlat / 2.0);  // centre of stored row 0
  info.lat_first =
      info.north_up ? snap(top_or_bottom - static_cast<double>(h - 1) * info.dlat, info.dlat / 2.0) : top_or_bottom;
  const double q = info.lon_first_found / info.dlon;
  const double qy = info.lat_first / info.dlat;
  info.registration = (std::abs(q - std::round(q)) < 1e-6 && std::abs(qy - std::round(qy)) < 1e-6) ? "grid" : "pixel";
  if (info.lat_first < -90.0 - 1e-6 || info.lat_first + static_cast<double>(h - 1) * info.dlat > 90.0 + 1e-6) {
    throw InputError(fmt::format("{}: latitudes {}..{} outside [-90, 90]: not a lon/lat raster?", o.path,
                                 info.lat_first, info.lat_first + static_cast<double>(h - 1) * info.dlat));
  }

  // Memory estimate before reading.
  const std::int64_t need =
      estimate_raster_bytes(info.ncols, info.nrows) * (o.interpolation == Interpolation::kBicubic ? 4 : 1);
  const std::int64_t limit = o.max_memory_bytes > 0
                                 ? o.max_memory_bytes
                                 : static_cast<std::int64_t>(0.8 * static_cast<double>(physical_memory_bytes()));
  if (limit > 0 && need > limit) {
    throw InputError(
        fmt::format("{}: holding the raster needs {:.1f} GB, more than the limit {:.1f} GB "
                    "(input.max_memory_gb); use a coarser raster or a region",
                    o.path, static_cast<double>(need) / 1e9, static_cast<double>(limit) / 1e9));
  }

  int has_nd = 0;
  const double nd = band->GetNoDataValue(&has_nd);
  info.has_nodata = has_nd != 0;
  info.nodata = nd;
  int has_scale = 0, has_offset = 0;
  info.scale = band->GetScale(&has_scale);
  info.offset = band->GetOffset(&has_offset);
  if (has_scale == 0) info.scale = 1.0;
  if (has_offset == 0) info.offset = 0.0;

  // Read in bands of rows through GDAL windows straight into the normalised array.
  im->v.resize(static_cast<std::size_t>(info.ncols * info.nrows));
  const float ndf = static_cast<float>(nd);
  const std::int64_t chunk = std::max<std::int64_t>(1, (64LL << 20) / std::max<std::int64_t>(1, w * 4));
  std::vector<float> buf(static_cast<std::size_t>(std::min(chunk, h) * w));
  auto progress = log.progress("read");
  const double sgn = o.positive_down ? -1.0 : 1.0;
  for (std::int64_t y0 = 0; y0 < h; y0 += chunk) {
    const std::int64_t ny = std::min(chunk, h - y0);
    if (band->RasterIO(GF_Read, 0, static_cast<int>(y0), static_cast<int>(w), static_cast<int>(ny), buf.data(),
                       static_cast<int>(w), static_cast<int>(ny), GDT_Float32, 0, 0, nullptr) != CE_None) {
      throw InputError(fmt::format("{}: read error at rows {}..{}{}", o.path, y0, y0 + ny - 1, gdal_message()));
    }
    for (std::int64_t yy = 0; yy < ny; ++yy) {
      const std::int64_t y = y0 + yy;
      const std::int64_t r = info.north_up ? h - 1 - y : y;
      const float* src = buf.data() + yy * w;
      float* dst = im->v.data() + r * info.ncols;
      for (std::int64_t c = 0; c < info.ncols; ++c) {
        const float raw = src[c];
        const bool missing = std::isnan(raw) || (info.has_nodata && raw == ndf) || std::abs(raw) > 1e30f;
        dst[c] = missing ? std::numeric_limits<float>::quiet_NaN()
                         : static_cast<float>(sgn * (raw * info.scale + info.offset));
      }
    }
    if (progress) progress(static_cast<double>(y0 + ny) / static_cast<double>(h), "rows");
  }
  im->compute_stats();
  if (im->info.valid_count == 0) {
    throw InputError(
        fmt::format("{}: band {} ({}) holds no data: every value is no-data", o.path, o.band, info.variable));
  }
  if (o.interpolation == Interpolation::kBicubic) {
    im->build_spline();
    im->compute_stats();
  }
  if (!info.global_lon) {
    log.warn("{}: the raster covers longitudes {:.4f}..{:.4f} only; the rest of the lattice is dry", o.path,
             info.lon_first, info.lon_first + static_cast<double>(info.ncols - 1) * info.dlon);
  }
  return Bathymetry(std::move(im));
}

}  // namespace aq::raster
