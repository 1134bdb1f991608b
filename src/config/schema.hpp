// SPDX-License-Identifier: GPL-3.0-or-later
// Private to src/config: a table of configuration keys (section, name, help, setter, getter)
// that reads a TOML document into a plain option struct. Every problem (unknown section or key,
// wrong type, bad value) is collected with file:line:column and reported together in one
// ConfigError. Only files in src/config include this header (and so TOML).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <toml.hpp>
#include <tuple>
#include <type_traits>
#include <vector>

#include "core/edit_distance.hpp"
#include "core/enum_names.hpp"
#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/report.hpp"

namespace aq::config::detail {

/// The line number of a --set override's Origin (after every file position).
inline constexpr std::uint32_t kOverrideLine = 1000000;

/// Where a value came from and how to resolve relative paths in it.
struct Origin {
  std::string where;               ///< "file:line:col" or "--set section.key=value"
  std::filesystem::path base_dir;  ///< folder relative paths resolve against
  std::uint32_t line = 0, column = 0;
};

/// The line of a problem of a key left at its built-in default (after every file position and
/// every --set).
inline constexpr std::uint32_t kDefaultLine = 2000000;

/// All problems found in one pass, each with the position of the value at fault.
class Problems {
 public:
  void add(const Origin& o, const std::string& key, const std::string& text) {
    items_.push_back({o.line, o.column, fmt::format("{}: {}: {}", o.where, key, text)});
  }
  void add_plain(std::uint32_t line, const std::string& text) { items_.push_back({line, 0, text}); }
  /// Remembers that `key` ("section.key") was set at `o` (the last setting wins, as for values).
  void set_at(const std::string& key, const Origin& o) { where_[key] = o; }
  /// Where `key` was last set: its own position, else that of the array it is an element of
  /// ("quadtree.box_rules[2].level" -> "quadtree.box_rules"); nothing for a key at its default.
  [[nodiscard]] const Origin* origin(const std::string& key) const {
    if (auto it = where_.find(key); it != where_.end()) return &it->second;
    if (auto at = key.find('['); at != std::string::npos)
      if (auto it = where_.find(key.substr(0, at)); it != where_.end()) return &it->second;
    return nullptr;
  }
  /// A problem of one key, at the position its value came from ("built-in default" when it was
  /// never set).
  void add_key(const std::string& key, const std::string& text) { add_keys({key}, text); }
  /// A problem of several keys together (size.h_min_km above size.h_max_km): reported at the
  /// position of the one set last, naming them all.
  void add_keys(const std::vector<std::string>& keys, const std::string& text) {
    const Origin* at = nullptr;
    std::string names;
    for (const std::string& k : keys) {
      names += (names.empty() ? "" : ", ") + k;
      const Origin* o = origin(k);
      if (o != nullptr && (at == nullptr || std::tie(o->line, o->column) > std::tie(at->line, at->column))) at = o;
    }
    if (at != nullptr) return add(*at, names, text);
    items_.push_back({kDefaultLine, 0, fmt::format("{}: {}: {}", fallback_, names, text)});
  }
  /// Where a value no file line or --set gave comes from ("built-in default", or the seed-format
  /// file a regional run read first).
  void set_fallback(std::string where) { fallback_ = std::move(where); }
  [[nodiscard]] bool empty() const { return items_.empty(); }
  /// Throws ConfigError listing every problem (sorted by position) if there are any.
  void throw_if_any(const std::string& source) const {
    if (items_.empty()) return;
    auto v = items_;
    std::stable_sort(v.begin(), v.end(), [](const Item& a, const Item& b) {
      return a.line != b.line ? a.line < b.line : a.column < b.column;
    });
    std::string msg = fmt::format("{}: {} configuration error{}:", source, v.size(), v.size() == 1 ? "" : "s");
    for (const auto& it : v) msg += "\n  " + it.text;
    throw ConfigError(msg);
  }

