// SPDX-License-Identifier: GPL-3.0-or-later
// The regional run's kinds (grid_kinds.hpp): what is not a name table.
#include "grid_params/grid_kinds.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace aq::curvilinear {

Stage stage_from_mode(int mode) {
  if (mode < 0 || mode > 5) throw InternalError(fmt::format("stage_from_mode: mode = {} is outside 0..5", mode));
  return mode >= 4 ? Stage::kGrid : static_cast<Stage>(mode);
}

}  // namespace aq::curvilinear
