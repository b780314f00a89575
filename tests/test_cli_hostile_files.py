"""Hostile input FILES for every command that reads a table: exit 2, one line naming the file.

The option sweep (tests/test_cli_hostile.py) attacks option values; this attacks the contents
of the files those options name (issue 38, item 5): a NaN, an inf and a number with a unit in a
data cell, an empty file, a header without rows, and one column named twice (which the readers
accepted silently, taking one of the two). Each file is a valid example of the command's input
with one such damage; runs are in-process (``exofric.cli.run``): a refused file costs
milliseconds. Time: ~3 s.
"""

from __future__ import annotations

import contextlib
import io
import traceback
from pathlib import Path

import pytest

from exofric.cli import run

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
SQUEEZE = EXAMPLES / "friction-squeeze-eq8.csv"
FRICTION = EXAMPLES / "friction-synthetic-eq8.csv"

#: (command before the file, command after it, a valid input file, the column attacked)
READERS = {
    "material --fit": (["material", "--fit"], ["--model", "neo-hookean"],
                       ROOT / "src/exofric/material/data/srmd_dragonskin20_uniaxial.csv",
                       "stress_mpa"),
    "reduce": (["reduce"], [], EXAMPLES / "rig-log.csv", "force_n"),
    "fit-friction --friction": (["fit-friction", "--squeeze", str(SQUEEZE), "--friction"], [],
                                FRICTION, "friction_n"),
    "fit-friction --squeeze": (["fit-friction", "--friction", str(FRICTION), "--squeeze"], [],
                               SQUEEZE, "squeeze_force_n"),
    "control identify": (["control", "identify"], [], EXAMPLES / "step.csv", "pressure_mpa"),
    "gait --data": (["gait", "--strides", "1", "--controller", "ff", "--data"], [],
                    ROOT / "src/exofric/data/gait/walking_stride_opensim.csv", "knee_moment_nm"),
    "calibrate --data": (["calibrate", "--tube-od", "8.3", "--tube-id", "4.97", "--model",
                          "paper-table1", "--data"], [],
                         ROOT / "src/exofric/paper/data/table1_test.csv", "outer_diameter_mm"),
}
DAMAGE = ["nan", "inf", "unit", "empty", "header-only", "column-twice"]


def _damaged(src: Path, column: str, damage: str, out: Path) -> Path:
    lines = src.read_text().splitlines()
    comments = [ln for ln in lines if ln.startswith("#")]
    head, *rows = [ln for ln in lines if ln.strip() and not ln.startswith("#")]
    j, mid = head.split(",").index(column), len(rows) // 2
    cells = rows[mid].split(",")
    if damage in ("nan", "inf"):
        cells[j] = damage
    elif damage == "unit":
        cells[j] += " MPa"
    rows[mid] = ",".join(cells)
    if damage == "empty":
        text = ""
    elif damage == "header-only":
        text = "\n".join([*comments, head]) + "\n"
    elif damage == "column-twice":
        text = "\n".join([*comments, f"{head},{column}",
                          *(f"{r},{r.split(',')[j]}" for r in rows)]) + "\n"
    else:
        text = "\n".join([*comments, head, *rows]) + "\n"
    out.write_text(text)
    return out


@pytest.mark.parametrize("reader", sorted(READERS))
def test_a_damaged_file_is_one_line_exit_2(reader, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    before, after, src, column = READERS[reader]
    for damage in DAMAGE:
        path = _damaged(src, column, damage, tmp_path / f"{damage}.csv")
        err = io.StringIO()
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
            try:
                code = run([*before, str(path), *after, "--json"])
            except BaseException:  # noqa: BLE001 - what a user would see: a traceback
                pytest.fail(f"{reader} {damage}: traceback\n{traceback.format_exc()}")
        lines = [ln for ln in err.getvalue().splitlines()
                 if ln.strip() and not ln.startswith("exofric: warning:")]
        assert code == 2 and len(lines) == 1, (reader, damage, code, err.getvalue())
        assert f"{damage}.csv" in lines[0], (reader, damage, lines[0])
        if damage == "column-twice":
            assert f"column {column!r} is in the file 2 times" in lines[0], lines[0]
