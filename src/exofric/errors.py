"""Exceptions, input checks and the command line's exit codes, shared by every stage.

Every check raises :class:`InputError` with a one-line message that names the
field and the allowed range, so the CLI can print it as-is and exit 2.

Exit codes of ``exofric`` (:data:`EXIT_CODES`, defined here only):

* 0 -- done;
* 2 -- bad input (:class:`InputError`), found before any work: a bad value, file, device URL,
  register map, or a device that cannot be reached or refuses the handshake;
* 3 -- a solver did not converge (:class:`ConvergenceError`);
* 4 -- ``control run`` stopped on a run-time fault (watchdog, a limit, a device that went
  silent, dropped the connection or sent garbage) and the tube was vented;
* 5 -- as 4 (or a run that ended otherwise), but the vent could not be confirmed: the tube may
  still be pressurised;
* 130 -- interrupted (Ctrl-C); a running control loop vented first.
"""

from __future__ import annotations

import functools
import math
import os
import re
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, overload

if TYPE_CHECKING:  # numpy is imported where it is used: the CLI imports this module first
    from types import FrameType

    import numpy as np
    from numpy.typing import ArrayLike, NDArray

__all__ = [
    "EXIT_CODES",
    "EXIT_CONVERGENCE",
    "EXIT_FAULT",
    "EXIT_INPUT",
    "EXIT_INTERRUPTED",
    "EXIT_OK",
    "EXIT_VENT_NOT_CONFIRMED",
    "ConvergenceError",
    "InputError",
    "MaterialInstabilityError",
    "PlausibilityWarning",
    "check_finite",
    "warn_implausible",
    "warning_key",
    "check_positive",
    "check_pressures",
    "check_range",
    "check_seed",
    "check_series",
]

#: Exit code: success.
EXIT_OK = 0
#: Exit code: bad input (:class:`InputError`), before any work.
EXIT_INPUT = 2
#: Exit code: a solver did not converge (:class:`ConvergenceError`).
EXIT_CONVERGENCE = 3
#: Exit code: a control run stopped on a run-time fault and vented
#: (:class:`exofric.hardware.LoopFault`).
EXIT_FAULT = 4
#: Exit code: the vent could not be confirmed: the tube may still be pressurised.
EXIT_VENT_NOT_CONFIRMED = 5
#: Exit code: interrupted (Ctrl-C, SIGINT), after venting.
EXIT_INTERRUPTED = 130
#: Every exit code of the command line and what it means.
EXIT_CODES: dict[int, str] = {
    EXIT_OK: "done",
    EXIT_INPUT: "bad input (one line names the field), found before any work",
    EXIT_CONVERGENCE: "a solver did not converge",
    EXIT_FAULT: "control run stopped on a fault (watchdog, limit, device fault); vented",
    EXIT_VENT_NOT_CONFIRMED: "vent not confirmed: the tube may still be pressurised",
    EXIT_INTERRUPTED: "interrupted (Ctrl-C); a running control loop vented first",
}


class InputError(ValueError):
    """Invalid user input: the message names the field and the allowed range.

    Messages name the Python parameter (``pmax_mpa``), never a command-line flag; the CLI's
    central error handler maps parameter names to its flags (``--pmax``).

    Parameters
    ----------
    message : str
        One line: the parameter, what is allowed (with its unit) and what was given.
    param : str or None
        The Python parameter the message is about (default: the message's first word when it
        is an identifier, e.g. ``"pmax_mpa must be > 0 MPa, got -1"`` -> ``"pmax_mpa"``).

    Examples
    --------
    >>> InputError("pmax_mpa must be > 0 MPa, got -1").param
    'pmax_mpa'
    """

    def __init__(self, message: str, param: str | None = None) -> None:
        super().__init__(message)
        if param is None:
            head = message.split(" ", 1)[0]
            param = head if head.isidentifier() else None
        self.param = param


class ConvergenceError(RuntimeError):
    """A solver did not converge; no result is returned.

    Attributes
    ----------
    reached : float or None
        The last load level (e.g. pressure in MPa) that did converge.

    Parameters
    ----------
    message : str
        One line: what did not converge and where.
    reached : float, optional
        The last converged load level (MPa for pressure paths), or None.

    Examples
    --------
    >>> err = ConvergenceError("Newton stalled at 0.61 MPa", reached=0.6)
    >>> err.reached
    0.6
    """

    def __init__(self, message: str, reached: float | None = None) -> None:
        super().__init__(message)
        self.reached = reached