 private:
  struct Item {
    std::uint32_t line, column;
    std::string text;
  };
  std::vector<Item> items_;
  std::map<std::string, Origin> where_;
  std::string fallback_ = "built-in default";
};

/// True when `s` is UTF-8 text without control characters (tab allowed): what a --set value that
/// is not a TOML value may be taken as a string from.
inline bool is_plain_text(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      if ((c < 0x20 && c != '\t') || c == 0x7f) return false;
      ++i;
      continue;
    }
    const int extra = (c & 0xe0) == 0xc0 ? 1 : (c & 0xf0) == 0xe0 ? 2 : (c & 0xf8) == 0xf0 ? 3 : -1;
    if (extra < 0 || c == 0xc0 || c == 0xc1 || c > 0xf4 || s.size() - i <= static_cast<std::size_t>(extra))
      return false;
    for (int k = 1; k <= extra; ++k)
      if ((static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]) & 0xc0) != 0x80) return false;
    i += static_cast<std::size_t>(extra) + 1;
  }
  return true;
}

/// Where `text` is not UTF-8 ("line L, column C" of the first bad byte, columns counted in bytes),
/// or "". TOML is UTF-8, and toml11 (3.7) reads past the end of its buffer on some invalid bytes
/// inside a literal string: text must pass this before it reaches the parser.
inline std::string utf8_problem(std::string_view text) {
  std::size_t i = 0, line = 1, line_start = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      if (c == '\n') {
        ++line;
        line_start = i + 1;
      }
      ++i;
      continue;
    }
    const int extra = (c & 0xe0) == 0xc0 ? 1 : (c & 0xf0) == 0xe0 ? 2 : (c & 0xf8) == 0xf0 ? 3 : -1;
    bool ok = extra > 0 && c != 0xc0 && c != 0xc1 && c <= 0xf4 && text.size() - i > static_cast<std::size_t>(extra);
    for (int k = 1; ok && k <= extra; ++k)
      ok = (static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]) & 0xc0) == 0x80;
    if (!ok) return fmt::format("line {}, column {}", line, i - line_start + 1);
    i += static_cast<std::size_t>(extra) + 1;
  }
  return {};
}

/// `s` for a message: when it is not plain text, bytes other than printable ASCII as \xNN.
inline std::string printable(const std::string& s) {
  if (is_plain_text(s)) return s;
  std::string out;
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7f)
      out.push_back(ch);
    else
      out += fmt::format("\\x{:02x}", c);
  }
  return out;
}

inline Origin origin_of(const toml::value& v, const std::string& file, const std::filesystem::path& base) {
  const auto loc = v.location();
  Origin o;
  o.line = loc.line();
  o.column = loc.column();
  o.where = fmt::format("{}:{}:{}", file, loc.line(), loc.column());
  o.base_dir = base;
  return o;
}

// ---- conversions from TOML values; return an error text or nothing ----
inline std::optional<std::string> convert(const toml::value& v, double& out) {
  if (v.is_floating()) {
    out = v.as_floating();
    return std::nullopt;
  }
  if (v.is_integer()) {
    out = static_cast<double>(v.as_integer());
    return std::nullopt;
  }
  return "expected a number";
}
inline std::optional<std::string> convert(const toml::value& v, int& out) {
  if (!v.is_integer()) return "expected an integer";
  const auto x = v.as_integer();
  if (x < -2147483647 || x > 2147483647) return "integer out of range";
  out = static_cast<int>(x);
  return std::nullopt;
}
inline std::optional<std::string> convert(const toml::value& v, bool& out) {
  if (!v.is_boolean()) return "expected true or false";
  out = v.as_boolean();
  return std::nullopt;
}
inline std::optional<std::string> convert(const toml::value& v, std::string& out) {
  if (!v.is_string()) return "expected a string in quotes";
  // A NUL (TOML's \u0000) would cut a path or name at the system call: another file, silently.
  if (v.as_string().str.find('\0') != std::string::npos) return "contains a NUL byte (\\u0000)";
  out = v.as_string().str;
  return std::nullopt;
}

