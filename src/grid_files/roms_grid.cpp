// SPDX-License-Identifier: GPL-3.0-or-later
// ROMS grid file writer (schema in roms_grid.hpp, after ROMS's grd_spherical.cdl). Every nc_*
// status is checked; errors name the path and carry nc_strerror.
#include "grid_files/roms_grid.hpp"

#include <fmt/format.h>
#include <netcdf.h>

#include <array>
#include <variant>

#include "core/error.hpp"
#include "io/netcdf_file.hpp"

namespace aq::io {

namespace {

namespace fs = std::filesystem;

void check(int status, const fs::path& path, const std::string& what) { nc_check<OutputError>(status, path, what); }

// The open file, closed on scope exit (that close's status only matters on the success path,
// where close() is called explicitly).
class File {
 public:
  explicit File(const fs::path& path) : path_(path) {
    check(nc_create(path.c_str(), NC_CLOBBER | NC_64BIT_OFFSET, &id_), path, "create");
  }
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  ~File() {
    if (id_ >= 0) nc_abort(id_);  // an error is propagating: release the file without flushing it
  }
  [[nodiscard]] int id() const { return id_; }
  [[nodiscard]] const fs::path& path() const { return path_; }
  void close() {
    const int status = nc_close(id_);
    if (status != NC_NOERR) nc_abort(id_);
    id_ = -1;
    check(status, path_, "close");
  }

  int dim(const char* name, std::size_t len) {
    int d = -1;
    check(nc_def_dim(id_, name, len, &d), path_, fmt::format("dimension {}", name));
    return d;
  }
  int var(const char* name, nc_type type, const std::vector<int>& dims) {
    int v = -1;
    check(nc_def_var(id_, name, type, static_cast<int>(dims.size()), dims.data(), &v), path_,
          fmt::format("define variable {}", name));
    return v;
  }
  void text(int var, const char* name, const std::string& value) {
    check(nc_put_att_text(id_, var, name, value.size(), value.c_str()), path_, fmt::format("attribute {}", name));
  }
  void number(int var, const char* name, const std::vector<double>& values) {
    check(nc_put_att_double(id_, var, name, NC_DOUBLE, values.size(), values.data()), path_,
          fmt::format("attribute {}", name));
  }

