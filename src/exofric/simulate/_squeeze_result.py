"""What a squeeze returns: the curves, the contact outputs, the error estimate, the solver.

:class:`SqueezeResult` carries the per-pressure curves (N, wall force, directions, stretch)
and the :class:`~exofric.simulate.SqueezeSetup` that was solved, and groups the rest:
:class:`ContactOutputs` (what the two contacts carry: arcs, penetration, pressure integrals,
friction), :class:`ErrorEstimate` (the two-mesh discretisation error) and
:class:`~exofric.fe.SolverStats` (where the Newton work went). The mesh fields (nodes,
elements, displacements, stresses), ``dofs``, ``newton_iterations`` and ``solve_time_s`` stay
at the top level: they are the shape shared with the inflation and ring results, which the
plots and the VTU writer read alike. Units: mm, N, MPa.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric import defaults
from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.fe import MeshSpec, SolverStats
from exofric.geometry import Structure
from exofric.material import HyperelasticModel, MooneyRivlin
from exofric.simulate._common import opt_list
from exofric.simulate._setup import SqueezeSetup

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["ContactOutputs", "ErrorEstimate", "SqueezeResult"]


def _nan_list(a: np.ndarray | None) -> list[float | None] | None:
    """An optional array as a JSON list, NaN as None (JSON has no NaN)."""
    if a is None:
        return None
    return [None if not np.isfinite(v) else float(v) for v in np.asarray(a, dtype=float)]



def _opt_col(a: np.ndarray | None, like: np.ndarray) -> np.ndarray:
    """An optional per-pressure array as a column (NaN when absent)."""
    return np.full(len(like), np.nan) if a is None else np.asarray(a, dtype=float)


@checked_init
@dataclass(frozen=True)
class ContactOutputs:
    """What the tube-wire and tube-wall contacts carry, per pressure (mm, N/mm, unitless).

    A part of :class:`SqueezeResult` (its ``contact``). Forces are for the full section per
    unit depth (N per mm of tube).

    Attributes
    ----------
    wire_contact_halfwidth_mm : ndarray
        Half-width of the contact arc on the wire (mm, 0 before contact).
    wall_contact_arc_mm : ndarray
        Length of hole wall in contact with the tube (mm, full section).
    max_penetration_mm : ndarray
        Largest penalty penetration into the hole or the wire (mm).
    friction_penalty : float
        Tangential penalty (N/mm^3).
    wire_pressure_integral_n_per_mm, wall_pressure_integral_n_per_mm : ndarray or None
        Integral of the normal contact pressure over the tube-wire (S_wire) and tube-wall
        contact arcs per pressure (N per mm of tube), full section.
    wire_tangential_force_n_per_mm, wall_tangential_force_n_per_mm : ndarray or None
        Integral of the magnitude of the in-plane friction traction over those arcs (N/mm;
        0 without friction).
    stick_fraction_wire, stick_fraction_wall : ndarray or None
        Share of each contact arc (by length) that sticks (unitless; NaN without contact or
        without friction).
    profiles : tuple of dict
        Per pressure, ``{"wire": ..., "wall": ...}``, each with lists along the contact arc
        (nodes in contact, sorted): ``node`` (mesh node index), ``arc_mm`` and
        ``angle_deg`` from the arc's centre (the
        side of the circle facing away from the other obstacle; the half model's x >= 0
        half), ``pressure_mpa`` (true normal pressure), ``shear_mpa`` (signed friction
        traction, MPa) and ``stick``.
    friction_dissipation_n_per_mm : ndarray or None
        Frictional work of each committed load sub-step (N mm per mm depth, full section;
        >= 0), None without friction (per unit reference length with closed or open ends).

    Examples
    --------
    >>> from exofric.fe import MeshSpec
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import squeeze
    >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.6], mesh=MeshSpec(2, 12))
    >>> c = r.contact
    >>> bool(c.wire_contact_halfwidth_mm[0] > 0), c.stick_fraction_wire  # frictionless: NaN
    (True, array([nan]))
    """

    wire_contact_halfwidth_mm: np.ndarray
    wall_contact_arc_mm: np.ndarray
    max_penetration_mm: np.ndarray
    friction_penalty: float = defaults.CONTACT_PENALTY_N_PER_MM3 * defaults.FRICTION_PENALTY_REL
    wire_pressure_integral_n_per_mm: np.ndarray | None = None
    wall_pressure_integral_n_per_mm: np.ndarray | None = None
    wire_tangential_force_n_per_mm: np.ndarray | None = None
    wall_tangential_force_n_per_mm: np.ndarray | None = None
    stick_fraction_wire: np.ndarray | None = None
    stick_fraction_wall: np.ndarray | None = None
    profiles: tuple[dict[str, dict[str, list[Any]]], ...] = field(default=(), repr=False)
    friction_dissipation_n_per_mm: np.ndarray | None = field(default=None, repr=False)


@checked_init
@dataclass(frozen=True)
class ErrorEstimate:
    """The two-mesh discretisation error of the squeezing force N, per pressure (%, N/mm).

    A part of :class:`SqueezeResult` (its ``estimate``).

    Attributes
    ----------
    accuracy : str
        The named accuracy level (``'draft'``, ``'standard'``, ``'fine'``) or ``'mesh'``
        for an explicit mesh.
    mesh : MeshSpec or None
        The nested coarser mesh of the error estimate (None for an explicit mesh).
    pct : ndarray or None
        Estimated discretisation error of N (%) per pressure, Fs |N - N_coarse| / N with the
        safety factor Fs = :data:`exofric.defaults.ESTIMATE_SAFETY_FACTOR`, at least
        :data:`exofric.defaults.ESTIMATE_FLOOR_PCT` where N > 0 and at most 100; 0 where both
        meshes give 0, 100 where only one has contact (None for an explicit mesh).
    n_per_mm : ndarray or None
        The same estimate in N/mm (per depth).
    coarse_n_per_mm : ndarray or None
        N on the coarse mesh (N/mm), full section.
    reliable : ndarray of bool or None
        Per pressure: False where the estimate cannot be trusted to bound the error (the
        coarse mesh does not resolve the wire's contact patch, or only one mesh has wire
        contact: typically the first pressure or two after the contact onset); the number is
        then indicative only (docs/formulation.md section 6). None for an explicit mesh.
    wire_tangential_pct : ndarray or None
        The same two-mesh estimate (%) of the friction force along the wire's contact arc
        (``contact.wire_tangential_force_n_per_mm``), with the same window, floor, cap and
        ``reliable`` flags; None without friction on the wire or for an explicit mesh. It is
        far larger than N's near the onset (a traction on 2-5 nodes of the arc, issue 35).

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import squeeze
    >>> e = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.6], accuracy="draft").estimate
    >>> e.accuracy, bool(e.pct[0] < 5.0)  # % of N
    ('draft', True)
    """

    accuracy: str = "mesh"
    mesh: MeshSpec | None = None
    pct: np.ndarray | None = None
    n_per_mm: np.ndarray | None = None
    coarse_n_per_mm: np.ndarray | None = field(default=None, repr=False)
    reliable: np.ndarray | None = None
    wire_tangential_pct: np.ndarray | None = None

    @property
    def unreliable_outputs(self) -> tuple[int, ...]:
        """Indices of the outputs whose estimate is flagged unreliable (empty if none)."""
        if self.reliable is None:
            return ()
        return tuple(int(i) for i in np.flatnonzero(~np.asarray(self.reliable, bool)))


@checked_init
@dataclass(frozen=True)
class SqueezeResult(DisplayMixin):
    """Squeeze of the wire by the inflated tube, per pressure (paper Figs 6-7).

    Forces are for the full section (2 x the half model): per unit depth (N/mm)
    and in total over the tube length (N). With an off-centre wire (``wire_angle_deg`` != 0,
    the full model) the squeezing force N is the magnitude of the resultant contact force of
    the tube on the wire and the wall force the magnitude of the hole wall's resultant on the
    tube; their directions are reported separately.

    Attributes
    ----------
    pressure_mpa : ndarray
        Pressures (MPa).
    squeeze_force_n_per_mm, squeeze_force_n : ndarray
        Tube-wire contact force along the line of centres (N/mm, N); with an off-centre wire
        the magnitude of the resultant force of the tube on the wire.
    wall_force_n_per_mm, wall_force_n : ndarray
        Net vertical force of the hole wall on the tube (N/mm, N); with an off-centre wire the
        magnitude of its resultant.
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
    setup : SqueezeSetup
        What was solved (structure, material, ends, friction, accuracy, gravity, ...); its
        fields are also this result's properties ``structure``, ``material``, ``penalty``
        (N/mm^3), ``density`` (t/mm^3), ``gravity``, ``wire_angle_deg`` (deg), ``mu_wall``,
        ``mu_wire`` and ``ends``.
    mesh : MeshSpec
        Mesh used.
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
    contact : ContactOutputs
        What the two contacts carry per pressure: arc sizes, penetration, normal-pressure
        integrals, friction forces, stick shares, the profiles along the arcs.
    estimate : ErrorEstimate
        The two-mesh discretisation error of N (``accuracy``, the coarse mesh, % and N/mm).
    solver_stats : SolverStats
        Newton attempts, failed attempts, iterations, linear solves and the wall time (s)
        spent in them and in the failed ones, over both meshes, the onset bracketing and the
        regulariser's release.
    squeeze_force_direction_deg : ndarray or None
        Direction of the tube's resultant force on the wire (deg from +y, positive toward +x;
        0 for the half model, NaN where N = 0).
    wall_force_direction_deg : ndarray or None
        Direction of the hole wall's resultant force on the tube (deg from +y, positive toward
        +x; NaN where it is 0).
    axial_stretch : ndarray or None
        Axial stretch of the tube (unitless) per pressure (1 in plane strain).

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import squeeze
    >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.6], keep_fields=False)
    >>> round(float(r.squeeze_force_n[0]))
    241
    """

    pressure_mpa: np.ndarray
    squeeze_force_n_per_mm: np.ndarray
    squeeze_force_n: np.ndarray
    wall_force_n_per_mm: np.ndarray
    wall_force_n: np.ndarray
    max_stretch: np.ndarray
    newton_iterations: np.ndarray
    contact_onset_pressure_mpa: float | None
    weight_n_per_mm: float
    dofs: int
    solve_time_s: float
    setup: SqueezeSetup
    mesh: MeshSpec
    symmetry: str
    contact: ContactOutputs
    estimate: ErrorEstimate
    nodes: np.ndarray = field(repr=False)
    elements: np.ndarray = field(repr=False)
    displacements: tuple[np.ndarray, ...] = field(default=(), repr=False)
    von_mises_mpa: tuple[np.ndarray, ...] = field(default=(), repr=False)
    solver_stats: SolverStats = field(default_factory=SolverStats, repr=False)
    squeeze_force_direction_deg: np.ndarray | None = None
    wall_force_direction_deg: np.ndarray | None = None
    axial_stretch: np.ndarray | None = None

    # -- what was solved: the setup's fields, as before the setup existed ---------------------

    @property
    def structure(self) -> Structure:
        """Hole, tube and wire (mm)."""
        return self.setup.structure

    @property
    def material(self) -> MooneyRivlin | HyperelasticModel:
        """Tube material."""
        return self.setup.material

    @property
    def penalty(self) -> float:
        """Contact penalty used (N/mm^3)."""
        return float(self.setup.penalty)

    @property
    def density(self) -> float:
        """Tube density used for the self-weight (t/mm^3)."""
        return float(self.setup.density)

    @property
    def gravity(self) -> str:
        """Orientation of gravity (unitless): ``'none'``, ``'toward-wall'`` or ``'toward-wire'``."""
        return self.setup.gravity

    @property
    def wire_angle_deg(self) -> float:
        """Angle of the wire centre from the top of the hole (deg; 0: the half model)."""
        return self.setup.angle_deg

    @property
    def mu_wall(self) -> float:
        """Coulomb coefficient of the tube on the hole wall (unitless)."""
        return self.setup.mu[0]

    @property
    def mu_wire(self) -> float:
        """Coulomb coefficient of the tube on the wire (unitless)."""
        return self.setup.mu[1]

    @property
    def ends(self) -> str:
        """The tube's axial condition: ``'plane-strain'``, ``'closed'`` or ``'open'``."""
        return self.setup.ends

    def contact_point_data(self, index: int = -1) -> dict[str, np.ndarray]:
        """Per-node contact fields of one pressure, for VTU point data (0 off the arcs).

        Parameters
        ----------
        index : int
            Position in :attr:`pressure_mpa` (default the last).

        Returns
        -------
        dict of str to ndarray (n_nodes,)
            ``contact_pressure_wire_mpa``, ``contact_pressure_wall_mpa`` (true normal
            pressure), ``contact_shear_wire_mpa``, ``contact_shear_wall_mpa`` (signed friction
            traction) and ``contact_stick`` (1 where a contact node sticks).

        Examples
        --------
        >>> from exofric.fe import MeshSpec
        >>> from exofric.geometry import BASE
        >>> from exofric.material import MooneyRivlin
        >>> from exofric.simulate import squeeze
        >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.6], mesh=MeshSpec(2, 12))
        >>> d = r.contact_point_data()
        >>> float(d["contact_pressure_wire_mpa"].max()) > 1.0
        True
        """
        n = len(self.nodes)
        out = {k: np.zeros(n) for k in ("contact_pressure_wire_mpa", "contact_pressure_wall_mpa",
                                        "contact_shear_wire_mpa", "contact_shear_wall_mpa",
                                        "contact_stick")}
        if not self.contact.profiles:
            return out
        prof = self.contact.profiles[index]
        for name in ("wire", "wall"):
            arc = prof[name]
            idx = np.asarray(arc["node"], dtype=int)
            out[f"contact_pressure_{name}_mpa"][idx] = arc["pressure_mpa"]
            out[f"contact_shear_{name}_mpa"][idx] = arc["shear_mpa"]
            out["contact_stick"][idx] = np.maximum(out["contact_stick"][idx],
                                                   np.asarray(arc["stick"], dtype=float))
        return out

    @property
    def length_mm(self) -> float:
        """Tube length L (mm) over which totals are integrated."""
        return self.structure.length_mm

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unit-suffixed keys; the groups' keys flat, as before grouping)."""
        c, e = self.contact, self.estimate
        return {
            "pressure_mpa": self.pressure_mpa.tolist(),
            "squeeze_force_n": self.squeeze_force_n.tolist(),
            "squeeze_force_n_per_mm": self.squeeze_force_n_per_mm.tolist(),
            "wall_force_n": self.wall_force_n.tolist(),
            "wall_force_n_per_mm": self.wall_force_n_per_mm.tolist(),
            "wire_contact_halfwidth_mm": c.wire_contact_halfwidth_mm.tolist(),
            "wall_contact_arc_mm": c.wall_contact_arc_mm.tolist(),
            "max_penetration_mm": c.max_penetration_mm.tolist(),
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
            "accuracy": e.accuracy,
            "gravity": self.gravity,
            "estimate_mesh": None if e.mesh is None else e.mesh.to_dict(),
            "n_error_estimate_pct": opt_list(e.pct),
            "n_error_estimate_n_per_mm": opt_list(e.n_per_mm),
            "n_error_estimate_reliable": (None if e.reliable is None
                                          else [bool(x) for x in e.reliable]),
            "coarse_squeeze_force_n_per_mm": opt_list(e.coarse_n_per_mm),
            "wire_tangential_force_error_estimate_pct": opt_list(e.wire_tangential_pct),
            "solver_stats": self.solver_stats.to_dict(),
            "wire_angle_deg": self.wire_angle_deg,
            "squeeze_force_direction_deg": _nan_list(self.squeeze_force_direction_deg),
            "wall_force_direction_deg": _nan_list(self.wall_force_direction_deg),
            "mu_wall": self.mu_wall,
            "mu_wire": self.mu_wire,
            "friction_penalty_n_per_mm3": c.friction_penalty,
            "wire_pressure_integral_n_per_mm": _nan_list(c.wire_pressure_integral_n_per_mm),
            "wall_pressure_integral_n_per_mm": _nan_list(c.wall_pressure_integral_n_per_mm),
            "wire_tangential_force_n_per_mm": _nan_list(c.wire_tangential_force_n_per_mm),
            "wall_tangential_force_n_per_mm": _nan_list(c.wall_tangential_force_n_per_mm),
            "stick_fraction_wire": _nan_list(c.stick_fraction_wire),
            "stick_fraction_wall": _nan_list(c.stick_fraction_wall),
            "contact": list(c.profiles),
            "ends": self.ends,
            "axial_stretch": (np.ones_like(self.pressure_mpa) if self.axial_stretch is None
                              else self.axial_stretch).tolist(),
        }

    def to_frame(self) -> pd.DataFrame:
        """The per-pressure curves as a DataFrame: one row per pressure (MPa, N, N/mm, mm).

        Columns: ``pressure_mpa``, ``squeeze_force_n`` (total over the tube length),
        ``squeeze_force_per_depth_n_per_mm``, ``wall_force_n``,
        ``wall_force_per_depth_n_per_mm``, ``wire_contact_halfwidth_mm``,
        ``wall_contact_arc_mm``, ``max_penetration_mm``, ``max_stretch`` (unitless),
        ``newton_iterations`` (count) and ``n_error_estimate_pct`` (%, NaN for an explicit
        mesh).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> from exofric.fe import MeshSpec
        >>> from exofric.geometry import BASE
        >>> from exofric.material import MooneyRivlin
        >>> from exofric.simulate import squeeze
        >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.3, 0.6], mesh=MeshSpec(2, 12))
        >>> df = r.to_frame()
        >>> list(df.columns[:3]), len(df)
        (['pressure_mpa', 'squeeze_force_n', 'squeeze_force_per_depth_n_per_mm'], 2)
        """
        import pandas as pd

        c, p = self.contact, self.pressure_mpa
        return pd.DataFrame({
            "pressure_mpa": self.pressure_mpa,
            "squeeze_force_n": self.squeeze_force_n,
            "squeeze_force_per_depth_n_per_mm": self.squeeze_force_n_per_mm,
            "wall_force_n": self.wall_force_n,
            "wall_force_per_depth_n_per_mm": self.wall_force_n_per_mm,
            "wire_contact_halfwidth_mm": c.wire_contact_halfwidth_mm,
            "wall_contact_arc_mm": c.wall_contact_arc_mm,
            "max_penetration_mm": c.max_penetration_mm,
            "max_stretch": self.max_stretch,
            "newton_iterations": np.asarray(self.newton_iterations, dtype=int),
            "n_error_estimate_pct": _opt_col(self.estimate.pct, p),
            "n_error_estimate_reliable": (np.full(p.size, np.nan) if self.estimate.reliable
                                          is None else self.estimate.reliable.astype(float)),
            "wire_pressure_integral_n_per_mm": _opt_col(c.wire_pressure_integral_n_per_mm, p),
            "wall_pressure_integral_n_per_mm": _opt_col(c.wall_pressure_integral_n_per_mm, p),
            "wire_tangential_force_n_per_mm": _opt_col(c.wire_tangential_force_n_per_mm, p),
            "wire_tangential_force_error_estimate_pct": _opt_col(
                self.estimate.wire_tangential_pct, p),
            "wall_tangential_force_n_per_mm": _opt_col(c.wall_tangential_force_n_per_mm, p),
            "stick_fraction_wire": _opt_col(c.stick_fraction_wire, p),
            "stick_fraction_wall": _opt_col(c.stick_fraction_wall, p),
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
        >>> from exofric.simulate import squeeze
        >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.3, 0.6], mesh=MeshSpec(2, 12))
        >>> r.plot().get_xlabel()
        'pressure P (MPa)'
        """
        from exofric.plots import plot_squeeze_force

        return plot_squeeze_force(self, ax)

