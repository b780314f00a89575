"""Interface-resolved friction (issue 15): F = mu_tube S_wire + mu_wall N_wall (+ F0).

The paper's equivalent coefficient gamma (F = gamma N, Eq 1) lumps two sliding interfaces:
the pulled wire rubs on the inflated silicone tube and on the aluminium hole wall. With the
wire held against the wall by the tube, the friction over the tube length L is

    F = mu_tube S_wire + mu_wall N_wall + F0                      (all N)

* ``S_wire`` (N) = L x the integral of the tube-wire contact pressure over the contact arc
  (``wire_pressure_integral_n_per_mm`` x ``length_mm`` of a squeeze result). It is not the
  resultant N: the tube wraps the wire, and pressure at an angle to the line of centres adds
  to S but only its component to N. For any contact S >= N (|integral of p n| <= integral of
  p), typically by a few to 20 %, depending on geometry and pressure.
* ``N_wall`` (N) = the normal force between the wire and the hole wall. The wire is in
  equilibrium between the tube and the wall, so N_wall = N, the squeezing force
  (``squeeze_force_n``).
* ``mu_tube`` (silicone-steel) and ``mu_wall`` (aluminium-steel) are Coulomb coefficients
  (unitless); ``F0`` (N) an optional pressure-independent drag, as in the affine gamma model.

gamma N = mu_tube S + mu_wall N means gamma = mu_tube S/N + mu_wall: one gamma fits one
structure only as long as its wrap ratio S/N does not change; two coefficients can transfer
between wires, tubes and holes where one gamma cannot.

Fitting (:func:`fit_interfaces`): F_i = mu_tube S_i + mu_wall N_i (+ F0) is linear in the
coefficients, so it is a no-intercept (or, with F0, affine) ordinary least-squares fit on the
design matrix X = [S, N (, 1)], with S and N read off each structure's FE curves by monotone
PCHIP at the test pressures (as :func:`~exofric.friction.fit_gamma` does for N). Points of
several structures are pooled; the standard errors are classical (``ci="ols"``),
heteroscedasticity-robust HC3 (``"analytic"``, the default without replicates) or
cluster-robust over (structure, pressure) replicate clusters (``"cluster"``, the default with
replicates; the same CR2/Bell-McCaffrey covariance as ``fit_gamma``), with t quantiles.

Identifiability. On one structure S/N varies little with pressure (1.00 to 1.07 from 0.2 to
0.6 MPa on the paper's structures), so the columns S and N are nearly proportional and only the
combination mu_tube S/N + mu_wall (a gamma) is determined; geometrically similar structures
(the paper's tests 1-3 are near scalings of one another) have the same S/N(P) and add nothing.
:class:`InterfaceFit` reports the scaled condition number kappa of X (columns scaled to unit
length, not centred; Belsley, Kuh & Welsch 1980) and the correlation of the two estimates (for
two columns of unit length and cosine c, kappa = sqrt((1 + c) / (1 - c)) and the OLS
correlation is -c). The fit is flagged ``identifiable = False`` when

* kappa > :data:`KAPPA_MAX` = 100 (|correlation| > 0.9998 for two columns). A relative error
  eps in the FE columns moves the coefficients by up to about kappa x eps (first-order
  least-squares perturbation, Golub & Van Loan, *Matrix Computations* Sec. 5.3; an error common
  to S and N only rescales both coefficients, so eps is the error of the wrap ratio S/N).
  exofric's ``standard`` accuracy mesh gives S/N within 0.14-0.25 % of a mesh-converged
  (6 x 128) reference on six structures with 1.1-2 mm wires (1.2 % for a 0.6 mm wire), so at
  kappa = 100 the FE error alone may move each coefficient by about 25 %: past that, the split
  reflects discretisation error more than friction. Measured: fitting planted data from
  converged curves with 2 x 16-mesh curves (S/N off by 0.5-0.8 %) at kappa = 116-138 moved
  the coefficients by 25-62 %; with 3 x 32-mesh curves (0.13-0.25 %), by 1-7 %. One paper
  structure gives kappa = 115-150 and tests 1-3 pooled 138; a tube of another wall thickness
  or wire size beside them brings it to 30-55. ``max_condition_number`` changes the threshold.
* a coefficient's 95 % CI half-width exceeds :data:`CI_REL_MAX` = 50 % of its estimate: the
  data (noise and design together) do not pin it down.

The reason is stated in ``identifiability_reason`` and warned (:class:`IdentifiabilityWarning`;
the CLI lists it under ``warnings`` in ``--json``).

Examples
--------
>>> law = InterfaceFrictionModel(mu_tube=0.5, mu_wall=0.2)
>>> round(law.friction_n(110.0, 100.0), 9)       # S_wire = 110 N, N_wall = 100 N
75.0
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, Literal, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric._display import DisplayMixin
from exofric._lsq import hc3_covariance, lsq_covariance, residual_variance, standard_errors
from exofric._validate import checked_init
from exofric.errors import (
    InputError,
    check_finite,
    check_range,
    check_series,
    warn_implausible,
)
from exofric.fe import MU_WARN
from exofric.friction._curve import SqueezeCurve
from exofric.simulate import check_friction

if TYPE_CHECKING:
    import pandas as pd

    from exofric.friction._rig import RigConfig, RigRun

__all__ = [
    "CI_REL_MAX",
    "KAPPA_MAX",
    "IdentifiabilityWarning",
    "InterfaceCurves",
    "InterfaceFit",
    "InterfaceFrictionModel",
    "InterfaceRigRun",
    "InterfaceTest",
    "fit_interfaces",
    "simulate_interface_rig",
]

#: Largest scaled condition number of the design [S, N (, 1)] at which mu_tube and mu_wall
#: count as separable: kappa x the FE's ~0.25 % wrap-ratio error = ~25 % (module docstring).
KAPPA_MAX = 100.0
#: Largest 95 % CI half-width, as a fraction of the estimate, of an identified coefficient.
CI_REL_MAX = 0.5
#: The key of a squeeze result (``exofric squeeze --json``) that the interface law needs.
WIRE_KEY = "wire_pressure_integral_n_per_mm"

ModelKind = Literal["proportional", "affine"]
InterfaceCi = Literal["auto", "analytic", "ols", "cluster"]


class IdentifiabilityWarning(UserWarning):
    """The data cannot separate mu_tube from mu_wall (see :class:`InterfaceFit`).

    Emitted by :func:`fit_interfaces` when the fit is not identifiable; the estimates are still
    returned, with ``identifiable = False`` and the reason.

    Examples
    --------
    >>> issubclass(IdentifiabilityWarning, UserWarning)
    True
    """


@checked_init
@dataclass(frozen=True)
class InterfaceFrictionModel:
    """The interface-resolved friction law F = mu_tube S_wire + mu_wall N_wall + F0 (N).

    Parameters
    ----------
    mu_tube : float
        Coulomb coefficient of the wire on the tube (silicone-steel), unitless, in [0, 2]
        (warned above 1.5).
    mu_wall : float
        Coulomb coefficient of the wire on the hole wall (aluminium-steel), unitless, in
        [0, 2] (warned above 1.5).
    f0_n : float
        Pressure-independent drag F0 in N (0 by default).

    Raises
    ------
    InputError
        A coefficient NaN, negative or above 2, or F0 not finite; the message names it.

    Examples
    --------
    >>> law = InterfaceFrictionModel(0.5, 0.2, f0_n=1.0)
    >>> law.friction_n(110.0, 100.0)
    76.0
    >>> law.friction_n(np.array([0.0, 110.0]), np.array([0.0, 100.0])).tolist()
    [1.0, 76.0]
    """

    mu_tube: float
    mu_wall: float
    f0_n: float = 0.0

    def __post_init__(self) -> None:
        # Normalised at construction, where a frozen dataclass sets its fields (through
        # object.__setattr__, as its generated __init__ does): stored as float whatever number
        # type is given (JSON-ready, one repr).
        object.__setattr__(self, "mu_tube", check_friction("mu_tube", self.mu_tube))
        object.__setattr__(self, "mu_wall", check_friction("mu_wall", self.mu_wall))
        object.__setattr__(self, "f0_n", check_finite("f0_n (friction offset, N)", self.f0_n))

    @overload
    def friction_n(self, s_wire_n: float, n_wall_n: float) -> float: ...
    @overload
    def friction_n(self, s_wire_n: NDArray[np.float64],
                   n_wall_n: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def friction_n(self, s_wire_n: Any, n_wall_n: Any) -> Any:
        """Friction F in N from S_wire (N) and N_wall (N): mu_tube S + mu_wall N + F0.

        Parameters
        ----------
        s_wire_n : float or ndarray
            Arc integral of the tube-wire contact pressure times the tube length, in N.
        n_wall_n : float or ndarray
            Wall-wire normal force (the squeezing force N), in N.

        Returns
        -------
        float or ndarray
            Friction in N (float for scalar inputs).

        Examples
        --------
        >>> InterfaceFrictionModel(0.5, 0.2).friction_n(100.0, 90.0)
        68.0
        """
        if np.ndim(s_wire_n) == 0 and np.ndim(n_wall_n) == 0:
            return float(self.mu_tube * float(s_wire_n) + self.mu_wall * float(n_wall_n)
                         + self.f0_n)
        return (self.mu_tube * np.asarray(s_wire_n, dtype=float)
                + self.mu_wall * np.asarray(n_wall_n, dtype=float) + self.f0_n)

    def equivalent_gamma(self, s_wire_n: Any, n_wall_n: Any) -> Any:
        """The gamma (unitless) this law implies: (F - F0) / N = mu_tube S/N + mu_wall.

        Parameters
        ----------
        s_wire_n : float or ndarray
            S_wire in N.
        n_wall_n : float or ndarray
            N_wall (the squeezing force) in N; NaN where it is 0.

        Returns
        -------
        float or ndarray
            gamma, unitless.

        Examples
        --------
        >>> round(InterfaceFrictionModel(0.5, 0.2).equivalent_gamma(110.0, 100.0), 12)
        0.75
        """
        s = np.asarray(s_wire_n, dtype=float)
        n = np.asarray(n_wall_n, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            g = np.where(n > 0, self.mu_tube * s / np.where(n > 0, n, 1.0) + self.mu_wall,
                         np.nan)
        return float(g) if g.ndim == 0 else g

    # -- the FrictionLaw protocol -----------------------------------------------------------

    @property
    def name(self) -> str:
        """``"interfaces"``: the law's label (:class:`~exofric.friction.FrictionLaw`)."""
        return "interfaces"

    @property
    def inputs(self) -> tuple[str, ...]:
        """The FE curves it reads: ``wire_pressure_integral_n`` (S_wire, N) and
        ``squeeze_force_n`` (N_wall, N)."""
        return ("wire_pressure_integral_n", "squeeze_force_n")

    def friction_of(self, columns: Mapping[str, Any]) -> NDArray[np.float64]:
        """Friction in N per pressure from S_wire and N: mu_tube S + mu_wall N + F0.

        Parameters
        ----------
        columns : mapping
            ``wire_pressure_integral_n`` (S_wire, N) and ``squeeze_force_n`` (N), one per
            pressure (other keys are not read).

        Returns
        -------
        numpy.ndarray
            F in N.

        Examples
        --------
        >>> InterfaceFrictionModel(0.5, 0.2).friction_of(
        ...     {"wire_pressure_integral_n": [110.0], "squeeze_force_n": [100.0]})
        array([75.])
        """
        return np.asarray(self.friction_n(np.asarray(columns["wire_pressure_integral_n"],
                                                     dtype=float),
                                          np.asarray(columns["squeeze_force_n"], dtype=float)),
                          dtype=float)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: ``law``, ``mu_tube``, ``mu_wall`` (unitless), ``f0_n`` (N)."""
        return {"law": "interfaces", "mu_tube": float(self.mu_tube),
                "mu_wall": float(self.mu_wall), "f0_n": float(self.f0_n)}


def _get(source: Any, key: str) -> Any:
    """``key`` of a dict (a squeeze's JSON), or of a result object: at its top level or in its
    contact group (:class:`~exofric.simulate.ContactOutputs`, where S_wire lives)."""
    if isinstance(source, Mapping):
        return source.get(key)
    value = getattr(source, key, None)
    if value is None:
        value = getattr(getattr(source, "contact", None), key, None)
    return value


@checked_init
@dataclass(frozen=True, init=False)
class InterfaceCurves:
    """One structure's FE curves S_wire(P) and N(P), interpolated by monotone PCHIP.

    Parameters
    ----------
    pressure_mpa : array_like
        Pressures in MPa: finite, >= 0, strictly increasing, at least 2.
    wire_pressure_integral_n : array_like
        S_wire in N (total over the tube length): the arc integral of the tube-wire contact
        pressure times L; >= 0, one per pressure.
    squeeze_force_n : array_like
        The squeezing force N = N_wall in N (total over the tube length), >= 0.
    name : str
        The structure's name (labels, messages).

    Attributes
    ----------
    pressure_mpa, wire_pressure_integral_n, squeeze_force_n : tuple of float
        The nodes (MPa, N, N).
    name : str
        The structure's name.

    Warns
    -----
    PlausibilityWarning
        S_wire below N by more than 2 % of the largest N somewhere: the integral of a contact
        pressure is at least its resultant (are the columns swapped?).

    Examples
    --------
    >>> c = InterfaceCurves([0.2, 0.4, 0.6], [22.0, 110.0, 264.0], [20.0, 100.0, 240.0], "a")
    >>> s, n, inside = c.at([0.4, 0.7])
    >>> float(s[0]), float(n[0]), inside.tolist()
    (110.0, 100.0, [True, False])
    >>> [round(r, 3) for r in c.wrap_ratio]
    [1.1, 1.1, 1.1]
    """

    pressure_mpa: tuple[float, ...]
    wire_pressure_integral_n: tuple[float, ...]
    squeeze_force_n: tuple[float, ...]
    name: str = ""

    def __init__(self, pressure_mpa: ArrayLike, wire_pressure_integral_n: ArrayLike,
                 squeeze_force_n: ArrayLike, name: str = "") -> None:
        where = f"{name}: FE curves" if name else "FE curves"
        p, s = check_series("pressure_mpa", pressure_mpa, "wire_pressure_integral_n",
                            wire_pressure_integral_n, x_unit="MPa", y_unit="N", x_min=0.0,
                            y_min=0.0, where=where)
        curve = SqueezeCurve(p, squeeze_force_n)       # validates N(P) as everywhere else
        n = np.asarray(curve.squeeze_force_n)
        if n.size and float(n.max()) > 0:
            short = np.flatnonzero(s < n - 0.02 * float(n.max()))
            if short.size:
                k = int(short[0])
                warn_implausible(
                    f"{where}: wire_pressure_integral_n = {s[k]:g} N is below the squeeze "
                    f"force {n[k]:g} N at {p[k]:g} MPa; the arc integral of a contact pressure "
                    "is at least its resultant (swapped columns, or per-mm values not "
                    "multiplied by the length?)")
        # The constructor of a frozen value type sets each field once, normalised (tuples of
        # float: hashable, comparable), whatever arrays it is given; object.__setattr__ is how
        # a frozen dataclass initialises a field (its generated __init__ does the same).
        object.__setattr__(self, "pressure_mpa", tuple(p.tolist()))
        object.__setattr__(self, "wire_pressure_integral_n", tuple(s.tolist()))
        object.__setattr__(self, "squeeze_force_n", tuple(n.tolist()))
        object.__setattr__(self, "name", str(name))

    @classmethod
    def from_squeeze(cls, result: Any, name: str | None = None) -> InterfaceCurves:
        """From a squeeze result (:class:`~exofric.simulate.SqueezeResult`) or its JSON dict.

        Reads ``pressure_mpa`` (MPa), ``squeeze_force_n`` (N), ``wire_pressure_integral_n_per_mm``
        (N/mm) and ``length_mm`` (mm): S_wire = the per-mm integral x L.

        Parameters
        ----------
        result : SqueezeResult or mapping
            The result object or the parsed ``exofric squeeze --json`` output.
        name : str, optional
            The structure's name (default: the result's structure name, if any).

        Returns
        -------
        InterfaceCurves

        Raises
        ------
        InputError
            ``wire_pressure_integral_n_per_mm`` missing (a result from a version without
            per-interface contact outputs) or any other key missing or malformed.

        Examples
        --------
        >>> d = {"pressure_mpa": [0.2, 0.6], "squeeze_force_n": [20.0, 240.0],
        ...      "wire_pressure_integral_n_per_mm": [0.2, 2.2], "length_mm": 116.0}
        >>> [round(v, 6) for v in InterfaceCurves.from_squeeze(d).wire_pressure_integral_n]
        [23.2, 255.2]
        """
        per_mm = _get(result, WIRE_KEY)
        if per_mm is None:
            raise InputError(
                f"squeeze result has no {WIRE_KEY!r} (the tube-wire contact pressure "
                "integral that the interface law needs); make it with `exofric squeeze ... "
                "--json` from a version with contact outputs", param=WIRE_KEY)
        length = _get(result, "length_mm")
        if length is None:
            st = _get(result, "structure")
            length = _get(st, "length_mm") if st is not None else None
        if length is None:
            raise InputError("squeeze result has no 'length_mm' (mm, to turn "
                             f"{WIRE_KEY} into a total over the tube length)", param="length_mm")
        ell = check_range("length_mm", length, 0.0, 1e5, lo_open=True, unit="mm")
        for key in ("pressure_mpa", "squeeze_force_n"):
            if _get(result, key) is None:
                raise InputError(f"squeeze result has no {key!r}", param=key)
        try:
            s = np.asarray(per_mm, dtype=float).ravel() * ell
        except (TypeError, ValueError):
            raise InputError(f"{WIRE_KEY} must be a list of numbers (N/mm)",
                             param=WIRE_KEY) from None
        if name is None:
            st = _get(result, "structure")
            name = str(_get(st, "name") or "") if st is not None else ""
        return cls(_get(result, "pressure_mpa"), s, _get(result, "squeeze_force_n"), name)

    @property
    def pressure_range_mpa(self) -> tuple[float, float]:
        """(first, last) node pressure in MPa."""
        return self.pressure_mpa[0], self.pressure_mpa[-1]

    @property
    def wrap_ratio(self) -> tuple[float, ...]:
        """S_wire / N per node (unitless, >= 1 for any contact; NaN where N = 0)."""
        s = np.asarray(self.wire_pressure_integral_n)
        n = np.asarray(self.squeeze_force_n)
        with np.errstate(divide="ignore", invalid="ignore"):
            return tuple(np.where(n > 0, s / np.where(n > 0, n, 1.0), np.nan).tolist())

    def at(self, pressure_mpa: ArrayLike, *, edge_tol_mpa: float = 0.005
           ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
        """S_wire (N) and N (N) at pressures (MPa) by monotone PCHIP, and the inside mask.

        Parameters
        ----------
        pressure_mpa : array_like
            Pressures in MPa (any order).
        edge_tol_mpa : float
            Pressures up to this far (MPa) beyond the curves' ends count as inside, as in
            :func:`~exofric.friction.match_squeeze`.

        Returns
        -------
        (S, N, inside)
            S_wire and N in N (NaN outside) and the mask of pressures inside.

        Examples
        --------
        >>> c = InterfaceCurves([0.2, 0.6], [22.0, 264.0], [20.0, 240.0])
        >>> [round(float(v[0]), 6) for v in c.at([0.4])[:2]]
        [143.0, 130.0]
        """
        p = np.asarray(pressure_mpa, dtype=float).ravel()
        tol = check_range("edge_tol_mpa", edge_tol_mpa, 0.0, 0.1, unit="MPa")
        lo, hi = self.pressure_range_mpa
        inside = (p >= lo - tol) & (p <= hi + tol)
        s = np.full(p.shape, np.nan)
        n = np.full(p.shape, np.nan)
        if np.any(inside):
            s[inside], n[inside] = self._pchip(p[inside]).T
        return s, n, inside

    @cached_property
    def _pchip(self) -> Any:
        """PCHIP of the columns (S_wire, N) on P, each independently (built on first use)."""
        from scipy.interpolate import PchipInterpolator

        return PchipInterpolator(np.asarray(self.pressure_mpa),
                                 np.column_stack([self.wire_pressure_integral_n,
                                                  self.squeeze_force_n]))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready nodes (MPa, N) and the wrap ratio S/N (unitless)."""
        return {"name": self.name, "pressure_mpa": list(self.pressure_mpa),
                "wire_pressure_integral_n": list(self.wire_pressure_integral_n),
                "squeeze_force_n": list(self.squeeze_force_n),
                "wrap_ratio": list(self.wrap_ratio)}


