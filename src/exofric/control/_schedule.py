"""Controllers beyond fixed PID: gain scheduling on dF/dP, hysteresis-aware feedforward.

The friction map F(P) is strongly nonlinear: dF/dP is 0 below contact onset and varies along
the map above it, so a PID tuned at one operating point is too slow where the map is flat and
too aggressive where it is steep. This module adds:

* :class:`ScheduledController` -- a :class:`~exofric.control.Controller` whose gains are the
  nominal gains times ``slope_ref / max(dF/dP(P_op), floor)``: the loop gain (controller gain x
  local slope) stays that of the tuning point. ``P_op`` is the model's pressure for the
  target (default) or the measured tube pressure. Gain changes are bumpless (the integral
  absorbs the jump of the proportional and derivative terms); anti-windup, derivative
  filtering, limits and feedforward are the Controller's.
* :class:`HystereticFrictionMap` -- a two-branch hysteretic friction for the simulated plant:
  F_k = clip(F_{k-1}, F_up(P_k), F_down(P_k)) (rising pressure drives F along the lower *up*
  branch, falling pressure along the upper *down* branch, in between F holds). With branches
  g(P - w) and g(P + w) this is a backlash (play) of half-width w MPa in pressure.
* :class:`HysteresisInverse` -- the feedforward P_ff(F) from the up-branch inverse when the
  target rises and the down-branch inverse when it falls.
* :func:`compare_strategies` -- {PD, PI, PID} x {no feedforward, model inverse,
  hysteresis-aware inverse} x {fixed, scheduled} on a simulated plant: a :class:`StrategyTable`
  of settling time, overshoot and steady-state error.

Units: friction N, pressure MPa, time s, slopes N/MPa; gains kp MPa/N, ki MPa/(N s),
kd MPa s/N.

Examples
--------
>>> c = ScheduledController(PIDGains(0.002, 0.004), lambda p: 100.0 * p * p,
...                         slope_ref_n_per_mpa=60.0)
>>> _ = c.step(9.0, 0.0, 0.01)             # target 9 N: P = 0.3 MPa, slope 60 N/MPa
>>> round(c.gain_factor, 12)
1.0
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from exofric import defaults as D
from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.control._metrics import step_metrics
from exofric.control._pid import Controller, ModelFeedforward, PIDGains
from exofric.control._plant import CurveFrictionMap, FrictionFn, PlantParams, local_slope
from exofric.control._simulate import PlantLike, simulate
from exofric.control._tuning import CONTROLLERS, rule_gains
from exofric.errors import InputError, check_finite, check_range

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "ScheduledController",
    "HystereticFrictionMap",
    "HysteresisInverse",
    "StrategyOptions",
    "StrategyRow",
    "StrategyTable",
    "compare_strategies",
    "friction_inverse",
]

# Module constants (candidates for exofric.defaults).
#: Default slope floor as a fraction of the reference slope (unitless): scheduled gains are at
#: most 1/0.1 = 10 x the nominal gains (below contact onset, where dF/dP = 0).
SCHEDULE_FLOOR_RATIO = D.SCHEDULE_FLOOR_RATIO
#: Central-difference step for the local slope dF/dP in MPa.
SCHEDULE_SLOPE_STEP_MPA = 1e-4
#: Relative gain change below which the gains are left as they are (unitless): keeps a
#: constant-slope map bit-identical to the plain Controller.
SCHEDULE_GAIN_RTOL = 1e-9
#: Pressure tolerance of the bisection inverse of a friction map in MPa.
INVERSE_TOL_MPA = 1e-12
#: Default backlash half-width of the hysteretic plant in the comparison, MPa (10 kPa: the
#: up/down branches differ by about 2 x 0.01 x 471 = 9.4 N at the paper's 54.4 N target).
COMPARE_HYSTERESIS_MPA = D.SCHEDULE_COMPARE_HYSTERESIS_MPA
#: Feedforward variants of :func:`compare_strategies`.
FEEDFORWARDS = ("none", "model", "hysteresis")

ScheduleOn = Literal["target", "measured"]


def friction_inverse(friction_map: FrictionFn, friction_n: float, *, p_max_mpa: float = 0.6,
                     tol_mpa: float = INVERSE_TOL_MPA) -> float:
    """Smallest pressure (MPa) in [0, p_max] at which a monotone map reaches ``friction_n`` (N).

    A map with its own exact ``inverse`` (:class:`~exofric.control.CurveFrictionMap`: the root
    of the squeeze curve's interpolant; :class:`~exofric.control.CubicFrictionMap`: the cubic's
    root) is inverted by it wherever it answers, so the feedforward, the scheduling and
    ``exofric invert`` agree to round-off. Elsewhere (an Eq 9 cubic below its fit range, down
    to contact onset; a bare callable) it bisects the forward map to ``tol_mpa``. Targets
    <= F(0) give 0 MPa (nothing to hold: vent); targets above F(p_max) give p_max (the best
    reachable).

    Parameters
    ----------
    friction_map : callable
        Friction F(P): pressure in MPa -> N, non-decreasing; optionally with ``inverse``.
    friction_n : float
        Target friction in N.
    p_max_mpa : float
        Upper end of the search in MPa (the supply pressure).
    tol_mpa : float
        Bracket width at which the bisection stops, in MPa.

    Returns
    -------
    float
        Pressure in MPa.

    Examples
    --------
    >>> round(friction_inverse(lambda p: 100.0 * p * p, 9.0), 9)
    0.3
    """
    f = check_finite("friction_n", friction_n)
    lo, hi = 0.0, float(p_max_mpa)
    if f <= float(friction_map(lo)):
        return lo
    if f > float(friction_map(hi)):
        return hi
    exact = getattr(friction_map, "inverse", None)
    if callable(exact):
        try:
            p = float(exact(f))
        except InputError:          # outside the range its own inverse covers
            p = math.nan
        if lo <= p <= hi:
            return p
    for _ in range(200):
        if hi - lo <= tol_mpa:
            break
        mid = 0.5 * (lo + hi)
        if float(friction_map(mid)) < f:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


class ScheduledController(Controller):
    """PID/PI/PD with gains scheduled on the local slope dF/dP of the friction map.

    Effective gains = nominal gains x ``slope_ref / max(dF/dP(P_op), floor)`` (all three by
    the same factor, so Ti, Td, the tracking time and the derivative filter are unchanged).
    ``P_op`` is the model's pressure for the set-point (``schedule_on='target'``, evaluated
    when the set-point changes) or the measured tube pressure (``'measured'``; the loop
    passes it as ``step(..., pressure_mpa=p)``; without it the target is used).

    A gain change is bumpless: before the sample that uses new gains, the derivative state is
    rescaled with the gains and the integral (the bias for a PD) absorbs the change of the
    proportional and derivative terms at the previous sample's signals, so the command does
    not jump.

    Parameters
    ----------
    gains : PIDGains
        Nominal gains (kp MPa/N, ki MPa/(N s), kd MPa s/N), tuned where the slope is
        ``slope_ref_n_per_mpa``.
    friction_map : callable
        Model friction F(P): MPa -> N, non-decreasing.
    slope_ref_n_per_mpa : float
        The slope dF/dP (N/MPa) the nominal gains were tuned for (> 0).
    floor_n_per_mpa : float or None
        Lower bound of the slope in N/MPa (> 0), bounding the gains below contact onset;
        default ``SCHEDULE_FLOOR_RATIO`` (0.1) x the reference slope.
    schedule_on : {'target', 'measured'}
        Operating point: model pressure for the set-point, or the measured pressure (then
        the attribute ``uses_pressure`` is True and :func:`~exofric.control.simulate` passes
        the tube pressure each sample).
    operating_pressure : callable or None
        P(F): N -> MPa for the target; default :func:`friction_inverse` of the map over
        [0, u_max].
    slope_step_mpa : float
        Central-difference step of the slope in MPa.
    **controller_options
        Passed to :class:`~exofric.control.Controller` (``u_min``, ``u_max`` in MPa,
        ``antiwindup``, ``tracking_time_s``, ``derivative_filter_s``, ``derivative_on``,
        ``feedforward``, ``bias_mpa``).

    Examples
    --------
    >>> c = ScheduledController(PIDGains(0.002, 0.004), lambda p: 100.0 * p * p,
    ...                         slope_ref_n_per_mpa=60.0)
    >>> _ = c.step(2.25, 0.0, 0.01)         # 2.25 N at 0.15 MPa: slope 30 N/MPa
    >>> round(c.gain_factor, 9), round(c.gains.kp, 9)
    (2.0, 0.004)
    """

    def __init__(
        self,
        gains: PIDGains,
        friction_map: FrictionFn,
        *,
        slope_ref_n_per_mpa: float,
        floor_n_per_mpa: float | None = None,
        schedule_on: ScheduleOn = "target",
        operating_pressure: Callable[[float], float] | None = None,
        slope_step_mpa: float = SCHEDULE_SLOPE_STEP_MPA,
        **controller_options: Any,
    ) -> None:
        self.nominal_gains = gains
        self.friction_map = friction_map
        self.slope_ref_n_per_mpa = check_range("slope_ref_n_per_mpa", slope_ref_n_per_mpa,
                                               0.0, 1e12, lo_open=True, unit="N/MPa")
        floor = (SCHEDULE_FLOOR_RATIO * self.slope_ref_n_per_mpa if floor_n_per_mpa is None
                 else floor_n_per_mpa)
        self.floor_n_per_mpa = check_range("floor_n_per_mpa", floor, 0.0, 1e12, lo_open=True,
                                           unit="N/MPa")
        if schedule_on not in ("target", "measured"):
            raise InputError(f"schedule_on must be target or measured, got {schedule_on!r}")
        self.schedule_on: str = schedule_on
        #: True when scheduled on the measured pressure: simulate() then passes pressure_mpa.
        self.uses_pressure = schedule_on == "measured"
        self.slope_step_mpa = check_range("slope_step_mpa", slope_step_mpa, 0.0, 1.0,
                                          lo_open=True, unit="MPa")
        self._operating_pressure = operating_pressure
        self.gain_factor = 1.0
        self.operating_pressure_mpa = math.nan
        self._sp = math.nan
        self._sp_p = math.nan
        super().__init__(gains, **controller_options)

    def reset(self, output: float | None = None) -> None:
        """Clear the state and return to the nominal gains (see :meth:`Controller.reset`).

        Parameters
        ----------
        output : float or None
            The command in MPa currently applied, returned by the next :meth:`step`
            (bumpless start); None to start from a zero state.

        Examples
        --------
        >>> c = ScheduledController(PIDGains(0.002, 0.004), lambda p: 100.0 * p * p,
        ...                         slope_ref_n_per_mpa=60.0)
        >>> c.reset(output=0.3)
        >>> round(c.step(2.25, 2.0, 0.01), 9)      # bumpless start at the scheduled gains
        0.3
        """
        self.gains = self.nominal_gains
        self.gain_factor = 1.0
        super().reset(output)

    def factor_at(self, pressure_mpa: float) -> float:
        """Gain factor slope_ref / max(dF/dP, floor) at ``pressure_mpa`` (unitless).

        Parameters
        ----------
        pressure_mpa : float
            Operating pressure in MPa.

        Returns
        -------
        float
            The multiplier of the nominal gains (unitless).

        Examples
        --------
        >>> c = ScheduledController(PIDGains(0.002), lambda p: 100.0 * p * p,
        ...                         slope_ref_n_per_mpa=60.0)
        >>> c.factor_at(0.0)            # below onset: the floor (0.1 x 60 N/MPa)
        10.0
        """
        slope = local_slope(self.friction_map, pressure_mpa, self.slope_step_mpa)
        return self.slope_ref_n_per_mpa / max(slope, self.floor_n_per_mpa)

    def _target_pressure(self, setpoint: float) -> float:
        if setpoint != self._sp:
            inv = self._operating_pressure
            self._sp_p = (float(inv(setpoint)) if inv is not None
                          else friction_inverse(self.friction_map, setpoint, p_max_mpa=self.u_max))
            self._sp = setpoint
        return self._sp_p

    def _rescale(self, factor: float) -> None:
        """Switch to ``factor`` x nominal gains without a jump of the command."""
        rho = factor / self.gain_factor
        g = self.gains
        if not self._first:
            # Terms at the previous sample's signals: P = kp e, D (state). New gains give
            # rho P and rho D; the integral (bias for PD) takes the difference.
            corr = (1.0 - rho) * (g.kp * self._e_prev + self.derivative_mpa)
            self.derivative_mpa *= rho
            if g.ki > 0.0:
                self.integral_mpa += corr
            else:
                self.bias_mpa += corr
        n = self.nominal_gains
        self.gains = PIDGains(n.kp * factor, n.ki * factor, n.kd * factor)
        self.gain_factor = factor

    def step(self, setpoint: float, measurement: float, dt: float,
             pressure_mpa: float | None = None) -> float:
        """One sample: set-point, measurement (N), dt (s), optional pressure (MPa) -> MPa.

        Parameters
        ----------
        setpoint : float
            Friction set-point r in N.
        measurement : float
            Measured friction y in N.
        dt : float
            Time since the previous call in s (> 0).
        pressure_mpa : float or None
            Measured tube pressure in MPa (used when ``schedule_on='measured'``).

        Returns
        -------
        float
            Pressure command in MPa, within [u_min, u_max].

        Examples
        --------
        >>> c = ScheduledController(PIDGains(0.002), lambda p: 100.0 * p * p,
        ...                         slope_ref_n_per_mpa=60.0, schedule_on="measured")
        >>> round(c.step(9.0, 4.0, 0.01, pressure_mpa=0.6), 9)   # slope 120: kp halved
        0.005
        """
        if self.schedule_on == "measured" and pressure_mpa is not None:
            p_op = check_finite("pressure_mpa", pressure_mpa)
        else:
            if not math.isfinite(setpoint):
                raise InputError(f"setpoint must be finite (N), got {setpoint}")
            p_op = self._target_pressure(setpoint)
        self.operating_pressure_mpa = p_op
        factor = self.factor_at(p_op)
        if abs(factor - self.gain_factor) > SCHEDULE_GAIN_RTOL * self.gain_factor:
            self._rescale(factor)
        return super().step(setpoint, measurement, dt)

    def state(self) -> dict[str, Any]:
        """Controller state for logging, plus ``gain_factor`` and ``operating_pressure_mpa``.

        Returns
        -------
        dict
            Integral, derivative, feedforward and bias terms (MPa), the gain factor
            (unitless) and the operating pressure (MPa).

        Examples
        --------
        >>> c = ScheduledController(PIDGains(0.002), lambda p: 100.0 * p * p,
        ...                         slope_ref_n_per_mpa=60.0)
        >>> c.state()["gain_factor"]
        1.0
        """
        out = super().state()
        out.update(gain_factor=self.gain_factor,
                   operating_pressure_mpa=self.operating_pressure_mpa)
        return out


class HystereticFrictionMap:
    """Two-branch hysteretic friction for a simulated plant (stateful; sequential calls).

    Each call moves the friction to ``clip(F_prev, F_up(P), F_down(P))``: rising pressure
    drives it along the lower *up* branch, falling pressure along the upper *down* branch,
    and on a reversal it holds until it meets the other branch (a Preisach-lite / backlash
    model; ``F_up <= F_down`` is required). :meth:`from_play` builds the branches
    g(P - w), g(P + w) of a backlash of half-width w in pressure. Call it once per sample in
    time order (as :func:`~exofric.control.simulate` does); :meth:`reset` restarts it.

    Parameters
    ----------
    up, down : callable
        Branch frictions F(P): MPa -> N (scalar), ``up(P) <= down(P)``.
    friction0_n : float
        Initial friction in N (default 0: an empty tube).

    Examples
    --------
    >>> h = HystereticFrictionMap.from_play(lambda p: 100.0 * p, 0.05)
    >>> [round(h(p), 6) for p in (0.3, 0.4, 0.38, 0.3)]   # up, up, hold, down branch
    [25.0, 35.0, 35.0, 35.0]
    """

    def __init__(self, up: FrictionFn, down: FrictionFn, *, friction0_n: float = 0.0) -> None:
        self.up = up
        self.down = down
        self._f0 = check_finite("friction0_n", friction0_n)
        self.friction_n = self._f0

    @classmethod
    def from_play(cls, friction_map: FrictionFn, width_mpa: float) -> HystereticFrictionMap:
        """Backlash of half-width ``width_mpa`` in pressure around ``friction_map``.

        Up branch g(max(P - w, 0)), down branch g(P + w).

        Parameters
        ----------
        friction_map : callable
            The middle (anhysteretic) map g(P): MPa -> N, non-decreasing.
        width_mpa : float
            Half-width w of the play in MPa (>= 0).

        Returns
        -------
        HystereticFrictionMap

        Examples
        --------
        >>> h = HystereticFrictionMap.from_play(lambda p: 100.0 * p, 0.05)
        >>> round(h.up(0.3), 6), round(h.down(0.3), 6)
        (25.0, 35.0)
        """
        w = check_range("width_mpa", width_mpa, 0.0, 10.0, unit="MPa")
        return cls(lambda p: float(friction_map(max(p - w, 0.0))),
                   lambda p: float(friction_map(p + w)))

    def reset(self, friction_n: float | None = None) -> None:
        """Restart from ``friction_n`` N (default the initial friction).

        Parameters
        ----------
        friction_n : float or None
            Friction in N to restart from.

        Examples
        --------
        >>> h = HystereticFrictionMap.from_play(lambda p: 100.0 * p, 0.05)
        >>> _ = h(0.5); h.reset(); h.friction_n
        0.0
        """
        self.friction_n = self._f0 if friction_n is None else check_finite("friction_n",
                                                                             friction_n)

    def __call__(self, pressure_mpa: float) -> float:
        """Friction in N after the pressure moved to ``pressure_mpa`` MPa (updates the state)."""
        p = float(pressure_mpa)
        lo, hi = float(self.up(p)), float(self.down(p))
        f = self.friction_n
        f = lo if f < lo else (hi if f > hi else f)
        self.friction_n = f
        return f

    def settled(self, pressure_mpa: float) -> float:
        """Friction in N the map settles at if the pressure moves monotonically to ``pressure_mpa``.

        ``clip(F_now, F_up(P), F_down(P))`` from the current state, which it leaves unchanged
        (the 2-DOF :class:`~exofric.control.ModelFeedforward` asks it where its model reference
        settles).

        Parameters
        ----------
        pressure_mpa : float
            Final pressure in MPa.

        Returns
        -------
        float
            Friction in N.

        Examples
        --------
        >>> h = HystereticFrictionMap.from_play(lambda p: 100.0 * p, 0.05)
        >>> _ = h(0.4); h.settled(0.3), h.friction_n     # down to 0.3 MPa: the down branch
        (35.0, 35.0)
        """
        p = float(pressure_mpa)
        lo, hi = float(self.up(p)), float(self.down(p))
        f = self.friction_n
        return lo if f < lo else (hi if f > hi else f)


class HysteresisInverse:
    """Hysteresis-aware feedforward P_ff(F): up-branch inverse on rising targets, down on falling.

    Stateful: it remembers the previous target and the branch in use (starting on the up
    branch, from an empty tube). Use it as :class:`~exofric.control.Controller`'s
    ``feedforward`` (or inside a :class:`~exofric.control.ModelFeedforward`), which calls it
    when the set-point changes.

    Parameters
    ----------
    up_inverse, down_inverse : callable
        P(F): N -> MPa of the up branch (reached with rising pressure) and of the down
        branch (falling pressure).
    branch : {'up', 'down'}
        Branch before the first target.

    Examples
    --------
    >>> inv = HysteresisInverse.from_play(lambda p: 100.0 * p, 0.05)
    >>> [round(inv(f), 6) for f in (30.0, 40.0, 30.0)]    # up: g^-1 + w; down: g^-1 - w
    [0.35, 0.45, 0.25]
    >>> inv.branch
    'down'
    """

    def __init__(self, up_inverse: Callable[[float], float],
                 down_inverse: Callable[[float], float], *,
                 branch: Literal["up", "down"] = "up") -> None:
        if branch not in ("up", "down"):
            raise InputError(f"branch must be up or down, got {branch!r}")
        self.up_inverse = up_inverse
        self.down_inverse = down_inverse
        self._branch0: str = branch
        self.branch: str = branch
        self._last = math.nan

    @classmethod
    def from_maps(cls, up_map: Any, down_map: Any) -> HysteresisInverse:
        """From two friction maps with an ``inverse(F) -> P`` (e.g. CurveFrictionMap).

        Parameters
        ----------
        up_map, down_map : friction maps
            Maps F(P) (MPa -> N) of the up and down branches with ``inverse`` (N -> MPa).

        Returns
        -------
        HysteresisInverse

        Examples
        --------
        >>> from exofric.control import CurveFrictionMap
        >>> up = CurveFrictionMap((0.2, 0.6), (20.0, 60.0), 1.0)
        >>> dn = CurveFrictionMap((0.2, 0.6), (30.0, 70.0), 1.0)
        >>> round(HysteresisInverse.from_maps(up, dn)(40.0), 9)
        0.4
        """
        return cls(up_map.inverse, down_map.inverse)

    @classmethod
    def from_play(cls, friction_map: FrictionFn, width_mpa: float, *,
                  p_max_mpa: float = 0.6) -> HysteresisInverse:
        """Inverse of :meth:`HystereticFrictionMap.from_play`: g^-1(F) + w up, g^-1(F) - w down.

        Parameters
        ----------
        friction_map : callable
            Middle map g(P): MPa -> N, non-decreasing (inverted by bisection,
            :func:`friction_inverse`).
        width_mpa : float
            Half-width w of the play in MPa (>= 0).
        p_max_mpa : float
            Upper end of the inverse's search, MPa.

        Returns
        -------
        HysteresisInverse

        Examples
        --------
        >>> inv = HysteresisInverse.from_play(lambda p: 100.0 * p, 0.05)
        >>> round(inv.up_inverse(30.0), 9), round(inv.down_inverse(30.0), 9)
        (0.35, 0.25)
        """
        w = check_range("width_mpa", width_mpa, 0.0, 10.0, unit="MPa")

        def mid(f: float) -> float:
            return friction_inverse(friction_map, f, p_max_mpa=p_max_mpa)

        return cls(lambda f: mid(f) + w, lambda f: max(mid(f) - w, 0.0))

    @classmethod
    def from_curve(cls, curve: Mapping[str, Sequence[Any]]) -> HysteresisInverse:
        """From a reduced rig curve with up and down branches (``reduce_log(...).curve``).

        Parameters
        ----------
        curve : mapping of sequences
            Columns ``pressure_mpa`` (MPa), ``kinetic_n`` (N) and ``branch`` ('up'/'down'),
            one row per set point and branch; each branch needs >= 2 points with increasing
            friction.

        Returns
        -------
        HysteresisInverse

        Examples
        --------
        >>> c = {"pressure_mpa": [0.2, 0.4, 0.6, 0.4, 0.2],
        ...      "kinetic_n": [10.0, 30.0, 50.0, 36.0, 14.0],
        ...      "branch": ["up", "up", "up", "down", "down"]}
        >>> inv = HysteresisInverse.from_curve(c)
        >>> round(inv(30.0), 6), round(inv(25.0), 6)
        (0.4, 0.3)
        """
        try:
            p = np.asarray(curve["pressure_mpa"], dtype=float)
            f = np.asarray(curve["kinetic_n"], dtype=float)
            b = np.asarray(curve["branch"], dtype=str)
        except KeyError as exc:
            raise InputError(f"curve needs columns pressure_mpa, kinetic_n, branch; "
                             f"missing {exc}") from None
        maps = []
        for name in ("up", "down"):
            sel = b == name
            if sel.sum() < 2:
                raise InputError(f"curve needs >= 2 points on the {name} branch, "
                                 f"got {int(sel.sum())}")
            order = np.argsort(p[sel])
            maps.append(CurveFrictionMap(tuple(p[sel][order].tolist()),
                                         tuple(f[sel][order].tolist()), 1.0))
        return cls.from_maps(maps[0], maps[1])

    def reset(self, branch: Literal["up", "down"] | None = None) -> None:
        """Forget the previous target; continue on ``branch`` (default the initial one).

        Parameters
        ----------
        branch : {'up', 'down'} or None
            Branch the tube is on now.

        Examples
        --------
        >>> inv = HysteresisInverse.from_play(lambda p: 100.0 * p, 0.05)
        >>> _ = inv(40.0); _ = inv(30.0); inv.reset(); inv.branch
        'up'
        """
        self.branch = self._branch0 if branch is None else branch
        self._last = math.nan

    def __call__(self, friction_n: float) -> float:
        """Feedforward pressure (MPa) for target ``friction_n`` (N); updates the branch."""
        f = check_finite("friction_n", friction_n)
        if f > self._last:
            self.branch = "up"
        elif f < self._last:
            self.branch = "down"
        self._last = f
        inv = self.up_inverse if self.branch == "up" else self.down_inverse
        return float(inv(f))


# ---------------------------------------------------------------------------------------------
# The comparison.


@checked_init
@dataclass(frozen=True)
class StrategyRow:
    """One strategy on one scenario: metrics of the last step (s, %, N).

    Attributes
    ----------
    scenario : str
        E.g. ``'up 54.4 N'`` (step from rest) or ``'down 150->54.4 N'``.
    start_n, target_n : float
        Set-point before and after the measured step, in N (start 0 for a step from rest).
    controller : str
        ``'pd'``, ``'pi'`` or ``'pid'``.
    feedforward : str
        ``'none'``, ``'model'`` (inverse of the model map) or ``'hysteresis'`` (branch-aware).
    scheduled : bool
        Gains scheduled on dF/dP (else fixed at the tuning point).
    gain_factor : float
        Scheduled gain multiplier at the end of the run (1 for fixed gains), unitless.
    settling_time_s : float or None
        Time from the step to staying within the band of the target, s; None if never.
    overshoot_pct : float
        Overshoot in % of the step.
    steady_state_error_n : float
        Target - final friction, N.

    Examples
    --------
    >>> r = StrategyRow("up 54.4 N", 0.0, 54.4, "pi", "model", True, 1.0, 4.1, 0.0, 0.0)
    >>> r.to_dict()["settling_time_s"]
    4.1
    """

    scenario: str
    start_n: float
    target_n: float
    controller: str
    feedforward: str
    scheduled: bool
    gain_factor: float
    settling_time_s: float | None
    overshoot_pct: float
    steady_state_error_n: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (s, %, N)."""
        return asdict(self)


