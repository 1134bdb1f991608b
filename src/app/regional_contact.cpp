// The contact-point step of `aquatoria regional` (see regional_contact.hpp).
#include "app/regional_contact.hpp"

#include <fmt/format.h>

#include "core/error.hpp"
#include "curvilinear/cgrid.hpp"
#include "handoff/contact_points.hpp"
#include "io/contact_netcdf.hpp"

namespace aq::app {

bool wants_regional_contact(const config::RegionalConfig& c, const curvilinear::RegionalResult& result) {
  return result.completed == curvilinear::Stage::kGrid && result.projection && !c.nesting.parent.empty();
}

void write_regional_contact(const config::RegionalConfig& c, const std::string& config_source,
                            const curvilinear::RegionalResult& result, OutputSet& out, Json& outputs, Report& report,
                            const Logger& log) {
  if (!wants_regional_contact(c, result)) return;
  StageScope stage("contact", &report, log);
  const io::RomsGridFields parent = io::read_roms_grid_fields(c.nesting.parent);
  curvilinear::CGridOptions co;
  co.earth_radius_m = c.roms.earth_radius_m;
  co.distances = curvilinear::parse_distance_model(c.roms.distances, "roms.distances");
  const curvilinear::CGrid cg = curvilinear::build_cgrid(result.grid, *result.projection, co);
  handoff::ContactSummary sum;
  io::ContactFile f = handoff::contact_points(
      parent, cg, fmt::format("{}: nesting.parent = {}", config_source, c.nesting.parent), &sum);
  f.history = fmt::format("aquatoria {} regional {}", AQ_VERSION, config_source);
  f.attributes.emplace(f.attributes.begin(), "parent_grid", c.nesting.parent);
  f.attributes.emplace(f.attributes.begin() + 1, "receiver_grid_file", c.name + "_grd.nc");
  const std::string name = c.name + "_contact.nc";
  io::write_contact(out.temp_path(name), f);
  outputs.push_back(Json{{"file", name}, {"checksum_fnv1a64", file_checksum(out.pending_path(name))}});
  report["contact"] = Json{{"parent_grid", c.nesting.parent},
                           {"parent_rho", {parent.L + 1, parent.M + 1}},
                           {"points", sum.points},
                           {"rho_points", sum.rho},
                           {"u_points", sum.u},
                           {"v_points", sum.v},
                           {"wet_points", sum.wet_points},
                           {"refine_factor", f.refine_factor[1]},
                           {"refinement_ratio_median", sum.ratio_median},
                           {"refinement_ratio_min", sum.ratio_min},
                           {"refinement_ratio_max", sum.ratio_max},
                           {"qweights", "biquadratic Lagrange, 3 x 3 donor points"}};
  stage.done(
      fmt::format("{}: {} points ({} ρ, {} u, {} v; {} over parent water) in {}; refinement ratio {:.3g} "
                  "(median, {:.3g}..{:.3g}), refine_factor {}",
                  name, sum.points, sum.rho, sum.u, sum.v, sum.wet_points, c.nesting.parent, sum.ratio_median,
                  sum.ratio_min, sum.ratio_max, f.refine_factor[1]));
}

}  // namespace aq::app
