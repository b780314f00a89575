"""The knee lock through a gait cycle: walking data in, pneumatic dynamics, controllers.

The paper controls a friction force to a constant target (Fig 12: settling in 4.2-5.7 s). A
knee exosuit works within a stride of about 1.1 s; :func:`simulate_gait` asks whether the
friction lock can deliver a torque profile stride after stride, with which controller.

**The joint.** The knee angle theta (rad, flexion positive; from walking data, repeated stride
after stride and time-scaled to the cadence) drives the wire through the pulley radius R
(wire travel R theta). The lock is a controllable brake: its friction capacity at the block
is F(P) (the friction map), at the joint T_cap = c F(P) R with the capstan factor c of the
wrap (``locking`` while the knee flexes and pulls the wire, ``buffering`` while it extends:
:func:`~exofric.friction.capstan_factor`). The kinematics are prescribed (the wearer walks as
in the data; the lock changes the muscles' moment, not the motion), so the lock *slides*
whenever the knee moves and its torque is -sign(d theta) T_cap: it only resists motion
(power <= 0). When the knee does not move over a sample it *sticks* and carries the demand up
to the static capacity (``static_ratio`` = mu_static / mu_kinetic) x T_cap; until the
pull-out stiffness K(P) is used, it is rigid below breakaway.

**The demand.** T_d = ``assist`` x the biological knee moment where a brake can deliver it:
by default the loading-response window of early stance, where the knee flexes under an
extension moment and absorbs energy (Winter's K1 phase): from the first sample of the stride
at which the moment is extensor while the knee flexes to the stance flexion peak, zero
elsewhere (in particular in swing). There the quadriceps work eccentrically and an assisting
brake relieves them; at the flexion peak the knee starts extending under the same extension
moment (positive work), which a brake cannot supply: it must release. A ``window`` (fractions
of the stride) widens or moves it, still only where the moment resists the motion.

**The loop.** The plant is any pressure plant (:class:`~exofric.control.PneumaticPlant` by
default: ISO 6358 valve ports, line and tube volumes), the sensor reports the delivered
friction and the pressure ``sensor_delay_s`` late, and each controller is stepped once per
sample ``dt_s`` (fixed step) -- the same :class:`~exofric.control.Controller` code that
``exofric control run`` steps on the hardware (:mod:`exofric.control._gait_controllers`).

Units: time s, angle rad (deg in tables), torque Nm, friction N, pressure MPa, air normal
litres (NL: ISO 8778 reference atmosphere), energy J.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from exofric._display import DisplayMixin, HtmlReprMixin
from exofric._validate import checked_init
from exofric.control._gait_controllers import (
    IterativeLearning,
    PlantModel,
    PressureMPC,
    PreviewFeedforward,
)
from exofric.control._pid import Controller, ModelFeedforward, PIDGains
from exofric.control._plant import local_slope
from exofric.control._pneumatic import (
    R_AIR_J_PER_KG_K,
    RHO0_KG_PER_M3,
    PneumaticParams,
    PneumaticPlant,
)
from exofric.control._schedule import ScheduledController, friction_inverse
from exofric.control._simulate import PlantLike
from exofric.control._tuning import rule_gains
from exofric.errors import InputError, PlausibilityWarning, check_range

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "GAIT_CONTROLLERS",
    "GaitComparison",
    "GaitLike",
    "GaitResult",
    "GaitSetup",
    "GaitSizing",
    "StrideMetrics",
    "compare_gait",
    "identify_model",
    "simulate_gait",
    "size_valve",
]

#: Controllers of :func:`simulate_gait`.
GAIT_CONTROLLERS = ("pid", "ff", "preview", "ilc", "mpc")
#: Allowed cadence (stride frequency) in Hz.
CADENCE_RANGE_HZ = (0.3, 2.0)
#: Stride closure beyond which data are not one periodic stride: angle (deg), moment (share of
#: the moment's range).
PERIODIC_ANGLE_DEG = 5.0
PERIODIC_MOMENT_SHARE = 0.1
#: Latency threshold: share of the peak demand at which the lock counts as engaged/released.
LATENCY_LEVEL = 0.1
#: Strides after which the summary reports the metrics.
SUMMARY_STRIDES = (1, 5, 10)
FrictionFn = Callable[[float], float]


@runtime_checkable
class GaitLike(Protocol):
    """Walking data as the gait simulation reads it (e.g. :class:`exofric.io.GaitData`).

    ``stance_fraction`` (unitless) is used when present.

    Attributes
    ----------
    time_s : numpy.ndarray
        Sample times of one stride (s), increasing.
    knee_angle_rad : numpy.ndarray
        Knee flexion (rad, flexion positive).
    knee_moment_nm : numpy.ndarray
        Net knee moment (Nm, flexion positive).

    Examples
    --------
    >>> from exofric.io import gait_data_path, read_gait
    >>> isinstance(read_gait(gait_data_path()), GaitLike)
    True
    """

    time_s: NDArray[np.float64]
    knee_angle_rad: NDArray[np.float64]
    knee_moment_nm: NDArray[np.float64]


@checked_init
@dataclass(frozen=True)
class GaitSetup:
    """The gait scenario: assistance, joint, sensor, timing and controller settings.

    Parameters
    ----------
    assist : float
        Share of the biological knee moment demanded from the lock (0-1; default 0.3).
    cadence_hz : float or None
        Stride frequency in Hz (strides per second, 0.3-2); None: the data's own. The data
        are time-scaled (the moment is kept: a simplification).
    strides : int
        Strides simulated (1-200).
    radius_m : float
        Pulley (lever) radius R in m (paper: 0.10 m).
    wrap_deg, mu_arc : float
        Wrap of the wire on the knee arc (deg) and its coefficient (capstan factor).
    static_ratio : float
        mu_static / mu_kinetic (>= 1): the stuck lock holds up to this x the capacity.
    window : (float, float) or None
        Demand window as fractions of the stride; None: the loading-response window.
    stance_fraction : float or None
        Stance share of the stride for the error metrics; None: the data's (else 0.6).
    dt_s : float
        Control sample and simulation step in s.
    sensor_delay_s : float
        Age of the friction and pressure measurements in s.
    p_max_mpa : float
        Command limit in MPa (the supply).
    precharge_mpa : float
        Lowest command in MPa (hold the tube near contact onset between demands; 0: vent).
    ilc_gain, ilc_forgetting : float
        Learning gain gamma in (0, 2) and the scalar part of Q in (0, 1] (both unitless).
    ilc_smoothing_s : float
        Half-width in s of Q's zero-phase moving average.
    mpc_sample_s, mpc_horizon_s, mpc_weight_du : float
        MPC sample time (s), horizon (s) and the command-change penalty.

    Examples
    --------
    >>> GaitSetup().assist, GaitSetup(assist=0.2).radius_m
    (0.3, 0.1)
    """

    assist: float = 0.3
    cadence_hz: float | None = None
    strides: int = 10
    radius_m: float = 0.10
    wrap_deg: float = 0.0
    mu_arc: float = 0.0
    static_ratio: float = 1.0
    window: tuple[float, float] | None = None
    stance_fraction: float | None = None
    dt_s: float = 0.002
    sensor_delay_s: float = 0.002
    p_max_mpa: float = 0.6
    precharge_mpa: float = 0.0
    ilc_gain: float = 0.3
    ilc_forgetting: float = 1.0
    ilc_smoothing_s: float = 0.02
    mpc_sample_s: float = 0.02
    mpc_horizon_s: float = 0.15
    mpc_weight_du: float = 0.01

    def __post_init__(self) -> None:
        check_range("assist", self.assist, 0.0, 1.0, lo_open=True)
        if self.cadence_hz is not None:
            lo, hi = CADENCE_RANGE_HZ
            check_range("cadence_hz", self.cadence_hz, lo, hi, unit="Hz")
        if not (isinstance(self.strides, int) and 1 <= self.strides <= 200):
            raise InputError(f"strides must be an integer in 1-200, got {self.strides!r}",
                             param="strides")
        check_range("radius_m", self.radius_m, 0.0, 1.0, lo_open=True, unit="m")
        check_range("wrap_deg", self.wrap_deg, 0.0, 720.0, unit="deg")
        check_range("mu_arc", self.mu_arc, 0.0, 2.0)
        check_range("static_ratio", self.static_ratio, 1.0, 5.0)
        if self.window is not None:
            a, b = self.window
            if not 0.0 <= a < b <= 1.0:
                raise InputError(f"window must be (start, end) fractions of the stride with "
                                 f"0 <= start < end <= 1, got {self.window!r}", param="window")
        if self.stance_fraction is not None:
            check_range("stance_fraction", self.stance_fraction, 0.2, 0.9)
        check_range("dt_s", self.dt_s, 1e-5, 0.05, unit="s")
        check_range("sensor_delay_s", self.sensor_delay_s, 0.0, 1.0, unit="s")
        check_range("p_max_mpa", self.p_max_mpa, 0.0, 10.0, lo_open=True, unit="MPa")
        check_range("precharge_mpa", self.precharge_mpa, 0.0, self.p_max_mpa, hi_open=True,
                    unit="MPa")
        check_range("ilc_gain", self.ilc_gain, 0.0, 2.0, lo_open=True, hi_open=True)
        check_range("ilc_forgetting", self.ilc_forgetting, 0.0, 1.0, lo_open=True)
        check_range("ilc_smoothing_s", self.ilc_smoothing_s, 0.0, 1.0, unit="s")
        check_range("mpc_sample_s", self.mpc_sample_s, self.dt_s, 0.1, unit="s")
        check_range("mpc_horizon_s", self.mpc_horizon_s, 2 * self.mpc_sample_s, 2.0, unit="s")
        check_range("mpc_weight_du", self.mpc_weight_du, 0.0, 1e6)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready settings (units in the names)."""
        d = asdict(self)
        d["window"] = None if self.window is None else list(self.window)
        return d


