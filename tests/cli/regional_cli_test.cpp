// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria regional` as a user runs it: the seed's Black Sea from the TOML config and from the
// seed's own .izogrid file, stop-after pictures, and bad contours refused with clear messages and
// no partial files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_outputs.hpp"
#include "support/run_command.hpp"

namespace cli_regional_cli_test {

namespace fs = std::filesystem;
using aq::test::run_aquatoria;
using ::testing::HasSubstr;

namespace {
const std::string kConfigs = std::string(AQ_SOURCE_DIR) + "/configs/";

fs::path fresh_dir(const std::string& name) { return aq::test::fresh_dir("regional_cli", name); }

fs::path write_izogrid(const std::string& name, const std::string& points) {
  const fs::path dir = fs::temp_directory_path() / "aq_regional_cli_inputs";
  fs::create_directories(dir);
  std::ofstream(dir / name) << "mode=4 proj=ME rlat=43.75 rlon=34.5 rota=0 uscale=0.001 ny=20 spline_type=5\n---\n"
                            << points;
  return dir / name;
}
}  // namespace

TEST(RegionalCli, BlackSeaFromTomlBuildsTheSeedGrid) {
  const fs::path out = fresh_dir("toml");
  const auto r =
      run_aquatoria("regional -q -c " + kConfigs + "black_sea.toml -o " + out.string() + " --set roms.enabled=false");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "black_sea_xygrid.nc"));
  EXPECT_TRUE(fs::exists(out / "black_sea_grid.png"));
  const auto rep = nlohmann::json::parse(std::ifstream(out / "black_sea_report.json"));
  const auto& g = rep.at("regional");
  EXPECT_EQ(g.at("nx"), 65);
  EXPECT_EQ(g.at("supergrid"), nlohmann::json::array({131, 101}));
  EXPECT_NEAR(g.at("aspect_ratio").get<double>(), 1.300823, 1e-5);
  const auto& h = g.at("residual_history");
  for (std::size_t k = 1; k < h.size(); ++k) EXPECT_LT(h[k].get<double>(), h[k - 1].get<double>());
  EXPECT_LT(h.back().get<double>(), 1e-11);
  // Orthogonality (50) of the seed's grid: worst ~6.6e-3 in a corner cell, rms ~2.6e-4.
  EXPECT_LT(rep.at("quality").at("ortho_err_50").at("worst").get<double>(), 1e-2);
  EXPECT_LT(rep.at("quality").at("ortho_err_50").at("rms").get<double>(), 5e-4);
}

TEST(RegionalCli, SeedFileFormatStopsWhereItsModeSays) {
  const fs::path out = fresh_dir("izogrid");
  const auto r = run_aquatoria("regional " + kConfigs + "black_sea.izogrid -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("mode=1 stops after the contour stage"));
  EXPECT_TRUE(fs::exists(out / "black_sea_contour.png"));
  EXPECT_FALSE(fs::exists(out / "black_sea_xygrid.nc"));
}

TEST(RegionalCli, EachStopAfterStageDrawsItsPicture) {
  for (const std::string stage : {"map", "contour", "uniform", "conformal"}) {
    const fs::path out = fresh_dir("stage_" + stage);
    const auto r =
        run_aquatoria("regional -q -c " + kConfigs + "black_sea.toml --stop-after " + stage + " -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << stage << ": " << r.err;
    EXPECT_TRUE(fs::exists(out / ("black_sea_" + stage + ".png"))) << stage;
    EXPECT_GT(fs::file_size(out / ("black_sea_" + stage + ".png")), 10000u) << stage;
  }
}

TEST(RegionalCli, ThreeCornersIsAClearError) {
  const auto f =
      write_izogrid("three.izogrid", "-50 -20 south-west\n50 -20 < south-east\n50 20 < north-east\n-50 20\n");
  const fs::path out = fresh_dir("three");
  const auto r = run_aquatoria("regional " + f.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("three.izogrid"));
  EXPECT_THAT(r.err, HasSubstr("corner"));
  EXPECT_TRUE(!fs::exists(out) || fs::is_empty(out));
}

TEST(RegionalCli, SelfIntersectingContourIsRefused) {
  const auto f = write_izogrid("bow.izogrid",
                               "-50 -20 south-west\n50 -20 < south-east\n50 20 < north-east\n"
                               "0 -40\n-50 20 < north-west\n");
  const fs::path out = fresh_dir("bow");
  const auto r = run_aquatoria("regional " + f.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, ::testing::AnyOf(HasSubstr("intersect"), HasSubstr("clockwise")));
  EXPECT_TRUE(!fs::exists(out) || fs::is_empty(out));
}

TEST(RegionalCli, IterationLimitIsANumericalError) {
  const fs::path out = fresh_dir("limit");
  const auto r =
      run_aquatoria("regional -q -c " + kConfigs + "black_sea.toml --set regional.max_outer=2 -o " + out.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("residual"));
  EXPECT_TRUE(!fs::exists(out) || fs::is_empty(out));
}

TEST(RegionalCli, FourPointLonLatRectangleConvergesAtItsRoundOffFloor) {
  // Corners only: the node distribution's residual stalls near 4e-12, above the 1e-12 tolerance;
  // the run accepts the floor (three fully converged iterates no longer halving it) and says so.
  const fs::path dir = fresh_dir("four_points");
  fs::create_directories(dir);
  std::ofstream(dir / "r4.toml") << "[regional]\nname = \"r4\"\nproj = \"ME\"\nrlat = 25.0\nrlon = -89.0\n"
                                    "uscale = 0.001\npoints = \"lonlat\"\n"
                                    "control_points = [[-93.0, 22.0], [-85.0, 22.0], [-85.0, 28.0], [-93.0, 28.0]]\n"
                                    "corners = [1, 2, 3, 4]\nny = 20\nstop_after = \"grid\"\n[roms]\nenabled = false\n";
  const auto r =
      run_aquatoria("regional -c " + (dir / "r4.toml").string() + " --no-coastline -o " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("round-off floor"));
  std::ifstream rf(dir / "out" / "r4_report.json");
  const auto j = nlohmann::json::parse(rf);
  EXPECT_LT(j["quality"]["ortho_err_50"]["worst"].get<double>(), 0.01);
  // A tolerance above the floor converges without it.
  const auto t = run_aquatoria("regional -c " + (dir / "r4.toml").string() +
                               " --set regional.tolerance=1e-10 --no-coastline -o " + (dir / "out2").string());
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_THAT(t.err, ::testing::Not(HasSubstr("round-off floor")));
  fs::remove_all(dir);
}

}  // namespace cli_regional_cli_test
