// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria mesh --keys` and `aquatoria regional --keys`: every configuration key with its default
// and help, the names of an enumerated key with their meanings (from the one name table of each
// option, config/kinds.hpp), as TOML lines a user can copy.
#pragma once

#include <cstdio>
#include <vector>

#include "config/load.hpp"

namespace aq::app {

/// Writes one line per key to `out`: `section.key = <default>  # <help>` (the help only when the
/// key has one), in documentation order.
void print_keys(const std::vector<config::KeyInfo>& keys, std::FILE* out);

}  // namespace aq::app
