"""The FE problems users ask for: free inflation and the tube-wire-hole squeeze.

Units: mm, N, MPa, s. Forces per unit depth in N/mm; totals = per depth x length.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .analytic import incompressible_inflation, incompressible_limit_pressure
from .errors import InputError, check_positive, check_pressures
from .fe.hyperelastic import von_mises
from .fe.inflation import InflationProblem, MeshSpec
from .fe.solver import NewtonSettings, solve_path
from .geometry import Structure
from .materials import MooneyRivlin

__all__ = [
    "InflationResult",
    "inflate",
    "MeshSpec",
    "DEFAULT_INFLATION_MESH",
    "SqueezeResult",
    "squeeze",
    "DEFAULT_SQUEEZE_MESH",
]

#: Default free-inflation mesh: quarter model, 2 x 6 quad9 (130 dofs); within 3e-5 of the
#: 1D reference for 8.3/4.97 mm up to 0.6 MPa (tests/test_inflate.py, convergence study).
DEFAULT_INFLATION_MESH = MeshSpec(n_radial=2, n_circ=6)


@dataclass(frozen=True)
class InflationResult:
    """Free inflation of the tube at each pressure.

    Attributes
    ----------
    pressure_mpa : ndarray
        Pressures (MPa).
    outer_diameter_mm, inner_diameter_mm : ndarray
        Deformed diameters (mm), measured on the symmetry axis.
    newton_iterations : ndarray of int
        Newton iterations spent reaching each pressure (all sub-steps).
    dofs : int
        Degrees of freedom of the model (incl. constrained).
    solve_time_s : float
        Wall time of the solve alone (s).
    symmetry : str
        Which symmetry was used.
    nodes : ndarray (n, 2)
        Undeformed node coordinates (mm), quarter model.
    elements : ndarray (e, 9)
        Element connectivity (quad9).
    displacements : tuple of ndarray (n, 2)
        Nodal displacements (mm) per pressure.
    von_mises_mpa : tuple of ndarray (e,)
        Element-mean von Mises Cauchy stress (MPa) per pressure.
    """

    pressure_mpa: np.ndarray
    outer_diameter_mm: np.ndarray
    inner_diameter_mm: np.ndarray
    newton_iterations: np.ndarray
    dofs: int
    solve_time_s: float
    symmetry: str
    tube_od_mm: float
    tube_id_mm: float
    material: MooneyRivlin
    mesh: MeshSpec
    nodes: np.ndarray = field(repr=False)
    elements: np.ndarray = field(repr=False)
    element_kind: str = "quad9"
    displacements: tuple[np.ndarray, ...] = field(default=(), repr=False)
    von_mises_mpa: tuple[np.ndarray, ...] = field(default=(), repr=False)

    def analytic_outer_diameter_mm(self) -> np.ndarray:
        """Incompressible closed-form outer diameters (mm) at the same pressures."""
        return incompressible_inflation(
            self.tube_od_mm, self.tube_id_mm, self.material.shear_modulus, self.pressure_mpa
        ).outer_diameter_mm

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unit-suffixed keys)."""
        return {
            "pressure_mpa": self.pressure_mpa.tolist(),
            "outer_diameter_mm": self.outer_diameter_mm.tolist(),
            "inner_diameter_mm": self.inner_diameter_mm.tolist(),
            "analytic_outer_diameter_mm": self.analytic_outer_diameter_mm().tolist(),
            "newton_iterations": [int(i) for i in self.newton_iterations],
            "dofs": self.dofs,
            "solve_time_s": self.solve_time_s,
            "symmetry": self.symmetry,
            "tube_od_mm": self.tube_od_mm,
            "tube_id_mm": self.tube_id_mm,
            "material": self.material.to_dict(),
            "mesh": self.mesh.to_dict(),
        }


