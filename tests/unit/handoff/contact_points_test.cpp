// ROMS contact points of a child grid in a parent ROMS grid: a warped (curvilinear) parent written
// with the ROMS grid writer and read back, a finer child inside it (bilinear weights in [0, 1],
// summing to 1, reproducing every point to 1e-9°; Idg/Jdg the containing cell; quadratic weights
// exact for quadratic fields in index space), the netCDF file, and a child partly outside refused.
#include <gtest/gtest.h>
#include <netcdf.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "curvilinear/cgrid.hpp"
#include "handoff/contact_points.hpp"
#include "io/contact_netcdf.hpp"
#include "io/roms_grid.hpp"
#include "support/temp_dir.hpp"

namespace {

using aq::curvilinear::CGrid;
using aq::curvilinear::Grid2D;
using aq::curvilinear::Projection;
using aq::curvilinear::ProjectionParams;

// L x M cells on [cx-w, cx+w] x [cy-h, cy+h] plane units, warped by `warp` (curvilinear lines).
Grid2D grid(int L, int M, double cx, double cy, double w, double h, double warp) {
  Grid2D g(2 * L + 1, 2 * M + 1);
  for (int j = 0; j < g.ny_pts; ++j)
    for (int i = 0; i < g.nx_pts; ++i) {
      const double x = cx - w + 2.0 * w * i / (g.nx_pts - 1), y = cy - h + 2.0 * h * j / (g.ny_pts - 1);
      g.x[g.at(i, j)] = x + warp * std::sin(y / 40.0);
      g.y[g.at(i, j)] = y + warp * std::sin(x / 50.0);
    }
  return g;
}

Projection mercator() {
  ProjectionParams p;
  p.rlon_deg = -60.0;
  p.rlat_deg = 30.0;
  p.uscale = 0.001;
  return Projection(p);
}

// Writes a parent ROMS grid (20 x 16 cells, ±100 x ±80 plane units, warped) and reads it back.
aq::io::RomsGridFields parent_fields(const aq::testing::TempDir& dir, CGrid* out_grid = nullptr) {
  const CGrid cg = aq::curvilinear::build_cgrid(grid(20, 16, 0, 0, 100, 80, 6.0), mercator());
  aq::io::RomsGridData d;
  d.grid = &cg;
  d.h.assign(cg.rho.size(), 0.0);
  for (std::size_t k = 0; k < d.h.size(); ++k) d.h[k] = 100.0 + 10.0 * static_cast<double>(k % 7);
  d.hraw = d.h;
  d.mask_rho.assign(cg.rho.size(), 1);
  d.mask_u.assign(cg.u.size(), 1);
  d.mask_v.assign(cg.v.size(), 1);
  d.mask_psi.assign(cg.psi.size(), 1);
  const auto path = dir.path() / "parent_grd.nc";
  aq::io::write_roms_grid(path, d);
  if (out_grid != nullptr) *out_grid = cg;
  return aq::io::read_roms_grid_fields(path);
}

}  // namespace

