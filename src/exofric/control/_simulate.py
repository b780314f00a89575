"""Closed-loop simulation of the friction control loop with a fixed sample time (Fig 12b).

Each sample k (time t_k = k dt): the friction sensor reads F_true(p_k) + noise, the
controller returns a pressure command u_k, held for dt (zero-order hold) while the pressure
supply (lag + dead time + saturation, optionally PWM valves) moves p_k -> p_{k+1}. The loop is
sequential by nature (feedback with saturation), so it runs sample by sample; the sensor
noise is drawn once, vectorised, from a seeded generator.

Units: time in s, friction in N, pressure and command in MPa.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.control._pid import Controller
from exofric.control._plant import FrictionFn, PlantParams, PressurePlant
from exofric.errors import InputError, check_range, check_series

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["PlantLike", "SimulationResult", "simulate", "setpoint_profile"]


@runtime_checkable
class PlantLike(Protocol):
    """Any pressure plant :func:`simulate` can drive (duck-typed).

    It has the tube pressure ``pressure_mpa`` (MPa) as an attribute and ``advance(command_mpa,
    dt)`` holding a pressure command (MPa) for ``dt`` s and returning the new pressure (MPa).
    :class:`~exofric.control.PressurePlant` (lag + dead time) satisfies it, as does any
    physical plant model with the same two members.

    Examples
    --------
    >>> from exofric.control import PlantParams, PressurePlant
    >>> isinstance(PressurePlant(PlantParams()), PlantLike)
    True
    """

    pressure_mpa: float

    def advance(self, command_mpa: float, dt: float) -> float:
        """Hold ``command_mpa`` (MPa) for ``dt`` s; return the tube pressure (MPa).

        Parameters
        ----------
        command_mpa : float
            Pressure command in MPa (zero-order hold over the step).
        dt : float
            Step length in s (> 0).

        Returns
        -------
        float
            Tube pressure in MPa at the end of the step.
        """
        ...


@checked_init
@dataclass(frozen=True)
class SimulationResult(DisplayMixin):
    """Sampled closed-loop trajectories (length n + 1, sample k at time k dt).

    Attributes
    ----------
    time_s : ndarray
        Sample times in s.
    setpoint_n : ndarray
        Friction set-point in N.
    friction_n : ndarray
        True (noise-free) friction in N.
    measured_n : ndarray
        Friction the controller saw (with sensor noise) in N.
    command_mpa : ndarray
        Controller output in MPa (held over the following sample; last value repeated).
    pressure_mpa : ndarray
        Tube pressure in MPa.
    dt_s : float
        Sample time in s.

    Examples
    --------
    >>> from exofric.control import Controller, PIDGains, PlantParams
    >>> sim = simulate(Controller(PIDGains(0.002, 0.003)), PlantParams(), lambda p: 200.0 * p,
    ...                40.0, duration_s=2.0, dt=0.01)
    >>> sim.time_s.size, sim.dt_s, float(sim.pressure_mpa[0]), float(sim.command_mpa[0])
    (201, 0.01, 0.0, 0.08)
    """

    time_s: NDArray[np.float64]
    setpoint_n: NDArray[np.float64]
    friction_n: NDArray[np.float64]
    measured_n: NDArray[np.float64]
    command_mpa: NDArray[np.float64]
    pressure_mpa: NDArray[np.float64]
    dt_s: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready trajectories (s, N, MPa)."""
        return {
            "time_s": self.time_s.tolist(),
            "setpoint_n": self.setpoint_n.tolist(),
            "friction_n": self.friction_n.tolist(),
            "measured_n": self.measured_n.tolist(),
            "command_mpa": self.command_mpa.tolist(),
            "pressure_mpa": self.pressure_mpa.tolist(),
            "dt_s": self.dt_s,
        }

    def to_frame(self) -> pd.DataFrame:
        """The trajectories as a DataFrame: one row per sample (s, N, MPa).

        Columns: ``time_s``, ``setpoint_n``, ``friction_n``, ``measured_friction_n``
        (with sensor noise), ``command_mpa`` and ``pressure_mpa``.

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> from exofric.control import Controller, PIDGains, PlantParams
        >>> sim = simulate(Controller(PIDGains(0.002, 0.01, 0.0), u_max=0.6), PlantParams(),
        ...                lambda p: 200.0 * p, 50.0, duration_s=1.0, dt=0.01)
        >>> df = sim.to_frame()
        >>> len(df), list(df.columns[:3])
        (101, ['time_s', 'setpoint_n', 'friction_n'])
        """
        import pandas as pd

        return pd.DataFrame({
            "time_s": self.time_s,
            "setpoint_n": self.setpoint_n,
            "friction_n": self.friction_n,
            "measured_friction_n": self.measured_n,
            "command_mpa": self.command_mpa,
            "pressure_mpa": self.pressure_mpa,
        })

    def plot(self, ax: Any | None = None) -> Any:
        """Draw the friction (N) and its set-point against time (s).

        Two lines (:func:`exofric.plots.plot_simulation`); write the figure with
        :func:`exofric.plots.save`.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (default a new figure).

        Returns
        -------
        matplotlib Axes

        Examples
        --------
        >>> from exofric.control import Controller, PIDGains, PlantParams
        >>> sim = simulate(Controller(PIDGains(0.002, 0.01, 0.0), u_max=0.6), PlantParams(),
        ...                lambda p: 200.0 * p, 50.0, duration_s=1.0, dt=0.01)
        >>> len(sim.plot().lines)
        2
        """
        from exofric.plots import plot_simulation

        return plot_simulation(self, ax)


