// SPDX-License-Identifier: GPL-3.0-or-later
// Bathymetry: GDAL raster input, normalisation (longitude origin, registration, duplicated
// column, orientation, no-data, scale/offset, positive-down) and sampling (ARCHITECTURE §4.1).
// Bilinear sampling on the smallest cell of raster points containing the point is the seed's
// rule (seed 002); the bicubic option is the C2 spline of reference splines.md §4 (periodic in
// longitude on a global raster, natural ends in latitude).
#include "raster/bathymetry.hpp"

#include <cpl_virtualmem.h>
#include <cpl_vsi.h>
#include <fmt/format.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <future>
#include <limits>
#include <list>
#include <mutex>
#include <optional>
#include <unordered_map>

#ifdef _OPENMP
#include <omp.h>
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/cancel.hpp"
#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/row_progress.hpp"
#include "core/timer.hpp"
#include "raster/gdal_common.hpp"
#include "raster/netcdf_coordinates.hpp"
#include "raster/source_stack.hpp"
#include "raster/spline1d.hpp"

namespace aq::raster {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The smallest pixel (degrees) a lon/lat raster may have: 1e-9° is 0.1 mm on the Earth.
constexpr double kMinPixelDeg = 1e-9;

// Snaps x to the nearest multiple of q when within 1e-3·q (float32 coordinate noise).
double snap(double x, double q) {
  const double k = std::round(x / q);
  return std::abs(x / q - k) < 1e-3 ? k * q : x;
}

DatasetPtr open_dataset(const OpenOptions& o, std::string& used_name) {
  // GDAL's virtual file systems (/vsimem/: raster/memory_raster.hpp; /vsizip/, /vsicurl/, ...)
  // are not on the disk: GDAL itself says whether the name exists.
  const bool virtual_file = o.path.rfind("/vsi", 0) == 0;
  if (virtual_file) {
    VSIStatBufL stat;
    if (VSIStatL(o.path.c_str(), &stat) != 0) throw InputError(fmt::format("{}: no such file", o.path));
  } else if (const std::string bad = input_file_problem(o.path); !bad.empty()) {
    // A FIFO would block GDAL forever, a device never ends, a directory is not a raster.
    throw InputError(fmt::format("{}: {}", o.path, bad));
  }
  DatasetPtr ds(static_cast<GDALDataset*>(
      GDALOpenEx(o.path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds) {
    if (virtual_file) throw InputError(fmt::format("{}: not a raster GDAL can read{}", o.path, gdal_message()));
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

// Bilinear value on the cell (a = (c0, r0), b = (c1, r0), c = (c0, r1), d = (c1, r1)) at weights
// t (of c1) and u (of r1): the one formula of every path (whole, row, banded, streamed).
inline double bilinear4(double a, double b, double c, double d, double t, double u) {
  // Exact grid values where the weights vanish (no 0·NaN, no rounding).
  if (t == 0.0 && u == 0.0) return a;
  const double lo = (t == 0.0) ? a : (1.0 - t) * a + t * b;
  if (u == 0.0) return lo;
  const double hi = (t == 0.0) ? c : (1.0 - t) * c + t * d;
  return (1.0 - u) * lo + u * hi;
}

}  // namespace

// The types Bathymetry::Impl holds live in a named namespace of this file: in the unity build
// this file is included by another, and a member of an anonymous namespace's type warns there
// (-Wsubobject-linkage).
namespace bathymetry_detail {

// Statistics of one normalised row; combined in row order, so the whole and streamed paths
// give the same min/max/mean bit for bit.
struct RowStats {
  double mn = std::numeric_limits<double>::infinity(), mx = -std::numeric_limits<double>::infinity(), sum = 0.0;
  std::int64_t count = 0;
  std::int64_t implausible = 0;  // values beyond ±max_abs_elevation_m, made no-data
};

}  // namespace bathymetry_detail

namespace {

using bathymetry_detail::RowStats;

RowStats row_stats(const float* row, std::int64_t n) {
  RowStats s;
  for (std::int64_t c = 0; c < n; ++c) {
    const float x = row[c];
    if (std::isnan(x)) continue;
    s.mn = std::min(s.mn, static_cast<double>(x));
    s.mx = std::max(s.mx, static_cast<double>(x));
    s.sum += x;
    ++s.count;
  }
  return s;
}

// A streamed pass reads the file in bands of stored rows [s·B, (s+1)·B), in storage order, each
// with the stored row just before it (the row the previous band ended with: copied when that band
// was read, read again otherwise). In normalised (south-up) rows the buffer of band s holds
// [lo, hi); a sample between rows r0 <= r1 = r0 + 1 belongs to the band whose own stored rows
// hold its key row (r0 for a north-up file, r1 for a south-up one), so both rows are in its buffer.
struct BandGeometry {
  std::int64_t h = 0, rows = 1;  // stored rows, rows per band
  bool north_up = true;
  [[nodiscard]] std::int64_t count() const { return (h + rows - 1) / rows; }
  [[nodiscard]] std::int64_t first(std::int64_t s) const { return std::max<std::int64_t>(0, s * rows - 1); }
  [[nodiscard]] std::int64_t end(std::int64_t s) const { return std::min(h, (s + 1) * rows); }
  [[nodiscard]] std::int64_t lo(std::int64_t s) const { return north_up ? h - end(s) : first(s); }
  [[nodiscard]] std::int64_t hi(std::int64_t s) const { return north_up ? h - first(s) : end(s); }
  [[nodiscard]] std::int64_t band_of(std::int64_t r0, std::int64_t r1) const {
    const std::int64_t y = north_up ? h - 1 - r0 : r1;
    return y / rows;
  }
};

// out[k] = the bilinear value between rows p0 (r0) and p1 (r1) at weight u, columns of `cols`.
void fill_row(const float* p0, const float* p1, const Bathymetry::Columns& cols, double u, float* out) {
  const auto n = static_cast<std::int64_t>(cols.c0.size());
  for (std::int64_t k = 0; k < n; ++k) {
    const auto s = static_cast<std::size_t>(k);
    const std::int64_t c0 = cols.c0[s], c1 = cols.c1[s];
    out[k] = c0 < 0 ? std::numeric_limits<float>::quiet_NaN()
                    : static_cast<float>(bilinear4(p0[c0], p0[c1], p1[c0], p1[c1], cols.t[s], u));
  }
}

// fill_row for a run of lattice rows on one thread, with the horizontal step of bilinear4 (the
// value along a raster row at each column's weight t) made once per raster row: consecutive
// lattice rows share a raster row (r1 of one is r0 of the next when the lattice is as fine as
// the raster), so each is computed once instead of twice. Columns come in runs: inside the
// raster (c0 >= 0, the vertical step), and among those the ones where c0 steps by one raster
// column with c1 = c0 + 1 and t != 0 (the horizontal step; on a lattice as fine as the raster
// every column but the seam's), both computed two columns at a time (SSE2: the same IEEE
// operations per lane); the others column by column. The same products and sums in the same
// order as bilinear4: the same bits.
class RowFiller {
 public:
  explicit RowFiller(const Bathymetry::Columns& cols) : cols_(cols), n_(static_cast<std::int64_t>(cols.c0.size())) {
    for (auto& s : slot_) s.h.resize(static_cast<std::size_t>(n_));
    const std::int64_t *c0 = cols.c0.data(), *c1 = cols.c1.data();
    const double* t = cols.t.data();
    split([&](std::int64_t k) { return c0[k] >= 0; }, [](std::int64_t) { return true; }, inside_);
    split([&](std::int64_t k) { return c0[k] >= 0 && c1[k] == c0[k] + 1 && t[k] != 0.0; },
          [&](std::int64_t k) { return c0[k] == c0[k - 1] + 1; }, steps_);
  }
  // fill_row(p0, p1, cols, u, out), p0 and p1 being normalised raster rows r0 and r1.
  void fill(const float* p0, std::int64_t r0, const float* p1, std::int64_t r1, double u, float* out) {
    const double* lo = horizontal(p0, r0, -1);
    const double* hi = u == 0.0 ? lo : horizontal(p1, r1, r0);
    const double a = 1.0 - u;
    for (const Run& run : inside_) {
      std::int64_t k = run.begin;
      if (!run.fast) {
        const std::int64_t* c0 = cols_.c0.data();
        for (; k < run.end; ++k) {
          const double v = u == 0.0 ? lo[k] : a * lo[k] + u * hi[k];
          out[k] = c0[k] < 0 ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(v);
        }
        continue;
      }
#if defined(__SSE2__)
      if (u == 0.0) {
        for (; k + 2 <= run.end; k += 2)
          _mm_storel_epi64(reinterpret_cast<__m128i*>(out + k), _mm_castps_si128(_mm_cvtpd_ps(_mm_loadu_pd(lo + k))));
      } else {
        const __m128d a2 = _mm_set1_pd(a), u2 = _mm_set1_pd(u);
        for (; k + 2 <= run.end; k += 2) {
          const __m128d v = _mm_add_pd(_mm_mul_pd(a2, _mm_loadu_pd(lo + k)), _mm_mul_pd(u2, _mm_loadu_pd(hi + k)));
          _mm_storel_epi64(reinterpret_cast<__m128i*>(out + k), _mm_castps_si128(_mm_cvtpd_ps(v)));
        }
      }
#endif
      for (; k < run.end; ++k) out[k] = static_cast<float>(u == 0.0 ? lo[k] : a * lo[k] + u * hi[k]);
    }
  }

 private:
  struct Slot {
    std::int64_t row = -1;
    std::vector<double> h;
  };
  struct Run {
    std::int64_t begin, end;
    bool fast;  // every column of the run has the property (else none has it or the run is short)
  };
  // Runs of columns with `has` (continuing while `joins` holds for the column after the first)
  // of at least kMinRun columns, and the runs between them.
  template <typename Has, typename Joins>
  void split(const Has& has, const Joins& joins, std::vector<Run>& runs) const {
    constexpr std::int64_t kMinRun = 16;
    std::int64_t k = 0;
    while (k < n_) {
      std::int64_t e = k;
      if (has(k)) {
        e = k + 1;
        while (e < n_ && has(e) && joins(e)) ++e;
      }
      const bool fast = e - k >= kMinRun;
      const std::int64_t stop = std::max(e, k + 1);
      if (!fast && !runs.empty() && !runs.back().fast && runs.back().end == k)
        runs.back().end = stop;
      else
        runs.push_back({k, stop, fast});
      k = stop;
    }
  }
  // The horizontal values of raster row r (kept in one of two slots; the one holding row `keep`
  // is not overwritten).
  const double* horizontal(const float* p, std::int64_t r, std::int64_t keep) {
    for (const Slot& s : slot_)
      if (s.row == r) return s.h.data();
    Slot& s = slot_[0].row == keep ? slot_[1] : slot_[0];
    s.row = r;
    const std::int64_t *c0 = cols_.c0.data(), *c1 = cols_.c1.data();
    const double* t = cols_.t.data();
    double* h = s.h.data();
    for (const Run& run : steps_) {
      std::int64_t k = run.begin;
      if (run.fast) {
        const float* q = p + (c0[k] - k);  // q[k] = p[c0[k]], q[k + 1] = p[c1[k]]
#if defined(__SSE2__)
        const __m128d one = _mm_set1_pd(1.0);
        for (; k + 2 <= run.end; k += 2) {
          const __m128d tk = _mm_loadu_pd(t + k);
          const __m128d x = _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(q + k))));
          const __m128d y =
              _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(q + k + 1))));
          _mm_storeu_pd(h + k, _mm_add_pd(_mm_mul_pd(_mm_sub_pd(one, tk), x), _mm_mul_pd(tk, y)));
        }
#endif
        for (; k < run.end; ++k) h[k] = (1.0 - t[k]) * static_cast<double>(q[k]) + t[k] * static_cast<double>(q[k + 1]);
        continue;
      }
      for (; k < run.end; ++k) {
        if (c0[k] < 0) {
          h[k] = 0.0;
          continue;
        }
        const double x = p[c0[k]];
        h[k] = t[k] == 0.0 ? x : (1.0 - t[k]) * x + t[k] * static_cast<double>(p[c1[k]]);
      }
    }
    return s.h.data();
  }

  const Bathymetry::Columns& cols_;
  std::int64_t n_;
  Slot slot_[2];
  std::vector<Run> inside_, steps_;
};

}  // namespace