# ---- the stride profile ------------------------------------------------------------------------


@dataclass(frozen=True)
class _Profile:
    """One stride on the simulation grid: n samples of dt, angle with the closing sample."""

    dt: float
    theta: NDArray[np.float64]        # n + 1 (rad), periodic: theta[n] = theta[0]
    moment: NDArray[np.float64]       # n (Nm)
    demand: NDArray[np.float64]       # n (Nm), signed
    window: tuple[int, int]           # first and one-past-last demand samples
    stance: int                       # samples of stance

    @property
    def n(self) -> int:
        return int(self.moment.size)


def _check_gait(gait: GaitLike, controller: str) -> tuple[NDArray[np.float64], ...]:
    try:
        t = np.asarray(gait.time_s, dtype=float)
        a = np.asarray(gait.knee_angle_rad, dtype=float)
        m = np.asarray(gait.knee_moment_nm, dtype=float)
    except (AttributeError, TypeError, ValueError):
        raise InputError("gait must have time_s, knee_angle_rad and knee_moment_nm arrays "
                         "(e.g. exofric.io.read_gait)", param="gait") from None
    if not (t.ndim == a.ndim == m.ndim == 1 and t.size == a.size == m.size >= 10):
        raise InputError("gait time_s, knee_angle_rad and knee_moment_nm must be 1-D, of one "
                         "length, >= 10 samples", param="gait")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(a)) and np.all(np.isfinite(m))):
        raise InputError("gait data must be finite", param="gait")
    if np.any(np.diff(t) <= 0.0):
        raise InputError("gait time_s must increase strictly", param="gait")
    jump_deg = abs(math.degrees(a[-1] - a[0]))
    span = float(np.ptp(m)) or 1.0
    jump_m = abs(m[-1] - m[0]) / span
    if jump_deg > PERIODIC_ANGLE_DEG or jump_m > PERIODIC_MOMENT_SHARE:
        msg = (f"the gait data are not one periodic stride: the angle ends {jump_deg:.1f} deg "
               f"and the moment {100 * jump_m:.0f} % of its range away from where they start "
               f"(allowed {PERIODIC_ANGLE_DEG:g} deg, {100 * PERIODIC_MOMENT_SHARE:g} %)")
        if controller == "ilc":
            raise InputError(msg + ": ILC learns across repeated strides; give one stride, "
                             "heel strike to heel strike", param="gait")
        warnings.warn(msg + ": repeated as is", PlausibilityWarning, stacklevel=3)
    return t - t[0], a, m


