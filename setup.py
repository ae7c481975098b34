"""setuptools drives CMake for `pip install --no-build-isolation .` (pyproject.toml).

The wheel holds what `make build` makes for Python users: the extension module `brdfit` (the
CMake target brdfit_python) at the top of site-packages, and the `brdfit` command, installed
into the environment's bin/ (docs/python.md, "Installing with pip").

The CMake build folder is `build-pip/` beside this file (configured Release, without tests
and benchmarks), or the one $BRDFIT_CMAKE_BUILD_DIR names: an existing, configured build is
then built (targets brdfit and brdfit_python only) and packaged as it is, which is how the
test suite checks this route without compiling the project a second time. Its Python must be
the installing interpreter's ABI; that is checked, not assumed.
"""

import os
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def project_version():
    """The version of CMakeLists.txt's project() call: one number for C++, CLI and wheel."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        m = re.search(r"project\(\s*brdfit\s+VERSION\s+([0-9][0-9.]*)", f.read())
    if not m:
        sys.exit("setup.py: no 'project(brdfit VERSION ...)' in CMakeLists.txt")
    return m.group(1)


def cmake_build_dir():
    given = os.environ.get("BRDFIT_CMAKE_BUILD_DIR")
    return os.path.abspath(given) if given else os.path.join(ROOT, "build-pip")


def run(cmd):
    print("setup.py: " + " ".join(cmd), flush=True)
    try:
        subprocess.run(cmd, check=True)
    except FileNotFoundError:
        sys.exit(f"setup.py: {cmd[0]} not found (scripts/setup-deps.sh installs the build tools)")
    except subprocess.CalledProcessError as e:
        sys.exit(f"setup.py: '{' '.join(cmd)}' failed with exit status {e.returncode}; "
                 "scripts/setup-deps.sh installs the packages brdfit builds with (Debian 12)")


class CMakeBuild(build_ext):
    """Builds the CMake targets and copies the module and the command where setuptools wants
    them; the command is then installed by install_data (data_files, below)."""

    def build_extension(self, ext):
        build = cmake_build_dir()
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            if "BRDFIT_CMAKE_BUILD_DIR" in os.environ:
                sys.exit(f"setup.py: BRDFIT_CMAKE_BUILD_DIR={build} is not a configured CMake "
                         "build folder (no CMakeCache.txt)")
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            run(["cmake", "-S", ROOT, "-B", build, *generator, "-DCMAKE_BUILD_TYPE=Release",
                 "-DBRDFIT_BUILD_TESTS=OFF", "-DBRDFIT_BUILD_BENCH=OFF", "-DBRDFIT_PYTHON=ON",
                 f"-DPython_EXECUTABLE={sys.executable}"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        run(["cmake", "--build", build, "--target", "brdfit", "brdfit_python", "-j", jobs])

        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        module = os.path.join(build, "python", "brdfit" + suffix)
        if not os.path.exists(module):
            built = [f for f in os.listdir(os.path.join(build, "python"))
                     if f.startswith("brdfit.") and f.endswith(".so")] \
                if os.path.isdir(os.path.join(build, "python")) else []
            sys.exit(f"setup.py: {build} has no Python module for this interpreter "
                     f"({sys.executable}, brdfit{suffix}); it has {built or 'none'}. "
                     "Configure it with -DPython_EXECUTABLE=<this python>, or install "
                     "pybind11 (Debian python3-pybind11) if the module was not built at all")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy2(module, target)
        command = os.path.join(build, "brdfit")
        staged = os.path.join(self.build_temp, "bin", "brdfit")
        os.makedirs(os.path.dirname(staged), exist_ok=True)
        shutil.copy2(command, staged)


# setuptools' own build folder and egg-info go under the CMake build folder, not into the
# source tree, whose build/ is the CMake build of `make build`.
_staging = os.path.join(cmake_build_dir(), "setuptools")
os.makedirs(_staging, exist_ok=True)

setup(
    version=project_version(),
    packages=[],  # no Python packages: the module is the extension alone
    py_modules=[],
    ext_modules=[Extension("brdfit", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # The command, built by CMakeBuild into the temp folder named here, goes to <env>/bin.
    data_files=[("bin", [os.path.join(_staging, "temp", "bin", "brdfit")])],
    options={
        "build": {"build_base": _staging},
        "build_ext": {"build_temp": os.path.join(_staging, "temp")},
        "egg_info": {"egg_base": _staging},
    },
    zip_safe=False,
)