namespace bathymetry_detail {

// A streamed raster's file mapped into memory: GDAL's file mapping of an uncompressed band in the
// machine's byte order (GDALRasterBand::GetVirtualMemAuto, without its copying fallback). The
// threads read the stored rows where they lie: no read buffer, no copy out of the page cache, no
// lock around GDAL. Rows a pass is done with are given back (release), so the file's pages never
// add up in the process's resident memory. Values convert to Float32 as GDAL's RasterIO converts
// them (Byte, Int16, UInt16: exactly; Float32: as stored); other types are not mapped.
class FileMap {
 public:
  // nullptr when GDAL has no file mapping of the band, or for another data type.
  static std::unique_ptr<FileMap> open(GDALRasterBand* band, std::int64_t width) {
    const GDALDataType type = band->GetRasterDataType();
    if (type != GDT_Byte && type != GDT_Int16 && type != GDT_UInt16 && type != GDT_Float32) return nullptr;
    int pixel = 0;
    GIntBig line = 0;
    char no_fallback[] = "USE_DEFAULT_IMPLEMENTATION=NO";
    char* options[] = {no_fallback, nullptr};
    CPLVirtualMem* vm = band->GetVirtualMemAuto(GF_Read, &pixel, &line, options);
    CPLErrorReset();  // "not available" is no error of the run
    if (vm == nullptr) return nullptr;
    auto m = std::unique_ptr<FileMap>(new FileMap(vm, type, pixel, line));
    const std::int64_t size = GDALGetDataTypeSizeBytes(type);
    if (CPLVirtualMemIsFileMapping(vm) == 0 || pixel < size || line < pixel * width) return nullptr;
    return m;
  }
  ~FileMap() { CPLVirtualMemFree(vm_); }
  FileMap(const FileMap&) = delete;
  FileMap& operator=(const FileMap&) = delete;

  // Stored row y, column x, as RasterIO gives it in Float32.
  [[nodiscard]] float value(std::int64_t x, std::int64_t y) const {
    const unsigned char* p = base_ + y * line_ + x * pixel_;
    switch (type_) {
      case GDT_Byte:
        return static_cast<float>(*p);
      case GDT_Int16: {
        std::int16_t v = 0;
        std::memcpy(&v, p, sizeof v);
        return static_cast<float>(v);
      }
      case GDT_UInt16: {
        std::uint16_t v = 0;
        std::memcpy(&v, p, sizeof v);
        return static_cast<float>(v);
      }
      default: {
        float v = 0.0f;
        std::memcpy(&v, p, sizeof v);
        return v;
      }
    }
  }
  // Columns [0, n) of stored row y into out, as RasterIO gives them in Float32.
  void row(std::int64_t y, std::int64_t n, float* out) const {
    const unsigned char* p = base_ + y * line_;
    switch (type_) {
      case GDT_Byte:
        return convert<std::uint8_t>(p, n, out);
      case GDT_Int16:
        return convert<std::int16_t>(p, n, out);
      case GDT_UInt16:
        return convert<std::uint16_t>(p, n, out);
      default:
        return convert<float>(p, n, out);
    }
  }
  // Stored row y as int16 values side by side (an Int16 band without interleaving), else nullptr.
  [[nodiscard]] const std::int16_t* int16_row(std::int64_t y) const {
    return type_ == GDT_Int16 && pixel_ == 2 ? reinterpret_cast<const std::int16_t*>(base_ + y * line_) : nullptr;
  }
  // Gives back the pages that lie wholly inside stored rows [y0, y1) (they are read again from
  // the page cache if a later pass needs them).
  void release(std::int64_t y0, std::int64_t y1) const { advise(y0, y1, MADV_DONTNEED, false); }
  // Asks the kernel to read stored rows [y0, y1) from the disk now, in the background (the
  // reader thread's overlap of the GDAL path: a fault on a page not yet in the page cache would
  // stop the thread that meets it).
  void prefetch(std::int64_t y0, std::int64_t y1) const { advise(y0, y1, MADV_WILLNEED, true); }

 private:
  FileMap(CPLVirtualMem* vm, GDALDataType type, std::int64_t pixel, std::int64_t line)
      : vm_(vm),
        base_(static_cast<const unsigned char*>(CPLVirtualMemGetAddr(vm))),
        pixel_(pixel),
        line_(line),
        type_(type) {}
  // madvise over the whole pages inside stored rows [y0, y1), or over every page they touch.
  void advise(std::int64_t y0, std::int64_t y1, int advice, bool touched) const {
    static const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
    auto a = reinterpret_cast<std::uintptr_t>(base_ + y0 * line_);
    auto b = reinterpret_cast<std::uintptr_t>(base_ + y1 * line_);
    a = touched ? a / page * page : (a + page - 1) / page * page;
    b = touched ? (b + page - 1) / page * page : b / page * page;
    if (b > a) (void)madvise(reinterpret_cast<void*>(a), b - a, advice);
  }
  template <typename T>
  void convert(const unsigned char* p, std::int64_t n, float* out) const {
    if (pixel_ == static_cast<std::int64_t>(sizeof(T))) {
      for (std::int64_t c = 0; c < n; ++c) {
        T v;
        std::memcpy(&v, p + c * static_cast<std::int64_t>(sizeof(T)), sizeof v);
        out[c] = static_cast<float>(v);
      }
      return;
    }
    for (std::int64_t c = 0; c < n; ++c) {
      T v;
      std::memcpy(&v, p + c * pixel_, sizeof v);
      out[c] = static_cast<float>(v);
    }
  }

  CPLVirtualMem* vm_;
  const unsigned char* base_;  // column 0 of stored row 0
  std::int64_t pixel_, line_;  // bytes from a column to the next, and from a stored row to the next
  GDALDataType type_;
};

}  // namespace bathymetry_detail

namespace {

using bathymetry_detail::FileMap;

// The float32 bytes of a band of a pass through the file map, at most (Impl::pass_rows): with
// the thread's sampling rows, well inside a processor's last-level cache.
constexpr std::int64_t kMappedBandBytes = std::int64_t{8} << 20;

}  // namespace

struct Bathymetry::Impl {
  mutable RasterInfo info;         // a streamed raster's statistics and pass count are filled while sampling
  std::vector<float> v;            // ncols × (row_hi - row_lo), south-up (empty when streamed)
  std::vector<float> fx, fy, fxy;  // bicubic: slopes per degree, only when bicubic
  Interpolation interp = Interpolation::kBilinear;
  bool global_lat = false;
  std::int64_t row_lo = 0, row_hi = 0;  // normalised rows held in v (a latitude window)
  // Normalised columns held in v: col_lo .. col_lo + held_nc - 1 (wrapping on a global raster);
  // a longitude window when held_nc < ncols, else col_lo = 0 and held_nc = ncols.
  std::int64_t col_lo = 0, held_nc = 0;

  [[nodiscard]] bool col_window() const { return held_nc < info.ncols; }
  // The held column of normalised column c (0 <= c < ncols), -1 when outside the window.
  [[nodiscard]] std::int64_t local_col(std::int64_t c) const {
    if (!col_window()) return c;
    std::int64_t l = c - col_lo;
    if (l < 0 && info.global_lon) l += info.ncols;
    return l >= 0 && l < held_nc ? l : -1;
  }

  // Reading (whole: during open; streamed: on every pass). GDAL datasets are not thread-safe:
  // one read at a time.
  DatasetPtr ds;
  GDALRasterBand* band = nullptr;
  double sgn = 1.0;
  bool signed_byte = false;                                  // a Byte band marked PIXELTYPE=SIGNEDBYTE
  float max_abs_m = std::numeric_limits<float>::infinity();  // OpenOptions::max_abs_elevation_m
  bool integral_plain = false;  // Byte/Int16/UInt16 values, no scale/offset/sign change (normalise_row)
  int band_number = 1;
  std::unique_ptr<FileMap> map;  // streamed and mapped (RasterInfo::mapped); freed before ds closes
  mutable std::mutex io;
  mutable std::vector<RowStats> stats_rows;  // streamed: per normalised row, filled by the first pass
  mutable bool stats_done = false;

  // Tiled: normalised tiles of kTileCells × kTileCells values by key ty·ntx + tx, least recently
  // used first in `lru`. Reads go through `io` (GDAL datasets are not thread-safe).
  struct Tile {
    std::vector<float> v;
    std::list<std::int64_t>::iterator at;
  };
  mutable std::mutex tiles_io;
  mutable std::unordered_map<std::int64_t, Tile> tiles;
  mutable std::list<std::int64_t> lru;
  std::int64_t max_tiles = 0;

  [[nodiscard]] std::int64_t tiles_x() const { return (info.ncols + kTileCells - 1) / kTileCells; }

  // The values of tile (tx, ty), read when it is not cached (the least recently used one goes);
  // the caller holds tiles_io.
  [[nodiscard]] const std::vector<float>& tile_locked(std::int64_t tx, std::int64_t ty) const {
    const std::int64_t key = ty * tiles_x() + tx;
    auto it = tiles.find(key);
    if (it == tiles.end()) {
      Tile t;
      read_tile(tx, ty, t.v);
      ++info.tiles_read;
      if (static_cast<std::int64_t>(tiles.size()) >= max_tiles && !lru.empty()) {
        tiles.erase(lru.front());
        lru.pop_front();
      }
      lru.push_back(key);
      t.at = std::prev(lru.end());
      it = tiles.emplace(key, std::move(t)).first;
    } else {
      lru.splice(lru.end(), lru, it->second.at);
    }
    return it->second.v;
  }

  // Value (c, r) of a tiled raster (0 <= c < ncols, 0 <= r < nrows).
  [[nodiscard]] float tile_value(std::int64_t c, std::int64_t r) const {
    const std::int64_t tx = c / kTileCells, ty = r / kTileCells;
    const std::lock_guard<std::mutex> lock(tiles_io);
    return tile_locked(tx, ty)[static_cast<std::size_t>((r - ty * kTileCells) * kTileCells + (c - tx * kTileCells))];
  }

