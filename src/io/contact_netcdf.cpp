// ROMS grid field reader and contact-point writer; schema in contact_netcdf.hpp.
#include "io/contact_netcdf.hpp"

#include <fmt/format.h>
#include <netcdf.h>

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

struct VarSpec {
  const char* name;
  nc_type type;
  Dim dim;
  const char* long_name;
  const char* units;  // nullptr: none
};

constexpr VarSpec kVars[] = {
    {"spherical", NC_INT, Dim::kScalar, "grid type logical switch (1: spherical)", nullptr},
    {"Lm", NC_INT, Dim::kGrids, "number of interior RHO-points in the I-direction", nullptr},
    {"Mm", NC_INT, Dim::kGrids, "number of interior RHO-points in the J-direction", nullptr},
    {"refine_factor", NC_INT, Dim::kGrids, "refinement factor from donor grid", nullptr},
    {"coincident", NC_INT, Dim::kContact, "coincident donor and receiver grids logical switch", nullptr},
    {"composite", NC_INT, Dim::kContact, "composite grid type logical switch", nullptr},
    {"hybrid", NC_INT, Dim::kContact, "hybrid nested grids logical switch", nullptr},
    {"mosaic", NC_INT, Dim::kContact, "mosaic grid type logical switch", nullptr},
    {"refinement", NC_INT, Dim::kContact, "refinement grid type logical switch", nullptr},
    {"interpolate", NC_INT, Dim::kContact, "vertical interpolation at contact points logical switch", nullptr},
    {"donor_grid", NC_INT, Dim::kContact, "data donor grid number", nullptr},
    {"receiver_grid", NC_INT, Dim::kContact, "data receiver grid number", nullptr},
    {"NstrR", NC_INT, Dim::kContact, "starting contact RHO-point index in data vector", nullptr},
    {"NendR", NC_INT, Dim::kContact, "ending contact RHO-point index in data vector", nullptr},
    {"NstrU", NC_INT, Dim::kContact, "starting contact U-point index in data vector", nullptr},
    {"NendU", NC_INT, Dim::kContact, "ending contact U-point index in data vector", nullptr},
    {"NstrV", NC_INT, Dim::kContact, "starting contact V-point index in data vector", nullptr},
    {"NendV", NC_INT, Dim::kContact, "ending contact V-point index in data vector", nullptr},
    {"contact_region", NC_INT, Dim::kDatum, "contact region number", nullptr},
    {"on_boundary", NC_INT, Dim::kDatum, "contact point on receiver grid physical boundary", nullptr},
    {"Idg", NC_INT, Dim::kDatum, "I-left index of donor cell containing contact point", nullptr},
    {"Jdg", NC_INT, Dim::kDatum, "J-bottom index of donor cell containing contact point", nullptr},
    {"Irg", NC_INT, Dim::kDatum, "receiver grid I-index of contact point", nullptr},
    {"Jrg", NC_INT, Dim::kDatum, "receiver grid J-index of contact point", nullptr},
    {"Xrg", NC_DOUBLE, Dim::kDatum, "longitude of receiver grid contact point", "degree_east"},
    {"Yrg", NC_DOUBLE, Dim::kDatum, "latitude of receiver grid contact point", "degree_north"},
    {"Lweight", NC_DOUBLE, Dim::kL, "linear interpolation weights", nullptr},
    {"Qweight", NC_DOUBLE, Dim::kQ, "quadratic interpolation weights", nullptr},
    {"angle", NC_DOUBLE, Dim::kDatum, "angle between XI-axis and EAST at contact points", "radians"},
    {"dmde", NC_DOUBLE, Dim::kDatum, "ETA-derivative of inverse metric factor pm at contact points", "meter"},
    {"dndx", NC_DOUBLE, Dim::kDatum, "XI-derivative of inverse metric factor pn at contact points", "meter"},
    {"f", NC_DOUBLE, Dim::kDatum, "Coriolis parameter at contact points", "second-1"},
    {"h", NC_DOUBLE, Dim::kDatum, "bathymetry at contact points", "meter"},
    {"mask", NC_DOUBLE, Dim::kDatum, "land-sea mask of contact points", nullptr},
    {"pm", NC_DOUBLE, Dim::kDatum, "curvilinear coordinate metric in XI at contact points", "meter-1"},
    {"pn", NC_DOUBLE, Dim::kDatum, "curvilinear coordinate metric in ETA at contact points", "meter-1"},
};

}  // namespace

RomsGridFields read_roms_grid_fields(const fs::path& path) {
  if (!fs::exists(path)) throw InputError(fmt::format("{}: no such ROMS grid file", path.string()));
  NcFile nc;
  nc_check<InputError>(nc_open(path.c_str(), NC_NOWRITE, nc.out()), path, "open");
  const int id = nc.id();
  const std::size_t xr = dim_len(id, "xi_rho", path), er = dim_len(id, "eta_rho", path);
  if (xr < 3 || er < 3) throw InputError(fmt::format("{}: a ROMS grid needs xi_rho, eta_rho >= 3", path.string()));
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
  g.h = read_2d(id, "h", er, xr, path);
  g.f = read_2d(id, "f", er, xr, path);
  g.pm = read_2d(id, "pm", er, xr, path);
  g.pn = read_2d(id, "pn", er, xr, path);
  g.dndx = read_2d(id, "dndx", er, xr, path);
  g.dmde = read_2d(id, "dmde", er, xr, path);
  g.angle = read_2d(id, "angle", er, xr, path);
  return g;
}

const std::vector<std::string>& contact_variables() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const VarSpec& v : kVars) n.emplace_back(v.name);
    return n;
  }();
  return names;
}