@checked_init
@dataclass(frozen=True)
class InterfaceTest:
    """Friction tests of one structure with its FE curves: one block of :func:`fit_interfaces`.

    Parameters
    ----------
    curves : InterfaceCurves
        The structure's S_wire(P) and N(P) (MPa, N).
    pressure_mpa : array_like
        Test pressures in MPa (replicates allowed).
    friction_n : array_like
        Measured friction in N, one per pressure.
    groups : array_like, optional
        Cluster label per point (e.g. the pressure plateau); default: the pressure.

    Attributes
    ----------
    curves : InterfaceCurves
    pressure_mpa, friction_n : tuple of float
        The points (MPa, N).
    groups : tuple
        Cluster labels (empty: by pressure).

    Examples
    --------
    >>> c = InterfaceCurves([0.2, 0.6], [22.0, 264.0], [20.0, 240.0], "a")
    >>> InterfaceTest(c, [0.2, 0.6], [15.0, 180.0]).friction_n
    (15.0, 180.0)
    """

    curves: InterfaceCurves
    pressure_mpa: Any
    friction_n: Any
    groups: Any = ()

    def __post_init__(self) -> None:
        if not isinstance(self.curves, InterfaceCurves):
            raise InputError("curves must be InterfaceCurves (the structure's FE S_wire(P) "
                             "and N(P))", param="curves")
        where = f"{self.curves.name}: friction test" if self.curves.name else "friction test"
        p, f = check_series("pressure_mpa", self.pressure_mpa, "friction_n", self.friction_n,
                            x_unit="MPa", y_unit="N", increasing=False, min_points=1,
                            x_min=0.0, where=where)
        # Normalised at construction (see InterfaceCurves): tuples of float, labels a tuple.
        object.__setattr__(self, "pressure_mpa", tuple(p.tolist()))
        object.__setattr__(self, "friction_n", tuple(f.tolist()))
        g = () if self.groups is None else tuple(np.asarray(self.groups, dtype=object).tolist())
        if g and len(g) != p.size:
            raise InputError(f"{where}: groups has {len(g)} labels, need one per point "
                             f"({p.size})", param="groups")
        object.__setattr__(self, "groups", g)