def _window(theta: NDArray[np.float64], moment: NDArray[np.float64],
            window: tuple[float, float] | None) -> tuple[NDArray[np.bool_], tuple[int, int]]:
    """Samples where the brake can deliver the demand (moment resisting the motion)."""
    n = moment.size
    dth = theta[1:] - theta[:-1]
    resist = moment * dth < 0.0
    if window is not None:
        i0, i1 = int(round(window[0] * n)), int(round(window[1] * n))
        mask = np.zeros(n, dtype=bool)
        mask[i0:i1] = True
        mask &= resist
    else:
        # loading response: extension moment while flexing, first run in the first 40 %
        k1 = resist & (moment < 0.0) & (dth > 0.0)
        idx = np.flatnonzero(k1[: int(0.4 * n)])
        mask = np.zeros(n, dtype=bool)
        if idx.size:
            i0 = int(idx[0])
            i1 = i0 + int(np.argmin(k1[i0:])) if not k1[i0:].all() else n
            mask[i0:i1] = True
    hits = np.flatnonzero(mask)
    if hits.size == 0:
        raise InputError("no demand: the knee moment never resists the knee's motion in the "
                         "demand window (a brake can only absorb); check the data's sign "
                         "convention or the window", param="window")
    return mask, (int(hits[0]), int(hits[-1]) + 1)


def _profile(gait: GaitLike, setup: GaitSetup, controller: str) -> _Profile:
    t, a, m = _check_gait(gait, controller)
    period = float(t[-1] + np.median(np.diff(t)))
    stride = period if setup.cadence_hz is None else 1.0 / setup.cadence_hz
    lo, hi = CADENCE_RANGE_HZ
    if not lo <= 1.0 / stride <= hi:
        raise InputError(f"cadence_hz must be in {lo:g}-{hi:g} Hz, the data's stride gives "
                         f"{1.0 / stride:.3g} Hz", param="cadence_hz")
    n = int(round(stride / setup.dt_s))
    phase = np.arange(n + 1) / n * period
    theta = np.interp(phase, t, a, period=period)
    theta[n] = theta[0]
    moment = np.interp(phase[:n], t, m, period=period)
    mask, win = _window(theta, moment, setup.window)
    demand = np.where(mask, setup.assist * moment, 0.0)
    frac = setup.stance_fraction or getattr(gait, "stance_fraction", None) or 0.6
    return _Profile(stride / n, theta, moment, demand, win, int(round(frac * n)))


# ---- plant, model, friction ----------------------------------------------------------------


def _default_friction() -> FrictionFn:
    from exofric import paper
    from exofric.control._plant import CubicFrictionMap
    from exofric.friction import CubicFit

    lo, hi = paper.load()["eq8"]["fit_range_mpa"]
    return CubicFrictionMap(CubicFit(paper.eq8(), lo, hi), paper.scalar("gamma"))


def _plant_factory(plant: PneumaticParams | Callable[[], PlantLike] | None
                   ) -> Callable[[], PlantLike]:
    if plant is None:
        params = PneumaticParams()
        return lambda: PneumaticPlant(params)
    if isinstance(plant, PneumaticParams):
        return lambda: PneumaticPlant(plant)
    if callable(plant):
        return plant
    raise InputError("plant must be PneumaticParams, a factory of plants or None",
                     param="plant")


_MODELS: dict[tuple[Any, ...], PlantModel] = {}


def _model(plant: Any, make: Callable[[], PlantLike], command: float, dt: float) -> PlantModel:
    """identify_model, remembered for PneumaticParams plants (compare_gait runs five)."""
    if plant is not None and not isinstance(plant, PneumaticParams):
        return identify_model(make, command, dt)
    key = (plant, round(command, 12), dt)
    if key not in _MODELS:
        if len(_MODELS) > 64:
            _MODELS.clear()
        _MODELS[key] = identify_model(make, command, dt)
    return _MODELS[key]


def identify_model(make_plant: Callable[[], PlantLike], command_mpa: float, dt: float,
                   duration_s: float = 2.0) -> PlantModel:
    """Two-point FOPDT model of a plant from a simulated step 0 -> ``command_mpa`` (MPa).

    K = p_end / command; dead time d = time to 2 % of p_end; lag tau = t_63 - d (the times at
    which the pressure first reaches 2 % and 63.2 % of its final value; Astrom & Hagglund
    2006, Sec 2.7). A choked fill ramps rather than lags: the model then matches its t_63.

    Parameters
    ----------
    make_plant : callable
        Returns a fresh plant at 0 MPa (``pressure_mpa``, ``advance(command_mpa, dt)``).
    command_mpa : float
        Step size in MPa (> 0).
    dt : float
        Sample time in s.
    duration_s : float
        Simulated time in s (the pressure must settle within it).

    Returns
    -------
    PlantModel

    Examples
    --------
    >>> from exofric.control import PlantParams, PressurePlant
    >>> m = identify_model(lambda: PressurePlant(PlantParams(time_constant_s=0.1,
    ...                    delay_s=0.02)), 0.3, 0.001)
    >>> round(m.gain, 3), round(m.time_constant_s + m.delay_s, 2)
    (1.0, 0.12)
    """
    check_range("command_mpa", command_mpa, 0.0, 10.0, lo_open=True, unit="MPa")
    plant = make_plant()
    n = int(round(duration_s / dt))
    p = np.array([plant.advance(command_mpa, dt) for _ in range(n)])
    p_end = float(p[-1])
    if not p_end > 0.0 or abs(p[-1] - p[int(0.9 * n)]) > 0.01 * p_end:
        raise InputError(f"the plant does not settle within {duration_s:g} s of a "
                         f"{command_mpa:g} MPa step: give a PlantModel", param="model")
    t = np.arange(1, n + 1) * dt
    t2 = float(t[np.argmax(p >= 0.02 * p_end)]) - dt
    t63 = float(t[np.argmax(p >= (1.0 - math.exp(-1.0)) * p_end)])
    d = max(t2, 0.0)
    return PlantModel(p_end / command_mpa, max(t63 - d, dt), d)


# ---- controllers ------------------------------------------------------------------------------


@dataclass
class _Context:
    """What every controller needs: the stride, the maps and the model."""

    prof: _Profile
    setup: GaitSetup
    friction: FrictionFn
    model: PlantModel
    setpoint: NDArray[np.float64]       # friction set-point at the block (N), per sample
    p_ref: NDArray[np.float64]          # model pressure for the set-point (MPa), per sample
    cache: dict[float, float] = field(default_factory=dict)

    def inverse(self, f: float) -> float:
        """friction_inverse, remembered: the set-points repeat exactly stride after stride."""
        p = self.cache.get(f)
        if p is None:
            p = self.cache[f] = friction_inverse(self.friction, f,
                                                 p_max_mpa=self.setup.p_max_mpa)
        return p


