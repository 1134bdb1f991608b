#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the Python package `aquatoria` for Debian's /usr/bin/python3 with pip (pyproject.toml;
# README "Python"), for those who want it without a virtual environment. A thin wrapper around
#   /usr/bin/python3 -m pip install --no-build-isolation --no-deps --no-index --upgrade --target DEST .
# (--target: Debian's pip installs nothing into the system interpreter itself, PEP 668), with the
# project's Release tree build/ as the build tree (AQ_BUILD_DIR), so only the Python module is
# compiled when build/ is there. numpy, xarray and netCDF4 come from Debian packages
# (scripts/install_deps.sh). Offline: nothing is downloaded but Debian packages.
#   scripts/install_python.sh              into the user's site-packages (python3 -m site --user-site)
#   scripts/install_python.sh DIR          into DIR (e.g. /usr/local/lib/python3/dist-packages, or a
#                                          folder on PYTHONPATH)
set -euo pipefail
cd "$(dirname "$0")/.."
py=/usr/bin/python3
bash scripts/install_deps.sh
dest="${1:-$("$py" -c 'import site; print(site.getusersitepackages())')}"
mkdir -p "$dest"
AQ_BUILD_DIR="${AQ_BUILD_DIR:-build}" "$py" -m pip install --quiet --no-build-isolation --no-deps --no-index \
  --disable-pip-version-check --root-user-action=ignore --upgrade --target "$dest" .
cd /  # import the installed copy, not anything in the clone
PYTHONPATH="$dest${PYTHONPATH:+:$PYTHONPATH}" "$py" -c \
  'import aquatoria, os; print("aquatoria", aquatoria.__version__, "installed in", os.path.dirname(aquatoria.__file__))'