@checked_init
@dataclass(frozen=True)
class InterfaceFit(DisplayMixin):
    """Result of :func:`fit_interfaces`: mu_tube, mu_wall (unitless) and F0 (N) with CIs.

    Attributes
    ----------
    kind : {"proportional", "affine"}
        Without or with the drag F0.
    mu_tube, mu_wall : float
        Fitted coefficients (unitless).
    f0_n : float
        Fitted drag F0 in N (0 for the proportional fit).
    mu_tube_ci, mu_wall_ci : (float, float)
        95 % confidence intervals (unitless).
    f0_ci_n : (float, float) or None
        95 % confidence interval of F0 in N (affine only).
    mu_tube_se, mu_wall_se : float
        Standard errors (unitless) of the chosen covariance.
    f0_se_n : float or None
        Standard error of F0 in N (affine only).
    correlation : float
        Correlation of the mu_tube and mu_wall estimates (unitless, -1..1).
    condition_number : float
        Scaled condition number kappa of the design [S, N (, 1)] (unitless).
    identifiable : bool
        False when kappa > ``condition_number_max`` or a CI is wider than
        :data:`CI_REL_MAX` of its estimate (see the module docstring).
    identifiability_reason : str
        One sentence: why (not).
    ci_method : {"analytic", "ols", "cluster"}
        How the CIs were computed (``"auto"`` resolved).
    ci_note : str
        What the interval accounts for.
    dof : float
        Degrees of freedom of the t quantile (of mu_tube's; Bell-McCaffrey for clusters).
    n_clusters : int
        Replicate clusters among the points used.
    lack_of_fit : LackOfFit or None
        Lack-of-fit F test against the cluster means, when replicates exist.
    structure, pressure_mpa, wire_pressure_integral_n, squeeze_force_n, friction_n, \
predicted_friction_n : tuple
        Per point used: structure name, MPa, S_wire (N), N (N), measured and fitted F (N).
    relative_error_pct, max_relative_error_pct, relative_rms_residual_pct : float
        Mean |relative error|, signed largest and RMS relative residual, in % (as for gamma).
    n_dropped : int
        Points outside their structure's curve range (not used).
    gamma_pooled : float
        The single gamma (unitless) fitted to the same pooled points, F = gamma N (+ F0),
        for comparison.
    gamma_predicted_friction_n : tuple of float
        Its fitted F per point (N).
    warnings : tuple of str
        Identifiability and plausibility warnings (also emitted).
    group : tuple
        Cluster label per point used.
    condition_number_max : float
        The threshold on kappa used (unitless; :data:`KAPPA_MAX` by default).

    Examples
    --------
    >>> c = InterfaceCurves([0.2, 0.4, 0.6], [22.0, 110.0, 260.0], [20.0, 100.0, 240.0], "a")
    >>> d = InterfaceCurves([0.2, 0.4, 0.6], [30.0, 150.0, 360.0], [20.0, 100.0, 240.0], "b")
    >>> tests = [InterfaceTest(c, [0.2, 0.4, 0.6], [15.0, 75.0, 178.0]),
    ...          InterfaceTest(d, [0.2, 0.4, 0.6], [19.0, 95.0, 228.0])]
    >>> fit = fit_interfaces(tests)
    >>> round(fit.mu_tube, 4), round(fit.mu_wall, 4), fit.identifiable
    (0.5, 0.2, True)
    """

    kind: ModelKind
    mu_tube: float
    mu_wall: float
    f0_n: float
    mu_tube_ci: tuple[float, float]
    mu_wall_ci: tuple[float, float]
    f0_ci_n: tuple[float, float] | None
    mu_tube_se: float
    mu_wall_se: float
    f0_se_n: float | None
    correlation: float
    condition_number: float
    identifiable: bool
    identifiability_reason: str
    ci_method: str
    ci_note: str
    dof: float
    n_clusters: int
    lack_of_fit: Any
    structure: tuple[str, ...]
    pressure_mpa: tuple[float, ...]
    wire_pressure_integral_n: tuple[float, ...]
    squeeze_force_n: tuple[float, ...]
    friction_n: tuple[float, ...]
    predicted_friction_n: tuple[float, ...]
    relative_error_pct: float
    max_relative_error_pct: float
    relative_rms_residual_pct: float
    n_dropped: int
    gamma_pooled: float
    gamma_predicted_friction_n: tuple[float, ...]
    warnings: tuple[str, ...] = ()
    group: tuple[Any, ...] = field(default=())
    condition_number_max: float = KAPPA_MAX

    @property
    def model(self) -> InterfaceFrictionModel:
        """The fitted law (InputError if a coefficient came out negative or above 2)."""
        return InterfaceFrictionModel(self.mu_tube, self.mu_wall, self.f0_n)

    @property
    def n_points(self) -> int:
        """Number of points used."""
        return len(self.pressure_mpa)

    @property
    def structures(self) -> tuple[str, ...]:
        """Structure names in order of first appearance."""
        return tuple(dict.fromkeys(self.structure))

    @property
    def residual_n(self) -> NDArray[np.float64]:
        """Residuals F^_i - F_i in N."""
        return np.asarray(self.predicted_friction_n) - np.asarray(self.friction_n)

    @property
    def point_relative_error_pct(self) -> NDArray[np.float64]:
        """Signed relative error per point in % (NaN where F_i = 0)."""
        from exofric.friction._fit import relative_errors

        return relative_errors(self.predicted_friction_n, self.friction_n)

    @property
    def gamma_relative_error_pct(self) -> float:
        """Mean |relative error| (%) of the pooled single-gamma fit on the same points."""
        from exofric.friction._fit import relative_errors

        e = relative_errors(self.gamma_predicted_friction_n, self.friction_n)
        e = e[np.isfinite(e)]
        return float(np.mean(np.abs(e))) if e.size else float("nan")

    def per_structure(self) -> list[dict[str, Any]]:
        """Per structure: points, wrap ratio range and both laws' mean |relative error| (%).

        Returns
        -------
        list of dict
            ``name``, ``n_points``, ``wrap_ratio_min``/``_max`` (S/N, unitless),
            ``relative_error_pct`` (this law) and ``gamma_relative_error_pct`` (pooled gamma).

        Examples
        --------
        >>> c = InterfaceCurves([0.2, 0.6], [22.0, 264.0], [20.0, 240.0], "a")
        >>> d = InterfaceCurves([0.2, 0.6], [30.0, 360.0], [20.0, 240.0], "b")
        >>> fit = fit_interfaces([InterfaceTest(c, [0.2, 0.4, 0.6], [15.0, 98.0, 180.0]),
        ...                       InterfaceTest(d, [0.2, 0.6], [19.0, 228.0])])
        >>> [s["name"] for s in fit.per_structure()]
        ['a', 'b']
        """
        from exofric.friction._fit import relative_errors

        names = np.asarray(self.structure, dtype=object)
        e_i = relative_errors(self.predicted_friction_n, self.friction_n)
        e_g = relative_errors(self.gamma_predicted_friction_n, self.friction_n)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.asarray(self.wire_pressure_integral_n) / np.asarray(self.squeeze_force_n)
        out = []
        for s in self.structures:
            m = names == s
            r = ratio[m][np.isfinite(ratio[m])]
            out.append({
                "name": s, "n_points": int(m.sum()),
                "wrap_ratio_min": float(r.min()) if r.size else None,
                "wrap_ratio_max": float(r.max()) if r.size else None,
                "relative_error_pct": _mean_abs(e_i[m]),
                "gamma_relative_error_pct": _mean_abs(e_g[m]),
            })
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (coefficients unitless, forces N, pressures MPa, errors %)."""
        d: dict[str, Any] = {
            "law": "interfaces",
            "model": self.kind,
            "mu_tube": self.mu_tube,
            "mu_wall": self.mu_wall,
            "mu_tube_ci": list(self.mu_tube_ci),
            "mu_wall_ci": list(self.mu_wall_ci),
            "mu_tube_se": self.mu_tube_se,
            "mu_wall_se": self.mu_wall_se,
            "correlation": self.correlation,
            "condition_number": self.condition_number,
            "condition_number_max": self.condition_number_max,
            "identifiable": self.identifiable,
            "identifiability_reason": self.identifiability_reason,
            "ci_method": self.ci_method,
            "ci_note": self.ci_note,
            "dof": self.dof,
            "relative_error_pct": self.relative_error_pct,
            "max_relative_error_pct": self.max_relative_error_pct,
            "relative_rms_residual_pct": self.relative_rms_residual_pct,
            "gamma_pooled": self.gamma_pooled,
            "gamma_relative_error_pct": self.gamma_relative_error_pct,
            "n_points": self.n_points,
            "n_dropped": self.n_dropped,
            "n_clusters": self.n_clusters,
            "n_structures": len(self.structures),
            "lack_of_fit": None if self.lack_of_fit is None else self.lack_of_fit.to_dict(),
            "per_structure": self.per_structure(),
            "structure": list(self.structure),
            "pressure_mpa": list(self.pressure_mpa),
            "wire_pressure_integral_n": list(self.wire_pressure_integral_n),
            "squeeze_force_n": list(self.squeeze_force_n),
            "friction_n": list(self.friction_n),
            "predicted_friction_n": list(self.predicted_friction_n),
            "gamma_predicted_friction_n": list(self.gamma_predicted_friction_n),
            "residual_n": self.residual_n.tolist(),
            "point_relative_error_pct": self.point_relative_error_pct.tolist(),
            "warnings": list(self.warnings),
        }
        if self.kind == "affine":
            d["f0_n"] = self.f0_n
            d["f0_ci_n"] = None if self.f0_ci_n is None else list(self.f0_ci_n)
        return d

    def to_frame(self) -> pd.DataFrame:
        """The points used as a DataFrame: one row per point (MPa, N, %).

        Columns: ``structure``, ``pressure_mpa``, ``wire_pressure_integral_n``,
        ``squeeze_force_n``, ``friction_n`` (measured), ``predicted_friction_n``,
        ``gamma_predicted_friction_n`` (pooled gamma), ``residual_n``,
        ``relative_error_pct`` and ``group``.

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> c = InterfaceCurves([0.2, 0.6], [22.0, 264.0], [20.0, 240.0], "a")
        >>> d = InterfaceCurves([0.2, 0.6], [30.0, 360.0], [20.0, 240.0], "b")
        >>> fit = fit_interfaces([InterfaceTest(c, [0.2, 0.6], [15.0, 180.0]),
        ...                       InterfaceTest(d, [0.2, 0.6], [19.0, 228.0])])
        >>> fit.to_frame()["structure"].tolist()
        ['a', 'a', 'b', 'b']
        """
        import pandas as pd

        return pd.DataFrame({
            "structure": list(self.structure),
            "pressure_mpa": np.asarray(self.pressure_mpa, dtype=float),
            "wire_pressure_integral_n": np.asarray(self.wire_pressure_integral_n, dtype=float),
            "squeeze_force_n": np.asarray(self.squeeze_force_n, dtype=float),
            "friction_n": np.asarray(self.friction_n, dtype=float),
            "predicted_friction_n": np.asarray(self.predicted_friction_n, dtype=float),
            "gamma_predicted_friction_n": np.asarray(self.gamma_predicted_friction_n,
                                                     dtype=float),
            "residual_n": self.residual_n,
            "relative_error_pct": self.point_relative_error_pct,
            "group": [str(g) for g in self.group] if self.group else list(self.pressure_mpa),
        })

    def plot(self, fig: Any | None = None, *, title: str = "") -> Any:
        """Draw measured vs fitted friction per structure (both laws) and relative errors (%).

        Two Axes (:func:`exofric.plots.plot_interface_fit`); write the figure with
        :func:`exofric.plots.save`.

        Parameters
        ----------
        fig : matplotlib Figure, optional
            Empty figure to draw on (default a new one).
        title : str
            Figure title.

        Returns
        -------
        matplotlib Figure

        Examples
        --------
        >>> c = InterfaceCurves([0.2, 0.6], [22.0, 264.0], [20.0, 240.0], "a")
        >>> d = InterfaceCurves([0.2, 0.6], [30.0, 360.0], [20.0, 240.0], "b")
        >>> fit = fit_interfaces([InterfaceTest(c, [0.2, 0.6], [15.0, 180.0]),
        ...                       InterfaceTest(d, [0.2, 0.6], [19.0, 228.0])])
        >>> len(fit.plot().axes)
        2
        """
        from exofric.plots import plot_interface_fit

        return plot_interface_fit(self, title, fig=fig)


def _mean_abs(e: NDArray[np.float64]) -> float | None:
    e = e[np.isfinite(e)]
    return float(np.mean(np.abs(e))) if e.size else None


def _scaled_condition(x: NDArray[np.float64]) -> float:
    """Condition number of x with its columns scaled to unit length (not centred)."""
    norms = np.linalg.norm(x, axis=0)
    if np.any(norms == 0):
        return float("inf")
    sv = np.linalg.svd(x / norms, compute_uv=False)
    return float(sv[0] / sv[-1]) if sv[-1] > 0 else float("inf")


def _check_interface_options(tests: Sequence[InterfaceTest], model: str, ci: str,
                             edge_tol_mpa: float, max_condition_number: float
                             ) -> tuple[list[InterfaceTest], float, float]:
    """Check the options; return the tests, the edge tolerance (MPa) and the kappa threshold."""
    if model not in ("proportional", "affine"):
        raise InputError(f"model must be 'proportional' or 'affine', got {model!r}")
    methods = ("auto", "analytic", "ols", "cluster")
    if ci not in methods:
        raise InputError(f"ci must be one of {', '.join(methods)} for the interface law, got "
                         f"{ci!r}")
    tests = list(tests)
    if not tests:
        raise InputError("fit_interfaces needs at least one structure's tests")
    for t in tests:
        if not isinstance(t, InterfaceTest):
            raise InputError("tests must be InterfaceTest objects (FE curves + friction "
                             "points of one structure)", param="tests")
    tol = check_range("edge_tol_mpa", edge_tol_mpa, 0.0, 0.1, unit="MPa")
    kmax = check_range("max_condition_number", max_condition_number, 1.0, 1e9)
    return tests, tol, kmax


@dataclass(frozen=True)
class _InterfacePoints:
    """The points an interface fit uses: structure, P (MPa), S_wire, N, F (N), cluster label.

    Each structure's points are sorted by pressure; ``labels`` join the block index and the
    point's group (or pressure) with ``\\x1f``; ``n_given`` counts all points given.
    """

    names: tuple[str, ...]
    p: NDArray[np.float64]
    s: NDArray[np.float64]
    n: NDArray[np.float64]
    f: NDArray[np.float64]
    labels: NDArray[Any]
    n_given: int

    @property
    def m(self) -> int:
        """Number of points used."""
        return int(self.p.size)


def _interface_points(tests: list[InterfaceTest], tol: float, model: str, k: int
                      ) -> _InterfacePoints:
    """Read S and N (N) off each structure's curves at its test pressures (MPa), in range."""
    rows: list[tuple[str, float, float, float, float, str]] = []
    n_all = 0
    for i, t in enumerate(tests):
        p = np.asarray(t.pressure_mpa)
        f = np.asarray(t.friction_n)
        s, n, inside = t.curves.at(p, edge_tol_mpa=tol)
        n_all += p.size
        lab = t.groups if t.groups else tuple(p.tolist())
        name = t.curves.name or f"structure {i + 1}"
        order = np.argsort(p, kind="stable")
        for j in order:
            if inside[j]:
                rows.append((name, float(p[j]), float(s[j]), float(n[j]), float(f[j]),
                             f"{i}\x1f{lab[j]}"))
    m = len(rows)
    if m < k + 1:
        raise InputError(f"only {m} friction points lie inside the FE curves' pressure ranges; "
                         f"the {model} interface fit needs at least {k + 1}")
    return _InterfacePoints(
        names=tuple(r[0] for r in rows), p=np.array([r[1] for r in rows]),
        s=np.array([r[2] for r in rows]), n=np.array([r[3] for r in rows]),
        f=np.array([r[4] for r in rows]), labels=np.array([r[5] for r in rows]),
        n_given=n_all,
    )


