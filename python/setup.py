"""Builds lpir_gseg: the C++ extension _core through CMake (python/CMakeLists.txt, which compiles
the library from the repository one folder up), and the sensor profiles of ../sensors copied into
the package as lpir_gseg/sensors/, where the installed package finds them.

The build folder of CMake is setuptools' build_temp (python/build/temp.*), kept between pip runs
of the same checkout, so a second install recompiles only what changed. The environment's
CMAKE_CXX_COMPILER_LAUNCHER (ccache) and CMAKE_BUILD_PARALLEL_LEVEL are honoured; LPIR_PY_DEBUG=1
builds with debug information instead of Release.

Before anything is built it checks that the Python running it has what the build needs (pybind11,
numpy, and setuptools able to make a wheel) and stops with one message naming that Python and
what to install when it does not: the build would otherwise fail much later, or as pip's
"invalid command 'bdist_wheel'".
"""
import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path


def _check_build_requirements() -> None:
    """Exits with a message naming the interpreter and what it lacks."""

    def found(name: str) -> bool:
        try:
            return importlib.util.find_spec(name) is not None
        except ImportError:  # a parent package is missing
            return False

    missing = [name for name in ("setuptools", "pybind11", "numpy") if not found(name)]
    if not found("setuptools.command.bdist_wheel") and not found("wheel"):
        missing.append("wheel")
    if not missing:
        return
    sys.exit(
        f"lpir_gseg: {sys.executable} has no {', '.join(missing)}, which building lpir_gseg "
        "needs.\nUse Debian's /usr/bin/python3, whose site packages hold python3-setuptools, "
        "python3-pybind11, python3-numpy and python3-wheel (scripts/install_deps.sh installs "
        "them), and a venv that sees them:\n"
        "  /usr/bin/python3 -m venv --system-site-packages venv\n"
        "  venv/bin/pip install --no-build-isolation --no-index ./python\n"
        "With another Python (pyenv, conda, a newer system Python), install those packages into "
        "it first: pip install setuptools pybind11 numpy wheel (docs/python.md).")


_check_build_requirements()

from setuptools import Extension, setup  # noqa: E402 (after the check, which names what is missing)
from setuptools.command.build_ext import build_ext  # noqa: E402
from setuptools.command.build_py import build_py  # noqa: E402

HERE = Path(__file__).resolve().parent
REPO = HERE.parent


class CMakeExtension(Extension):
    """An extension whose sources CMake knows (python/CMakeLists.txt)."""

    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        import pybind11

        if not (REPO / "CMakeLists.txt").is_file():
            raise RuntimeError(
                f"{REPO}/CMakeLists.txt is missing: lpir_gseg builds from a checkout of the "
                "repository (pip install <repo>/python), not from a copy of python/ alone")
        target = Path(self.get_ext_fullpath(ext.name)).resolve()
        build_dir = Path(self.build_temp).resolve() / "cmake"
        build_dir.mkdir(parents=True, exist_ok=True)
        config = "RelWithDebInfo" if os.environ.get("LPIR_PY_DEBUG") == "1" else "Release"
        generator = ["-G", "Ninja"] if shutil.which("ninja") else []
        cache = build_dir / "CMakeCache.txt"
        if cache.is_file() and generator and "CMAKE_GENERATOR:INTERNAL=Ninja" not in cache.read_text():
            shutil.rmtree(build_dir)  # configured by another generator: cmake would refuse
            build_dir.mkdir(parents=True)
        configure = [
            "cmake", "-S", str(HERE), "-B", str(build_dir), *generator,
            f"-DCMAKE_BUILD_TYPE={config}",
            f"-DCMAKE_LIBRARY_OUTPUT_DIRECTORY={target.parent}",
            f"-DPython_EXECUTABLE={sys.executable}",
            f"-DPYTHON_EXECUTABLE={sys.executable}",
            f"-Dpybind11_DIR={pybind11.get_cmake_dir()}",
        ]
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 2)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "_core",
                        "--parallel", jobs], check=True)
        built = next(target.parent.glob("_core.*"), None)
        if built is None or built.name != target.name:
            raise RuntimeError(f"CMake built {built}, setuptools expects {target.name}")


class BuildPyWithSensors(build_py):
    """Copies ../sensors (the profiles and their README) into the package as sensors/."""

    def run(self):
        super().run()
        dest = Path(self.build_lib) / "lpir_gseg" / "sensors"
        dest.mkdir(parents=True, exist_ok=True)
        profiles = sorted((REPO / "sensors").glob("*.txt"))
        if not profiles:
            raise RuntimeError(f"no sensor profiles in {REPO / 'sensors'}")
        for source in profiles + [REPO / "sensors" / "README.md"]:
            shutil.copyfile(source, dest / source.name)


setup(
    ext_modules=[CMakeExtension("lpir_gseg._core")],
    cmdclass={"build_ext": CMakeBuild, "build_py": BuildPyWithSensors},
)
