"""The FE problems users ask for: free inflation and the tube-wire-hole squeeze.

Units: mm, N, MPa, s. Forces per unit depth in N/mm; totals = per depth x length.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from exofric import defaults
from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, check_pressures
from exofric.fe import (
    InflationProblem,
    MeshSpec,
    NewtonSettings,
    PathPoint,
    check_ends,
    solve_path,
    von_mises,
)
from exofric.geometry import check_size_mm
from exofric.material import HyperelasticModel, MooneyRivlin
from exofric.simulate._analytic import incompressible_inflation, incompressible_limit_pressure
from exofric.simulate._common import fe_material_of, opt_list, resolve_accuracy
from exofric.simulate._stretch import check_stretch

if TYPE_CHECKING:
    import pandas as pd

    from exofric.simulate._common import FEMaterial

__all__ = ["InflationResult", "inflate"]


@checked_init
@dataclass(frozen=True)
class InflationResult(DisplayMixin):
    """Free inflation of the tube at each pressure.

    Attributes
    ----------
    pressure_mpa : ndarray
        Pressures (MPa).
    outer_diameter_mm, inner_diameter_mm : ndarray
        Deformed diameters (mm), measured on the symmetry axis.
    max_stretch : ndarray
        Largest principal stretch (unitless) in the tube at each pressure (a StretchWarning
        is issued above :data:`exofric.defaults.MR_STRETCH_LIMIT`).
    newton_iterations : ndarray of int
        Newton iterations spent reaching each pressure (all sub-steps).
    dofs : int
        Degrees of freedom of the model (incl. constrained).
    solve_time_s : float
        Wall time of the solve alone (s).
    symmetry : str
        Which symmetry was used.
    tube_od_mm, tube_id_mm : float
        Undeformed outer and inner tube diameters (mm).
    material : MooneyRivlin or HyperelasticModel
        Tube material.
    mesh : MeshSpec
        Mesh used.
    nodes : ndarray (n, 2)
        Undeformed node coordinates (mm), quarter model.
    elements : ndarray (e, 9)
        Element connectivity (quad9).
    element_kind : str
        Element type of ``elements`` (``"quad9"``).
    displacements : tuple of ndarray (n, 2)
        Nodal displacements (mm) per pressure.
    von_mises_mpa : tuple of ndarray (e,)
        Element-mean von Mises Cauchy stress (MPa) per pressure.
    accuracy : str
        The named accuracy level (``'draft'``, ``'standard'``, ``'fine'``) or ``'mesh'``.
    estimate_mesh : MeshSpec or None
        The nested coarser mesh of the error estimate (None for an explicit mesh).
    outer_diameter_error_estimate_mm, inner_diameter_error_estimate_mm : ndarray or None
        Estimated discretisation error of the diameters (mm) per pressure, Fs |d - d_coarse|
        with Fs = :data:`exofric.defaults.ESTIMATE_SAFETY_FACTOR` (None for an explicit mesh).
    ends : str
        ``'plane-strain'`` (the paper's), ``'closed'`` or ``'open'`` (generalised plane
        strain; see :class:`exofric.fe.PressurizedTube`).
    axial_stretch : ndarray or None
        Axial stretch l (unitless) per pressure (all 1 in plane strain).

    Examples
    --------
    >>> from exofric.material import MooneyRivlin
    >>> r = inflate(8.3, 4.97, MooneyRivlin.from_shore(62.5), [0.2], keep_fields=False)
    >>> round(float(r.outer_diameter_mm[0]), 2)
    8.75
    """

    pressure_mpa: np.ndarray
    outer_diameter_mm: np.ndarray
    inner_diameter_mm: np.ndarray
    max_stretch: np.ndarray
    newton_iterations: np.ndarray
    dofs: int
    solve_time_s: float
    symmetry: str
    tube_od_mm: float
    tube_id_mm: float
    material: MooneyRivlin | HyperelasticModel
    mesh: MeshSpec
    nodes: np.ndarray = field(repr=False)
    elements: np.ndarray = field(repr=False)
    element_kind: str = "quad9"
    displacements: tuple[np.ndarray, ...] = field(default=(), repr=False)
    von_mises_mpa: tuple[np.ndarray, ...] = field(default=(), repr=False)
    accuracy: str = "mesh"
    estimate_mesh: MeshSpec | None = None
    outer_diameter_error_estimate_mm: np.ndarray | None = None
    inner_diameter_error_estimate_mm: np.ndarray | None = None
    ends: str = "plane-strain"
    axial_stretch: np.ndarray | None = None

    def analytic_outer_diameter_mm(self) -> np.ndarray:
        """Incompressible reference outer diameters (mm) at the same pressures.

        Plane strain: the closed form with the model's shear modulus (neo-Hookean); closed or
        open ends: the semi-analytic thick tube of :func:`~exofric.simulate.tube_inflation`
        with the model itself (NaN past its limit pressure).
        """
        if self.ends != "plane-strain":
            from exofric.errors import ConvergenceError
            from exofric.simulate._analytic import tube_inflation

            try:
                return tube_inflation(self.tube_od_mm, self.tube_id_mm, self.material,
                                      self.pressure_mpa, ends=self.ends).outer_diameter_mm
            except ConvergenceError:
                return np.full_like(self.pressure_mpa, np.nan)
        return incompressible_inflation(
            self.tube_od_mm, self.tube_id_mm, _shear_modulus(self.material), self.pressure_mpa
        ).outer_diameter_mm

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unit-suffixed keys)."""

        return {
            "pressure_mpa": self.pressure_mpa.tolist(),
            "outer_diameter_mm": self.outer_diameter_mm.tolist(),
            "inner_diameter_mm": self.inner_diameter_mm.tolist(),
            "max_stretch": self.max_stretch.tolist(),
            "analytic_outer_diameter_mm": self.analytic_outer_diameter_mm().tolist(),
            "newton_iterations": [int(i) for i in self.newton_iterations],
            "dofs": self.dofs,
            "solve_time_s": self.solve_time_s,
            "symmetry": self.symmetry,
            "tube_od_mm": self.tube_od_mm,
            "tube_id_mm": self.tube_id_mm,
            "material": self.material.to_dict(),
            "mesh": self.mesh.to_dict(),
            "accuracy": self.accuracy,
            "estimate_mesh": None if self.estimate_mesh is None else self.estimate_mesh.to_dict(),
            "outer_diameter_error_estimate_mm": opt_list(self.outer_diameter_error_estimate_mm),
            "inner_diameter_error_estimate_mm": opt_list(self.inner_diameter_error_estimate_mm),
            "ends": self.ends,
            "axial_stretch": self._stretch().tolist(),
        }

    def _stretch(self) -> np.ndarray:
        """Axial stretch per pressure (unitless; ones when not stored)."""
        return (np.ones_like(self.pressure_mpa) if self.axial_stretch is None
                else np.asarray(self.axial_stretch, dtype=float))

    def to_frame(self) -> pd.DataFrame:
        """The per-pressure diameters as a DataFrame: one row per pressure (MPa, mm).

        Columns: ``pressure_mpa``, ``outer_diameter_mm``, ``inner_diameter_mm``,
        ``analytic_outer_diameter_mm`` (incompressible closed form), ``max_stretch``
        (unitless), ``axial_stretch`` (unitless; 1 in plane strain) and ``newton_iterations``
        (count).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> from exofric.material import MooneyRivlin
        >>> r = inflate(8.3, 4.97, MooneyRivlin.from_shore(62.5), [0.1, 0.2])
        >>> r.to_frame()[["pressure_mpa", "outer_diameter_mm"]].round(2).values.tolist()
        [[0.1, 8.5], [0.2, 8.75]]
        """
        import pandas as pd

        return pd.DataFrame({
            "pressure_mpa": self.pressure_mpa,
            "outer_diameter_mm": self.outer_diameter_mm,
            "inner_diameter_mm": self.inner_diameter_mm,
            "analytic_outer_diameter_mm": self.analytic_outer_diameter_mm(),
            "max_stretch": self.max_stretch,
            "axial_stretch": self._stretch(),
            "newton_iterations": np.asarray(self.newton_iterations, dtype=int),
        })

    def plot(self, ax: Any | None = None) -> Any:
        """Draw the outer diameter (mm) against pressure (MPa), FE beside the closed form.

        Two lines (:func:`exofric.plots.plot_inflation_curve`); the deformed section is
        :func:`exofric.plots.plot_inflation`. Write it with :func:`exofric.plots.save`.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (default a new figure).

        Returns
        -------
        matplotlib Axes

        Examples
        --------
        >>> from exofric.material import MooneyRivlin
        >>> r = inflate(8.3, 4.97, MooneyRivlin.from_shore(62.5), [0.1, 0.2])
        >>> len(r.plot().lines)
        2
        """
        from exofric.plots import plot_inflation_curve

        return plot_inflation_curve(self, ax)