def _interface_design(pts: _InterfacePoints, affine: bool) -> tuple[NDArray[np.float64], float]:
    """The design [S, N (, 1)] (N) and its scaled condition number; InputError if singular."""
    cols = [pts.s, pts.n] + ([np.ones(pts.m)] if affine else [])
    x = np.column_stack(cols)
    kappa = _scaled_condition(x)
    if not kappa < 1e10:
        raise InputError(
            "wire_pressure_integral_n and squeeze_force_n are proportional (or zero) at the "
            "test pressures, so mu_tube and mu_wall cannot be separated; fit gamma instead "
            "(law gamma) or add a structure of different geometry")
    return x, kappa


def _interface_method(ci: str, replicates: bool, g: int, k: int, model: str
                      ) -> tuple[str, str]:
    """The interval method (``"auto"`` resolved) and the note's fallback clause, if any."""
    method = ci
    fallback = ""
    if ci == "auto":
        method = "cluster" if replicates and g > k else "analytic"
        if replicates and g <= k:
            fallback = (f"; only {g} clusters (a cluster-robust interval needs {k + 1}), so "
                        "replicates are treated as independent")
    if method == "cluster" and g <= k:
        raise InputError(f"ci cluster needs at least {k + 1} clusters for the {model} "
                         f"interface fit, got {g}")
    return method, fallback


