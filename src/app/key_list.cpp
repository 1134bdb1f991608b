// SPDX-License-Identifier: GPL-3.0-or-later
// The key list of --keys (see key_list.hpp).
#include "app/key_list.hpp"

#include <fmt/format.h>

namespace aq::app {

void print_keys(const std::vector<config::KeyInfo>& keys, std::FILE* out) {
  for (const config::KeyInfo& k : keys) {
    const std::string line = fmt::format("{} = {}", k.key, k.default_value.dump());
    if (k.help.empty())
      fmt::print(out, "{}\n", line);
    else
      fmt::print(out, "{:<44}  # {}\n", line, k.help);
  }
}

}  // namespace aq::app
