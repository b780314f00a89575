"""Gains for the friction loop: an IMC/SIMC rule and ITAE optimisation under saturation.

The loop seen by the controller is pressure supply (gain Kv, lag tau, dead time theta)
followed by the friction map, linearised at the target: process gain
K = Kv dF/dP (N/MPa). The paper determined its gains "by the experimental method" and prints
none, so exofric uses documented rules:

* PI -- SIMC (Skogestad 2003, J. Process Control 13:291): Kc = tau / (K (tau_c + theta)),
  Ti = min(tau, 4 (tau_c + theta)).
* PID -- IMC with a first-order Pade delay (Rivera, Morari & Skogestad 1986, Ind. Eng. Chem.
  Process Des. Dev. 25:252; Seborg et al., Process Dynamics and Control, Table 12.1):
  Kc = (tau + theta/2) / (K (tau_c + theta/2)), Ti = tau + theta/2, Td = tau theta/(2 tau + theta).
* PD -- the PID rule's Kc and Td without integral action (the paper keeps Kp and Kd the same
  with and without the model).

The single tuning knob is the desired closed-loop time constant tau_c (s). Default:
tau_c = tau + theta, a smooth "lambda tuning" (closed loop about as fast as the supply's own
step response), consistent with the 4-6 s settling times of the paper's rig; SIMC's tight
setting is tau_c = theta. See ``docs/paper-notes.md`` for how the feedforward benefit
depends on this choice.

Units: gains kp MPa/N, ki MPa/(N s), kd MPa s/N; times s; process gain N/MPa.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.control._metrics import itae
from exofric.control._pid import Controller, ModelFeedforward, PIDGains
from exofric.control._plant import FrictionFn, PlantParams
from exofric.control._simulate import simulate
from exofric.errors import InputError, check_positive, check_range

__all__ = ["TuningResult", "rule_gains", "itae_gains", "CONTROLLERS"]

#: The controller kinds the tuning rules give gains for.
CONTROLLERS = ("pd", "pi", "pid")


@checked_init
@dataclass(frozen=True)
class TuningResult(DisplayMixin):
    """Gains and how they were obtained.

    Attributes
    ----------
    controller : str
        'pd', 'pi' or 'pid'.
    gains : PIDGains
        kp (MPa/N), ki (MPa/(N s)), kd (MPa s/N).
    method : str
        'imc-simc' (rule) or 'itae' (optimised).
    process_gain_n_per_mpa, time_constant_s, delay_s, tau_c_s : float
        The linearised loop and the closed-loop time constant used (s).
    itae_n_s2 : float or None
        ITAE of the friction error (N s^2) for optimised gains.

    Examples
    --------
    >>> r = rule_gains("pid", 400.0, 0.8, 0.2)        # N/MPa, s, s
    >>> r.method, r.tau_c_s, r.gains.kind, r.itae_n_s2
    ('imc-simc', 1.0, 'pid', None)
    """

    controller: str
    gains: PIDGains
    method: str
    process_gain_n_per_mpa: float
    time_constant_s: float
    delay_s: float
    tau_c_s: float
    itae_n_s2: float | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (gains with units in their keys)."""
        return {
            "controller": self.controller,
            "method": self.method,
            "gains": self.gains.to_dict(),
            "process_gain_n_per_mpa": self.process_gain_n_per_mpa,
            "time_constant_s": self.time_constant_s,
            "delay_s": self.delay_s,
            "tau_c_s": self.tau_c_s,
            "itae_n_s2": self.itae_n_s2,
        }


def _kind(controller: str) -> str:
    c = str(controller).lower()
    if c not in CONTROLLERS:
        raise InputError(f"controller must be one of {', '.join(CONTROLLERS)}, got {controller!r}")
    return c


def rule_gains(
    controller: str,
    process_gain_n_per_mpa: float,
    time_constant_s: float,
    delay_s: float,
    *,
    tau_c_s: float | None = None,
) -> TuningResult:
    """PD/PI/PID gains by the IMC/SIMC rules for a first-order-plus-dead-time loop.

    Parameters
    ----------
    controller : {'pd', 'pi', 'pid'}
    process_gain_n_per_mpa : float
        K = supply gain x dF/dP at the operating point, in N/MPa.
    time_constant_s, delay_s : float
        Supply lag tau and dead time theta in s (e.g. identified).
    tau_c_s : float or None
        Desired closed-loop time constant in s; default tau + theta.

    Returns
    -------
    TuningResult

    Examples
    --------
    >>> r = rule_gains("pi", 400.0, 0.8, 0.2, tau_c_s=0.2)      # SIMC tight
    >>> round(r.gains.kp, 6), round(r.gains.ti_s, 3)            # 0.8/(400*0.4), Ti = tau
    (0.005, 0.8)
    """
    kind = _kind(controller)
    k = check_positive("process gain (N/MPa)", process_gain_n_per_mpa)
    tau = check_positive("time_constant_s", time_constant_s, "s")
    theta = check_range("delay_s", delay_s, 0.0, 1e3, unit="s")
    tc = tau + theta if tau_c_s is None else check_positive("tau_c_s", tau_c_s, "s")
    if kind == "pi":
        kc = tau / (k * (tc + theta))
        ti = min(tau, 4.0 * (tc + theta))
        gains = PIDGains(kc, kc / ti, 0.0)
    else:
        kc = (tau + theta / 2.0) / (k * (tc + theta / 2.0))
        ti = tau + theta / 2.0
        td = tau * theta / (2.0 * tau + theta)
        gains = PIDGains(kc, kc / ti if kind == "pid" else 0.0, kc * td)
    return TuningResult(kind, gains, "imc-simc", k, tau, theta, tc)