def _interface_covariance(
    method: str, x: NDArray[np.float64], f: NDArray[np.float64], beta: NDArray[np.float64],
    codes: NDArray[np.intp], g: int, fallback: str,
) -> tuple[NDArray[np.float64], NDArray[np.float64], str]:
    """Covariance of the coefficients (unitless, N), t dof per coefficient and the note."""
    from exofric.friction import _fit as fitmod

    m, k = x.shape
    e = f - x @ beta
    dofs = np.full(k, float(m - k))
    if method == "cluster":
        variant = fitmod._CLUSTER_VARIANT
        if variant == "cr2bm":
            cov, dofs = fitmod._cr2_bm(x, f, beta, codes, g)
            dof_text = f"{dofs[0]:.1f} (Bell-McCaffrey)"
        else:
            cov = fitmod._cluster_covariance(x, f, beta, codes, g, variant)
            dofs = np.full(k, float(g - 1))
            dof_text = str(g - 1)
        note = (f"cluster-robust ({fitmod._VARIANT_TEXT[variant]}) over {g} (structure, "
                f"pressure) clusters of {m} points; t with {dof_text} dof")
    elif method == "ols":
        cov = lsq_covariance(x, residual_variance(e, k))
        note = f"classical OLS (equal variances); t with {m - k} dof; points independent"
    else:
        cov = hc3_covariance(x, e)
        note = (f"HC3 heteroscedasticity-robust; t with {m - k} dof; {m} points treated as "
                "independent" + fallback)
    return cov, dofs, note


