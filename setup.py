"""Builds and installs the penumbra Python package (python/, docs/python.md) with CMake:

    pip install --no-build-isolation .

The extension module is the CMake target penumbra_python, configured for the interpreter that runs
this (sys.executable) in build-pip/ (the library, without tests, benchmarks or the viewer), then
copied into the package. The dependencies are those of scripts/setup.sh; nothing is downloaded.
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
BUILD = ROOT / "build-pip"  # setuptools' own default, build/, is the release build's folder


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(penumbra VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    """Builds penumbra._penumbra with CMake instead of compiling sources itself."""

    def build_extension(self, extension):
        cmake_build = BUILD / "cmake"
        configure = ["cmake", "-S", str(ROOT), "-B", str(cmake_build), "-DCMAKE_BUILD_TYPE=RelWithDebInfo",
                     f"-DPython3_EXECUTABLE={sys.executable}", "-DPENUMBRA_BUILD_TESTS=OFF",
                     "-DPENUMBRA_BUILD_BENCH=OFF", "-DPENUMBRA_BUILD_VIEWER=OFF", "-DPENUMBRA_BUILD_PYTHON=ON"]
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(cmake_build), "--target", "penumbra_python",
                        "-j", str(os.cpu_count() or 1)], check=True)
        built = list((cmake_build / "python" / "penumbra").glob("_penumbra*.so"))
        if len(built) != 1:
            raise RuntimeError(f"penumbra: CMake made no Python module for {sys.executable} "
                               "(does it import numpy? is pybind11-dev installed?)")
        target = pathlib.Path(self.get_ext_fullpath(extension.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    name="penumbra",
    version=project_version(),
    description="Real-time shadow rendering on Vulkan with a ray-traced ground truth and a comparison metric",
    packages=["penumbra"],
    package_dir={"": "python"},
    package_data={"penumbra": ["__init__.pyi", "py.typed"]},
    ext_modules=[Extension("penumbra._penumbra", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": str(BUILD / "setuptools")}, "egg_info": {"egg_base": str(BUILD)}},
    install_requires=["numpy"],
    python_requires=">=3.9",
    zip_safe=False,
)
