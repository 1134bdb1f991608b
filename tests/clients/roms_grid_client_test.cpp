// SPDX-License-Identifier: GPL-3.0-or-later
// The Black Sea ROMS grid file (`aquatoria regional -c configs/black_sea.toml`) read the way users
// read it: ncdump lists every grd_spherical.cdl variable with its dimensions, CDO sees a
// curvilinear grid of 66 x 51 ρ points and its bilinear remap of ETOPO5 agrees with our hraw;
// the file's metrics against great circles computed here; the mask against the global run's
// K-fill (interior wet points in Ω_L, the Sea of Azov — not connected at K = 2 — left land, the
// ROMS u/v/ψ rules, boundary copies); same bytes with 1 and 2 threads; bad input.
#include <gtest/gtest.h>
#include <netcdf.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/load.hpp"
#include "core/lattice.hpp"
#include "core/rotation.hpp"
#include "mask/regional_mask.hpp"
#include "mask/wet_area.hpp"
#include "raster/bathymetry.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace clients_roms_grid_client_test {

namespace {

namespace fs = std::filesystem;
using aq::test::run_command;

const fs::path kConfigs = fs::path(AQ_SOURCE_DIR) / "configs";
const std::string kEtopo5 = std::string(AQ_ETOPO_DIR) + "/etopo5.cdf";
constexpr double kD2R = 3.14159265358979323846 / 180.0;

bool have(const std::string& program) { return run_command("command -v " + program).exit_code == 0; }

// A 2-D (or bath x 2-D) double variable of a netCDF file, with its shape.
struct Field {
  std::size_t nj = 0, ni = 0;
  std::vector<double> v;
  [[nodiscard]] double at(std::size_t i, std::size_t j) const { return v[j * ni + i]; }
};

Field read_field(const fs::path& file, const std::string& name) {
  int nc = -1, var = -1, nd = 0;
  int dims[NC_MAX_VAR_DIMS];
  EXPECT_EQ(nc_open(file.c_str(), NC_NOWRITE, &nc), NC_NOERR) << file;
  EXPECT_EQ(nc_inq_varid(nc, name.c_str(), &var), NC_NOERR) << name;
  nc_inq_varndims(nc, var, &nd);
  nc_inq_vardimid(nc, var, dims);
  Field f;
  nc_inq_dimlen(nc, dims[nd - 2], &f.nj);
  nc_inq_dimlen(nc, dims[nd - 1], &f.ni);
  f.v.resize(f.ni * f.nj);
  EXPECT_EQ(nc_get_var_double(nc, var, f.v.data()), NC_NOERR) << name;  // 'bath' has one record
  nc_close(nc);
  return f;
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

double haversine(double lon1, double lat1, double lon2, double lat2) {
  const double a = std::sin(0.5 * (lat2 - lat1) * kD2R), b = std::sin(0.5 * (lon2 - lon1) * kD2R);
  return 2.0 * 6371000.0 * std::asin(std::sqrt(a * a + std::cos(lat1 * kD2R) * std::cos(lat2 * kD2R) * b * b));
}

class BlackSeaRoms : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new aq::testing::TempDir();
    const auto r = run_command("OMP_NUM_THREADS=2 " + std::string(AQ_BINARY) + " regional -c " +
                               (kConfigs / "black_sea.toml").string() + " -o " + dir_->path().string());
    exit_code_ = r.exit_code;
    log_ = r.err;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  void SetUp() override {
    ASSERT_EQ(exit_code_, 0) << log_;
    ASSERT_TRUE(fs::exists(grd())) << log_;
  }
  static fs::path grd() { return dir_->path() / "black_sea_grd.nc"; }

  static aq::testing::TempDir* dir_;
  static int exit_code_;
  static std::string log_;
};
aq::testing::TempDir* BlackSeaRoms::dir_ = nullptr;
int BlackSeaRoms::exit_code_ = -1;
std::string BlackSeaRoms::log_;

TEST_F(BlackSeaRoms, LogsTheStageAndWritesThePicture) {
  EXPECT_NE(log_.find("roms: done black_sea_grd.nc (66 x 51 ρ points"), std::string::npos) << log_;
  EXPECT_TRUE(fs::exists(dir_->path() / "black_sea_roms.png"));
  const std::string report = bytes(dir_->path() / "black_sea_report.json");
  for (const char* key : {"\"roms\"", "\"wet_rho\"", "\"pm_min\"", "\"isotropy_max_abs_pm_over_pn_minus_1\"",
                          "\"rx0_after\"", "black_sea_grd.nc"})
    EXPECT_NE(report.find(key), std::string::npos) << key;
}

TEST_F(BlackSeaRoms, NcdumpListsEveryGrdSphericalVariableWithItsDimensions) {
  if (!have("ncdump")) GTEST_SKIP() << "ncdump not installed";
  const auto r = run_command("ncdump -h " + grd().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The supergrid is 131 x 101 (nx = 65, ny = 50): L = 65, M = 50.
  for (const char* d : {"xi_psi = 65 ;", "xi_rho = 66 ;", "xi_u = 65 ;", "xi_v = 66 ;", "eta_psi = 50 ;",
                        "eta_rho = 51 ;", "eta_u = 51 ;", "eta_v = 50 ;", "bath = UNLIMITED ; // (1 currently)"})
    EXPECT_NE(r.out.find(d), std::string::npos) << d;
  std::vector<std::string> lines = {"char spherical ;", "double xl ;", "double el ;",
                                    "double hraw(bath, eta_rho, xi_rho) ;"};
  for (const char* v :
       {"h", "f", "pm", "pn", "dndx", "dmde", "angle", "x_rho", "y_rho", "lat_rho", "lon_rho", "mask_rho"})
    lines.push_back(std::string("double ") + v + "(eta_rho, xi_rho) ;");
  for (const char* fam : {"psi", "u", "v"})
    for (const char* pre : {"x_", "y_", "lat_", "lon_", "mask_"})
      lines.push_back(std::string("double ") + pre + fam + "(eta_" + fam + ", xi_" + fam + ") ;");
  EXPECT_EQ(lines.size(), 31u);
  for (const auto& l : lines) EXPECT_NE(r.out.find("\t" + l + "\n"), std::string::npos) << l;
  EXPECT_NE(r.out.find(":type = \"ROMS GRID file\" ;"), std::string::npos);
  EXPECT_NE(r.out.find("angle:long_name = \"angle between XI-axis and EAST\" ;"), std::string::npos);
  EXPECT_NE(r.out.find("mask_rho:flag_meanings = \"land water\" ;"), std::string::npos);
  EXPECT_NE(r.out.find(":global_config = "), std::string::npos);
  EXPECT_NE(r.out.find(":rmax = 0.2 ;"), std::string::npos);
}

TEST_F(BlackSeaRoms, CdoSeesACurvilinearGridAndItsRemapOfEtopo5MatchesHraw) {
  if (!have("cdo")) GTEST_SKIP() << "cdo not installed";
  const fs::path dir = dir_->path();
  const auto g = run_command("cdo -s griddes -selname,h " + grd().string());
  ASSERT_EQ(g.exit_code, 0) << g.err;
  EXPECT_NE(g.out.find("gridtype  = curvilinear"), std::string::npos) << g.out;
  EXPECT_NE(g.out.find("gridsize  = 3366"), std::string::npos) << g.out;
  EXPECT_NE(g.out.find("xsize     = 66"), std::string::npos) << g.out;
  EXPECT_NE(g.out.find("ysize     = 51"), std::string::npos) << g.out;
  EXPECT_NE(g.out.find("xname     = lon_rho"), std::string::npos) << g.out;
  std::ofstream(dir / "target.txt") << g.out;

  // ETOPO5's stored longitude axis steps by 0.08333411° (float32 rounding), not 1/12°; our
  // raster reader uses the nominal 5' grid, CDO the stored axis. So the remap is done twice:
  // (a) on the nominal grid (cdo setgrid): both are bilinear on the same cells and must agree to
  //     the precision of CDO's float32 output (1e-4 m at 2000 m);
  // (b) on the file as stored: positions differ by λ·9.3e-6° (≈ 40 m at 40°E), so the depths
  //     differ by the local slope times 40 m: a few metres on the steepest slopes.
  std::ofstream(dir / "etopo5_nominal.txt") << "gridtype = lonlat\nxsize = 4320\nysize = 2161\nxfirst = 0\n"
                                               "xinc = 0.08333333333333333\nyfirst = -90\nyinc = 0.08333333333333333\n";
  const auto a = run_command("cdo -s remapbil," + (dir / "target.txt").string() + " -setgrid," +
                             (dir / "etopo5_nominal.txt").string() + " -selname,ROSE " + kEtopo5 + " " +
                             (dir / "remap_nominal.nc").string());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const auto b = run_command("cdo -s remapbil," + (dir / "target.txt").string() + " -selname,ROSE " + kEtopo5 + " " +
                             (dir / "remap_stored.nc").string());
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const Field hraw = read_field(grd(), "hraw");
  const Field na = read_field(dir / "remap_nominal.nc", "ROSE");
  const Field st = read_field(dir / "remap_stored.nc", "ROSE");
  ASSERT_EQ(na.v.size(), hraw.v.size());
  double worst_a = 0.0, worst_b = 0.0, sum_b = 0.0;
  for (std::size_t k = 0; k < hraw.v.size(); ++k) {
    worst_a = std::max(worst_a, std::fabs(-na.v[k] - hraw.v[k]) / (1e-3 + 1e-6 * std::fabs(hraw.v[k])));
    worst_b = std::max(worst_b, std::fabs(-st.v[k] - hraw.v[k]));
    sum_b += std::fabs(-st.v[k] - hraw.v[k]);
  }
  EXPECT_LT(worst_a, 1.0) << "nominal grid: |cdo + hraw| > 1e-3 m + 1e-6 |hraw|";
  EXPECT_LT(worst_b, 10.0);
  EXPECT_LT(sum_b / static_cast<double>(hraw.v.size()), 0.5);
}

TEST_F(BlackSeaRoms, MetricsAgreeWithGreatCirclesBetweenTheFilesPoints) {
  const Field lon = read_field(grd(), "lon_rho"), lat = read_field(grd(), "lat_rho");
  const Field lon_u = read_field(grd(), "lon_u"), lat_u = read_field(grd(), "lat_u");
  const Field lon_v = read_field(grd(), "lon_v"), lat_v = read_field(grd(), "lat_v");
  const Field pm = read_field(grd(), "pm"), pn = read_field(grd(), "pn"), f = read_field(grd(), "f");
  const Field angle = read_field(grd(), "angle");
  ASSERT_EQ(lon.ni, 66u);
  ASSERT_EQ(lon.nj, 51u);
  double worst = 0.0, iso = 0.0;
  for (std::size_t j = 1; j + 1 < lon.nj; ++j)
    for (std::size_t i = 1; i + 1 < lon.ni; ++i) {
      const double dx = haversine(lon_u.at(i - 1, j), lat_u.at(i - 1, j), lon.at(i, j), lat.at(i, j)) +
                        haversine(lon.at(i, j), lat.at(i, j), lon_u.at(i, j), lat_u.at(i, j));
      const double dy = haversine(lon_v.at(i, j - 1), lat_v.at(i, j - 1), lon.at(i, j), lat.at(i, j)) +
                        haversine(lon.at(i, j), lat.at(i, j), lon_v.at(i, j), lat_v.at(i, j));
      worst = std::max({worst, std::fabs(pm.at(i, j) * dx - 1.0), std::fabs(pn.at(i, j) * dy - 1.0)});
      iso = std::max(iso, std::fabs(pm.at(i, j) / pn.at(i, j) - 1.0));
    }
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(iso, 0.01);  // conformal: the seed's prototype has 0.992..1.0001 at this size
  for (std::size_t k = 0; k < f.v.size(); ++k) {
    EXPECT_NEAR(f.v[k], 2.0 * 7.2921e-5 * std::sin(lat.v[k] * kD2R), 1e-18);
    EXPECT_TRUE(std::isfinite(angle.v[k]));
  }
}

TEST_F(BlackSeaRoms, MaskIsTheGlobalOceanWithRomsRules) {
  const Field m = read_field(grd(), "mask_rho"), mu = read_field(grd(), "mask_u"), mv = read_field(grd(), "mask_v"),
              mp = read_field(grd(), "mask_psi");
  const Field lon = read_field(grd(), "lon_rho"), lat = read_field(grd(), "lat_rho"), hraw = read_field(grd(), "hraw");
  const Field h = read_field(grd(), "h");
  const std::size_t ni = m.ni, nj = m.nj;
  // u/v/psi rules and boundary copies.
  for (std::size_t j = 0; j < nj; ++j)
    for (std::size_t k = 0; k + 1 < ni; ++k) EXPECT_EQ(mu.at(k, j), m.at(k, j) * m.at(k + 1, j));
  for (std::size_t l = 0; l + 1 < nj; ++l)
    for (std::size_t i = 0; i < ni; ++i) EXPECT_EQ(mv.at(i, l), m.at(i, l) * m.at(i, l + 1));
  for (std::size_t l = 0; l + 1 < nj; ++l)
    for (std::size_t k = 0; k + 1 < ni; ++k)
      EXPECT_EQ(mp.at(k, l), m.at(k, l) * m.at(k + 1, l) * m.at(k, l + 1) * m.at(k + 1, l + 1));
  for (std::size_t j = 1; j + 1 < nj; ++j) {
    EXPECT_EQ(m.at(0, j), m.at(1, j));
    EXPECT_EQ(m.at(ni - 1, j), m.at(ni - 2, j));
  }
  for (std::size_t i = 0; i < ni; ++i) {
    EXPECT_EQ(m.at(i, 0), m.at(i, 1));
    EXPECT_EQ(m.at(i, nj - 1), m.at(i, nj - 2));
  }

  // The global run of configs/black_sea_global.toml, recomputed here.
  const auto g = aq::config::load_global((kConfigs / "black_sea_global.toml").string(), {});
  const aq::Lattice lattice =
      aq::Lattice::make(g.options.quadtree.step_deg, g.options.quadtree.levels, g.options.quadtree.lon0_deg);
  aq::raster::OpenOptions ro;
  ro.path = g.options.input.path;
  const auto bathy = aq::raster::Bathymetry::open(ro);
  const aq::mask::WetArea area =
      aq::mask::compute_wet_area(bathy, lattice, aq::PoleRotation(), g.options.mask, aq::Logger::null(), nullptr);
  std::size_t wet = 0, azov_deep = 0;
  for (std::size_t j = 1; j + 1 < nj; ++j)
    for (std::size_t i = 1; i + 1 < ni; ++i) {
      const auto p = aq::mask::pixel_of_point(lattice, aq::PoleRotation(), lon.at(i, j), lat.at(i, j));
      const bool in = area.filled.get(p.i, p.j);
      if (m.at(i, j) != 0) {
        ++wet;
        EXPECT_TRUE(in) << "wet ρ (" << i << ", " << j << ") outside the global ocean";
        EXPECT_GE(hraw.at(i, j), 0.0);
      } else {
        EXPECT_FALSE(in && hraw.at(i, j) >= 0.0) << "ρ (" << i << ", " << j << ") is global ocean but land";
      }
      // The Sea of Azov (behind the Kerch Strait, closed for K = 2 on 3.75' pixels): a lake.
      if (lon.at(i, j) > 35.2 && lon.at(i, j) < 39.2 && lat.at(i, j) > 45.6 && lat.at(i, j) < 47.2 &&
          hraw.at(i, j) > 2.0) {
        ++azov_deep;
        EXPECT_EQ(m.at(i, j), 0.0) << "Sea of Azov at (" << lon.at(i, j) << ", " << lat.at(i, j) << ")";
        EXPECT_FALSE(in);
      }
    }
  EXPECT_GT(wet, 2000u);
  EXPECT_GT(azov_deep, 20u);
  // Depth: h >= hmin everywhere, h >= hraw, and the r-factor on wet faces within rmax = 0.2.
  double rx0 = 0.0;
  for (std::size_t j = 0; j < nj; ++j)
    for (std::size_t i = 0; i < ni; ++i) {
      EXPECT_GE(h.at(i, j), 10.0);
      EXPECT_GE(h.at(i, j), hraw.at(i, j));
      if (i + 1 < ni && m.at(i, j) * m.at(i + 1, j) != 0)
        rx0 = std::max(rx0, std::fabs(h.at(i, j) - h.at(i + 1, j)) / (h.at(i, j) + h.at(i + 1, j)));
      if (j + 1 < nj && m.at(i, j) * m.at(i, j + 1) != 0)
        rx0 = std::max(rx0, std::fabs(h.at(i, j) - h.at(i, j + 1)) / (h.at(i, j) + h.at(i, j + 1)));
    }
  EXPECT_LE(rx0, 0.2 + 1e-12);
  EXPECT_GT(rx0, 0.19);
}

TEST_F(BlackSeaRoms, SameBytesWithOneThread) {
  aq::testing::TempDir one;
  const auto r = run_command("OMP_NUM_THREADS=1 " + std::string(AQ_BINARY) + " -q regional -c " +
                             (kConfigs / "black_sea.toml").string() + " -o " + one.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(bytes(one / "black_sea_grd.nc"), bytes(grd()));
  EXPECT_EQ(bytes(one / "black_sea_roms.png"), bytes(dir_->path() / "black_sea_roms.png"));
}

TEST(GulfOfMexicoRoms, TheBuiltInGlobalRunGivesTheMaskOfAConnectedSea) {
  // roms.global_config = "": the seed's reference run (0.5° pixels, K = 2, one Atlantic seed).
  aq::testing::TempDir d;
  const auto r = aq::test::run_aquatoria("regional -c " + (kConfigs / "gulf_of_mexico.toml").string() + " -o " +
                                         d.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path file = d / "gulf_of_mexico_grd.nc";
  const Field m = read_field(file, "mask_rho"), lon = read_field(file, "lon_rho"), lat = read_field(file, "lat_rho");
  EXPECT_EQ(m.ni, 51u);
  EXPECT_EQ(m.nj, 41u);
  const auto g = aq::config::load_global(std::nullopt, {});
  const aq::Lattice lattice =
      aq::Lattice::make(g.options.quadtree.step_deg, g.options.quadtree.levels, g.options.quadtree.lon0_deg);
  aq::raster::OpenOptions ro;
  ro.path = g.options.input.path;
  const auto bathy = aq::raster::Bathymetry::open(ro);
  const auto area =
      aq::mask::compute_wet_area(bathy, lattice, aq::PoleRotation(), g.options.mask, aq::Logger::null(), nullptr);
  std::size_t wet = 0;
  for (std::size_t j = 1; j + 1 < m.nj; ++j)
    for (std::size_t i = 1; i + 1 < m.ni; ++i) {
      if (m.at(i, j) == 0) continue;
      ++wet;
      const auto p = aq::mask::pixel_of_point(lattice, aq::PoleRotation(), lon.at(i, j), lat.at(i, j));
      EXPECT_TRUE(area.filled.get(p.i, p.j)) << i << "," << j;
    }
  EXPECT_GT(wet, 1000u);  // the deep Gulf, open to the Atlantic through the Florida Strait
}

TEST(RomsBadInput, ABlockWithoutWaterOfTheGlobalOceanIsAClearError) {
  // The built-in global run (0.5° pixels, one Atlantic seed) never reaches the Black Sea.
  aq::testing::TempDir d;
  const auto r = aq::test::run_aquatoria("regional -c " + (kConfigs / "black_sea.toml").string() +
                                         " --set 'roms.global_config=\"\"' -o " + d.path().string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("black_sea.toml: the regional grid has no water of the global ocean"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("roms.global_config"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("mask.seeds"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(d / "black_sea_grd.nc"));  // all-or-nothing outputs
  EXPECT_FALSE(fs::exists(d / "black_sea_xygrid.nc"));
}

TEST(RomsBadInput, AGridLeavingARegionalRasterIsAClearError) {
  if (!have("gdal_translate")) GTEST_SKIP() << "gdal_translate not installed";
  aq::testing::TempDir d;
  // ETOPO5 cut to 26..36°E: the Black Sea grid reaches 42°E.
  const auto cut = run_command("gdal_translate -q -of GTiff -projwin 26 48 36 40 NETCDF:" + kEtopo5 + ":ROSE " +
                               (d / "west.tif").string());
  ASSERT_EQ(cut.exit_code, 0) << cut.err;
  std::ofstream(d / "global.toml") << "[input]\npath = \"west.tif\"\n[mask]\nseeds = [[31.0, 43.0]]\n"
                                      "[quadtree]\nstep_deg = 4.0\nlevels = 5\n";
  const auto r = aq::test::run_aquatoria("regional -c " + (kConfigs / "black_sea.toml").string() +
                                         " --set roms.global_config=" + (d / "global.toml").string() + " -o " +
                                         (d / "out").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("west.tif: no depth at"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("leaves the raster's coverage"), std::string::npos) << r.err;
}

TEST(RomsBadInput, MercatorCentreAtAPoleAndBadRomsKeysNameTheKey) {
  aq::testing::TempDir d;
  const auto pole = aq::test::run_aquatoria("regional -c " + (kConfigs / "black_sea.toml").string() +
                                            " --set regional.rlat=90 -o " + d.path().string());
  EXPECT_EQ(pole.exit_code, 2) << pole.err;
  EXPECT_NE(pole.err.find("rlat = 90"), std::string::npos) << pole.err;
  const auto keys = aq::test::run_aquatoria("regional -c " + (kConfigs / "black_sea.toml").string() +
                                            " --set roms.rmax=1.5 --set roms.distances=ellipsoid --set roms.hmin_m=0"
                                            " -o " +
                                            d.path().string());
  EXPECT_EQ(keys.exit_code, 2) << keys.err;
  for (const char* k : {"roms.rmax", "roms.distances", "roms.hmin_m"})
    EXPECT_NE(keys.err.find(k), std::string::npos) << k << "\n" << keys.err;
}

TEST(RomsDisabled, NoGridFileWhenRomsIsOff) {
  aq::testing::TempDir d;
  const auto r = aq::test::run_aquatoria("-q regional -c " + (kConfigs / "black_sea.toml").string() +
                                         " --set roms.enabled=false -o " + d.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(d / "black_sea_xygrid.nc"));
  EXPECT_FALSE(fs::exists(d / "black_sea_grd.nc"));
}

}  // namespace

}  // namespace clients_roms_grid_client_test