/// An enumerated option: one of the names of E's table (core/enum_names.hpp).
template <NamedEnum E>
std::optional<std::string> convert(const toml::value& v, E& out) {
  if (!v.is_string()) return fmt::format("expected one of {} in quotes", name_list<E>());
  const std::string& text = v.as_string().str;
  if (const std::optional<E> e = parse_name<E>(text)) {
    out = *e;
    return std::nullopt;
  }
  return unknown_name_message<E>(printable(text));
}

/// The problem of a path key's value that names an existing file which is not a regular file
/// (a FIFO, a device, a directory: refused before anything opens it), or "".
inline std::string input_path_problem(const std::filesystem::path& path) {
  const std::string problem = special_file_problem(path);
  return problem.empty() ? problem : fmt::format("{} {}", path.string(), problem);
}
template <std::size_t N>
std::optional<std::string> convert(const toml::value& v, std::array<double, N>& out) {
  if (!v.is_array() || v.as_array().size() != N) return fmt::format("expected an array of {} numbers", N);
  for (std::size_t k = 0; k < N; ++k)
    if (auto err = convert(v.as_array()[k], out[k])) return *err;
  return std::nullopt;
}
template <typename E>
std::optional<std::string> convert(const toml::value& v, std::vector<E>& out) {
  if (!v.is_array()) return "expected an array [ ... ]";
  std::vector<E> r;
  for (const auto& e : v.as_array()) {
    E x{};
    if (auto err = convert(e, x)) return fmt::format("element {}: {}", r.size(), *err);
    r.push_back(std::move(x));
  }
  out = std::move(r);
  return std::nullopt;
}

// ---- JSON echo of values (enums by their names) ----
template <typename V>
struct IsNamedEnumVector : std::false_type {};
template <NamedEnum E>
struct IsNamedEnumVector<std::vector<E>> : std::true_type {};
/// The enum of an enumerated key's value type (E or std::vector<E>), else V itself.
template <typename V>
struct KeyEnum {
  using type = V;
};
template <NamedEnum E>
struct KeyEnum<std::vector<E>> {
  using type = E;
};

template <typename V>
Json to_json(const V& v) {
  if constexpr (NamedEnum<V>) {
    return Json(std::string(name_of(v)));
  } else if constexpr (IsNamedEnumVector<V>::value) {
    Json a = Json::array();
    for (const auto& e : v) a.push_back(std::string(name_of(e)));
    return a;
  } else {
    return Json(v);
  }
}

/// The names an enumerated key takes (none for other keys), for help texts and the Python binding.
template <typename V>
std::vector<std::string> value_names() {
  using E = typename KeyEnum<V>::type;
  std::vector<std::string> out;
  if constexpr (NamedEnum<E>) {
    const auto t = names_of<E>();
    for (std::size_t k = 0; k < t.size(); ++k)
      if (!is_alias<E>(k)) out.emplace_back(t[k].name);
  }
  return out;
}
/// The help of an enumerated key: `help`, then every name with its meaning.
template <typename V>
std::string value_help(const std::string& help) {
  using E = typename KeyEnum<V>::type;
  if constexpr (NamedEnum<E>) return help + (help.empty() ? "" : ": ") + "one of " + name_help<E>();
  return help;
}

/// A table of keys for option struct T.
template <typename T>
class Schema {
 public:
  using Setter = std::function<void(T&, const toml::value&, const Origin&, Problems&)>;
  using Getter = std::function<Json(const T&)>;
  struct Key {
    std::string section, name, help;
    Setter set;
    Getter get;
    std::vector<std::string> values;  ///< the names an enumerated key takes; empty for others
  };

