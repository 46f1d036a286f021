"""pip install . : builds the Python module sfit with the project's own CMake build.

    pip install --no-build-isolation .          (offline; see docs/python.md)

CMake configures this source tree in setuptools' temporary build folder (tests, benchmarks
and the install target off), builds the target sfit_python for the interpreter running pip,
and the package python/sfit/ is installed with the compiled sfit/_sfit*.so beside it.
Environment: SFIT_CMAKE_ARGS adds CMake arguments (e.g. -DSFIT_BUILD_EXCHANGE=OFF).
"""

import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(sfit VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        build.mkdir(parents=True, exist_ok=True)
        args = [
            "cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython3_EXECUTABLE={sys.executable}", "-DSFIT_BUILD_PYTHON=ON",
            "-DSFIT_BUILD_TESTS=OFF", "-DSFIT_BUILD_BENCH=OFF", "-DSFIT_INSTALL=OFF",
        ]
        if shutil.which("ninja"):
            args += ["-G", "Ninja"]
        if shutil.which("ccache"):
            args += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"]
        args += shlex.split(os.environ.get("SFIT_CMAKE_ARGS", ""))
        subprocess.run(args, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(build), "--target", "sfit_python", "-j", jobs],
                       check=True)  # builds the CAD module too (STEP/IGES, loaded on first use)
        built = list((build / "python" / "sfit").glob("_sfit*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one built module in {build}/python/sfit, got {built}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)
        # STEP and IGES: the module the compiled part loads on first use, looked for beside it.
        for cad in (build / "src" / "exchange").glob("libsfit_cad.so"):
            shutil.copyfile(cad, target.parent / cad.name)


setup(
    name="sfit",
    version=project_version(),
    description="Rows of 3D points to one B-spline surface within a per-axis tolerance "
                "(Vergeest 1989, SFIT01)",
    python_requires=">=3.9",
    install_requires=["numpy"],
    packages=["sfit"],
    package_dir={"sfit": "python/sfit"},
    package_data={"sfit": ["__init__.pyi", "py.typed"]},
    ext_modules=[Extension("sfit._sfit", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own folder inside build/, apart from a CMake build configured there.
    options={"build": {"build_base": "build/pip"}},
    zip_safe=False,
)
