"""End to end: `exofric predict --gamma 0.7168 --paper --json` through the real FE squeeze.

Runs the seven Table 3 structures through ``exofric.simulate.squeeze`` (the FE solver) in a
subprocess. Checks plumbing and sanity, not the paper's friction values (the paper publishes
no friction curves): 7 structures, finite non-negative forces on the requested pressures,
friction = gamma x N exactly, and the applicability flags of exofric's deviation metric
(tests 6 and 7 outside the 20 % region, with a warning on stderr).
"""

from __future__ import annotations

import math

import pytest


@pytest.mark.slow
def test_predict_paper_end_to_end(cli) -> None:  # type: ignore[no-untyped-def]
    r = cli(["predict", "--gamma", "0.7168", "--paper", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    s = d["structures"]
    assert [x["name"] for x in s] == [f"test {i}" for i in range(1, 8)]
    for x in s:
        assert x["pressure_mpa"] == pytest.approx([0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
        f, n = x["predicted_friction_n"], x["squeeze_force_n"]
        # finite and not negative (the FE may report -0.0 or round-off before contact)
        assert len(f) == 6 and all(v is not None and math.isfinite(v) and v >= -1e-9 for v in f)
        assert f == pytest.approx([0.7168 * v for v in n], rel=1e-12)
        assert isinstance(x["in_validated_region"], bool)
        assert isinstance(x["deviation_pct"], float)
    assert [x["in_validated_region"] for x in s] == [True] * 5 + [False] * 2
    assert s[-1]["predicted_friction_n"][-1] > 0      # contact is reached by 0.6 MPa
    assert "test 6" in r.err and "test 7" in r.err and "warning" in r.err
