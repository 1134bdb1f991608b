// SPDX-License-Identifier: GPL-3.0-or-later
// Critical passages: the built-in table and the box-restricted connectivity test (passages.hpp).
#include "mask/passages.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <string_view>

#include "core/types.hpp"
#include "mask/lattice_coords.hpp"

namespace aq::mask {

namespace {

// Boxes are {lon_min, lon_max, lat_min, lat_max} in geographic degrees (east and north positive).
// The depth after the boxes is the strait's nominal sill depth (m; charts and the oceanographic
// literature, rounded): the depth a carved channel gets where the raster has no path deeper than
// mask.min_depth_m between the sides (ETOPO5's Bosphorus is land). Names after it are aliases.
// Each box spans the strait; sides A and B are open water at its two ends. Inside each box the
// only water route between the sides is the strait itself (alternative routes, e.g. around
// Iceland, Newfoundland, Taiwan or Sicily, leave the box). Checked on ETOPO5: every 5' sample
// point of every side box is water (<= 0 m), and on the ETOPO5 wet pixels at 1.875' every passage
// is open except the Bosphorus, which ETOPO5 does not have (+2..+6 m across 28.7-29.5°E at
// 41.08-41.17°N), and the Little Belt, whose 5' cells meet only at a corner; see
// tests/integration/mask_etopo5_test.cpp.
// clang-format off
constexpr std::array<Passage, 37> kPassages{{
    {"Gibraltar", "Gulf of Cadiz", "Mediterranean Sea",
     {-7.0, -4.0, 35.0, 37.0}, {-7.0, -6.4, 35.6, 36.4}, {-4.8, -4.0, 35.6, 36.3}, 284.0, "Strait of Gibraltar"},
    {"Bosphorus", "Sea of Marmara", "Black Sea",
     {28.3, 29.6, 40.6, 41.6}, {28.3, 28.9, 40.65, 40.9}, {29.0, 29.6, 41.35, 41.6}, 35.0, "Bosporus|Istanbul Strait"},
    {"Bering", "Bering Sea", "Chukchi Sea",
     {-171.0, -167.0, 64.0, 67.3}, {-170.5, -168.0, 64.2, 64.8}, {-170.5, -167.5, 66.5, 67.2}, 50.0, "Bering Strait"},
    {"Bab-el-Mandeb", "Red Sea", "Gulf of Aden",
     {42.0, 44.5, 11.7, 14.9}, {42.2, 42.9, 13.9, 14.5}, {43.6, 44.4, 11.8, 12.3}, 137.0, "Bab el Mandeb|Bab al-Mandab"},
    {"Hormuz", "Persian Gulf", "Gulf of Oman",
     {54.8, 57.8, 24.8, 27.0}, {54.8, 55.6, 26.0, 26.4}, {57.0, 57.8, 24.8, 25.4}, 70.0, "Strait of Hormuz"},
    {"Malacca/Singapore", "Strait of Malacca", "South China Sea",
     {100.3, 105.3, 0.8, 3.3}, {100.3, 101.0, 2.7, 3.3}, {104.6, 105.3, 1.5, 2.2}, 25.0, "Malacca|Singapore|Strait of Malacca|Singapore Strait"},
    {"Lombok", "Indian Ocean", "Bali Sea",
     {115.2, 116.3, -9.6, -7.6}, {115.3, 116.2, -9.6, -9.1}, {115.3, 116.2, -8.0, -7.6}, 250.0, "Lombok Strait"},
    {"Torres", "Arafura Sea", "Coral Sea",
     {140.5, 144.0, -11.0, -9.0}, {140.5, 141.3, -10.8, -10.0}, {143.3, 144.0, -10.5, -9.8}, 10.0, "Torres Strait"},
    {"Bass", "Indian Ocean", "Tasman Sea",
     {142.0, 149.8, -41.0, -38.9}, {142.0, 142.8, -40.3, -39.4}, {149.0, 149.8, -40.3, -39.2}, 50.0, "Bass Strait"},
    {"Fram", "Greenland Sea", "Arctic Ocean",
     {-10.0, 8.0, 76.0, 82.5}, {-5.0, 5.0, 76.0, 77.0}, {-5.0, 5.0, 81.5, 82.5}, 2500.0, "Fram Strait"},
    {"Nares", "Baffin Bay", "Lincoln Sea",
     {-78.0, -50.0, 76.5, 83.2}, {-76.0, -72.0, 76.5, 77.2}, {-60.0, -54.0, 82.6, 83.2}, 220.0, "Nares Strait"},
    {"Davis", "Labrador Sea", "Baffin Bay",
     {-64.0, -54.0, 63.5, 70.0}, {-60.0, -56.0, 63.5, 64.5}, {-62.0, -58.0, 69.0, 70.0}, 640.0, "Davis Strait"},
    {"Belle Isle", "Gulf of St. Lawrence", "Labrador Sea",
     {-58.6, -54.2, 50.4, 52.4}, {-58.6, -57.9, 50.4, 50.9}, {-55.0, -54.2, 51.8, 52.3}, 60.0, "Strait of Belle Isle"},
    {"Florida", "Gulf of Mexico", "Atlantic Ocean",
     {-84.5, -79.4, 22.8, 26.5}, {-84.5, -83.5, 23.5, 24.3}, {-79.9, -79.5, 25.2, 26.3}, 750.0, "Straits of Florida|Florida Straits"},
    {"Yucatan", "Caribbean Sea", "Gulf of Mexico",
     {-87.0, -84.8, 20.2, 23.8}, {-86.5, -85.5, 20.2, 20.8}, {-86.5, -85.5, 23.0, 23.8}, 2000.0, "Yucatan Channel|Yucatán"},
    {"Drake", "Pacific Ocean", "Scotia Sea",
     {-72.0, -56.0, -61.0, -56.2}, {-72.0, -70.0, -60.0, -57.0}, {-58.0, -56.0, -59.0, -57.0}, 3000.0, "Drake Passage"},
    {"Denmark", "Irminger Sea", "Iceland Sea",
     {-33.0, -17.0, 64.0, 68.5}, {-33.0, -28.0, 64.0, 65.0}, {-22.0, -17.0, 67.5, 68.5}, 620.0, "Denmark Strait"},
    {"Dover", "English Channel", "North Sea",
     {0.0, 2.8, 50.2, 51.8}, {0.0, 0.8, 50.2, 50.6}, {2.0, 2.8, 51.4, 51.8}, 35.0, "Strait of Dover|Dover Strait|Pas de Calais"},
    {"Danish straits", "Kattegat", "Baltic Sea",
     {9.5, 13.6, 54.3, 57.0}, {11.0, 11.8, 56.5, 57.0}, {12.8, 13.6, 54.75, 55.2}, 18.0, "Belts|Danish Straits"},
    {"Kerch", "Black Sea", "Sea of Azov",
     {35.8, 37.2, 44.5, 46.0}, {36.2, 37.0, 44.5, 44.85}, {36.0, 36.8, 45.6, 46.0}, 5.0, "Kerch Strait"},
    {"Tsugaru", "Sea of Japan", "Pacific Ocean",
     {138.8, 142.6, 40.9, 41.9}, {138.8, 139.6, 41.0, 41.6}, {141.8, 142.6, 41.0, 41.6}, 130.0, "Tsugaru Strait"},
    {"Korea", "East China Sea", "Sea of Japan",
     {127.8, 131.2, 33.3, 35.8}, {127.8, 128.8, 33.5, 34.2}, {130.3, 131.2, 35.2, 35.8}, 120.0, "Korea Strait|Tsushima"},
    {"La Perouse", "Sea of Japan", "Sea of Okhotsk",
     {140.3, 143.4, 45.1, 46.2}, {140.3, 141.0, 45.6, 46.2}, {142.7, 143.4, 45.2, 45.8}, 55.0, "La Pérouse|Soya|Soya Strait"},
    {"Taiwan", "East China Sea", "South China Sea",
     {118.5, 121.4, 22.3, 26.2}, {120.4, 121.2, 25.6, 26.2}, {118.5, 119.5, 22.3, 22.9}, 60.0, "Taiwan Strait"},
    {"Messina", "Tyrrhenian Sea", "Ionian Sea",
     {15.2, 16.0, 37.55, 38.7}, {15.3, 15.75, 38.35, 38.7}, {15.35, 15.9, 37.55, 37.85}, 80.0, "Strait of Messina"},
    {"Sicily", "Western Mediterranean", "Eastern Mediterranean",
     {10.0, 14.0, 35.5, 38.4}, {10.0, 11.0, 37.6, 38.4}, {13.0, 14.0, 35.9, 36.6}, 430.0, "Strait of Sicily|Sicily Channel"},
    {"Luzon", "South China Sea", "Philippine Sea",
     {118.5, 123.5, 18.8, 21.8}, {118.5, 119.5, 19.5, 21.0}, {122.5, 123.5, 19.5, 21.0}, 2400.0, "Luzon Strait|Bashi Channel"},
    {"Hudson", "Hudson Bay", "Labrador Sea",
     {-82.0, -62.5, 60.0, 64.0}, {-82.0, -80.8, 61.0, 61.5}, {-63.8, -62.5, 60.8, 61.5}, 200.0, "Hudson Strait"},
    {"Barrow", "Lancaster Sound", "Viscount Melville Sound",
     {-104.0, -83.0, 73.5, 75.0}, {-85.0, -83.0, 74.0, 74.4}, {-104.0, -101.0, 74.2, 74.6}, 125.0, "Barrow Strait"},
    {"Juan de Fuca", "Pacific Ocean", "Salish Sea",
     {-126.0, -122.8, 47.9, 48.7}, {-126.0, -125.2, 47.9, 48.4}, {-123.3, -122.8, 48.15, 48.35}, 55.0, "Strait of Juan de Fuca"},
    {"Dardanelles", "Aegean Sea", "Sea of Marmara",
     {25.8, 27.8, 39.85, 40.7}, {25.8, 26.1, 39.85, 40.1}, {27.2, 27.8, 40.45, 40.65}, 60.0, "Canakkale|Çanakkale|Hellespont"},
    {"Oresund", "Kattegat", "Baltic Sea",
     {12.2, 13.2, 55.3, 56.22}, {12.25, 12.48, 56.12, 56.22}, {12.5, 13.0, 55.3, 55.4}, 8.0, "Øresund|Öresund|The Sound"},
    {"Great Belt", "Kattegat", "Kiel Bay",
     {10.6, 11.4, 54.95, 56.05}, {10.8, 11.05, 55.95, 56.05}, {10.7, 10.95, 54.96, 55.04}, 16.0, "Storebælt|Storebaelt"},
    {"Little Belt", "Kattegat", "Kiel Bay",
     {9.4, 10.2, 54.9, 55.75}, {9.85, 10.15, 55.62, 55.72}, {9.95, 10.2, 54.9, 55.0}, 10.0, "Lillebælt|Lillebaelt"},
    {"Chesapeake", "Atlantic Ocean", "Chesapeake Bay",
     {-76.6, -75.3, 36.8, 37.9}, {-75.7, -75.4, 36.9, 37.1}, {-76.4, -76.1, 37.6, 37.9}, 15.0, "Chesapeake Bay"},
    {"Delaware", "Atlantic Ocean", "Delaware Bay",
     {-75.7, -74.7, 38.6, 39.5}, {-75.0, -74.75, 38.6, 38.75}, {-75.45, -75.3, 39.12, 39.28}, 15.0, "Delaware Bay"},
    {"Gorlo", "White Sea", "Barents Sea",
     {38.0, 44.5, 65.2, 68.0}, {38.0, 39.0, 65.3, 65.7}, {42.0, 43.5, 67.3, 67.8}, 40.0, "Gorlo Strait|White Sea"},
}};
// clang-format on

// Cell flags of the local grid.
enum : unsigned char { kInBox = 1, kSideA = 2, kSideB = 4, kFilled = 8, kSeen = 16 };

// Largest great-circle distance from the box centre to its outline (degrees).
double box_radius_deg(const GeoBox& b, LonLat c) {
  double r = 0.0;
  constexpr int kSteps = 16;
  for (int s = 0; s <= kSteps; ++s) {
    const double t = static_cast<double>(s) / kSteps;
    const double lon = b.lon_min_deg + t * (b.lon_max_deg - b.lon_min_deg);
    const double lat = b.lat_min_deg + t * (b.lat_max_deg - b.lat_min_deg);
    for (const LonLat q : {LonLat{lon, b.lat_min_deg}, LonLat{lon, b.lat_max_deg}, LonLat{b.lon_min_deg, lat},
                           LonLat{b.lon_max_deg, lat}})
      r = std::max(r, angular_distance_deg(c, q));
  }
  return r;
}

}  // namespace

bool GeoBox::contains(double lon_deg, double lat_deg) const {
  if (lat_deg < lat_min_deg || lat_deg > lat_max_deg) return false;
  return wrap_lon_deg(lon_deg, lon_min_deg) <= lon_max_deg;
}

std::span<const Passage> critical_passages() { return kPassages; }

namespace {
bool same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const auto x = static_cast<unsigned char>(a[k]), y = static_cast<unsigned char>(b[k]);
    const auto lx = x < 0x80 ? std::tolower(x) : x, ly = y < 0x80 ? std::tolower(y) : y;
    if (lx != ly) return false;
  }
  return true;
}
}  // namespace

