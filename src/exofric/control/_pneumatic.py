"""A physical pneumatic plant: ISO 6358 orifices, a regulator, line and tube volumes, gas law.

Why: the lag-plus-dead-time plant (:class:`~exofric.control.PressurePlant`) fits a step but
its parameters say nothing about the hardware. Here every parameter is physical and can be
sized or identified:

* :class:`Orifice` -- ISO 6358 flow through a valve port: sonic conductance C and critical
  pressure ratio b (datasheet values), choked and subsonic regimes.
* :class:`PneumaticParams` -- supply, fill and vent orifices, line volume, the tube's own
  volume V(P) (constant, or a table from the FE squeeze: :func:`tube_volume_table`), the gas
  (polytropic exponent n, temperature) and the valve: a proportional pressure regulator
  (proportional band, dead band, hysteresis, optional command filter) or on/off valves.
* :class:`PneumaticPlant` -- steps the pressure ODE with the same interface as
  :class:`~exofric.control.PressurePlant` (``advance(command_mpa, dt)``, ``pressure_mpa``).
* :func:`simulate_charge` and :func:`identify_charge` -- charge/discharge transients after
  on/off valve steps, and the least-squares fit of C and the volume from them (beside the
  first-order-plus-dead-time fit of :func:`~exofric.control.identify_step`).

Model. With gauge pressure p (MPa), absolute p_abs = p + p_atm, total volume V(p) = line +
tube (mm^3) and the net mass flow m_dot into the volume (kg/s),

    dp/dt = n R T m_dot / (V(p) + n p_abs dV/dp)

(polytropic gas, n = 1 isothermal .. 1.4 adiabatic; T the supply temperature; for n = 1 it is
exactly the mass balance d(p_abs V / R T)/dt = m_dot). It is integrated by an adaptive
L-stable Rosenbrock method (Shampine and Reichelt's ode23s, scalar), which copes with the
stiffness of a narrow proportional band.

Units: pressure MPa (gauge unless the name says _abs), volume mm^3, time s, temperature K,
mass flow kg/s, sonic conductance dm^3/(s bar).

Examples
--------
>>> plant = PneumaticPlant(PneumaticParams(valve="on-off"))
>>> p = [plant.advance(0.6, 0.05) for _ in range(20)]    # fill valve open for 1 s
>>> round(p[-1], 3)                                       # charged to the 0.6 MPa supply
0.6
"""

from __future__ import annotations

import bisect
import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field, fields, replace
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric import defaults as D
from exofric._display import DisplayMixin
from exofric._lsq import lsq_covariance, residual_variance, standard_errors
from exofric._validate import checked_init
from exofric.control._identify import IdentifiedPlant, identify_step
from exofric.errors import (
    InputError,
    PlausibilityWarning,
    check_positive,
    check_range,
    check_series,
)

if TYPE_CHECKING:
    import pandas as pd

    from exofric.simulate import SqueezeResult

__all__ = [
    "ChargeFit",
    "Orifice",
    "PneumaticParams",
    "PneumaticPlant",
    "identify_charge",
    "simulate_charge",
    "tube_volume_table",
]

# ---- constants (the lead moves the defaults to exofric.defaults) --------------------------
#: ISO 8778 standard reference atmosphere (ANR): density of air in kg/m^3 (20 degC, 100 kPa,
#: 65 % RH), the rho0 of ISO 6358.
RHO0_KG_PER_M3 = 1.185
#: ISO 8778 reference temperature T0 in K.
T0_K = 293.15
#: Specific gas constant of dry air in J/(kg K).
R_AIR_J_PER_KG_K = 287.1
#: Standard atmosphere in MPa (absolute): the exhaust pressure of the vent.
ATMOSPHERE_MPA = 0.101325
#: Default supply pressure (gauge) in MPa: the top of the paper's tested range.
DEFAULT_SUPPLY_MPA = D.PNEU_SUPPLY_MPA
#: Default sonic conductance C of the fill and vent ports in dm^3/(s bar) (a small 1/8"
#: valve; an assumption, not a measurement).
DEFAULT_C_DM3_PER_S_BAR = D.PNEU_C_DM3_PER_S_BAR
#: Default critical pressure ratio b (unitless; typical of small valves).
DEFAULT_CRITICAL_RATIO = D.PNEU_CRITICAL_RATIO
#: Pressure ratio above which the ISO 6358 subsonic law is replaced by a linear (laminar)
#: law to zero flow at ratio 1, continuous at the ratio (unitless; removes the infinite
#: slope dm/dp at equal pressures, as ISO 6358-3's laminar range; Simscape uses 0.999).
DEFAULT_LAMINAR_RATIO = D.PNEU_LAMINAR_RATIO
#: Default line (hose + fittings + regulator outlet) volume in mm^3 (1 m of 4 mm ID hose).
DEFAULT_LINE_VOLUME_MM3 = D.PNEU_LINE_VOLUME_MM3
#: Default tube cavity volume in mm^3: pi 4.97^2 / 4 x 116 mm (the base-group tube at P = 0).
DEFAULT_TUBE_VOLUME_MM3 = D.PNEU_TUBE_VOLUME_MM3
#: Default proportional band of the regulator in MPa (pressure error for a full opening).
DEFAULT_PROPORTIONAL_BAND_MPA = D.PNEU_PROPORTIONAL_BAND_MPA
#: Default relative and absolute (MPa) tolerances of the plant's ODE integrator.
DEFAULT_RTOL = D.PNEU_RTOL
DEFAULT_ATOL_MPA = D.PNEU_ATOL_MPA

VALVES = ("regulator", "on-off")

# ode23s (Shampine and Reichelt 1997) coefficients
_D = 1.0 / (2.0 + math.sqrt(2.0))
_E32 = 6.0 + math.sqrt(2.0)


def _flow_factor(c_dm3_per_s_bar: float, temperature_k: float) -> float:
    """kg/(s MPa): C rho0 sqrt(T0/T) with C in m^3/(s Pa) (1 dm^3/(s bar) = 1e-8) x 1e6 Pa/MPa."""
    return c_dm3_per_s_bar * 1e-2 * RHO0_KG_PER_M3 * math.sqrt(T0_K / temperature_k)


