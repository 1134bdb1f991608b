// SPDX-License-Identifier: GPL-3.0-or-later
// Carving passages, channels and blockages (mask/carving.hpp) and the dropped-sea report
// (mask/dropped_seas.hpp) on a synthetic world of 0.5° pixels: two basins joined through land by
// a channel one pixel wide (closed at K = 2 unless a transect carves it), a wide channel (closed
// by a blockage line), a river burned into the land (kept at K = 3), a diagonal transect that
// opens the way at every cursor on the lon-lat, Mercator and rotated lattices; the dropped east
// basin's area against the closed form on WGS84, its contact and land gap; the line files' errors.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "mask/carving.hpp"
#include "mask/dropped_seas.hpp"
#include "mask/wet_area.hpp"

namespace aq::mask::unit_mask_carving_test {
namespace {

// A scratch folder removed at the end of the test (support/temp_dir.hpp's aq::testing would hide
// ::testing inside aq::mask in the unity build).
class Scratch {
 public:
  Scratch() {
    std::string t = (std::filesystem::temp_directory_path() / "aq_carving_XXXXXX").string();
    if (::mkdtemp(t.data()) == nullptr) throw std::runtime_error("mkdtemp");
    path_ = t;
  }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  std::filesystem::path operator/(const std::string& n) const { return path_ / n; }