  /// A key whose value converts with `convert` and passes `check` (returns an error text or "").
  template <typename V>
  void add(const std::string& section, const std::string& name, std::function<V&(T&)> field,
           std::function<std::string(const V&)> check, const std::string& help) {
    Key k;
    k.section = section;
    k.name = name;
    k.help = value_help<V>(help);
    k.values = value_names<V>();
    k.set = [field, check, section, name](T& t, const toml::value& v, const Origin& o, Problems& p) {
      V x{};
      if (auto err = convert(v, x)) {
        p.add(o, section + "." + name, *err);
        return;
      }
      if (check) {
        const std::string e = check(x);
        if (!e.empty()) {
          p.add(o, section + "." + name, e);
          return;
        }
      }
      field(t) = std::move(x);
    };
    k.get = [field](const T& t) { return to_json(field(const_cast<T&>(t))); };
    keys_.push_back(std::move(k));
  }
  /// A key with a fully custom setter and getter (arrays of tables, paths).
  /// `values`: the names of an enumerated key whose setter parses them itself.
  void add_custom(const std::string& section, const std::string& name, Setter set, Getter get, const std::string& help,
                  std::vector<std::string> values = {}) {
    keys_.push_back(Key{section, name, help, std::move(set), std::move(get), std::move(values)});
  }

  [[nodiscard]] const std::vector<Key>& keys() const { return keys_; }

  /// Applies a parsed document to `t`, reporting unknown sections/keys and bad values into `p`.
  void apply(T& t, const toml::value& doc, const std::string& file, const std::filesystem::path& base,
             Problems& p) const {
    if (!doc.is_table()) return;
    for (const auto& [sec, table] : doc.as_table()) {
      const Origin so = origin_of(table, file, base);
      if (!has_section(sec)) {
        p.add(so, sec, fmt::format("unknown section [{}]{}", sec, suggest_section(sec)));
        continue;
      }
      if (!table.is_table()) {
        p.add(so, sec, "expected a table [" + sec + "]");
        continue;
      }
      apply_section(t, sec, table, file, base, p);
    }
  }

  /// The keys of one table; a sub-table whose dotted name is a known section ([size.wavelength],
  /// or `wavelength.wl = 30` inside [size]) is applied as that section.
  void apply_section(T& t, const std::string& sec, const toml::value& table, const std::string& file,
                     const std::filesystem::path& base, Problems& p) const {
    for (const auto& [name, value] : table.as_table()) {
      const Origin o = origin_of(value, file, base);
      const Key* k = find(sec, name);
      if (k == nullptr && value.is_table() && has_section(sec + "." + name)) {
        apply_section(t, sec + "." + name, value, file, base, p);
        continue;
      }
      if (k == nullptr) {
        p.add(o, sec + "." + name, fmt::format("unknown key{}", suggest_key(sec, name)));
        continue;
      }
      p.set_at(sec + "." + name, o);
      k->set(t, value, o, p);
    }
  }

  /// Applies one `section.key=value` override; the value is read as TOML, or as a plain string
  /// when it is not valid TOML (so --set output.dir=out2 works without quotes).
  void apply_override(T& t, const std::string& text, Problems& p) const {
    Origin o;
    o.where = "--set " + printable(text);
    o.line = kOverrideLine;  // after every file position
    o.base_dir = std::filesystem::current_path();
    const auto eq = text.find('=');
    const std::string path = eq == std::string::npos ? text : text.substr(0, eq);
    const auto dot = path.rfind('.');  // the key is after the last dot: size.wavelength.wl
    if (eq == std::string::npos || dot == std::string::npos) {
      p.add(o, printable(path), "expected --set section.key=value");
      return;
    }
    const std::string sec = path.substr(0, dot), name = path.substr(dot + 1);
    const Key* k = find(sec, name);
    if (k == nullptr) {
      p.add(o, printable(path),
            fmt::format("unknown key{}", has_section(sec) ? suggest_key(sec, name) : suggest_section(sec)));
      return;
    }
    const std::string raw = text.substr(eq + 1);
    if (!utf8_problem(raw).empty()) {
      p.add(o, printable(path), "value is neither TOML nor plain text (not UTF-8)");
      return;
    }
    toml::value value;
    try {
      std::istringstream in("v = " + raw);
      value = toml::parse(in, "--set").as_table().at("v");
    } catch (const std::exception&) {
      // Not a TOML value: the text itself is the (string) value, when it is text.
      if (!is_plain_text(raw)) {
        p.add(o, path, "value is neither TOML nor plain text (control characters or invalid UTF-8)");
        return;
      }
      value = toml::value(raw);
    }
    p.set_at(path, o);
    k->set(t, value, o, p);
  }

