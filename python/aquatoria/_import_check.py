# SPDX-License-Identifier: GPL-3.0-or-later
"""What ``import aquatoria`` checks before it loads the compiled module, so that a missing piece is
one message at the import naming what to install or which interpreter to use, not an error at the
first array (``No module named 'numpy'``) or a bare ``No module named 'aquatoria._core'``:

* the interpreter's Python version is the one the module was built for (_build_info.py, written by
  python/CMakeLists.txt with the module);
* numpy imports;
* the module loads (its shared libraries, GDAL, netCDF, ..., are installed).
"""

import platform
import sys


def _built_for():
    """(interpreter path, "3.11.2") the module was built for, or None (a tree without the file)."""
    try:
        from . import _build_info
    except ImportError:
        return None
    return _build_info.python, _build_info.python_version


def _this():
    return "%s (Python %s)" % (sys.executable or "this interpreter", platform.python_version())


def _use(built):
    if built is None:
        return "the interpreter aquatoria was built for"
    return "%s (Python %s), the interpreter aquatoria was built for" % built


def check_interpreter():
    """Raises ImportError with one message when aquatoria cannot work in this interpreter."""
    built = _built_for()
    if built is not None:
        want = tuple(int(v) for v in built[1].split(".")[:2])
        if want != tuple(sys.version_info[:2]):
            raise ImportError(
                "aquatoria's compiled module was built for Python %d.%d, but this is %s. Run %s, or install "
                "aquatoria for this interpreter: %s -m pip install --no-build-isolation <aquatoria's source folder>"
                % (want[0], want[1], _this(), _use(built), sys.executable or "python3"))
    try:
        import numpy  # noqa: F401
    except ImportError as e:
        raise ImportError(
            "aquatoria needs numpy, which this interpreter, %s, cannot import (%s). Install numpy for it "
            "(Debian: apt-get install python3-numpy; a virtual environment made with --system-site-packages "
            "sees Debian's), or run %s." % (_this(), e, _use(built))) from None
    try:
        from . import _core  # noqa: F401
    except ImportError as e:
        text = str(e)
        if "cannot open shared object file" in text:
            lib = text.split(":", 1)[0].strip()
            raise ImportError(
                "aquatoria's compiled module needs the shared library %s, which is not installed (%s). Install the "
                "runtime libraries it was built against (on Debian 12: scripts/install_deps.sh of aquatoria's "
                "sources installs them all)." % (lib, text)) from None
        raise ImportError("aquatoria's compiled module cannot be loaded into %s: %s. Run %s, or install aquatoria "
                          "again with this interpreter's pip." % (_this(), text, _use(built))) from None
