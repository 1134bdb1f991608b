// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria check`: the table on stdout, the netCDF/PNG/JSON outputs, and failures (exit 1,
// path named, no partial outputs).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netcdf.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/types.hpp"
#include "curvilinear/conformal/laplace_fill.hpp"
#include "grid_files/xygrid_netcdf.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace cli_check_cli_test {

namespace {

using aq::test::run_aquatoria;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;
namespace fs = std::filesystem;

/// A 31×21 grid of parallelograms with a 60° angle: every orthogonality error is cos 60° = 0.5.
aq::io::XyGrid sheared_grid() {
  aq::io::XyGrid g;
  g.grid = aq::curvilinear::Grid2D(31, 21);
  const double c = std::cos(60.0 * aq::kDegToRad);
  const double s = std::sin(60.0 * aq::kDegToRad);
  for (int j = 0; j < 21; ++j) {
    for (int i = 0; i < 31; ++i) {
      g.grid.x[g.grid.at(i, j)] = 1000.0 * i + 1000.0 * c * j;
      g.grid.y[g.grid.at(i, j)] = 1000.0 * s * j;
    }
  }
  g.dxi = 1.0;
  g.deta = 1.0;
  return g;
}

/// The filled conformal grid of w = exp(ζ) on [0, 1.3] × [0, 1], 131 × 101 (ρ = 1).
aq::io::XyGrid annulus_grid() {
  aq::io::XyGrid g;
  g.grid = aq::curvilinear::Grid2D(131, 101);
  g.dxi = 1.3 / 130;
  g.deta = 1.0 / 100;
  for (int j = 0; j < 101; ++j) {
    for (int i = 0; i < 131; ++i) {
      const auto z = 1e5 * std::exp(std::complex<double>(i * g.dxi, j * g.deta));
      g.grid.x[g.grid.at(i, j)] = z.real();
      g.grid.y[g.grid.at(i, j)] = z.imag();
    }
  }
  const auto r = aq::curvilinear::laplace_fill(g.grid, g.dxi, g.deta);
  g.residual_history = r.residual_history;
  return g;
}

TEST(CheckCli, PrintsTheTableAndWritesNetcdfPngAndJson) {
  const aq::testing::TempDir dir;
  const aq::io::XyGrid in = annulus_grid();
  aq::io::write_xygrid(dir / "annulus.nc", in);
  const auto r = run_aquatoria("check " + (dir / "annulus.nc").string() + " --json " + (dir / "q.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("size:     131 x 101 points (130 x 100 cells)"));
  EXPECT_THAT(r.out, HasSubstr("dxi/deta: 1 (from the file)"));
  for (const char* name : {"ortho_err_46", "ortho_err_50", "ortho_err_52", "isotropy_51", "laplace_residual", "f1 ",
                           "f2 ", "f3 ", "f4 "}) {
    EXPECT_THAT(r.out, HasSubstr(std::string("\n") + name)) << name;
  }
  EXPECT_THAT(r.out, HasSubstr("non-convex cells (f1 <= 0): 0"));
  // exp: isosceles-trapezoid cells, so (46) is zero up to the fill's 4th-order error.
  nlohmann::json j;
  std::ifstream(dir / "q.json") >> j;
  EXPECT_LT(j["criteria"]["ortho_err_46"]["worst"].get<double>(), 1e-9);
  EXPECT_LT(j["criteria"]["laplace_residual"]["worst"].get<double>(), 1e-12);
  EXPECT_EQ(j["nx_pts"].get<int>(), 131);
  EXPECT_TRUE(fs::exists(dir / "annulus_check.png"));
  const aq::io::XyGrid back = aq::io::read_xygrid(dir / "annulus_check.nc");
  EXPECT_EQ(back.grid.x, in.grid.x);
  int nc = -1;
  ASSERT_EQ(nc_open((dir / "annulus_check.nc").c_str(), NC_NOWRITE, &nc), NC_NOERR);
  int var = -1;
  EXPECT_EQ(nc_inq_varid(nc, "f1", &var), NC_NOERR);
  EXPECT_EQ(nc_inq_varid(nc, "ortho_err_50", &var), NC_NOERR);
  nc_close(nc);
}

TEST(CheckCli, ShearedGridShowsTheKnownErrorAndWhere) {
  const aq::testing::TempDir dir;
  aq::io::write_xygrid(dir / "shear.nc", sheared_grid());
  const auto r =
      run_aquatoria("check " + (dir / "shear.nc").string() + " -o " + (dir / "out" / "q.nc").string() + " --no-png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // (46), (50): worst = average = rms = 0.5; f2 = sin 60°, f1 = 1 (parallelograms).
  EXPECT_THAT(r.out, MatchesRegex(".*\northo_err_46 +orthogonality error[^\n]+ 5.000e-01   5.000e-01   5.000e-01  "
                                  "cell \\([0-9]+, [0-9]+\\)\n.*"));
  EXPECT_THAT(r.out, MatchesRegex(".*\northo_err_50 +orthogonality error[^\n]+ 5.000e-01   5.000e-01   5.000e-01  "
                                  "cell \\([0-9]+, [0-9]+\\)\n.*"));
  EXPECT_THAT(r.out, MatchesRegex(".*\nf2 +seed-004[^\n]+ 8.660e-01   8.660e-01           -  cell .*"));
  EXPECT_THAT(r.out, MatchesRegex(".*\nf1 +seed-004[^\n]+ 1.000e\\+00   1.000e\\+00           -  cell .*"));
  EXPECT_TRUE(fs::exists(dir / "out" / "q.nc"));
  EXPECT_FALSE(fs::exists(dir / "shear_check.png"));
  EXPECT_FALSE(fs::exists(dir / "shear_check.nc"));
}

TEST(CheckCli, NamesTheNonConvexCell) {
  const aq::testing::TempDir dir;
  aq::io::XyGrid g;
  g.grid = aq::curvilinear::Grid2D(6, 5);
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 6; ++i) {
      g.grid.x[g.grid.at(i, j)] = i;
      g.grid.y[g.grid.at(i, j)] = j;
    }
  }
  g.grid.x[g.grid.at(3, 2)] = 2.3;  // pushed into cell (2, 1), which becomes a dart
  g.grid.y[g.grid.at(3, 2)] = 1.3;
  aq::io::write_xygrid(dir / "dart.nc", g);
  const auto r = run_aquatoria("check " + (dir / "dart.nc").string() + " --no-png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, MatchesRegex(".*\nf1 +seed-004[^\n]+ -[0-9.e+-]+ +[0-9.e+-]+ +-  cell \\(2, 1\\)\n.*"));
  EXPECT_THAT(r.out, MatchesRegex(".*non-convex cells \\(f1 <= 0\\): [1-4]\n.*"));
}

TEST(CheckCli, MissingOrWrongFileIsExitOneNamingIt) {
  const aq::testing::TempDir dir;
  const fs::path missing = dir / "no_such_grid.nc";
  const auto r = run_aquatoria("check " + missing.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr(missing.string()));

  const fs::path other = dir / "other.nc";
  int nc = -1;
  ASSERT_EQ(nc_create(other.c_str(), NC_CLOBBER, &nc), NC_NOERR);
  ASSERT_EQ(nc_close(nc), NC_NOERR);
  const auto w = run_aquatoria("check " + other.string());
  EXPECT_EQ(w.exit_code, 1);
  EXPECT_THAT(w.err, HasSubstr(other.string()));
  EXPECT_THAT(w.err, HasSubstr("no variable 'x'"));
  EXPECT_FALSE(fs::exists(dir / "other_check.nc"));
  EXPECT_FALSE(fs::exists(dir / "other_check.png"));
}

TEST(CheckCli, UnwritableOutputLeavesNoPartialFiles) {
  const aq::testing::TempDir dir;
  aq::io::write_xygrid(dir / "g.nc", sheared_grid());
  std::ofstream(dir / "plain_file") << "x";
  const fs::path bad = dir / "plain_file" / "q.png";  // a "directory" that is a file
  const auto r = run_aquatoria("check " + (dir / "g.nc").string() + " --png " + bad.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("plain_file"));
  EXPECT_FALSE(fs::exists(dir / "g_check.nc"));
  for (const auto& e : fs::directory_iterator(dir.path())) {
    EXPECT_THAT(e.path().filename().string(), ::testing::Not(HasSubstr(".tmp"))) << e.path();
  }
}

TEST(CheckCli, PngAndNoPngExcludeEachOther) {
  const auto r = run_aquatoria("check g.nc --png a.png --no-png");
  EXPECT_EQ(r.exit_code, 2);
}

}  // namespace

}  // namespace cli_check_cli_test
