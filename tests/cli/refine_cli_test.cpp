// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria regional` for a refinement grid: the Black Sea grid as the parent, its north-western
// shelf (configs/black_sea_nw_shelf.toml) split 3 x 3. The fine grid's ψ points at every third
// index are the parent's ψ points, its size follows the box, its ROMS file carries coarse2fine's
// parent attributes, and <name>_contact.nc has the variables and values of ROMS's nesting.cdl
// (c_contact.m) for both contact regions. Bad refinement settings stop with the config's name and
// no output files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <netcdf.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "curvilinear/common/cgrid.hpp"
#include "grid_files/contact_netcdf.hpp"
#include "support/nest_invariant.hpp"
#include "support/run_command.hpp"

namespace cli_refine_cli_test {

namespace fs = std::filesystem;
using aq::test::run_aquatoria;
using ::testing::HasSubstr;

namespace {

std::string run_text(const std::string& cmd) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen((cmd + " 2>&1").c_str(), "r"), pclose);
  char buf[4096];
  while (p && fgets(buf, sizeof buf, p.get()) != nullptr) out += buf;
  return out;
}

const std::string kChild = std::string(AQ_SOURCE_DIR) + "/configs/black_sea_nw_shelf.toml";

std::string file_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

std::vector<double> nc_doubles(const fs::path& path, const char* name) {
  int id = -1, var = -1, ndims = 0, dims[NC_MAX_VAR_DIMS];
  std::vector<double> v;
  if (nc_open(path.c_str(), NC_NOWRITE, &id) != NC_NOERR) return v;
  if (nc_inq_varid(id, name, &var) == NC_NOERR && nc_inq_varndims(id, var, &ndims) == NC_NOERR &&
      nc_inq_vardimid(id, var, dims) == NC_NOERR) {
    std::size_t n = 1;
    for (int k = 0; k < ndims; ++k) {
      std::size_t len = 0;
      nc_inq_dimlen(id, dims[k], &len);
      n *= len;
    }
    v.resize(n);
    nc_get_var_double(id, var, v.data());
  }
  nc_close(id);
  return v;
}

// Largest r-factor |h1 - h2|/(h1 + h2) over faces between wet rho points of a ROMS grid file.
double file_rx0(const fs::path& path) {
  const auto g = aq::io::read_roms_grid_fields(path);
  double r = 0.0;
  const auto pair = [&](std::size_t a, std::size_t b) {
    if (g.mask_rho[a] > 0.5 && g.mask_rho[b] > 0.5) r = std::max(r, std::abs(g.h[a] - g.h[b]) / (g.h[a] + g.h[b]));
  };
  for (int j = 0; j <= g.M; ++j)
    for (int i = 0; i <= g.L; ++i) {
      if (i < g.L) pair(g.rho_at(i, j), g.rho_at(i + 1, j));
      if (j < g.M) pair(g.rho_at(i, j), g.rho_at(i, j + 1));
    }
  return r;
}

}  // namespace

class RefineCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("aq_refine_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const auto r = run_aquatoria("regional -q -c " + std::string(AQ_SOURCE_DIR) + "/configs/black_sea.toml -o " +
                                 (dir_ / "parent").string() + " --no-coastline");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    parent_ = dir_ / "parent" / "black_sea_grd.nc";
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static std::string child_args(const std::string& out, const std::string& more = "") {
    return "regional -c " + kChild + " --set nesting.parent=\"" + parent_.string() + "\" -o " + (dir_ / out).string() +
           " --no-coastline " + more;
  }
  static fs::path dir_, parent_;
};
fs::path RefineCli::dir_, RefineCli::parent_;

