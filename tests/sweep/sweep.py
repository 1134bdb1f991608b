#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Configuration sweep (ctest label `sweep`): runs `aquatoria` over a deterministic sample of the
configuration space and checks every run (exit 0, "all checks passed", finite areas).

Global part, on ETOPO5 and ETOPO60 (a 1° raster with another origin and registration): the full
product h × rotation × L (6 × 2 × 4 = 48 runs per raster, so every pair of those three keys; h = -10
is a floodplain to +10 m), and
K, balance and elements assigned from the indices of (h, rotation, L) so that every value of every
key and every pair of keys appears (the assignment is checked below):
  K        = (ih + ir + iL + shift) mod 4
  balance  = (ih + iL + shift) mod 2
  elements = (ih + ir + shift) mod 2
with shift 0 for ETOPO5 and 1 for ETOPO60. Δ0 per L keeps each run small (lattices up to
1920 × 960 pixels) and varies Δ0 too: 2°, 4°, 5°, 6° for L = 2, 3, 4, 5. The rotated runs take the
Mercator lattice (issue 12) when (iL div 2 + ih + shift) is even, so each h, L, K, balance, elements
value meets both lattices (rows to the default |φ′| of 86.5° rounded up to whole level-0 squares); every
run also writes the global run file (`tif`).

Regional part, on the Black Sea contour: every projection × spline type × param × solver ×
schedule in a pairwise design (12 runs; sqrt with max_outer = 80), one full run per projection
with the ROMS stage, and
ROMS refinement grids with factors 3, 5 and 7 of the Black Sea parent.

  sweep.py BINARY PART        PART: global-etopo5-N, global-etopo60-N (N = 0..3: a quarter of the
                              runs each, so ctest -j2 runs them in parallel), regional-ME,
                              regional-LC, regional-ST (one projection each), refine
A failed run prints the exact command that reproduces it.
"""
import itertools
import json
import math
import os
import shlex
import subprocess
import sys
import tempfile
import time

ETOPO = "/usr/share/ferret-vis/data"
HS = [-10, 0, 10, 50, 200, 1000]
ROT = [False, True]
LS = [2, 3, 4, 5]
KS = [1, 2, 3, 4]
BAL = ["face", "corner"]
ELEM = ["triangles", "squares"]
STEP = {2: 2, 3: 4, 4: 5, 5: 6}  # Δ0 per L: pixels of 30', 30', 18.75', 11.25'; four Δ0 values
PARTS = 4


def global_design(shift):
    runs = []
    for (ih, h), (ir, r), (il, lv) in itertools.product(enumerate(HS), enumerate(ROT), enumerate(LS)):
        runs.append(dict(h=h, rot=r, L=lv, K=KS[(ih + ir + il + shift) % 4], balance=BAL[(ih + il + shift) % 2],
                         elements=ELEM[(ih + ir + shift) % 2],
                         lattice="mercator" if r and (il // 2 + ih + shift) % 2 == 0 else "lonlat"))
    return runs


def check_design():
    """Every value of every key, and every pair of keys, appears in each raster's design."""
    values = dict(h=HS, rot=ROT, L=LS, K=KS, balance=BAL, elements=ELEM)
    for shift in (0, 1):
        runs = global_design(shift)
        for a, b in itertools.combinations(values, 2):
            seen = {(r[a], r[b]) for r in runs}
            want = set(itertools.product(values[a], values[b]))
            if seen != want:
                sys.exit(f"sweep design: pairs {a} x {b} missing: {sorted(want - seen)}")
        rotated = [r for r in runs if r["rot"]]
        for a in ("h", "L", "K", "balance", "elements"):
            seen = {(r[a], r["lattice"]) for r in rotated}
            want = set(itertools.product(values[a], ["lonlat", "mercator"]))
            if seen != want:
                sys.exit(f"sweep design: rotated pairs {a} x lattice missing: {sorted(want - seen)}")


