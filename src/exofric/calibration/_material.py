"""Joint material calibration: inflation, tensile and ring tests and a Shore prior, at once.

One hyperelastic model (neo-Hookean, Mooney-Rivlin, Yeoh, Ogden 1-3) and, optionally, the tube's
inner diameter are fitted to any combination of

* **inflation** curves (outer diameter in mm against pressure in MPa; the FE
  :func:`exofric.simulate.inflate` in the loop, plane strain or closed/open ends);
* **tensile** curves (nominal stress in MPa against stretch; uniaxial, equibiaxial, planar;
  the model's closed forms);
* **ring** tests (one pin's force in N against pin displacement in mm, a ring cut from the tube
  pulled over two pins; the FE ring test in the loop);
* a **Shore A prior**: a residual on ``ln mu`` with ``mu = E(Shore) / 3``
  (:func:`exofric.material.shore_to_modulus`).

Residuals (all unitless, so datasets of different units combine): inflation
``(OD_sim / OD_meas - 1) / s_infl`` (default ``s_infl`` = 0.5 % of the OD, the paper's
calibration target of 0.5 % average error); tensile ``(P_sim - P_meas) / (s_t max|P_meas|)``
per mode and ring ``(F_sim - F_meas) / (s_r max|F_meas|)`` (defaults 2 % of the largest
value: of all tensile modes together, of the ring curve; a load cell's error is about the same
size at every point, and the curves start at 0); the prior ``(ln mu - ln mu_S) / s_ln`` with
``s_ln`` the change of ``ln E`` over +-``shore_sd`` Shore A (default 2.5 Shore A, a default:
set it from your own repeat readings).
The tensile residuals are absolute (MPa) up to one factor, so the tensile-only optimum is
that of :func:`exofric.material.fit_material` with ``residuals="absolute"``.

Standard errors: ``sqrt(diag(s^2 (J^T J)^+))`` from the Jacobian ``J`` of the scaled residuals
at the optimum (central differences). By default (``stderr_from="residuals"``) ``s^2 = 2 cost /
(n - p)``: the noise levels are only relative weights and the scatter of the fit sets the size.
With ``stderr_from="noise"`` (the default when any noise level is given) ``s^2 = 1``: the noise
levels are believed.

Identifiability (:class:`Identifiability`): the eigen-decomposition of ``J_r^T J_r`` in relative
parameters (each parameter divided by its magnitude at the optimum, so for positive parameters
the directions are those of ``ln p``), its condition number, the worst-determined direction and
its standard deviation, the most correlated pair, and a profile of the misfit along that
direction (the forward models re-run at each point): a flat profile is a direction the data do
not see.

Units: mm, N, MPa, s; stretches, Ogden exponents and scaled residuals unitless.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from exofric import defaults as D
from exofric._display import DisplayMixin
from exofric._lsq import correlation as correlation_matrix
from exofric._lsq import lsq_covariance, standard_errors
from exofric._validate import checked_init
from exofric.errors import (
    ConvergenceError,
    InputError,
    check_positive,
    check_range,
    warn_implausible,
)
from exofric.fe import check_ends
from exofric.material import HYPERELASTIC_MODELS, HyperelasticModel, StabilityCheck

if TYPE_CHECKING:
    import pandas as pd

    from exofric.calibration._result import InflationData
    from exofric.fe import MeshSpec

__all__ = [
    "CONDITION_LIMIT",
    "CORRELATION_LIMIT",
    "DatasetFit",
    "Identifiability",
    "MaterialCalibration",
    "MisfitProfile",
    "RingTest",
    "calibrate_material",
]

#: |correlation| above which two parameters count as not separately identifiable (unitless).
CORRELATION_LIMIT = 0.99
#: Condition number of the relative-parameter Jacobian above which the fit counts as not
#: identifiable (unitless; 1e3 = a direction known 1000 times worse than the best one).
CONDITION_LIMIT = 1e3
#: Default noise levels (unitless fractions): inflation of the OD, tensile and ring of the
#: curve's largest stress/force.
DEFAULT_NOISE_REL: dict[str, float] = {"inflation": 0.005, "tensile": 0.02, "ring": 0.02}
#: Default Shore A uncertainty of the prior (Shore A): a default, not a measured spread.
DEFAULT_SHORE_SD = 2.5

_FIT_COLUMN = {"outer_diameter_mm": "outer_diameter_fit_mm", "stress_mpa": "stress_fit_mpa",
               "force_n": "force_fit_n"}
_FAILED = 1e4  # scaled residual of a forward model that failed (no equilibrium, bad material)
_MODE_NAMES = ("uniaxial", "biaxial", "planar")


# --------------------------------------------------------------------------------------------
# Ring test data


@checked_init
@dataclass(frozen=True)
class RingTest:
    """A ring tensile test: a ring cut from the tube, pulled over two pins; force per displacement.

    Attributes
    ----------
    displacement_mm : numpy.ndarray
        Pin displacement (mm), >= 0 and strictly increasing (one loading curve), as
        :func:`exofric.simulate.ring_test` defines it.
    force_n : numpy.ndarray
        Measured force (N) of one pin at each displacement.
    ring_width_mm : float
        Axial width of the ring (mm), > 0.
    pin_mm : float
        Pin diameter (mm), > 0 and < the ring's inner diameter.
    ring_od_mm, ring_id_mm : float or None
        Ring outer and inner diameters (mm). None: the tube's (the OD given to
        :func:`calibrate_material`, the fitted or given tube ID).
    section : str
        ``plane-stress`` (a thin ring, the default) or what else the ring model offers.

    Examples
    --------
    >>> r = RingTest([0.5, 1.0], [0.2, 0.5], ring_width_mm=5.0, pin_mm=3.0)
    >>> r.force_n.tolist(), r.ring_id_mm is None
    ([0.2, 0.5], True)
    """

    displacement_mm: np.ndarray
    force_n: np.ndarray
    ring_width_mm: float
    pin_mm: float
    ring_od_mm: float | None = None
    ring_id_mm: float | None = None
    section: str = "plane-stress"

    def __post_init__(self) -> None:
        d, f = _curve("ring", "displacement_mm", self.displacement_mm, "force_n", self.force_n)
        if np.any(d < 0.0):
            raise InputError(f"ring: displacement_mm must be >= 0 mm, got {d[d < 0][0]:g}",
                             param="ring")
        # Normalised at construction, where a frozen dataclass sets its fields (through
        # object.__setattr__, as its generated __init__ does): the curve stored as float arrays and
        # the sizes as float, whatever is given.
        object.__setattr__(self, "displacement_mm", d)
        object.__setattr__(self, "force_n", f)
        object.__setattr__(self, "ring_width_mm",
                           check_positive("ring_width_mm", self.ring_width_mm, "mm"))
        object.__setattr__(self, "pin_mm", check_positive("pin_mm", self.pin_mm, "mm"))
        if self.ring_od_mm is not None:
            object.__setattr__(self, "ring_od_mm",
                               check_positive("ring_od_mm", self.ring_od_mm, "mm"))
        if self.ring_id_mm is not None:
            rid = check_positive("ring_id_mm", self.ring_id_mm, "mm")
            object.__setattr__(self, "ring_id_mm", rid)
            if self.ring_od_mm is not None and rid >= self.ring_od_mm:
                raise InputError(f"ring_id_mm must be < ring_od_mm ({self.ring_od_mm:g} mm), "
                                 f"got {rid:g}", param="ring_id_mm")
            check_pin(self.pin_mm, rid)
        if not isinstance(self.section, str) or not self.section:
            raise InputError(f"section must be a section name such as plane-stress, got "
                             f"{self.section!r}", param="section")


def check_pin(pin_mm: float, ring_id_mm: float) -> None:
    """Raise :class:`InputError` unless the pin (mm) fits inside the ring (inner diameter, mm)."""
    if not pin_mm < ring_id_mm:
        raise InputError(f"pin_mm must be < the ring's inner diameter ({ring_id_mm:g} mm), got "
                         f"{pin_mm:g}", param="pin_mm")


def _curve(name: str, xname: str, x: Any, yname: str, y: Any,
           monotonic: str = "rising") -> tuple[np.ndarray, np.ndarray]:
    try:
        xa = np.asarray(x, dtype=float).ravel()
        ya = np.asarray(y, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{name}: {xname} and {yname} must be numbers", param=name) from None
    if xa.size != ya.size:
        raise InputError(f"{name}: {xname} and {yname} must have the same length, got "
                         f"{xa.size} and {ya.size}", param=name)
    if xa.size == 0:
        raise InputError(f"{name}: no data points", param=name)
    for nm, a in ((xname, xa), (yname, ya)):
        bad = np.flatnonzero(~np.isfinite(a))
        if bad.size:
            raise InputError(f"{name}: {nm} must be finite, got {a[bad[0]]} at index {bad[0]}",
                             param=name)
    step = np.diff(xa)
    sign = -1.0 if monotonic == "either" and step.size and step[0] < 0 else 1.0
    if np.any(sign * step <= 0.0):
        i = int(np.flatnonzero(sign * step <= 0.0)[0]) + 1
        how = "rise strictly" if monotonic == "rising" else "be strictly monotonic"
        raise InputError(f"{name}: {xname} must {how} (one loading curve), got "
                         f"{xa[i - 1]:g} then {xa[i]:g} at index {i}",
                         param=name if monotonic == "rising" else "tensile")
    return xa, ya


# --------------------------------------------------------------------------------------------
# Results


def _unit_of(name: str) -> str:
    for suf, unit in (("_mm", "mm"), ("_mpa", "MPa"), ("_n", "N")):
        if name.endswith(suf):
            return unit
    return "unitless"


@checked_init
@dataclass(frozen=True)
class DatasetFit:
    """One dataset of a joint calibration: data, the fitted model's values, the misfit.

    Attributes
    ----------
    name : str
        ``inflation``, ``uniaxial``, ``biaxial``, ``planar``, ``ring`` or ``shore-prior``.
    x_name, y_name : str
        Column names with units of the abscissa (``pressure_mpa``, ``stretch``,
        ``displacement_mm``, ``shore``) and the measured quantity (``outer_diameter_mm``,
        ``stress_mpa`` nominal, ``force_n``, ``shear_modulus_mpa``).
    x : numpy.ndarray
        Abscissa of each point (unit of ``x_name``).
    measured, fitted : numpy.ndarray
        Measured and fitted values (unit of ``y_name``).
    noise : float
        Residual scale of this dataset (unit of ``y_name``; for the prior, unitless on ln mu).
    noise_rel : float
        The noise level given (unitless fraction; the prior: its Shore A sd).

    Examples
    --------
    >>> f = DatasetFit("ring", "displacement_mm", "force_n", np.array([1.0]), np.array([2.0]),
    ...                np.array([2.1]), 0.04, 0.02)
    >>> round(f.rms, 3), f.unit, f.n_points
    (0.1, 'N', 1)
    """

    name: str
    x_name: str
    y_name: str
    x: np.ndarray
    measured: np.ndarray
    fitted: np.ndarray
    noise: float
    noise_rel: float

    @property
    def unit(self) -> str:
        """Unit of ``measured``/``fitted`` (``mm``, ``MPa``, ``N``)."""
        return _unit_of(self.y_name)

    @property
    def n_points(self) -> int:
        """Number of points (count)."""
        return int(self.measured.size)

    @property
    def rms(self) -> float:
        """Root-mean-square of ``fitted - measured`` (unit of ``y_name``)."""
        return float(np.sqrt(np.mean((self.fitted - self.measured) ** 2)))

    @property
    def scaled_residuals(self) -> np.ndarray:
        """``(fitted - measured) / noise`` per point (unitless; the prior on ln mu)."""
        if self.name == "shore-prior":
            return np.asarray((np.log(self.fitted) - np.log(self.measured)) / self.noise)
        return np.asarray((self.fitted - self.measured) / self.noise)

    @property
    def rms_pct(self) -> float:
        """RMS relative to the largest measured magnitude (%)."""
        ref = float(np.max(np.abs(self.measured)))
        return 100.0 * self.rms / ref if ref > 0 else float("nan")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: points, RMS in the dataset's unit and in %, the noise level.

        Returns
        -------
        dict
            ``n_points``, ``x_name``, ``y_name``, ``x``, ``measured``, ``fitted``,
            ``rms_<unit>`` (e.g. ``rms_mm``), ``rms_pct``, ``noise_<unit>``, ``noise_rel``,
            ``chi2`` (sum of squared scaled residuals, unitless).
        """
        u = {"mm": "mm", "MPa": "mpa", "N": "n"}.get(self.unit, "unitless")
        return {
            "n_points": self.n_points, "x_name": self.x_name, "y_name": self.y_name,
            "x": self.x.tolist(), "measured": self.measured.tolist(),
            "fitted": self.fitted.tolist(), f"rms_{u}": self.rms, "rms_pct": self.rms_pct,
            f"noise_{u}" if self.name != "shore-prior" else "noise_ln_mu": self.noise,
            "noise_rel" if self.name != "shore-prior" else "shore_sd": self.noise_rel,
            "chi2": float(np.sum(self.scaled_residuals ** 2)),
        }


