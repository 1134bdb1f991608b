// SPDX-License-Identifier: GPL-3.0-or-later
// FESOM2 (nod2d/elem2d/aux3d.out) and SCHISM (hgrid.gr3/.ll) files, parsed back here
// independently of the writers: counts, 1-based ids, every element's orientation on the sphere
// (clockwise for FESOM, anticlockwise for SCHISM), depth signs, boundary flags and land boundary
// lists closed and made of exactly the mesh's boundary edges; and FESOM's Euler angles against
// FESOM's own rotation formula.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/rotation.hpp"
#include "mesh_files/fesom_writer.hpp"
#include "mesh_files/geographic_mesh.hpp"
#include "mesh_files/schism_writer.hpp"
#include "support/io_test_mesh.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_mesh_files_fesom_schism_writer_test {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

const ElevationSampler kSampler = [](const std::vector<double>& lon, const std::vector<double>& lat,
                                     std::vector<double>& out) {
  out.resize(lon.size());
  for (std::size_t k = 0; k < lon.size(); ++k) out[k] = -1000.0 - lat[k];
};

// Signed area (steradians, anticlockwise from outside positive) of the triangle a, b, c given as
// lon/lat degrees: the sum over edges of the planar cross products of unit vectors (l'Huilier is
// not needed for the sign of small and medium triangles).
double signed_area(const std::array<double, 2>& a, const std::array<double, 2>& b, const std::array<double, 2>& c) {
  auto v = [](const std::array<double, 2>& p) {
    return std::array<double, 3>{std::cos(p[1] * kDeg) * std::cos(p[0] * kDeg),
                                 std::cos(p[1] * kDeg) * std::sin(p[0] * kDeg), std::sin(p[1] * kDeg)};
  };
  const auto A = v(a), B = v(b), C = v(c);
  // det[A, B, C] is 6 × the signed volume of the tetrahedron with the centre: the triangle's sense.
  return A[0] * (B[1] * C[2] - B[2] * C[1]) - A[1] * (B[0] * C[2] - B[2] * C[0]) + A[2] * (B[0] * C[1] - B[1] * C[0]);
}

std::istringstream open_text(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return std::istringstream(ss.str());
}

// The capped geographic mesh of the arctic test mesh: a pole cap, an island, a coast at 70°N.
const mesh::Mesh& capped() {
  static const mesh::Mesh lattice = testing::arctic_mesh();
  static const GeographicMesh g(lattice, ElementKinds::kTriangles, kSampler);
  return g.mesh();
}

// Directed boundary edges of triangles given by 0-based node triples (edges in one triangle only).
std::set<std::pair<long, long>> boundary_of(const std::vector<std::array<long, 3>>& tris) {
  std::map<std::pair<long, long>, int> half;
  for (const auto& t : tris)
    for (int e = 0; e < 3; ++e) ++half[{t[e], t[(e + 1) % 3]}];
  std::set<std::pair<long, long>> b;
  for (const auto& [e, k] : half)
    if (half.count({e.second, e.first}) == 0) b.insert(e);
  return b;
}

TEST(FesomWriter, NodesElementsAndDepthsReadBack) {
  testing::TempDir dir;
  const mesh::Mesh& m = capped();
  const std::vector<double> levels{0, 10, 25, 50, 100, 250};
  write_fesom_nod2d(m, dir / "nod2d.out");
  write_fesom_elem2d(m, dir / "elem2d.out");
  write_fesom_aux3d(m, dir / "aux3d.out", levels);

  auto nod = open_text(dir / "nod2d.out");
  long n2d = 0;
  nod >> n2d;
  ASSERT_EQ(n2d, m.node_count());
  std::vector<std::array<double, 2>> ll(static_cast<std::size_t>(n2d));
  std::vector<int> flag(ll.size());
  for (long k = 0; k < n2d; ++k) {
    long id = 0;
    nod >> id >> ll[k][0] >> ll[k][1] >> flag[k];
    ASSERT_EQ(id, k + 1);
    EXPECT_GE(ll[k][0], -180.0);
    EXPECT_LT(ll[k][0], 180.0);
    EXPECT_LT(ll[k][1], 90.0);  // nothing on the pole
    EXPECT_TRUE(flag[k] == 0 || flag[k] == 1);
  }
  auto ele = open_text(dir / "elem2d.out");
  long e2d = 0;
  ele >> e2d;
  ASSERT_EQ(e2d, m.triangle_count());
  std::vector<std::array<long, 3>> tris(static_cast<std::size_t>(e2d));
  for (auto& t : tris) {
    for (auto& v : t) {
      ele >> v;
      ASSERT_GE(v, 1);
      ASSERT_LE(v, n2d);
      --v;
    }
    // Clockwise seen from outside (FESOM's sense), never degenerate.
    EXPECT_LT(signed_area(ll[t[0]], ll[t[1]], ll[t[2]]), -1e-9);
  }
  // Flag 1 exactly on the nodes of the triangles' boundary (coast at 70°N and the polar island).
  std::set<long> on_boundary;
  for (const auto& e : boundary_of(tris)) on_boundary.insert({e.first, e.second});
  for (long k = 0; k < n2d; ++k) EXPECT_EQ(flag[k], on_boundary.count(k) ? 1 : 0) << k;
  EXPECT_GT(on_boundary.size(), 36u);

  auto aux = open_text(dir / "aux3d.out");
  long nl = 0;
  aux >> nl;
  ASSERT_EQ(nl, 6);
  for (const double z : levels) {
    double read = 0;
    aux >> read;
    EXPECT_EQ(read, -z);  // negative below the surface
  }
  for (long k = 0; k < n2d; ++k) {
    double d = 0;
    aux >> d;
    EXPECT_EQ(d, m.depth_m[static_cast<std::size_t>(k)]);  // negative: -1000 - lat
    EXPECT_LT(d, 0.0);
  }
  std::string rest;
  aux >> rest;
  EXPECT_TRUE(rest.empty());
}