class _ControllerStep:
    """The project's Controller, stepped once per sample (pid, ff, preview)."""

    def __init__(self, ctx: _Context, ctrl: Controller, preview: PreviewFeedforward | None
                 ) -> None:
        self.ctx, self.ctrl, self.preview = ctx, ctrl, preview
        self.lead = int(round(ctx.model.lead_s / ctx.prof.dt))
        self.pressure = bool(getattr(ctrl, "uses_pressure", False))
        self.description = ""

    def command(self, k: int, i: int, y: float, p: float) -> float:
        ctx = self.ctx
        r = ctx.setpoint
        if self.preview is not None:
            self.preview.set_preview(float(r[(i + self.lead) % r.size]))
        if self.pressure:
            return float(self.ctrl.step(float(r[i]), y, ctx.prof.dt,   # type: ignore[call-arg]
                                        pressure_mpa=p))
        return float(self.ctrl.step(float(r[i]), y, ctx.prof.dt))

    def end_stride(self, error_n: NDArray[np.float64]) -> None:
        return None


def _pid(ctx: _Context) -> _ControllerStep:
    s, m = ctx.setup, ctx.model
    p_op = float(np.max(ctx.p_ref)) * 0.5 or 0.5 * s.p_max_mpa
    slope = max(local_slope(ctx.friction, p_op), 1e-6)
    tune = rule_gains("pi", m.gain * slope, max(m.time_constant_s, ctx.prof.dt),
                      m.delay_s + s.sensor_delay_s)
    ff = ModelFeedforward(ctx.inverse, ctx.friction, time_constant_s=max(m.time_constant_s,
                                                                          1e-4),
                          delay_s=m.delay_s, gain=m.gain, p_max_mpa=s.p_max_mpa)
    ctrl = ScheduledController(tune.gains, ctx.friction, slope_ref_n_per_mpa=slope,
                               operating_pressure=ctx.inverse, feedforward=ff,
                               u_min=s.precharge_mpa, u_max=s.p_max_mpa)
    step = _ControllerStep(ctx, ctrl, None)
    g = tune.gains
    step.description = (f"PI (SIMC: kp {g.kp:.3g} MPa/N, Ti {g.ti_s:.3g} s) scheduled on dF/dP, "
                        "2-DOF model feedforward")
    return step


def _feedforward(ctx: _Context, preview: bool) -> _ControllerStep:
    s, m = ctx.setup, ctx.model
    ff = (PreviewFeedforward(ctx.inverse, gain=m.gain) if preview
          else ModelFeedforward(ctx.inverse, gain=m.gain))
    ctrl = Controller(PIDGains(0.0), feedforward=ff, u_min=s.precharge_mpa, u_max=s.p_max_mpa)
    step = _ControllerStep(ctx, ctrl, ff if isinstance(ff, PreviewFeedforward) else None)
    step.description = ("static model feedforward g^-1(r(t + %.0f ms)) / K" % (1e3 * m.lead_s)
                        if preview else "static model feedforward g^-1(r) / K, no feedback")
    return step


class _ILCStep:
    """Preview feedforward plus the learned command trajectory, clipped to the limits."""

    def __init__(self, ctx: _Context) -> None:
        self.ctx = ctx
        self.base = _feedforward(ctx, preview=True)
        s, prof = ctx.setup, ctx.prof
        # learning window: the demand window and, before it, the time the supply needs
        i0, i1 = prof.window
        mask = np.zeros(prof.n, dtype=bool)
        mask[max(0, i0 - self.base.lead - 1): i1] = True   # not into the previous stride
        self.ilc = IterativeLearning(ctx.model, prof.dt, prof.n, gain=s.ilc_gain,
                                     forgetting=s.ilc_forgetting,
                                     smoothing_samples=int(round(s.ilc_smoothing_s / prof.dt)),
                                     mask=mask)
        self.u_ff = np.zeros(prof.n)
        top = float(np.max(ctx.p_ref))
        floor = 0.1 * max(local_slope(ctx.friction, top), 1e-6)
        self.slope = np.array([max(local_slope(ctx.friction, float(p)), floor)
                               for p in ctx.p_ref])
        self.description = (f"model-inverse ILC (gamma {s.ilc_gain:g}, Q = {s.ilc_forgetting:g} "
                            f"x zero-phase average over +-{1e3 * s.ilc_smoothing_s:g} ms; "
                            f"contraction {self.ilc.contraction:.3g} per stride for an exact "
                            "linear model) on the preview feedforward")

    def command(self, k: int, i: int, y: float, p: float) -> float:
        u_ff = self.base.command(k, i, y, p)
        self.u_ff[i] = u_ff
        s = self.ctx.setup
        return min(max(u_ff + float(self.ilc.command[i]), s.precharge_mpa), s.p_max_mpa)

    def end_stride(self, error_n: NDArray[np.float64]) -> None:
        self.ilc.learn(error_n / self.slope)
        s = self.ctx.setup
        self.ilc.command = np.clip(self.ilc.command, s.precharge_mpa - self.u_ff,
                                   s.p_max_mpa - self.u_ff)


class _MPCStep:
    """Pressure-tracking MPC every ``mpc_sample_s`` from each heel strike (the samples repeat
    stride after stride; the last interval of a stride may be shorter), command held in
    between."""

    def __init__(self, ctx: _Context) -> None:
        s, prof = ctx.setup, ctx.prof
        self.ctx = ctx
        self.every = max(1, int(round(s.mpc_sample_s / prof.dt)))
        ts = self.every * prof.dt
        h = max(2, int(round(s.mpc_horizon_s / ts)))
        self.mpc = PressureMPC(ctx.model, ts, h, s.precharge_mpa, s.p_max_mpa,
                               weight_du=s.mpc_weight_du, measurement_delay_s=s.sensor_delay_s)
        self.offsets = (self.mpc.nd + 1 + np.arange(h)) * self.every
        self.u = s.precharge_mpa
        self.description = (f"pressure MPC (FOPDT model, {1e3 * ts:g} ms sample, horizon {h}, "
                            f"du weight {s.mpc_weight_du:g}; bounded least squares, active "
                            "set checked against scipy.optimize.lsq_linear)")

    def command(self, k: int, i: int, y: float, p: float) -> float:
        if i % self.every == 0:          # MPC samples synchronised to the heel strike
            ref = self.ctx.p_ref[(i + self.offsets) % self.ctx.prof.n]
            self.u = self.mpc.command(p, ref)
        return self.u

    def end_stride(self, error_n: NDArray[np.float64]) -> None:
        return None


def _stepper(name: str, ctx: _Context) -> Any:
    if name == "pid":
        return _pid(ctx)
    if name in ("ff", "preview"):
        return _feedforward(ctx, preview=name == "preview")
    if name == "ilc":
        return _ILCStep(ctx)
    return _MPCStep(ctx)


