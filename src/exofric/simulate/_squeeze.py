"""The tube-wire-hole squeeze problem users ask for (paper §3.4, Figs 6-7).

Units: mm, N, MPa; forces per unit depth in
N/mm, totals = per depth x tube length.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric import defaults
from exofric.errors import check_positive, check_pressures
from exofric.fe import (
    MeshSpec,
    NewtonSettings,
    SqueezeProblem,
    solve_path,
    von_mises,
    wall_arc,
    wire_halfwidth,
)
from exofric.geometry import Structure
from exofric.material import MooneyRivlin
from exofric.simulate._stretch import check_stretch

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["SqueezeResult", "squeeze"]


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
    max_stretch : ndarray
        Largest principal stretch (unitless) in the tube (StretchWarning above 2.5).
    newton_iterations : ndarray of int
        Newton iterations spent reaching each pressure (all sub-steps).
    contact_onset_pressure_mpa : float or None
        Pressure at which the tube first touches the wire (None if not reached).
    weight_n_per_mm : float
        Self-weight of the tube section per unit depth (N/mm), the regulariser's load.
    dofs : int
        Degrees of freedom of the model (incl. constrained).
    solve_time_s : float
        Wall time of the solve alone (s).
    structure : Structure
        Hole, tube and wire (mm).
    material : MooneyRivlin
        Tube material.
    mesh : MeshSpec
        Mesh used.
    penalty : float
        Contact penalty used (N/mm^3).
    density : float
        Tube density used for the self-weight (t/mm^3).
    symmetry : str
        Which symmetry was used.
    nodes : ndarray (n, 2)
        Undeformed node coordinates (mm), half model.
    elements : ndarray (e, 9)
        Element connectivity (quad9).
    displacements : tuple of ndarray (n, 2)
        Nodal displacements (mm) per pressure (empty unless ``keep_fields``).
    von_mises_mpa : tuple of ndarray (e,)
        Element-mean von Mises Cauchy stress (MPa) per pressure (empty unless ``keep_fields``).

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.6], keep_fields=False)
    >>> round(float(r.squeeze_force_n[0]))
    240
    """

    pressure_mpa: np.ndarray
    squeeze_force_n_per_mm: np.ndarray
    squeeze_force_n: np.ndarray
    wall_force_n_per_mm: np.ndarray
    wall_force_n: np.ndarray
    wire_contact_halfwidth_mm: np.ndarray
    wall_contact_arc_mm: np.ndarray
    max_penetration_mm: np.ndarray
    max_stretch: np.ndarray
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
            "max_stretch": self.max_stretch.tolist(),
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

    def to_frame(self) -> pd.DataFrame:
        """The per-pressure curves as a DataFrame: one row per pressure (MPa, N, N/mm, mm).

        Columns: ``pressure_mpa``, ``squeeze_force_n`` (total over the tube length),
        ``squeeze_force_per_depth_n_per_mm``, ``wall_force_n``,
        ``wall_force_per_depth_n_per_mm``, ``wire_contact_halfwidth_mm``,
        ``wall_contact_arc_mm``, ``max_penetration_mm``, ``max_stretch`` (unitless) and
        ``newton_iterations`` (count).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> from exofric.fe import MeshSpec
        >>> from exofric.geometry import BASE
        >>> from exofric.material import MooneyRivlin
        >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.3, 0.6], mesh=MeshSpec(2, 12))
        >>> df = r.to_frame()
        >>> list(df.columns[:3]), len(df)
        (['pressure_mpa', 'squeeze_force_n', 'squeeze_force_per_depth_n_per_mm'], 2)
        """
        import pandas as pd

        return pd.DataFrame({
            "pressure_mpa": self.pressure_mpa,
            "squeeze_force_n": self.squeeze_force_n,
            "squeeze_force_per_depth_n_per_mm": self.squeeze_force_n_per_mm,
            "wall_force_n": self.wall_force_n,
            "wall_force_per_depth_n_per_mm": self.wall_force_n_per_mm,
            "wire_contact_halfwidth_mm": self.wire_contact_halfwidth_mm,
            "wall_contact_arc_mm": self.wall_contact_arc_mm,
            "max_penetration_mm": self.max_penetration_mm,
            "max_stretch": self.max_stretch,
            "newton_iterations": np.asarray(self.newton_iterations, dtype=int),
        })

    def plot(self, ax: Any | None = None) -> Any:
        """Draw N(P), the squeezing force (N) against pressure (MPa) (Fig 7).

        One line, plus a dotted vertical line at the contact onset when reached
        (:func:`exofric.plots.plot_squeeze_force`); the deformed sections of Fig 6 are
        :func:`exofric.plots.plot_squeeze`. Write it with :func:`exofric.plots.save`.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (default a new figure).

        Returns
        -------
        matplotlib Axes

        Examples
        --------
        >>> from exofric.fe import MeshSpec
        >>> from exofric.geometry import BASE
        >>> from exofric.material import MooneyRivlin
        >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.3, 0.6], mesh=MeshSpec(2, 12))
        >>> r.plot().get_xlabel()
        'pressure P (MPa)'
        """
        from exofric.plots import plot_squeeze_force

        return plot_squeeze_force(self, ax)


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
    penalty: float = defaults.CONTACT_PENALTY_N_PER_MM3,
    density: float = defaults.SILICONE_DENSITY_T_PER_MM3,
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
        Half-tube mesh (default :data:`exofric.defaults.SQUEEZE_MESH`).
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
    >>> from exofric.material import MooneyRivlin
    >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.3, 0.6], keep_fields=False)
    >>> [round(float(n), 1) for n in r.squeeze_force_n]
    [47.8, 240.4]
    """

    p = check_pressures("pressures_mpa", pressures_mpa, max_mpa=2.0)
    check_positive("penalty", penalty, "N/mm^3")
    check_positive("density", density, "t/mm^3")
    spec = mesh or MeshSpec(**defaults.SQUEEZE_MESH)
    prob = SqueezeProblem(structure, material, spec, penalty, density)
    path: list[tuple[float, float]] = []
    t0 = time.perf_counter()
    pts = solve_path(
        prob,
        p,
        settings or NewtonSettings(**defaults.SQUEEZE_NEWTON),
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
    stretch = np.array([prob.body.max_stretch(pt.u) for pt in pts])
    check_stretch(stretch, p, f"squeeze of {structure.name or 'the structure'}")
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
        max_stretch=stretch,
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