 private:
  fs::path path_;
  int id_ = -1;
};

struct RomsVarSpec {
  const char* name;
  int family;  // 0 rho, 1 psi, 2 u, 3 v
  const char* long_name;
  const char* units;          // "" = none
  const char* standard_name;  // "" = none
  bool coordinates;           // add coordinates = "lon_<f> lat_<f>"
};

constexpr std::array<const char*, 4> kFamily = {"rho", "psi", "u", "v"};
constexpr std::array<const char*, 5> kRomsReserved = {"type", "Conventions", "title", "history", "source"};

}  // namespace

const std::vector<std::string>& roms_grid_variables() {
  static const std::vector<std::string> names = {
      "spherical", "xl",    "el",    "hraw",  "h",     "f",        "pm",     "pn",      "dndx",    "dmde",    "x_rho",
      "y_rho",     "x_psi", "y_psi", "x_u",   "y_u",   "x_v",      "y_v",    "lat_rho", "lon_rho", "lat_psi", "lon_psi",
      "lat_u",     "lon_u", "lat_v", "lon_v", "angle", "mask_rho", "mask_u", "mask_v",  "mask_psi"};
  return names;
}

void write_roms_grid(const fs::path& path, const RomsGridData& d) {
  if (d.grid == nullptr) throw InternalError(fmt::format("write_roms_grid {}: no grid", path.string()));
  const curvilinear::CGrid& g = *d.grid;
  const std::array<const curvilinear::StaggeredPoints*, 4> pts = {&g.rho, &g.psi, &g.u, &g.v};
  const std::array<const std::vector<std::uint8_t>*, 4> masks = {&d.mask_rho, &d.mask_psi, &d.mask_u, &d.mask_v};
  const std::size_t nr = g.rho.size();
  bool ok = g.rho.ni == g.L + 1 && g.rho.nj == g.M + 1 && g.psi.ni == g.L && g.psi.nj == g.M && g.u.ni == g.L &&
            g.u.nj == g.M + 1 && g.v.ni == g.L + 1 && g.v.nj == g.M;
  for (const auto* v : {&d.h, &d.hraw, &g.pm, &g.pn, &g.dndx, &g.dmde, &g.angle, &g.f}) ok = ok && v->size() == nr;
  for (std::size_t f = 0; f < 4; ++f) {
    const auto n = pts[f]->size();
    ok = ok && masks[f]->size() == n && pts[f]->lon_deg.size() == n && pts[f]->lat_deg.size() == n &&
         pts[f]->x_m.size() == n && pts[f]->y_m.size() == n;
  }
  if (!ok)
    throw InternalError(fmt::format("write_roms_grid {}: array sizes do not match the {} x {} ρ grid", path.string(),
                                    g.L + 1, g.M + 1));
  for (const auto& [key, value] : d.attributes)
    for (const char* r : kRomsReserved)
      if (key.empty() || key == r)
        throw InternalError(
            fmt::format("write_roms_grid {}: attribute name '{}' is reserved or empty", path.string(), key));

  File nc(path);
  const int id = nc.id();
  const auto L = static_cast<std::size_t>(g.L), M = static_cast<std::size_t>(g.M);
  // Dimensions in the CDL's order.
  const int xi_psi = nc.dim("xi_psi", L), xi_rho = nc.dim("xi_rho", L + 1), xi_u = nc.dim("xi_u", L),
            xi_v = nc.dim("xi_v", L + 1), eta_psi = nc.dim("eta_psi", M), eta_rho = nc.dim("eta_rho", M + 1),
            eta_u = nc.dim("eta_u", M + 1), eta_v = nc.dim("eta_v", M), bath = nc.dim("bath", NC_UNLIMITED);
  const std::array<std::vector<int>, 4> fdims = {std::vector<int>{eta_rho, xi_rho}, std::vector<int>{eta_psi, xi_psi},
                                                 std::vector<int>{eta_u, xi_u}, std::vector<int>{eta_v, xi_v}};
  const auto coords = [](int family) {
    return fmt::format("lon_{0} lat_{0}", kFamily[static_cast<std::size_t>(family)]);
  };

  const int v_sph = nc.var("spherical", NC_CHAR, {});
  nc.text(v_sph, "long_name", "Grid type logical switch");
  nc.text(v_sph, "option_T", "spherical");
  nc.text(v_sph, "option_F", "Cartesian");
  const int v_xl = nc.var("xl", NC_DOUBLE, {});
  nc.text(v_xl, "long_name", "domain length in the XI-direction");
  nc.text(v_xl, "units", "meter");
  const int v_el = nc.var("el", NC_DOUBLE, {});
  nc.text(v_el, "long_name", "domain length in the ETA-direction");
  nc.text(v_el, "units", "meter");
  const int v_hraw = nc.var("hraw", NC_DOUBLE, {bath, eta_rho, xi_rho});
  nc.text(v_hraw, "long_name", "Working bathymetry at RHO-points");
  nc.text(v_hraw, "units", "meter");
  nc.text(v_hraw, "standard_name", "sea_floor_depth_below_mean_sea_level");
  nc.text(v_hraw, "comment", "raw depth sampled from the bathymetry, positive down, not clipped or smoothed");
  nc.text(v_hraw, "coordinates", "lon_rho lat_rho");

  // The ρ fields after hraw, in the CDL's order.
  const std::array<RomsVarSpec, 7> rho_fields = {{
      {"h", 0, "Final bathymetry at RHO-points", "meter", "sea_floor_depth_below_mean_sea_level", true},
      {"f", 0, "Coriolis parameter at RHO-points", "second-1", "coriolis_parameter", true},
      {"pm", 0, "curvilinear coordinate metric in XI", "meter-1", "", true},
      {"pn", 0, "curvilinear coordinate metric in ETA", "meter-1", "", true},
      {"dndx", 0, "xi derivative of inverse metric factor pn", "meter", "", true},
      {"dmde", 0, "eta derivative of inverse metric factor pm", "meter", "", true},
      {"angle", 0, "angle between XI-axis and EAST", "radians", "angle_of_rotation_from_east_to_x", true},
  }};
  const std::array<const std::vector<double>*, 7> rho_data = {&d.h, &g.f, &g.pm, &g.pn, &g.dndx, &g.dmde, &g.angle};
  std::array<int, 7> rho_vars{};
  const auto define = [&](const RomsVarSpec& s) {
    const int v = nc.var(s.name, NC_DOUBLE, fdims[static_cast<std::size_t>(s.family)]);
    nc.text(v, "long_name", s.long_name);
    if (*s.units) nc.text(v, "units", s.units);
    if (*s.standard_name) nc.text(v, "standard_name", s.standard_name);
    if (s.coordinates) nc.text(v, "coordinates", coords(s.family));
    return v;
  };
  for (std::size_t k = 0; k < 6; ++k) rho_vars[k] = define(rho_fields[k]);  // angle after the coordinates
  nc.text(rho_vars[0], "comment",
          "hraw clipped to hmin_m and smoothed to the r-factor bound rmax on wet faces (global attributes)");

  // x, y then lat, lon of each family (CDL order: rho, psi, u, v).
  static constexpr std::array<const char*, 4> kUpper = {"RHO", "PSI", "U", "V"};
  std::array<int, 4> vx{}, vy{}, vlat{}, vlon{}, vmask{};
  std::array<std::string, 4> nx_name, ny_name, nlat, nlon, lx, ly, llat, llon;
  for (std::size_t f = 0; f < 4; ++f) {
    nx_name[f] = fmt::format("x_{}", kFamily[f]);
    ny_name[f] = fmt::format("y_{}", kFamily[f]);
    lx[f] = fmt::format("x location of {}-points", kUpper[f]);
    ly[f] = fmt::format("y location of {}-points", kUpper[f]);
    vx[f] = nc.var(nx_name[f].c_str(), NC_DOUBLE, fdims[f]);
    nc.text(vx[f], "long_name", lx[f]);
    nc.text(vx[f], "units", "meter");
    vy[f] = nc.var(ny_name[f].c_str(), NC_DOUBLE, fdims[f]);
    nc.text(vy[f], "long_name", ly[f]);
    nc.text(vy[f], "units", "meter");
  }
  for (std::size_t f = 0; f < 4; ++f) {
    nlat[f] = fmt::format("lat_{}", kFamily[f]);
    nlon[f] = fmt::format("lon_{}", kFamily[f]);
    llat[f] = fmt::format("latitude of {}-points", kUpper[f]);
    llon[f] = fmt::format("longitude of {}-points", kUpper[f]);
    vlat[f] = nc.var(nlat[f].c_str(), NC_DOUBLE, fdims[f]);
    nc.text(vlat[f], "long_name", llat[f]);
    nc.text(vlat[f], "units", "degree_north");
    nc.text(vlat[f], "standard_name", "latitude");
    vlon[f] = nc.var(nlon[f].c_str(), NC_DOUBLE, fdims[f]);
    nc.text(vlon[f], "long_name", llon[f]);
    nc.text(vlon[f], "units", "degree_east");
    nc.text(vlon[f], "standard_name", "longitude");
  }
  rho_vars[6] = define(rho_fields[6]);
  // Masks: rho, u, v, psi as in the CDL.
  for (const std::size_t f : {std::size_t{0}, std::size_t{2}, std::size_t{3}, std::size_t{1}}) {
    const std::string name = fmt::format("mask_{}", kFamily[f]);
    vmask[f] = nc.var(name.c_str(), NC_DOUBLE, fdims[f]);
    nc.text(vmask[f], "long_name", fmt::format("mask on {}-points", kUpper[f]));
    nc.number(vmask[f], "flag_values", {0.0, 1.0});
    nc.text(vmask[f], "flag_meanings", "land water");
    nc.text(vmask[f], "coordinates", coords(static_cast<int>(f)));
  }

  // Global attributes.
  nc.text(NC_GLOBAL, "type", "ROMS GRID file");
  nc.text(NC_GLOBAL, "Conventions", "CF-1.8");
  nc.text(NC_GLOBAL, "title", d.title.empty() ? std::string("aquatoria orthogonal curvilinear ROMS grid") : d.title);
  nc.text(NC_GLOBAL, "history", d.history.empty() ? std::string("created by aquatoria") : d.history);
  nc.text(NC_GLOBAL, "source", d.source.empty() ? std::string("aquatoria") : d.source);
  put_attributes(id, NC_GLOBAL, d.attributes, path);
  int old_fill = 0;
  check(nc_set_fill(id, NC_NOFILL, &old_fill), path, "set no-fill mode");
  check(nc_enddef(id), path, "end of definitions");

  // Data.
  check(nc_put_var_text(id, v_sph, "T"), path, "write spherical");
  check(nc_put_var_double(id, v_xl, &g.xl_m), path, "write xl");
  check(nc_put_var_double(id, v_el, &g.el_m), path, "write el");
  const std::array<std::size_t, 3> start{0, 0, 0}, count{1, M + 1, L + 1};
  check(nc_put_vara_double(id, v_hraw, start.data(), count.data(), d.hraw.data()), path, "write hraw");
  for (std::size_t k = 0; k < rho_vars.size(); ++k)
    check(nc_put_var_double(id, rho_vars[k], rho_data[k]->data()), path, fmt::format("write {}", rho_fields[k].name));
  for (std::size_t f = 0; f < 4; ++f) {
    check(nc_put_var_double(id, vx[f], pts[f]->x_m.data()), path, "write " + nx_name[f]);
    check(nc_put_var_double(id, vy[f], pts[f]->y_m.data()), path, "write " + ny_name[f]);
    check(nc_put_var_double(id, vlat[f], pts[f]->lat_deg.data()), path, "write " + nlat[f]);
    check(nc_put_var_double(id, vlon[f], pts[f]->lon_deg.data()), path, "write " + nlon[f]);
    const std::vector<double> m(masks[f]->begin(), masks[f]->end());
    check(nc_put_var_double(id, vmask[f], m.data()), path, fmt::format("write mask_{}", kFamily[f]));
  }
  nc.close();
}

void write_updated_roms_grid(const fs::path& source, const fs::path& path, const RomsGridUpdate& u) {
  for (const auto& [key, value] : u.attributes)
    for (const char* r : kRomsReserved)
      if (key.empty() || key == r)
        throw InternalError(
            fmt::format("write_updated_roms_grid {}: attribute name '{}' is reserved or empty", path.string(), key));
  if (!fs::exists(source)) throw InputError(fmt::format("{}: no such ROMS grid file", source.string()));
  std::error_code ec;
  fs::copy_file(source, path, fs::copy_options::overwrite_existing, ec);
  if (ec) throw OutputError(fmt::format("{}: cannot copy {}: {}", path.string(), source.string(), ec.message()));
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::add, ec);

