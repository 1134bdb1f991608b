// Names of the regional run's kinds (grid_kinds.hpp).
#include "grid_params/grid_kinds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <string>

#include "core/error.hpp"

namespace aq::curvilinear {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

}  // namespace

ProjectionKind parse_projection_kind(std::string_view text) {
  const std::string t = lower(text);
  if (t == "me" || t == "mercator") return ProjectionKind::kMercator;
  if (t == "lc" || t == "lambert") return ProjectionKind::kLambertConic;
  if (t == "st" || t == "stereographic") return ProjectionKind::kStereographic;
  throw ConfigError(
      fmt::format("proj = '{}' is not a supported conformal projection (use ME = rotated Mercator, LC = Lambert "
                  "conformal conic or ST = stereographic)",
                  text));
}

std::string projection_code(ProjectionKind kind) {
  switch (kind) {
    case ProjectionKind::kMercator:
      return "ME";
    case ProjectionKind::kLambertConic:
      return "LC";
    case ProjectionKind::kStereographic:
      return "ST";
  }
  return "??";
}

InnerSchedule parse_inner_schedule(std::string_view text) {
  if (text == "exponential") return InnerSchedule::kExponential;
  if (text == "sqrt") return InnerSchedule::kSqrt;
  throw ConfigError(fmt::format("inner pass schedule '{}' is unknown (use 'exponential' or 'sqrt')", text));
}

const char* inner_schedule_name(InnerSchedule schedule) {
  return schedule == InnerSchedule::kExponential ? "exponential" : "sqrt";
}

const char* grid_method_name(GridMethod m) {
  switch (m) {
    case GridMethod::kConformal:
      return "conformal";
    case GridMethod::kBvp:
      return "bvp";
    case GridMethod::kTfi:
      return "tfi";
    case GridMethod::kStar:
      return "star";
    case GridMethod::kEd2:
      return "ed2";
    case GridMethod::kRl:
      return "rl";
    case GridMethod::kBest:
      return "best";
  }
  return "?";
}

bool parse_grid_method(std::string_view text, GridMethod& out) {
  for (const GridMethod m : {GridMethod::kConformal, GridMethod::kBvp, GridMethod::kTfi, GridMethod::kStar,
                             GridMethod::kEd2, GridMethod::kRl, GridMethod::kBest}) {
    if (text == grid_method_name(m)) {
      out = m;
      return true;
    }
  }
  return false;
}

}  // namespace aq::curvilinear
