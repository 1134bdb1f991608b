# SPDX-License-Identifier: GPL-3.0-or-later
"""Ctrl-C (SIGINT sent to the Python process) during a long aquatoria call: KeyboardInterrupt within
a fraction of the run, nothing left behind, and the session usable afterwards.

* aq.mesh on a 1' lattice (Δ0 = 16', L = 4: 21600 × 10800 pixels from ETOPO5), interrupted after
  its read stage, in the middle of the pixel classes: the call raises KeyboardInterrupt long before
  the run would end, and a seed run in the same process afterwards works (the lock and the stop
  request are released).
* Run.write of the seed run with an 8000-pixel preview, interrupted once its first temporary file
  exists: KeyboardInterrupt, and the folder is empty afterwards (no temporary, no partial set).
Each runs in a child process (the signal goes to it alone); its stderr carries the stage lines
(verbose=True), which tell the test when to send the signal.
"""

import os
import signal
import subprocess
import sys
import time

from conftest import ETOPO_DIR

ONE_MINUTE = {"input.path": os.path.join(ETOPO_DIR, "etopo5.cdf"), "quadtree.step_deg": 16 / 60,
              "quadtree.levels": 4}

CHILD_MESH = r"""
import sys, time, warnings
import aquatoria as aq
warnings.simplefilter("ignore")
try:
    aq.mesh(None, %r, verbose=True)
    print("FINISHED", flush=True)
except KeyboardInterrupt:
    print("INTERRUPTED %%.6f" %% time.monotonic(), flush=True)
run = aq.mesh(None)
print("AFTER", len(run.triangles), flush=True)
""" % ONE_MINUTE

CHILD_WRITE = r"""
import sys, os, time, warnings
import aquatoria as aq
warnings.simplefilter("ignore")
run = aq.mesh(None, {"output.png_width": 8000})
print("READY", flush=True)
try:
    run.write(os.path.join(sys.argv[1], "seed"), formats=["msh", "ugrid", "vtu", "fort14", "text", "png"])
    print("FINISHED", flush=True)
except KeyboardInterrupt:
    print("INTERRUPTED %.6f" % time.monotonic(), flush=True)
print("LEFT", sorted(os.listdir(sys.argv[1])), flush=True)
"""


def child(code, *args):
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    return subprocess.Popen([sys.executable, "-c", code, *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, env=env)


def test_ctrl_c_stops_a_1_minute_run_at_once(tmp_path):
    p = child(CHILD_MESH)
    lines, sent = [], None
    for line in p.stdout:
        lines.append(line.rstrip("\n"))
        if sent is None and line.startswith("read: done"):
            time.sleep(0.5)  # into the pixel classes (seconds of work on the 1' lattice)
            sent = time.monotonic()
            p.send_signal(signal.SIGINT)
    p.wait(timeout=600)
    text = "\n".join(lines)
    assert sent is not None, text
    assert p.returncode == 0, text
    assert "FINISHED" not in text, text
    done = [l for l in lines if l.startswith("INTERRUPTED")]
    assert done, text
    latency = float(done[0].split()[1]) - sent
    print("KeyboardInterrupt %.3f s after SIGINT" % latency)
    # The run would go on for tens of seconds (classify, fill, quadtree, mesh, statistics); the
    # pipeline looks at the request between raster chunks and rows, so this is well under a
    # second of CPU time even on a loaded machine.
    assert latency < 10.0, text
    after = lines.index(done[0])
    assert not any(": done" in l for l in lines[after:] if not l.startswith("AFTER")), text
    assert [l for l in lines if l.startswith("AFTER")] and int(lines[-1].split()[1]) > 60000, text


def test_ctrl_c_while_writing_leaves_nothing(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    p = child(CHILD_WRITE, str(out))
    saw_temporary = False
    lines = []
    for line in p.stdout:
        lines.append(line.rstrip("\n"))
        if line.startswith("READY"):
            deadline = time.monotonic() + 120
            while time.monotonic() < deadline and not saw_temporary and p.poll() is None:
                saw_temporary = any(".tmp" in n for n in os.listdir(out))
                if not saw_temporary:
                    time.sleep(0.002)
            if saw_temporary:
                p.send_signal(signal.SIGINT)
    p.wait(timeout=600)
    text = "\n".join(lines)
    assert saw_temporary, "the write ended before its first temporary file was seen:\n" + text
    assert p.returncode == 0, text
    assert any(l.startswith("INTERRUPTED") for l in lines), text
    assert lines[-1] == "LEFT []", text
    assert os.listdir(out) == []
