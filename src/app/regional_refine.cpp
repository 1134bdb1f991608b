// SPDX-License-Identifier: GPL-3.0-or-later
// The refinement grid of a regional run and its contact points (see regional_refine.hpp).
#include "app/regional_refine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "app/regional_roms.hpp"
#include "core/error.hpp"
#include "curvilinear/common/cgrid.hpp"
#include "grid_files/roms_grid.hpp"
#include "handoff/contact_points.hpp"
#include "handoff/nested_bathymetry.hpp"
#include "pictures/roms_grid_png.hpp"

#ifndef AQ_VERSION
#define AQ_VERSION "dev"
#endif

namespace aq::app {

namespace fs = std::filesystem;

namespace {

std::string refine_box_text(const curvilinear::RefineBox& b) {
  return fmt::format("[{}, {}, {}, {}]", b.i_left, b.i_right, b.j_bottom, b.j_top);
}

// `base` in the parent's plane: the projection its aquatoria attributes name, else a stereographic
// plane centred on the box (any conformal plane keeps the grid orthogonal; the parent's own one
// makes the fine grid's plane coordinates the parent's).
curvilinear::RegionalParams parent_plane(const curvilinear::RegionalParams& base, const io::RomsGridFields& p,
                                         const curvilinear::RefineBox& b, double radius_m, const std::string& path,
                                         std::string& source) {
  curvilinear::RegionalParams q = base;
  if (!p.proj.empty() && std::isfinite(p.rlat) && std::isfinite(p.rlon) && std::isfinite(p.rota) &&
      std::isfinite(p.uscale)) {
    const auto kind = parse_name_any_case<curvilinear::ProjectionKind>(p.proj);
    if (!kind)
      throw InputError(
          fmt::format("{}: attribute proj: {}", path, unknown_name_message<curvilinear::ProjectionKind>(p.proj)));
    q.projection.kind = *kind;
    q.projection.rlat_deg = p.rlat;
    q.projection.rlon_deg = p.rlon;
    q.projection.rota_deg = p.rota;
    q.projection.uscale = p.uscale;
    q.projection.lat1_deg = p.lat1;
    q.projection.lat2_deg = p.lat2;
    q.projection.radius_m = std::isfinite(p.radius) ? p.radius : radius_m;
    source = fmt::format("the parent's projection ({} rlat {} rlon {} rota {})", p.proj, p.rlat, p.rlon, p.rota);
    return q;
  }
  const int k = (b.i_left + b.i_right) / 2 - 1, l = (b.j_bottom + b.j_top) / 2 - 1;  // ψ file indices
  const std::size_t c = static_cast<std::size_t>(l) * static_cast<std::size_t>(p.L) + static_cast<std::size_t>(k);
  q.projection.kind = curvilinear::ProjectionKind::kStereographic;
  q.projection.rlat_deg = p.lat_psi[c];
  q.projection.rlon_deg = p.lon_psi[c];
  q.projection.rota_deg = 0.0;
  q.projection.radius_m = radius_m;
  source = fmt::format("a stereographic plane centred at {:.4f}E {:.4f}N (the parent file names no projection)",
                       q.projection.rlon_deg, q.projection.rlat_deg);
  return q;
}

// The parent's (2L+1) × (2M+1) supergrid in the plane from its ρ, u, v and ψ points.
curvilinear::Grid2D parent_supergrid(const io::RomsGridFields& p, const curvilinear::Projection& proj,
                                     const std::string& parent_path) {
  curvilinear::Grid2D g(2 * p.L + 1, 2 * p.M + 1);
  const auto put = [&](int I, int J, double lon, double lat) {
    const curvilinear::PlanePoint q = proj.forward(lon, lat);
    if (!std::isfinite(q.x) || !std::isfinite(q.y))
      throw InputError(
          fmt::format("{}: the point {:.6f}E {:.6f}N (supergrid {}, {}) has no finite plane position in "
                      "the parent's projection",
                      parent_path, lon, lat, I, J));
    g.x[g.at(I, J)] = q.x;
    g.y[g.at(I, J)] = q.y;
  };
  const auto idx = [](int i, int j, int ni) {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i);
  };
  for (int j = 0; j <= p.M; ++j)
    for (int i = 0; i <= p.L; ++i) put(2 * i, 2 * j, p.lon_rho[idx(i, j, p.L + 1)], p.lat_rho[idx(i, j, p.L + 1)]);
  for (int j = 0; j <= p.M; ++j)
    for (int k = 0; k < p.L; ++k) put(2 * k + 1, 2 * j, p.lon_u[idx(k, j, p.L)], p.lat_u[idx(k, j, p.L)]);
  for (int l = 0; l < p.M; ++l)
    for (int i = 0; i <= p.L; ++i) put(2 * i, 2 * l + 1, p.lon_v[idx(i, l, p.L + 1)], p.lat_v[idx(i, l, p.L + 1)]);
  for (int l = 0; l < p.M; ++l)
    for (int k = 0; k < p.L; ++k) put(2 * k + 1, 2 * l + 1, p.lon_psi[idx(k, l, p.L)], p.lat_psi[idx(k, l, p.L)]);
  return g;
}

// Δξ/Δη of the parent's computational steps: from its izogrid attributes, else pn/pm (a conformal
// grid has dx/dξ = dy/dη, so Δξ/Δη = (1/pm)/(1/pn)), the median over its ρ points.
double step_ratio(const io::RomsGridFields& p) {
  if (std::isfinite(p.aspect_ratio) && p.izogrid_nx > 0 && p.izogrid_ny > 0)
    return p.aspect_ratio * p.izogrid_ny / p.izogrid_nx;
  std::vector<double> q;
  for (std::size_t k = 0; k < p.pm.size(); ++k)
    if (p.pm[k] > 0.0 && p.pn[k] > 0.0) q.push_back(p.pn[k] / p.pm[k]);
  if (q.empty()) return 1.0;
  std::nth_element(q.begin(), q.begin() + static_cast<std::ptrdiff_t>(q.size() / 2), q.end());
  return q[q.size() / 2];
}

}  // namespace

