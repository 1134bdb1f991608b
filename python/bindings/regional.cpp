// SPDX-License-Identifier: GPL-3.0-or-later
// aquatoria.regional in the compiled module: a regional orthogonal grid as `aquatoria regional`
// builds it (contour -> conformal map -> Laplace fill, or a regional.method generator), up to the
// complete grid, with its C-grid (the ROMS ρ/u/v/ψ points and metrics, app/regional_roms.hpp's
// roms_cgrid_options) and its checks (curvilinear/grid_checks.hpp). The ROMS file's depth and
// masks need a global run; they stay with the command line (aquatoria regional).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <optional>
#include <string>
#include <vector>

#include "app/global_run.hpp"
#include "app/regional_roms.hpp"
#include "config/regional.hpp"
#include "core/error.hpp"
#include "curvilinear/common/cgrid.hpp"
#include "curvilinear/common/grid_checks.hpp"
#include "curvilinear/regional.hpp"
#include "python_common.hpp"
#include "raster/bathymetry.hpp"

namespace py = pybind11;

namespace aq::python {

/// One regional grid.
class RegionalRun {
 public:
  RegionalRun(const std::string& path, const std::vector<std::string>& overrides, bool verbose, int threads)
      : lines_(std::make_shared<LogLines>()), log_(make_logger(lines_, verbose)) {
    WorkScope work(threads);
    loaded_ = config::load_regional(path, overrides);
    const config::RegionalConfig& c = loaded_.options;
    report_["command"] = "regional";
    report_["interface"] = "python";
    report_["config_source"] = loaded_.source;
    report_["config"] = loaded_.echo;
    if (c.nesting.refinement())
      throw ConfigError(
          fmt::format("{}: a refinement grid (nesting.refine_factor = {}) is made by `aquatoria "
                      "regional`; aquatoria.regional builds grids from a contour",
                      path, c.nesting.refine_factor));
    std::optional<raster::Bathymetry> bathy;
    curvilinear::DepthSampler depth;
    if (c.params.weight_depth > 0.0 && curvilinear::uses_weight(c.params.method) && !c.input.path.empty()) {
      bathy.emplace(raster::Bathymetry::open(app::raster_options(c.input, 0), log_));
      depth = [&bathy](double lon, double lat) { return -bathy->sample(lon, lat); };
    }
    result_ = curvilinear::run_regional(c.params, curvilinear::Stage::kGrid, log_, &report_, bathy ? &depth : nullptr);
    if (result_.completed != curvilinear::Stage::kGrid || !result_.projection)
      throw NumericalError(fmt::format("{}: the grid was not completed (stopped after {})", path,
                                       std::string(name_of(result_.completed))));
    cgrid_ = curvilinear::build_cgrid(result_.grid, *result_.projection, app::roms_cgrid_options(c));
  }

  py::dict check(int threads) const {
    curvilinear::GridQuality q;
    {
      WorkScope work(threads);
      curvilinear::CheckOptions co;
      co.dxi_over_deta = result_.dxi_over_deta;
      q = curvilinear::check_grid(result_.grid, co);
    }
    py::dict out;
    for (const auto* f : q.fields()) {
      py::dict d;
      d["long_name"] = f->long_name;
      d["worst"] = f->worst;
      d["average"] = f->average;
      d["rms"] = f->rms;
      d["worst_cell"] = py::make_tuple(f->worst_i, f->worst_j);
      d["is_error"] = f->is_error;
      out[py::str(f->name)] = d;
    }
    out["non_convex_cells"] = q.non_convex_cells;
    out["isotropy_ratio_min"] = q.isotropy_ratio_min;
    out["isotropy_ratio_max"] = q.isotropy_ratio_max;
    out["non_finite"] = q.non_finite;
    out["passed"] = q.non_finite.empty() && q.non_convex_cells == 0;
    return out;
  }

  const curvilinear::CGrid& cgrid() const { return cgrid_; }
  const curvilinear::RegionalResult& result() const { return result_; }
  py::object report() const { return json_to_python(report_.root()); }
  std::vector<std::pair<int, std::string>> take_log() { return lines_->take(); }

 private:
  std::shared_ptr<LogLines> lines_;
  Logger log_;
  config::Loaded<config::RegionalConfig> loaded_;
  Report report_;
  curvilinear::RegionalResult result_;
  curvilinear::CGrid cgrid_;
};

void bind_regional(py::module_& m) {
  auto points = [](const char* which) {
    return [which](py::object self) {
      const auto& g = self.cast<RegionalRun&>().cgrid();
      const std::string w(which);
      const auto& p = w.rfind("rho", 0) == 0 ? g.rho : w.rfind("u", 0) == 0 ? g.u : w.rfind("v", 0) == 0 ? g.v : g.psi;
      const bool lon = w.find("lon") != std::string::npos;
      const auto& v = lon ? p.lon_deg : p.lat_deg;
      return view(v.data(), {p.nj, p.ni}, self);
    };
  };
  auto rho_field = [](std::vector<double> curvilinear::CGrid::*field) {
    return [field](py::object self) {
      const auto& g = self.cast<RegionalRun&>().cgrid();
      return view((g.*field).data(), {g.rho.nj, g.rho.ni}, self);
    };
  };
  py::class_<RegionalRun>(m, "RegionalRun")
      .def(py::init<const std::string&, const std::vector<std::string>&, bool, int>(), py::arg("config"),
           py::arg("overrides"), py::arg("verbose"), py::arg("threads"))
      .def_property_readonly("lon_rho", points("rho_lon"))
      .def_property_readonly("lat_rho", points("rho_lat"))
      .def_property_readonly("lon_u", points("u_lon"))
      .def_property_readonly("lat_u", points("u_lat"))
      .def_property_readonly("lon_v", points("v_lon"))
      .def_property_readonly("lat_v", points("v_lat"))
      .def_property_readonly("lon_psi", points("psi_lon"))
      .def_property_readonly("lat_psi", points("psi_lat"))
      .def_property_readonly("pm", rho_field(&curvilinear::CGrid::pm))
      .def_property_readonly("pn", rho_field(&curvilinear::CGrid::pn))
      .def_property_readonly("dndx", rho_field(&curvilinear::CGrid::dndx))
      .def_property_readonly("dmde", rho_field(&curvilinear::CGrid::dmde))
      .def_property_readonly("angle", rho_field(&curvilinear::CGrid::angle))
      .def_property_readonly("f", rho_field(&curvilinear::CGrid::f))
      .def_property_readonly("x_plane",
                             [](py::object self) {
                               const auto& g = self.cast<RegionalRun&>().result().grid;
                               return view(g.x.data(), {g.ny_pts, g.nx_pts}, self);
                             })
      .def_property_readonly("y_plane",
                             [](py::object self) {
                               const auto& g = self.cast<RegionalRun&>().result().grid;
                               return view(g.y.data(), {g.ny_pts, g.nx_pts}, self);
                             })
      .def_property_readonly("xl_m", [](const RegionalRun& r) { return r.cgrid().xl_m; })
      .def_property_readonly("el_m", [](const RegionalRun& r) { return r.cgrid().el_m; })
      .def("check", &RegionalRun::check, py::arg("threads"))
      .def("report", &RegionalRun::report)
      .def("take_log", &RegionalRun::take_log);
}

}  // namespace aq::python
