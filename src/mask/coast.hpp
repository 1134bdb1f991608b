// SPDX-License-Identifier: GPL-3.0-or-later
// What the coastal band (quadtree/leaves.hpp) and the size field's coast terms (size/size_field.hpp)
// take for the coast, beyond the edge of the filled set Ω_L (README "Regional FE meshes", "A
// storm-surge mesh"):
//
//   open   a regional run's water beyond the domain edge: the open boundary is not coast, so its
//          squares follow the size field and the level rules like any water, instead of being
//          split to the finest level (the time step is then set by the coast, not the deep edge);
//   sea    a floodplain run (mask.min_depth_m = -z < 0): the filled pixels that are wet at the
//          datum. The shoreline at 0 m lies inside Ω_L; the coast terms measure from it (and the
//          band holds the sea pixels next to it), the floodplain's own terms inland from it.
//
//      land above +z | floodplain (0..z m) | sea (wet at 0 m)          | open (beyond the domain)
//      not filled    | filled, not sea     | filled, sea               | not filled, not coast
//                    ^ mesh land boundary  ^ shoreline at the datum    ^ open boundary
//
// Both are null when they do not apply (a global run; h >= 0), and then everything is as before:
// every pixel outside Ω_L is coast.
#pragma once

#include "core/bitmap.hpp"

namespace aq::mask {

struct CoastSources {
  const Bitmap* open = nullptr;  ///< nx × ny: beyond the domain, in water at the datum (never filled)
  const Bitmap* sea = nullptr;   ///< nx × ny: filled pixels wet at the datum (a subset of Ω_L)
  [[nodiscard]] bool plain() const { return open == nullptr && sea == nullptr; }
};

}  // namespace aq::mask
