// SPDX-License-Identifier: GPL-3.0-or-later
// izogrid input file reader; see izogrid_file.hpp (seed 000 Appendix 1, Fig. 3).
#include "grid_params/izogrid_file.hpp"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "core/input_files.hpp"
#include "grid_params/control_function.hpp"

namespace aq::curvilinear {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::string lowercase(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// A line made only of 3 or more dashes: ASCII '-', en dash U+2013 (E2 80 93), em dash U+2014
// (E2 80 94); blanks allowed around.
bool is_end_marker(std::string_view line) {
  line = trim(line);
  int dashes = 0;
  std::size_t i = 0;
  while (i < line.size()) {
    if (line[i] == '-') {
      ++dashes;
      ++i;
    } else if (line.size() - i >= 3 && static_cast<unsigned char>(line[i]) == 0xE2 &&
               static_cast<unsigned char>(line[i + 1]) == 0x80 &&
               (static_cast<unsigned char>(line[i + 2]) == 0x93 || static_cast<unsigned char>(line[i + 2]) == 0x94)) {
      ++dashes;
      i += 3;
    } else {
      return false;
    }
  }
  return dashes >= 3;
}

// Strict number: the whole token, an optional leading '+'.
bool parse_double(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, out);
  return r.ec == std::errc() && r.ptr == end;
}

bool parse_int(std::string_view s, int& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, out);
  return r.ec == std::errc() && r.ptr == end;
}

bool parse_bool(std::string_view s, bool& out) {
  const std::string v = lowercase(s);
  if (v == "true" || v == "yes" || v == "1" || v == "on") {
    out = true;
    return true;
  }
  if (v == "false" || v == "no" || v == "0" || v == "off") {
    out = false;
    return true;
  }
  return false;
}

