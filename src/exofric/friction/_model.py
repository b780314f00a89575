"""The friction model (paper Eqs 1, 8, 9): F = gamma N + F0, the Eq 8 cubic, the Eq 9 inverse."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, check_finite, check_positive

__all__ = [
    "CubicFit",
    "FrictionModel",
    "pressure_for_friction",
]


@checked_init
@dataclass(frozen=True)
class FrictionModel:
    """Friction F = gamma N + F0 (paper Eq 1 with F0 = 0).

    Parameters
    ----------
    gamma : float
        Equivalent coefficient (unitless, > 0); the paper's value is 0.7168.
    f0_n : float
        Pressure-independent offset in N (rig drag); 0 for the paper's proportional model.

    Examples
    --------
    >>> round(FrictionModel(0.7168).friction(100.0), 10)
    71.68
    """

    gamma: float
    f0_n: float = 0.0

    def __post_init__(self) -> None:
        check_positive("gamma (equivalent coefficient)", self.gamma)
        check_finite("f0_n (friction offset, N)", self.f0_n)

    @overload
    def friction(self, squeeze_force_n: float) -> float: ...
    @overload
    def friction(self, squeeze_force_n: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def friction(self, squeeze_force_n: Any) -> Any:
        """Friction force in N for squeezing force(s) N in N: gamma N + F0.

        Parameters
        ----------
        squeeze_force_n : float or ndarray
            Squeezing force(s) N in N (float in, float out; array in, array out).

        Examples
        --------
        >>> FrictionModel(0.5, f0_n=2.0).friction(100.0)
        52.0
        """
        if np.ndim(squeeze_force_n) == 0:
            return float(self.gamma * float(squeeze_force_n) + self.f0_n)
        return self.gamma * np.asarray(squeeze_force_n, dtype=float) + self.f0_n

    @overload
    def squeeze(self, friction_n: float) -> float: ...
    @overload
    def squeeze(self, friction_n: NDArray[np.float64]) -> NDArray[np.float64]: ...
    def squeeze(self, friction_n: Any) -> Any:
        """Squeezing force in N that gives friction(s) F in N: (F - F0) / gamma.

        Parameters
        ----------
        friction_n : float or ndarray
            Friction force(s) F in N (float in, float out; array in, array out).

        Examples
        --------
        >>> FrictionModel(0.5, f0_n=2.0).squeeze(52.0)
        100.0
        """
        if np.ndim(friction_n) == 0:
            return float((float(friction_n) - self.f0_n) / self.gamma)
        return (np.asarray(friction_n, dtype=float) - self.f0_n) / self.gamma

    # -- the FrictionLaw protocol -----------------------------------------------------------

    @property
    def name(self) -> str:
        """``"gamma"``: the law's label (:class:`~exofric.friction.FrictionLaw`)."""
        return "gamma"

    @property
    def inputs(self) -> tuple[str, ...]:
        """The FE curve it reads: ``("squeeze_force_n",)``, N in N."""
        return ("squeeze_force_n",)

    def friction_of(self, columns: Mapping[str, Any]) -> NDArray[np.float64]:
        """Friction in N per pressure from the squeezing force: gamma N + F0.

        Parameters
        ----------
        columns : mapping
            ``squeeze_force_n``: N in N per pressure (other keys are not read).

        Returns
        -------
        numpy.ndarray
            F in N.

        Examples
        --------
        >>> FrictionModel(0.5, f0_n=2.0).friction_of({"squeeze_force_n": [0.0, 100.0]})
        array([ 2., 52.])
        """
        return np.asarray(self.friction(np.asarray(columns["squeeze_force_n"], dtype=float)),
                          dtype=float)

    def to_dict(self) -> dict[str, float]:
        """JSON-ready dict: ``gamma`` (unitless), ``f0_n`` (N)."""
        return {"gamma": float(self.gamma), "f0_n": float(self.f0_n)}


