# SPDX-License-Identifier: GPL-3.0-or-later
"""Threads: the arrays do not depend on the OpenMP thread count; two Python threads may call at
once (their calls run one after another, each result correct); the GIL is released meanwhile."""

import threading
import time

import numpy as np

import aquatoria as aq

MERCATOR = {"quadtree.lattice": "mercator", "quadtree.mercator_lat_max_deg": 86.5, "rotation.enabled": True,
            "rotation.pole_lon_deg": -44.858333, "rotation.pole_lat_deg": 78.141667,
            "quadtree.size_km": 220.0, "quadtree.coast_size_km": 55.0}


def same(a, b):
    np.testing.assert_array_equal(a.nodes, b.nodes)
    np.testing.assert_array_equal(a.triangles, b.triangles)
    np.testing.assert_array_equal(a.depth, b.depth)
    np.testing.assert_array_equal(a.level, b.level)


def test_one_thread_equals_two():
    one = aq.mesh(None, MERCATOR, threads=1)
    two = aq.mesh(None, MERCATOR, threads=2)
    same(one, two)
    m1 = aq.mask(None, threads=1)
    m2 = aq.mask(None, threads=2)
    np.testing.assert_array_equal(m1.classes, m2.classes)
    np.testing.assert_array_equal(m1.levels, m2.levels)


def test_two_python_threads_at_once(seed_run):
    results, errors = [None, None], []

    def work(k):
        try:
            r = aq.mesh(None, {"output.formats": ["msh"]})
            r.nodes
            results[k] = r
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    for r in results:
        same(r, seed_run)


def test_the_gil_is_released_during_the_run():
    ticks = []
    done = threading.Event()

    def run():
        aq.mesh(None, MERCATOR)
        done.set()

    t = threading.Thread(target=run)
    t.start()
    while not done.is_set():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    t.join()
    # With the GIL held for the whole run this thread could not tick meanwhile.
    assert len(ticks) > 20
