// The refinement grid of a regional run and its contact points (see regional_refine.hpp).
#include "app/regional_refine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "app/regional_roms.hpp"
#include "core/error.hpp"
#include "curvilinear/cgrid.hpp"
#include "handoff/contact_points.hpp"
#include "io/roms_grid_png.hpp"

#ifndef AQ_VERSION
#define AQ_VERSION "dev"
#endif

namespace aq::app {

namespace {

std::string box_text(const curvilinear::RefineBox& b) {
  return fmt::format("[{}, {}, {}, {}]", b.i_left, b.i_right, b.j_bottom, b.j_top);
}

// `base` in the parent's plane: the projection its aquatoria attributes name, else a stereographic
// plane centred on the box (any conformal plane keeps the grid orthogonal; the parent's own one
// makes the fine grid's plane coordinates the parent's).
curvilinear::RegionalParams parent_plane(const curvilinear::RegionalParams& base, const io::RomsGridFields& p,
                                         const curvilinear::RefineBox& b, double radius_m, std::string& source) {
  curvilinear::RegionalParams q = base;
  if (!p.proj.empty() && std::isfinite(p.rlat) && std::isfinite(p.rlon) && std::isfinite(p.rota) &&
      std::isfinite(p.uscale)) {
    q.proj = curvilinear::parse_projection_kind(p.proj);
    q.rlat = p.rlat;
    q.rlon = p.rlon;
    q.rota = p.rota;
    q.uscale = p.uscale;
    q.lat1 = p.lat1;
    q.lat2 = p.lat2;
    q.radius = std::isfinite(p.radius) ? p.radius : radius_m;
    source = fmt::format("the parent's projection ({} rlat {} rlon {} rota {})", p.proj, p.rlat, p.rlon, p.rota);
    return q;
  }
  const int k = (b.i_left + b.i_right) / 2 - 1, l = (b.j_bottom + b.j_top) / 2 - 1;  // ψ file indices
  const std::size_t c = static_cast<std::size_t>(l) * static_cast<std::size_t>(p.L) + static_cast<std::size_t>(k);
  q.proj = curvilinear::ProjectionKind::kStereographic;
  q.rlat = p.lat_psi[c];
  q.rlon = p.lon_psi[c];
  q.rota = 0.0;
  q.radius = radius_m;
  source = fmt::format("a stereographic plane centred at {:.4f}E {:.4f}N (the parent file names no projection)", q.rlon,
                       q.rlat);
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

RefinedGrid build_refinement(const config::RegionalConfig& c, const std::string& config_source, const Logger& log,
                             Report* report) {
  StageScope stage("refine", report, log);
  RefinedGrid g;
  const auto& n = c.nesting;
  g.box = {n.parent_box[0], n.parent_box[1], n.parent_box[2], n.parent_box[3], n.refine_factor};
  g.parent = io::read_roms_grid_fields(n.parent);
  if (const std::string bad = handoff::refinement_box_problem(g.box, g.parent.L, g.parent.M); !bad.empty())
    throw ConfigError(fmt::format("{}: nesting.parent_box = {} in nesting.parent = {}: {}", config_source,
                                  box_text(g.box), n.parent, bad));

  curvilinear::RegionalResult& r = g.result;
  r.params = parent_plane(c.params, g.parent, g.box, c.roms.earth_radius_m, g.projection_source);
  const curvilinear::Projection proj(curvilinear::projection_params(r.params));
  g.parent_plane = parent_supergrid(g.parent, proj, n.parent);
  g.parent_h_on_grid = handoff::parent_rho_on_fine(g.parent, g.parent.h, g.box);
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

void write_refinement_contact(const config::RegionalConfig& c, const std::string& config_source, const RefinedGrid& g,
                              OutputSet& out, Json& outputs, Report& report, const Logger& log) {
  StageScope stage("contact", &report, log);
  const curvilinear::CGrid fine = curvilinear::build_cgrid(g.padded, *g.result.projection, roms_cgrid_options(c));
  handoff::ContactSummary sum;
  io::ContactFile f = handoff::refinement_contact(g.parent, g.box, fine, kRefinePad, &sum);

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

  const std::string grd = c.name + "_grd.nc";
  f.grid_files = fmt::format(" \n{} \n{}", c.nesting.parent, grd);
  f.history = fmt::format("aquatoria {} regional {}", AQ_VERSION, config_source);
  f.attributes = {{"parent_grid", c.nesting.parent},
                  {"receiver_grid_file", grd},
                  {"refine_factor", static_cast<std::int64_t>(r)},
                  {"coarse_psi_coincidence_m", coincide_m},
                  {"refinement_ratio_median", sum.ratio_median}};
  const std::string name = c.name + "_contact.nc";
  io::write_contact(out.temp_path(name), f);
  outputs.push_back(Json{{"file", name}, {"checksum_fnv1a64", file_checksum(out.pending_path(name))}});
  // The parent with this grid outlined.
  io::RomsPictureOptions po;
  po.title =
      fmt::format("{} in {}: psi I {}..{} x J {}..{} split {} x {} ({} x {} rho points)", c.name, c.nesting.parent,
                  g.box.i_left, g.box.i_right, g.box.j_bottom, g.box.j_top, r, r, g.box.L() + 1, g.box.M() + 1);
  po.outlines.push_back(g.result.contour_samples);
  std::vector<std::uint8_t> pmask(g.parent.mask_rho.size());
  for (std::size_t k = 0; k < pmask.size(); ++k) pmask[k] = g.parent.mask_rho[k] > 0.5 ? 1 : 0;
  const std::string png = c.name + "_in_parent.png";
  io::write_roms_png(out.temp_path(png), g.parent_plane, pmask, g.parent.h, po);
  outputs.push_back(Json{{"file", png}, {"checksum_fnv1a64", file_checksum(out.pending_path(png))}});

  const auto& a = sum.coarse_to_fine;
  const auto& b = sum.fine_to_coarse;
  report["contact"] = Json{{"file", name},
                           {"parent_grid", c.nesting.parent},
                           {"points", sum.points},
                           {"coarse_to_fine", {{"rho", a[0]}, {"u", a[1]}, {"v", a[2]}}},
                           {"fine_to_coarse", {{"rho", b[0]}, {"u", b[1]}, {"v", b[2]}}},
                           {"wet_points", sum.wet_points},
                           {"refine_factor", r},
                           {"refinement_ratio_median", sum.ratio_median},
                           {"coarse_psi_coincidence_m", coincide_m}};
  stage.done(fmt::format(
      "{}: {} points, coarse->fine {} rho {} u {} v, fine->coarse {} rho {} u {} v ({} over water); "
      "fine/coarse step ratio {:.4g}; coarse psi points on the fine grid within {:.2g} m; {}",
      name, sum.points, a[0], a[1], a[2], b[0], b[1], b[2], sum.wet_points, sum.ratio_median, coincide_m, png));
}

}  // namespace aq::app
