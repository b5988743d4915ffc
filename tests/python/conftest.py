"""Shared fixtures of the Python module's tests: where the repository, the command line and the
shared test data are, and how to read the command line's OBJ output back exactly."""
import os
import pathlib
import shutil
import subprocess
import tempfile

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = pathlib.Path(os.environ.get("SKINSLIDE_SHARED_DIR", ROOT.parent / "shared"))


def pytest_configure(config):
    """tmp_path folders in a temporary folder of this session, removed when it ends: pytest's own
    default (TMPDIR/pytest-of-USER, the last three sessions kept) would outlive the test run."""
    if config.option.basetemp is None:
        config.option.basetemp = tempfile.mkdtemp(prefix="skinslide_pytest.")
        config.skinslide_basetemp = config.option.basetemp


def pytest_unconfigure(config):
    basetemp = getattr(config, "skinslide_basetemp", None)
    if basetemp:
        shutil.rmtree(basetemp, ignore_errors=True)


def pytest_report_header(config):
    import skinslide
    return f"skinslide module {skinslide.__file__}"


@pytest.fixture(scope="session")
def cli():
    """The command line, run with arguments; fails the test on a non-zero exit."""
    binary = os.environ.get("SKINSLIDE")
    if not binary:
        pytest.fail("SKINSLIDE (the path of the skinslide command) is not set")

    def run(*args):
        done = subprocess.run([binary, "-q", *map(str, args)], capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
    return run


def shared(relative):
    """A file of the shared test data; the test is skipped when it is missing (failed when
    SKINSLIDE_REQUIRE_SHARED=1, as in CI)."""
    path = SHARED / relative
    if not path.exists():
        if os.environ.get("SKINSLIDE_REQUIRE_SHARED") == "1":
            pytest.fail(f"missing {path} (SKINSLIDE_REQUIRE_SHARED=1)")
        pytest.skip(f"missing {path}")
    return path


def obj_positions(path):
    """The `v` lines of an OBJ as float64 (the command writes shortest round-trip numbers, so
    these are the bits it computed)."""
    rows = [line.split()[1:4] for line in open(path) if line.startswith("v ")]
    return np.array(rows, dtype=np.float64)
