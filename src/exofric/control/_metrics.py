"""Step-response metrics: rise time, settling time, overshoot, steady-state error, ITAE.

Conventions (identical to python-control's ``step_info`` when the response starts at 0 and
the reference is its ``yfinal``, so the two can be compared sample for sample):

* reference ``ref`` (the target, e.g. 54.40 N) and start value ``y0`` (first sample);
* rise time: first sample at or beyond 90 % of the change minus the first sample at or beyond
  10 % (``rise_limits``);
* settling time: the first sample after the last one with |y - ref| >= band |ref - y0|
  (2 % band by default); None if the last sample is still outside (never settled);
* overshoot: largest excursion beyond ``ref`` in the direction of the change, in % of
  |ref - y0| (0 if none);
* steady-state error: ref - mean of y over the final ``tail_s`` seconds.

Units: time in s, response in its own unit (N for friction).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, check_range, check_series

__all__ = ["StepMetrics", "step_metrics", "itae"]


@checked_init
@dataclass(frozen=True)
class StepMetrics(DisplayMixin):
    """Metrics of one step response (s, %, and the response's unit, N for friction).

    ``None`` marks a quantity the response never reached (e.g. no settling into the band of the
    target when a steady-state error remains). Built by :func:`step_metrics`.

    Attributes
    ----------
    rise_time_s : float or None
        10-90 % rise time in s.
    settling_time_s : float or None
        Time in s from the first sample to entering the band for good; None if never.
    overshoot_pct : float
        Largest excursion beyond the reference, in % of the step (0 if none).
    steady_state_error_n : float
        target - final value, in the response's unit (N for friction; ``steady_state_error``
        is a read-only alias).
    final_friction_n : float
        Mean of the response over the final window, in the response's unit (N; alias
        ``final_value``).
    target_friction_n : float
        The target, in the response's unit (N; alias ``reference``). The names are the
        ``to_dict()`` keys.
    band : float
        Settling band as a fraction of the step (0.02 = 2 %).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 10.0, 1001)
    >>> m = step_metrics(t, 50.0 * (1.0 - np.exp(-t)), 50.0)
    >>> round(m.steady_state_error_n, 2), m.overshoot_pct, m.to_dict()["settling_band_pct"]
    (0.0, 0.0, 2.0)
    """

    rise_time_s: float | None
    settling_time_s: float | None
    overshoot_pct: float
    steady_state_error_n: float
    final_friction_n: float
    target_friction_n: float
    band: float

    @property
    def steady_state_error(self) -> float:
        """Alias of ``steady_state_error_n`` (N)."""
        return self.steady_state_error_n

    @property
    def final_value(self) -> float:
        """Alias of ``final_friction_n`` (N)."""
        return self.final_friction_n

    @property
    def reference(self) -> float:
        """Alias of ``target_friction_n`` (N)."""
        return self.target_friction_n

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict; friction responses: ``steady_state_error_n``, ``final_friction_n``."""
        return {
            "rise_time_s": self.rise_time_s,
            "settling_time_s": self.settling_time_s,
            "overshoot_pct": self.overshoot_pct,
            "steady_state_error_n": self.steady_state_error_n,
            "final_friction_n": self.final_friction_n,
            "target_friction_n": self.target_friction_n,
            "settling_band_pct": 100.0 * self.band,
        }


def _check(t: ArrayLike, y: ArrayLike,
           y_name: str = "y") -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Sample times t (s, strictly increasing, >= 2) and one finite ``y_name`` per sample."""
    return check_series("t", t, y_name, y, x_unit="s", where="time series")


def step_metrics(
    t: ArrayLike,
    y: ArrayLike,
    reference: float,
    *,
    band: float = 0.02,
    rise_limits: tuple[float, float] = (0.1, 0.9),
    tail_s: float | None = None,
) -> StepMetrics:
    """Rise time, settling time, overshoot and steady-state error of a sampled step response.

    Parameters
    ----------
    t : array_like
        Sample times in s, strictly increasing; the step happens at ``t[0]``.
    y : array_like
        Response samples (N for friction), ``y[0]`` is the value before the step acts.
    reference : float
        The target the response should reach (same unit as ``y``), e.g. 54.40 N.
    band : float
        Settling band as a fraction of the step |reference - y0| (default 0.02 = 2 %).
    rise_limits : (lo, hi)
        Fractions of the step for the rise time (default 10 % - 90 %).
    tail_s : float or None
        Averaging window at the end for the final value, in s; default 5 % of the duration
        (at least one sample).

    Returns
    -------
    StepMetrics

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 10.0, 1001)
    >>> m = step_metrics(t, 1.0 - np.exp(-t), 1.0)
    >>> round(m.rise_time_s, 2), round(m.settling_time_s, 2)   # ln 9 = 2.20, ln 50 = 3.91
    (2.2, 3.92)
    """
    ta, ya = _check(t, y)
    ref = float(reference)
    check_range("band", band, 0.0, 1.0, lo_open=True, hi_open=True)
    lo_f, hi_f = rise_limits
    if not 0.0 <= lo_f < hi_f <= 1.0:
        raise InputError(f"rise_limits must satisfy 0 <= lo < hi <= 1, got {rise_limits}")
    y0 = float(ya[0])
    step = ref - y0
    if step == 0.0:
        raise InputError("reference equals the initial value: no step to measure")
    sgn = 1.0 if step > 0 else -1.0
    progress = sgn * (ya - y0) / abs(step)          # 0 at start, 1 at the reference
    i_lo = np.flatnonzero(progress >= lo_f)
    i_hi = np.flatnonzero(progress >= hi_f)
    rise = float(ta[i_hi[0]] - ta[i_lo[0]]) if i_hi.size and i_lo.size else None
    outside = np.flatnonzero(np.abs(ya - ref) >= band * abs(step))
    if outside.size == 0:
        settle: float | None = float(ta[0])
    elif outside[-1] + 1 < ta.size:
        settle = float(ta[outside[-1] + 1])
    else:
        settle = None
    overshoot = float(max(0.0, 100.0 * (progress.max() - 1.0)))
    if tail_s is None:
        tail_s = 0.05 * float(ta[-1] - ta[0])
    tail = ya[ta >= ta[-1] - tail_s]
    final = float(tail.mean()) if tail.size else float(ya[-1])
    return StepMetrics(rise, settle, overshoot, ref - final, final, ref, float(band))


def itae(t: ArrayLike, error: ArrayLike) -> float:
    """Integral of time-weighted absolute error, sum t |e| dt (trapezoid), in (unit) s^2.

    Time is measured from ``t[0]``.

    Parameters
    ----------
    t : array_like
        Sample times in s, strictly increasing.
    error : array_like
        Error samples (e.g. set-point - friction, in N), one per time.

    Returns
    -------
    float
        ITAE in the error's unit times s^2 (N s^2 for friction).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 40.0, 40001)
    >>> round(itae(t, np.exp(-t / 2.0)), 4)      # analytic: T^2 = 4
    4.0
    """
    ta, ea = _check(t, error, "error")
    w = (ta - ta[0]) * np.abs(ea)
    return float(np.sum(0.5 * (w[1:] + w[:-1]) * np.diff(ta)))
