"""Builds the extension granchain._granchain with the project's CMake for pip (pyproject.toml).

The C++ sources are listed once, in CMakeLists.txt; this only configures a build folder (or uses
the one named by GRANCHAIN_BUILD_DIR, an existing configured build such as ./build), builds the
target _granchain with the interpreter that runs pip, and puts the library into the package. The
version is the project's (project(granchain VERSION ...) in CMakeLists.txt).
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
# setuptools' own files (build/lib.*, egg-info) go inside the ignored build folder, beside CMake's.
PIP_FILES = pathlib.Path("build") / "pip"


def project_version():
    match = re.search(r"project\(granchain VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())
    if not match:
        raise RuntimeError("CMakeLists.txt: no project(granchain VERSION x.y.z)")
    return match.group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(os.environ.get("GRANCHAIN_BUILD_DIR") or pathlib.Path(self.build_temp).resolve() / "cmake")
        if not (build / "CMakeCache.txt").exists():
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                            f"-DPython3_EXECUTABLE={sys.executable}", "-DGRANCHAIN_BUILD_TESTS=OFF",
                            "-DGRANCHAIN_BUILD_BENCH=OFF"], check=True)
        jobs = str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build), "--target", "_granchain", "-j", jobs], check=True)
        built = sorted((build / "python" / "granchain").glob("_granchain*.so"))
        if not built:
            raise RuntimeError(f"the build in {build} made no _granchain library (is pybind11-dev installed?)")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


(ROOT / PIP_FILES).mkdir(parents=True, exist_ok=True)
setup(
    version=project_version(),
    options={"build": {"build_base": str(PIP_FILES)}, "egg_info": {"egg_base": str(PIP_FILES)}},
    ext_modules=[Extension("granchain._granchain", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
)
