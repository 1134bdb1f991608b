// SPDX-License-Identifier: GPL-3.0-or-later
// ROMS contact points of a refinement grid (handoff/contact_points.hpp): a warped parent written
// with the ROMS grid writer and read back, its ψ box refined 3 × 3 (curvilinear/refine.hpp). The
// worked example of the ROMS contact.m conventions (Idg/Jdg, bilinear weights), the point counts of
// both regions, the on_boundary lines ROMS needs one point per row of, the fine→coarse points
// carrying the parent's own values at the centre fine point, the netCDF file, and boxes too close to
// the parent's edge refused.
#include <gtest/gtest.h>
#include <netcdf.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "curvilinear/common/cgrid.hpp"
#include "curvilinear/common/refine.hpp"
#include "grid_files/contact_netcdf.hpp"
#include "grid_files/roms_grid.hpp"
#include "handoff/contact_points.hpp"
#include "support/temp_dir.hpp"
#include "support/uniform_grid.hpp"

namespace unit_handoff_contact_points_test {

namespace {

using aq::curvilinear::CGrid;
using aq::curvilinear::Grid2D;
using aq::curvilinear::Projection;
using aq::curvilinear::ProjectionParams;
using aq::curvilinear::RefineBox;

constexpr int kPad = 4;

// L x M cells on [cx-w, cx+w] x [cy-h, cy+h] plane units, warped by `warp` (curvilinear lines).
Grid2D grid(int L, int M, double cx, double cy, double w, double h, double warp) {
  Grid2D g = aq::testing::uniform_grid(2 * L + 1, 2 * M + 1, cx - w, cx + w, cy - h, cy + h);
  for (std::size_t k = 0; k < g.x.size(); ++k) {
    const double x = g.x[k], y = g.y[k];
    g.x[k] = x + warp * std::sin(y / 40.0);
    g.y[k] = y + warp * std::sin(x / 50.0);
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

struct ParentGrid {
  Grid2D plane;  // the parent's supergrid
  aq::io::RomsGridFields parent;
};

// A parent ROMS grid (30 x 26 cells, ±150 x ±130 plane units, warped) written and read back; h and
// the ρ mask vary so that copied values can be told apart.
ParentGrid parent_setup(const aq::testing::TempDir& dir) {
  ParentGrid s;
  s.plane = grid(30, 26, 0, 0, 150, 130, 6.0);
  const CGrid cg = aq::curvilinear::build_cgrid(s.plane, mercator());
  aq::io::RomsGridData d;
  d.grid = &cg;
  d.h.assign(cg.rho.size(), 0.0);
  for (std::size_t k = 0; k < d.h.size(); ++k) d.h[k] = 100.0 + 10.0 * static_cast<double>(k % 7);
  d.hraw = d.h;
  d.mask_rho.assign(cg.rho.size(), 1);
  for (std::size_t k = 0; k < d.mask_rho.size(); k += 5) d.mask_rho[k] = 0;
  d.mask_u.assign(cg.u.size(), 1);
  d.mask_v.assign(cg.v.size(), 1);
  d.mask_psi.assign(cg.psi.size(), 1);
  const auto path = dir.path() / "parent_grd.nc";
  aq::io::write_roms_grid(path, d);
  s.parent = aq::io::read_roms_grid_fields(path);
  return s;
}

CGrid fine_grid(const ParentGrid& s, const RefineBox& b) {
  return aq::curvilinear::build_cgrid(aq::curvilinear::refine_supergrid(s.plane, b, kPad), mercator());
}

// Index of the first point of `region` (1, 2) and type (0 ρ, 1 u, 2 v) with receiver (I, J), or -1.
long find(const aq::io::ContactFile& f, int region, int type, int I, int J) {
  const auto& r = f.regions[static_cast<std::size_t>(region - 1)];
  const int s = type == 0 ? r.NstrR : type == 1 ? r.NstrU : r.NstrV;
  const int e = type == 0 ? r.NendR : type == 1 ? r.NendU : r.NendV;
  for (int k = s - 1; k < e; ++k)
    if (f.Irg[static_cast<std::size_t>(k)] == I && f.Jrg[static_cast<std::size_t>(k)] == J) return k;
  return -1;
}

}  // namespace

TEST(ContactPoints, WorkedExampleOfTheRomsConventions) {
  // r = 3, Io = 10, Jo = 20 (the conventions of ROMS's contact.m): fine ρ(i) lies at coarse
  // ξ = 10 + (i − 1/2)/3, in the coarse ρ cell whose lower-left ρ point is at ξ = Idg + 1/2.
  aq::testing::TempDir dir;
  const ParentGrid s = parent_setup(dir);
  const RefineBox b{10, 16, 20, 24, 3};
  const auto f = aq::handoff::refinement_contact(s.parent, b, fine_grid(s, b), kPad);
  const long r11 = find(f, 1, 0, 1, 1), r22 = find(f, 1, 0, 2, 2), u11 = find(f, 1, 1, 1, 1);
  // ρ (1,1) and (2,2) are interior fine points (1..Lm x 1..Mm), which are not contact points.
  EXPECT_EQ(r11, -1);
  EXPECT_EQ(r22, -1);
  // ρ (1, 0): ξ = 10 + 1/6, η = 20 − 1/6 → cell (9, 19), p = 2/3, q = 1/3.
  const long r10 = find(f, 1, 0, 1, 0);
  ASSERT_GE(r10, 0);
  const auto k = static_cast<std::size_t>(r10);
  EXPECT_EQ(f.Idg[k], 9);
  EXPECT_EQ(f.Jdg[k], 19);
  const double p = 2.0 / 3.0, q = 1.0 / 3.0;
  EXPECT_NEAR(f.Lweight[k][0], (1 - p) * (1 - q), 1e-15);
  EXPECT_NEAR(f.Lweight[k][1], p * (1 - q), 1e-15);
  EXPECT_NEAR(f.Lweight[k][2], p * q, 1e-15);
  EXPECT_NEAR(f.Lweight[k][3], (1 - p) * q, 1e-15);
  EXPECT_NEAR(f.xi_rg[k], 10.0 + 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(f.eta_rg[k], 20.0 - 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(f.xi_dg[k], 9.5, 0.0);
  // u (1, 1): on the fine western boundary, at coarse ξ = 10 exactly: donor u (10, 19), p = 0,
  // q = 2/3 → weights (1/3, 0, 0, 2/3); on_boundary = 1 (west).
  ASSERT_GE(u11, 0);
  const auto ku = static_cast<std::size_t>(u11);
  EXPECT_EQ(f.Idg[ku], 10);
  EXPECT_EQ(f.Jdg[ku], 19);
  EXPECT_NEAR(f.Lweight[ku][0], 1.0 / 3.0, 1e-15);
  EXPECT_EQ(f.Lweight[ku][1], 0.0);
  EXPECT_EQ(f.Lweight[ku][2], 0.0);
  EXPECT_NEAR(f.Lweight[ku][3], 2.0 / 3.0, 1e-15);
  EXPECT_EQ(f.on_boundary[ku], 1);
  // ρ (−1, −1): ξ = 10 − 1/2 → coarse ρ (9, 19) itself, weight 1 on the first corner.
  const long rm = find(f, 1, 0, -1, -1);
  ASSERT_GE(rm, 0);
  const auto km = static_cast<std::size_t>(rm);
  EXPECT_EQ(f.Idg[km], 9);
  EXPECT_EQ(f.Jdg[km], 19);
  EXPECT_EQ(f.Lweight[km][0], 1.0);
  // A fine ρ point that is a coarse ρ point sits there on the Earth, and carries its h.
  const std::size_t cr = s.parent.rho_at(9, 19);
  EXPECT_NEAR(f.Xrg[km], s.parent.lon_rho[cr], 1e-9);
  EXPECT_NEAR(f.Yrg[km], s.parent.lat_rho[cr], 1e-9);
  EXPECT_EQ(f.h[km], s.parent.h[cr]);
}

TEST(ContactPoints, CountsRangesBoundaryLinesAndWeights) {
  aq::testing::TempDir dir;
  const ParentGrid s = parent_setup(dir);
  const RefineBox b{6, 20, 5, 17, 3};
  const CGrid fine = fine_grid(s, b);
  aq::handoff::ContactSummary sum;
  const auto f = aq::handoff::refinement_contact(s.parent, b, fine, kPad, &sum);
  const std::size_t Lm = 3 * 14, Mm = 3 * 12;
  EXPECT_EQ(f.Lm[1], static_cast<int>(Lm));
  EXPECT_EQ(f.Mm[1], static_cast<int>(Mm));
  EXPECT_EQ(f.Lm[0], 29);
  EXPECT_EQ(f.Mm[0], 25);
  // Region 1: the band of 4 (west/south) and 3 (east/north) rows around the interior.
  EXPECT_EQ(sum.coarse_to_fine[0], (Lm + 7) * (Mm + 7) - Lm * Mm);
  EXPECT_EQ(sum.coarse_to_fine[1], (Lm + 6) * (Mm + 7) - (Lm - 1) * Mm);
  EXPECT_EQ(sum.coarse_to_fine[2], (Lm + 7) * (Mm + 6) - Lm * (Mm - 1));
  // Region 2: the coarse points inside the box.
  EXPECT_EQ(sum.fine_to_coarse[0], 14u * 12u);
  EXPECT_EQ(sum.fine_to_coarse[1], 13u * 12u);
  EXPECT_EQ(sum.fine_to_coarse[2], 14u * 11u);
  // The six ranges tile 1..N.
  int next = 1;
  for (const auto& r : f.regions)
    for (const auto& [a, e] : {std::pair{r.NstrR, r.NendR}, std::pair{r.NstrU, r.NendU}, std::pair{r.NstrV, r.NendV}}) {
      EXPECT_EQ(a, next);
      next = e + 1;
    }
  EXPECT_EQ(static_cast<std::size_t>(next - 1), f.size());
  EXPECT_EQ(sum.points, f.size());
  EXPECT_NEAR(sum.ratio_median, 3.0, 0.01);  // fine steps a third of the coarse

  // on_boundary: exactly one u point per fine row j = 1..Mm on each of west (1) and east (3), one v
  // point per column i = 1..Lm on south (2) and north (4); none elsewhere.
  std::vector<int> west(Mm + 1), east(Mm + 1), south(Lm + 1), north(Lm + 1);
  for (std::size_t k = 0; k < f.size(); ++k) {
    const int ob = f.on_boundary[k];
    if (ob == 0) continue;
    ASSERT_EQ(f.contact_region[k], 1);
    if (ob == 1 || ob == 3) {
      ASSERT_GE(static_cast<int>(k), f.regions[0].NstrU - 1);
      ASSERT_LT(static_cast<int>(k), f.regions[0].NendU);
      EXPECT_EQ(f.Irg[k], ob == 1 ? 1 : static_cast<int>(Lm) + 1);
      ++(ob == 1 ? west : east)[static_cast<std::size_t>(f.Jrg[k])];
    } else {
      ASSERT_GE(static_cast<int>(k), f.regions[0].NstrV - 1);
      EXPECT_EQ(f.Jrg[k], ob == 2 ? 1 : static_cast<int>(Mm) + 1);
      ++(ob == 2 ? south : north)[static_cast<std::size_t>(f.Irg[k])];
    }
  }
  for (std::size_t j = 1; j <= Mm; ++j) EXPECT_TRUE(west[j] == 1 && east[j] == 1) << j;
  for (std::size_t i = 1; i <= Lm; ++i) EXPECT_TRUE(south[i] == 1 && north[i] == 1) << i;

  // Region 1 weights: in [0, 1], sum 1; bilinear weights reproduce the point's coarse fractional
  // index; quadratic weights sum to 1 and reproduce the linear offset; fields only in ρ slots.
  for (int k = 0; k < f.regions[0].NendV; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const auto& w = f.Lweight[kk];
    double sw = 0;
    for (double x : w) {
      EXPECT_GE(x, 0.0);
      EXPECT_LE(x, 1.0);
      sw += x;
    }
    EXPECT_NEAR(sw, 1.0, 1e-14);
    const bool u = k >= f.regions[0].NstrU - 1 && k < f.regions[0].NendU;
    const bool v = k >= f.regions[0].NstrV - 1;
    const double x0 = u ? f.Idg[kk] : f.Idg[kk] + 0.5, y0 = v ? f.Jdg[kk] : f.Jdg[kk] + 0.5;
    EXPECT_NEAR(x0 + w[1] + w[2], f.xi_rg[kk], 1e-13);
    EXPECT_NEAR(y0 + w[2] + w[3], f.eta_rg[kk], 1e-13);
    double qs = 0, qx = 0;
    for (std::size_t m = 0; m < 9; ++m) {
      qs += f.Qweight[kk][m];
      qx += f.Qweight[kk][m] * (static_cast<double>(m % 3) - 1.0);
    }
    EXPECT_NEAR(qs, 1.0, 1e-13);
    EXPECT_NEAR(qx + x0, f.xi_rg[kk], 1e-13);
    if (u || v) {
      EXPECT_EQ(f.h[kk], aq::io::kContactFill);
      EXPECT_EQ(f.pm[kk], aq::io::kContactFill);
    } else {
      EXPECT_GT(f.h[kk], 99.0);
      EXPECT_GT(f.pm[kk], 0.0);
    }
  }

  // Region 2: the coarse grid's own values and positions; the donor is the fine point at the
  // coarse point's centre, so for ρ it is the same place on the Earth; weights 0.
  for (int k = f.regions[1].NstrR - 1; k < f.regions[1].NendR; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const std::size_t c = s.parent.rho_at(f.Irg[kk], f.Jrg[kk]);
    EXPECT_EQ(f.contact_region[kk], 2);
    EXPECT_EQ(f.on_boundary[kk], 0);
    EXPECT_EQ(f.h[kk], s.parent.h[c]);
    EXPECT_EQ(f.pm[kk], s.parent.pm[c]);
    EXPECT_EQ(f.angle[kk], s.parent.angle[c]);
    EXPECT_EQ(f.mask[kk], s.parent.mask_rho[c]);
    EXPECT_EQ(f.Xrg[kk], s.parent.lon_rho[c]);
    EXPECT_EQ((f.Idg[kk] - 2) % 3, 0);  // (r+1)/2 + 3 (i − Io)
    EXPECT_NEAR(f.Xdg[kk], s.parent.lon_rho[c], 1e-9);
    EXPECT_NEAR(f.Ydg[kk], s.parent.lat_rho[c], 1e-9);
    for (double x : f.Lweight[kk]) EXPECT_EQ(x, 0.0);
  }

  const auto path = dir.path() / "fine_contact.nc";
  aq::io::write_contact(path, f);
  int nc = -1;
  ASSERT_EQ(nc_open(path.c_str(), NC_NOWRITE, &nc), NC_NOERR);
  for (const auto& name : aq::io::contact_variables()) {
    int id = -1;
    EXPECT_EQ(nc_inq_varid(nc, name.c_str(), &id), NC_NOERR) << name;
  }
  int dim = -1, var = -1;
  std::size_t len = 0;
  ASSERT_EQ(nc_inq_dimid(nc, "datum", &dim), NC_NOERR);
  ASSERT_EQ(nc_inq_dimlen(nc, dim, &len), NC_NOERR);
  EXPECT_EQ(len, f.size());
  int box[2] = {0, 0};
  ASSERT_EQ(nc_inq_varid(nc, "I_left", &var), NC_NOERR);
  ASSERT_EQ(nc_get_var_int(nc, var, box), NC_NOERR);
  EXPECT_EQ(box[0], -999);
  EXPECT_EQ(box[1], 6);
  nc_close(nc);
}

TEST(ContactPoints, BoxTooCloseToTheParentEdgeIsRefused) {
  aq::testing::TempDir dir;
  const ParentGrid s = parent_setup(dir);
  for (const RefineBox b : {RefineBox{1, 10, 5, 10, 3}, RefineBox{5, 30, 5, 10, 3}, RefineBox{5, 10, 5, 26, 5}}) {
    EXPECT_NE(aq::handoff::refinement_box_problem(b, s.parent.L, s.parent.M).find("must lie within"),
              std::string::npos);
  }
  EXPECT_EQ(aq::handoff::refinement_box_problem(RefineBox{2, 29, 2, 25, 3}, s.parent.L, s.parent.M), "");
  const RefineBox bad{1, 10, 5, 10, 3};
  EXPECT_THROW((void)aq::handoff::refinement_contact(s.parent, bad, CGrid{}, kPad), aq::ConfigError);
}

TEST(ContactPoints, MissingParentFileIsAnInputError) {
  EXPECT_THROW((void)aq::io::read_roms_grid_fields("/nonexistent/p_grd.nc"), aq::InputError);
}

TEST(ContactPoints, ParentFieldOnTheFineGridMatchesTheContactPoints) {
  aq::testing::TempDir dir;
  const ParentGrid s = parent_setup(dir);
  const RefineBox b{6, 20, 5, 17, 3};
  const auto f = aq::handoff::refinement_contact(s.parent, b, fine_grid(s, b), kPad);
  const auto h = aq::handoff::parent_rho_on_fine(s.parent, s.parent.h, b);
  const int L = b.L(), M = b.M();
  ASSERT_EQ(h.size(), static_cast<std::size_t>((L + 1) * (M + 1)));
  const auto at = [&](int i, int j) { return h[static_cast<std::size_t>(j * (L + 1) + i)]; };
  // Fine ρ (2 + 3m, 2 + 3n) is coarse ρ (6 + m, 5 + n): the parent's value itself.
  for (int n = 0; n < 12; ++n)
    for (int m = 0; m < 14; ++m) EXPECT_EQ(at(2 + 3 * m, 2 + 3 * n), s.parent.h[s.parent.rho_at(6 + m, 5 + n)]);
  // On the outer ring it is the region-1 contact value.
  int ring = 0;
  for (int k = 0; k < f.regions[0].NendR; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    if (f.Irg[kk] < 0 || f.Jrg[kk] < 0 || f.Irg[kk] > L || f.Jrg[kk] > M) continue;
    EXPECT_EQ(at(f.Irg[kk], f.Jrg[kk]), f.h[kk]);
    ++ring;
  }
  EXPECT_EQ(ring, 2 * (L + 1) + 2 * (M - 1));
}

TEST(ContactPoints, ReceiverValuesInsideTheFineGridComeFromItsFile) {
  // With the fine grid file's h and masks, region-1 points inside the fine grid carry them (ROMS
  // copies them onto the grid: the files then agree); points outside keep the coarse values.
  aq::testing::TempDir dir;
  const ParentGrid s = parent_setup(dir);
  const RefineBox b{6, 20, 5, 17, 3};
  const int L = b.L(), M = b.M();
  aq::handoff::ReceiverValues rv;
  rv.h.resize(static_cast<std::size_t>((L + 1) * (M + 1)));
  for (std::size_t k = 0; k < rv.h.size(); ++k) rv.h[k] = 1000.0 + static_cast<double>(k);
  rv.mask_rho.assign(rv.h.size(), 0);
  rv.mask_u.assign(static_cast<std::size_t>(L * (M + 1)), 0);
  rv.mask_v.assign(static_cast<std::size_t>((L + 1) * M), 0);
  rv.mask_u[static_cast<std::size_t>(3 * L + 0)] = 1;  // u I = 1, J = 3 (file 0, 3)
  const auto plain = aq::handoff::refinement_contact(s.parent, b, fine_grid(s, b), kPad);
  const auto f = aq::handoff::refinement_contact(s.parent, b, fine_grid(s, b), kPad, nullptr, &rv);
  ASSERT_EQ(f.size(), plain.size());
  int inside = 0, outside = 0;
  const auto& r1 = f.regions[0];
  for (int k = 0; k < r1.NendV; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const int I = f.Irg[kk], J = f.Jrg[kk];
    const bool rho = k < r1.NendR, u = !rho && k < r1.NendU;
    const int fi = u ? I - 1 : I, fj = (!rho && !u) ? J - 1 : J;
    const int ni = u ? L : L + 1, nj = (!rho && !u) ? M : M + 1;
    if (fi < 0 || fj < 0 || fi >= ni || fj >= nj) {
      EXPECT_EQ(f.mask[kk], plain.mask[kk]) << k;
      EXPECT_EQ(f.h[kk], plain.h[kk]) << k;
      ++outside;
      continue;
    }
    ++inside;
    const auto at = static_cast<std::size_t>(fj * ni + fi);
    if (rho) {
      EXPECT_EQ(f.h[kk], rv.h[at]) << k;
      EXPECT_EQ(f.mask[kk], 0.0) << k;
    } else {
      EXPECT_EQ(f.mask[kk], (u ? rv.mask_u : rv.mask_v)[at]) << k;
    }
  }
  EXPECT_GT(outside, 0);
  // The ring's ρ points, the boundary u (I = 1, L and along rows 0, M) and v points.
  EXPECT_EQ(inside, (2 * (L + 1) + 2 * (M - 1)) + (2 * (M + 1) + 2 * (L - 2)) + (2 * (L + 1) + 2 * (M - 2)));
  // Region 2 and everything but h and mask is untouched.
  for (std::size_t k = static_cast<std::size_t>(r1.NendV); k < f.size(); ++k) {
    EXPECT_EQ(f.h[k], plain.h[k]);
    EXPECT_EQ(f.mask[k], plain.mask[k]);
  }
  EXPECT_EQ(f.Lweight, plain.Lweight);
  EXPECT_EQ(f.pm, plain.pm);
  aq::handoff::ReceiverValues short_rv = rv;
  short_rv.mask_v.pop_back();
  EXPECT_THROW((void)aq::handoff::refinement_contact(s.parent, b, fine_grid(s, b), kPad, nullptr, &short_rv),
               aq::InternalError);
}

}  // namespace unit_handoff_contact_points_test
