#!/usr/bin/env bash
# The main job: installs what is missing, builds Release, and runs the global mesh with the
# seed's reference parameters on the installed ETOPO5 (outputs in ./out). Extra arguments go to
# `aquatoria mesh`, e.g.  scripts/run.sh -c configs/global_1deg_L5.toml
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh release >/dev/null
exec ./build/aquatoria mesh "$@"
