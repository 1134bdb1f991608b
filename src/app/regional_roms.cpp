// SPDX-License-Identifier: GPL-3.0-or-later
// The ROMS grid file of a regional run: global mask and depth from roms.global_config, C-grid
// metrics on the Earth, depth clip/smoothing, netCDF and picture (see regional_roms.hpp).
#include "app/regional_roms.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "app/global_run.hpp"
#include "config/load.hpp"
#include "core/error.hpp"
#include "core/lattice.hpp"
#include "core/rotation.hpp"
#include "curvilinear/common/cgrid.hpp"
#include "curvilinear/common/roms_depth.hpp"
#include "grid_files/mom6_grid.hpp"
#include "grid_files/roms_grid.hpp"
#include "io/depth.hpp"
#include "mask/cell_elevation.hpp"
#include "mask/regional_mask.hpp"
#include "mask/wet_area.hpp"
#include "pictures/roms_grid_png.hpp"
#include "raster/bathymetry.hpp"

#ifndef AQ_VERSION
#define AQ_VERSION "dev"
#endif

namespace aq::app {

namespace {

// Thresholds of the metric warnings: ROMS's metrics should vary smoothly and its cells be nearly
// square (WikiROMS "Grid generation"); beyond these the grid is legal but a model will suffer.
constexpr double kIsotropyWarn = 0.5;  // max |pm/pn − 1| over interior ρ points
constexpr double kAreaJumpWarn = 2.0;  // largest area ratio of two neighbouring interior ρ cells

// Warns about extreme metrics (curvilinear::cgrid_stats, max_area_jump) with their values and
// places; returns them for the report.
MetricWarnings warn_extreme_metrics(const curvilinear::CGrid& cg, const curvilinear::CGridStats& st,
                                    const std::string& name, const Logger& log) {
  MetricWarnings w;
  const curvilinear::AreaJump jump = curvilinear::max_area_jump(cg);
  w.area_jump = jump.ratio;
  w.area_jump_i = jump.i;
  w.area_jump_j = jump.j;
  if (st.isotropy_max_interior > kIsotropyWarn) {
    const std::size_t k = cg.rho.at(st.isotropy_worst_i, st.isotropy_worst_j);
    log.warn(
        "{}: extreme cell shapes: max |pm/pn - 1| = {:.3g} inside the grid ({:.3g} with the boundary; worst at "
        "rho ({}, {}), {:.4f}°E {:.4f}°N; > {} makes cells far from square: a model's time step and mixing suffer)",
        name, st.isotropy_max_interior, st.isotropy_max, st.isotropy_worst_i, st.isotropy_worst_j, cg.rho.lon_deg[k],
        cg.rho.lat_deg[k], kIsotropyWarn);
    w.isotropy = true;
  }
  if (w.area_jump > kAreaJumpWarn) {
    const std::size_t k = cg.rho.at(w.area_jump_i, w.area_jump_j);
    log.warn(
        "{}: cell-area jump: neighbouring rho cells differ in area by a factor {:.3g} at rho ({}, {}), {:.4f}°E "
        "{:.4f}°N (> {}: the metrics should vary smoothly)",
        name, w.area_jump, w.area_jump_i, w.area_jump_j, cg.rho.lon_deg[k], cg.rho.lat_deg[k], kAreaJumpWarn);
  }
  return w;
}

// ρ cells smaller than the raster spacing under them in both directions
// (curvilinear::finer_than_raster): warns with the count and the finest place.
Json warn_finer_than_raster(const curvilinear::CGrid& cg, double dlon, double dlat, double radius_m,
                            const std::string& name, const std::string& raster, const Logger& log) {
  const curvilinear::FinerThanRaster f = curvilinear::finer_than_raster(cg, dlon, dlat, radius_m);
  if (f.finer > 0)
    log.warn(
        "{}: {} of {} interior rho cells ({:.3g} %) are finer than the raster under them ({} at {:.4g}' x {:.4g}'; "
        "up to {:.3g} cells per raster spacing, at {:.4f}°E {:.4f}°N): their depths are interpolated, not "
        "measured. A finer roms.global_config input.path, or fewer cells (regional.ny), match grid and data",
        name, f.finer, f.interior,
        100.0 * static_cast<double>(f.finer) / static_cast<double>(std::max<std::int64_t>(f.interior, 1)), raster,
        dlon * 60.0, dlat * 60.0, f.worst, cg.rho.lon_deg[f.worst_k], cg.rho.lat_deg[f.worst_k]);
  return Json{{"rho_cells_finer_than_raster", f.finer},
              {"interior_rho_cells", f.interior},
              {"max_cells_per_raster_spacing", f.worst}};
}

// The figures of one ROMS grid that its file's attributes and its report section show.
struct RomsFigures {
  mask::CellElevations cells;  ///< the elevation of each ρ cell (roms.depth_statistic)
  mask::RomsMasks masks;
  std::vector<double> hraw;  ///< depth below the datum of each ρ cell, before clipping and smoothing
  curvilinear::DepthResult depth;
  int blend = 0;  ///< nesting.blend_cells of a refinement grid, else 0
  double blend_change_m = 0.0;
  Json nested_report;  ///< the "nested" section of a refinement grid
  std::string nested_line;
  curvilinear::CGridStats stats;
  MetricWarnings warnings;
  Json finer;  ///< warn_finer_than_raster's figures
};

// The ROMS file's global attributes: the projection, how metrics, depth and masks were made, and
// for a refinement grid its parent (as ROMS's coarse2fine.m marks one).
io::AttributeMap roms_attributes(const config::RegionalConfig& c, const std::string& config_source,
                                 const curvilinear::RegionalResult& result, const curvilinear::CGrid& cg,
                                 const RegionalGlobal& global, const RomsFigures& f, const Json& config_echo) {
  const auto& p = c.params;
  const auto distances = cg.options.distances;
  const config::GlobalConfig& g = global.loaded.options;
  const Lattice& lattice = global.run.setup.lattice;
  io::AttributeMap a = {
      {"grid_name", c.name},
      {"regional_config", config_source},
      {"aquatoria_config", config_echo.dump()},
      {"proj", std::string(name_of(p.projection.kind))},
      {"rlat", p.projection.rlat_deg},
      {"rlon", p.projection.rlon_deg},
      {"rota", p.projection.rota_deg},
      {"uscale", p.projection.uscale},
      {"lat1", std::isnan(p.projection.lat1_deg) ? p.projection.rlat_deg : p.projection.lat1_deg},
      {"lat2", std::isnan(p.projection.lat2_deg) ? p.projection.rlat_deg : p.projection.lat2_deg},
      {"radius", p.projection.radius_m},
      {"spline_type", static_cast<std::int64_t>(p.spline_type)},
      {"izogrid_nx", static_cast<std::int64_t>(result.nx)},
      {"izogrid_ny", static_cast<std::int64_t>(result.ny)},
      {"aspect_ratio", result.aspect_ratio},
      {"index_convention",
       std::string("rho(i,j) = supergrid(2i,2j) including the contour, u(k,j) = (2k+1,2j), v(i,l) = (2i,2l+1), "
                   "psi(k,l) = (2k+1,2l+1); 0-based file indices")},
      {"metrics",
       fmt::format("1/pm, 1/pn: sums of the two supergrid half steps through rho ({}); on the contour the outer "
                   "half step is extrapolated linearly, 1/pm = max(3 h1 - h2, 1.5 h1); angle: direction of the xi "
                   "line from Earth-centred positions (centred, one-sided second order on the contour), "
                   "counter-clockwise from east; dndx, dmde: centred differences, one-sided on the boundary",
                   distances == curvilinear::DistanceModel::kWgs84 ? "WGS84 geodesics, GeographicLib"
                                                                   : "great circles on the sphere")},
      {"distances", std::string(std::string(name_of(distances)))},
      {"earth_radius_m", c.roms.earth_radius_m},
      {"earth_rotation_rate_per_s", curvilinear::kEarthOmega},
      {"xy_metres_per_plane_unit", cg.xy_metres_per_unit},
      {"global_config", global.loaded.source},
      {"bathymetry", g.input.path},
      {"bathymetry_sampling", std::string(name_of(g.input.interpolation))},
      {"depth_statistic", std::string(name_of(f.cells.used))},
      {"depth_statistic_rule",
       std::string("hraw and the mask's elevation at rho: point = the bathymetry sampled at rho; mean/median/min = "
                   "over the raster sample points inside the rho cell (the psi quadrilateral, extrapolated on the "
                   "contour), cells without one keep the point sample")},
      {"mask_rule",
       std::string("wet iff the rho point's lattice pixel is in the global K-fill set and its elevation <= -h; "
                   "boundary rows/columns copy the nearest interior point; mask_u, mask_v, mask_psi are products "
                   "of the adjacent mask_rho")},
      {"mask_min_depth_m", g.mask.min_depth_m},
      {"mask_cursor", static_cast<std::int64_t>(g.mask.cursor)},
      {"lattice_kind", std::string(lattice.kind_name())},
      {"lattice_pixel_deg", lattice.pixel_deg()},
      {"lattice_lon0_deg", lattice.lon0_deg},
      {"rotation", g.rotation.enabled
                       ? fmt::format("pole at lon {} lat {}", g.rotation.pole_lon_deg, g.rotation.pole_lat_deg)
                       : std::string("none")},
      {"hmin_m", c.roms.hmin_m},
      {"rmax", c.roms.rmax},
      {"smoothing",
       std::string("r-factor |h1-h2|/(h1+h2) <= rmax on faces between wet rho points, by raising the shallower "
                   "depth only (minimal solution, Sikiric et al. 2009 positive rx0); land keeps max(hraw, hmin)")},
      {"rx0_before", f.depth.rx0_before},
      {"rx0_after", f.depth.rx0_after},
      {"rx1_before", f.depth.rx1_before},
      {"rx1_after", f.depth.rx1_after},
      {"rx1_vertical_grid", rx1_grid_text()},
  };
  if (c.nesting.refinement()) {  // as ROMS's coarse2fine.m marks a refinement grid
    const auto& b = c.nesting.parent_box;
    a.emplace("parent_grid", c.nesting.parent);
    a.emplace("parent_Imin", static_cast<std::int64_t>(b[0]));
    a.emplace("parent_Imax", static_cast<std::int64_t>(b[1]));
    a.emplace("parent_Jmin", static_cast<std::int64_t>(b[2]));
    a.emplace("parent_Jmax", static_cast<std::int64_t>(b[3]));
    a.emplace("refine_factor", static_cast<std::int64_t>(c.nesting.refine_factor));
    a.emplace("parent_grid_nested", nested_parent_file(c));
    a.emplace(
        "parent_depth_blend",
        fmt::format("h = w h_parent + (1-w) hraw over the {} rho rows next to the boundary, w = 1 - d/{} at d rows "
                    "from the outer ring (h_parent: the h of {}, bilinear in the parent's index space as in the "
                    "contact file), before clipping and smoothing",
                    f.blend, f.blend, nested_parent_file(c)));
    a.emplace("parent_consistency",
              std::string("the parent's h over this grid (parent_grid_nested) is this h averaged over each parent cell "
                          "(weights 1/(pm pn) of the wet points); where the parent's r-factor bound needed more, the "
                          "cell's points were deepened by the difference (aquatoria handoff/nested_bathymetry.hpp)"));
    a["mask_rule"] =
        std::get<std::string>(a["mask_rule"]) +
        "; refinement grid: the outer rho ring takes the mask of the parent rho cell holding the point (the contact "
        "file's, which ROMS copies there), and the parent's cells over this grid take the mask of this grid's rho "
        "point at their centre";
  }
  return a;
}

// The same grid for MOM6 (grid_files/mom6_grid.hpp): supergrid, topography, mask; the report's
// "mom6" section.
void write_mom6_companion(const config::RegionalConfig& c, const std::string& config_source,
                          const curvilinear::RegionalResult& result, const RomsFigures& f, const std::string& nc,
                          OutputSet& out, Json& outputs, Report& report, const Logger& log) {
  const std::vector<double> mask_d(f.masks.rho.begin(), f.masks.rho.end());
  const io::Mom6Grid m6 = io::mom6_grid(result.grid, *result.projection, f.depth.h, mask_d, c.roms.earth_radius_m);
  const std::string hg = c.name + "_ocean_hgrid.nc", tp = c.name + "_ocean_topog.nc", mk = c.name + "_ocean_mask.nc";
  io::write_mom6_files(m6, out.temp_path(hg), out.temp_path(tp), out.temp_path(mk),
                       fmt::format("aquatoria regional {} (the grid of {})", config_source, nc));
  for (const auto& file : {hg, tp, mk})
    outputs.push_back(Json{{"file", file}, {kChecksumKey, file_checksum(out.pending_path(file))}});
  double m6_area = 0.0;
  for (const double a : m6.area) m6_area += a;
  report["mom6"] = Json{{"hgrid", hg},
                        {"topog", tp},
                        {"mask", mk},
                        {"nx", m6.nx},
                        {"ny", m6.ny},
                        {"supergrid", {m6.nxp(), m6.nyp()}},
                        {"area_m2", m6_area},
                        {"cells",
                         "MOM6 cell (i, j) = ROMS rho (i+1, j+1); supergrid = the izogrid supergrid without its "
                         "outer ring"}};
  log.info("mom6: {}, {}, {} ({} x {} cells, supergrid {} x {}, grid area {:.6g} km²)", hg, tp, mk, m6.nx, m6.ny,
           m6.nxp(), m6.nyp(), m6_area * 1e-6);
}

// The report's "roms" section.
Json roms_report_json(const config::RegionalConfig& c, const curvilinear::CGrid& cg, const RegionalGlobal& global,
                      const RomsFigures& f, const std::string& nc) {
  const int ni = cg.L + 1, nj = cg.M + 1;
  const auto distances = cg.options.distances;
  const config::GlobalConfig& g = global.loaded.options;
  const Lattice& lattice = global.run.setup.lattice;
  const mask::WetArea& area = global.run.area;
  const auto& ms = f.masks.stats;
  const auto& st = f.stats;
  const auto& mw = f.warnings;
  const auto& depth = f.depth;
  double hmax = 0.0;
  for (std::size_t k = 0; k < cg.rho.size(); ++k)
    if (f.masks.rho[k] != 0) hmax = std::max(hmax, depth.h[k]);
  Json j = Json{{"file", nc},
                {"xi_rho", ni},
                {"eta_rho", nj},
                {"global_config", global.loaded.source},
                {"bathymetry", g.input.path},
                {"lattice", Json{{"nx", lattice.nx}, {"ny", lattice.ny}, {"pixel_deg", lattice.pixel_deg()}}},
                {"global_filled_pixels", area.filled_pixels},
                {"mask", Json{{"rho_points", ms.rho_points},
                              {"in_global_ocean", ms.in_filled},
                              {"deeper_than_h", ms.deep_enough},
                              {"lake_points", ms.lake_points},
                              {"coastal_pixel_points", ms.coastal_points},
                              {"shallow_in_global_ocean", ms.shallow_in_filled},
                              {"boundary_changed", ms.boundary_changed},
                              {"wet_rho", ms.wet_rho},
                              {"wet_rho_interior", ms.wet_rho_interior},
                              {"wet_u", ms.wet_u},
                              {"wet_v", ms.wet_v},
                              {"wet_psi", ms.wet_psi}}},
                {"metrics", Json{{"distances", std::string(name_of(distances))},
                                 {"earth_radius_m", c.roms.earth_radius_m},
                                 {"pm_min", st.pm_min},
                                 {"pm_max", st.pm_max},
                                 {"pn_min", st.pn_min},
                                 {"pn_max", st.pn_max},
                                 {"dx_min_m", st.dx_min_m},
                                 {"dx_max_m", st.dx_max_m},
                                 {"isotropy_max_abs_pm_over_pn_minus_1", st.isotropy_max},
                                 {"isotropy_worst_rho", {st.isotropy_worst_i, st.isotropy_worst_j}},
                                 {"isotropy_max_interior", st.isotropy_max_interior},
                                 {"area_jump_max", mw.area_jump},
                                 {"area_jump_rho", {mw.area_jump_i, mw.area_jump_j}},
                                 {"warn_isotropy_above", kIsotropyWarn},
                                 {"warn_area_jump_above", kAreaJumpWarn},
                                 {"finer_than_raster", f.finer},
                                 {"angle_min_rad", st.angle_min},
                                 {"angle_max_rad", st.angle_max},
                                 {"xl_m", cg.xl_m},
                                 {"el_m", cg.el_m}}},
                {"depth", Json{{"statistic", std::string(name_of(f.cells.used))},
                               {"statistic_requested", std::string(name_of(c.roms.depth_statistic))},
                               {"median_raster_points_per_cell", f.cells.median_points_per_cell},
                               {"cells_with_point_sample", f.cells.point_cells},
                               {"hmin_m", c.roms.hmin_m},
                               {"rmax", c.roms.rmax},
                               {"clipped", depth.clipped},
                               {"clipped_wet", depth.clipped_wet},
                               {"rx0_before", depth.rx0_before},
                               {"rx0_after", depth.rx0_after},
                               {"rx1_before", depth.rx1_before},
                               {"rx1_after", depth.rx1_after},
                               {"rx1_vertical_grid", rx1_grid_text()},
                               {"parent_blend_cells", f.blend},
                               {"parent_blend_max_change_m", f.blend_change_m},
                               {"smoothed_points", depth.smoothed},
                               {"max_deepening_m", depth.max_deepening_m},
                               {"volume_added_rel", depth.volume_added_rel},
                               {"sweeps", depth.sweeps},
                               {"h_max_wet_m", hmax}}}};
  j["lattice"]["kind"] = lattice.kind_name();
  return j;
}

// Elevation of each ρ cell (roms.depth_statistic: the global run's sampling at ρ, or a statistic
// of the raster points in the cell); the global ocean; the masks (land where that elevation is
// above −h, so the mask follows the same rule as the depth). InputError when no interior ρ point
// is in the global ocean.
void sample_cells(const config::RegionalConfig& c, const std::string& config_source, const curvilinear::CGrid& cg,
                  const RegionalGlobal& global, RomsFigures& f, const Logger& log) {
  const config::GlobalConfig& g = global.loaded.options;
  const Lattice& lattice = global.run.setup.lattice;
  const PoleRotation& rot = global.run.setup.rotation;
  const raster::Bathymetry& bathy = *global.run.bathy;
  const int ni = cg.L + 1, nj = cg.M + 1;
  const std::size_t nr = cg.rho.size();
  const std::vector<double> point_elevation =
      mask::sample_elevations(bathy, cg.rho.lon_deg.data(), cg.rho.lat_deg.data(), nr);
  std::vector<double> corner_lon, corner_lat;
  curvilinear::rho_cell_corners(cg, corner_lon, corner_lat);
  f.cells = mask::cell_elevations(bathy, corner_lon.data(), corner_lat.data(), ni, nj, point_elevation.data(),
                                  c.roms.depth_statistic);
  const mask::CellElevations& cells = f.cells;
  const std::vector<double>& elevation = cells.elevation_m;
  log.info("roms: depth statistic {} ({} of roms.depth_statistic = \"{}\"; median {} raster points per ρ cell{})",
           cells.used,
           cells.used == mask::CellStatistic::kPoint ? "interpolated at ρ," : "over the raster points in each ρ cell,",
           c.roms.depth_statistic, cells.median_points_per_cell,
           cells.point_cells > 0 ? fmt::format(", {} cells without one keep the point sample", cells.point_cells) : "");
  const mask::WetArea& area = global.run.area;
  f.masks = mask::build_roms_masks(area.filled, lattice, rot, cg.rho.lon_deg.data(), cg.rho.lat_deg.data(),
                                   elevation.data(), g.mask.min_depth_m, ni, nj, &area.wet);
  const auto& ms = f.masks.stats;
  if (ms.wet_rho_interior == 0)
    throw InputError(fmt::format(
        "{}: the regional grid has no water of the global ocean: none of its {} interior ρ points lies in the K-fill "
        "of roms.global_config = \"{}\" ({}; K = {}, h = {} m, {} seed{}, {:.4g}' pixels), although {} ρ points are "
        "deeper than h (a lake, or a sea the fill does not reach at this lattice, e.g. the Black Sea behind the "
        "Bosphorus): add a seed in the region to mask.seeds of that global config, use a finer lattice or a smaller "
        "cursor, or set roms.enabled = false",
        config_source, (ni - 2) * (nj - 2), c.roms.global_config, global.loaded.source, g.mask.cursor,
        g.mask.min_depth_m, g.mask.seeds.size(), g.mask.seeds.size() == 1 ? "" : "s", lattice.pixel_deg() * 60.0,
        ms.deep_enough));
}

}  // namespace

std::string rx1_grid_text() {
  const curvilinear::VerticalGrid v;
  return fmt::format(
      "Vtransform 2, Vstretching 4, N = {}, theta_s = {}, theta_b = {}, hc = {} m (a reference ROMS "
      "vertical grid; rx1 depends on the model's own)",
      v.n, v.theta_s, v.theta_b, v.hc_m);
}

curvilinear::CGridOptions roms_cgrid_options(const config::RegionalConfig& c) {
  curvilinear::CGridOptions co;
  co.earth_radius_m = c.roms.earth_radius_m;
  co.distances = c.roms.distances;
  return co;
}

RegionalGlobal run_regional_global(const config::RegionalConfig& c, const Logger& log, Report* report) {
  const auto named = [&](const ConfigError& e) {
    return ConfigError(fmt::format("roms.global_config = \"{}\": {}", c.roms.global_config, e.what()));
  };
  RegionalGlobal r;
  try {
    // A floodplain or several rasters are refused there, at their positions (config::GlobalUse).
    r.loaded = config::load_global(c.roms.global_config.empty() ? std::optional<std::string>() : c.roms.global_config,
                                   {}, config::GlobalUse::kRomsGlobal);
  } catch (const ConfigError& e) {
    throw named(e);
  }
  config::GlobalConfig& g = r.loaded.options;
  if (g.mesh.elements == config::ElementKinds::kSquares)
    g.mesh.elements = config::ElementKinds::kTriangles;  // the nesting weights live on triangles
  GlobalSetup setup;
  try {
    setup = prepare_global_run(g, {.allow_window = false});  // the nesting locates grid points on the global lattice
  } catch (const ConfigError& e) {
    throw named(e);
  }
  // Its stage lines and warnings belong to `aquatoria mesh`; here one summary line.
  StageScope stage("global run", report, log);
  Logger quiet = log;
  quiet.set_level(LogLevel::kError);
  r.run = run_global_pipeline(g, setup, quiet, nullptr, false, true);
  if (!r.run.area_file_differs.empty()) log.warn("global run: {}; ran the global fill again", r.run.area_file_differs);
  stage.done(
      fmt::format("{} ({} lattice, Δ0 = {}°, L = {}, {:.4g}' pixels, K = {}, h = {} m): {} filled pixels{}, {} "
                  "triangles (the ocean, depth and mesh this grid shares)",
                  r.loaded.source, setup.lattice.kind_name(), g.quadtree.step_deg, g.quadtree.levels,
                  setup.lattice.pixel_deg() * 60.0, g.mask.cursor, g.mask.min_depth_m, r.run.area.filled_pixels,
                  r.run.area_file.empty() ? std::string() : " (mask reused from " + r.run.area_file + ")",
                  r.run.mesh.triangle_count()));
  return r;
}

void write_regional_roms(const config::RegionalConfig& c, const std::string& config_source,
                         const curvilinear::RegionalResult& result, const curvilinear::CGrid& cg,
                         const RegionalGlobal& global, OutputSet& out, Json& outputs, Report& report, const Logger& log,
                         RefinedGrid* refined) {
  if (result.completed != curvilinear::Stage::kGrid || !result.projection)
    throw InternalError("roms: the regional run did not complete the grid stage");
  StageScope rs("roms", &report, log);

  // The global run whose ocean the grid shares.
  const config::GlobalConfig& g = global.loaded.options;
  if (!c.input.path.empty() && c.input.path != g.input.path)
    log.warn("roms: depth and mask come from the global run's bathymetry {} ({}), not from [input] path {}",
             g.input.path, global.loaded.source, c.input.path);
  if (c.params.projection.radius_m != c.roms.earth_radius_m)
    log.warn("roms: regional.radius = {} m but roms.earth_radius_m = {} m; the ROMS file uses roms.earth_radius_m",
             c.params.projection.radius_m, c.roms.earth_radius_m);
  const raster::Bathymetry& bathy = *global.run.bathy;
  if (bathy.source_count() > 1)  // refused when roms.global_config was loaded (config::GlobalUse::kRomsGlobal)
    throw InternalError(
        fmt::format("roms: the global run {} reads {} rasters", global.loaded.source, bathy.source_count()));

  const int ni = cg.L + 1, nj = cg.M + 1;
  const std::size_t nr = cg.rho.size();
  RomsFigures f;

  sample_cells(c, config_source, cg, global, f, log);
  const std::vector<double>& elevation = f.cells.elevation_m;
  const auto& ms = f.masks.stats;

  // The depth: clipped and smoothed (curvilinear/common/roms_depth.hpp), or nested in the parent.
  f.hraw.resize(nr);
  for (std::size_t k = 0; k < nr; ++k) f.hraw[k] = io::depth_below_datum_m(elevation[k]);
  curvilinear::DepthOptions dopt;
  dopt.hmin_m = c.roms.hmin_m;
  dopt.rmax = c.roms.rmax;
  f.blend = refined != nullptr ? c.nesting.blend_cells : 0;
  if (refined == nullptr) {
    f.depth = curvilinear::roms_depth(f.hraw, f.masks.rho, ni, nj, dopt);
  } else {
    // A refinement grid and its parent: consistent masks, then consistent depths.
    NestedDepths nd = nest_in_parent(c, cg, f.hraw, dopt, f.masks, *refined, log);
    f.depth = std::move(nd.depth);
    f.blend_change_m = nd.blend_change_m;
    f.nested_report = std::move(nd.report);
    f.nested_line = std::move(nd.line);
  }
  const curvilinear::DepthResult& depth = f.depth;
  f.stats = curvilinear::cgrid_stats(cg);
  f.finer = warn_finer_than_raster(cg, bathy.info().dlon, bathy.info().dlat, c.roms.earth_radius_m, c.name,
                                   g.input.path, log);
  f.warnings = warn_extreme_metrics(cg, f.stats, c.name, log);
  if (c.roms.rmax == 0.0 && depth.rx0_after > 0.2)
    log.warn(
        "{}: roms.rmax = 0 leaves rx0 = {:.3g} (rx1 = {:.3g}); ROMS needs rx0 <= 0.2 or so (roms.rmax = 0.2, the "
        "default, smooths to it)",
        c.name, depth.rx0_after, depth.rx1_after);

  // The file, its MOM6 twin and the picture (with the coastline of the global bathymetry).
  io::RomsGridData data;
  data.grid = &cg;
  data.h = depth.h;
  data.hraw = f.hraw;
  data.mask_rho = f.masks.rho;
  data.mask_u = f.masks.u;
  data.mask_v = f.masks.v;
  data.mask_psi = f.masks.psi;
  data.title = fmt::format("aquatoria regional grid {} (izogrid method, Shchepetkin 2020)", c.name);
  data.history = fmt::format("aquatoria regional {}", config_source);
  data.source = fmt::format("aquatoria {}", AQ_VERSION);
  data.attributes = roms_attributes(c, config_source, result, cg, global, f, report["config"]);
  const std::string nc = c.name + "_grd.nc";
  io::write_roms_grid(out.temp_path(nc), data);
  outputs.push_back(Json{{"file", nc}, {kChecksumKey, file_checksum(out.pending_path(nc))}});
  write_mom6_companion(c, config_source, result, f, nc, out, outputs, report, log);
  io::RomsPictureOptions po;
  po.title = fmt::format("{}: ROMS grid {} x {} rho points, {} wet; h >= {} m{}", c.name, ni, nj, ms.wet_rho,
                         c.roms.hmin_m, c.roms.rmax > 0.0 ? fmt::format(", r <= {}", c.roms.rmax) : std::string());
  po.coastlines =
      io::grid_coastlines(bathy, c.coast_level_m, cg.rho.lon_deg.data(), cg.rho.lat_deg.data(), nr, *result.projection);
  const std::string png = c.name + "_roms.png";
  io::write_roms_png(out.temp_path(png), result.grid, f.masks.rho, depth.h, po);
  outputs.push_back(Json{{"file", png}, {kChecksumKey, file_checksum(out.pending_path(png))}});

  report["roms"] = roms_report_json(c, cg, global, f, nc);
  if (refined != nullptr) report["nested"] = f.nested_report;
  const auto& st = f.stats;
  rs.done(fmt::format(
      "{} ({} x {} ρ points, {} wet; land although deeper than h: {} in unconnected water, {} in "
      "coastal pixels); dx {:.4g}..{:.4g} km, max |pm/pn-1| "
      "{:.3g} (interior {:.3g}), area jump {:.3g}; rx0 {:.3g} -> {:.3g}, rx1 {:.3g} -> {:.3g} (roms.rmax = {:g}, {} "
      "points deepened); {}{}",
      nc, ni, nj, ms.wet_rho, ms.lake_points, ms.coastal_points, st.dx_min_m / 1000.0, st.dx_max_m / 1000.0,
      st.isotropy_max, st.isotropy_max_interior, f.warnings.area_jump, depth.rx0_before, depth.rx0_after,
      depth.rx1_before, depth.rx1_after, c.roms.rmax, depth.smoothed, png, f.nested_line));
}

}  // namespace aq::app
