"""Regression pins of the calibration stage: numbers that came out of exofric's own code.

These are not independent references (those are in tests/test_calibrate.py: the paper's
printed diameters, brentq, grids, statsmodels, planted truths). They only catch unintended
changes. Provenance of every number: the ``paper_columns_fits`` fixture (tests/conftest.py),
i.e. ``calibrate(InflationData.paper_simulated(), 8.3, model="fe", c10_convention=C)`` on the
default inflation mesh (2 x 6 quad9), run on the working tree of commit 5b6499e (the same
values as before the package layout change); as documented in
docs/paper-notes.md (tube ID 4.9666 mm, max error 0.422 % with Eq 4; 5.0539 mm, 0.403 % with
the printed C10). Measured then: 4.966628 / 0.422107 and 5.053898 / 0.403158.
Tolerances: 1e-3 mm and 0.005 %-points (the digits documented in the notes).
"""

from __future__ import annotations

import pytest


@pytest.mark.parametrize(
    ("convention", "tube_id_mm", "max_error_pct"),
    [("eq4", 4.9666, 0.422), ("paper-slip", 5.0539, 0.403)],
)
def test_known_hardness_tube_id_and_max_error_pinned(
    paper_columns_fits, convention, tube_id_mm, max_error_pct
) -> None:
    r = paper_columns_fits[convention]
    assert r.tube_id_mm == pytest.approx(tube_id_mm, abs=1e-3)
    assert r.max_error_pct == pytest.approx(max_error_pct, abs=0.005)