TEST(ContactPoints, ChildInsideParent) {
  aq::testing::TempDir dir;
  const auto parent = parent_fields(dir);
  EXPECT_EQ(parent.L, 20);
  EXPECT_EQ(parent.M, 16);
  const CGrid child = aq::curvilinear::build_cgrid(grid(24, 18, 10, -5, 50, 40, 3.0), mercator());
  aq::handoff::ContactSummary sum;
  const auto f = aq::handoff::contact_points(parent, child, "child.toml", &sum);
  // Perimeter points: ρ 2(L+1) + 2(M-1), u 2L + 2(M-1), v 2(L-1) + 2M (each once).
  const std::size_t L = 24, M = 18;
  EXPECT_EQ(sum.rho, 2 * (L + 1) + 2 * (M - 1));
  EXPECT_EQ(sum.u, 2 * L + 2 * (M - 1));
  EXPECT_EQ(sum.v, 2 * (L - 1) + 2 * M);
  ASSERT_EQ(f.size(), sum.rho + sum.u + sum.v);
  EXPECT_EQ(f.NstrR, 1);
  EXPECT_EQ(f.NendR + 1, f.NstrU);
  EXPECT_EQ(f.NendU + 1, f.NstrV);
  EXPECT_EQ(static_cast<std::size_t>(f.NendV), f.size());
  // Child cells ~2.4 times smaller than the parent's (100/20 vs 50/24 plane units).
  EXPECT_NEAR(sum.ratio_median, 2.4, 0.2);
  EXPECT_EQ(f.refine_factor[1], 2);
  for (std::size_t k = 0; k < f.size(); ++k) {
    const int type = static_cast<int>(k) < f.NstrU - 1 ? 0 : static_cast<int>(k) < f.NstrV - 1 ? 1 : 2;
    const auto& lon = type == 0 ? parent.lon_rho : type == 1 ? parent.lon_u : parent.lon_v;
    const auto& lat = type == 0 ? parent.lat_rho : type == 1 ? parent.lat_u : parent.lat_v;
    const int ni = type == 1 ? parent.L : parent.L + 1;
    const int ci = f.Idg[k] - (type == 1 ? 1 : 0), cj = f.Jdg[k] - (type == 2 ? 1 : 0);
    ASSERT_GE(ci, 0);
    ASSERT_GE(cj, 0);
    const auto at = [&](int i, int j) { return static_cast<std::size_t>(j * ni + i); };
    const std::size_t c[4] = {at(ci, cj), at(ci + 1, cj), at(ci + 1, cj + 1), at(ci, cj + 1)};
    double s = 0, x = 0, y = 0;
    for (std::size_t q = 0; q < 4; ++q) {
      const double w = f.Lweight[k][q];
      EXPECT_GE(w, 0.0);
      EXPECT_LE(w, 1.0);
      s += w;
      x += w * lon[c[q]];
      y += w * lat[c[q]];
    }
    EXPECT_NEAR(s, 1.0, 1e-12) << k;
    EXPECT_NEAR(x, f.Xrg[k], 1e-9) << k;
    EXPECT_NEAR(y, f.Yrg[k], 1e-9) << k;
    // Weights strictly inside [0, 1] on both axes is what "containing cell" means; a neighbour cell
    // would need a negative weight to reproduce the point.
    double qs = 0;
    for (double w : f.Qweight[k]) qs += w;
    EXPECT_NEAR(qs, 1.0, 1e-12) << k;
    EXPECT_GE(f.on_boundary[k], 1);
    EXPECT_LE(f.on_boundary[k], 4);
    EXPECT_GT(f.pm[k], 0.0);
    EXPECT_GT(f.h[k], 99.0);
    EXPECT_EQ(f.mask[k], 1.0);
  }
  // A known point: the child's south-west ρ corner is ρ (0, 0), on the western boundary.
  EXPECT_EQ(f.Irg[0], 0);
  EXPECT_EQ(f.Jrg[0], 0);
  EXPECT_EQ(f.on_boundary[0], 1);
  EXPECT_NEAR(f.Xrg[0], child.rho.lon_deg[0], 0.0);
  // The first u point has ROMS I = 1.
  EXPECT_EQ(f.Irg[static_cast<std::size_t>(f.NstrU - 1)], 1);

  const auto path = dir.path() / "child_contact.nc";
  aq::io::write_contact(path, f);
  int nc = -1;
  ASSERT_EQ(nc_open(path.c_str(), NC_NOWRITE, &nc), NC_NOERR);
  for (const auto& v : aq::io::contact_variables()) {
    int id = -1;
    EXPECT_EQ(nc_inq_varid(nc, v.c_str(), &id), NC_NOERR) << v;
  }
  int dim = -1;
  std::size_t len = 0;
  ASSERT_EQ(nc_inq_dimid(nc, "datum", &dim), NC_NOERR);
  ASSERT_EQ(nc_inq_dimlen(nc, dim, &len), NC_NOERR);
  EXPECT_EQ(len, f.size());
  nc_close(nc);
}

TEST(ContactPoints, IdgJdgIsTheContainingCellOfAKnownPoint) {
  // A child ρ point at a parent ρ cell's centre (in index space of an unwarped parent): the
  // child is built from the parent's own supergrid lines.
  aq::testing::TempDir dir;
  CGrid pg;
  const auto parent = parent_fields(dir, &pg);
  // Every parent ρ point strictly inside is located in a cell having it as a corner with weight 1.
  aq::curvilinear::CGrid child = pg;  // child = parent's interior ρ points (a trimmed copy)
  const int ni = 5, nj = 4, i0 = 7, j0 = 6;
  child.L = ni - 1;
  child.M = nj - 1;
  const auto take = [&](const aq::curvilinear::StaggeredPoints& src, int n_i, int n_j, int a, int b) {
    aq::curvilinear::StaggeredPoints s;
    s.ni = n_i;
    s.nj = n_j;
    for (int j = 0; j < n_j; ++j)
      for (int i = 0; i < n_i; ++i) {
        s.lon_deg.push_back(src.lon_deg[src.at(a + i, b + j)]);
        s.lat_deg.push_back(src.lat_deg[src.at(a + i, b + j)]);
      }
    return s;
  };
  child.rho = take(pg.rho, ni, nj, i0, j0);
  child.u = take(pg.u, ni - 1, nj, i0, j0);
  child.v = take(pg.v, ni, nj - 1, i0, j0);
  child.pm.clear();
  const auto f = aq::handoff::contact_points(parent, child, "child.toml");
  // ρ (0, 0) of the child is parent ρ (7, 6): the point is a corner of the donor cell, weight 1.
  const int i = f.Idg[0], j = f.Jdg[0];
  EXPECT_TRUE((i == i0 || i == i0 - 1) && (j == j0 || j == j0 - 1)) << i << " " << j;
  double wmax = 0;
  for (double w : f.Lweight[0]) wmax = std::max(wmax, w);
  EXPECT_NEAR(wmax, 1.0, 1e-9);
}

TEST(ContactPoints, ChildPartlyOutsideIsAnError) {
  aq::testing::TempDir dir;
  const auto parent = parent_fields(dir);
  // Reaches 30 plane units past the parent's eastern edge.
  const CGrid child = aq::curvilinear::build_cgrid(grid(20, 10, 80, 0, 50, 30, 0.0), mercator());
  try {
    (void)aq::handoff::contact_points(parent, child, "configs/child.toml: nesting.parent = p_grd.nc");
    FAIL() << "no error";
  } catch (const aq::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("configs/child.toml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("outside the parent"), std::string::npos) << e.what();
  }
}

TEST(ContactPoints, MissingParentFileIsAnInputError) {
  EXPECT_THROW((void)aq::io::read_roms_grid_fields("/nonexistent/p_grd.nc"), aq::InputError);
}
