"""Shared test helpers."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Sequence
from dataclasses import dataclass

import pytest


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