def inflate(
    tube_od_mm: float,
    tube_id_mm: float,
    material: MooneyRivlin,
    pressures_mpa: np.ndarray | list[float],
    *,
    mesh: MeshSpec | None = None,
    settings: NewtonSettings | None = None,
    keep_fields: bool = True,
) -> InflationResult:
    """Free plane-strain inflation of the air tube under internal follower pressure.

    Quarter model (two symmetry planes), large deformation, mixed u/p
    Mooney-Rivlin (Eq 2), Newton with line search and load stepping.

    Parameters
    ----------
    tube_od_mm, tube_id_mm : float
        Undeformed outer and inner diameters (mm).
    material : MooneyRivlin
        Constants C10, C01 (MPa), d (1/MPa).
    pressures_mpa : array-like
        Strictly increasing pressures (MPa), each below the tube's limit pressure.
    mesh : MeshSpec, optional
        Resolution (default :data:`DEFAULT_INFLATION_MESH`).
    settings : NewtonSettings, optional
        Solver tolerances and stepping.
    keep_fields : bool
        Keep displacements and stresses for plotting/export (default True).

    Returns
    -------
    InflationResult

    Raises
    ------
    InputError
        Bad sizes or pressures, or a pressure at/above the limit pressure
        ``mu ln(OD/ID)`` beyond which free inflation has no equilibrium.
    ConvergenceError
        If the solver cannot reach a pressure (the message names it).

    Examples
    --------
    >>> from exofric.materials import MooneyRivlin
    >>> r = inflate(8.3, 4.97, MooneyRivlin.from_shore(62.5), [0.1, 0.4])
    >>> [round(float(d), 3) for d in r.outer_diameter_mm]
    [8.496, 9.584]
    """
    od = check_positive("tube_od_mm", tube_od_mm, "mm")
    idm = check_positive("tube_id_mm", tube_id_mm, "mm")
    if idm >= od:
        raise InputError(f"tube_id_mm must be < tube_od_mm ({od:g} mm), got {idm:g}")
    p = check_pressures("pressures_mpa", pressures_mpa, allow_zero=True)
    plim = incompressible_limit_pressure(od, idm, material.shear_modulus)
    if p[-1] >= 0.99 * plim:
        raise InputError(
            f"pressure {p[-1]:g} MPa is beyond 99% of the tube's limit pressure {plim:.4g} MPa "
            f"(mu ln(OD/ID)): free inflation has no equilibrium near and above it; "
            f"allowed range [0, {0.99 * plim:.4g}) MPa"
        )
    spec = mesh or DEFAULT_INFLATION_MESH
    prob = InflationProblem(od, idm, material, spec)
    t0 = time.perf_counter()
    pts = solve_path(prob, p, settings or NewtonSettings(max_step=0.05))
    dt = time.perf_counter() - t0
    g = prob.mesh.grid
    xo = [(prob.X + pt.u)[2 * g[-1, 0]] for pt in pts]
    xi = [(prob.X + pt.u)[2 * g[0, 0]] for pt in pts]
    disp: tuple[np.ndarray, ...] = ()
    vm: tuple[np.ndarray, ...] = ()
    if keep_fields:
        disp = tuple(pt.u.reshape(-1, 2).copy() for pt in pts)
        vm = tuple(von_mises(prob.body.cauchy_stress(pt.u)).mean(axis=1) for pt in pts)
    return InflationResult(
        pressure_mpa=p,
        outer_diameter_mm=2.0 * np.array(xo),
        inner_diameter_mm=2.0 * np.array(xi),
        newton_iterations=np.array([pt.iterations for pt in pts]),
        dofs=prob.n_dofs,
        solve_time_s=dt,
        symmetry="quarter model: u_y = 0 on the x axis, u_x = 0 on the y axis",
        tube_od_mm=od,
        tube_id_mm=idm,
        material=material,
        mesh=spec,
        nodes=prob.mesh.nodes.copy(),
        elements=prob.mesh.elements.copy(),
        element_kind=prob.mesh.kind,
        displacements=disp,
        von_mises_mpa=vm,
    )


# ----------------------------------------------------------------------------- squeeze

#: Default squeeze mesh: half model, 2 x 24 quad9 graded 6:1 toward the wire (490 dofs).
DEFAULT_SQUEEZE_MESH = MeshSpec(n_radial=2, n_circ=24, grading=6.0)
#: Default contact penalty (N/mm^3): penetration ~3e-5 mm at 0.6 MPa for the base group.
DEFAULT_PENALTY = 1e5
#: Silicone density (t/mm^3) for the self-weight regulariser.
SILICONE_DENSITY = 1.1e-9


