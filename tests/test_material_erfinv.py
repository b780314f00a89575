"""The standard-library inverse error function behind the Qi et al. correlation.

``exofric.material`` computes ``erfinv`` from :class:`statistics.NormalDist` (plus one Newton
step) instead of importing ``scipy.special`` (~0.1 s of start-up). Reference: SciPy's
``scipy.special.erfinv`` (Boost), independent code. Tolerance: 2e-15 relative on (-1, 1),
observed <= 5e-16, from 1e-300 up to 1 - 2**-53; the Qi correlation itself agrees to 1e-14.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exofric.material import CORRELATIONS

special = pytest.importorskip("scipy.special")
models = pytest.importorskip("exofric.material._models")

RTOL = 2e-15


def _points() -> np.ndarray:
    near_one = 1.0 - np.logspace(-16, -0.5, 200)
    tiny = np.logspace(-300, -1, 120)
    grid = np.linspace(-0.999999, 0.999999, 4001)
    special_pts = [0.5, np.nextafter(0.5, 0.0), np.nextafter(0.5, 1.0), 1.0 - 2.0**-53, 5e-324]
    pos = np.concatenate([near_one, tiny, special_pts])
    return np.concatenate([pos, -pos, grid])


def test_erfinv_matches_scipy() -> None:
    x = _points()
    ours = np.array([models._erfinv(float(v)) for v in x])
    ref = special.erfinv(x)
    rel = np.abs(ours - ref) / np.abs(ref)
    worst = int(np.argmax(rel))
    assert rel[worst] <= RTOL, f"x = {x[worst]!r}: {ours[worst]!r} vs {ref[worst]!r}"
    assert np.array_equal(np.sign(ours), np.sign(ref))


def test_erfinv_edges_as_scipy() -> None:
    for x in (1.0, -1.0, 0.0, -0.0, 1.5, -2.0, math.nan):  # (erfinv(-0.0) is -0.0 here)
        ours, ref = models._erfinv(x), float(special.erfinv(x))
        assert (math.isnan(ours) and math.isnan(ref)) or ours == ref, x


@pytest.mark.parametrize("shore", [0.5, 10.0, 20.0, 40.0, 62.5, 80.0, 95.0, 99.9])
def test_qi_correlation_matches_the_scipy_formula(shore: float) -> None:
    # S = 100 erf(3.186e-4 sqrt(E[Pa]))  ->  E = (erfinv(S/100) / 3.186e-4)^2 Pa
    ref = float((special.erfinv(shore / 100.0) / 3.186e-4) ** 2) * 1e-6
    assert CORRELATIONS["qi"].func(shore) == pytest.approx(ref, rel=1e-14)