# ---- the simulation loop -------------------------------------------------------------------


@dataclass
class _Trace:
    torque: NDArray[np.float64]
    measured: NDArray[np.float64]
    pressure: NDArray[np.float64]
    command: NDArray[np.float64]
    opening: NDArray[np.float64]
    air_kg: NDArray[np.float64]


def _gas(plant: PlantLike) -> tuple[Callable[[NDArray[np.float64]], NDArray[np.float64]] | None,
                                    Callable[[float, float], float] | None]:
    """Mass (kg) in the volume at pressures (MPa) and the valve opening, for a PneumaticPlant."""
    if not isinstance(plant, PneumaticPlant):
        return None, None
    pr = plant.params

    def mass(p: NDArray[np.float64]) -> NDArray[np.float64]:
        v_m3 = np.asarray(plant.volume_mm3(p), dtype=float) * 1e-9
        return (p + pr.atmosphere_mpa) * 1e6 * v_m3 / (R_AIR_J_PER_KG_K * pr.temperature_k)

    if pr.valve == "regulator":
        return mass, lambda u, p: plant._opening(u, p)
    return mass, lambda u, p: 1.0 if u > 0.0 else -1.0


def _run(ctx: _Context, make_plant: Callable[[], PlantLike], stepper: Any) -> _Trace:
    prof, s = ctx.prof, ctx.setup
    n, dt = prof.n, prof.dt
    total = n * s.strides
    r_c = s.radius_m
    c_lock = _capstan(s, "locking")
    c_buf = _capstan(s, "buffering")
    plant = make_plant()
    mass, opening = _gas(plant)
    nd = int(round(s.sensor_delay_s / dt))
    out = _Trace(np.zeros(total), np.zeros(total), np.zeros(total), np.zeros(total),
                 np.full(total, math.nan), np.full(total + 1, math.nan))
    fric = ctx.friction
    dth = np.diff(prof.theta).tolist()
    eps = 1e-9 * dt           # rad per sample: below it the knee does not move (stick)
    demand = prof.demand.tolist()
    hold = s.static_ratio * c_lock * r_c
    p = float(plant.pressure_mpa)
    y_true = np.zeros(total)
    for k in range(total):
        i = k % n
        f = float(fric(p))
        d = dth[i]
        if d > eps:
            tau = -c_lock * f * r_c
        elif d < -eps:
            tau = c_buf * f * r_c
        else:
            cap = hold * f
            tau = min(max(demand[i], -cap), cap)
        out.torque[k] = tau
        y_true[k] = abs(tau) / (r_c * c_lock)
        out.pressure[k] = p
        y = y_true[k - nd] if k >= nd else 0.0
        pm = out.pressure[k - nd] if k >= nd else out.pressure[0]
        out.measured[k] = y
        u = stepper.command(k, i, y, pm)
        out.command[k] = u
        if opening is not None:
            out.opening[k] = opening(u, p)
        p = float(plant.advance(u, dt))
        if i == n - 1:
            stepper.end_stride(ctx.setpoint - y_true[k - n + 1: k + 1])
    if mass is not None:
        out.air_kg[:] = mass(np.append(out.pressure, p))
    return out


def _capstan(s: GaitSetup, direction: str) -> float:
    from exofric.friction import capstan_factor

    return capstan_factor(s.wrap_deg, s.mu_arc, direction)


# ---- metrics ------------------------------------------------------------------------------------