std::vector<std::string_view> split_blanks(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

// Setter of one key: returns an empty string on success, else why the value is bad.
using Setter = std::function<std::string(RegionalParams&, std::string_view)>;

Setter real(double RegionalParams::*field) {
  return [field](RegionalParams& p, std::string_view v) -> std::string {
    double d = 0.0;
    if (!parse_double(v, d)) return "is not a number";
    p.*field = d;
    return {};
  };
}
// A number of the projection (RegionalParams::projection).
Setter map_real(double ProjectionParams::*field) {
  return [field](RegionalParams& p, std::string_view v) -> std::string {
    double d = 0.0;
    if (!parse_double(v, d)) return "is not a number";
    p.projection.*field = d;
    return {};
  };
}
Setter integer(int RegionalParams::*field) {
  return [field](RegionalParams& p, std::string_view v) -> std::string {
    int d = 0;
    if (!parse_int(v, d)) return "is not an integer";
    p.*field = d;
    return {};
  };
}
Setter text(std::string RegionalParams::*field) {
  return [field](RegionalParams& p, std::string_view v) -> std::string {
    p.*field = std::string(v);
    return {};
  };
}
Setter boolean(bool RegionalParams::*field) {
  return [field](RegionalParams& p, std::string_view v) -> std::string {
    bool b = false;
    if (!parse_bool(v, b)) return "is not true/false";
    p.*field = b;
    return {};
  };
}

// An enumerated key: a name of E's table (grid_kinds.hpp) in any case, as the seed's files write
// "ME" or "me".
// A key's setter and, for an enumerated key, the names it takes.
struct KeySetter {
  KeySetter(Setter s, std::vector<std::string> v = {}) : set(std::move(s)), values(std::move(v)) {}  // NOLINT
  Setter set;
  std::vector<std::string> values;
};

template <NamedEnum E>
std::vector<std::string> names_without_aliases() {
  std::vector<std::string> out;
  const auto t = names_of<E>();
  for (std::size_t k = 0; k < t.size(); ++k)
    if (!is_alias<E>(k)) out.emplace_back(t[k].name);
  return out;
}

template <NamedEnum E>
KeySetter named(std::function<E&(RegionalParams&)> field) {
  return {[field](RegionalParams& p, std::string_view v) -> std::string {
            const std::optional<E> e = parse_name_any_case<E>(v);
            if (!e) return "is not one of " + name_list<E>();
            field(p) = *e;
            return {};
          },
          names_without_aliases<E>()};
}
template <NamedEnum E>
KeySetter named(E RegionalParams::*member) {
  return named<E>([member](RegionalParams& p) -> E& { return p.*member; });
}

const std::map<std::string, KeySetter>& setters() {
  static const std::map<std::string, KeySetter> table = {
      {"mode", integer(&RegionalParams::mode)},
      {"npass", integer(&RegionalParams::npass)},
      {"gshhs_data", text(&RegionalParams::gshhs_data)},
      {"proj", named<ProjectionKind>([](RegionalParams& p) -> ProjectionKind& { return p.projection.kind; })},
      {"rlat", map_real(&ProjectionParams::rlat_deg)},
      {"rlon", map_real(&ProjectionParams::rlon_deg)},
      {"rota", map_real(&ProjectionParams::rota_deg)},
      {"lat1", map_real(&ProjectionParams::lat1_deg)},
      {"lat2", map_real(&ProjectionParams::lat2_deg)},
      {"uscale", map_real(&ProjectionParams::uscale)},
      {"radius", map_real(&ProjectionParams::radius_m)},
      {"west_edge", real(&RegionalParams::west_edge)},
      {"east_edge", real(&RegionalParams::east_edge)},
      {"south_edge", real(&RegionalParams::south_edge)},
      {"north_edge", real(&RegionalParams::north_edge)},
      {"latlongrid", real(&RegionalParams::latlongrid)},
      {"lwidth", real(&RegionalParams::lwidth)},
      {"spline_type", integer(&RegionalParams::spline_type)},
      {"param", named(&RegionalParams::param)},
      {"points",
       {[](RegionalParams& p, std::string_view v) -> std::string {
          const std::optional<PointUnits> u = parse_name_any_case<PointUnits>(v);
          if (!u) return "is not one of " + name_list<PointUnits>();
          p.points_lonlat = *u == PointUnits::kLonLat;
          return {};
        },
        names_without_aliases<PointUnits>()}},
      {"nx", integer(&RegionalParams::nx)},
      {"ny", integer(&RegionalParams::ny)},
      {"auto_nx", boolean(&RegionalParams::auto_nx)},
      {"schedule", named(&RegionalParams::schedule)},
      {"tolerance", real(&RegionalParams::tolerance)},
      {"method", named(&RegionalParams::method)},
      {"weight", Setter([](RegionalParams& p, std::string_view v) -> std::string {
         try {
           p.weight = ControlFunction::parse(v, "weight");
         } catch (const ConfigError& e) {
           return fmt::format("is not a formula in x, y ({})", e.what());
         }
         return {};
       })},
      {"weight_depth", real(&RegionalParams::weight_depth)},
      {"relaxation", real(&RegionalParams::relaxation)},
      {"elliptic_tolerance", real(&RegionalParams::elliptic_tolerance)},
      {"elliptic_criteria_tolerance", real(&RegionalParams::elliptic_criteria_tolerance)},
      {"elliptic_iterations", integer(&RegionalParams::elliptic_iterations)},
      // Any method name parses; regional_params_problems() then allows only the two elliptic ones.
      {"best_final",
       {named(&RegionalParams::best_final).set,
        {std::string(name_of(GridMethod::kEd2)), std::string(name_of(GridMethod::kRl))}}},
      {"max_outer", integer(&RegionalParams::max_outer)},
      {"max_inner", integer(&RegionalParams::max_inner)},
      {"interp_points", integer(&RegionalParams::interp_points)},
      {"inner_rtol", real(&RegionalParams::inner_rtol)},
      {"anderson", integer(&RegionalParams::anderson)},
      {"solver", named(&RegionalParams::solver)},
      {"xygrid", text(&RegionalParams::xygrid)},
      {"surface", named(&RegionalParams::surface)},
      {"bvp_iterations", integer(&RegionalParams::bvp_iterations)},
      {"bvp_interpolation", named(&RegionalParams::bvp_interpolation)},
      {"bvp_ratio_xi", real(&RegionalParams::bvp_ratio_xi)},
      {"bvp_ratio_eta", real(&RegionalParams::bvp_ratio_eta)},
      {"threads", integer(&RegionalParams::threads)},
  };
  return table;
}

// Corner label: 0 = none, 1 = SE, 2 = NE, 3 = NW, 4 = '<' without a recognised name,
// -1 = "south-west" (only allowed on the first point).
int corner_label(std::string_view label) {
  std::string s = lowercase(trim(label));
  const bool arrow = !s.empty() && s.front() == '<';
  if (arrow) s = std::string(trim(std::string_view(s).substr(1)));
  auto starts = [&](const char* name) { return s.rfind(name, 0) == 0; };
  if (starts("south-east") || starts("southeast")) return 1;
  if (starts("north-east") || starts("northeast")) return 2;
  if (starts("north-west") || starts("northwest")) return 3;
  if (starts("south-west") || starts("southwest")) return -1;
  return arrow ? 4 : 0;
}

}  // namespace

std::string set_izogrid_key(RegionalParams& params, const std::string& key, std::string_view value) {
  const auto it = setters().find(key);
  if (it == setters().end()) return "unknown key";
  return it->second.set(params, value);
}

std::vector<std::string> izogrid_keys() {
  std::vector<std::string> keys;
  for (const auto& [k, s] : setters()) keys.push_back(k);
  return keys;
}

std::vector<std::string> izogrid_key_values(const std::string& key) {
  const auto it = setters().find(key);
  return it == setters().end() ? std::vector<std::string>() : it->second.values;
}

