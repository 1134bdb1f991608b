// SPDX-License-Identifier: GPL-3.0-or-later
// The regional izogrid pipeline; see regional.hpp (seed 000 Sec. 1–2.5, modes 0–4).
#include "curvilinear/regional.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"
#include "core/timer.hpp"
#include "curvilinear/elliptic/boundary_equidistribution.hpp"
#include "curvilinear/common/grid_checks.hpp"

namespace aq::curvilinear {

std::vector<PlanePoint> RegionalResult::node_points(const BoundaryNodes& n) const {
  std::vector<PlanePoint> out;
  if (!contour) return out;
  out.reserve(n.s.size());
  for (double s : n.s) out.push_back(contour->point(s));
  return out;
}

namespace {

// ny, and nx0 = params.nx or, when 0, guessed from the contour's side lengths (square cells).
void set_first_grid_size(RegionalResult& r) {
  const RegionalParams& p = r.params;
  r.ny = p.ny;
  r.nx_initial = p.nx;
  if (r.nx_initial <= 0) {
    const double ratio = (r.side_length[0] + r.side_length[2]) / (r.side_length[1] + r.side_length[3]);
    r.nx_initial = std::max(1, static_cast<int>(std::lround(p.ny * ratio)));
  }
}

// Stages 3–4 of method = bvp: the orthogonal-family grid (seed 003, regional_bvp.hpp) replaces the
// inverse problem and the fill; it starts from the uniform boundary nodes of stage 2.
void bvp_stage(RegionalResult& r, const Logger& log, Report* report, Json* section) {
  const RegionalParams& p = r.params;
  StageScope scope("regional bvp", report, log);
  const Timer t;
  // A second block (its west side is the first block's east side): its contour and nodes.
  std::optional<SplineContour> contour2;
  BoundaryNodes uniform2;
  if (!p.x2.empty()) {
    std::vector<double> x2 = p.x2, y2 = p.y2;
    if (p.points_lonlat)
      for (std::size_t k = 0; k < x2.size(); ++k) {
        const PlanePoint q = r.projection->forward(p.x2[k], p.y2[k]);
        x2[k] = q.x;
        y2[k] = q.y;
      }
    ContourOptions co;
    co.degree = p.spline_type == 3 ? 3 : 5;
    co.parametrisation = p.param;
    co.source = p.source + " (block2_points)";
    contour2.emplace(x2, y2, p.corner2, co);
    const double ratio = (contour2->side_length(Side::kSouth) + contour2->side_length(Side::kNorth)) /
                         (contour2->side_length(Side::kEast) + contour2->side_length(Side::kWest));
    const int nx2 = p.nx2 > 0 ? p.nx2 : std::max(1, static_cast<int>(std::lround(p.ny * ratio)));
    uniform2 = uniform_boundary_nodes(*contour2, 2 * nx2 + 1, 2 * p.ny + 1);
  }
  RegionalBvp b = regional_bvp(*r.contour, r.uniform_nodes, *r.projection, p, contour2 ? &*contour2 : nullptr,
                               contour2 ? &uniform2 : nullptr);
  r.grid = std::move(b.grid);
  r.nodes = std::move(b.nodes);
  r.nx = b.nx;
  r.aspect_ratio = b.aspect_ratio;
  r.dxi_over_deta = r.aspect_ratio * (r.nodes.ny_pts - 1) / (r.nodes.nx_pts - 1);
  r.bvp = std::move(b.bvp);
  r.bvp->grid = {};
  if (contour2) {
    // The outline of the merged grid (the picture's extent), counter-clockwise from SW.
    r.contour_samples = grid_outline(r.grid);
  }
  r.stage_seconds[4] = t.wall_s();
  r.completed = Stage::kGrid;
  const BvpResult& h = *r.bvp;
  if (section != nullptr) {
    (*section)["method"] = "bvp";
    (*section)["surface"] = p.surface == RegionalSurface::kSphere ? "sphere" : "plane";
    (*section)["nx"] = r.nx;
    (*section)["aspect_ratio"] = r.aspect_ratio;
    (*section)["dxi_over_deta"] = r.dxi_over_deta;
    (*section)["supergrid"] = {r.grid.nx_pts, r.grid.ny_pts};
    (*section)["bvp_f_max"] = h.f_max;
    (*section)["bvp_f_avg"] = h.f_avg;
    (*section)["bvp_energy_product"] = h.energy_product;
    (*section)["bvp_cg_iterations"] = h.cg_iterations;
    (*section)["bvp_best_iteration"] = h.best_iteration;
    if (contour2) {
      (*section)["bvp_blocks"] = 2;
      (*section)["bvp_interface_kink_rad"] = b.interface_kink;
    }
    (*section)["stage_seconds"] = r.stage_seconds;
  }
  scope.done(
      fmt::format("{} x {} supergrid on the {} (nx = {}, W/H = {:.6f}): f_max {:.3g} -> {:.3g}, f_avg {:.3g} "
                  "-> {:.3g} in {} outer iterations (best {})",
                  r.grid.nx_pts, r.grid.ny_pts, p.surface == RegionalSurface::kSphere ? "sphere" : "plane", r.nx,
                  r.aspect_ratio, h.f_max.front(), h.f_max[static_cast<std::size_t>(h.best_iteration)], h.f_avg.front(),
                  h.f_avg[static_cast<std::size_t>(h.best_iteration)], h.iterations, h.best_iteration));
}

// Stages 2–4 of the conformal (izogrid) method; with method = bvp, stages 3–4 are bvp_stage().
void conformal_stages(RegionalResult& r, Stage stop_after, const Logger& log, Report* report, Json* section) {
  const RegionalParams& p = r.params;
  // Stage 2: uniform boundary nodes of the (2nx0+1) × (2ny+1) supergrid.
  {
    StageScope scope("regional uniform", report, log);
    const Timer t;
    set_first_grid_size(r);
    r.uniform_nodes = uniform_boundary_nodes(*r.contour, 2 * r.nx_initial + 1, 2 * p.ny + 1, {}, &r.uniform_stats);
    r.stage_seconds[2] = t.wall_s();
    r.completed = Stage::kUniform;
    scope.done(fmt::format("{} boundary nodes of a {} x {} supergrid", r.uniform_nodes.count(), r.uniform_nodes.nx_pts,
                           r.uniform_nodes.ny_pts));
  }
  if (section != nullptr) (*section)["stage_seconds"] = r.stage_seconds;
  if (stop_after == Stage::kUniform) return;
  if (p.method == GridMethod::kBvp) return bvp_stage(r, log, report, section);

  // Stage 3: inverse problem.
  {
    StageScope scope("regional conformal", report, log);
    const Timer t;
    InverseOptions io;
    io.schedule = p.schedule;
    io.tolerance = p.tolerance;
    io.max_outer_iterations = p.max_outer;
    io.max_inner_passes = p.max_inner;
    io.interpolation_points = p.interp_points;
    io.inner_relative_tolerance = p.inner_rtol;
    io.acceleration_depth = p.anderson;
    io.auto_nx = p.auto_nx;
    io.cell_multiple = 2;
    io.threads = p.threads;
    r.inverse = solve_inverse_problem(*r.contour, r.uniform_nodes, io, log);
    r.nodes = r.inverse.nodes;
    r.aspect_ratio = r.inverse.aspect_ratio;
    r.nx = (r.nodes.nx_pts - 1) / 2;
    r.dxi_over_deta = r.aspect_ratio * (r.nodes.ny_pts - 1) / (r.nodes.nx_pts - 1);
    r.stage_seconds[3] = t.wall_s();
    r.completed = Stage::kConformal;
    int passes = 0;
    for (int q : r.inverse.inner_passes) passes += q;
    if (section != nullptr) {
      (*section)["nx"] = r.nx;
      (*section)["aspect_ratio"] = r.aspect_ratio;
      (*section)["dxi_over_deta"] = r.dxi_over_deta;
      (*section)["supergrid"] = {r.nodes.nx_pts, r.nodes.ny_pts};
      (*section)["residual_history"] = r.inverse.residual_history;
      (*section)["aspect_history"] = r.inverse.aspect_history;
      (*section)["iz89_passes"] = r.inverse.inner_passes;
      (*section)["residual"] = r.inverse.residual;
      (*section)["tolerance"] = r.inverse.tolerance;
    }
    scope.done(
        fmt::format("W/H = {:.7f}, nx = {} for ny = {} (supergrid {} x {}), residual {:.2e} after {} outer "
                    "iterations, {} IZ89 passes",
                    r.aspect_ratio, r.nx, r.ny, r.nodes.nx_pts, r.nodes.ny_pts, r.inverse.residual,
                    r.inverse.outer_iterations, passes));
  }
  if (section != nullptr) (*section)["stage_seconds"] = r.stage_seconds;
  if (stop_after == Stage::kConformal) return;

  // Stage 4: Laplace fill of the supergrid.
  {
    StageScope scope("regional grid", report, log);
    const Timer t;
    r.grid = Grid2D(r.nodes.nx_pts, r.nodes.ny_pts);
    set_grid_boundary(*r.contour, r.nodes, r.grid);
    LaplaceOptions lo;
    lo.solver = p.solver;
    r.laplace = laplace_fill(r.grid, r.aspect_ratio / (r.nodes.nx_pts - 1), 1.0 / (r.nodes.ny_pts - 1), lo);
    r.stage_seconds[4] = t.wall_s();
    r.completed = Stage::kGrid;
    if (section != nullptr) {
      (*section)["laplace_solver"] = p.solver == LaplaceOptions::Solver::kDst ? "dst" : "sor";
      (*section)["laplace_residual"] = r.laplace.residual;
      (*section)["laplace_iterations"] = r.laplace.iterations;
    }
    scope.done(fmt::format("{} x {} supergrid filled ({} solver, residual {:.1e})", r.grid.nx_pts, r.grid.ny_pts,
                           p.solver == LaplaceOptions::Solver::kDst ? "DST" : "SOR", r.laplace.residual));
  }
  if (section != nullptr) (*section)["stage_seconds"] = r.stage_seconds;
}

// Stages 2 and 4 of a seed-004 method: equidistributed boundary nodes, then the method's grid.
void method_stages(RegionalResult& r, Stage stop_after, const Logger& log, Report* report, Json* section,
                   const DepthSampler* depth) {
  const RegionalParams& p = r.params;
  ControlFunction w = p.weight;
  if (p.weight_depth > 0.0 && depth != nullptr) {
    std::array<double, 4> box{1e300, -1e300, 1e300, -1e300};
    for (const PlanePoint& q : r.contour_samples) {
      box[0] = std::min(box[0], q.x), box[1] = std::max(box[1], q.x);
      box[2] = std::min(box[2], q.y), box[3] = std::max(box[3], q.y);
    }
    w = depth_weighted(w, p.weight_depth, box, *r.projection, *depth);
  }
  {
    StageScope scope("regional uniform", report, log);
    const Timer t;
    set_first_grid_size(r);
    r.uniform_nodes = equidistributed_boundary_nodes(*r.contour, 2 * r.nx_initial + 1, 2 * p.ny + 1, w);
    r.nodes = r.uniform_nodes;
    r.nx = r.nx_initial;
    r.stage_seconds[2] = t.wall_s();
    r.completed = Stage::kUniform;
    scope.done(fmt::format("{} boundary nodes of a {} x {} supergrid by equidistribution of w = {}",
                           r.uniform_nodes.count(), r.uniform_nodes.nx_pts, r.uniform_nodes.ny_pts, w.text()));
  }
  if (section != nullptr) (*section)["stage_seconds"] = r.stage_seconds;
  if (stop_after != Stage::kGrid) return;
  {
    StageScope scope("regional grid", report, log);
    const Timer t;
    std::optional<RegionalResult> conformal;
    if (p.method == GridMethod::kBest) {
      conformal = r;
      conformal->params.method = GridMethod::kConformal;
      try {
        conformal_stages(*conformal, Stage::kGrid, Logger::null(), nullptr, nullptr);
      } catch (const NumericalError& e) {
        log.info("regional best: no conformal candidate: {}", e.what());
        conformal.reset();
      }
    }
    r.method_run = build_method_grid(p, *r.contour, r.nodes, *r.projection, w, conformal ? &conformal->grid : nullptr,
                                     conformal ? &conformal->nodes : nullptr, log);
    MethodRun& m = *r.method_run;
    r.grid = m.grid;
    r.nodes = m.nodes;
    r.nx = (r.grid.nx_pts - 1) / 2;
    r.ny = (r.grid.ny_pts - 1) / 2;
    r.dxi_over_deta = estimate_step_ratio(r.grid);
    r.aspect_ratio = r.dxi_over_deta * (r.grid.nx_pts - 1) / (r.grid.ny_pts - 1);
    r.stage_seconds[4] = t.wall_s();
    r.completed = Stage::kGrid;
    const int folded = self_intersecting_cells(r.grid);
    if (section != nullptr) {
      Json& j = *section;
      j["nx"] = r.nx;
      j["supergrid"] = {r.grid.nx_pts, r.grid.ny_pts};
      j["initial_grid"] = m.initial;
      j["initial_self_intersecting_cells"] = m.self_intersecting_cells;
      j["initial_boundary_crossings"] = m.boundary_crossings;
      j["self_intersecting_cells"] = folded;
      j["boundary_crossings"] = boundary_crossings(r.grid);
      if (m.elliptic) {
        j["elliptic_iterations"] = m.elliptic->iterations;
        j["elliptic_cg_iterations"] = m.elliptic->cg_iterations;
        j["elliptic_converged"] = m.elliptic->converged;
        j["elliptic_stop"] = elliptic_stop_name(m.elliptic->stop);
        j["elliptic_last_move"] = m.elliptic->last_move;
        j["elliptic_rejected"] = m.elliptic_rejected;
      }
      const auto table = [](const std::vector<Candidate>& cands) {
        Json rows = Json::array();
        for (const Candidate& c : cands)
          rows.push_back(Json{{"name", c.name},
                              {"f_worst", c.criteria.worst},
                              {"f_average", c.criteria.average},
                              {"self_intersecting_cells", c.self_intersecting_cells},
                              {"boundary_crossings", c.boundary_crossings}});
        return rows;
      };
      if (!m.candidates.empty()) {
        j["candidates"] = table(m.candidates);
        j["selection_steps"] = m.selection.steps;
        j["chosen"] = m.initial;
      }
      if (!m.final_check.empty()) j["final_check"] = table(m.final_check);
    }
    std::string what = m.initial;
    if (m.elliptic)
      what = fmt::format("{} from {} ({} iterations, {} CG iterations, {}, last node move {:.1e} of the diameter{})",
                         std::string(name_of(p.method == GridMethod::kBest ? p.best_final : p.method)), m.initial,
                         m.elliptic->iterations, m.elliptic->cg_iterations,
                         m.elliptic->converged ? elliptic_stop_name(m.elliptic->stop) : "not settled",
                         m.elliptic->last_move,
                         m.elliptic_rejected ? ", " + m.rejected_because + ": initial grid kept" : "");
    scope.done(
        fmt::format("{} x {} supergrid by {}; {} self-intersecting cells", r.grid.nx_pts, r.grid.ny_pts, what, folded));
  }
  if (section != nullptr) (*section)["stage_seconds"] = r.stage_seconds;
}

}  // namespace

RegionalResult run_regional(const RegionalParams& params, Stage stop_after, const Logger& log, Report* report,
                            const DepthSampler* depth) {
  validate_regional_params(params);
  // The configuration checks these at load (config/regional.cpp); here they are preconditions.
  if (params.method != GridMethod::kConformal && stop_after == Stage::kConformal)
    throw InternalError(fmt::format("{}: method = {} has no conformal stage", params.source, params.method));
  if (uses_weight(params.method) && params.weight_depth > 0.0 && depth == nullptr)
    throw InternalError(
        fmt::format("{}: regional.weight_depth = {} without a bathymetry", params.source, params.weight_depth));
  RegionalResult r;
  r.params = params;
  const RegionalParams& p = r.params;
  Json* section = nullptr;
  if (report != nullptr) {
    section = &(*report)["regional"];
    *section = Json{{"source", p.source},
                    {"proj", std::string(name_of(p.projection.kind))},
                    {"rlat", p.projection.rlat_deg},
                    {"rlon", p.projection.rlon_deg},
                    {"rota", p.projection.rota_deg},
                    {"uscale", p.projection.uscale},
                    {"spline_type", p.spline_type},
                    {"param", std::string(name_of(p.param))},
                    {"npass", p.npass},
                    {"ny", p.ny},
                    {"schedule", std::string(name_of(p.schedule))},
                    {"control_points", p.x.size()},
                    {"method", std::string(name_of(p.method))}};
    if (uses_weight(p.method)) {
      (*section)["weight"] = p.weight.text();
      (*section)["sections"] = p.sections;
    }
  }

  // Stage 0: map. Project the control points if they are geographic.
  {
    StageScope scope("regional map", report, log);
    const Timer t;
    r.projection.emplace(p.projection);
    r.control_corner = p.corner;
    if (p.points_lonlat) {
      for (std::size_t k = 0; k < p.x.size(); ++k) {
        const PlanePoint q = r.projection->forward(p.x[k], p.y[k]);
        if (!std::isfinite(q.x) || !std::isfinite(q.y))
          throw InputError(fmt::format("{}: control point {} ({}, {}) lies where the {} projection is singular",
                                       p.source, k + 1, p.x[k], p.y[k], std::string(name_of(p.projection.kind))));
        r.control_x.push_back(q.x);
        r.control_y.push_back(q.y);
      }
    } else {
      r.control_x = p.x;
      r.control_y = p.y;
    }
    r.stage_seconds[0] = t.wall_s();
    r.completed = Stage::kMap;
    // (lon, lat) as in the blocks table: longitude first.
    scope.done(fmt::format("{} projection centred at lon {}, lat {}, rota {}, {} control points",
                           std::string(name_of(p.projection.kind)), p.projection.rlon_deg, p.projection.rlat_deg,
                           p.projection.rota_deg, r.control_x.size()));
  }
  if (section != nullptr) (*section)["stage_seconds"] = r.stage_seconds;
  if (stop_after == Stage::kMap) return r;

  // Stage 1: contour.
  {
    StageScope scope("regional contour", report, log);
    const Timer t;
    ContourOptions co;
    co.degree = p.spline_type == 3 ? 3 : 5;
    co.parametrisation = p.param;
    co.source = p.source;
    r.contour.emplace(r.control_x, r.control_y, r.control_corner, co);
    if (p.spline_type == 4) {
      co.degree = 3;
      r.cubic_contour.emplace(r.control_x, r.control_y, r.control_corner, co);
    }
    r.contour_samples = r.contour->sample(32);
    for (int s = 0; s < 4; ++s)
      r.side_length[static_cast<std::size_t>(s)] = r.contour->side_length(static_cast<Side>(s));
    r.stage_seconds[1] = t.wall_s();
    r.completed = Stage::kContour;
    if (section != nullptr) (*section)["side_lengths"] = r.side_length;
    scope.done(fmt::format("{} spline through {} points, sides S {:.4g}, E {:.4g}, N {:.4g}, W {:.4g}",
                           co.degree == 3 && p.spline_type == 3 ? "cubic" : "quintic", r.control_x.size(),
                           r.side_length[0], r.side_length[1], r.side_length[2], r.side_length[3]));
  }
  if (section != nullptr) (*section)["stage_seconds"] = r.stage_seconds;
  if (stop_after == Stage::kContour) return r;

  if (p.method == GridMethod::kConformal || p.method == GridMethod::kBvp) {
    conformal_stages(r, stop_after, log, report, section);
  } else {
    method_stages(r, stop_after, log, report, section, depth);
  }
  return r;
}

}  // namespace aq::curvilinear
