"""A bracketing root finder that does not import :mod:`scipy.optimize` (start-up time).

``from scipy.optimize import brentq`` imports all of :mod:`scipy.optimize` (linear
programming, global optimisers, ...: about 0.15 s of every process that brackets a root, such as
the contact onset of every squeeze). :func:`brentq` here is Brent's method in the form of
SciPy's ``brentq`` (Brent 1973, ch. 4, as written in SciPy's ``Zeros/brentq.c`` by Charles
Harris): the same steps, the same stopping rule ``|b - a| / 2 < (xtol + rtol |x|) / 2``, so it
returns the same root (``tests/test_roots.py`` compares it with ``scipy.optimize.brentq``).
"""

from __future__ import annotations

import math
from collections.abc import Callable

__all__ = ["brentq"]

_EPS = 2.220446049250313e-16


def brentq(f: Callable[..., float], a: float, b: float, *, xtol: float = 2e-12,
           rtol: float = 4 * _EPS, maxiter: int = 100) -> float:
    """A root of ``f`` in ``[a, b]`` by Brent's method (``f(a)`` and ``f(b)`` of opposite signs).

    Parameters
    ----------
    f : callable
        A continuous function of one float, returning a finite float.
    a, b : float
        The bracket (in ``f``'s unit; either order).
    xtol, rtol : float
        The root is returned once it is bracketed within ``xtol + rtol |x|`` (``xtol > 0``,
        ``rtol >= 4 eps``, as in SciPy).
    maxiter : int
        Most iterations (evaluations of ``f`` after the two ends).

    Returns
    -------
    float
        The root.

    Raises
    ------
    ValueError
        If the tolerances are invalid, ``f(a)`` and ``f(b)`` have the same sign, or ``f``
        returns a value that is not finite.
    RuntimeError
        If the root is not bracketed within the tolerance after ``maxiter`` iterations.

    Examples
    --------
    >>> round(brentq(lambda x: x * x - 2.0, 0.0, 2.0), 12)
    1.414213562373
    """
    if not xtol > 0.0:
        raise ValueError(f"xtol must be > 0, got {xtol!r}")
    if not rtol >= 4 * _EPS:
        raise ValueError(f"rtol must be >= 4 eps ({4 * _EPS:.3g}), got {rtol!r}")
    xpre, xcur = float(a), float(b)
    fpre, fcur = _value(f, xpre), _value(f, xcur)
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    if math.copysign(1.0, fpre) == math.copysign(1.0, fcur):
        raise ValueError(f"f(a) and f(b) must have different signs, got f({xpre!r}) = {fpre!r} "
                         f"and f({xcur!r}) = {fcur!r}")
    xblk = fblk = spre = scur = 0.0
    for _ in range(maxiter):
        if fpre != 0.0 and fcur != 0.0 and (
                math.copysign(1.0, fpre) != math.copysign(1.0, fcur)):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):   # xcur: the best estimate so far
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2.0
        sbis = (xblk - xcur) / 2.0
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        spre, scur = _step(xpre, xcur, xblk, fpre, fcur, fblk, spre, scur, sbis, delta)
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0.0 else -delta)
        fcur = _value(f, xcur)
    raise RuntimeError(f"brentq: no convergence after {maxiter} iterations, last x = {xcur!r}")


def _step(xpre: float, xcur: float, xblk: float, fpre: float, fcur: float, fblk: float,
          spre: float, scur: float, sbis: float, delta: float) -> tuple[float, float]:
    """``(spre, scur)``: the next step; interpolated where short and safe, else bisection."""
    if abs(spre) > delta and abs(fcur) < abs(fpre):
        if xpre == xblk:   # secant (linear interpolation)
            stry = -fcur * (xcur - xpre) / (fcur - fpre)
        else:              # inverse quadratic interpolation
            dpre = (fpre - fcur) / (xpre - xcur)
            dblk = (fblk - fcur) / (xblk - xcur)
            stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
        if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
            return scur, stry   # a good short step
    return sbis, sbis


def _value(f: Callable[..., float], x: float) -> float:
    y = float(f(x))
    if not math.isfinite(y):
        raise ValueError(f"f({x!r}) = {y!r} is not finite")
    return y
