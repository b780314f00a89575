"""Independent FElupe models of exofric's two FE problems (cross-check and benchmark).

FElupe is GPL-3: this module lives in ``benchmarks/`` and is imported only by the
benchmarks and the tests, never by ``src/exofric`` (MIT). It uses nothing of
exofric's FE code: the Mooney-Rivlin law, the meshes, the contact and the solver
are FElupe's or written here from scratch. Units: mm, N, MPa, s; forces per unit
depth in N/mm.

Models
------
* :func:`felupe_inflate`: free plane-strain inflation of the tube under an internal
  follower pressure (:class:`felupe.SolidBodyPressure`), quarter model, on any
  quad9 mesh given in exofric's local node order (``a = 3 j + i``).
* :func:`felupe_squeeze` / :func:`felupe_squeeze_model`: the tube-wire-hole squeeze,
  half model ``x >= 0``, frictionless node-to-surface penalty contact with two
  :class:`felupe.ContactRigidCylinder` (the hole from inside, the wire from outside),
  self-weight :class:`felupe.SolidBodyForce` toward the wall.

Both use FElupe's three-field ``(u, p, J)`` formulation
(:class:`felupe.FieldsMixed` + :class:`felupe.NearlyIncompressible`): 9-node
displacement, discontinuous bilinear pressure and volume ratio, volumetric energy
``K/2 (J - 1)^2`` with ``K = 2/d`` (the ANSYS ``(J - 1)^2 / d``).

Example
-------
>>> n = felupe_squeeze([0.3, 0.6])  # doctest: +SKIP
>>> n.round(3)  # N per mm, full model  # doctest: +SKIP
array([0.413, 2.073])
"""

from __future__ import annotations

import argparse
import json
import sys
import time
import warnings
from dataclasses import dataclass, field
from typing import Any

import felupe as fem
import numpy as np
from scipy.sparse.linalg import MatrixRankWarning

__all__ = [
    "EXOFRIC_TO_VTK_QUAD9",
    "FelupeInflation",
    "FelupeSqueeze",
    "SqueezeSetup",
    "WEIGHTLESS_DENSITY",
    "felupe_inflate",
    "felupe_inflate_tube",
    "felupe_squeeze",
    "felupe_squeeze_model",
    "mooney_rivlin_iso_stress",
    "mooney_rivlin_umat",
    "polar_quad9",
    "main",
]

#: exofric's quad9 local order (a = 3 j + i, tensor order) -> FElupe/VTK quad9 order
#: (4 corners counter-clockwise, 4 edge mid-nodes, centre).
EXOFRIC_TO_VTK_QUAD9 = np.array([0, 2, 8, 6, 1, 5, 7, 3, 4])

GRAVITY_MM_S2 = 9810.0

#: Density (t/mm^3) that makes the squeeze practically weightless: 1e-4 of silicone's
#: 1.1e-9, enough to keep the floating tube on the wall (see SqueezeSetup.from_structure).
WEIGHTLESS_DENSITY = 1.1e-13

# errors after which FElupe's CutbackPlugin halves the increment; SuperLU raises a bare
# RuntimeError for a (numerically) singular matrix, e.g. when a contact opens mid-iteration
_CUTBACK_ERRORS = (fem.NewtonConvergenceError, ArithmeticError, np.linalg.LinAlgError,
                   RuntimeError)



