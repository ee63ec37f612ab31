"""Shared fixtures of the Python module's tests (run by ctest as python.pytest,
with PYTHONPATH at <build>/python; see tests/python/CMakeLists.txt)."""

import json
import os
import subprocess

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.environ.get("CAIRN_SOURCE_DIR", os.path.normpath(os.path.join(HERE, "..", "..")))
SHARED_DIR = os.environ.get("CAIRN_SHARED_DIR", os.path.join(SOURCE_DIR, "..", "shared"))


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: builds the module again (the venv install)")


def example(*parts):
    """A path under examples/ of the repository."""
    return os.path.join(SOURCE_DIR, "examples", *parts)


def shared_file(rel):
    """A file of the shared data (../shared/datasets), or skip saying so."""
    path = os.path.join(SHARED_DIR, "datasets", rel)
    if not os.path.exists(path):
        pytest.skip(f"shared/datasets/{rel} not found (CAIRN_SHARED_DIR={SHARED_DIR}): skipping")
    return path


def load_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


@pytest.fixture
def cli():
    """Runs the `cairn` executable (CAIRN_CLI) in the repository's root and
    returns (exit code, stdout, stderr)."""
    exe = os.environ.get("CAIRN_CLI")
    if not exe or not os.path.exists(exe):
        pytest.skip("the cairn executable is not known (CAIRN_CLI): run through ctest")

    def run(*args):
        p = subprocess.run([exe, *args], cwd=SOURCE_DIR, capture_output=True, text=True,
                           check=False)
        return p.returncode, p.stdout, p.stderr
    return run


@pytest.fixture(autouse=True)
def in_source_dir(monkeypatch):
    """Every test runs in the repository's root, so relative paths read as the
    CLI's do."""
    monkeypatch.chdir(SOURCE_DIR)
