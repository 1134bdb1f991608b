# SPDX-License-Identifier: GPL-3.0-or-later
"""The package as Python users install it: pip into a fresh virtual environment (ctest's fixture
python_install ran `pip install --no-build-isolation .`, make_venv.py), imported from outside the
clone; a wheel made by `pip wheel`, installed into a second environment and imported there; and the
one message an import gives when it cannot work (no numpy, another Python version)."""

import filecmp
import os
import re
import shutil
import subprocess
import sys
import zipfile

import pytest

from conftest import SOURCE_DIR, VENV


def project_version():
    with open(os.path.join(SOURCE_DIR, "CMakeLists.txt")) as f:
        return re.search(r"project\(aquatoria VERSION ([0-9.]+)", f.read()).group(1)


def clean_env():
    """The environment without PYTHONPATH (nothing from the clone on the path)."""
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    return env


def run_python(python, code, cwd, *args):
    return subprocess.run([python, "-c", code, *args], cwd=cwd, env=clean_env(), capture_output=True, text=True)


@pytest.fixture
def venv_python():
    if not VENV:
        pytest.skip("run by ctest, which installs the package into AQ_PYTHON_VENV")
    return os.path.join(VENV, "bin", "python")


def test_installed_package_from_outside_the_clone_writes_the_cli_ugrid(venv_python, seed_cli, tmp_path):
    code = ("import sys, warnings, aquatoria as aq\n"
            "warnings.simplefilter('ignore')\n"
            "print(aq.__file__)\n"
            "print(aq.mesh(None).write(sys.argv[1], formats=['ugrid'])[0])\n")
    p = run_python(venv_python, code, tmp_path, str(tmp_path / "seed"))
    assert p.returncode == 0, p.stderr
    where, nc = p.stdout.split()
    assert os.path.realpath(where).startswith(os.path.realpath(VENV) + os.sep)
    assert not os.path.realpath(where).startswith(os.path.realpath(os.path.join(SOURCE_DIR, "python")) + os.sep)
    assert filecmp.cmp(nc, seed_cli.path(".nc"), shallow=False)


def test_pip_wheel_installs_into_another_environment(venv_python, tmp_path):
    dist = tmp_path / "dist"
    p = subprocess.run([venv_python, "-m", "pip", "wheel", "--no-build-isolation", "--no-deps", "--no-index",
                        "--disable-pip-version-check", "-w", str(dist), SOURCE_DIR],
                       cwd=tmp_path, env=clean_env(), capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    wheels = os.listdir(dist)
    version = project_version()
    tag = "cp%d%d" % sys.version_info[:2]
    assert wheels == ["aquatoria-%s-%s-%s-linux_x86_64.whl" % (version, tag, tag)], wheels
    wheel = dist / wheels[0]
    with zipfile.ZipFile(wheel) as z:
        names = z.namelist()
        metadata = z.read("aquatoria-%s.dist-info/METADATA" % version).decode()
    package = sorted(n for n in names if n.startswith("aquatoria/"))
    expected = sorted("aquatoria/" + f for f in os.listdir(os.path.join(SOURCE_DIR, "python", "aquatoria"))
                      if f.endswith(".py"))
    assert [n for n in package if n.endswith(".py") and not n.endswith("_build_info.py")] == expected
    assert "aquatoria/_build_info.py" in package
    assert any(re.fullmatch(r"aquatoria/_core\.cpython-\d+-[^/]*\.so", n) for n in package), package
    assert all(n.startswith(("aquatoria/", "aquatoria-%s.dist-info/" % version)) for n in names), names
    assert "Requires-Dist: numpy" in metadata and "Version: %s" % version in metadata
    # a second environment, the wheel alone (no source folder, no build tree)
    other = tmp_path / "other"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(other)], check=True)
    p = subprocess.run([str(other / "bin" / "python"), "-m", "pip", "install", "--no-index", "--no-deps",
                        "--disable-pip-version-check", str(wheel)], env=clean_env(), capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    p = run_python(str(other / "bin" / "python"), "import aquatoria as aq; print(aq.__version__, aq.__file__)", tmp_path)
    assert p.returncode == 0, p.stderr
    got_version, where = p.stdout.split()
    assert got_version == version and os.path.realpath(where).startswith(os.path.realpath(other) + os.sep)


def installed_copy(tmp_path):
    """A copy of the package import would find (to break it on purpose)."""
    import aquatoria

    dest = tmp_path / "site" / "aquatoria"
    shutil.copytree(os.path.dirname(aquatoria.__file__), dest,
                    ignore=shutil.ignore_patterns("__pycache__"))
    return dest


def test_import_without_numpy_says_what_to_install(tmp_path):
    import aquatoria._build_info as built

    dest = installed_copy(tmp_path)
    # -S: no site packages, so no numpy; the copy is the only thing on the path
    code = "import sys; sys.path.insert(0, sys.argv[1]); import aquatoria"
    p = subprocess.run([sys.executable, "-S", "-c", code, str(dest.parent)], env=clean_env(), capture_output=True,
                       text=True, cwd=tmp_path)
    assert p.returncode != 0
    last = p.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: aquatoria needs numpy, which this interpreter, %s" % sys.executable), last
    assert "python3-numpy" in last and built.python in last
    assert "No module named 'numpy'" in last
    assert p.stderr.count("Traceback") == 1  # one message, not a chain


def test_import_by_another_python_version_names_the_one_to_use(tmp_path):
    import aquatoria._build_info as built

    dest = installed_copy(tmp_path)
    info = dest / "_build_info.py"
    info.write_text(info.read_text().replace('python_version = "%s"' % built.python_version,
                                             'python_version = "3.99.0"'))
    code = "import sys; sys.path.insert(0, sys.argv[1]); import aquatoria"
    p = subprocess.run([sys.executable, "-c", code, str(dest.parent)], env=clean_env(), capture_output=True,
                       text=True, cwd=tmp_path)
    assert p.returncode != 0
    last = p.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: aquatoria's compiled module was built for Python 3.99"), last
    assert "-m pip install --no-build-isolation" in last


def test_pip_in_an_environment_without_wheel_says_which_python_to_use(tmp_path):
    # a venv without --system-site-packages has pip and setuptools but no wheel, as pyenv's python3
    # first on PATH: pip --no-build-isolation then fails before CMake with one message naming the fix
    env_dir = tmp_path / "bare"
    subprocess.run([sys._base_executable, "-m", "venv", str(env_dir)], check=True, env=clean_env())
    bare = str(env_dir / "bin" / "python")
    assert subprocess.run([bare, "-c", "import wheel"], capture_output=True).returncode != 0
    env = clean_env()
    env["AQ_BUILD_DIR"] = str(tmp_path / "tree")
    p = subprocess.run([bare, "-m", "pip", "install", "--no-build-isolation", "--no-index", "--no-deps",
                        "--disable-pip-version-check", SOURCE_DIR], cwd=tmp_path, env=env, capture_output=True,
                       text=True)
    assert p.returncode != 0
    out = p.stdout + p.stderr
    assert "aquatoria: building needs the package `wheel` in the interpreter running pip, %s" % bare in out, out
    assert "/usr/bin/python3 -m venv --system-site-packages" in out and "python3-wheel" in out
    assert not (tmp_path / "tree").exists()  # nothing configured or built
