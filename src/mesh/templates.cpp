// Triangle templates: option parsing (the table itself is constexpr in templates.hpp).
#include "mesh/templates.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace aq::mesh {

Diagonal parse_diagonal(std::string_view text) {
  if (text == "ne") return Diagonal::kNE;
  if (text == "nw") return Diagonal::kNW;
  if (text == "alternate") return Diagonal::kAlternate;
  throw ConfigError(fmt::format("mesh.diagonal = \"{}\": must be \"ne\", \"nw\" or \"alternate\"", text));
}

}  // namespace aq::mesh
