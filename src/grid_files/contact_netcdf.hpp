// SPDX-License-Identifier: GPL-3.0-or-later
// ROMS nested-grid contact points (ROMS Data/ROMS/CDL/nesting.cdl; the ROMS Matlab tools
// c_contact.m / contact.m / write_contact.m, which write the same layout; ROMS reads it in
// Utility/set_contact.F): the parent ROMS grid fields the contact points need, read from a
// `_grd.nc`, and the contact-point file `<name>_contact.nc` of a two-grid refinement, written as
// netCDF classic 64-bit offset:
//
//   dimensions: Ngrids = 2, Ncontact = 2, nLweights = 4, nQweights = 9, datum = N
//   variables:  int spherical;  int Lm(Ngrids), Mm(Ngrids) (interior ρ points);
//               int refine_factor(Ngrids) (0 for the parent, r for the child);
//               int coincident, composite, mosaic, refinement, interpolate, donor_grid,
//               receiver_grid (Ncontact);  int I_left, I_right, J_bottom, J_top (Ngrids; the
//               parent ψ box of the child, _FillValue −999 for the parent);
//               int NstrR, NendR, NstrU, NendU, NstrV, NendV (Ncontact; 1-based, inclusive);
//               int contact_region, on_boundary, Idg, Jdg, Irg, Jrg (datum);
//               double xi_dg, eta_dg, xi_rg, eta_rg (datum; fractional ROMS index coordinates);
//               double Xdg, Ydg, Xrg, Yrg (datum; longitude, latitude in degrees);
//               double Lweight(datum, nLweights), Qweight(datum, nQweights);
//               double h, f, pm, pn, dndx, dmde, angle (datum; ρ slots only, 1e37 elsewhere);
//               double mask (datum).
//   global:     type = "ROMS Nesting Contact Regions Data", title, grid_files, history, then the
//               caller's attributes.
//
// Datum order: region 1 (donor grid 1 → receiver grid 2) ρ, u, v points, then region 2 (donor 2 →
// receiver 1) ρ, u, v; within each, j outer and i inner.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "io/attribute_value.hpp"

namespace aq::io {

/// What contact points need from a ROMS grid file (grd_spherical.cdl): ρ/u/v/ψ positions, masks,
/// the ρ fields, and aquatoria's generation attributes when present. Arrays are (eta, xi)
/// row-major, ξ fastest.
struct RomsGridFields {
  int L = 0, M = 0;  ///< xi_rho = L+1, eta_rho = M+1
  std::vector<double> lon_rho, lat_rho, lon_u, lat_u, lon_v, lat_v, lon_psi, lat_psi;
  std::vector<double> mask_rho, mask_u, mask_v;
  std::vector<double> mask_psi;  ///< empty when the file has none
  std::vector<double> h, f, pm, pn, dndx, dmde, angle;
  /// Global attributes of aquatoria's regional grids ("" / NaN when absent): the projection the
  /// grid was made in and the computational step ratio.
  std::string proj;
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double rlat = kNaN, rlon = kNaN, rota = kNaN, uscale = kNaN, lat1 = kNaN, lat2 = kNaN, radius = kNaN,
         aspect_ratio = kNaN;
  int izogrid_nx = 0, izogrid_ny = 0;
  /// What made the file (aquatoria's global attributes; "" when absent): the effective regional
  /// configuration as JSON text, and the configuration's source (file name).
  std::string aquatoria_config, regional_config;

  [[nodiscard]] std::size_t rho_at(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(L + 1) + static_cast<std::size_t>(i);
  }
};

/// Reads the fields from a ROMS grid file. Throws InputError naming `path` when it is missing, a
/// variable is absent or its dimensions do not fit xi_rho/eta_rho.
RomsGridFields read_roms_grid_fields(const std::filesystem::path& path);

/// One contact region's 1-based, inclusive datum ranges (an empty type has Nend = Nstr − 1).
struct ContactRegion {
  int donor_grid = 1, receiver_grid = 2;
  int NstrR = 0, NendR = 0, NstrU = 0, NendU = 0, NstrV = 0, NendV = 0;
};

/// The two contact regions of a refinement and their points.
struct ContactFile {
  std::array<int, 2> Lm{}, Mm{}, refine_factor{0, 3};
  std::array<int, 4> parent_box{};  ///< I_left, I_right, J_bottom, J_top of grid 2 in grid 1
  std::array<ContactRegion, 2> regions{};
  // Per contact point.
  std::vector<std::int32_t> contact_region, on_boundary, Idg, Jdg, Irg, Jrg;
  std::vector<double> xi_dg, eta_dg, xi_rg, eta_rg, Xdg, Ydg, Xrg, Yrg;
  std::vector<std::array<double, 4>> Lweight;
  std::vector<std::array<double, 9>> Qweight;
  std::vector<double> h, f, pm, pn, dndx, dmde, angle, mask;
  std::string title = "aquatoria ROMS nesting contact points (refinement: grid 1 parent, grid 2 child)";
  std::string grid_files;  ///< the two grid files, parent first
  std::string history;
  std::vector<std::pair<std::string, AttributeValue>> attributes;  ///< global, in order, after the fixed ones

  [[nodiscard]] std::size_t size() const { return Idg.size(); }
};

/// ROMS's fill value of the per-point fields h … angle in u and v slots.
inline constexpr double kContactFill = 1.0e37;

/// The variable names written, in order.
const std::vector<std::string>& contact_variables();

/// Writes `data` to `path`. InternalError when the per-point arrays differ in length or the
/// region ranges do not tile the data vector, OutputError naming the path on a netCDF failure.
void write_contact(const std::filesystem::path& path, const ContactFile& data);

}  // namespace aq::io
