// SPDX-License-Identifier: GPL-3.0-or-later
// Our mesh files read by the programs users read them with: gmsh (MSH 4.1 ASCII/binary, with
// $Periodic), ncdump and CDO (UGRID netCDF: CDO must see an unstructured grid with the right
// cell count and bounds), and VTK's XML reader from python3-vtk9 (VTU). Each test skips only when
// its program is not installed.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <string>

#include "mesh_files/msh_writer.hpp"
#include "mesh_files/ugrid_writer.hpp"
#include "mesh_files/vtu_writer.hpp"
#include "support/io_test_mesh.hpp"
#include "support/msh_parse.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::clients_mesh_formats_client_test {
namespace {

bool have(const std::string& program) { return test::run_command("command -v " + program).exit_code == 0; }

// A python3 that can import vtk (python3-vtk9 is installed for the system python).
std::string python_with_vtk() {
  for (const std::string py : {"/usr/bin/python3", "python3"}) {
    if (test::run_command(py + " -c 'import vtk'").exit_code == 0) return py;
  }
  return "";
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

void expect_gmsh_reads(const std::filesystem::path& in, const std::filesystem::path& out, std::size_t nodes,
                       std::size_t triangles, std::size_t lines, std::size_t periodic_pairs) {
  const auto r = test::run_command("gmsh " + in.string() + " -0 -o " + out.string() + " -format msh41");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.err.find("Error"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("Error"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(std::to_string(triangles + lines) + " elements"), std::string::npos) << r.out;
  // gmsh re-writes only elements that are in physical groups: all of ours must survive.
  const testing::MshFile f = testing::parse_msh(out.string());
  EXPECT_EQ(f.nodes.size(), nodes);
  EXPECT_EQ(f.count_type(2), triangles);
  EXPECT_EQ(f.count_type(1), lines);
  if (periodic_pairs == 0) {
    EXPECT_TRUE(f.periodic.empty());
  } else {
    ASSERT_EQ(f.periodic.size(), 1u);
    EXPECT_EQ(f.periodic[0].pairs.size(), periodic_pairs);
    EXPECT_EQ(f.periodic[0].affine.at(3), 360.0);
    for (const auto& [slave, master] : f.periodic[0].pairs) {
      EXPECT_EQ(f.nodes.at(slave)[0], f.nodes.at(master)[0] + 360.0);
    }
  }
  std::set<std::string> physical;
  for (const auto& p : f.physical_names) physical.insert(p.second);
  EXPECT_EQ(physical, (std::set<std::string>{"coast", "ocean"}));
}

TEST(GmshClient, ReadsAsciiBinaryAndSphereMsh) {
  if (!have("gmsh")) GTEST_SKIP() << "gmsh not installed";
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  MshOptions o;
  write_msh(m, dir / "a.msh", o);
  expect_gmsh_reads(dir / "a.msh", dir / "a_out.msh", 23, 17, 19, 2);
  o.binary = true;
  write_msh(m, dir / "b.msh", o);
  expect_gmsh_reads(dir / "b.msh", dir / "b_out.msh", 23, 17, 19, 2);
  o.coordinates = MshCoordinates::kSphere;
  write_msh(m, dir / "s.msh", o);
  expect_gmsh_reads(dir / "s.msh", dir / "s_out.msh", 19, 15, 17, 0);
}

TEST(GmshClient, ReadsABandAroundTheGlobeWithManySeamPairs) {
  if (!have("gmsh")) GTEST_SKIP() << "gmsh not installed";
  testing::TempDir dir;
  const auto m = testing::band_mesh(Lattice::make(4.0, 1, -180.0), 40, 50);  // 10 rows x 180 columns
  MshOptions o;
  o.binary = true;
  const WriteStats st = write_msh(m, dir / "band.msh", o);
  EXPECT_EQ(st.seam_duplicates, 11);
  expect_gmsh_reads(dir / "band.msh", dir / "band_out.msh", 181 * 11, 3600, 360, 11);
}

TEST(NcdumpClient, ShowsUgridTopologyAndConventions) {
  if (!have("ncdump")) GTEST_SKIP() << "ncdump not installed";
  testing::TempDir dir;
  write_ugrid(testing::tiny_mesh(), dir / "m.nc");
  const auto r = test::run_command("ncdump -h " + (dir / "m.nc").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("mesh:cf_role = \"mesh_topology\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(":Conventions = \"CF-1.8 UGRID-1.0\""), std::string::npos);
  EXPECT_NE(r.out.find("mesh_face_nodes:start_index = 0"), std::string::npos);
  EXPECT_NE(r.out.find("nMesh_face = 17"), std::string::npos);
  const auto d = test::run_command("ncdump -v mesh_face_nodes " + (dir / "m.nc").string());
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_NE(d.out.find("mesh_face_nodes ="), std::string::npos);
}

// Issue 9: UGRID is netCDF-4, chunked and deflated by default (output.ugrid_deflate = 1); 0 gives
// the classic 64-bit-offset file; both hold the same data as ncdump prints it.
TEST(NcdumpClient, UgridIsChunkedDeflatedNetcdf4OrClassicWithTheSameData) {
  if (!have("ncdump")) GTEST_SKIP() << "ncdump not installed";
  testing::TempDir a, b;
  const auto m = testing::band_mesh(Lattice::make(4.0, 1, -180.0), 10, 80);
  write_ugrid(m, a / "m.nc");
  UgridOptions classic;
  classic.deflate = 0;
  write_ugrid(m, b / "m.nc", classic);
  EXPECT_EQ(test::run_command("ncdump -k " + (a / "m.nc").string()).out, "netCDF-4\n");
  EXPECT_EQ(test::run_command("ncdump -k " + (b / "m.nc").string()).out, "64-bit offset\n");
  const auto hs = test::run_command("ncdump -hs " + (a / "m.nc").string());
  ASSERT_EQ(hs.exit_code, 0) << hs.err;
  EXPECT_NE(hs.out.find("mesh_face_nodes:_DeflateLevel = 1"), std::string::npos) << hs.out;
  EXPECT_NE(hs.out.find("mesh_face_nodes:_Shuffle = \"true\""), std::string::npos) << hs.out;
  EXPECT_NE(hs.out.find("mesh_face_nodes:_Storage = \"chunked\""), std::string::npos) << hs.out;
  EXPECT_LT(std::filesystem::file_size(a / "m.nc"), std::filesystem::file_size(b / "m.nc"));
  const auto da = test::run_command("ncdump " + (a / "m.nc").string());
  const auto db = test::run_command("ncdump " + (b / "m.nc").string());
  ASSERT_EQ(da.exit_code, 0) << da.err;
  EXPECT_EQ(da.out, db.out);
}

TEST(CdoClient, SeesAnUnstructuredGridWithBoundsAndReadsTheData) {
  if (!have("cdo")) GTEST_SKIP() << "cdo not installed";
  testing::TempDir dir;
  const auto file = (dir / "m.nc").string();
  write_ugrid(testing::tiny_mesh(), file);
  const auto g = test::run_command("cdo -s griddes " + file);
  ASSERT_EQ(g.exit_code, 0) << g.err;
  EXPECT_NE(g.out.find("gridtype  = unstructured\ngridsize  = 17\n"), std::string::npos) << g.out;
  EXPECT_NE(g.out.find("nvertex   = 3"), std::string::npos) << g.out;
  EXPECT_NE(g.out.find("xbounds"), std::string::npos);
  EXPECT_NE(g.out.find("gridtype  = unstructured\ngridsize  = 21\n"), std::string::npos) << g.out;  // nodes
  EXPECT_EQ(g.err.find("skipped variable"), std::string::npos) << g.err;
  const auto level = test::run_command("cdo -s infon -selname,level " + file);
  ASSERT_EQ(level.exit_code, 0) << level.err;
  EXPECT_NE(level.out.find("17       0 :      0.0000"), std::string::npos) << level.out;
  const auto depth = test::run_command("cdo -s infon -selname,depth " + file);
  ASSERT_EQ(depth.exit_code, 0) << depth.err;
  EXPECT_NE(depth.out.find("21       0 :      102.00"), std::string::npos) << depth.out;  // min depth 102 m
  EXPECT_NE(depth.out.find("253.00 : depth"), std::string::npos) << depth.out;
}

TEST(VtkClient, XmlReaderReadsPointsCellsAndArrays) {
  const std::string py = python_with_vtk();
  if (py.empty()) GTEST_SKIP() << "no python3 with vtk";
  testing::TempDir dir;
  const auto file = (dir / "m.vtu").string();
  VtuOptions o;
  o.elements = ElementKinds::kBoth;
  write_vtu(testing::tiny_mesh(), file, o);
  const std::string script =
      "import vtk\n"
      "r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName('" +
      file +
      "'); r.Update()\n"
      "g = r.GetOutput(); pd = g.GetPointData(); cd = g.GetCellData()\n"
      "print('error', r.GetErrorCode())\n"
      "print('points', g.GetNumberOfPoints(), 'cells', g.GetNumberOfCells())\n"
      "print('pointdata', ' '.join(pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())))\n"
      "print('celldata', ' '.join(cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())))\n"
      "print('depth %.1f %.1f' % pd.GetArray('depth_m').GetRange())\n"
      "print('level %.0f %.0f' % cd.GetArray('level').GetRange())\n"
      "print('types', ' '.join(str(g.GetCellType(i)) for i in range(g.GetNumberOfCells())))\n"
      "b = g.GetBounds(); print('zmax %.6f' % b[5])\n";
  std::ofstream(dir / "read.py") << script;
  const auto r = test::run_command(py + " " + (dir / "read.py").string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("error 0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("points 19 cells 22\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pointdata depth_m flags lon_deg lat_deg\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("celldata level kind\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("depth 102.0 253.0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("level 0 1\n"), std::string::npos) << r.out;
  EXPECT_EQ(count_of(r.out, " 7"), 1u) << r.out;  // one polygon (square A with its hanging node)
  EXPECT_NE(r.out.find("zmax 1.000000"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty() || r.err.find("rror") == std::string::npos) << r.err;
}

// A Mercator-lattice mesh (issue 12) through every client: a band of 10 rows × 180 columns at
// the Mercator ordinates y = 20°..40° (rows 80..90 of the 4°, L = 1 lattice to ±80°).
TEST(MercatorClients, GmshNcdumpCdoAndVtkReadAMercatorMesh) {
  const Lattice lat = Lattice::make_mercator(4.0, 1, -180.0, 80.0);
  ASSERT_EQ(lat.plane_y_of(90), 40.0);
  const auto m = testing::band_mesh(lat, 80, 90);
  testing::TempDir dir;
  if (have("gmsh")) {
    MshOptions o;
    write_msh(m, dir / "p.msh", o);
    expect_gmsh_reads(dir / "p.msh", dir / "p_out.msh", 181 * 11, 3600, 360, 11);
    // The plane is the Mercator plane: y runs over the ordinates 20..40, in 2° steps.
    const testing::MshFile f = testing::parse_msh((dir / "p_out.msh").string());
    double ymin = 1e9, ymax = -1e9;
    for (const auto& [id, xyz] : f.nodes) {
      ymin = std::min(ymin, xyz[1]);
      ymax = std::max(ymax, xyz[1]);
      EXPECT_NEAR(std::remainder(xyz[1], 2.0), 0.0, 1e-12) << xyz[1];
    }
    EXPECT_EQ(ymin, 20.0);
    EXPECT_EQ(ymax, 40.0);
    o.coordinates = MshCoordinates::kSphere;
    write_msh(m, dir / "s.msh", o);
    expect_gmsh_reads(dir / "s.msh", dir / "s_out.msh", 180 * 11, 3600, 360, 0);
  }
  write_ugrid(m, dir / "m.nc");
  if (have("ncdump")) {
    const auto r = test::run_command("ncdump -h " + (dir / "m.nc").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(":aquatoria_lattice_kind = \"mercator\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("nMesh_face = 3600"), std::string::npos) << r.out;
  }
  if (have("cdo")) {
    const auto g = test::run_command("cdo -s griddes " + (dir / "m.nc").string());
    ASSERT_EQ(g.exit_code, 0) << g.err;
    EXPECT_NE(g.out.find("gridtype  = unstructured\ngridsize  = 3600\n"), std::string::npos) << g.out;
    EXPECT_NE(g.out.find("gridtype  = unstructured\ngridsize  = 1980\n"), std::string::npos) << g.out;  // nodes
  }
  const std::string py = python_with_vtk();
  if (!py.empty()) {
    const auto file = (dir / "m.vtu").string();
    write_vtu(m, file, VtuOptions{});
    std::ofstream(dir / "read.py") << "import vtk\n"
                                      "r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName('"
                                   << file
                                   << "'); r.Update()\n"
                                      "g = r.GetOutput(); b = g.GetBounds()\n"
                                      "print('error', r.GetErrorCode())\n"
                                      "print('points', g.GetNumberOfPoints(), 'cells', g.GetNumberOfCells())\n"
                                      "print('z %.9f %.9f' % (b[4], b[5]))\n";
    const auto r = test::run_command(py + " " + (dir / "read.py").string());
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("error 0\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("points 1980 cells 3600\n"), std::string::npos) << r.out;
    // z on the unit sphere = sin φ of the Mercator rows 80 and 90 (φ = atan sinh y).
    const std::string z =
        fmt::format("z {:.9f} {:.9f}\n", std::sin(lat.lat_of(80) * kDegToRad), std::sin(lat.lat_of(90) * kDegToRad));
    EXPECT_NE(r.out.find(z), std::string::npos) << r.out << " expected " << z;
  }
}

}  // namespace
}  // namespace aq::io::clients_mesh_formats_client_test