  /// Every key as "section.key", in table order.
  [[nodiscard]] std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& k : keys_) out.push_back(k.section + "." + k.name);
    return out;
  }
  /// Every key as Info{"section.key", its default as the echo has it, help, names}, in table order.
  template <typename Info>
  [[nodiscard]] std::vector<Info> infos() const {
    const Json defaults = echo(T{});
    std::vector<Info> out;
    for (const auto& k : keys_)
      out.push_back({k.section + "." + k.name, defaults[k.section][k.name], k.help, k.values});
    return out;
  }

  /// The effective configuration as JSON: {section: {key: value}} in table order.
  [[nodiscard]] Json echo(const T& t) const {
    Json j = Json::object();
    for (const auto& k : keys_) j[k.section][k.name] = k.get(t);
    return j;
  }

 private:
  [[nodiscard]] bool has_section(const std::string& s) const {
    return std::any_of(keys_.begin(), keys_.end(), [&](const Key& k) { return k.section == s; });
  }
  [[nodiscard]] const Key* find(const std::string& s, const std::string& n) const {
    for (const auto& k : keys_)
      if (k.section == s && k.name == n) return &k;
    return nullptr;
  }
  static std::size_t distance(const std::string& a, const std::string& b) { return edit_distance(a, b); }
  [[nodiscard]] std::string suggest_key(const std::string& sec, const std::string& name) const {
    std::string best;
    std::size_t bd = 3;
    for (const auto& k : keys_)
      if (k.section == sec && distance(k.name, name) < bd) {
        bd = distance(k.name, name);
        best = k.name;
      }
    return best.empty() ? std::string() : fmt::format(" (did you mean {}.{}?)", sec, best);
  }
  [[nodiscard]] std::string suggest_section(const std::string& sec) const {
    std::string best;
    std::size_t bd = 3;
    for (const auto& k : keys_)
      if (distance(k.section, sec) < bd) {
        bd = distance(k.section, sec);
        best = k.section;
      }
    return best.empty() ? std::string() : fmt::format(" (did you mean [{}]?)", best);
  }

  std::vector<Key> keys_;
};

/// Parses a TOML file; a syntax error becomes a ConfigError with toml11's file:line:column text.
inline toml::value parse_file(const std::filesystem::path& path) {
  // A FIFO would block the parser forever, /dev/zero never ends, a directory is not a file.
  if (const std::string problem = input_file_problem(path, kMaxTextFileBytes); !problem.empty())
    throw ConfigError(fmt::format(
        "{}: {}", path.string(),
        problem == "no such file" ? std::string("no such configuration file") : "configuration file " + problem));
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw ConfigError(fmt::format("{}: cannot read", path.string()));
  if (const std::string where = utf8_problem(text); !where.empty())
    throw ConfigError(fmt::format("{}: {}: not UTF-8 text (a TOML file is UTF-8)", path.string(), where));
  try {
    std::istringstream stream(text);
    return toml::parse(stream, path.string());
  } catch (const toml::syntax_error& e) {
    throw ConfigError(fmt::format("{}: TOML syntax error:\n{}", path.string(), e.what()));
  } catch (const std::runtime_error& e) {
    throw ConfigError(fmt::format("{}: cannot read: {}", path.string(), e.what()));
  }
}

}  // namespace aq::config::detail