class MaterialInstabilityError(ConvergenceError):
    """A load path stopped where the material itself is Drucker-unstable (a
    :class:`ConvergenceError`, exit code 3, that no finer mesh or smaller step cures).

    Raised instead of the plain "did not converge" when the largest principal stretch of the
    last converged state has reached the stretch from which the material's parameters are
    Drucker-unstable (``dP/dl <= 0``) along the planar or uniaxial path: the message names
    the model, its parameters, that stretch and the one reached.

    Attributes
    ----------
    reached : float or None
        The last converged load level (MPa for pressure paths).
    stretch : float
        Largest principal stretch (unitless) at the last converged state.
    onset : float
        The stretch (unitless) from which the parameters are Drucker-unstable.
    param : str
        ``"params"``: the material parameters are the input to change.

    Parameters
    ----------
    message : str
        One line.
    reached : float, optional
        The last converged load level.
    stretch, onset : float
        As the attributes.

    Examples
    --------
    >>> err = MaterialInstabilityError("ogden1 is unstable", reached=0.54, stretch=3.3,
    ...                                onset=3.1)
    >>> isinstance(err, ConvergenceError), err.param
    (True, 'params')
    """

    def __init__(self, message: str, reached: float | None = None, stretch: float = math.nan,
                 onset: float = math.nan) -> None:
        super().__init__(message, reached=reached)
        self.reached = reached
        self.stretch = stretch
        self.onset = onset
        self.param = "params"


class PlausibilityWarning(UserWarning):
    """Data that parses and is physically possible, but unlikely to be what the user meant.

    Physically impossible data raises :class:`InputError`; implausible data warns with this
    category (the CLI prints it as one ``exofric: warning:`` line and lists it under
    ``warnings`` in ``--json``). Each check states its rule in its docstring.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as w:
    ...     warnings.simplefilter("always")
    ...     warn_implausible("R^2 = 0.003: the model explains nothing")
    >>> w[0].category.__name__
    'PlausibilityWarning'
    """


def warn_implausible(message: str) -> None:
    """Warn (:class:`PlausibilityWarning`) with a one-line ``message``.

    Parameters
    ----------
    message : str
        What is implausible and what to check, one line.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     warn_implausible("the curve falls")
    """
    import warnings

    warnings.warn(message, PlausibilityWarning, stacklevel=_outside_stacklevel())


def _outside_stacklevel() -> int:
    """The ``stacklevel`` that points a warning at the first caller outside exofric.

    Counted from the function that calls ``warnings.warn`` (level 1); exofric's own frames
    (the argument-checking wrappers of the public functions included) are skipped, so the
    warning names the user's line, as Python 3.12's ``skip_file_prefixes`` would.
    """
    import sys

    root = os.path.dirname(os.path.abspath(__file__)) + os.sep
    frame = sys._getframe(2)           # the caller of the function that warns
    level = 2
    while frame.f_back is not None and _inside(frame, root):
        frame = frame.f_back
        level += 1
    return level


def _inside(frame: FrameType, root: str) -> bool:
    """Whether ``frame`` runs exofric's code: a file of the package, or code a dataclass
    generated for one of its classes (``__init__``, with the defining module's globals)."""
    name = frame.f_code.co_filename
    return name.startswith(root) or (
        name == "<string>" and str(frame.f_globals.get("__name__", "")).startswith("exofric."))


#: Units after a whole number that make it a measured value (``1 MPa``, ``150%``, ``3 N``).
_UNITS = r"(?:MPa|kPa|bar|mm|Nm|N|%|ms|s|Hz|Shore|deg|rad)(?![A-Za-z])"


@functools.cache
def _measured_number() -> re.Pattern[str]:
    return re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+(?=[eE][-+]?\d))(?:[eE][-+]?\d+)?"
                      rf"|[-+]?\d+(?=\s?{_UNITS})")


def warning_key(category: type[Warning], message: str) -> tuple[type[Warning], str]:
    """What makes two warnings "the same" when a batch of solves issues each kind once.

    The category and the message with its measured numbers replaced by ``#``: a number with a
    decimal point or an exponent (``1.23``, ``2e-3``) or a whole number followed by a unit
    (``1 MPa``, ``150%``, ``3 N``). Other whole numbers name or count things (``test 6``,
    ``3 of 64 samples``) and keep messages apart. Used by every "each warning once" batch
    (the tolerance bands' samples, ``exofric predict``).

    Parameters
    ----------
    category : type
        The warning's class.
    message : str
        Its text.

    Returns
    -------
    tuple
        ``(category, message with the measured numbers as '#')``.

    Examples
    --------
    >>> warning_key(UserWarning, "test 6: N = 1.23 N at 0.6 MPa")[1]
    'test 6: N = # N at # MPa'
    >>> warning_key(UserWarning, "N = 1.24 N") == warning_key(UserWarning, "N = 1.23 N")
    True
    >>> warning_key(UserWarning, "test 6") == warning_key(UserWarning, "test 7")
    False
    """
    return category, _measured_number().sub("#", str(message))


