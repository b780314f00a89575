"""Tables read at 80 columns (issue 20): no ellipsis in a header or a number.

Each command runs in a subprocess with ``COLUMNS=80`` (what rich uses for a terminal's width)
and its rendered tables are checked: every line fits in 80 characters and nothing is cut with
an ellipsis.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EX = ROOT / "examples"

CASES = {
    "predict --paper": ["predict", "--gamma", "0.7168", "--paper", "--pressures", "0.3,0.6"],
    "squeeze": ["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire",
                "1.6", "--shore", "62.5", "--pressures", "0.3,0.6", "--accuracy", "draft"],
    "reduce": ["reduce", str(EX / "rig-log.csv")],
    "fit-friction": ["fit-friction", "--squeeze", str(EX / "friction-squeeze-eq8.csv"),
                     "--friction", str(EX / "rig-log.csv")],
    "control compare": ["control", "compare", "--duration", "8"],
    "inflate": ["inflate", "--shore", "62.5", "--tube-od", "8.3", "--tube-id", "4.97",
                "--pressures", "0.1,0.2,0.3,0.4"],
    "material": ["material", "--shore", "62.5"],
    "design": ["design", str(EX / "sweep-small.toml"), "--out", "{tmp}/d", "--no-plot",
               "--target-torque", "15"],
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_table_fits_80_columns(name: str, tmp_path: Path) -> None:
    env = {**os.environ, "COLUMNS": "80", "LINES": "50"}
    args = [a.replace("{tmp}", str(tmp_path)) for a in CASES[name]]
    proc = subprocess.run([sys.executable, "-m", "exofric", *args], capture_output=True,
                          text=True, env=env, timeout=300, cwd=ROOT)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert lines, "no output"
    too_long = [ln for ln in lines if len(ln) > 80]
    assert not too_long, too_long[:3]
    cut = [ln for ln in lines if "\u2026" in ln]
    assert not cut, cut[:3]


def test_paper_text_output_has_table1_and_the_per_test_errors() -> None:
    """`exofric paper` prints Table 1 and the per-test maximum errors, not only in --json."""
    proc = subprocess.run([sys.executable, "-m", "exofric", "paper"], capture_output=True,
                          text=True, env={**os.environ, "COLUMNS": "80"}, timeout=60)
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    assert "Table 1" in out and "ANSYS Shore 62.5" in out and "9.44" in out
    assert "188.64" in out and "-92.36" in out        # Figs 8-10 maximum errors, tests 6-7
    assert all(len(ln) <= 80 and "\u2026" not in ln for ln in out.splitlines())