TEST_F(RefineCli, NorthWesternShelfNestedInTheBlackSea) {
  const auto c = run_aquatoria(child_args("child"));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_THAT(c.err, HasSubstr("refine: done"));
  EXPECT_THAT(c.err, HasSubstr("contact: done"));
  const fs::path out = dir_ / "child";
  for (const char* f : {"black_sea_nw_shelf_grd.nc", "black_sea_nw_shelf_contact.nc", "black_sea_nw_shelf_xygrid.nc",
                        "black_sea_nw_shelf_grid.png", "black_sea_nw_shelf_roms.png",
                        "black_sea_nw_shelf_in_parent.png", "black_sea_nw_shelf_parent_grd.nc"})
    EXPECT_TRUE(fs::exists(out / f)) << f;

  // Sizes: parent ψ I 6..24, J 28..47 split 3 x 3 → Lm = 54, Mm = 57, 56 x 59 ρ points.
  const auto parent = aq::io::read_roms_grid_fields(parent_);
  const auto fine = aq::io::read_roms_grid_fields(out / "black_sea_nw_shelf_grd.nc");
  ASSERT_EQ(fine.L, 55);
  ASSERT_EQ(fine.M, 58);
  // Every parent ψ point in the box is the fine ψ point 3 (I − 6) + 1, 3 (J − 28) + 1 (ROMS indices).
  double worst = 0;
  for (int J = 28; J <= 47; ++J)
    for (int I = 6; I <= 24; ++I) {
      const auto pk = static_cast<std::size_t>((J - 1) * parent.L + (I - 1));
      const auto fk = static_cast<std::size_t>(3 * (J - 28) * fine.L + 3 * (I - 6));
      worst = std::max(worst, aq::curvilinear::great_circle_m(parent.lon_psi[pk], parent.lat_psi[pk], fine.lon_psi[fk],
                                                              fine.lat_psi[fk], 6371000.0));
    }
  EXPECT_LT(worst, 1e-6) << "metres";
  // The fine grid was made in the parent's plane and says where it came from.
  EXPECT_EQ(fine.proj, parent.proj);
  EXPECT_EQ(fine.rlat, parent.rlat);
  const std::string gh = run_text("ncdump -h " + (out / "black_sea_nw_shelf_grd.nc").string());
  EXPECT_THAT(gh, HasSubstr(":parent_Imin = 6 ;"));
  EXPECT_THAT(gh, HasSubstr(":parent_Jmax = 47 ;"));
  EXPECT_THAT(gh, HasSubstr(":refine_factor = 3 ;"));

  // The contact file: c_contact.m's schema ...
  const fs::path nc = out / "black_sea_nw_shelf_contact.nc";
  const std::string h = run_text("ncdump -h " + nc.string());
  for (const char* v : {"Ngrids = 2 ;",
                        "Ncontact = 2 ;",
                        "nLweights = 4 ;",
                        "nQweights = 9 ;",
                        "int spherical ;",
                        "int Lm(Ngrids) ;",
                        "int Mm(Ngrids) ;",
                        "int refine_factor(Ngrids) ;",
                        "int coincident(Ncontact) ;",
                        "int composite(Ncontact) ;",
                        "int mosaic(Ncontact) ;",
                        "int refinement(Ncontact) ;",
                        "int interpolate(Ncontact) ;",
                        "int donor_grid(Ncontact) ;",
                        "int receiver_grid(Ncontact) ;",
                        "int I_left(Ngrids) ;",
                        "int I_right(Ngrids) ;",
                        "int J_bottom(Ngrids) ;",
                        "int J_top(Ngrids) ;",
                        "int NstrR(Ncontact) ;",
                        "int NendV(Ncontact) ;",
                        "int contact_region(datum) ;",
                        "int on_boundary(datum) ;",
                        "int Idg(datum) ;",
                        "int Jdg(datum) ;",
                        "int Irg(datum) ;",
                        "int Jrg(datum) ;",
                        "double xi_dg(datum) ;",
                        "double eta_dg(datum) ;",
                        "double xi_rg(datum) ;",
                        "double eta_rg(datum) ;",
                        "double Xdg(datum) ;",
                        "double Ydg(datum) ;",
                        "double Xrg(datum) ;",
                        "double Yrg(datum) ;",
                        "double Lweight(datum, nLweights) ;",
                        "double Qweight(datum, nQweights) ;",
                        "double h(datum) ;",
                        "double f(datum) ;",
                        "double pm(datum) ;",
                        "double pn(datum) ;",
                        "double dndx(datum) ;",
                        "double dmde(datum) ;",
                        "double angle(datum) ;",
                        "double mask(datum) ;",
                        "h:_FillValue = 1.e+37 ;",
                        "I_left:_FillValue = -999 ;",
                        ":type = \"ROMS Nesting Contact Regions Data\" ;"})
    EXPECT_THAT(h, HasSubstr(v));
  EXPECT_THAT(h, ::testing::Not(HasSubstr("hybrid")));
  // ... and values: the two regions, the box, the counts of the band and of the coarse points inside.
  const std::string v = run_text(
      "ncdump -v Lm,Mm,refine_factor,I_left,J_top,donor_grid,receiver_grid,refinement,"
      "NstrR,NendR,NendV " +
      nc.string());
  for (const char* s : {"Lm = 64, 54 ;", "Mm = 49, 57 ;", "refine_factor = 0, 3 ;", "I_left = _, 6 ;",
                        "J_top = _, 47 ;", "donor_grid = 1, 2 ;", "receiver_grid = 2, 1 ;", "refinement = 1, 1 ;",
                        "NstrR = 1, 2465 ;", "NendR = 826, 2806 ;", "NendV = 2464, 3453 ;"})
    EXPECT_THAT(v, HasSubstr(s));

  // The fine grid's depth on its outer ρ ring is the contact file's (the parent's, interpolated),
  // which ROMS copies there; blending over 6 rows keeps the r-factor bound.
  {
    int id = -1, var = -1;
    ASSERT_EQ(nc_open(nc.c_str(), NC_NOWRITE, &id), NC_NOERR);
    int nend[2] = {0, 0};
    ASSERT_EQ(nc_inq_varid(id, "NendR", &var), NC_NOERR);
    ASSERT_EQ(nc_get_var_int(id, var, nend), NC_NOERR);
    const auto n = static_cast<std::size_t>(nend[0]);
    std::vector<int> irg(n), jrg(n);
    std::vector<double> hc(n);
    const std::size_t start = 0;
    ASSERT_EQ(nc_inq_varid(id, "Irg", &var), NC_NOERR);
    ASSERT_EQ(nc_get_vara_int(id, var, &start, &n, irg.data()), NC_NOERR);
    ASSERT_EQ(nc_inq_varid(id, "Jrg", &var), NC_NOERR);
    ASSERT_EQ(nc_get_vara_int(id, var, &start, &n, jrg.data()), NC_NOERR);
    ASSERT_EQ(nc_inq_varid(id, "h", &var), NC_NOERR);
    ASSERT_EQ(nc_get_vara_double(id, var, &start, &n, hc.data()), NC_NOERR);
    nc_close(id);
    int ring = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (irg[k] < 0 || jrg[k] < 0 || irg[k] > fine.L || jrg[k] > fine.M) continue;
      EXPECT_NEAR(fine.h[fine.rho_at(irg[k], jrg[k])], hc[k], 1e-9 * hc[k]) << irg[k] << " " << jrg[k];
      ++ring;
    }
    EXPECT_EQ(ring, 2 * (fine.L + 1) + 2 * (fine.M - 1));
  }

  // The report: the coarse ψ points coincide, the step ratio is the factor.
  std::ifstream rf(out / "black_sea_nw_shelf_report.json");
  std::stringstream ss;
  ss << rf.rdbuf();
  const auto j = nlohmann::json::parse(ss.str());
  EXPECT_LT(j["contact"]["coarse_psi_coincidence_m"].get<double>(), 1e-6);
  EXPECT_NEAR(j["contact"]["refinement_ratio_median"].get<double>(), 3.0, 0.01);
  EXPECT_EQ(j["contact"]["fine_to_coarse"]["rho"].get<int>(), 18 * 19);
  EXPECT_LT(j["quality"]["ortho_err_50"]["worst"].get<double>(), 1e-3);
  EXPECT_EQ(j["roms"]["depth"]["parent_blend_cells"].get<int>(), 6);
  EXPECT_LE(j["roms"]["depth"]["rx0_after"].get<double>(), 0.2 + 1e-12);
}

