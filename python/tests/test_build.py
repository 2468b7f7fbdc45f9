"""The package's build (python/setup.py) stops before compiling anything, with one message naming
the interpreter and what it lacks, when pybind11, numpy or wheel is missing."""
import re
import subprocess
import sys
from pathlib import Path

from conftest import REPO

# Runs setup.py with the named top-level packages made unimportable (a finder that refuses them),
# as in a Python whose site packages do not hold them.
RUN_WITHOUT = """
import importlib.abc, runpy, sys
hidden = set(sys.argv[1].split(",")) - {""}
class Hide(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in hidden:
            raise ModuleNotFoundError(name)
        return None
sys.meta_path.insert(0, Hide())
sys.argv = ["setup.py", "--version"]
runpy.run_path("setup.py", run_name="__main__")
"""


def setup_without(*hidden):
    return subprocess.run([sys.executable, "-c", RUN_WITHOUT, ",".join(hidden)],
                          cwd=REPO / "python", capture_output=True, text=True)


def test_missing_build_packages_are_named_with_the_interpreter():
    result = setup_without("pybind11", "numpy")
    assert result.returncode != 0
    named = re.match(r"lpir_gseg: (\S+) has no pybind11, numpy, which building", result.stderr)
    assert named and Path(named.group(1)).resolve() == Path(sys.executable).resolve(), \
        result.stderr
    assert "/usr/bin/python3 -m venv --system-site-packages" in result.stderr
    assert "Traceback" not in result.stderr
    result = setup_without("wheel", "setuptools")
    assert result.returncode != 0 and "has no setuptools, wheel" in result.stderr


def test_with_everything_present_setup_runs():
    result = setup_without()
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip().splitlines()[-1] == "0.1.0"
