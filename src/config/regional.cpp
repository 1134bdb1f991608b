// SPDX-License-Identifier: GPL-3.0-or-later
// The key table of the regional run. [regional] reuses the izogrid keys through
// curvilinear::set_izogrid_key; the rest are aquatoria's.
#include "config/regional.hpp"

#include <cmath>

#include "config/schema.hpp"
#include "grid_params/izogrid_file.hpp"

namespace aq::config {

namespace {

using detail::Origin;
using detail::Problems;
using RegionalSchema = detail::Schema<RegionalConfig>;

// TOML scalar -> the izogrid preamble's text form.
std::optional<std::string> scalar_text(const toml::value& v) {
  if (v.is_string()) return v.as_string().str == "auto" ? std::string("nan") : v.as_string().str;
  if (v.is_integer()) return std::to_string(v.as_integer());
  if (v.is_floating()) return fmt::format("{}", v.as_floating());
  if (v.is_boolean()) return v.as_boolean() ? "true" : "false";
  return std::nullopt;
}

Json param_json(const curvilinear::RegionalParams& p, const std::string& key);

const RegionalSchema& regional_schema() {
  static const RegionalSchema s = [] {
    RegionalSchema t;
    t.add<std::string>(
        "regional", "name", [](RegionalConfig& c) -> std::string& { return c.name; },
        [](const std::string& v) {
          return (v.empty() || v.find('/') != std::string::npos) ? std::string("must be a plain name") : std::string();
        },
        "");
    t.add_custom(
        "regional", "contour_file",
        [](RegionalConfig&, const toml::value& v, const Origin& o, Problems& p) {
          if (!v.is_string()) p.add(o, "regional.contour_file", "expected a file name in quotes");
          // Read before the other keys by load_regional().
        },
        [](const RegionalConfig& c) { return Json(c.contour_file); }, "");
    t.add_custom(
        "regional", "stop_after",
        [](RegionalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
          if (v.is_string() && v.as_string().str.empty()) {
            c.stop_after.reset();  // "" = from regional.mode
            return;
          }
          curvilinear::Stage stage{};
          if (auto err = detail::convert(v, stage)) return p.add(o, "regional.stop_after", *err + " or \"\"");
          c.stop_after = stage;
        },
        [](const RegionalConfig& c) {
          return Json(c.stop_after ? std::string(name_of(*c.stop_after)) : std::string());
        },
        fmt::format("the stage to stop after; \"\" = regional.mode: one of {}", name_help<curvilinear::Stage>()),
        detail::value_names<curvilinear::Stage>());
    for (const std::string& key : curvilinear::izogrid_keys()) {
      t.add_custom(
          "regional", key,
          [key](RegionalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
            const auto text = scalar_text(v);
            if (!text) return p.add(o, "regional." + key, "expected a number, string or boolean");
            const std::string err = curvilinear::set_izogrid_key(c.params, key, *text);
            if (!err.empty()) p.add(o, "regional." + key, fmt::format("'{}' {}", *text, err));
          },
          [key](const RegionalConfig& c) { return param_json(c.params, key); }, "",
          curvilinear::izogrid_key_values(key));
    }
    // Control points and corner numbers of the (first) block and of the bvp method's block 2.
    struct PointKeys {
      const char* points;
      const char* corners;
      std::vector<double> curvilinear::RegionalParams::*x;
      std::vector<double> curvilinear::RegionalParams::*y;
      std::vector<bool> curvilinear::RegionalParams::*corner;
      std::vector<int> RegionalConfig::*numbers;
    };
    using RP = curvilinear::RegionalParams;
    for (const PointKeys& k :
         {PointKeys{"control_points", "corners", &RP::x, &RP::y, &RP::corner, &RegionalConfig::corners},
          PointKeys{"block2_points", "block2_corners", &RP::x2, &RP::y2, &RP::corner2, &RegionalConfig::corners2}}) {
      const std::string pkey = std::string("regional.") + k.points, ckey = std::string("regional.") + k.corners;
      t.add_custom(
          "regional", k.points,
          [k, pkey](RegionalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
            std::vector<std::array<double, 2>> pts;
            if (auto err = detail::convert(v, pts)) return p.add(o, pkey, *err);
            if (pts.empty()) return;  // keep the points of contour_file, if any
            (c.params.*k.x).clear();
            (c.params.*k.y).clear();
            for (const auto& q : pts) {
              (c.params.*k.x).push_back(q[0]);
              (c.params.*k.y).push_back(q[1]);
            }
            (c.params.*k.corner).assign(pts.size(), false);
            (c.params.*k.corner)[0] = true;
          },
          [k](const RegionalConfig& c) {
            Json a = Json::array();
            for (std::size_t n = 0; n < (c.params.*k.x).size(); ++n)
              a.push_back({(c.params.*k.x)[n], (c.params.*k.y)[n]});
            return a;
          },
          "");
      t.add_custom(
          "regional", k.corners,
          [k, ckey](RegionalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
            std::vector<int> idx;
            if (auto err = detail::convert(v, idx)) return p.add(o, ckey, *err);
            if (idx.empty()) return;
            if (idx.size() != 4 || idx[0] != 1)
              return p.add(o, ckey, "expected the 4 corner point numbers, SW first: [1, SE, NE, NW]");
            // The points go counter-clockwise from the SW corner, so SE < NE < NW; another order
            // was once sorted silently, which made other points the corners.
            if (!(idx[0] < idx[1] && idx[1] < idx[2] && idx[2] < idx[3]))
              return p.add(o, ckey,
                           fmt::format("[{}, {}, {}, {}]: the corner numbers must increase, [1, SE, NE, NW] with the "
                                       "points counter-clockwise from the SW corner",
                                       idx[0], idx[1], idx[2], idx[3]));
            c.*k.numbers = idx;  // applied to the points once all keys are read
          },
          [k](const RegionalConfig& c) {
            Json a = Json::array();
            for (std::size_t n = 0; n < (c.params.*k.corner).size(); ++n)
              if ((c.params.*k.corner)[n]) a.push_back(n + 1);
            return a;
          },
          "");
    }
    t.add<int>(
        "regional", "block2_nx", [](RegionalConfig& c) -> int& { return c.params.nx2; }, {}, "");
    using Sections = std::vector<std::vector<double>>;
    for (const auto& [section_name, section_member] :
         {std::pair{"sections", &curvilinear::RegionalParams::sections},
          std::pair{"sections_eta", &curvilinear::RegionalParams::sections_eta}}) {
      // Copies: clang before 16 cannot capture a structured binding.
      const char* name = section_name;
      const auto member = section_member;
      const std::string key = std::string("regional.") + name;
      t.add_custom(
          "regional", name,
          [member, key](RegionalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
            Sections secs;
            if (auto err = detail::convert(v, secs)) return p.add(o, key, *err);
            c.params.*member = secs;  // checked by regional_params_problems()
          },
          [member](const RegionalConfig& c) { return Json(c.params.*member); }, "");
    }
    t.add_custom(
        "input", "path",
        [](RegionalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
          std::string x;
          if (auto err = detail::convert(v, x)) return p.add(o, "input.path", *err);
          std::filesystem::path path(x);
          if (!x.empty() && path.is_relative()) path = o.base_dir / path;
          c.input.path = x.empty() ? x : path.lexically_normal().string();
          if (const std::string bad = detail::input_path_problem(c.input.path); !x.empty() && !bad.empty())
            p.add(o, "input.path", bad);
        },
        [](const RegionalConfig& c) { return Json(c.input.path); }, "");
    t.add<std::string>(
        "input", "variable", [](RegionalConfig& c) -> std::string& { return c.input.variable; }, {}, "");
    t.add<bool>(
        "input", "positive_down", [](RegionalConfig& c) -> bool& { return c.input.positive_down; }, {}, "");
    t.add<double>(
        "input", "max_abs_elevation_m", [](RegionalConfig& c) -> double& { return c.input.max_abs_elevation_m; },
        [](const double& v) {
          return (v >= 100.0 && v <= 1e6) ? std::string() : fmt::format("{} must be within [100, 1e6] (m)", v);
        },
        "");
    t.add<double>(
        "input", "coast_level_m", [](RegionalConfig& c) -> double& { return c.coast_level_m; },
        [](const double& v) { return std::isfinite(v) ? std::string() : std::string("must be finite"); }, "");
    t.add<std::string>(
        "output", "dir", [](RegionalConfig& c) -> std::string& { return c.output_dir; },
        [](const std::string& v) { return v.empty() ? std::string("must not be empty") : output_dir_problem(v); }, "");
    t.add<bool>(
        "roms", "enabled", [](RegionalConfig& c) -> bool& { return c.roms.enabled; }, {}, "");
    t.add_custom(
        "roms", "global_config",
        [](RegionalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
          std::string x;
          if (auto err = detail::convert(v, x)) return p.add(o, "roms.global_config", *err);
          std::filesystem::path path(x);
          if (!x.empty() && path.is_relative()) path = o.base_dir / path;
          c.roms.global_config = x.empty() ? x : path.lexically_normal().string();
          if (const std::string bad = detail::input_path_problem(c.roms.global_config); !x.empty() && !bad.empty())
            p.add(o, "roms.global_config", bad);
        },
        [](const RegionalConfig& c) { return Json(c.roms.global_config); }, "");
    t.add<std::string>(
        "roms", "global_config_checksum", [](RegionalConfig& c) -> std::string& { return c.roms.global_config_checksum; },
        [](const std::string& v) {
          if (v.empty()) return std::string();
          const bool hex = v.size() == 16 && v.find_first_not_of("0123456789abcdef") == std::string::npos;
          return hex ? std::string() : std::string("must be \"\" or 16 lower-case hex digits (an XXH64 checksum)");
        },
        "");
    t.add<double>(
        "roms", "hmin_m", [](RegionalConfig& c) -> double& { return c.roms.hmin_m; },
        [](const double& v) {
          return (v > 0.0 && v <= 12000.0) ? std::string() : std::string("must be a depth in (0, 12000] (m)");
        },
        "");
    t.add<double>(
        "roms", "rmax", [](RegionalConfig& c) -> double& { return c.roms.rmax; },
        [](const double& v) {
          return (v >= 0.0 && v < 1.0) ? std::string() : std::string("must be in [0, 1) (0 = no smoothing)");
        },
        "");
    t.add<curvilinear::DistanceModel>(
        "roms", "distances", [](RegionalConfig& c) -> curvilinear::DistanceModel& { return c.roms.distances; }, {},
        "how pm, pn measure lengths");
    t.add<CellStatistic>(
        "roms", "depth_statistic", [](RegionalConfig& c) -> CellStatistic& { return c.roms.depth_statistic; }, {},
        "the elevation of a rho cell from the raster");
    t.add<double>(
        "roms", "earth_radius_m", [](RegionalConfig& c) -> double& { return c.roms.earth_radius_m; },
        [](const double& v) {
          return (std::isfinite(v) && v > 0.0) ? std::string() : std::string("must be a radius > 0 (m)");
        },
        "");
    t.add_custom(
        "nesting", "parent",
        [](RegionalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
          std::string x;
          if (auto err = detail::convert(v, x)) return p.add(o, "nesting.parent", *err);
          std::filesystem::path path(x);
          if (!x.empty() && path.is_relative()) path = o.base_dir / path;
          c.nesting.parent = x.empty() ? x : path.lexically_normal().string();
          if (const std::string bad = detail::input_path_problem(c.nesting.parent); !x.empty() && !bad.empty())
            p.add(o, "nesting.parent", bad);
        },
        [](const RegionalConfig& c) { return Json(c.nesting.parent); }, "");
    t.add<int>(
        "nesting", "refine_factor", [](RegionalConfig& c) -> int& { return c.nesting.refine_factor; },
        [](const int& v) {
          return (v == 0 || (v >= 3 && v <= 55 && v % 2 == 1))
                     ? std::string()
                     : std::string(
                           "must be an odd factor 3..55 (ROMS averages r x r fine cells around a centre "
                           "point) or 0 for no refinement");
        },
        "");
    t.add<int>(
        "nesting", "blend_cells", [](RegionalConfig& c) -> int& { return c.nesting.blend_cells; },
        [](const int& v) { return v >= 0 ? std::string() : std::string("must be >= 0 (0 = no blending)"); }, "");
    t.add_custom(
        "nesting", "parent_box",
        [](RegionalConfig& c, const toml::value& v, const Origin& o, Problems& p) {
          std::vector<int> b;
          if (auto err = detail::convert(v, b)) return p.add(o, "nesting.parent_box", *err);
          if (b.empty()) {
            c.nesting.parent_box = {0, 0, 0, 0};
            return;
          }
          if (b.size() != 4 || b[0] < 1 || b[2] < 1 || b[1] <= b[0] || b[3] <= b[2])
            return p.add(o, "nesting.parent_box",
                         "expected the parent's psi indices [I_left, I_right, J_bottom, J_top] (ROMS, 1-based) "
                         "with I_left < I_right and J_bottom < J_top");
          c.nesting.parent_box = {b[0], b[1], b[2], b[3]};
        },
        [](const RegionalConfig& c) {
          if (c.nesting.parent_box == std::array<int, 4>{0, 0, 0, 0}) return Json::array();
          return Json(std::vector<int>(c.nesting.parent_box.begin(), c.nesting.parent_box.end()));
        },
        "");
    return t;
  }();
  return s;
}

Json param_json(const curvilinear::RegionalParams& p, const std::string& key) {
  // Echo through the izogrid names; enums as their text.
  if (key == "mode") return p.mode;
  if (key == "npass") return p.npass;
  if (key == "gshhs_data") return p.gshhs_data;
  if (key == "rlat") return p.projection.rlat_deg;
  if (key == "rlon") return p.projection.rlon_deg;
  if (key == "rota") return p.projection.rota_deg;
  if (key == "uscale") return p.projection.uscale;
  if (key == "radius") return p.projection.radius_m;
  if (key == "latlongrid") return p.latlongrid;
  if (key == "spline_type") return p.spline_type;
  if (key == "nx") return p.nx;
  if (key == "ny") return p.ny;
  if (key == "auto_nx") return p.auto_nx;
  if (key == "tolerance") return p.tolerance;
  if (key == "max_outer") return p.max_outer;
  if (key == "max_inner") return p.max_inner;
  if (key == "interp_points") return p.interp_points;
  if (key == "inner_rtol") return p.inner_rtol;
  if (key == "anderson") return p.anderson;
  if (key == "xygrid") return p.xygrid;
  if (key == "threads") return p.threads;
  const auto name = [](auto e) { return Json(std::string(name_of(e))); };
  if (key == "method") return name(p.method);
  if (key == "best_final") return name(p.best_final);
  if (key == "weight") return p.weight.text();
  if (key == "weight_depth") return p.weight_depth;
  if (key == "relaxation") return p.relaxation;
  if (key == "elliptic_tolerance") return p.elliptic_tolerance;
  if (key == "elliptic_criteria_tolerance") return p.elliptic_criteria_tolerance;
  if (key == "elliptic_iterations") return p.elliptic_iterations;
  if (key == "lwidth") return p.lwidth;
  if (key == "solver") return name(p.solver);
  if (key == "surface") return name(p.surface);
  if (key == "bvp_iterations") return p.bvp_iterations;
  if (key == "bvp_interpolation") return name(p.bvp_interpolation);
  if (key == "bvp_ratio_xi") return p.bvp_ratio_xi;
  if (key == "bvp_ratio_eta") return p.bvp_ratio_eta;
  if (key == "schedule") return name(p.schedule);
  if (key == "param") return name(p.param);
  if (key == "points")
    return name(p.points_lonlat ? curvilinear::PointUnits::kLonLat : curvilinear::PointUnits::kPlane);
  auto num = [](double v) { return std::isnan(v) ? Json("auto") : Json(v); };
  if (key == "lat1") return num(p.projection.lat1_deg);
  if (key == "lat2") return num(p.projection.lat2_deg);
  if (key == "west_edge") return num(p.west_edge);
  if (key == "east_edge") return num(p.east_edge);
  if (key == "south_edge") return num(p.south_edge);
  if (key == "north_edge") return num(p.north_edge);
  if (key == "proj") return name(p.projection.kind);
  return nullptr;
}

}  // namespace

Loaded<RegionalConfig> load_regional(const std::string& path, const std::vector<std::string>& overrides) {
  Loaded<RegionalConfig> out;
  Problems p;
  const std::filesystem::path file(path);
  out.source = file.string();
  RegionalConfig& c = out.options;
  if (file.extension() == ".izogrid") {
    c.params = curvilinear::read_izogrid_file(file);
    c.contour_file = file.string();
    p.set_fallback(file.string());
    c.name = file.stem().string();
  } else {
    const toml::value doc = detail::parse_file(file);
    std::filesystem::path base = file.parent_path();
    if (base.empty()) base = ".";
    c.name = file.stem().string();
    // The izogrid contour file first, so that TOML keys override its preamble.
    if (doc.is_table() && doc.contains("regional") && doc.at("regional").is_table() &&
        doc.at("regional").contains("contour_file") && doc.at("regional").at("contour_file").is_string() &&
        !doc.at("regional").at("contour_file").as_string().str.empty()) {
      std::filesystem::path cf(doc.at("regional").at("contour_file").as_string().str);
      if (cf.is_relative()) cf = base / cf;
      if (const std::string bad = input_file_problem(cf, kMaxTextFileBytes); !bad.empty())
        throw ConfigError(fmt::format("{}: regional.contour_file = {}: {}", file.string(), cf.string(), bad));
      c.params = curvilinear::read_izogrid_file(cf);
      c.contour_file = cf.lexically_normal().string();
      p.set_fallback(fmt::format("{} (regional.contour_file) or built-in default", c.contour_file));
    }
    regional_schema().apply(c, doc, file.string(), base, p);
  }
  for (const auto& o : overrides) regional_schema().apply_override(c, o, p);
  const auto apply_corners = [&p](const std::vector<int>& numbers, std::size_t points, std::vector<bool>& corner,
                                  const char* key, const char* points_key) {
    if (numbers.empty()) return;
    corner.assign(points, false);
    for (const int k : numbers) {
      if (k < 1 || k > static_cast<int>(points)) {
        p.add_keys({fmt::format("regional.{}", key), fmt::format("regional.{}", points_key)},
                   fmt::format("point number {} is outside 1..{} (regional.{})", k, points, points_key));
      } else {
        corner[static_cast<std::size_t>(k - 1)] = true;
      }
    }
  };
  apply_corners(c.corners, c.params.x.size(), c.params.corner, "corners", "control_points");
  apply_corners(c.corners2, c.params.x2.size(), c.params.corner2, "block2_corners", "block2_points");
  {
    const auto& n = c.nesting;
    const bool box = n.parent_box != std::array<int, 4>{0, 0, 0, 0};
    if (n.refinement() && n.parent.empty())
      p.add_key("nesting.refine_factor", "a refinement grid needs nesting.parent, the parent's _grd.nc");
    if (n.refinement() && !box)
      p.add_key("nesting.refine_factor",
                "a refinement grid needs nesting.parent_box = [I_left, I_right, J_bottom, J_top], the parent's psi "
                "indices of its corners");
    if (!n.refinement() && box) p.add_key("nesting.parent_box", "only used with nesting.refine_factor (odd, >= 3)");
    if (!n.parent.empty() && !n.refinement())
      p.add_key("nesting.parent",
                fmt::format("\"{}\": ROMS nests a grid inside a parent only as a refinement, the parent's psi cells "
                            "split r x r (r odd), so that fine-to-coarse averaging and the boundary fluxes line up; "
                            "set nesting.refine_factor and nesting.parent_box (the grid is then made from the parent, "
                            "not from a contour), or remove nesting.parent",
                            n.parent));
  }
  for (const KeyProblem& bad : stop_stage_problems(c, stop_stage(c))) p.add_keys(bad.keys, bad.text);
  // The bathymetry weight samples the [input] raster.
  if (curvilinear::uses_weight(c.params.method) && c.params.weight_depth > 0.0 && c.input.path.empty())
    p.add_keys({"regional.weight_depth", "input.path"},
               fmt::format("regional.weight_depth = {} needs the bathymetry ([input] path)", c.params.weight_depth));
  // The run's parameters (the izogrid keys), at the position of the key (a value of contour_file
  // is reported at that file).
  for (const auto& [key, msg] : curvilinear::regional_params_problems(c.params))
    p.add_key(key == "points" ? "regional.control_points" : "regional." + key, msg);
  p.throw_if_any(out.source);
  c.params.source = out.source;
  out.echo = regional_schema().echo(c);
  return out;
}

curvilinear::Stage stop_stage(const RegionalConfig& c, std::optional<curvilinear::Stage> command_line) {
  if (command_line) return *command_line;
  if (c.stop_after) return *c.stop_after;
  return c.params.mode >= 0 && c.params.mode <= 5 ? curvilinear::stage_from_mode(c.params.mode)
                                                  : curvilinear::Stage::kGrid;  // a bad mode is reported apart
}

std::vector<KeyProblem> stop_stage_problems(const RegionalConfig& c, curvilinear::Stage stage) {
  std::vector<KeyProblem> out;
  const std::string stop_key = c.stop_after ? "regional.stop_after" : "regional.mode";
  if (c.params.method != curvilinear::GridMethod::kConformal && stage == curvilinear::Stage::kConformal)
    out.push_back({{stop_key, "regional.method"},
                   fmt::format("method = {} has no conformal stage (stop after map, contour, uniform or grid)",
                               c.params.method)});
  if (c.nesting.refinement() && stage != curvilinear::Stage::kGrid)
    out.push_back({{stop_key, "nesting.refine_factor"},
                   fmt::format("a refinement grid (nesting.refine_factor = {}) is cut from its parent in one step; "
                               "stopping after the {} stage does not apply",
                               c.nesting.refine_factor, stage)});
  return out;
}

std::vector<KeyInfo> regional_key_info() { return regional_schema().infos<KeyInfo>(); }

std::vector<std::string> regional_keys() { return regional_schema().names(); }

}  // namespace aq::config
