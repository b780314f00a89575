"""Tolerances propagated to N(P) (issue 19, second part).

References: plain Monte Carlo with NumPy's generator (a different sampler from the Sobol
sequence) on the same FE model, and the linearisation for a small standard deviation (the
percentile band of a nearly linear response is 2 x 1.645 x |dN/dx| sd).
"""

from __future__ import annotations

import numpy as np
import pytest

from exofric.errors import InputError
from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.simulate import squeeze, squeeze_tolerances

P = [0.4, 0.6]
OPTS = {"accuracy": "draft"}


def test_small_tolerance_band_matches_the_linearisation() -> None:
    sd = 0.01                                   # mm on the tube ID: N nearly linear in it
    r = squeeze_tolerances(BASE, 62.5, P, {"tube_id_mm": sd}, samples=64, **OPTS)
    mat = MooneyRivlin.from_shore(62.5)
    h = 0.02
    hi = squeeze(BASE.__class__(**{**BASE.__dict__, "tube_id_mm": BASE.tube_id_mm + h}), mat, P,
                 keep_fields=False, **OPTS).squeeze_force_n
    lo = squeeze(BASE.__class__(**{**BASE.__dict__, "tube_id_mm": BASE.tube_id_mm - h}), mat, P,
                 keep_fields=False, **OPTS).squeeze_force_n
    slope = (np.asarray(hi) - np.asarray(lo)) / (2 * h)
    band = np.asarray(r.percentiles_n[95]) - np.asarray(r.percentiles_n[5])
    np.testing.assert_allclose(band, 2 * 1.645 * np.abs(slope) * sd, rtol=0.08)
    np.testing.assert_allclose(r.percentiles_n[50], r.nominal_n, rtol=5e-3)
    assert r.ranking[0][0] == "tube_id_mm" and r.failed == 0
    d = r.to_dict()
    assert {"squeeze_force_n_p05", "squeeze_force_n_p50", "squeeze_force_n_p95"} <= set(d)


@pytest.mark.slow
def test_quasi_monte_carlo_against_plain_monte_carlo() -> None:
    """ID +-0.1 mm and Shore +-2: 32 Sobol samples against 64 plain MC samples (NumPy); the
    percentiles agree within the plain MC's own sampling error (~4 % at the tails)."""
    tol = {"tube_id_mm": 0.1, "shore": 2.0}
    q = squeeze_tolerances(BASE, 62.5, [0.6], tol, samples=32, **OPTS)
    rng = np.random.default_rng(1)
    mc = []
    for z in rng.standard_normal((64, 2)):
        st = BASE.__class__(**{**BASE.__dict__, "tube_id_mm": BASE.tube_id_mm + 0.1 * z[0]})
        mc.append(squeeze(st, MooneyRivlin.from_shore(62.5 + 2.0 * z[1]), [0.6],
                          keep_fields=False, **OPTS).squeeze_force_n[0])
    for pct in (5, 50, 95):
        assert q.percentiles_n[pct][0] == pytest.approx(np.percentile(mc, pct), rel=0.05)
    # the ranking's shares are a partition of the (linearised) variance at each pressure
    shares = np.array([v for _, v in q.ranking])
    np.testing.assert_allclose(shares.sum(axis=0), 1.0, rtol=1e-12)


def test_bad_tolerances() -> None:
    with pytest.raises(InputError, match="unknown name 'colour'"):
        squeeze_tolerances(BASE, 62.5, P, {"colour": 1.0})
    with pytest.raises(InputError, match="not smaller than the value"):
        squeeze_tolerances(BASE, 62.5, P, {"wire_mm": 5.0})
    with pytest.raises(InputError, match="tolerance tube_id_mm"):
        squeeze_tolerances(BASE, 62.5, P, {"tube_id_mm": -0.1})


def test_failing_nominal_design_is_reported_as_such() -> None:
    """The nominal design's own error reaches the caller: a solver failure stays a
    ConvergenceError (exit 3 in the CLI), not an input error; failing samples are counted."""
    from exofric.errors import ConvergenceError

    def never_converges(st, mat, p):  # type: ignore[no-untyped-def]
        raise ConvergenceError("squeeze did not converge at 0.31 MPa", reached=0.3)

    with pytest.raises(ConvergenceError, match="did not converge at 0.31 MPa"):
        squeeze_tolerances(BASE, 62.5, P, {"tube_id_mm": 0.05}, solver=never_converges)

    calls = []

    def nominal_only(st, mat, p):  # type: ignore[no-untyped-def]
        calls.append(st.tube_id_mm)
        if len(calls) > 1 and st.tube_id_mm > BASE.tube_id_mm:
            raise ConvergenceError("sample did not converge")
        return type("R", (), {"squeeze_force_n": [1.0 + st.tube_id_mm] * len(p)})()

    r = squeeze_tolerances(BASE, 62.5, P, {"tube_id_mm": 0.05}, samples=16,
                           solver=nominal_only)
    above = sum(1 for x in calls[1:17] if x > BASE.tube_id_mm)
    assert r.failed == above and 0 < above < 16