// ROMS two-way nesting (issue 13): the parent's h over the refinement is the refinement's h averaged
// over each parent cell (area-weighted), masks follow one rule, and the contact file's receiver h
// and masks are the grid files' values at every contact point inside them, with the r-factor bound
// on both grids. The input parent is not touched: the consistent parent is a new file.
TEST_F(RefineCli, ParentRefinementAndContactFileAgreeForTwoWayNesting) {
  const std::string parent_before = file_bytes(parent_);
  const auto c = run_aquatoria(child_args("twoway"));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const fs::path out = dir_ / "twoway";
  const fs::path nested = out / "black_sea_nw_shelf_parent_grd.nc", child = out / "black_sea_nw_shelf_grd.nc",
                 contact = out / "black_sea_nw_shelf_contact.nc";
  EXPECT_EQ(file_bytes(parent_), parent_before) << "the input parent grid must not change";
  EXPECT_TRUE(fs::exists(nested)) << "the updated parent grid " << nested << " was not written";

  // The parent ROMS runs with (without the updated file: the input parent, as before issue 13).
  const fs::path roms_parent = fs::exists(nested) ? nested : parent_;
  const aq::test::NestInvariant inv = aq::test::check_nest_invariant(roms_parent, child, contact);
  EXPECT_TRUE(inv.holds()) << inv.summary();
  ASSERT_TRUE(fs::exists(nested));
  EXPECT_EQ(inv.footprint_cells, 18 * 19);
  // Region 1 inside the refinement (ring ρ, boundary u and v: L = 55, M = 58) and all of region 2.
  EXPECT_EQ(inv.contact_points_in_grids, (2 * 56 + 2 * 57) + (2 * 59 + 2 * 53) + (2 * 56 + 2 * 56) + 342 + 323 + 324);
  EXPECT_LE(file_rx0(nested), 0.2 + 1e-12);
  EXPECT_LE(file_rx0(child), 0.2 + 1e-12);

  // What ROMS was given before: the input parent breaks the invariant (deeper over the shelf).
  const aq::test::NestInvariant before = aq::test::check_nest_invariant(parent_, child, contact);
  EXPECT_GT(before.h_mismatches, 100) << before.summary();

  // The new parent is the input parent but for h and the masks.
  for (const char* v : {"lon_rho", "lat_psi", "pm", "pn", "f", "angle", "hraw", "x_u", "dmde"})
    EXPECT_EQ(nc_doubles(nested, v), nc_doubles(parent_, v)) << v;
  EXPECT_NE(nc_doubles(nested, "h"), nc_doubles(parent_, "h"));
  const std::string nh = run_text("ncdump -h " + nested.string());
  EXPECT_THAT(nh, HasSubstr(":nested_child_grid = \"black_sea_nw_shelf_grd.nc\""));
  EXPECT_THAT(nh, HasSubstr(":type = \"ROMS GRID file\""));
  EXPECT_THAT(run_text("ncdump -h " + contact.string()),
              HasSubstr(":parent_grid = \"black_sea_nw_shelf_parent_grd.nc\""));
  EXPECT_THAT(run_text("ncdump -h " + child.string()),
              HasSubstr(":parent_grid_nested = \"black_sea_nw_shelf_parent_grd.nc\""));
  std::ifstream rf(out / "black_sea_nw_shelf_report.json");
  std::stringstream ss;
  ss << rf.rdbuf();
  const auto j = nlohmann::json::parse(ss.str());
  EXPECT_TRUE(j["nested"]["settled"].get<bool>());
  EXPECT_EQ(j["nested"]["invariant_residual_m"].get<double>(), 0.0);
}