@dataclass(frozen=True)
class _InterfaceInterval:
    """The 95 % CI of an interface fit: method, note, standard errors, half-widths (unitless,
    F0 in N), the t dof of mu_tube, the mu_tube-mu_wall correlation and the cluster count."""

    method: str
    note: str
    se: NDArray[np.float64]
    half: NDArray[np.float64]
    dof: float
    corr: float
    n_clusters: int


def _interface_interval(
    method: str, x: NDArray[np.float64], f: NDArray[np.float64], beta: NDArray[np.float64],
    codes: NDArray[np.intp], g: int, fallback: str,
) -> _InterfaceInterval:
    """t x standard-error 95 % CIs of the coefficients by ``method`` (F in N)."""
    from scipy import stats

    cov, dofs, note = _interface_covariance(method, x, f, beta, codes, g, fallback)
    se = standard_errors(cov)
    tq = np.array([float(stats.t.ppf(0.975, d)) if d > 0 else float("nan") for d in dofs])
    with np.errstate(divide="ignore", invalid="ignore"):
        corr = float(cov[0, 1] / np.sqrt(cov[0, 0] * cov[1, 1]))
    return _InterfaceInterval(method=method, note=note, se=se, half=tq * se,
                              dof=float(dofs[0]), corr=corr, n_clusters=g)


