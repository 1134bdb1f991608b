#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The one list of system packages aquatoria needs (ARCHITECTURE §2). Idempotent: quiet and fast
# when everything is present; otherwise runs `apt-get update` once and installs what is missing.
# Only Debian's registry is used; nothing is downloaded from anywhere else.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libgdal-dev gdal-bin
  libgeographiclib-dev
  libnetcdf-dev netcdf-bin
  libgtest-dev libgmock-dev
  libtoml11-dev libcli11-dev libfmt-dev nlohmann-json3-dev
  libcairo2-dev zlib1g-dev libxxhash-dev xxhash
  libfftw3-dev
  ferret-datasets
  gmsh cdo python3-vtk9 python3-netcdf4 python3-numpy
  # the Python package (python/, pyproject.toml: pip install --no-build-isolation . in a venv;
  # scripts/install_python.sh) and its tests and README picture
  python3-dev pybind11-dev python3-xarray python3-pytest python3-matplotlib
  python3-pip python3-venv python3-setuptools python3-wheel
  # the ADCIRC and ROMS client tests (../shared/clients/adcirc and roms build the models with these)
  gfortran libnetcdff-dev make perl patch xz-utils python3
  # the forest engine (quadtree.engine = "forest": p4est's forest of quadtrees on MPI ranks) and the
  # FESOM2 and SCHISM client tests (MPI models: mpif90/mpicc and mpirun)
  libp4est-dev libopenmpi-dev openmpi-bin
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install_deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install_deps: done" >&2
