// Any grid file aquatoria writes, as a planar grid for `aquatoria check`: a planar xygrid
// (<name>_xygrid.nc: x, y), a ROMS grid (<name>_grd.nc: the supergrid put together from its ρ, u,
// v and ψ points) or a MOM6 supergrid (ocean_hgrid.nc: x, y). Geographic positions (ROMS, MOM6) are
// mapped by a stereographic projection centred on the grid: conformal, so the angles the checks
// measure are the angles on the sphere.
#pragma once

#include <filesystem>
#include <string>

#include "grid_files/xygrid_netcdf.hpp"

namespace aq::io {

struct AnyGrid {
  XyGrid xy;
  std::string kind;  ///< "xygrid", "roms" or "mom6"
};

/// Reads `path` by what it holds (MOM6: dimension nxp and variable angle_dx; ROMS: variable
/// lon_psi; otherwise an xygrid). Throws InputError naming the file when it is none of them.
AnyGrid read_any_grid(const std::filesystem::path& path);

}  // namespace aq::io
