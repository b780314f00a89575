"""Forward models for calibration: free inflation of the air tube, memoised.

A calibration model is any callable ``model(shore, tube_id_mm, pressures_mpa)``
returning the tube's outer diameters (mm) at the given strictly increasing
pressures (MPa) for a trial Shore A hardness and tube inner diameter (mm).
:class:`CachedModel` wraps one and memoises its evaluations, so repeated trials
(a bisection revisiting a bracket end, a Jacobian probe) cost nothing.

Factories (:func:`make_model`):

* ``"fe"``: :func:`exofric.simulate.inflate`, the 2D plane-strain FE solver;
* ``"1d"``: :func:`exofric.simulate.compressible_inflation`, the same physics
  (plane strain, Eq 2 with its volumetric term, follower pressure) as a 1D
  radial boundary value problem;
* ``"paper-table1"``: the paper's own ANSYS columns of Table 1 (60, 62.5, 65,
  70 Shore at 0.1-0.4 MPa) interpolated linearly in hardness and pressure; it
  ignores the tube inner diameter (the paper's ANSYS model had a fixed, unprinted
  one). Used to replay the paper's bisection without any simulation.

The material for a trial hardness is built by :func:`material_for` (Eqs 3-6),
either exactly (``c10_convention="eq4"``) or with the paper's printed Table 2
slip (``"paper-slip"``: C10 = G/2/1.005 instead of G/2/1.05).

Units: mm, MPa.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Literal

import numpy as np

from exofric import defaults as D
from exofric.errors import InputError, check_positive, check_pressures
from exofric.material import MooneyRivlin

if TYPE_CHECKING:
    from exofric.fe import MeshSpec

__all__ = [
    "ModelFn",
    "CachedModel",
    "C10Convention",
    "MODEL_KINDS",
    "DEFAULT_MODEL",
    "material_for",
    "make_model",
    "paper_table1_model",
]

#: ``model(shore, tube_id_mm, pressures_mpa) -> outer diameters (mm)``.
ModelFn = Callable[[float, float, np.ndarray], np.ndarray]
#: How C10 follows from E: ``"eq4"`` (the paper's Eq 4) or ``"paper-slip"`` (Table 2's printed
#: values, a /1.005 for /1.05 slip; see paper note M1).
C10Convention = Literal["eq4", "paper-slip"]
#: The inflation models: the FE (``"fe"``), the 1-D radial BVP (``"1d"``), or the paper's Table 1
#: ANSYS columns interpolated (``"paper-table1"``, no simulation).
MODEL_KINDS = ("fe", "1d", "paper-table1")
#: The default inflation model of the calibration.
DEFAULT_MODEL = "fe"

# The divisor the paper printed in Table 2 (C10 = G/2/1.005), a slip for 1 + 0.05.
_SLIP_DIVISOR = 1.005


class CachedModel:
    """Memoising wrapper around a calibration model.

    Parameters
    ----------
    fn : callable
        ``fn(shore, tube_id_mm, pressures_mpa) -> outer diameters (mm)``; pressures
        in MPa, strictly increasing.
    name : str
        Label used in results (``'fe'``, ``'1d'``, ...).

    Attributes
    ----------
    calls : int
        Evaluations that reached ``fn``.
    hits : int
        Evaluations answered from the cache.

    Examples
    --------
    >>> m = CachedModel(lambda s, i, p: 8.3 + p / s, "toy")
    >>> a = m(60.0, 5.0, np.array([0.1, 0.2])); b = m(60.0, 5.0, np.array([0.1, 0.2]))
    >>> (m.calls, m.hits)
    (1, 1)
    """

    def __init__(self, fn: ModelFn, name: str = "custom") -> None:
        self.fn = fn
        self.name = name
        self.calls = 0
        self.hits = 0
        self._cache: dict[tuple[float, float, tuple[float, ...]], np.ndarray] = {}

    def __call__(self, shore: float, tube_id_mm: float, pressures_mpa: np.ndarray) -> np.ndarray:
        """Outer diameters (mm) at ``pressures_mpa`` (MPa) for this hardness and ID (mm)."""
        p = np.asarray(pressures_mpa, dtype=float)
        key = (float(shore), float(tube_id_mm), tuple(p.tolist()))
        hit = self._cache.get(key)
        if hit is not None:
            self.hits += 1
            return hit.copy()
        out = np.asarray(self.fn(float(shore), float(tube_id_mm), p), dtype=float)
        if out.shape != p.shape:
            raise ValueError(
                f"model {self.name!r} returned shape {out.shape} for {p.shape} pressures"
            )
        self.calls += 1
        self._cache[key] = out.copy()
        return out

    def clear(self) -> None:
        """Forget all cached evaluations (and reset the counters)."""
        self._cache.clear()
        self.calls = self.hits = 0


def material_for(
    shore: float,
    *,
    correlation: str = "paper",
    c01_ratio: float = 0.05,
    poisson: float = D.POISSON,
    c10_convention: C10Convention = "eq4",
) -> MooneyRivlin:
    """Mooney-Rivlin constants (MPa, 1/MPa) for a trial Shore A hardness (Eqs 3-6).

    Parameters
    ----------
    shore : float
        Shore A hardness in (0, 100).
    correlation : str
        Shore -> E0 correlation (Eq 3 is ``'paper'``).
    c01_ratio : float
        C01/C10 (Eq 5).
    poisson : float
        Poisson's ratio in Eq 6.
    c10_convention : {'eq4', 'paper-slip'}
        ``'eq4'``: C10 = G/2/(1 + c01_ratio) exactly. ``'paper-slip'``: the paper's
        printed Table 2 value C10 = G/2/1.005 (a slip for 1.05), C01 = c01_ratio C10,
        d from Eq 6 with those constants (4.5% stiffer than Eq 4).

    Returns
    -------
    MooneyRivlin

    Examples
    --------
    >>> round(material_for(62.5, c10_convention="paper-slip").c10_mpa, 4)
    0.6639
    """
    if c10_convention == "eq4":
        return MooneyRivlin.from_shore(shore, correlation, c01_ratio=c01_ratio, poisson=poisson)
    if c10_convention != "paper-slip":
        raise InputError(f"c10_convention must be 'eq4' or 'paper-slip', got {c10_convention!r}")
    return MooneyRivlin.from_shore(shore, correlation, c01_ratio=c01_ratio, poisson=poisson,
                                   c10_divisor=_SLIP_DIVISOR)


def paper_table1_model() -> CachedModel:
    """The paper's Table 1 ANSYS columns as a model (no simulation).

    Linear interpolation in hardness between the printed columns (60, 62.5, 65,
    70 Shore A) and in pressure within 0.1-0.4 MPa; outside these ranges it
    raises :class:`InputError`. The tube ID argument is ignored.

    Returns
    -------
    CachedModel
        Outer diameters in mm.

    Examples
    --------
    >>> m = paper_table1_model()
    >>> m(62.5, 5.0, np.array([0.1, 0.4])).tolist()
    [8.53, 9.56]
    """
    from exofric import paper

    t = paper.table1()
    shores = np.asarray(t["simulated_shore"], dtype=float)
    cols = np.asarray(t["simulated_outer_diameter_mm"], dtype=float)
    order = np.argsort(shores)
    shores, cols = shores[order], cols[order]
    p_tab = np.asarray(t["pressure_mpa"], dtype=float)

    def fn(shore: float, tube_id_mm: float, pressures_mpa: np.ndarray) -> np.ndarray:
        if not shores[0] <= shore <= shores[-1]:
            raise InputError(
                f"shore must be in [{shores[0]:g}, {shores[-1]:g}] for the paper-table1 model, "
                f"got {shore:g}"
            )
        p = np.asarray(pressures_mpa, dtype=float)
        if np.any(p < p_tab[0]) or np.any(p > p_tab[-1]):
            raise InputError(
                f"pressures must be in [{p_tab[0]:g}, {p_tab[-1]:g}] MPa for the paper-table1 "
                f"model, got {p.tolist()}"
            )
        # the column at this hardness (linear between neighbouring columns), then in pressure
        col = np.array([np.interp(shore, shores, cols[:, j]) for j in range(p_tab.size)])
        return np.interp(p, p_tab, col)

    return CachedModel(fn, "paper-table1")


def make_model(
    kind: str = DEFAULT_MODEL,
    tube_od_mm: float = 8.3,
    *,
    correlation: str = "paper",
    c01_ratio: float = 0.05,
    poisson: float = D.POISSON,
    c10_convention: C10Convention = "eq4",
    mesh: MeshSpec | None = None,
    ends: str = "plane-strain",
) -> CachedModel:
    """A memoised free-inflation model ``(shore, tube_id_mm, pressures_mpa) -> OD (mm)``.

    Parameters
    ----------
    kind : {'fe', '1d', 'paper-table1'}
        ``'fe'``: 2D FE (:func:`exofric.simulate.inflate`); ``'1d'``: 1D radial BVP
        (:func:`exofric.simulate.compressible_inflation`); ``'paper-table1'``: the
        paper's printed ANSYS columns (see :func:`paper_table1_model`).
    tube_od_mm : float
        Undeformed tube outer diameter (mm).
    correlation, c01_ratio, poisson, c10_convention
        How a trial hardness becomes a material (see :func:`material_for`).
    mesh : exofric.fe.MeshSpec, optional
        Resolution passed to :func:`exofric.simulate.inflate` (``'fe'`` only).
    ends : {'plane-strain', 'closed', 'open'}
        End condition of the tube (``'fe'`` only; the other kinds are plane strain).

    Returns
    -------
    CachedModel

    Examples
    --------
    >>> m = make_model("1d", 8.3)
    >>> round(float(m(62.5, 4.97, np.array([0.4]))[0]), 2)
    9.58
    """
    od = check_positive("tube_od_mm", tube_od_mm, "mm")
    from exofric.fe import check_ends

    check_ends(ends)
    if ends != "plane-strain" and kind != "fe":
        raise InputError(f"ends {ends!r} needs the fe model: model {kind!r} is plane strain",
                         param="ends")
    if kind == "paper-table1":
        return paper_table1_model()

    def mat(shore: float) -> MooneyRivlin:
        return material_for(shore, correlation=correlation, c01_ratio=c01_ratio, poisson=poisson,
                            c10_convention=c10_convention)

    mat(62.5)  # validate the material options once, up front
    if kind == "1d":
        from exofric.simulate import compressible_inflation

        def fn_1d(shore: float, tube_id_mm: float, pressures_mpa: np.ndarray) -> np.ndarray:
            p = check_pressures("pressures_mpa", pressures_mpa)
            return compressible_inflation(od, tube_id_mm, mat(shore), p).outer_diameter_mm

        return CachedModel(fn_1d, "1d")
    if kind == "fe":
        try:
            from exofric.simulate import inflate
        except ModuleNotFoundError as exc:
            if exc.name != f"{__package__}.simulate":
                raise
            raise InputError("model 'fe' is not available in this build (exofric.simulate "
                             "missing); use model '1d'") from None

        from exofric import defaults
        from exofric.fe import MeshSpec as _MeshSpec

        # one mesh per model evaluation (the fit's inner loop needs no error estimate): the
        # 2 x 6 quarter mesh is 3e-5 from the 1D reference (defaults.INFLATION_MESH)
        fe_mesh = mesh if mesh is not None else _MeshSpec(**defaults.INFLATION_MESH)

        def fn_fe(shore: float, tube_id_mm: float, pressures_mpa: np.ndarray) -> np.ndarray:
            p = check_pressures("pressures_mpa", pressures_mpa)
            res = inflate(od, tube_id_mm, mat(shore), p, mesh=fe_mesh, keep_fields=False,
                          ends=ends)
            return np.asarray(res.outer_diameter_mm, dtype=float)

        return CachedModel(fn_fe, "fe" if ends == "plane-strain" else f"fe ({ends} ends)")
    raise InputError(f"model must be one of {', '.join(MODEL_KINDS)}, got {kind!r}")
