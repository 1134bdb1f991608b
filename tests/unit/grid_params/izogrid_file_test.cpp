// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the izogrid input-file reader (seed 000 Appendix 1, Fig. 3; ARCHITECTURE §5 "Input
// compatibility"): the seed's Black Sea file read back verbatim, the end-of-preamble variants,
// corner labels, and the errors (file:line, key, value, corner counts) for bad files.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "grid_params/izogrid_file.hpp"

namespace aq::curvilinear::unit_grid_params_izogrid_file_test {
namespace {

const char* kPoints =
    "-97 -26 south-west\n-77 -39.5\n-44 -46\n-9 -31.5\n+25 -44\n+75 -47\n+104 -33 < south-east\n+89.2 -14\n"
    "+55 +10\n+38 +29\n+57.5 +63.5 < north-east\n+3 +47\n-40 +60 < north-west\n-74 +12\n-84 -6.2\n";

std::string message_of(const std::string& text) {
  try {
    (void)parse_izogrid(text, "test.izogrid");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(IzogridFileTest, ReadsTheSeedBlackSeaFile) {
  const RegionalParams p = read_izogrid_file(std::string(AQ_SOURCE_DIR) + "/configs/black_sea.izogrid");
  EXPECT_EQ(p.mode, 1);
  EXPECT_EQ(p.latlongrid, 2.0);
  EXPECT_EQ(p.spline_type, 4);
  EXPECT_EQ(p.npass, 4);
  EXPECT_EQ(p.projection.kind, ProjectionKind::kMercator);
  EXPECT_EQ(p.projection.rlat_deg, 43.75);
  EXPECT_EQ(p.projection.rlon_deg, 34.5);
  EXPECT_EQ(p.projection.rota_deg, 0.0);
  EXPECT_EQ(p.west_edge, 26.5);
  EXPECT_EQ(p.east_edge, 43.0);
  EXPECT_EQ(p.south_edge, 40.75);
  EXPECT_EQ(p.north_edge, 47.25);
  EXPECT_EQ(p.nx, 65);
  EXPECT_EQ(p.ny, 50);
  EXPECT_EQ(p.projection.uscale, 0.001);
  ASSERT_EQ(p.x.size(), 15u);
  EXPECT_EQ(p.x[6], 104.0);
  EXPECT_EQ(p.y[14], -6.2);
  EXPECT_EQ(p.x[4], 25.0);  // "+25"
  const std::vector<bool> corners{true,  false, false, false, false, false, true, false,
                                  false, false, true,  false, true,  false, false};
  EXPECT_EQ(p.corner, corners);  // corners at points 1, 7, 11, 13 (digest §2.3)
  EXPECT_FALSE(p.points_lonlat);
  EXPECT_NE(p.input_text.find("uscale=0.001"), std::string::npos);
  // Defaults of what the file does not set.
  EXPECT_EQ(p.xygrid, "xygrid.nc");
  EXPECT_EQ(p.lwidth, 1.0);
  EXPECT_EQ(p.gshhs_data, "i");
  EXPECT_EQ(p.schedule, InnerSchedule::kExponential);
}

TEST(IzogridFileTest, AcceptsEveryDashMarkerAndComments) {
  for (const std::string marker : {"---", "-----", "–––", "———", "  -–—  ", "\xE2\x80\x93\xE2\x80\x93-"}) {
    const std::string text = "ny=20 # grid rows\nproj=st rlat=90 uscale=0.01\n" + marker + "\n" + kPoints;
    const RegionalParams p = parse_izogrid(text, "t");
    EXPECT_EQ(p.ny, 20) << marker;
    EXPECT_EQ(p.projection.kind, ProjectionKind::kStereographic);
    EXPECT_EQ(p.x.size(), 15u) << marker;
  }
  // Two dashes are not a marker: the points are then read as bad key=value tokens.
  EXPECT_NE(message_of(std::string("ny=20\n--\n") + kPoints).find("not key=value"), std::string::npos);
}

TEST(IzogridFileTest, CornerLabelsStartWithAnArrowOrNameTheCorner) {
  const std::string text = "---\n0 0 start\n10 0 south-east\n10 10 <\n5 12 a note\n0 10 <north-west\n";
  const RegionalParams p = parse_izogrid(text, "t");
  EXPECT_EQ(p.corner, (std::vector<bool>{true, true, true, false, true}));
}

TEST(IzogridFileTest, UnknownKeysAndBadValuesNameFileLineAndKey) {
  const std::string m = message_of("mode=1 colour=blue\nrlat=north ny=50\nspline_type=7\n---\n" + std::string(kPoints));
  EXPECT_NE(m.find("test.izogrid:1: unknown key 'colour'"), std::string::npos) << m;
  EXPECT_NE(m.find("test.izogrid:2: rlat = 'north' is not a number"), std::string::npos) << m;
  try {
    (void)parse_izogrid("mode=1 colour=blue\n---\n" + std::string(kPoints), "f");
    FAIL();
  } catch (const ConfigError&) {
  }
  // Range errors after parsing also carry the line of their key; all problems in one message.
  const std::string r = message_of("mode=9\nny=0 uscale=-1\n---\n" + std::string(kPoints));
  EXPECT_NE(r.find("test.izogrid:1: mode = 9"), std::string::npos) << r;
  EXPECT_NE(r.find("test.izogrid:2: ny = 0"), std::string::npos) << r;
  EXPECT_NE(r.find("test.izogrid:2: uscale = -1"), std::string::npos) << r;
  EXPECT_NE(message_of("ny=5 ny=6\n---\n" + std::string(kPoints)).find("given again"), std::string::npos);
  EXPECT_NE(message_of("proj=XX\n---\n" + std::string(kPoints)).find("proj = 'XX'"), std::string::npos);
  EXPECT_NE(message_of("mode\n---\n" + std::string(kPoints)).find("'mode' is not key=value"), std::string::npos);
}

TEST(IzogridFileTest, WrongCornerCountsAreInputErrorsWithTheCount) {
  // 3 corners: drop the north-west mark.
  std::string three = std::string("---\n") + kPoints;
  three.replace(three.find("< north-west"), 12, "");
  try {
    (void)parse_izogrid(three, "t.izogrid");
    FAIL();
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("exactly 4 corners"), std::string::npos) << m;
    EXPECT_NE(m.find("found 3 (lines 2, 8, 12)"), std::string::npos) << m;
  }
  // 5 corners: an extra '<'.
  std::string five = std::string("---\n") + kPoints;
  five.replace(five.find("+3 +47"), 6, "+3 +47 <");
  try {
    (void)parse_izogrid(five, "t.izogrid");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("found 5"), std::string::npos) << e.what();
  }
}

TEST(IzogridFileTest, MalformedFilesAreInputErrors) {
  EXPECT_THROW(parse_izogrid("ny=5\n", "t"), InputError);  // no marker
  EXPECT_NE(message_of("ny=5\n").find("no end-of-preamble line"), std::string::npos);
  EXPECT_THROW(parse_izogrid("---\n", "t"), InputError);  // no points
  EXPECT_NE(message_of(std::string("---\n1 2\n3 x\n") + kPoints).find("test.izogrid:3: expected a point"),
            std::string::npos);
  // Corners out of counter-clockwise order.
  const std::string swapped = "---\n0 0\n10 0 < north-east\n10 10 < south-east\n0 10 < north-west\n";
  EXPECT_NE(message_of(swapped).find("must be the south-east corner"), std::string::npos) << message_of(swapped);
  EXPECT_NE(message_of("---\n0 0\n10 0 <\n10 10 south-west\n0 10 <\n").find("must be the first point"),
            std::string::npos);
  EXPECT_THROW(read_izogrid_file("/nonexistent/file.izogrid"), InputError);
}

TEST(IzogridFileTest, AquatoriaKeysMapToTheParams) {
  const RegionalParams p = parse_izogrid(
      "proj=LC rlat=45 rlon=10 lat1=35 lat2=55 radius=6378137 param=arclength points=lonlat auto_nx=false\n"
      "schedule=sqrt tolerance=1e-10 max_outer=7 max_inner=30 interp_points=6 inner_rtol=0 anderson=2\n"
      "solver=sor threads=2 xygrid=out.nc lwidth=2 gshhs_data=f\n---\n"
      "8 44\n12 44 <\n12 47 <\n8 47 <\n",
      "t");
  EXPECT_EQ(p.projection.kind, ProjectionKind::kLambertConic);
  EXPECT_EQ(p.projection.lat1_deg, 35.0);
  EXPECT_EQ(p.projection.lat2_deg, 55.0);
  EXPECT_EQ(p.projection.radius_m, 6378137.0);
  EXPECT_EQ(p.param, Parametrisation::kArcLength);
  EXPECT_TRUE(p.points_lonlat);
  EXPECT_FALSE(p.auto_nx);
  EXPECT_EQ(p.schedule, InnerSchedule::kSqrt);
  EXPECT_EQ(p.tolerance, 1e-10);
  EXPECT_EQ(p.max_outer, 7);
  EXPECT_EQ(p.max_inner, 30);
  EXPECT_EQ(p.interp_points, 6);
  EXPECT_EQ(p.inner_rtol, 0.0);
  EXPECT_EQ(p.anderson, 2);
  EXPECT_EQ(p.solver, LaplaceSolver::kSor);
  EXPECT_EQ(p.threads, 2);
  EXPECT_EQ(p.xygrid, "out.nc");
  EXPECT_EQ(p.lwidth, 2.0);
  EXPECT_EQ(p.gshhs_data, "f");
}

TEST(IzogridFileTest, SurvivesGarbage) {
  // A small fuzz: random bytes and truncations never crash, only throw aq::Error.
  std::string base = std::string("mode=1 ny=50\n---\n") + kPoints;
  unsigned state = 12345;
  for (int trial = 0; trial < 2000; ++trial) {
    std::string t = base.substr(0, (state >> 4) % (base.size() + 1));
    for (int k = 0; k < 3; ++k) {
      state = state * 1103515245u + 12345u;
      if (!t.empty()) t[(state >> 8) % t.size()] = static_cast<char>(state >> 24);
    }
    try {
      (void)parse_izogrid(t, "fuzz");
    } catch (const Error&) {
    }
  }
  SUCCEED();
}

}  // namespace
}  // namespace aq::curvilinear::unit_grid_params_izogrid_file_test