std::string nested_parent_file(const config::RegionalConfig& c) { return c.name + "_parent_grd.nc"; }

RefinedGrid build_refinement(const config::RegionalConfig& c, const std::string& config_source, const Logger& log,
                             Report* report) {
  StageScope stage("refine", report, log);
  RefinedGrid g;
  const auto& n = c.nesting;
  g.box = {n.parent_box[0], n.parent_box[1], n.parent_box[2], n.parent_box[3], n.refine_factor};
  // The parent made consistent with this grid is a new file: never the input parent itself.
  if (c.roms.enabled) {
    std::error_code ec;
    const fs::path target = fs::weakly_canonical(fs::path(c.output_dir) / nested_parent_file(c), ec);
    if (target == fs::weakly_canonical(n.parent, ec))
      throw ConfigError(
          fmt::format("{}: the updated parent grid {} would overwrite nesting.parent = {}; give this grid another "
                      "regional.name or output.dir",
                      config_source, (fs::path(c.output_dir) / nested_parent_file(c)).string(), n.parent));
  }
  g.parent = io::read_roms_grid_fields(n.parent);
  if (const std::string bad = handoff::refinement_box_problem(g.box, g.parent.L, g.parent.M); !bad.empty())
    throw ConfigError(fmt::format("{}: nesting.parent_box = {} in nesting.parent = {}: {}", config_source,
                                  refine_box_text(g.box), n.parent, bad));

  curvilinear::RegionalResult& r = g.result;
  r.params = parent_plane(c.params, g.parent, g.box, c.roms.earth_radius_m, n.parent, g.projection_source);
  const curvilinear::Projection proj(r.params.projection);
  g.parent_plane = parent_supergrid(g.parent, proj, n.parent);
  g.padded = curvilinear::refine_supergrid(g.parent_plane, g.box, kRefinePad);
  r.projection.emplace(proj);
  r.grid = curvilinear::unpad_supergrid(g.padded, kRefinePad);
  r.nx = g.box.L();
  r.ny = g.box.M();
  r.nx_initial = r.nx;
  r.dxi_over_deta = step_ratio(g.parent);
  r.aspect_ratio = r.dxi_over_deta * r.nx / r.ny;
  r.completed = curvilinear::Stage::kGrid;
  // The perimeter, counter-clockwise from the SW corner (the picture's extent).
  const std::vector<curvilinear::PlanePoint> outline = curvilinear::grid_outline(r.grid);
  r.contour_samples.insert(r.contour_samples.end(), outline.begin(), outline.end());
  r.stage_seconds[4] = stage.wall_s();
  if (report != nullptr)
    (*report)["refinement"] = Json{{"parent_grid", n.parent},
                                   {"parent_rho", {g.parent.L + 1, g.parent.M + 1}},
                                   {"parent_box", {g.box.i_left, g.box.i_right, g.box.j_bottom, g.box.j_top}},
                                   {"refine_factor", g.box.factor},
                                   {"rho", {g.box.L() + 1, g.box.M() + 1}},
                                   {"plane", g.projection_source},
                                   {"dxi_over_deta", r.dxi_over_deta}};
  stage.done(
      fmt::format("parent psi I {}..{} x J {}..{} of {} split {} x {}: {} x {} rho points (supergrid {} x {}) "
                  "in {}",
                  g.box.i_left, g.box.i_right, g.box.j_bottom, g.box.j_top, n.parent, g.box.factor, g.box.factor,
                  g.box.L() + 1, g.box.M() + 1, r.grid.nx_pts, r.grid.ny_pts, g.projection_source));
  return g;
}

