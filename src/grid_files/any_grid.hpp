// SPDX-License-Identifier: GPL-3.0-or-later
// Any grid file aquatoria writes, as a planar grid for `aquatoria check`: a planar xygrid
// (<name>_xygrid.nc: x, y), a ROMS grid (<name>_grd.nc: the supergrid put together from its ρ, u,
// v and ψ points) or a MOM6 supergrid (ocean_hgrid.nc: x, y). Geographic positions (ROMS, MOM6) are
// mapped by a stereographic projection centred on the grid: conformal, so the angles the checks
// measure are the angles on the sphere.
#pragma once

#include <array>
#include <filesystem>
#include <span>
#include <string>

#include "core/enum_names.hpp"
#include "grid_files/xygrid_netcdf.hpp"

namespace aq::io {

/// What a grid file is.
enum class GridFileKind { kXygrid, kRoms, kMom6 };
inline constexpr std::array<EnumName<GridFileKind>, 3> kGridFileKindNames{{
    {GridFileKind::kXygrid, "xygrid", "a planar grid, <name>_xygrid.nc"},
    {GridFileKind::kRoms, "roms", "a ROMS grid, <name>_grd.nc"},
    {GridFileKind::kMom6, "mom6", "a MOM6 supergrid, ocean_hgrid.nc"},
}};
constexpr std::span<const EnumName<GridFileKind>> enum_names(GridFileKind) { return kGridFileKindNames; }

struct AnyGrid {
  XyGrid xy;
  GridFileKind kind = GridFileKind::kXygrid;
};

/// Reads `path` by what it holds (MOM6: dimension nxp and variable angle_dx; ROMS: variable
/// lon_psi; otherwise an xygrid). Throws InputError naming the file when it is none of them.
AnyGrid read_any_grid(const std::filesystem::path& path);

}  // namespace aq::io
