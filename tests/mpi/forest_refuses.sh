#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Bad input on the forest engine under `mpirun -np NP` (ctest label mpi): every rank ends with the
# configuration error's exit code 2, the message is printed once and names the key, and no file is
# written. Cases: a coastal band wider than the forest's patches (refused when the configuration is
# loaded, with its position: config::load_global), and a mesh above input.max_memory_gb once the
# leaves are known.
#   forest_refuses.sh AQUATORIA MPIEXEC NP OUTDIR CONFIG
set -uo pipefail
bin=$1 mpiexec=$2 np=$3 out=$4 cfg=$5
fail=0
cfg_args=(-c "$cfg")
check() {  # check NAME EXPECTED-TEXT --set ...
  local name=$1 text=$2
  shift 2
  rm -rf "$out/$name"
  "$mpiexec" --oversubscribe -np "$np" "$bin" mesh "${cfg_args[@]}" --set quadtree.engine=forest "$@" -o "$out/$name" \
    >"$out/$name.log" 2>&1
  local rc=$?
  if [ $rc != 2 ]; then echo "FAIL $name: exit $rc, not 2"; cat "$out/$name.log"; fail=1; fi
  local n
  # the message is printed once: its first line "error: ...", the text there or on a line of the
  # configuration's list of problems below it
  n=$(grep -c "$text" "$out/$name.log")
  if ! grep -q "^error: " "$out/$name.log"; then echo "FAIL $name: no 'error:' line"; fail=1; fi
  if [ "$n" != 1 ]; then echo "FAIL $name: '$text' printed $n times, not once"; cat "$out/$name.log"; fail=1; fi
  if [ -d "$out/$name" ] && [ -n "$(ls -A "$out/$name")" ]; then
    echo "FAIL $name: files written:"; ls "$out/$name"; fail=1
  fi
}
mkdir -p "$out"
check band "quadtree.coast_band = 40: the forest engine needs at most" --set quadtree.coast_band=40
check band_at "^  --set quadtree.coast_band=40: quadtree.coast_band, quadtree.levels, quadtree.engine: " \
  --set quadtree.coast_band=40
# The memory limit once the leaves are known: the seed run with 20 km squares over the whole ocean
# (1.45 million triangles) passes the estimate before the data (0.33 GB per rank) and is stopped
# before the mesh (0.55 GB on rank 0: the mesh alone is 0.31 GB) by a limit of 0.38 GB.
cfg_args=()
check memory "once its 697044 leaves are known (1450796 triangles" --set quadtree.levels=5 --set quadtree.size_km=20 \
  --set input.max_memory_gb=0.38
[ $fail = 0 ] && echo "OK: refused on $np rank(s) with exit 2, one message, no files"
exit $fail
