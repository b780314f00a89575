"""Exceptions and input checks shared by every stage of the pipeline.

Every check raises :class:`InputError` with a one-line message that names the
field and the allowed range, so the CLI can print it as-is and exit 2.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

import numpy as np


class InputError(ValueError):
    """Invalid user input: the message names the field and the allowed range."""


class ConvergenceError(RuntimeError):
    """A solver did not converge; no result is returned.

    Attributes
    ----------
    reached : float or None
        The last load level (e.g. pressure in MPa) that did converge.
    """

    def __init__(self, message: str, reached: float | None = None) -> None:
        super().__init__(message)
        self.reached = reached


def check_finite(name: str, value: float) -> float:
    """Return ``float(value)`` or raise if it is NaN/inf or not a number."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise InputError(f"{name} must be a finite number, got {value!r}")
    return v


def check_positive(name: str, value: float, unit: str = "") -> float:
    """Return ``value`` if finite and > 0, else raise :class:`InputError`."""
    v = check_finite(name, value)
    if v <= 0.0:
        raise InputError(f"{name} must be > 0{(' ' + unit) if unit else ''}, got {v:g}")
    return v


def check_range(
    name: str,
    value: float,
    lo: float,
    hi: float,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
    unit: str = "",
) -> float:
    """Return ``value`` if finite and inside [lo, hi] (ends open on request)."""
    v = check_finite(name, value)
    bad = (v < lo or v > hi) or (lo_open and v == lo) or (hi_open and v == hi)
    if bad:
        lb = "(" if lo_open else "["
        rb = ")" if hi_open else "]"
        u = f" {unit}" if unit else ""
        raise InputError(f"{name} must be in {lb}{lo:g}, {hi:g}{rb}{u}, got {v:g}")
    return v


def check_pressures(
    name: str,
    values: Iterable[float] | Sequence[float] | np.ndarray,
    *,
    max_mpa: float = 10.0,
    allow_zero: bool = True,
) -> np.ndarray:
    """Validate a strictly increasing list of pressures in MPa.

    Raises :class:`InputError` for an empty list, NaN or negative values,
    values above ``max_mpa`` or a list that is not strictly increasing.
    """
    arr = np.asarray(list(values), dtype=float)
    if arr.ndim != 1 or arr.size == 0:
        raise InputError(f"{name} must be a non-empty list of pressures in MPa")
    if not np.all(np.isfinite(arr)):
        raise InputError(f"{name} must be finite numbers in MPa, got {arr.tolist()}")
    lo_ok = arr >= 0.0 if allow_zero else arr > 0.0
    if not np.all(lo_ok) or np.any(arr > max_mpa):
        lo = "[0" if allow_zero else "(0"
        raise InputError(f"{name} must lie in {lo}, {max_mpa:g}] MPa, got {arr.tolist()}")
    if np.any(np.diff(arr) <= 0.0):
        raise InputError(f"{name} must be strictly increasing, got {arr.tolist()}")
    return arr
