// SPDX-License-Identifier: GPL-3.0-or-later
// ROMS grid field reader and contact-point writer; schema in contact_netcdf.hpp.
#include "grid_files/contact_netcdf.hpp"

#include <fmt/format.h>
#include <netcdf.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "io/netcdf_file.hpp"

namespace aq::io {

namespace fs = std::filesystem;

namespace {

std::vector<double> read_2d(int nc, const char* name, std::size_t nj, std::size_t ni, const fs::path& path) {
  int var = -1;
  nc_check<InputError>(nc_inq_varid(nc, name, &var), path, fmt::format("variable {}", name));
  int ndims = 0;
  nc_check<InputError>(nc_inq_varndims(nc, var, &ndims), path, name);
  if (ndims != 2) throw InputError(fmt::format("{}: {} has {} dimensions, expected 2", path.string(), name, ndims));
  int dims[2] = {-1, -1};
  nc_check<InputError>(nc_inq_vardimid(nc, var, dims), path, name);
  std::size_t len[2] = {0, 0};
  for (int k = 0; k < 2; ++k) nc_check<InputError>(nc_inq_dimlen(nc, dims[k], &len[k]), path, name);
  if (len[0] != nj || len[1] != ni)
    throw InputError(
        fmt::format("{}: {} is {} x {}, expected {} x {} (eta, xi)", path.string(), name, len[0], len[1], nj, ni));
  std::vector<double> v(nj * ni);
  nc_check<InputError>(nc_get_var_double(nc, var, v.data()), path, fmt::format("read {}", name));
  return v;
}

std::size_t dim_len(int nc, const char* name, const fs::path& path) {
  int d = -1;
  nc_check<InputError>(nc_inq_dimid(nc, name, &d), path, fmt::format("dimension {}", name));
  std::size_t n = 0;
  nc_check<InputError>(nc_inq_dimlen(nc, d, &n), path, name);
  return n;
}

enum class Dim { kScalar, kGrids, kContact, kDatum, kL, kQ };

// Extra attributes of a variable, as nesting.cdl / c_contact.m give them.
enum Extra : unsigned {
  kNone = 0,
  kFlags01 = 1u << 0,  // int flag_values 0, 1; flag_meanings "false true"
  kCoord = 1u << 1,    // coordinates "Xrg Yrg"
  kFill = 1u << 2,     // double _FillValue 1e37
  kIntFill = 1u << 3,  // int _FillValue -999
  kLon = 1u << 4,      // standard_name longitude
  kLat = 1u << 5,      // standard_name latitude
};

struct ContactVarSpec {
  const char* name;
  nc_type type;
  Dim dim;
  const char* long_name;
  const char* units;  // nullptr: none
  unsigned extra;
};

// In the order of c_contact.m.
constexpr ContactVarSpec kContactVars[] = {
    {"spherical", NC_INT, Dim::kScalar, "grid type logical switch", nullptr, kNone},
    {"Lm", NC_INT, Dim::kGrids, "number of interior RHO-points in the I-direction", nullptr, kNone},
    {"Mm", NC_INT, Dim::kGrids, "number of interior RHO-points in the J-direction", nullptr, kNone},
    {"refine_factor", NC_INT, Dim::kGrids, "refinement factor from donor grid", nullptr, kNone},
    {"coincident", NC_INT, Dim::kContact, "coincident donor and receiver grids logical switch", nullptr, kFlags01},
    {"composite", NC_INT, Dim::kContact, "composite grid type logical switch", nullptr, kFlags01},
    {"mosaic", NC_INT, Dim::kContact, "mosaic grid type logical switch", nullptr, kFlags01},
    {"refinement", NC_INT, Dim::kContact, "refinement grid type logical switch", nullptr, kFlags01},
    {"interpolate", NC_INT, Dim::kContact, "vertical interpolation at contact points logical switch", nullptr,
     kFlags01},
    {"donor_grid", NC_INT, Dim::kContact, "data donor grid number", nullptr, kNone},
    {"receiver_grid", NC_INT, Dim::kContact, "data receiver grid number", nullptr, kNone},
    {"I_left", NC_INT, Dim::kGrids, "donor grid I-left index at PSI points used to extract refinement grid", nullptr,
     kIntFill},
    {"I_right", NC_INT, Dim::kGrids, "donor grid I-right index at PSI points used to extract refinement grid", nullptr,
     kIntFill},
    {"J_bottom", NC_INT, Dim::kGrids, "donor grid J-bottom index at PSI points used to extract refinement grid",
     nullptr, kIntFill},
    {"J_top", NC_INT, Dim::kGrids, "donor grid J-top index at PSI points used to extract refinement grid", nullptr,
     kIntFill},
    {"NstrR", NC_INT, Dim::kContact, "starting contact RHO-point index in data vector", nullptr, kNone},
    {"NendR", NC_INT, Dim::kContact, "ending contact RHO-point index in data vector", nullptr, kNone},
    {"NstrU", NC_INT, Dim::kContact, "starting contact U-point index in data vector", nullptr, kNone},
    {"NendU", NC_INT, Dim::kContact, "ending contact U-point index in data vector", nullptr, kNone},
    {"NstrV", NC_INT, Dim::kContact, "starting contact V-point index in data vector", nullptr, kNone},
    {"NendV", NC_INT, Dim::kContact, "ending contact V-point index in data vector", nullptr, kNone},
    {"contact_region", NC_INT, Dim::kDatum, "contact region number", nullptr, kNone},
    {"on_boundary", NC_INT, Dim::kDatum, "contact point on receiver grid physical boundary", nullptr, kNone},
    {"Idg", NC_INT, Dim::kDatum, "I-left index of donor cell containing contact point", nullptr, kNone},
    {"Jdg", NC_INT, Dim::kDatum, "J-bottom index of donor cell containing contact point", nullptr, kNone},
    {"Irg", NC_INT, Dim::kDatum, "receiver grid I-index of contact point", nullptr, kCoord},
    {"Jrg", NC_INT, Dim::kDatum, "receiver grid J-index of contact point", nullptr, kCoord},
    {"xi_dg", NC_DOUBLE, Dim::kDatum, "XI-coordinate of donor cell bottom-left corner containing contact point",
     nullptr, kNone},
    {"eta_dg", NC_DOUBLE, Dim::kDatum, "ETA-coordinate of donor cell bottom-left corner containing contact point",
     nullptr, kNone},
    {"xi_rg", NC_DOUBLE, Dim::kDatum, "XI-coordinate of receiver grid contact points", nullptr, kNone},
    {"eta_rg", NC_DOUBLE, Dim::kDatum, "ETA-location of receiver grid contact points", nullptr, kNone},
    {"Xdg", NC_DOUBLE, Dim::kDatum, "longitude of donor cell bottom-left corner containing contact point",
     "degree_east", kLon},
    {"Ydg", NC_DOUBLE, Dim::kDatum, "latitude of donor cell bottom-left corner containing contact point",
     "degree_north", kLat},
    {"Xrg", NC_DOUBLE, Dim::kDatum, "longitude of receiver grid contact points", "degree_east", kLon},
    {"Yrg", NC_DOUBLE, Dim::kDatum, "latitude of receiver grid contact points", "degree_north", kLat},
    {"Lweight", NC_DOUBLE, Dim::kL, "horizontal linear interpolation weights", nullptr, kCoord},
    {"Qweight", NC_DOUBLE, Dim::kQ, "horizontal quadratic interpolation weights", nullptr, kCoord},
    {"h", NC_DOUBLE, Dim::kDatum, "bathymetry at RHO-points", "meter", kCoord | kFill},
    {"f", NC_DOUBLE, Dim::kDatum, "Coriolis parameter at RHO-points", "second-1", kCoord | kFill},
    {"pm", NC_DOUBLE, Dim::kDatum, "curvilinear coordinate metric in XI", "meter-1", kCoord | kFill},
    {"pn", NC_DOUBLE, Dim::kDatum, "curvilinear coordinate metric in ETA", "meter-1", kCoord | kFill},
    {"dndx", NC_DOUBLE, Dim::kDatum, "XI-derivative of inverse metric factor pn", "meter", kCoord | kFill},
    {"dmde", NC_DOUBLE, Dim::kDatum, "ETA-derivative of inverse metric factor pm", "meter", kCoord | kFill},
    {"angle", NC_DOUBLE, Dim::kDatum, "angle between XI-axis and EAST", "radians", kCoord | kFill},
    {"mask", NC_DOUBLE, Dim::kDatum, "land-sea mask of contact points", nullptr, kCoord},
};

}  // namespace

RomsGridFields read_roms_grid_fields(const fs::path& path) {
  if (!fs::exists(path)) throw InputError(fmt::format("{}: no such ROMS grid file", path.string()));
  NcFile nc;
  open_for_reading(path, nc);
  const int id = nc.id();
  const std::size_t xr = dim_len(id, "xi_rho", path), er = dim_len(id, "eta_rho", path);
  if (xr < 3 || er < 3) throw InputError(fmt::format("{}: a ROMS grid needs xi_rho, eta_rho >= 3", path.string()));
  check_declared_size(path, 22.0 * static_cast<double>(xr) * static_cast<double>(er),
                      fmt::format("a ROMS grid of {} x {} rho points", xr, er));
  RomsGridFields g;
  g.L = static_cast<int>(xr) - 1;
  g.M = static_cast<int>(er) - 1;
  g.lon_rho = read_2d(id, "lon_rho", er, xr, path);
  g.lat_rho = read_2d(id, "lat_rho", er, xr, path);
  g.mask_rho = read_2d(id, "mask_rho", er, xr, path);
  g.lon_u = read_2d(id, "lon_u", er, xr - 1, path);
  g.lat_u = read_2d(id, "lat_u", er, xr - 1, path);
  g.mask_u = read_2d(id, "mask_u", er, xr - 1, path);
  g.lon_v = read_2d(id, "lon_v", er - 1, xr, path);
  g.lat_v = read_2d(id, "lat_v", er - 1, xr, path);
  g.mask_v = read_2d(id, "mask_v", er - 1, xr, path);
  g.lon_psi = read_2d(id, "lon_psi", er - 1, xr - 1, path);
  g.lat_psi = read_2d(id, "lat_psi", er - 1, xr - 1, path);
  int psi_var = -1;
  if (nc_inq_varid(id, "mask_psi", &psi_var) == NC_NOERR) g.mask_psi = read_2d(id, "mask_psi", er - 1, xr - 1, path);
  g.h = read_2d(id, "h", er, xr, path);
  g.f = read_2d(id, "f", er, xr, path);
  g.pm = read_2d(id, "pm", er, xr, path);
  g.pn = read_2d(id, "pn", er, xr, path);
  g.dndx = read_2d(id, "dndx", er, xr, path);
  g.dmde = read_2d(id, "dmde", er, xr, path);
  g.angle = read_2d(id, "angle", er, xr, path);
  g.proj = global_text(id, "proj");
  g.rlat = global_number(id, "rlat");
  g.rlon = global_number(id, "rlon");
  g.rota = global_number(id, "rota");
  g.uscale = global_number(id, "uscale");
  g.lat1 = global_number(id, "lat1");
  g.lat2 = global_number(id, "lat2");
  g.radius = global_number(id, "radius");
  g.aspect_ratio = global_number(id, "aspect_ratio");
  const double nx = global_number(id, "izogrid_nx"), ny = global_number(id, "izogrid_ny");
  g.izogrid_nx = std::isfinite(nx) ? static_cast<int>(nx) : 0;
  g.izogrid_ny = std::isfinite(ny) ? static_cast<int>(ny) : 0;
  g.aquatoria_config = global_text(id, "aquatoria_config");
  g.regional_config = global_text(id, "regional_config");
  return g;
}

const std::vector<std::string>& contact_variables() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const ContactVarSpec& v : kContactVars) n.emplace_back(v.name);
    return n;
  }();
  return names;
}