@checked_init
@dataclass(frozen=True)
class MisfitProfile:
    """The misfit along one direction of relative parameter space, the forward models re-run.

    Point ``k`` has the parameters ``p_j = p*_j + step_rel[k] v_j scale_j`` (``v`` a unit
    vector over the fitted parameters, ``scale`` their magnitudes at the optimum).

    Attributes
    ----------
    names : tuple of str
        Fitted parameters (unit suffixes; ``tube_id_mm`` in mm).
    direction : numpy.ndarray
        The unit vector ``v`` (unitless, relative parameters).
    step_rel : numpy.ndarray
        Step along ``v`` of each point (unitless: 0.01 = 1 % of each parameter's magnitude).
    sd_rel : float
        Standard deviation of the fit along ``v`` (unitless, same measure as ``step_rel``).
    params : numpy.ndarray
        Parameters of each point (n x p; each column in its parameter's unit).
    cost : numpy.ndarray
        Half the sum of squared scaled residuals (unitless) per point; NaN where a forward
        model failed.
    delta_chi2 : numpy.ndarray
        ``2 (cost - cost*) / s^2`` (unitless): 1 = one standard deviation of the fit (``s = 1``,
        the noise levels, when the fit is exact).

    Examples
    --------
    >>> p = MisfitProfile(("c10_mpa",), np.array([1.0]), np.array([-0.1, 0.0, 0.1]), 0.1,
    ...                   np.array([[0.9], [1.0], [1.1]]), np.array([2.0, 1.0, 2.0]),
    ...                   np.array([1.0, 0.0, 1.0]))
    >>> p.relative_cost_change
    1.0
    """

    names: tuple[str, ...]
    direction: np.ndarray
    step_rel: np.ndarray
    sd_rel: float
    params: np.ndarray
    cost: np.ndarray
    delta_chi2: np.ndarray

    @property
    def relative_cost_change(self) -> float:
        """Largest ``(cost - cost at step 0) / cost at step 0`` over the profile (unitless)."""
        c0 = float(self.cost[int(np.argmin(np.abs(self.step_rel)))])
        return float(np.nanmax(self.cost) - c0) / c0 if c0 > 0 else float("inf")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: direction by name, steps, parameters, cost and delta chi^2.

        Returns
        -------
        dict
            ``direction`` (name -> component), ``step_rel``, ``sd_rel``, ``params`` (one dict
            per point), ``cost``, ``delta_chi2``, ``relative_cost_change``.
        """
        return {
            "direction": dict(zip(self.names, self.direction.tolist(), strict=True)),
            "step_rel": self.step_rel.tolist(), "sd_rel": self.sd_rel,
            "params": [dict(zip(self.names, row.tolist(), strict=True)) for row in self.params],
            "cost": [None if not np.isfinite(c) else float(c) for c in self.cost],
            "delta_chi2": [None if not np.isfinite(c) else float(c) for c in self.delta_chi2],
            "relative_cost_change": self.relative_cost_change,
        }


@checked_init
@dataclass(frozen=True)
class Identifiability:
    """How well the data determine the parameters: eigen-analysis, correlation, profile.

    Attributes
    ----------
    names : tuple of str
        Fitted parameters.
    scales : numpy.ndarray
        Magnitude of each parameter that defines the relative parameters (its unit): ``|p|``
        at the optimum, at least a floor (1e-3 mu for MPa parameters, 0.1 for exponents).
    eigenvalues : numpy.ndarray
        Eigenvalues of ``J_r^T J_r`` (unitless), ascending; ``J_r`` the Jacobian of the scaled
        residuals with respect to the relative parameters.
    eigenvectors : numpy.ndarray
        The matching unit eigenvectors as columns (p x p, unitless).
    condition_number : float
        ``sqrt(max / min eigenvalue)``, the condition number of ``J_r`` (unitless).
    worst_direction : numpy.ndarray
        The eigenvector of the smallest eigenvalue, largest component positive (unitless).
    worst_sd_rel : float
        Standard deviation along it (unitless relative step: 0.05 = 5 %).
    max_correlation : float
        The largest |correlation| between two parameters (unitless; NaN with one parameter).
    max_correlation_pair : tuple of str
        The two parameters of ``max_correlation`` (empty with one parameter).
    identifiable : bool
        False when ``max_correlation`` > :data:`CORRELATION_LIMIT` or ``condition_number`` >
        :data:`CONDITION_LIMIT`.
    reason : str
        Why (one line).
    profile : MisfitProfile or None
        The misfit along ``worst_direction`` (None when not computed).

    Examples
    --------
    >>> from exofric.calibration import calibrate_material
    >>> lam = np.linspace(1.1, 2.5, 6)
    >>> r = calibrate_material("neo-hookean", tensile=(lam, 0.4 * (lam - lam**-2)))
    >>> r.identifiability.identifiable, r.identifiability.condition_number
    (True, 1.0)
    """

    names: tuple[str, ...]
    scales: np.ndarray
    eigenvalues: np.ndarray
    eigenvectors: np.ndarray
    condition_number: float
    worst_direction: np.ndarray
    worst_sd_rel: float
    max_correlation: float
    max_correlation_pair: tuple[str, ...]
    identifiable: bool
    reason: str
    profile: MisfitProfile | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict of everything above (directions by parameter name).

        Returns
        -------
        dict
            ``identifiable``, ``reason``, ``condition_number``, ``eigenvalues``,
            ``eigenvectors`` (list of name -> component), ``worst_direction``,
            ``worst_sd_rel``, ``max_correlation``, ``max_correlation_pair``,
            ``scales``, ``profile``, ``limits``.
        """
        vecs = [dict(zip(self.names, self.eigenvectors[:, k].tolist(), strict=True))
                for k in range(self.eigenvectors.shape[1])]
        return {
            "identifiable": self.identifiable, "reason": self.reason,
            "condition_number": self.condition_number,
            "eigenvalues": self.eigenvalues.tolist(), "eigenvectors": vecs,
            "worst_direction": dict(zip(self.names, self.worst_direction.tolist(), strict=True)),
            "worst_sd_rel": self.worst_sd_rel,
            "max_correlation": None if not np.isfinite(self.max_correlation)
            else self.max_correlation,
            "max_correlation_pair": list(self.max_correlation_pair),
            "scales": dict(zip(self.names, self.scales.tolist(), strict=True)),
            "profile": None if self.profile is None else self.profile.to_dict(),
            "limits": {"correlation": CORRELATION_LIMIT, "condition_number": CONDITION_LIMIT},
        }


