// SPDX-License-Identifier: GPL-3.0-or-later
// The UGRID dataset described once (ugrid_dataset, io/dataset.hpp) for two destinations: the
// netCDF file write_ugrid makes and a MemoryDataset (what the Python package's to_xarray turns into
// an xarray.Dataset). Read back with the netCDF-C API, the file must hold exactly the memory
// dataset: the same dimensions, variables (name, type, dimensions, values byte for byte) and
// attributes (name, type, values), in the same order, for triangles, squares, both, a rotated
// pole and the classic (uncompressed) format. Also: MemoryDataset's conversions and misuse, and a
// stop request between blocks of faces.
#include <gtest/gtest.h>
#include <netcdf.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/cancel.hpp"
#include "core/error.hpp"
#include "io/memory_dataset.hpp"
#include "mesh_files/ugrid_writer.hpp"
#include "support/io_test_mesh.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_mesh_files_ugrid_dataset_test {
namespace {

void ok(int status) { ASSERT_EQ(status, NC_NOERR) << nc_strerror(status); }

nc_type nc_type_of(DataType t) {
  switch (t) {
    case DataType::kByte:
      return NC_BYTE;
    case DataType::kShort:
      return NC_SHORT;
    case DataType::kInt:
      return NC_INT;
    case DataType::kInt64:
      return NC_INT64;
    case DataType::kDouble:
      return NC_DOUBLE;
  }
  return NC_NAT;
}

void expect_attributes(int nc, int var, const std::vector<MemoryDataset::Attribute>& atts, const std::string& where) {
  int natts = 0;
  ok(var == NC_GLOBAL ? nc_inq_natts(nc, &natts) : nc_inq_varnatts(nc, var, &natts));
  ASSERT_EQ(static_cast<std::size_t>(natts), atts.size()) << where;
  for (int a = 0; a < natts; ++a) {
    char name[NC_MAX_NAME + 1] = {};
    ok(nc_inq_attname(nc, var, a, name));
    const auto& m = atts[static_cast<std::size_t>(a)];
    EXPECT_EQ(name, m.name) << where;
    nc_type type = NC_NAT;
    std::size_t len = 0;
    ok(nc_inq_att(nc, var, name, &type, &len));
    if (m.is_text) {
      ASSERT_EQ(type, NC_CHAR) << where << " " << name;
      std::string text(len, '\0');
      ok(nc_get_att_text(nc, var, name, text.data()));
      EXPECT_EQ(text, m.text) << where << " " << name;
      continue;
    }
    EXPECT_EQ(type, nc_type_of(m.type)) << where << " " << name;
    std::vector<double> values(len);
    ok(nc_get_att_double(nc, var, name, values.data()));
    ASSERT_EQ(values.size(), m.values.size()) << where << " " << name;
    for (std::size_t k = 0; k < len; ++k) {
      if (std::isnan(m.values[k]))
        EXPECT_TRUE(std::isnan(values[k])) << where << " " << name;
      else
        EXPECT_EQ(values[k], m.values[k]) << where << " " << name;
    }
  }
}

// The file at `path` holds exactly `m`.
void expect_file_is(const std::filesystem::path& path, const MemoryDataset& m) {
  int nc = -1;
  ok(nc_open(path.c_str(), NC_NOWRITE, &nc));
  int ndims = 0, nvars = 0, ngatts = 0, unlimited = 0;
  ok(nc_inq(nc, &ndims, &nvars, &ngatts, &unlimited));
  ASSERT_EQ(static_cast<std::size_t>(ndims), m.dimensions().size());
  for (int d = 0; d < ndims; ++d) {
    char name[NC_MAX_NAME + 1] = {};
    std::size_t len = 0;
    ok(nc_inq_dim(nc, d, name, &len));
    EXPECT_EQ(name, m.dimensions()[static_cast<std::size_t>(d)].name);
    EXPECT_EQ(static_cast<std::int64_t>(len), m.dimensions()[static_cast<std::size_t>(d)].length) << name;
  }
  expect_attributes(nc, NC_GLOBAL, m.global_attributes(), "global");
  ASSERT_EQ(static_cast<std::size_t>(nvars), m.variables().size());
  for (int v = 0; v < nvars; ++v) {
    const auto& mv = m.variables()[static_cast<std::size_t>(v)];
    char name[NC_MAX_NAME + 1] = {};
    nc_type type = NC_NAT;
    int nd = 0, dims[NC_MAX_VAR_DIMS] = {}, natts = 0;
    ok(nc_inq_var(nc, v, name, &type, &nd, dims, &natts));
    EXPECT_EQ(name, mv.name);
    EXPECT_EQ(type, nc_type_of(mv.type)) << name;
    EXPECT_EQ(std::vector<int>(dims, dims + nd), mv.dims) << name;
    expect_attributes(nc, v, mv.attributes, name);
    std::vector<unsigned char> data(mv.data.size());
    ok(nc_get_var(nc, v, data.data()));
    EXPECT_TRUE(data == mv.data) << name << ": the values differ";
  }
  nc_close(nc);
}

void check(const mesh::Mesh& mesh, const UgridOptions& options) {
  testing::TempDir dir;
  write_ugrid(mesh, dir / "m.nc", options);
  MemoryDataset m;
  const UgridCounts counts = ugrid_dataset(mesh, options, m);
  EXPECT_EQ(counts.nodes, mesh.node_count());
  EXPECT_FALSE(m.variables().empty());
  expect_file_is(dir / "m.nc", m);
}

TEST(UgridDataset, TheFileHoldsTheMemoryDatasetTriangles) { check(testing::tiny_mesh(), {}); }

TEST(UgridDataset, TheFileHoldsTheMemoryDatasetSquaresAndBoth) {
  UgridOptions o;
  o.elements = ElementKinds::kSquares;
  check(testing::tiny_mesh(false), o);
  o.elements = ElementKinds::kBoth;
  check(testing::tiny_mesh(true), o);  // two topologies, polygons padded with _FillValue -1
}

TEST(UgridDataset, TheFileHoldsTheMemoryDatasetRotatedAndClassic) {
  mesh::RotationInfo r;
  r.enabled = true;
  r.pole_lon_deg = -44.858333;
  r.pole_lat_deg = 78.141667;
  check(testing::tiny_mesh(true, r), {});
  UgridOptions classic;
  classic.deflate = 0;
  check(testing::tiny_mesh(), classic);
  auto m = testing::tiny_mesh();
  m.depth_m[2] = std::numeric_limits<double>::quiet_NaN();  // a node without data: depth gets _FillValue NaN
  check(m, {});
}

TEST(MemoryDataset, StoresValuesInTheVariablesTypeAndRefusesMisuse) {
  MemoryDataset m;
  m.start(false);
  const int rows = m.dim("rows", 3), two = m.dim("two", 2);
  const int idx = m.var("idx", DataType::kInt, {rows, two});
  const int scalar = m.var("s", DataType::kInt, {});
  m.numbers(idx, "flags", DataType::kByte, {1, 2});
  m.text(DatasetSink::kGlobal, "title", "t");
  EXPECT_THROW(m.put(idx, 0, 1, static_cast<const long long*>(nullptr)), InternalError);  // before end_definitions
  m.end_definitions();
  EXPECT_THROW(m.dim("late", 1), InternalError);
  const long long values[4] = {7, 8, 9, 10};
  m.put(idx, 1, 2, values);
  std::vector<std::int32_t> stored(6);
  ASSERT_EQ(m.variables()[0].data.size(), 6 * sizeof(std::int32_t));
  std::memcpy(stored.data(), m.variables()[0].data.data(), 6 * sizeof(std::int32_t));
  EXPECT_EQ(stored, (std::vector<std::int32_t>{0, 0, 7, 8, 9, 10}));
  EXPECT_EQ(m.variables()[static_cast<std::size_t>(scalar)].data.size(), 4U);  // a scalar holds one 0
  EXPECT_THROW(m.put(idx, 2, 2, values), InternalError);                       // rows 2..3 of 3
  EXPECT_EQ(m.global_attributes().at(0).text, "t");
  EXPECT_EQ(m.variables()[0].attributes.at(0).values, (std::vector<double>{1, 2}));
}

TEST(UgridDataset, AStopRequestEndsTheDescriptionWithCancelled) {
  const auto mesh = testing::tiny_mesh();
  CancelToken token;
  token.request();
  const CancelScope scope(token);
  MemoryDataset m;
  try {
    ugrid_dataset(mesh, {}, m);
    FAIL() << "no Cancelled";
  } catch (const Cancelled& e) {
    EXPECT_EQ(e.exit_code(), 130);
  }
}

}  // namespace
}  // namespace aq::io::unit_mesh_files_ugrid_dataset_test