void write_contact(const fs::path& path, const ContactFile& d) {
  const std::size_t n = d.size();
  bool ok = d.on_boundary.size() == n && d.Jdg.size() == n && d.Irg.size() == n && d.Jrg.size() == n &&
            d.Xrg.size() == n && d.Yrg.size() == n && d.Lweight.size() == n && d.Qweight.size() == n;
  for (const auto* v : {&d.angle, &d.dmde, &d.dndx, &d.f, &d.h, &d.mask, &d.pm, &d.pn}) ok = ok && v->size() == n;
  if (!ok) throw InternalError(fmt::format("write_contact {}: per-point arrays differ in length", path.string()));
  if (n == 0) throw InternalError(fmt::format("write_contact {}: no contact points", path.string()));

  NcFile nc;
  nc_check<OutputError>(nc_create(path.c_str(), NC_CLOBBER | NC_64BIT_OFFSET, nc.out()), path, "create");
  const int id = nc.id();
  int dg = -1, dc = -1, dl = -1, dq = -1, dd = -1;
  nc_check<OutputError>(nc_def_dim(id, "Ngrids", 2, &dg), path, "dimension Ngrids");
  nc_check<OutputError>(nc_def_dim(id, "Ncontact", 1, &dc), path, "dimension Ncontact");
  nc_check<OutputError>(nc_def_dim(id, "nLweights", 4, &dl), path, "dimension nLweights");
  nc_check<OutputError>(nc_def_dim(id, "nQweights", 9, &dq), path, "dimension nQweights");
  nc_check<OutputError>(nc_def_dim(id, "datum", n, &dd), path, "dimension datum");
  std::vector<int> vars;
  for (const VarSpec& v : kVars) {
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
    vars.push_back(var);
  }
  const auto var_of = [&](const char* name) {
    for (std::size_t k = 0; k < std::size(kVars); ++k)
      if (std::string(kVars[k].name) == name) return vars[k];
    throw InternalError(fmt::format("write_contact: no variable {}", name));
  };
  {
    const int fv[2] = {0, 1};
    nc_check<OutputError>(nc_put_att_int(id, var_of("spherical"), "flag_values", NC_INT, 2, fv), path, "flag_values");
    put_text(id, var_of("spherical"), "flag_meanings", "Cartesian spherical", path);
    const int bv[5] = {0, 1, 2, 3, 4};
    nc_check<OutputError>(nc_put_att_int(id, var_of("on_boundary"), "flag_values", NC_INT, 5, bv), path, "flag_values");
    put_text(id, var_of("on_boundary"), "flag_meanings", "other western southern eastern northern", path);
    put_text(id, var_of("Lweight"), "comment",
             "corners (Idg,Jdg), (Idg+1,Jdg), (Idg+1,Jdg+1), (Idg,Jdg+1) of the donor cell of the point's type", path);
  }
  put_text(id, NC_GLOBAL, "type", "ROMS Nesting Contact Points file", path);
  put_text(id, NC_GLOBAL, "title", d.title, path);
  if (!d.history.empty()) put_text(id, NC_GLOBAL, "history", d.history, path);
  for (const auto& [key, value] : d.attributes) {
    if (const auto* s = std::get_if<std::string>(&value)) {
      put_text(id, NC_GLOBAL, key.c_str(), *s, path);
    } else if (const auto* x = std::get_if<double>(&value)) {
      nc_check<OutputError>(nc_put_att_double(id, NC_GLOBAL, key.c_str(), NC_DOUBLE, 1, x), path, key);
    } else {
      const int v = static_cast<int>(std::get<std::int64_t>(value));
      nc_check<OutputError>(nc_put_att_int(id, NC_GLOBAL, key.c_str(), NC_INT, 1, &v), path, key);
    }
  }
  nc_check<OutputError>(nc_enddef(id), path, "end of definitions");

  const auto put_i = [&](const char* name, const std::vector<std::int32_t>& v) {
    nc_check<OutputError>(nc_put_var_int(id, var_of(name), v.data()), path, fmt::format("write {}", name));
  };
  const auto put_d = [&](const char* name, const std::vector<double>& v) {
    nc_check<OutputError>(nc_put_var_double(id, var_of(name), v.data()), path, fmt::format("write {}", name));
  };
  put_i("spherical", {1});
  put_i("Lm", {d.Lm[0], d.Lm[1]});
  put_i("Mm", {d.Mm[0], d.Mm[1]});
  put_i("refine_factor", {d.refine_factor[0], d.refine_factor[1]});
  put_i("coincident", {0});
  put_i("composite", {0});
  put_i("hybrid", {0});
  put_i("mosaic", {0});
  put_i("refinement", {1});
  put_i("interpolate", {1});
  put_i("donor_grid", {1});
  put_i("receiver_grid", {2});
  put_i("NstrR", {d.NstrR});
  put_i("NendR", {d.NendR});
  put_i("NstrU", {d.NstrU});
  put_i("NendU", {d.NendU});
  put_i("NstrV", {d.NstrV});
  put_i("NendV", {d.NendV});
  put_i("contact_region", std::vector<std::int32_t>(n, 1));
  put_i("on_boundary", d.on_boundary);
  put_i("Idg", d.Idg);
  put_i("Jdg", d.Jdg);
  put_i("Irg", d.Irg);
  put_i("Jrg", d.Jrg);
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
  put_d("angle", d.angle);
  put_d("dmde", d.dmde);
  put_d("dndx", d.dndx);
  put_d("f", d.f);
  put_d("h", d.h);
  put_d("mask", d.mask);
  put_d("pm", d.pm);
  put_d("pn", d.pn);
  nc_check<OutputError>(nc.close(), path, "close");
}

}  // namespace aq::io