@checked_init
@dataclass(frozen=True)
class Orifice:
    """An ISO 6358 flow restriction (valve port): sonic conductance C and critical ratio b.

    Mass flow from upstream p_u to downstream p_d (absolute), r = p_d / p_u:

    * choked, r <= b:      m = C rho0 p_u sqrt(T0 / T)
    * subsonic, b < r:     m = C rho0 p_u sqrt(T0 / T) sqrt(1 - ((r - b) / (1 - b))^2)
    * r > ``laminar_ratio``: linear in (1 - r) to 0 at r = 1, continuous (a laminar range
      that keeps dm/dp finite at equal pressures; set it near 1 to approach pure ISO 6358);

    with rho0 = 1.185 kg/m^3 and T0 = 293.15 K (ISO 8778 reference atmosphere). Reverse flow
    (p_d > p_u) is the same law with the roles swapped and a negative sign.

    C is kept in dm^3/(s bar), the unit of ISO 6358 and of valve datasheets (it is a volume
    flow at the reference density per upstream pressure), so values can be copied from a
    datasheet; 1 dm^3/(s bar) = 1e-8 m^3/(s Pa).

    Parameters
    ----------
    c_dm3_per_s_bar : float
        Sonic conductance C in dm^3/(s bar), > 0.
    b : float
        Critical pressure ratio (unitless), 0 <= b < 1.
    laminar_ratio : float
        Pressure ratio (unitless) where the laminar range starts, b < laminar_ratio < 1.

    Examples
    --------
    >>> o = Orifice(0.1, 0.3)
    >>> round(o.mass_flow_kg_per_s(0.7, 0.1), 7)        # choked: C rho0 p_u = 1e-9 x 1.185 x 7e5
    0.0008295
    >>> o.mass_flow_kg_per_s(0.5, 0.5)
    0.0
    """

    c_dm3_per_s_bar: float
    b: float = DEFAULT_CRITICAL_RATIO
    laminar_ratio: float = DEFAULT_LAMINAR_RATIO

    def __post_init__(self) -> None:
        check_range("c_dm3_per_s_bar", self.c_dm3_per_s_bar, 0.0, 1e4, lo_open=True,
                    unit="dm^3/(s bar)")
        check_range("b", self.b, 0.0, 1.0, hi_open=True)
        check_range("laminar_ratio", self.laminar_ratio, self.b, 1.0, lo_open=True,
                    hi_open=True)

    def _phi(self, r: float) -> float:
        """Subsonic factor in [0, 1] at pressure ratio 0 <= r <= 1 (scalar)."""
        b, rl = self.b, self.laminar_ratio
        if r <= b:
            return 1.0
        if r <= rl:
            x = (r - b) / (1.0 - b)
            return math.sqrt(1.0 - x * x)
        xl = (rl - b) / (1.0 - b)
        return math.sqrt(1.0 - xl * xl) * (1.0 - r) / (1.0 - rl)

    def mass_flow_kg_per_s(self, p_up_abs_mpa: ArrayLike, p_down_abs_mpa: ArrayLike,
                           temperature_k: float = T0_K) -> Any:
        """Mass flow in kg/s from ``p_up_abs_mpa`` to ``p_down_abs_mpa`` (absolute MPa).

        Vectorised (arrays broadcast; float in, float out); negative when p_down > p_up.

        Parameters
        ----------
        p_up_abs_mpa, p_down_abs_mpa : array_like
            Absolute upstream and downstream pressures in MPa (>= 0).
        temperature_k : float
            Upstream gas temperature in K (> 0).

        Returns
        -------
        float or ndarray
            Mass flow in kg/s.

        Examples
        --------
        >>> import numpy as np
        >>> o = Orifice(0.1, 0.0)
        >>> np.round(o.mass_flow_kg_per_s(0.6, [0.0, 0.3, 0.6, 0.7]) * 1e3, 5).tolist()
        [0.711, 0.61574, 0.0, -0.42726]
        """
        t = check_positive("temperature_k", temperature_k, "K")
        k = _flow_factor(self.c_dm3_per_s_bar, t)
        pu = np.asarray(p_up_abs_mpa, dtype=float)
        pd_ = np.asarray(p_down_abs_mpa, dtype=float)
        scalar = pu.ndim == 0 and pd_.ndim == 0
        pu, pd_ = np.broadcast_arrays(pu, pd_)
        hi = np.maximum(pu, pd_)
        lo = np.minimum(pu, pd_)
        sign = np.where(pu >= pd_, 1.0, -1.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(hi > 0.0, lo / np.where(hi > 0.0, hi, 1.0), 1.0)
        b, rl = self.b, self.laminar_ratio
        x = np.clip((r - b) / (1.0 - b), 0.0, 1.0)
        xl = (rl - b) / (1.0 - b)
        phi = np.where(r <= rl, np.sqrt(np.clip(1.0 - x * x, 0.0, None)),
                       math.sqrt(1.0 - xl * xl) * (1.0 - r) / (1.0 - rl))
        m = sign * k * hi * phi + 0.0
        return float(m) if scalar else m


@checked_init
@dataclass(frozen=True)
class PneumaticParams:
    """Parameters of the physical pneumatic plant (defaults: assumptions, not measurements).

    Parameters
    ----------
    supply_mpa : float
        Supply pressure (gauge) in MPa upstream of the fill port.
    fill, vent : Orifice
        Fill port (supply -> tube) and vent port (tube -> atmosphere), ISO 6358 (C in
        dm^3/(s bar), b unitless).
    line_volume_mm3 : float
        Hose, fittings and regulator outlet volume in mm^3 (>= 0; line + tube > 0).
    tube_volume_mm3 : float
        The tube's cavity volume in mm^3 when no table is given (constant, >= 0).
    tube_table_pressure_mpa, tube_table_volume_mm3 : tuple of float
        Optional table of the tube's cavity volume (mm^3) against gauge pressure (MPa), e.g.
        from :func:`tube_volume_table`: pressures strictly increasing, volumes > 0 and
        non-decreasing; monotone cubic (PCHIP) in between, constant below the first point and
        linear with the end slope above the last. Empty: the constant volume is used.
    polytropic_n : float
        Polytropic exponent n (unitless), 1 (isothermal) .. 1.4 (adiabatic).
    temperature_k : float
        Supply gas temperature in K.
    atmosphere_mpa : float
        Absolute atmospheric pressure in MPa (the vent's exhaust; gauge zero).
    valve : {'regulator', 'on-off'}
        ``'regulator'``: a proportional pressure regulator whose command is the target
        pressure (MPa); spool opening clip(e / proportional_band, -1, 1) with the error e =
        command - p reduced by the dead band (positive: fill port from the supply, negative:
        vent port). ``'on-off'``: two on/off valves, the fill port open when the command is
        > 0 MPa, else the vent port (for charge/discharge experiments).
    proportional_band_mpa : float
        Pressure error in MPa that opens the regulator fully (> 0).
    dead_band_mpa : float
        Half-width in MPa of the error range with no flow (>= 0).
    hysteresis_mpa : float
        Backlash (play) width in MPa on the regulator's command (>= 0): the command the spool
        sees moves only when the command leaves a band of this width around it.
    bandwidth_hz : float or None
        First-order filter on the regulator's command with this -3 dB bandwidth in Hz (the
        pilot stage); None: no filter.

    Examples
    --------
    >>> pp = PneumaticParams(dead_band_mpa=0.005)
    >>> pp.total_volume_mm3(0.0), pp.valve
    (14816.4, 'regulator')
    """

    supply_mpa: float = DEFAULT_SUPPLY_MPA
    fill: Orifice = field(default_factory=lambda: Orifice(DEFAULT_C_DM3_PER_S_BAR))
    vent: Orifice = field(default_factory=lambda: Orifice(DEFAULT_C_DM3_PER_S_BAR))
    line_volume_mm3: float = DEFAULT_LINE_VOLUME_MM3
    tube_volume_mm3: float = DEFAULT_TUBE_VOLUME_MM3
    tube_table_pressure_mpa: tuple[float, ...] = ()
    tube_table_volume_mm3: tuple[float, ...] = ()
    polytropic_n: float = 1.0
    temperature_k: float = T0_K
    atmosphere_mpa: float = ATMOSPHERE_MPA
    valve: str = "regulator"
    proportional_band_mpa: float = DEFAULT_PROPORTIONAL_BAND_MPA
    dead_band_mpa: float = 0.0
    hysteresis_mpa: float = 0.0
    bandwidth_hz: float | None = None

    def __post_init__(self) -> None:
        check_range("supply_mpa", self.supply_mpa, 0.0, 10.0, lo_open=True, unit="MPa")
        for name in ("fill", "vent"):
            if not isinstance(getattr(self, name), Orifice):
                raise InputError(f"{name} must be an Orifice, got {getattr(self, name)!r}",
                                 param=name)
        check_range("line_volume_mm3", self.line_volume_mm3, 0.0, 1e12, unit="mm^3")
        check_range("tube_volume_mm3", self.tube_volume_mm3, 0.0, 1e12, unit="mm^3")
        check_range("polytropic_n", self.polytropic_n, 1.0, 1.4)
        check_range("temperature_k", self.temperature_k, 150.0, 500.0, unit="K")
        check_range("atmosphere_mpa", self.atmosphere_mpa, 0.0, 1.0, lo_open=True, unit="MPa")
        if self.valve not in VALVES:
            raise InputError(f"valve must be one of {', '.join(VALVES)}, got {self.valve!r}",
                             param="valve")
        check_range("proportional_band_mpa", self.proportional_band_mpa, 0.0, 10.0,
                    lo_open=True, unit="MPa")
        check_range("dead_band_mpa", self.dead_band_mpa, 0.0, 1.0, unit="MPa")
        check_range("hysteresis_mpa", self.hysteresis_mpa, 0.0, 1.0, unit="MPa")
        if self.bandwidth_hz is not None:
            check_range("bandwidth_hz", self.bandwidth_hz, 0.0, 1e5, lo_open=True, unit="Hz")
        tp, tv = self.tube_table_pressure_mpa, self.tube_table_volume_mm3
        if tp or tv:
            p, v = check_series("tube_table_pressure_mpa", tp, "tube_table_volume_mm3", tv,
                                x_unit="MPa", y_unit="mm^3", min_points=2, y_min=0.0)
            if np.any(np.diff(v) < 0.0):
                i = int(np.flatnonzero(np.diff(v) < 0.0)[0])
                raise InputError(f"tube_table_volume_mm3 must not decrease with pressure, got "
                                 f"{v[i]:g} then {v[i + 1]:g} mm^3", param="tube_table_volume_mm3")
            # Normalised at construction, where a frozen dataclass sets its fields (through
            # object.__setattr__, as its generated __init__ does): the table stored as tuples of
            # float (hashable, comparable) whatever sequence is given.
            object.__setattr__(self, "tube_table_pressure_mpa", tuple(float(x) for x in p))
            object.__setattr__(self, "tube_table_volume_mm3", tuple(float(x) for x in v))
        vmin = self.line_volume_mm3 + (min(self.tube_table_volume_mm3) if tv
                                       else self.tube_volume_mm3)
        if vmin <= 0.0:
            raise InputError("line_volume_mm3 + tube volume must be > 0 mm^3, got 0",
                             param="line_volume_mm3")

    @cached_property
    def _table(self) -> _HermiteTable | None:
        """The tube volume table's interpolant (None without a table; built on first use)."""
        return _HermiteTable.build(self.tube_table_pressure_mpa, self.tube_table_volume_mm3)

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any]) -> PneumaticParams:
        """Build from a dict (e.g. a ``[plant]`` TOML table); orifices as sub-tables.

        Unknown keys raise :class:`InputError` naming them.

        Parameters
        ----------
        data : mapping
            Field name -> value as the fields (MPa, mm^3, K, Hz); ``fill`` and ``vent`` may
            be mappings of :class:`Orifice` fields (C in dm^3/(s bar), b unitless).

        Returns
        -------
        PneumaticParams

        Examples
        --------
        >>> pp = PneumaticParams.from_mapping({"fill": {"c_dm3_per_s_bar": 0.2, "b": 0.4}})
        >>> pp.fill.b, pp.supply_mpa
        (0.4, 0.6)
        """
        known = {f.name for f in fields(cls)}
        extra = sorted(set(data) - known)
        if extra:
            raise InputError(f"unknown pneumatic plant key(s) {', '.join(extra)}; known: "
                             f"{', '.join(sorted(known))}")
        kw = dict(data)
        for name in ("fill", "vent"):
            if isinstance(kw.get(name), Mapping):
                okeys = {f.name for f in fields(Orifice)}
                bad = sorted(set(kw[name]) - okeys)
                if bad:
                    raise InputError(f"unknown {name} orifice key(s) {', '.join(bad)}; known: "
                                     f"{', '.join(sorted(okeys))}", param=name)
                kw[name] = Orifice(**kw[name])
        for name in ("tube_table_pressure_mpa", "tube_table_volume_mm3"):
            if name in kw:
                kw[name] = tuple(kw[name])
        return cls(**kw)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict with unit-suffixed keys (MPa, mm^3, K, Hz; C in dm^3/(s bar))."""
        d = asdict(self)
        d["tube_table_pressure_mpa"] = list(self.tube_table_pressure_mpa)
        d["tube_table_volume_mm3"] = list(self.tube_table_volume_mm3)
        return d

    def tube_volume_at_mm3(self, pressure_mpa: float) -> float:
        """The tube's cavity volume in mm^3 at gauge pressure ``pressure_mpa`` (MPa).

        Parameters
        ----------
        pressure_mpa : float
            Gauge pressure in MPa.

        Returns
        -------
        float
            Volume in mm^3.

        Examples
        --------
        >>> PneumaticParams(tube_table_pressure_mpa=(0.0, 0.2),
        ...                 tube_table_volume_mm3=(2000.0, 2400.0)).tube_volume_at_mm3(0.1)
        2200.0
        """
        tab = self._table
        return self.tube_volume_mm3 if tab is None else tab.value(float(pressure_mpa))[0]

    def total_volume_mm3(self, pressure_mpa: float) -> float:
        """Line + tube volume in mm^3 at gauge pressure ``pressure_mpa`` (MPa).

        Parameters
        ----------
        pressure_mpa : float
            Gauge pressure in MPa.

        Returns
        -------
        float
            Volume in mm^3.

        Examples
        --------
        >>> PneumaticParams(line_volume_mm3=1000.0, tube_volume_mm3=500.0).total_volume_mm3(0.3)
        1500.0
        """
        return self.line_volume_mm3 + self.tube_volume_at_mm3(pressure_mpa)


@dataclass(frozen=True)
class _HermiteTable:
    """Monotone cubic Hermite (PCHIP knots and slopes), scalar evaluation for the ODE."""

    x: tuple[float, ...]
    y: tuple[float, ...]
    m: tuple[float, ...]

    @classmethod
    def build(cls, x: Sequence[float], y: Sequence[float]) -> _HermiteTable | None:
        if not x:
            return None
        from scipy.interpolate import PchipInterpolator

        xa, ya = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        m = PchipInterpolator(xa, ya).derivative()(xa)
        return cls(tuple(xa.tolist()), tuple(ya.tolist()), tuple(np.asarray(m).tolist()))

    def value(self, p: float) -> tuple[float, float]:
        """(V in mm^3, dV/dp in mm^3/MPa) at p (MPa)."""
        x, y, m = self.x, self.y, self.m
        if p <= x[0]:
            return y[0], 0.0
        if p >= x[-1]:
            return y[-1] + m[-1] * (p - x[-1]), m[-1]
        i = bisect.bisect_right(x, p) - 1
        h = x[i + 1] - x[i]
        s = (p - x[i]) / h
        s2, s3 = s * s, s * s * s
        v = ((2 * s3 - 3 * s2 + 1) * y[i] + (s3 - 2 * s2 + s) * h * m[i]
             + (-2 * s3 + 3 * s2) * y[i + 1] + (s3 - s2) * h * m[i + 1])
        dv = ((6 * s2 - 6 * s) * (y[i] - y[i + 1]) / h + (3 * s2 - 4 * s + 1) * m[i]
              + (3 * s2 - 2 * s) * m[i + 1])
        return v, dv


class PneumaticPlant:
    """The physical pneumatic plant, stepped like :class:`~exofric.control.PressurePlant`.

    Integrates dp/dt = n R T m_dot / (V(p) + n p_abs dV/dp) (gauge p in MPa) over each held
    command with an adaptive Rosenbrock method (ode23s, L-stable, error-controlled); the
    step size carries over between calls. With ``valve='regulator'`` the command is the
    regulator's target pressure (MPa); with ``'on-off'`` a command > 0 opens the fill port
    and one <= 0 the vent port.

    Parameters
    ----------
    params : PneumaticParams
        The plant.
    p0_mpa : float
        Initial gauge pressure in MPa (the regulator's filter and play start at it).
    rtol : float
        Relative tolerance of the integrator (unitless).
    atol_mpa : float
        Absolute tolerance of the integrator in MPa.

    Attributes
    ----------
    pressure_mpa : float
        Current gauge pressure in MPa.
    time_s : float
        Current time in s.
    n_steps : int
        Accepted integrator steps so far (count).

    Examples
    --------
    >>> plant = PneumaticPlant(PneumaticParams())
    >>> p = [plant.advance(0.3, 0.01) for _ in range(100)]   # regulator set to 0.3 MPa, 1 s
    >>> round(p[-1], 4)
    0.3
    """

    def __init__(self, params: PneumaticParams, p0_mpa: float = 0.0, *,
                 rtol: float = DEFAULT_RTOL, atol_mpa: float = DEFAULT_ATOL_MPA) -> None:
        if not isinstance(params, PneumaticParams):
            raise InputError(f"params must be PneumaticParams, got {type(params).__name__}",
                             param="params")
        self.params = params
        p0 = check_range("p0_mpa", p0_mpa, -params.atmosphere_mpa, 10.0, lo_open=True,
                         unit="MPa")
        self.rtol = check_range("rtol", rtol, 1e-13, 1e-2)
        self.atol_mpa = check_positive("atol_mpa", atol_mpa, "MPa")
        self.pressure_mpa = p0
        self.time_s = 0.0
        self.n_steps = 0
        self._filtered = p0       # filter state (MPa)
        self._play = p0           # backlash output (MPa)
        self._h: float | None = None
        pr = params
        t = pr.temperature_k
        self._kfill = _flow_factor(pr.fill.c_dm3_per_s_bar, t)
        self._kvent = _flow_factor(pr.vent.c_dm3_per_s_bar, t)
        self._gain = pr.polytropic_n * R_AIR_J_PER_KG_K * t * 1e3   # MPa mm^3 / kg
        self._psup = pr.supply_mpa + pr.atmosphere_mpa
        self._table = pr._table
        self._omega = None if pr.bandwidth_hz is None else 2.0 * math.pi * pr.bandwidth_hz

    # -- model ---------------------------------------------------------------------------
    def volume_mm3(self, pressure_mpa: ArrayLike) -> Any:
        """Total (line + tube) volume in mm^3 at gauge pressure(s) in MPa.

        Parameters
        ----------
        pressure_mpa : array_like
            Gauge pressure(s) in MPa.

        Returns
        -------
        float or ndarray
            Volume in mm^3 (float in, float out).

        Examples
        --------
        >>> PneumaticPlant(PneumaticParams()).volume_mm3(0.2)
        14816.4
        """
        return self._vec(pressure_mpa, 0)

    def compliance_mm3_per_mpa(self, pressure_mpa: ArrayLike) -> Any:
        """dV/dp of the tube in mm^3/MPa at gauge pressure(s) in MPa (0 for a constant volume).

        Parameters
        ----------
        pressure_mpa : array_like
            Gauge pressure(s) in MPa.

        Returns
        -------
        float or ndarray
            Compliance in mm^3/MPa.

        Examples
        --------
        >>> pp = PneumaticParams(tube_table_pressure_mpa=(0.0, 0.5),
        ...                      tube_table_volume_mm3=(2000.0, 3000.0))
        >>> PneumaticPlant(pp).compliance_mm3_per_mpa(0.25)
        2000.0
        """
        return self._vec(pressure_mpa, 1)

    def _vd(self, p: float) -> tuple[float, float]:
        line = self.params.line_volume_mm3
        if self._table is None:
            return line + self.params.tube_volume_mm3, 0.0
        v, dv = self._table.value(p)
        return line + v, dv

    def _vec(self, pressure_mpa: ArrayLike, which: int) -> Any:
        arr = np.asarray(pressure_mpa, dtype=float)
        out = np.array([self._vd(float(x))[which] for x in arr.ravel()]).reshape(arr.shape)
        return float(out) if arr.ndim == 0 else out

    @staticmethod
    def _orifice_flow(k: float, o: Orifice, pu: float, pd: float) -> float:
        """Scalar ISO 6358 flow (kg/s) with factor ``k`` (kg/(s MPa)); signed."""
        if pu >= pd:
            return k * pu * o._phi(pd / pu) if pu > 0.0 else 0.0
        return -k * pd * o._phi(pu / pd)

    def mass_flow_kg_per_s(self, opening: float, pressure_mpa: float) -> float:
        """Net mass flow into the volume in kg/s at a valve opening and gauge pressure.

        Parameters
        ----------
        opening : float
            Valve opening in [-1, 1] (unitless): > 0 the fill port (scaled), < 0 the vent.
        pressure_mpa : float
            Gauge pressure in MPa.

        Returns
        -------
        float
            Mass flow in kg/s (> 0 into the tube).

        Examples
        --------
        >>> pl = PneumaticPlant(PneumaticParams())
        >>> pl.mass_flow_kg_per_s(1.0, 0.0) > 0.0 > pl.mass_flow_kg_per_s(-1.0, 0.2)
        True
        """
        pr = self.params
        pa = pressure_mpa + pr.atmosphere_mpa
        if opening > 0.0:
            return opening * self._orifice_flow(self._kfill, pr.fill, self._psup, pa)
        if opening < 0.0:
            return opening * self._orifice_flow(self._kvent, pr.vent, pa, pr.atmosphere_mpa)
        return 0.0

    def _opening(self, target: float, p: float) -> float:
        pr = self.params
        e = target - p
        d = pr.dead_band_mpa
        if d > 0.0:
            e = e - d if e > d else (e + d if e < -d else 0.0)
        s = e / pr.proportional_band_mpa
        return 1.0 if s > 1.0 else (-1.0 if s < -1.0 else s)

    def _rhs_factory(self, command: float) -> tuple[Any, bool]:
        """f(tau, p) over the step (tau from its start) and whether it depends on tau."""
        pr = self.params
        gain = self._gain

        def dpdt(m: float, p: float) -> float:
            v, dv = self._vd(p)
            return gain * m / (v + pr.polytropic_n * (p + pr.atmosphere_mpa) * dv)

        if pr.valve == "on-off":
            s = 1.0 if command > 0.0 else -1.0
            return (lambda tau, p: dpdt(self.mass_flow_kg_per_s(s, p), p)), False
        half = 0.5 * pr.hysteresis_mpa
        y0 = self._play
        if self._omega is None:
            y = min(max(y0, command - half), command + half)
            return (lambda tau, p: dpdt(self.mass_flow_kg_per_s(self._opening(y, p), p),
                                        p)), False
        w, uf0 = self._omega, self._filtered

        def f(tau: float, p: float) -> float:
            uf = command + (uf0 - command) * math.exp(-w * tau)
            yy = min(max(y0, uf - half), uf + half)
            return dpdt(self.mass_flow_kg_per_s(self._opening(yy, p), p), p)

        return f, True

    # -- stepping ------------------------------------------------------------------------
    def advance(self, command_mpa: float, dt: float) -> float:
        """Hold ``command_mpa`` (MPa) for ``dt`` s; return the gauge pressure (MPa) at the end.

        Parameters
        ----------
        command_mpa : float
            The regulator's pressure set-point in MPa (``'on-off'``: > 0 fills, <= 0 vents),
            held over the step (zero-order hold).
        dt : float
            Step length in s (> 0).

        Returns
        -------
        float
            Gauge pressure in MPa at the end of the step.

        Examples
        --------
        >>> pl = PneumaticPlant(PneumaticParams(valve="on-off"))
        >>> round(pl.advance(1.0, 0.01), 4)          # 10 ms of choked filling from 0 MPa
        0.0236
        """
        if not math.isfinite(command_mpa):
            raise InputError(f"pressure command must be a finite number in MPa, got {command_mpa}")
        if not (dt > 0.0 and math.isfinite(dt)):
            raise InputError(f"dt (sample time) must be > 0 s, got {dt}")
        f, timedep = self._rhs_factory(float(command_mpa))
        self.pressure_mpa = self._integrate(f, timedep, self.pressure_mpa, float(dt))
        pr = self.params
        if pr.valve == "regulator":
            half = 0.5 * pr.hysteresis_mpa
            u = float(command_mpa)
            if self._omega is not None:
                u = u + (self._filtered - u) * math.exp(-self._omega * dt)
                self._filtered = u
            self._play = min(max(self._play, u - half), u + half)
        self.time_s += dt
        return self.pressure_mpa

    def _integrate(self, f: Any, timedep: bool, p: float, span: float) -> float:
        """ode23s (scalar) from 0 to ``span`` s; returns p(span)."""
        rtol, atol = self.rtol, self.atol_mpa
        h = span if self._h is None else self._h
        t = 0.0
        f0 = f(0.0, p)
        hmin = 1e-14 * max(span, 1.0)
        while t < span:
            hp = h                       # the proposal, kept if this step is truncated
            last = h >= span - t
            if last:
                h = span - t
            dp = 1e-7 * (abs(p) + 0.1)
            jac = (f(t, p + dp) - f0) / dp
            tt = 0.0
            if timedep:
                dtt = 1e-7 * max(span, h)
                tt = (f(t + dtt, p) - f0) / dtt
            w = 1.0 - h * _D * jac
            if w < 0.5:                   # growing mode: keep W well conditioned
                h = 0.5 / (_D * jac)
                last = False
                hp = h
                w = 0.5
            k1 = (f0 + h * _D * tt) / w
            f1 = f(t + 0.5 * h, p + 0.5 * h * k1)
            k2 = (f1 - k1) / w + k1
            pn = p + h * k2
            f2 = f(t + h, pn)
            k3 = (f2 - _E32 * (k2 - f1) - 2.0 * (k1 - f0) + h * _D * tt) / w
            err = abs(h / 6.0 * (k1 - 2.0 * k2 + k3)) / (atol + rtol * max(abs(p), abs(pn)))
            if err <= 1.0 or h <= hmin:
                t = span if last else t + h
                p, f0 = pn, f2
                self.n_steps += 1
                fac = 5.0 if err == 0.0 else min(5.0, max(0.2, 0.8 * err ** (-1.0 / 3.0)))
                h = max(hp, h * fac) if last else h * fac
            else:
                h = h * max(0.2, 0.8 * err ** (-1.0 / 3.0))
        self._h = h
        return p


# ---- the FE tube volume ------------------------------------------------------------------
def _cavity_area_mm2(nodes: NDArray[np.float64], quadratic: bool) -> float:
    """Area (mm^2) enclosed by the inner-surface polyline ``nodes`` (by angle, half model)
    closed along the symmetry plane; quadratic edges (x_a, x_mid, x_b) integrated exactly."""
    x, y = nodes[:, 0], nodes[:, 1]
    if not quadratic:
        xs, ys = np.append(x, x[0]), np.append(y, y[0])
        return 0.5 * float(np.sum(xs[:-1] * ys[1:] - xs[1:] * ys[:-1]))
    # 1/2 closed integral of (x dy - y dx) over each quadratic edge: degree 3 in the edge
    # parameter, exact with 2-point Gauss; plus the straight closing segment.
    g = np.array([-1.0, 1.0]) / math.sqrt(3.0)
    a, m, b = nodes[0:-2:2], nodes[1:-1:2], nodes[2::2]
    area = 0.0
    for s in g:
        n0, n1, n2 = 0.5 * s * (s - 1.0), 1.0 - s * s, 0.5 * s * (s + 1.0)
        d0, d1, d2 = s - 0.5, -2.0 * s, s + 0.5
        px = n0 * a[:, 0] + n1 * m[:, 0] + n2 * b[:, 0]
        py = n0 * a[:, 1] + n1 * m[:, 1] + n2 * b[:, 1]
        dx = d0 * a[:, 0] + d1 * m[:, 0] + d2 * b[:, 0]
        dy = d0 * a[:, 1] + d1 * m[:, 1] + d2 * b[:, 1]
        area += 0.5 * float(np.sum(px * dy - py * dx))
    area += 0.5 * float(x[-1] * y[0] - x[0] * y[-1])
    return area


def tube_volume_table(squeeze_result: SqueezeResult,
                      length_mm: float | None = None) -> tuple[NDArray[np.float64],
                                                               NDArray[np.float64]]:
    """The tube's cavity volume (mm^3) at each pressure of an FE squeeze result.

    The inner-surface nodes are those of the reference (half-model) mesh at the inner radius
    from the tube's centre; displaced, their boundary (quadratic edges for quad9, straight for
    quad4, closed along the symmetry plane x = 0) encloses half the cavity: its area (the
    shoelace/Green formula, exact on quadratic edges) is doubled and multiplied by the length.

    Parameters
    ----------
    squeeze_result : SqueezeResult
        From :func:`exofric.simulate.squeeze` with ``keep_fields=True`` (the displacements).
    length_mm : float or None
        Tube length in mm (default the structure's length).

    Returns
    -------
    pressure_mpa, volume_mm3 : ndarray
        The squeeze result's pressures (MPa) and the cavity volumes (mm^3).

    Raises
    ------
    InputError
        A result without displacements, or a bad length.

    Examples
    --------
    >>> from exofric.fe import MeshSpec
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import squeeze
    >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.0, 0.3], mesh=MeshSpec(2, 12),
    ...             gravity="none")
    >>> p, v = tube_volume_table(r)
    >>> round(float(v[0]), 1), bool(v[1] > v[0])   # pi 4.97^2 / 4 x 116 = 2250.4 mm^3 (exact)
    (2250.3, True)
    """
    if str(getattr(squeeze_result, "symmetry", "")).startswith("full"):
        raise InputError("squeeze_result is a full model (off-centre wire): use the centred "
                         "squeeze (wire_angle_deg = 0); the frictionless tube's cavity is the "
                         "same, turned", param="squeeze_result")
    disp = getattr(squeeze_result, "displacements", ())
    if not disp or len(disp) != len(squeeze_result.pressure_mpa):
        raise InputError("squeeze_result has no displacements: run squeeze with "
                         "keep_fields=True", param="squeeze_result")
    length = squeeze_result.length_mm if length_mm is None else length_mm
    length = check_positive("length_mm", length, "mm")
    nodes = np.asarray(squeeze_result.nodes, dtype=float)
    a = 0.5 * squeeze_result.structure.tube_id_mm
    yc = 0.5 * (nodes[:, 1].min() + nodes[:, 1].max())   # outer nodes span yc -/+ B on x = 0
    r = np.hypot(nodes[:, 0], nodes[:, 1] - yc)
    inner = np.flatnonzero(np.abs(r - a) <= 1e-9 * max(a, 1.0) + 1e-12)
    if inner.size < 3:
        raise InputError("squeeze_result: could not find the tube's inner surface nodes",
                         param="squeeze_result")
    ang = np.arctan2(nodes[inner, 1] - yc, nodes[inner, 0])
    inner = inner[np.argsort(ang)]
    quadratic = squeeze_result.elements.shape[1] == 9 and inner.size % 2 == 1
    vol = np.array([2.0 * _cavity_area_mm2(nodes[inner] + np.asarray(u)[inner], quadratic)
                    for u in disp]) * length
    return np.asarray(squeeze_result.pressure_mpa, dtype=float).copy(), vol


# ---- charge / discharge experiments --------------------------------------------------------
def simulate_charge(
    params: PneumaticParams,
    *,
    duration_s: float = 2.0,
    dt_s: float = 0.01,
    step_s: float = 0.1,
    fill_s: float | None = None,
    delay_s: float = 0.0,
    noise_mpa: float = 0.0,
    seed: int = 0,
) -> pd.DataFrame:
    """A charge-then-discharge log of on/off valve steps (for tests and ``identify --charge``).

    Vent open (command 0 MPa) until ``step_s``, the fill port open (command = supply) for
    ``fill_s``, then the vent again. Row k holds the time t_k, the pressure sampled at t_k
    (plus Gaussian noise) and the command held from t_k on (the valves act ``delay_s`` later).

    Parameters
    ----------
    params : PneumaticParams
        The plant (its orifices, volumes and supply; the valve is forced to ``'on-off'``).
        From one orifice and a volume: ``PneumaticParams(fill=o, vent=o, line_volume_mm3=v,
        tube_volume_mm3=0)``.
    duration_s : float
        Log length in s.
    dt_s : float
        Sample time in s.
    step_s : float
        Time of the fill step in s.
    fill_s : float or None
        How long the fill port stays open in s (default: half the time after the step).
    delay_s : float
        Valve dead time in s (>= 0).
    noise_mpa : float
        Standard deviation of the pressure sensor noise in MPa (>= 0).
    seed : int
        Seed of the noise generator.

    Returns
    -------
    pandas.DataFrame
        Columns ``time_s``, ``pressure_mpa``, ``command_mpa``.

    Examples
    --------
    >>> df = simulate_charge(PneumaticParams(), duration_s=1.0)
    >>> list(df.columns), len(df), round(float(df.pressure_mpa.max()), 2)
    (['time_s', 'pressure_mpa', 'command_mpa'], 101, 0.6)
    """
    import pandas as pd

    check_range("duration_s", duration_s, 0.0, 1e5, lo_open=True, unit="s")
    check_range("dt_s", dt_s, 0.0, duration_s, lo_open=True, unit="s")
    check_range("step_s", step_s, 0.0, duration_s, unit="s")
    fill = 0.5 * (duration_s - step_s) if fill_s is None else fill_s
    check_range("fill_s", fill, 0.0, duration_s, unit="s")
    check_range("delay_s", delay_s, 0.0, duration_s, unit="s")
    check_range("noise_mpa", noise_mpa, 0.0, 1.0, unit="MPa")
    n = int(round(duration_s / dt_s)) + 1
    t = np.arange(n) * dt_s
    cmd = np.where((t >= step_s - 1e-12) & (t < step_s + fill - 1e-12), params.supply_mpa, 0.0)
    plant = PneumaticPlant(replace(params, valve="on-off"), 0.0, rtol=1e-8, atol_mpa=1e-10)
    change = np.flatnonzero(cmd[1:] != cmd[:-1]) + 1
    switch_t, switch_u = t[change] + delay_s, cmd[change]
    p = np.empty(n)
    p[0] = 0.0
    held = float(cmd[0])
    for k in range(n - 1):
        a, b = t[k], t[k + 1]
        inside = np.flatnonzero((switch_t >= a) & (switch_t < b))
        for j in inside:                      # the valves switch delay_s after the command
            if switch_t[j] > a:
                plant.advance(held, float(switch_t[j] - a))
                a = float(switch_t[j])
            held = float(switch_u[j])
        p[k + 1] = plant.advance(held, float(b - a))
    rng = np.random.default_rng(seed)
    if noise_mpa > 0.0:
        p = p + rng.normal(0.0, noise_mpa, n)
    return pd.DataFrame({"time_s": t, "pressure_mpa": p, "command_mpa": cmd})


@checked_init
@dataclass(frozen=True)
class ChargeFit(DisplayMixin):
    """Sonic conductances and volume fitted to charge/discharge transients, and the fit.

    Attributes
    ----------
    c_fill_dm3_per_s_bar, c_vent_dm3_per_s_bar : float
        Sonic conductance C of the fill and vent ports in dm^3/(s bar) (NaN: no such
        transient in the data).
    volume_mm3 : float
        Total (line + tube) volume in mm^3, excluding the runs' added volumes.
    critical_ratio : float
        Critical pressure ratio b (unitless), fixed or fitted (``b_fitted``).
    b_fitted : bool
        Whether b was fitted (else fixed at the given value).
    delay_s : float
        Valve dead time in s (fitted, >= 0).
    p0_mpa : tuple of float
        Fitted initial gauge pressure of each run (MPa).
    stderr_c_fill, stderr_c_vent : float
        Standard errors of the conductances in dm^3/(s bar) (NaN when fixed or absent).
    stderr_volume_mm3 : float
        Standard error of the volume in mm^3 (NaN when fixed).
    stderr_critical_ratio : float
        Standard error of b (unitless; NaN when fixed).
    stderr_delay_s : float
        Standard error of the dead time in s.
    fixed : tuple of str
        Parameters given rather than fitted (``'c_fill'``, ``'volume'``).
    r2 : float
        Coefficient of determination of the pressure fit (unitless).
    rmse_mpa : float
        Root-mean-square residual in MPa.
    n_samples : int
        Samples fitted (count).
    time_s, pressure_mpa, fitted_mpa : ndarray
        The samples (s, MPa) and the model's pressure (MPa), runs concatenated.
    run : ndarray of int
        Run index of each sample.
    fopdt : IdentifiedPlant or None
        The first-order-plus-dead-time fit (:func:`identify_step`) of the first run, for
        comparison (None if it could not be fitted).

    Examples
    --------
    >>> df = simulate_charge(PneumaticParams(), duration_s=1.5)
    >>> fit = identify_charge(df.time_s, df.pressure_mpa, command_mpa=df.command_mpa,
    ...                       supply_mpa=0.6, volume_mm3=14816.4, critical_ratio=0.3)
    >>> round(fit.c_fill_dm3_per_s_bar, 4), round(fit.c_vent_dm3_per_s_bar, 4)
    (0.05, 0.05)
    """

    c_fill_dm3_per_s_bar: float
    c_vent_dm3_per_s_bar: float
    volume_mm3: float
    critical_ratio: float
    b_fitted: bool
    delay_s: float
    p0_mpa: tuple[float, ...]
    stderr_c_fill: float
    stderr_c_vent: float
    stderr_volume_mm3: float
    stderr_critical_ratio: float
    stderr_delay_s: float
    fixed: tuple[str, ...]
    r2: float
    rmse_mpa: float
    n_samples: int
    time_s: NDArray[np.float64] = field(repr=False)
    pressure_mpa: NDArray[np.float64] = field(repr=False)
    fitted_mpa: NDArray[np.float64] = field(repr=False)
    run: NDArray[np.int64] = field(repr=False)
    fopdt: IdentifiedPlant | None = None

    @property
    def residuals_mpa(self) -> NDArray[np.float64]:
        """Measured minus fitted pressure in MPa, per sample."""
        return np.asarray(self.pressure_mpa - self.fitted_mpa, dtype=float)

    def to_params(self, base: PneumaticParams | None = None) -> PneumaticParams:
        """A :class:`PneumaticParams` with the fitted ports and the total volume as the line.

        Parameters
        ----------
        base : PneumaticParams or None
            Supplies the other fields (supply in MPa, regulator, gas); default the defaults.

        Returns
        -------
        PneumaticParams

        Examples
        --------
        >>> df = simulate_charge(PneumaticParams(), duration_s=1.5)
        >>> fit = identify_charge(df.time_s, df.pressure_mpa, command_mpa=df.command_mpa,
        ...                       supply_mpa=0.6, volume_mm3=14816.4)
        >>> round(fit.to_params().fill.c_dm3_per_s_bar, 3)
        0.05
        """
        base = base or PneumaticParams()
        b = self.critical_ratio
        fill = Orifice(self.c_fill_dm3_per_s_bar, b, max(base.fill.laminar_ratio, b + 1e-6)) \
            if math.isfinite(self.c_fill_dm3_per_s_bar) else base.fill
        vent = Orifice(self.c_vent_dm3_per_s_bar, b, max(base.vent.laminar_ratio, b + 1e-6)) \
            if math.isfinite(self.c_vent_dm3_per_s_bar) else base.vent
        return replace(base, fill=fill, vent=vent, line_volume_mm3=self.volume_mm3,
                       tube_volume_mm3=0.0, tube_table_pressure_mpa=(),
                       tube_table_volume_mm3=())

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (C in dm^3/(s bar), mm^3, s, MPa) with the FOPDT fit beside it."""
        keys = ("c_fill_dm3_per_s_bar", "c_vent_dm3_per_s_bar", "volume_mm3", "critical_ratio",
                "b_fitted", "delay_s", "stderr_c_fill", "stderr_c_vent", "stderr_volume_mm3",
                "stderr_critical_ratio", "stderr_delay_s", "r2", "rmse_mpa", "n_samples")
        d: dict[str, Any] = {k: getattr(self, k) for k in keys}
        d["p0_mpa"] = list(self.p0_mpa)
        d["fixed"] = list(self.fixed)
        d["fopdt"] = None if self.fopdt is None else self.fopdt.to_dict()
        return d

    def to_frame(self) -> pd.DataFrame:
        """Samples, fit and residuals as a DataFrame (s, MPa).

        Columns: ``run``, ``time_s``, ``pressure_mpa``, ``fitted_mpa``, ``residual_mpa``.

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> df = simulate_charge(PneumaticParams(), duration_s=1.0)
        >>> fit = identify_charge(df.time_s, df.pressure_mpa, command_mpa=df.command_mpa,
        ...                       supply_mpa=0.6, volume_mm3=14816.4)
        >>> list(fit.to_frame().columns)
        ['run', 'time_s', 'pressure_mpa', 'fitted_mpa', 'residual_mpa']
        """
        import pandas as pd

        return pd.DataFrame({"run": self.run, "time_s": self.time_s,
                             "pressure_mpa": self.pressure_mpa, "fitted_mpa": self.fitted_mpa,
                             "residual_mpa": self.residuals_mpa})


