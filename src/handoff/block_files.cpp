// SPDX-License-Identifier: GPL-3.0-or-later
// Texts of a block's contour file and regional config (see block_files.hpp).
#include "handoff/block_files.hpp"

#include <fmt/format.h>

#include <sstream>

#include "core/error.hpp"

namespace aq::handoff {

std::string toml_string(const std::string& text);

namespace {

std::string comment_lines(const std::string& text) {
  std::string out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out += "# " + line + "\n";
  return out;
}

std::string toml_value(const Json& v) {
  if (v.is_string()) return toml_string(v.get<std::string>());
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return v.dump();
  if (v.is_number_float()) {
    std::string t = v.dump();  // shortest round-trip form; make sure TOML reads it as a float
    if (t.find_first_of(".eE") == std::string::npos && t.find_first_of("0123456789") != std::string::npos) t += ".0";
    return t;
  }
  if (v.is_array()) {
    std::string t = "[";
    for (std::size_t k = 0; k < v.size(); ++k) t += (k ? ", " : "") + toml_value(v[k]);
    return t + "]";
  }
  if (v.is_object()) {
    std::string t = "{";
    bool first = true;
    for (const auto& [key, x] : v.items()) {
      t += (first ? "" : ", ") + key + " = " + toml_value(x);
      first = false;
    }
    return t + "}";
  }
  throw InternalError("config_text_from_echo: a value TOML cannot hold: " + v.dump());
}

}  // namespace

std::string toml_string(const std::string& text) {
  std::string out = "\"";
  for (const char ch : text) {
    switch (ch) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) {
          out += fmt::format("\\u{:04x}", static_cast<unsigned>(static_cast<unsigned char>(ch)));
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

std::string izogrid_text(const BlockContour& c, int ny, double latlongrid_deg, const std::string& comment) {
  const auto& p = c.projection;
  std::string s = comment_lines(comment);
  s += fmt::format("proj={} rlat={:.12g} rlon={:.12g} rota={:.12g} uscale={:.6g}\n", std::string(name_of(p.kind)),
                   p.rlat_deg, p.rlon_deg, p.rota_deg, p.uscale);
  s += fmt::format("ny={} nx=0 spline_type=5 latlongrid={:.6g}\n", ny, latlongrid_deg);
  s += "---\n";
  const char* labels[4] = {"south-west", "< south-east", "< north-east", "< north-west"};
  for (std::size_t k = 0; k < c.x.size(); ++k) {
    s += fmt::format("{:.12g} {:.12g}", c.x[k], c.y[k]);
    for (std::size_t q = 0; q < 4; ++q)
      if (static_cast<std::size_t>(c.corners[q]) == k) s += std::string(" ") + labels[q];
    s += "\n";
  }
  return s;
}

std::string regional_config_text(const BlockConfigInfo& i) {
  std::string s = comment_lines(i.description);
  s += fmt::format(
      "# The projection and the contour are in {} (plane units of its projection: edit them\n"
      "# together). Build the grid:  aquatoria regional -c {}.toml\n\n",
      i.izogrid_file, i.name);
  s += "[regional]\n";
  s += fmt::format("name = {}\n", toml_string(i.name));
  s += fmt::format("contour_file = {}\n", toml_string(i.izogrid_file));
  s += fmt::format("ny = {}\n\n", i.ny);
  s += "[input]\n";
  s += fmt::format("path = {}\n", toml_string(i.input_path));
  s += fmt::format("variable = {}\n", toml_string(i.input_variable));
  s += fmt::format("positive_down = {}\n", i.positive_down ? "true" : "false");
  s += fmt::format("coast_level_m = {:.6g}\n\n", i.coast_level_m + 0.0);  // never "-0"
  s += "[output]\n";
  s += fmt::format("dir = {}\n", toml_string(i.output_dir));
  if (!i.global_config.empty()) {
    if (i.write_global_config) {
      s += "\n[roms]\n";
      s += fmt::format("global_config = {}  # the global run this block came from (lattice, mask, nesting)\n",
                       toml_string(i.global_config));
      if (!i.global_config_checksum.empty())
        s += fmt::format(
            "global_config_checksum = {}  # XXH64 of that file as written: a run refuses when it has changed\n",
            toml_string(i.global_config_checksum));
    } else {
      s += fmt::format("\n# global run this block came from: {}\n", i.global_config);
    }
  }
  return s;
}

std::string config_text_from_echo(const Json& echo, const std::string& comment) {
  std::string s = comment_lines(comment);
  for (const auto& [section, table] : echo.items()) {
    s += "\n[" + section + "]\n";
    for (const auto& [key, value] : table.items()) s += key + " = " + toml_value(value) + "\n";
  }
  return s;
}

}  // namespace aq::handoff
