"""Plant models for friction force control: pneumatic pressure supply and friction map.

The plant of paper §5 (Fig 12b) is a pressure supply feeding the air tube, followed by the
static friction map F = g(P) (Eq 11). Here:

* :class:`PlantParams` -- first-order lag with dead time from the pressure command (MPa) to the
  tube pressure (MPa), saturation 0..``p_max_mpa``, optional on/off valves driven by PWM,
  optional friction-sensor noise (N) and a model mismatch on the friction map.
* :class:`PressurePlant` -- a stepping simulator of that supply (exact for piecewise-constant
  inputs, fractional delays included), usable as a virtual rig.
* :class:`CubicFrictionMap` / :class:`CurveFrictionMap` -- F(P) in N for P in MPa from the
  Eq 9 cubic or from an FE squeeze curve, physically clipped to F >= 0 and defined on
  0..any pressure, with their inverses P(F) for the model feedforward;
  :meth:`CurveFrictionMap.from_law` builds the map of any
  :class:`~exofric.friction.FrictionLaw` (gamma, interfaces, ...) on FE curves.

Units: pressure and pressure command in MPa, friction in N, time in s.

Examples
--------
>>> plant = PressurePlant(PlantParams(time_constant_s=1.0, delay_s=0.0))
>>> round(plant.advance(0.4, 1.0), 4)     # 0.4 MPa step, after one time constant
0.2528
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, fields
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric._validate import checked_init
from exofric.errors import InputError, check_finite, check_positive, check_range
from exofric.friction import (
    CubicFit,
    FrictionLaw,
    FrictionModel,
    SqueezeCurve,
    law_columns,
    pressure_for_friction,
)

__all__ = [
    "PlantParams",
    "PressurePlant",
    "CubicFrictionMap",
    "CurveFrictionMap",
    "local_slope",
]

#: A friction map: pressure in MPa -> friction in N (scalar in, scalar out).
FrictionFn = Callable[[float], float]


@checked_init
@dataclass(frozen=True)
class PlantParams:
    """Pneumatic supply and sensor parameters (defaults: a small pneumatic supply).

    The defaults are assumptions, not measurements (the paper prints no plant parameters):
    see ``docs/paper-notes.md`` for the reasoning.

    Parameters
    ----------
    gain : float
        Static gain from pressure command to tube pressure (MPa/MPa); 1 for a pressure
        regulator whose command is the target pressure.
    time_constant_s : float
        Lag time constant tau in s (filling the tube and hose through the valve orifice,
        including the sensor filtering). Default 0.8 s.
    delay_s : float
        Dead time theta in s (valve switching, transport in the hose, acquisition). Default 0.2 s.
    p_max_mpa : float
        Supply pressure in MPa: the tube pressure is saturated to [0, p_max]. Default 0.6 MPa,
        the top of the paper's tested range (Eq 8 is fitted on 0.2-0.6 MPa).
    pwm_period_s : float
        0 for a proportional valve (default). > 0: two on/off (3/2) valves, inflate to
        ``p_max_mpa`` or exhaust to 0, driven by PWM with duty = gain * command / p_max; the
        PWM period is the controller's sample time (this value must equal it).
    noise_n : float
        Standard deviation of the friction sensor noise in N (default 0: noise-free).
    seed : int
        Seed of the sensor-noise generator (reproducible runs).
    mismatch : float
        Relative model mismatch: the true plant's gamma is (1 + mismatch) times the model's,
        so the true friction map is (1 + mismatch) g(P). In (-0.9, 10).

    Examples
    --------
    >>> PlantParams().to_dict()["time_constant_s"]
    0.8
    """

    gain: float = 1.0
    time_constant_s: float = 0.8
    delay_s: float = 0.2
    p_max_mpa: float = 0.6
    pwm_period_s: float = 0.0
    noise_n: float = 0.0
    seed: int = 0
    mismatch: float = 0.0

    def __post_init__(self) -> None:
        check_positive("gain (MPa/MPa)", self.gain)
        check_range("time_constant_s", self.time_constant_s, 1e-4, 1e4, unit="s")
        check_range("delay_s", self.delay_s, 0.0, 1e3, unit="s")
        check_range("p_max_mpa", self.p_max_mpa, 1e-3, 10.0, unit="MPa")
        check_range("pwm_period_s", self.pwm_period_s, 0.0, 10.0, unit="s")
        check_range("noise_n", self.noise_n, 0.0, 1e4, unit="N")
        check_range("mismatch", self.mismatch, -0.9, 10.0, lo_open=True, hi_open=True)
        if isinstance(self.seed, bool) or not isinstance(self.seed, int | np.integer):
            raise InputError(f"seed must be an integer, got {self.seed!r}")

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any]) -> PlantParams:
        """Build from a dict (e.g. the ``[plant]`` table of a plant TOML file).

        Unknown keys raise :class:`InputError` naming them and the known keys.

        Parameters
        ----------
        data : mapping
            Field name -> value, keys as the fields (``time_constant_s`` in s,
            ``p_max_mpa`` in MPa, ...); missing keys take their defaults.

        Returns
        -------
        PlantParams

        Examples
        --------
        >>> PlantParams.from_mapping({"time_constant_s": 0.5, "delay_s": 0.1}).delay_s
        0.1
        """
        known = {f.name for f in fields(cls)}
        extra = sorted(set(data) - known)
        if extra:
            raise InputError(
                f"unknown plant key(s) {', '.join(extra)}; known: {', '.join(sorted(known))}"
            )
        return cls(**dict(data))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict with unit-suffixed keys (MPa, s, N; gain in MPa/MPa)."""
        return asdict(self)


