"""Builds the texproc Python package with CMake, offline, from this source tree.

    pip install --no-build-isolation ./python      (or: python3 -m build --no-isolation ./python)

The extension and texproc's runtime modules (OpenEXR, OpenImageIO,
OpenColorIO) are copied into the package. TEXPROC_CMAKE_BUILD_DIR names a
configured texproc build folder to reuse instead of a fresh one, and
TEXPROC_SOURCE_DIR the source tree when this folder was copied out of it.
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = Path(__file__).resolve().parent
# The texproc source tree (TEXPROC_SOURCE_DIR where this folder was copied out of it).
ROOT = Path(os.environ.get("TEXPROC_SOURCE_DIR") or HERE.parent).resolve()


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(texproc VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        given = os.environ.get("TEXPROC_CMAKE_BUILD_DIR")
        build_dir = Path(given).resolve() if given else Path(self.build_temp).resolve() / "cmake"
        if not (build_dir / "CMakeCache.txt").exists():
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.check_call(
                ["cmake", "-S", str(ROOT), "-B", str(build_dir), *generator, "-DCMAKE_BUILD_TYPE=Release",
                 "-DTEXPROC_BUILD_CLI=OFF", "-DTEXPROC_BUILD_TESTS=OFF", "-DTEXPROC_BUILD_BENCH=OFF",
                 "-DTEXPROC_BUILD_PYTHON=ON", f"-DPython_EXECUTABLE={sys.executable}"])
        subprocess.check_call(["cmake", "--build", str(build_dir), "--target", "texproc_python",
                               "-j", str(os.cpu_count() or 1)])
        built = build_dir / "python" / "texproc"
        dest = Path(self.get_ext_fullpath(ext.name)).resolve().parent
        dest.mkdir(parents=True, exist_ok=True)
        for f in built.iterdir():
            if f.suffix == ".so":
                shutil.copy2(f, dest / f.name)


setup(
    name="texproc",
    version=project_version(),
    description="Texture processing for asset pipelines: mip chains, block compression, normal and cone maps",
    license="Apache-2.0",
    python_requires=">=3.9",
    install_requires=["numpy"],
    packages=["texproc"],
    package_data={"texproc": ["__init__.pyi", "py.typed"]},
    ext_modules=[Extension("texproc._texproc", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