// The report's section of the parent/child depth rounds (nest_in_parent).
static Json nesting_report_json(const config::RegionalConfig& c, const handoff::NestedDepthResult& nd,
                                const handoff::NestedMaskStats& nm, double parent_rmax, double parent_rx0_input) {
  return Json{{"parent_file", nested_parent_file(c)},
              {"rounds", nd.rounds},
              {"settled", nd.settled},
              {"last_round_change_m", nd.last_round_change_m},
              {"parent_rmax", parent_rmax},
              {"parent_rx0_input", parent_rx0_input},
              {"parent_rx0", nd.parent_rx0},
              {"child_rx0", nd.child_rx0},
              {"parent_points_changed", nd.parent_points_changed},
              {"parent_points_changed_outside_footprint", nd.parent_outside_changed},
              {"parent_max_change_m", nd.parent_max_change_m},
              {"parent_mean_change_wet_footprint_m", nd.parent_mean_change_wet_m},
              {"blocks_deepened", nd.blocks_raised},
              {"block_deepening_max_m", nd.block_raise_max_m},
              {"parent_mask_changed", nm.parent_rho_changed},
              {"ring_mask_changed", nm.child_ring_changed},
              {"invariant_residual_m", nd.invariant_residual_m}};
}

// The summary line of the parent/child depth rounds (nest_in_parent).
static std::string nesting_summary_line(const config::RegionalConfig& c, const handoff::NestedDepthResult& nd,
                                        const handoff::NestedMaskStats& nm) {
  return fmt::format(
      "; parent {} over the footprint: h = the block averages to {:.2g} m after {} round{} ({} parent points "
      "changed, max {:.4g} m; {} blocks deepened, max {:.4g} m), rx0 {:.3g} (parent) and {:.3g}, masks: {} "
      "parent cells and {} ring points changed",
      nested_parent_file(c), nd.invariant_residual_m, nd.rounds, nd.rounds == 1 ? "" : "s", nd.parent_points_changed,
      nd.parent_max_change_m, nd.blocks_raised, nd.block_raise_max_m, nd.parent_rx0, nd.child_rx0,
      nm.parent_rho_changed, nm.child_ring_changed);
}

