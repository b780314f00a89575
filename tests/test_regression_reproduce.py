"""Regression pins of `exofric reproduce --fast`: numbers that came out of exofric's own code.

Not independent references (those are in tests/test_reproduce.py: the paper's printed values,
hand arithmetic, np.roots). They only catch unintended changes. Provenance: the shared
``exofric reproduce --fast --json`` run of tests/test_reproduce.py (``fast_report_dir``),
stage 2 (``exofric.reproduction.stage_calibration`` on the fast 1 x 4 inflation mesh), on the
working tree of commit 5b6499e: tube ID 4.966476 mm, Shore 62.568 (the default 2 x 6 mesh
gives 4.9666 mm and 62.57, as documented in docs/paper-notes.md: 4.9666 +- 0.011 mm).
Tolerances: 0.002 mm (the fast mesh is within 2e-4 mm of the default) and 0.05 Shore.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from test_reproduce import fast_report_dir


@pytest.fixture(scope="module")
def results(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    out = fast_report_dir(tmp_path_factory)
    cli = json.loads((out / "cli.json").read_text())
    assert cli["code"] == 0, cli["stderr"]
    return json.loads((Path(out) / "results.json").read_text())


def test_calibration_stage_tube_id_and_shore_pinned(results) -> None:  # type: ignore[no-untyped-def]
    cal = results["stages"]["calibration"]
    assert cal["tube_id_mm"] == pytest.approx(4.9666, abs=0.002)
    assert cal["shore"] == pytest.approx(62.57, abs=0.05)
