// SPDX-License-Identifier: GPL-3.0-or-later
// Names of enumerated options: ONE table per enum, beside the enum, that everything else reads
// (the config's key table and its error messages, the help text, the echo in the run report, the
// command-line parsers, the Python binding; a test keeps configs/example.toml's comments in step).
// Adding a value to an enum means adding one row to its table.
//
// An enum E takes part by declaring, in its own namespace (found by argument-dependent lookup):
//
//   inline constexpr std::array<EnumName<Sampling>, 2> kSamplingNames{{
//       {Sampling::kVertex, "vertex", "a pixel is wet when its 4 corners are (the seed's rule)"},
//       {Sampling::kArea, "area", "the deepest raster cell inside the pixel decides"}}};
//   constexpr std::span<const EnumName<Sampling>> enum_names(Sampling) { return kSamplingNames; }
//
// The first row of a value gives its name; a later row of the same value is an alias, accepted by
// parse_name() but never printed or listed (the izogrid file's "mercator" for "ME").
// fmt prints such an enum by its name: fmt::format("{} rule", Sampling::kVertex) is "vertex rule".
#pragma once

#include <fmt/format.h>

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

namespace aq {

/// One row of an enum's name table.
template <typename E>
struct EnumName {
  E value;
  std::string_view name;     ///< as written in configs, on the command line and in reports
  std::string_view meaning;  ///< a few words for help texts ("" for an alias)
};

/// True for an enum with a name table (an `enum_names(E)` found by argument-dependent lookup).
template <typename E>
concept NamedEnum = std::is_enum_v<E> && requires(E e) {
  { enum_names(e) } -> std::convertible_to<std::span<const EnumName<E>>>;
};

/// The name table of E, aliases included.
template <NamedEnum E>
constexpr std::span<const EnumName<E>> names_of() {
  return enum_names(E{});
}

/// True when row `k` of E's table repeats the value of an earlier row (an alias).
template <NamedEnum E>
constexpr bool is_alias(std::size_t k) {
  const auto t = names_of<E>();
  for (std::size_t i = 0; i < k; ++i)
    if (t[i].value == t[k].value) return true;
  return false;
}

/// The name of `value` (its first row); "?" for a value without a row (a bug a test catches).
template <NamedEnum E>
constexpr std::string_view name_of(E value) {
  for (const auto& row : names_of<E>())
    if (row.value == value) return row.name;
  return "?";
}

/// The value named `text` (a name or an alias, exactly as written); nothing for an unknown name.
template <NamedEnum E>
constexpr std::optional<E> parse_name(std::string_view text) {
  for (const auto& row : names_of<E>())
    if (row.name == text) return row.value;
  return std::nullopt;
}

/// parse_name() ignoring ASCII case ("me", "Me" and "ME" alike).
template <NamedEnum E>
constexpr std::optional<E> parse_name_any_case(std::string_view text) {
  const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
  for (const auto& row : names_of<E>()) {
    if (row.name.size() != text.size()) continue;
    bool same = true;
    for (std::size_t k = 0; k < text.size() && same; ++k) same = lower(row.name[k]) == lower(text[k]);
    if (same) return row.value;
  }
  return std::nullopt;
}

/// The names of E without aliases, quoted and separated by ", ": "\"vertex\", \"area\"".
template <NamedEnum E>
std::string name_list(std::string_view quote = "\"") {
  std::string out;
  const auto t = names_of<E>();
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (is_alias<E>(k)) continue;
    if (!out.empty()) out += ", ";
    out.append(quote).append(t[k].name).append(quote);
  }
  return out;
}

/// Every name with its meaning, for help texts: "\"vertex\" (a pixel is wet ...); \"area\" (...)".
template <NamedEnum E>
std::string name_help() {
  std::string out;
  const auto t = names_of<E>();
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (is_alias<E>(k)) continue;
    if (!out.empty()) out += "; ";
    out.append("\"").append(t[k].name).append("\"");
    if (!t[k].meaning.empty()) out.append(" (").append(t[k].meaning).append(")");
  }
  return out;
}

/// The message for a name E does not know: "\"vertx\" is not one of \"vertex\", \"area\"".
template <NamedEnum E>
std::string unknown_name_message(std::string_view text) {
  return std::string("\"").append(text).append("\" is not one of ").append(name_list<E>());
}

}  // namespace aq

/// fmt prints an enum with a name table by its name.
template <aq::NamedEnum E>
struct fmt::formatter<E> : fmt::formatter<std::string_view> {
  template <typename FormatContext>
  auto format(E value, FormatContext& ctx) const {
    return fmt::formatter<std::string_view>::format(aq::name_of(value), ctx);
  }
};