const Passage* find_passage(const std::string& name) {
  for (const Passage& p : kPassages) {
    if (same_name(p.name, name)) return &p;
    std::string_view rest = p.aliases;
    while (!rest.empty()) {
      const std::size_t bar = rest.find('|');
      if (same_name(rest.substr(0, bar), name)) return &p;
      rest = bar == std::string_view::npos ? std::string_view() : rest.substr(bar + 1);
    }
  }
  return nullptr;
}

const char* passage_status_name(PassageStatus s) {
  switch (s) {
    case PassageStatus::kOpen:
      return "open";
    case PassageStatus::kClosed:
      return "closed";
    case PassageStatus::kNotResolvable:
      return "not resolvable";
  }
  return "?";
}

PassageResult judge_passage(const Passage& p, const PixelSet& filled, const Lattice& lattice, const PoleRotation& rot) {
  PassageResult res;
  res.name = p.name;
  res.box = p.box;
  const double dpx = lattice.pixel_deg();
  const GeoBox& b = p.box;
  const double mid_lat = 0.5 * (b.lat_min_deg + b.lat_max_deg);
  const double width = (b.lon_max_deg - b.lon_min_deg) * std::cos(mid_lat * kDegToRad);
  const double height = b.lat_max_deg - b.lat_min_deg;
  const LonLat centre{b.lon_min_deg + 0.5 * (b.lon_max_deg - b.lon_min_deg), mid_lat};
  const LonLat rc = geographic_to_lattice(rot, centre);
  // A Mercator pixel is Δ·cos φ′ of great circle on each side; a lon-lat one Δ along φ.
  const double pixel = lattice.mercator() ? dpx * std::cos(rc.lat_deg * kDegToRad) : dpx;
  if (width < pixel || height < pixel) {
    res.status = PassageStatus::kNotResolvable;
    res.note =
        fmt::format("box {:.2f}° × {:.2f}° (great-circle) is smaller than a pixel of {:g}°", width, height, pixel);
    return res;
  }
  // Local grid of lattice pixels around the box: rows by latitude, columns by the cap's λ extent.
  const double radius = box_radius_deg(b, centre) + dpx;
  const std::int64_t nx = lattice.nx, ny = lattice.ny;
  const std::int64_t j0 = std::max<std::int64_t>(
      0, static_cast<std::int64_t>(std::floor(lattice.row_of_lat(std::max(rc.lat_deg - radius, -90.0)))) - 1);
  const std::int64_t j1 = std::min<std::int64_t>(
      ny - 1, static_cast<std::int64_t>(std::ceil(lattice.row_of_lat(std::min(rc.lat_deg + radius, 90.0)))) + 1);
  std::int64_t i0 = 0, cols = nx;
  bool wrap = true;
  const double clat = std::cos(rc.lat_deg * kDegToRad), srad = std::sin(std::min(radius, 90.0) * kDegToRad);
  if (std::abs(rc.lat_deg) + radius < 89.0 && srad < clat) {
    const auto w = static_cast<std::int64_t>(std::ceil(std::asin(srad / clat) * kRadToDeg / dpx)) + 2;
    if (2 * w + 1 < nx) {
      double x = 0.0, y = 0.0;
      deg_to_lattice_xy(lattice, rc, x, y);
      i0 = static_cast<std::int64_t>(std::floor(x)) - w;
      cols = 2 * w + 1;
      wrap = false;
    }
  }
  const std::int64_t rows = j1 - j0 + 1;
  std::vector<unsigned char> cell(static_cast<std::size_t>(std::max<std::int64_t>(rows, 0) * cols), 0);
  const auto at = [cols](std::int64_t x, std::int64_t y) { return static_cast<std::size_t>(y * cols + x); };
  // Only pixel centres within `radius` of the box centre can be in the box: on the row at φ′ they
  // are those with cos(λ′ − λ′c) >= (cos r − sin φ′ sin φ′c) / (cos φ′ cos φ′c), an interval of λ′
  // (widened by two pixels) instead of the whole row near the rotated pole.
  const double cos_r = std::cos(std::min(radius, 180.0) * kDegToRad), sin_c = std::sin(rc.lat_deg * kDegToRad);
  double xc = 0.0, yc = 0.0;
  deg_to_lattice_xy(lattice, rc, xc, yc);
  const auto row_span = [&](std::int64_t y, std::int64_t& x_lo, std::int64_t& x_hi) {
    x_lo = 0;
    x_hi = cols - 1;
    if (!wrap) return;
    const double phi = pixel_center_lattice_deg(lattice, {0, j0 + y}).lat_deg * kDegToRad;
    const double den = std::cos(phi) * clat;
    if (den <= 1e-12) return;
    const double q = (cos_r - std::sin(phi) * sin_c) / den;
    if (q <= -1.0) return;
    if (q > 1.0) {
      x_hi = -1;
      return;
    }
    const double half = std::acos(q) * kRadToDeg / dpx + 2.0;
    if (2.0 * half + 1.0 >= static_cast<double>(cols)) return;
    x_lo = static_cast<std::int64_t>(std::floor(xc - 0.5 - half));  // pixel x has its centre at x + ½
    x_hi = static_cast<std::int64_t>(std::ceil(xc - 0.5 + half));
  };
  // Runs of kRun pixel centres along a row lie in the cap around the middle one of radius half
  // the run's length (an arc of the row's parallel, longer than the great circle). A run whose cap
  // misses the box holds no pixel of it; one whose cap lies inside the box, and inside or outside
  // each side, holds only pixels of that kind: both are decided without mapping their pixels. The
  // cap's radius has a margin of 1e-9° over the rounding of a pixel's coordinates, so the pixels
  // decided this way are those the per-pixel test would decide the same way.
  constexpr std::int64_t kRun = 64;
  struct RunCap {
    LonLat g;
    double r = 0.0, h = 0.0;  ///< radius; half-width in λ (only when `lon_box`)
    bool lon_box = false;     ///< the cap has a λ extent (does not reach a pole)
  };
  const auto run_cap = [&](std::int64_t y, std::int64_t xx0, std::int64_t xx1) {
    RunCap c;
    const double xm = 0.5 * static_cast<double>(xx0 + xx1) + 0.5;  // fractional x of the middle
    const LonLat m =
        lattice_xy_to_deg(lattice, wrap ? xm : xm + static_cast<double>(i0), static_cast<double>(j0 + y) + 0.5);
    c.r = 0.5 * static_cast<double>(xx1 - xx0) * dpx * std::cos(m.lat_deg * kDegToRad) + 1e-9;
    c.g = lattice_to_geographic(rot, m);
    if (std::abs(c.g.lat_deg) + c.r < 89.0) {
      c.h = std::asin(std::min(1.0, std::sin(c.r * kDegToRad) / std::cos(c.g.lat_deg * kDegToRad))) * kRadToDeg;
      c.lon_box = c.h < 180.0;
    }
    return c;
  };
  // -1: the cap misses `q`; +1: it lies inside `q`; 0: either may hold.
  const auto relation = [](const RunCap& c, const GeoBox& q) {
    if (c.g.lat_deg - c.r > q.lat_max_deg || c.g.lat_deg + c.r < q.lat_min_deg) return -1;
    if (!c.lon_box) return 0;
    const double w = wrap_lon_deg(c.g.lon_deg - c.h, q.lon_min_deg);  // the run's west end east of lon_min
    if (w > q.lon_max_deg && w + 2.0 * c.h < q.lon_min_deg + 360.0) return -1;
    const bool lat_in = c.g.lat_deg - c.r >= q.lat_min_deg && c.g.lat_deg + c.r <= q.lat_max_deg;
    return lat_in && w + 2.0 * c.h <= q.lon_max_deg ? 1 : 0;
  };
  // Pixel centres to geographic: sines and cosines once per lattice column and row, then the
  // rotation (the same bits as lattice_to_geographic of pixel_center_lattice_deg).
  std::vector<double> cos_lon(static_cast<std::size_t>(cols)), sin_lon(cos_lon.size());
  for (std::int64_t x = 0; x < cols; ++x) {
    const double lo = pixel_center_lattice_deg(lattice, {wrap_index(i0 + x, nx), j0}).lon_deg * kDegToRad;
    cos_lon[static_cast<std::size_t>(x)] = std::cos(lo);
    sin_lon[static_cast<std::size_t>(x)] = std::sin(lo);
  }
  std::int64_t in_a = 0, in_b = 0;
  // Records pixel (x, y) of lattice pixel px, in the box, with its side flags.
  const auto record = [&](std::int64_t x, std::int64_t y, const PixelIJ& px, unsigned char f) {
    if ((f & kSideA) != 0) ++in_a;
    if ((f & kSideB) != 0) ++in_b;
    ++res.pixels_in_box;
    if (filled.get(px.i, px.j)) {
      f |= kFilled;
      ++res.filled_in_box;
      if ((f & kSideA) != 0) ++res.filled_side_a;
      if ((f & kSideB) != 0) ++res.filled_side_b;
    }
    cell[at(x, y)] = f;
  };
  for (std::int64_t y = 0; y < rows; ++y) {
    std::int64_t x_lo = 0, x_hi = 0;
    row_span(y, x_lo, x_hi);
    const double row_lat = pixel_center_lattice_deg(lattice, {0, j0 + y}).lat_deg;
    const double cos_lat = std::cos(row_lat * kDegToRad), sin_lat = std::sin(row_lat * kDegToRad);
    for (std::int64_t xx = x_lo; xx <= x_hi; ++xx) {
      if ((xx - x_lo) % kRun == 0) {
        const std::int64_t xx1 = std::min(x_hi, xx + kRun - 1);
        const RunCap c = run_cap(y, xx, xx1);
        const int in_box = relation(c, b);
        if (in_box < 0) {
          xx = xx1;
          continue;
        }
        const int sa = in_box > 0 ? relation(c, p.side_a) : 0, sb = in_box > 0 ? relation(c, p.side_b) : 0;
        if (in_box > 0 && sa != 0 && sb != 0) {
          const auto f = static_cast<unsigned char>(kInBox | (sa > 0 ? kSideA : 0) | (sb > 0 ? kSideB : 0));
          for (std::int64_t k = xx; k <= xx1; ++k) {
            const std::int64_t x = wrap ? wrap_index(k, cols) : k;
            record(x, y, PixelIJ{wrap_index(i0 + x, nx), j0 + y}, f);
          }
          xx = xx1;
          continue;
        }
      }
      const std::int64_t x = wrap ? wrap_index(xx, cols) : xx;
      const PixelIJ px{wrap_index(i0 + x, nx), j0 + y};
      LonLat g;
      if (rot.identity())
        g = pixel_center_lattice_deg(lattice, px);
      else
        rot.to_geographic(cos_lon[static_cast<std::size_t>(x)], sin_lon[static_cast<std::size_t>(x)], cos_lat, sin_lat,
                          g.lon_deg, g.lat_deg);
      if (!b.contains(g.lon_deg, g.lat_deg)) continue;
      auto f = static_cast<unsigned char>(kInBox);
      if (p.side_a.contains(g.lon_deg, g.lat_deg)) f |= kSideA;
      if (p.side_b.contains(g.lon_deg, g.lat_deg)) f |= kSideB;
      record(x, y, px, f);
    }
  }
  if (in_a == 0 || in_b == 0) {
    res.status = PassageStatus::kNotResolvable;
    res.note = fmt::format("side {} ({}) holds no pixel centre", in_a == 0 ? "A" : "B",
                           in_a == 0 ? p.side_a_name : p.side_b_name);
    return res;
  }
  // 4-connected search through filled in-box pixels from side A.
  std::vector<std::int64_t> stack;
  for (std::int64_t q = 0; q < rows * cols; ++q) {
    auto& f = cell[static_cast<std::size_t>(q)];
    if ((f & (kSideA | kFilled)) == (kSideA | kFilled)) {
      f |= kSeen;
      stack.push_back(q);
    }
  }
  bool open = false;
  while (!stack.empty() && !open) {
    const std::int64_t q = stack.back();
    stack.pop_back();
    if ((cell[static_cast<std::size_t>(q)] & kSideB) != 0) {
      open = true;
      break;
    }
    const std::int64_t x = q % cols, y = q / cols;
    std::int64_t xl = x - 1, xr = x + 1;
    if (wrap) {
      xl = wrap_index(xl, cols);
      xr = wrap_index(xr, cols);
    }
    const std::int64_t nb[4][2] = {{xl, y}, {xr, y}, {x, y - 1}, {x, y + 1}};
    for (const auto& n : nb) {
      if (n[0] < 0 || n[0] >= cols || n[1] < 0 || n[1] >= rows) continue;
      auto& f = cell[at(n[0], n[1])];
      if ((f & (kInBox | kFilled)) != (kInBox | kFilled) || (f & kSeen) != 0) continue;
      f |= kSeen;
      stack.push_back(n[1] * cols + n[0]);
    }
  }
  if (open) {
    res.status = PassageStatus::kOpen;
  } else {
    res.status = PassageStatus::kClosed;
    if (res.filled_side_a == 0 || res.filled_side_b == 0)
      res.note = fmt::format("no filled pixel on side {} ({})", res.filled_side_a == 0 ? "A" : "B",
                             res.filled_side_a == 0 ? p.side_a_name : p.side_b_name);
    else
      res.note = fmt::format("{} and {} not connected inside the box", p.side_a_name, p.side_b_name);
  }
  return res;
}

