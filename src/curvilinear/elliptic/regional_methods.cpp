// SPDX-License-Identifier: GPL-3.0-or-later
// Seed-004 methods in the regional pipeline (digest B.2–B.6); see regional_methods.hpp.
#include "curvilinear/elliptic/regional_methods.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace aq::curvilinear {

namespace {

EllipticOptions elliptic_options(const RegionalParams& p, GridMethod m) {
  EllipticOptions o;
  o.method = m == GridMethod::kRl ? EllipticMethod::kRyskinLeal : EllipticMethod::kEd2;
  o.relaxation = p.relaxation;
  o.tolerance = p.elliptic_tolerance;
  o.criteria_tolerance = p.elliptic_criteria_tolerance;
  o.max_iterations = p.elliptic_iterations;
  // RL is sensitive to λ (seed 004 Sec. 3) and takes the more exact inner solve: with 0.2/6 its
  // Black Sea grid settles at the same 60 iterations with twice the orthogonality error (50), 0.053
  // against 0.021 worst.
  if (o.method == EllipticMethod::kRyskinLeal) {
    o.inner_tolerance = 0.1;
    o.inner_iterations = 10;
  }
  return o;
}

// Grid with the boundary of `nodes` and TFI inside (with the given sections).
Grid2D tfi_grid(const SplineContour& contour, const BoundaryNodes& nodes, const RegionalSections& sections,
                const ControlFunction& w) {
  Grid2D g(nodes.nx_pts, nodes.ny_pts);
  set_grid_boundary(contour, nodes, g);
  tfi_with_sections(g, sections.sections, sections.lines, w);
  return g;
}

std::string tfi_name(const RegionalSections& s) {
  const std::size_t n = s.sections.size();
  if (n == 0) return "tfi";
  return fmt::format("tfi+{} {}section{}", n, s.lines == SectionLines::kRows ? "eta " : "", n == 1 ? "" : "s");
}

void log_criteria_table(const std::vector<Candidate>& c, int chosen, const Logger& log) {
  log.info("  {:<16} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>6} {:>6}", "candidate", "f1", "f1_o", "f2",
           "f2_o", "f3", "f3_o", "f4", "f4_o", "folded", "cross");
  for (std::size_t k = 0; k < c.size(); ++k) {
    const Criteria& q = c[k].criteria;
    log.info("{} {:<16} {:>9.4f} {:>9.4f} {:>9.4f} {:>9.4f} {:>9.4f} {:>9.4f} {:>9.4f} {:>9.4f} {:>6} {:>6}",
             static_cast<int>(k) == chosen ? "*" : " ", c[k].name, q.worst[0], q.average[0], q.worst[1], q.average[1],
             q.worst[2], q.average[2], q.worst[3], q.average[3], c[k].self_intersecting_cells, c[k].boundary_crossings);
  }
}

}  // namespace

ControlFunction depth_weighted(const ControlFunction& w, double a, std::array<double, 4> box,
                               const Projection& projection, const DepthSampler& depth) {
  constexpr int n = 257;
  const double px = 0.02 * (box[1] - box[0]), py = 0.02 * (box[3] - box[2]);
  const double x0 = box[0] - px, y0 = box[2] - py;
  const double dx = (box[1] - box[0] + 2 * px) / (n - 1), dy = (box[3] - box[2] + 2 * py) / (n - 1);
  std::vector<double> h(static_cast<std::size_t>(n) * n), out(h.size());
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const GeoPoint g = projection.inverse(x0 + i * dx, y0 + j * dy);
      const double d = depth(g.lon_deg, g.lat_deg);
      h[static_cast<std::size_t>(j) * n + i] = std::isfinite(d) ? d : 0.0;
    }
  double gmax = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto at = [&](int a1, int b1) {
        return h[static_cast<std::size_t>(std::clamp(b1, 0, n - 1)) * n +
                 static_cast<std::size_t>(std::clamp(a1, 0, n - 1))];
      };
      const double gx = (at(i + 1, j) - at(i - 1, j)) / ((std::min(i + 1, n - 1) - std::max(i - 1, 0)) * dx);
      const double gy = (at(i, j + 1) - at(i, j - 1)) / ((std::min(j + 1, n - 1) - std::max(j - 1, 0)) * dy);
      out[static_cast<std::size_t>(j) * n + i] = std::hypot(gx, gy);
      gmax = std::max(gmax, out[static_cast<std::size_t>(j) * n + i]);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      double& v = out[static_cast<std::size_t>(j) * n + i];
      v = w(x0 + i * dx, y0 + j * dy) * (1.0 + (gmax > 0.0 ? a * v / gmax : 0.0));
    }
  return ControlFunction::sampled(x0, y0, dx, dy, n, n, std::move(out));
}

