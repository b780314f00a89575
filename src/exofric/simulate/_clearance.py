"""Squeezing force with a clearance that varies along the tube (issue 19, first part).

The 2D squeeze assumes one clearance c = D - d1 - d2 (mm) over the whole tube length L. A real
tube is bowed, its OD and wall have tolerances and the wire is not straight, so c varies along
the length. With the clearance distributed as p(c) along the tube (the share of the length with
clearance c), the total squeezing force is

    N_eff(P) = L * integral n(P; c) p(c) dc,

where n(P; c) (N/mm) is the plane-strain squeeze of the section with clearance c (the hole
diameter set to d1 + d2 + c, tube and wire as given). The sections are independent: the 2D
model's own assumption, applied slice by slice.

* :class:`ClearanceDistribution` -- ``delta`` (today's model), ``discrete`` (values and
  weights), ``uniform``, ``normal`` (truncated at the smallest feasible clearance) or
  ``profile`` (a measured clearance along the length).
* :func:`squeeze_with_clearance` -> :class:`ClearanceSqueeze` -- the quadrature: few distinct
  clearances (delta, discrete, a short profile) are each solved directly; a continuous
  distribution is integrated with Gauss quadrature over a monotone (PCHIP) interpolation in c
  of direct solves at Chebyshev-Lobatto clearances (``n_solves``), whose error a test measures
  against direct solves.

Units: mm, MPa, N (N/mm per depth).

Examples
--------
>>> from exofric.geometry import BASE
>>> from exofric.material import MooneyRivlin
>>> d = ClearanceDistribution.uniform(0.0, 0.2)
>>> c, w = d.quadrature(4)
>>> round(float(w.sum()), 12), round(float(c.min()), 4) > 0.0
(1.0, True)
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, check_positive, check_range, warn_implausible
from exofric.geometry import Structure
from exofric.simulate._squeeze import squeeze

if TYPE_CHECKING:
    import pandas as pd

    from exofric.material import MooneyRivlin

__all__ = ["ClearanceDistribution", "ClearanceSqueeze", "squeeze_with_clearance"]

Kind = Literal["delta", "discrete", "uniform", "normal", "profile"]

#: Smallest clearance (mm) a slice may have: the 2D model needs the tube and the wire to fit.
MIN_CLEARANCE_MM = 1e-3
#: Up to this many distinct clearances are solved directly (no interpolation in c).
MAX_DIRECT = 9
#: A clearance more than this share of the tube wall above the structure's own free gap
#: D - d1 - d2 is implausible (the tube's OD or the hole would locally be off by half a wall:
#: far beyond the +-0.1-0.3 mm of extruded silicone tubing); unitless.
PLAUSIBLE_EXCESS_WALL = 0.5
#: Share of the length (unitless) above which impossible clearances are an error and
#: implausible ones a warning.
IMPOSSIBLE_SHARE = 0.01
IMPLAUSIBLE_SHARE = 0.05


@checked_init
@dataclass(frozen=True)
class ClearanceDistribution:
    """How the clearance c (mm) is distributed along the tube (weights: shares of its length).

    Build it with :meth:`delta`, :meth:`discrete`, :meth:`uniform`, :meth:`normal` or
    :meth:`profile`.

    Attributes
    ----------
    kind : {"delta", "discrete", "uniform", "normal", "profile"}
    values_mm : tuple of float
        delta/discrete/profile: the clearances (mm); uniform: (lo, hi); normal: (mean, sd).
    weights : tuple of float
        discrete/profile: the share of the length of each value (unitless, sum 1).

    Examples
    --------
    >>> ClearanceDistribution.normal(0.1, 0.03).support_mm(0.0)
    (0.001, 0.28)
    """

    kind: Kind
    values_mm: tuple[float, ...]
    weights: tuple[float, ...] = field(default=())

    @classmethod
    def delta(cls, clearance_mm: float) -> ClearanceDistribution:
        """One clearance everywhere (today's 2D model).

        Parameters
        ----------
        clearance_mm : float
            Clearance in mm (> 0).

        Returns
        -------
        ClearanceDistribution

        Examples
        --------
        >>> ClearanceDistribution.delta(0.1).quadrature(5)[0].tolist()
        [0.1]
        """
        c = check_range("clearance_mm", clearance_mm, MIN_CLEARANCE_MM, 100.0, unit="mm")
        return cls("delta", (c,), (1.0,))

    @classmethod
    def discrete(cls, clearance_mm: ArrayLike, weights: ArrayLike) -> ClearanceDistribution:
        """Given clearances with the share of the length each covers.

        Parameters
        ----------
        clearance_mm : array_like
            Clearances in mm (> 0).
        weights : array_like
            Shares of the length (>= 0, unitless; normalised to sum 1).

        Returns
        -------
        ClearanceDistribution

        Examples
        --------
        >>> ClearanceDistribution.discrete([0.0, 0.6], [1, 1]).weights
        (0.5, 0.5)
        """
        c = np.asarray(clearance_mm, dtype=float).ravel()
        w = np.asarray(weights, dtype=float).ravel()
        if c.size == 0 or c.size != w.size:
            raise InputError(f"clearance_mm and weights need equal, non-zero lengths, got "
                             f"{c.size} and {w.size}")
        if not (np.all(np.isfinite(c)) and np.all(np.isfinite(w))) or np.any(w < 0) \
                or w.sum() <= 0:
            raise InputError("weights must be finite, >= 0 and not all 0")
        if np.any(c < 0):
            raise InputError(f"clearance_mm must be >= 0 mm (tube and wire must fit the hole), "
                             f"got {float(c.min()):g}")
        c = np.maximum(c, MIN_CLEARANCE_MM)
        return cls("discrete", tuple(c.tolist()), tuple((w / w.sum()).tolist()))

    @classmethod
    def uniform(cls, lo_mm: float, hi_mm: float) -> ClearanceDistribution:
        """Clearance uniform on [lo, hi] mm along the tube.

        Parameters
        ----------
        lo_mm, hi_mm : float
            Bounds in mm (0 <= lo < hi).

        Returns
        -------
        ClearanceDistribution

        Examples
        --------
        >>> ClearanceDistribution.uniform(0.0, 0.6).values_mm
        (0.0, 0.6)
        """
        lo = check_range("lo_mm", lo_mm, 0.0, 100.0, unit="mm")
        hi = check_range("hi_mm", hi_mm, 0.0, 100.0, unit="mm")
        if not hi > lo:
            raise InputError(f"hi_mm must be > lo_mm ({lo:g} mm), got {hi:g}")
        return cls("uniform", (lo, hi))

    @classmethod
    def normal(cls, mean_mm: float, sd_mm: float) -> ClearanceDistribution:
        """Normally distributed clearance, truncated at the smallest feasible clearance.

        Parameters
        ----------
        mean_mm : float
            Mean clearance in mm (> 0).
        sd_mm : float
            Standard deviation in mm (> 0).

        Returns
        -------
        ClearanceDistribution

        Examples
        --------
        >>> ClearanceDistribution.normal(0.3, 0.05).values_mm
        (0.3, 0.05)
        """
        m = check_range("mean_mm", mean_mm, MIN_CLEARANCE_MM, 100.0, unit="mm")
        sd = check_positive("sd_mm", sd_mm, "mm")
        return cls("normal", (m, sd))

    @classmethod
    def profile(cls, position_mm: ArrayLike, clearance_mm: ArrayLike,
                length_mm: float) -> ClearanceDistribution:
        """A measured clearance along the tube, linear between samples.

        Parameters
        ----------
        position_mm : array_like
            Positions along the tube in mm, strictly increasing, covering [0, length_mm].
        clearance_mm : array_like
            Clearance at each position in mm (>= 0).
        length_mm : float
            Tube length in mm.

        Returns
        -------
        ClearanceDistribution

        Raises
        ------
        InputError
            Positions not increasing or not covering the length; negative clearances.

        Examples
        --------
        >>> d = ClearanceDistribution.profile([0, 58, 116], [0.1, 0.3, 0.1], 116.0)
        >>> round(sum(c * w for c, w in zip(d.values_mm, d.weights)), 9)    # mean, mm
        0.2
        """
        x = np.asarray(position_mm, dtype=float).ravel()
        c = np.asarray(clearance_mm, dtype=float).ravel()
        length = check_positive("length_mm", length_mm, "mm")
        if x.size < 2 or x.size != c.size:
            raise InputError(f"profile needs >= 2 positions and one clearance each, got "
                             f"{x.size} and {c.size}")
        if not np.all(np.diff(x) > 0):
            raise InputError("profile positions (mm) must be strictly increasing")
        tol = 1e-6 * length
        if x[0] > tol or x[-1] < length - tol:
            raise InputError(f"profile covers {x[0]:g}-{x[-1]:g} mm, not the tube's 0-"
                             f"{length:g} mm")
        if np.any(c < 0) or not np.all(np.isfinite(c)):
            raise InputError("profile clearances must be finite and >= 0 mm")
        # each linear segment, split at 16 Gauss-Legendre points: the clearance distribution
        g, gw = np.polynomial.legendre.leggauss(16)
        t = 0.5 * (g + 1.0)
        seg = np.diff(x)
        vals = c[:-1, None] + (c[1:] - c[:-1])[:, None] * t[None, :]
        wts = seg[:, None] * 0.5 * gw[None, :]
        vals = np.maximum(vals.ravel(), MIN_CLEARANCE_MM)
        return cls("profile", tuple(vals.tolist()), tuple((wts.ravel() / wts.sum()).tolist()))

    def support_mm(self, lo_floor: float = MIN_CLEARANCE_MM) -> tuple[float, float]:
        """The clearance range (mm) the distribution covers (normal: mean +- 6 sd, floored).

        Parameters
        ----------
        lo_floor : float
            Smallest clearance in mm.

        Returns
        -------
        (float, float)
            Lowest and highest clearance in mm.

        Examples
        --------
        >>> ClearanceDistribution.uniform(0.1, 0.4).support_mm()
        (0.1, 0.4)
        """
        if self.kind == "normal":
            m, sd = self.values_mm
            return (max(m - 6.0 * sd, max(lo_floor, MIN_CLEARANCE_MM)), m + 6.0 * sd)
        if self.kind == "uniform":
            return (max(self.values_mm[0], MIN_CLEARANCE_MM), self.values_mm[1])
        return (min(self.values_mm), max(self.values_mm))

    def check_fits(self, structure: Structure, n: int = 32) -> None:
        """Check the clearances against the structure's hole (issue 38).

        A clearance c at or above D - d2 - ID is impossible (the tube's OD there, D - d2 - c,
        would be at most its ID): an error when it covers more than
        :data:`IMPOSSIBLE_SHARE` of the length. A clearance above the structure's own free gap
        D - d1 - d2 plus half the wall (:data:`PLAUSIBLE_EXCESS_WALL`) is implausible: a
        warning when it covers more than :data:`IMPLAUSIBLE_SHARE` of the length.

        Parameters
        ----------
        structure : Structure
            The hole, tube and wire the clearance is in (mm).
        n : int
            Gauss points of the uniform and normal distributions (1-200, as in
            :meth:`quadrature`).

        Raises
        ------
        InputError
            Clearances impossible in the hole.

        Examples
        --------
        >>> from exofric.geometry import BASE
        >>> try:
        ...     ClearanceDistribution.delta(50.0).check_fits(BASE)
        ... except ValueError as exc:
        ...     print(str(exc)[:57])
        clearance: 100 % of the length has a clearance >= 3.43 mm
        """
        s = structure
        c, w = self.quadrature(n)
        bound = s.hole_mm - s.wire_mm - s.tube_id_mm
        share = float(w[c >= bound].sum())
        if share > IMPOSSIBLE_SHARE:
            raise InputError(
                f"clearance: {100 * share:.0f} % of the length has a clearance >= {bound:.3g} "
                f"mm, impossible in a {s.hole_mm:g} mm hole with a {s.wire_mm:g} mm wire and a "
                f"{s.tube_id_mm:g} mm tube ID (the tube's OD would be at most its ID; its "
                f"own clearance D - d1 - d2 is {s.clearance_mm:.3g} mm)", param="clearance")
        limit = max(s.clearance_mm, 0.0) + PLAUSIBLE_EXCESS_WALL * s.wall_mm
        share = float(w[c > limit].sum())
        if share > IMPLAUSIBLE_SHARE:
            warn_implausible(
                f"clearance: {100 * share:.0f} % of the length has a clearance above "
                f"{limit:.3g} mm (the structure's own D - d1 - d2 = {s.clearance_mm:.3g} mm "
                f"plus half its {s.wall_mm:.3g} mm wall): check the values are mm")

    def quadrature(self, n: int = 32) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Clearances (mm) and weights (sum 1) that integrate over the distribution.

        Parameters
        ----------
        n : int
            Gauss points for uniform and normal (1-200); the others use their own points.

        Returns
        -------
        (ndarray, ndarray)
            Clearances in mm and weights (unitless).

        Examples
        --------
        >>> c, w = ClearanceDistribution.normal(0.3, 0.05).quadrature(20)
        >>> round(float(c @ w), 6)           # the mean
        0.3
        """
        if not isinstance(n, int) or not 1 <= n <= 200:
            raise InputError(f"n must be an integer in [1, 200], got {n!r}")
        if self.kind in ("delta", "discrete", "profile"):
            return np.asarray(self.values_mm, float), np.asarray(self.weights, float)
        if self.kind == "uniform":
            lo, hi = self.support_mm()
            g, gw = np.polynomial.legendre.leggauss(n)
            return lo + (hi - lo) * 0.5 * (g + 1.0), 0.5 * gw
        m, sd = self.values_mm
        g, gw = np.polynomial.hermite_e.hermegauss(n)
        c = m + sd * g
        w = gw / gw.sum()
        keep = c >= MIN_CLEARANCE_MM
        lost = float(w[~keep].sum())
        if lost > 1e-4:
            warn_implausible(f"normal clearance {m:g} +- {sd:g} mm puts {100 * lost:.1f} % of "
                             f"the length below {MIN_CLEARANCE_MM:g} mm (tube and wire would "
                             "not fit): that share is left out and the rest renormalised")
        c, w = c[keep], w[keep] / w[keep].sum()
        return c, w


@checked_init
@dataclass(frozen=True)
class ClearanceSqueeze(DisplayMixin):
    """N_eff(P) over a clearance distribution, with the per-clearance solves it used.

    Attributes
    ----------
    pressure_mpa : tuple of float
        Pressures (MPa).
    squeeze_force_n : tuple of float
        N_eff(P) over the tube length (N).
    squeeze_force_n_per_mm : tuple of float
        The length average of n(P; c) (N/mm).
    solved_clearance_mm : tuple of float
        Clearances solved by the FE (mm).
    solved_force_n_per_mm : tuple of tuple of float
        n(P; c) of each solved clearance (N/mm), one row per clearance.
    interpolated : bool
        True when N_eff integrates an interpolation in c of the solves (continuous
        distributions), False when every clearance was solved directly.
    distribution : ClearanceDistribution
    length_mm : float

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> r = squeeze_with_clearance(BASE, MooneyRivlin.from_shore(62.5), [0.4],
    ...                            ClearanceDistribution.delta(BASE.clearance_mm),
    ...                            accuracy="draft")
    >>> r.interpolated, len(r.solved_clearance_mm)
    (False, 1)
    """

    pressure_mpa: tuple[float, ...]
    squeeze_force_n: tuple[float, ...]
    squeeze_force_n_per_mm: tuple[float, ...]
    solved_clearance_mm: tuple[float, ...]
    solved_force_n_per_mm: tuple[tuple[float, ...], ...]
    interpolated: bool
    distribution: ClearanceDistribution
    length_mm: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (MPa, N, N/mm, mm)."""
        return {
            "pressure_mpa": list(self.pressure_mpa),
            "squeeze_force_n": list(self.squeeze_force_n),
            "squeeze_force_n_per_mm": list(self.squeeze_force_n_per_mm),
            "solved_clearance_mm": list(self.solved_clearance_mm),
            "solved_force_n_per_mm": [list(r) for r in self.solved_force_n_per_mm],
            "interpolated": self.interpolated,
            "clearance_distribution": {"kind": self.distribution.kind,
                                       "values_mm": list(self.distribution.values_mm)[:64]},
            "length_mm": self.length_mm,
        }

    def to_frame(self) -> pd.DataFrame:
        """One row per pressure: ``pressure_mpa``, ``squeeze_force_n``, ``squeeze_force_n_per_mm``.

        Returns
        -------
        pandas.DataFrame
        """
        import pandas as pd

        return pd.DataFrame({"pressure_mpa": self.pressure_mpa,
                             "squeeze_force_n": self.squeeze_force_n,
                             "squeeze_force_n_per_mm": self.squeeze_force_n_per_mm})


def squeeze_with_clearance(
    structure: Structure,
    material: MooneyRivlin,
    pressures_mpa: ArrayLike,
    distribution: ClearanceDistribution,
    *,
    n_solves: int = 7,
    n_quadrature: int = 32,
    **squeeze_options: Any,
) -> ClearanceSqueeze:
    """N_eff(P) = L * integral n(P; c) p(c) dc over a clearance distribution (module docstring).

    Parameters
    ----------
    structure : Structure
        Tube, wire and length (mm); its hole is replaced by d1 + d2 + c for each clearance c.
    material : MooneyRivlin
        Tube material.
    pressures_mpa : array_like
        Strictly increasing pressures (MPa).
    distribution : ClearanceDistribution
        How the clearance is spread along the length.
    n_solves : int
        Direct FE solves over the support for a continuous distribution (3-33; Chebyshev-
        Lobatto clearances, PCHIP in c between them). Up to ``MAX_DIRECT`` distinct clearances
        are always solved directly.
    n_quadrature : int
        Gauss points of the uniform and normal distributions (1-200).
    **squeeze_options
        Passed to :func:`exofric.simulate.squeeze` (``accuracy``, ``mesh``, ``gravity``, ...).

    Returns
    -------
    ClearanceSqueeze

    Raises
    ------
    InputError
        Bad distribution or options, or clearances impossible in the structure's hole
        (:meth:`ClearanceDistribution.check_fits`; implausible ones warn); ConvergenceError
        from a squeeze.

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> two = ClearanceDistribution.discrete([0.05, 0.15], [1, 1])
    >>> r = squeeze_with_clearance(BASE, MooneyRivlin.from_shore(62.5), [0.6], two,
    ...                            accuracy="draft")
    >>> len(r.solved_clearance_mm), r.interpolated
    (2, False)
    """
    from scipy.interpolate import PchipInterpolator

    if not isinstance(distribution, ClearanceDistribution):
        raise InputError("distribution must be a ClearanceDistribution (delta, discrete, "
                         "uniform, normal or profile)")
    if not isinstance(n_solves, int) or not 3 <= n_solves <= 33:
        raise InputError(f"n_solves must be an integer in [3, 33], got {n_solves!r}")
    distribution.check_fits(structure, n_quadrature)
    squeeze_options.setdefault("keep_fields", False)
    c_q, w_q = distribution.quadrature(n_quadrature)
    distinct = np.unique(np.round(c_q, 12))
    p = np.asarray(pressures_mpa, dtype=float).ravel()

    def solve(c: float) -> NDArray[np.float64]:
        hole = structure.tube_od_mm + structure.wire_mm + float(c)
        st = replace(structure, hole_mm=hole)
        r = squeeze(st, material, p, **squeeze_options)
        return np.asarray(r.squeeze_force_n_per_mm, dtype=float)

    if distinct.size <= MAX_DIRECT:
        solved = distinct
        n_c = np.array([solve(c) for c in solved])               # (n_c, n_p)
        idx = np.searchsorted(solved, np.round(c_q, 12))
        n_eff = w_q @ n_c[idx]
        interpolated = False
    else:
        lo, hi = distribution.support_mm()
        k = np.arange(n_solves)
        solved = lo + (hi - lo) * 0.5 * (1.0 - np.cos(np.pi * k / (n_solves - 1)))
        n_c = np.array([solve(c) for c in solved])
        n_eff = w_q @ PchipInterpolator(solved, n_c, axis=0)(np.clip(c_q, lo, hi))
        interpolated = True
    length = structure.length_mm
    return ClearanceSqueeze(
        pressure_mpa=tuple(p.tolist()),
        squeeze_force_n=tuple((length * n_eff).tolist()),
        squeeze_force_n_per_mm=tuple(n_eff.tolist()),
        solved_clearance_mm=tuple(float(c) for c in solved),
        solved_force_n_per_mm=tuple(tuple(r.tolist()) for r in n_c),
        interpolated=interpolated,
        distribution=distribution,
        length_mm=float(length),
    )
