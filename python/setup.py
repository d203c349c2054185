"""Builds the extension uniparam._uniparam with the project's CMake (the
repository root is this directory's parent): configures with
UNIPARAM_PYTHON=ON for the interpreter running this build, builds the
target uniparam_python only, and copies the module into the package.

Environment: UNIPARAM_PY_BUILD_DIR (the CMake build directory, default
python/build/cmake), CMAKE_BUILD_PARALLEL_LEVEL (jobs, default 2).
Needs cmake, a C++17 compiler, FLINT 2.9 + Arb 2.23 and pybind11 (Debian:
scripts/install-deps.sh installs them all).
"""

import glob
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        if not (ROOT / "CMakeLists.txt").is_file() or not (ROOT / "cli" / "json_reports.hpp").is_file():
            raise RuntimeError("uniparam: build from the source tree (python/ inside a clone of the repository); "
                               "%s is not its root" % ROOT)
        build = Path(os.environ.get("UNIPARAM_PY_BUILD_DIR", str(HERE / "build" / "cmake"))).resolve()
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.check_call([
            "cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release", "-DUNIPARAM_PYTHON=ON",
            "-DUNIPARAM_BUILD_TESTS=OFF", "-DUNIPARAM_BUILD_BENCH=OFF", "-DPython_EXECUTABLE=" + sys.executable])
        subprocess.check_call(["cmake", "--build", str(build), "--target", "uniparam_python", "--parallel", jobs])
        built = glob.glob(str(build / "python" / "uniparam" / "_uniparam*.so"))
        if len(built) != 1:
            raise RuntimeError("uniparam: expected one built module in %s, found %r" % (build, built))
        dest = Path(self.get_ext_fullpath(ext.name))
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], dest)


setup(ext_modules=[CMakeExtension("uniparam._uniparam")], cmdclass={"build_ext": CMakeBuild})
