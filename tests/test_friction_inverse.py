"""One exact inverse of a friction map built on a squeeze curve (issue 30).

Before, ``CurveInverse`` interpolated P against N by its own PCHIP, which is not the inverse of
the PCHIP of N against P that every forward evaluation uses: on N = 0, 5, 40, 90, 150, 240 N at
0.1..0.6 MPa a 20 N target gave 0.2608 MPa, where the curve gives 22.9 N (+14 %). Now
:meth:`SqueezeCurve.pressure` (the first root of the forward interpolant) is the one inverse,
and the control map, the feedforward, the scheduling, ``exofric invert`` and the design search
all reach it. The reference is the forward interpolant itself, which is what "inverse" means:
N(inverse(F)) == F to 1e-9 relative (Brent to 1e-12 MPa on slopes below 1e3 N/MPa: at most
1e-9 N), and the least such pressure (checked on a fine grid of the forward curve).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

import exofric.friction
from exofric.cli import app
from exofric.control import CurveFrictionMap, PIDGains, ScheduledController, friction_inverse
from exofric.friction import FrictionModel, SqueezeCurve

ISSUE_P = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]
ISSUE_N = [0.0, 5.0, 40.0, 90.0, 150.0, 240.0]

CURVES = {
    "issue": (ISSUE_P, ISSUE_N),
    # contact onset after two zero nodes, then a flat shelf at 5 N, a nearly flat rise
    "flat": ([0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6], [0.0, 0.0, 5.0, 5.0, 5.0 + 1e-7, 30.0, 80.0]),
    "nearly-flat": ([0.2, 0.3, 0.4, 0.5], [10.0, 10.0 + 1e-9, 10.0 + 2e-9, 60.0]),
    "fe-like": (list(np.linspace(0.0, 0.6, 25)),
                list(600.0 * np.clip(np.linspace(0.0, 0.6, 25) - 0.15, 0.0, None) ** 1.5)),
}


def _targets(n: list[float]) -> np.ndarray:
    lo, hi = n[0], max(n)
    t = np.r_[np.linspace(lo, hi, 97), n, np.nextafter(hi, 0.0)]
    return t[(t >= lo) & (t <= hi)]


@pytest.mark.parametrize("name", sorted(CURVES))
def test_forward_of_inverse_is_identity_and_least(name: str) -> None:
    p, n = CURVES[name]
    c = SqueezeCurve(p, n)
    grid = np.linspace(p[0], p[-1], 200001)
    values = c(grid)
    for f in _targets(n):
        x = c.pressure(float(f))
        if f == n[0]:
            # the first node's force: the end of the leading plateau (contact onset)
            assert values[grid > x + 1e-5].min() > f
            continue
        assert c(x) == pytest.approx(f, rel=1e-9, abs=1e-12)
        # least: no pressure of the fine grid below x - 1e-5 MPa reaches f
        assert not np.any(values[grid < x - 1e-5] >= f)


def test_issue_curve_agrees_everywhere() -> None:
    c = SqueezeCurve(ISSUE_P, ISSUE_N)
    p20 = c.pressure(20.0)
    assert c(p20) == pytest.approx(20.0, rel=1e-9)        # the old inverse gave 22.9 N
    fmap = CurveFrictionMap(tuple(ISSUE_P), tuple(ISSUE_N), 0.5)
    assert fmap.inverse(10.0) == p20                       # F = gamma N = 0.5 x 20 N
    assert friction_inverse(fmap, 10.0) == p20             # feedforward of compare/scheduling
    sc = ScheduledController(PIDGains(0.002, 0.004), fmap, slope_ref_n_per_mpa=100.0)
    sc.step(10.0, 0.0, 0.01)
    assert sc.operating_pressure_mpa == p20                # scheduling's operating point
    assert c.pressure_for_friction(10.0, FrictionModel(0.5)) == p20


def test_invert_cli_uses_the_same_inverse(tmp_path) -> None:
    f = tmp_path / "curve.json"
    f.write_text(json.dumps({"pressure_mpa": ISSUE_P, "squeeze_force_n": ISSUE_N}))
    res = CliRunner().invoke(app, ["invert", "--gamma", "0.5", "--target-friction", "10",
                                   "--squeeze", str(f), "--json"])
    assert res.exit_code == 0, res.output
    got = json.loads(res.stdout)["pressure_mpa"]
    assert got == pytest.approx(SqueezeCurve(ISSUE_P, ISSUE_N).pressure(20.0), abs=1e-15)


def test_one_import_path() -> None:
    assert not hasattr(exofric.friction, "CurveInverse")
    assert "CurveInverse" not in exofric.friction.__all__
