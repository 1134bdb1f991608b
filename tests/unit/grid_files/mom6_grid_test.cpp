// SPDX-License-Identifier: GPL-3.0-or-later
// MOM6 grid files (ocean_hgrid.nc, ocean_topog.nc, ocean_mask.nc) of an izogrid supergrid, parsed
// back: the supergrid's dx, dy and area summed on the sphere against the ROMS metrics pm, pn of
// the same grid; the topography and mask on the cells; any_grid reads ROMS and MOM6 files for
// `aquatoria check`.
#include "grid_files/mom6_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "curvilinear/common/cgrid.hpp"
#include "curvilinear/common/grid_checks.hpp"
#include "grid_files/any_grid.hpp"
#include "grid_files/roms_grid.hpp"
#include "support/temp_dir.hpp"
#include "support/uniform_grid.hpp"

namespace aq::io::unit_grid_files_mom6_grid_test {
namespace {

// A curved (but conformal-map-like) supergrid of (2nx+1) x (2ny+1) points in Mercator plane units.
curvilinear::Grid2D plane_grid(int nx, int ny) {
  curvilinear::Grid2D g = aq::testing::uniform_supergrid(nx, ny, 50.0, 30.0);
  for (std::size_t k = 0; k < g.x.size(); ++k) {
    const double u = g.x[k], v = g.y[k];
    g.x[k] = u + 1e-3 * (u * u - v * v);  // z + 0.001 z²: conformal, orthogonal lines
    g.y[k] = v + 2e-3 * u * v;
  }
  return g;
}

struct Fixture {
  curvilinear::Grid2D super = plane_grid(12, 8);
  curvilinear::ProjectionParams params;
  std::optional<curvilinear::Projection> proj;
  curvilinear::CGrid cg;
  std::vector<double> h, mask;
  Fixture() {
    params.rlat_deg = 43.75;
    params.rlon_deg = 34.5;
    proj.emplace(params);
    cg = curvilinear::build_cgrid(super, *proj);
    for (std::size_t k = 0; k < cg.rho.size(); ++k) {
      h.push_back(50.0 + static_cast<double>(k));
      mask.push_back(k % 5 == 0 ? 0.0 : 1.0);
    }
  }
};

TEST(Mom6Grid, SupergridMetricsAddUpToTheRomsMetricsOnTheSphere) {
  Fixture f;
  aq::testing::TempDir dir;
  const Mom6Grid m = mom6_grid(f.super, *f.proj, f.h, f.mask, 6371000.0);
  write_mom6_files(m, dir / "ocean_hgrid.nc", dir / "ocean_topog.nc", dir / "ocean_mask.nc", "test");
  const Mom6Grid r = read_mom6_hgrid(dir / "ocean_hgrid.nc");
  ASSERT_EQ(r.nx, f.cg.L - 1);
  ASSERT_EQ(r.ny, f.cg.M - 1);
  const int nxp = r.nxp(), nyp = r.nyp();
  ASSERT_EQ(r.x.size(), static_cast<std::size_t>(nxp * nyp));
  double area_mom6 = 0.0, area_roms = 0.0;
  for (int j = 0; j < r.ny; ++j)
    for (int i = 0; i < r.nx; ++i) {
      const std::size_t k = f.cg.rho.at(i + 1, j + 1);
      // The cell centre is supergrid (2i+1, 2j+1); the two half steps through it along i and j.
      const double dx = r.dx[static_cast<std::size_t>(2 * j + 1) * static_cast<std::size_t>(nxp - 1) + 2 * i] +
                        r.dx[static_cast<std::size_t>(2 * j + 1) * static_cast<std::size_t>(nxp - 1) + 2 * i + 1];
      const double dy = r.dy[static_cast<std::size_t>(2 * j) * static_cast<std::size_t>(nxp) + 2 * i + 1] +
                        r.dy[static_cast<std::size_t>(2 * j + 1) * static_cast<std::size_t>(nxp) + 2 * i + 1];
      EXPECT_NEAR(dx * f.cg.pm[k], 1.0, 1e-9) << i << "," << j;
      EXPECT_NEAR(dy * f.cg.pn[k], 1.0, 1e-9) << i << "," << j;
      double a = 0.0;
      for (int q = 0; q < 4; ++q)
        a += r.area[static_cast<std::size_t>(2 * j + q / 2) * static_cast<std::size_t>(nxp - 1) + 2 * i + q % 2];
      EXPECT_NEAR(a * f.cg.pm[k] * f.cg.pn[k], 1.0, 2e-3) << i << "," << j;
      area_mom6 += a;
      area_roms += 1.0 / (f.cg.pm[k] * f.cg.pn[k]);
      // Positions: the cell centre is the ROMS rho point, the corners its psi points.
      const std::size_t c = static_cast<std::size_t>(2 * j + 1) * static_cast<std::size_t>(nxp) + 2 * i + 1;
      EXPECT_NEAR(r.x[c], f.cg.rho.lon_deg[k], 1e-12);
      EXPECT_NEAR(r.y[c], f.cg.rho.lat_deg[k], 1e-12);
      // angle_dx in degrees against the ROMS angle in radians.
      EXPECT_NEAR(r.angle_dx[c] * M_PI / 180.0, f.cg.angle[k], 2e-3) << i << "," << j;
    }
  EXPECT_NEAR(area_mom6 / area_roms, 1.0, 1e-4);
  // Depth and mask on the cells: ROMS rho (i+1, j+1); land has depth 0.
  int nx = 0, ny = 0;
  const auto depth = read_mom6_field(dir / "ocean_topog.nc", "depth", nx, ny);
  const auto mask = read_mom6_field(dir / "ocean_mask.nc", "mask", nx, ny);
  ASSERT_EQ(nx, r.nx);
  ASSERT_EQ(ny, r.ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = f.cg.rho.at(i + 1, j + 1), c = static_cast<std::size_t>(j * nx + i);
      EXPECT_EQ(mask[c], f.mask[k]);
      EXPECT_EQ(depth[c], f.mask[k] != 0.0 ? f.h[k] : 0.0);
    }
}

TEST(Mom6Grid, CheckReadsRomsAndMom6FilesAsOrthogonalGrids) {
  Fixture f;
  aq::testing::TempDir dir;
  const Mom6Grid m = mom6_grid(f.super, *f.proj, f.h, f.mask, 6371000.0);
  write_mom6_files(m, dir / "h.nc", dir / "t.nc", dir / "m.nc", "test");
  RomsGridData data;
  data.grid = &f.cg;
  data.h = f.h;
  data.hraw = f.h;
  for (const double v : f.mask) data.mask_rho.push_back(v != 0.0 ? 1 : 0);
  data.mask_u.assign(f.cg.u.size(), 1);
  data.mask_v.assign(f.cg.v.size(), 1);
  data.mask_psi.assign(f.cg.psi.size(), 1);
  write_roms_grid(dir / "x_grd.nc", data);

  const AnyGrid roms = read_any_grid(dir / "x_grd.nc");
  EXPECT_EQ(roms.kind, GridFileKind::kRoms);
  EXPECT_EQ(roms.xy.grid.nx_pts, f.super.nx_pts);
  EXPECT_EQ(roms.xy.grid.ny_pts, f.super.ny_pts);
  const AnyGrid mom6 = read_any_grid(dir / "h.nc");
  EXPECT_EQ(mom6.kind, GridFileKind::kMom6);
  EXPECT_EQ(mom6.xy.grid.nx_pts, f.super.nx_pts - 2);
  // The source grid is conformal, so the checks see orthogonal cells on the sphere too.
  for (const AnyGrid* g : {&roms, &mom6}) {
    const curvilinear::GridQuality q = curvilinear::check_grid(g->xy.grid, {});
    EXPECT_TRUE(q.non_finite.empty());
    EXPECT_LT(q.ortho_50.worst, 1e-3) << name_of(g->kind);
  }
  EXPECT_THROW(read_any_grid(dir / "t.nc"), InputError);  // a topography is not a grid
}

}  // namespace
}  // namespace aq::io::unit_grid_files_mom6_grid_test