@checked_init
@dataclass(frozen=True)
class MaterialCalibration(DisplayMixin):
    """A hyperelastic model (and tube ID) calibrated jointly to several tests.

    Attributes
    ----------
    model : HyperelasticModel
        The fitted material (parameters in MPa or unitless, d in 1/MPa).
    tube_od_mm : float or None
        Tube outer diameter (mm) of the inflation/ring models (None without them).
    tube_id_mm : float or None
        Tube inner diameter (mm): fitted or as given (None without inflation/ring data).
    tube_id_fitted : bool
        Whether the tube ID was a fitted parameter.
    names : tuple of str
        The fitted parameters: the model's (``c10_mpa``, ..., ``alpha1``) then ``tube_id_mm``.
    values, stderr : tuple of float
        Their values and standard errors (each in its parameter's unit).
    correlation : numpy.ndarray
        Correlation matrix of the fitted parameters (unitless, p x p).
    shear_modulus_stderr_mpa : float
        Standard error of the model's shear modulus mu (MPa).
    datasets : dict of str to DatasetFit
        Per dataset (and the prior): data, fitted values and misfit.
    identifiability : Identifiability
        Eigen-analysis, correlations and the misfit profile along the worst direction.
    stability : StabilityCheck
        Drucker check of the fitted model over the stretches the data reach.
    cost : float
        Half the sum of squared scaled residuals at the optimum (unitless).
    stderr_from : str
        ``residuals`` (``s^2 = 2 cost / (n - p)``) or ``noise`` (``s^2 = 1``).
    ends : str
        End condition of the inflation model (``plane-strain``, ``closed``, ``open``).
    converged : bool
        The optimiser met a tolerance (not the evaluation limit).
    n_model_evaluations : int
        Forward-model evaluations (count), the profile's included.
    elapsed_s : float
        Wall time (s), the profile's included.
    notes : tuple of str
        Warnings of the fit (bounds, instability allowed, non-identifiability).
    _problem : object or None
        Internal: the forward models, kept by :func:`calibrate_material` for
        :meth:`profile` (None for a result built otherwise; not compared or shown).

    Examples
    --------
    >>> from exofric.calibration import calibrate_material
    >>> lam = np.linspace(1.1, 2.5, 6)
    >>> r = calibrate_material("neo-hookean", tensile=(lam, 0.4 * (lam - lam**-2)))
    >>> round(r.model.params[0], 6), r.datasets["uniaxial"].n_points
    (0.2, 6)
    """

    model: HyperelasticModel
    tube_od_mm: float | None
    tube_id_mm: float | None
    tube_id_fitted: bool
    names: tuple[str, ...]
    values: tuple[float, ...]
    stderr: tuple[float, ...]
    correlation: np.ndarray
    shear_modulus_stderr_mpa: float
    datasets: dict[str, DatasetFit]
    identifiability: Identifiability
    stability: StabilityCheck
    cost: float
    stderr_from: str
    ends: str = "plane-strain"
    converged: bool = True
    n_model_evaluations: int = 0
    elapsed_s: float = 0.0
    notes: tuple[str, ...] = field(default=())
    _problem: Any = field(default=None, repr=False, compare=False)  # a _Problem (private)

    @property
    def tube_id_stderr_mm(self) -> float | None:
        """Standard error of the fitted tube ID (mm); None when the ID was not fitted."""
        if not self.tube_id_fitted:
            return None
        return self.stderr[self.names.index("tube_id_mm")]

    def corr(self, a: str, b: str) -> float:
        """Correlation (unitless) of two fitted parameters by name.

        Parameters
        ----------
        a, b : str
            Names from :attr:`names` (e.g. ``c10_mpa``, ``tube_id_mm``).

        Returns
        -------
        float
        """
        for n in (a, b):
            if n not in self.names:
                raise InputError(f"parameter must be one of {', '.join(self.names)}, got {n!r}",
                                 param="parameter")
        return float(self.correlation[self.names.index(a), self.names.index(b)])

    def profile(self, direction: Any = None, *, span_rel: float | None = None,
                span_sd: float = 3.0, n_points: int = 9) -> MisfitProfile:
        """Re-run the forward models along a direction of relative parameter space.

        Only on a result of :func:`calibrate_material` (it keeps its forward models).

        Parameters
        ----------
        direction : array_like of float or mapping, optional
            Direction over :attr:`names` (unitless, relative parameters; normalised here), as
            a sequence or a mapping name -> component. Default: the worst-determined one.
        span_rel : float, optional
            Half-width of the profile (unitless relative step, e.g. 0.02 = 2 %). Default:
            ``span_sd`` standard deviations of the fit along the direction (at most 0.5).
        span_sd : float
            Half-width in standard deviations when ``span_rel`` is not given (unitless).
        n_points : int
            Points of the profile (count, >= 3; odd keeps the optimum among them).

        Returns
        -------
        MisfitProfile
        """
        prob = self._problem
        if prob is None:
            raise InputError("profile needs a result of calibrate_material (its forward models "
                             "are not kept otherwise)", param="profile")
        v = _direction(direction, self.names, self.identifiability.worst_direction)
        return prob.profile(np.asarray(self.values), v, self.identifiability.scales,
                            self._s2(), span_rel=span_rel, span_sd=span_sd, n_points=n_points)

    def _s2(self) -> float:
        n = sum(d.n_points for d in self.datasets.values())
        dof = n - len(self.names)
        return 2.0 * self.cost / dof if self.stderr_from == "residuals" and dof > 0 else 1.0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: model, fitted values and standard errors, datasets, identifiability.

        Returns
        -------
        dict
            ``model``, ``params`` (by name, unit suffix), ``param_units``, ``stderr``,
            ``shear_modulus_mpa``, ``shear_modulus_stderr_mpa``, ``d_per_mpa``,
            ``bulk_modulus_mpa``, ``tube_od_mm``, ``tube_id_mm``, ``tube_id_stderr_mm``,
            ``tube_id_fitted``, ``fitted`` (names), ``correlation`` (``names``, ``matrix``),
            ``datasets``, ``identifiability``, ``stability``, ``cost``, ``stderr_from``,
            ``ends``, ``converged``, ``n_model_evaluations``, ``elapsed_s``, ``notes``.
        """
        d = self.model.to_dict()
        se = dict(zip(self.names, self.stderr, strict=True))
        d.update({
            "param_units": {n: "MPa" if n.endswith("_mpa") else "unitless"
                            for n in self.model.param_names},
            "stderr": {n: se.get(n) for n in self.model.param_names},
            "shear_modulus_stderr_mpa": self.shear_modulus_stderr_mpa,
            "tube_od_mm": self.tube_od_mm, "tube_id_mm": self.tube_id_mm,
            "tube_id_stderr_mm": self.tube_id_stderr_mm, "tube_id_fitted": self.tube_id_fitted,
            "fitted": list(self.names),
            "correlation": {"names": list(self.names),
                            "matrix": [[float(v) for v in row] for row in self.correlation]},
            "datasets": {k: v.to_dict() for k, v in self.datasets.items()},
            "identifiability": self.identifiability.to_dict(),
            "stability": self.stability.to_dict(), "cost": self.cost,
            "stderr_from": self.stderr_from, "ends": self.ends, "converged": self.converged,
            "n_model_evaluations": self.n_model_evaluations, "elapsed_s": self.elapsed_s,
            "notes": list(self.notes),
        })
        return d

    def to_frame(self) -> pd.DataFrame:
        """One row per data point of every dataset (the prior excluded), unit-suffixed columns.

        Returns
        -------
        pandas.DataFrame
            Columns ``dataset``, ``pressure_mpa``, ``stretch``, ``displacement_mm`` (the
            abscissa of the dataset's kind, NaN in the others), ``outer_diameter_mm``,
            ``outer_diameter_fit_mm``, ``stress_mpa``, ``stress_fit_mpa``, ``force_n``,
            ``force_fit_n`` (likewise) and ``scaled_residual`` (unitless).

        Examples
        --------
        >>> from exofric.calibration import calibrate_material
        >>> lam = np.linspace(1.1, 2.5, 6)
        >>> r = calibrate_material("neo-hookean", tensile=(lam, 0.4 * (lam - lam**-2)))
        >>> r.to_frame()[["stretch", "stress_mpa"]].shape
        (6, 2)
        """
        import pandas as pd

        cols = ["pressure_mpa", "stretch", "displacement_mm", "outer_diameter_mm",
                "outer_diameter_fit_mm", "stress_mpa", "stress_fit_mpa", "force_n",
                "force_fit_n"]
        frames = []
        for name, ds in self.datasets.items():
            if name == "shore-prior":
                continue
            f = pd.DataFrame({c: np.full(ds.n_points, np.nan) for c in cols})
            f.insert(0, "dataset", name)
            f[ds.x_name] = ds.x
            f[ds.y_name] = ds.measured
            f[_FIT_COLUMN[ds.y_name]] = ds.fitted
            f["scaled_residual"] = ds.scaled_residuals
            frames.append(f)
        if not frames:
            return pd.DataFrame(columns=["dataset", *cols, "scaled_residual"])
        return pd.concat(frames, ignore_index=True)

    def plot(self, fig: Any | None = None) -> Any:
        """Data and model per dataset (one panel each) and the misfit profile.

        Delegates to :func:`exofric.plots.plot_material_calibration`.

        Parameters
        ----------
        fig : matplotlib Figure, optional
            An empty figure to draw on (default a new one): several panels need a figure,
            not one Axes.

        Returns
        -------
        matplotlib Figure
        """
        from exofric.plots import plot_material_calibration

        return plot_material_calibration(self, fig)


def _direction(direction: Any, names: tuple[str, ...], default: np.ndarray) -> np.ndarray:
    if direction is None:
        v = np.asarray(default, dtype=float)
    elif isinstance(direction, Mapping):
        extra = sorted(set(direction) - set(names))
        if extra:
            raise InputError(f"direction names must be among {', '.join(names)}, got "
                             f"{', '.join(map(str, extra))}", param="direction")
        v = np.array([float(direction.get(n, 0.0)) for n in names])
    else:
        try:
            v = np.asarray(direction, dtype=float).ravel()
        except (TypeError, ValueError):
            raise InputError("direction must be numbers, one per fitted parameter",
                             param="direction") from None
        if v.size != len(names):
            raise InputError(f"direction must have {len(names)} components ({', '.join(names)}),"
                             f" got {v.size}", param="direction")
    norm = float(np.linalg.norm(v))
    if not (np.all(np.isfinite(v)) and norm > 0):
        raise InputError("direction must be finite and nonzero", param="direction")
    return v / norm


# --------------------------------------------------------------------------------------------
# The problem: forward models, residuals, Jacobian


class _Problem:
    """Datasets, forward models (memoised) and scaled residuals of one joint calibration."""

    def __init__(self, name: str, *, inflation: InflationData | None, od: float | None,
                 tube_id_fixed: float | None, fit_id: bool,
                 tensile: dict[str, tuple[np.ndarray, np.ndarray]],
                 ring: RingTest | None, prior: tuple[float, float, float, float] | None,
                 noise: dict[str, float], ends: str, poisson: float,
                 inflation_mesh: MeshSpec | None, ring_mesh: Any) -> None:
        self.name = name
        self.n_model = len(HYPERELASTIC_MODELS[name])
        self.inflation = inflation
        self.od = od
        self.tube_id_fixed = tube_id_fixed
        self.fit_id = fit_id
        self.tensile = tensile
        self.ring = ring
        self.prior = prior  # (shore, mu_prior_mpa, sd_ln, shore_sd)
        self.noise = noise
        self.ends = ends
        self.poisson = poisson
        self.inflation_mesh = inflation_mesh
        self.ring_mesh = ring_mesh
        self.calls = 0
        self.max_stretch = 1.0
        self._cache: dict[tuple[float, ...], dict[str, np.ndarray] | None] = {}
        self.failures: list[str] = []
        # residual scales (unit of each dataset)
        self.scale: dict[str, float] = {}
        if inflation is not None:
            self.scale["inflation"] = noise["inflation"]  # relative to each OD
        if tensile:  # one scale for every mode: the same rig, a load cell's error (MPa)
            ref = max(float(np.max(np.abs(p))) for _, p in tensile.values())
            if not ref > 0:
                raise InputError("tensile: stress_mpa is 0 everywhere: nothing to fit",
                                 param="tensile")
            for m in tensile:
                self.scale[m] = noise["tensile"] * ref
        if ring is not None:
            ref = float(np.max(np.abs(ring.force_n)))
            if not ref > 0:
                raise InputError("ring: force_n is 0 everywhere: nothing to fit", param="ring")
            self.scale["ring"] = noise["ring"] * ref
        if prior is not None:
            self.scale["shore-prior"] = prior[2]

    # --- parameters -------------------------------------------------------------------

    @property
    def names(self) -> tuple[str, ...]:
        return HYPERELASTIC_MODELS[self.name] + (("tube_id_mm",) if self.fit_id else ())

    def tube_id(self, x: np.ndarray) -> float | None:
        return float(x[-1]) if self.fit_id else self.tube_id_fixed

    def material(self, x: np.ndarray) -> HyperelasticModel:
        from exofric.material import material_model

        return material_model(self.name, x[: self.n_model], poisson=self.poisson)

    # --- forward models ---------------------------------------------------------------

    def predict(self, x: np.ndarray) -> dict[str, np.ndarray] | None:
        """Model values per dataset (their units; the prior: mu in MPa), None on failure."""
        key = tuple(float(v) for v in x)
        if key in self._cache:
            return self._cache[key]
        out: dict[str, np.ndarray] | None
        try:
            out = self._predict(x)
        except (InputError, ConvergenceError, ArithmeticError, ValueError,
                np.linalg.LinAlgError) as exc:  # a trial the models cannot solve
            self.failures.append(f"{dict(zip(self.names, key, strict=True))}: {exc}")
            out = None
        self._cache[key] = out
        return out

    def _predict(self, x: np.ndarray) -> dict[str, np.ndarray]:
        out: dict[str, np.ndarray] = {}
        trial = tuple(float(v) for v in x[: self.n_model])   # any values: no model checks
        for m, (lam, _) in self.tensile.items():
            with np.errstate(all="ignore"):
                out[m] = HyperelasticModel.trial_stress_mpa(self.name, trial, m, lam)
        if self.prior is not None:
            out["shore-prior"] = np.array([HyperelasticModel.trial_shear_modulus_mpa(self.name,
                                                                                      trial)])
        if self.inflation is None and self.ring is None:
            return out
        self.calls += 1
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # stretch warnings of trial materials
            mat = self.material(x)
            tid = self.tube_id(x)
            assert tid is not None and self.od is not None
            if self.inflation is not None:
                out["inflation"], ms = self._inflate(mat, tid)
                self.max_stretch = max(self.max_stretch, ms)
            if self.ring is not None:
                out["ring"], ms = self._ring(mat, tid)
                self.max_stretch = max(self.max_stretch, ms)
        return out

    def _inflate(self, mat: HyperelasticModel, tid: float) -> tuple[np.ndarray, float]:
        from exofric import defaults
        from exofric.fe import MeshSpec
        from exofric.simulate import inflate

        assert self.inflation is not None and self.od is not None
        mesh = self.inflation_mesh or MeshSpec(**defaults.INFLATION_MESH)
        res = inflate(self.od, tid, mat, self.inflation.pressure_mpa, mesh=mesh,
                      keep_fields=False, ends=self.ends)
        return (np.asarray(res.outer_diameter_mm, dtype=float),
                float(np.max(res.max_stretch)) if len(res.max_stretch) else 1.0)

    def _ring(self, mat: HyperelasticModel, tid: float) -> tuple[np.ndarray, float]:
        from exofric.simulate import ring_test

        r = self.ring
        assert r is not None and self.od is not None
        rod = r.ring_od_mm if r.ring_od_mm is not None else self.od
        rid = r.ring_id_mm if r.ring_id_mm is not None else tid
        check_pin(r.pin_mm, rid)
        d = r.displacement_mm
        pos = d > 0.0  # the undeformed point (force 0) needs no solve
        force = np.zeros(d.size)
        ms = 1.0
        if np.any(pos):
            kw: dict[str, Any] = {"section": r.section}
            if self.ring_mesh is not None:
                kw["mesh"] = self.ring_mesh
            res = ring_test(rod, rid, r.ring_width_mm, r.pin_mm, d[pos], mat, **kw)
            force[pos] = np.asarray(res.force_n, dtype=float)
            stretch = getattr(res, "max_stretch", None)
            if stretch is not None and np.size(stretch):
                ms = float(np.max(stretch))
        return force, ms

    # --- residuals --------------------------------------------------------------------

    def measured(self) -> dict[str, np.ndarray]:
        out: dict[str, np.ndarray] = {}
        for m, (_, p) in self.tensile.items():
            out[m] = p
        if self.prior is not None:
            out["shore-prior"] = np.array([self.prior[1]])
        if self.inflation is not None:
            out["inflation"] = self.inflation.outer_diameter_mm
        if self.ring is not None:
            out["ring"] = self.ring.force_n
        return out

    def n_residuals(self) -> int:
        return sum(v.size for v in self.measured().values())

    def residuals(self, x: np.ndarray) -> np.ndarray:
        pred = self.predict(x)
        meas = self.measured()
        if pred is None:
            return np.full(self.n_residuals(), _FAILED)
        parts = []
        for k, y in meas.items():
            f = pred[k]
            if k == "inflation":
                r = (f / y - 1.0) / self.scale[k]
            elif k == "shore-prior":
                with np.errstate(all="ignore"):
                    r = (np.log(f) - np.log(y)) / self.scale[k]
            else:
                r = (f - y) / self.scale[k]
            parts.append(np.where(np.isfinite(r), r, _FAILED))
        return np.concatenate(parts)

    def cost(self, x: np.ndarray) -> float:
        r = self.residuals(x)
        if np.any(r == _FAILED):
            return float("nan")
        return 0.5 * float(r @ r)

    def jac(self, x: np.ndarray, steps: np.ndarray, lo: np.ndarray, hi: np.ndarray,
            central: bool = False) -> np.ndarray:
        f0 = self.residuals(x)
        J = np.empty((f0.size, x.size))
        for k in range(x.size):
            h = float(steps[k])
            up = x[k] + h <= hi[k]
            dn = x[k] - h >= lo[k]
            xp, xm = x.copy(), x.copy()
            xp[k] += h
            xm[k] -= h
            if central and up and dn:
                fp, fm = self.residuals(xp), self.residuals(xm)
                if not (np.any(fp == _FAILED) or np.any(fm == _FAILED)):
                    J[:, k] = (fp - fm) / (2 * h)
                    continue
            fk = self.residuals(xp) if up else None
            if fk is None or np.any(fk == _FAILED):
                fk = self.residuals(xm)
                J[:, k] = (f0 - fk) / h
            else:
                J[:, k] = (fk - f0) / h
        return J

    def profile(self, x: np.ndarray, v: np.ndarray, scales: np.ndarray, s2: float, *,
                span_rel: float | None, span_sd: float, n_points: int,
                sd_rel: float | None = None) -> MisfitProfile:
        n = int(check_range("n_points", n_points, 3, 201))
        if sd_rel is None:
            sd_rel = _sd_along(self, x, v, scales, s2)
        if span_rel is None:
            span = check_range("span_sd", span_sd, 0.0, 1e3, lo_open=True) * sd_rel
            span = min(span, 0.5) if np.isfinite(span) else 0.5
            if span < 1e-6:  # an exact fit (s = 0): show +-1 % instead
                span = 0.01
        else:
            span = check_range("span_rel", span_rel, 0.0, 10.0, lo_open=True)
        t = np.linspace(-span, span, n)
        params = x[None, :] + t[:, None] * (v * scales)[None, :]
        cost = np.array([self.cost(p) for p in params])
        c0 = self.cost(x)
        # an exact fit (planted data without noise) has s ~ 0: delta chi^2 in units of the
        # noise levels then
        return MisfitProfile(self.names, v, t, float(sd_rel), params, cost,
                             2.0 * (cost - c0) / (s2 if s2 > 1e-16 else 1.0))


def _sd_along(prob: _Problem, x: np.ndarray, v: np.ndarray, scales: np.ndarray,
              s2: float) -> float:
    """Standard deviation (relative step) of the fit along the unit direction ``v``."""
    lo = np.full(x.size, -np.inf)
    hi = np.full(x.size, np.inf)
    J = prob.jac(x, 1e-4 * scales, lo, hi, central=True) * scales[None, :]
    curv = float(np.sum((J @ v) ** 2))
    return math.sqrt(s2 / curv) if curv > 0 else float("inf")


# --------------------------------------------------------------------------------------------
# Helpers for the entry point


def _model_name(model: str) -> str:
    if not isinstance(model, str):
        raise InputError(f"model must be a model name, got {model!r}", param="model")
    name = model.strip().lower().replace("_", "-")
    name = {"neohookean": "neo-hookean", "mooneyrivlin": "mooney-rivlin"}.get(name, name)
    if name not in HYPERELASTIC_MODELS:
        raise InputError(f"model must be one of {', '.join(HYPERELASTIC_MODELS)}, got "
                         f"{model!r}", param="model")
    return name



def _mode_data(mode: str, data: Any, kind: str) -> tuple[np.ndarray, np.ndarray]:
    """``(stretch, nominal stress in MPa)`` of one tensile mode, checked."""
    try:
        stretch, stress = data
    except (TypeError, ValueError):
        raise InputError(f"{mode} must be a pair (stretch, stress_mpa) of number lists",
                         param="tensile") from None
    lam, p = _curve(mode, "stretch", stretch, "stress_mpa", stress, monotonic="either")
    bad = np.flatnonzero(lam <= 0.0)
    if bad.size:
        raise InputError(f"{mode}: stretch must be > 0 (unitless), got {lam[bad[0]]:g} at index "
                         f"{bad[0]}", param="tensile")
    return lam, (p / lam if kind == "true" else p)  # sigma = l P in the loaded direction


def _model_start(name: str, mu: float) -> tuple[list[float], list[float], list[float]]:
    """Start and bounds ``(x0, lower, upper)`` of a model from a shear modulus mu (MPa), as
    :func:`exofric.material.fit_material` starts (C10 >= 0 for neo-Hookean and Yeoh, |alpha|
    <= 30 for Ogden)."""
    inf = float("inf")
    if name == "neo-hookean":
        return [mu / 2], [0.0], [inf]
    if name == "mooney-rivlin":
        return [0.4 * mu, 0.1 * mu], [-inf, -inf], [inf, inf]
    if name == "yeoh":
        return [mu / 2, -1e-2 * mu, 1e-4 * mu], [0.0, -inf, -inf], [inf, inf, inf]
    n = int(name[-1])
    alphas = {1: (2.0,), 2: (1.5, 5.0), 3: (1.3, 5.0, -2.0)}[n]
    mus = [0.95 * mu] + [0.02 * mu * (1 if a > 0 else -1) for a in alphas[1:]]
    x0 = [v for pair in zip(mus, alphas, strict=True) for v in pair]
    lo = [v for _ in range(n) for v in (-100 * max(mu, 1e-3), -30.0)]
    hi = [v for _ in range(n) for v in (100 * max(mu, 1e-3), 30.0)]
    return x0, lo, hi


def _mu_from_tensile(data: dict[str, tuple[np.ndarray, np.ndarray]]) -> float:
    """Neo-Hookean shear modulus (MPa) of the tensile points nearest stretch 1."""
    est: list[float] = []
    for mode, (lam, p) in data.items():
        lat = {"uniaxial": lam ** -0.5, "biaxial": lam ** -2.0, "planar": 1.0 / lam}[mode]
        den = (lam ** 2 - lat ** 2) / lam
        ok = np.abs(den) > 1e-9
        g = p[ok] / den[ok]
        est.extend(g[np.argsort(np.abs(np.log(lam[ok])))[:3]].tolist())
    mu = float(np.median(est)) if est else 1.0
    return mu if np.isfinite(mu) and mu > 0 else 1.0


def _tensile_data(tensile: Any, stress_kind: str | Mapping[str, str]
                  ) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    if tensile is None:
        return {}
    if isinstance(tensile, Mapping):
        extra = sorted(set(tensile) - set(_MODE_NAMES))
        if extra:
            raise InputError(f"tensile modes must be among {', '.join(_MODE_NAMES)}, got "
                             f"{', '.join(map(str, extra))}", param="tensile")
        given = {m: v for m, v in tensile.items() if v is not None}
    else:
        given = {"uniaxial": tensile}
    kinds = (dict(stress_kind) if isinstance(stress_kind, Mapping)
             else dict.fromkeys(_MODE_NAMES, stress_kind))
    out = {}
    for m in _MODE_NAMES:
        if m in given:
            kind = kinds.get(m, "engineering")
            if kind not in ("engineering", "true"):
                raise InputError(f"stress_kind must be engineering or true, got {kind!r}",
                                 param="stress_kind")
            out[m] = _mode_data(m, given[m], kind)
    return out


def _noise(name: str, value: float | None) -> float:
    if value is None:
        return DEFAULT_NOISE_REL[name]
    return check_range(f"{name}_noise_rel", value, 0.0, 1.0, lo_open=True)


def _mu_from_inflation(data: InflationData, od: float, tid: float) -> float | None:
    """Shear modulus (MPa) whose closed-form neo-Hookean inflation meets the highest point."""
    from scipy.optimize import brentq

    from exofric.simulate import incompressible_inflation

    p, d = data.pressure_mpa, data.outer_diameter_mm
    k = int(np.argmax(p))
    if not p[k] > 0 or not d[k] > od:
        return None
    lo = p[k] / math.log(od / tid) * 1.0001

    def g(mu: float) -> float:
        return float(incompressible_inflation(od, tid, mu, [p[k]]).outer_diameter_mm[0]) - d[k]

    try:
        if g(lo) < 0 or g(1e4) > 0:
            return None
        return float(brentq(g, lo, 1e4, xtol=1e-10, rtol=1e-8))
    except (InputError, ValueError, ZeroDivisionError):
        return None


def _floors(name: str, mu0: float) -> np.ndarray:
    return np.array([1e-3 * mu0 if n.endswith("_mpa") else 0.1
                     for n in HYPERELASTIC_MODELS[name]])


# --------------------------------------------------------------------------------------------
# The entry point


def _stability(fitted: HyperelasticModel, fe_max_stretch: float,
               tens: Mapping[str, tuple[np.ndarray, np.ndarray]], *, fe_data: bool
               ) -> tuple[StabilityCheck, list[str]]:
    """Drucker stability where the data reach it (refused when unstable), and notes for the
    margin beyond the data and for the tensile modes never measured (issue 31: a uniaxial
    range used to be applied to biaxial, which was refused without biaxial data).

    Each measured tensile mode is checked over its own stretches; with inflation or ring data,
    every mode also over the FE's stretches (the tube's wall reaches general states). An
    instability within ``defaults.FIT_STABILITY_MARGIN_REL`` beyond the data, or anywhere in
    the whole range for a mode never measured, is a note (a warning), not a refusal.
    """
    from exofric import defaults
    from exofric.material import MODES

    margin = float(defaults.FIT_STABILITY_MARGIN_REL)

    def widen(lo: float, hi: float) -> tuple[float, float]:
        return (lo / (1.0 + margin) if lo < 1.0 else lo,
                hi * (1.0 + margin) if hi > 1.0 else hi * (1.0 + 1e-3))

    def first_unstable(m: str, ranges: list[tuple[float, float]]) -> float | None:
        found: float | None = None
        for lo, hi in ranges:
            u = fitted.stability(lo, max(hi, lo * (1.0 + 1e-3)), modes=(m,)).unstable_from[m]
            if u is not None and (found is None or abs(math.log(u)) < abs(math.log(found))):
                found = u
        return found

    fe_hi = max(1.0, fe_max_stretch)
    data_ranges: dict[str, list[tuple[float, float]]] = {}
    for m in MODES:
        ranges = [(1.0 / fe_hi, fe_hi)] if fe_data else []
        if m in tens:
            lam = tens[m][0]
            ranges.append((min(float(lam.min()), 1.0), max(float(lam.max()), 1.0)))
        if ranges:
            data_ranges[m] = ranges
    lo_all = min((r[0] for rs in data_ranges.values() for r in rs), default=1.0)
    hi_all = max((r[1] for rs in data_ranges.values() for r in rs), default=1.0)
    first = {m: (first_unstable(m, data_ranges[m]) if m in data_ranges else None)
             for m in MODES}
    stab = StabilityCheck(all(v is None for v in first.values()), lo_all,
                          max(hi_all, lo_all * (1.0 + 1e-3)), first, 401, tuple(data_ranges))
    notes = []
    w_lo, w_hi = widen(lo_all, hi_all)
    for m in MODES:
        if m in data_ranges:
            if first[m] is None:
                u = first_unstable(m, [widen(*r) for r in data_ranges[m]])
                if u is not None:
                    notes.append(f"{m}: Drucker-unstable from stretch {u:.3g}, within "
                                 f"{100 * margin:g} % beyond the data: do not extrapolate")
            continue
        u = first_unstable(m, [(w_lo, w_hi)])
        if u is not None:
            notes.append(f"{m} (not measured): Drucker-unstable from stretch {u:.3g}; the fit "
                         f"predicts {m} deformation only where it is stable: test that mode")
    return stab, notes


# --------------------------------------------------------------------------------------------
# The steps of calibrate_material


class _ShorePrior(NamedTuple):
    """The Shore A prior: hardness (Shore A), its mu (MPa), sd of ln mu (unitless), sd (Shore A).

    A tuple, so :class:`_Problem` reads it by position as before (``prior[1]`` is mu in MPa).
    """

    shore: float
    mu_mpa: float
    sd_ln: float
    shore_sd: float


@dataclass(frozen=True)
class _Tube:
    """The tube of the inflation/ring models: OD, ID start and fixed ID (mm), fit flag."""

    od_mm: float | None
    id_start_mm: float | None
    id_fixed_mm: float | None
    fit_id: bool
    needed: bool


@dataclass(frozen=True)
class _Start:
    """Start, bounds and magnitude floors of the fitted parameters (each in its unit), and the
    relative finite-difference step (unitless)."""

    x0: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    floors: np.ndarray
    step_rel: float

    def steps(self, x: np.ndarray) -> np.ndarray:
        """Finite-difference steps at ``x`` (each parameter's unit)."""
        return self.step_rel * np.maximum(np.abs(x), self.floors)


@dataclass(frozen=True)
class _Optimum:
    """The optimiser's end: parameters (their units), scaled residuals and half their sum of
    squares (unitless), whether it converged, and its notes."""

    x: np.ndarray
    residuals: np.ndarray
    cost: float
    converged: bool
    notes: tuple[str, ...]


@dataclass(frozen=True)
class _Uncertainty:
    """The fit's covariance: Jacobian of the scaled residuals, s^2 (unitless), covariance,
    standard errors and correlation of the parameters, standard error of mu (MPa), notes."""

    jac: np.ndarray
    s2: float
    cov: np.ndarray
    stderr: np.ndarray
    correlation: np.ndarray
    shear_modulus_stderr_mpa: float
    notes: tuple[str, ...]


def _noise_levels(inflation_noise_rel: float | None, tensile_noise_rel: float | None,
                  ring_noise_rel: float | None, stderr_from: str | None
                  ) -> tuple[dict[str, float], str]:
    """Noise level per dataset kind (unitless fractions) and the covariance scale's source."""
    if stderr_from is not None and stderr_from not in ("residuals", "noise"):
        raise InputError(f"stderr_from must be residuals or noise, got {stderr_from!r}",
                         param="stderr_from")
    noise = {"inflation": _noise("inflation", inflation_noise_rel),
             "tensile": _noise("tensile", tensile_noise_rel),
             "ring": _noise("ring", ring_noise_rel)}
    if stderr_from is None:
        given = (inflation_noise_rel, tensile_noise_rel, ring_noise_rel)
        stderr_from = "noise" if any(v is not None for v in given) else "residuals"
    return noise, stderr_from


def _datasets_in(inflation: Any, tensile: Any, stress_kind: str | Mapping[str, str], ring: Any
                 ) -> tuple[InflationData | None, dict[str, tuple[np.ndarray, np.ndarray]]]:
    """The checked inflation data (pressure MPa, OD mm; or None) and tensile curves (stretch,
    nominal stress MPa) per mode; the ring's type checked and at least one dataset given."""
    tens = _tensile_data(tensile, stress_kind)
    data = None
    if inflation is not None:
        from exofric.calibration._api import _as_data

        data = _as_data(inflation)
        if data.shore is not None:
            raise InputError("inflation data with a shore column: give the hardness as "
                             "shore_prior instead", param="inflation")
    if ring is not None and not isinstance(ring, RingTest):
        raise InputError(f"ring must be a RingTest, got {type(ring).__name__}", param="ring")
    if data is None and not tens and ring is None:
        raise InputError("calibrate_material needs at least one dataset: inflation, tensile or "
                         "ring (a Shore prior alone is not data)", param="inflation")
    return data, tens


def _tube(tube_od_mm: float | None, tube_id_mm: float | None, fit_tube_id: bool, *,
          inflation: bool, ring: RingTest | None) -> _Tube:
    """The tube's OD and ID (mm, checked) and whether the ID is fitted (inflation data or a
    ring of the tube's ID); the ID's start is 0.6 OD when not given."""
    if not (inflation or ring is not None):
        od = check_positive("tube_od_mm", tube_od_mm, "mm") if tube_od_mm is not None else None
        return _Tube(od, None, None, fit_id=False, needed=False)
    ring_od = ring.ring_od_mm if ring is not None else None
    if tube_od_mm is None and ring_od is None:
        raise InputError("tube_od_mm is required with inflation or ring data (mm)",
                         param="tube_od_mm")
    od_in = tube_od_mm if tube_od_mm is not None else ring_od
    assert od_in is not None
    od = check_positive("tube_od_mm", od_in, "mm")
    tid0 = None
    if tube_id_mm is not None:
        tid0 = check_positive("tube_id_mm", tube_id_mm, "mm")
        if tid0 >= od:
            raise InputError(f"tube_id_mm must be < tube_od_mm ({od:g} mm), got {tid0:g}",
                             param="tube_id_mm")
    uses_id = inflation or (ring is not None and ring.ring_id_mm is None)
    fit_id = bool(fit_tube_id) and uses_id
    tid_fixed = None
    if uses_id and not fit_id:
        if tid0 is None:
            raise InputError("tube_id_mm is required (mm) when the tube ID is not fitted",
                             param="tube_id_mm")
        tid_fixed = tid0
    if ring is not None and ring.ring_id_mm is None and tid_fixed is not None:
        check_pin(ring.pin_mm, tid_fixed)
    return _Tube(od, tid0 if tid0 is not None else 0.6 * od, tid_fixed, fit_id=fit_id,
                 needed=True)


def _shore_prior(shore_prior: float | None, shore_sd: float, correlation: str
                 ) -> _ShorePrior | None:
    """The Shore A prior on mu = E(Shore) / 3 (MPa) and its sd on ln mu, or None."""
    if shore_prior is None:
        return None
    from exofric.material import shore_to_modulus

    s = check_range("shore_prior", shore_prior, 0.0, 100.0, lo_open=True, hi_open=True)
    sd = check_range("shore_sd", shore_sd, 0.0, 50.0, lo_open=True)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        e0 = shore_to_modulus(s, correlation)
        e_hi = shore_to_modulus(min(s + sd, 99.9), correlation)
        e_lo = shore_to_modulus(max(s - sd, 0.1), correlation)
    sd_ln = 0.5 * abs(math.log(e_hi) - math.log(e_lo))
    return _ShorePrior(s, e0 / 3.0, sd_ln, sd)


def _start_modulus(name: str, tens: dict[str, tuple[np.ndarray, np.ndarray]],
                   prior: _ShorePrior | None, data: InflationData | None, tube: _Tube
                   ) -> tuple[float, list[float] | None]:
    """Start shear modulus mu0 (MPa): of a tensile-only fit (whose parameters, in their units,
    are then the start), else the prior's, else the closed-form inflation's, else 1 MPa."""
    if tens:
        from exofric.material import fit_material

        x_model: list[float] | None = None
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                start_fit = fit_material(name, tens.get("uniaxial"), tens.get("biaxial"),
                                         tens.get("planar"), allow_unstable=True)
            x_model = list(start_fit.model.params)
            mu0 = start_fit.model.shear_modulus_mpa
        except InputError:
            mu0 = _mu_from_tensile(tens)
        return mu0, x_model
    if prior is not None:
        return prior.mu_mpa, None
    if data is not None and tube.od_mm is not None and tube.id_start_mm is not None:
        return _mu_from_inflation(data, tube.od_mm, tube.id_start_mm) or 1.0, None
    return 1.0, None


def _id_bounds(od: float, ring: RingTest | None) -> tuple[float, float]:
    """Bounds (mm) of a fitted tube ID: 2-98 % of the OD (mm), above the pin of a ring of the
    tube's ID."""
    id_lo = 0.02 * od
    if ring is not None and ring.ring_id_mm is None:
        id_lo = max(id_lo, ring.pin_mm * 1.001)
    id_hi = 0.98 * od
    if id_lo >= id_hi:
        raise InputError(f"pin_mm must be < the tube's inner diameter, which is < "
                         f"{id_hi:g} mm, got {ring.pin_mm if ring else float('nan'):g}",
                         param="pin_mm")
    return id_lo, id_hi


def _ring_only_start(prob: _Problem, x0: np.ndarray, lo: np.ndarray, hi: np.ndarray
                     ) -> np.ndarray:
    """The start (parameters in their units) with its MPa parameters rescaled so the ring
    force (N) there meets the data's largest force, kept within the bounds."""
    # force is linear in a common scale of the MPa parameters (displacement control and
    # d ~ 1/mu): rescale the start so its force meets the data
    assert prob.ring is not None
    f = prob.predict(x0)
    if f is None or not np.max(np.abs(f["ring"])) > 0:
        return x0
    ratio = float(np.max(np.abs(prob.ring.force_n)) / np.max(np.abs(f["ring"])))
    mpa = np.array([n.endswith("_mpa") for n in prob.names])
    return np.clip(np.where(mpa, x0 * ratio, x0), lo, hi)


def _start_and_bounds(prob: _Problem, mu0: float, x_model: list[float] | None, tube: _Tube,
                      fe: bool) -> _Start:
    """Start, bounds and floors (each parameter's unit) of the model's parameters from mu0
    (MPa) or a tensile fit's ``x_model``, then of the tube ID (mm) when fitted."""
    x_start, lo, hi = _model_start(prob.name, mu0)
    x0 = list(x_model if x_model is not None else x_start)
    floors = _floors(prob.name, mu0)
    if tube.fit_id:
        assert tube.od_mm is not None and tube.id_start_mm is not None
        id_lo, id_hi = _id_bounds(tube.od_mm, prob.ring)
        x0.append(min(max(tube.id_start_mm, id_lo), id_hi))
        lo.append(id_lo)
        hi.append(id_hi)
        floors = np.append(floors, 1e-3 * float(tube.od_mm))
    lo_a, hi_a = np.asarray(lo, float), np.asarray(hi, float)
    x0_a = np.clip(np.asarray(x0, float), lo_a, hi_a)
    if (prob.ring is not None and prob.inflation is None and not prob.tensile
            and prob.prior is None):
        x0_a = _ring_only_start(prob, x0_a, lo_a, hi_a)
    return _Start(x0_a, lo_a, hi_a, floors, 1e-5 if fe else 1e-7)


def _optimise(prob: _Problem, start: _Start, fe: bool, max_nfev: int) -> _Optimum:
    """Bounded least squares (scipy's trf) of the scaled residuals from the start; a start or
    an end where a forward model fails is a ConvergenceError."""
    from scipy.optimize import least_squares

    if np.any(prob.residuals(start.x0) == _FAILED):
        detail = prob.failures[-1] if prob.failures else "non-finite model values"
        raise ConvergenceError(f"the forward models fail at the starting point: {detail}")
    tol = 1e-10 if fe else 1e-14
    res = least_squares(prob.residuals, start.x0,
                        jac=lambda x: prob.jac(x, start.steps(x), start.lo, start.hi),
                        bounds=(start.lo, start.hi), method="trf",
                        x_scale=np.maximum(np.abs(start.x0), start.floors),
                        ftol=tol, xtol=tol, gtol=tol, max_nfev=int(max_nfev))
    x = np.asarray(res.x, dtype=float)
    r = prob.residuals(x)
    if np.any(r == _FAILED):
        raise ConvergenceError("the joint calibration ended where a forward model fails: "
                               + (prob.failures[-1] if prob.failures else ""))
    converged = bool(res.status > 0)
    notes = () if converged else (f"least squares stopped before converging ({res.message})",)
    return _Optimum(x, r, 0.5 * float(r @ r), converged, notes)


def _shear_modulus_stderr(name: str, x: np.ndarray, n_model: int, cov: np.ndarray) -> float:
    """Standard error (MPa) of mu from the covariance of all p fitted parameters."""
    grad_mu = np.zeros(x.size)  # mu is linear in the parameters of every model
    mu_at = HyperelasticModel.trial_shear_modulus_mpa(name, x[:n_model])
    for k in range(n_model):
        e = np.zeros(n_model)
        e[k] = 1.0
        grad_mu[k] = HyperelasticModel.trial_shear_modulus_mpa(name, x[:n_model] + e) - mu_at
    return math.sqrt(max(float(grad_mu @ cov @ grad_mu), 0.0))


def _uncertainty(prob: _Problem, opt: _Optimum, start: _Start, fe: bool,
                 stderr_from: str) -> _Uncertainty:
    """Covariance ``s^2 (J^T J)^+`` from the central-difference Jacobian at the optimum, with
    ``s^2`` from the residuals (``2 cost / (n - p)``) or the noise levels (1)."""
    x = opt.x
    p, n = x.size, opt.residuals.size
    steps = 1e2 * start.steps(x) if fe else 1e1 * start.steps(x)
    J = prob.jac(x, steps, start.lo, start.hi, central=True)
    dof = n - p
    notes: tuple[str, ...] = ()
    if stderr_from == "residuals" and dof <= 0:
        notes = (f"{n} residuals for {p} parameters: standard errors from the noise levels",)
    s2 = 2.0 * opt.cost / dof if stderr_from == "residuals" and dof > 0 else 1.0
    cov = lsq_covariance(J, s2)
    return _Uncertainty(J, s2, cov, standard_errors(cov), correlation_matrix(cov),
                        _shear_modulus_stderr(prob.name, x, prob.n_model, cov), notes)


def _eigen(J: np.ndarray, scales: np.ndarray, s2: float
           ) -> tuple[np.ndarray, np.ndarray, float, np.ndarray, float]:
    """Eigenvalues/vectors of ``J_r^T J_r`` (relative parameters, unitless), its condition
    number, the worst direction (largest component positive) and its sd (relative step)."""
    Jr = J * scales[None, :]
    lam, vecs = np.linalg.eigh(Jr.T @ Jr)
    lam = np.clip(lam, 0.0, None)
    cond = math.sqrt(lam[-1] / lam[0]) if lam[0] > 0 else float("inf")
    v = vecs[:, 0].copy()
    if v[int(np.argmax(np.abs(v)))] < 0:
        v = -v
    sd_rel = math.sqrt(s2 / lam[0]) if lam[0] > 0 else float("inf")
    return lam, vecs, cond, v, sd_rel


def _max_correlation(corr: np.ndarray, names: tuple[str, ...]
                     ) -> tuple[float, tuple[str, ...]]:
    """The largest off-diagonal correlation (unitless, signed; NaN with one parameter) and
    its pair of parameter names (empty with one parameter)."""
    p = len(names)
    if p <= 1:
        return float("nan"), ()
    off = np.abs(corr) * (1 - np.eye(p))
    off = np.where(np.isfinite(off), off, 0.0)
    i, j = np.unravel_index(int(np.argmax(off)), off.shape)
    return float(corr[i, j]), (names[min(i, j)], names[max(i, j)])


def _identifiability_reason(names: tuple[str, ...], v: np.ndarray, sd_rel: float, cond: float,
                            maxc: float, pair: tuple[str, ...]) -> tuple[bool, str]:
    """Whether the fit is identifiable (correlation and condition limits) and why (one line)."""
    p = len(names)
    why = []
    if p > 1 and abs(maxc) > CORRELATION_LIMIT:
        why.append(f"{pair[0]} and {pair[1]} correlate at {maxc:.4f} (|r| > "
                   f"{CORRELATION_LIMIT:g})")
    if cond > CONDITION_LIMIT:
        why.append(f"condition number {cond:.3g} > {CONDITION_LIMIT:g}")
    if why:
        worst = ", ".join(f"{c:+.3f} {nm}" for nm, c in zip(names, v, strict=True))
        return False, ("; ".join(why) + f": the data barely see the direction ({worst}) in "
                       f"relative parameters, known to +-{100 * sd_rel:.3g} % (1 sd)")
    return True, (f"max |correlation| {abs(maxc):.3f}, condition number {cond:.3g}" if p > 1
                  else "one parameter")


def _identifiability(prob: _Problem, x: np.ndarray, unc: _Uncertainty, floors: np.ndarray,
                     profile_points: int, profile_span_sd: float) -> Identifiability:
    """The identifiability report at the optimum ``x``: eigen-analysis in relative parameters
    (scales ``max(|x|, floors)``, each parameter's unit), correlation, misfit profile."""
    names = prob.names
    scales = np.maximum(np.abs(x), floors)
    lam, vecs, cond, v, sd_rel = _eigen(unc.jac, scales, unc.s2)
    maxc, pair = _max_correlation(unc.correlation, names)
    ok, reason = _identifiability_reason(names, v, sd_rel, cond, maxc, pair)
    prof = prob.profile(x, v, scales, unc.s2, span_rel=None, span_sd=profile_span_sd,
                        n_points=profile_points, sd_rel=sd_rel) if profile_points else None
    return Identifiability(names, scales, lam, vecs, cond, v, sd_rel, maxc, pair, ok, reason,
                           prof)


def _identifiability_notes(ident: Identifiability, fit_id: bool, ring: RingTest | None
                           ) -> list[str]:
    """The note of a fit that is not identifiable, with a hint when a ring would help."""
    if ident.identifiable:
        return []
    hint = ""
    if fit_id and ring is None:
        hint = (" A ring test (or a measured tube ID, or tensile data) separates modulus "
                "from wall thickness.")
    return [f"not identifiable: {ident.reason}.{hint}"]


def _bound_notes(names: tuple[str, ...], x: np.ndarray, lo: np.ndarray, hi: np.ndarray
                 ) -> list[str]:
    """A note per parameter that stopped at a bound (values in each parameter's unit)."""
    notes = []
    for k in range(x.size):
        span = hi[k] - lo[k]
        near = min(x[k] - lo[k], hi[k] - x[k])
        if np.isfinite(near) and near <= 1e-6 * (span if np.isfinite(span) else abs(x[k]) + 1):
            notes.append(f"{names[k]} stopped at its bound {x[k]:.4g}: the standard errors are "
                         "indicative only")
    return notes


def _checked_stability(prob: _Problem, x: np.ndarray, fe: bool, allow_unstable: bool
                       ) -> tuple[HyperelasticModel, StabilityCheck, list[str]]:
    """The fitted material, its Drucker check over the data's stretches (refused when unstable
    unless allowed) and the notes of instability allowed or beyond the data."""
    name = prob.name
    try:
        fitted = prob.material(x)
    except InputError as exc:
        raise InputError(f"the {name} fit gives an invalid material ({exc}); try another "
                         "model", param="model") from None
    stab, unmeasured = _stability(fitted, prob.max_stretch, prob.tensile, fe_data=fe)
    notes = []
    if not stab.stable:
        where = ", ".join(f"{k} from stretch {v_:.3g}" for k, v_ in stab.unstable_from.items()
                          if v_ is not None)
        msg = (f"the {name} fit is Drucker-unstable (dP/dl <= 0) within the stretches the data "
               f"reach, {stab.stretch_min:.3g}-{stab.stretch_max:.3g}: {where}")
        if not allow_unstable:
            raise InputError(f"model: {msg}; use another model or allow_unstable",
                             param="model")
        notes.append(msg)
    return fitted, stab, notes + unmeasured


def _dataset_fits(prob: _Problem, x: np.ndarray) -> dict[str, DatasetFit]:
    """Data, fitted values and residual scale (each dataset's unit) per dataset and prior."""
    pred = prob.predict(x)
    assert pred is not None
    meas = prob.measured()
    noise = prob.noise
    data, ring, prior = prob.inflation, prob.ring, prob.prior
    datasets: dict[str, DatasetFit] = {}
    if data is not None:
        datasets["inflation"] = DatasetFit(
            "inflation", "pressure_mpa", "outer_diameter_mm", data.pressure_mpa,
            data.outer_diameter_mm, pred["inflation"],
            noise["inflation"] * float(np.mean(data.outer_diameter_mm)), noise["inflation"])
    for m, (lam_t, _) in prob.tensile.items():
        datasets[m] = DatasetFit(m, "stretch", "stress_mpa", lam_t, meas[m], pred[m],
                                 prob.scale[m], noise["tensile"])
    if ring is not None:
        datasets["ring"] = DatasetFit("ring", "displacement_mm", "force_n", ring.displacement_mm,
                                      ring.force_n, pred["ring"], prob.scale["ring"],
                                      noise["ring"])
    if prior is not None:
        datasets["shore-prior"] = DatasetFit("shore-prior", "shore", "shear_modulus_mpa",
                                             np.array([prior[0]]), np.array([prior[1]]),
                                             pred["shore-prior"], prior[2], prior[3])
    return datasets


def calibrate_material(
    model: str,
    *,
    inflation: InflationData | Mapping[str, Any] | Any = None,
    tube_od_mm: float | None = None,
    tube_id_mm: float | None = None,
    fit_tube_id: bool = True,
    tensile: Any = None,
    stress_kind: str | Mapping[str, str] = "engineering",
    ring: RingTest | None = None,
    shore_prior: float | None = None,
    shore_sd: float = DEFAULT_SHORE_SD,
    correlation: str = "paper",
    ends: str = "plane-strain",
    inflation_noise_rel: float | None = None,
    tensile_noise_rel: float | None = None,
    ring_noise_rel: float | None = None,
    stderr_from: str | None = None,
    poisson: float = D.POISSON,
    allow_unstable: bool = False,
    profile_points: int = 9,
    profile_span_sd: float = 3.0,
    inflation_mesh: MeshSpec | None = None,
    ring_mesh: Any = None,
    max_nfev: int = 200,
) -> MaterialCalibration:
    """Fit a hyperelastic model (and the tube ID) to inflation, tensile and ring tests at once.

    Parameters
    ----------
    model : str
        ``neo-hookean``, ``mooney-rivlin``, ``yeoh``, ``ogden1``, ``ogden2`` or ``ogden3``.
    inflation : InflationData, DataFrame or mapping, optional
        Inflation test: ``pressure_mpa`` (MPa) and ``outer_diameter_mm`` (mm); no ``shore``
        column (give a hardness as ``shore_prior``).
    tube_od_mm : float, optional
        Undeformed tube outer diameter (mm); required with inflation or ring data (default
        with a ring: its own ``ring_od_mm``).
    tube_id_mm : float, optional
        Tube inner diameter (mm): the start when fitted (default 0.6 ``tube_od_mm``), the
        value otherwise.
    fit_tube_id : bool
        Fit the tube ID (default) when inflation data or a ring of the tube's ID are given;
        False needs ``tube_id_mm``.
    tensile : (array_like, array_like) or mapping, optional
        ``(stretch, stress_mpa)`` of a uniaxial test (stretch unitless, stress in MPa), or a
        mapping ``uniaxial``/``biaxial``/``planar`` -> such a pair.
    stress_kind : {'engineering', 'true'} or mapping
        Stress measure of the tensile data (all modes, or per mode).
    ring : RingTest, optional
        Ring test (displacement in mm, force in N, width and pin in mm).
    shore_prior : float, optional
        Shore A hardness used as a prior on the shear modulus: ``mu = E(Shore) / 3`` (MPa).
    shore_sd : float
        Uncertainty of ``shore_prior`` (Shore A; default 2.5, a default).
    correlation : str
        Shore -> E0 correlation of the prior (see :func:`exofric.material.shore_to_modulus`).
    ends : {'plane-strain', 'closed', 'open'}
        End condition of the inflation model.
    inflation_noise_rel, tensile_noise_rel, ring_noise_rel : float, optional
        Noise levels (unitless fractions): of each OD (default 0.005), and of the curve's
        largest stress (0.02) and force (0.02).
    stderr_from : {'residuals', 'noise'}, optional
        Scale of the covariance: ``residuals`` (``s^2 = 2 cost / (n - p)``) or ``noise``
        (``s^2 = 1``). Default: ``noise`` when a noise level is given, else ``residuals``.
    poisson : float
        Small-strain Poisson ratio behind the model's d (unitless; the paper's 0.498).
    allow_unstable : bool
        Accept a model that is Drucker-unstable over the data's stretches (a note instead of
        an InputError).
    profile_points : int
        Points of the misfit profile (count, >= 3; 0 skips it).
    profile_span_sd : float
        Half-width of the profile in standard deviations of the worst direction (unitless;
        at most a relative step of 0.5).
    inflation_mesh : exofric.fe.MeshSpec, optional
        Mesh of the inflation FE (default :data:`exofric.defaults.INFLATION_MESH`).
    ring_mesh : optional
        Mesh of the ring FE, passed to the ring model (default: its own).
    max_nfev : int
        Largest number of optimiser evaluations (count).

    Returns
    -------
    MaterialCalibration

    Raises
    ------
    InputError
        Unknown model, no dataset, missing tube sizes, a pin that does not fit the ring, bad
        data, an unstable fit without ``allow_unstable``.
    ConvergenceError
        No forward-model evaluation succeeded at the start.

    Examples
    --------
    >>> import numpy as np
    >>> lam = np.linspace(1.1, 2.5, 6)
    >>> r = calibrate_material("neo-hookean", tensile=(lam, 0.4 * (lam - lam**-2)),
    ...                        shore_prior=50.0)
    >>> r.names, 0.19 < r.model.params[0] < 0.21
    (('c10_mpa',), True)
    """
    t0 = time.perf_counter()
    name = _model_name(model)
    ends = check_ends(ends)
    noise, stderr_from = _noise_levels(inflation_noise_rel, tensile_noise_rel, ring_noise_rel,
                                       stderr_from)
    nu = check_range("poisson", poisson, 0.0, 0.5, lo_open=True, hi_open=True)
    data, tens = _datasets_in(inflation, tensile, stress_kind, ring)
    tube = _tube(tube_od_mm, tube_id_mm, fit_tube_id, inflation=data is not None, ring=ring)
    prior = _shore_prior(shore_prior, shore_sd, correlation)
    prob = _Problem(name, inflation=data, od=tube.od_mm, tube_id_fixed=tube.id_fixed_mm,
                    fit_id=tube.fit_id, tensile=tens, ring=ring, prior=prior, noise=noise,
                    ends=ends, poisson=nu, inflation_mesh=inflation_mesh, ring_mesh=ring_mesh)
    fe = data is not None or ring is not None  # forward models by FE in the loop

    # --- start and bounds, the optimisation -------------------------------------------
    mu0, x_model = _start_modulus(name, tens, prior, data, tube)
    start = _start_and_bounds(prob, mu0, x_model, tube, fe)
    opt = _optimise(prob, start, fe, max_nfev)
    x = opt.x

    # --- uncertainty and identifiability ----------------------------------------------
    unc = _uncertainty(prob, opt, start, fe, stderr_from)
    ident = _identifiability(prob, x, unc, start.floors, profile_points, profile_span_sd)

    # --- bounds, stability, result ----------------------------------------------------
    fitted, stab, stab_notes = _checked_stability(prob, x, fe, allow_unstable)
    notes = [*opt.notes, *unc.notes, *_identifiability_notes(ident, tube.fit_id, ring),
             *_bound_notes(prob.names, x, start.lo, start.hi), *stab_notes]
    datasets = _dataset_fits(prob, x)
    result = MaterialCalibration(
        model=fitted, tube_od_mm=tube.od_mm, tube_id_mm=prob.tube_id(x) if tube.needed else None,
        tube_id_fitted=tube.fit_id, names=prob.names, values=tuple(float(v_) for v_ in x),
        stderr=tuple(float(v_) for v_ in unc.stderr), correlation=unc.correlation,
        shear_modulus_stderr_mpa=unc.shear_modulus_stderr_mpa, datasets=datasets,
        identifiability=ident, stability=stab, cost=opt.cost, stderr_from=stderr_from,
        ends=ends, converged=opt.converged, n_model_evaluations=prob.calls,
        elapsed_s=time.perf_counter() - t0, notes=tuple(notes), _problem=prob)
    for note in notes:
        if not note.startswith("not identifiable"):  # that one is the identifiability report's
            warn_implausible(note)
    return result
