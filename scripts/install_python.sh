#!/usr/bin/env bash
# Builds the Python package `aquatoria` with the project's CMake (Release, in build/: the compiled
# module aquatoria/_core*.so beside the package's .py files, build/python/aquatoria) and installs it
# for Debian's /usr/bin/python3, whose numpy, xarray and netCDF4 come from Debian packages
# (scripts/install_deps.sh). Offline: nothing is downloaded but Debian packages.
#   scripts/install_python.sh              into the user's site-packages (python3 -m site --user-site)
#   scripts/install_python.sh DIR          into DIR (e.g. /usr/local/lib/python3/dist-packages, or a
#                                          folder on PYTHONPATH)
set -euo pipefail
cd "$(dirname "$0")/.."
py=/usr/bin/python3
bash scripts/install_deps.sh
bash scripts/build.sh release aq_python aquatoria >/dev/null
dest="${1:-$("$py" -c 'import site; print(site.getusersitepackages())')}"
mkdir -p "$dest"
rm -rf "${dest:?}/aquatoria"
cp -r build/python/aquatoria "$dest/aquatoria"
find "$dest/aquatoria" -name __pycache__ -prune -exec rm -rf {} +
cd /  # import the installed copy, not anything in the clone
PYTHONPATH="$dest${PYTHONPATH:+:$PYTHONPATH}" "$py" -c \
  'import aquatoria, os; print("aquatoria", aquatoria.__version__, "installed in", os.path.dirname(aquatoria.__file__))'