def inflate(
    tube_od_mm: float,
    tube_id_mm: float,
    material: MooneyRivlin | HyperelasticModel,
    pressures_mpa: np.ndarray | list[float],
    *,
    accuracy: str | None = None,
    mesh: MeshSpec | None = None,
    settings: NewtonSettings | None = None,
    keep_fields: bool = True,
    ends: str = "plane-strain",
) -> InflationResult:
    """Free inflation of the air tube under internal follower pressure.

    Quarter model (two symmetry planes), large deformation, mixed u/p
    Mooney-Rivlin (Eq 2), Newton with line search and load stepping. Plane strain (the
    paper's model) by default; ``ends='closed'`` or ``'open'`` adds a uniform axial
    stretch (generalised plane strain, :class:`exofric.fe.PressurizedTube`).

    Parameters
    ----------
    tube_od_mm, tube_id_mm : float
        Undeformed outer and inner diameters (mm).
    material : MooneyRivlin or HyperelasticModel
        Constants C10, C01 (MPa), d (1/MPa), or a neo-Hookean, Mooney-Rivlin, Yeoh or Ogden model
        from :func:`~exofric.material.material_model`. The
        closed form beside it is neo-Hookean with the model's shear modulus.
    pressures_mpa : array-like
        Strictly increasing pressures (MPa), each below the tube's limit pressure.
    accuracy : {'draft', 'standard', 'fine'}, optional
        Named accuracy level (default :data:`exofric.defaults.ACCURACY`): solved on two nested
        meshes (:data:`exofric.defaults.INFLATION_ACCURACY`), the finer answer returned with
        an error estimate of the diameters. Not together with ``mesh``.
    mesh : MeshSpec, optional
        An explicit quarter-tube mesh instead of a named level (no error estimate).
    settings : NewtonSettings, optional
        Solver tolerances and stepping.
    keep_fields : bool
        Keep displacements and stresses for plotting/export (default True).
    ends : {'plane-strain', 'closed', 'open'}
        Axial condition: plane strain (axial stretch 1), closed ends (the end caps carry
        P times the deformed cavity area) or open ends (no axial force).

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
    >>> from exofric.material import MooneyRivlin
    >>> r = inflate(8.3, 4.97, MooneyRivlin.from_shore(62.5), [0.1, 0.4])
    >>> [round(float(d), 3) for d in r.outer_diameter_mm]
    [8.496, 9.584]
    """
    od = check_size_mm("tube_od_mm", tube_od_mm, "tube outer diameter")
    idm = check_size_mm("tube_id_mm", tube_id_mm, "tube inner diameter")
    if idm >= od:
        raise InputError(f"tube_id_mm must be < tube_od_mm ({od:g} mm), got {idm:g}")
    ends = check_ends(ends)

    fe_material = fe_material_of(material)
    p = check_pressures("pressures_mpa", pressures_mpa, allow_zero=True)
    plim = incompressible_limit_pressure(od, idm, fe_material.shear_modulus)
    if p[-1] >= 0.99 * plim:
        raise InputError(
            f"pressure {p[-1]:g} MPa is beyond 99% of the tube's limit pressure {plim:.4g} MPa "
            f"(mu ln(OD/ID)): free inflation has no equilibrium near and above it; "
            f"allowed range [0, {0.99 * plim:.4g}) MPa"
        )

    level, spec, coarse_spec = resolve_accuracy(accuracy, mesh, defaults.INFLATION_ACCURACY)
    s = settings or NewtonSettings(**defaults.INFLATION_NEWTON)
    t0 = time.perf_counter()
    prob, pts, od_fe, id_fe = _solve_inflation(od, idm, fe_material, p, spec, s, ends)
    od_est: np.ndarray | None = None
    id_est: np.ndarray | None = None
    if coarse_spec is not None:
        _, _, od_c, id_c = _solve_inflation(od, idm, fe_material, p, coarse_spec, s, ends)
        od_est = defaults.ESTIMATE_SAFETY_FACTOR * np.abs(od_fe - od_c)
        id_est = defaults.ESTIMATE_SAFETY_FACTOR * np.abs(id_fe - id_c)
    dt = time.perf_counter() - t0
    stretch = np.array([prob.body.max_stretch(pt.u) for pt in pts])
    check_stretch(stretch, p, "free inflation")
    disp: tuple[np.ndarray, ...] = ()
    vm: tuple[np.ndarray, ...] = ()
    lz = np.array([prob.axial_stretch(pt.u) for pt in pts])
    if keep_fields:
        n2 = prob.n_nodal
        disp = tuple(pt.u[:n2].reshape(-1, 2).copy() for pt in pts)
        vm = tuple(von_mises(prob.body.cauchy_stress(pt.u[:n2], lz[i])).mean(axis=1)
                   for i, pt in enumerate(pts))
    return InflationResult(
        pressure_mpa=p,
        outer_diameter_mm=od_fe,
        inner_diameter_mm=id_fe,
        max_stretch=stretch,
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
        accuracy=level,
        estimate_mesh=coarse_spec,
        outer_diameter_error_estimate_mm=od_est,
        inner_diameter_error_estimate_mm=id_est,
        ends=ends,
        axial_stretch=lz,
    )


def _solve_inflation(
    od: float, idm: float, material: FEMaterial, p: np.ndarray, spec: MeshSpec,
    s: NewtonSettings, ends: str = "plane-strain",
) -> tuple[InflationProblem, list[PathPoint], np.ndarray, np.ndarray]:
    """Solve on one mesh: (problem, states, outer and inner diameters in mm)."""
    # InflationProblem reads only shear_modulus (and its body the kernel): either type serves
    prob = InflationProblem(od, idm, cast(MooneyRivlin, material), spec, ends=ends)
    pts = solve_path(prob, p, s)
    g = prob.mesh.grid
    xo = np.array([prob.nodal(pt.u)[g[-1, 0], 0] for pt in pts])
    xi = np.array([prob.nodal(pt.u)[g[0, 0], 0] for pt in pts])
    return prob, pts, 2.0 * xo, 2.0 * xi



def _shear_modulus(material: MooneyRivlin | HyperelasticModel) -> float:
    """Initial shear modulus mu (MPa) of either material type."""
    if isinstance(material, MooneyRivlin):
        return float(material.shear_modulus)
    return float(material.shear_modulus_mpa)