@dataclass(frozen=True)
class SqueezeResult:
    """Squeeze of the wire by the inflated tube, per pressure (paper Figs 6-7).

    Forces are for the full section (2 x the half model): per unit depth (N/mm)
    and in total over the tube length (N).

    Attributes
    ----------
    pressure_mpa : ndarray
        Pressures (MPa).
    squeeze_force_n_per_mm, squeeze_force_n : ndarray
        Tube-wire contact force along the line of centres (N/mm, N).
    wall_force_n_per_mm, wall_force_n : ndarray
        Net vertical force of the hole wall on the tube (N/mm, N).
    wire_contact_halfwidth_mm : ndarray
        Half-width of the contact arc on the wire (mm, 0 before contact).
    wall_contact_arc_mm : ndarray
        Length of hole wall in contact with the tube (mm, full section).
    max_penetration_mm : ndarray
        Largest penalty penetration into the hole or the wire (mm).
    contact_onset_pressure_mpa : float or None
        Pressure at which the tube first touches the wire (None if not reached).
    """

    pressure_mpa: np.ndarray
    squeeze_force_n_per_mm: np.ndarray
    squeeze_force_n: np.ndarray
    wall_force_n_per_mm: np.ndarray
    wall_force_n: np.ndarray
    wire_contact_halfwidth_mm: np.ndarray
    wall_contact_arc_mm: np.ndarray
    max_penetration_mm: np.ndarray
    newton_iterations: np.ndarray
    contact_onset_pressure_mpa: float | None
    weight_n_per_mm: float
    dofs: int
    solve_time_s: float
    structure: Structure
    material: MooneyRivlin
    mesh: MeshSpec
    penalty: float
    density: float
    symmetry: str
    nodes: np.ndarray = field(repr=False)
    elements: np.ndarray = field(repr=False)
    displacements: tuple[np.ndarray, ...] = field(default=(), repr=False)
    von_mises_mpa: tuple[np.ndarray, ...] = field(default=(), repr=False)

    @property
    def length_mm(self) -> float:
        """Tube length L (mm) over which totals are integrated."""
        return self.structure.length_mm

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unit-suffixed keys)."""
        return {
            "pressure_mpa": self.pressure_mpa.tolist(),
            "squeeze_force_n": self.squeeze_force_n.tolist(),
            "squeeze_force_n_per_mm": self.squeeze_force_n_per_mm.tolist(),
            "wall_force_n": self.wall_force_n.tolist(),
            "wall_force_n_per_mm": self.wall_force_n_per_mm.tolist(),
            "wire_contact_halfwidth_mm": self.wire_contact_halfwidth_mm.tolist(),
            "wall_contact_arc_mm": self.wall_contact_arc_mm.tolist(),
            "max_penetration_mm": self.max_penetration_mm.tolist(),
            "newton_iterations": [int(i) for i in self.newton_iterations],
            "contact_onset_pressure_mpa": self.contact_onset_pressure_mpa,
            "weight_n_per_mm": self.weight_n_per_mm,
            "dofs": self.dofs,
            "length_mm": self.length_mm,
            "solve_time_s": self.solve_time_s,
            "structure": self.structure.to_dict(),
            "material": self.material.to_dict(),
            "mesh": self.mesh.to_dict(),
            "penalty_n_per_mm3": self.penalty,
            "density_t_per_mm3": self.density,
            "symmetry": self.symmetry,
        }


def _onset(path: list[tuple[float, float]]) -> float | None:
    """First pressure where the wire gap reaches 0, by linear interpolation on the path."""
    prev_p, prev_g = 0.0, None
    for p, g in path:
        if g <= 0.0:
            if prev_g is None or prev_g <= 0.0:
                return p if prev_g is None else prev_p
            return prev_p + (p - prev_p) * prev_g / (prev_g - g)
        prev_p, prev_g = p, g
    return None


def squeeze(
    structure: Structure,
    material: MooneyRivlin,
    pressures_mpa: np.ndarray | list[float],
    *,
    mesh: MeshSpec | None = None,
    penalty: float = DEFAULT_PENALTY,
    density: float = SILICONE_DENSITY,
    settings: NewtonSettings | None = None,
    keep_fields: bool = True,
) -> SqueezeResult:
    """Squeezing force N(P) between the inflated tube and the wire (paper §3.4, Figs 6-7).

    Plane strain, half model through the line of centres, large deformation,
    mixed u/p Mooney-Rivlin tube, follower pressure, frictionless penalty contact
    with the rigid hole and wire, self-weight regulariser.

    Parameters
    ----------
    structure : Structure
        Hole, tube and wire (mm) and tube length (mm).
    material : MooneyRivlin
        Tube material.
    pressures_mpa : array-like
        Strictly increasing pressures (MPa), in [0, 2].
    mesh : MeshSpec, optional
        Half-tube mesh (default :data:`DEFAULT_SQUEEZE_MESH`).
    penalty : float
        Contact penalty (N/mm^3).
    density : float
        Tube density (t/mm^3) for the self-weight; 0 is refused (no regularisation).
    settings : NewtonSettings, optional
        Solver settings (default: sub-steps of at most 0.025 MPa).
    keep_fields : bool
        Keep displacements and stresses for plots/export.

    Returns
    -------
    SqueezeResult

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.materials import MooneyRivlin
    >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.3, 0.6], keep_fields=False)
    >>> [round(float(n), 1) for n in r.squeeze_force_n]
    [47.8, 240.4]
    """
    from .fe.squeeze import SqueezeProblem, wall_arc, wire_halfwidth

    p = check_pressures("pressures_mpa", pressures_mpa, max_mpa=2.0)
    check_positive("penalty", penalty, "N/mm^3")
    check_positive("density", density, "t/mm^3")
    spec = mesh or DEFAULT_SQUEEZE_MESH
    prob = SqueezeProblem(structure, material, spec, penalty, density)
    path: list[tuple[float, float]] = []
    t0 = time.perf_counter()
    pts = solve_path(
        prob,
        p,
        settings or NewtonSettings(max_step=0.025),
        on_step=lambda lam, u: path.append((lam, prob.wire_gap(u))),
    )
    dt = time.perf_counter() - t0
    L = structure.length_mm
    rows = []
    for pt in pts:
        ch, cw = prob.contact(pt.u)
        xo = (prob.X + pt.u).reshape(-1, 2)[prob.outer]
        rows.append(
            (
                -2.0 * cw.force[:, 1].sum() + 0.0,  # + 0.0: no negative zero
                2.0 * ch.force[:, 1].sum(),
                wire_halfwidth(xo, cw.gap, prob.wire.center, prob.wire.radius),
                wall_arc(xo, ch.active, prob.hole.radius),
                max(0.0, -float(ch.gap.min()), -float(cw.gap.min())),
            )
        )
    arr = np.array(rows).reshape(-1, 5)
    disp: tuple[np.ndarray, ...] = ()
    vm: tuple[np.ndarray, ...] = ()
    if keep_fields:
        disp = tuple(pt.u.reshape(-1, 2).copy() for pt in pts)
        vm = tuple(von_mises(prob.body.cauchy_stress(pt.u)).mean(axis=1) for pt in pts)
    return SqueezeResult(
        pressure_mpa=p,
        squeeze_force_n_per_mm=arr[:, 0],
        squeeze_force_n=arr[:, 0] * L,
        wall_force_n_per_mm=arr[:, 1],
        wall_force_n=arr[:, 1] * L,
        wire_contact_halfwidth_mm=arr[:, 2],
        wall_contact_arc_mm=arr[:, 3],
        max_penetration_mm=arr[:, 4],
        newton_iterations=np.array([pt.iterations for pt in pts]),
        contact_onset_pressure_mpa=_onset(path),
        weight_n_per_mm=prob.weight_per_mm(),
        dofs=prob.n_dofs,
        solve_time_s=dt,
        structure=structure,
        material=material,
        mesh=spec,
        penalty=float(penalty),
        density=float(density),
        symmetry="half model: u_x = 0 on the plane x = 0 through the hole, tube and wire centres",
        nodes=prob.mesh.nodes.copy(),
        elements=prob.mesh.elements.copy(),
        displacements=disp,
        von_mises_mpa=vm,
    )