@checked_init
@dataclass(frozen=True)
class StrideMetrics:
    """How one stride went (see :func:`simulate_gait`).

    Attributes
    ----------
    stride : int
        Stride number (1-based).
    rms_error_nm, peak_error_nm : float
        RMS and largest |delivered - demanded| torque over stance in Nm.
    rms_error_pct, peak_error_pct : float
        The same in % of the stride's peak |demand|.
    engage_latency_ms, release_latency_ms : float
        Time from the demand reaching (leaving) 10 % of its peak to the delivered torque doing
        so, in ms (NaN: never within the stride).
    air_nl : float
        Air drawn from the supply in normal litres (positive mass increments of the line and
        tube; NaN for a plant without a gas model).
    peak_pressure_mpa : float
        Largest tube pressure in MPa.
    valve_duty : float
        Mean |valve opening| (0-1; regulator: spool opening, on/off: fill open); NaN without
        a valve model.
    energy_dissipated_j : float
        Work absorbed by the lock in J (-sum torque x d theta; >= 0).
    unwanted_torque_nms : float
        Integral of |torque| where nothing was demanded during stance, in N m s (the lock
        holding too long or engaging too early).
    wrong_direction : bool
        Whether the lock ever did positive work (resisted in the wrong direction): never.

    Examples
    --------
    >>> m = StrideMetrics(1, 2.0, 5.0, 10.0, 25.0, 10.0, 60.0, 0.05, 0.4, 0.5, 1.0, 0.2, False)
    >>> m.to_dict()["rms_error_nm"]
    2.0
    """

    stride: int
    rms_error_nm: float
    peak_error_nm: float
    rms_error_pct: float
    peak_error_pct: float
    engage_latency_ms: float
    release_latency_ms: float
    air_nl: float
    peak_pressure_mpa: float
    valve_duty: float
    energy_dissipated_j: float
    unwanted_torque_nms: float
    wrong_direction: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (units in the keys)."""
        return asdict(self)


def _latencies(tau: NDArray[np.float64], demand: NDArray[np.float64], dt: float
               ) -> tuple[float, float]:
    peak = float(np.max(np.abs(demand)))
    level = LATENCY_LEVEL * peak
    on_d = np.flatnonzero(np.abs(demand) >= level)
    if on_d.size == 0:
        return math.nan, math.nan
    d0, d1 = int(on_d[0]), int(on_d[-1])
    sign = math.copysign(1.0, float(demand[d0]))
    engaged = np.flatnonzero(sign * tau >= level)
    engaged = engaged[engaged >= d0 - int(0.1 / dt)] if engaged.size else engaged
    engage = 1e3 * (int(engaged[0]) - d0) * dt if engaged.size else math.nan
    free = np.flatnonzero(np.abs(tau[d1 + 1:]) < level)
    release = 1e3 * (int(free[0]) + 1) * dt if free.size else math.nan
    return engage, release


def _metrics(ctx: _Context, tr: _Trace) -> tuple[StrideMetrics, ...]:
    prof = ctx.prof
    n, dt, st = prof.n, prof.dt, prof.stance
    demand = prof.demand
    dth = np.diff(prof.theta)
    peak = float(np.max(np.abs(demand)))
    out = []
    for j in range(ctx.setup.strides):
        sl = slice(j * n, (j + 1) * n)
        tau = tr.torque[sl]
        err = (tau - demand)[:st]
        rms = float(np.sqrt(np.mean(err ** 2)))
        pk = float(np.max(np.abs(err)))
        eng, rel = _latencies(tau, demand, dt)
        air = tr.air_kg[j * n: (j + 1) * n + 1]
        air_nl = float(np.sum(np.maximum(np.diff(air), 0.0))) / RHO0_KG_PER_M3 * 1e3
        work = tau * dth
        idle = (demand == 0.0)[:st]
        out.append(StrideMetrics(
            j + 1, rms, pk, 100.0 * rms / peak, 100.0 * pk / peak, eng, rel, air_nl,
            float(np.max(tr.pressure[sl])), float(np.mean(np.abs(tr.opening[sl]))),
            float(-np.sum(work)), float(np.sum(np.abs(tau[:st][idle])) * dt),
            bool(np.any(work > 1e-12))))
    return tuple(out)


# ---- results ------------------------------------------------------------------------------------


@checked_init
@dataclass(frozen=True)
class GaitResult(HtmlReprMixin):
    """One controller through ``strides`` strides (built by :func:`simulate_gait`).

    Attributes
    ----------
    controller : str
        'pid', 'ff', 'preview', 'ilc' or 'mpc'.
    description : str
        What the controller is (gains, filters, horizon).
    setup : GaitSetup
        The scenario.
    dt_s : float
        Sample time in s.
    time_s, knee_angle_rad : ndarray
        Sample times (s) and knee flexion (rad) over all strides (time step ``dt_s``).
    demand_nm, torque_nm : ndarray
        Demanded and delivered joint torque in Nm (negative: extension).
    pressure_mpa, command_mpa, valve_opening : ndarray
        Tube pressure and pressure command (MPa), valve opening (-1..1; NaN without a
        valve model).
    strides : tuple of StrideMetrics
        Per-stride metrics.
    model : PlantModel
        The FOPDT model the controllers used.
    plant, friction, window : str
        What was simulated: the plant, the friction map, the demand window.
    peak_demand_nm : float
        Largest |demand| of the stride in Nm.
    warnings : tuple of str
        Plausibility warnings raised while setting up (also emitted).

    Examples
    --------
    >>> import numpy as np
    >>> from exofric.control import GaitSetup, simulate_gait
    >>> t = np.linspace(0.0, 1.0, 200, endpoint=False)
    >>> class Walk:                       # a stand-in for exofric.io.read_gait(...)
    ...     time_s = t
    ...     knee_angle_rad = 0.5 * (1 - np.cos(2 * np.pi * t))
    ...     knee_moment_nm = -40.0 * np.sin(2 * np.pi * t)
    >>> r = simulate_gait(Walk(), GaitSetup(strides=2), controller="ff")
    >>> len(r.strides), r.strides[-1].wrong_direction
    (2, False)
    """

    controller: str
    description: str
    setup: GaitSetup
    dt_s: float
    time_s: NDArray[np.float64]
    knee_angle_rad: NDArray[np.float64]
    demand_nm: NDArray[np.float64]
    torque_nm: NDArray[np.float64]
    pressure_mpa: NDArray[np.float64]
    command_mpa: NDArray[np.float64]
    valve_opening: NDArray[np.float64]
    strides: tuple[StrideMetrics, ...]
    model: PlantModel
    plant: str
    friction: str
    window: str
    peak_demand_nm: float
    warnings: tuple[str, ...] = field(default=())

    @property
    def wrong_direction(self) -> bool:
        """True when the lock did positive work in any stride (must never happen)."""
        return any(m.wrong_direction for m in self.strides)

    def summary(self) -> dict[int, StrideMetrics]:
        """Metrics after 1, 5 and 10 strides (those simulated; always the last)."""
        keep = [k for k in SUMMARY_STRIDES if k <= len(self.strides)]
        keep += [len(self.strides)] if len(self.strides) not in keep else []
        return {k: self.strides[k - 1] for k in keep}

    def to_dict(self, *, series: bool = False) -> dict[str, Any]:
        """JSON-ready: settings, model, per-stride metrics and the summary.

        Parameters
        ----------
        series : bool
            Include the time series (:meth:`to_frame` as lists).

        Returns
        -------
        dict
        """
        d: dict[str, Any] = {
            "controller": self.controller, "description": self.description,
            "setup": self.setup.to_dict(), "model": self.model.to_dict(),
            "plant": self.plant, "friction": self.friction, "window": self.window,
            "peak_demand_nm": self.peak_demand_nm, "dt_s": self.dt_s,
            "wrong_direction": self.wrong_direction,
            "strides": [m.to_dict() for m in self.strides],
            "summary": {str(k): m.to_dict() for k, m in self.summary().items()},
            "warnings": list(self.warnings),
        }
        if series:
            d["series"] = self.to_frame().to_dict(orient="list")
        return d

    def to_frame(self) -> pd.DataFrame:
        """The time series: ``time_s``, ``stride``, ``knee_angle_deg``, ``demand_nm``,
        ``torque_nm``, ``pressure_mpa``, ``command_mpa``, ``valve_opening``."""
        import pandas as pd

        n = self.time_s.size // len(self.strides)
        return pd.DataFrame({
            "time_s": self.time_s, "stride": np.arange(self.time_s.size) // n + 1,
            "knee_angle_deg": np.degrees(self.knee_angle_rad), "demand_nm": self.demand_nm,
            "torque_nm": self.torque_nm, "pressure_mpa": self.pressure_mpa,
            "command_mpa": self.command_mpa, "valve_opening": self.valve_opening})

    def metrics_frame(self) -> pd.DataFrame:
        """One row per stride (:class:`StrideMetrics` columns)."""
        import pandas as pd

        return pd.DataFrame([m.to_dict() for m in self.strides])

    def plot(self, fig: Any | None = None) -> Any:
        """Demand vs delivered torque, pressure and command, valve, knee angle over strides.

        Parameters
        ----------
        fig : matplotlib Figure, optional
            Empty figure to draw on (:func:`exofric.plots.plot_gait`; default a new one).

        Returns
        -------
        matplotlib Figure
        """
        from exofric.plots import plot_gait

        return plot_gait(self, fig)


def _describe_plant(make_plant: Callable[[], PlantLike]) -> str:
    pl = make_plant()
    if isinstance(pl, PneumaticPlant):
        pr = pl.params
        return (f"pneumatic ({pr.valve}, fill C {pr.fill.c_dm3_per_s_bar:g} and vent C "
                f"{pr.vent.c_dm3_per_s_bar:g} dm3/(s bar), line {pr.line_volume_mm3:g} mm3, "
                f"tube {pr.total_volume_mm3(0.0) - pr.line_volume_mm3:g} mm3 at 0 MPa, supply "
                f"{pr.supply_mpa:g} MPa)")
    return type(pl).__name__


def simulate_gait(
    gait: GaitLike,
    setup: GaitSetup | None = None,
    *,
    controller: str = "pid",
    plant: PneumaticParams | Callable[[], PlantLike] | None = None,
    friction: FrictionFn | None = None,
    model: PlantModel | None = None,
) -> GaitResult:
    """Simulate the knee lock over ``setup.strides`` strides of walking with one controller.

    Parameters
    ----------
    gait : GaitData-like
        One stride (heel strike to heel strike) with ``time_s`` (s), ``knee_angle_rad`` (rad,
        flexion positive) and ``knee_moment_nm`` (Nm, same axis): :func:`exofric.io.read_gait`.
    setup : GaitSetup, optional
        The scenario (default :class:`GaitSetup()`).
    controller : {'pid', 'ff', 'preview', 'ilc', 'mpc'}
        See the module docstring and ``docs/gait.md``.
    plant : PneumaticParams, callable or None
        The pneumatic plant's parameters (default ``PneumaticParams()``), or a factory returning
        a fresh plant at 0 MPa with ``pressure_mpa`` and ``advance(command_mpa, dt)``.
    friction : callable or None
        Friction at the block F(P) in N (MPa in); default the paper's Eq 9 (gamma x Eq 8).
    model : PlantModel or None
        The supply model the controllers use; default identified from a simulated step of
        the plant to the pressure of the peak demand (:func:`identify_model`).

    Returns
    -------
    GaitResult

    Raises
    ------
    InputError
        Bad data or settings (one line naming the parameter): non-periodic data with ILC, a
        cadence outside 0.3-2 Hz, no deliverable demand, an unknown controller.

    Examples
    --------
    >>> from exofric.io import gait_data_path, read_gait
    >>> r = simulate_gait(read_gait(gait_data_path()), GaitSetup(strides=1), controller="ff")
    >>> round(r.peak_demand_nm, 1), r.wrong_direction
    (19.3, False)
    """
    if controller not in GAIT_CONTROLLERS:
        raise InputError(f"controller must be one of {', '.join(GAIT_CONTROLLERS)}, got "
                         f"{controller!r}", param="controller")
    s = GaitSetup() if setup is None else setup
    fr = _default_friction() if friction is None else friction
    make = _plant_factory(plant)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", PlausibilityWarning)
        prof = _profile(gait, s, controller)
    r_n = np.abs(prof.demand) / (s.radius_m * _capstan(s, "locking"))
    inv: dict[float, float] = {}
    for f in r_n:
        if f not in inv:
            inv[float(f)] = friction_inverse(fr, float(f), p_max_mpa=s.p_max_mpa)
    p_ref = np.maximum(np.array([inv[float(f)] for f in r_n]), s.precharge_mpa)
    if float(fr(s.p_max_mpa)) < float(np.max(r_n)):
        caught.append(warnings.WarningMessage(
            f"the peak demand needs {np.max(r_n):.4g} N at the block, above the "
            f"{float(fr(s.p_max_mpa)):.4g} N the map gives at p_max_mpa {s.p_max_mpa:g} MPa: "
            "the lock saturates", PlausibilityWarning, __file__, 0))
    mdl = model if model is not None else _model(
        plant, make, max(float(np.max(p_ref)), 0.05 * s.p_max_mpa), prof.dt)
    for w in caught:
        warnings.warn(str(w.message), PlausibilityWarning, stacklevel=2)
    ctx = _Context(prof, s, fr, mdl, r_n, p_ref, inv)
    stepper = _stepper(controller, ctx)
    tr = _run(ctx, make, stepper)
    n_all = prof.n * s.strides
    i0, i1 = prof.window
    return GaitResult(
        controller, stepper.description, s, prof.dt, np.arange(n_all, dtype=float) * prof.dt,
        np.tile(prof.theta[:-1], s.strides), np.tile(prof.demand, s.strides), tr.torque,
        tr.pressure, tr.command, tr.opening, _metrics(ctx, tr), mdl, _describe_plant(make),
        getattr(fr, "__class__", type(fr)).__name__,
        f"{100 * i0 / prof.n:.1f}-{100 * i1 / prof.n:.1f} % of the stride "
        f"({'given' if s.window else 'loading response'})",
        float(np.max(np.abs(prof.demand))), tuple(str(w.message) for w in caught))


@checked_init
@dataclass(frozen=True)
class GaitComparison(DisplayMixin):
    """Every controller on one scenario (built by :func:`compare_gait`).

    Attributes
    ----------
    results : tuple of GaitResult
        One per controller, in the order asked.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 200, endpoint=False)
    >>> class Walk:
    ...     time_s = t
    ...     knee_angle_rad = 0.5 * (1 - np.cos(2 * np.pi * t))
    ...     knee_moment_nm = -40.0 * np.sin(2 * np.pi * t)
    >>> c = compare_gait(Walk(), GaitSetup(strides=1), controllers=("ff",))
    >>> list(c.to_frame()["controller"])
    ['ff']
    """

    results: tuple[GaitResult, ...]

    def to_frame(self) -> pd.DataFrame:
        """One row per controller and summary stride (1, 5, 10): the metrics."""
        import pandas as pd

        rows = []
        for r in self.results:
            for k, m in r.summary().items():
                rows.append({"controller": r.controller, "after_strides": k, **m.to_dict()})
        return pd.DataFrame(rows)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: per controller its full :meth:`GaitResult.to_dict`."""
        return {r.controller: r.to_dict() for r in self.results}

    def format(self) -> str:
        """A text table of the last stride's metrics per controller."""
        head = (f"{'controller':<10} {'RMS err Nm':>10} {'%':>6} {'peak Nm':>8} {'engage ms':>9} "
                f"{'release ms':>10} {'air NL':>7} {'Pmax MPa':>8} {'duty':>5} {'E J':>6}")
        lines = [head]
        for r in self.results:
            m = r.strides[-1]
            lines.append(f"{r.controller:<10} {m.rms_error_nm:>10.2f} {m.rms_error_pct:>6.1f} "
                         f"{m.peak_error_nm:>8.2f} {m.engage_latency_ms:>9.0f} "
                         f"{m.release_latency_ms:>10.0f} {m.air_nl:>7.3f} "
                         f"{m.peak_pressure_mpa:>8.3f} {m.valve_duty:>5.2f} "
                         f"{m.energy_dissipated_j:>6.2f}")
        return "\n".join(lines)