RegionalParams parse_izogrid(std::string_view text, const std::string& source) {
  RegionalParams p;
  p.source = source;
  p.input_text = std::string(text);
  std::vector<std::string> config_errors, input_errors;
  std::map<std::string, int> seen;  // key -> line
  std::vector<int> point_lines, corner_lines;
  std::vector<int> corner_kinds;
  bool in_points = false;
  int line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    if (trim(line).empty()) {
      if (eol == text.size()) break;
      continue;
    }
    const std::string where = fmt::format("{}:{}", source, line_no);
    if (!in_points) {
      if (is_end_marker(line)) {
        in_points = true;
        continue;
      }
      for (std::string_view tok : split_blanks(line)) {
        const auto eq = tok.find('=');
        if (eq == std::string_view::npos || eq == 0) {
          config_errors.push_back(
              fmt::format("{}: '{}' is not key=value (or the end-of-preamble line '---' is missing)", where, tok));
          continue;
        }
        const std::string key = lowercase(tok.substr(0, eq));
        const std::string_view value = tok.substr(eq + 1);
        const auto it = setters().find(key);
        if (it == setters().end()) {
          config_errors.push_back(fmt::format("{}: unknown key '{}'", where, key));
          continue;
        }
        if (const auto s = seen.find(key); s != seen.end()) {
          config_errors.push_back(fmt::format("{}: key '{}' given again (first on line {})", where, key, s->second));
          continue;
        }
        seen[key] = line_no;
        const std::string why = it->second.set(p, value);
        if (!why.empty()) config_errors.push_back(fmt::format("{}: {} = '{}' {}", where, key, value, why));
      }
      continue;
    }
    // A point: x y [label]
    const auto toks = split_blanks(line);
    double x = 0.0, y = 0.0;
    if (toks.size() < 2 || !parse_double(toks[0], x) || !parse_double(toks[1], y)) {
      input_errors.push_back(fmt::format("{}: expected a point 'x y [label]', got '{}'", where, trim(line)));
      continue;
    }
    std::string_view label;
    if (toks.size() > 2) label = trim(line.substr(static_cast<std::size_t>(toks[2].data() - line.data())));
    const int kind = corner_label(label);
    const bool first = p.x.empty();
    bool corner = false;
    if (first) {
      if (kind > 0 && kind != 4)
        input_errors.push_back(
            fmt::format("{}: the first point is the south-west corner, but it is labelled '{}'", where, label));
    } else if (kind == -1) {
      input_errors.push_back(
          fmt::format("{}: 'south-west' must be the first point (points run counter-clockwise "
                      "from the south-west corner)",
                      where));
    } else if (kind != 0) {
      corner = true;
      corner_lines.push_back(line_no);
      corner_kinds.push_back(kind);
    }
    p.x.push_back(x);
    p.y.push_back(y);
    p.corner.push_back(first || corner);
    point_lines.push_back(line_no);
  }
  if (!in_points) {
    input_errors.push_back(
        fmt::format("{}: no end-of-preamble line (a line of three or more dashes '---') before "
                    "the points",
                    source));
  } else {
    if (p.x.empty()) input_errors.push_back(fmt::format("{}: no points after the end-of-preamble line", source));
    // Corners: the first point plus exactly three marked, in the order SE, NE, NW when named.
    if (!p.x.empty() && corner_lines.size() != 3) {
      std::string lines = fmt::format("{}", point_lines.front());
      for (int l : corner_lines) lines += fmt::format(", {}", l);
      input_errors.push_back(
          fmt::format("{}: the contour needs exactly 4 corners (the first point is south-west, "
                      "then south-east, north-east and north-west marked with '<'); found {} "
                      "(lines {})",
                      source, corner_lines.size() + 1, lines));
    } else {
      for (std::size_t i = 0; i < corner_kinds.size(); ++i)
        if (corner_kinds[i] != 4 && corner_kinds[i] != static_cast<int>(i) + 1)
          input_errors.push_back(fmt::format(
              "{}:{}: corner {} of the contour must be the {} corner (counter-clockwise: south-east, north-east, "
              "north-west)",
              source, corner_lines[i], i + 2, i == 0 ? "south-east" : (i == 1 ? "north-east" : "north-west")));
    }
  }
  if (config_errors.empty()) {
    for (const auto& [key, why] : regional_params_problems(p)) {
      const auto s = seen.find(key);
      if (s != seen.end()) {
        config_errors.push_back(fmt::format("{}:{}: {}", source, s->second, why));
      } else {
        config_errors.push_back(fmt::format("{}: {}", source, why));
      }
    }
  }
  if (!config_errors.empty() || !input_errors.empty()) {
    std::string msg;
    for (const auto& e : config_errors) msg += (msg.empty() ? "" : "\n") + e;
    for (const auto& e : input_errors) msg += (msg.empty() ? "" : "\n") + e;
    if (!config_errors.empty()) throw ConfigError(msg);
    throw InputError(msg);
  }
  return p;
}

RegionalParams read_izogrid_file(const std::filesystem::path& path) {
  if (const std::string bad = input_file_problem(path, kMaxTextFileBytes); !bad.empty())
    throw InputError(fmt::format("{}: izogrid file: {}", path.string(), bad));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the izogrid file", path.string()));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(fmt::format("{}: read error", path.string()));
  return parse_izogrid(ss.str(), path.string());
}

}  // namespace aq::curvilinear
