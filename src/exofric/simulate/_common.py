"""Helpers every FE problem of :mod:`exofric.simulate` shares (squeeze, inflation, ring, laws).

* :func:`check_friction` -- the one check of a Coulomb coefficient a user gives.
* :func:`fe_material_of` -- the FE's view of a tube material.
* :func:`resolve_accuracy` -- a named accuracy level to the pair of nested meshes.
* :func:`opt_list` -- an optional array as a JSON list.

They live here, not in one problem's module, so that inflation, the ring test and the friction
laws import them without importing the squeeze.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from exofric import defaults
from exofric.errors import InputError, warn_implausible
from exofric.fe import MU_MAX, MU_WARN, MeshSpec, PlaneStrainMaterial
from exofric.material import MooneyRivlin

__all__ = ["FEMaterial", "check_friction", "fe_material_of", "opt_list", "resolve_accuracy"]


def check_friction(name: str, value: float) -> float:
    """A Coulomb coefficient (unitless): finite, in [0, 2]; warns above 1.5.

    The one check of every friction coefficient a user gives (``mu_wall``, ``mu_wire`` of the
    squeeze, ``mu_tube``, ``mu_wall`` of the interface law, ``mu_arc`` of the capstan).

    Parameters
    ----------
    name : str
        Parameter name for the messages (e.g. ``"mu_wall"``).
    value : float
        The coefficient (unitless).

    Returns
    -------
    float

    Raises
    ------
    InputError
        Not a number, NaN/inf, negative, or above :data:`exofric.fe.MU_MAX` (one line naming
        ``name``).

    Examples
    --------
    >>> check_friction("mu_wall", 0.3)
    0.3
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number (unitless friction coefficient), got "
                         f"{value!r}", param=name) from None
    if not np.isfinite(v):
        raise InputError(f"{name} must be a finite friction coefficient (unitless), got {v}",
                         param=name)
    if v < 0.0:
        raise InputError(f"{name} must be >= 0 (unitless friction coefficient), got {v:g}",
                         param=name)
    if v > MU_MAX:
        raise InputError(f"{name} must be <= {MU_MAX:g} (unitless friction coefficient), got "
                         f"{v:g}", param=name)
    if v > MU_WARN:
        warn_implausible(f"{name} = {v:g} is above {MU_WARN:g}: implausible for a Coulomb "
                         "coefficient of silicone or steel on metal (measured 0.2-1.2); check "
                         "the value")
    return v


#: What the FE problems take: the paper's MooneyRivlin as is, any other model adapted.
FEMaterial = MooneyRivlin | PlaneStrainMaterial


def fe_material_of(material: Any) -> FEMaterial:
    """The FE's view of a tube material: a MooneyRivlin unchanged, a model adapted.

    Parameters
    ----------
    material : MooneyRivlin or HyperelasticModel
        Tube material (MPa, 1/MPa).

    Returns
    -------
    MooneyRivlin or PlaneStrainMaterial

    Raises
    ------
    InputError
        Another type, or parameters Drucker-unstable within the FE's stretches
        (:meth:`~exofric.material.HyperelasticModel.check_fe_stability`).
    """
    if isinstance(material, MooneyRivlin):
        material.check_fe_stability()
        return material
    fe = PlaneStrainMaterial(material)
    fe.source.check_fe_stability()  # Drucker-unstable parameters: InputError (issue 38)
    return fe


def resolve_accuracy(accuracy: str | None, mesh: MeshSpec | None,
                     levels: Mapping[str, Mapping[str, Any]]) -> tuple[str, MeshSpec,
                                                                       MeshSpec | None]:
    """(level name, mesh returned, nested coarse mesh for the estimate or None).

    Parameters
    ----------
    accuracy : {'draft', 'standard', 'fine'} or None
        Named level; None means :data:`exofric.defaults.ACCURACY` unless ``mesh`` is given.
    mesh : MeshSpec or None
        An explicit mesh (then no error estimate: ``accuracy`` is ``"mesh"``).
    levels : mapping
        :data:`exofric.defaults.SQUEEZE_ACCURACY` or :data:`exofric.defaults.INFLATION_ACCURACY`.

    Returns
    -------
    tuple of (str, MeshSpec, MeshSpec or None)

    Examples
    --------
    >>> from exofric import defaults
    >>> name, m, c = resolve_accuracy(None, None, defaults.SQUEEZE_ACCURACY)
    >>> name, m.n_circ, c.n_circ
    ('standard', 32, 16)
    """
    if mesh is not None and accuracy is not None:
        raise InputError("give accuracy or mesh, not both (accuracy names a pair of meshes)",
                         param="accuracy")
    if mesh is not None:
        return "mesh", mesh, None
    name = defaults.ACCURACY if accuracy is None else str(accuracy)
    if name not in levels:
        raise InputError(f"accuracy must be one of {', '.join(levels)}, got {accuracy!r}",
                         param="accuracy")
    lvl = dict(levels[name])
    fr, fc = lvl.pop("coarsen")
    spec = MeshSpec(**lvl)
    return name, spec, spec.coarsened(fr, fc)


def opt_list(a: np.ndarray | None) -> list[float] | None:
    """An optional array as a JSON list (None stays None).

    Examples
    --------
    >>> opt_list(np.array([1, 2])), opt_list(None)
    ([1.0, 2.0], None)
    """
    return None if a is None else np.asarray(a, dtype=float).tolist()
