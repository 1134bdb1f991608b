// SPDX-License-Identifier: GPL-3.0-or-later
// Reads the triangles of a UGRID file written by aquatoria with the netCDF C API (tests that check
// the written mesh independently of the program's own statistics).
#pragma once

#include <netcdf.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace aq::test {

struct UgridTriangles {
  std::vector<double> lon, lat;                        ///< mesh_node_x, mesh_node_y (degrees)
  std::vector<std::array<std::int64_t, 3>> triangles;  ///< 0-based node indices (start_index applied)
  std::string error;                                   ///< non-empty when the file is not as expected
};

inline UgridTriangles read_ugrid_triangles(const std::filesystem::path& path) {
  UgridTriangles u;
  int nc = -1, v = -1, d = -1;
  if (nc_open(path.c_str(), NC_NOWRITE, &nc) != NC_NOERR) {
    u.error = "cannot open " + path.string();
    return u;
  }
  const auto fail = [&](const std::string& what) {
    u.error = path.string() + ": " + what;
    nc_close(nc);
    return u;
  };
  std::size_t np = 0, nf = 0, corners = 0;
  if (nc_inq_dimid(nc, "nMesh_node", &d) != NC_NOERR || nc_inq_dimlen(nc, d, &np) != NC_NOERR)
    return fail("no nMesh_node");
  if (nc_inq_dimid(nc, "nMesh_face", &d) != NC_NOERR || nc_inq_dimlen(nc, d, &nf) != NC_NOERR)
    return fail("no nMesh_face");
  u.lon.resize(np);
  u.lat.resize(np);
  if (nc_inq_varid(nc, "mesh_node_x", &v) != NC_NOERR || nc_get_var_double(nc, v, u.lon.data()) != NC_NOERR)
    return fail("no mesh_node_x");
  if (nc_inq_varid(nc, "mesh_node_y", &v) != NC_NOERR || nc_get_var_double(nc, v, u.lat.data()) != NC_NOERR)
    return fail("no mesh_node_y");
  if (nc_inq_varid(nc, "mesh_face_nodes", &v) != NC_NOERR) return fail("no mesh_face_nodes");
  int dims[2] = {-1, -1};
  if (nc_inq_vardimid(nc, v, dims) != NC_NOERR || nc_inq_dimlen(nc, dims[1], &corners) != NC_NOERR || corners != 3)
    return fail("mesh_face_nodes is not nMesh_face × 3");
  int start = 0;
  if (nc_get_att_int(nc, v, "start_index", &start) != NC_NOERR) return fail("no mesh_face_nodes:start_index");
  std::vector<long long> faces(3 * nf);
  if (nc_get_var_longlong(nc, v, faces.data()) != NC_NOERR) return fail("cannot read mesh_face_nodes");
  nc_close(nc);
  u.triangles.resize(nf);
  for (std::size_t k = 0; k < nf; ++k)
    for (std::size_t a = 0; a < 3; ++a) u.triangles[k][a] = faces[3 * k + a] - start;
  return u;
}

}  // namespace aq::test
