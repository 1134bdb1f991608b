// SPDX-License-Identifier: GPL-3.0-or-later
// Critical passages: open/closed/not resolvable on drawn masks, with and without pole rotation,
// and the consistency of the built-in table.
#include "mask/passages.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "mask/lattice_coords.hpp"
#include "unit/mask/mask_drawing.hpp"

namespace aq::mask::unit_mask_passages_test {
namespace {

// 1° lattice; the drawing is pasted with its pixel (0, 0) at (200, 100): λ 20..28, φ 10..15.
const Lattice kLat = Lattice::make(1.0, 0, -180.0);
constexpr std::int64_t kI0 = 200, kJ0 = 100;

Bitmap pasted(const std::vector<std::string_view>& rows) {
  Bitmap f(kLat.nx, kLat.ny);
  test::paste(f, test::draw(rows), kI0, kJ0);
  return f;
}

// Box across the drawing; side A = its westernmost pixel column, side B = its easternmost.
const Passage kStrait{
    "Test strait",           "West Sea", "East Sea", {20.0, 28.0, 10.0, 15.0}, {20.0, 21.0, 10.0, 15.0},
    {27.0, 28.0, 10.0, 15.0}};

TEST(Passages, OpenWhenFilledPixelsJoinTheSidesInsideTheBox) {
  const Bitmap f = pasted({
      // clang-format off
      "........",
      "###.....",
      "..#.....",
      "..######",
      "........",
      // clang-format on
  });
  const PassageResult r = judge_passage(kStrait, f, kLat, PoleRotation());
  EXPECT_EQ(r.status, PassageStatus::kOpen);
  EXPECT_EQ(r.pixels_in_box, 40);
  EXPECT_EQ(r.filled_in_box, 10);
  EXPECT_EQ(r.filled_side_a, 1);
  EXPECT_EQ(r.filled_side_b, 1);
  EXPECT_TRUE(r.note.empty());
}

TEST(Passages, ClosedByAGapOrACornerTouch) {
  const Bitmap gap = pasted({
      // clang-format off
      "........",
      "###.....",
      "..#.....",
      "..###.##",
      "........",
      // clang-format on
  });
  PassageResult r = judge_passage(kStrait, gap, kLat, PoleRotation());
  EXPECT_EQ(r.status, PassageStatus::kClosed);
  EXPECT_THAT(r.note, testing::HasSubstr("not connected"));
  const Bitmap corner = pasted({
      // clang-format off
      "........",
      "###.....",
      "...#####",
      "........",
      "........",
      // clang-format on
  });
  EXPECT_EQ(judge_passage(kStrait, corner, kLat, PoleRotation()).status, PassageStatus::kClosed);
  const Bitmap dry_side = pasted({
      // clang-format off
      "........",
      ".#######",
      "........",
      "........",
      "........",
      // clang-format on
  });
  r = judge_passage(kStrait, dry_side, kLat, PoleRotation());
  EXPECT_EQ(r.status, PassageStatus::kClosed);
  EXPECT_THAT(r.note, testing::HasSubstr("side A (West Sea)"));
}

TEST(Passages, PathsOutsideTheBoxDoNotCount) {
  // The pixels join the sides only through row 5 of the drawing, which is north of the box.
  Bitmap f = pasted({
      // clang-format off
      "########",
      "#......#",
      "#......#",
      "#......#",
      "#......#",
      "#......#",
      // clang-format on
  });
  EXPECT_EQ(judge_passage(kStrait, f, kLat, PoleRotation()).status, PassageStatus::kClosed);
  f.set(kI0 + 3, kJ0 + 2);  // not enough: a single pixel in the middle
  EXPECT_EQ(judge_passage(kStrait, f, kLat, PoleRotation()).status, PassageStatus::kClosed);
  for (std::int64_t i = 1; i < 7; ++i) f.set(kI0 + i, kJ0 + 2);
  EXPECT_EQ(judge_passage(kStrait, f, kLat, PoleRotation()).status, PassageStatus::kOpen);
}

TEST(Passages, NotResolvableBelowAPixel) {
  const Passage tiny{"Tiny", "a", "b", {20.1, 20.6, 10.1, 10.9}, {20.1, 20.2, 10.1, 10.9}, {20.5, 20.6, 10.1, 10.9}};
  const Bitmap f(kLat.nx, kLat.ny);
  const PassageResult r = judge_passage(tiny, f, kLat, PoleRotation());
  EXPECT_EQ(r.status, PassageStatus::kNotResolvable);
  EXPECT_THAT(r.note, testing::HasSubstr("smaller than a pixel"));
  // A box of two pixels whose side A holds no pixel centre.
  const Passage thin_side{
      "Thin", "a", "b", {20.0, 22.0, 10.0, 12.0}, {20.0, 20.4, 10.0, 12.0}, {21.0, 22.0, 10.0, 12.0}};
  const PassageResult r2 = judge_passage(thin_side, f, kLat, PoleRotation());
  EXPECT_EQ(r2.status, PassageStatus::kNotResolvable);
  EXPECT_THAT(r2.note, testing::HasSubstr("side A"));
}

TEST(Passages, WorkOnARotatedLatticeAndAcrossTheSeam) {
  // Fill the rotated-lattice pixels whose geographic centre lies in a geographic channel; the box
  // is geographic and straddles λ = 180.
  const PoleRotation rot(-44.858333, 78.141667);
  const Lattice l = Lattice::make(1.0, 2, -180.0);  // 0.25° pixels
  const Passage p{"Seam strait",
                  "west",
                  "east",
                  {176.0, 184.0, -42.0, -38.0},
                  {176.0, 177.0, -42.0, -38.0},
                  {183.0, 184.0, -42.0, -38.0}};
  const auto channel = [](double lon, double lat, bool cut) {
    const double x = wrap_lon_deg(lon, 170.0);
    if (cut && x > 179.5 && x < 180.5) return false;
    return lat > -40.6 && lat < -39.4 && x > 172.0 && x < 188.0;
  };
  for (const bool cut : {false, true}) {
    Bitmap f(l.nx, l.ny);
    for (std::int64_t j = 0; j < l.ny; ++j)
      for (std::int64_t i = 0; i < l.nx; ++i) {
        const LonLat g = lattice_to_geographic(rot, pixel_center_lattice_deg(l, {i, j}));
        if (channel(g.lon_deg, g.lat_deg, cut)) f.set(i, j);
      }
    const PassageResult r = judge_passage(p, f, l, rot);
    EXPECT_EQ(r.status, cut ? PassageStatus::kClosed : PassageStatus::kOpen) << "cut=" << cut;
    EXPECT_GT(r.filled_side_a, 4);
    EXPECT_GT(r.filled_side_b, 4);
    // Box area / pixel area; a rotated-lattice pixel covers 0.25°·0.25°·cos φ' (φ' rotated latitude).
    const LonLat rc = geographic_to_lattice(rot, {180.0, -40.0});
    const double expected = 8.0 * 4.0 * std::cos(40.0 * kDegToRad) / (0.0625 * std::cos(rc.lat_deg * kDegToRad));
    EXPECT_NEAR(static_cast<double>(r.pixels_in_box), expected, 0.05 * expected);
  }
}

// The judge scans only the runs of pixels that can reach the box (around the rotated pole a box's
// cap takes whole Mercator rows). Every passage of the table, on the Mercator lattice of the
// Greenland frame (Nares, Fram and Davis lie next to the rotated pole), gives what a scan of every
// pixel of the lattice gives: the pixels and filled pixels in the box and on each side, and
// whether the filled in-box pixels join the sides.
TEST(Passages, RotatedMercatorJudgeEqualsAScanOfTheWholeLattice) {
  const PoleRotation rot(-44.858333, 78.141667);
  const Lattice l = Lattice::make_mercator(2.0, 3, -180.0, 86.5);  // 0.25° pixels
  std::vector<LonLat> centre(static_cast<std::size_t>(l.nx * l.ny));
  Bitmap f(l.nx, l.ny);
  for (std::int64_t j = 0; j < l.ny; ++j)
    for (std::int64_t i = 0; i < l.nx; ++i) {
      const LonLat g = lattice_to_geographic(rot, pixel_center_lattice_deg(l, {i, j}));
      centre[static_cast<std::size_t>(j * l.nx + i)] = g;
      // Water with islands and cuts at every scale: some straits open, some closed.
      const double w = std::sin(0.9 * g.lon_deg * kDegToRad * 7.0) * std::cos(g.lat_deg * kDegToRad * 5.0) +
                       0.6 * std::sin(g.lon_deg * 1.3 + g.lat_deg * 2.1);
      if (w > -0.35) f.set(i, j);
    }
  int open = 0, closed = 0;
  for (const Passage& p : critical_passages()) {
    std::int64_t in_box = 0, filled = 0, side_a = 0, side_b = 0;
    std::vector<unsigned char> in(centre.size(), 0), seen(centre.size(), 0);
    std::vector<std::int64_t> stack;
    for (std::int64_t q = 0; q < l.nx * l.ny; ++q) {
      const LonLat g = centre[static_cast<std::size_t>(q)];
      if (!p.box.contains(g.lon_deg, g.lat_deg)) continue;
      ++in_box;
      if (!f.get(q % l.nx, q / l.nx)) continue;
      ++filled;
      in[static_cast<std::size_t>(q)] = 1;
      if (p.side_a.contains(g.lon_deg, g.lat_deg)) {
        ++side_a;
        seen[static_cast<std::size_t>(q)] = 1;
        stack.push_back(q);
      }
      if (p.side_b.contains(g.lon_deg, g.lat_deg)) ++side_b;
    }
    bool joined = false;
    while (!stack.empty() && !joined) {
      const std::int64_t q = stack.back();
      stack.pop_back();
      const LonLat g = centre[static_cast<std::size_t>(q)];
      joined = p.side_b.contains(g.lon_deg, g.lat_deg);
      const std::int64_t i = q % l.nx, j = q / l.nx;
      for (const auto& [di, dj] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
        const std::int64_t jj = j + dj;
        if (jj < 0 || jj >= l.ny) continue;
        const std::int64_t n = jj * l.nx + wrap_index(i + di, l.nx);
        if (in[static_cast<std::size_t>(n)] == 0 || seen[static_cast<std::size_t>(n)] != 0) continue;
        seen[static_cast<std::size_t>(n)] = 1;
        stack.push_back(n);
      }
    }
    const PassageResult r = judge_passage(p, f, l, rot);
    EXPECT_EQ(r.pixels_in_box, in_box) << p.name;
    EXPECT_EQ(r.filled_in_box, filled) << p.name;
    EXPECT_EQ(r.filled_side_a, side_a) << p.name;
    EXPECT_EQ(r.filled_side_b, side_b) << p.name;
    if (r.status == PassageStatus::kNotResolvable) continue;
    EXPECT_EQ(r.status == PassageStatus::kOpen, joined) << p.name;
    (joined ? open : closed)++;
  }
  EXPECT_GT(open, 3);  // the field leaves both kinds
  EXPECT_GT(closed, 3);
  // The judges of the whole table in one call (in parallel) are the same, in table order.
  const std::vector<PassageResult> all = judge_passages(critical_passages(), f, l, rot);
  ASSERT_EQ(all.size(), critical_passages().size());
  for (std::size_t k = 0; k < all.size(); ++k) {
    const PassageResult one = judge_passage(critical_passages()[k], f, l, rot);
    EXPECT_EQ(all[k].name, one.name);
    EXPECT_EQ(all[k].status, one.status);
    EXPECT_EQ(all[k].pixels_in_box, one.pixels_in_box);
  }
}

TEST(Passages, TableHasTheNamedStraitsWithSidesInsideTheirBoxes) {
  const auto t = critical_passages();
  ASSERT_EQ(t.size(), 37U);
  std::set<std::string> names;
  for (const Passage& p : t) {
    names.insert(p.name);
    for (const GeoBox* s : {&p.side_a, &p.side_b}) {
      EXPECT_TRUE(p.box.contains(s->lon_min_deg, s->lat_min_deg)) << p.name;
      EXPECT_TRUE(p.box.contains(s->lon_max_deg, s->lat_max_deg)) << p.name;
      EXPECT_LT(s->lon_min_deg, s->lon_max_deg) << p.name;
      EXPECT_LT(s->lat_min_deg, s->lat_max_deg) << p.name;
    }
    // The sides do not overlap.
    const bool lon_apart = p.side_a.lon_max_deg <= p.side_b.lon_min_deg || p.side_b.lon_max_deg <= p.side_a.lon_min_deg;
    const bool lat_apart = p.side_a.lat_max_deg <= p.side_b.lat_min_deg || p.side_b.lat_max_deg <= p.side_a.lat_min_deg;
    EXPECT_TRUE(lon_apart || lat_apart) << p.name;
  }
  for (const char* n : {"Gibraltar",      "Bosphorus", "Bering",     "Bab-el-Mandeb", "Hormuz",     "Malacca/Singapore",
                        "Lombok",         "Torres",    "Bass",       "Fram",          "Nares",      "Davis",
                        "Belle Isle",     "Florida",   "Yucatan",    "Drake",         "Denmark",    "Dover",
                        "Danish straits", "Kerch",     "Tsugaru",    "Korea",         "La Perouse", "Taiwan",
                        "Messina",        "Sicily",    "Luzon",      "Hudson",        "Barrow",     "Juan de Fuca",
                        "Dardanelles",    "Oresund",   "Great Belt", "Little Belt",   "Chesapeake", "Delaware",
                        "Gorlo"})
    EXPECT_EQ(names.count(n), 1U) << n;
  // Every strait has a nominal sill depth for the carving (mask/carving.hpp).
  for (const Passage& p : t) {
    EXPECT_GT(p.sill_depth_m, 0.0) << p.name;
    EXPECT_LT(p.sill_depth_m, 4000.0) << p.name;
  }
}

// Names and aliases, without case for ASCII letters; the issue's names among them.
TEST(Passages, FoundByNameOrAliasWithoutCase) {
  ASSERT_NE(find_passage("Gibraltar"), nullptr);
  EXPECT_STREQ(find_passage("gibraltar")->name, "Gibraltar");
  EXPECT_STREQ(find_passage("Strait of Gibraltar")->name, "Gibraltar");
  EXPECT_STREQ(find_passage("Øresund")->name, "Oresund");
  EXPECT_STREQ(find_passage("ORESUND")->name, "Oresund");
  EXPECT_STREQ(find_passage("Bab el Mandeb")->name, "Bab-el-Mandeb");
  EXPECT_STREQ(find_passage("Storebælt")->name, "Great Belt");
  EXPECT_STREQ(find_passage("Bosporus")->name, "Bosphorus");
  EXPECT_STREQ(find_passage("dover strait")->name, "Dover");
  EXPECT_EQ(find_passage("Gibralter"), nullptr);
  EXPECT_EQ(find_passage(""), nullptr);
  EXPECT_EQ(find_passage("Strait"), nullptr);
}

TEST(Passages, JsonAndTextTable) {
  const Bitmap f = pasted({"........", "########", "........", "........", "........"});
  const std::vector<PassageResult> rs = judge_passages(std::span<const Passage>(&kStrait, 1), f, kLat, PoleRotation());
  const Json j = to_json(rs);
  ASSERT_EQ(j.size(), 1U);
  EXPECT_EQ(j[0]["name"], "Test strait");
  EXPECT_EQ(j[0]["status"], "open");
  EXPECT_EQ(j[0]["box"][1], 28.0);
  const std::vector<std::string> lines = format_passage_table(rs);
  ASSERT_EQ(lines.size(), 3U);
  EXPECT_THAT(lines[1], testing::HasSubstr("Test strait"));
  EXPECT_THAT(lines[1], testing::HasSubstr("open"));
  EXPECT_THAT(lines[1], testing::HasSubstr("8/40"));
  EXPECT_EQ(lines[2], "passages: 1 open, 0 closed, 0 not resolvable");
}

}  // namespace
}  // namespace aq::mask::unit_mask_passages_test
