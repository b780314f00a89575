"""What a friction law is to its consumers: the :class:`FrictionLaw` protocol.

A friction law turns a structure's FE curves into friction: the paper's equivalent coefficient
F = gamma N + F0 (:class:`~exofric.friction.FrictionModel`), the interface-resolved
F = mu_tube S_wire + mu_wall N + F0 (:class:`~exofric.friction.InterfaceFrictionModel`), or a
new one. Prediction (:func:`~exofric.friction.predict`), the virtual rig
(:func:`~exofric.friction.simulate_law_rig`) and the controller's friction map
(:meth:`exofric.control.CurveFrictionMap.from_law`) ask a law only for

* ``name`` -- a short label (``"gamma"``, ``"interfaces"``): the ``law`` of JSON outputs and
  the prefix of comparison columns;
* ``inputs`` -- the FE curve columns it reads besides the pressure, each a force in N totalled
  over the tube length: ``"squeeze_force_n"`` (the squeezing force N), and
  ``"wire_pressure_integral_n"`` (S_wire, the tube-wire contact pressure integrated over the
  arc, times the length);
* ``f0_n`` -- its pressure-independent drag in N;
* ``friction_of(columns)`` -- F in N at each pressure, given ``columns["pressure_mpa"]`` (MPa)
  and one array per name in ``inputs`` (N), all of one length;
* ``to_dict()`` -- its coefficients, JSON-ready (unit-suffixed keys).

:func:`law_columns` reads those columns off curves (an object with attributes of these names,
such as :class:`~exofric.friction.SqueezeCurve` or :class:`~exofric.friction.InterfaceCurves`,
or a mapping) and names a missing one.

Examples
--------
>>> from exofric.friction import FrictionModel, InterfaceFrictionModel
>>> isinstance(FrictionModel(0.7), FrictionLaw), isinstance(InterfaceFrictionModel(0.5, 0.2),
...                                                          FrictionLaw)
(True, True)
>>> law = FrictionModel(0.5, f0_n=1.0)
>>> law.friction_of({"pressure_mpa": [0.2, 0.4], "squeeze_force_n": [20.0, 60.0]}).tolist()
[11.0, 31.0]
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from exofric.errors import InputError

__all__ = ["FrictionLaw", "curve_column", "law_columns"]

#: The column every law is given: the pressures (MPa).
PRESSURE_KEY = "pressure_mpa"


@runtime_checkable
class FrictionLaw(Protocol):
    """A friction law F (N) of a structure's FE curves (see the module docstring).

    Attributes
    ----------
    name : str
        Short label of the law (``"gamma"``, ``"interfaces"``).
    inputs : tuple of str
        The FE curve columns it reads besides ``pressure_mpa`` (each in N).
    f0_n : float
        Pressure-independent drag in N.

    Examples
    --------
    A law is any object with these members; no base class is needed:

    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Constant:                      # F = f0, whatever the pressure
    ...     f0_n: float
    ...     name = "constant"
    ...     inputs = ()
    ...     def friction_of(self, columns):
    ...         return np.full(np.shape(columns["pressure_mpa"]), self.f0_n)
    ...     def to_dict(self):
    ...         return {"f0_n": self.f0_n}
    >>> isinstance(Constant(5.0), FrictionLaw)
    True
    """

    @property
    def name(self) -> str:
        """Short label of the law (``"gamma"``, ``"interfaces"``)."""
        ...

    @property
    def inputs(self) -> tuple[str, ...]:
        """The FE curve columns read besides ``pressure_mpa`` (each a force in N)."""
        ...

    @property
    def f0_n(self) -> float:
        """Pressure-independent drag in N."""
        ...

    def friction_of(self, columns: Mapping[str, Any]) -> NDArray[np.float64]:
        """Friction F in N per pressure.

        Parameters
        ----------
        columns : mapping of str to array_like
            ``pressure_mpa`` (MPa) and one array per name in :attr:`inputs` (N), one length.

        Returns
        -------
        numpy.ndarray
            F in N, one per pressure.
        """
        ...

    def to_dict(self) -> dict[str, Any]:
        """The law's coefficients, JSON-ready (unit-suffixed keys)."""
        ...


def curve_column(curves: Any, key: str, law: str, *, size: int | None = None,
                 where: str = "") -> NDArray[np.float64]:
    """One column of ``curves`` (attribute or key ``key``) as a 1-D float array.

    Parameters
    ----------
    curves : object or mapping
        The curves.
    key : str
        The column (``pressure_mpa`` in MPa, or a force in N).
    law : str
        The name of the law that needs it (for the message).
    size : int, optional
        The length it must have (the number of pressures).
    where : str
        Prefix of the error message (a structure's name).

    Returns
    -------
    numpy.ndarray
        The values (MPa or N).

    Raises
    ------
    InputError
        Missing, or not of length ``size``; the message names the column.

    Examples
    --------
    >>> curve_column({"squeeze_force_n": [1, 2]}, "squeeze_force_n", "gamma").tolist()
    [1.0, 2.0]
    """
    prefix = f"{where}: " if where else ""
    value = curves.get(key) if isinstance(curves, Mapping) else getattr(curves, key, None)
    if value is None:
        raise InputError(f"{prefix}the friction law {law!r} needs the curve {key!r}, which is "
                         "missing", param=key)
    try:
        out = np.asarray(value, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{prefix}{key} must be numbers", param=key) from None
    if size is not None and out.size != size:
        raise InputError(f"{prefix}{key} has {out.size} values for {size} pressures", param=key)
    return out


def law_columns(law: FrictionLaw, curves: Any, *,
                where: str = "") -> dict[str, NDArray[np.float64]]:
    """The columns ``law.friction_of`` needs, read off ``curves`` as float arrays.

    Parameters
    ----------
    law : FrictionLaw
        The law (its :attr:`~FrictionLaw.inputs`).
    curves : object or mapping
        Attributes or keys ``pressure_mpa`` (MPa) and each of the law's inputs (N), e.g. a
        :class:`~exofric.friction.SqueezeCurve` or :class:`~exofric.friction.InterfaceCurves`.
    where : str
        Prefix of the error message (a structure's name).

    Returns
    -------
    dict of str to numpy.ndarray
        ``pressure_mpa`` (MPa) and the inputs (N), each 1-D and of the pressures' length.

    Raises
    ------
    InputError
        A column missing or of another length; the message names it and the law.

    Examples
    --------
    >>> from exofric.friction import FrictionModel, SqueezeCurve
    >>> cols = law_columns(FrictionModel(0.5), SqueezeCurve([0.2, 0.4], [20.0, 60.0]))
    >>> sorted(cols), cols["squeeze_force_n"].tolist()
    (['pressure_mpa', 'squeeze_force_n'], [20.0, 60.0])
    """
    p = curve_column(curves, PRESSURE_KEY, law.name, where=where)
    out = {PRESSURE_KEY: p}
    for key in law.inputs:
        out[key] = curve_column(curves, key, law.name, size=p.size, where=where)
    return out