class PressurePlant:
    """Tube pressure dynamics: first-order lag + dead time + saturation (+ PWM valves).

    ``tau dp/dt = clip(gain * u(t - theta), 0, p_max) - p``, integrated exactly for
    piecewise-constant inputs (zero-order hold), fractional delays included. With PWM
    (``pwm_period_s > 0``) the valve input is ``p_max`` for ``duty * dt`` then 0 for the rest
    of each sample, duty = clip(gain * u / p_max, 0, 1).

    Parameters
    ----------
    params : PlantParams
        Supply parameters (only the pressure part is used here).
    p0_mpa : float
        Initial pressure in MPa (in equilibrium with a held command p0 / gain).

    Examples
    --------
    >>> pl = PressurePlant(PlantParams(time_constant_s=0.5, delay_s=0.1))
    >>> [round(pl.advance(0.3, 0.05), 4) for _ in range(3)]  # 0.3 (1 - e^-0.1) after the delay
    [0.0, 0.0, 0.0285]
    """

    def __init__(self, params: PlantParams, p0_mpa: float = 0.0) -> None:
        self.params = params
        p0 = check_range("p0_mpa", p0_mpa, 0.0, params.p_max_mpa, unit="MPa")
        self.pressure_mpa = p0
        self.time_s = 0.0
        # Valve-input segments (start time s, valve target MPa); the first covers the past.
        self._segments: deque[tuple[float, float]] = deque([(-math.inf, p0)])

    def _valve_target(self, command_mpa: float) -> float:
        p = self.params
        return min(max(p.gain * command_mpa, 0.0), p.p_max_mpa)

    def advance(self, command_mpa: float, dt: float) -> float:
        """Hold ``command_mpa`` (MPa) for ``dt`` s; return the tube pressure (MPa) at the end.

        NaN commands raise :class:`InputError`; the command is saturated physically.

        Parameters
        ----------
        command_mpa : float
            Pressure command in MPa, held constant over the step (zero-order hold); the valve
            input is clip(gain x command, 0, p_max).
        dt : float
            Step length in s (> 0).

        Returns
        -------
        float
            Tube pressure in MPa at the end of the step.

        Examples
        --------
        >>> pl = PressurePlant(PlantParams(time_constant_s=1.0, delay_s=0.0))
        >>> round(pl.advance(5.0, 1.0), 4)          # saturated at p_max = 0.6 MPa
        0.3793
        """
        if not math.isfinite(command_mpa):
            raise InputError(f"pressure command must be a finite number in MPa, got {command_mpa}")
        if not (dt > 0.0 and math.isfinite(dt)):
            raise InputError(f"dt (sample time) must be > 0 s, got {dt}")
        prm = self.params
        t0, t1 = self.time_s, self.time_s + dt
        target = self._valve_target(command_mpa)
        segs = self._segments
        if prm.pwm_period_s > 0.0:
            duty = target / prm.p_max_mpa
            segs.append((t0, prm.p_max_mpa))
            segs.append((t0 + duty * dt, 0.0))
        else:
            segs.append((t0, target))
        # Integrate over the delayed input on [t0 - theta, t1 - theta].
        lo, hi = t0 - prm.delay_s, t1 - prm.delay_s
        while len(segs) > 1 and segs[1][0] <= lo:
            segs.popleft()
        p = self.pressure_mpa
        tau = prm.time_constant_s
        s = lo
        n = len(segs)
        for i in range(n):
            start, value = segs[i]
            end = segs[i + 1][0] if i + 1 < n else math.inf
            if end <= s:
                continue
            if start >= hi:
                break
            h = min(end, hi) - s
            if h > 0.0:
                p = value + (p - value) * math.exp(-h / tau)
                s += h
        self.pressure_mpa = p
        self.time_s = t1
        return p