NestedDepths nest_in_parent(const config::RegionalConfig& c, const curvilinear::CGrid& cg,
                            const std::vector<double>& hraw, const curvilinear::DepthOptions& dopt,
                            mask::RomsMasks& masks, RefinedGrid& g, const Logger& log) {
  const std::size_t nr = cg.rho.size();
  const int ni = cg.L + 1, nj = cg.M + 1, blend = c.nesting.blend_cells;
  const io::RomsGridFields& p0 = g.parent;
  const curvilinear::RefineBox& box = g.box;
  if (box.L() != cg.L || box.M() != cg.M)
    throw InternalError(fmt::format("roms: the refinement box gives {} x {} rho points, the grid {} x {}", box.L() + 1,
                                    box.M() + 1, ni, nj));
  const auto bytes = [](const std::vector<double>& v) {
    std::vector<std::uint8_t> b(v.size());
    for (std::size_t k = 0; k < v.size(); ++k) b[k] = v[k] > 0.5 ? 1 : 0;
    return b;
  };
  std::vector<std::uint8_t> prho = bytes(p0.mask_rho), pu = bytes(p0.mask_u), pv = bytes(p0.mask_v),
                            ppsi = bytes(p0.mask_psi);
  const std::vector<std::uint8_t> prho0 = prho;
  const handoff::NestedMaskStats nm =
      handoff::nest_masks(box, p0.L, p0.M, prho, pu, pv, ppsi, masks.rho, masks.u, masks.v, masks.psi);
  const auto wet = [](const std::vector<std::uint8_t>& m) {
    return static_cast<std::int64_t>(std::count(m.begin(), m.end(), std::uint8_t{1}));
  };
  masks.stats.wet_rho = wet(masks.rho);
  masks.stats.wet_u = wet(masks.u);
  masks.stats.wet_v = wet(masks.v);
  masks.stats.wet_psi = wet(masks.psi);

  handoff::NestedDepthInput in;
  in.box = box;
  in.parent_L = p0.L;
  in.parent_M = p0.M;
  in.parent_h = p0.h;
  in.parent_mask = prho;
  // The parent keeps the bound it already has when that is looser than roms.rmax (a parent
  // smoothed less is not smoothed anew far from the refinement).
  const double parent_rx0_input = curvilinear::max_r_factor(p0.h, prho0, p0.L + 1, p0.M + 1);
  in.parent_rmax = c.roms.rmax > 0.0 ? std::max(c.roms.rmax, parent_rx0_input) : 0.0;
  in.child_hraw = hraw;
  in.child_mask = masks.rho;
  in.child_area.resize(nr);
  for (std::size_t k = 0; k < nr; ++k) in.child_area[k] = 1.0 / (cg.pm[k] * cg.pn[k]);
  in.child_options = dopt;
  in.blend_cells = blend;
  handoff::NestedDepthResult nd = handoff::nested_depth(in);
  if (!nd.settled)
    log.warn(
        "roms: the parent/child depth rounds did not settle in {} rounds (last change {:.3g} m); the parent's h "
        "is the child's block average, the r-factors are {:.6g} (child) and {:.6g} (parent)",
        nd.rounds, nd.last_round_change_m, nd.child_rx0, nd.parent_rx0);
  NestedDepths out;
  out.depth = std::move(nd.child_depth);
  out.depth.h = nd.child_h;
  out.depth.rx0_after = nd.child_rx0;
  out.blend_change_m = nd.blend_max_change_m;

  io::RomsGridFields& pn = g.parent_nested;
  pn = p0;
  pn.h = nd.parent_h;
  const auto doubles = [](const std::vector<std::uint8_t>& b) { return std::vector<double>(b.begin(), b.end()); };
  pn.mask_rho = doubles(prho);
  pn.mask_u = doubles(pu);
  pn.mask_v = doubles(pv);
  if (!p0.mask_psi.empty()) pn.mask_psi = doubles(ppsi);
  g.receiver = handoff::ReceiverValues{nd.child_h, masks.rho, masks.u, masks.v};
  g.parent_rmax = in.parent_rmax;
  g.nested = true;
  g.nested_summary = fmt::format(
      "h over the footprint (parent rho cells I {}..{}, J {}..{}) = the refinement's h averaged per cell "
      "(weights 1/(pm pn) of its wet points); r-factor <= {:.6g} by deepening only ({} points changed, {} "
      "outside the footprint, max |change| {:.4g} m, mean change over the wet footprint {:.4g} m); mask_rho "
      "over the footprint = the refinement's at each cell's centre ({} changed), mask_u/v/psi products",
      box.i_left, box.i_right - 1, box.j_bottom, box.j_top - 1, in.parent_rmax, nd.parent_points_changed,
      nd.parent_outside_changed, nd.parent_max_change_m, nd.parent_mean_change_wet_m, nm.parent_rho_changed);
  out.report = nesting_report_json(c, nd, nm, in.parent_rmax, parent_rx0_input);
  out.line = nesting_summary_line(c, nd, nm);
  return out;
}

