#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The main job: installs what is missing, builds the Release `aquatoria` binary only (not the
# test suite; scripts/test.sh later builds the rest in the same tree, reusing these objects), and
# runs the global mesh with the seed's reference parameters on the installed ETOPO5 (outputs in
# ./out). Extra arguments go to `aquatoria mesh`, e.g.  scripts/run.sh -c configs/global_1deg_L5.toml
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh release aquatoria >/dev/null
exec ./build/aquatoria mesh "$@"