def check_finite(name: str, value: float) -> float:
    """Return ``float(value)`` or raise if it is NaN/inf or not a number.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : float
        The value to check (any unit; the unit is the caller's).

    Returns
    -------
    float
        ``float(value)``.

    Raises
    ------
    InputError
        If ``value`` is not a number or not finite.

    Examples
    --------
    >>> check_finite("hole_mm", "10")
    10.0
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise InputError(f"{name} must be a finite number, got {value!r}")
    return v


def check_positive(name: str, value: float, unit: str = "") -> float:
    """Return ``value`` if finite and > 0, else raise :class:`InputError`.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : float
        The value to check, in ``unit``.
    unit : str
        Unit printed in the error message (e.g. ``"mm"``); empty for none.

    Returns
    -------
    float
        ``float(value)``.

    Examples
    --------
    >>> check_positive("hole_mm", 10.0, "mm")
    10.0
    >>> check_positive("hole_mm", -1.0, "mm")
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: hole_mm must be > 0 mm, got -1
    """
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
    """Return ``value`` if finite and inside [lo, hi] (ends open on request).

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : float
        The value to check, in ``unit``.
    lo, hi : float
        Allowed range, in the same unit as ``value``; ``lo <= hi``.
    lo_open, hi_open : bool
        Exclude the lower / upper end.
    unit : str
        Unit printed in the error message (e.g. ``"MPa"``); empty for none.

    Returns
    -------
    float
        ``float(value)``.

    Examples
    --------
    >>> check_range("shore", 62.5, 0.0, 100.0)
    62.5
    >>> check_range("pmax_mpa", 0.0, 0.0, 2.0, lo_open=True, unit="MPa")
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: pmax_mpa must be in (0, 2] MPa, got 0
    """
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

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    values : array-like of float
        Pressures (MPa), strictly increasing, in [0, ``max_mpa``].
    max_mpa : float
        Largest allowed pressure (MPa).
    allow_zero : bool
        Accept 0 MPa as the first value (otherwise the range is (0, ``max_mpa``]).

    Returns
    -------
    numpy.ndarray
        The pressures as a 1-D float array (MPa).

    Examples
    --------
    >>> check_pressures("pressures_mpa", [0.0, 0.3, 0.6]).tolist()
    [0.0, 0.3, 0.6]
    """
    import numpy as np

    try:
        arr = np.asarray(list(values), dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a list of numbers in MPa", param=name) from None
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


def _series_array(name: str, values: ArrayLike, unit: str, pre: str) -> NDArray[np.float64]:
    """``values`` as a flat float array; InputError if not numbers or not all finite."""
    import numpy as np

    try:
        raw = np.asarray(values)
        numbers = raw.dtype.kind in "biuf" or (raw.dtype.kind == "O" and all(
            isinstance(v, (int, float, np.number)) and not isinstance(v, bool)
            for v in raw.ravel()))
        if not numbers:       # text ("0.2", ["0.1", "0.2"]), None, other objects
            raise ValueError
        a = raw.astype(float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{pre}{name} must be a list of numbers{unit}",
                         param=name if name.isidentifier() else None) from None
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        i = int(bad[0])
        raise InputError(f"{pre}{name} must be finite numbers{unit}, got {a[i]} at index {i}",
                         param=name if name.isidentifier() else None)
    return a


@overload
def check_series(
    x_name: str, x: ArrayLike, y_name: None = None, y: None = None, *, x_unit: str = "",
    y_unit: str = "", increasing: bool = True, min_points: int = 2, x_min: float | None = None,
    y_min: float | None = None, where: str = "",
) -> tuple[NDArray[np.float64], None]: ...


@overload
def check_series(
    x_name: str, x: ArrayLike, y_name: str, y: ArrayLike, *, x_unit: str = "",
    y_unit: str = "", increasing: bool = True, min_points: int = 2, x_min: float | None = None,
    y_min: float | None = None, where: str = "",
) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...


def check_series(
    x_name: str,
    x: ArrayLike,
    y_name: str | None = None,
    y: ArrayLike | None = None,
    *,
    x_unit: str = "",
    y_unit: str = "",
    increasing: bool = True,
    min_points: int = 2,
    x_min: float | None = None,
    y_min: float | None = None,
    where: str = "",
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """Validate a sampled series x (and y(x)): finite, equal lengths, x strictly increasing.

    The one check behind every tabulated curve (pressure in MPa vs force in N, time in s vs
    response). Arrays are flattened; checks run in this order, each raising
    :class:`InputError` with one line naming the parameter (``param`` is set to it):

    1. numbers and finite (no NaN/inf), naming the first bad index;
    2. ``y`` has as many values as ``x``;
    3. at least ``min_points`` values;
    4. ``x >= x_min`` and ``y >= y_min`` when given;
    5. ``x`` strictly increasing (if ``increasing``), naming the first offending pair.

    Parameters
    ----------
    x_name, y_name : str
        Parameter names used in messages (``y_name`` only with ``y``).
    x, y : array_like
        The abscissa (e.g. pressure, MPa) and the optional ordinate (e.g. force, N).
    x_unit, y_unit : str
        Units quoted in messages (``"MPa"``, ``"N"``, ``"s"``).
    increasing : bool
        Require ``x`` strictly increasing (default True).
    min_points : int
        Least number of values (default 2).
    x_min, y_min : float or None
        Lower bounds (inclusive), e.g. 0 for pressures and forces.
    where : str
        Context prefixed to messages (``"squeeze curve"`` -> ``"squeeze curve: ..."``).

    Returns
    -------
    (x, y) : tuple of ndarray
        Flat float copies; ``y`` is None when not given.

    Examples
    --------
    >>> x, y = check_series("pressure_mpa", [0.1, 0.2], "squeeze_force_n", [1, 3])
    >>> x.tolist(), y.tolist()
    ([0.1, 0.2], [1.0, 3.0])
    >>> check_series("pressure_mpa", [0.2, 0.1], x_unit="MPa")
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: pressure_mpa must be strictly increasing (MPa), got 0.2 then \
0.1 at index 1
    """
    import numpy as np

    pre = f"{where}: " if where else ""
    xu = f" ({x_unit})" if x_unit else ""
    yu = f" ({y_unit})" if y_unit else ""
    xa = _series_array(x_name, x, xu, pre)
    ya = None
    if y is not None:
        yn = y_name or "y"
        ya = _series_array(yn, y, yu, pre)
        if ya.size != xa.size:
            raise InputError(f"{pre}{x_name} and {yn} must have the same length, got "
                             f"{xa.size} and {ya.size}",
                             param=x_name if x_name.isidentifier() else None)
    if xa.size < min_points:
        raise InputError(f"{pre}{x_name} needs at least {min_points} value"
                         f"{'' if min_points == 1 else 's'}, got {xa.size}",
                         param=x_name if x_name.isidentifier() else None)
    for name, a, lo, unit in ((x_name, xa, x_min, x_unit), (y_name or "y", ya, y_min, y_unit)):
        if a is None or lo is None:
            continue
        below = np.flatnonzero(a < lo)
        if below.size:
            i = int(below[0])
            raise InputError(f"{pre}{name} must be >= {lo:g}{' ' + unit if unit else ''}, "
                             f"got {a[i]:g} at index {i}",
                             param=name if name.isidentifier() else None)
    if increasing:
        bad = np.flatnonzero(np.diff(xa) <= 0.0)
        if bad.size:
            i = int(bad[0]) + 1
            raise InputError(f"{pre}{x_name} must be strictly increasing{xu}, got "
                             f"{xa[i - 1]:g} then {xa[i]:g} at index {i}",
                             param=x_name if x_name.isidentifier() else None)
    return xa, ya


def check_seed(name: str, value: object) -> int:
    """Return ``value`` as an RNG seed: an integer in [0, 2**64 - 1], else :class:`InputError`.

    NumPy's generators take only non-negative integers; this says so in one line instead of
    NumPy's traceback.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : int
        The seed (``bool`` and non-integral numbers are refused).

    Returns
    -------
    int
        ``int(value)``.

    Examples
    --------
    >>> check_seed("seed", 7)
    7
    >>> check_seed("seed", -1)
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: seed must be an integer in [0, 2**64 - 1], got -1
    """
    import numbers

    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise InputError(f"{name} must be an integer in [0, 2**64 - 1], got {value!r}")
    v = int(value)
    if not 0 <= v < 2**64:
        raise InputError(f"{name} must be an integer in [0, 2**64 - 1], got {v}")
    return v
