// SPDX-License-Identifier: GPL-3.0-or-later
// The quadtree stage driver (see build_leaves.hpp).
#include "quadtree/build_leaves.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "config/load.hpp"
#include "core/cancel.hpp"
#include "core/error.hpp"
#include "core/timer.hpp"
#include "quadtree/balance.hpp"
#include "quadtree/grading.hpp"

namespace aq::quadtree {

namespace {

double round3(double x) { return static_cast<double>(static_cast<std::int64_t>(x * 1000.0 + 0.5)) / 1000.0; }

std::int64_t pixels_of(const std::vector<std::int64_t>& per_level, int levels) {
  std::int64_t n = 0;
  for (int l = 0; l <= levels; ++l) {
    const std::int64_t s = std::int64_t{1} << (levels - l);
    n += per_level[static_cast<std::size_t>(l)] * s * s;
  }
  return n;
}

// Leaf sizes (km, square_size_km) in bands of 10° of |φ′| (the lattice frame): per band the
// count, min, median and max, and with size targets the share of leaves within √2 of one of them.
struct SizeBand {
  std::vector<double> sizes;
};

Json size_bands_json(const std::vector<Leaf>& leaves, const Lattice& lat, const std::vector<double>& targets_km,
                     std::string& line) {
  std::vector<SizeBand> bands(9);
  for (const Leaf& f : leaves) {
    const double centre = leaf_centre_row(lat, f);
    const auto band = std::min<std::size_t>(8, static_cast<std::size_t>(std::fabs(lat.lat_of_row(centre)) / 10.0));
    bands[band].sizes.push_back(square_size_km(lat, f.level, centre));
  }
  Json out = Json::array();
  for (std::size_t k = 0; k < bands.size(); ++k) {
    std::vector<double>& v = bands[k].sizes;
    if (v.empty()) continue;
    std::sort(v.begin(), v.end());
    Json b{{"abs_lat_min_deg", 10 * k},
           {"abs_lat_max_deg", 10 * (k + 1)},
           {"leaves", v.size()},
           {"min_km", round3(v.front())},
           {"median_km", round3(v[(v.size() - 1) / 2])},
           {"max_km", round3(v.back())}};
    line +=
        fmt::format(" {}-{}°: {:.0f}/{:.0f}/{:.0f}", 10 * k, 10 * (k + 1), v.front(), v[(v.size() - 1) / 2], v.back());
    if (!targets_km.empty()) {
      const auto within = std::count_if(v.begin(), v.end(), [&](double x) {
        return std::any_of(targets_km.begin(), targets_km.end(), [x](double t) {
          return x >= t / std::sqrt(2.0) * (1.0 - 1e-12) && x <= t * std::sqrt(2.0) * (1.0 + 1e-12);
        });
      });
      b["share_within_sqrt2_of_a_target"] = round3(static_cast<double>(within) / static_cast<double>(v.size()));
    }
    out.push_back(b);
  }
  return out;
}

// The depth or box rules as the user gave them (config::rule_json), logged one a line; a size rule
// also with the level it asks at φ′ = 0 and at the lattice's last pixel row (the lon-lat lattice's
// pole row, the Mercator rows' end), where level L means the pixels are coarser than its target.
template <typename Rule>
Json rules_json(const std::vector<Rule>& rules, const char* key, const Lattice& lat, const Logger& log) {
  Json out = Json::array();
  for (std::size_t k = 0; k < rules.size(); ++k) {
    Json j = config::rule_json(rules[k]);
    const std::string given = j.dump();
    std::string asks;
    if (rules[k].size_km > 0.0) {
      const double equator = lat.row_of_lat(0.0), last = 0.5;
      const int at_equator = level_for_size(lat, rules[k].size_km, equator);
      const int at_last = level_for_size(lat, rules[k].size_km, last);
      const double last_lat = std::fabs(lat.lat_of_row(last));
      j["level_at_equator"] = at_equator;
      j["level_at_last_row"] = at_last;
      j["last_row_abs_lat_deg"] = round3(last_lat);
      asks =
          fmt::format(": level {} ({:.0f} km) at φ′ = 0°, level {} ({:.0f} km) at |φ′| = {:.1f}°", at_equator,
                      square_size_km(lat, at_equator, equator), at_last, square_size_km(lat, at_last, last), last_lat);
    }
    log.info("quadtree: {}[{}] = {}{}", key, k, given, asks);
    out.push_back(j);
  }
  return out;
}

}  // namespace

void check_leaf_steps(const LeafSteps& steps, int levels, std::int64_t filled_pixels) {
  for (const std::vector<std::int64_t>* c : {&steps.bare, &steps.banded, &steps.refined, &steps.balanced})
    if (pixels_of(*c, levels) != filled_pixels)
      throw InternalError(
          fmt::format("quadtree: leaves hold {} pixels but Ω_L has {}", pixels_of(*c, levels), filled_pixels));
}

void check_leaves_per_level(const std::vector<Leaf>& leaves, const std::vector<std::int64_t>& per_level) {
  std::vector<std::int64_t> got(per_level.size(), 0);
  for (const Leaf& f : leaves) {
    if (f.level < 0 || static_cast<std::size_t>(f.level) >= got.size())
      throw InternalError(fmt::format("quadtree: a leaf of level {} outside 0..{}", f.level, got.size() - 1));
    ++got[static_cast<std::size_t>(f.level)];
  }
  if (got != per_level)
    throw InternalError(fmt::format("quadtree: {} leaves per level extracted, the pyramid has {}", fmt::join(got, "/"),
                                    fmt::join(per_level, "/")));
}

void leaf_steps_json(Json& q, const Lattice& lat, const config::QuadtreeOptions& options, std::int64_t filled_pixels,
                     const LeafSteps& steps, std::int64_t violations) {
  q["lattice"] = lat.kind_name();
  q["size_km"] = options.size_km;
  q["coast_size_km"] = options.coast_size_km;
  q["levels"] = lat.levels;
  q["step_deg"] = lat.step0_deg;
  q["coast_band"] = options.coast_band;
  q["balance"] = std::string(name_of(options.balance));
  q["filled_pixels"] = filled_pixels;
  q["leaves_per_level_bare"] = steps.bare;
  q["leaves_per_level_coast_band"] = steps.banded;
  q["leaves_per_level_rules"] = steps.refined;
  q["leaves_per_level"] = steps.balanced;
  q["balance_violations"] = violations;
}

std::vector<Leaf> build_leaves(const Bitmap& filled, const Lattice& lat, const config::QuadtreeOptions& options,
                               const PoleRotation& rotation, const raster::Bathymetry* bathy, const Logger& log,
                               Report* report, const size::SizeField* field, const mask::CoastSources& coast) {
  StageScope stage("quadtree", report, log);
  const BalanceMode mode = options.balance;
  const std::int64_t filled_pixels = filled.count();

  Timer t_masks;
  LevelMasks masks = make_level_masks(filled, lat, 0, coast);
  const std::vector<std::int64_t> bare = count_leaves_per_level(masks);
  if (options.coast_band != 0 && options.coast_size_km == 0.0) apply_coast_band(masks, options.coast_band);
  const std::vector<std::int64_t> banded = count_leaves_per_level(masks);
  const double masks_s = t_masks.wall_s();
  throw_if_cancelled();  // between the steps (core/cancel.hpp)

  Timer t_rules;
  apply_refinement_rules(masks, lat, options, rotation, bathy);
  if (field != nullptr) {
    apply_size_field(masks, lat, *field);
  } else if (options.size_km != 0.0 || options.coast_size_km != 0.0 ||
             size::has_size_rules(options)) {  // the size keys of [quadtree] alone
    config::GlobalConfig only;
    only.quadtree = options;
    apply_size_field(masks, lat,
                     size::build_size_field(filled, lat, only, rotation, bathy, Logger::null(), nullptr, coast));
  }
  GradeStats grade;
  if (field != nullptr) grade = grade_levels(masks, lat, *field);
  const std::vector<std::int64_t> refined = count_leaves_per_level(masks);
  const double rules_s = t_rules.wall_s();
  throw_if_cancelled();

  Timer t_balance;
  const BalanceStats bstats = balance(masks, mode);
  const std::vector<std::int64_t> balanced = count_leaves_per_level(masks);
  const double balance_s = t_balance.wall_s();
  throw_if_cancelled();

  Timer t_extract;
  std::vector<Leaf> leaves = extract_leaves(masks, lat);
  const double extract_s = t_extract.wall_s();
  throw_if_cancelled();

  // The checks: the balance on the pyramid the leaves were read from (the pyramid rebuilt from
  // the leaves, masks_from_leaves, is the same bitmaps: building it again cost more than the
  // count), and the leaves per level against the pyramid's.
  Timer t_check;
  const LeafSteps steps{bare, banded, refined, balanced};
  check_leaf_steps(steps, lat.levels, filled_pixels);
  const std::int64_t violations = count_balance_violations(masks, mode);
  masks = LevelMasks{};
  check_leaves_per_level(leaves, balanced);
  if (violations != 0) {
    throw InternalError(fmt::format("quadtree: {} {}-balance violations left after smoothing", violations, mode));
  }
  const double check_s = t_check.wall_s();

  const Json depth_rules = rules_json(options.depth_rules, "depth_rules", lat, log);
  const Json box_rules = rules_json(options.box_rules, "box_rules", lat, log);
  std::string size_line;
  std::vector<double> targets;
  for (const double t : {options.size_km, options.coast_size_km})
    if (t > 0.0) targets.push_back(t);
  const Json size_bands = size_bands_json(leaves, lat, targets, size_line);
  if (lat.mercator() || options.size_km > 0.0 || options.coast_size_km > 0.0)
    log.info("quadtree: leaf size km (min/median/max) by |φ′| band:{}", size_line);
  Json grading_json;
  if (field != nullptr && field->has_grid()) {
    // On a map as fine as 2^25 cells (bytes) allow: the field's own grid may be level 0 on fine lattices.
    const Grading gr = achieved_grading(leaves, lat, size::choose_grid_level(lat, -1, std::int64_t{1} << 25));
    grading_json = Json{{"map_level", gr.map_level},
                        {"gradation", field->gradation()},
                        {"grading_splits", grade.splits},
                        {"cfl_refused_splits", grade.cfl_refused},
                        {"runs", gr.runs},
                        {"median", round3(gr.median)},
                        {"p90", round3(gr.p90)},
                        {"max", round3(gr.max)},
                        {"definition", "a/(sqrt2 * D) over runs of one level between a finer and a coarser one "
                                       "(a: the level's square size, D: the run's length); 2:1 balance alone: 0.71"}};
    log.info("quadtree: achieved grading {:.3f} median, {:.3f} p90, {:.3f} max over {} level runs (size.gradation = {}; "
             "{} squares split to keep it{})",
             gr.median, gr.p90, gr.max, gr.runs, field->gradation(), grade.splits,
             grade.cfl_refused > 0 ? fmt::format(", {} splits refused by the CFL bound", grade.cfl_refused) : std::string());
  }
  if (report != nullptr) {
    Json& q = (*report)["quadtree"];
    if (!grading_json.is_null()) q["grading"] = grading_json;
    leaf_steps_json(q, lat, options, filled_pixels, steps, violations);
    q["size_by_latitude"] = size_bands;
    q["depth_rules"] = depth_rules;
    q["box_rules"] = box_rules;
    q["leaves"] = leaves.size();
    q["balance_forced_splits"] = bstats.forced_splits;
    q["timings_s"] = Json{{"masks", round3(masks_s)},
                          {"rules", round3(rules_s)},
                          {"balance", round3(balance_s)},
                          {"extract", round3(extract_s)},
                          {"check", round3(check_s)}};
  }
  stage.done(fmt::format("{} leaves (levels 0..{}: {}), {}-balanced", leaves.size(), lat.levels,
                         fmt::join(balanced, "/"), mode));
  return leaves;
}

}  // namespace aq::quadtree
