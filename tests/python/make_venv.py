# SPDX-License-Identifier: GPL-3.0-or-later
"""The ctest fixture of the Python tests (tests/CMakeLists.txt, test python_install): a fresh virtual
environment inside the build tree with the package installed the way a user installs it,

    python3 -m venv --system-site-packages VENV
    VENV/bin/pip install --no-build-isolation --no-index SOURCE

with AQ_BUILD_DIR set to the build tree, so the install reuses the compiled module (pip builds the
wheel through setup.py, which builds the target aq_python there: nothing to compile when CI has
built it). --no-index: offline, numpy comes from Debian's site packages.

    usage: make_venv.py SOURCE_DIR VENV_DIR
"""

import os
import shutil
import subprocess
import sys
import time


def main():
    source, venv = (os.path.abspath(a) for a in sys.argv[1:3])
    start = time.monotonic()
    shutil.rmtree(venv, ignore_errors=True)
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", venv], check=True)
    pip = [os.path.join(venv, "bin", "python"), "-m", "pip"]
    subprocess.run(pip + ["install", "--no-build-isolation", "--no-index", "--disable-pip-version-check", source],
                   check=True, cwd=venv)
    # The installed copy, imported from outside the clone, is the one the tests get.
    out = subprocess.run([os.path.join(venv, "bin", "python"), "-c",
                          "import aquatoria, os; print(os.path.realpath(aquatoria.__file__))"],
                         check=True, cwd=venv, capture_output=True, text=True).stdout.strip()
    site = os.path.realpath(venv)
    if not out.startswith(site + os.sep):
        sys.exit("make_venv: `import aquatoria` in %s gives %s, not the installed package" % (venv, out))
    print("make_venv: aquatoria installed in %s (%.1f s)" % (os.path.dirname(out), time.monotonic() - start))


if __name__ == "__main__":
    main()