  NcFile nc;
  check(nc_open(path.c_str(), NC_WRITE, nc.out()), path, "open the copy");
  const int id = nc.id();
  // The variables first, so that a source without one fails before anything is written.
  struct Target {
    const char* name;
    const std::vector<double>* data;
    int var = -1;
  };
  std::array<Target, 5> targets = {{{"h", &u.h},
                                    {"mask_rho", &u.mask_rho},
                                    {"mask_u", &u.mask_u},
                                    {"mask_v", &u.mask_v},
                                    {"mask_psi", &u.mask_psi}}};
  for (Target& t : targets) {
    if (t.data->empty()) continue;
    nc_check<InputError>(nc_inq_varid(id, t.name, &t.var), source, fmt::format("variable {}", t.name));
    int ndims = 0;
    nc_check<InputError>(nc_inq_varndims(id, t.var, &ndims), source, t.name);
    std::array<int, NC_MAX_VAR_DIMS> dims{};
    nc_check<InputError>(nc_inq_vardimid(id, t.var, dims.data()), source, t.name);
    std::size_t n = 1;
    for (int k = 0; k < ndims; ++k) {
      std::size_t len = 0;
      nc_check<InputError>(nc_inq_dimlen(id, dims[static_cast<std::size_t>(k)], &len), source, t.name);
      n *= len;
    }
    if (n != t.data->size())
      throw InputError(fmt::format("{}: {} has {} values, the update {}", source.string(), t.name, n, t.data->size()));
  }
  check(nc_redef(id), path, "define mode");
  const auto text = [&](const char* name, const std::string& v) {
    check(nc_put_att_text(id, NC_GLOBAL, name, v.size(), v.c_str()), path, fmt::format("attribute {}", name));
  };
  if (!u.history_append.empty()) {
    const std::string old = global_text(id, "history");
    text("history", old.empty() ? u.history_append : old + "\n" + u.history_append);
  }
  put_attributes(id, NC_GLOBAL, u.attributes, path);
  check(nc_enddef(id), path, "end of definitions");
  for (const Target& t : targets)
    if (t.var >= 0) check(nc_put_var_double(id, t.var, t.data->data()), path, fmt::format("write {}", t.name));
  check(nc.close(), path, "close");
}

}  // namespace aq::io