 private:
  std::filesystem::path path_;
};

enum class Strait { kNone, kOnePixel, kTwoPixels, kWide };

// A 0.05° raster over 10°W..40°E, 10°S..40°N (no data outside: dry): -1000 m in the west basin
// (0.75..9.75°E) and the east basin (12.25..21.25°E), both 0.75..9.75°N, land (+50 m) between
// and around; a strait through the land at 9.75..12.25°E. Water edges at .25/.75: halfway between
// the lattice's vertices (multiples of 0.5°), so each vertex is clearly wet or dry.
raster::Bathymetry world(Strait s) {
  const std::int64_t nc = 1001, nr = 1001;
  std::vector<float> v(static_cast<std::size_t>(nc * nr), 50.0F);
  for (std::int64_t r = 0; r < nr; ++r)
    for (std::int64_t c = 0; c < nc; ++c) {
      const double lon = -10.0 + 0.05 * static_cast<double>(c), lat = -10.0 + 0.05 * static_cast<double>(r);
      const bool rows = lat > 0.75 && lat < 9.75;
      bool wet = rows && ((lon > 0.75 && lon < 9.75) || (lon > 12.25 && lon < 21.25));
      if (lon >= 9.75 && lon <= 12.25) {
        if (s == Strait::kOnePixel) wet = lat > 4.75 && lat < 5.75;   // vertex rows 5.0, 5.5: one pixel row
        if (s == Strait::kTwoPixels) wet = lat > 4.75 && lat < 6.25;  // two pixel rows
        if (s == Strait::kWide) wet = lat > 2.75 && lat < 7.25;       // eight pixel rows
      }
      if (wet) v[static_cast<std::size_t>(r * nc + c)] = -1000.0F;
    }
  return raster::Bathymetry::from_grid(std::move(v), nc, nr, -10.0, -10.0, 0.05, 0.05);
}

// A GeoJSON FeatureCollection of LineStrings with properties.
struct Line {
  std::vector<std::pair<double, double>> pts;
  std::string props;  // JSON object members, e.g. "\"kind\": \"blockage\""
};
std::string write_lines(const Scratch& dir, const std::string& name, const std::vector<Line>& lines) {
  const auto path = dir / name;
  std::ofstream f(path);
  f << R"({"type": "FeatureCollection", "features": [)";
  for (std::size_t k = 0; k < lines.size(); ++k) {
    f << (k ? ", " : "") << R"({"type": "Feature", "properties": {)" << lines[k].props
      << R"(}, "geometry": {"type": "LineString", "coordinates": [)";
    for (std::size_t q = 0; q < lines[k].pts.size(); ++q)
      f << (q ? ", " : "") << "[" << lines[k].pts[q].first << ", " << lines[k].pts[q].second << "]";
    f << "]}}";
  }
  f << "]}\n";
  return path.string();
}

struct MaskRun {
  Lattice lattice;
  PoleRotation rot;
  Carving carving;
  WetArea area;
};

MaskRun run(raster::Bathymetry& b, const config::MaskOptions& o, const Lattice& lat = Lattice::make(4.0, 3, -180.0),
            const PoleRotation& rot = PoleRotation()) {
  MaskRun r{lat, rot, {}, {}};
  b.set_edits(nullptr);
  r.carving = plan_carving(o, lat, rot, b);
  b.set_edits(r.carving.edits);
  r.area = compute_wet_area(b, lat, rot, o, Logger::null(), nullptr);
  return r;
}

bool filled_at(const MaskRun& r, double lon, double lat) {
  double x = 0.0, y = 0.0;
  deg_to_lattice_xy(r.lattice, geographic_to_lattice(r.rot, {lon, lat}), x, y);
  return r.area.filled.get(wrap_index(static_cast<std::int64_t>(std::floor(x)), r.lattice.nx),
                           static_cast<std::int64_t>(std::floor(y)));
}

config::MaskOptions options(int k) {
  config::MaskOptions o;
  o.cursor = k;
  o.seeds = {{5.0, 5.0}};
  o.passages = false;
  return o;
}

TEST(Carving, OnePixelChannelClosedAtK2OpenWithATransect) {
  Scratch dir;
  raster::Bathymetry b = world(Strait::kOnePixel);
  config::MaskOptions o = options(2);
  const MaskRun closed = run(b, o);
  EXPECT_TRUE(filled_at(closed, 5.0, 5.0));
  EXPECT_FALSE(filled_at(closed, 17.0, 5.0));
  EXPECT_TRUE(closed.area.wet.get(380, 190));  // the channel pixel (10..10.5°E, 5..5.5°N) is wet
  o.cursor = 1;
  EXPECT_TRUE(filled_at(run(b, o), 17.0, 5.0));  // K = 1 passes it
  o.cursor = 2;
  o.transects = write_lines(dir, "t.geojson", {{{{7.0, 5.25}, {15.0, 5.25}}, R"("name": "the strait")"}});
  const MaskRun open = run(b, o);
  EXPECT_TRUE(filled_at(open, 17.0, 5.0));
  ASSERT_EQ(open.carving.lines.size(), 1U);
  const CarvedLine& l = open.carving.lines[0];
  EXPECT_EQ(l.name, "the strait");
  EXPECT_EQ(l.kind, LineKind::kPassage);
  EXPECT_DOUBLE_EQ(l.depth_m, 1000.0);  // the raster's sill on the deepest path along the line
  EXPECT_NE(l.depth_from.find("raster's sill"), std::string::npos) << l.depth_from;
  // Half-width ((K + 1)/√2 + 1/4) pixels of 0.5° (55.6 km per degree of arc).
  EXPECT_NEAR(l.half_width_km_max, (3.0 / std::sqrt(2.0) + 0.25) * 0.5 * 111.195, 0.1);
  EXPECT_NEAR(l.length_km, 8.0 * 111.195 * std::cos(5.25 * kDegToRad), 1.0);
  // The carved land is as deep as the line's depth; the basins keep the raster's water.
  EXPECT_EQ(b.sample(11.0, 5.25), -1000.0);
  EXPECT_EQ(b.sample(11.0, 5.9), -1000.0);  // within the corridor, off the old channel
  EXPECT_EQ(b.sample(11.0, 8.0), 50.0);     // outside it
}

TEST(Carving, DiagonalTransectOpensTheWayAtEveryCursorOnEveryLattice) {
  Scratch dir;
  raster::Bathymetry b = world(Strait::kNone);
  const std::string t = write_lines(dir, "diag.geojson", {{{{6.0, 2.0}, {16.0, 8.5}}, ""}});
  const PoleRotation rotated(-44.858333, 78.141667);
  for (int k = 1; k <= 4; ++k)
    for (int kind = 0; kind < 3; ++kind) {
      config::MaskOptions o = options(k);
      const Lattice lat = kind == 1 ? Lattice::make_mercator(4.0, 3, -180.0, 86.5) : Lattice::make(4.0, 3, -180.0);
      const PoleRotation rot = kind == 2 ? rotated : PoleRotation();
      EXPECT_FALSE(filled_at(run(b, o, lat, rot), 17.0, 5.0)) << "K=" << k << " lattice " << kind;
      o.transects = t;
      const MaskRun r = run(b, o, lat, rot);
      EXPECT_TRUE(filled_at(r, 17.0, 5.0)) << "K=" << k << " lattice " << kind;
      EXPECT_DOUBLE_EQ(r.carving.lines.at(0).depth_m, o.channel_depth_m);
      EXPECT_NE(r.carving.lines[0].depth_from.find("mask.channel_depth_m"), std::string::npos);  // land all across
    }
}

TEST(Carving, BlockageClosesAWideChannel) {
  Scratch dir;
  raster::Bathymetry b = world(Strait::kWide);
  config::MaskOptions o = options(2);
  EXPECT_TRUE(filled_at(run(b, o), 17.0, 5.0));
  o.transects = write_lines(dir, "b.geojson", {{{{11.1, 1.0}, {11.1, 9.5}}, R"("kind": "blockage", "name": "dam")"}});
  for (int k : {1, 2}) {
    o.cursor = k;
    const MaskRun r = run(b, o);
    EXPECT_FALSE(filled_at(r, 17.0, 5.0)) << "K=" << k;
    ASSERT_EQ(r.carving.lines.size(), 1U);
    EXPECT_EQ(r.carving.lines[0].kind, LineKind::kBlockage);
    EXPECT_EQ(r.carving.lines[0].height_m, kBlockageHeightM);
    EXPECT_EQ(b.sample(11.1, 5.0), kBlockageHeightM);
  }
}

TEST(Carving, RiverSurvivesACursorOfThree) {
  Scratch dir;
  raster::Bathymetry b = world(Strait::kNone);
  config::MaskOptions o = options(3);
  o.min_depth_m = 2.0;
  EXPECT_FALSE(filled_at(run(b, o), 5.2, 20.0));
  o.channels = write_lines(dir, "river.geojson",
                           {{{{5.2, 8.0}, {5.2, 18.0}, {7.0, 25.0}}, R"("width_m": 800, "depth_m": 1.5)"}});
  const MaskRun r = run(b, o);
  for (const double lat : {12.0, 16.0, 20.0, 23.0})
    EXPECT_TRUE(filled_at(r, 5.2 + (lat > 18.0 ? (lat - 18.0) * 1.8 / 7.0 : 0.0), lat)) << lat;
  ASSERT_EQ(r.carving.lines.size(), 1U);
  const CarvedLine& l = r.carving.lines[0];
  EXPECT_EQ(l.kind, LineKind::kChannel);
  EXPECT_DOUBLE_EQ(l.depth_m, 3.0);  // 1.5 m stated, deepened to 1 m below h = 2 m
  EXPECT_EQ(b.sample(5.2, 12.0), -3.0);
  // 800 m is narrower than the cursor: the corridor is the K-pixel one.
  EXPECT_NEAR(l.half_width_km_min, (4.0 / std::sqrt(2.0) + 0.25) * 0.5 * 111.195, 0.1);
  // A stated width wider than that wins.
  o.channels = write_lines(dir, "wide.geojson", {{{{5.2, 8.0}, {5.2, 18.0}}, R"("width_m": 500000)"}});
  const MaskRun w = run(b, o);
  EXPECT_NEAR(w.carving.lines.at(0).half_width_km_min, 250.0, 0.5);
  EXPECT_DOUBLE_EQ(w.carving.lines[0].depth_m, o.channel_depth_m);
}

// A floodplain (h < 0): a carved passage is sea at the datum (at least 1 m below 0 m, whatever
// the line states), so the basin behind it is reached through sea, not across land; a blockage
// stays above the floodplain's top.
TEST(Carving, FloodplainKeepsPassagesBelowTheDatumAndBlockagesAboveItsTop) {
  Scratch dir;
  raster::Bathymetry b = world(Strait::kNone);
  config::MaskOptions o = options(2);
  o.min_depth_m = -20.0;  // land up to +20 m; the +50 m land stays dry
  EXPECT_FALSE(filled_at(run(b, o), 17.0, 5.0));
  o.transects = write_lines(dir, "t.geojson", {{{{7.0, 5.25}, {15.0, 5.25}}, R"("depth_m": 0.5)"}});
  const MaskRun r = run(b, o);
  EXPECT_TRUE(filled_at(r, 17.0, 5.0));
  ASSERT_EQ(r.carving.lines.size(), 1U);
  EXPECT_DOUBLE_EQ(r.carving.lines[0].depth_m, 1.0);  // 0.5 m stated, deepened to 1 m below max(h, 0)
  EXPECT_EQ(b.sample(11.0, 5.25), -1.0);
  EXPECT_GT(r.area.datum_wet_pixels, 0);
  EXPECT_EQ(r.area.inland_sea_pixels, 0);  // the east basin is reached through sea at the datum
  // A blockage across the carved passage: above the floodplain's top (+20 m), so it cuts it.
  o.transects = write_lines(dir, "tb.geojson",
                            {{{{7.0, 5.25}, {15.0, 5.25}}, ""}, {{{11.1, 1.0}, {11.1, 9.5}}, R"("kind": "blockage")"}});
  const MaskRun cut = run(b, o);
  EXPECT_FALSE(filled_at(cut, 17.0, 5.0));
  ASSERT_EQ(cut.carving.lines.size(), 2U);
  const CarvedLine& dam = cut.carving.lines[cut.carving.lines[0].kind == LineKind::kBlockage ? 0 : 1];
  EXPECT_EQ(dam.kind, LineKind::kBlockage);
  EXPECT_DOUBLE_EQ(dam.height_m, 21.0);  // the default 10 m raised to 1 m above -h
  EXPECT_EQ(b.sample(11.1, 5.25), 21.0);
}

TEST(DroppedSeas, AreaContactAndLandGapOfTheEastBasin) {
  raster::Bathymetry b = world(Strait::kNone);
  const MaskRun r = run(b, options(2));
  const DroppedSeas d = find_dropped_seas(r.area.wet, r.area.filled, r.lattice, r.rot, 2, 1e4, {});
  ASSERT_EQ(d.large.size(), 1U);
  const DroppedSea& s = d.large[0];
  // Wet pixels 12.5..21°E × 1..9.5°N (17 × 17): the rectangle's area on WGS84 in closed form.
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f), e = std::sqrt(e2);
  const auto g = [&](double lat_deg) {
    const double x = std::sin(lat_deg * kDegToRad);
    return x / (1.0 - e2 * x * x) + std::log((1.0 + e * x) / (1.0 - e * x)) / (2.0 * e);
  };
  const double want = a * a * (1.0 - e2) / 2.0 * (8.5 * kDegToRad) * (g(9.5) - g(1.0)) / 1e6;
  EXPECT_EQ(s.pixels, 17 * 17);
  EXPECT_NEAR(s.area_km2, want, 1e-9 * want);
  EXPECT_NEAR(s.area_km2, 8.5 * 8.5 * 12309.0, 0.01 * 8.5 * 8.5 * 12309.0);  // ~12 309 km² per square degree
  EXPECT_NEAR(s.centre.lon_deg, 16.75, 0.01);
  EXPECT_NEAR(s.centre.lat_deg, 5.25, 0.05);
  EXPECT_EQ(s.name, "");
  EXPECT_EQ(s.connecting_cursor, 0);
  EXPECT_EQ(s.contact_pixels, 0);
  EXPECT_EQ(s.land_gap_pixels, 6);  // columns 9.5..12.5°E
  EXPECT_NEAR(s.gap_at.lon_deg, 12.75, 1e-9);
  EXPECT_NE(s.keep.find("mask.transects"), std::string::npos) << s.keep;
  EXPECT_NE(describe(s, 2).find("wet area around 16.75°E"), std::string::npos) << describe(s, 2);
  // Below the threshold it is counted, not listed.
  const DroppedSeas quiet = find_dropped_seas(r.area.wet, r.area.filled, r.lattice, r.rot, 2, 1e6, {});
  EXPECT_TRUE(quiet.large.empty());
  EXPECT_EQ(quiet.components, 1);
  EXPECT_NEAR(quiet.area_km2, s.area_km2, 1e-6);
}

TEST(DroppedSeas, TheWidestNarrowerCursorAndWhereItTouches) {
  raster::Bathymetry one = world(Strait::kOnePixel);
  const MaskRun r1 = run(one, options(2));
  const DroppedSeas d1 = find_dropped_seas(r1.area.wet, r1.area.filled, r1.lattice, r1.rot, 2, 1e4, {});
  ASSERT_EQ(d1.large.size(), 1U);
  EXPECT_EQ(d1.large[0].connecting_cursor, 1);
  EXPECT_GE(d1.large[0].contact_pixels, 1);
  EXPECT_NEAR(d1.large[0].contact.lat_deg, 5.25, 1e-9);
  EXPECT_NEAR(d1.large[0].contact.lon_deg, 9.75, 0.51);
  EXPECT_NE(d1.large[0].keep.find("mask.cursor = 1"), std::string::npos);
  // Two pixels wide at K = 3 and K = 4: a 2-pixel cursor would pass.
  raster::Bathymetry two = world(Strait::kTwoPixels);
  for (int k : {3, 4}) {
    const MaskRun r = run(two, options(k));
    const DroppedSeas d = find_dropped_seas(r.area.wet, r.area.filled, r.lattice, r.rot, k, 1e4, {});
    ASSERT_EQ(d.large.size(), 1U) << k;
    EXPECT_EQ(d.large[0].connecting_cursor, 2) << k;
  }
}

TEST(Carving, MinimaxPathFindsTheSillAndKeepsToDeepWater) {
  // 5 × 4 grid: two routes from the left column to the right one, sills -20 (row 0) and -5 (row 3).
  const std::vector<double> z = {-90, -20, -90, -90, -90,  //
                                 -90, 100, 100, 100, -90,  //
                                 -90, 100, 100, 100, -90,  //
                                 -90, -5,  -90, -90, -90};
  std::vector<unsigned char> target(z.size(), 0);
  for (int j = 0; j < 4; ++j) target[static_cast<std::size_t>(j * 5 + 4)] = 1;
  std::vector<std::int64_t> path;
  const std::vector<double> dx(4, 1.0);
  EXPECT_EQ(minimax_path(z, 5, 4, {0, 5, 10, 15}, target, dx, 1.0, &path), -20.0);
  ASSERT_FALSE(path.empty());
  for (const std::int64_t c : path) EXPECT_LE(z[static_cast<std::size_t>(c)], -20.0);
  EXPECT_EQ(path.front() % 5, 0);
  EXPECT_EQ(path.back() % 5, 4);
  std::vector<double> cut = z;  // both sills no-data: over the land (+100 m)
  cut[1] = cut[16] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(minimax_path(cut, 5, 4, {0, 5, 10, 15}, target, dx, 1.0, nullptr), 100.0);
  for (int j = 0; j < 4; ++j) cut[static_cast<std::size_t>(j * 5 + 2)] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isinf(minimax_path(cut, 5, 4, {0, 5, 10, 15}, target, dx, 1.0, nullptr)));
}