def _as_array(p: ArrayLike) -> tuple[NDArray[np.float64], bool]:
    arr = np.asarray(p, dtype=float)
    return arr, arr.ndim == 0


@checked_init
@dataclass(frozen=True)
class CubicFrictionMap:
    """Friction F(P) = scale * gamma * N(P) from a cubic N(P) (Eq 9), clipped to F >= 0.

    Behaviour over 0..any P (documented extension of the fit):

    * inside [p_min, p_max] of the fit: the cubic;
    * below p_min: the cubic continued down to its root (contact onset; about 0.144 MPa for
      Eq 8), and 0 below it (no contact, no friction) -- F = max(0, gamma N(P));
    * above p_max: straight line with the end slope (monotone).

    Parameters
    ----------
    cubic : CubicFit
        Squeezing force N(P) in N, P in MPa (e.g. Eq 8 on 0.2-0.6 MPa).
    gamma : float
        Equivalent coefficient (unitless; the paper's 0.7168).
    scale : float
        Multiplies the map (the true plant: 1 + mismatch).

    Examples
    --------
    >>> from exofric import paper
    >>> from exofric.friction import CubicFit
    >>> g = CubicFrictionMap(CubicFit(paper.eq8(), 0.2, 0.6), 0.7168)
    >>> round(g(0.3), 2), g(0.1), round(g.inverse(g(0.3)), 6)
    (57.89, 0.0, 0.3)
    """

    cubic: CubicFit
    gamma: float
    scale: float = 1.0

    def __post_init__(self) -> None:
        check_positive("gamma (equivalent coefficient)", self.gamma)
        check_positive("friction map scale", self.scale)

    def __call__(self, pressure_mpa: Any) -> Any:
        """Friction in N at pressure(s) in MPa (float in, float out; array in, array out)."""
        k = self.scale * self.gamma
        c3, c2, c1, c0 = self.cubic.coefficients
        hi = self.cubic.p_max_mpa
        if isinstance(pressure_mpa, float | int):
            x = float(pressure_mpa)
            if x > hi:
                n = ((c3 * hi + c2) * hi + c1) * hi + c0 + (x - hi) * ((3 * c3 * hi + 2 * c2) * hi
                                                                        + c1)
            else:
                n = ((c3 * x + c2) * x + c1) * x + c0
            return k * n if n > 0.0 else 0.0
        x_arr, _ = _as_array(pressure_mpa)
        inside = np.polyval(self.cubic.coefficients, np.minimum(x_arr, hi))
        slope = float(self.cubic.derivative(hi))
        n_arr = inside + np.maximum(x_arr - hi, 0.0) * slope
        return k * np.maximum(n_arr, 0.0)

    def inverse(self, friction_n: float) -> float:
        """Pressure (MPa) inside the fit range giving friction ``friction_n`` (N).

        Raises :class:`InputError` outside the friction range covered by the fit.

        Parameters
        ----------
        friction_n : float
            Target friction in N, reachable over the cubic's fitted pressure range.

        Returns
        -------
        float
            Pressure in MPa.

        Examples
        --------
        >>> from exofric.friction import CubicFit
        >>> g = CubicFrictionMap(CubicFit((0.0, 0.0, 100.0, 0.0), 0.2, 0.6), 0.5)
        >>> round(g.inverse(15.0), 12)
        0.3
        """
        return pressure_for_friction(friction_n, self.cubic, FrictionModel(self.gamma * self.scale))

    def scaled(self, factor: float) -> CubicFrictionMap:
        """The same map multiplied by ``factor`` (true plant = model x (1 + mismatch)).

        Parameters
        ----------
        factor : float
            Multiplier (> 0, unitless), e.g. 1 + mismatch.

        Returns
        -------
        CubicFrictionMap

        Examples
        --------
        >>> from exofric.friction import CubicFit
        >>> g = CubicFrictionMap(CubicFit((0.0, 0.0, 100.0, 0.0), 0.2, 0.6), 0.5)
        >>> round(g.scaled(1.2)(0.4), 9)
        24.0
        """
        return CubicFrictionMap(self.cubic, self.gamma, self.scale * factor)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description (cubic in N vs MPa, gamma, scale)."""
        return {"kind": "cubic", "cubic": self.cubic.to_dict(), "gamma": self.gamma,
                "scale": self.scale}


@checked_init
@dataclass(frozen=True)
class CurveFrictionMap:
    """Friction F(P) = scale * gamma * N(P) from a tabulated (FE) squeeze curve N(P).

    N(P) is the :class:`~exofric.friction.SqueezeCurve` interpolant (monotone PCHIP) between
    the given points. Below the first pressure: straight line to (0 MPa, 0 N) (no pressure,
    no squeeze) if that point has N > 0, else 0. Above the last pressure: straight line with
    the interpolant's end slope dN/dP (C1 at the last point, as :class:`CubicFrictionMap`).
    F is clipped to >= 0. The inverse covers the given points only: it is the exact inverse
    of the same interpolant (:meth:`~exofric.friction.SqueezeCurve.pressure_for_friction`), so
    ``g(g.inverse(F)) == F`` to round-off.

    Parameters
    ----------
    pressure_mpa, squeeze_force_n : tuple of float
        The curve (MPa, N): finite, >= 0, pressures strictly increasing (a
        :class:`~exofric.friction.SqueezeCurve`).
    gamma : float
        Equivalent coefficient (unitless).
    scale : float
        Multiplies the map (true plant: 1 + mismatch).

    Examples
    --------
    >>> g = CurveFrictionMap((0.2, 0.4, 0.6), (20.0, 120.0, 280.0), 0.5)
    >>> round(g(0.4), 6), round(g.inverse(60.0), 6)
    (60.0, 0.4)
    """

    pressure_mpa: tuple[float, ...]
    squeeze_force_n: tuple[float, ...]
    gamma: float
    scale: float = 1.0

    def __post_init__(self) -> None:
        check_positive("gamma (equivalent coefficient)", self.gamma)
        check_positive("friction map scale", self.scale)
        _ = self._curve            # validate the nodes now: InputError at construction

    @cached_property
    def _curve(self) -> SqueezeCurve:
        """The nodes as a :class:`~exofric.friction.SqueezeCurve` (its PCHIP and inverse)."""
        return SqueezeCurve(self.pressure_mpa, self.squeeze_force_n)

    @cached_property
    def _slope(self) -> float:
        """dN/dP at the last node (N/MPa): the slope of the linear extension above it."""
        return float(self._curve.slope(self._curve.pressure_range_mpa[1]))

    def __call__(self, pressure_mpa: Any) -> Any:
        """Friction in N at pressure(s) in MPa (float in, float out; array in, array out)."""
        curve = self._curve
        x, scalar = _as_array(pressure_mpa)
        lo, hi = curve.pressure_range_mpa
        inside = curve(np.clip(x, lo, hi))
        n = inside + np.maximum(x - hi, 0.0) * self._slope
        if lo > 0.0:
            n = np.where(x < lo, curve.squeeze_force_n[0] * np.clip(x, 0.0, None) / lo, n)
        f = self.scale * self.gamma * np.maximum(n, 0.0)
        return float(f) if scalar else f

    def inverse(self, friction_n: float) -> float:
        """Pressure (MPa) on the curve giving friction ``friction_n`` (N); InputError outside.

        Parameters
        ----------
        friction_n : float
            Target friction in N, inside the range the given points reach.

        Returns
        -------
        float
            Pressure in MPa.

        Examples
        --------
        >>> g = CurveFrictionMap((0.2, 0.4), (20.0, 60.0), 0.5)
        >>> round(g.inverse(20.0), 12)
        0.3
        """
        return self._curve.pressure_for_friction(friction_n, FrictionModel(self.gamma * self.scale))

    @classmethod
    def from_law(cls, law: FrictionLaw, curves: Any, scale: float = 1.0) -> CurveFrictionMap:
        """The map of any friction law on a structure's FE curves: F(P) = scale x law(P).

        The law's friction at the curves' nodes (N) becomes the tabulated curve, with
        ``gamma`` = 1 (``squeeze_force_n`` of the map then holds F, in N): its PCHIP between
        the nodes, the extensions outside them and the exact inverse are this class's.

        Parameters
        ----------
        law : FrictionLaw
            The law (:class:`~exofric.friction.FrictionModel`,
            :class:`~exofric.friction.InterfaceFrictionModel` or any other).
        curves : object or mapping
            ``pressure_mpa`` (MPa) and the law's inputs (N) at the nodes, e.g. a
            :class:`~exofric.friction.SqueezeCurve` or
            :class:`~exofric.friction.InterfaceCurves`.
        scale : float
            Multiplies the map (true plant: 1 + mismatch).

        Returns
        -------
        CurveFrictionMap

        Raises
        ------
        InputError
            A curve the law needs is missing, or the friction at the nodes is not a valid
            curve (negative, or falling with pressure).

        Examples
        --------
        >>> from exofric.friction import FrictionModel, SqueezeCurve
        >>> g = CurveFrictionMap.from_law(FrictionModel(0.5), SqueezeCurve((0.2, 0.4, 0.6),
        ...                                                                (20.0, 120.0, 280.0)))
        >>> round(g(0.4), 6), round(g.inverse(60.0), 6)
        (60.0, 0.4)
        """
        cols = law_columns(law, curves)
        friction = np.asarray(law.friction_of(cols), dtype=float)
        return cls(tuple(cols["pressure_mpa"].tolist()), tuple(friction.tolist()), 1.0, scale)

    def scaled(self, factor: float) -> CurveFrictionMap:
        """The same map multiplied by ``factor``.

        Parameters
        ----------
        factor : float
            Multiplier (> 0, unitless), e.g. 1 + mismatch.

        Returns
        -------
        CurveFrictionMap

        Examples
        --------
        >>> CurveFrictionMap((0.2, 0.4), (20.0, 60.0), 0.5).scaled(2.0)(0.4)
        60.0
        """
        return CurveFrictionMap(self.pressure_mpa, self.squeeze_force_n, self.gamma,
                                self.scale * factor)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description (curve in MPa and N, gamma, scale)."""
        return {"kind": "curve", "pressure_mpa": list(self.pressure_mpa),
                "squeeze_force_n": list(self.squeeze_force_n), "gamma": self.gamma,
                "scale": self.scale}


def local_slope(friction_of_pressure: FrictionFn, pressure_mpa: float, h: float = 1e-4) -> float:
    """dF/dP in N/MPa at ``pressure_mpa`` by a central difference (step ``h`` MPa).

    Parameters
    ----------
    friction_of_pressure : callable
        Friction map F(P): pressure in MPa -> friction in N.
    pressure_mpa : float
        Operating pressure in MPa.
    h : float
        Difference step in MPa; the lower point is clipped at 0 MPa (one-sided there).

    Returns
    -------
    float
        Slope in N/MPa.

    Examples
    --------
    >>> round(local_slope(lambda p: 100.0 * p**2, 0.3), 6)
    60.0
    """
    p = check_finite("pressure_mpa", pressure_mpa)
    lo = max(p - h, 0.0)
    return float((friction_of_pressure(p + h) - friction_of_pressure(lo)) / (p + h - lo))
