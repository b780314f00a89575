"""Identification of the pressure supply (gain, lag, dead time) from a recorded step response.

Model (first-order plus dead time, zero-order-hold command):

    p(t) = b + K u(t - theta) filtered by 1/(tau s + 1),

i.e. p(t) = b + K [u_0 + sum_j du_j (1 - exp(-(t - t_j - theta)/tau)) H(t - t_j - theta)]
for command changes du_j at sample times t_j (the plant at rest before the first sample).
Without a command column the command is a step at t = 0 of unknown size A (samples with
t < 0 are the pre-step baseline): p(t) = b + A h(t - theta), and the gain is taken as 1
(a pressure regulator whose command is the target pressure), flagged ``gain_assumed``.

Fitting: least squares by variable projection -- for each (tau, theta) the linear parameters
(b, K or A) are solved exactly, (tau, theta) by ``scipy.optimize.least_squares`` from a
10 %/63 % crossing guess and a few dead-time starts; then a joint Gauss-Newton polish gives
the standard errors (sqrt of the diagonal of s^2 (J^T J)^-1). Fit quality: R^2 and RMSE.

Units: time s, pressure and command MPa, gain MPa/MPa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric import defaults
from exofric._display import DisplayMixin
from exofric._lsq import lsq_covariance, residual_variance, standard_errors
from exofric._validate import checked_init
from exofric.control._plant import PlantParams
from exofric.errors import InputError, check_series, warn_implausible

__all__ = ["IdentifiedPlant", "identify_step", "fopdt_response"]


@checked_init
@dataclass(frozen=True)
class IdentifiedPlant(DisplayMixin):
    """A fitted first-order-plus-dead-time pressure supply and its fit quality.

    Attributes
    ----------
    gain : float
        Static gain K, MPa/MPa (1 and ``gain_assumed`` without a command column).
    time_constant_s, delay_s : float
        Lag tau and dead time theta in s.
    offset_mpa : float
        Pressure offset b in MPa.
    step_mpa : float
        Size of the pressure change the model explains (K x largest command step, or A).
    r2 : float
        Coefficient of determination of the fit.
    rmse_mpa : float
        Root-mean-square residual in MPa.
    stderr_time_constant_s, stderr_delay_s, stderr_gain : float
        Standard errors (s, s, MPa/MPa; NaN if not estimable).
    n_samples : int
        Number of samples fitted.
    gain_assumed : bool
        True when no command was recorded and the gain was taken as 1.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(-0.5, 4.0, 0.01)
    >>> p = 0.05 + 0.3 * (1 - np.exp(-np.clip(t - 0.1, 0, None) / 0.5))
    >>> r = identify_step(t, p)
    >>> round(r.time_constant_s, 4), round(r.delay_s, 4), round(r.offset_mpa, 4), r.gain_assumed
    (0.5, 0.1, 0.05, True)
    """

    gain: float
    time_constant_s: float
    delay_s: float
    offset_mpa: float
    step_mpa: float
    r2: float
    rmse_mpa: float
    stderr_time_constant_s: float
    stderr_delay_s: float
    stderr_gain: float
    n_samples: int
    gain_assumed: bool

    def to_plant(self, base: PlantParams | None = None) -> PlantParams:
        """A :class:`PlantParams` with this gain, lag and delay (other fields from ``base``).

        Parameters
        ----------
        base : PlantParams or None
            Supplies the other fields (p_max_mpa in MPa, noise_n in N, PWM period in s, ...);
            default ``PlantParams()``.

        Returns
        -------
        PlantParams

        Examples
        --------
        >>> ip = IdentifiedPlant(1.0, 0.5, 0.1, 0.0, 0.3, 1.0, 0.0, 0.0, 0.0, float("nan"),
        ...                      100, True)
        >>> pp = ip.to_plant(PlantParams(p_max_mpa=0.8))
        >>> pp.time_constant_s, pp.delay_s, pp.p_max_mpa
        (0.5, 0.1, 0.8)
        """
        from dataclasses import replace

        return replace(base or PlantParams(), gain=self.gain,
                       time_constant_s=self.time_constant_s, delay_s=self.delay_s)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (s, MPa, gain MPa/MPa)."""
        return {
            "gain": self.gain,
            "gain_assumed": self.gain_assumed,
            "time_constant_s": self.time_constant_s,
            "delay_s": self.delay_s,
            "offset_mpa": self.offset_mpa,
            "step_mpa": self.step_mpa,
            "r2": self.r2,
            "rmse_mpa": self.rmse_mpa,
            "stderr_time_constant_s": self.stderr_time_constant_s,
            "stderr_delay_s": self.stderr_delay_s,
            "stderr_gain": self.stderr_gain,
            "n_samples": self.n_samples,
        }


