// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the planar grid netCDF (round trip, schema, errors, reproducibility).
#include <gtest/gtest.h>
#include <netcdf.h>

#include <cmath>
#include <complex>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "core/output_files.hpp"
#include "curvilinear/common/grid_checks.hpp"
#include "curvilinear/conformal/laplace_fill.hpp"
#include "grid_files/xygrid_netcdf.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_grid_files_xygrid_netcdf_test {
namespace {

namespace fs = std::filesystem;

using aq::testing::TempDir;

/// A filled conformal grid: boundary of z = 1e5·exp(ζ/2) + false easting, DST fill.
XyGrid sample_grid(int nx = 41, int ny = 29) {
  XyGrid out;
  out.grid = curvilinear::Grid2D(nx, ny);
  out.dxi = 1.3 / (nx - 1);
  out.deta = 1.0 / (ny - 1);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::complex<double> z =
          std::complex<double>(4.5e5, 5.1e6) + 1e5 * std::exp(0.5 * std::complex<double>(i * out.dxi, j * out.deta));
      out.grid.x[out.grid.at(i, j)] = z.real();
      out.grid.y[out.grid.at(i, j)] = z.imag();
    }
  }
  const curvilinear::LaplaceResult r = curvilinear::laplace_fill(out.grid, out.dxi, out.deta);
  out.residual_history = {0.1, 1e-3, r.residual};
  out.units = "m";
  out.title = "test grid";
  out.history = "aquatoria test";
  out.attributes = {{"projection", std::string("rotated Mercator")},
                    {"rlat", 44.125},
                    {"rlon", 34.0},
                    {"nx", std::int64_t{20}},
                    {"ny", std::int64_t{14}},
                    {"w_over_h", 1.30082939},
                    {"big", std::int64_t{1} << 40},
                    {"input_file", std::string("mode=4\nproj=ME\n---\n0 0 <SW\n")}};
  return out;
}

std::string text_attribute(int nc, int var, const char* name) {
  std::size_t len = 0;
  EXPECT_EQ(nc_inq_attlen(nc, var, name, &len), NC_NOERR) << name;
  std::string s(len, '\0');
  EXPECT_EQ(nc_get_att_text(nc, var, name, s.data()), NC_NOERR) << name;
  return s;
}