TEST(Carving, NamesOfTheTableAreChecked) {
  config::MaskOptions o;
  o.passages_open = {"Gibraltar", "bab el mandeb", "Øresund"};
  EXPECT_NO_THROW(check_passage_names(o));
  o.passages_open = {"Gibraltar", "Gibralter"};
  try {
    check_passage_names(o);
    FAIL();
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("mask.passages_open"), std::string::npos) << m;
    EXPECT_NE(m.find("\"Gibralter\" (did you mean \"Gibraltar\"?)"), std::string::npos) << m;
    EXPECT_NE(m.find("Dover"), std::string::npos) << m;  // the list of names
  }
}

TEST(Carving, BadLineFilesAreInputErrorsNamingFileLayerAndFeature) {
  Scratch dir;
  raster::Bathymetry b = world(Strait::kNone);
  const Lattice lat = Lattice::make(4.0, 3, -180.0);
  const auto message = [&](config::MaskOptions o) {
    try {
      (void)plan_carving(o, lat, PoleRotation(), b);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  config::MaskOptions o = options(2);
  o.channels = (dir / "missing.geojson").string();
  EXPECT_NE(message(o).find("mask.channels = \"" + o.channels + "\": GDAL/OGR cannot open it"), std::string::npos)
      << message(o);
  {
    std::ofstream f(dir / "poly.geojson");
    f << R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {}, "geometry": )"
      << R"({"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]}}]})";
  }
  o.channels = (dir / "poly.geojson").string();
  EXPECT_NE(message(o).find("feature 0: the geometry is POLYGON, not a line"), std::string::npos) << message(o);
  o.channels =
      write_lines(dir, "bad_width.geojson", {{{{1, 1}, {2, 2}}, ""}, {{{1, 1}, {2, 2}}, R"("width_m": "wide")"}});
  EXPECT_NE(message(o).find("feature 1: attribute width_m = \"wide\" is not a number"), std::string::npos)
      << message(o);
  o.channels = write_lines(dir, "neg.geojson", {{{{1, 1}, {2, 2}}, R"("depth_m": -3)"}});
  EXPECT_NE(message(o).find("depth_m = -3 is not a depth"), std::string::npos) << message(o);
  o.channels = "";
  o.transects = write_lines(dir, "kind.geojson", {{{{1, 1}, {2, 2}}, R"("kind": "bridge")"}});
  EXPECT_NE(message(o).find("mask.transects = "), std::string::npos);
  EXPECT_NE(message(o).find("kind = \"bridge\" is not \"passage\" or \"blockage\""), std::string::npos) << message(o);
  o.transects_layer = "nope";
  EXPECT_NE(message(o).find("mask.transects_layer = \"nope\": no such layer"), std::string::npos) << message(o);
  o.transects_layer = "";
  o.transects = write_lines(dir, "one.geojson", {{{{1, 1}}, ""}});
  EXPECT_NE(message(o).find("one.geojson\", layer \"one\", feature 0"), std::string::npos) << message(o);
}

}  // namespace
}  // namespace aq::mask::unit_mask_carving_test