def compare_gait(gait: GaitLike, setup: GaitSetup | None = None, *,
                 controllers: Sequence[str] = GAIT_CONTROLLERS,
                 plant: PneumaticParams | Callable[[], PlantLike] | None = None,
                 friction: FrictionFn | None = None,
                 model: PlantModel | None = None) -> GaitComparison:
    """Run :func:`simulate_gait` for each controller on one scenario.

    Parameters
    ----------
    gait, setup, plant, model
        As for :func:`simulate_gait`.
    friction : callable or None
        Friction at the block F(P) in N (MPa in), as for :func:`simulate_gait`.
    controllers : sequence of str
        Controllers to compare (default all five).

    Returns
    -------
    GaitComparison

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 200, endpoint=False)
    >>> class Walk:
    ...     time_s = t
    ...     knee_angle_rad = 0.5 * (1 - np.cos(2 * np.pi * t))
    ...     knee_moment_nm = -40.0 * np.sin(2 * np.pi * t)
    >>> c = compare_gait(Walk(), GaitSetup(strides=1), controllers=("ff", "preview"))
    >>> [r.controller for r in c.results]
    ['ff', 'preview']
    """
    return GaitComparison(tuple(simulate_gait(gait, setup, controller=c, plant=plant,
                                              friction=friction, model=model)
                                for c in controllers))


