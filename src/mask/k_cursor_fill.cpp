// SPDX-License-Identifier: GPL-3.0-or-later
// K-cursor fill (seed 002 §2, ARCHITECTURE §4.3): erosion to all-wet windows, span flood fill
// over windows from the seeds, dilation back to pixels, seed placement and statistics.
#include "mask/k_cursor_fill.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/types.hpp"
#include "mask/bit_rows.hpp"

namespace aq::mask {

namespace {

// A run of set bits of one row: columns lo, lo+1, ..., lo+len-1 (mod nx), 0 <= lo < nx.
struct Run {
  std::int64_t lo = 0;
  std::int64_t len = 0;
};

// The run of set bits of `row` (length nx) that contains bit p (which must be set), periodic.
Run run_containing(const std::uint64_t* row, std::int64_t nx, std::int64_t p) {
  const std::int64_t r = bits::find_first_clear(row, p, nx);  // first clear bit east of p
  const std::int64_t l = bits::find_last_clear(row, 0, p);    // last clear bit west of p
  if (r == nx && l == -1) return {0, nx};                     // the whole row
  if (r == nx) {                                              // continues east over the seam
    const std::int64_t r2 = bits::find_first_clear(row, 0, l + 1);
    return {l + 1, nx - (l + 1) + r2};
  }
  if (l == -1) {  // continues west over the seam
    const std::int64_t l2 = bits::find_last_clear(row, r, nx);
    if (l2 + 1 == nx) return {0, r};
    return {l2 + 1, nx - (l2 + 1) + r};
  }
  return {l + 1, r - (l + 1)};
}

// Calls f(a, b) for the (at most two) linear pieces [a, b) of a periodic run.
template <typename F>
void for_each_piece(Run run, std::int64_t nx, F&& f) {
  const std::int64_t end = run.lo + run.len;
  if (end <= nx) {
    f(run.lo, end);
  } else {
    f(run.lo, nx);
    f(std::int64_t{0}, end - nx);
  }
}

// Span flood fill that consumes set bits of a bitmap. One instance reuses its stack over many
// fills (component counting).
class SpanFiller {
 public:
  FloodCount fill(Bitmap& rem, PixelIJ s, Bitmap* reached, const Bitmap* probe, const RunVisitor* visit = nullptr) {
    visit_ = visit;
    FloodCount fc;
    if (s.j < 0 || s.j >= rem.ny() || s.i < 0 || s.i >= rem.nx() || !rem.get(s.i, s.j)) return fc;
    const std::int64_t nx = rem.nx(), ny = rem.ny();
    take(rem, s.j, s.i, reached, probe, fc);
    while (!stack_.empty()) {
      const Span sp = stack_.back();
      stack_.pop_back();
      for (const std::int64_t jj : {sp.j - 1, sp.j + 1}) {
        if (jj < 0 || jj >= ny) continue;
        for_each_piece(sp.run, nx, [&](std::int64_t a, std::int64_t b) {
          std::int64_t p = bits::find_first_set(rem.row(jj), a, b);
          while (p < b) {
            take(rem, jj, p, reached, probe, fc);
            p = bits::find_first_set(rem.row(jj), p + 1, b);
          }
        });
      }
    }
    return fc;
  }

 private:
  struct Span {
    std::int64_t j;
    Run run;
  };

  void take(Bitmap& rem, std::int64_t j, std::int64_t p, Bitmap* reached, const Bitmap* probe, FloodCount& fc) {
    const std::int64_t nx = rem.nx();
    const Run run = run_containing(rem.row(j), nx, p);
    for_each_piece(run, nx, [&](std::int64_t a, std::int64_t b) {
      bits::clear_range(rem.row(j), a, b);
      if (visit_ != nullptr) (*visit_)(j, a, b);
      if (reached != nullptr) bits::set_range(reached->row(j), a, b);
      if (probe != nullptr) fc.probe_hits += bits::count_range(probe->row(j), a, b);
    });
    fc.cells += run.len;
    stack_.push_back({j, run});
  }