TEST(XyGridNetcdf, RoundTripPreservesNodesBitExactlyAndAttributes) {
  const TempDir dir;
  const XyGrid in = sample_grid();
  write_xygrid(dir / "grid.nc", in);
  const XyGrid out = read_xygrid(dir / "grid.nc");
  ASSERT_EQ(out.grid.nx_pts, in.grid.nx_pts);
  ASSERT_EQ(out.grid.ny_pts, in.grid.ny_pts);
  EXPECT_EQ(std::memcmp(out.grid.x.data(), in.grid.x.data(), in.grid.x.size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(out.grid.y.data(), in.grid.y.data(), in.grid.y.size() * sizeof(double)), 0);
  EXPECT_EQ(out.units, "m");
  EXPECT_TRUE(out.has_steps);
  EXPECT_EQ(out.dxi, in.dxi);
  EXPECT_EQ(out.deta, in.deta);
  EXPECT_EQ(out.title, "test grid");
  EXPECT_EQ(out.history, "aquatoria test");
  EXPECT_EQ(out.residual_history, in.residual_history);
  EXPECT_EQ(out.attributes, in.attributes);
  EXPECT_EQ(std::get<std::int64_t>(out.attributes.at("big")), std::int64_t{1} << 40);
}

TEST(XyGridNetcdf, SchemaHasCfAttributesDimensionsAndQualityFields) {
  const TempDir dir;
  const XyGrid in = sample_grid(21, 15);
  curvilinear::CheckOptions co;
  co.dxi_over_deta = in.dxi / in.deta;
  const curvilinear::GridQuality q = curvilinear::check_grid(in.grid, co);
  write_xygrid(dir / "q.nc", in, &q);

  int nc = -1;
  ASSERT_EQ(nc_open((dir / "q.nc").c_str(), NC_NOWRITE, &nc), NC_NOERR);
  EXPECT_EQ(text_attribute(nc, NC_GLOBAL, "Conventions"), "CF-1.8");
  EXPECT_EQ(text_attribute(nc, NC_GLOBAL, "aquatoria_file"), "xygrid");
  for (const auto& [name, expect] : {std::pair{"xi_s", 21u}, std::pair{"eta_s", 15u}, std::pair{"xi_c", 20u},
                                     std::pair{"eta_c", 14u}, std::pair{"iteration", 3u}}) {
    int dim = -1;
    std::size_t len = 0;
    ASSERT_EQ(nc_inq_dimid(nc, name, &dim), NC_NOERR) << name;
    ASSERT_EQ(nc_inq_dimlen(nc, dim, &len), NC_NOERR);
    EXPECT_EQ(len, expect) << name;
  }
  int var = -1;
  ASSERT_EQ(nc_inq_varid(nc, "x", &var), NC_NOERR);
  EXPECT_EQ(text_attribute(nc, var, "standard_name"), "projection_x_coordinate");
  EXPECT_EQ(text_attribute(nc, var, "units"), "m");
  for (const curvilinear::QualityField* f : q.fields()) {
    ASSERT_EQ(nc_inq_varid(nc, f->name.c_str(), &var), NC_NOERR) << f->name;
    std::vector<double> v(f->values.size());
    ASSERT_EQ(nc_get_var_double(nc, var, v.data()), NC_NOERR);
    for (std::size_t k = 0; k < v.size(); ++k) {
      if (std::isnan(f->values[k])) {
        EXPECT_TRUE(std::isnan(v[k])) << f->name << " " << k;
      } else {
        EXPECT_EQ(v[k], f->values[k]) << f->name << " " << k;
      }
    }
    double worst = 0.0;
    ASSERT_EQ(nc_get_att_double(nc, var, "worst", &worst), NC_NOERR);
    EXPECT_EQ(worst, f->worst) << f->name;
    int ndims = 0;
    int dims[2];
    ASSERT_EQ(nc_inq_var(nc, var, nullptr, nullptr, &ndims, dims, nullptr), NC_NOERR);
    char dim_name[NC_MAX_NAME + 1] = {};
    ASSERT_EQ(nc_inq_dimname(nc, dims[1], dim_name), NC_NOERR);
    EXPECT_STREQ(dim_name, f->location == curvilinear::FieldLocation::kCell ? "xi_c" : "xi_s") << f->name;
  }
  nc_close(nc);
}

TEST(XyGridNetcdf, WritingIsReproducible) {
  const TempDir dir;
  const XyGrid in = sample_grid();
  const curvilinear::GridQuality q = curvilinear::check_grid(in.grid);
  write_xygrid(dir / "a.nc", in, &q);
  write_xygrid(dir / "b.nc", in, &q);
  EXPECT_EQ(file_checksum(dir / "a.nc"), file_checksum(dir / "b.nc"));
}

TEST(XyGridNetcdf, FileWithoutStepsReadsWithHasStepsFalse) {
  const TempDir dir;
  const fs::path p = dir / "plain.nc";
  int nc = -1;
  ASSERT_EQ(nc_create(p.c_str(), NC_CLOBBER, &nc), NC_NOERR);
  int dims[2];
  ASSERT_EQ(nc_def_dim(nc, "eta", 3, &dims[0]), NC_NOERR);
  ASSERT_EQ(nc_def_dim(nc, "xi", 4, &dims[1]), NC_NOERR);
  int vx = -1;
  int vy = -1;
  ASSERT_EQ(nc_def_var(nc, "x", NC_FLOAT, 2, dims, &vx), NC_NOERR);
  ASSERT_EQ(nc_def_var(nc, "y", NC_FLOAT, 2, dims, &vy), NC_NOERR);
  const short levels[2] = {3, 4};
  ASSERT_EQ(nc_put_att_short(nc, NC_GLOBAL, "levels", NC_SHORT, 2, levels), NC_NOERR);
  ASSERT_EQ(nc_enddef(nc), NC_NOERR);
  float x[12];
  float y[12];
  for (int k = 0; k < 12; ++k) {
    x[k] = static_cast<float>(k % 4);
    y[k] = static_cast<float>(k / 4);
  }
  ASSERT_EQ(nc_put_var_float(nc, vx, x), NC_NOERR);
  ASSERT_EQ(nc_put_var_float(nc, vy, y), NC_NOERR);
  ASSERT_EQ(nc_close(nc), NC_NOERR);
  const XyGrid g = read_xygrid(p);
  EXPECT_FALSE(g.has_steps);
  EXPECT_EQ(g.grid.nx_pts, 4);
  EXPECT_EQ(g.grid.ny_pts, 3);
  EXPECT_EQ(g.grid.x[g.grid.at(3, 2)], 3.0);
  EXPECT_EQ(g.grid.y[g.grid.at(3, 2)], 2.0);
  EXPECT_EQ(std::get<std::string>(g.attributes.at("levels")), "3 4");
}

/// The InputError message of read_xygrid(p); fails the test if none is thrown.
std::string read_error(const fs::path& p) {
  try {
    read_xygrid(p);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << p;
  return {};
}

TEST(XyGridNetcdf, ReadingSomethingElseNamesTheFileAndWhatIsMissing) {
  const TempDir dir;
  const std::string missing = read_error(dir / "nope.nc");
  EXPECT_NE(missing.find((dir / "nope.nc").string()), std::string::npos) << missing;

  const fs::path text = dir / "text.nc";
  std::ofstream(text) << "not a netCDF file\n";
  const std::string garbage = read_error(text);
  EXPECT_NE(garbage.find(text.string()), std::string::npos) << garbage;

  const fs::path other = dir / "depth.nc";
  int nc = -1;
  ASSERT_EQ(nc_create(other.c_str(), NC_CLOBBER, &nc), NC_NOERR);
  int dim = -1;
  int var = -1;
  ASSERT_EQ(nc_def_dim(nc, "n", 5, &dim), NC_NOERR);
  ASSERT_EQ(nc_def_var(nc, "x", NC_DOUBLE, 1, &dim, &var), NC_NOERR);
  ASSERT_EQ(nc_close(nc), NC_NOERR);
  const std::string one_d = read_error(other);
  EXPECT_NE(one_d.find(other.string()), std::string::npos) << one_d;
  EXPECT_NE(one_d.find("'x' has 1 dimensions"), std::string::npos) << one_d;

  const fs::path no_y = dir / "no_y.nc";
  ASSERT_EQ(nc_create(no_y.c_str(), NC_CLOBBER, &nc), NC_NOERR);
  int dims[2];
  ASSERT_EQ(nc_def_dim(nc, "a", 3, &dims[0]), NC_NOERR);
  ASSERT_EQ(nc_def_dim(nc, "b", 3, &dims[1]), NC_NOERR);
  ASSERT_EQ(nc_def_var(nc, "x", NC_DOUBLE, 2, dims, &var), NC_NOERR);
  ASSERT_EQ(nc_close(nc), NC_NOERR);
  const std::string msg = read_error(no_y);
  EXPECT_NE(msg.find("no variable 'y'"), std::string::npos) << msg;
}

TEST(XyGridNetcdf, WriterErrorsNameThePath) {
  const TempDir dir;
  XyGrid in = sample_grid(5, 4);
  const fs::path bad = dir / "missing_dir" / "g.nc";
  try {
    write_xygrid(bad, in);
    FAIL() << "no exception";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
  in.attributes["history"] = std::string("clash");
  EXPECT_THROW(write_xygrid(dir / "g.nc", in), InternalError);
}

TEST(XyGridNetcdf, WorksThroughAnOutputSet) {
  const TempDir dir;
  const XyGrid in = sample_grid(9, 7);
  {
    OutputSet out(dir.path());
    write_xygrid(out.temp_path("grid.nc"), in);
    EXPECT_FALSE(fs::exists(dir / "grid.nc"));
    out.commit();
  }
  EXPECT_EQ(read_xygrid(dir / "grid.nc").grid.x, in.grid.x);
}

}  // namespace
}  // namespace aq::io::unit_grid_files_xygrid_netcdf_test