def _is_runs(x: Any) -> bool:
    """True for a sequence of 1-D series (several runs), False for one series."""
    if isinstance(x, list | tuple) and len(x) > 0:
        return np.ndim(x[0]) == 1
    return False


def _onoff_model(t: NDArray[np.float64], cmd: NDArray[np.float64], p0: float, delay: float,
                 kf: float, kv: float, b: float, vol: float, n: float, temp: float,
                 psup_abs: float, patm: float, rl: float) -> NDArray[np.float64]:
    """Pressure (MPa) at ``t`` of a fixed volume behind on/off ports, the command's state
    switching ``delay`` s after each change (LSODA per segment, tight tolerances)."""
    from scipy.integrate import solve_ivp

    gain = n * R_AIR_J_PER_KG_K * temp * 1e3 / vol
    fo = Orifice(1.0, b, rl)

    def phi(r: float) -> float:
        return fo._phi(r)

    def rhs_fill(_t: float, y: NDArray[np.float64]) -> list[float]:
        pa = y[0] + patm
        m = kf * psup_abs * phi(pa / psup_abs) if pa <= psup_abs else -kf * pa * phi(psup_abs / pa)
        return [gain * m]

    def rhs_vent(_t: float, y: NDArray[np.float64]) -> list[float]:
        pa = y[0] + patm
        m = -kv * pa * phi(patm / pa) if pa >= patm else kv * patm * phi(pa / patm)
        return [gain * m]

    state = cmd > 0.0
    change = np.flatnonzero(state[1:] != state[:-1]) + 1
    bounds = np.concatenate([[t[0]], t[change] + delay, [np.inf]])
    states = np.concatenate([[state[0]], state[change]])
    out = np.empty_like(t)
    p = p0
    for i, st in enumerate(states):
        a, b = float(bounds[i]), float(bounds[i + 1])
        if a > t[-1]:
            break
        sel = (t >= a) & (t < b) if i > 0 else t < b
        end = min(b, float(t[-1]))
        ev = t[sel]
        if end <= a:
            out[sel] = p
            continue
        tev = ev if ev.size and ev[-1] >= end else np.append(ev, end)
        sol = solve_ivp(rhs_fill if st else rhs_vent, (a, end), [p], method="LSODA",
                        t_eval=tev, rtol=1e-10, atol=1e-12)
        y = sol.y[0]
        out[sel] = y[: ev.size]
        p = float(y[-1])
    return out


