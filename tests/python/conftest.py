"""Shared fixtures of the hoilcd Python tests (run by ctest as python_pytest).

ctest sets PYTHONPATH to build/python, HOILCD_EXE to the hoilcd executable and
HOILCD_TEST_SOURCE_DIR to the source tree (for tests/data/tiny_room.json)."""
import os
import subprocess
import tempfile

import pytest


def pytest_configure(config):
    # Our own temp folder (pid + suite name), so runs side by side never share one.
    if not config.option.basetemp:
        config.option.basetemp = os.path.join(tempfile.gettempdir(), f"hoilcd_{os.getpid()}_pytest")


@pytest.fixture(scope="session")
def hoilcd_exe():
    return os.environ["HOILCD_EXE"]


@pytest.fixture(scope="session")
def tiny_scene():
    return os.path.join(os.environ["HOILCD_TEST_SOURCE_DIR"], "tests", "data", "tiny_room.json")


@pytest.fixture(scope="session")
def tiny_dataset(tmp_path_factory, hoilcd_exe, tiny_scene):
    """The whole tiny_room sequence (two laps, 440 frames of 128 x 96), rendered by the CLI."""
    out = tmp_path_factory.mktemp("tiny") / "dataset"
    subprocess.run([hoilcd_exe, "-q", "render", tiny_scene, "-o", str(out), "--threads", "2"], check=True,
                   stdout=subprocess.DEVNULL)
    return str(out)


def run_cli(hoilcd_exe, *args):
    """(exit code, stdout, stderr) of the hoilcd executable."""
    done = subprocess.run([hoilcd_exe, "-q", *args], capture_output=True, text=True)
    return done.returncode, done.stdout, done.stderr
