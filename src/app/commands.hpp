// SPDX-License-Identifier: GPL-3.0-or-later
// Subcommands of the `aquatoria` executable. Each file cmd_<name>.cpp defines one
// add_<name>_command(); it registers options on the CLI11 app and sets ctx.run to the action.
// The action returns the exit code; aq::Error escaping it is printed by main with its exit code.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

#include "core/log.hpp"

namespace aq::app {

struct Context {
  Logger log;                ///< stderr logger; verbosity set by -v/-q
  std::function<int()> run;  ///< the chosen subcommand's action
};

void add_info_command(CLI::App& app, Context& ctx);
void add_mesh_command(CLI::App& app, Context& ctx);
void add_regional_command(CLI::App& app, Context& ctx);
void add_check_command(CLI::App& app, Context& ctx);
void add_blocks_command(CLI::App& app, Context& ctx);

}  // namespace aq::app