std::vector<PassageResult> judge_passages(std::span<const Passage> passages, const PixelSet& filled,
                                          const Lattice& lattice, const PoleRotation& rot) {
  // Each passage is judged on its own: one per thread, results in table order.
  std::vector<PassageResult> out(passages.size());
  const auto n = static_cast<std::int64_t>(passages.size());
#pragma omp parallel for default(none) shared(passages, filled, lattice, rot, out, n) \
    schedule(dynamic, 1) if (filled.nx() * filled.ny() >= (std::int64_t{1} << 22))
  for (std::int64_t k = 0; k < n; ++k)
    out[static_cast<std::size_t>(k)] = judge_passage(passages[static_cast<std::size_t>(k)], filled, lattice, rot);
  return out;
}

PassageResult judge_passage(const Passage& p, const Bitmap& filled, const Lattice& lattice, const PoleRotation& rot) {
  return judge_passage(p, ConstBitmapSet(filled), lattice, rot);
}

std::vector<PassageResult> judge_passages(std::span<const Passage> passages, const Bitmap& filled,
                                          const Lattice& lattice, const PoleRotation& rot) {
  return judge_passages(passages, ConstBitmapSet(filled), lattice, rot);
}

Json to_json(std::span<const PassageResult> results) {
  Json arr = Json::array();
  for (const PassageResult& r : results) {
    arr.push_back(Json{{"name", r.name},
                       {"status", passage_status_name(r.status)},
                       {"box", {r.box.lon_min_deg, r.box.lon_max_deg, r.box.lat_min_deg, r.box.lat_max_deg}},
                       {"pixels_in_box", r.pixels_in_box},
                       {"filled_in_box", r.filled_in_box},
                       {"filled_side_a", r.filled_side_a},
                       {"filled_side_b", r.filled_side_b},
                       {"carved", r.carved},
                       {"note", r.note}});
  }
  return arr;
}

std::vector<std::string> format_passage_table(std::span<const PassageResult> results) {
  std::vector<std::string> lines;
  lines.push_back(fmt::format("{:<18} {:<14} {:<34} {:>13}  {}", "passage", "status", "box lon x lat (deg)",
                              "filled/pixels", "note"));
  int n_open = 0, n_closed = 0, n_nr = 0;
  for (const PassageResult& r : results) {
    if (r.status == PassageStatus::kOpen) ++n_open;
    if (r.status == PassageStatus::kClosed) ++n_closed;
    if (r.status == PassageStatus::kNotResolvable) ++n_nr;
    const std::string box = fmt::format("[{:.2f}, {:.2f}] x [{:.2f}, {:.2f}]", r.box.lon_min_deg, r.box.lon_max_deg,
                                        r.box.lat_min_deg, r.box.lat_max_deg);
    lines.push_back(fmt::format("{:<18} {:<14} {:<34} {:>13}  {}", r.name, passage_status_name(r.status), box,
                                fmt::format("{}/{}", r.filled_in_box, r.pixels_in_box), r.note));
  }
  lines.push_back(fmt::format("passages: {} open, {} closed, {} not resolvable", n_open, n_closed, n_nr));
  return lines;
}

}  // namespace aq::mask
