"""`pip install .` into a fresh virtual environment works offline (Debian's
setuptools, setup.py), and the installed module answers as the built one
does. Under ctest, setup.py installs the module the suite built and tested
(CAIRN_PREBUILT_EXTENSION, with its sanitizer runtime preloaded); without
that variable, its build_ext runs CMake and builds the module again (a
Release build: minutes). Pytest marker `slow`."""

import json
import os
import shutil
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

pytestmark = pytest.mark.slow

SCRIPT = """
import json, cairn
m = cairn.load({scene!r})
print(json.dumps({{"file": cairn.__file__, "stable": cairn.check(m)["stable"],
                  "without_c": cairn.check(m, without=["C"])["moving"]}}))
"""


def test_pip_install_into_a_venv(tmp_path):
    work = os.environ.get("CAIRN_VENV_WORK_DIR") or str(tmp_path)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    # A copy of the sources, so that setuptools' build/ and egg-info stay out
    # of the repository (and out of any build tree inside it).
    src = os.path.join(work, "src")
    shutil.copytree(SOURCE_DIR, src, ignore=shutil.ignore_patterns(
        ".git", "build*", "*.egg-info", "__pycache__", ".cache", "v", "venv*"))
    venv = os.path.join(work, "v")
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", venv], check=True)
    prebuilt = bool(os.environ.get("CAIRN_PREBUILT_EXTENSION"))
    # A module built again is a Release one, without the sanitizers' runtime.
    dropped = ("PYTHONPATH",) if prebuilt else ("PYTHONPATH", "LD_PRELOAD")
    env = {k: v for k, v in os.environ.items() if k not in dropped}
    env.setdefault("CMAKE_BUILD_PARALLEL_LEVEL", "2")
    pip = subprocess.run([os.path.join(venv, "bin", "pip"), "install", "--no-build-isolation",
                          "--no-index", src], env=env, capture_output=True, text=True,
                         check=False)
    assert pip.returncode == 0, pip.stdout[-3000:] + pip.stderr[-3000:]
    scene = os.path.join(SOURCE_DIR, "examples", "paper_fig1.json")
    run = subprocess.run([os.path.join(venv, "bin", "python"), "-c", SCRIPT.format(scene=scene)],
                         env=env, cwd=work, capture_output=True, text=True, check=False)
    assert run.returncode == 0, run.stderr
    out = json.loads(run.stdout)
    assert out["file"].startswith(venv)  # the installed package, not the build tree's
    assert out["stable"] is True and "B" in out["without_c"]