def _basis(t: NDArray[np.float64], t_steps: NDArray[np.float64], du: NDArray[np.float64],
           tau: float, theta: float) -> NDArray[np.float64]:
    """sum_j du_j h(t - t_j - theta), vectorised over samples x steps."""
    s = t[:, None] - t_steps[None, :] - theta
    h = -np.expm1(-np.maximum(s, 0.0) / tau)
    return np.asarray(h @ du, dtype=float)


def fopdt_response(
    time_s: ArrayLike,
    command_mpa: ArrayLike,
    *,
    gain: float,
    time_constant_s: float,
    delay_s: float,
    offset_mpa: float = 0.0,
) -> NDArray[np.float64]:
    """Exact FOPDT response (MPa) to a zero-order-hold command sampled at ``time_s``.

    The plant is at rest under ``command_mpa[0]`` before the first sample; each later command
    holds from its sample time on.

    Parameters
    ----------
    time_s : array_like
        Sample times in s.
    command_mpa : array_like
        Pressure command in MPa at each sample (zero-order hold).
    gain : float
        Static gain K in MPa/MPa.
    time_constant_s : float
        Lag tau in s (> 0).
    delay_s : float
        Dead time theta in s (>= 0).
    offset_mpa : float
        Pressure offset b in MPa added to the response.

    Returns
    -------
    ndarray
        Pressure in MPa at each sample time.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.array([0.0, 1.0, 2.0])
    >>> np.round(fopdt_response(t, [1.0, 1.0, 1.0], gain=1.0, time_constant_s=1.0,
    ...                         delay_s=0.0), 6).tolist()            # at rest at u0 = 1
    [1.0, 1.0, 1.0]
    """
    t, u = check_series("time_s", time_s, "command_mpa", command_mpa, x_unit="s",
                        y_unit="MPa", increasing=False, min_points=1)
    du = np.diff(u)
    idx = np.flatnonzero(du != 0.0)
    steps = _basis(t, t[idx + 1], du[idx], time_constant_s, delay_s)
    return np.asarray(offset_mpa + gain * (u[0] + steps), dtype=float)


