// SPDX-License-Identifier: GPL-3.0-or-later
// MOM6 grid files of a regional grid (what MOM6's MOM_grid_initialize reads with GRID_CONFIG =
// "mosaic", and its topography with TOPO_CONFIG = "file"; the FMS "mosaic" supergrid convention):
//
//   ocean_hgrid.nc  the supergrid: nxp = 2 nx + 1 by nyp = 2 ny + 1 points for nx × ny model cells;
//                   x, y (degrees east/north, [nyp][nxp]), dx ([nyp][nx], metres between
//                   neighbours along i), dy ([ny][nxp], along j), area ([ny][nx], m², each
//                   supergrid cell on the sphere), angle_dx ([nyp][nxp], degrees counter-clockwise
//                   from east to the i direction), tile = "tile1".
//   ocean_topog.nc  depth ([ny][nx], metres, positive down, 0 on land) at the cell centres.
//   ocean_mask.nc   mask ([ny][nx], 1 ocean, 0 land).
//
// From an izogrid supergrid of (2L+1) × (2M+1) points (ROMS: ρ at even indices including the
// contour, ψ at odd ones): MOM6's cells are ROMS's interior ρ cells, nx = L − 1, ny = M − 1, their
// corners the ψ points, so MOM6's supergrid is ours without its outer ring: MOM6 (I, J) = ours
// (I + 1, J + 1). MOM6's cell (i, j) is ROMS ρ (i + 1, j + 1). Distances are great circles on the
// sphere of the ROMS metrics, so the two dx of a cell's middle row add up to the ROMS file's 1/pm
// there (and dy to 1/pn); areas are spherical quadrilaterals on the same sphere.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "curvilinear/common/grid2d.hpp"
#include "curvilinear/common/projection.hpp"

namespace aq::io {

struct Mom6Grid {
  int nx = 0, ny = 0;                            ///< model cells
  std::vector<double> x, y;                      ///< (2ny+1)·(2nx+1), degrees
  std::vector<double> dx;                        ///< (2ny+1)·(2nx), m
  std::vector<double> dy;                        ///< (2ny)·(2nx+1), m
  std::vector<double> area;                      ///< (2ny)·(2nx), m²
  std::vector<double> angle_dx;                  ///< (2ny+1)·(2nx+1), degrees
  std::vector<double> depth;                     ///< ny·nx, m, positive down, 0 on land
  std::vector<double> mask;                      ///< ny·nx, 0/1
  double radius_m = 6371000.0;
  [[nodiscard]] int nxp() const { return 2 * nx + 1; }
  [[nodiscard]] int nyp() const { return 2 * ny + 1; }
};

/// The MOM6 grid of an izogrid supergrid (see the top of this file). `h` and `mask_rho` are ROMS ρ
/// arrays of (L+1)·(M+1) values (row-major, ξ fastest); depth is h where the mask is wet, else 0.
/// Throws InternalError for sizes that do not fit, InputError for a grid with fewer than 1 model
/// cell in a direction or a non-finite position.
Mom6Grid mom6_grid(const curvilinear::Grid2D& supergrid, const curvilinear::Projection& projection,
                   const std::vector<double>& h, const std::vector<double>& mask_rho, double radius_m);

/// Writes the three files (callers pass OutputSet::temp_path for each). `history` goes into every
/// file's attributes. Throws OutputError naming the path.
void write_mom6_files(const Mom6Grid& g, const std::filesystem::path& hgrid, const std::filesystem::path& topog,
                      const std::filesystem::path& mask, const std::string& history);

/// Reads ocean_hgrid.nc back (x, y, dx, dy, area, angle_dx; depth and mask stay empty). Throws
/// InputError naming the path when a variable is missing or has other dimensions.
Mom6Grid read_mom6_hgrid(const std::filesystem::path& path);

/// Reads the depth ([ny][nx]) of ocean_topog.nc or the mask of ocean_mask.nc (`variable`).
std::vector<double> read_mom6_field(const std::filesystem::path& path, const char* variable, int& nx, int& ny);

}  // namespace aq::io
