"""``exofric._roots.brentq`` against ``scipy.optimize.brentq`` (the independent reference).

The start-up paths (the squeeze's contact onset, the closed-form inflation, the cubic's inverse)
bracket roots with :func:`exofric._roots.brentq` so as not to import all of scipy.optimize.
It follows SciPy's Brent steps, so the roots are asserted *equal* (same iterates, same
stopping rule), and the number of function evaluations too; the errors are checked as well.
"""

from __future__ import annotations

import math

import pytest
from scipy.optimize import brentq as scipy_brentq

from exofric._roots import brentq

CASES = [  # (label, f, a, b, options)
    ("sqrt2", lambda x: x * x - 2.0, 0.0, 2.0, {}),
    ("cos-x", lambda x: math.cos(x) - x, 0.0, 1.0, {}),
    ("cubic", lambda x: x**3 - 2 * x - 5, 2.0, 3.0, {}),
    ("exp, loose xtol", lambda x: math.exp(x) - 10.0, 0.0, 5.0, {"xtol": 1e-6}),
    ("triple root", lambda x: (x - 0.3) ** 3, 0.0, 1.0, {}),
    ("steep onset", lambda x: math.tanh(50 * (x - 0.0751)), 0.0, 0.6,
     {"xtol": 1e-5, "rtol": 1e-12, "maxiter": 60}),
    ("reversed bracket", lambda x: x * x - 2.0, 2.0, 0.0, {}),
    ("jump", lambda x: x - 1e-9 if x > 1e-9 else -1.0, 0.0, 1.0, {"xtol": 1e-12}),
    ("tight", lambda x: math.sin(x), 3.0, 4.0, {"xtol": 1e-14, "rtol": 1e-15}),
    ("root at an end", lambda x: x - 1.0, 1.0, 2.0, {}),
]


@pytest.mark.parametrize("f,a,b,opts", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_same_root_and_evaluations_as_scipy(f, a, b, opts) -> None:
    calls = [0, 0]

    def f_scipy(x: float) -> float:
        calls[0] += 1
        return f(x)

    def f_ours(x: float) -> float:
        calls[1] += 1
        return f(x)

    # tolerance 0: the same algorithm in double precision gives the same bits
    assert brentq(f_ours, a, b, **opts) == scipy_brentq(f_scipy, a, b, **opts)
    assert calls[0] == calls[1]


def test_errors() -> None:
    with pytest.raises(ValueError, match="different signs"):
        brentq(lambda x: x * x + 1.0, -1.0, 1.0)
    with pytest.raises(ValueError, match="xtol"):
        brentq(lambda x: x, -1.0, 1.0, xtol=0.0)
    with pytest.raises(ValueError, match="rtol"):
        brentq(lambda x: x, -1.0, 1.0, rtol=1e-17)
    with pytest.raises(ValueError, match="not finite"):
        brentq(lambda x: math.nan if x > 0 else -1.0, -1.0, 1.0)
    with pytest.raises(RuntimeError, match="no convergence"):
        brentq(lambda x: (x - 0.3) ** 3, 0.0, 1.0, maxiter=5)
