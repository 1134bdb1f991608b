// ROMS nested-grid contact points (myroms/roms Data/ROMS/CDL/nesting.cdl; ROMS Matlab tools
// contact.m / write_contact.m): the parent ROMS grid fields the contact points need, read from a
// `_grd.nc`, and the contact-point file `<name>_contact.nc` of one refinement-style contact
// region, donor grid 1 (the parent) -> receiver grid 2 (the child), written as netCDF classic
// 64-bit offset:
//
//   dimensions: Ngrids = 2, Ncontact = 1, nLweights = 4, nQweights = 9, datum = N
//   variables:  int spherical (1 = T);  int Lm(Ngrids), Mm(Ngrids) (interior ρ points);
//               int refine_factor(Ngrids) (1 for the parent, round(median refinement ratio) for
//               the child);  int coincident, composite, hybrid, mosaic, refinement, interpolate,
//               donor_grid, receiver_grid, NstrR, NendR, NstrU, NendU, NstrV, NendV (Ncontact);
//               int contact_region, on_boundary, Idg, Jdg, Irg, Jrg (datum);
//               double Xrg, Yrg (datum) (receiver point longitude/latitude, degrees);
//               double Lweight(datum, nLweights), Qweight(datum, nQweights);
//               double angle, dmde, dndx, f, h, mask, pm, pn (datum) (donor data at the point).
//   global:     type, title, history, parent_grid, receiver_grid_name, refinement_ratio_*,
//               Qweight_stencil, then the caller's attributes.
//
// Datum order: the receiver's perimeter ρ points (NstrR..NendR, 1-based), then u, then v.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace aq::io {

/// What contact points need from a ROMS grid file (grd_spherical.cdl): ρ/u/v positions and masks,
/// and the ρ fields interpolated to the contact points. Arrays are (eta, xi) row-major, ξ fastest.
struct RomsGridFields {
  int L = 0, M = 0;  ///< xi_rho = L+1, eta_rho = M+1
  std::vector<double> lon_rho, lat_rho, lon_u, lat_u, lon_v, lat_v;
  std::vector<double> mask_rho, mask_u, mask_v;
  std::vector<double> h, f, pm, pn, dndx, dmde, angle;
};

/// Reads the fields from a ROMS grid file. Throws InputError naming `path` when it is missing, a
/// variable is absent or its dimensions do not fit xi_rho/eta_rho.
RomsGridFields read_roms_grid_fields(const std::filesystem::path& path);

/// One contact region of nesting.cdl (donor 1 -> receiver 2) with its contact points.
struct ContactFile {
  std::array<int, 2> Lm{}, Mm{}, refine_factor{1, 1};
  int NstrR = 0, NendR = 0, NstrU = 0, NendU = 0, NstrV = 0, NendV = 0;  ///< 1-based datum ranges
  // Per contact point.
  std::vector<std::int32_t> on_boundary, Idg, Jdg, Irg, Jrg;
  std::vector<double> Xrg, Yrg;
  std::vector<std::array<double, 4>> Lweight;
  std::vector<std::array<double, 9>> Qweight;
  std::vector<double> angle, dmde, dndx, f, h, mask, pm, pn;
  std::string title = "aquatoria ROMS nesting contact points (refinement: parent donor, child receiver)";
  std::string history;
  std::vector<std::pair<std::string, std::variant<std::string, double, std::int64_t>>> attributes;

  [[nodiscard]] std::size_t size() const { return Idg.size(); }
};

/// The variable names written, in order.
const std::vector<std::string>& contact_variables();

/// Writes `data` to `path`. InternalError when the per-point arrays differ in length, OutputError
/// naming the path on a netCDF failure.
void write_contact(const std::filesystem::path& path, const ContactFile& data);

}  // namespace aq::io