class Failures:
    def __init__(self):
        self.list = []
        self.runs = 0

    def run(self, cmd, cwd, check):
        self.runs += 1
        t0 = time.time()
        p = subprocess.run(cmd, cwd=cwd, shell=True, capture_output=True, text=True)
        dt = time.time() - t0
        problem = None
        if p.returncode != 0:
            problem = f"exit {p.returncode}: {p.stderr.strip()[-2000:]}"
        else:
            try:
                problem = check(p)
            except Exception as e:  # a missing report or key is a failure too
                problem = f"{type(e).__name__}: {e}"
        status = "ok  " if problem is None else "FAIL"
        print(f"{status} {dt:6.2f} s  {cmd}", flush=True)
        if problem is not None:
            print(f"     {problem}\n     reproduce with: (cd {shlex.quote(cwd)} && {cmd})", flush=True)
            self.list.append(cmd)


def finite(x):
    return isinstance(x, (int, float)) and math.isfinite(x)


def global_check(out, name):
    def check(p):
        if "all checks passed" not in p.stderr + p.stdout:
            return "the log does not say 'all checks passed'"
        r = json.load(open(os.path.join(out, name + "_report.json")))
        s = r["statistics"]
        if not s["ok"] or s["failed_checks"]:
            return f"report: checks failed: {s['failed_checks']}"
        a = s["area"]
        for k in ("triangles_km2", "filled_km2", "relative_difference"):
            if not finite(a.get(k)):
                return f"report: statistics.area.{k} = {a.get(k)} is not finite"
        if not finite(s.get("total_wet_area_km2")) or s["total_wet_area_km2"] <= 0:
            return f"report: total_wet_area_km2 = {s.get('total_wet_area_km2')}"
        return None
    return check


def run_global(binary, raster, part, tmp):
    shift = 0 if raster == "etopo5" else 1
    runs = global_design(shift)
    f = Failures()
    for k, r in enumerate(runs):
        if k % PARTS != part:
            continue
        name = (f"{raster}_h{r['h']}_K{r['K']}_L{r['L']}_{'rot' if r['rot'] else 'plain'}_{r['balance']}_"
                f"{r['elements']}_{r['lattice']}")
        out = os.path.join(tmp, name)
        sets = [f"input.path={ETOPO}/{raster}.cdf", f"mask.min_depth_m={r['h']}", f"mask.cursor={r['K']}",
                f"quadtree.step_deg={STEP[r['L']]}", f"quadtree.levels={r['L']}", f"quadtree.balance={r['balance']}",
                f"rotation.enabled={'true' if r['rot'] else 'false'}", f"mesh.elements={r['elements']}",
                f"quadtree.lattice={r['lattice']}", f"output.name={name}",
                # fort14 is triangular: refused (a config error) with squares only
                'output.formats=["msh","ugrid","fort14","tif"]' if r["elements"] == "triangles" else
                'output.formats=["msh","ugrid","tif"]']
        cmd = f"{shlex.quote(binary)} mesh -o {shlex.quote(out)} " + " ".join(f"--set {shlex.quote(s)}" for s in sets)
        f.run(cmd, tmp, global_check(out, name))
    return f


def regional_check(out, name, roms):
    def check(p):
        r = json.load(open(os.path.join(out, name + "_report.json")))
        files = {o["file"] for o in r["outputs"]}
        want = [name + "_xygrid.nc"] + ([name + "_grd.nc"] if roms else [])
        for w in want:
            if w not in files or not os.path.getsize(os.path.join(out, w)):
                return f"{w} missing"
        for k, q in r["quality"].items():
            if k.startswith("ortho") and not finite(q["worst"]):
                return f"quality.{k}.worst = {q['worst']} is not finite"
        if r["quality"]["f1"]["worst"] <= 0:
            return f"a non-convex cell: f1 worst {r['quality']['f1']['worst']}"
        return None
    return check


