"""Shared fixtures of the brdfit Python tests (run by ctest: python3 -m pytest python/tests with
PYTHONPATH=<build>/python and BRDFIT_EXE=<build>/brdfit; docs/python.md)."""
import os
import subprocess

import pytest

import brdfit


@pytest.fixture(scope="session")
def cli():
    """Runs the brdfit CLI of the same build; returns the CompletedProcess."""
    exe = os.environ.get("BRDFIT_EXE")
    if not exe or not os.path.exists(exe):
        pytest.skip("BRDFIT_EXE is not set to the brdfit executable (run through ctest)")

    def run(*args, check=True):
        r = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
        if check and r.returncode != 0:
            raise AssertionError(f"brdfit {' '.join(map(str, args))}: exit {r.returncode}\n"
                                 f"{r.stdout}\n{r.stderr}")
        return r

    return run


# A small lambert+ggx table: 20 x 20 x 40 cells with sqrt theta_h mapping (a few ms to make).
TRUTH = {"lambert.kd_r": 0.3, "lambert.kd_g": 0.2, "lambert.kd_b": 0.1,
         "ggx.ks_r": 0.8, "ggx.ks_g": 0.7, "ggx.ks_b": 0.6, "ggx.alpha": 0.15}
GRID = (20, 20, 40)


@pytest.fixture(scope="session")
def small_table():
    return brdfit.synth("lambert+ggx", TRUTH, grid=GRID)


@pytest.fixture(scope="session")
def small_table_file(tmp_path_factory, small_table):
    path = tmp_path_factory.mktemp("tables") / "small.h5"
    small_table.save(str(path))
    return path
