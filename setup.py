"""setuptools driving CMake (pyproject.toml has the metadata).

`pip install --no-build-isolation --no-index .` runs build_ext below: it
configures the project in build-pip/ (not build/) for the interpreter that runs
pip, builds the targets mdrmap_python and mdrmap only (no tests, no
benchmarks), and puts the extension _core into the package and the program at
mdrmap/bin/mdrmap, which the console script `mdrmap` (mdrmap/_program.py) runs,
with the programs it runs for study and fit (mdrmap-study, mdrmap-fit) beside it.

Environment:
  CMAKE_ARGS                  more configure arguments, split as the shell does
                              (e.g. -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  CMAKE_BUILD_PARALLEL_LEVEL  build jobs (default: every core)
  MDRMAP_PIP_BUILD_DIR        the CMake build directory (default: build-pip)
"""

import os
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
# the program and the programs it runs for `study` and `fit` (from its own directory)
PROGRAMS = ("mdrmap", "mdrmap-study", "mdrmap-fit")


def cmake_version():
    """project(mdrmap VERSION x.y.z) of CMakeLists.txt: one version for both."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        found = re.search(r"project\(\s*mdrmap\s+VERSION\s+([0-9.]+)", f.read())
    if not found:
        raise RuntimeError("setup.py: no project(mdrmap VERSION x.y.z) in CMakeLists.txt")
    return found.group(1)


def run(command, cwd):
    print("setup.py: " + " ".join(shlex.quote(c) for c in command), flush=True)
    subprocess.run(command, cwd=cwd, check=True)


class CMakeBuild(build_ext):
    """Builds the extension and the program with CMake instead of compiling
    the (empty) sources of the Extension."""

    def build_extension(self, ext):
        build_dir = os.path.join(ROOT, os.environ.get("MDRMAP_PIP_BUILD_DIR", "build-pip"))
        cmake = shutil.which("cmake")
        if cmake is None:
            raise RuntimeError("setup.py: cmake not found on PATH (Debian: apt-get install cmake; "
                               "or bash tools/setup.sh)")
        configure = [cmake, "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                     "-DPython_EXECUTABLE=" + sys.executable, "-DMDRMAP_PYTHON=ON",
                     "-DMDRMAP_BUILD_TESTS=OFF", "-DMDRMAP_BUILD_BENCH=OFF"]
        configure += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        run(configure, ROOT)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        run([cmake, "--build", build_dir, "--parallel", jobs,
             "--target", "mdrmap_python", "mdrmap"], ROOT)

        core = self.get_ext_fullpath(ext.name)  # .../mdrmap/_core.<abi>.so
        os.makedirs(os.path.dirname(core), exist_ok=True)
        built = os.path.join(build_dir, "python", "mdrmap", os.path.basename(core))
        if not os.path.isfile(built):
            raise RuntimeError("setup.py: CMake built no " + built + " (is it the extension for "
                               + sys.executable + "?)")
        shutil.copy2(built, core)
        for name in PROGRAMS:
            program = self._program_paths(name)[0]
            os.makedirs(os.path.dirname(program), exist_ok=True)
            shutil.copy2(os.path.join(build_dir, "src", name), program)

    # The programs are outputs besides the extension: built into build_lib,
    # and (pip install -e, build_ext --inplace) copied into the source tree.
    def _program_paths(self, name):
        """(in build_lib, in the source tree) paths of mdrmap/bin/NAME."""
        package_dir = self.get_finalized_command("build_py").get_package_dir("mdrmap")
        return (os.path.join(self.build_lib, "mdrmap", "bin", name),
                os.path.join(package_dir, "bin", name))

    def copy_extensions_to_source(self):
        super().copy_extensions_to_source()
        for name in PROGRAMS:
            built, inplace = self._program_paths(name)
            os.makedirs(os.path.dirname(inplace), exist_ok=True)
            self.copy_file(built, inplace, level=self.verbose)

    def get_outputs(self):
        return super().get_outputs() + [self._program_paths(name)[0] for name in PROGRAMS]

    def get_output_mapping(self):
        mapping = dict(getattr(super(), "get_output_mapping", dict)())
        if self.inplace:
            for name in PROGRAMS:
                built, inplace = self._program_paths(name)
                mapping[built] = inplace
        return mapping


setup(
    version=cmake_version(),
    ext_modules=[Extension("mdrmap._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own build and bdist trees: not in build/, CMake's usual directory
    options={"build": {"build_base": os.path.join("build-pip", "setuptools")}},
)