def identify_charge(
    time_s: Any,
    pressure_mpa: Any,
    *,
    supply_mpa: float,
    command_mpa: Any = None,
    volume_mm3: float | None = None,
    c_dm3_per_s_bar: float | None = None,
    added_volume_mm3: float | Sequence[float] = 0.0,
    critical_ratio: float = DEFAULT_CRITICAL_RATIO,
    fit_b: bool = False,
    polytropic_n: float = 1.0,
    temperature_k: float = T0_K,
    atmosphere_mpa: float = ATMOSPHERE_MPA,
) -> ChargeFit:
    """Fit the valve's sonic conductance C and the volume to charge/discharge transients.

    Model: a fixed volume V (+ a run's known added volume) behind an on/off fill port from
    the supply and a vent port to the atmosphere, ISO 6358 flow (:class:`Orifice`), gas law
    with exponent n; the ports switch ``delay_s`` after each command change (command > 0
    opens the fill port, <= 0 the vent). Fitted by nonlinear least squares on the pressure
    (``scipy.optimize.least_squares``, log-parameters; standard errors from s^2 (J^T J)^-1):
    C of each port present, V, the dead time, each run's initial pressure, and b only with
    ``fit_b`` (by default b is fixed at ``critical_ratio``: it is weakly determined by a
    noisy charge curve).

    Identifiability: a fixed volume's pressure depends on C and V only through C / V. So
    either V (``volume_mm3``) or C of the fill port (``c_dm3_per_s_bar``) must be given, or
    the runs must include at least two different known ``added_volume_mm3`` (e.g. one run
    with a calibrated reservoir added); otherwise :class:`InputError` says so.

    Beside it, the first-order-plus-dead-time fit (:func:`identify_step`) of the first run is
    returned in ``fopdt``.

    Parameters
    ----------
    time_s, pressure_mpa : array_like or sequence of array_like
        One run (time in s, strictly increasing; gauge pressure in MPa) or a list of runs.
    supply_mpa : float
        Supply pressure (gauge) in MPa.
    command_mpa : array_like, sequence of array_like or None
        On/off command per sample in MPa (> 0: fill), held from its sample time on. None: one
        valve step at t = 0 s, a charge if the pressure rises, else a discharge.
    volume_mm3 : float or None
        Known total volume in mm^3 (then not fitted).
    c_dm3_per_s_bar : float or None
        Known sonic conductance of the fill port in dm^3/(s bar) (then not fitted).
    added_volume_mm3 : float or sequence of float
        Known volume added in each run, mm^3 (>= 0).
    critical_ratio : float
        Critical pressure ratio b (unitless), fixed, or the start value with ``fit_b``.
    fit_b : bool
        Fit b (one value for both ports).
    polytropic_n : float
        Polytropic exponent n (unitless, 1 .. 1.4).
    temperature_k : float
        Gas temperature in K.
    atmosphere_mpa : float
        Absolute atmospheric pressure in MPa.

    Returns
    -------
    ChargeFit

    Raises
    ------
    InputError
        Mismatched or too short series (< 10 samples a run), no transient, pressure above
        the supply, or C and V not separately identifiable.

    Examples
    --------
    >>> pp = PneumaticParams(fill=Orifice(0.08), vent=Orifice(0.05))
    >>> df = simulate_charge(pp, duration_s=2.0)
    >>> fit = identify_charge(df.time_s, df.pressure_mpa, command_mpa=df.command_mpa,
    ...                       supply_mpa=0.6, c_dm3_per_s_bar=0.08)
    >>> round(fit.volume_mm3), round(fit.c_vent_dm3_per_s_bar, 4), round(fit.fopdt.r2, 2)
    (14816, 0.05, 0.98)
    """
    from scipy.optimize import least_squares

    sup = check_range("supply_mpa", supply_mpa, 0.0, 10.0, lo_open=True, unit="MPa")
    check_range("polytropic_n", polytropic_n, 1.0, 1.4)
    check_range("temperature_k", temperature_k, 150.0, 500.0, unit="K")
    patm = check_range("atmosphere_mpa", atmosphere_mpa, 0.0, 1.0, lo_open=True, unit="MPa")
    b0 = check_range("critical_ratio", critical_ratio, 0.0, 0.99, hi_open=True)
    data, added, step_only = _charge_runs(time_s, pressure_mpa, command_mpa, added_volume_mm3,
                                          sup)
    fit_v, fit_cf = volume_mm3 is None, c_dm3_per_s_bar is None
    if fit_v and fit_cf and np.unique(added).size < 2:
        raise InputError("C and the volume are not separately identifiable from one volume's "
                         "transients (only C/V is): give volume_mm3 or c_dm3_per_s_bar, or runs "
                         "with two different known added_volume_mm3", param="volume_mm3")
    v_given = math.nan if volume_mm3 is None else check_positive("volume_mm3", volume_mm3,
                                                                  "mm^3")
    c_given = math.nan if c_dm3_per_s_bar is None else check_positive(
        "c_dm3_per_s_bar", c_dm3_per_s_bar, "dm^3/(s bar)")
    gas = _ChargeGas(sup + patm, patm, polytropic_n, temperature_k)
    params = _charge_parameters(data, gas, v_given, c_given, b0, fit_b)
    p_all = np.concatenate([p for _, p, _ in data])

    def resid(x: NDArray[np.float64]) -> NDArray[np.float64]:
        d = params.unpack(x)
        return np.concatenate(_charge_model(d, data, added, gas, v_given, c_given, b0)) - p_all

    sol = least_squares(resid, params.x0, bounds=(params.lo, params.hi),
                        diff_step=1e-6, x_scale="jac", xtol=1e-12, ftol=1e-12, gtol=1e-12,
                        max_nfev=400)
    r = resid(sol.x)
    se = standard_errors(lsq_covariance(sol.jac, residual_variance(r, len(params.names),
                                                                   min_dof=1)))
    d = params.unpack(sol.x)
    sed = dict(zip(params.names, (float(v) for v in se), strict=True))
    nan = math.nan
    cf = math.exp(d["log_cf"]) if "log_cf" in d else c_given
    cvnt = math.exp(d["log_cv"]) if "log_cv" in d else nan
    vol = math.exp(d["log_v"]) if "log_v" in d else v_given
    ss_tot = float(np.sum((p_all - p_all.mean()) ** 2))
    fixed = tuple(k for k, f in (("c_fill", not fit_cf), ("volume", not fit_v)) if f)
    return ChargeFit(
        c_fill_dm3_per_s_bar=cf, c_vent_dm3_per_s_bar=cvnt, volume_mm3=vol,
        critical_ratio=d.get("b", b0), b_fitted=fit_b, delay_s=d["delay"],
        p0_mpa=tuple(d[f"p0_{i}"] for i in range(len(data))),
        stderr_c_fill=cf * sed["log_cf"] if "log_cf" in sed else nan,
        stderr_c_vent=cvnt * sed["log_cv"] if "log_cv" in sed else nan,
        stderr_volume_mm3=vol * sed["log_v"] if "log_v" in sed else nan,
        stderr_critical_ratio=sed.get("b", nan), stderr_delay_s=sed["delay"],
        fixed=fixed, r2=1.0 - float(r @ r) / ss_tot if ss_tot > 0 else nan,
        rmse_mpa=float(np.sqrt(np.mean(r**2))), n_samples=int(r.size),
        time_s=np.concatenate([t for t, _, _ in data]), pressure_mpa=p_all,
        fitted_mpa=r + p_all,
        run=np.concatenate([np.full(t.size, i, dtype=np.int64)
                            for i, (t, _, _) in enumerate(data)]),
        fopdt=_first_run_fopdt(data[0], step_only),
    )