RegionalSections regional_sections(const RegionalParams& p, int nx_pts, int ny_pts, const Projection& projection) {
  RegionalSections result;
  const bool rows = !p.sections_eta.empty();
  result.lines = rows ? SectionLines::kRows : SectionLines::kColumns;
  const auto& given = rows ? p.sections_eta : p.sections;
  const int n_pts = rows ? ny_pts : nx_pts;
  std::vector<Section>& out = result.sections;
  for (std::size_t k = 0; k < given.size(); ++k) {
    const auto& s = given[k];
    Section sec;
    sec.column = static_cast<int>(std::lround(s[0] * (n_pts - 1)));
    if (sec.column < 1 || sec.column > n_pts - 2 || (!out.empty() && sec.column <= out.back().column))
      throw ConfigError(
          fmt::format("{}: regional.{}[{}]: {} = {} gives grid {} {}, which is not inside 1..{} after the previous "
                      "section (list sections by increasing {}, at least one {} apart)",
                      p.source, rows ? "sections_eta" : "sections", k + 1, rows ? "q2" : "q1", s[0],
                      rows ? "row" : "column", sec.column, n_pts - 2, rows ? "q2" : "q1", rows ? "row" : "column"));
    for (std::size_t m = 1; m + 1 < s.size(); m += 2) {
      if (p.points_lonlat) {
        sec.points.push_back(projection.forward(s[m], s[m + 1]));
      } else {
        sec.points.push_back({s[m], s[m + 1]});
      }
    }
    out.push_back(std::move(sec));
  }
  return result;
}

Candidate make_candidate(std::string name, const Grid2D& grid, const ControlFunction& w) {
  Candidate c;
  c.name = std::move(name);
  c.criteria = grid_criteria(grid, w);
  c.self_intersecting_cells = self_intersecting_cells(grid);
  c.boundary_crossings = boundary_crossings(grid);
  return c;
}

