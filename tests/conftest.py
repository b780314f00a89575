"""Shared test helpers."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections.abc import Sequence
from dataclasses import dataclass

import pytest

# One BLAS thread per process, as `make test` sets it (Makefile): with `pytest -n 2` run by hand
# two workers with two BLAS threads each on two cores made the pull-out fits ~10x slower
# (tests/test_pullfit.py: 330 s against 37 s). Set before NumPy is first imported (nothing above
# imports it); the CLI's subprocesses inherit it.
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


@dataclass
class CliResult:
    code: int
    out: str
    err: str

    def json(self) -> dict:
        return json.loads(self.out)


def _run_cli(args: Sequence[str]) -> CliResult:
    proc = subprocess.run(
        [sys.executable, "-m", "exofric", *args], capture_output=True, text=True, timeout=600
    )
    return CliResult(proc.returncode, proc.stdout, proc.stderr)


@pytest.fixture
def cli():
    """Run ``exofric ARGS`` in a subprocess (real exit codes, real stdout/stderr)."""
    return _run_cli


@pytest.fixture(scope="session")
def paper_columns_fits() -> dict:
    """Known-hardness fits of the tube ID (mm) to the paper's ANSYS columns (Table 1), FE model.

    ``{convention: CalibrationResult}`` for the Eq 4 and the printed ("paper-slip") C10;
    computed once (~1 s each) for tests/test_calibrate.py (acceptance against the printed
    diameters) and tests/test_regression_calibrate.py (pins of the fitted numbers).
    """
    from exofric.calibration import InflationData, calibrate

    sim = InflationData.paper_simulated()
    return {c: calibrate(sim, 8.3, model="fe", c10_convention=c) for c in ("eq4", "paper-slip")}
