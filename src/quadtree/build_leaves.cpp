// The quadtree stage driver (see build_leaves.hpp).
#include "quadtree/build_leaves.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.hpp"
#include "core/timer.hpp"
#include "quadtree/balance.hpp"

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

}  // namespace

std::vector<Leaf> build_leaves(const Bitmap& filled, const Lattice& lat, const config::QuadtreeOptions& options,
                               const PoleRotation& rotation, const raster::Bathymetry* bathy, const Logger& log,
                               Report* report) {
  StageScope stage("quadtree", report, log);
  const BalanceMode mode = parse_balance_mode(options.balance);
  const std::int64_t filled_pixels = filled.count();

  Timer t_masks;
  LevelMasks masks = make_level_masks(filled, lat, 0);
  const std::vector<std::int64_t> bare = count_leaves_per_level(masks);
  if (options.coast_band != 0) apply_coast_band(masks, options.coast_band);
  const std::vector<std::int64_t> banded = count_leaves_per_level(masks);
  const double masks_s = t_masks.wall_s();

  Timer t_rules;
  apply_refinement_rules(masks, lat, options, rotation, bathy);
  const std::vector<std::int64_t> refined = count_leaves_per_level(masks);
  const double rules_s = t_rules.wall_s();

  Timer t_balance;
  const BalanceStats bstats = balance(masks, mode);
  const std::vector<std::int64_t> balanced = count_leaves_per_level(masks);
  const double balance_s = t_balance.wall_s();

  Timer t_extract;
  std::vector<Leaf> leaves = extract_leaves(masks, lat);
  const double extract_s = t_extract.wall_s();
  masks = LevelMasks{};

  Timer t_check;
  for (const std::vector<std::int64_t>* c : {&bare, &banded, &refined, &balanced}) {
    if (pixels_of(*c, lat.levels) != filled_pixels) {
      throw InternalError(
          fmt::format("quadtree: leaves hold {} pixels but Ω_L has {}", pixels_of(*c, lat.levels), filled_pixels));
    }
  }
  const std::int64_t violations = count_balance_violations(leaves, lat, mode);
  if (violations != 0) {
    throw InternalError(
        fmt::format("quadtree: {} {}-balance violations left after smoothing", violations, balance_mode_name(mode)));
  }
  const double check_s = t_check.wall_s();

  if (report != nullptr) {
    Json& q = (*report)["quadtree"];
    q["levels"] = lat.levels;
    q["step_deg"] = lat.step0_deg;
    q["coast_band"] = options.coast_band;
    q["balance"] = std::string(balance_mode_name(mode));
    q["depth_rules"] = options.depth_rules.size();
    q["box_rules"] = options.box_rules.size();
    q["filled_pixels"] = filled_pixels;
    q["leaves_per_level_bare"] = bare;
    q["leaves_per_level_coast_band"] = banded;
    q["leaves_per_level_rules"] = refined;
    q["leaves_per_level"] = balanced;
    q["leaves"] = leaves.size();
    q["balance_forced_splits"] = bstats.forced_splits;
    q["balance_violations"] = violations;
    q["timings_s"] = Json{{"masks", round3(masks_s)},
                          {"rules", round3(rules_s)},
                          {"balance", round3(balance_s)},
                          {"extract", round3(extract_s)},
                          {"check", round3(check_s)}};
  }
  stage.done(fmt::format("{} leaves (levels 0..{}: {}), {}-balanced", leaves.size(), lat.levels,
                         fmt::join(balanced, "/"), balance_mode_name(mode)));
  return leaves;
}

}  // namespace aq::quadtree