@checked_init
@dataclass(frozen=True)
class StrategyTable(DisplayMixin):
    """Settling time, overshoot and steady-state error of every strategy and scenario.

    Attributes
    ----------
    rows : tuple of StrategyRow
        One per scenario x controller x feedforward x schedule.
    plant : str
        Description of the simulated plant.
    tune_target_n : float
        Target (N) at whose pressure the fixed gains were tuned (the reference slope).
    slope_ref_n_per_mpa : float
        dF/dP at the tuning point, N/MPa.
    hysteresis_mpa : float
        Backlash half-width of the true friction in MPa (0: none).
    band : float
        Settling band, fraction of the step.
    dt_s, duration_s : float
        Sample time and horizon per step in s.

    Examples
    --------
    >>> from exofric.control import PlantParams
    >>> opts = StrategyOptions(controllers=("pi",), duration_s=3.0)
    >>> t = compare_strategies(PlantParams(), lambda p: 400.0 * p, targets_n=(40.0,),
    ...                        options=opts)
    >>> len(t.rows), t.rows[0].feedforward
    (4, 'none')
    """

    rows: tuple[StrategyRow, ...]
    plant: str
    tune_target_n: float
    slope_ref_n_per_mpa: float
    hysteresis_mpa: float
    band: float
    dt_s: float
    duration_s: float

    def get(self, scenario: str, controller: str, feedforward: str,
            scheduled: bool) -> StrategyRow:
        """The row of one strategy (KeyError if absent).

        Parameters
        ----------
        scenario : str
            Scenario label, e.g. ``'up 54.4 N'``.
        controller : str
            ``'pd'``, ``'pi'`` or ``'pid'``.
        feedforward : str
            ``'none'``, ``'model'`` or ``'hysteresis'``.
        scheduled : bool
            Scheduled or fixed gains.

        Returns
        -------
        StrategyRow

        Examples
        --------
        >>> from exofric.control import PlantParams
        >>> opts = StrategyOptions(controllers=("pi",), duration_s=3.0)
        >>> t = compare_strategies(PlantParams(), lambda p: 400.0 * p, targets_n=(40.0,),
        ...                        options=opts)
        >>> t.get("up 40 N", "pi", "model", False).target_n
        40.0
        """
        for r in self.rows:
            if (r.scenario, r.controller, r.feedforward, r.scheduled) == (
                    scenario, controller, feedforward, scheduled):
                return r
        raise KeyError((scenario, controller, feedforward, scheduled))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the settings and ``rows`` (each :meth:`StrategyRow.to_dict`)."""
        return {"plant": self.plant, "tune_target_n": self.tune_target_n,
                "slope_ref_n_per_mpa": self.slope_ref_n_per_mpa,
                "hysteresis_mpa": self.hysteresis_mpa, "settling_band_pct": 100.0 * self.band,
                "dt_s": self.dt_s, "duration_s": self.duration_s,
                "rows": [r.to_dict() for r in self.rows]}

    def to_frame(self) -> pd.DataFrame:
        """One row per strategy and scenario (columns as :class:`StrategyRow`; s, %, N).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> from exofric.control import PlantParams
        >>> opts = StrategyOptions(controllers=("pi",), duration_s=3.0)
        >>> t = compare_strategies(PlantParams(), lambda p: 400.0 * p, targets_n=(40.0,),
        ...                        options=opts)
        >>> list(t.to_frame().columns[:3])
        ['scenario', 'start_n', 'target_n']
        """
        import pandas as pd

        return pd.DataFrame([r.to_dict() for r in self.rows])

    def format(self) -> str:
        """Plain-text table (one line per row; settling s, overshoot %, error N).

        Returns
        -------
        str

        Examples
        --------
        >>> from exofric.control import PlantParams
        >>> opts = StrategyOptions(controllers=("pi",), duration_s=3.0)
        >>> t = compare_strategies(PlantParams(), lambda p: 400.0 * p, targets_n=(40.0,),
        ...                        options=opts)
        >>> t.format().splitlines()[0].split()[:3]
        ['scenario', 'ctrl', 'ff']
        """
        head = (f"{'scenario':<20} {'ctrl':<4} {'ff':<10} {'gains':<6} {'factor':>6} "
                f"{'settle_s':>8} {'over_%':>7} {'sse_N':>8}")
        lines = [head]
        for r in self.rows:
            ts = "never" if r.settling_time_s is None else f"{r.settling_time_s:.2f}"
            lines.append(f"{r.scenario:<20} {r.controller:<4} {r.feedforward:<10} "
                         f"{'sched' if r.scheduled else 'fixed':<6} {r.gain_factor:>6.2f} "
                         f"{ts:>8} {r.overshoot_pct:>7.1f} {r.steady_state_error_n:>8.3f}")
        return "\n".join(lines)


def _label(start: float, target: float) -> str:
    return f"up {target:g} N" if start == 0.0 else (
        f"{'down' if target < start else 'up'} {start:g}->{target:g} N")


@checked_init
@dataclass(frozen=True)
class StrategyOptions:
    """Which loops :func:`compare_strategies` builds, how it tunes them, how it judges a step.

    Defaults: PD, PI and PID; every relevant feedforward; fixed and scheduled gains, tuned by
    the IMC/SIMC rule at the paper's 54.4 N target; the 2-DOF feedforward; 10 ms steps over
    15 s per step, settled within 2 %.

    Parameters
    ----------
    controllers : sequence of str
        Among ``'pd'``, ``'pi'``, ``'pid'``.
    feedforwards : sequence of str or None
        Among ``'none'``, ``'model'``, ``'hysteresis'``; default all that are relevant
        (``'hysteresis'`` only when ``hysteresis_mpa`` > 0).
    schedules : sequence of bool
        False for fixed gains, True for scheduled.
    tune_target_n : float
        Target friction in N at which the fixed gains are tuned.
    tau_c_s : float or None
        Closed-loop time constant of the rule in s (default lag + dead time).
    ff_mode : {'2dof', 'static'}
        How the feedforward is combined with the feedback.
    schedule_on : {'target', 'measured'}
        Operating point of the scheduling.
    floor_n_per_mpa : float or None
        Slope floor of the scheduling in N/MPa (default 0.1 x the reference slope).
    dt, duration_s : float
        Sample time and horizon per step in s.
    band : float
        Settling band, fraction of the step (0.02 = 2 %).

    Examples
    --------
    >>> StrategyOptions(controllers=("pi",)).schedules
    (False, True)
    >>> StrategyOptions(controllers=("p",))
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: controller must be one of pd, pi, pid, got 'p'
    """

    controllers: Sequence[str] = CONTROLLERS
    feedforwards: Sequence[str] | None = None
    schedules: Sequence[bool] = (False, True)
    tune_target_n: float = 54.4
    tau_c_s: float | None = None
    ff_mode: Literal["2dof", "static"] = "2dof"
    schedule_on: ScheduleOn = "target"
    floor_n_per_mpa: float | None = None
    dt: float = 0.01
    duration_s: float = 15.0
    band: float = 0.02

    def __post_init__(self) -> None:
        check_range("tune_target_n", self.tune_target_n, 0.0, 1e6, lo_open=True, unit="N")
        for ff_name in self.feedforwards or ():
            if ff_name not in FEEDFORWARDS:
                raise InputError(f"feedforward must be one of {', '.join(FEEDFORWARDS)}, "
                                 f"got {ff_name!r}")
        for k in self.controllers:
            if k.lower() not in CONTROLLERS:
                raise InputError(f"controller must be one of {', '.join(CONTROLLERS)}, "
                                 f"got {k!r}")


def compare_strategies(
    plant: PlantParams,
    model_map: FrictionFn,
    *,
    targets_n: Sequence[float] = (54.4, 10.0, 150.0),
    steps_n: Sequence[tuple[float, float]] = (),
    true_map: FrictionFn | None = None,
    hysteresis_mpa: float = 0.0,
    plant_factory: Callable[[], PlantLike] | None = None,
    plant_label: str | None = None,
    options: StrategyOptions | None = None,
) -> StrategyTable:
    """Simulate {controllers} x {feedforwards} x {fixed, scheduled} on each scenario.

    Gains come from the IMC/SIMC rule (:func:`~exofric.control.rule_gains`) for the loop
    linearised at ``options.tune_target_n`` (slope of ``model_map`` there x plant gain, the
    plant's lag and dead time), and are the same for every feedforward, as in the paper's
    Fig 12. The scheduled variant scales them by slope_ref / max(dF/dP, floor) of the model map
    (:class:`ScheduledController`). Feedforwards: ``'model'`` inverts the model map over
    [0, p_max] (:func:`friction_inverse`), ``'hysteresis'`` uses
    :meth:`HysteresisInverse.from_play` with ``hysteresis_mpa`` (both 2-DOF with the plant's
    lag and delay, or static). The true friction is ``true_map`` (default the model), made
    hysteretic by a backlash of ``hysteresis_mpa`` MPa when > 0.

    Parameters
    ----------
    plant : PlantParams
        Lag, dead time, gain and supply of the tuning model and the 2-DOF feedforward; also
        the simulated plant unless ``plant_factory`` is given.
    model_map : callable
        Model friction F(P): MPa -> N, non-decreasing.
    targets_n : sequence of float
        Step targets from rest (N): one scenario each.
    steps_n : sequence of (float, float)
        (start, target) set-points in N: the loop settles at ``start`` for ``duration_s``,
        then steps to ``target`` (measured over the next ``duration_s``).
    true_map : callable or None
        True friction F(P) (N) of the simulated plant; default ``model_map``.
    hysteresis_mpa : float
        Backlash half-width of the true friction in MPa (0: none).
    plant_factory : callable or None
        Returns a fresh plant object (:class:`~exofric.control.PlantLike`) per run, e.g. a
        physical pneumatic plant; default a :class:`~exofric.control.PressurePlant` of
        ``plant``.
    plant_label : str or None
        Description of the plant for the table.
    options : StrategyOptions or None
        Which loops are built, how they are tuned and how the steps are judged (controllers,
        feedforwards, schedules, tuning target and rule, 2-DOF or static feedforward, time
        step, horizon, settling band); default :class:`StrategyOptions` ().

    Returns
    -------
    StrategyTable

    Examples
    --------
    >>> from exofric.control import PlantParams
    >>> opts = StrategyOptions(controllers=("pi",), duration_s=8.0)
    >>> t = compare_strategies(PlantParams(), lambda p: 400.0 * p, targets_n=(40.0,), options=opts)
    >>> r = t.get("up 40 N", "pi", "model", False)
    >>> r.settling_time_s is not None and abs(r.steady_state_error_n) < 0.8
    True
    """
    o = StrategyOptions() if options is None else options
    check_range("hysteresis_mpa", hysteresis_mpa, 0.0, 1.0, unit="MPa")
    feedforwards = (tuple(o.feedforwards) if o.feedforwards is not None
                    else FEEDFORWARDS if hysteresis_mpa > 0.0 else FEEDFORWARDS[:2])
    pmax = plant.p_max_mpa
    p_tune = friction_inverse(model_map, o.tune_target_n, p_max_mpa=pmax)
    slope_map = local_slope(model_map, p_tune)          # dF/dP, N/MPa
    slope_ref = slope_map * plant.gain                  # dF/du of the loop, N/MPa (command)
    if slope_ref <= 0.0:
        raise InputError(f"tune_target_n {o.tune_target_n:g} N is below the map's contact "
                         "onset (dF/dP = 0 there): tune where the map rises")
    scenarios = [(0.0, float(t)) for t in targets_n] + [(float(a), float(b)) for a, b in steps_n]
    if not scenarios:
        raise InputError("compare_strategies needs at least one target or step")
    true_fn = model_map if true_map is None else true_map
    run = _StrategyRun(plant, model_map, slope_map, slope_ref, o, hysteresis_mpa,
                       HystereticFrictionMap.from_play(true_fn, hysteresis_mpa)
                       if hysteresis_mpa > 0.0 else true_fn, plant_factory)
    rows = [run.row(start, target, kind.lower(), ff_name, bool(sched))
            for start, target in scenarios for kind in o.controllers
            for ff_name in feedforwards for sched in o.schedules]
    label = plant_label or (f"FOPDT tau {plant.time_constant_s:g} s, delay {plant.delay_s:g} s"
                            if plant_factory is None else "plant object")
    return StrategyTable(tuple(rows), label, float(o.tune_target_n), float(slope_ref),
                         float(hysteresis_mpa), float(o.band), float(o.dt), float(o.duration_s))


@dataclass(frozen=True)
class _StrategyRun:
    """One compare_strategies call: builds, simulates and measures each loop (one row)."""

    plant: PlantParams
    model_map: FrictionFn
    slope_map: float
    slope_ref: float
    o: StrategyOptions
    hysteresis_mpa: float
    true_fn: FrictionFn
    plant_factory: Callable[[], PlantLike] | None

    def model_inverse(self, f: float) -> float:
        return friction_inverse(self.model_map, f, p_max_mpa=self.plant.p_max_mpa)

    def feedforward(self, ff_name: str) -> ModelFeedforward | None:
        """The feedforward ``ff_name`` (None for ``'none'``), static or 2-DOF."""
        if ff_name == "none":
            return None
        pl, pmax = self.plant, self.plant.p_max_mpa
        if ff_name == "model":
            inv: Callable[[float], float] = self.model_inverse
            fwd: FrictionFn = self.model_map
        else:
            inv = HysteresisInverse.from_play(self.model_map, self.hysteresis_mpa,
                                              p_max_mpa=pmax)
            fwd = HystereticFrictionMap.from_play(self.model_map, self.hysteresis_mpa)
        if self.o.ff_mode == "static":
            return ModelFeedforward(inv, gain=pl.gain, p_max_mpa=pmax)
        return ModelFeedforward(inv, fwd, time_constant_s=pl.time_constant_s,
                                delay_s=pl.delay_s, gain=pl.gain, p_max_mpa=pmax)

    def controller(self, kind: str, ff_name: str, sched: bool) -> Controller:
        """The loop: rule gains at the tuning point, fixed or scheduled, with its feedforward."""
        pl = self.plant
        tuning = rule_gains(kind, self.slope_ref, pl.time_constant_s, pl.delay_s,
                            tau_c_s=self.o.tau_c_s)
        opts: dict[str, Any] = {"u_max": pl.p_max_mpa, "feedforward": self.feedforward(ff_name)}
        if not sched:
            return Controller(tuning.gains, **opts)
        return ScheduledController(tuning.gains, self.model_map,
                                   slope_ref_n_per_mpa=self.slope_map,
                                   floor_n_per_mpa=self.o.floor_n_per_mpa,
                                   schedule_on=self.o.schedule_on,
                                   operating_pressure=self.model_inverse, **opts)

    def row(self, start: float, target: float, kind: str, ff_name: str,
            sched: bool) -> StrategyRow:
        """Simulate one loop on one step and measure it (a row of the table)."""
        if start == target:
            raise InputError(f"step from {start:g} N to {target:g} N: no change")
        dur = self.o.duration_s
        if start == 0.0:
            sp: float | Callable[[Any], Any] = target
            horizon, t_step = dur, 0.0
        else:
            def sp(t: Any, a: float = start, b: float = target) -> Any:
                return np.where(t < dur, a, b)
            horizon, t_step = 2.0 * dur, dur
        ctrl = self.controller(kind, ff_name, sched)
        pl: PlantParams | PlantLike = (self.plant if self.plant_factory is None
                                       else self.plant_factory())
        sim = simulate(ctrl, pl, self.true_fn, sp, duration_s=horizon, dt=self.o.dt)
        sel = sim.time_s >= t_step - 1e-12
        met = step_metrics(sim.time_s[sel] - t_step, sim.friction_n[sel], target,
                           band=self.o.band)
        factor = ctrl.gain_factor if isinstance(ctrl, ScheduledController) else 1.0
        return StrategyRow(_label(start, target), start, target, kind, ff_name, sched,
                           float(factor), met.settling_time_s, met.overshoot_pct,
                           met.steady_state_error_n)