def _identifiability(kappa: float, kmax: float, corr: float, beta: NDArray[np.float64],
                     half: NDArray[np.float64]) -> tuple[bool, str]:
    """Whether mu_tube and mu_wall are separated (kappa, CI half-widths ``half``) and why."""
    reasons = []
    if kappa > kmax:
        reasons.append(
            f"the design is collinear: condition number {kappa:.3g} > {kmax:g} (estimate "
            f"correlation {corr:.4f}); S_wire/N varies too little over the data "
            "(one structure, or structures with like wrap ratios), so only their combination, "
            "gamma, is determined; add a structure of different geometry")
    for nm, b, h in (("mu_tube", beta[0], half[0]), ("mu_wall", beta[1], half[1])):
        if not (np.isfinite(h) and h <= CI_REL_MAX * abs(b)):
            reasons.append(f"{nm}'s 95 % CI [{b - h:.4g}, {b + h:.4g}] is wider than "
                           f"+-{100 * CI_REL_MAX:g} % of its estimate")
    if not reasons:
        return True, (f"condition number {kappa:.3g} <= {kmax:g} and both 95 % CIs within "
                      f"+-{100 * CI_REL_MAX:g} % of the estimates")
    return False, "mu_tube and mu_wall are not separated by these data: " + "; ".join(reasons)


def _interface_warnings(identifiable: bool, reason: str, beta: NDArray[np.float64]
                        ) -> list[str]:
    """The fit's warnings: not identifiable, a coefficient negative or above ``MU_WARN``."""
    warns: list[str] = []
    if not identifiable:
        warns.append(reason)
    for nm, b in (("mu_tube", beta[0]), ("mu_wall", beta[1])):
        if b < 0:
            warns.append(f"fitted {nm} = {b:.4g} is negative, which is unphysical: the data "
                         "do not support the interface law as fitted (collinear design, "
                         "model error or mispaired files)")
        elif b > MU_WARN:
            warns.append(f"fitted {nm} = {b:.4g} is above {MU_WARN:g}: implausible for a "
                         "Coulomb coefficient; check the data pairing")
    return [" ".join(w.split()) for w in warns]


def _interface_result(
    pts: _InterfacePoints, model: ModelKind, x: NDArray[np.float64],
    beta: NDArray[np.float64], iv: _InterfaceInterval, kappa: float, kmax: float,
    identifiable: bool, reason: str, warns: list[str], lof: Any,
) -> InterfaceFit:
    """The :class:`InterfaceFit`, with the pooled single-gamma fit of the same points."""
    from exofric.friction import _fit as fitmod

    affine = model == "affine"
    m, f_used, se = pts.m, pts.f, iv.se
    pred = x @ beta
    e = f_used - pred
    lo, hi = beta - iv.half, beta + iv.half
    # pooled single-gamma comparison on the same points
    xg = np.column_stack([pts.n] + ([np.ones(m)] if affine else []))
    bg, *_ = np.linalg.lstsq(xg, f_used, rcond=None)
    pred_g = xg @ bg
    rel = fitmod.relative_errors(pred, f_used)
    ok = np.isfinite(rel)
    mean_rel = float(np.mean(np.abs(rel[ok]))) if np.any(ok) else float("nan")
    rms = (float(100.0 * np.sqrt(float(e @ e) / float(f_used @ f_used)))
           if np.any(f_used) else float("nan"))
    return InterfaceFit(
        kind=model,
        mu_tube=float(beta[0]), mu_wall=float(beta[1]), f0_n=float(beta[2]) if affine else 0.0,
        mu_tube_ci=(float(lo[0]), float(hi[0])), mu_wall_ci=(float(lo[1]), float(hi[1])),
        f0_ci_n=(float(lo[2]), float(hi[2])) if affine else None,
        mu_tube_se=float(se[0]), mu_wall_se=float(se[1]),
        f0_se_n=float(se[2]) if affine else None,
        correlation=iv.corr, condition_number=kappa, identifiable=identifiable,
        identifiability_reason=reason, ci_method=iv.method, ci_note=iv.note, dof=iv.dof,
        n_clusters=iv.n_clusters, lack_of_fit=lof, structure=pts.names,
        pressure_mpa=tuple(pts.p.tolist()),
        wire_pressure_integral_n=tuple(pts.s.tolist()),
        squeeze_force_n=tuple(pts.n.tolist()), friction_n=tuple(f_used.tolist()),
        predicted_friction_n=tuple(pred.tolist()), relative_error_pct=mean_rel,
        max_relative_error_pct=fitmod._signed_max(rel), relative_rms_residual_pct=rms,
        n_dropped=int(pts.n_given - m), gamma_pooled=float(bg[0]),
        gamma_predicted_friction_n=tuple(pred_g.tolist()), warnings=tuple(warns),
        group=tuple(str(v).split("\x1f", 1)[1] for v in pts.labels), condition_number_max=kmax,
    )


