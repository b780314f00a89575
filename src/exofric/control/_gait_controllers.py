"""Controllers for the knee lock through a gait cycle (:func:`~exofric.control.simulate_gait`).

Every controller turns the friction set-point r (N, at the block) and the measured friction y
(N) into a pressure command (MPa) once per sample. ``pid``, ``ff`` and ``preview`` are the
project's :class:`~exofric.control.Controller` (the code ``exofric control run`` steps on the
hardware), with different feedforward objects and gains; ``ilc`` adds a learned command
trajectory across strides; ``mpc`` solves a small box-constrained least-squares problem per
MPC sample.

* :class:`PlantModel` -- the first-order-plus-dead-time model (gain K, lag tau, dead time d)
  the feedforward, preview, ILC and MPC use (identified from a simulated step of the plant).
* :class:`PreviewFeedforward` -- u_ff = g^-1(r(t + lead)) / K: the static model feedforward of
  the set-point ``lead_s`` ahead (the profile is known a stride ahead).
* :class:`IterativeLearning` -- u_{j+1} = Q(u_j + L e_j) across strides j: L = gamma x the
  inverse of the sampled FOPDT model (model-inverse ILC, Bristow, Tharayil & Alleyne 2006,
  IEEE Control Systems 26(3)), Q a scalar forgetting factor times a zero-phase moving average.
  With an exact linear model and Q = 1 the error contracts by |1 - gamma| per stride.
* :class:`PressureMPC` -- a pressure-tracking MPC over the FOPDT model: minimise
  sum (p - p_ref)^2 + lambda sum (du)^2 with u_min <= u <= u_max, a bounded least-squares
  problem: the unconstrained optimum when it lies within the bounds (then it is the
  constrained one, the problem being convex), else :func:`box_lsq`, an exact active-set
  solver tested against :func:`scipy.optimize.lsq_linear` (whose per-call overhead, ~1 ms,
  would cap the simulation at ~5x real time).

Units: friction N, pressure MPa, time s.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from exofric._validate import checked_init
from exofric.control._pid import ModelFeedforward
from exofric.errors import InputError, check_range

__all__ = ["IterativeLearning", "PlantModel", "PressureMPC", "PreviewFeedforward"]


def box_lsq(a: NDArray[np.float64], b: NDArray[np.float64], lo: float, hi: float, *,
            hessian: NDArray[np.float64] | None = None, max_iter: int = 200
            ) -> NDArray[np.float64]:
    """min ||a x - b||^2 subject to lo <= x <= hi, by a primal active-set method (exact).

    The same problem as :func:`scipy.optimize.lsq_linear` with ``method='bvls'`` (tested
    against it to 1e-9), without its per-call overhead: the MPC solves ~100 of these per
    simulated second. ``a`` must have full column rank (the MPC's stacked matrix has: its
    command-change rows are invertible). Starting from the clipped unconstrained optimum, it
    fixes variables at the bound they cross and frees the one whose multiplier has the wrong
    sign until the KKT conditions hold (Nocedal & Wright 2006, Algorithm 16.3).

    Parameters
    ----------
    a : ndarray (m, n)
        Design matrix (full column rank).
    b : ndarray (m,)
        Target.
    lo, hi : float
        Bounds on every x_i (lo < hi).
    hessian : ndarray (n, n), optional
        a^T a, if already computed.
    max_iter : int
        Iteration limit (an active-set change per iteration).

    Returns
    -------
    ndarray (n,)

    Examples
    --------
    >>> a = np.eye(2); b = np.array([2.0, -1.0])
    >>> box_lsq(a, b, 0.0, 1.0).tolist()
    [1.0, 0.0]
    """
    h = a.T @ a if hessian is None else hessian
    g = a.T @ b
    for bound in (lo, hi):          # all at one bound (a vented or saturated horizon)?
        grad = h @ np.full(h.shape[0], bound) - g
        if (bound == lo and np.all(grad >= 0.0)) or (bound == hi and np.all(grad <= 0.0)):
            return np.full(h.shape[0], bound)
    x = np.clip(np.linalg.solve(h, g), lo, hi)
    at_lo = x <= lo
    at_hi = x >= hi
    for _ in range(max_iter):
        free = ~(at_lo | at_hi)
        y = x.copy()
        if free.any():
            fixed = ~free
            rhs = g[free] - h[np.ix_(free, fixed)] @ x[fixed]
            y[free] = np.linalg.solve(h[np.ix_(free, free)], rhs)
        step = y - x
        viol = free & ((y < lo) | (y > hi))
        if viol.any():              # move to the first bound hit, fix it
            with np.errstate(divide="ignore", invalid="ignore"):
                t_lo = np.where(step < 0.0, (lo - x) / step, np.inf)
                t_hi = np.where(step > 0.0, (hi - x) / step, np.inf)
            t = np.where(viol | free, np.minimum(t_lo, t_hi), np.inf)
            j = int(np.argmin(t))
            x = x + max(float(t[j]), 0.0) * step
            x = np.clip(x, lo, hi)
            at_lo[j], at_hi[j] = step[j] < 0.0, step[j] > 0.0
            continue
        x = y
        grad = h @ x - g
        wrong = np.where(at_lo, -grad, 0.0) + np.where(at_hi, grad, 0.0)   # > 0: leave
        j = int(np.argmax(wrong))
        if wrong[j] <= 1e-12 * (1.0 + float(np.max(np.abs(g)))):
            return x
        at_lo[j] = at_hi[j] = False
    return np.clip(x, lo, hi)


@checked_init
@dataclass(frozen=True)
class PlantModel:
    """First-order-plus-dead-time pressure model p' = (K u(t - d) - p) / tau.

    Parameters
    ----------
    gain : float
        Static gain K (MPa/MPa, > 0).
    time_constant_s : float
        Lag tau in s (>= 0; 0: a pure dead time).
    delay_s : float
        Dead time d in s (>= 0).

    Examples
    --------
    >>> m = PlantModel(1.0, 0.05, 0.01)
    >>> round(m.lead_s, 3)                 # the preview lead: dead time + lag
    0.06
    """

    gain: float
    time_constant_s: float
    delay_s: float = 0.0

    def __post_init__(self) -> None:
        check_range("gain", self.gain, 0.0, 1e3, lo_open=True, unit="MPa/MPa")
        check_range("time_constant_s", self.time_constant_s, 0.0, 1e3, unit="s")
        check_range("delay_s", self.delay_s, 0.0, 1e3, unit="s")

    @property
    def lead_s(self) -> float:
        """Dead time + lag in s: how far ahead the preview feedforward commands."""
        return self.delay_s + self.time_constant_s

    def discrete(self, dt: float) -> tuple[float, float, int]:
        """(a, b, n_delay) of p[k+1] = a p[k] + b u[k - n_delay] (zero-order hold).

        Parameters
        ----------
        dt : float
            Sample time in s.

        Returns
        -------
        (float, float, int)
            a = exp(-dt / tau) (0 for tau = 0), b = (1 - a) K (MPa/MPa), dead time in samples.
        """
        a = math.exp(-dt / self.time_constant_s) if self.time_constant_s > 0.0 else 0.0
        return a, (1.0 - a) * self.gain, int(round(self.delay_s / dt))

    def to_dict(self) -> dict[str, float]:
        """JSON-ready: gain, time constant (s), dead time (s), lead (s)."""
        return {"gain": self.gain, "time_constant_s": self.time_constant_s,
                "delay_s": self.delay_s, "lead_s": self.lead_s}


class PreviewFeedforward(ModelFeedforward):
    """Static model feedforward of the set-point ``lead_s`` ahead: u_ff = g^-1(r(t + lead)) / K.

    The gait loop calls :meth:`set_preview` with r(t + lead) before each
    :meth:`~exofric.control.Controller.step`; the feedback (if any) still acts on r(t).

    Parameters
    ----------
    pressure_for_friction : callable
        Inverse friction model P(F): N -> MPa.
    gain : float
        Static gain K of the supply (MPa/MPa).

    Examples
    --------
    >>> ff = PreviewFeedforward(lambda f: f / 100.0)
    >>> ff.set_preview(50.0)
    >>> ff.update(0.0, 0.01)            # commands for 50 N although r(t) = 0 N
    (0.5, 0.0)
    """

    def __init__(self, pressure_for_friction: Callable[[float], float], *,
                 gain: float = 1.0) -> None:
        super().__init__(pressure_for_friction, gain=gain)
        self._preview = 0.0

    def set_preview(self, setpoint_ahead: float) -> None:
        """Give the set-point ``lead_s`` ahead of the sample about to be stepped.

        Parameters
        ----------
        setpoint_ahead : float
            Friction set-point in N at t + lead.
        """
        self._preview = float(setpoint_ahead)

    def update(self, setpoint: float, dt: float) -> tuple[float, float]:
        """Feedforward for the previewed set-point and the feedback's reference.

        Parameters
        ----------
        setpoint : float
            The set-point r(t) in N of this sample (the feedback's reference).
        dt : float
            Sample time in s.

        Returns
        -------
        (float, float)
            u_ff in MPa for r(t + lead), and r(t) in N.
        """
        u, _ = super().update(self._preview, dt)
        return u, setpoint


def _moving_average(x: NDArray[np.float64], half: int) -> NDArray[np.float64]:
    """Zero-phase (centred) moving average over 2 half + 1 samples, periodic ends."""
    if half <= 0:
        return x
    k = 2 * half + 1
    xp = np.concatenate([x[-half:], x, x[:half]])
    c = np.cumsum(np.concatenate([[0.0], xp]))
    return (c[k:] - c[:-k]) / k


class IterativeLearning:
    """Model-inverse iterative learning control across strides: u_{j+1} = Q(u_j + L e_j).

    The learned command trajectory u_j (MPa, one value per sample of the stride) is added to
    the feedforward. After stride j with pressure-domain error e_j(t) (MPa; the friction error
    over dF/dP), the next stride uses

        u_{j+1}(t) = Q[ u_j(t) + gamma (e_j(t + d + 1) - a e_j(t + d)) / b ],

    the inverse of the sampled FOPDT model p[k+1] = a p[k] + b u[k - d] (``PlantModel``),
    scaled by the learning gain gamma; Q = ``forgetting`` x a zero-phase moving average of
    ``smoothing_samples`` each side. For a linear plant equal to the model and Q = 1, the
    error of the next stride is (1 - gamma) e_j exactly: the contraction factor |1 - gamma|.

    Parameters
    ----------
    model : PlantModel
        The supply model.
    dt : float
        Sample time in s.
    n_samples : int
        Samples per stride.
    gain : float
        Learning gain gamma in (0, 2) (unitless; 1: one-stride dead-beat for an exact model).
    forgetting : float
        Scalar part of Q in (0, 1] (unitless).
    smoothing_samples : int
        Half-width of Q's zero-phase moving average (samples, >= 0).
    extra_delay_samples : int
        Samples (unitless count) between the command and the measured error on top of the
        model's dead time: the sensor delay.
    mask : ndarray of bool, optional
        Samples where the command may be learned (a learning window; elsewhere it stays 0).
        Default: all.

    Examples
    --------
    >>> ilc = IterativeLearning(PlantModel(1.0, 0.01), 0.01, 5, gain=0.5)
    >>> round(ilc.contraction, 3)
    0.5
    """

    def __init__(self, model: PlantModel, dt: float, n_samples: int, *, gain: float = 0.5,
                 forgetting: float = 1.0, smoothing_samples: int = 0,
                 extra_delay_samples: int = 0,
                 mask: NDArray[np.bool_] | None = None) -> None:
        self.gain = check_range("ilc_gain", gain, 0.0, 2.0, lo_open=True, hi_open=True)
        self.forgetting = check_range("ilc_forgetting", forgetting, 0.0, 1.0, lo_open=True)
        if smoothing_samples < 0 or extra_delay_samples < 0:
            raise InputError("ilc smoothing and delay samples must be >= 0")
        self.a, self.b, nd = model.discrete(dt)
        self.shift = nd + int(extra_delay_samples)
        self.half = int(smoothing_samples)
        self.command = np.zeros(int(n_samples))
        self.model = model
        self.mask = (np.ones(int(n_samples), dtype=bool) if mask is None
                     else np.asarray(mask, dtype=bool))
        if self.mask.shape != self.command.shape:
            raise InputError(f"ILC mask must have {int(n_samples)} samples, got {self.mask.size}")

    @property
    def contraction(self) -> float:
        """|forgetting x (1 - gamma)|: the error ratio per stride for an exact linear model."""
        return abs(self.forgetting * (1.0 - self.gain))

    def learn(self, error_mpa: NDArray[np.float64]) -> None:
        """Update the command trajectory from one stride's pressure-domain error.

        The error is taken as periodic (the stride repeats): samples past the end wrap.

        Parameters
        ----------
        error_mpa : ndarray
            Reference minus achieved, in MPa, one value per sample of the stride.
        """
        e = np.asarray(error_mpa, dtype=float)
        if e.shape != self.command.shape:
            raise InputError(f"ILC error must have {self.command.size} samples, got {e.size}")
        s = self.shift
        e0 = np.roll(e, -s)
        e1 = np.roll(e, -(s + 1))
        corr = self.gain * (e1 - self.a * e0) / self.b
        new = self.forgetting * _moving_average(self.command + corr, self.half)
        self.command = np.where(self.mask, new, 0.0)


class PressureMPC:
    """Box-constrained pressure-tracking MPC on the FOPDT model (see the module docstring).

    At each MPC sample (``sample_s``) it predicts the pressure over ``horizon`` samples from
    the measured pressure (advanced over the sensor delay and the dead time with the commands
    already sent) and chooses the commands u_0..u_{H-1} (held over each MPC sample) that
    minimise sum_i (p_i - p_ref,i)^2 + lam sum_i (u_i - u_{i-1})^2 with u_min <= u <= u_max.
    Only u_0 is applied. The problem is solved by :func:`box_lsq` (bounded least squares,
    checked against :func:`scipy.optimize.lsq_linear`).

    Parameters
    ----------
    model : PlantModel
        The supply model.
    sample_s : float
        MPC sample time in s.
    horizon : int
        Prediction horizon in MPC samples (unitless count, >= 2).
    u_min, u_max : float
        Command bounds in MPa.
    weight_du : float
        lam, the penalty on command changes (MPa^2/MPa^2, >= 0).
    measurement_delay_s : float
        Age of the pressure measurement in s.

    Examples
    --------
    >>> mpc = PressureMPC(PlantModel(1.0, 0.05), 0.01, 20, 0.0, 0.6)
    >>> u = mpc.command(0.0, np.full(20, 0.3))
    >>> 0.3 < u <= 0.6                     # pushes harder than the target to get there fast
    True
    """

    def __init__(self, model: PlantModel, sample_s: float, horizon: int, u_min: float,
                 u_max: float, *, weight_du: float = 1e-3,
                 measurement_delay_s: float = 0.0) -> None:
        if horizon < 2:
            raise InputError(f"mpc horizon must be >= 2 samples, got {horizon}")
        self.model = model
        self.ts = check_range("mpc_sample_s", sample_s, 1e-5, 10.0, unit="s")
        self.a, self.b, self.nd = model.discrete(self.ts)
        self.n_meas = int(round(measurement_delay_s / self.ts))
        self.h = int(horizon)
        self.u_min, self.u_max = float(u_min), float(u_max)
        self.lam = check_range("mpc_weight_du", weight_du, 0.0, 1e6)
        # commands sent over the last nd + n_meas MPC samples, oldest first (u(t-L) .. u(t-1))
        self.past = np.zeros(self.nd + self.n_meas)
        self.last = 0.0
        self._build()
        self.n_constrained = 0

    def _build(self) -> None:
        h, a, b = self.h, self.a, self.b
        # p_i (i = 1..h) = a^i p0 + sum_j a^(i-1-j) b u_j  (+ past commands through the delay)
        g = np.zeros((h, h))
        for i in range(h):
            g[i, : i + 1] = b * a ** np.arange(i, -1, -1)
        self.g = g
        d = np.eye(h) - np.eye(h, k=-1)
        self.d = d
        self.m = np.vstack([g, math.sqrt(self.lam) * d])
        self.pinv = np.linalg.pinv(self.m)
        self.hessian = self.m.T @ self.m

    def _state_now(self, p_measured: float) -> tuple[float, NDArray[np.float64]]:
        """Pressure predicted for the first command's effect (s) and the delayed inputs."""
        a, b, nd = self.a, self.b, self.nd
        p = p_measured
        hist = self.past
        # advance over the measurement age with the commands that acted then
        for k in range(self.n_meas):
            p = a * p + b * hist[k]
        # commands already sent that act over the next nd samples
        inflight = hist[self.n_meas: self.n_meas + nd]
        return p, inflight

    def command(self, p_measured: float, p_ref: NDArray[np.float64]) -> float:
        """The command (MPa) for the next MPC sample.

        Parameters
        ----------
        p_measured : float
            The measured tube pressure in MPa (``measurement_delay_s`` old).
        p_ref : ndarray
            Reference pressure in MPa over the next ``horizon`` MPC samples after the dead
            time (padded with its last value when shorter).

        Returns
        -------
        float
            The command in MPa, within [u_min, u_max].
        """
        h = self.h
        ref = np.asarray(p_ref, dtype=float)[:h]
        if ref.size < h:
            ref = np.concatenate([ref, np.full(h - ref.size, ref[-1] if ref.size else 0.0)])
        p, inflight = self._state_now(p_measured)
        for u in inflight:                      # through the dead time
            p = self.a * p + self.b * u
        free = p * self.a ** np.arange(1, h + 1)
        target = np.concatenate([ref - free, np.zeros(h)])
        target[h] = math.sqrt(self.lam) * self.last    # du_0 = u_0 - u_{-1}
        u = self.pinv @ target
        if u.min() < self.u_min - 1e-12 or u.max() > self.u_max + 1e-12:
            u = box_lsq(self.m, target, self.u_min, self.u_max, hessian=self.hessian)
            self.n_constrained += 1
        u0 = float(min(max(u[0], self.u_min), self.u_max))
        if self.past.size:
            self.past = np.concatenate([self.past[1:], [u0]])
        self.last = u0
        return u0
