# SPDX-License-Identifier: GPL-3.0-or-later
"""Fixtures of the Python interface's tests: the command line's files for the same runs.

Run through ctest (label python), which first installs the package with pip into a virtual
environment in the build tree (make_venv.py) and runs pytest with that environment's python
(AQ_PYTHON_VENV names it: the tests then insist on importing the installed copy), with AQ_BINARY
naming the aquatoria executable; by hand, on the package assembled in the build tree:
    PYTHONPATH=build/python AQ_BINARY=build/aquatoria /usr/bin/python3 -m pytest tests/python
"""

import os
import subprocess

import pytest

#: The virtual environment ctest installed the package into (None: whatever `import aquatoria` finds).
VENV = os.environ.get("AQ_PYTHON_VENV")


def pytest_sessionstart(session):
    if VENV:
        import aquatoria

        where = os.path.realpath(aquatoria.__file__)
        if not where.startswith(os.path.realpath(VENV) + os.sep):
            pytest.exit("AQ_PYTHON_VENV=%s, but `import aquatoria` gives %s: the tests must run on the "
                        "installed package" % (VENV, where), returncode=3)

SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ETOPO_DIR = "/usr/share/ferret-vis/data"
#: Every format whose bytes depend only on the mesh (the global run file "tif" included).
FORMATS = ["msh", "ugrid", "vtu", "fort14", "text", "png", "fesom", "schism", "tif"]


def binary():
    path = os.environ.get("AQ_BINARY", os.path.join(SOURCE_DIR, "build", "aquatoria"))
    if not os.path.exists(path):
        pytest.fail("AQ_BINARY=%s does not exist (build the aquatoria target)" % path)
    return path


def cli(args, cwd):
    """Runs the command line; returns (exit code, stderr)."""
    p = subprocess.run([binary()] + args, cwd=cwd, capture_output=True, text=True)
    return p.returncode, p.stderr


def cli_error(args, cwd):
    """The message of `aquatoria ...` failing: its stderr's "error: " line without the prefix."""
    code, err = cli(args, cwd)
    assert code != 0, err
    lines = [l for l in err.splitlines() if l.startswith("error: ")]
    assert lines, err
    return code, "\n".join([lines[0][len("error: "):]] + err.split(lines[0], 1)[1].splitlines()[1:]).strip()


class CliRun:
    def __init__(self, folder, name, config, sets):
        self.folder, self.name, self.config, self.sets = folder, name, config, sets

    def path(self, suffix):
        return os.path.join(self.folder, self.name + suffix)


def _cli_run(tmp_path_factory, key, config, sets):
    folder = str(tmp_path_factory.mktemp("cli_" + key))
    args = ["mesh", "-q", "-o", folder, "--set", "output.name=%s" % key,
            "--set", "output.formats=[%s]" % ", ".join('"%s"' % f for f in FORMATS)]
    if config:
        args += ["-c", config]
    for s in sets:
        args += ["--set", s]
    code, err = cli(args, folder)
    assert code == 0, err
    return CliRun(folder, key, config, sets)


@pytest.fixture(scope="session")
def seed_cli(tmp_path_factory):
    """`aquatoria mesh` (the seed's reference run) with every format."""
    return _cli_run(tmp_path_factory, "seed", None, [])


@pytest.fixture(scope="session")
def mercator_cli(tmp_path_factory):
    """`aquatoria mesh -c configs/global_mercator.toml` with every format."""
    return _cli_run(tmp_path_factory, "mercator", os.path.join(SOURCE_DIR, "configs", "global_mercator.toml"), [])


#: The North Sea regional mesh (open, mainland and island boundaries): every format it can write.
REGIONAL_FORMATS = [f for f in FORMATS if f != "tif"]
NORTH_SEA = os.path.join(SOURCE_DIR, "configs", "north_sea.toml")


@pytest.fixture(scope="session")
def north_sea_cli(tmp_path_factory):
    """`aquatoria mesh -c configs/north_sea.toml` with every format of a regional mesh."""
    folder = str(tmp_path_factory.mktemp("cli_north_sea"))
    args = ["mesh", "-q", "-c", NORTH_SEA, "-o", folder, "--set", "output.name=north_sea",
            "--set", "output.formats=[%s]" % ", ".join('"%s"' % f for f in REGIONAL_FORMATS)]
    code, err = cli(args, folder)
    assert code == 0, err
    return CliRun(folder, "north_sea", NORTH_SEA, [])


@pytest.fixture(scope="session")
def north_sea_run():
    import aquatoria as aq
    return aq.mesh(NORTH_SEA, {"output.formats": REGIONAL_FORMATS})


@pytest.fixture(scope="session")
def seed_run():
    import aquatoria as aq
    return aq.mesh(None, {"output.formats": FORMATS})


@pytest.fixture(scope="session")
def mercator_run():
    import aquatoria as aq
    return aq.mesh(os.path.join(SOURCE_DIR, "configs", "global_mercator.toml"), {"output.formats": FORMATS})