  // Values [c, c + n) × [r, r + rows) of one tile into out (row stride `stride`).
  void tile_rows(std::int64_t c, std::int64_t n, std::int64_t r, std::int64_t rows, float* out,
                 std::int64_t stride) const {
    const std::int64_t tx = c / kTileCells, ty = r / kTileCells;
    const std::lock_guard<std::mutex> lock(tiles_io);
    const float* tv = tile_locked(tx, ty).data();
    for (std::int64_t y = 0; y < rows; ++y)
      std::copy_n(tv + (r + y - ty * kTileCells) * kTileCells + (c - tx * kTileCells), n, out + y * stride);
  }

  // Reads tile (tx, ty) normalised (south-up rows; NaN past the raster's last row or column).
  void read_tile(std::int64_t tx, std::int64_t ty, std::vector<float>& out) const {
    const std::int64_t c0 = tx * kTileCells, r0 = ty * kTileCells;
    const std::int64_t nc = std::min(kTileCells, info.ncols - c0), nr = std::min(kTileCells, info.nrows - r0);
    out.assign(static_cast<std::size_t>(kTileCells * kTileCells), std::numeric_limits<float>::quiet_NaN());
    std::vector<float> raw(static_cast<std::size_t>(nc * nr));
    const std::int64_t y0 = info.north_up ? info.height - (r0 + nr) : r0;  // stored rows y0 .. y0 + nr - 1
    {
      const std::lock_guard<std::mutex> lock(io);
      if (band->RasterIO(GF_Read, static_cast<int>(c0), static_cast<int>(y0), static_cast<int>(nc),
                         static_cast<int>(nr), raw.data(), static_cast<int>(nc), static_cast<int>(nr), GDT_Float32, 0,
                         0, nullptr) != CE_None)
        throw InputError(fmt::format("{}: read error at rows {}..{}, columns {}..{}{}", info.path, y0, y0 + nr - 1, c0,
                                     c0 + nc - 1, gdal_message()));
    }
    std::int64_t implausible = 0;
    for (std::int64_t k = 0; k < nr; ++k) {
      const std::int64_t y = y0 + k;                                   // stored row
      const std::int64_t r = info.north_up ? info.height - 1 - y : y;  // normalised row
      for (std::int64_t c = 0; c < nc; ++c)
        out[static_cast<std::size_t>((r - r0) * kTileCells + c)] =
            normalise(raw[static_cast<std::size_t>(k * nc + c)], implausible);
    }
  }

  [[nodiscard]] std::size_t idx(std::int64_t c, std::int64_t r) const {
    return static_cast<std::size_t>((r - row_lo) * held_nc + c);
  }
  [[nodiscard]] const float* row_ptr(std::int64_t r) const { return v.data() + (r - row_lo) * held_nc; }

  // Reads stored rows [y0, y1) and writes them normalised (orientation, duplicated column,
  // no-data, scale/offset, sign) to dst, normalised row r at dst + (r - lo)·ncols. `raw` is scratch
  // (resized). Records per-row statistics in `stats` (indexed by normalised row) when given.
  void read_stored(std::int64_t y0, std::int64_t y1, float* dst, std::int64_t lo, std::vector<float>& raw,
                   RowStats* stats) const {
    if (map) {
      normalise_mapped(y0, y1, dst, lo, stats);
      return;
    }
    read_raw(y0, y1, raw);
    normalise_rows(y0, y1, raw.data(), dst, lo, stats, false);
  }

  // normalise_rows of stored rows [y0, y1) read from the file map, on the OpenMP threads.
  void normalise_mapped(std::int64_t y0, std::int64_t y1, float* dst, std::int64_t lo, RowStats* stats) const {
    const std::int64_t h = info.height, nc = held_nc;
    const bool north_up = info.north_up;
    const FileMap& m = *map;
#pragma omp parallel for schedule(static) default(none) \
    shared(y0, y1, dst, lo, stats, h, nc, north_up, m) if ((y1 - y0) * nc >= (std::int64_t{1} << 16))
    for (std::int64_t y = y0; y < y1; ++y) {
      const std::int64_t r = north_up ? h - 1 - y : y;
      float* out = dst + (r - lo) * nc;
      const std::int16_t* ints = integral_plain ? m.int16_row(y) : nullptr;
      if (ints != nullptr) {
        normalise_int16(ints, nc, out, stats != nullptr ? stats + r : nullptr);
        continue;
      }
      m.row(y, nc, out);
      normalise_row(out, out, nc, stats != nullptr ? stats + r : nullptr);
    }
  }

  // normalise_row of int16 values straight from the file (integral_plain), eight at a time with
  // SSE2: the same values and figures (every step is exact: int16 -> float, the comparisons,
  // min/max, and integer sums kept below 2^31 per lane).
  void normalise_int16(const std::int16_t* src, std::int64_t nc, float* out, RowStats* stat) const {
    const float nd = info.has_nodata ? static_cast<float>(info.nodata) : std::numeric_limits<float>::quiet_NaN();
    const float lim = max_abs_m, nan = std::numeric_limits<float>::quiet_NaN();
    constexpr float kInf = std::numeric_limits<float>::infinity();
    float mn = kInf, mx = -kInf;
    std::int64_t sum = 0, count = 0, implausible = 0, c = 0;
#if defined(__SSE2__)
    {
      const __m128 nd4 = _mm_set1_ps(nd), lim4 = _mm_set1_ps(lim), nan4 = _mm_set1_ps(nan), inf4 = _mm_set1_ps(kInf),
                   ninf4 = _mm_set1_ps(-kInf), abs4 = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff)),
                   ones4 = _mm_castsi128_ps(_mm_set1_epi32(-1));
      __m128 mn4 = inf4, mx4 = ninf4;
      __m128i sum4 = _mm_setzero_si128(), cnt4 = sum4, bad4 = sum4;
      const auto lanes = [](__m128i x) {
        alignas(16) std::int32_t a[4];
        _mm_store_si128(reinterpret_cast<__m128i*>(a), x);
        return static_cast<std::int64_t>(a[0]) + a[1] + a[2] + a[3];
      };
      std::int64_t block = 0;  // iterations since sum4 was emptied: at most 2·32768 per lane each
      for (; c + 8 <= nc; c += 8) {
        const __m128i eight = _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + c));
        const __m128i halves[2] = {_mm_srai_epi32(_mm_unpacklo_epi16(eight, eight), 16),
                                   _mm_srai_epi32(_mm_unpackhi_epi16(eight, eight), 16)};
        for (int k = 0; k < 2; ++k) {
          const __m128i xi = halves[k];
          const __m128 x = _mm_cvtepi32_ps(xi);
          const __m128 missing = _mm_cmpeq_ps(x, nd4);
          const __m128 ok = _mm_cmple_ps(_mm_and_ps(x, abs4), lim4);
          const __m128 valid = _mm_andnot_ps(missing, ok);
          const __m128 bad = _mm_andnot_ps(missing, _mm_xor_ps(ok, ones4));
          _mm_storeu_ps(out + c + 4 * k, _mm_or_ps(_mm_and_ps(valid, x), _mm_andnot_ps(valid, nan4)));
          mn4 = _mm_min_ps(mn4, _mm_or_ps(_mm_and_ps(valid, x), _mm_andnot_ps(valid, inf4)));
          mx4 = _mm_max_ps(mx4, _mm_or_ps(_mm_and_ps(valid, x), _mm_andnot_ps(valid, ninf4)));
          const __m128i vi = _mm_castps_si128(valid);
          sum4 = _mm_add_epi32(sum4, _mm_and_si128(vi, xi));
          cnt4 = _mm_sub_epi32(cnt4, vi);
          bad4 = _mm_sub_epi32(bad4, _mm_castps_si128(bad));
        }
        if (++block == 16384) {
          sum += lanes(sum4);
          sum4 = _mm_setzero_si128();
          block = 0;
        }
      }
      sum += lanes(sum4);
      count += lanes(cnt4);
      implausible += lanes(bad4);
      alignas(16) float a[4], b[4];
      _mm_store_ps(a, mn4);
      _mm_store_ps(b, mx4);
      for (int k = 0; k < 4; ++k) {
        mn = std::min(mn, a[k]);
        mx = std::max(mx, b[k]);
      }
    }
