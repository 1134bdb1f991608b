// SPDX-License-Identifier: GPL-3.0-or-later
// The key table of the global run (ARCHITECTURE §7) and its validation. Adding a key here
// without documenting it in configs/example.toml fails tests/unit/config/example_toml_test.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <fmt/ranges.h>

#include "config/load.hpp"
#include "config/schema.hpp"
#include "core/lattice.hpp"

namespace aq::config {

namespace {

using detail::Origin;
using detail::Problems;
using S = detail::Schema<GlobalConfig>;

// mask.min_depth_m's lowest value: a floodplain up to 100 m above the datum. Surge meshes reach
// +10 to +20 m, tsunami inundation tens of metres; land higher than that is no floodplain (and a
// typo such as -5000 for 5000 would mesh the continents).
constexpr double kMinDepthLowest = -100.0;

std::string in_range(double v, double lo, double hi) {
  if (!std::isfinite(v) || v < lo || v > hi) return fmt::format("{} is outside [{}, {}]", v, lo, hi);
  return {};
}

template <typename V>
std::function<V&(GlobalConfig&)> F(V& (*f)(GlobalConfig&)) {
  return f;
}

// A number field of a depth or box rule (every field but level / size_km).
template <typename R>
struct RuleField {
  const char* name;
  double R::*member;
};

constexpr std::array<RuleField<DepthRule>, 2> kDepthRuleFields{
    {{"min_depth_m", &DepthRule::min_depth_m}, {"max_depth_m", &DepthRule::max_depth_m}}};
constexpr std::array<RuleField<BoxRule>, 4> kBoxRuleFields{{{"lon_min_deg", &BoxRule::lon_min_deg},
                                                            {"lon_max_deg", &BoxRule::lon_max_deg},
                                                            {"lat_min_deg", &BoxRule::lat_min_deg},
                                                            {"lat_max_deg", &BoxRule::lat_max_deg}}};

std::string depth_range_problem(const DepthRule& r) {
  return r.min_depth_m < r.max_depth_m ? std::string() : "needs min_depth_m < max_depth_m";
}
// A longitude of the configuration: finite and within ±360° (any wider value names no place).
bool lon_ok(double v) { return v >= -360.0 && v <= 360.0; }

std::string box_range_problem(const BoxRule& r) {
  if (r.lon_min_deg < r.lon_max_deg && lon_ok(r.lon_min_deg) && lon_ok(r.lon_max_deg) &&
      r.lat_min_deg < r.lat_max_deg && r.lat_min_deg >= -90 && r.lat_max_deg <= 90)
    return {};
  return "needs -360 <= lon_min_deg < lon_max_deg <= 360 and -90 <= lat_min_deg < lat_max_deg <= 90";
}

// Reads the array of rule tables `key` (quadtree.depth_rules / box_rules): the number fields
// `fields` and exactly one of level (>= 0) and size_km (finite, > 0). Every bad rule is reported,
// named key[index]; `out` is set only when all rules are good.
template <typename R, std::size_t N>
void read_rules(std::vector<R>& out, const toml::value& v, const Origin& o, Problems& p, const std::string& key,
                const std::array<RuleField<R>, N>& fields, std::string (*range_problem)(const R&)) {
  if (!v.is_array()) return p.add(o, key, "expected an array of tables");
  std::string names;
  for (const RuleField<R>& f : fields) names += fmt::format("{}, ", f.name);
  names += "and level or size_km";
  std::vector<R> rules;
  const auto& items = v.as_array();
  for (std::size_t k = 0; k < items.size(); ++k) {
    const std::string at = fmt::format("{}[{}]", key, k);
    if (!items[k].is_table()) {
      p.add(o, at, "expected a table {" + names + "}");
      continue;
    }
    R r;
    bool has_level = false, has_size = false, good = true;
    for (const auto& [field_name, x] : items[k].as_table()) {
      const std::string& name = field_name;  // clang before 16 cannot capture a structured binding
      const auto f = std::find_if(fields.begin(), fields.end(), [&](const RuleField<R>& g) { return name == g.name; });
      std::optional<std::string> err;
      if (f != fields.end())
        err = detail::convert(x, r.*(f->member));
      else if (name == "level") {
        has_level = true;
        err = detail::convert(x, r.level);
      } else if (name == "size_km") {
        has_size = true;
        err = detail::convert(x, r.size_km);
      } else {
        err = "unknown field '" + name + "' (" + names + ")";
      }
      if (err) p.add(o, at + "." + name, *err);
      good = good && !err;
    }
    if (!good) continue;
    if (const std::string range = range_problem(r); !range.empty()) p.add(o, at, range);
    if (has_level == has_size)
      p.add(o, at, has_level ? "gives both level and size_km: give one of them" : "needs level or size_km");
    else if (has_level && r.level < 0)
      p.add(o, at + ".level", fmt::format("{} is below 0", r.level));
    else if (has_size && !(std::isfinite(r.size_km) && r.size_km > 0.0))
      p.add(o, at + ".size_km", fmt::format("{} is not a finite number > 0 (km)", r.size_km));
    rules.push_back(r);
  }
  if (rules.size() == items.size()) out = std::move(rules);
}

// A rule as the user gave it: its fields, then level or size_km.
template <typename R, std::size_t N>
Json rule_json(const R& r, const std::array<RuleField<R>, N>& fields) {
  Json j = Json::object();
  for (const RuleField<R>& f : fields) j[f.name] = r.*(f.member);
  if (r.size_km != 0.0)
    j["size_km"] = r.size_km;
  else
    j["level"] = r.level;
  return j;
}

template <typename R>
Json rules_json(const std::vector<R>& rules) {
  Json a = Json::array();
  for (const R& r : rules) a.push_back(config::rule_json(r));
  return a;
}

void add_rules(S& s) {
  s.add_custom(
      "quadtree", "depth_rules",
      [](GlobalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
        read_rules(c.quadtree.depth_rules, v, o, p, "quadtree.depth_rules", kDepthRuleFields, depth_range_problem);
      },
      [](const GlobalConfig& c) { return rules_json(c.quadtree.depth_rules); },
      "minimum level (or size target in km) in depth bands");
  s.add_custom(
      "quadtree", "box_rules",
      [](GlobalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
        read_rules(c.quadtree.box_rules, v, o, p, "quadtree.box_rules", kBoxRuleFields, box_range_problem);
      },
      [](const GlobalConfig& c) { return rules_json(c.quadtree.box_rules); },
      "minimum level (or size target in km) inside lon/lat boxes");
}

const S& schema() {
  static const S s = [] {
    S t;
    // [input]
    t.add_custom(
        "input", "path",
        [](GlobalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
          std::string x;
          if (auto err = detail::convert(v, x)) return p.add(o, "input.path", *err);
          if (x.empty()) return p.add(o, "input.path", "must not be empty");
          // "~/..." is the user's home (configs/global_15s.toml names the cached 15" raster so).
          const char* home = std::getenv("HOME");
          if (x.rfind("~/", 0) == 0 && home != nullptr && *home != '\0') x = std::string(home) + x.substr(1);
          std::filesystem::path path(x);
          if (path.is_relative()) path = o.base_dir / path;
          c.input.path = path.lexically_normal().string();
          c.input.path_layer = o.line == detail::kOverrideLine ? 2 : 1;
          if (const std::string bad = detail::input_path_problem(c.input.path); !bad.empty())
            p.add(o, "input.path", bad);
        },
        [](const GlobalConfig& c) { return Json(c.input.path); }, "bathymetry raster");
    t.add_custom(
        "input", "paths",
        [](GlobalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
          const std::string example = R"(expected a list of raster paths, highest priority first, e.g. ["coastal_survey.tif", "gebco.nc"])";
          if (!v.is_array()) return p.add(o, "input.paths", example);
          const auto& items = v.as_array();
          if (items.empty()) return p.add(o, "input.paths", "[] is empty: " + example);
          std::vector<std::string> paths;
          bool good = true;
          for (std::size_t k = 0; k < items.size(); ++k) {
            const std::string at = fmt::format("input.paths[{}]", k);
            std::string x;
            if (auto err = detail::convert(items[k], x)) {
              p.add(o, at, *err);
              good = false;
              continue;
            }
            if (x.empty()) {
              p.add(o, at, "must not be empty");
              good = false;
              continue;
            }
            const std::string given = x;
            const char* home = std::getenv("HOME");
            if (x.rfind("~/", 0) == 0 && home != nullptr && *home != '\0') x = std::string(home) + x.substr(1);
            std::filesystem::path path(x);
            if (path.is_relative()) path = o.base_dir / path;
            x = path.lexically_normal().string();
            if (const std::string bad = detail::input_path_problem(x); !bad.empty()) {
              p.add(o, at, bad);
              good = false;
            }
            const auto same = std::find(paths.begin(), paths.end(), x);
            if (same != paths.end()) {
              p.add(o, at, fmt::format("\"{}\" repeats input.paths[{}]", given, same - paths.begin()));
              good = false;
            }
            paths.push_back(x);
          }
          if (good) c.input.paths = std::move(paths);
          c.input.paths_layer = o.line == detail::kOverrideLine ? 2 : 1;
        },
        [](const GlobalConfig& c) { return Json(c.input.sources()); }, "bathymetry rasters, highest priority first");
    t.add<double>(
        "input", "blend_km", [](GlobalConfig& c) -> double& { return c.input.blend_km; },
        [](const double& v) { return in_range(v, 0.0, 1000.0); }, "blend width at source edges (km)");
    t.add<std::string>(
        "input", "variable", [](GlobalConfig& c) -> std::string& { return c.input.variable; }, {}, "netCDF variable");
    t.add<int>(
        "input", "band", [](GlobalConfig& c) -> int& { return c.input.band; },
        [](const int& v) { return v >= 1 ? std::string() : fmt::format("{} must be >= 1", v); }, "band");
    t.add<bool>(
        "input", "positive_down", [](GlobalConfig& c) -> bool& { return c.input.positive_down; }, {}, "");
    t.add<Interpolation>(
        "input", "interpolation", [](GlobalConfig& c) -> Interpolation& { return c.input.interpolation; }, {},
        "sampling between raster points");
    t.add<double>(
        "input", "max_memory_gb", [](GlobalConfig& c) -> double& { return c.input.max_memory_gb; },
        [](const double& v) { return in_range(v, 0.0, 1e6); }, "");
    t.add<double>(
        "input", "max_abs_elevation_m", [](GlobalConfig& c) -> double& { return c.input.max_abs_elevation_m; },
        [](const double& v) { return in_range(v, 100.0, 1e6); }, "");
    // [mask]
    // h < 0 keeps a floodplain above the datum (down to kMinDepthLowest); the stages do not check it again.
    t.add<double>(
        "mask", "min_depth_m", [](GlobalConfig& c) -> double& { return c.mask.min_depth_m; },
        [](const double& v) { return in_range(v, kMinDepthLowest, 12000.0); }, "h");
    t.add<int>(
        "mask", "cursor", [](GlobalConfig& c) -> int& { return c.mask.cursor; },
        [](const int& v) { return in_range(v, 1, 64); }, "K");
    t.add<std::vector<std::array<double, 2>>>(
        "mask", "seeds", [](GlobalConfig& c) -> std::vector<std::array<double, 2>>& { return c.mask.seeds; },
        [](const std::vector<std::array<double, 2>>& v) {
          if (v.empty()) return std::string("at least one seed [lon, lat] is needed");
          for (std::size_t k = 0; k < v.size(); ++k)
            if (!lon_ok(v[k][0]) || !(v[k][1] >= -90 && v[k][1] <= 90))
              return fmt::format("seed {} = [{}, {}]: expected a longitude in [-360, 360] and a latitude in [-90, 90]",
                                 k, v[k][0], v[k][1]);
          return std::string();
        },
        "");
    t.add<double>(
        "mask", "seed_radius_deg", [](GlobalConfig& c) -> double& { return c.mask.seed_radius_deg; },
        [](const double& v) { return in_range(v, 0.0, 180.0); }, "");
    t.add<Sampling>(
        "mask", "sampling", [](GlobalConfig& c) -> Sampling& { return c.mask.sampling; }, {}, "what makes a pixel wet");
    t.add<bool>(
        "mask", "remove_pinches", [](GlobalConfig& c) -> bool& { return c.mask.remove_pinches; }, {}, "");
    t.add<bool>(
        "mask", "passages", [](GlobalConfig& c) -> bool& { return c.mask.passages; }, {}, "");
    t.add<std::vector<std::string>>(
        "mask", "passages_open", [](GlobalConfig& c) -> std::vector<std::string>& { return c.mask.passages_open; },
        [](const std::vector<std::string>& v) {
          for (std::size_t k = 0; k < v.size(); ++k) {
            if (v[k].empty()) return fmt::format("element {} is empty: give a passage name, e.g. \"Gibraltar\"", k);
            for (std::size_t q = 0; q < k; ++q)
              if (v[q] == v[k]) return fmt::format("\"{}\" is given twice", v[k]);
          }
          return std::string();
        },
        "passages of the built-in table carved open");
    const auto line_file = [&t](const char* name, std::string& (*f)(GlobalConfig&)) {
      t.add_custom(
          "mask", name,
          [name, f](GlobalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
            const std::string key = std::string("mask.") + name;
            std::string text;
            if (auto err = detail::convert(v, text)) return p.add(o, key, *err);
            std::filesystem::path path(text);
            if (!text.empty() && path.is_relative()) path = o.base_dir / path;
            f(c) = text.empty() ? text : path.lexically_normal().string();
            if (!text.empty())
              if (const std::string bad = detail::input_path_problem(f(c)); !bad.empty()) p.add(o, key, bad);
          },
          [f](const GlobalConfig& c) { return Json(f(const_cast<GlobalConfig&>(c))); }, "");
    };
    line_file("transects", [](GlobalConfig& c) -> std::string& { return c.mask.transects; });
    t.add<std::string>(
        "mask", "transects_layer", [](GlobalConfig& c) -> std::string& { return c.mask.transects_layer; }, {}, "");
    line_file("channels", [](GlobalConfig& c) -> std::string& { return c.mask.channels; });
    t.add<std::string>(
        "mask", "channels_layer", [](GlobalConfig& c) -> std::string& { return c.mask.channels_layer; }, {}, "");
    t.add<double>(
        "mask", "channel_width_m", [](GlobalConfig& c) -> double& { return c.mask.channel_width_m; },
        [](const double& v) { return in_range(v, 0.0, 1e6); }, "");
    t.add<double>(
        "mask", "channel_depth_m", [](GlobalConfig& c) -> double& { return c.mask.channel_depth_m; },
        [](const double& v) { return in_range(v, 0.01, 12000.0); }, "");
    t.add<double>(
        "mask", "warn_dropped_km2", [](GlobalConfig& c) -> double& { return c.mask.warn_dropped_km2; },
        [](const double& v) { return in_range(v, 0.0, 1e9); }, "");
    // [quadtree]
    t.add<double>(
        "quadtree", "step_deg", [](GlobalConfig& c) -> double& { return c.quadtree.step_deg; },
        [](const double& v) {
          const std::string problem = Lattice::step_problem(v);
          return problem.empty() ? problem : fmt::format("{}: {}", v, problem);
        },
        "");
    t.add<int>(
        "quadtree", "levels", [](GlobalConfig& c) -> int& { return c.quadtree.levels; },
        [](const int& v) { return in_range(v, 0, 20); }, "");
    t.add<int>(
        "quadtree", "coast_band", [](GlobalConfig& c) -> int& { return c.quadtree.coast_band; },
        [](const int& v) { return in_range(v, 0, 64); }, "");
    t.add<BalanceMode>(
        "quadtree", "balance", [](GlobalConfig& c) -> BalanceMode& { return c.quadtree.balance; }, {},
        "the neighbours 2:1 smoothing holds");
    t.add<double>(
        "quadtree", "lon0_deg", [](GlobalConfig& c) -> double& { return c.quadtree.lon0_deg; },
        [](const double& v) { return in_range(v, -360.0, 360.0); }, "");
    t.add<LatticeKind>(
        "quadtree", "lattice", [](GlobalConfig& c) -> LatticeKind& { return c.quadtree.lattice; }, {},
        "the lattice's rows");
    t.add<QuadtreeEngine>(
        "quadtree", "engine", [](GlobalConfig& c) -> QuadtreeEngine& { return c.quadtree.engine; }, {},
        "what holds the quadtree");
    t.add<double>(
        "quadtree", "mercator_lat_max_deg", [](GlobalConfig& c) -> double& { return c.quadtree.mercator_lat_max_deg; },
        [](const double& v) { return in_range(v, 1.0, 89.5); }, "");
    t.add<double>(
        "quadtree", "size_km", [](GlobalConfig& c) -> double& { return c.quadtree.size_km; },
        [](const double& v) { return in_range(v, 0.0, 1e5); }, "");
    t.add<double>(
        "quadtree", "coast_size_km", [](GlobalConfig& c) -> double& { return c.quadtree.coast_size_km; },
        [](const double& v) { return in_range(v, 0.0, 1e5); }, "");
    add_rules(t);
    // [size] and its sub-tables
    const auto size_num = [&t](const char* sec, const char* name, double& (*f)(GlobalConfig&), double lo, double hi) {
      t.add<double>(sec, name, F(f), [lo, hi](const double& v) { return in_range(v, lo, hi); }, "");
    };
    size_num("size", "h_min_km", [](GlobalConfig& c) -> double& { return c.size.h_min_km; }, 0.0, 1e5);
    size_num("size", "h_max_km", [](GlobalConfig& c) -> double& { return c.size.h_max_km; }, 0.0, 1e5);
    size_num("size", "gradation", [](GlobalConfig& c) -> double& { return c.size.gradation; }, 0.0, 10.0);
    size_num("size", "min_depth_m", [](GlobalConfig& c) -> double& { return c.size.min_depth_m; }, 0.01, 1e4);
    t.add<int>(
        "size", "grid_level", [](GlobalConfig& c) -> int& { return c.size.grid_level; },
        [](const int& v) { return in_range(v, -1, 20); }, "");
    t.add_custom(
        "size", "raster",
        [](GlobalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
          std::string text;
          if (auto err = detail::convert(v, text)) return p.add(o, "size.raster", *err);
          std::filesystem::path path(text);
          if (!text.empty() && path.is_relative()) path = o.base_dir / path;
          c.size.raster = text.empty() ? text : path.lexically_normal().string();
          // A FIFO or a directory is refused before GDAL opens it (a FIFO would block it).
          if (const std::string bad = detail::input_path_problem(c.size.raster); !text.empty() && !bad.empty())
            p.add(o, "size.raster", bad);
        },
        [](const GlobalConfig& c) { return Json(c.size.raster); }, "");
    size_num("size.coast", "h0_km", [](GlobalConfig& c) -> double& { return c.size.coast.h0_km; }, 0.0, 1e5);
    size_num("size.coast", "alpha", [](GlobalConfig& c) -> double& { return c.size.coast.alpha; }, 0.0, 10.0);
    size_num("size.feature", "r", [](GlobalConfig& c) -> double& { return c.size.feature.r; }, 0.0, 1e3);
    size_num("size.wavelength", "wl", [](GlobalConfig& c) -> double& { return c.size.wavelength.wl; }, 0.0, 1e4);
    size_num("size.wavelength", "period_h", [](GlobalConfig& c) -> double& { return c.size.wavelength.period_h; },
             0.01, 1e4);
    size_num("size.slope", "slp", [](GlobalConfig& c) -> double& { return c.size.slope.slp; }, 0.0, 1e4);
    size_num("size.slope", "filter", [](GlobalConfig& c) -> double& { return c.size.slope.filter; }, 0.0, 100.0);
    size_num("size.slope", "filter_max_km", [](GlobalConfig& c) -> double& { return c.size.slope.filter_max_km; },
             0.0, 1e4);
    size_num(
        "size.inland", "h0_km", [](GlobalConfig& c) -> double& { return c.size.inland.h0_km; }, 0.0, 1e5);
    size_num(
        "size.inland", "alpha", [](GlobalConfig& c) -> double& { return c.size.inland.alpha; }, 0.0, 10.0);
    size_num(
        "size.elevation", "h0_km", [](GlobalConfig& c) -> double& { return c.size.elevation.h0_km; }, 0.0, 1e5);
    size_num(
        "size.elevation", "km_per_m", [](GlobalConfig& c) -> double& { return c.size.elevation.km_per_m; }, 0.0, 1e3);
    size_num("size.cfl", "dt_s", [](GlobalConfig& c) -> double& { return c.size.cfl.dt_s; }, 0.0, 1e6);
    size_num("size.cfl", "courant_max", [](GlobalConfig& c) -> double& { return c.size.cfl.courant_max; }, 1e-3,
             100.0);
    size_num("size.cfl", "velocity_ms", [](GlobalConfig& c) -> double& { return c.size.cfl.velocity_ms; }, 0.0,
             100.0);
    // [domain]
    t.add<DomainKind>(
        "domain", "kind", [](GlobalConfig& c) -> DomainKind& { return c.domain.kind; }, {}, "what is meshed");
    t.add<std::vector<double>>(
        "domain", "box", [](GlobalConfig& c) -> std::vector<double>& { return c.domain.box; },
        [](const std::vector<double>& v) {
          if (v.empty()) return std::string();
          for (const double x : v)
            if (!std::isfinite(x)) return std::string("expected 4 finite numbers [lon_min, lon_max, lat_min, lat_max]");
          if (v.size() != 4 || !(v[2] < v[3]) || v[2] < -90 || v[3] > 90 || v[0] == v[1] ||
              std::abs(v[0]) > 360.0 || std::abs(v[1]) > 360.0)
            return std::string(
                "expected [lon_min, lon_max, lat_min, lat_max] with -90 <= lat_min < lat_max <= 90, lon_min != lon_max "
                "(lon_max < lon_min: the box crosses the seam), |lon| <= 360");
          double w = v[1] - v[0];
          if (w < 0.0) w += 360.0;
          if (!(w < 360.0)) return std::string("the box spans 360° of longitude or more: use kind = \"global\"");
          // lon_max < lon_min reads as a box across the seam; a wide one is more likely the two
          // bounds swapped ([10, -5] for [-5, 10]), so it must be written unambiguously.
          if (v[1] < v[0] && w > 180.0) {
            const double west = v[1] + 360.0 <= 360.0 ? v[0] : v[0] - 360.0;
            const double east = v[1] + 360.0 <= 360.0 ? v[1] + 360.0 : v[1];
            return fmt::format(
                "lon_min = {} > lon_max = {} reads as a box across the seam {}° wide (east from {}° to {}°); a box "
                "across the seam wider than 180° is refused as ambiguous: for the {}° from {}° to {}° write "
                "[{}, {}, {}, {}] (lon_max > lon_min), for that seam-crossing box write [{}, {}, {}, {}]",
                v[0], v[1], w, v[0], v[1], 360.0 - w, v[1], v[0], v[1], v[0], v[2], v[3], west, east, v[2], v[3]);
          }
          return std::string();
        },
        "");
    t.add_custom(
        "domain", "polygon",
        [](GlobalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
          std::string text;
          if (auto err = detail::convert(v, text)) return p.add(o, "domain.polygon", *err);
          std::filesystem::path path(text);
          if (!text.empty() && path.is_relative()) path = o.base_dir / path;
          c.domain.polygon = text.empty() ? text : path.lexically_normal().string();
          // A FIFO would block OGR for ever (a shapefile's folder is a directory OGR reads: allowed).
          std::error_code ec;
          if (!text.empty() && !std::filesystem::is_directory(c.domain.polygon, ec))
            if (const std::string bad = detail::input_path_problem(c.domain.polygon); !bad.empty())
              p.add(o, "domain.polygon", bad);
        },
        [](const GlobalConfig& c) { return Json(c.domain.polygon); }, "");
    t.add<std::string>(
        "domain", "layer", [](GlobalConfig& c) -> std::string& { return c.domain.layer; }, {}, "");
    t.add<int>(
        "domain", "feature", [](GlobalConfig& c) -> int& { return c.domain.feature; },
        [](const int& v) { return in_range(v, -1, 1000000000); }, "");
    t.add<std::string>(
        "domain", "where", [](GlobalConfig& c) -> std::string& { return c.domain.where; }, {}, "");
    // [rotation]
    t.add<bool>(
        "rotation", "enabled", [](GlobalConfig& c) -> bool& { return c.rotation.enabled; }, {}, "");
    t.add<double>(
        "rotation", "pole_lon_deg", [](GlobalConfig& c) -> double& { return c.rotation.pole_lon_deg; },
        [](const double& v) { return in_range(v, -360.0, 360.0); }, "");
    t.add<double>(
        "rotation", "pole_lat_deg", [](GlobalConfig& c) -> double& { return c.rotation.pole_lat_deg; },
        [](const double& v) { return in_range(v, -90.0, 90.0); }, "");
    // [mesh]
    t.add<ElementKinds>(
        "mesh", "elements", [](GlobalConfig& c) -> ElementKinds& { return c.mesh.elements; }, {},
        "the elements of the mesh");
    t.add<Diagonal>(
        "mesh", "diagonal", [](GlobalConfig& c) -> Diagonal& { return c.mesh.diagonal; }, {},
        "the diagonal of squares without midside nodes");
    // [output]
    t.add<std::string>(
        "output", "dir", [](GlobalConfig& c) -> std::string& { return c.output.dir; },
        [](const std::string& v) { return v.empty() ? std::string("must not be empty") : output_dir_problem(v); }, "");
    t.add<std::string>(
        "output", "name", [](GlobalConfig& c) -> std::string& { return c.output.name; },
        [](const std::string& v) { return output_name_problem(v); }, "");
    t.add<std::vector<OutputFormat>>(
        "output", "formats", [](GlobalConfig& c) -> std::vector<OutputFormat>& { return c.output.formats; }, {},
        "the files written");
    t.add<bool>(
        "output", "msh_binary", [](GlobalConfig& c) -> bool& { return c.output.msh_binary; }, {}, "");
    t.add<int>(
        "output", "ugrid_deflate", [](GlobalConfig& c) -> int& { return c.output.ugrid_deflate; },
        [](const int& v) { return in_range(v, 0, 9); }, "");
    t.add<VtuCoordinates>(
        "output", "vtu_coordinates", [](GlobalConfig& c) -> VtuCoordinates& { return c.output.vtu_coordinates; }, {},
        "where the VTU points are");
    t.add<int>(
        "output", "png_width", [](GlobalConfig& c) -> int& { return c.output.png_width; },
        [](const int& v) { return in_range(v, 200, 20000); }, "");
    t.add<std::vector<double>>(
        "output", "png_zoom", [](GlobalConfig& c) -> std::vector<double>& { return c.output.png_zoom; },
        [](const std::vector<double>& v) {
          if (v.empty()) return std::string();
          const bool finite = std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
          if (v.size() != 4 || !finite || !lon_ok(v[0]) || !lon_ok(v[1]) || !(v[0] < v[1]) || v[1] - v[0] > 360.0 ||
              !(v[2] < v[3]) || v[2] < -90 || v[3] > 90)
            return std::string(
                "expected 4 finite numbers [lon_min, lon_max, lat_min, lat_max] with -360 <= lon_min < lon_max <= "
                "lon_min + 360, lon_max <= 360 and -90 <= lat_min < lat_max <= 90");
          return std::string();
        },
        "");
    t.add<PreviewColour>(
        "output", "png_color", [](GlobalConfig& c) -> PreviewColour& { return c.output.png_color; }, {},
        "what fills the preview's elements");
    t.add<std::vector<double>>(
        "output", "fesom_levels", [](GlobalConfig& c) -> std::vector<double>& { return c.output.fesom_levels; },
        [](const std::vector<double>& v) {
          if (v.empty()) return std::string();
          if (v.size() < 5)
            return std::string("expected at least 5 depth levels (FESOM raises shallower nodes to the 5th)");
          if (v[0] != 0.0) return std::string("the first level must be 0 (the surface)");
          for (std::size_t k = 1; k < v.size(); ++k)
            if (!std::isfinite(v[k]) || !(v[k] > v[k - 1]))
              return fmt::format(
                  "levels must be depths in metres, positive down and strictly increasing (level {} = {})", k + 1,
                  v[k]);
          return std::string();
        },
        "");
    // [blocks]
    t.add<int>(
        "blocks", "top", [](GlobalConfig& c) -> int& { return c.blocks.top; },
        [](const int& v) { return in_range(v, 1, 999); }, "");
    t.add<std::vector<std::array<double, 4>>>(
        "blocks", "boxes", [](GlobalConfig& c) -> std::vector<std::array<double, 4>>& { return c.blocks.boxes; },
        [](const std::vector<std::array<double, 4>>& v) {
          for (std::size_t k = 0; k < v.size(); ++k) {
            const auto& b = v[k];
            if (!lon_ok(b[0]) || !lon_ok(b[1]) || !(b[0] < b[1]) || b[1] - b[0] > 180.0 || !(b[2] < b[3]) ||
                b[2] < -90.0 || b[3] > 90.0)
              return fmt::format(
                  "box {} = [{}, {}, {}, {}]: expected [lon_min, lon_max, lat_min, lat_max] with "
                  "-360 <= lon_min < lon_max <= lon_min + 180, lon_max <= 360 and -90 <= lat_min < lat_max <= 90",
                  k, b[0], b[1], b[2], b[3]);
          }
          return std::string();
        },
        "");
    t.add<bool>(
        "blocks", "shrink_to_wet", [](GlobalConfig& c) -> bool& { return c.blocks.shrink_to_wet; }, {}, "");
    t.add<double>(
        "blocks", "max_inset", [](GlobalConfig& c) -> double& { return c.blocks.max_inset; },
        [](const double& v) { return in_range(v, 0.0, 0.45); }, "");
    t.add<int>(
        "blocks", "ny", [](GlobalConfig& c) -> int& { return c.blocks.ny; },
        [](const int& v) { return in_range(v, 0, 100000); }, "");
    t.add<int>(
        "blocks", "refinement", [](GlobalConfig& c) -> int& { return c.blocks.refinement; },
        [](const int& v) { return in_range(v, 1, 1000); }, "");
    t.add<int>(
        "blocks", "points_per_side", [](GlobalConfig& c) -> int& { return c.blocks.points_per_side; },
        [](const int& v) { return in_range(v, 2, 64); }, "");
    return t;
  }();
  return s;
}

// The level form of a rule asks at most quadtree.levels (a size rule asks at most level L).
template <typename R>
void check_rule_levels(const std::vector<R>& rules, const char* key, int levels, Problems& p) {
  for (std::size_t k = 0; k < rules.size(); ++k)
    if (rules[k].size_km == 0.0 && rules[k].level > levels)
      p.add_keys({fmt::format("{}[{}].level", key, k), "quadtree.levels"},
                 fmt::format("level {} exceeds quadtree.levels = {}", rules[k].level, levels));
}

// Checks that involve several keys, each reported at the position of the key set last.
void cross_check(GlobalConfig& c, Problems& p) {
  // [domain]: the kind from the keys given (README "Regional FE meshes").
  DomainOptions& d = c.domain;
  const bool has_box = !d.box.empty(), has_polygon = !d.polygon.empty();
  switch (d.kind) {
    case DomainKind::kAuto:
      d.resolved = has_polygon ? DomainKind::kPolygon : has_box ? DomainKind::kBox : DomainKind::kGlobal;
      break;
    case DomainKind::kGlobal:
      d.resolved = DomainKind::kGlobal;
      if (has_box || has_polygon)
        p.add_keys({"domain.kind", has_box ? "domain.box" : "domain.polygon"},
                   "domain.kind = \"global\" but domain.box or domain.polygon is set: remove the kind (\"auto\" takes "
                   "the polygon, else the box) or the region");
      break;
    case DomainKind::kBox:
      d.resolved = DomainKind::kBox;
      if (!has_box) p.add_key("domain.kind", "\"box\" needs domain.box = [lon_min, lon_max, lat_min, lat_max]");
      break;
    case DomainKind::kPolygon:
      d.resolved = DomainKind::kPolygon;
      if (!has_polygon)
        p.add_key("domain.kind", "\"polygon\" needs domain.polygon = \"file\" (GeoPackage, GeoJSON, Shapefile, ...)");
      break;
  }
  // input.paths = [input.path] is one raster said twice (configs/example.toml does so); anything
  // else with both keys is ambiguous.
  if (!c.input.paths.empty() && c.input.path_layer != 0 && c.input.path_layer == c.input.paths_layer &&
      c.input.paths != std::vector<std::string>{c.input.path})
    p.add_keys({"input.path", "input.paths"},
               fmt::format("input.path = \"{}\" and input.paths = [{} raster(s)] are both set: give input.path for one "
                           "raster or input.paths for several (highest priority first)",
                           c.input.path, c.input.paths.size()));
  if (c.input.blend_km > 0.0 && c.input.paths.size() < 2)
    p.add_keys({"input.blend_km", "input.paths"},
               fmt::format("input.blend_km = {} blends between sources: it needs input.paths with two or more rasters",
                           c.input.blend_km));
  if (c.input.paths.size() > 1 && c.mask.sampling == Sampling::kArea)
    p.add_keys({"mask.sampling", "input.paths"},
               "mask.sampling = \"area\" reads the cells of one raster: it is not available with several input.paths "
               "(use \"vertex\")");
  if (c.input.paths.size() > 1 && c.input.interpolation == Interpolation::kBicubic)
    p.add_keys({"input.interpolation", "input.paths"},
               "input.interpolation = \"bicubic\" is not available with several input.paths (the spline of one "
               "raster); use \"bilinear\"");
  check_rule_levels(c.quadtree.depth_rules, "quadtree.depth_rules", c.quadtree.levels, p);
  check_rule_levels(c.quadtree.box_rules, "quadtree.box_rules", c.quadtree.levels, p);
  // [size]: the clamp must be an interval.
  if (c.size.h_min_km > 0.0 && c.size.h_max_km > 0.0 && c.size.h_min_km > c.size.h_max_km)
    p.add_keys({"size.h_min_km", "size.h_max_km"},
               fmt::format("size.h_min_km = {} is above size.h_max_km = {}", c.size.h_min_km, c.size.h_max_km));
  for (const KeyProblem& bad : output_problems(c.output, c.mesh.elements)) p.add_keys(bad.keys, bad.text);
  // The floodplain terms size land above the datum: without a floodplain they would size nothing.
  for (const auto& [key, on] : {std::pair{"size.inland.h0_km", c.size.inland.h0_km > 0.0},
                                std::pair{"size.elevation.h0_km", c.size.elevation.h0_km > 0.0}})
    if (on && !(c.mask.min_depth_m < 0.0))
      p.add_keys({key, "mask.min_depth_m"},
                 fmt::format("{} sizes the floodplain (land above the datum inside the mesh), but "
                             "mask.min_depth_m = {} >= 0 meshes none: set mask.min_depth_m = -z to reach "
                             "land up to z m above the datum, or remove {}",
                             key, c.mask.min_depth_m, key));
}

// What the forest engine (quadtree.engine = "forest", README "The forest engine") cannot do, from
// the keys alone. Its patches are P × P pixels, P = 2^min(L, 7) (forest_patch_pixels): the coastal
// band and the K-cursor must fit in one.
void forest_check(const GlobalConfig& c, Problems& p) {
  if (c.quadtree.engine != QuadtreeEngine::kForest) return;
  if (!forest_engine_built())
    return p.add_key("quadtree.engine",
                     "\"forest\": this aquatoria was built without the forest engine (AQ_MPI=OFF: p4est and MPI "
                     "were not found; scripts/install_deps.sh installs them); use \"dense\"");
  if (c.mask.sampling == Sampling::kArea)
    p.add_keys({"mask.sampling", "quadtree.engine"},
               "mask.sampling = \"area\": the forest engine classifies by the vertex rule only; quadtree.engine = "
               "\"dense\" for the area rule");
  if (c.output.writes(OutputFormat::kTif))
    p.add_keys({"output.formats", "quadtree.engine"},
               "output.formats = [..., \"tif\"]: the global run file holds the lattice's bitmaps, which the forest "
               "engine never makes; quadtree.engine = \"dense\" writes it");
  if (c.quadtree.levels < 1)
    return p.add_keys({"quadtree.levels", "quadtree.engine"},
                      "quadtree.levels = 0: the forest engine needs at least one level (quadtree.engine = \"dense\")");
  const std::int64_t patch = forest_patch_pixels(c.quadtree.levels);
  if (c.quadtree.coast_band > patch)
    p.add_keys({"quadtree.coast_band", "quadtree.levels", "quadtree.engine"},
               fmt::format("quadtree.coast_band = {}: the forest engine needs at most {} pixels (its patches of "
                           "2^min(quadtree.levels, {}) pixels); more quadtree.levels, or quadtree.engine = \"dense\"",
                           c.quadtree.coast_band, patch, kForestMaxPatchLog2));
  if (c.mask.cursor > patch)
    p.add_keys({"mask.cursor", "quadtree.levels", "quadtree.engine"},
               fmt::format("mask.cursor = {}: the forest engine needs K <= {} pixels (its patches of "
                           "2^min(quadtree.levels, {}) pixels); more quadtree.levels, or quadtree.engine = \"dense\"",
                           c.mask.cursor, patch, kForestMaxPatchLog2));
}

// output.png_zoom on the Mercator lattice must reach its rows (|φ′| up to mercator_lat_max_deg
// rounded up to whole level-0 squares).
void png_zoom_check(const GlobalConfig& c, Problems& p) {
  const QuadtreeOptions& q = c.quadtree;
  const std::vector<double>& z = c.output.png_zoom;
  if (q.lattice != LatticeKind::kMercator || z.size() != 4 || !Lattice::step_problem(q.step_deg).empty() ||
      !in_range(q.mercator_lat_max_deg, 1.0, 89.5).empty() || !in_range(q.levels, 0, 20).empty() ||
      !std::isfinite(q.lon0_deg))
    return;
  const double cap = Lattice::make_mercator(q.step_deg, q.levels, q.lon0_deg, q.mercator_lat_max_deg).lat_max_deg();
  if (!(std::max(z[2], -cap) < std::min(z[3], cap)))
    p.add_keys({"output.png_zoom", "quadtree.mercator_lat_max_deg", "quadtree.lattice"},
               fmt::format("output.png_zoom: latitudes [{}, {}] are outside the Mercator lattice's rows (|φ′| <= "
                           "{:.4f})",
                           z[2], z[3], cap));
}

// What the command the configuration is loaded for cannot take (load_global's `use`).
void use_check(const GlobalConfig& c, GlobalUse use, Problems& p) {
  if (use == GlobalUse::kMesh) return;
  if (use == GlobalUse::kMask) {
    if (c.quadtree.engine == QuadtreeEngine::kForest)
      p.add_key("quadtree.engine",
                "\"forest\": the mask and levels are the dense engine's bitmaps, which the forest never makes; "
                "quadtree.engine = \"dense\" (a mesh runs on the forest too)");
    return;
  }
  // The blocks become regional ROMS grids (app/regional_roms.cpp); a ROMS grid's mask follows the
  // global fill (land where the elevation is above −h) and its h is clipped at roms.hmin_m, so a
  // floodplain would become water hmin_m deep.
  if (c.mask.min_depth_m < 0.0)
    p.add_key("mask.min_depth_m",
              use == GlobalUse::kBlocks
                  ? fmt::format("mask.min_depth_m = {} meshes a floodplain above the datum; the blocks' regional ROMS "
                                "grids share this run's land mask and cannot hold it: run `aquatoria blocks` with "
                                "mask.min_depth_m >= 0",
                                c.mask.min_depth_m)
                  : fmt::format("mask.min_depth_m = {} meshes a floodplain up to {} m above the datum, which a ROMS "
                                "grid's land mask and depth (clipped at roms.hmin_m) cannot hold: give a global "
                                "config with mask.min_depth_m >= 0",
                                c.mask.min_depth_m, -c.mask.min_depth_m));
  // A ROMS grid's cell depths are statistics over one raster's cells.
  if (use == GlobalUse::kRomsGlobal && c.input.sources().size() > 1)
    p.add_key("input.paths",
              fmt::format("input.paths lists {} rasters; a ROMS grid's cell depths are statistics over one raster's "
                          "cells, so the global run it shares must read one raster (input.path)",
                          c.input.sources().size()));
}

}  // namespace

bool forest_engine_built() {
#ifdef AQ_HAVE_MPI
  return true;
#else
  return false;
#endif
}

std::string output_name_problem(const std::string& name) {
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
    return "must be a plain file name without '/'";
  return {};
}

std::vector<KeyProblem> output_problems(const OutputOptions& o, ElementKinds elements) {
  std::vector<KeyProblem> out;
  // The model formats and the coloured previews are made of triangles.
  if (!has_triangles(elements)) {
    for (const OutputFormat f : {OutputFormat::kFort14, OutputFormat::kFesom, OutputFormat::kSchism})
      if (o.writes(f))
        out.push_back({{"output.formats", "mesh.elements"},
                       fmt::format("\"{}\" needs triangles but mesh.elements = \"squares\" (the model's meshes are "
                                   "triangular; use mesh.elements = \"both\" or drop \"{}\")",
                                   name_of(f), name_of(f))});
    if (o.png_color != PreviewColour::kLevel)
      out.push_back({{"output.png_color", "mesh.elements"},
                     fmt::format("output.png_color = \"{}\" colours triangles but mesh.elements = \"squares\" (use "
                                 "\"level\")",
                                 name_of(o.png_color))});
  }
  return out;
}

Json rule_json(const DepthRule& r) { return rule_json(r, kDepthRuleFields); }
Json rule_json(const BoxRule& r) { return rule_json(r, kBoxRuleFields); }

Loaded<GlobalConfig> load_global(const std::optional<std::string>& path, const std::vector<std::string>& overrides,
                                 GlobalUse use) {
  Loaded<GlobalConfig> out;
  Problems p;
  out.source = "built-in defaults";
  if (path && !path->empty()) {
    const std::filesystem::path file(*path);
    const toml::value doc = detail::parse_file(file);
    std::filesystem::path base = file.parent_path();
    if (base.empty()) base = ".";
    schema().apply(out.options, doc, file.string(), base, p);
    out.source = file.string();
  }
  for (const auto& o : overrides) schema().apply_override(out.options, o, p);
  // --set input.path over a file's input.paths: the one raster replaces the list (the other way
  // round, a non-empty input.paths is used anyway).
  if (out.options.input.path_layer == 2 && out.options.input.paths_layer == 1) out.options.input.paths.clear();
  cross_check(out.options, p);
  forest_check(out.options, p);
  png_zoom_check(out.options, p);
  use_check(out.options, use, p);
  p.throw_if_any(out.source);
  out.echo = schema().echo(out.options);
  return out;
}

RunName default_run_name(const GlobalConfig& c) {
  RunName out;
  const GlobalConfig d;
  const Json now = schema().echo(c), def = schema().echo(d);
  for (const auto& [sec, keys] : now.items()) {
    if (sec == "output" || sec == "blocks") continue;
    for (const auto& [key, value] : keys.items()) {
      if (sec == "quadtree" && key == "engine") continue;  // both engines write the same files
      if (!def.contains(sec) || !def[sec].contains(key) || def[sec][key] != value)
        out.changed.push_back(fmt::format("{}.{} = {}", sec, key, value.dump()));
    }
  }
  if (out.changed.empty()) {
    out.name = "seed_4deg_L3";
    return out;
  }
  // The keys the name below follows.
  static const char* const kNamed[] = {
      "quadtree.step_deg", "quadtree.levels",  "mask.min_depth_m", "mask.cursor",      "rotation.enabled",
      "input.path",        "input.paths",      "input.blend_km",   "quadtree.balance", "quadtree.coast_band",
      "quadtree.lattice",  "quadtree.size_km", "mesh.elements"};
  for (const std::string& k : out.changed) {
    bool named = false;
    for (const char* n : kNamed) named = named || k.rfind(std::string(n) + " =", 0) == 0;
    if (!named) out.unnamed.push_back(k);
  }
  const auto step_s = static_cast<long long>(std::llround(c.quadtree.step_deg * 3600.0));
  const std::string step = step_s % 3600 == 0 ? fmt::format("{}deg", step_s / 3600)
                           : step_s % 60 == 0 ? fmt::format("{}min", step_s / 60)
                                              : fmt::format("{}sec", step_s);
  out.name = fmt::format("global_{}_L{}", step, c.quadtree.levels);
  if (c.mask.min_depth_m != d.mask.min_depth_m) out.name += fmt::format("_h{:g}", c.mask.min_depth_m);
  if (c.mask.cursor != d.mask.cursor) out.name += fmt::format("_K{}", c.mask.cursor);
  if (c.rotation.enabled) out.name += "_rot";
  if (c.domain.resolved == DomainKind::kBox) out.name += "_box";
  if (c.domain.resolved == DomainKind::kPolygon) out.name += "_polygon";
  if (c.input.sources() != d.input.sources()) {
    for (const std::string& source : c.input.sources()) {
      std::string stem = std::filesystem::path(source).stem().string();
      for (char& ch : stem)  // a file-name part: keep letters, digits, '-', '.'
        if (std::isalnum(static_cast<unsigned char>(ch)) == 0 && ch != '-' && ch != '.') ch = '_';
      if (!stem.empty()) out.name += "_" + stem;
    }
  }
  if (c.input.blend_km != d.input.blend_km) out.name += fmt::format("_blend{:g}km", c.input.blend_km);
  if (c.quadtree.balance != d.quadtree.balance) out.name += fmt::format("_{}", name_of(c.quadtree.balance));
  if (c.quadtree.coast_band != d.quadtree.coast_band) out.name += fmt::format("_cb{}", c.quadtree.coast_band);
  if (c.quadtree.lattice != d.quadtree.lattice) out.name += fmt::format("_{}", name_of(c.quadtree.lattice));
  if (c.quadtree.size_km != d.quadtree.size_km) out.name += fmt::format("_s{:g}km", c.quadtree.size_km);
  if (c.mesh.elements != d.mesh.elements) out.name += fmt::format("_{}", name_of(c.mesh.elements));
  return out;
}

std::vector<std::string> global_keys() { return schema().names(); }

std::vector<KeyInfo> global_key_info() { return schema().infos<KeyInfo>(); }

}  // namespace aq::config