# --------------------------------------------------------------------------- material
def _outer(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a_ij b_kl`` for fields (3, 3, ...) -> (3, 3, 3, 3, ...)."""
    return a[:, :, None, None] * b[None, None]


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a_il b_kj`` for fields (3, 3, ...) -> (3, 3, 3, 3, ...)."""
    return a[:, None, None, :] * np.swapaxes(b, 0, 1)[None, :, :, None]


def mooney_rivlin_iso_stress(
    F: np.ndarray, c10: float, c01: float, tangent: bool = False
) -> np.ndarray:
    """Isochoric Mooney-Rivlin: first Piola-Kirchhoff stress (MPa) or its tangent.

    ``W = C10 (I1b - 3) + C01 (I2b - 3)`` with ``I1b = J^(-2/3) I1``,
    ``I2b = J^(-4/3) I2``. Closed forms::

        P = C10 J^(-2/3) (2 F - 2/3 I1 F^-T) + C01 J^(-4/3) (2 M - 4/3 I2 F^-T),
        M = I1 F - F C,

    and ``dP/dF`` by the product rule (checked against finite differences in the
    tests).

    Parameters
    ----------
    F : ndarray (3, 3, ...)
        Deformation gradients (FElupe layout: components first).
    c10, c01 : float
        Material constants (MPa).
    tangent : bool
        Return the fourth-order tangent ``dP_iJ/dF_kL`` (3, 3, 3, 3, ...) instead.
    """
    Fm = np.moveaxis(F, (0, 1), (-2, -1))
    J = np.linalg.det(Fm)
    G = np.moveaxis(np.linalg.inv(Fm), (-2, -1), (1, 0))  # F^-T
    C = np.einsum("ki...,kj...->ij...", F, F)
    I1 = np.einsum("ii...->...", C)
    I2 = 0.5 * (I1**2 - np.einsum("ij...,ji...->...", C, C))
    M = I1 * F - np.einsum("ik...,kj...->ij...", F, C)
    j23, j43 = J ** (-2.0 / 3.0), J ** (-4.0 / 3.0)
    P1 = j23 * (2.0 * F - (2.0 / 3.0) * I1 * G)
    P2 = j43 * (2.0 * M - (4.0 / 3.0) * I2 * G)
    if not tangent:
        return c10 * P1 + c01 * P2
    e = np.eye(3).reshape((3, 3) + (1,) * J.ndim)
    I4 = e[:, None, :, None] * e[None, :, None, :]  # d_ik d_JL
    GGil = _cross(G, G)
    A1 = -(2.0 / 3.0) * _outer(P1, G) + j23 * (
        2.0 * I4 - (4.0 / 3.0) * _outer(G, F) + (2.0 / 3.0) * I1 * GGil
    )
    B = np.einsum("ik...,jk...->ij...", F, F)  # F F^T
    dM = (  # dM_iJ / dF_kL
        2.0 * _outer(F, F)
        + I1 * I4
        - e[:, None, :, None] * np.swapaxes(C, 0, 1)[None, :, None, :]  # d_ik C_LJ
        - _cross(F, F)  # F_iL F_kJ
        - B[:, None, :, None] * e[None, :, None, :]  # (F F^T)_ik d_JL
    )
    A2 = -(4.0 / 3.0) * _outer(P2, G) + j43 * (
        2.0 * dM - (8.0 / 3.0) * _outer(G, M) + (4.0 / 3.0) * I2 * GGil
    )
    return c10 * A1 + c01 * A2


def mooney_rivlin_umat(c10: float, c01: float, d: float) -> fem.NearlyIncompressible:
    """FElupe three-field material: isochoric Mooney-Rivlin + ``(J - 1)^2 / d``.

    Parameters
    ----------
    c10, c01 : float
        Mooney-Rivlin constants (MPa).
    d : float
        Incompressibility parameter (1/MPa); bulk modulus ``K = 2 / d``.
    """

    def stress(x: list[np.ndarray], **_: Any) -> list[np.ndarray]:
        return [mooney_rivlin_iso_stress(x[0], c10, c01), x[-1]]

    def elasticity(x: list[np.ndarray], **_: Any) -> list[np.ndarray]:
        return [mooney_rivlin_iso_stress(x[0], c10, c01, tangent=True)]

    return fem.NearlyIncompressible(fem.Material(stress, elasticity), bulk=2.0 / d)


def _constants(material: Any) -> tuple[float, float, float]:
    """(c10, c01, d) from an object with those attributes or a 3-sequence."""
    if hasattr(material, "c10"):
        return float(material.c10_mpa), float(material.c01_mpa), float(material.d_per_mpa)
    c10, c01, d = material
    return float(c10), float(c01), float(d)


# ------------------------------------------------------------------------------ meshes
def polar_quad9(
    inner_radius: float,
    outer_radius: float,
    n_radial: int,
    n_circ: int,
    theta0: float,
    theta1: float,
    grading: float = 1.0,
    center: tuple[float, float] = (0.0, 0.0),
    radial_grading: float = 1.0,
    n_circ0: int = 0,
    grading0: float = 1.0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Structured quad9 mesh of an annular sector, graded toward ``theta1``.

    Written independently of exofric's mesher. Element angles grow geometrically
    from ``theta1`` (ratio largest/smallest = ``grading``); element thicknesses grow
    geometrically from the outer radius inward (ratio innermost/outermost =
    ``radial_grading``, 1 = uniform); every node lies on its circle (mid-nodes at
    mid-radius and mid-angle). With ``n_circ0 > 0`` the first ``n_circ0`` elements
    from ``theta0`` are refined toward ``theta0`` instead (ratio ``grading0``) and the
    largest elements of both parts meet with equal size.

    Returns
    -------
    nodes : ndarray (n, 2)
        Coordinates (mm).
    cells : ndarray (e, 9)
        Connectivity in FElupe/VTK quad9 order.
    grid : ndarray (2 n_radial + 1, 2 n_circ + 1)
        Node index per (radial line, angular line); row 0 inner, last row outer.
    """
    if n_circ0 > 0:  # two-sided: n_circ0 elements refined toward theta0, the rest theta1
        sizes = np.concatenate([_geometric(n_circ0, grading0),
                                _geometric(n_circ - n_circ0, grading)[::-1]])
    else:
        q = grading ** (1.0 / max(n_circ - 1, 1))
        sizes = q ** np.arange(n_circ)[::-1]  # largest at theta0, smallest at theta1
    tb = theta0 + np.concatenate([[0.0], np.cumsum(sizes)]) / sizes.sum() * (theta1 - theta0)
    qr = radial_grading ** (1.0 / max(n_radial - 1, 1))
    thick = qr ** np.arange(n_radial)[::-1]  # thickest at the inner radius
    rb = inner_radius + np.concatenate([[0.0], np.cumsum(thick)]) / thick.sum() * (
        outer_radius - inner_radius)
    radii = np.sort(np.concatenate([rb, 0.5 * (rb[1:] + rb[:-1])]))
    angles = np.sort(np.concatenate([tb, 0.5 * (tb[1:] + tb[:-1])]))
    R, T = np.meshgrid(radii, angles, indexing="ij")
    nodes = np.stack([center[0] + R * np.cos(T), center[1] + R * np.sin(T)], -1).reshape(-1, 2)
    grid = np.arange(radii.size * angles.size).reshape(radii.size, angles.size)
    i0, j0 = (a.ravel() for a in np.meshgrid(2 * np.arange(n_radial), 2 * np.arange(n_circ),
                                            indexing="ij"))
    local = [(i, j) for j in range(3) for i in range(3)]  # tensor order a = 3 j + i
    tensor = np.stack([grid[i0 + i, j0 + j] for i, j in local], axis=1)
    return nodes, tensor[:, EXOFRIC_TO_VTK_QUAD9], grid


def _geometric(n: int, ratio: float) -> np.ndarray:
    """``n`` sizes growing geometrically from ``1 / ratio`` to 1."""
    return ratio ** (np.arange(n) / max(n - 1, 1) - 1.0)


def _mesh(nodes: np.ndarray, cells_vtk: np.ndarray) -> fem.Mesh:
    return fem.Mesh(np.array(nodes, dtype=float), np.array(cells_vtk, dtype=int), "quad9")


def _jsonable(obj: Any) -> dict[str, Any]:
    """Dataclass fields as JSON-ready values (arrays -> lists, nested ``to_dict``)."""
    out: dict[str, Any] = {}
    for key, val in obj.__dict__.items():
        if isinstance(val, np.ndarray):
            val = val.tolist()
        elif hasattr(val, "to_dict"):
            val = val.to_dict()
        out[key] = val
    return out


class _Recorder:
    """FElupe plugin: counts linear solves and calls ``record`` after each substep."""

    def __init__(self, record: Any) -> None:
        self.record = record
        self.solves = 0
        self.per_substep: list[int] = []

    def after_linear_solve(self, context: Any, state: Any) -> None:
        self.solves += 1

    def after_substep(self, context: Any, state: Any) -> None:
        self.per_substep.append(self.solves - sum(self.per_substep))
        self.record(state.substepnumber)


# --------------------------------------------------------------------------- inflation
@dataclass(frozen=True)
class FelupeInflation:
    """FElupe free inflation results (mm, MPa, s).

    Attributes
    ----------
    pressure_mpa, outer_diameter_mm, inner_diameter_mm : ndarray
        Pressures and deformed diameters on the x axis (theta = 0).
    newton_iterations : ndarray of int
        Linear solves spent reaching each pressure.
    dofs : int
        Unknowns of FElupe's system (u, p and J fields).
    solve_time_s : float
        Wall time of ``Job.evaluate`` (s).
    """

    pressure_mpa: np.ndarray
    outer_diameter_mm: np.ndarray
    inner_diameter_mm: np.ndarray
    newton_iterations: np.ndarray
    dofs: int
    solve_time_s: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unit-suffixed keys)."""
        return _jsonable(self)


def felupe_inflate(
    nodes: np.ndarray,
    elements: np.ndarray,
    material: Any,
    pressures_mpa: np.ndarray | list[float],
    *,
    element_order: str = "exofric",
) -> FelupeInflation:
    """Free plane-strain inflation of a quarter tube (0..90 deg, centre at the origin).

    Parameters
    ----------
    nodes : ndarray (n, 2)
        Node coordinates (mm).
    elements : ndarray (e, 9)
        quad9 connectivity, in exofric's local order (``element_order="exofric"``,
        ``a = 3 j + i``, i radial, j angular) or already in VTK order (``"vtk"``).
    material : object with ``c10, c01, d`` or (c10, c01, d)
        Mooney-Rivlin constants (MPa, MPa, 1/MPa).
    pressures_mpa : array-like
        Increasing internal (follower) pressures (MPa); each is one load increment.

    Returns
    -------
    FelupeInflation

    Examples
    --------
    >>> from exofric.fe import polar_mesh  # doctest: +SKIP
    >>> m = polar_mesh(2.485, 4.15, 2, 6)  # doctest: +SKIP
    >>> felupe_inflate(m.nodes, m.elements, (0.635, 0.0318, 0.006), [0.1]).outer_diameter_mm
    array([8.496...])  # doctest: +SKIP
    """
    c10, c01, d = _constants(material)
    cells = np.asarray(elements)
    if element_order == "exofric":
        cells = cells[:, EXOFRIC_TO_VTK_QUAD9]
    mesh = _mesh(nodes, cells)
    x, y = mesh.points.T
    r = np.hypot(x, y)
    scale = r.max()
    region = fem.RegionBiQuadraticQuad(mesh)
    fields = fem.FieldsMixed(region, n=3, planestrain=True)
    solid = fem.SolidBody(mooney_rivlin_umat(c10, c01, d), fields)
    inner = np.isclose(r, r.min(), rtol=0, atol=1e-9 * scale)
    boundary = fem.RegionBiQuadraticQuadBoundary(mesh, mask=inner, ensure_3d=True)
    pressure = fem.SolidBodyPressure(fem.FieldContainer([fem.FieldPlaneStrain(boundary, dim=2)]))
    u = fields[0]
    tol = 1e-9 * scale
    bcs = {
        "x=0": fem.Boundary(u, mask=np.abs(x) < tol, skip=(0, 1)),
        "y=0": fem.Boundary(u, mask=np.abs(y) < tol, skip=(1, 0)),
    }
    p = np.asarray(pressures_mpa, dtype=float)
    axis = np.abs(y) < tol
    i_out = np.flatnonzero(axis & np.isclose(r, r.max(), rtol=0, atol=tol))[0]
    i_in = np.flatnonzero(axis & inner)[0]
    od, idm = np.empty(p.size), np.empty(p.size)

    def record(k: int) -> None:
        xx = mesh.points[:, 0] + u.values[:, 0]
        od[k], idm[k] = 2.0 * xx[i_out], 2.0 * xx[i_in]

    rec = _Recorder(record)
    step = fem.Step([solid, pressure], ramp={pressure: p}, boundaries=bcs)
    t0 = time.perf_counter()
    fem.Job([step], plugins=[rec]).evaluate(verbose=0)
    dt = time.perf_counter() - t0
    return FelupeInflation(p, od, idm, np.array(rec.per_substep), int(sum(fields.fieldsizes)), dt)


# ----------------------------------------------------------------------------- squeeze
@dataclass(frozen=True)
class SqueezeSetup:
    """Geometry, material and discretisation of the FElupe squeeze model.

    Defaults: the paper's base group (D = 10, d1 = 8.3, ID = 4.97, d2 = 1.6 mm),
    Shore 62.5 Mooney-Rivlin (c10, c01 in MPa, d in 1/MPa), density 1.1e-9 t/mm^3.

    Attributes
    ----------
    n_radial, n_circ : int
        Elements through the wall and over the half circumference (180 deg).
    grading : float
        Ratio of the largest (at the wall, -90 deg) to the smallest (at the wire,
        +90 deg) element angle.
    penalty : float
        Node-to-surface penalty multiplier of ``ContactRigidCylinder`` (N/mm per mm of
        penetration, per mm depth; the same for every contact node).
    max_increment_mpa : float
        Largest load increment (MPa); each interval between requested pressures (the
        first starts at 0) is split evenly so that no increment exceeds it.
    shift_mm : float
        The tube is placed this much below its touching position so that the node
        on the wall starts in (penalty) contact; the self-weight problem does not
        depend on it because the tube moves freely until its contacts carry it.
    radial_grading : float
        Ratio of the thickest (inner) to the thinnest (outer) element layer; > 1
        refines toward the contact surfaces.
    n_circ_wall : int
        With ``n_circ_wall > 0``, that many of the ``n_circ`` elements are refined toward
        the wall (-90 deg) instead, with ratio ``wall_grading`` (the hole contact patch);
        the others keep ``grading`` toward the wire.
    wall_grading : float
        Largest/smallest element angle of the wall-side part.
    newton_tol : float
        FElupe's Newton tolerance: norm of the free residual over the norm of the
        reactions (unitless; round-off floor ~3e-9).
    contact_curvature : str
        ``curvature`` of :class:`felupe.ContactRigidCylinder`: ``"converged"`` (FElupe's
        default, bounded but inconsistent tangent) or ``"trial"`` (consistent tangent,
        quadratic Newton convergence).

    Examples
    --------
    >>> from exofric.friction import paper_structures
    >>> from exofric.material import MooneyRivlin
    >>> s = SqueezeSetup.from_structure(paper_structures()[4], MooneyRivlin.from_shore(62.5))
    >>> s.hole_mm, s.density_t_per_mm3
    (11.0, 1.1e-13)
    """

    hole_mm: float = 10.0
    tube_od_mm: float = 8.3
    tube_id_mm: float = 4.97
    wire_mm: float = 1.6
    c10: float = 0.6354497354497354
    c01: float = 0.03177248677248677
    d: float = 0.005995004163197341
    density_t_per_mm3: float = 1.1e-9
    n_radial: int = 4
    n_circ: int = 40
    grading: float = 10.0
    penalty: float = 1e4
    max_increment_mpa: float = 0.05
    shift_mm: float = 1e-6
    radial_grading: float = 1.0
    n_circ_wall: int = 0
    wall_grading: float = 1.0
    newton_tol: float = 1.5e-8
    contact_curvature: str = "converged"

    @classmethod
    def from_structure(
        cls, structure: Any, material: Any, *, density_t_per_mm3: float = WEIGHTLESS_DENSITY,
        **settings: Any,
    ) -> SqueezeSetup:
        """Setup for any hole-tube-wire geometry, by default practically without weight.

        The default density (1.1e-13 t/mm^3, 1e-4 of silicone's) only keeps the tube
        on the wall before it touches the wire (the penalty contact with the wall then
        restrains the otherwise free vertical motion); its force (~4e-8 N/mm for the
        base tube) changes N by far less than the solver tolerance. FElupe offers no
        weightless alternative that keeps the tube free to move: fixing a node would
        add a support force once the tube spans wall to wire.

        Parameters
        ----------
        structure : object
            Anything with ``hole_mm``, ``tube_od_mm``, ``tube_id_mm`` and ``wire_mm``
            (mm), e.g. an :class:`exofric.geometry.Structure`.
        material : object with ``c10, c01, d`` or (c10, c01, d)
            Mooney-Rivlin constants (MPa, MPa, 1/MPa).
        density_t_per_mm3 : float
            Tube density (t/mm^3) of the self-weight toward the wall.
        **settings
            Further :class:`SqueezeSetup` fields (mesh, penalty, increments).

        Returns
        -------
        SqueezeSetup

        Examples
        --------
        >>> s = SqueezeSetup.from_structure(SqueezeSetup(), (0.6, 0.03, 0.006), n_circ=80)
        >>> s.c10, s.n_circ, s.density_t_per_mm3
        (0.6, 80, 1.1e-13)
        """
        c10, c01, d = _constants(material)
        return cls(hole_mm=float(structure.hole_mm), tube_od_mm=float(structure.tube_od_mm),
                   tube_id_mm=float(structure.tube_id_mm), wire_mm=float(structure.wire_mm),
                   c10=c10, c01=c01, d=d, density_t_per_mm3=density_t_per_mm3, **settings)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return dict(self.__dict__)


@dataclass(frozen=True)
class FelupeSqueeze:
    """FElupe squeeze results per requested pressure (full model unless stated).

    Attributes
    ----------
    pressure_mpa : ndarray
        Pressures (MPa).
    squeeze_force_n_per_mm : ndarray
        y-force of the tube on the wire per mm depth (N/mm), 2 x the half model.
    wall_force_n_per_mm : ndarray
        y-force of the wall on the tube (N/mm, upward positive), full model.
    weight_n_per_mm : float
        Self-weight of the full tube per mm depth (N/mm).
    equilibrium_n_per_mm : ndarray
        Wall force - squeeze force - weight (N/mm); zero at equilibrium.
    max_penetration_mm : ndarray
        Largest penalty penetration into the hole or the wire (mm).
    newton_iterations : ndarray of int
        Linear solves per pressure (including cut-back attempts).
    dofs : int
        Unknowns (u, p and J fields, both rigid centre points).
    solve_time_s : float
        Wall time of ``Job.evaluate`` (s).
    setup : SqueezeSetup
        The model settings.
    """

    pressure_mpa: np.ndarray
    squeeze_force_n_per_mm: np.ndarray
    wall_force_n_per_mm: np.ndarray
    weight_n_per_mm: float
    equilibrium_n_per_mm: np.ndarray
    max_penetration_mm: np.ndarray
    newton_iterations: np.ndarray
    dofs: int
    solve_time_s: float
    setup: SqueezeSetup = field(repr=False)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unit-suffixed keys)."""
        return _jsonable(self)


def felupe_squeeze_model(
    pressures_mpa: np.ndarray | list[float], setup: SqueezeSetup | None = None
) -> FelupeSqueeze:
    """Solve the tube-wire-hole squeeze in FElupe (half model, plane strain).

    Hole (rigid, diameter D) centred at (0, 0); wire (rigid, d2) at
    (0, D/2 - d2/2); tube (d1, ID) at (0, -(D/2 - d1/2)) touching the wall at the
    bottom. Internal follower pressure, frictionless penalty contact of all outer
    nodes with both circles, self-weight toward the wall, ``u_x = 0`` on x = 0.
    A :class:`felupe.CutbackPlugin` halves failed increments.

    Parameters
    ----------
    pressures_mpa : array-like
        Increasing pressures (MPa, > 0) at which results are reported.
    setup : SqueezeSetup, optional
        Geometry, material and discretisation (default: base group, 4 x 40 graded
        10:1, penalty 1e4, increments <= 0.05 MPa).

    Returns
    -------
    FelupeSqueeze

    Examples
    --------
    >>> r = felupe_squeeze_model([0.3, 0.6])  # doctest: +SKIP
    >>> r.squeeze_force_n_per_mm * 116  # total over 116 mm (N)  # doctest: +SKIP
    """
    s = setup or SqueezeSetup()
    p_out = np.asarray(pressures_mpa, dtype=float)
    if p_out.ndim != 1 or p_out.size == 0 or np.any(p_out <= 0) or np.any(np.diff(p_out) <= 0):
        raise ValueError("pressures_mpa must be positive and strictly increasing (MPa)")
    a, b = 0.5 * s.tube_id_mm, 0.5 * s.tube_od_mm
    yc = -(0.5 * s.hole_mm - b) - s.shift_mm
    nodes, cells, grid = polar_quad9(a, b, s.n_radial, s.n_circ, -0.5 * np.pi, 0.5 * np.pi,
                                     s.grading, (0.0, yc), s.radial_grading,
                                     s.n_circ_wall, s.wall_grading)
    nodes[grid[:, [0, -1]].ravel(), 0] = 0.0  # exactly on the symmetry plane
    wire_c = (0.0, 0.5 * s.hole_mm - 0.5 * s.wire_mm)
    mesh = _mesh(np.vstack([nodes, [[0.0, 0.0], wire_c]]), cells)
    i_hole, i_wire = mesh.npoints - 2, mesh.npoints - 1
    region = fem.RegionBiQuadraticQuad(mesh)
    fields = fem.FieldsMixed(region, n=3, planestrain=True)
    u = fields[0]
    solid = fem.SolidBody(mooney_rivlin_umat(s.c10, s.c01, s.d), fields)
    mask = np.zeros(mesh.npoints, dtype=bool)
    mask[grid[0]] = True
    boundary = fem.RegionBiQuadraticQuadBoundary(mesh, mask=mask, ensure_3d=True)
    pressure = fem.SolidBodyPressure(fem.FieldContainer([fem.FieldPlaneStrain(boundary, dim=2)]))
    rho_g = s.density_t_per_mm3 * GRAVITY_MM_S2  # N/mm^3
    weight = fem.SolidBodyForce(fields, values=[0.0, -GRAVITY_MM_S2], scale=s.density_t_per_mm3)
    outer = grid[-1]
    hole = fem.ContactRigidCylinder(fields, outer, i_hole, radius=0.5 * s.hole_mm, inside=True,
                                    multiplier=s.penalty, curvature=s.contact_curvature)
    wire = fem.ContactRigidCylinder(fields, outer, i_wire, radius=0.5 * s.wire_mm,
                                    multiplier=s.penalty, curvature=s.contact_curvature)
    sym = np.zeros(mesh.npoints, dtype=bool)
    sym[grid[:, [0, -1]].ravel()] = True
    centres = np.zeros(mesh.npoints, dtype=bool)
    centres[[i_hole, i_wire]] = True
    bcs = {"symmetry": fem.Boundary(u, mask=sym, skip=(0, 1)),
           "centres": fem.Boundary(u, mask=centres)}
    # ramp: 0 (so that the cut-back plugin may split the first increment), then even
    # increments <= max_increment_mpa; results are recorded at the requested pressures
    knots = np.concatenate([[0.0], p_out])
    nsub = np.maximum(1, np.ceil(np.diff(knots) / s.max_increment_mpa - 1e-9)).astype(int)
    ramp = np.concatenate([[0.0]] + [np.linspace(knots[k], knots[k + 1], nsub[k] + 1)[1:]
                                     for k in range(p_out.size)])
    ends = np.cumsum(nsub)  # substep index (0 = the zero load) of each requested pressure
    report = {int(e): k for k, e in enumerate(ends)}
    n = p_out.size
    squeeze, wall, pen = np.empty(n), np.empty(n), np.empty(n)

    def record(sub: int) -> None:
        k = report.get(sub)
        if k is None:
            return
        fw = np.asarray(wire.assemble.vector(fields).todense()).reshape(-1, 2)
        fh = np.asarray(hole.assemble.vector(fields).todense()).reshape(-1, 2)
        # the centre point carries minus the sum of the point forces: force ON the obstacle
        squeeze[k] = -2.0 * fw[i_wire, 1]  # tube on wire, +y
        wall[k] = 2.0 * fh[i_hole, 1]  # wall on tube = -(tube on wall)
        g = np.concatenate([c._kinematics(c._gap_vectors())[0] for c in (hole, wire)])
        pen[k] = max(0.0, -float(g.min()))

    rec = _Recorder(record)
    step = fem.Step([solid, pressure, weight, hole, wire], ramp={pressure: ramp}, boundaries=bcs)
    t0 = time.perf_counter()
    cutback = fem.CutbackPlugin(growth=1.0, exceptions=_CUTBACK_ERRORS)
    # failed attempts (inverted elements, singular matrices) are expected and cut back
    with warnings.catch_warnings(), np.errstate(invalid="ignore", divide="ignore"):
        warnings.simplefilter("ignore", MatrixRankWarning)
        fem.Job([step], plugins=[cutback, rec]).evaluate(verbose=0, tol=s.newton_tol)
    dt = time.perf_counter() - t0
    w_full = 2.0 * rho_g * float(region.dV.sum())  # weight of the discretised full tube
    per = np.array(rec.per_substep)
    iters = np.array([per[e - m + 1: e + 1].sum() for e, m in zip(ends, nsub, strict=True)])
    iters[0] += per[0]
    return FelupeSqueeze(p_out, squeeze, wall, w_full, wall - squeeze - w_full, pen, iters,
                         int(sum(fields.fieldsizes)), dt, s)


def felupe_squeeze(
    pressures_mpa: np.ndarray | list[float], setup: SqueezeSetup | None = None
) -> np.ndarray:
    """Squeeze force N (N per mm depth, full model) at each pressure (MPa), FElupe.

    See :func:`felupe_squeeze_model`; multiply by the tube length (mm) for N.

    Examples
    --------
    >>> felupe_squeeze([0.6])  # doctest: +SKIP
    array([2.07...])
    """
    return felupe_squeeze_model(pressures_mpa, setup).squeeze_force_n_per_mm


# ------------------------------------------------------------ standalone (whole process)
def felupe_inflate_tube(
    tube_od_mm: float,
    tube_id_mm: float,
    material: Any,
    pressures_mpa: np.ndarray | list[float],
    *,
    n_radial: int = 2,
    n_circ: int = 6,
) -> FelupeInflation:
    """Free inflation of a quarter tube on FElupe's own polar quad9 mesh (no exofric).

    Parameters
    ----------
    tube_od_mm, tube_id_mm : float
        Undeformed diameters (mm).
    material : object with ``c10, c01, d`` or (c10, c01, d)
        Mooney-Rivlin constants (MPa, MPa, 1/MPa).
    pressures_mpa : array-like
        Increasing pressures (MPa); each is one load increment.
    n_radial, n_circ : int
        Uniform elements through the wall and over the quarter (0..90 deg).

    Returns
    -------
    FelupeInflation

    Examples
    --------
    >>> r = felupe_inflate_tube(8.3, 4.97, (0.635, 0.0318, 0.006), [0.1])  # doctest: +SKIP
    """
    nodes, cells, grid = polar_quad9(0.5 * tube_id_mm, 0.5 * tube_od_mm, n_radial, n_circ,
                                     0.0, 0.5 * np.pi)
    nodes[grid[:, 0], 1] = 0.0  # exactly on the symmetry planes
    nodes[grid[:, -1], 0] = 0.0
    return felupe_inflate(nodes, cells, material, pressures_mpa, element_order="vtk")


def main(argv: list[str] | None = None) -> dict[str, Any]:
    """Standalone FElupe run for whole-process timing; prints one JSON object.

    ``python benchmarks/felupe_models.py squeeze|inflate --c10 .. --c01 .. --d ..
    --pressures 0.05,0.1 [--n-radial ..] [--n-circ ..] [--grading ..]`` (mm, MPa). The
    squeeze is weightless (:data:`WEIGHTLESS_DENSITY`); ``--hole/--tube-od/--tube-id/--wire``
    default to the base group.

    Examples
    --------
    >>> main(["inflate", "--pressures", "0.1", "--c10", "0.6", "--c01", "0.03",
    ...       "--d", "0.006"])  # doctest: +SKIP
    """
    ap = argparse.ArgumentParser(description="Standalone FElupe squeeze / free inflation.")
    ap.add_argument("problem", choices=("squeeze", "inflate"))
    ap.add_argument("--c10", type=float, required=True)
    ap.add_argument("--c01", type=float, required=True)
    ap.add_argument("--d", type=float, required=True)
    ap.add_argument("--pressures", required=True, help="comma-separated, MPa")
    ap.add_argument("--hole", type=float, default=10.0)
    ap.add_argument("--tube-od", type=float, default=8.3)
    ap.add_argument("--tube-id", type=float, default=4.97)
    ap.add_argument("--wire", type=float, default=1.6)
    ap.add_argument("--n-radial", type=int, default=None)
    ap.add_argument("--n-circ", type=int, default=None)
    ap.add_argument("--grading", type=float, default=10.0)
    ap.add_argument("--penalty", type=float, default=1e4)
    args = ap.parse_args(argv)
    p = [float(v) for v in args.pressures.split(",")]
    mat = (args.c10, args.c01, args.d)
    if args.problem == "inflate":
        r = felupe_inflate_tube(args.tube_od, args.tube_id, mat, p,
                                n_radial=args.n_radial or 2, n_circ=args.n_circ or 6)
        out: dict[str, Any] = {"problem": "inflate", **r.to_dict()}
    else:
        setup = SqueezeSetup(hole_mm=args.hole, tube_od_mm=args.tube_od,
                             tube_id_mm=args.tube_id, wire_mm=args.wire, c10=args.c10,
                             c01=args.c01, d=args.d, density_t_per_mm3=WEIGHTLESS_DENSITY,
                             n_radial=args.n_radial or 4, n_circ=args.n_circ or 40,
                             grading=args.grading, penalty=args.penalty)
        out = {"problem": "squeeze", **felupe_squeeze_model(p, setup).to_dict()}
    json.dump(out, sys.stdout)
    sys.stdout.write("\n")
    return out


if __name__ == "__main__":
    main()