#endif
    for (; c < nc; ++c) {
      const auto x = static_cast<float>(src[c]);
      const bool missing = x == nd;
      const bool bad = !missing && !(std::abs(x) <= lim);
      const bool valid = !missing && !bad;
      out[c] = valid ? x : nan;
      implausible += bad ? 1 : 0;
      if (valid) {
        sum += static_cast<std::int64_t>(x);
        ++count;
        mn = std::min(mn, x);
        mx = std::max(mx, x);
      }
    }
    if (stat != nullptr) {
      stat->mn = count > 0 ? static_cast<double>(mn) : std::numeric_limits<double>::infinity();
      stat->mx = count > 0 ? static_cast<double>(mx) : -std::numeric_limits<double>::infinity();
      stat->sum = static_cast<double>(sum);
      stat->count = count;
      stat->implausible = implausible;
    }
  }

  // normalise() over one row (in place when src == out), and its RowStats when `stat` is given.
  // Integer values with no scale, offset or sign change (integral_plain: int16 GEBCO, ETOPO) keep
  // their value or become no-data, and their sum is an integer below 2^53 at every step, so it
  // is summed as an integer: the same figures as row_stats, in one pass the compiler need not
  // chain through a double addition per value.
  void normalise_row(const float* src, float* out, std::int64_t nc, RowStats* stat) const {
    if (!integral_plain) {
      std::int64_t implausible = 0;
      for (std::int64_t c = 0; c < nc; ++c) out[c] = normalise(src[c], implausible);
      if (stat != nullptr) {
        *stat = row_stats(out, nc);
        stat->implausible = implausible;
      }
      return;
    }
    const float nd = info.has_nodata ? static_cast<float>(info.nodata) : std::numeric_limits<float>::quiet_NaN();
    const float lim = max_abs_m, nan = std::numeric_limits<float>::quiet_NaN();
    constexpr float kInf = std::numeric_limits<float>::infinity();
    // Four independent lanes (min, max and integer sums are exact in any order): no chain of
    // dependent minimum or addition instructions through the row.
    constexpr int kLanes = 4;
    float mns[kLanes] = {kInf, kInf, kInf, kInf}, mxs[kLanes] = {-kInf, -kInf, -kInf, -kInf};
    std::int64_t sums[kLanes] = {0, 0, 0, 0}, counts[kLanes] = {0, 0, 0, 0};
    std::int64_t implausible = 0;
    const auto one = [&](std::int64_t c, int l) {
      const float x = src[c];
      const bool missing = x == nd;
      const bool bad = !missing && !(std::abs(x) <= lim);
      const bool valid = !missing && !bad;
      out[c] = valid ? x : nan;
      implausible += bad ? 1 : 0;
      sums[l] += valid ? static_cast<std::int64_t>(x) : 0;
      counts[l] += valid ? 1 : 0;
      mns[l] = std::min(mns[l], valid ? x : kInf);
      mxs[l] = std::max(mxs[l], valid ? x : -kInf);
    };
    std::int64_t c = 0;
    for (; c + kLanes <= nc; c += kLanes)
      for (int l = 0; l < kLanes; ++l) one(c + l, l);
    for (; c < nc; ++c) one(c, 0);
    float mn = kInf, mx = -kInf;
    std::int64_t sum = 0, count = 0;
    for (int l = 0; l < kLanes; ++l) {
      mn = std::min(mn, mns[l]);
      mx = std::max(mx, mxs[l]);
      sum += sums[l];
      count += counts[l];
    }
    if (stat != nullptr) {
      stat->mn = count > 0 ? static_cast<double>(mn) : std::numeric_limits<double>::infinity();
      stat->mx = count > 0 ? static_cast<double>(mx) : -std::numeric_limits<double>::infinity();
      stat->sum = static_cast<double>(sum);
      stat->count = count;
      stat->implausible = implausible;
    }
  }

  // Stored rows [y0, y1) as GDAL gives them (Float32) into `raw` (resized). One read at a time.
  void read_raw(std::int64_t y0, std::int64_t y1, std::vector<float>& raw) const {
    const std::int64_t w = info.width, ny = y1 - y0;
    const std::lock_guard<std::mutex> lock(io);
    if (col_window()) {  // the window's columns only: one piece, or two across the seam
      raw.resize(static_cast<std::size_t>(ny * held_nc));
      const std::int64_t n1 = std::min(held_nc, info.ncols - col_lo);
      const auto line = static_cast<GSpacing>(held_nc * sizeof(float));
      for (int piece = 0; piece < 2; ++piece) {
        const std::int64_t x0 = piece == 0 ? col_lo : 0, n = piece == 0 ? n1 : held_nc - n1;
        if (n <= 0) continue;
        float* dst = raw.data() + (piece == 0 ? 0 : n1);
        if (band->RasterIO(GF_Read, static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(n),
                           static_cast<int>(ny), dst, static_cast<int>(n), static_cast<int>(ny), GDT_Float32,
                           sizeof(float), line, nullptr) != CE_None) {
          throw InputError(fmt::format("{}: read error at rows {}..{}, columns {}..{}{}", info.path, y0, y1 - 1, x0,
                                       x0 + n - 1, gdal_message()));
        }
      }
      return;
    }
    raw.resize(static_cast<std::size_t>(ny * w));
    if (band->RasterIO(GF_Read, 0, static_cast<int>(y0), static_cast<int>(w), static_cast<int>(ny), raw.data(),
                       static_cast<int>(w), static_cast<int>(ny), GDT_Float32, 0, 0, nullptr) != CE_None) {
      throw InputError(fmt::format("{}: read error at rows {}..{}{}", info.path, y0, y1 - 1, gdal_message()));
    }
  }

  // The stored rows [y0, y1) in `raw` normalised into dst (see read_stored); rows are shared
  // among the OpenMP threads when `parallel` (each row is written and summarised on its own).
  void normalise_rows(std::int64_t y0, std::int64_t y1, const float* raw, float* dst, std::int64_t lo, RowStats* stats,
                      [[maybe_unused]] bool parallel) const {
    const std::int64_t w = col_window() ? held_nc : info.width, h = info.height, ny = y1 - y0, nc = held_nc;
    const bool north_up = info.north_up;
#pragma omp parallel for schedule(static) default(none) \
    shared(y0, raw, dst, lo, stats, w, h, ny, nc, north_up) if (parallel && ny * nc >= (std::int64_t{1} << 20))
    for (std::int64_t yy = 0; yy < ny; ++yy) {
      const std::int64_t y = y0 + yy;
      const std::int64_t r = north_up ? h - 1 - y : y;
      normalise_row(raw + yy * w, dst + (r - lo) * nc, nc, stats != nullptr ? stats + r : nullptr);
    }
  }

  // Normalised rows [r_lo, r_lo + nr) into dst (streamed reads, any order of the file).
  void read_rows(std::int64_t r_lo, std::int64_t nr, float* dst) const {
    std::vector<float> raw;
    const std::int64_t h = info.height;
    const std::int64_t y0 = info.north_up ? h - (r_lo + nr) : r_lo;
    read_stored(y0, y0 + nr, dst, r_lo, raw, nullptr);
  }

  // Stored rows per band of a pass. Through the file map, a band is at most about 8 MB of float32
  // (kMappedBandBytes): its buffer is normalised and then sampled while it is still in the
  // processor's cache (a 64 MB band went out to memory and was read back); the disk is still
  // asked for info.band_rows ahead (stream). Through GDAL reads, info.band_rows.
  [[nodiscard]] std::int64_t pass_rows() const {
    if (!map) return info.band_rows;
    const std::int64_t cached = std::max<std::int64_t>(1, kMappedBandBytes / std::max<std::int64_t>(1, info.ncols * 4));
    return std::min(info.band_rows, cached);
  }
  [[nodiscard]] BandGeometry bands() const { return BandGeometry{info.height, pass_rows(), info.north_up}; }
  /// The bands the disk is read in (info.band_rows rows), whatever a pass works in.
  [[nodiscard]] BandGeometry disk_bands() const { return BandGeometry{info.height, info.band_rows, info.north_up}; }

  // One streamed pass: for every band s with wanted(s) (all bands when `stats` is given), its
  // buffer (normalised rows [lo(s), hi(s))) and then work(s, buffer). Records row statistics when
  // `stats` is given. Through GDAL, a second thread reads the next band's stored rows while the
  // OpenMP threads normalise this one's and work on it:
  //
  //   reader:  read band k+1 ──────────┐ read band k+2 ...
  //   team:    normalise k │ work(k)   └> normalise k+1 │ work(k+1) ...
  //
  // Through the file map, the team normalises each band straight from the map (the band's first
  // row, the last of the band before when that one was just worked on, is moved over instead),
  // the disk is asked for the stored rows info.band_rows ahead, and the band's rows are released
  // after its work.
  template <typename Wanted, typename Work>
  void stream(const Wanted& wanted, const Work& work, RowStats* stats, const ProgressFn& progress,
              std::string_view label) const {
    const BandGeometry g = bands();
    const std::int64_t nb = g.count(), nc = info.ncols;
    std::vector<std::int64_t> todo;
    for (std::int64_t s = 0; s < nb; ++s)
      if (stats != nullptr || wanted(s)) todo.push_back(s);
    ++info.passes;
    if (todo.empty()) return;
    std::vector<float> buf(static_cast<std::size_t>((g.rows + 1) * nc));
    const auto done = [&](std::size_t k) {
      if (progress) progress(static_cast<double>(k + 1) / static_cast<double>(todo.size()), label);
    };
    // Band todo[k]'s first stored row is the last of the band before when that band was worked on
    // just before: then it is moved over in `buf` (and returns the next row to read), not read again.
    const auto carried = [&](std::size_t k) { return k > 0 && todo[k] > 0 && todo[k - 1] == todo[k] - 1; };
    const auto carry_over = [&](std::size_t k) {
      const std::int64_t s = todo[k], y0 = g.first(s);
      const std::int64_t r = g.north_up ? g.h - 1 - y0 : y0;  // stored row y0 = s·B - 1
      std::memmove(buf.data() + (r - g.lo(s)) * nc, buf.data() + (r - g.lo(s - 1)) * nc,
                   static_cast<std::size_t>(nc) * sizeof(float));
      return y0 + 1;
    };
    if (map) {
      std::int64_t asked = 0;  // stored rows below this one were asked for (each row once)
      for (std::size_t k = 0; k < todo.size(); ++k) {
        throw_if_cancelled();  // between bands (core/cancel.hpp)
        const std::int64_t s = todo[k], lo = g.lo(s);
        std::int64_t y0 = g.first(s);
        const std::int64_t ahead = std::min(g.h, y0 + info.band_rows + 1);
        if (ahead > std::max(asked, y0)) map->prefetch(std::max(asked, y0), ahead);
        asked = std::max(asked, ahead);
        if (carried(k)) y0 = carry_over(k);
        normalise_mapped(y0, g.end(s), buf.data(), lo, stats);
        if (wanted(s)) work(s, static_cast<const float*>(buf.data()));
        map->release(g.first(s), g.end(s));
        done(k);
      }
      return;
    }
    // Band todo[k]'s stored rows go to raw[k % 2], all but its first when it is carried over.
    std::vector<float> raw[2];
    const auto read = [&](std::size_t k) {
      const std::int64_t s = todo[k];
      read_raw(g.first(s) + (carried(k) ? 1 : 0), g.end(s), raw[k % 2]);
    };
    std::future<void> next = std::async(std::launch::async, read, std::size_t{0});
    for (std::size_t k = 0; k < todo.size(); ++k) {
      next.get();
      if (k + 1 < todo.size()) next = std::async(std::launch::async, read, k + 1);
      try {
        throw_if_cancelled();  // between bands (core/cancel.hpp)
        const std::int64_t s = todo[k], lo = g.lo(s);
        const std::int64_t y0 = carried(k) ? carry_over(k) : g.first(s);
        normalise_rows(y0, g.end(s), raw[k % 2].data(), buf.data(), lo, stats, true);
        if (wanted(s)) work(s, static_cast<const float*>(buf.data()));
      } catch (...) {
        if (next.valid()) next.wait();
        throw;
      }
      done(k);
    }
  }

  // Column position: c0, t (c1 = next column, wrapped). Returns false outside coverage.
  bool col(double lon, std::int64_t& c0, std::int64_t& c1, double& t) const {
    const auto n = info.ncols;
    double x = (lon - info.lon_first) / info.dlon;
    if (info.global_lon) {
      // fmod(x, n), which is x - n exactly for n <= x < 2n and x for |x| < n (the usual cases:
      // a call of fmod costs as much as the rest of the sample).
      const auto nd = static_cast<double>(n);
      if (x >= nd && x < 2.0 * nd) {
        x -= nd;
      } else if (!(x > -nd && x < nd)) {
        x = std::fmod(x, nd);
      }
      if (x < 0.0) x += nd;
    } else if (x < -0.5 || x > static_cast<double>(n) - 0.5) {
      // Any longitude origin, also for a regional raster: the same meridian a whole turn away
      // (a raster over 280..350°E answers at -40°E). Points inside keep the formula above.
      const double turn = 360.0 / info.dlon;
      x -= turn * std::floor((x + 0.5) / turn);
    }
    const double xr = std::round(x);
    if (std::abs(x - xr) < 1e-9) x = xr;  // a point on a grid line takes the grid value exactly
    if (info.global_lon) {
      if (x >= static_cast<double>(n)) x -= static_cast<double>(n);
      c0 = static_cast<std::int64_t>(std::floor(x));
      t = x - static_cast<double>(c0);
      c1 = (c0 + 1 == n) ? 0 : c0 + 1;
      return to_held(c0, c1);
    }
    if (x < -0.5 || x > static_cast<double>(n) - 0.5) return false;
    x = std::clamp(x, 0.0, static_cast<double>(n - 1));
    c0 = std::min<std::int64_t>(static_cast<std::int64_t>(std::floor(x)), n - 1);
    t = x - static_cast<double>(c0);
    c1 = std::min<std::int64_t>(c0 + 1, n - 1);
    return to_held(c0, c1);
  }
  // Normalised columns -> held columns (a longitude window); false when either is outside it.
  bool to_held(std::int64_t& c0, std::int64_t& c1) const {
    if (!col_window()) return true;
    c0 = local_col(c0);
    c1 = local_col(c1);
    return c0 >= 0 && c1 >= 0;
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
    return info.streamed || info.tiled || (r0 >= row_lo && r1 < row_hi);  // a latitude window: NaN outside
  }

  [[nodiscard]] double bilinear(std::int64_t c0, std::int64_t c1, double t, std::int64_t r0, std::int64_t r1,
                                double u) const {
    const float* p0 = row_ptr(r0);
    const float* p1 = row_ptr(r1);
    return bilinear4(p0[c0], p0[c1], p1[c0], p1[c1], t, u);
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
    if (info.streamed)
      return bilinear4(read_value(c0, r0), read_value(c1, r0), read_value(c0, r1), read_value(c1, r1), t, u);
    if (info.tiled)
      return bilinear4(tile_value(c0, r0), tile_value(c1, r0), tile_value(c0, r1), tile_value(c1, r1), t, u);
    if (interp == Interpolation::kBicubic && !fx.empty()) return bicubic(c0, c1, t, r0, r1, u);
    return bilinear(c0, c1, t, r0, r1, u);
  }

  // One value of a streamed raster (normalised column c, row r, both in range).
  [[nodiscard]] float read_value(std::int64_t c, std::int64_t r) const {
    float x = 0.0f;
    const std::int64_t y = info.north_up ? info.height - 1 - r : r;
    std::int64_t implausible = 0;
    if (map) return normalise(map->value(c, y), implausible);
    const std::lock_guard<std::mutex> lock(io);
    if (band->RasterIO(GF_Read, static_cast<int>(c), static_cast<int>(y), 1, 1, &x, 1, 1, GDT_Float32, 0, 0, nullptr) !=
        CE_None) {
      throw InputError(fmt::format("{}: read error at row {}{}", info.path, y, gdal_message()));
    }
    return normalise(x, implausible);
  }

  // The values out[order[q]] of the points order[q0..q1) of one band (raw_points): bilinear(c0,
  // c1, r0, r1, t, u) interpolates between the normalised values at columns c0, c1 and rows r0,
  // r1 (south-up) at (t, u), through the file map or from the band's rows read into memory.
  template <class Bilinear>
  static void band_points(const Impl& im, const std::int64_t* order, std::int64_t q0, std::int64_t q1,
                          const double* lon_deg, const double* lat_deg, double* out, Bilinear bilinear) {
#pragma omp parallel for default(none) shared(im, order, q0, q1, lon_deg, lat_deg, out) firstprivate(bilinear) \
    schedule(static) if (q1 - q0 > 20000)
    for (std::int64_t q = q0; q < q1; ++q) {
      const std::int64_t k = order[q];
      std::int64_t c0 = 0, c1 = 0, r0 = 0, r1 = 0;
      double t = 0.0, u = 0.0;
      (void)im.col(lon_deg[k], c0, c1, t);
      (void)im.row(lat_deg[k], r0, r1, u);
      out[k] = bilinear(c0, c1, r0, r1, t, u);
    }
  }

  // A stored value -> metres, elevation up; NaN for no-data, and for values beyond
  // ±max_abs_m (counted in `implausible`: a sentinel such as -1e29 or a wrong scale is not a depth).
  [[nodiscard]] float normalise(float x, std::int64_t& implausible) const {
    if (signed_byte && x >= 128.0f) x -= 256.0f;
    const bool missing =
        std::isnan(x) || (info.has_nodata && x == static_cast<float>(info.nodata)) || std::abs(x) > 1e30f;
    if (missing) return std::numeric_limits<float>::quiet_NaN();
    const auto elevation = static_cast<float>(sgn * (x * info.scale + info.offset));
    if (!(std::abs(elevation) <= max_abs_m)) {
      ++implausible;
      return std::numeric_limits<float>::quiet_NaN();
    }
    return elevation;
  }

  void compute_stats() {
    const std::int64_t nr = row_hi - row_lo;
    std::vector<RowStats> rows(static_cast<std::size_t>(nr));
    for (std::int64_t r = 0; r < nr; ++r) rows[static_cast<std::size_t>(r)] = row_stats(row_ptr(row_lo + r), held_nc);
    finish_stats(rows);
  }
  // The statistics from the held rows' own (rows [row_lo, row_hi) in order), and the memory held.
  void finish_stats(const std::vector<RowStats>& rows) {
    set_stats(rows);
    info.memory_bytes = static_cast<std::int64_t>((v.size() + fx.size() + fy.size() + fxy.size()) * sizeof(float));
  }

  void set_stats(const std::vector<RowStats>& rows) const {
    RowStats t;
    for (const RowStats& r : rows) {
      t.mn = std::min(t.mn, r.mn);
      t.mx = std::max(t.mx, r.mx);
      t.sum += r.sum;
      t.count += r.count;
      t.implausible += r.implausible;
    }
    info.valid_count = t.count;
    info.implausible_count = t.implausible;
    info.min_m = t.count > 0 ? t.mn : kNaN;
    info.max_m = t.count > 0 ? t.mx : kNaN;
    info.mean_m = t.count > 0 ? t.sum / static_cast<double>(t.count) : kNaN;
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
bool Bathymetry::samples_bilinear() const {
  if (stack_) return false;
  return impl_->info.streamed || !(impl_->interp == Interpolation::kBicubic && !impl_->fx.empty());
}
double Bathymetry::sample(double lon_deg, double lat_deg) const {
  const double z = stack_ ? stack_->sample(lon_deg, lat_deg) : impl_->sample(lon_deg, lat_deg);
  return edits_ ? edits_->apply(lon_deg, lat_deg, z) : z;
}

void Bathymetry::set_edits(std::shared_ptr<const ElevationEdits> edits) {
  edits_ = edits && !edits->empty() ? std::move(edits) : nullptr;
}

void Bathymetry::point_lonlat(std::int64_t c, std::int64_t r, double& lon_deg, double& lat_deg) const {
  const auto& i = impl_->info;
  lon_deg = i.lon_first + static_cast<double>(c) * i.dlon;
  lat_deg = i.lat_first + static_cast<double>(r) * i.dlat;
}

namespace {
[[noreturn]] void no_single_grid(const char* what) {
  throw InternalError(fmt::format("Bathymetry::{} of several sources: there is no one raster grid", what));
}
}  // namespace

float Bathymetry::value(std::int64_t c, std::int64_t r) const {
  if (stack_) no_single_grid("value");
  const auto& i = impl_->info;
  if (i.global_lon) c = ((c % i.ncols) + i.ncols) % i.ncols;
  if (c < 0 || c >= i.ncols || r < impl_->row_lo || r >= (i.streamed ? i.nrows : impl_->row_hi))
    return std::numeric_limits<float>::quiet_NaN();
  float z = 0.0F;
  if (i.streamed) {
    z = impl_->read_value(c, r);
  } else if (i.tiled) {
    z = impl_->tile_value(c, r);
  } else {
    const std::int64_t l = impl_->local_col(c);
    z = l < 0 ? std::numeric_limits<float>::quiet_NaN() : impl_->v[impl_->idx(l, r)];
  }
  if (edits_) {
    double lon = 0.0, lat = 0.0;
    point_lonlat(c, r, lon, lat);
    z = static_cast<float>(edits_->apply(lon, lat, static_cast<double>(z)));
  }
  return z;
}

void Bathymetry::values(std::int64_t c_lo, std::int64_t nc, std::int64_t r_lo, std::int64_t nr, float* out) const {
  if (stack_) no_single_grid("values");
  const Impl& im = *impl_;
  const auto& i = im.info;
  std::fill(out, out + nc * nr, std::numeric_limits<float>::quiet_NaN());
  const std::int64_t a = std::max(r_lo, im.row_lo), b = std::min(r_lo + nr, i.streamed ? i.nrows : im.row_hi);
  if (i.tiled && a < b) {  // tile by tile: one lock per tile and row piece
    for (std::int64_t k0 = 0; k0 < nc;) {
      std::int64_t c = c_lo + k0;
      if (i.global_lon) c = ((c % i.ncols) + i.ncols) % i.ncols;
      if (c < 0 || c >= i.ncols) {
        ++k0;
        continue;
      }
      const std::int64_t tx = c / kTileCells;
      const std::int64_t run = std::min({nc - k0, (tx + 1) * kTileCells - c, i.ncols - c});
      for (std::int64_t r = a; r < b;) {
        const std::int64_t ty = r / kTileCells, rows = std::min(b, (ty + 1) * kTileCells) - r;
        im.tile_rows(c, run, r, rows, out + (r - r_lo) * nc + k0, nc);
        r += rows;
      }
      k0 += run;
    }
  }
  std::vector<float> rows;
  const std::int64_t b_rows = i.tiled ? a : b;  // tiled: read above, tile by tile; the edits below still apply
  if (i.streamed && a < b) {
    rows.resize(static_cast<std::size_t>((b - a) * i.ncols));
    im.read_rows(a, b - a, rows.data());
  }
  for (std::int64_t r = a; r < b_rows; ++r) {
    const float* src = i.streamed ? rows.data() + (r - a) * i.ncols : im.row_ptr(r);
    float* dst = out + (r - r_lo) * nc;
    if (c_lo >= 0 && c_lo + nc <= i.ncols && !im.col_window()) {  // no wrap and nothing outside: one copy
      std::copy(src + c_lo, src + c_lo + nc, dst);
      continue;
    }
    for (std::int64_t k = 0; k < nc; ++k) {
      std::int64_t c = c_lo + k;
      if (i.global_lon) c = ((c % i.ncols) + i.ncols) % i.ncols;
      if (c >= 0 && c < i.ncols && !i.streamed) c = im.local_col(c);
      if (c >= 0 && c < i.ncols) dst[k] = src[c];
    }
  }
  if (edits_) {  // at the raster points' positions (columns as asked: unwrapped longitudes are fine)
    std::vector<double> lons(static_cast<std::size_t>(nc));
    for (std::int64_t k = 0; k < nc; ++k) {
      double lat = 0.0;
      point_lonlat(c_lo + k, 0, lons[static_cast<std::size_t>(k)], lat);
    }
    for (std::int64_t r = r_lo; r < r_lo + nr; ++r) {
      double lon = 0.0, lat = 0.0;
      point_lonlat(0, r, lon, lat);
      edits_->apply_row(lons.data(), lat, out + (r - r_lo) * nc, nc);
    }
  }
}

void Bathymetry::sample_points(const double* lon_deg, const double* lat_deg, std::int64_t n, double* out,
                               const ProgressFn& progress) const {
  raw_points(lon_deg, lat_deg, n, out, progress);
  if (!edits_) return;
  const ElevationEdits* ed = edits_.get();
#pragma omp parallel for default(none) shared(ed, lon_deg, lat_deg, n, out) schedule(static) if (n > 20000)
  for (std::int64_t k = 0; k < n; ++k) out[k] = ed->apply(lon_deg[k], lat_deg[k], out[k]);
}

void Bathymetry::raw_points(const double* lon_deg, const double* lat_deg, std::int64_t n, double* out,
                            const ProgressFn& progress) const {
  if (stack_) return stack_->sample_points(lon_deg, lat_deg, n, out, nullptr);
  const Impl* im = impl_.get();
  if (!im->info.streamed) {
#pragma omp parallel for default(none) shared(im, lon_deg, lat_deg, n, out) schedule(static) if (n > 20000)
    for (std::int64_t k = 0; k < n; ++k) out[k] = im->sample(lon_deg[k], lat_deg[k]);
    return;
  }
  // Streamed: points grouped by band (counting sort), one pass over the bands that hold points.
  // The disk's bands (info.band_rows), not a pass's cache-sized ones (pass_rows): a point reads
  // four values where they lie, so a smaller band only adds steps (the 15" mesh's 11 M node
  // depths took 1.29 s in 8 MB bands, 0.82 s in the 96 MB ones).
  const BandGeometry g = im->disk_bands();
  const std::int64_t nb = g.count(), nc = im->info.ncols;
  std::vector<std::int32_t> band(static_cast<std::size_t>(n));
#pragma omp parallel for default(none) shared(im, g, lon_deg, lat_deg, n, out, band) schedule(static) if (n > 20000)
  for (std::int64_t k = 0; k < n; ++k) {
    std::int64_t c0 = 0, c1 = 0, r0 = 0, r1 = 0;
    double t = 0.0, u = 0.0;
    const bool in = im->col(lon_deg[k], c0, c1, t) && im->row(lat_deg[k], r0, r1, u);
    band[static_cast<std::size_t>(k)] = in ? static_cast<std::int32_t>(g.band_of(r0, r1)) : -1;
    if (!in) out[k] = kNaN;
  }
  std::vector<std::int64_t> start(static_cast<std::size_t>(nb + 1), 0);
  for (const std::int32_t b : band)
    if (b >= 0) ++start[static_cast<std::size_t>(b) + 1];
  for (std::int64_t b = 0; b < nb; ++b) start[static_cast<std::size_t>(b + 1)] += start[static_cast<std::size_t>(b)];
  std::vector<std::int64_t> order(static_cast<std::size_t>(start.back()));
  {
    std::vector<std::int64_t> at(start.begin(), start.end() - 1);
    for (std::int64_t k = 0; k < n; ++k) {
      const std::int32_t b = band[static_cast<std::size_t>(k)];
      if (b >= 0) order[static_cast<std::size_t>(at[static_cast<std::size_t>(b)]++)] = k;
    }
  }
  band = {};
  if (im->map) {
    // Through the file map: the four values of each point read where they lie, band after band
    // (the rows of a band released after it).
    const FileMap& m = *im->map;
    ++im->info.passes;
    const auto has_points = [&start](std::int64_t s) {
      return start[static_cast<std::size_t>(s + 1)] > start[static_cast<std::size_t>(s)];
    };
    const std::int64_t h = im->info.height;
    const bool north_up = im->info.north_up;
    const auto mapped = [im, &m, h, north_up](std::int64_t c0, std::int64_t c1, std::int64_t r0, std::int64_t r1,
                                              double t, double u) {
      const std::int64_t y0 = north_up ? h - 1 - r0 : r0, y1 = north_up ? h - 1 - r1 : r1;
      std::int64_t implausible = 0;
      const float a = im->normalise(m.value(c0, y0), implausible), b = im->normalise(m.value(c1, y0), implausible),
                  c = im->normalise(m.value(c0, y1), implausible), d = im->normalise(m.value(c1, y1), implausible);
      return bilinear4(a, b, c, d, t, u);
    };
    std::int64_t prefetched = -1;  // the bands with points up to this one were prefetched
    for (std::int64_t s = 0; s < nb; ++s) {
      const std::int64_t k0 = start[static_cast<std::size_t>(s)], k1 = start[static_cast<std::size_t>(s + 1)];
      if (k1 == k0) continue;
      // This band and the next one with points: read from the disk in the background.
      std::int64_t next = s + 1;
      while (next < nb && !has_points(next)) ++next;
      for (; prefetched < std::min(next, nb - 1);)
        if (has_points(++prefetched)) m.prefetch(g.first(prefetched), g.end(prefetched));
      Impl::band_points(*im, order.data(), k0, k1, lon_deg, lat_deg, out, mapped);
      m.release(g.first(s), g.end(s));
      if (progress) progress(static_cast<double>(s + 1) / static_cast<double>(nb), "bands of raster rows");
    }
    return;
  }
  const auto wanted = [&start](std::int64_t s) {
    return start[static_cast<std::size_t>(s + 1)] > start[static_cast<std::size_t>(s)];
  };
  const auto work = [&](std::int64_t s, const float* buf) {
    const std::int64_t lo = g.lo(s);
    const auto buffered = [buf, lo, nc](std::int64_t c0, std::int64_t c1, std::int64_t r0, std::int64_t r1, double t,
                                        double u) {
      const float* p0 = buf + (r0 - lo) * nc;
      const float* p1 = buf + (r1 - lo) * nc;
      return bilinear4(p0[c0], p0[c1], p1[c0], p1[c1], t, u);
    };
    Impl::band_points(*im, order.data(), start[static_cast<std::size_t>(s)], start[static_cast<std::size_t>(s + 1)],
                      lon_deg, lat_deg, out, buffered);
  };
  im->stream(wanted, work, nullptr, progress, "bands of raster rows");
}

Bathymetry::Columns Bathymetry::prepare_columns(const double* lons, std::int64_t n, bool skip_tiled) const {
  if (stack_) return stack_->prepare_columns(lons, n, skip_tiled);
  Columns c;
  c.skip_tiled = skip_tiled;
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
  raw_row(cols, lat_deg, out);
  if (edits_) edits_->apply_row(cols.lon.data(), lat_deg, out, static_cast<std::int64_t>(cols.lon.size()));
}

void Bathymetry::raw_row(const Columns& cols, double lat_deg, float* out) const {
  if (stack_) return stack_->sample_row(cols, lat_deg, out);
  const Impl& im = *impl_;
  std::int64_t r0 = 0, r1 = 0;
  double u = 0.0;
  const auto n = static_cast<std::int64_t>(cols.c0.size());
  if (!im.row(lat_deg, r0, r1, u)) {
    std::fill(out, out + n, std::numeric_limits<float>::quiet_NaN());
    return;
  }
  if (im.info.streamed) {
    std::vector<float> rows(static_cast<std::size_t>((r1 - r0 + 1) * im.info.ncols));
    im.read_rows(r0, r1 - r0 + 1, rows.data());
    fill_row(rows.data(), rows.data() + (r1 - r0) * im.info.ncols, cols, u, out);
    return;
  }
  if (im.info.tiled && cols.skip_tiled) {
    std::fill(out, out + n, std::numeric_limits<float>::quiet_NaN());
    return;
  }
  if (im.info.tiled) {  // fill_row's formula on the tiles' values
    for (std::int64_t k = 0; k < n; ++k) {
      const auto s = static_cast<std::size_t>(k);
      const std::int64_t c0 = cols.c0[s], c1 = cols.c1[s];
      out[k] = c0 < 0 ? std::numeric_limits<float>::quiet_NaN()
                      : static_cast<float>(bilinear4(im.tile_value(c0, r0), im.tile_value(c1, r0),
                                                     im.tile_value(c0, r1), im.tile_value(c1, r1), cols.t[s], u));
    }
    return;
  }
  if (im.interp != Interpolation::kBicubic || im.fx.empty()) {
    fill_row(im.row_ptr(r0), im.row_ptr(r1), cols, u, out);
    return;
  }
  for (std::int64_t k = 0; k < n; ++k) {
    const auto s = static_cast<std::size_t>(k);
    out[k] = cols.c0[s] < 0 ? std::numeric_limits<float>::quiet_NaN()
                            : static_cast<float>(im.bicubic(cols.c0[s], cols.c1[s], cols.t[s], r0, r1, u));
  }
}

void Bathymetry::sample_rows(const Columns& cols, const double* lats, std::int64_t n, const RowSink& sink,
                             const ProgressFn& progress) const {
  if (!edits_) return raw_rows(cols, lats, n, sink, progress);
  const ElevationEdits* ed = edits_.get();
  const auto nc = static_cast<std::int64_t>(cols.lon.size());
  raw_rows(
      cols, lats, n,
      [&](std::int64_t k, const float* values) {
        if (!ed->touches_lat(lats[k])) return sink(k, values);
        std::vector<float> row(values, values + nc);
        ed->apply_row(cols.lon.data(), lats[k], row.data(), nc);
        sink(k, row.data());
      },
      progress);
}

void Bathymetry::raw_rows(const Columns& cols, const double* lats, std::int64_t n, const RowSink& sink,
                          const ProgressFn& progress) const {
  if (stack_) return stack_->sample_rows(cols, lats, n, sink, progress);
  const Impl& im = *impl_;
  const auto nc = static_cast<std::int64_t>(cols.c0.size());
  [[maybe_unused]] const bool parallel = n * nc >= (std::int64_t{1} << 16);  // OpenMP off: unused
  if (!im.info.streamed) {
    RowProgress rp(progress, n, "rows");
    // A tiled raster has no rows in memory: sample_row reads its tiles (row_ptr is for held rows).
    const bool bilinear = !im.info.tiled && (im.interp != Interpolation::kBicubic || im.fx.empty());
#pragma omp parallel default(none) shared(im, cols, lats, n, nc, sink, rp, bilinear) if (parallel)
    {
      std::vector<float> buf(static_cast<std::size_t>(nc));
      std::optional<RowFiller> filler;  // a thread's rows are consecutive (static schedule)
      if (bilinear) filler.emplace(cols);
#pragma omp for schedule(static)
      for (std::int64_t k = 0; k < n; ++k) {
        if (cancel_requested()) continue;  // a stop request (core/cancel.hpp): skipped, thrown below
        std::int64_t r0 = 0, r1 = 0;
        double u = 0.0;
        if (!bilinear) {
          raw_row(cols, lats[k], buf.data());
        } else if (im.row(lats[k], r0, r1, u)) {
          filler->fill(im.row_ptr(r0), r0, im.row_ptr(r1), r1, u, buf.data());
        } else {
          std::fill(buf.begin(), buf.end(), std::numeric_limits<float>::quiet_NaN());
        }
        sink(k, buf.data());
        rp.row_done();
      }
    }
    throw_if_cancelled();
    rp.finish();
    return;
  }
  // Streamed: rows grouped by band; rows outside the raster are NaN.
  const BandGeometry g = im.bands();
  std::vector<std::vector<std::int64_t>> rows(static_cast<std::size_t>(g.count()));
  std::vector<std::int64_t> r0s(static_cast<std::size_t>(n)), r1s(r0s.size());
  std::vector<double> us(r0s.size());
  {
    const std::vector<float> nan_row(static_cast<std::size_t>(nc), std::numeric_limits<float>::quiet_NaN());
    for (std::int64_t k = 0; k < n; ++k) {
      const auto q = static_cast<std::size_t>(k);
      if (im.row(lats[k], r0s[q], r1s[q], us[q]))
        rows[static_cast<std::size_t>(g.band_of(r0s[q], r1s[q]))].push_back(k);
      else
        sink(k, nan_row.data());
    }
  }
  RowStats* stats = nullptr;
  if (!im.stats_done) {
    im.stats_rows.assign(static_cast<std::size_t>(im.info.nrows), RowStats{});
    stats = im.stats_rows.data();
  }
  const std::int64_t ncols = im.info.ncols;
  const auto wanted = [&rows](std::int64_t s) { return !rows[static_cast<std::size_t>(s)].empty(); };
  // One RowFiller and output row per thread for the whole pass (a raster row shared by the last
  // lattice row of a band and the first of the next is found again).
#ifdef _OPENMP
  const auto threads = static_cast<std::size_t>(omp_get_max_threads());
#else
  const std::size_t threads = 1;
#endif
  std::vector<std::optional<RowFiller>> fillers(threads);
  std::vector<std::vector<float>> outs(threads);
  const auto work = [&](std::int64_t s, const float* buf) {
    const std::vector<std::int64_t>& ks = rows[static_cast<std::size_t>(s)];
    const std::int64_t lo = g.lo(s), m = static_cast<std::int64_t>(ks.size());
#pragma omp parallel default(none) \
    shared(ks, buf, cols, sink, r0s, r1s, us, lo, m, nc, ncols, fillers, outs) if (m * nc >= (std::int64_t{1} << 16))
    {
#ifdef _OPENMP
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
#else
      const std::size_t t = 0;
#endif
      if (!fillers[t]) {
        fillers[t].emplace(cols);
        outs[t].resize(static_cast<std::size_t>(nc));
      }
#pragma omp for schedule(static)
      for (std::int64_t q = 0; q < m; ++q) {
        const auto k = static_cast<std::size_t>(ks[static_cast<std::size_t>(q)]);
        fillers[t]->fill(buf + (r0s[k] - lo) * ncols, r0s[k], buf + (r1s[k] - lo) * ncols, r1s[k], us[k],
                         outs[t].data());
        sink(static_cast<std::int64_t>(k), outs[t].data());
      }
    }
  };
  im.stream(wanted, work, stats, progress, "bands of raster rows");
  if (stats != nullptr) {
    im.set_stats(im.stats_rows);
    im.stats_rows = {};
    im.stats_done = true;
    if (im.info.valid_count == 0)
      throw InputError(fmt::format("{}: band {} ({}) holds no data: every value is no-data", im.info.path,
                                   im.band_number, im.info.variable));
  }
}

void Bathymetry::ensure_statistics(const ProgressFn& progress) const {
  if (stack_) return stack_->ensure_statistics(progress);
  if (!impl_->info.streamed || impl_->stats_done) return;
  // A pass that samples no row still reads every band for the statistics (sample_rows).
  sample_rows(
      prepare_columns(nullptr, 0), nullptr, 0, [](std::int64_t, const float*) {}, progress);
}

bool Bathymetry::surely_empty(std::int64_t c_lo, std::int64_t c_hi, std::int64_t r_lo, std::int64_t r_hi) const {
  if (stack_) return false;
  const Impl& im = *impl_;
  const auto& i = im.info;
  if (im.band == nullptr) return false;  // held: not asked (its bounds are exact)
  r_lo = std::max<std::int64_t>(r_lo, 0);
  r_hi = std::min(r_hi, i.nrows - 1);
  if (r_lo > r_hi) return true;
  // Columns: one piece, or two across the seam of a global raster.
  std::vector<std::array<std::int64_t, 2>> pieces;
  if (i.global_lon) {
    if (c_hi - c_lo + 1 >= i.ncols) {
      pieces.push_back({0, i.ncols - 1});
    } else {
      const std::int64_t a = ((c_lo % i.ncols) + i.ncols) % i.ncols, b = ((c_hi % i.ncols) + i.ncols) % i.ncols;
      if (a <= b) {
        pieces.push_back({a, b});
      } else {
        pieces.push_back({a, i.ncols - 1});
        pieces.push_back({0, b});
      }
    }
  } else {
    c_lo = std::max<std::int64_t>(c_lo, 0);
    c_hi = std::min(c_hi, i.ncols - 1);
    if (c_lo > c_hi) return true;
    pieces.push_back({c_lo, c_hi});
  }
  const std::int64_t y0 = i.north_up ? i.height - 1 - r_hi : r_lo, ny = r_hi - r_lo + 1;
  const std::lock_guard<std::mutex> lock(im.io);
  for (const auto& p : pieces) {
    double pct = 0.0;
    const int st = GDALGetDataCoverageStatus(im.band, static_cast<int>(p[0]), static_cast<int>(y0),
                                             static_cast<int>(p[1] - p[0] + 1), static_cast<int>(ny), 0, &pct);
    if ((st & GDAL_DATA_COVERAGE_STATUS_EMPTY) == 0 || (st & GDAL_DATA_COVERAGE_STATUS_DATA) != 0 ||
        (st & GDAL_DATA_COVERAGE_STATUS_UNIMPLEMENTED) != 0)
      return false;
  }
  return true;
}

std::vector<std::string> raster_files(const std::string& path) {
  gdal_init();
  std::vector<std::string> out;
  DatasetPtr ds(static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds) return out;
  char** files = ds->GetFileList();
  for (char** f = files; f != nullptr && *f != nullptr; ++f) out.emplace_back(*f);
  CSLDestroy(files);
  return out;
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
  im->row_lo = 0;
  im->row_hi = nrows;
  im->held_nc = ncols;
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

Bathymetry Bathymetry::stack(std::vector<Bathymetry> sources, double blend_km) {
  if (sources.empty()) throw InputError("Bathymetry::stack: no sources");
  if (sources.size() == 1) return std::move(sources.front());
  if (!(blend_km >= 0.0) || !std::isfinite(blend_km))
    throw InputError(fmt::format("input.blend_km = {} is not a finite number >= 0", blend_km));
  auto st = std::make_unique<Stack>();
  st->blend_km = blend_km;
  // The summary: the finest steps, streamed or global when any source is.
  auto im = std::make_unique<Impl>();
  RasterInfo& i = im->info;
  i.driver = "several";
  i.registration = "several";
  i.data_type = "several";
  i.units = "m";
  i.crs_name = "several";
  i.variable = "several";
  i.min_m = std::numeric_limits<double>::infinity();
  i.max_m = -std::numeric_limits<double>::infinity();
  i.dlon = i.dlat = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < sources.size(); ++k) {
    if (sources[k].stack_) throw InputError("Bathymetry::stack: a source is itself several sources");
    const RasterInfo& s = sources[k].info();
    if (sources[k].impl_->interp == Interpolation::kBicubic && !sources[k].impl_->fx.empty())
      throw InputError(fmt::format("{}: bicubic sampling is not available with several sources", s.path));
    i.path += (k == 0 ? "" : " + ") + s.path;
    i.dlon = std::min(i.dlon, s.dlon);
    i.dlat = std::min(i.dlat, s.dlat);
    i.streamed = i.streamed || s.streamed;
    i.global_lon = i.global_lon || s.global_lon;
    i.memory_bytes += s.memory_bytes;
    i.min_m = std::min(i.min_m, s.min_m);
    i.max_m = std::max(i.max_m, s.max_m);
    i.implausible_count += s.implausible_count;
    i.max_abs_elevation_m = s.max_abs_elevation_m;
  }
  if (blend_km > 0.0)
    for (std::size_t k = 0; k + 1 < sources.size(); ++k) {
      st->distances.push_back(edge_distance_field(sources[k], blend_km));
      i.memory_bytes += st->distances.back().info().memory_bytes;
    }
  // The summary's grid: the finest steps over the globe (what callers size their loops by).
  i.lon_first = i.lon_first_found = -180.0;
  i.lat_first = -90.0;
  i.ncols = i.width = static_cast<std::int64_t>(std::ceil(360.0 / i.dlon - 1e-9));
  i.nrows = i.height = static_cast<std::int64_t>(std::ceil(180.0 / i.dlat - 1e-9)) + 1;
  i.valid_count = -1;
  st->sources = std::move(sources);
  Bathymetry b(std::move(im));
  b.stack_ = std::move(st);
  return b;
}

namespace {

// The values made no-data for lying beyond ±max_abs_elevation_m, if any.
void log_implausible(const RasterInfo& i, const Logger& log) {
  if (const std::string note = implausible_note(i); !note.empty()) log.warn("{}: {}", i.path, note);
}

// 80% of the machine's memory when `bytes` is 0.
std::int64_t memory_limit(std::int64_t bytes) {
  return bytes > 0 ? bytes : static_cast<std::int64_t>(0.8 * static_cast<double>(physical_memory_bytes()));
}

}  // namespace

// Opens the dataset, reads its header into the normalised description and decides whole or
// streamed (nothing is read yet).
std::unique_ptr<Bathymetry::Impl> Bathymetry::open_header(const OpenOptions& o) {
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
  if (GDALDataTypeIsComplex(band->GetRasterDataType()) != 0)
    throw InputError(fmt::format("{}: band {} ({}) holds complex numbers ({}); elevations must be real numbers", o.path,
                                 o.band, info.variable, info.data_type));
  // GDAL 3.6 reads a signed-byte band as Byte with PIXELTYPE=SIGNEDBYTE: values 128..255 are
  // -128..-1 (normalise() maps them).
  const char* pixel_type = band->GetMetadataItem("PIXELTYPE", "IMAGE_STRUCTURE");
  im->signed_byte =
      band->GetRasterDataType() == GDT_Byte && pixel_type != nullptr && std::string_view(pixel_type) == "SIGNEDBYTE";
  if (im->signed_byte) info.data_type = "Int8 (signed byte)";

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
  for (const double x : gt)
    if (!std::isfinite(x))
      throw InputError(fmt::format("{}: the geotransform ({}, {}, {}, {}, {}, {}) is not finite", o.path, gt[0], gt[1],
                                   gt[2], gt[3], gt[4], gt[5]));
  if (gt[2] != 0.0 || gt[4] != 0.0) throw InputError(fmt::format("{}: rotated rasters are not supported", o.path));
  if (info.driver == "netCDF") {
    // A classic file cut short reads as zeros past the cut: its header must fit its size. And
    // every coordinate value must be where the geotransform says (GDAL looks at a few only).
    check_netcdf_coordinates(o.path, info.variable, {gt[0], gt[1], gt[2], gt[3], gt[4], gt[5]}, info.width,
                             info.height);
  }
  const double rx = gt[1];
  const double ry = std::abs(gt[5]);
  if (!(rx > 0.0) || !(ry > 0.0)) throw InputError(fmt::format("{}: invalid pixel size {} × {}", o.path, gt[1], gt[5]));
  // A lon/lat pixel is at most the globe (360° × 180°) and at least 1e-9° (0.1 mm): anything else
  // is a broken geotransform (a pixel of 1e300° was once meshed as if it were a small raster).
  if (rx > 360.0 || ry > 180.0 || rx < kMinPixelDeg || ry < kMinPixelDeg)
    throw InputError(
        fmt::format("{}: the geotransform's pixel is {}° × {}°: a lon/lat raster's pixel is between "
                    "{}° and 360° × 180°; is the georeferencing (or the CRS) right?",
                    o.path, gt[1], gt[5], kMinPixelDeg));
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
    if (static_cast<double>(w) * rx > 360.0)
      throw InputError(fmt::format("{}: {} columns of {}° span {}° of longitude, more than the globe's 360°", o.path, w,
                                   rx, static_cast<double>(w) * rx));
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

  int has_nd = 0;
  const double nd = band->GetNoDataValue(&has_nd);
  info.has_nodata = has_nd != 0;
  info.nodata = nd;
  int has_scale = 0, has_offset = 0;
  info.scale = band->GetScale(&has_scale);
  info.offset = band->GetOffset(&has_offset);
  if (has_scale == 0) info.scale = 1.0;
  if (has_offset == 0) info.offset = 0.0;
  im->sgn = o.positive_down ? -1.0 : 1.0;
  im->max_abs_m = static_cast<float>(o.max_abs_elevation_m);
  {
    const GDALDataType t = band->GetRasterDataType();
    im->integral_plain = (t == GDT_Int16 || t == GDT_UInt16 || (t == GDT_Byte && !im->signed_byte)) &&
                         info.scale == 1.0 && info.offset == 0.0 && !o.positive_down;
  }
  info.max_abs_elevation_m = o.max_abs_elevation_m;
  int bx = 0, by = 0;
  band->GetBlockSize(&bx, &by);
  info.block_rows = std::max(1, by);
  im->row_lo = 0;
  im->row_hi = info.nrows;
  im->held_nc = info.ncols;

  // Whole or streamed (README "Big rasters"): streamed when the caller can use it (unrotated
  // vertex rule, bilinear, no latitude window) and the float32 copy would be above 1 GiB or above
  // the memory limit. A band is whole blocks of the file, about 64 MB of float32 (or band_rows).
  const std::int64_t whole = estimate_raster_bytes(info.ncols, info.nrows);
  const bool can_stream = o.allow_streaming && o.interpolation == Interpolation::kBilinear && std::isnan(o.lat_min) &&
                          std::isnan(o.lat_max) && std::isnan(o.lon_min) && std::isnan(o.lon_max);
  using S = OpenOptions::Streaming;
  info.streamed = can_stream && o.streaming != S::kNever &&
                  (o.streaming == S::kAlways || whole > kStreamAboveBytes || whole > memory_limit(o.max_memory_bytes));
  if (info.streamed) {
    const std::int64_t target = std::max<std::int64_t>(1, (64LL << 20) / std::max<std::int64_t>(1, w * 4));
    info.band_rows =
        o.band_rows > 0 ? o.band_rows : std::max(info.block_rows, target / info.block_rows * info.block_rows);
    info.band_rows = std::min(info.band_rows, h);
    if (o.map_file) {
      im->map = FileMap::open(band, w);
      info.mapped = im->map != nullptr;
    }
    // The band buffer (with the carried row) and, through GDAL, two raw read buffers; through the
    // file map, one band of the file's rows mapped instead.
    info.memory_bytes = (info.band_rows + 1) * info.ncols * 4 +
                        (info.mapped ? info.band_rows * w * GDALGetDataTypeSizeBytes(band->GetRasterDataType())
                                     : 2 * info.band_rows * w * 4);
    info.min_m = info.max_m = info.mean_m = kNaN;
    info.valid_count = -1;  // known after the first pass
  }
  if (!info.streamed && o.interpolation == Interpolation::kBilinear) {
    // A latitude window: the rows covering it and 2 more each side.
    if (!std::isnan(o.lat_min) || !std::isnan(o.lat_max)) {
      const double a = std::isnan(o.lat_min) ? -90.0 : o.lat_min, b = std::isnan(o.lat_max) ? 90.0 : o.lat_max;
      im->row_lo = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((a - info.lat_first) / info.dlat)) - 2,
                                            0, info.nrows - 1);
      im->row_hi = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::ceil((b - info.lat_first) / info.dlat)) + 3,
                                            im->row_lo + 1, info.nrows);
    }
    // A longitude window: the columns covering it and 3 more each side (4 after the last).
    if (!std::isnan(o.lon_min) && !std::isnan(o.lon_max) && o.lon_max > o.lon_min) {
      const auto n = info.ncols;
      const double x0 = std::floor((o.lon_min - info.lon_first) / info.dlon) - 3.0;
      const double x1 = std::ceil((o.lon_max - info.lon_first) / info.dlon) + 4.0;  // exclusive
      if (info.global_lon) {
        if (x1 - x0 < static_cast<double>(n)) {
          const auto c0 = static_cast<std::int64_t>(x0);
          im->col_lo = ((c0 % n) + n) % n;
          im->held_nc = static_cast<std::int64_t>(x1 - x0);
        }
      } else {
        // Sampling takes a longitude a whole turn away as the same meridian (col()): the turn of
        // the window that overlaps the raster; a raster so wide that the window could meet it in
        // two places is held whole.
        const double turn = 360.0 / info.dlon;
        if (static_cast<double>(n) + (x1 - x0) + 2.0 < turn) {
          double best = 0.0, lo_best = 0.0, hi_best = 0.0;
          for (int k = -2; k <= 2; ++k) {
            const double lo = std::max(0.0, std::floor(x0 + k * turn)),
                         hi = std::min(static_cast<double>(n), std::ceil(x1 + k * turn));
            if (hi - lo > best) {
              best = hi - lo;
              lo_best = lo;
              hi_best = hi;
            }
          }
          if (best > 0.0 && best < static_cast<double>(n)) {
            im->col_lo = static_cast<std::int64_t>(lo_best);
            im->held_nc = static_cast<std::int64_t>(hi_best - lo_best);
          }
        }
      }
    }
  }
  // Tiled: values read in tiles on demand when what would be held is too large (the whole raster
  // is addressed then, the window only bounds what the caller samples).
  if (!info.streamed && o.interpolation == Interpolation::kBilinear && o.tiles_above_bytes > 0 &&
      estimate_raster_bytes(im->held_nc, im->row_hi - im->row_lo) > o.tiles_above_bytes) {
    info.tiled = true;
    im->row_lo = 0;
    im->row_hi = info.nrows;
    im->col_lo = 0;
    im->held_nc = info.ncols;
    const std::int64_t tile_bytes = kTileCells * kTileCells * static_cast<std::int64_t>(sizeof(float));
    im->max_tiles = std::max<std::int64_t>(16, o.tile_cache_bytes / tile_bytes);
    info.tile_cache_bytes = im->max_tiles * tile_bytes;
    info.memory_bytes = info.tile_cache_bytes;
    info.min_m = info.max_m = info.mean_m = kNaN;
    info.valid_count = -1;
  }
  info.held_cols = im->held_nc;
  info.held_rows = im->row_hi - im->row_lo;
  info.held_col_first = im->col_lo;
  info.held_row_first = im->row_lo;
  im->band = band;
  im->band_number = o.band;
  im->ds = std::move(ds);
  return im;
}

