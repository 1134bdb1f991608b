// SPDX-License-Identifier: GPL-3.0-or-later
// The ROMS grid writer: every grd_spherical.cdl variable with its dimensions and attributes,
// read back with the netCDF-C API; same bytes on every write.
#include "grid_files/roms_grid.hpp"

#include <gtest/gtest.h>
#include <netcdf.h>

#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "core/error.hpp"
#include "support/temp_dir.hpp"
#include "support/uniform_grid.hpp"

namespace aq::io::unit_grid_files_roms_grid_test {
namespace {

curvilinear::Grid2D plane_rectangle(int nx, int ny) { return aq::testing::uniform_supergrid(nx, ny, 50.0, 30.0); }

struct Fixture {
  curvilinear::Grid2D super = plane_rectangle(6, 4);
  curvilinear::CGrid grid;
  RomsGridData data;
  Fixture() {
    curvilinear::ProjectionParams p;
    p.rlat_deg = 43.75;
    p.rlon_deg = 34.5;
    grid = curvilinear::build_cgrid(super, curvilinear::Projection(p));
    data.grid = &grid;
    const std::size_t n = grid.rho.size();
    for (std::size_t k = 0; k < n; ++k) {
      data.hraw.push_back(k % 3 == 0 ? -20.0 : 100.0 + static_cast<double>(k));
      data.h.push_back(k % 3 == 0 ? 10.0 : 100.0 + static_cast<double>(k));
      data.mask_rho.push_back(k % 3 == 0 ? 0 : 1);
    }
    data.mask_u.assign(grid.u.size(), 1);
    data.mask_v.assign(grid.v.size(), 0);
    data.mask_psi.assign(grid.psi.size(), 1);
    data.history = "test";
    data.attributes = {{"rlat", 43.75}, {"izogrid_nx", std::int64_t{6}}, {"proj", std::string("ME")}};
  }
};

std::string text_att(int nc, int var, const char* name) {
  std::size_t len = 0;
  if (nc_inq_attlen(nc, var, name, &len) != NC_NOERR) return "<missing>";
  std::string s(len, '\0');
  nc_get_att_text(nc, var, name, s.data());
  return s;
}

std::string bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(RomsGridFile, HasEveryGrdSphericalVariableWithItsDimensions) {
  Fixture f;
  testing::TempDir dir;
  write_roms_grid(dir / "grd.nc", f.data);

  int nc = -1;
  ASSERT_EQ(nc_open((dir / "grd.nc").c_str(), NC_NOWRITE, &nc), NC_NOERR);
  int format = 0;
  nc_inq_format(nc, &format);
  EXPECT_EQ(format, NC_FORMAT_64BIT_OFFSET);
  const std::map<std::string, std::size_t> dims = {{"xi_rho", 7}, {"eta_rho", 5}, {"xi_u", 6},
                                                   {"eta_u", 5},  {"xi_v", 7},    {"eta_v", 4},
                                                   {"xi_psi", 6}, {"eta_psi", 4}, {"bath", 1}};
  for (const auto& [name, len] : dims) {
    int d = -1;
    ASSERT_EQ(nc_inq_dimid(nc, name.c_str(), &d), NC_NOERR) << name;
    std::size_t l = 0;
    nc_inq_dimlen(nc, d, &l);
    EXPECT_EQ(l, len) << name;
  }
  int unlimited = -1, bath = -2;
  nc_inq_unlimdim(nc, &unlimited);
  nc_inq_dimid(nc, "bath", &bath);
  EXPECT_EQ(unlimited, bath);

  // Expected dimensions of every variable (grd_spherical.cdl).
  std::map<std::string, std::vector<std::string>> expect = {
      {"spherical", {}}, {"xl", {}}, {"el", {}}, {"hraw", {"bath", "eta_rho", "xi_rho"}}};
  for (const char* v :
       {"h", "f", "pm", "pn", "dndx", "dmde", "angle", "x_rho", "y_rho", "lon_rho", "lat_rho", "mask_rho"})
    expect[v] = {"eta_rho", "xi_rho"};
  for (const char* fam : {"u", "v", "psi"})
    for (const char* pre : {"x_", "y_", "lon_", "lat_", "mask_"})
      expect[std::string(pre) + fam] = {std::string("eta_") + fam, std::string("xi_") + fam};
  ASSERT_EQ(expect.size(), roms_grid_variables().size());
  int nvars = 0;
  nc_inq_nvars(nc, &nvars);
  EXPECT_EQ(nvars, static_cast<int>(expect.size()));
  for (const auto& name : roms_grid_variables()) {
    int v = -1;
    ASSERT_EQ(nc_inq_varid(nc, name.c_str(), &v), NC_NOERR) << name;
    int nd = 0;
    int ids[NC_MAX_VAR_DIMS];
    nc_type type = NC_NAT;
    nc_inq_var(nc, v, nullptr, &type, &nd, ids, nullptr);
    EXPECT_EQ(type, name == "spherical" ? NC_CHAR : NC_DOUBLE) << name;
    std::vector<std::string> got;
    for (int k = 0; k < nd; ++k) {
      char dn[NC_MAX_NAME + 1] = {};
      nc_inq_dimname(nc, ids[k], dn);
      got.emplace_back(dn);
    }
    EXPECT_EQ(got, expect.at(name)) << name;
    EXPECT_NE(text_att(nc, v, "long_name"), "<missing>") << name;
    if (name.rfind("mask_", 0) == 0) {
      EXPECT_EQ(text_att(nc, v, "flag_meanings"), "land water");
      EXPECT_EQ(text_att(nc, v, "_FillValue"), "<missing>") << "a _FillValue of 1 would hide the water from CF readers";
      const std::string fam = name.substr(5);
      EXPECT_EQ(text_att(nc, v, "coordinates"), "lon_" + fam + " lat_" + fam);
    }
  }
  int v = -1;
  nc_inq_varid(nc, "angle", &v);
  EXPECT_EQ(text_att(nc, v, "units"), "radians");
  EXPECT_EQ(text_att(nc, v, "long_name"), "angle between XI-axis and EAST");
  nc_inq_varid(nc, "lon_psi", &v);
  EXPECT_EQ(text_att(nc, v, "standard_name"), "longitude");
  EXPECT_EQ(text_att(nc, v, "units"), "degree_east");
  nc_inq_varid(nc, "pm", &v);
  EXPECT_EQ(text_att(nc, v, "units"), "meter-1");
  EXPECT_EQ(text_att(nc, NC_GLOBAL, "type"), "ROMS GRID file");
  EXPECT_EQ(text_att(nc, NC_GLOBAL, "Conventions"), "CF-1.8");
  EXPECT_EQ(text_att(nc, NC_GLOBAL, "proj"), "ME");
  int ix = 0;
  nc_get_att_int(nc, NC_GLOBAL, "izogrid_nx", &ix);
  EXPECT_EQ(ix, 6);

  // Values: spherical = 'T', hraw keeps the raw (negative on land) depth, masks 0/1, metrics.
  char sph = 0;
  nc_inq_varid(nc, "spherical", &v);
  nc_get_var_text(nc, v, &sph);
  EXPECT_EQ(sph, 'T');
  std::vector<double> buf(f.grid.rho.size());
  nc_inq_varid(nc, "hraw", &v);
  nc_get_var_double(nc, v, buf.data());
  EXPECT_EQ(buf, f.data.hraw);
  nc_inq_varid(nc, "pm", &v);
  nc_get_var_double(nc, v, buf.data());
  EXPECT_EQ(buf, f.grid.pm);
  nc_inq_varid(nc, "mask_rho", &v);
  nc_get_var_double(nc, v, buf.data());
  for (std::size_t k = 0; k < buf.size(); ++k) EXPECT_EQ(buf[k], static_cast<double>(f.data.mask_rho[k]));
  std::vector<double> vb(f.grid.v.size());
  nc_inq_varid(nc, "lat_v", &v);
  nc_get_var_double(nc, v, vb.data());
  EXPECT_EQ(vb, f.grid.v.lat_deg);
  double xl = 0.0;
  nc_inq_varid(nc, "xl", &v);
  nc_get_var_double(nc, v, &xl);
  EXPECT_EQ(xl, f.grid.xl_m);
  nc_close(nc);
}

TEST(RomsGridFile, SameBytesEveryTime) {
  Fixture f;
  testing::TempDir dir;
  write_roms_grid(dir / "a.nc", f.data);
  write_roms_grid(dir / "b.nc", f.data);
  const std::string a = bytes(dir / "a.nc");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, bytes(dir / "b.nc"));
}

TEST(RomsGridFile, RefusesInconsistentData) {
  Fixture f;
  testing::TempDir dir;
  f.data.mask_u.pop_back();
  EXPECT_THROW(write_roms_grid(dir / "x.nc", f.data), InternalError);
  Fixture g;
  g.data.attributes["type"] = std::string("mine");
  EXPECT_THROW(write_roms_grid(dir / "x.nc", g.data), InternalError);
  Fixture h;
  EXPECT_THROW(write_roms_grid(dir / "no_such_dir" / "x.nc", h.data), OutputError);
}

TEST(RomsGridFile, UpdatedCopyChangesDepthAndMasksOnly) {
  // The parent of a refinement: a copy of the file with new h and masks and added attributes;
  // every other variable, and the source file, unchanged.
  Fixture f;
  testing::TempDir dir;
  write_roms_grid(dir / "parent_grd.nc", f.data);
  const auto bytes = [](const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  const std::string source = bytes(dir / "parent_grd.nc");
  RomsGridUpdate u;
  u.h.assign(f.grid.rho.size(), 77.0);
  u.mask_rho.assign(f.grid.rho.size(), 1.0);
  u.mask_u.assign(f.grid.u.size(), 0.0);
  u.attributes = {
      {"nested_child_grid", std::string("child_grd.nc")}, {"nested_refine_factor", std::int64_t{3}}, {"rlat", 1.5}};
  u.history_append = "updated";
  write_updated_roms_grid(dir / "parent_grd.nc", dir / "nested_grd.nc", u);
  EXPECT_EQ(bytes(dir / "parent_grd.nc"), source);

  int nc = -1;
  ASSERT_EQ(nc_open((dir / "nested_grd.nc").c_str(), NC_NOWRITE, &nc), NC_NOERR);
  const auto var = [&](const char* name) {
    int v = -1;
    EXPECT_EQ(nc_inq_varid(nc, name, &v), NC_NOERR) << name;
    return v;
  };
  std::vector<double> h(f.grid.rho.size()), mr(h.size()), mu(f.grid.u.size()), mv(f.grid.v.size()), pm(h.size()),
      hraw(h.size());
  nc_get_var_double(nc, var("h"), h.data());
  nc_get_var_double(nc, var("mask_rho"), mr.data());
  nc_get_var_double(nc, var("mask_u"), mu.data());
  nc_get_var_double(nc, var("mask_v"), mv.data());
  nc_get_var_double(nc, var("pm"), pm.data());
  nc_get_var_double(nc, var("hraw"), hraw.data());
  EXPECT_EQ(h, u.h);
  EXPECT_EQ(mr, u.mask_rho);
  EXPECT_EQ(mu, u.mask_u);
  EXPECT_EQ(mv, std::vector<double>(mv.size(), 0.0));  // not in the update: as written
  EXPECT_EQ(pm, f.grid.pm);
  EXPECT_EQ(hraw, f.data.hraw);
  EXPECT_EQ(text_att(nc, NC_GLOBAL, "history"), "test\nupdated");
  EXPECT_EQ(text_att(nc, NC_GLOBAL, "nested_child_grid"), "child_grd.nc");
  EXPECT_EQ(text_att(nc, NC_GLOBAL, "proj"), "ME");
  double rlat = 0.0;
  nc_get_att_double(nc, NC_GLOBAL, "rlat", &rlat);
  EXPECT_EQ(rlat, 1.5);
  int r = 0;
  nc_get_att_int(nc, NC_GLOBAL, "nested_refine_factor", &r);
  EXPECT_EQ(r, 3);
  nc_close(nc);

  RomsGridUpdate wrong;
  wrong.h.assign(3, 1.0);
  EXPECT_THROW(write_updated_roms_grid(dir / "parent_grd.nc", dir / "x.nc", wrong), InputError);
  EXPECT_THROW(write_updated_roms_grid(dir / "missing_grd.nc", dir / "y.nc", u), InputError);
  RomsGridUpdate reserved;
  reserved.attributes = {{"type", std::string("x")}};
  EXPECT_THROW(write_updated_roms_grid(dir / "parent_grd.nc", dir / "z.nc", reserved), InternalError);
}

}  // namespace
}  // namespace aq::io::unit_grid_files_roms_grid_test
