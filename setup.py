# SPDX-License-Identifier: GPL-3.0-or-later
"""The build of the Python package for setuptools (pyproject.toml names it as the backend).

The compiled module aquatoria._core is a target of the project's CMake (python/CMakeLists.txt), so
build_ext here does not compile anything itself: it configures a CMake build tree when there is none,
builds the one target `aq_python` in it (with what it links: the stage libraries and aq_app) and
copies the module into the wheel beside the package's .py files and _build_info.py.

The build tree (environment, read at build time):
  AQ_BUILD_DIR   the CMake build tree to use or make; relative to this folder; default `build`, the
                 project's Release tree (scripts/build.sh release), so a clone that has been built,
                 or CI's tree, installs without compiling the libraries again. A tree configured
                 for another source folder, or a sanitizer tree, is refused with a message.
  AQ_JOBS        parallel compile jobs (default: the number of CPUs), as for scripts/build.sh.
A fresh tree is configured as Release with Ninja when it is installed (else Makefiles) and with
the C/C++ compiler launchers of CMAKE_<LANG>_COMPILER_LAUNCHER (ccache) when they are set.
The interpreter the module is built for is the one running this build (for a virtual environment,
the interpreter it was made from: the same headers and ABI); CMake's AQ_PYTHON_EXECUTABLE.
"""

import os
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build import build
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def project_version():
    """The version of CMakeLists.txt's project() (one number for the command and the package)."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        m = re.search(r"project\(\s*aquatoria\s+VERSION\s+([0-9][0-9.]*)", f.read())
    if not m:
        raise RuntimeError("CMakeLists.txt: no `project(aquatoria VERSION x.y.z)` to take the version from")
    return m.group(1)


def build_dir():
    """The CMake build tree: AQ_BUILD_DIR (relative to the source folder) or build/."""
    d = os.environ.get("AQ_BUILD_DIR", "").strip() or "build"
    return os.path.abspath(os.path.join(ROOT, os.path.expanduser(d)))


def base_interpreter():
    """The interpreter the module is for: this one, or the one a virtual environment was made from
    (a venv's python is a link to it; its cached path would vanish with the venv)."""
    base = getattr(sys, "_base_executable", None) or sys.executable
    return base if os.path.exists(base) else sys.executable


def read_cache(folder):
    """CMakeCache.txt of `folder` as {name: value}, or None when there is none."""
    path = os.path.join(folder, "CMakeCache.txt")
    if not os.path.exists(path):
        return None
    cache = {}
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            m = re.match(r"([A-Za-z0-9_.+-]+):[A-Z_]+=(.*)$", line.rstrip("\n"))
            if m:
                cache[m.group(1)] = m.group(2)
    return cache


def same_file(a, b):
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


class BuildError(Exception):
    pass


def run(cmd, what):
    print("aquatoria: " + " ".join(cmd), flush=True)
    if subprocess.call(cmd, cwd=ROOT) != 0:
        raise BuildError("%s failed (the command above); its output is above (pip: run with -v to see it)" % what)


def configure(folder, python):
    """Configures `folder` for the module unless it already is: a fresh tree as Release, an
    existing one keeping its build type and options (only the Python ones are set)."""
    cache = read_cache(folder)
    if cache is not None:
        home = cache.get("CMAKE_HOME_DIRECTORY", "")
        if home and not same_file(home, ROOT):
            raise BuildError("AQ_BUILD_DIR=%s is the build tree of %s, not of %s: choose another folder" %
                             (folder, home, ROOT))
        for flag in ("AQ_SANITIZE", "AQ_FUZZ"):
            if cache.get(flag, "OFF").upper() in ("ON", "1", "TRUE", "YES"):
                raise BuildError("AQ_BUILD_DIR=%s is a %s tree (the module cannot load sanitizer-built code "
                                 "into Python): use a Release tree such as build/" % (folder, flag))
        if cache.get("AQ_PYTHON", "").upper() in ("ON", "1", "TRUE", "YES") and \
                same_file(cache.get("AQ_PYTHON_EXECUTABLE", ""), python):
            return  # configured for this interpreter: only the build runs (it re-configures itself if needed)
        cmd = ["cmake", "-S", ROOT, "-B", folder]
    else:
        cmd = ["cmake", "-S", ROOT, "-B", folder, "-DCMAKE_BUILD_TYPE=Release"]
        if shutil.which("ninja"):
            cmd += ["-G", "Ninja"]
    run(cmd + ["-DAQ_PYTHON=ON", "-DAQ_PYTHON_EXECUTABLE=" + python], "configuring the CMake build tree")


class CMakeExtension(Extension):
    """The module aquatoria._core, built by CMake's target aq_python."""

    def __init__(self, name):
        super().__init__(name, sources=[])


class BuildCMake(build_ext):
    def build_extension(self, ext):
        folder = build_dir()
        python = base_interpreter()
        try:
            configure(folder, python)
            jobs = os.environ.get("AQ_JOBS", "").strip() or str(os.cpu_count() or 1)
            run(["cmake", "--build", folder, "--target", "aq_python", "-j", jobs], "building the target aq_python")
        except BuildError as e:
            sys.exit("error: aquatoria: %s" % e)
        package = os.path.join(folder, "python", "aquatoria")
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        built = os.path.join(package, "_core" + suffix)
        if not os.path.exists(built):
            found = sorted(f for f in os.listdir(package) if f.startswith("_core")) if os.path.isdir(package) else []
            sys.exit("error: aquatoria: %s has no _core%s for this Python %d.%d (found: %s); the tree was built "
                     "for another interpreter" % (package, suffix, sys.version_info[0], sys.version_info[1],
                                                  ", ".join(found) or "none"))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)
        # _build_info.py: what the module was built for (aquatoria/__init__.py names it when the
        # import fails), made by CMake beside the module.
        shutil.copyfile(os.path.join(package, "_build_info.py"), os.path.join(os.path.dirname(target), "_build_info.py"))


class Build(build):
    """setuptools' build, starting from an empty package folder: its folder is kept between builds
    (inside the CMake tree), and a module since removed from python/aquatoria must not stay in it."""

    def run(self):
        shutil.rmtree(os.path.join(self.build_lib, "aquatoria"), ignore_errors=True)
        super().run()


def check_build_tools():
    """pip --no-build-isolation builds with what the interpreter running it has: without `wheel`
    setuptools stops with "invalid command 'bdist_wheel'", which names neither the cause nor the fix
    (pyenv's or conda's python3 first on PATH, a venv made without --system-site-packages)."""
    try:
        import wheel  # noqa: F401
    except ImportError:
        sys.exit("aquatoria: building needs the package `wheel` in the interpreter running pip, %s (Python %s), "
                 "and pip --no-build-isolation takes only what it has. Make the virtual environment with "
                 "Debian's interpreter, which sees Debian's wheel, setuptools and numpy (apt-get install "
                 "python3-wheel python3-setuptools python3-numpy): /usr/bin/python3 -m venv --system-site-packages "
                 ".venv; or install wheel for this one" % (sys.executable, sys.version.split()[0]))


check_build_tools()
# setuptools' own working folders (build/lib.*, bdist.*) go inside the CMake tree, not beside it.
_work = os.path.join(build_dir(), "python-setuptools")
os.makedirs(_work, exist_ok=True)
setup(
    version=project_version(),
    ext_modules=[CMakeExtension("aquatoria._core")],
    cmdclass={"build": Build, "build_ext": BuildCMake},
    options={"build": {"build_base": _work}, "egg_info": {"egg_base": _work}},
)