TEST_F(RefineCli, TheUpdatedParentNeverOverwritesTheInputParent) {
  // A refinement named "x" whose parent is x_parent_grd.nc in its own output folder.
  const fs::path d = dir_ / "self";
  fs::create_directories(d);
  fs::copy_file(parent_, d / "x_parent_grd.nc", fs::copy_options::overwrite_existing);
  const std::string before = file_bytes(d / "x_parent_grd.nc");
  const auto o = run_aquatoria("regional -c " + kChild + " --set nesting.parent=\"" + (d / "x_parent_grd.nc").string() +
                               "\" --set regional.name=\"x\" -o " + d.string() + " --no-coastline");
  EXPECT_EQ(o.exit_code, 2) << o.err;
  EXPECT_THAT(o.err, HasSubstr("would overwrite nesting.parent"));
  EXPECT_EQ(file_bytes(d / "x_parent_grd.nc"), before);
  EXPECT_FALSE(fs::exists(d / "x_grd.nc"));
}

TEST_F(RefineCli, BadRefinementSettingsStopWithTheConfigName) {
  struct Case {
    std::string set, message;
  };
  for (const Case& k : {Case{"--set nesting.refine_factor=4", "nesting.refine_factor"},
                        Case{"--set nesting.parent_box=[1,10,28,47]", "must lie within the parent's psi points"},
                        Case{"--set nesting.parent_box=[20,10,28,47]", "nesting.parent_box"},
                        Case{"--set nesting.refine_factor=0", "only as a refinement"}}) {
    const auto o = run_aquatoria(child_args("bad", k.set));
    EXPECT_TRUE(o.exit_code == 1 || o.exit_code == 2) << k.set << ": " << o.exit_code;
    EXPECT_THAT(o.err, HasSubstr("black_sea_nw_shelf.toml")) << k.set;
    EXPECT_THAT(o.err, HasSubstr(k.message)) << k.set;
    EXPECT_FALSE(fs::exists(dir_ / "bad" / "black_sea_nw_shelf_contact.nc")) << k.set;
    EXPECT_FALSE(fs::exists(dir_ / "bad" / "black_sea_nw_shelf_grd.nc")) << k.set;
  }
  const auto m = run_aquatoria("regional -c " + kChild + " --set nesting.parent=/nonexistent/p_grd.nc -o " +
                               (dir_ / "bad").string() + " --no-coastline");
  EXPECT_TRUE(m.exit_code == 1 || m.exit_code == 2);
  EXPECT_THAT(m.err, HasSubstr("/nonexistent/p_grd.nc"));
}