TEST(FesomWriter, LandNodesGetDepthZeroAndBadLevelsThrow) {
  testing::TempDir dir;
  mesh::Mesh m = testing::tiny_mesh();
  m.depth_m[0] = 25.0;  // above sea level
  write_fesom_aux3d(m, dir / "aux3d.out", default_fesom_levels_m());
  auto aux = open_text(dir / "aux3d.out");
  long nl = 0;
  aux >> nl;
  EXPECT_EQ(nl, static_cast<long>(default_fesom_levels_m().size()));
  double v = 0;
  for (long k = 0; k < nl; ++k) aux >> v;
  EXPECT_EQ(v, -6250.0);
  aux >> v;
  EXPECT_EQ(v, 0.0);
  EXPECT_FALSE(std::signbit(v));
  EXPECT_THROW(write_fesom_aux3d(m, dir / "bad.out", {0, 5, 10}), InternalError);
  EXPECT_THROW(write_fesom_aux3d(m, dir / "bad.out", {0, 5, 10, 10, 20}), InternalError);
}

// FESOM's geographic -> rotated matrix for Euler angles (degrees), as gen_modules_rotate_grid.F90
// defines it (z, new x, new z), applied to a geographic point.
std::array<double, 2> fesom_g2r(double alpha, double beta, double gamma, double lon, double lat) {
  const double al = alpha * kDeg, be = beta * kDeg, ga = gamma * kDeg;
  const double M[3][3] = {
      {std::cos(ga) * std::cos(al) - std::sin(ga) * std::cos(be) * std::sin(al),
       std::cos(ga) * std::sin(al) + std::sin(ga) * std::cos(be) * std::cos(al), std::sin(ga) * std::sin(be)},
      {-std::sin(ga) * std::cos(al) - std::cos(ga) * std::cos(be) * std::sin(al),
       -std::sin(ga) * std::sin(al) + std::cos(ga) * std::cos(be) * std::cos(al), std::cos(ga) * std::sin(be)},
      {std::sin(be) * std::sin(al), -std::sin(be) * std::cos(al), std::cos(be)}};
  const double g[3] = {std::cos(lat * kDeg) * std::cos(lon * kDeg), std::cos(lat * kDeg) * std::sin(lon * kDeg),
                       std::sin(lat * kDeg)};
  double r[3];
  for (int i = 0; i < 3; ++i) r[i] = M[i][0] * g[0] + M[i][1] * g[1] + M[i][2] * g[2];
  return {std::atan2(r[1], r[0]) / kDeg, std::asin(r[2]) / kDeg};
}

TEST(FesomWriter, EulerAnglesGiveTheMeshsRotatedFrame) {
  // An unrotated mesh: FESOM's standard geographic setting (force_rotation with 50, 15, -90, its
  // model pole on Greenland), as the namelist line says.
  const FesomRotation u = fesom_rotation(mesh::RotationInfo{});
  EXPECT_TRUE(u.force_rotation);
  EXPECT_EQ(u.namelist(), "force_rotation = .true., alphaEuler = 50, betaEuler = 15, gammaEuler = -90");
  for (const auto& [plon, plat] :
       std::vector<std::pair<double, double>>{{-44.858333, 78.141667}, {-40.0, 75.0}, {100.0, 30.0}, {170.0, -20.0}}) {
    mesh::RotationInfo ri;
    ri.enabled = true;
    ri.pole_lon_deg = plon;
    ri.pole_lat_deg = plat;
    const FesomRotation f = fesom_rotation(ri);
    EXPECT_TRUE(f.force_rotation);
    const PoleRotation ours(plon, plat);
    for (const auto& [lon, lat] : std::vector<std::pair<double, double>>{
             {0.0, 0.0}, {-30.0, 60.0}, {120.0, -45.0}, {179.0, 10.0}, {-100.0, -80.0}}) {
      double rlon = 0, rlat = 0;
      ours.to_rotated(lon, lat, rlon, rlat);
      const auto fr = fesom_g2r(f.alpha_deg, f.beta_deg, f.gamma_deg, lon, lat);
      EXPECT_NEAR(fr[1], rlat, 1e-9) << plon << " " << plat;
      EXPECT_NEAR(std::remainder(fr[0] - rlon, 360.0), 0.0, 1e-9) << plon << " " << plat;
    }
  }
  // FESOM's default (50, 15, -90) is the pole at (-40, 75).
  mesh::RotationInfo d;
  d.enabled = true;
  d.pole_lon_deg = -40.0;
  d.pole_lat_deg = 75.0;
  const FesomRotation f = fesom_rotation(d);
  EXPECT_NEAR(f.alpha_deg, 50.0, 1e-12);
  EXPECT_NEAR(f.beta_deg, 15.0, 1e-12);
  EXPECT_EQ(f.gamma_deg, -90.0);
}

