"""Discrete PID/PI/PD controller (paper Eq 10) for friction force control, rig-ready.

The controller turns a friction error (N) into an inflation-pressure command (MPa):

    u = u_ff(r) + Kp e + Ki integral(e dt) - Kd dy_f/dt        (derivative on measurement)

with e = r - y, an optional feedforward u_ff = g^-1(r) / K from the inverse model (paper
Fig 12a "with the model"; static, or two-degree-of-freedom where the feedback acts on a model
reference that settles at r, see :class:`ModelFeedforward` and ``docs/control.md``), a
first-order filtered derivative, output limits and anti-windup (back-calculation, clamping or
none).

Use on a real rig
-----------------
* Units: ``setpoint`` and ``measurement`` in N (friction), returned command in MPa (pressure
  set-point for the regulator or the valve PWM stage); ``dt`` in s.
* Gains (parallel form of Eq 10): ``kp`` in MPa/N, ``ki`` in MPa/(N s), ``kd`` in MPa s/N.
* Sample time: call :meth:`Controller.step` once per sample with the *measured* elapsed time
  ``dt`` (jitter is handled: the integral and the derivative filter use the actual ``dt``).
  Choose dt at most about a tenth of the plant's dead time (default plant: 0.2 s -> dt <= 0.02 s;
  the simulations use 0.01 s). One call costs a few microseconds (see
  ``benchmarks/bench_control.py``), so 1 kHz loops are possible in plain Python.
* Limits: ``u_min``/``u_max`` (MPa) are the physical range of the supply (default 0..0.6 MPa);
  the returned command never leaves them.
* Start: :meth:`Controller.reset` with ``output`` = the command currently applied (manual mode)
  gives a bumpless transfer; the first call never produces a derivative kick.
* The controller is deterministic: the same calls give the same outputs (no clock, no
  randomness inside); it does no I/O.

Examples
--------
>>> c = Controller(PIDGains(kp=0.002, ki=0.004, kd=0.0), u_max=0.6)
>>> round(c.step(54.4, 0.0, 0.01), 6)       # first sample: proportional kick only
0.1088
>>> round(c.step(54.4, 0.0, 0.01), 6)       # + integral of the first error
0.110976
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

from exofric._validate import checked_init
from exofric.control._plant import PlantParams, PressurePlant
from exofric.errors import InputError, check_finite, check_range

__all__ = ["PIDGains", "Controller", "AntiWindup", "ModelFeedforward"]

#: The integrator's anti-windup when the command saturates: back-calculation (the default),
#: conditional integration (clamping), or none.
AntiWindup = Literal["back-calculation", "clamping", "none"]
_AW = ("back-calculation", "clamping", "none")


@checked_init
@dataclass(frozen=True)
class PIDGains:
    """Parallel PID gains of Eq 10 for a friction loop (error in N, command in MPa).

    Parameters
    ----------
    kp : float
        Proportional gain in MPa/N (>= 0).
    ki : float
        Integral gain in MPa/(N s) (>= 0); 0 for PD.
    kd : float
        Derivative gain in MPa s/N (>= 0); 0 for PI.

    Examples
    --------
    >>> PIDGains(0.002, 0.0025, 0.0).kind
    'pi'
    """

    kp: float
    ki: float = 0.0
    kd: float = 0.0

    def __post_init__(self) -> None:
        for name, unit in (("kp", "MPa/N"), ("ki", "MPa/(N s)"), ("kd", "MPa s/N")):
            check_range(name, getattr(self, name), 0.0, 1e6, unit=unit)

    @property
    def kind(self) -> str:
        """'pid', 'pi', 'pd', 'p', 'i', 'id' or 'off' from the non-zero gains."""
        s = ("p" if self.kp > 0 else "") + ("i" if self.ki > 0 else "") + (
            "d" if self.kd > 0 else "")
        return s or "off"

    @property
    def ti_s(self) -> float:
        """Integral time Ti = kp/ki in s (inf without integral action)."""
        return self.kp / self.ki if self.ki > 0 else math.inf

    @property
    def td_s(self) -> float:
        """Derivative time Td = kd/kp in s (0 without derivative; inf if kp = 0 < kd)."""
        if self.kd == 0:
            return 0.0
        return self.kd / self.kp if self.kp > 0 else math.inf

    def to_dict(self) -> dict[str, float]:
        """JSON-ready: ``kp_mpa_per_n``, ``ki_mpa_per_n_s``, ``kd_mpa_s_per_n``."""
        return {"kp_mpa_per_n": self.kp, "ki_mpa_per_n_s": self.ki, "kd_mpa_s_per_n": self.kd}


class ModelFeedforward:
    """Model feedforward u_ff = g^-1(r) / K, optionally two-degree-of-freedom (2-DOF).

    The feedforward inverts the whole model: the friction map g (N from MPa) and the static
    gain K of the pressure supply (MPa of tube pressure per MPa of command), so that
    u_ff = g^-1(r) / K is the command the model says holds the set-point r.

    *Static* (``time_constant_s=None``): u_ff is added to the command and the feedback acts on
    e = r - y (the plain "PID + model" of Fig 12a).

    *2-DOF* (time constant given): the feedback acts on e = r_m - y, with the model reference

        r_m(t) = r - [g(p_ss) - g(p_m(t))],

    where p_m is the pressure model (lag + dead time + saturation, gain K) driven by u_ff alone
    and p_ss = clip(K u_ff, 0, p_max) is where it settles. The bracket is the friction the model
    says is still to come; it decays to 0, so **r_m settles at the set-point r exactly**, by
    construction, whatever the errors of the model (plant gain, lag, dead time, gamma, the
    map's shape, saturation). With an exact model r_m = g(p_m) is the friction the plant
    produces and the feedback sees no error and does not fight the feedforward (Astrom &
    Hagglund 2006, Sec 5.2); with a wrong model the integral removes any constant offset,
    because in steady state the feedback error is r - y itself. (An earlier version used
    r_m = g(p_m): with an identified gain K = 0.968 it settled at g(K g^-1(r)), 8 % below r.)

    Parameters
    ----------
    pressure_for_friction : callable
        Inverse friction model P(F): N -> MPa (e.g. ``CubicFrictionMap.inverse``).
    friction_of_pressure : callable or None
        Forward model F(P): MPa -> N; required for 2-DOF. It is called once per sample, in
        time order, along the model pressure (a stateful hysteretic map works); a map with a
        ``settled(p)`` method (:class:`~exofric.control.HystereticFrictionMap`) gives g(p_ss)
        through it without changing its state, any other map is evaluated at p_ss once per
        set-point.
    time_constant_s, delay_s : float
        Pressure model (s, s); ``time_constant_s=None`` for static feedforward.
    gain : float
        Static gain K of the supply (MPa/MPa, > 0): the command is g^-1(r) / K.
    p_max_mpa : float
        Saturation of the pressure model in MPa.

    Examples
    --------
    >>> ff = ModelFeedforward(lambda f: f / 100.0, lambda p: 100.0 * p, time_constant_s=1.0)
    >>> ff.update(50.0, 0.1)        # (u_ff MPa, reference N): model at rest, all still to come
    (0.5, 0.0)
    >>> ModelFeedforward(lambda f: f / 100.0, gain=0.5).update(20.0, 0.01)   # 0.2 MPa / 0.5
    (0.4, 20.0)
    """

    def __init__(
        self,
        pressure_for_friction: Callable[[float], float],
        friction_of_pressure: Callable[[float], float] | None = None,
        *,
        time_constant_s: float | None = None,
        delay_s: float = 0.0,
        gain: float = 1.0,
        p_max_mpa: float = 0.6,
    ) -> None:
        self.pressure_for_friction = pressure_for_friction
        self.friction_of_pressure = friction_of_pressure
        self.gain = check_range("gain (supply, MPa/MPa)", gain, 0.0, 1e3, lo_open=True)
        self.p_max_mpa = check_range("p_max_mpa", p_max_mpa, 0.0, 100.0, lo_open=True,
                                     unit="MPa")
        self._model: PlantParams | None = None
        if time_constant_s is not None:
            if friction_of_pressure is None:
                raise InputError("2-DOF feedforward needs friction_of_pressure (the forward map)")
            self._model = PlantParams(gain=gain, time_constant_s=time_constant_s,
                                      delay_s=delay_s, p_max_mpa=p_max_mpa)
        self._r = math.nan
        self._u = 0.0
        self._p_ss = 0.0
        self._f_ss = math.nan
        self.reset()

    @property
    def two_dof(self) -> bool:
        """True when the feedback acts on the model reference r_m."""
        return self._model is not None

    def reset(self, command_mpa: float = 0.0) -> None:
        """Restart the pressure model at rest under a held command ``command_mpa`` (MPa).

        Parameters
        ----------
        command_mpa : float
            Command in MPa held so far; the model pressure starts at clip(gain x command, 0,
            p_max) MPa (no effect on static feedforward).

        Examples
        --------
        >>> ff = ModelFeedforward(lambda f: f / 100.0, lambda p: 100.0 * p, time_constant_s=1.0)
        >>> ff.reset(0.3)
        >>> ff.update(30.0, 0.1)        # model already at 0.3 MPa: nothing still to come
        (0.3, 30.0)
        """
        m = self._model
        self._plant = None if m is None else PressurePlant(
            m, min(max(m.gain * command_mpa, 0.0), m.p_max_mpa))
        self._r = math.nan

    def _settled_friction(self) -> float:
        """g(p_ss) in N: the friction the model settles at under the current u_ff."""
        fwd = self.friction_of_pressure
        assert fwd is not None
        settled = getattr(fwd, "settled", None)
        if callable(settled):               # stateful map: from its current state, pure
            return float(settled(self._p_ss))
        if math.isnan(self._f_ss):          # pure map: once per set-point
            self._f_ss = float(fwd(self._p_ss))
        return self._f_ss

    def update(self, setpoint: float, dt: float) -> tuple[float, float]:
        """Feedforward command (MPa) and the reference for the feedback (N) for this sample.

        The inverse model is evaluated only when the set-point changes; with 2-DOF the
        pressure model is then advanced by ``dt``.

        Parameters
        ----------
        setpoint : float
            Friction set-point r in N.
        dt : float
            Sample time in s (> 0).

        Returns
        -------
        (float, float)
            u_ff in MPa, and the feedback reference in N: r itself (static), or the model
            reference r_m = r - [g(p_ss) - g(p_m)] of this sample (2-DOF), which settles at r.

        Examples
        --------
        >>> ModelFeedforward(lambda f: f / 100.0).update(50.0, 0.01)    # static
        (0.5, 50.0)
        """
        if setpoint != self._r:
            p_ff = float(self.pressure_for_friction(setpoint))
            self._u = p_ff / self.gain
            self._r = setpoint
            self._p_ss = min(max(p_ff, 0.0), self.p_max_mpa)
            self._f_ss = math.nan
        if self._plant is None:
            return self._u, setpoint
        fwd = self.friction_of_pressure
        assert fwd is not None
        expected = float(fwd(self._plant.pressure_mpa))
        to_come = self._settled_friction() - expected
        self._plant.advance(self._u, dt)
        return self._u, setpoint - to_come


class Controller:
    """Discrete PID/PI/PD with filtered derivative, limits, anti-windup and feedforward.

    Parameters
    ----------
    gains : PIDGains
        kp (MPa/N), ki (MPa/(N s)), kd (MPa s/N).
    u_min, u_max : float
        Output limits in MPa (default 0..0.6 MPa).
    antiwindup : {'back-calculation', 'clamping', 'none'}
        Back-calculation (Astrom & Hagglund 2006, Sec 3.5): the integral is corrected by
        (u_sat - u)/Tt; clamping (conditional integration): the integral is frozen while the
        output is saturated and the error pushes further into saturation; 'none' for study.
    tracking_time_s : float or None
        Back-calculation tracking time Tt in s; default sqrt(Ti Td) for PID, Ti otherwise.
    derivative_filter_s : float or None
        Time constant Tf (s) of the first-order derivative filter; default Td/10.
    derivative_on : {'measurement', 'error'}
        Differentiate -y (no set-point kick, default) or e.
    feedforward : ModelFeedforward, callable or None
        Model feedforward; a bare callable ``pressure_for_friction(F_n) -> P_mpa`` means
        static feedforward. Evaluated when the set-point changes (cached) and added to the
        output; errors of the inverse (target outside its range) propagate.
    bias_mpa : float
        Constant added to the output in MPa (manual reset of a PD; default 0).

    Examples
    --------
    >>> c = Controller(PIDGains(0.002), feedforward=lambda f: 0.005 * f)
    >>> round(c.step(50.0, 50.0, 0.01), 6)   # zero error: the feedforward alone
    0.25
    """

    def __init__(
        self,
        gains: PIDGains,
        *,
        u_min: float = 0.0,
        u_max: float = 0.6,
        antiwindup: AntiWindup = "back-calculation",
        tracking_time_s: float | None = None,
        derivative_filter_s: float | None = None,
        derivative_on: Literal["measurement", "error"] = "measurement",
        feedforward: ModelFeedforward | Callable[[float], float] | None = None,
        bias_mpa: float = 0.0,
    ) -> None:
        self.gains = gains
        lo = check_finite("u_min (MPa)", u_min)
        hi = check_finite("u_max (MPa)", u_max)
        if not lo < hi:
            raise InputError(f"output limits must have u_min < u_max MPa, got [{lo:g}, {hi:g}]")
        if antiwindup not in _AW:
            raise InputError(f"antiwindup must be one of {', '.join(_AW)}, got {antiwindup!r}")
        if derivative_on not in ("measurement", "error"):
            raise InputError(f"derivative_on must be measurement or error, got {derivative_on!r}")
        self.u_min, self.u_max = lo, hi
        self.antiwindup: str = antiwindup
        self.derivative_on: str = derivative_on
        if feedforward is not None and not isinstance(feedforward, ModelFeedforward):
            feedforward = ModelFeedforward(feedforward)
        self.feedforward: ModelFeedforward | None = feedforward
        self._bias0 = check_finite("bias_mpa", bias_mpa)
        self.bias_mpa = self._bias0
        if tracking_time_s is None:
            tt = math.sqrt(gains.ti_s * gains.td_s) if gains.kd > 0 else gains.ti_s
            if gains.ki > 0 and antiwindup == "back-calculation" and not math.isfinite(tt):
                raise InputError("tracking_time_s is required for back-calculation when kp = 0")
            self.tracking_time_s = tt
        else:
            self.tracking_time_s = check_range("tracking_time_s", tracking_time_s, 1e-9, 1e6,
                                               unit="s")
        if derivative_filter_s is None:
            td = gains.td_s
            self.derivative_filter_s = td / 10.0 if math.isfinite(td) else 0.0
        else:
            self.derivative_filter_s = check_range("derivative_filter_s", derivative_filter_s,
                                                   0.0, 1e6, unit="s")
        self.reset()

    def reset(self, output: float | None = None) -> None:
        """Clear the state; with ``output`` (MPa) the next call returns it (bumpless start).

        With integral action the integral absorbs the difference; without it (PD) the bias
        does (the PD's manual reset).

        Parameters
        ----------
        output : float or None
            The command in MPa currently applied (e.g. in manual mode), returned by the next
            :meth:`step`; None to start from a zero state.

        Examples
        --------
        >>> c = Controller(PIDGains(kp=0.002, ki=0.004))
        >>> c.reset(output=0.3)
        >>> round(c.step(54.4, 50.0, 0.01), 6)      # bumpless: the held 0.3 MPa
        0.3
        """
        self.integral_mpa = 0.0
        self.derivative_mpa = 0.0
        self.bias_mpa = self._bias0
        self._y_prev = 0.0
        self._e_prev = 0.0
        self._first = True
        self._u_ff = 0.0
        self._start_output = None if output is None else check_finite("output (MPa)", output)
        if self.feedforward is not None:
            self.feedforward.reset(0.0 if output is None else output)

    def step(self, setpoint: float, measurement: float, dt: float) -> float:
        """One control sample: friction set-point and measurement (N), dt (s) -> command (MPa).

        Parameters
        ----------
        setpoint : float
            Friction set-point r in N.
        measurement : float
            Measured friction y in N.
        dt : float
            Time since the previous call in s (> 0; the measured elapsed time).

        Returns
        -------
        float
            Pressure command in MPa, within [u_min, u_max].

        Raises
        ------
        InputError
            Non-finite set-point/measurement or dt <= 0.

        Examples
        --------
        >>> c = Controller(PIDGains(kp=0.002), u_max=0.6)
        >>> round(c.step(54.4, 4.4, 0.01), 6)      # 0.002 MPa/N x 50 N
        0.1
        >>> c.step(1000.0, 0.0, 0.01)             # saturated at u_max
        0.6
        """
        if not (math.isfinite(setpoint) and math.isfinite(measurement)):
            raise InputError(f"setpoint and measurement must be finite (N), got {setpoint}, "
                             f"{measurement}")
        if not (dt > 0.0 and math.isfinite(dt)):
            raise InputError(f"dt (sample time) must be > 0 s, got {dt}")
        g = self.gains
        if self.feedforward is None:
            u_ff, ref = 0.0, setpoint
        else:
            u_ff, ref = self.feedforward.update(setpoint, dt)
            self._u_ff = u_ff
        e = ref - measurement
        # Derivative "on measurement" differentiates -(y - r_m): r_m is the 2-DOF model
        # reference (smooth, no kick), or 0 without it (plain -y).
        y_d = measurement - ref if (self.feedforward is not None
                                    and self.feedforward.two_dof) else measurement
        if self._first:
            self._y_prev, self._e_prev = y_d, e
        p_term = g.kp * e
        if g.kd > 0.0:
            tf = self.derivative_filter_s
            if self.derivative_on == "measurement":
                delta = -(y_d - self._y_prev)
            else:
                delta = e - self._e_prev
            self.derivative_mpa = (tf * self.derivative_mpa + g.kd * delta) / (tf + dt)
        if self._first:
            self._first = False
            if self._start_output is not None:
                rest = self._start_output - u_ff - p_term - self.derivative_mpa
                if g.ki > 0.0:
                    self.integral_mpa = rest - self.bias_mpa
                else:
                    self.bias_mpa = rest
        v = u_ff + self.bias_mpa + p_term + self.integral_mpa + self.derivative_mpa
        u = self.u_max if v > self.u_max else (self.u_min if v < self.u_min else v)
        if g.ki > 0.0:
            aw = self.antiwindup
            if aw == "back-calculation":
                self.integral_mpa += g.ki * e * dt + (dt / self.tracking_time_s) * (u - v)
            elif aw == "clamping":
                if u == v or (e > 0.0) != (v > u):
                    self.integral_mpa += g.ki * e * dt
            else:
                self.integral_mpa += g.ki * e * dt
        self._y_prev, self._e_prev = y_d, e
        return u

    def state(self) -> dict[str, Any]:
        """Internal state for logging: integral and derivative terms (MPa), feedforward."""
        return {"integral_mpa": self.integral_mpa, "derivative_mpa": self.derivative_mpa,
                "feedforward_mpa": self._u_ff, "bias_mpa": self.bias_mpa}