TEST_F(RefineCli, ParentWithoutProjectionAttributesUsesAStereographicPlane) {
  // A ROMS grid file from another tool names no projection: the fine grid is cut in a stereographic
  // plane centred on the box, and the parent's ψ points still lie on it.
  const fs::path foreign = dir_ / "foreign_grd.nc";
  fs::copy_file(parent_, foreign, fs::copy_options::overwrite_existing);
  int nc = -1;
  ASSERT_EQ(nc_open(foreign.c_str(), NC_WRITE, &nc), NC_NOERR);
  ASSERT_EQ(nc_redef(nc), NC_NOERR);
  for (const char* a : {"proj", "rlat", "rlon", "rota", "uscale", "aspect_ratio"}) nc_del_att(nc, NC_GLOBAL, a);
  ASSERT_EQ(nc_close(nc), NC_NOERR);
  const auto c = run_aquatoria("regional -c " + kChild + " --set nesting.parent=\"" + foreign.string() + "\" -o " +
                               (dir_ / "foreign").string() + " --no-coastline");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_THAT(c.err, HasSubstr("stereographic plane centred"));
  std::ifstream rf(dir_ / "foreign" / "black_sea_nw_shelf_report.json");
  std::stringstream ss;
  ss << rf.rdbuf();
  const auto j = nlohmann::json::parse(ss.str());
  EXPECT_LT(j["contact"]["coarse_psi_coincidence_m"].get<double>(), 1e-6);
  EXPECT_LT(j["quality"]["ortho_err_50"]["worst"].get<double>(), 1e-3);
}

TEST_F(RefineCli, StoppingBeforeTheGridDoesNotApply) {
  const auto o = run_aquatoria(child_args("stop", "--stop-after contour"));
  EXPECT_EQ(o.exit_code, 2) << o.err;
  EXPECT_THAT(o.err, HasSubstr("refinement grid"));
  EXPECT_FALSE(fs::exists(dir_ / "stop" / "black_sea_nw_shelf_grid.png"));
}

TEST_F(RefineCli, SameBytesOnOneAndTwoThreads) {
  const auto bytes = [](const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  };
  for (const char* t : {"1", "2"}) {
    const auto r = aq::test::run_command(std::string("OMP_NUM_THREADS=") + t + " " + AQ_BINARY + " -q " +
                                         child_args(std::string("threads") + t));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  for (const char* f : {"black_sea_nw_shelf_grd.nc", "black_sea_nw_shelf_contact.nc", "black_sea_nw_shelf_xygrid.nc",
                        "black_sea_nw_shelf_in_parent.png", "black_sea_nw_shelf_parent_grd.nc"}) {
    const std::string a = bytes(dir_ / "threads1" / f), b = bytes(dir_ / "threads2" / f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_TRUE(a == b) << f;
  }
}

}  // namespace cli_refine_cli_test
