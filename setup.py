"""`pip install .` of the Python module `cairn` (docs/python.md), offline and
with Debian's setuptools only (no scikit-build): build_ext runs CMake on this
repository (Release, no tests), builds the one target `cairn_python` and copies
the compiled `_cairn` into the package beside python/cairn/*.py.

    python3 -m venv --system-site-packages v
    v/bin/pip install --no-build-isolation --no-index .

CMAKE_BUILD_PARALLEL_LEVEL sets the build's jobs (default 2).
CAIRN_PREBUILT_EXTENSION, when set, is a `_cairn` already built by CMake
(<build>/python/cairn/_cairn*.so): it is installed as it is, instead of
building the module again (the test suite installs the module it tested).
"""

import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def version():
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        return re.search(r"project\(cairn VERSION ([0-9.]+)", f.read()).group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        target = self.get_ext_fullpath(ext.name)
        prebuilt = os.environ.get("CAIRN_PREBUILT_EXTENSION")
        # cairn-step-reader, the program that reads STEP files (OpenCASCADE
        # runs only there), goes beside the module, where it looks first.
        reader = os.path.join(os.path.dirname(target), "cairn-step-reader")
        if prebuilt:
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copy2(prebuilt, target)
            build = os.path.dirname(os.path.dirname(os.path.dirname(prebuilt)))
            shutil.copy2(os.path.join(build, "cairn-step-reader"), reader)
            return
        build = os.path.join(os.path.abspath(self.build_temp), "cmake")
        subprocess.check_call([
            "cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
            "-DCAIRN_BUILD_TESTS=OFF", "-DCAIRN_BUILD_PYTHON=ON",
            f"-DPython_EXECUTABLE={sys.executable}"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.check_call(["cmake", "--build", build, "--target", "cairn_python",
                               "cairn_step_reader", "-j", jobs])
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy2(os.path.join(build, "python", "cairn", os.path.basename(target)), target)
        shutil.copy2(os.path.join(build, "cairn-step-reader"), reader)


setup(
    name="cairn",
    version=version(),
    description="Does an assembly of rigid parts stay put? Contact LCPs and equilibrium LPs",
    packages=["cairn"],
    package_dir={"": "python"},
    ext_modules=[CMakeExtension("cairn._cairn")],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.8",
    install_requires=["numpy"],
    extras_require={"plot": ["matplotlib"]},
    zip_safe=False,
)