def fit_interfaces(
    tests: Sequence[InterfaceTest],
    *,
    model: ModelKind = "proportional",
    ci: InterfaceCi = "auto",
    edge_tol_mpa: float = 0.005,
    max_condition_number: float = KAPPA_MAX,
) -> InterfaceFit:
    """Fit mu_tube and mu_wall (and F0) to friction tests of one or more structures.

    Least squares of F_i = mu_tube S_i + mu_wall N_i (+ F0) over all points, with S and N of
    each point's structure read off its FE curves by PCHIP at the test pressure (points
    outside a curve's range, beyond ``edge_tol_mpa``, are dropped and counted).

    Parameters
    ----------
    tests : sequence of InterfaceTest
        One block per structure (its FE curves and its friction tests, MPa and N). Names
        should differ (they label the points); two blocks of one structure are fine.
    model : {"proportional", "affine"}
        Without (default) or with a pressure-independent drag F0 (N).
    ci : {"auto", "analytic", "ols", "cluster"}
        95 % CI: ``"analytic"`` t (n - k dof) x HC3-robust standard errors; ``"ols"``
        classical; ``"cluster"`` cluster-robust over replicate clusters (the covariance
        variant that :func:`fit_gamma` uses, default CR2
        with Bell-McCaffrey dof); ``"auto"``: ``"cluster"`` when some (structure, pressure)
        cluster holds >= 2 points and there are more than k clusters, else ``"analytic"``.
    edge_tol_mpa : float
        Pressure tolerance (MPa) beyond each curve's ends, as in ``fit_gamma``.
    max_condition_number : float
        Largest scaled condition number (unitless, >= 1) of an identifiable fit; default
        :data:`KAPPA_MAX` (justified in the module docstring).

    Returns
    -------
    InterfaceFit

    Raises
    ------
    InputError
        No tests, too few points inside the curves (k + 1 needed), a bad ``model``/``ci``, or
        S and N exactly proportional at the test pressures (the split is undefined).

    Warns
    -----
    IdentifiabilityWarning
        The data cannot separate the two coefficients (the estimates are still returned).

    Examples
    --------
    Two structures whose wrap ratios S/N differ (1.1 and 1.5) separate the coefficients:

    >>> c = InterfaceCurves([0.2, 0.4, 0.6], [22.0, 110.0, 264.0], [20.0, 100.0, 240.0], "a")
    >>> d = InterfaceCurves([0.2, 0.4, 0.6], [30.0, 150.0, 360.0], [20.0, 100.0, 240.0], "b")
    >>> law = InterfaceFrictionModel(0.5, 0.2)
    >>> tests = [InterfaceTest(k, [0.2, 0.4, 0.6],
    ...                        law.friction_n(*k.at([0.2, 0.4, 0.6])[:2])) for k in (c, d)]
    >>> fit = fit_interfaces(tests)
    >>> round(fit.mu_tube, 9), round(fit.mu_wall, 9), round(fit.condition_number, 1)
    (0.5, 0.2, 13.1)
    """
    from exofric.friction import _fit as fitmod

    tests, tol, kmax = _check_interface_options(tests, model, ci, edge_tol_mpa,
                                                max_condition_number)
    affine = model == "affine"
    k = 3 if affine else 2
    pts = _interface_points(tests, tol, model, k)
    x, kappa = _interface_design(pts, affine)
    beta = np.asarray(np.linalg.lstsq(x, pts.f, rcond=None)[0], dtype=np.float64)
    e = pts.f - x @ beta
    codes, g = fitmod._factorize(pts.labels)
    replicates = bool(np.bincount(codes).max() >= 2)
    lof = fitmod._lack_of_fit(pts.f, -e, codes, g, k) if replicates else None
    method, fallback = _interface_method(ci, replicates, g, k, model)
    iv = _interface_interval(method, x, pts.f, beta, codes, g, fallback)
    identifiable, reason = _identifiability(kappa, kmax, iv.corr, beta, iv.half)
    warns = _interface_warnings(identifiable, reason, beta)
    for w in warns:
        warnings.warn(w, IdentifiabilityWarning, stacklevel=2)
    return _interface_result(pts, model, x, beta, iv, kappa, kmax, identifiable, reason, warns,
                             lof)


@checked_init
@dataclass(frozen=True)
class InterfaceRigRun(DisplayMixin):
    """Virtual-rig tests of one structure with a planted interface law (SYNTHETIC).

    Built by :func:`simulate_interface_rig`.

    Attributes
    ----------
    curves : InterfaceCurves
        The structure's FE curves (MPa, N).
    mu_tube_true, mu_wall_true : float
        The planted coefficients (unitless).
    run : RigRun
        The rig run on the planted friction curve mu_tube S(P) + mu_wall N(P) (its
        ``gamma_true`` is 1: the curve already is the friction).

    Examples
    --------
    >>> c = InterfaceCurves([0.2, 0.4, 0.6], [22.0, 110.0, 264.0], [20.0, 100.0, 240.0], "a")
    >>> r = simulate_interface_rig(c, 0.5, 0.2, seed=1)
    >>> [round(f, 6) for f in r.run.true_friction_n]
    [15.0, 75.0, 180.0]
    """

    curves: InterfaceCurves
    mu_tube_true: float
    mu_wall_true: float
    run: RigRun

    @property
    def pressure_mpa(self) -> tuple[float, ...]:
        """Reduced test pressures (MPa)."""
        return self.run.pressure_mpa

    @property
    def friction_n(self) -> tuple[float, ...]:
        """Reduced friction per test point (N)."""
        return self.run.friction_n

    def to_test(self) -> InterfaceTest:
        """The points as an :class:`InterfaceTest` for :func:`fit_interfaces`.

        Returns
        -------
        InterfaceTest

        Examples
        --------
        >>> c = InterfaceCurves([0.2, 0.6], [22.0, 264.0], [20.0, 240.0], "a")
        >>> simulate_interface_rig(c, 0.5, 0.2).to_test().curves.name
        'a'
        """
        return InterfaceTest(self.curves, self.run.pressure_mpa, self.run.friction_n)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: planted coefficients (unitless), points (MPa, N), settings."""
        d = self.run.to_dict()
        d.pop("gamma_true", None)
        return {"structure": self.curves.name, "mu_tube_true": self.mu_tube_true,
                "mu_wall_true": self.mu_wall_true, **d}

    def to_csv_text(self) -> str:
        """The rig CSV (``pressure_mpa,friction_n`` [+ ``test``]) with a SYNTHETIC header."""
        head = f"# gamma_true={1.0:g} "
        text = self.run.to_csv_text()
        return text.replace(head, f"# planted F = mu_tube S_wire + mu_wall N + drag: mu_tube="
                            f"{self.mu_tube_true:g} mu_wall={self.mu_wall_true:g} "
                            f"structure={self.curves.name or '-'} ", 1)


def simulate_interface_rig(
    curves: InterfaceCurves,
    mu_tube: float,
    mu_wall: float,
    pressures_mpa: ArrayLike | None = None,
    *,
    config: RigConfig | None = None,
    seed: int = 0,
    repeats: int = 1,
) -> InterfaceRigRun:
    """The virtual rig (:func:`~exofric.friction.simulate_rig`) planting the interface law.

    The rig's friction curve is F(P) = mu_tube S(P) + mu_wall N(P) (+ its ``drag_n``) on the
    curves' nodes; the rig interpolates it by PCHIP and adds its usual noise, lag and
    reduction, exactly as for gamma.

    Parameters
    ----------
    curves : InterfaceCurves
        The structure's FE curves (MPa, N).
    mu_tube, mu_wall : float
        Planted coefficients (unitless; checked like :class:`InterfaceFrictionModel`).
    pressures_mpa : array_like, optional
        Set points (MPa, strictly increasing, inside the curves); default the nodes where
        N > 0.
    config : RigConfig, optional
        Rig, logger and sensor settings.
    seed : int
        RNG seed (deterministic output).
    repeats : int
        Repeated tests (1-100).

    Returns
    -------
    InterfaceRigRun

    Examples
    --------
    >>> c = InterfaceCurves([0.2, 0.4, 0.6], [22.0, 110.0, 264.0], [20.0, 100.0, 240.0], "a")
    >>> r = simulate_interface_rig(c, 0.5, 0.2, seed=3, repeats=2)
    >>> len(r.friction_n), abs(r.friction_n[2] / 180.0 - 1) < 0.01
    (6, True)
    """
    from exofric.friction._rig import simulate_law_rig

    law = InterfaceFrictionModel(mu_tube, mu_wall)
    run = simulate_law_rig(law, curves, pressures_mpa, config=config, seed=seed,
                           repeats=repeats)
    return InterfaceRigRun(curves, law.mu_tube, law.mu_wall, run)