def itae_gains(
    start: TuningResult,
    plant: PlantParams,
    true_friction: FrictionFn,
    target_n: float,
    *,
    feedforward: ModelFeedforward | None = None,
    duration_s: float = 15.0,
    dt: float = 0.01,
    max_evals: int = 120,
    controller_factory: Callable[[PIDGains], Controller] | None = None,
) -> TuningResult:
    """Gains minimising ITAE = integral t |F_target - F| dt on the saturated nonlinear loop.

    Nelder-Mead on the logarithms of the non-zero gains, started from ``start`` (the rule), on
    the closed-loop simulation (command saturated to 0..p_max, back-calculation anti-windup).
    Deterministic (fixed start, no randomness; sensor noise follows ``plant.seed``).

    Parameters
    ----------
    start : TuningResult
        Starting gains (e.g. from :func:`rule_gains`); its zero gains stay zero.
    plant : PlantParams
        Supply model (lag and dead time in s, saturation in MPa, sensor noise in N).
    true_friction : callable
        The friction map F(P) the loop acts on: pressure in MPa -> friction in N (scalar).
    target_n : float
        Step target in N.
    feedforward : ModelFeedforward or None
        Optional model feedforward used during the optimisation.
    duration_s, dt : float
        Simulated horizon and sample time in s.
    max_evals : int
        Budget of closed-loop simulations.
    controller_factory : callable or None
        Builds the controller from gains (default: limits 0..p_max, back-calculation).

    Returns
    -------
    TuningResult
        With ``method='itae'`` and the achieved ITAE (N s^2).

    Raises
    ------
    InputError
        ``max_evals`` < 1 or all starting gains zero.

    Examples
    --------
    A short horizon and a small budget keep this fast; never worse than the start.

    >>> from exofric.control import simulate
    >>> start = rule_gains("pi", 200.0, 0.8, 0.2)
    >>> fmap = lambda p: 200.0 * p
    >>> r = itae_gains(start, PlantParams(), fmap, 40.0, duration_s=5.0, max_evals=10)
    >>> s = simulate(Controller(start.gains), PlantParams(), fmap, 40.0, duration_s=5.0)
    >>> r.method, r.itae_n_s2 <= itae(s.time_s, s.setpoint_n - s.friction_n)
    ('itae', True)
    """
    from scipy.optimize import minimize

    if max_evals < 1:
        raise InputError(f"max_evals must be >= 1, got {max_evals}")
    g0 = start.gains
    names = [n for n in ("kp", "ki", "kd") if getattr(g0, n) > 0.0]
    if not names:
        raise InputError("starting gains are all zero: nothing to optimise")
    x0 = np.log([getattr(g0, n) for n in names])

    def build(x: np.ndarray) -> PIDGains:
        vals = {n: 0.0 for n in ("kp", "ki", "kd")}
        vals.update({n: float(math.exp(v)) for n, v in zip(names, x, strict=True)})
        return PIDGains(**vals)

    def make(g: PIDGains) -> Controller:
        if controller_factory is not None:
            return controller_factory(g)
        return Controller(g, u_max=plant.p_max_mpa, feedforward=feedforward)

    def cost(x: np.ndarray) -> float:
        if np.any(np.abs(x - x0) > 7.0):       # stay within e^7 ~ 1000x of the start
            return math.inf
        c = make(build(x))
        r = simulate(c, plant, true_friction, target_n, duration_s=duration_s, dt=dt)
        return itae(r.time_s, r.setpoint_n - r.friction_n)

    res = minimize(cost, x0, method="Nelder-Mead",
                   options={"maxfev": int(max_evals), "xatol": 1e-3, "fatol": 1e-6,
                            "initial_simplex": np.vstack([x0] + [x0 + 0.4 * np.eye(len(x0))[i]
                                                                 for i in range(len(x0))])})
    best_x = res.x if res.fun <= cost(x0) else x0
    return TuningResult(start.controller, build(best_x), "itae", start.process_gain_n_per_mpa,
                        start.time_constant_s, start.delay_s, start.tau_c_s,
                        float(min(res.fun, cost(x0))))