  std::vector<Span> stack_;
  const RunVisitor* visit_ = nullptr;
};

// Preconditions of the fill's entry points; the configuration's values (mask.cursor 1..64,
// mask.seeds, mask.seed_radius_deg) are validated at load, so failing one is a bug.
void check_cursor(int k) {
  if (k < 1 || k > 64) throw InternalError(fmt::format("K-cursor fill: K = {} is outside 1..64", k));
}

std::string seed_name(std::size_t n, const std::array<double, 2>& s) {
  return fmt::format("mask.seeds[{}] = ({}, {})", n, s[0], s[1]);
}

// Best (nearest centre, then smallest (j, i)) all-wet window among candidates.
struct Best {
  double dist = std::numeric_limits<double>::infinity();
  PixelIJ w{-1, -1};
  void offer(PixelIJ c, double d) {
    if (d < dist || (d == dist && (c.j < w.j || (c.j == w.j && c.i < w.i)))) {
      dist = d;
      w = c;
    }
  }
  [[nodiscard]] bool found() const { return w.i >= 0; }
};

}  // namespace

Bitmap all_wet_windows(const Bitmap& wet, int k) {
  check_cursor(k);
  const std::int64_t nx = wet.nx(), ny = wet.ny(), nw = wet.words_per_row();
  Bitmap win(nx, ny);
  const std::int64_t rows = ny - k + 1;  // windows above would cross the North pole
#pragma omp parallel default(none) shared(wet, win, nx, nw, rows, k) if (rows * nw >= bits::kParallelMinWords)
  {
    std::vector<std::uint64_t> v(static_cast<std::size_t>(nw));
#pragma omp for schedule(static)
    for (std::int64_t j = 0; j < rows; ++j) {
      std::copy_n(wet.row(j), nw, v.data());  // vertical AND over rows j .. j+K-1
      for (int b = 1; b < k; ++b) {
        const std::uint64_t* r = wet.row(j + b);
        for (std::int64_t w = 0; w < nw; ++w) v[static_cast<std::size_t>(w)] &= r[w];
      }
      std::uint64_t* dst = win.row(j);  // horizontal AND over columns i .. i+K-1 (periodic)
      std::copy_n(v.data(), nw, dst);
      for (int a = 1; a < k; ++a) bits::rotate_row(v.data(), dst, nx, a, bits::Combine::kAnd);
    }
  }
  return win;
}

Bitmap dilate_windows(const Bitmap& windows, int k) {
  check_cursor(k);
  const std::int64_t nx = windows.nx(), ny = windows.ny(), nw = windows.words_per_row();
  Bitmap out(nx, ny);
#pragma omp parallel default(none) shared(windows, out, nx, ny, nw, k) if (ny * nw >= bits::kParallelMinWords)
  {
    std::vector<std::uint64_t> v(static_cast<std::size_t>(nw));
#pragma omp for schedule(static)
    for (std::int64_t j = 0; j < ny; ++j) {
      std::fill(v.begin(), v.end(), 0);  // vertical OR over window rows j-K+1 .. j
      for (int b = 0; b < k && j - b >= 0; ++b) {
        const std::uint64_t* r = windows.row(j - b);
        for (std::int64_t w = 0; w < nw; ++w) v[static_cast<std::size_t>(w)] |= r[w];
      }
      std::uint64_t* dst = out.row(j);  // horizontal OR over window columns i-K+1 .. i
      std::copy_n(v.data(), nw, dst);
      for (int a = 1; a < k; ++a) bits::rotate_row(v.data(), dst, nx, -a, bits::Combine::kOr);
    }
  }
  return out;
}

FloodCount flood_consume(Bitmap& remaining, PixelIJ start, Bitmap* reached, const Bitmap* probe) {
  SpanFiller f;
  return f.fill(remaining, start, reached, probe);
}

std::int64_t flood_consume_runs(Bitmap& remaining, PixelIJ start, const RunVisitor& visit) {
  SpanFiller f;
  return f.fill(remaining, start, nullptr, nullptr, &visit).cells;
}

Bitmap flood_fill(const Bitmap& mask, std::span<const PixelIJ> starts) {
  Bitmap rem = mask;
  Bitmap reached(mask.nx(), mask.ny());
  SpanFiller f;
  for (const PixelIJ& s : starts) f.fill(rem, s, &reached, nullptr);
  return reached;
}

ComponentStats count_components(const Bitmap& mask, const Bitmap* probe, Bitmap* scratch) {
  ComponentStats st;
  Bitmap own;
  Bitmap& rem = scratch != nullptr ? *scratch : own;
  rem = mask;
  SpanFiller f;
  const std::int64_t nw = rem.words_per_row();
  for (std::int64_t j = 0; j < rem.ny(); ++j) {
    for (std::int64_t w = 0; w < nw; ++w) {
      while (rem.row(j)[w] != 0) {
        const std::int64_t i = (w << 6) + std::countr_zero(rem.row(j)[w]);
        const FloodCount fc = f.fill(rem, {i, j}, nullptr, probe);
        ++st.count;
        st.largest = std::max(st.largest, fc.cells);
        if (fc.probe_hits > 0) {
          ++st.touching_probe;
          st.cells_touching_probe += fc.cells;
        }
      }
    }
  }
  return st;
}

Bitmap k_fill(const Bitmap& wet, int k, std::span<const PixelIJ> seed_windows,
              std::vector<std::int64_t>* reached_per_seed) {
  Bitmap rem = all_wet_windows(wet, k);
  Bitmap reached(wet.nx(), wet.ny());
  SpanFiller f;
  if (reached_per_seed != nullptr) reached_per_seed->clear();
  for (const PixelIJ& s : seed_windows) {
    const FloodCount fc = f.fill(rem, s, &reached, nullptr);
    if (reached_per_seed != nullptr) reached_per_seed->push_back(fc.cells);
  }
  return dilate_windows(reached, k);
}

SeedSearchBox seed_search_box(const Lattice& lattice, double lat_deg, double x, double radius_deg, std::int64_t k) {
  const double half = 0.5 * static_cast<double>(k);
  SeedSearchBox b;
  b.jlo = static_cast<std::int64_t>(std::floor(lattice.row_of_lat(std::max(lat_deg - radius_deg, -90.0)) - half)) - 1;
  b.jhi = static_cast<std::int64_t>(std::ceil(lattice.row_of_lat(std::min(lat_deg + radius_deg, 90.0)) - half)) + 1;
  b.ilo = 0;
  b.ihi = lattice.nx - 1;
  const double clat = std::cos(lat_deg * kDegToRad);
  const double srad = std::sin(std::min(radius_deg, 90.0) * kDegToRad);
  if (std::abs(lat_deg) + radius_deg < 89.0 && srad < clat) {
    const double dlon = std::asin(srad / clat) * kRadToDeg;
    const auto w = static_cast<std::int64_t>(std::ceil(dlon / lattice.pixel_deg())) + k + 2;
    if (2 * w + 1 < lattice.nx) {
      const auto ic = static_cast<std::int64_t>(std::floor(x - half));
      b.ilo = ic - w;
      b.ihi = ic + w;
    }
  }
  return b;
}

std::vector<SeedInfo> place_seeds(const Bitmap& windows, int k, const Lattice& lattice, const PoleRotation& rot,
                                  const std::vector<std::array<double, 2>>& seeds, double radius_deg,
                                  const Logger& log) {
  check_cursor(k);
  if (seeds.empty()) throw InternalError("place_seeds: no seed");
  if (!std::isfinite(radius_deg) || radius_deg < 0.0)
    throw InternalError(fmt::format("place_seeds: seed radius {}° is not a finite number >= 0", radius_deg));
  const std::int64_t nx = lattice.nx, ny = lattice.ny;
  const double dpx = lattice.pixel_deg();
  std::vector<SeedInfo> out;
  for (std::size_t n = 0; n < seeds.size(); ++n) {
    const auto& s = seeds[n];
    if (!std::isfinite(s[0]) || !std::isfinite(s[1]) || s[1] < -90.0 || s[1] > 90.0)
      throw InternalError(
          fmt::format("{}: not a valid point (longitude, latitude in [-90, 90] degrees)", seed_name(n, s)));
    const LonLat r = geographic_to_lattice(rot, {s[0], s[1]});
    double x = 0.0, y = 0.0;
    deg_to_lattice_xy(lattice, r, x, y);
    const auto px = std::min<std::int64_t>(static_cast<std::int64_t>(std::floor(x)), nx - 1);
    const auto py = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(y)), 0, ny - 1);
    const auto offer = [&](Best& best, std::int64_t i0, std::int64_t j0) {
      if (j0 < 0 || j0 > ny - k) return;
      const PixelIJ w{wrap_index(i0, nx), j0};
      if (!windows.get(w.i, w.j)) return;
      best.offer(w, angular_distance_deg(r, window_center_lattice_deg(lattice, w, k)));
    };
    // 1. All-wet windows that hold the seed's pixel.
    Best best;
    for (std::int64_t j0 = py - k + 1; j0 <= py; ++j0)
      for (std::int64_t i0 = px - k + 1; i0 <= px; ++i0) offer(best, i0, j0);
    SeedInfo info;
    info.index = static_cast<int>(n);
    info.requested = {s[0], s[1]};
    if (!best.found()) {
      // 2. The nearest all-wet window centre within the radius (great-circle degrees).
      const SeedSearchBox box = seed_search_box(lattice, r.lat_deg, x, radius_deg, k);
      const std::int64_t jlo = box.jlo, jhi = box.jhi, ilo = box.ilo, ihi = box.ihi;
      Best near;
      for (std::int64_t j0 = std::max<std::int64_t>(jlo, 0); j0 <= std::min(jhi, ny - k); ++j0)
        for (std::int64_t i0 = ilo; i0 <= ihi; ++i0) offer(near, i0, j0);
      if (!near.found() || near.dist > radius_deg) {
        throw ConfigError(fmt::format(
            "{}: no all-wet {}×{} pixel window (K = mask.cursor, pixels of {}°; wet means elevation <= "
            "-mask.min_depth_m) within mask.seed_radius_deg = {}° of the seed; put the seed in open water or "
            "increase mask.seed_radius_deg",
            seed_name(n, s), k, k, dpx, radius_deg));
      }
      best = near;
      info.moved = true;
      info.moved_deg = near.dist;
    }
    info.window = best.w;
    info.window_center = lattice_to_geographic(rot, window_center_lattice_deg(lattice, best.w, k));
    if (info.moved) {
      log.warn("{}: not inside an all-wet {}×{} pixel window; moved {:.3f}° to ({:.4f}, {:.4f}) (window centre)",
               seed_name(n, s), k, k, info.moved_deg, info.window_center.lon_deg, info.window_center.lat_deg);
    }
    out.push_back(info);
  }
  return out;
}

