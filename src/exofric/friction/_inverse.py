"""Exact inverse P(N) of a tabulated (FE) squeeze curve: :class:`CurveInverse`.

The paper inverts its cubic fit (Eq 8/9); this inverts the FE curve N(P) itself by monotone
(PCHIP) interpolation of P against N, which the paper lacked. Units: pressure P in MPa,
squeezing force N and friction F in N (totals over the tube length).

:class:`CurveInverse` is also importable from :mod:`exofric.friction`, where the rest of the
friction model (Eqs 1, 8, 9) lives.

Examples
--------
>>> inv = CurveInverse.from_curve([0.1, 0.2, 0.3], [0.0, 0.0, 5.0])  # contact from 0.2 MPa
>>> inv.squeeze_force_n, inv.pressure_mpa
((0.0, 5.0), (0.2, 0.3))
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from exofric.errors import InputError, check_finite
from exofric.friction._curve import SqueezeCurve

if TYPE_CHECKING:
    from exofric.friction._model import FrictionModel

__all__ = ["CurveInverse"]


@dataclass(frozen=True)
class CurveInverse:
    """Exact inverse P(N) of a tabulated squeeze curve by monotone (PCHIP) interpolation.

    Built with :meth:`from_curve` from FE output (validated as a :class:`SqueezeCurve`);
    leading points with N = 0 (before contact) are dropped except the last one, which
    brackets the contact onset.

    Note that this interpolates P against N, which is not exactly the inverse of the PCHIP
    of N against P that :class:`SqueezeCurve` evaluates (:meth:`SqueezeCurve.pressure` is);
    the two agree at the nodes and differ between them by the interpolation error.

    Attributes
    ----------
    squeeze_force_n, pressure_mpa : tuple of float
        The interpolation nodes (N strictly increasing, N and MPa).

    Examples
    --------
    >>> inv = CurveInverse.from_curve([0.2, 0.3, 0.4], [10.0, 40.0, 90.0])
    >>> inv.pressure(40.0)
    0.3
    """

    squeeze_force_n: tuple[float, ...]
    pressure_mpa: tuple[float, ...]

    @classmethod
    def from_curve(cls, pressure_mpa: ArrayLike, squeeze_force_n: ArrayLike) -> CurveInverse:
        """Check that N(P) is strictly increasing (after contact) and build the inverse.

        Parameters
        ----------
        pressure_mpa : array_like
            Pressures P in MPa: finite, >= 0, strictly increasing.
        squeeze_force_n : array_like
            Squeezing forces N in N, one per pressure: 0 before contact, then strictly
            increasing (validated as a :class:`SqueezeCurve`).

        Returns
        -------
        CurveInverse

        Raises
        ------
        InputError
            Invalid curve, or N not strictly increasing after contact (no unique inverse).

        Examples
        --------
        >>> CurveInverse.from_curve([0.2, 0.4], [10.0, 30.0]).to_dict()
        {'squeeze_force_n': [10.0, 30.0], 'pressure_mpa': [0.2, 0.4]}
        """
        curve = SqueezeCurve(pressure_mpa, squeeze_force_n)
        return cls.from_squeeze_curve(curve)

    @classmethod
    def from_squeeze_curve(cls, curve: SqueezeCurve) -> CurveInverse:
        """The inverse of a :class:`SqueezeCurve` (N strictly increasing after contact).

        Parameters
        ----------
        curve : SqueezeCurve
            The curve N(P) (MPa, N); its leading zero-force nodes but the last are dropped.

        Examples
        --------
        >>> from exofric.friction import SqueezeCurve
        >>> inv = CurveInverse.from_squeeze_curve(SqueezeCurve([0.1, 0.2], [0.0, 4.0]))
        >>> round(inv.pressure(2.0), 12)
        0.15
        """
        p = np.asarray(curve.pressure_mpa)
        n = np.asarray(curve.squeeze_force_n)
        nonpos = np.flatnonzero(n <= 0.0)
        start = int(nonpos[-1]) if nonpos.size else 0
        p, n = p[start:], n[start:]
        bad = np.flatnonzero(np.diff(n) <= 0.0)
        if bad.size or p.size < 2:
            at = p[bad[0] + 1] if bad.size else p[0]
            raise InputError(
                f"squeeze force is not strictly increasing in pressure (at {at:g} MPa); "
                "the inverse P(N) is not unique"
            )
        return cls(tuple(n.tolist()), tuple(p.tolist()))

    def pressure(self, squeeze_force_n: float) -> float:
        """Pressure (MPa) at which the curve reaches squeezing force N (N).

        Parameters
        ----------
        squeeze_force_n : float
            Squeezing force N in N, inside the nodes' range [first, last] N.

        Returns
        -------
        float
            Pressure in MPa (PCHIP of P against N).

        Raises
        ------
        InputError
            The force is outside the curve's range.

        Examples
        --------
        >>> round(CurveInverse.from_curve([0.2, 0.4], [10.0, 30.0]).pressure(20.0), 12)
        0.3
        """
        from scipy.interpolate import PchipInterpolator

        v = check_finite("target squeezing force (N)", squeeze_force_n)
        lo, hi = self.squeeze_force_n[0], self.squeeze_force_n[-1]
        if not lo <= v <= hi:
            raise InputError(
                f"target squeezing force {v:g} N is outside the curve's range "
                f"[{lo:.4g}, {hi:.4g}] N"
            )
        pch = PchipInterpolator(np.array(self.squeeze_force_n), np.array(self.pressure_mpa))
        return float(pch(v))

    def pressure_for_friction(self, target_n: float, model: FrictionModel) -> float:
        """Pressure (MPa) for friction ``target_n`` (N): P(N = (F - F0) / gamma).

        Parameters
        ----------
        target_n : float
            Required friction force F in N.
        model : FrictionModel
            gamma (unitless) and offset F0 (N) that turn F into a squeezing force N.

        Returns
        -------
        float
            Pressure in MPa.

        Raises
        ------
        InputError
            The target friction is outside the range the curve reaches (message in N).

        Examples
        --------
        >>> from exofric.friction import FrictionModel
        >>> inv = CurveInverse.from_curve([0.2, 0.4], [10.0, 30.0])
        >>> round(inv.pressure_for_friction(10.0, FrictionModel(0.5)), 12)   # N = 20 N
        0.3
        """
        f = check_finite("target friction (N)", target_n)
        n = model.squeeze(f)
        lo, hi = self.squeeze_force_n[0], self.squeeze_force_n[-1]
        if not lo <= n <= hi:
            flo, fhi = model.friction(max(lo, 0.0)), model.friction(hi)
            raise InputError(
                f"target friction {f:g} N is outside the curve's range [{flo:.4g}, {fhi:.4g}] N"
            )
        return self.pressure(n)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready nodes: ``squeeze_force_n`` (N), ``pressure_mpa`` (MPa)."""
        return {"squeeze_force_n": list(self.squeeze_force_n),
                "pressure_mpa": list(self.pressure_mpa)}