MethodRun build_method_grid(const RegionalParams& p, const SplineContour& contour, const BoundaryNodes& nodes,
                            const Projection& projection, const ControlFunction& w, const Grid2D* conformal_grid,
                            const BoundaryNodes* conformal_nodes, const Logger& log) {
  MethodRun run;
  run.nodes = nodes;
  const RegionalSections sections = regional_sections(p, nodes.nx_pts, nodes.ny_pts, projection);
  GridMethod elliptic = p.method;
  switch (p.method) {
    case GridMethod::kConformal:
    case GridMethod::kBvp:
      throw InternalError("build_method_grid: the conformal and bvp methods are the izogrid pipeline's stages");
    case GridMethod::kStar: {
      run.grid = Grid2D(nodes.nx_pts, nodes.ny_pts);
      set_grid_boundary(contour, nodes, run.grid);
      star_fill(run.grid, w);
      run.initial = "star";
      break;
    }
    case GridMethod::kTfi:
    case GridMethod::kEd2:
    case GridMethod::kRl:
      run.grid = tfi_grid(contour, nodes, sections, w);
      run.initial = tfi_name(sections);
      break;
    case GridMethod::kBest: {
      std::vector<Grid2D> grids;
      std::vector<BoundaryNodes> grid_nodes;
      std::vector<Candidate>& cand = run.candidates;
      Grid2D star(nodes.nx_pts, nodes.ny_pts);
      set_grid_boundary(contour, nodes, star);
      try {
        star_fill(star, w);
        cand.push_back(make_candidate("star", star, w));
        grids.push_back(std::move(star));
        grid_nodes.push_back(nodes);
      } catch (const InputError& e) {
        log.info("regional best: no STAR candidate: {}", e.what());
      }
      grids.push_back(tfi_grid(contour, nodes, {}, w));
      cand.push_back(make_candidate("tfi", grids.back(), w));
      grid_nodes.push_back(nodes);
      RegionalSections variant = sections;
      if (variant.sections.empty() && nodes.nx_pts >= 5)
        variant.sections.push_back(Section{(nodes.nx_pts - 1) / 2, {}});
      if (!variant.sections.empty()) {
        grids.push_back(tfi_grid(contour, nodes, variant, w));
        cand.push_back(make_candidate(tfi_name(variant), grids.back(), w));
        grid_nodes.push_back(nodes);
      }
      if (conformal_grid != nullptr && conformal_nodes != nullptr) {
        grids.push_back(*conformal_grid);
        cand.push_back(make_candidate("conformal", grids.back(), w));
        grid_nodes.push_back(*conformal_nodes);
      }
      run.selection = select_best_grid(cand);
      log.info(
          "regional best: candidates (f = worst cell, f_o = average; folded = self-intersecting cells, cross = "
          "line segments crossing the boundary), * = chosen");
      log_criteria_table(cand, run.selection.chosen, log);
      for (const auto& s : run.selection.steps) log.info("  {}", s);
      const auto c = static_cast<std::size_t>(run.selection.chosen);
      run.grid = std::move(grids[c]);
      run.nodes = grid_nodes[c];
      run.initial = cand[c].name;
      elliptic = p.best_final;
      break;
    }
  }
  run.self_intersecting_cells = self_intersecting_cells(run.grid);
  run.boundary_crossings = boundary_crossings(run.grid);
  if (elliptic == GridMethod::kEd2 || elliptic == GridMethod::kRl) {
    Grid2D initial = run.grid;
    EllipticOptions eo = elliptic_options(p, elliptic);
    eo.progress = log.progress("regional elliptic");
    run.elliptic = elliptic_smooth(run.grid, w, eo);
    if (!run.elliptic->converged)
      log.warn("regional {}: not settled after {} iterations (last node move {:.2e} of the diameter)",
               std::string(name_of(elliptic)), run.elliptic->iterations, run.elliptic->last_move);
    // Never trade a valid grid for a folded one.
    const int folded = self_intersecting_cells(run.grid);
    if (folded > 0 && run.self_intersecting_cells == 0) {
      log.warn("regional {}: the grid has {} self-intersecting cells; keeping the {} grid, which has none",
               std::string(name_of(elliptic)), folded, run.initial);
      run.grid = std::move(initial);
      run.elliptic_rejected = true;
      run.rejected_because = "folded";
    } else if (p.method == GridMethod::kBest) {
      // best never returns a grid worse than the winner: the elliptic grid replaces it only if B.6
      // between the two (the same f1..f4 steps, ties to the winner) picks it.
      const std::string final_name = std::string(name_of(elliptic));
      run.final_check = {run.candidates[static_cast<std::size_t>(run.selection.chosen)],
                         make_candidate(final_name + " from " + run.initial, run.grid, w)};
      const Selection keep = select_best_grid(run.final_check);
      log.info(
          "regional best: rule: the {} grid replaces the chosen {} grid only if the same selection between "
          "the two (ties to {}) picks it",
          final_name, run.initial, run.initial);
      log_criteria_table(run.final_check, keep.chosen, log);
      for (const auto& s : keep.steps) log.info("  {}", s);
      if (keep.chosen == 0) {
        log.info(
            "regional best: the {} grid is worse than the {} grid by the selection criteria; the result is the {} "
            "grid itself",
            final_name, run.initial, run.initial);
        run.grid = std::move(initial);
        run.elliptic_rejected = true;
        run.rejected_because = "worse than " + run.initial;
      }
    }
  }
  return run;
}

}  // namespace aq::curvilinear
