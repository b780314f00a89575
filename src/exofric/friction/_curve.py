"""A tabulated squeeze curve N(P) and its monotone interpolation: :class:`SqueezeCurve`.

The FE gives the squeezing force N (N, total over the tube length) at a list of pressures P
(MPa). Everything downstream -- gamma fitting, the virtual rig, the friction map of the
controller, the design search -- reads N between those pressures off one interpolant: the
monotone piecewise cubic Hermite interpolant (PCHIP, Fritsch-Carlson) of N against P. It passes
through every node, is C1, and is monotone on every interval between nodes, so it never
overshoots the data (a cubic spline does, around the contact onset). Its inverse
:meth:`SqueezeCurve.pressure` is the first root of that same interpolant, so a round trip
``curve(curve.pressure(n)) == n`` holds to round-off.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric import defaults
from exofric.errors import InputError, check_finite, check_series, warn_implausible

if TYPE_CHECKING:
    from exofric.friction._model import FrictionModel
    from exofric.simulate import SqueezeResult

__all__ = ["SqueezeCurve"]


def _check_rise(p: np.ndarray, n: np.ndarray) -> None:
    """The squeeze force grows with pressure: the plausibility rule of :class:`SqueezeCurve`.

    With ``tol = defaults.PLAUSIBLE_N_DROP_REL x`` the largest force (2%, the rig's scatter):
    a net drop larger than ``tol`` from the first pressure with force to the last is an error
    (an inflating tube squeezes harder; the columns may be swapped); a drop between
    consecutive pressures larger than ``tol`` is a warning.
    """
    if n.size < 2 or float(np.max(n)) <= 0.0:
        return
    tol = defaults.PLAUSIBLE_N_DROP_REL * float(np.max(n))
    k0 = int(np.argmax(n > 0.0))
    if n[-1] < n[k0] - tol:
        raise InputError(f"squeeze curve: squeeze_force_n falls from {n[k0]:g} N at {p[k0]:g} "
                         f"MPa to {n[-1]:g} N at {p[-1]:g} MPa; the squeeze force grows with "
                         "pressure (are the columns swapped?)", param="squeeze_force_n")
    drops = np.flatnonzero(np.diff(n) < -tol)
    if drops.size:
        k = int(drops[0])
        warn_implausible(f"squeeze curve: squeeze_force_n falls from {n[k]:g} to {n[k + 1]:g} N "
                         f"between {p[k]:g} and {p[k + 1]:g} MPa, more than the "
                         f"{100 * defaults.PLAUSIBLE_N_DROP_REL:g}% scatter allowed; check "
                         "that row")


@dataclass(frozen=True, init=False)
class SqueezeCurve:
    """A validated squeeze curve N(P) with monotone (PCHIP) interpolation and its inverse.

    Parameters
    ----------
    pressure_mpa : array_like
        Pressures P in MPa: finite, >= 0, strictly increasing, at least 2.
    squeeze_force_n : array_like
        Squeezing forces N in N (totals over the tube length), finite, >= 0, one per pressure.
        N need not be monotone: before contact onset it is 0.

    Attributes
    ----------
    pressure_mpa, squeeze_force_n : tuple of float
        The nodes (MPa, N).

    Notes
    -----
    * ``curve(p)`` is the PCHIP of N on P, defined on the nodes' range
      :attr:`pressure_range_mpa` (``edge_tol_mpa`` admits points slightly outside, evaluated by
      the end cubic pieces); :meth:`slope` is its derivative dN/dP in N/MPa.
    * :meth:`pressure` is the least pressure at which the interpolant reaches a force: the
      first crossing, i.e. on the rising part above contact onset (for N equal to the first
      node's force, the last node of the leading plateau -- the contact onset when N starts
      at 0). Forces outside :attr:`force_range_n` raise :class:`InputError`.
    * The curve says nothing below its first pressure; :meth:`with_origin` adds the point
      (0 MPa, 0 N) -- no pressure, no squeeze -- as a node, as the design search does.

    Raises
    ------
    InputError
        NaN/inf, negative values, unequal lengths, fewer than 2 points, or pressures not
        strictly increasing; the message names the field.

    Examples
    --------
    >>> c = SqueezeCurve([0.1, 0.2, 0.3, 0.4], [0.0, 0.0, 40.0, 90.0])   # contact at 0.2 MPa
    >>> c(0.3), round(c(0.35), 3)
    (40.0, 63.681)
    >>> round(c.pressure(c(0.35)), 9), c.pressure(0.0)
    (0.35, 0.2)
    >>> c.force_range_n
    (0.0, 90.0)
    """

    pressure_mpa: tuple[float, ...]
    squeeze_force_n: tuple[float, ...]

    def __init__(self, pressure_mpa: ArrayLike, squeeze_force_n: ArrayLike) -> None:
        p, n = check_series("pressure_mpa", pressure_mpa, "squeeze_force_n", squeeze_force_n,
                            x_unit="MPa", y_unit="N", x_min=0.0, y_min=0.0,
                            where="squeeze curve")
        _check_rise(p, n)
        # Normalised at construction, where a frozen dataclass sets its fields (through
        # object.__setattr__, as its generated __init__ does): the nodes stored as tuples of float
        # (hashable, comparable) whatever arrays are given.
        object.__setattr__(self, "pressure_mpa", tuple(p.tolist()))
        object.__setattr__(self, "squeeze_force_n", tuple(n.tolist()))

    # -- construction ------------------------------------------------------------------------

    @classmethod
    def from_result(cls, result: SqueezeResult) -> SqueezeCurve:
        """The curve of an FE squeeze (:func:`exofric.simulate.squeeze`): P in MPa, N in N.

        Parameters
        ----------
        result : SqueezeResult
            Its ``pressure_mpa`` (MPa) and ``squeeze_force_n`` (N, total over the tube length).

        Examples
        --------
        >>> from types import SimpleNamespace        # stands in for a SqueezeResult
        >>> r = SimpleNamespace(pressure_mpa=np.array([0.2, 0.4]),
        ...                     squeeze_force_n=np.array([10.0, 30.0]))
        >>> SqueezeCurve.from_result(r).to_dict()
        {'pressure_mpa': [0.2, 0.4], 'squeeze_force_n': [10.0, 30.0]}
        """
        return cls(result.pressure_mpa, result.squeeze_force_n)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> SqueezeCurve:
        """From ``{"pressure_mpa": [...], "squeeze_force_n": [...]}`` (as :meth:`to_dict`).

        Parameters
        ----------
        data : mapping
            ``pressure_mpa`` (list, MPa) and ``squeeze_force_n`` (list, N); other keys are
            ignored.

        Examples
        --------
        >>> SqueezeCurve.from_dict({"pressure_mpa": [0, 1], "squeeze_force_n": [0, 5]})(0.5)
        2.5
        """
        for key in ("pressure_mpa", "squeeze_force_n"):
            if key not in data:
                raise InputError(f"squeeze curve: missing key {key!r} (need pressure_mpa in "
                                 "MPa, squeeze_force_n in N)", param=key)
        return cls(data["pressure_mpa"], data["squeeze_force_n"])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready nodes: ``pressure_mpa`` (MPa), ``squeeze_force_n`` (N)."""
        return {"pressure_mpa": list(self.pressure_mpa),
                "squeeze_force_n": list(self.squeeze_force_n)}

    def with_origin(self) -> SqueezeCurve:
        """This curve with the node (0 MPa, 0 N) prepended when it starts above 0 MPa.

        Examples
        --------
        >>> SqueezeCurve([0.2, 0.4], [10.0, 30.0]).with_origin().pressure_mpa
        (0.0, 0.2, 0.4)
        """
        if self.pressure_mpa[0] <= 0.0:
            return self
        return SqueezeCurve((0.0, *self.pressure_mpa), (0.0, *self.squeeze_force_n))

    # -- ranges ------------------------------------------------------------------------------

    @property
    def pressure_range_mpa(self) -> tuple[float, float]:
        """(first, last) node pressure in MPa: where the curve is defined."""
        return self.pressure_mpa[0], self.pressure_mpa[-1]

    @property
    def force_range_n(self) -> tuple[float, float]:
        """(first node's force, largest force) in N: the forces :meth:`pressure` can invert."""
        return self.squeeze_force_n[0], max(self.squeeze_force_n)

    # -- interpolation -----------------------------------------------------------------------

    @cached_property
    def _pchip(self) -> Any:
        """The PCHIP of N on P (built on first use, kept: a derived value, not a field)."""
        from scipy.interpolate import PchipInterpolator

        return PchipInterpolator(np.array(self.pressure_mpa), np.array(self.squeeze_force_n))

    def _points(self, pressure_mpa: Any, edge_tol_mpa: float) -> tuple[NDArray[np.float64], bool]:
        x = np.asarray(pressure_mpa, dtype=float)
        lo, hi = self.pressure_range_mpa
        tol = float(edge_tol_mpa)
        if not 0.0 <= tol <= 0.1:
            raise InputError(f"edge_tol_mpa must be in [0, 0.1] MPa, got {edge_tol_mpa!r}")
        out = ~((x >= lo - tol) & (x <= hi + tol))
        if np.any(out):
            bad = x[out].ravel()[0]
            raise InputError(f"pressure_mpa must be in the squeeze curve's range [{lo:g}, "
                             f"{hi:g}] MPa, got {bad:g}")
        return x, x.ndim == 0

    def __call__(self, pressure_mpa: Any, *, edge_tol_mpa: float = 0.0) -> Any:
        """Squeezing force N in N at pressure(s) in MPa (float in, float out; array in, array out).

        Parameters
        ----------
        pressure_mpa : float or array_like
            Pressures in MPa, inside :attr:`pressure_range_mpa` (InputError otherwise).
        edge_tol_mpa : float
            0-0.1 MPa: pressures up to this far outside the nodes' range are admitted and
            evaluated by the end cubic pieces (a rig logging 0.6002 MPa at a 0.6 MPa set
            point). Default 0.

        Examples
        --------
        >>> SqueezeCurve([0.2, 0.4], [10.0, 30.0])([0.2, 0.3])
        array([10., 20.])
        """
        x, scalar = self._points(pressure_mpa, edge_tol_mpa)
        y = self._pchip(x)
        return float(y) if scalar else np.asarray(y, dtype=float)

    def slope(self, pressure_mpa: Any, *, edge_tol_mpa: float = 0.0) -> Any:
        """dN/dP in N/MPa at pressure(s) in MPa: the derivative of the interpolant.

        Parameters
        ----------
        pressure_mpa : float or array_like
            Pressures in MPa, inside :attr:`pressure_range_mpa` (InputError otherwise).
        edge_tol_mpa : float
            Admitted distance (0-0.1 MPa) outside the nodes' range, as for ``__call__``.

        Examples
        --------
        >>> SqueezeCurve([0.0, 0.5, 1.0], [0.0, 50.0, 100.0]).slope(0.25)
        100.0
        """
        x, scalar = self._points(pressure_mpa, edge_tol_mpa)
        y = self._pchip.derivative()(x)
        return float(y) if scalar else np.asarray(y, dtype=float)

    def pressure(self, squeeze_force_n: float) -> float:
        """Least pressure (MPa) at which the curve reaches ``squeeze_force_n`` (N).

        The first root of the interpolant (Brent, 1e-12 MPa): on each interval between nodes
        the PCHIP is monotone, so the first interval whose end node reaches the force holds
        the unique first crossing. A force equal to the first node's gives the end of the
        leading plateau (the contact onset for a curve starting at 0 N).

        Parameters
        ----------
        squeeze_force_n : float
            The force in N, inside :attr:`force_range_n`.

        Returns
        -------
        float
            Pressure in MPa.

        Raises
        ------
        InputError
            The force is outside :attr:`force_range_n`, or the curve never rises.

        Examples
        --------
        >>> round(SqueezeCurve([0.2, 0.4], [10.0, 30.0]).pressure(20.0), 12)
        0.3
        """
        from scipy.optimize import brentq

        v = check_finite("squeeze_force_n", squeeze_force_n)
        nn = np.asarray(self.squeeze_force_n)
        pp = np.asarray(self.pressure_mpa)
        lo, hi = self.force_range_n
        if not lo <= v <= hi:
            raise InputError(f"squeeze_force_n must be in the squeeze curve's reachable range "
                             f"[{lo:.6g}, {hi:.6g}] N, got {v:g}")
        if v == lo:
            rise = np.flatnonzero(nn > lo)
            if not rise.size:
                raise InputError(f"squeeze_force_n: the squeeze curve stays at {lo:g} N; "
                                 "no pressure is singled out")
            return float(pp[int(rise[0]) - 1])
        i = int(np.flatnonzero(nn >= v)[0])
        if nn[i] == v:
            # node i is the first to reach v and the piece before it rises from below v
            # monotonically: it reaches v only at its end (no bracket needed, none of its
            # round-off)
            return float(pp[i])
        f = self._pchip
        a, b = float(pp[i - 1]), float(pp[i])
        # the piece is monotone from nn[i-1] < v to nn[i] > v: one root; round-off of the
        # polynomial at the nodes cannot flip the bracket's signs by more than an ulp
        if float(f(b)) - v <= 0.0:
            return b
        if float(f(a)) - v >= 0.0:
            return a
        return float(brentq(lambda x: float(f(x)) - v, a, b, xtol=1e-12))

    def pressure_for_friction(self, target_n: float, model: FrictionModel) -> float:
        """Pressure (MPa) for friction ``target_n`` (N): :meth:`pressure` of N = (F - F0)/gamma.

        The one inverse of a friction map built on a squeeze curve: the feedforward of
        :class:`~exofric.control.CurveFrictionMap`, ``exofric invert --squeeze`` and the design
        search all come here, so ``model.friction(curve(P)) == F`` to round-off.

        Parameters
        ----------
        target_n : float
            Required friction force F in N.
        model : FrictionModel
            gamma (unitless) and offset F0 (N) that turn F into a squeezing force N.

        Returns
        -------
        float
            Pressure in MPa (the contact onset for F = F0 on a curve starting at 0 N).

        Raises
        ------
        InputError
            The target friction is outside the range the curve reaches (message in N).

        Examples
        --------
        >>> from exofric.friction import FrictionModel
        >>> c = SqueezeCurve([0.2, 0.4], [10.0, 30.0])
        >>> round(c.pressure_for_friction(10.0, FrictionModel(0.5)), 12)   # N = 20 N
        0.3
        """
        f = check_finite("target friction (N)", target_n)
        lo, hi = self.force_range_n
        n = model.squeeze(f)
        if not lo <= n <= hi:
            raise InputError(f"target friction {f:g} N is outside the curve's range "
                             f"[{model.friction(max(lo, 0.0)):.4g}, {model.friction(hi):.4g}] N")
        return self.pressure(n)