def _guess(t: NDArray[np.float64], p: NDArray[np.float64], t_step: float,
           t_end: float) -> tuple[float, float]:
    """tau, theta from the 10 % and 63 % crossings of the (smoothed) primary step."""
    sel = (t >= t_step) & (t <= t_end)
    ts, ps = t[sel], p[sel]
    span = float(t_end - t_step) if math.isfinite(t_end) else float(t[-1] - t_step)
    if ts.size < 4:
        return span / 4.0, 0.0
    k = max(1, ts.size // 50)
    sm = np.convolve(ps, np.ones(k) / k, mode="same")
    base = float(np.median(p[t <= t_step][-k:])) if np.any(t <= t_step) else float(sm[0])
    end = float(np.mean(sm[-max(k, ts.size // 10):]))
    if end == base:
        return span / 4.0, 0.0
    y = (sm - base) / (end - base)
    i10 = np.flatnonzero(y >= 0.10)
    i63 = np.flatnonzero(y >= 0.632)
    if not (i10.size and i63.size):
        return span / 4.0, 0.0
    t10, t63 = ts[i10[0]] - t_step, ts[i63[0]] - t_step
    tau = max((t63 - t10) / (1.0 - 0.1054), span / 1000.0)   # h(t)=0.1 at 0.1054 tau
    return float(tau), float(max(t10 - 0.1054 * tau, 0.0))


def identify_step(
    time_s: ArrayLike,
    pressure_mpa: ArrayLike,
    command_mpa: ArrayLike | None = None,
) -> IdentifiedPlant:
    """Fit gain, time constant and dead time to a recorded pressure step response.

    Parameters
    ----------
    time_s : array_like
        Sample times in s, strictly increasing (step at t = 0 without a command column).
    pressure_mpa : array_like
        Measured tube pressure in MPa.
    command_mpa : array_like or None
        Pressure command in MPa, held between samples (ZOH); must change at least once.

    Returns
    -------
    IdentifiedPlant

    Raises
    ------
    InputError
        Mismatched lengths, fewer than 10 samples, no step, or a response with no change.

    Warns
    -----
    PlausibilityWarning
        When the fit explains less than ``defaults.PLAUSIBLE_IDENTIFY_MIN_R2`` (0.9) of the
        response's variance (R^2): the model, and gains tuned on it, do not describe the data.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(-0.5, 6.0, 0.01)
    >>> p = 0.4 * (1 - np.exp(-np.clip(t - 0.2, 0, None) / 0.8))
    >>> r = identify_step(t, p)
    >>> round(r.time_constant_s, 4), round(r.delay_s, 4), round(r.step_mpa, 4)
    (0.8, 0.2, 0.4)
    """
    from scipy.optimize import least_squares

    t, p = check_series("time_s", time_s, "pressure_mpa", pressure_mpa, x_unit="s",
                        y_unit="MPa", min_points=10, where="step response")
    if command_mpa is None:
        if not (t[0] <= 0.0 < t[-1]):
            raise InputError("without command_mpa the step is at t = 0 s: time_s must span it")
        t_steps, du = np.array([0.0]), np.array([1.0])
        u0, gain_assumed = 0.0, True
    else:
        _, u = check_series("time_s", t, "command_mpa", command_mpa, x_unit="s",
                            y_unit="MPa", where="step response")
        d = np.diff(u)
        idx = np.flatnonzero(d != 0.0)
        if idx.size == 0:
            raise InputError("command_mpa never changes: no step to identify")
        t_steps, du, u0, gain_assumed = t[idx + 1], d[idx], float(u[0]), False
    if float(np.ptp(p)) == 0.0:
        raise InputError("pressure_mpa never changes: nothing to identify")
    main = int(np.argmax(np.abs(du)))
    t_next = t_steps[main + 1] if main + 1 < t_steps.size else math.inf
    span = float(t[-1] - t[0])

    def linear(tau: float, theta: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        x = _basis(t, t_steps, du, tau, theta)
        a = np.column_stack([np.ones_like(t), u0 + x])
        coef = np.asarray(np.linalg.lstsq(a, p, rcond=None)[0], dtype=np.float64)
        return coef, p - a @ coef

    def vp_resid(z: NDArray[np.float64]) -> NDArray[np.float64]:
        return linear(float(z[0]), float(z[1]))[1]

    tau0, th0 = _guess(t, p, float(t_steps[main]), float(t_next))
    lo = np.array([span * 1e-4, 0.0])
    hi = np.array([span * 10.0, span])
    best = None
    for th_start in (th0, 0.5 * th0, 1.5 * th0 + 0.01 * span):
        z0 = np.clip([tau0, th_start], lo + 1e-12, hi - 1e-12)
        sol = least_squares(vp_resid, z0, bounds=(lo, hi), x_scale=[tau0, max(tau0, 1e-3)],
                            xtol=1e-12, ftol=1e-12)
        if best is None or sol.cost < best.cost:
            best = sol
    assert best is not None
    tau, theta = float(best.x[0]), float(best.x[1])
    (b, k), resid = linear(tau, theta)

    def full(z: NDArray[np.float64]) -> NDArray[np.float64]:
        x = _basis(t, t_steps, du, float(z[2]), float(z[3]))
        return np.asarray(z[0] + z[1] * (u0 + x) - p, dtype=float)

    z = np.array([b, k, tau, theta])
    h = 1e-6 * np.maximum(np.abs(z), [1e-3, 1e-3, tau, max(tau, 1e-3)])
    jac = np.column_stack([(full(z + hi_) - full(z - hi_)) / (2.0 * hi_[i])
                           for i, hi_ in enumerate(np.diag(h))])
    se = standard_errors(lsq_covariance(jac, residual_variance(resid, 4, min_dof=1)))
    ss_tot = float(np.sum((p - p.mean()) ** 2))
    r2 = 1.0 - float(resid @ resid) / ss_tot
    if r2 < defaults.PLAUSIBLE_IDENTIFY_MIN_R2:  # the rule: see defaults
        warn_implausible(f"step response: the first-order-plus-dead-time model explains only "
                         f"R^2 = {r2:.3f} of the pressure (< "
                         f"{defaults.PLAUSIBLE_IDENTIFY_MIN_R2:g}); the plant and any gains "
                         "tuned on it are not meaningful; check that the file holds one step")
    step = float(k * du[main])
    gain = 1.0 if gain_assumed else float(k)
    return IdentifiedPlant(
        gain=gain, time_constant_s=tau, delay_s=theta,
        offset_mpa=float(b),
        step_mpa=step, r2=r2, rmse_mpa=float(np.sqrt(np.mean(resid**2))),
        stderr_time_constant_s=float(se[2]), stderr_delay_s=float(se[3]),
        stderr_gain=math.nan if gain_assumed else float(se[1]),
        n_samples=int(t.size), gain_assumed=gain_assumed,
    )