_Run = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]


def _charge_runs(time_s: Any, pressure_mpa: Any, command_mpa: Any, added_volume_mm3: Any,
                 sup: float) -> tuple[list[_Run], NDArray[np.float64], bool]:
    """Validated runs (t s, p MPa, on/off command), added volumes (mm^3), whether the
    commands were implied (one valve step at t = 0) rather than given."""
    runs_t = list(time_s) if _is_runs(time_s) else [time_s]
    runs_p = list(pressure_mpa) if _is_runs(pressure_mpa) else [pressure_mpa]
    if len(runs_p) != len(runs_t):
        raise InputError(f"pressure_mpa has {len(runs_p)} runs but time_s has {len(runs_t)}",
                         param="pressure_mpa")
    nr = len(runs_t)
    if command_mpa is None:
        runs_u: list[Any] = [None] * nr
    else:
        runs_u = list(command_mpa) if _is_runs(command_mpa) else [command_mpa]
        if len(runs_u) != nr:
            raise InputError(f"command_mpa has {len(runs_u)} runs but time_s has {nr}",
                             param="command_mpa")
    added = np.broadcast_to(np.asarray(added_volume_mm3, dtype=float), (nr,)).copy() \
        if np.ndim(added_volume_mm3) == 0 else np.asarray(added_volume_mm3, dtype=float)
    if added.size != nr or not np.all(np.isfinite(added)) or np.any(added < 0.0):
        raise InputError(f"added_volume_mm3 must be {nr} value(s) >= 0 mm^3, got "
                         f"{added_volume_mm3!r}", param="added_volume_mm3")
    return [_charge_run(t, p, u, sup) for t, p, u in zip(runs_t, runs_p, runs_u, strict=True)], \
        added, command_mpa is None


