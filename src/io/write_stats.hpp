// SPDX-License-Identifier: GPL-3.0-or-later
// What a mesh writer reports back to its caller (counts go into the run report and the log).
#pragma once

#include <cstdint>

namespace aq::io {

struct WriteStats {
  std::int64_t bytes = 0;              ///< size of the written file
  std::int64_t nodes = 0;              ///< nodes written (with seam duplicates, after pole merging)
  std::int64_t elements = 0;           ///< 2-D elements (faces, cells) written
  std::int64_t boundary_edges = 0;     ///< boundary (coast) edges written
  std::int64_t seam_duplicates = 0;    ///< nodes duplicated at λ0 + 360 (λ–φ plane writers)
  std::int64_t merged_pole_nodes = 0;  ///< pole-row nodes merged away (3-D writers)
  std::int64_t dropped_elements = 0;   ///< elements degenerate after pole merging (3-D writers)
};

}  // namespace aq::io