@checked_init
@dataclass(frozen=True)
class CubicFit(DisplayMixin):
    """A cubic y(P) = c3 P^3 + c2 P^2 + c1 P + c0 over [p_min, p_max] MPa (paper Eq 8).

    ``y`` is usually the squeezing force N in N (Eq 8) or the friction F in N (Eq 9).

    Parameters
    ----------
    coefficients : (c3, c2, c1, c0)
        Highest power first, P in MPa, y in the unit of the fitted values (N).
    p_min_mpa, p_max_mpa : float
        The fitted pressure range in MPa; :meth:`inverse` only answers inside it.
    r2 : float or None
        Coefficient of determination of the fit (None when the coefficients were given).

    Examples
    --------
    >>> c = CubicFit((-1957.4, 2412.8, -251.95, -7.9531), 0.2, 0.6)
    >>> round(c(0.6), 2)
    286.69
    >>> round(c.inverse(c(0.4)), 12)
    0.4
    """

    coefficients: tuple[float, float, float, float]
    p_min_mpa: float
    p_max_mpa: float
    r2: float | None = None

    def __post_init__(self) -> None:
        if len(self.coefficients) != 4:
            n = len(self.coefficients)
            raise InputError(f"cubic coefficients must be 4 numbers (c3, c2, c1, c0), got {n}")
        coef = tuple(check_finite(f"cubic coefficient c{3 - i}", c)
                     for i, c in enumerate(self.coefficients))
        # Normalised at construction, where a frozen dataclass sets its fields (through
        # object.__setattr__, as its generated __init__ does): the coefficients stored as a tuple
        # of float (hashable) whatever sequence is given.
        object.__setattr__(self, "coefficients", coef)
        lo = check_finite("p_min_mpa", self.p_min_mpa)
        hi = check_finite("p_max_mpa", self.p_max_mpa)
        if not lo < hi:
            raise InputError(
                f"cubic pressure range must have p_min < p_max MPa, got [{lo:g}, {hi:g}]"
            )

    @classmethod
    def fit(
        cls,
        pressure_mpa: ArrayLike,
        values: ArrayLike,
        p_range_mpa: tuple[float, float] | None = None,
    ) -> CubicFit:
        """Least-squares cubic through (P, y) points.

        Parameters
        ----------
        pressure_mpa : array_like
            Pressures in MPa.
        values : array_like
            Values at those pressures (N).
        p_range_mpa : (lo, hi) or None
            Use only points with lo <= P <= hi and record that range; default: the data range.

        Returns
        -------
        CubicFit
            With ``r2`` = 1 - SS_res / SS_tot over the fitted points.

        Raises
        ------
        InputError
            Fewer than 4 distinct pressures in range, NaNs, or mismatched lengths.

        Examples
        --------
        >>> import numpy as np
        >>> p = np.linspace(0.2, 0.6, 9)
        >>> f = CubicFit.fit(p, 2 * p**3 - p + 1)
        >>> [round(c, 9) + 0.0 for c in f.coefficients]
        [2.0, 0.0, -1.0, 1.0]
        """
        p = np.asarray(pressure_mpa, dtype=float).ravel()
        y = np.asarray(values, dtype=float).ravel()
        if p.shape != y.shape:
            raise InputError(
                f"pressure_mpa and values must have the same length, got {p.size} and {y.size}"
            )
        if not (np.all(np.isfinite(p)) and np.all(np.isfinite(y))):
            raise InputError("pressure_mpa and values must be finite numbers (no NaN/inf)")
        if p_range_mpa is not None:
            lo, hi = (check_finite("p_range_mpa low", p_range_mpa[0]),
                      check_finite("p_range_mpa high", p_range_mpa[1]))
            if not lo < hi:
                raise InputError(f"p_range_mpa must have low < high MPa, got [{lo:g}, {hi:g}]")
            keep = (p >= lo) & (p <= hi)
            p, y = p[keep], y[keep]
        if np.unique(p).size < 4:
            raise InputError(
                f"a cubic fit needs at least 4 distinct pressures in range, got {np.unique(p).size}"
            )
        if p_range_mpa is None:
            lo, hi = float(p.min()), float(p.max())
        # Fit in a mapped domain (well conditioned), then convert to powers of P.
        poly = np.polynomial.Polynomial.fit(p, y, 3).convert()
        asc = np.zeros(4)
        asc[: poly.coef.size] = poly.coef
        coef = (float(asc[3]), float(asc[2]), float(asc[1]), float(asc[0]))
        resid = y - np.polyval(coef, p)
        ss_tot = float(np.sum((y - y.mean()) ** 2))
        r2 = 1.0 - float(np.sum(resid**2)) / ss_tot if ss_tot > 0 else 1.0
        return cls(coef, float(lo), float(hi), r2)

    @overload
    def __call__(self, pressure_mpa: float) -> float: ...
    @overload
    def __call__(
        self, pressure_mpa: NDArray[np.float64] | Sequence[float]
    ) -> NDArray[np.float64]: ...
    def __call__(self, pressure_mpa: Any) -> Any:
        """Evaluate y(P), P in MPa (float in, float out; array in, array out)."""
        if np.ndim(pressure_mpa) == 0:
            return float(np.polyval(self.coefficients, float(pressure_mpa)))
        return np.polyval(self.coefficients, np.asarray(pressure_mpa, dtype=float))

    def derivative(self, pressure_mpa: ArrayLike) -> NDArray[np.float64]:
        """dy/dP (unit of y per MPa, N/MPa for Eq 8) at P in MPa.

        Parameters
        ----------
        pressure_mpa : array_like
            Pressure(s) P in MPa (any, also outside the fitted range).

        Returns
        -------
        ndarray
            3 c3 P^2 + 2 c2 P + c1, same shape as ``pressure_mpa``.

        Examples
        --------
        >>> CubicFit((1.0, 0.0, 0.0, 0.0), 0.0, 1.0).derivative([0.5, 1.0]).tolist()
        [0.75, 3.0]
        """
        c3, c2, c1, _ = self.coefficients
        p = np.asarray(pressure_mpa, dtype=float)
        return np.asarray(3.0 * c3 * p**2 + 2.0 * c2 * p + c1, dtype=float)

    def monotonic_sign(self) -> int:
        """+1 if increasing on [p_min, p_max], -1 if decreasing, 0 if not monotonic there."""
        c3, c2, c1, _ = self.coefficients
        lo, hi = self.p_min_mpa, self.p_max_mpa
        # Candidate sign changes of y' are its real roots strictly inside (lo, hi).
        dcoef = np.trim_zeros(np.array([3.0 * c3, 2.0 * c2, c1]), "f")
        pts = [lo, hi]
        if dcoef.size > 1:
            r = np.roots(dcoef)
            r = r[np.abs(r.imag) <= 1e-12 * max(1.0, float(np.max(np.abs(r))))].real
            pts += [float(x) for x in r if lo < x < hi]
        pts = sorted(pts)
        # Sign of y' on each sub-interval (midpoints); endpoints/double roots are allowed zeros.
        mids = 0.5 * (np.array(pts[:-1]) + np.array(pts[1:]))
        s = np.sign(self.derivative(mids))
        if np.all(s > 0):
            return 1
        if np.all(s < 0):
            return -1
        return 0

    def inverse(self, value: float) -> float:
        """Pressure in MPa inside [p_min, p_max] where y(P) == ``value`` (Brent's method).

        Parameters
        ----------
        value : float
            Target y in the unit of the fitted values (N for Eq 8), between y(p_min) and
            y(p_max).

        Returns
        -------
        float
            Pressure in MPa.

        Raises
        ------
        InputError
            If the cubic is not monotonic on the fitted range, or ``value`` lies outside
            [min y, max y] over that range (the message gives the attainable range).

        Examples
        --------
        >>> round(CubicFit((0.0, 0.0, 100.0, 0.0), 0.2, 0.6).inverse(40.0), 12)
        0.4
        """
        from exofric._roots import brentq  # not scipy.optimize: 0.15 s of start-up

        v = check_finite("target value", value)
        sign = self.monotonic_sign()
        lo, hi = self.p_min_mpa, self.p_max_mpa
        if sign == 0:
            raise InputError(
                f"cubic is not monotonic on [{lo:g}, {hi:g}] MPa; its inverse is not unique there"
            )
        ylo, yhi = self(lo), self(hi)
        ymin, ymax = min(ylo, yhi), max(ylo, yhi)
        if not ymin <= v <= ymax:
            raise InputError(
                f"target {v:g} is outside the fit's range [{ymin:.4g}, {ymax:.4g}] "
                f"over [{lo:g}, {hi:g}] MPa"
            )
        if v == ylo:
            return lo
        if v == yhi:
            return hi
        root = brentq(lambda p: self(p) - v, lo, hi, xtol=1e-14, rtol=8.9e-16, maxiter=200)
        return float(root)

    def scaled(self, factor: float) -> CubicFit:
        """This cubic multiplied by ``factor`` (e.g. gamma: Eq 8 -> Eq 9).

        Parameters
        ----------
        factor : float
            Finite multiplier (unitless for gamma; the result's y unit is y's times factor's).

        Returns
        -------
        CubicFit
            Same pressure range (MPa) and ``r2``.

        Examples
        --------
        >>> CubicFit((1.0, 2.0, 3.0, 4.0), 0.2, 0.6).scaled(0.5).coefficients
        (0.5, 1.0, 1.5, 2.0)
        """
        f = check_finite("factor", factor)
        c3, c2, c1, c0 = self.coefficients
        return CubicFit((f * c3, f * c2, f * c1, f * c0), self.p_min_mpa, self.p_max_mpa, self.r2)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: ``coefficients`` (c3, c2, c1, c0; P in MPa), range in MPa, ``r2``."""
        return {
            "coefficients": list(self.coefficients),
            "p_min_mpa": float(self.p_min_mpa),
            "p_max_mpa": float(self.p_max_mpa),
            "r2": None if self.r2 is None else float(self.r2),
        }


def pressure_for_friction(target_n: float, cubic: CubicFit, model: FrictionModel) -> float:
    """Inflation pressure (MPa) that gives friction ``target_n`` (N) under F = gamma N(P) + F0.

    Parameters
    ----------
    target_n : float
        Required friction force in N.
    cubic : CubicFit
        Squeezing force N(P) in N (e.g. Eq 8) over its fitted range.
    model : FrictionModel
        gamma and the offset F0 (N).

    Returns
    -------
    float
        Pressure in MPa inside the cubic's range.

    Raises
    ------
    InputError
        Target outside the friction range reachable over the fitted pressures.

    Examples
    --------
    >>> c = CubicFit((-1957.4, 2412.8, -251.95, -7.9531), 0.2, 0.6)
    >>> round(pressure_for_friction(54.40, c, FrictionModel(0.7168)), 4)
    0.2926
    """
    f = check_finite("target friction (N)", target_n)
    n = model.squeeze(f)
    try:
        return cubic.inverse(n)
    except InputError as exc:
        if "outside" not in str(exc):
            raise
        lo, hi = cubic(cubic.p_min_mpa), cubic(cubic.p_max_mpa)
        flo, fhi = sorted((model.friction(lo), model.friction(hi)))
        raise InputError(
            f"target friction {f:g} N is outside the reachable range [{flo:.4g}, {fhi:.4g}] N "
            f"over [{cubic.p_min_mpa:g}, {cubic.p_max_mpa:g}] MPa"
        ) from None
