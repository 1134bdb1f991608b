#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Where a run waits, stage by stage: the state of each of its threads sampled every 20 ms.

    scripts/stage_states.py build/aquatoria mesh -c configs/global_15s.toml

runs the command (its stdout discarded, its log read from stderr, so do not pass -q) and prints
per stage (the stage ends at its "<stage>: done" line): the wall time, the share of samples in
which the main thread was R (running or waiting for a core), D (waiting for the disk) or S
(sleeping: waiting for another thread or for I/O), and the same summed over the other threads
(OpenMP's team, the writers' threads, the readers' threads; 100 = one thread all the time).

Unlike wall times, these shares say something on a loaded machine too: a stage whose main thread
sleeps half the time waits for another thread (the write stage waiting for the UGRID writer); a
stage whose other threads are never runnable runs on one core; D is the disk. A stage's CPU
seconds are in the run's report (stages[].cpu_s).
"""
import collections
import os
import re
import subprocess
import sys
import threading
import time


def main() -> int:
    if len(sys.argv) < 2:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    p = subprocess.Popen(sys.argv[1:], stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True, bufsize=1)
    ends = []  # (time, stage) of every "<stage>: done" line

    def read_log() -> None:
        for line in p.stderr:
            m = re.match(r"^([a-z_]+): done", line.strip())
            if m:
                ends.append((time.monotonic(), m.group(1)))

    reader = threading.Thread(target=read_log, daemon=True)
    reader.start()
    samples = []  # (time, {tid: state})
    while p.poll() is None:
        snap = {}
        try:
            for tid in os.listdir(f"/proc/{p.pid}/task"):
                try:
                    stat = open(f"/proc/{p.pid}/task/{tid}/stat").read()
                    snap[int(tid)] = stat[stat.rindex(")") + 2]
                except OSError:
                    pass
        except OSError:
            pass
        samples.append((time.monotonic(), snap))
        time.sleep(0.02)
    reader.join(timeout=2.0)
    if p.returncode != 0:
        print(f"stage_states: the command exited with {p.returncode}", file=sys.stderr)
    if not samples:
        return 1

    def stage_of(t: float) -> str:
        for te, s in ends:
            if t <= te:
                return s
        return "(after the last stage)"

    agg = collections.OrderedDict()
    for t, snap in samples:
        a = agg.setdefault(stage_of(t), {"n": 0, "main": collections.Counter(), "others": collections.Counter()})
        a["n"] += 1
        for tid, st in snap.items():
            a["main" if tid == p.pid else "others"][st] += 1
    end_of = {s: te for te, s in ends}
    prev = samples[0][0]
    print(f"{'stage':<24}{'wall s':>8} | main thread R D S % | other threads R D S %")
    for s, a in agg.items():
        te = end_of.get(s, samples[-1][0])
        n = a["n"]
        m, o = a["main"], a["others"]
        print(f"{s:<24}{te - prev:>8.2f} | {100 * m['R'] // n:>6}{100 * m['D'] // n:>4}{100 * m['S'] // n:>4}   | "
              f"{100 * o['R'] // n:>6}{100 * o['D'] // n:>4}{100 * o['S'] // n:>4}")
        prev = te
    return 0 if p.returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