KFillResult k_cursor_fill(const Bitmap& wet, const Lattice& lattice, const PoleRotation& rot, int k,
                          const std::vector<std::array<double, 2>>& seeds, double radius_deg, const Logger& log) {
  check_cursor(k);
  if (wet.nx() != lattice.nx || wet.ny() != lattice.ny)
    throw InternalError(fmt::format("k_cursor_fill: wet bitmap {}×{} does not match the lattice {}×{}", wet.nx(),
                                    wet.ny(), lattice.nx, lattice.ny));
  KFillResult res;
  Bitmap rem = all_wet_windows(wet, k);
  res.stats.cursor = k;
  res.stats.all_wet_windows = rem.count();
  res.seeds = place_seeds(rem, k, lattice, rot, seeds, radius_deg, log);
  Bitmap reached(wet.nx(), wet.ny());
  SpanFiller f;
  for (std::size_t n = 0; n < res.seeds.size(); ++n) {
    SeedInfo& si = res.seeds[n];
    const FloodCount fc = f.fill(rem, si.window, &reached, nullptr);
    si.windows_reached = fc.cells;
    // Later seeds whose window this fill reached (first time) belong to seed n's fill.
    for (std::size_t m = n + 1; m < res.seeds.size(); ++m) {
      SeedInfo& later = res.seeds[m];
      if (later.same_fill_as < 0 && fc.cells > 0 && reached.get(later.window.i, later.window.j))
        later.same_fill_as = static_cast<int>(n);
    }
  }
  res.stats.reached_windows = reached.count();
  res.filled = dilate_windows(reached, k);
  res.stats.wet_pixels = wet.count();
  res.stats.filled_pixels = res.filled.count();
  res.stats.wet_left_out = res.stats.wet_pixels - res.stats.filled_pixels;
  // The windows the fills left (rem) are not needed any more: their storage holds the copy of
  // `wet` the count consumes (at 15" a bitmap is 466 MB: no new pages to fault in and zero).
  const ComponentStats cs = count_components(wet, &res.filled, &rem);
  res.stats.wet_components = cs.count;
  res.stats.wet_components_filled = cs.touching_probe;
  res.stats.largest_wet_component = cs.largest;
  return res;
}

}  // namespace aq::mask