TEST(SchismWriter, HgridReadsBackWithClosedLandBoundariesOnTheMeshBoundary) {
  testing::TempDir dir;
  const mesh::Mesh& m = capped();
  const WriteStats st = write_schism_hgrid(m, dir / "hgrid.gr3");
  auto in = open_text(dir / "hgrid.gr3");
  std::string title;
  std::getline(in, title);
  EXPECT_EQ(title, "aquatoria global ocean mesh");
  long ne = 0, np = 0;
  in >> ne >> np;
  ASSERT_EQ(ne, m.triangle_count());
  ASSERT_EQ(np, m.node_count());
  std::vector<std::array<double, 2>> ll(static_cast<std::size_t>(np));
  for (long k = 0; k < np; ++k) {
    long id = 0;
    double depth = 0;
    in >> id >> ll[k][0] >> ll[k][1] >> depth;
    ASSERT_EQ(id, k + 1);
    EXPECT_EQ(depth, -m.depth_m[static_cast<std::size_t>(k)]);  // positive down
    EXPECT_GT(depth, 0.0);
  }
  std::vector<std::array<long, 3>> tris(static_cast<std::size_t>(ne));
  for (long k = 0; k < ne; ++k) {
    long id = 0, nv = 0;
    in >> id >> nv;
    ASSERT_EQ(id, k + 1);
    ASSERT_EQ(nv, 3);
    for (auto& v : tris[k]) {
      in >> v;
      --v;
    }
    EXPECT_GT(signed_area(ll[tris[k][0]], ll[tris[k][1]], ll[tris[k][2]]), 1e-9) << k;  // anticlockwise
  }
  auto number_line = [&in] {
    std::string line;
    while (line.find_first_not_of(" \t\r") == std::string::npos) std::getline(in, line);
    return line;
  };
  long nope = -1, neta = -1, nland = -1, nvel = -1;
  std::istringstream(number_line()) >> nope;
  std::istringstream(number_line()) >> neta;
  const std::string land_line = number_line();
  std::istringstream(land_line) >> nland;
  std::istringstream(number_line()) >> nvel;
  EXPECT_EQ(nope, 0);
  EXPECT_EQ(neta, 0);
  EXPECT_NE(land_line.find("NLAND"), std::string::npos) << land_line;
  EXPECT_EQ(nland, static_cast<long>(m.loops.size()));
  // Every land boundary closed (first node repeated), its steps exactly the boundary edges of the
  // triangles (wet area on the left), each once; one land (ibtype 0) boundary, the rest islands.
  const auto boundary = boundary_of(tris);
  std::set<std::pair<long, long>> listed;
  long total = 0, land = 0;
  for (long b = 0; b < nland; ++b) {
    long nn = 0, ibtype = -1;
    std::istringstream(number_line()) >> nn >> ibtype;
    ASSERT_GE(nn, 4);
    land += ibtype == 0 ? 1 : 0;
    EXPECT_TRUE(ibtype == 0 || ibtype == 1);
    std::vector<long> nodes(static_cast<std::size_t>(nn));
    for (auto& v : nodes) {
      std::istringstream(number_line()) >> v;
      --v;
    }
    EXPECT_EQ(nodes.front(), nodes.back());
    for (std::size_t k = 0; k + 1 < nodes.size(); ++k) {
      const std::pair<long, long> e{nodes[k], nodes[k + 1]};
      EXPECT_TRUE(boundary.count(e)) << e.first << "->" << e.second;
      EXPECT_TRUE(listed.insert(e).second);
    }
    total += nn;
  }
  EXPECT_EQ(land, 1);
  EXPECT_EQ(total, nvel);
  EXPECT_EQ(listed, boundary);
  EXPECT_EQ(st.boundary_edges, static_cast<std::int64_t>(boundary.size()));
}

}  // namespace
}  // namespace aq::io::unit_mesh_files_fesom_schism_writer_test