# ---- sizing ------------------------------------------------------------------------------

#: Sonic conductances (dm^3/(s bar)) of the default sizing sweep: 1/16" to 1/4" valves.
SIZING_CONDUCTANCES = (0.02, 0.03, 0.05, 0.07, 0.1, 0.15, 0.2, 0.3, 0.4)


@checked_init
@dataclass(frozen=True)
class GaitSizing(DisplayMixin):
    """Valve sizing from a sweep of the ports' sonic conductance (built by :func:`size_valve`).

    Attributes
    ----------
    controller : str
        The controller simulated.
    target_rms_pct : float
        Required RMS torque error over stance, % of the peak demand (last stride).
    conductance : tuple of float
        Fill and vent port conductance C of each run in dm^3/(s bar).
    rms_error_pct, release_latency_ms, air_nl : tuple of float
        Last-stride metrics of each run (%, ms, normal litres).
    smallest_conductance : float or None
        The smallest swept C meeting the target (None: none does).

    Examples
    --------
    >>> s = GaitSizing("mpc", 20.0, (0.05, 0.1), (25.0, 18.0), (80.0, 20.0), (0.05, 0.05), 0.1)
    >>> s.to_frame().shape
    (2, 4)
    """

    controller: str
    target_rms_pct: float
    conductance: tuple[float, ...]
    rms_error_pct: tuple[float, ...]
    release_latency_ms: tuple[float, ...]
    air_nl: tuple[float, ...]
    smallest_conductance: float | None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (units in the keys)."""
        d = asdict(self)
        d["conductance_dm3_per_s_bar"] = d.pop("conductance")
        return d

    def to_frame(self) -> pd.DataFrame:
        """One row per conductance: C, RMS %, release ms, air NL."""
        import pandas as pd

        return pd.DataFrame({"conductance_dm3_per_s_bar": self.conductance,
                             "rms_error_pct": self.rms_error_pct,
                             "release_latency_ms": self.release_latency_ms,
                             "air_nl": self.air_nl})


def size_valve(gait: GaitLike, setup: GaitSetup | None = None, *,
               target_rms_pct: float = 20.0, controller: str = "mpc",
               base: PneumaticParams | None = None,
               conductances: Sequence[float] = SIZING_CONDUCTANCES,
               friction: FrictionFn | None = None) -> GaitSizing:
    """The smallest valve (fill = vent sonic conductance) that meets a torque-error target.

    Runs :func:`simulate_gait` for each conductance (both ports, the rest of ``base``
    unchanged; the supply model re-identified for each) and reports the last stride's RMS
    error over stance (% of the peak demand).

    Parameters
    ----------
    gait, setup, controller
        As for :func:`simulate_gait`.
    friction : callable or None
        Friction at the block F(P) in N (MPa in), as for :func:`simulate_gait`.
    target_rms_pct : float
        Required RMS torque error in % of the peak demand (> 0).
    base : PneumaticParams or None
        The plant whose ports are swept (default ``PneumaticParams()``).
    conductances : sequence of float
        Sonic conductances C to try in dm^3/(s bar), ascending.

    Returns
    -------
    GaitSizing

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 200, endpoint=False)
    >>> class Walk:
    ...     time_s = t
    ...     knee_angle_rad = 0.5 * (1 - np.cos(2 * np.pi * t))
    ...     knee_moment_nm = -40.0 * np.sin(2 * np.pi * t)
    >>> s = size_valve(Walk(), GaitSetup(strides=2), controller="ff", conductances=(0.05, 0.4),
    ...                target_rms_pct=50.0)
    >>> len(s.rms_error_pct)
    2
    """
    from dataclasses import replace

    from exofric.control._pneumatic import Orifice

    check_range("target_rms_pct", target_rms_pct, 0.0, 100.0, lo_open=True, unit="%")
    cs = [float(c) for c in conductances]
    if not cs or any(c <= 0 for c in cs) or cs != sorted(cs):
        raise InputError("conductances must be > 0 dm^3/(s bar) and ascending",
                         param="conductances")
    pp = PneumaticParams() if base is None else base
    rms, rel, air = [], [], []
    for c in cs:
        params = replace(pp, fill=replace(pp.fill, c_dm3_per_s_bar=c),
                         vent=replace(pp.vent, c_dm3_per_s_bar=c))
        assert isinstance(params.fill, Orifice)
        m = simulate_gait(gait, setup, controller=controller, plant=params,
                          friction=friction).strides[-1]
        rms.append(m.rms_error_pct)
        rel.append(m.release_latency_ms)
        air.append(m.air_nl)
    ok = [c for c, e in zip(cs, rms, strict=True) if e <= target_rms_pct]
    return GaitSizing(controller, float(target_rms_pct), tuple(cs), tuple(rms), tuple(rel),
                      tuple(air), ok[0] if ok else None)
