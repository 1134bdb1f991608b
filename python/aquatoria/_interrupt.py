# SPDX-License-Identifier: GPL-3.0-or-later
"""Ctrl-C during a long call: the C++ work runs on a worker thread while the main thread waits for
it, so Python's SIGINT handler runs at once and raises KeyboardInterrupt in the main thread; the
wait then asks the C++ side to stop (a CancelToken, core/cancel.hpp: the pipeline looks at it
between stages, blocks of rows and blocks of a file), waits until it has unwound, so that every
temporary file of the call is removed and nothing is left behind, and re-raises the
KeyboardInterrupt. A second Ctrl-C while it unwinds stops the waiting (the work still stops at its
next look, and Python waits for it before it exits).

Calls from another thread than the main one run directly: Python delivers KeyboardInterrupt to the
main thread only.
"""

import signal
import threading

from . import _core

#: How often the main thread wakes while it waits (seconds): a SIGINT that the kernel hands to
#: another thread is seen by Python's handler at the main thread's next wake-up.
_POLL_S = 0.05


def _wait(done):
    # Not Thread.join: a KeyboardInterrupt inside join() can leave the thread marked as finished
    # while it still runs (CPython bpo-21822), and Python would then not wait for it at exit.
    while not done.wait(_POLL_S):
        pass


def call(fn, *args, **kwargs):
    """fn(*args, **kwargs), a call into the compiled module, interruptible by Ctrl-C."""
    if threading.current_thread() is not threading.main_thread():
        return fn(*args, **kwargs)
    token = _core.CancelToken()
    box = {}
    done = threading.Event()

    def work():
        try:
            box["value"] = _core.call_with_token(token, fn, *args, **kwargs)
        except BaseException as e:  # handed to the caller's thread
            box["error"] = e
        finally:
            done.set()

    worker = threading.Thread(target=work, name="aquatoria")
    # The worker and the OpenMP threads it starts inherit a mask without SIGINT, so the signal
    # lands on the main thread, which Python's handler runs on.
    blocked = hasattr(signal, "pthread_sigmask")
    if blocked:
        old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        worker.start()
    finally:
        if blocked:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)
    try:
        _wait(done)
    except KeyboardInterrupt:
        token.request()
        try:
            _wait(done)
        except KeyboardInterrupt:
            pass  # a second Ctrl-C: stop waiting (the worker still stops at its next look)
        raise
    if "error" in box:
        error = box.pop("error")
        try:
            raise error
        finally:
            del error
    return box.pop("value")