def run_regional(binary, src, tmp, only_proj):
    f = Failures()
    contour = os.path.join(src, "configs", "black_sea.izogrid")
    bs = os.path.join(src, "configs", "black_sea.toml")
    # Pairwise design over spline type, param, solver, schedule within each projection:
    # rows of a 2-level orthogonal array L4(2^3) plus the fourth factor from the projection index.
    oa = [(0, 0, 0), (0, 1, 1), (1, 0, 1), (1, 1, 0)]
    for ip, proj in enumerate(["ME", "LC", "ST"]):
        if proj != only_proj:
            continue
        for row in oa:
            spline = [3, 5][row[0]]
            param = ["index", "arclength"][row[1]]
            solver = ["dst", "sor"][row[2]]
            schedule = ["exponential", "sqrt"][(row[0] + row[1] + row[2] + ip) % 2]
            name = f"bs_{proj}_s{spline}_{param}_{solver}_{schedule}"
            out = os.path.join(tmp, name)
            sets = [f"regional.name={name}", f"regional.proj={proj}", f"regional.spline_type={spline}",
                    f"regional.param={param}", f"regional.solver={solver}", f"regional.schedule={schedule}",
                    "roms.enabled=false"]
            if schedule == "sqrt":
                # The paper's sqrt schedule (about 9 IZ89 passes per outer iteration at m = 40) needs
                # more than the default 40 outer iterations on LC quintic arclength: the inexact inner
                # solves hold the residual at 1.4e-10 for ~20 iterations (a known limit, not a check).
                sets.append("regional.max_outer=80")
            cmd = (f"{shlex.quote(binary)} regional -c {shlex.quote(bs)} -o {shlex.quote(out)} " +
                   " ".join(f"--set {shlex.quote(s)}" for s in sets))
            f.run(cmd, tmp, regional_check(out, name, False))
        # The whole chain (ROMS grid, nesting data) once per projection.
        name = f"bs_{proj}_roms"
        out = os.path.join(tmp, name)
        cmd = (f"{shlex.quote(binary)} regional -c {shlex.quote(bs)} -o {shlex.quote(out)} "
               f"--set regional.name={name} --set regional.proj={proj}")
        f.run(cmd, tmp, regional_check(out, name, True))
    del contour
    return f


def run_refine(binary, src, tmp):
    f = Failures()
    bs = os.path.join(src, "configs", "black_sea.toml")
    parent_dir = os.path.join(tmp, "parent")
    cmd = f"{shlex.quote(binary)} regional -c {shlex.quote(bs)} -o {shlex.quote(parent_dir)}"
    f.run(cmd, tmp, regional_check(parent_dir, "black_sea", True))
    nw = os.path.join(src, "configs", "black_sea_nw_shelf.toml")
    parent = os.path.join(parent_dir, "black_sea_grd.nc")
    for factor in (3, 5, 7):
        name = f"bs_nw_r{factor}"
        out = os.path.join(tmp, name)
        cmd = (f"{shlex.quote(binary)} regional -c {shlex.quote(nw)} -o {shlex.quote(out)} "
               f"--set regional.name={name} --set nesting.parent={shlex.quote(parent)} "
               f"--set nesting.refine_factor={factor}")
        f.run(cmd, tmp, regional_check(out, name, True))
    return f


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    binary, part = os.path.abspath(sys.argv[1]), sys.argv[2]
    src = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    check_design()
    t0 = time.time()
    with tempfile.TemporaryDirectory(prefix=f"aq_sweep_{part}_") as tmp:
        if part.startswith("global-"):
            _, raster, n = part.split("-")
            f = run_global(binary, raster, int(n), tmp)
        elif part.startswith("regional-"):
            f = run_regional(binary, src, tmp, part.split("-")[1])
        elif part == "refine":
            f = run_refine(binary, src, tmp)
        else:
            sys.exit(f"unknown part {part}")
    print(f"sweep {part}: {f.runs} runs, {len(f.list)} failed, {time.time() - t0:.1f} s")
    for c in f.list:
        print(f"FAILED: {c}")
    sys.exit(1 if f.list else 0)


if __name__ == "__main__":
    main()