void write_contact(const fs::path& path, const ContactFile& d) {
  const std::size_t n = d.size();
  bool ok = n > 0;
  for (const auto* v : {&d.contact_region, &d.on_boundary, &d.Jdg, &d.Irg, &d.Jrg}) ok = ok && v->size() == n;
  for (const auto* v : {&d.xi_dg, &d.eta_dg, &d.xi_rg, &d.eta_rg, &d.Xdg, &d.Ydg, &d.Xrg, &d.Yrg, &d.h, &d.f, &d.pm,
                        &d.pn, &d.dndx, &d.dmde, &d.angle, &d.mask})
    ok = ok && v->size() == n;
  ok = ok && d.Lweight.size() == n && d.Qweight.size() == n;
  // The six ranges of each region follow each other from 1 to n.
  int next = 1;
  for (const ContactRegion& r : d.regions) {
    for (const auto& [s, e] : {std::pair{r.NstrR, r.NendR}, std::pair{r.NstrU, r.NendU}, std::pair{r.NstrV, r.NendV}}) {
      ok = ok && s == next && e >= s - 1;
      next = e + 1;
    }
  }
  ok = ok && next == static_cast<int>(n) + 1;
  if (!ok)
    throw InternalError(
        fmt::format("write_contact {}: {} points, arrays of other lengths or region ranges that do not tile them",
                    path.string(), n));

  NcFile nc;
  nc_check<OutputError>(nc_create(path.c_str(), NC_CLOBBER | NC_64BIT_OFFSET, nc.out()), path, "create");
  const int id = nc.id();
  int dg = -1, dc = -1, dl = -1, dq = -1, dd = -1;
  nc_check<OutputError>(nc_def_dim(id, "Ngrids", 2, &dg), path, "dimension Ngrids");
  nc_check<OutputError>(nc_def_dim(id, "Ncontact", 2, &dc), path, "dimension Ncontact");
  nc_check<OutputError>(nc_def_dim(id, "nLweights", 4, &dl), path, "dimension nLweights");
  nc_check<OutputError>(nc_def_dim(id, "nQweights", 9, &dq), path, "dimension nQweights");
  nc_check<OutputError>(nc_def_dim(id, "datum", n, &dd), path, "dimension datum");
  std::vector<int> vars;
  for (const ContactVarSpec& v : kContactVars) {
    int dims[2] = {-1, -1};
    int nd = 1;
    switch (v.dim) {
      case Dim::kScalar:
        nd = 0;
        break;
      case Dim::kGrids:
        dims[0] = dg;
        break;
      case Dim::kContact:
        dims[0] = dc;
        break;
      case Dim::kDatum:
        dims[0] = dd;
        break;
      case Dim::kL:
        dims[0] = dd;
        dims[1] = dl;
        nd = 2;
        break;
      case Dim::kQ:
        dims[0] = dd;
        dims[1] = dq;
        nd = 2;
        break;
    }
    int var = -1;
    nc_check<OutputError>(nc_def_var(id, v.name, v.type, nd, dims, &var), path,
                          fmt::format("define variable {}", v.name));
    put_text(id, var, "long_name", v.long_name, path);
    if (v.units != nullptr) put_text(id, var, "units", v.units, path);
    if ((v.extra & kLon) != 0) put_text(id, var, "standard_name", "longitude", path);
    if ((v.extra & kLat) != 0) put_text(id, var, "standard_name", "latitude", path);
    if ((v.extra & kFlags01) != 0) {
      const int fv[2] = {0, 1};
      nc_check<OutputError>(nc_put_att_int(id, var, "flag_values", NC_INT, 2, fv), path, "flag_values");
      put_text(id, var, "flag_meanings", "false true", path);
    }
    if ((v.extra & kCoord) != 0) put_text(id, var, "coordinates", "Xrg Yrg", path);
    if ((v.extra & kFill) != 0)
      nc_check<OutputError>(nc_put_att_double(id, var, "_FillValue", NC_DOUBLE, 1, &kContactFill), path,
                            fmt::format("{} _FillValue", v.name));
    if ((v.extra & kIntFill) != 0) {
      const int fill = -999;
      nc_check<OutputError>(nc_put_att_int(id, var, "_FillValue", NC_INT, 1, &fill), path,
                            fmt::format("{} _FillValue", v.name));
    }
    vars.push_back(var);
  }
  const auto var_of = [&](const char* name) {
    for (std::size_t k = 0; k < std::size(kContactVars); ++k)
      if (std::string(kContactVars[k].name) == name) return vars[k];
    throw InternalError(fmt::format("write_contact: no variable {}", name));
  };
  {
    const int fv[2] = {0, 1};
    nc_check<OutputError>(nc_put_att_int(id, var_of("spherical"), "flag_values", NC_INT, 2, fv), path, "flag_values");
    put_text(id, var_of("spherical"), "flag_meanings", "Cartesian spherical", path);
    const int bv[5] = {0, 1, 2, 3, 4};
    nc_check<OutputError>(nc_put_att_int(id, var_of("on_boundary"), "flag_values", NC_INT, 5, bv), path, "flag_values");
    put_text(id, var_of("on_boundary"), "flag_meanings", "other western southern eastern northern", path);
    const double mv[2] = {0.0, 1.0};
    nc_check<OutputError>(nc_put_att_double(id, var_of("mask"), "flag_values", NC_DOUBLE, 2, mv), path, "flag_values");
    put_text(id, var_of("mask"), "flag_meanings", "land water", path);
    put_text(id, var_of("Lweight"), "comment",
             "donor points (Idg,Jdg), (Idg+1,Jdg), (Idg+1,Jdg+1), (Idg,Jdg+1) of the contact point's type, bilinear "
             "in the donor's fractional index space; 0 for fine-to-coarse points (ROMS averages those)",
             path);
    put_text(id, var_of("Qweight"), "comment",
             "donor points (Idg-1..Idg+1) x (Jdg-1..Jdg+1), I fastest: quadratic weights in fractional index space "
             "plus the cell-average correction ((1/r)^2-1)/24 per direction; used by ROMS with QUADRATIC_WEIGHTS",
             path);
  }
  put_text(id, NC_GLOBAL, "type", "ROMS Nesting Contact Regions Data", path);
  put_text(id, NC_GLOBAL, "title", d.title, path);
  if (!d.grid_files.empty()) put_text(id, NC_GLOBAL, "grid_files", d.grid_files, path);
  if (!d.history.empty()) put_text(id, NC_GLOBAL, "history", d.history, path);
  put_attributes(id, NC_GLOBAL, d.attributes, path);
  nc_check<OutputError>(nc_enddef(id), path, "end of definitions");

  const auto put_i = [&](const char* name, const std::vector<std::int32_t>& v) {
    nc_check<OutputError>(nc_put_var_int(id, var_of(name), v.data()), path, fmt::format("write {}", name));
  };
  const auto put_d = [&](const char* name, const std::vector<double>& v) {
    nc_check<OutputError>(nc_put_var_double(id, var_of(name), v.data()), path, fmt::format("write {}", name));
  };
  const auto per_region = [&](const char* name, auto get) { put_i(name, {get(d.regions[0]), get(d.regions[1])}); };
  put_i("spherical", {1});
  put_i("Lm", {d.Lm[0], d.Lm[1]});
  put_i("Mm", {d.Mm[0], d.Mm[1]});
  put_i("refine_factor", {d.refine_factor[0], d.refine_factor[1]});
  put_i("coincident", {0, 0});
  put_i("composite", {0, 0});
  put_i("mosaic", {0, 0});
  put_i("refinement", {1, 1});
  put_i("interpolate", {1, 1});
  per_region("donor_grid", [](const ContactRegion& r) { return r.donor_grid; });
  per_region("receiver_grid", [](const ContactRegion& r) { return r.receiver_grid; });
  put_i("I_left", {-999, d.parent_box[0]});
  put_i("I_right", {-999, d.parent_box[1]});
  put_i("J_bottom", {-999, d.parent_box[2]});
  put_i("J_top", {-999, d.parent_box[3]});
  per_region("NstrR", [](const ContactRegion& r) { return r.NstrR; });
  per_region("NendR", [](const ContactRegion& r) { return r.NendR; });
  per_region("NstrU", [](const ContactRegion& r) { return r.NstrU; });
  per_region("NendU", [](const ContactRegion& r) { return r.NendU; });
  per_region("NstrV", [](const ContactRegion& r) { return r.NstrV; });
  per_region("NendV", [](const ContactRegion& r) { return r.NendV; });
  put_i("contact_region", d.contact_region);
  put_i("on_boundary", d.on_boundary);
  put_i("Idg", d.Idg);
  put_i("Jdg", d.Jdg);
  put_i("Irg", d.Irg);
  put_i("Jrg", d.Jrg);
  put_d("xi_dg", d.xi_dg);
  put_d("eta_dg", d.eta_dg);
  put_d("xi_rg", d.xi_rg);
  put_d("eta_rg", d.eta_rg);
  put_d("Xdg", d.Xdg);
  put_d("Ydg", d.Ydg);
  put_d("Xrg", d.Xrg);
  put_d("Yrg", d.Yrg);
  {
    std::vector<double> lw(4 * n), qw(9 * n);
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t q = 0; q < 4; ++q) lw[4 * k + q] = d.Lweight[k][q];
      for (std::size_t q = 0; q < 9; ++q) qw[9 * k + q] = d.Qweight[k][q];
    }
    put_d("Lweight", lw);
    put_d("Qweight", qw);
  }
  put_d("h", d.h);
  put_d("f", d.f);
  put_d("pm", d.pm);
  put_d("pn", d.pn);
  put_d("dndx", d.dndx);
  put_d("dmde", d.dmde);
  put_d("angle", d.angle);
  put_d("mask", d.mask);
  nc_check<OutputError>(nc.close(), path, "close");
}

}  // namespace aq::io
