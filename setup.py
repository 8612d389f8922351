"""pip install --no-build-isolation .  builds the compiled module with the project's CMake build
(Debian's pybind11, the interpreter running pip) and installs it with the Python layer.
HORIZON_CMAKE_ARGS adds configure arguments (e.g. "-DHORIZON_CUDA=off")."""
import glob
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def cmake_version():
    """The version in CMakeLists.txt's project(horizon VERSION ...): the one place it is set."""
    with open(os.path.join(ROOT, "CMakeLists.txt")) as cmake:
        return re.search(r"project\(horizon VERSION ([0-9.]+)", cmake.read()).group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.path.abspath(os.path.join(self.build_temp, "cmake"))
        subprocess.run(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DHORIZON_PYTHON=on",
                        f"-DPython_EXECUTABLE={sys.executable}", "-DHORIZON_TESTS=OFF", "-DHORIZON_BENCH=OFF",
                        "-DHORIZON_MPI=OFF", *os.environ.get("HORIZON_CMAKE_ARGS", "").split()], check=True)
        subprocess.run(["cmake", "--build", build, "--target", "_horizon", "-j", str(os.cpu_count() or 1)], check=True)
        (built,) = glob.glob(os.path.join(build, "python", "horizon", "_horizon*.so"))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)


setup(version=cmake_version(), packages=["horizon"], package_dir={"": "python"}, ext_modules=[CMakeExtension("horizon._horizon")],
      cmdclass={"build_ext": CMakeBuild})