void write_refinement_contact(const config::RegionalConfig& c, const std::string& config_source, const RefinedGrid& g,
                              OutputSet& out, Json& outputs, Report& report, const Logger& log) {
  StageScope stage("contact", &report, log);
  const curvilinear::CGrid fine = curvilinear::build_cgrid(g.padded, *g.result.projection, roms_cgrid_options(c));
  const std::string grd = c.name + "_grd.nc";

  // The parent made consistent with this grid, as a new file beside it.
  std::string parent_file = c.nesting.parent;
  if (g.nested) {
    parent_file = nested_parent_file(c);
    io::RomsGridUpdate u;
    const io::RomsGridFields& p = g.parent_nested;
    u.h = p.h;
    u.mask_rho = p.mask_rho;
    u.mask_u = p.mask_u;
    u.mask_v = p.mask_v;
    u.mask_psi = p.mask_psi;
    const auto& b = g.box;
    u.attributes = {{"nested_child_grid", grd},
                    {"nested_child_config", config_source},
                    {"nested_source_grid", c.nesting.parent},
                    {"nested_parent_box", fmt::format("{} {} {} {}", b.i_left, b.i_right, b.j_bottom, b.j_top)},
                    {"nested_refine_factor", static_cast<std::int64_t>(b.factor)},
                    {"nested_rmax", g.parent_rmax},
                    {"nested_update", g.nested_summary}};
    u.history_append =
        fmt::format("aquatoria {} regional {}: h and masks over the refinement {} made consistent with it", AQ_VERSION,
                    config_source, grd);
    io::write_updated_roms_grid(c.nesting.parent, out.temp_path(parent_file), u);
    outputs.push_back(Json{{"file", parent_file}, {kChecksumKey, file_checksum(out.pending_path(parent_file))}});
  }
  const io::RomsGridFields& parent = g.nested ? g.parent_nested : g.parent;
  handoff::ContactSummary sum;
  io::ContactFile f =
      handoff::refinement_contact(parent, g.box, fine, kRefinePad, &sum, g.nested ? &g.receiver : nullptr);

  // The coarse ψ points inside and on the fine grid are fine ψ points: how closely, on the Earth.
  double coincide_m = 0.0;
  const int r = g.box.factor;
  for (int J = g.box.j_bottom; J <= g.box.j_top; ++J)
    for (int I = g.box.i_left; I <= g.box.i_right; ++I) {
      const std::size_t ck =
          static_cast<std::size_t>(J - 1) * static_cast<std::size_t>(g.parent.L) + static_cast<std::size_t>(I - 1);
      const std::size_t fk = fine.psi.at(r * (I - g.box.i_left) + kRefinePad, r * (J - g.box.j_bottom) + kRefinePad);
      coincide_m = std::max(
          coincide_m, curvilinear::great_circle_m(g.parent.lon_psi[ck], g.parent.lat_psi[ck], fine.psi.lon_deg[fk],
                                                  fine.psi.lat_deg[fk], c.roms.earth_radius_m));
    }

  f.grid_files = fmt::format(" \n{} \n{}", parent_file, grd);
  f.history = fmt::format("aquatoria {} regional {}", AQ_VERSION, config_source);
  f.attributes = {{"parent_grid", parent_file},
                  {"parent_grid_source", c.nesting.parent},
                  {"receiver_grid_file", grd},
                  {"refine_factor", static_cast<std::int64_t>(r)},
                  {"coarse_psi_coincidence_m", coincide_m},
                  {"refinement_ratio_median", sum.ratio_median}};
  const std::string name = c.name + "_contact.nc";
  io::write_contact(out.temp_path(name), f);
  outputs.push_back(Json{{"file", name}, {kChecksumKey, file_checksum(out.pending_path(name))}});
  // The parent with this grid outlined.
  io::RomsPictureOptions po;
  po.title = fmt::format("{} in {}: psi I {}..{} x J {}..{} split {} x {} ({} x {} rho points)", c.name, parent_file,
                         g.box.i_left, g.box.i_right, g.box.j_bottom, g.box.j_top, r, r, g.box.L() + 1, g.box.M() + 1);
  po.outlines.push_back(g.result.contour_samples);
  std::vector<std::uint8_t> pmask(parent.mask_rho.size());
  for (std::size_t k = 0; k < pmask.size(); ++k) pmask[k] = parent.mask_rho[k] > 0.5 ? 1 : 0;
  const std::string png = c.name + "_in_parent.png";
  io::write_roms_png(out.temp_path(png), g.parent_plane, pmask, parent.h, po);
  outputs.push_back(Json{{"file", png}, {kChecksumKey, file_checksum(out.pending_path(png))}});

  const auto& a = sum.coarse_to_fine;
  const auto& b = sum.fine_to_coarse;
  report["contact"] = Json{{"file", name},
                           {"parent_grid", parent_file},
                           {"parent_grid_source", c.nesting.parent},
                           {"points", sum.points},
                           {"coarse_to_fine", {{"rho", a[0]}, {"u", a[1]}, {"v", a[2]}}},
                           {"fine_to_coarse", {{"rho", b[0]}, {"u", b[1]}, {"v", b[2]}}},
                           {"wet_points", sum.wet_points},
                           {"refine_factor", r},
                           {"refinement_ratio_median", sum.ratio_median},
                           {"coarse_psi_coincidence_m", coincide_m}};
  stage.done(
      fmt::format("{}{}: {} points, coarse->fine {} rho {} u {} v, fine->coarse {} rho {} u {} v ({} over water); "
                  "fine/coarse step ratio {:.4g}; coarse psi points on the fine grid within {:.2g} m; {}",
                  g.nested ? parent_file + ", " : std::string(), name, sum.points, a[0], a[1], a[2], b[0], b[1], b[2],
                  sum.wet_points, sum.ratio_median, coincide_m, png));
}

}  // namespace aq::app