def setpoint_profile(
    steps: list[tuple[float, float]],
) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
    """Piecewise-constant set-point from ``[(t_start_s, value_n), ...]`` (vectorised).

    Parameters
    ----------
    steps : list of (float, float)
        (start time in s, set-point in N) pairs, start times strictly increasing; before the
        first start time the first value holds.

    Returns
    -------
    callable
        ``f(t_s) -> setpoint_n``: array of times in s to array of set-points in N (as the
        ``setpoint_n`` of :func:`simulate`).

    Examples
    --------
    >>> import numpy as np
    >>> f = setpoint_profile([(0.0, 250.0), (5.0, 54.4)])
    >>> f(np.array([0.0, 4.99, 5.0])).tolist()
    [250.0, 250.0, 54.4]
    """
    if not steps:
        raise InputError("set-point profile needs at least one (time_s, value_n) step")
    times, vals = check_series("t_start_s", [s[0] for s in steps], "value_n",
                               [s[1] for s in steps], x_unit="s", y_unit="N", min_points=1,
                               where="set-point profile")

    def profile(t: NDArray[np.float64]) -> NDArray[np.float64]:
        idx = np.clip(np.searchsorted(times, t, side="right") - 1, 0, None)
        return vals[idx]

    return profile


def simulate(
    controller: Controller,
    plant: PlantParams | PlantLike,
    true_friction: FrictionFn,
    setpoint_n: float | Callable[[NDArray[np.float64]], NDArray[np.float64]],
    *,
    duration_s: float = 15.0,
    dt: float = 0.01,
    p0_mpa: float | None = None,
    noise_n: float | None = None,
    seed: int | None = None,
) -> SimulationResult:
    """Run the closed loop for ``duration_s`` s at sample time ``dt`` s.

    Parameters
    ----------
    controller : Controller
        Used as is (call ``controller.reset()`` first to start from rest). A controller with
        a true ``uses_pressure`` attribute (e.g. :class:`~exofric.control.ScheduledController`
        scheduled on the measured pressure) also gets the tube pressure (MPa) of each sample:
        ``step(setpoint, measurement, dt, pressure_mpa=p)``.
    plant : PlantParams or PlantLike
        Supply and sensor parameters (a :class:`~exofric.control.PressurePlant` is built from
        them; ``plant.noise_n`` and ``plant.seed`` set the noise), or any plant object with
        ``pressure_mpa`` (MPa) and ``advance(command_mpa, dt)`` (:class:`PlantLike`), used as
        is from its current pressure (no noise unless ``noise_n`` is given).
        ``plant.mismatch`` is *not* applied here: pass the true map in ``true_friction``.
    true_friction : callable
        The true friction map F(P): MPa -> N (scalar). It is called once per sample, in time
        order, so a stateful (hysteretic) map such as
        :class:`~exofric.control.HystereticFrictionMap` works.
    setpoint_n : float or callable
        Constant target in N, or a vectorised function of time (s) -> N.
    duration_s, dt : float
        Simulated time and sample time in s (dt also the PWM period when PWM is on).
    p0_mpa : float or None
        Initial tube pressure in MPa for a ``PlantParams`` plant (default 0 MPa); a plant
        object starts from its own ``pressure_mpa`` (giving ``p0_mpa`` then is an error).
    noise_n, seed : float or None, int or None
        Friction-sensor noise standard deviation in N and its seed; None takes them from a
        ``PlantParams`` plant (0 N and seed 0 for a plant object).

    Returns
    -------
    SimulationResult

    Examples
    --------
    >>> from exofric.control import Controller, PIDGains
    >>> c = Controller(PIDGains(kp=0.002, ki=0.003))
    >>> r = simulate(c, PlantParams(), lambda p: 200.0 * p, 40.0, duration_s=20.0)
    >>> round(float(r.friction_n[-1]), 2)
    40.0
    """
    check_range("duration_s", duration_s, 0.0, 1e5, lo_open=True, unit="s")
    check_range("dt (sample time)", dt, 1e-6, 10.0, unit="s")
    supply: PlantLike
    if isinstance(plant, PlantParams):
        if plant.pwm_period_s > 0.0 and not math.isclose(plant.pwm_period_s, dt, rel_tol=1e-9):
            raise InputError(
                f"pwm_period_s ({plant.pwm_period_s:g} s) must equal the sample time dt "
                f"({dt:g} s)"
            )
        supply = PressurePlant(plant, 0.0 if p0_mpa is None else p0_mpa)
        sigma = plant.noise_n if noise_n is None else noise_n
        rng_seed = plant.seed if seed is None else seed
    elif callable(getattr(plant, "advance", None)) and hasattr(plant, "pressure_mpa"):
        if p0_mpa is not None:
            raise InputError("p0_mpa applies to PlantParams only: a plant object starts from "
                             "its own pressure_mpa")
        supply = plant
        sigma = 0.0 if noise_n is None else noise_n
        rng_seed = 0 if seed is None else seed
    else:
        raise InputError("plant must be PlantParams or an object with pressure_mpa (MPa) and "
                         f"advance(command_mpa, dt), got {type(plant).__name__}")
    check_range("noise_n", sigma, 0.0, 1e4, unit="N")
    n = int(round(duration_s / dt))
    if n < 1:
        raise InputError(f"duration_s must be at least one sample time ({dt:g} s)")
    t = np.round(np.arange(n + 1, dtype=float) * dt, 12)   # 6.06, not 6.0600000000000005
    if callable(setpoint_n):
        r = np.asarray(setpoint_n(t), dtype=float)
        if r.shape != t.shape or not np.all(np.isfinite(r)):
            raise InputError("set-point function must return finite values (N), one per sample")
    else:
        sp = float(setpoint_n)
        if not math.isfinite(sp):
            raise InputError(f"setpoint_n must be a finite number in N, got {setpoint_n!r}")
        r = np.full(n + 1, sp)
    noise = (np.random.default_rng(rng_seed).normal(0.0, sigma, n + 1)
             if sigma > 0 else np.zeros(n + 1))
    p = np.empty(n + 1)
    f = np.empty(n + 1)
    u = np.empty(n + 1)
    p[0] = float(supply.pressure_mpa)
    rl, nl = r.tolist(), noise.tolist()
    step, advance = controller.step, supply.advance
    if getattr(controller, "uses_pressure", False):
        for k in range(n):
            fk = float(true_friction(p[k]))
            f[k] = fk
            u[k] = step(rl[k], fk + nl[k], dt, pressure_mpa=float(p[k]))  # type: ignore[call-arg]
            p[k + 1] = advance(u[k], dt)
    else:
        for k in range(n):
            fk = float(true_friction(p[k]))
            f[k] = fk
            u[k] = step(rl[k], fk + nl[k], dt)
            p[k + 1] = advance(u[k], dt)
    f[n] = float(true_friction(p[n]))
    u[n] = u[n - 1]
    return SimulationResult(t, r, f, f + noise, u, p, float(dt))