def _charge_run(time_s: Any, pressure_mpa: Any, command_mpa: Any, sup: float) -> _Run:
    """One run checked: series, a valve switch, no pressure above the supply, a transient."""
    t, p = check_series("time_s", time_s, "pressure_mpa", pressure_mpa, x_unit="s",
                        y_unit="MPa", min_points=10, where="charge log")
    if command_mpa is None:
        if not (t[0] <= 0.0 < t[-1]):
            raise InputError("without command_mpa the valve step is at t = 0 s: time_s "
                             "must span it", param="time_s")
        rising = float(np.mean(p[-max(3, p.size // 20):])) > float(np.mean(p[:3]))
        u = np.where(t >= 0.0, 1.0 if rising else 0.0, 0.0 if rising else 1.0)
    else:
        _, u = check_series("time_s", t, "command_mpa", command_mpa, x_unit="s",
                            y_unit="MPa", where="charge log")
    st = u > 0.0
    if not np.any(st[1:] != st[:-1]):
        raise InputError("command_mpa never switches the valves: no transient to fit",
                         param="command_mpa")
    top = float(np.median(np.sort(p)[-min(10, p.size):]))
    if top > 1.02 * sup + 0.005:
        raise InputError(f"pressure_mpa rises to {top:g} MPa, above the supply "
                         f"{sup:g} MPa: wrong supply_mpa or units", param="pressure_mpa")
    resid_noise = float(np.median(np.abs(np.diff(p)))) * 1.5
    if float(np.ptp(p)) <= max(10.0 * resid_noise, 1e-3 * sup):
        raise InputError("pressure_mpa shows no charge or discharge transient",
                         param="pressure_mpa")
    return t, p, u


@dataclass(frozen=True)
class _ChargeGas:
    """The gas side of a charge fit: absolute supply and atmosphere (MPa), n, T (K)."""

    supply_abs_mpa: float
    atmosphere_mpa: float
    polytropic_n: float
    temperature_k: float


@dataclass(frozen=True)
class _ChargeParameters:
    """The fitted parameters of a charge fit: names, start values and bounds."""

    names: tuple[str, ...]
    x0: NDArray[np.float64]
    lo: NDArray[np.float64]
    hi: NDArray[np.float64]

    def unpack(self, x: NDArray[np.float64]) -> dict[str, float]:
        return dict(zip(self.names, (float(v) for v in x), strict=True))


def _charge_parameters(data: list[_Run], gas: _ChargeGas, v_given: float, c_given: float,
                       b0: float, fit_b: bool) -> _ChargeParameters:
    """Which parameters to fit, with start values (V from the given C or C from the given V,
    via the initial charge slope) and bounds; log-parameters for C and V."""
    sup = gas.supply_abs_mpa - gas.atmosphere_mpa
    fit_v, fit_cf = math.isnan(v_given), math.isnan(c_given)
    # a port is fitted when a run switches it open, or starts with it open away from its end
    has_fill = any(np.any(np.diff((u > 0.0).astype(int)) > 0)
                   or (u[0] > 0.0 and p[0] < 0.9 * sup) for _, p, u in data)
    has_vent = any(np.any(np.diff((u > 0.0).astype(int)) < 0)
                   or (u[0] <= 0.0 and p[0] > 0.1 * sup) for _, p, u in data)
    gain0 = gas.polytropic_n * R_AIR_J_PER_KG_K * gas.temperature_k * 1e3
    k1 = _flow_factor(1.0, gas.temperature_k)
    rate = []
    for t, p, u in data:
        i0 = int(np.flatnonzero(u > 0.0)[0]) if np.any(u > 0.0) else 0
        seg = p[i0: i0 + max(5, p.size // 10)]
        dt = float(np.median(np.diff(t)))
        slope = float(np.ptp(seg)) / max(dt * (seg.size - 1), 1e-9)
        rate.append(slope / (gain0 * k1 * gas.supply_abs_mpa))   # = C / V per C unit
    cv = max(float(np.median(rate)), 1e-12)
    v_start = v_given if not fit_v else (c_given / cv if not fit_cf else 0.05 / cv)
    c_start = c_given if not fit_cf else cv * v_start
    rows: list[tuple[str, float, float, float]] = []
    if fit_cf and has_fill:
        rows.append(("log_cf", math.log(c_start), -20.0, 10.0))
    if has_vent:
        rows.append(("log_cv", math.log(c_start), -20.0, 10.0))
    if fit_v:
        rows.append(("log_v", math.log(v_start), 0.0, 30.0))
    if fit_b:
        rows.append(("b", b0, 0.0, 0.95))
    span = min(float(t[-1] - t[0]) for t, _, _ in data)
    rows.append(("delay", 0.0, 0.0, 0.2 * span))
    for i, (_, p, _) in enumerate(data):
        rows.append((f"p0_{i}", float(np.median(p[:3])), -gas.atmosphere_mpa + 1e-3, sup + 0.5))
    lo = np.array([r[2] for r in rows])
    hi = np.array([r[3] for r in rows])
    x0 = np.clip([r[1] for r in rows], lo + 1e-9, hi - 1e-9)
    return _ChargeParameters(tuple(r[0] for r in rows), x0, lo, hi)


def _charge_model(d: dict[str, float], data: list[_Run], added: NDArray[np.float64],
                  gas: _ChargeGas, v_given: float, c_given: float,
                  b0: float) -> list[NDArray[np.float64]]:
    """The modelled pressure (MPa) of every run at the parameters ``d``."""
    cf = math.exp(d["log_cf"]) if "log_cf" in d else (c_given if not math.isnan(c_given)
                                                      else 1.0)
    cvnt = math.exp(d["log_cv"]) if "log_cv" in d else 1.0
    vol = math.exp(d["log_v"]) if "log_v" in d else v_given
    b = d.get("b", b0)
    tk = gas.temperature_k
    return [_onoff_model(t, u, d[f"p0_{i}"], d["delay"], _flow_factor(cf, tk),
                         _flow_factor(cvnt, tk), b, vol + float(added[i]), gas.polytropic_n, tk,
                         gas.supply_abs_mpa, gas.atmosphere_mpa,
                         max(DEFAULT_LAMINAR_RATIO, b + 1e-6))
            for i, (t, _, u) in enumerate(data)]


def _first_run_fopdt(run: _Run, step_only: bool) -> IdentifiedPlant | None:
    """The first-order-plus-dead-time fit of the first run, None where it does not apply."""
    t0, p0, u0 = run
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", PlausibilityWarning)
            return identify_step(t0, p0, None if step_only else u0)
    except (InputError, ValueError, np.linalg.LinAlgError):
        return None