std::string implausible_note(const RasterInfo& info) {
  if (info.implausible_count <= 0) return {};
  return fmt::format("{} value(s) beyond ±{:g} m treated as no-data (input.max_abs_elevation_m)",
                     info.implausible_count, info.max_abs_elevation_m);
}

RasterPlan plan_raster(const OpenOptions& options) {
  const auto im = Bathymetry::open_header(options);
  const RasterInfo& i = im->info;
  RasterPlan p;
  p.width = i.width;
  p.height = i.height;
  p.streamed = i.streamed;
  p.block_rows = i.block_rows;
  p.band_rows = i.band_rows;
  const std::int64_t factor = options.interpolation == Interpolation::kBicubic ? 4 : 1;
  p.bytes =
      i.streamed || i.tiled ? i.memory_bytes : estimate_raster_bytes(i.held_cols, i.held_rows) * factor + (64LL << 20);
  return p;
}

Bathymetry Bathymetry::open(const OpenOptions& o, const Logger& log) {
  auto im = open_header(o);
  RasterInfo& info = im->info;
  const std::int64_t h = info.height;
  if (info.streamed || info.tiled) {
    if (!info.global_lon && o.warn_partial_coverage) {
      log.warn("{}: the raster covers longitudes {:.4f}..{:.4f} only; the rest of the lattice is dry", o.path,
               info.lon_first, info.lon_first + static_cast<double>(info.ncols - 1) * info.dlon);
    }
    return Bathymetry(std::move(im));
  }
  // The window (regional runs) was chosen with the header (open_header).
  const std::int64_t rows_held = im->row_hi - im->row_lo;
  // Memory estimate before reading.
  const std::int64_t need =
      estimate_raster_bytes(im->held_nc, rows_held) * (o.interpolation == Interpolation::kBicubic ? 4 : 1);
  const std::int64_t limit = memory_limit(o.max_memory_bytes);
  if (limit > 0 && need > limit) {
    throw InputError(
        fmt::format("{}: holding the raster needs {:.1f} GB, more than the limit {:.1f} GB "
                    "(input.max_memory_gb); use a coarser raster or a region",
                    o.path, static_cast<double>(need) / 1e9, static_cast<double>(limit) / 1e9));
  }

  // Read in bands of stored rows through GDAL windows straight into the normalised array.
  im->v.resize(static_cast<std::size_t>(im->held_nc * rows_held));
  const std::int64_t w = info.width;
  const std::int64_t chunk = std::max<std::int64_t>(1, (64LL << 20) / std::max<std::int64_t>(1, w * 4));
  const std::int64_t y_lo = info.north_up ? h - im->row_hi : im->row_lo;
  const std::int64_t y_hi = info.north_up ? h - im->row_lo : im->row_hi;
  // GDAL reads chunk k + 1 on a second thread while the threads normalise chunk k and take its
  // row statistics (combined in row order afterwards: the same figures as compute_stats).
  std::vector<float> raw[2];
  std::vector<RowStats> rows(static_cast<std::size_t>(info.nrows));
  auto progress = log.progress("read");
  Impl* const p = im.get();
  const auto read = [p, &raw, chunk, y_hi](std::int64_t y0, std::size_t k) {
    p->read_raw(y0, std::min(y_hi, y0 + chunk), raw[k % 2]);
  };
  std::future<void> next = std::async(std::launch::async, read, y_lo, std::size_t{0});
  std::size_t k = 0;
  for (std::int64_t y0 = y_lo; y0 < y_hi; y0 += chunk, ++k) {
    const std::int64_t y1 = std::min(y_hi, y0 + chunk);
    next.get();
    if (y1 < y_hi) next = std::async(std::launch::async, read, y1, k + 1);
    try {
      im->normalise_rows(y0, y1, raw[k % 2].data(), im->v.data(), im->row_lo, rows.data(), true);
      if (progress) progress(static_cast<double>(y1 - y_lo) / static_cast<double>(y_hi - y_lo), "rows");
      throw_if_cancelled();  // between chunks (core/cancel.hpp)
    } catch (...) {
      if (next.valid()) next.wait();
      throw;
    }
  }
  im->ds.reset();  // everything is held
  im->band = nullptr;
  im->finish_stats(std::vector<RowStats>(rows.begin() + im->row_lo, rows.begin() + im->row_hi));
  if (im->info.valid_count == 0) {
    throw InputError(
        fmt::format("{}: band {} ({}) holds no data: every value is no-data", o.path, o.band, info.variable));
  }
  log_implausible(im->info, log);
  if (o.interpolation == Interpolation::kBicubic) {
    im->build_spline();
    im->compute_stats();
  }
  if (!info.global_lon && o.warn_partial_coverage) {
    log.warn("{}: the raster covers longitudes {:.4f}..{:.4f} only; the rest of the lattice is dry", o.path,
             info.lon_first, info.lon_first + static_cast<double>(info.ncols - 1) * info.dlon);
  }
  return Bathymetry(std::move(im));
}

}  // namespace aq::raster
