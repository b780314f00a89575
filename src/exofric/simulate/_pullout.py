"""Pull-out of the wire through the inflated tube, and the locked knee's stiffness (issue 39).

Three levels (docs/formulation.md, section 4f):

* **Section** (:func:`section_pullout`): the axial (anti-plane) response of the squeezed tube
  per unit length, from the converged squeeze at P: scalar problem on the reference section
  (:mod:`exofric.simulate._antiplane`), Coulomb friction on the tube-wire (``mu_wire``) and
  tube-wall (``mu_wall``) arcs with true stick (augmented Lagrangian), and the rigid-plastic
  wire-wall line contact (``mu_wire_wall`` x N). The normal pressures are the squeeze's, held.
* **Length** (:func:`pullout`): shear lag EA u'' = q(u) along the tube with the section's law
  as an Iwan (parallel Jenkins) model per station (Masing unloading/reloading), static
  coefficient until a slider first slides, the cable's EA, the pulled end displaced.
* **Knee**: :func:`exofric.friction.joint_stiffness` turns the first loading
  (``pullout(..., first_loading=True)``) into T = capstan x F R, theta = delta / R: K(P)
  (Nm/rad) and T_break(P) (Nm); it lives with the capstan in :mod:`exofric.friction`.

Units: mm, N, MPa; section forces in N per mm of tube; torques in Nm, angles in rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, overload

import numpy as np

from exofric import defaults
from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import ConvergenceError, InputError
from exofric.fe import nodal_weights
from exofric.geometry import Structure
from exofric.material import HyperelasticModel, MooneyRivlin
from exofric.simulate._antiplane import (
    CondensedSection,
    antiplane_stiffness,
    armijo,
    axial_shear,
    condense,
    mooney_rivlin_modulus,
    recover,
    solve_friction_steps,
)
from exofric.simulate._pullout_setup import PulloutSetup
from exofric.simulate._shear_lag import HeldEnds, zone_curve

if TYPE_CHECKING:
    import pandas as pd

    from exofric.simulate._squeeze_result import SqueezeResult

__all__ = ["PulloutResult", "SectionPullout", "pullout", "section_pullout"]


# ----------------------------------------------------------------------------------------------
# results


@checked_init
@dataclass(frozen=True)
class SectionPullout(DisplayMixin):
    """Axial pull of the wire through one unit length of squeezed tube (N/mm, mm).

    Attributes
    ----------
    pressure_mpa : float
        Tube pressure (MPa).
    displacement_mm : ndarray
        Imposed axial wire displacement per step (mm).
    force_n_per_mm : ndarray
        Pull force per unit tube length (N/mm): tube friction plus the wire-wall line contact.
    tube_force_n_per_mm : ndarray
        Part carried by the tube-wire arc (N/mm).
    initial_stiffness_n_per_mm2 : float
        Initial stiffness of the tube-borne part (N/mm per mm), all arcs stuck.
    slip_displacement_mm : float
        Wire displacement at which the whole tube-wire arc slides (mm, to 1/32 of a load
        step; NaN if not reached).
    sliding_force_n_per_mm : float
        Sliding plateau: mu_wire S_wire + mu_wire_wall N (N/mm), or mu_wall S_wall +
        mu_wire_wall N when the tube slides on the wall first (``ends='free'``).
    wire_pressure_integral_n_per_mm, wall_pressure_integral_n_per_mm : float
        S_wire, S_wall of the squeeze state (N/mm, held during the pull).
    squeeze_force_n_per_mm : float
        N of the squeeze: the wire-wall line contact's normal force (N/mm).
    stick_fraction_wire, stick_fraction_wall : ndarray
        Share (by reference length) of each arc that sticks (no slip increment) in each step
        (unitless; NaN without that arc).
    mu_wire, mu_wall, mu_wire_wall : float
        Kinetic Coulomb coefficients (unitless).
    ends : str
        ``'fixed'`` (tube held axially by its end fittings) or ``'free'``.
    shear_modulus_mpa : float
        Small-strain shear modulus G of the tube (MPa).
    modulus_note : str
        How the anti-plane modulus was built (exact Mooney-Rivlin, or linearised).
    in_plane_shear_ratio : float
        Largest |in-plane friction traction| / (mu_wire p) on the wire arc of the squeeze
        state (0 for a frictionless squeeze): the share of the Coulomb disk the pull neglects.
    stick_penalty_n_per_mm3 : float
        Stick penalty of the augmented Lagrangian (N/mm^3).
    notes : tuple of str
        Statements (e.g. no contact below the onset: zero force).
    axial_shear_max : float
        Largest axial shear |grad_X w| in the tube at full slip (unitless).
    in_plane_coupling_mpa : float
        G |g|^2 (MPa): the order of the in-plane stress change the axial shear would cause
        (neglected: the squeeze's contact pressures are held), to compare with the contact
        pressures.
    held_ends : HeldEnds or None
        What the length model needs to solve the zones next to held end faces (the section's
        stiffness without the fittings' rod or the regulariser, its contact nodes; N/mm^2,
        mm).
    max_stretch : float
        Largest in-plane principal stretch of the squeeze state (unitless; NaN if unknown):
        past :data:`~exofric.defaults.PULLOUT_HELD_STRETCH_NOTE` a pull with held ends notes
        that its end zones are too stiff in the early slip.

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> s = section_pullout(PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3,
    ...                                  mu_wall=0.5, mu_wire_wall=0.2, accuracy="draft"), 0.6)
    >>> bool(abs(s.force_n_per_mm[-1] - s.sliding_force_n_per_mm) < 1e-6)
    True
    """

    pressure_mpa: float
    displacement_mm: np.ndarray
    force_n_per_mm: np.ndarray
    tube_force_n_per_mm: np.ndarray
    initial_stiffness_n_per_mm2: float
    slip_displacement_mm: float
    sliding_force_n_per_mm: float
    wire_pressure_integral_n_per_mm: float
    wall_pressure_integral_n_per_mm: float
    squeeze_force_n_per_mm: float
    stick_fraction_wire: np.ndarray
    stick_fraction_wall: np.ndarray
    mu_wire: float
    mu_wall: float
    mu_wire_wall: float
    ends: str
    shear_modulus_mpa: float
    modulus_note: str
    in_plane_shear_ratio: float
    stick_penalty_n_per_mm3: float
    notes: tuple[str, ...] = ()
    axial_shear_max: float = 0.0
    in_plane_coupling_mpa: float = 0.0
    held_ends: HeldEnds | None = field(default=None, repr=False, compare=False)
    max_stretch: float = float("nan")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unit-suffixed keys; per-step lists)."""
        n = len(self.displacement_mm)
        return {
            "pressure_mpa": self.pressure_mpa,
            "displacement_mm": self.displacement_mm.tolist(),
            "force_n_per_mm": self.force_n_per_mm.tolist(),
            "tube_force_n_per_mm": self.tube_force_n_per_mm.tolist(),
            "initial_stiffness_n_per_mm2": self.initial_stiffness_n_per_mm2,
            "slip_displacement_mm": (None if not math.isfinite(self.slip_displacement_mm)
                                     else self.slip_displacement_mm),
            "sliding_force_n_per_mm": self.sliding_force_n_per_mm,
            "wire_pressure_integral_n_per_mm": [self.wire_pressure_integral_n_per_mm] * n,
            "wall_pressure_integral_n_per_mm": self.wall_pressure_integral_n_per_mm,
            "squeeze_force_n_per_mm": self.squeeze_force_n_per_mm,
            "stick_fraction_wire": _nan_none(self.stick_fraction_wire),
            "stick_fraction_wall": _nan_none(self.stick_fraction_wall),
            "mu_wire": self.mu_wire, "mu_wall": self.mu_wall,
            "mu_wire_wall": self.mu_wire_wall, "ends": self.ends,
            "shear_modulus_mpa": self.shear_modulus_mpa, "modulus_note": self.modulus_note,
            "in_plane_shear_ratio": self.in_plane_shear_ratio,
            "stick_penalty_n_per_mm3": self.stick_penalty_n_per_mm3,
            "axial_shear_max": self.axial_shear_max,
            "in_plane_coupling_mpa": self.in_plane_coupling_mpa,
            "max_stretch": None if not math.isfinite(self.max_stretch) else self.max_stretch,
            "notes": list(self.notes),
        }

    def to_frame(self) -> pd.DataFrame:
        """One row per step: displacement (mm), forces (N/mm), stick fractions."""
        import pandas as pd

        return pd.DataFrame({
            "displacement_mm": self.displacement_mm, "force_n_per_mm": self.force_n_per_mm,
            "tube_force_n_per_mm": self.tube_force_n_per_mm,
            "stick_fraction_wire": self.stick_fraction_wire,
            "stick_fraction_wall": self.stick_fraction_wall})

    def plot(self, ax: Any | None = None) -> Any:
        """q(delta): force per length (N/mm) vs wire displacement (mm).

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (default a new figure).

        Returns
        -------
        matplotlib Axes
        """
        from exofric.plots import plot_pullout

        return plot_pullout(self, ax)


@checked_init
@dataclass(frozen=True)
class PulloutResult(DisplayMixin):
    """Pull of the wire through the whole tube length: F(delta) at the pulled end (N, mm).

    Attributes
    ----------
    displacement_mm : ndarray
        Pulled-end displacement along the path (mm): 0 -> D -> -D -> D per cycle.
    force_n : ndarray
        Cable force at the pulled end (N).
    static_force_n : float
        Breakaway: the largest force on the first loading leg (N).
    sliding_force_n : float
        Force with the whole length sliding, L x the section's kinetic plateau (N).
    slip_length_mm : ndarray
        Length of tube (from the pulled end) over which the wire slides on its whole arc (mm).
    length_mm, cable_ea_n, mu_static : float
        Tube length (mm), cable EA (N), static coefficient (unitless).
    section : SectionPullout
        The section law used.
    notes : tuple of str
        Statements carried from the section (e.g. zero force below the contact onset).

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> r = pullout(PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
    ...                          mu_wire_wall=0.2, accuracy="draft"), 0.6, displacement_mm=3.0)
    >>> bool(abs(r.static_force_n - r.sliding_force_n) < 0.01 * r.sliding_force_n)
    True
    """

    displacement_mm: np.ndarray
    force_n: np.ndarray
    static_force_n: float
    sliding_force_n: float
    slip_length_mm: np.ndarray
    length_mm: float
    cable_ea_n: float
    mu_static: float
    section: SectionPullout = field(repr=False)
    notes: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unit-suffixed keys)."""
        return {
            "displacement_mm": self.displacement_mm.tolist(), "force_n": self.force_n.tolist(),
            "static_force_n": self.static_force_n, "sliding_force_n": self.sliding_force_n,
            "slip_length_mm": self.slip_length_mm.tolist(), "length_mm": self.length_mm,
            "cable_ea_n": self.cable_ea_n, "mu_static": self.mu_static,
            "pressure_mpa": self.section.pressure_mpa,
            "section_sliding_force_n_per_mm": self.section.sliding_force_n_per_mm,
            "section_initial_stiffness_n_per_mm2": self.section.initial_stiffness_n_per_mm2,
            "notes": list(self.notes),
        }

    def to_frame(self) -> pd.DataFrame:
        """One row per path step: displacement (mm), force (N), slip length (mm)."""
        import pandas as pd

        return pd.DataFrame({"displacement_mm": self.displacement_mm, "force_n": self.force_n,
                             "slip_length_mm": self.slip_length_mm})

    def plot(self, ax: Any | None = None) -> Any:
        """F(delta) at the pulled end (N vs mm), the hysteresis loop.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (default a new figure).

        Returns
        -------
        matplotlib Axes
        """
        from exofric.plots import plot_pullout

        return plot_pullout(self, ax)


def _nan_none(a: np.ndarray) -> list[float | None]:
    return [None if not np.isfinite(v) else float(v) for v in np.asarray(a, float)]


# ----------------------------------------------------------------------------------------------
# section


def _mooney_rivlin(material: Any) -> MooneyRivlin | None:
    """The material as Mooney-Rivlin constants (neo-Hookean: C01 = 0), or None (Yeoh, Ogden)."""
    if isinstance(material, MooneyRivlin):
        return material
    if isinstance(material, HyperelasticModel) and material.name in ("neo-hookean",
                                                                     "mooney-rivlin"):
        return material.to_mooney_rivlin()
    return None


def _modulus(material: Any, nodes: np.ndarray, elements: np.ndarray,
             disp: np.ndarray) -> tuple[np.ndarray | float, float, str]:
    """(anti-plane modulus, G MPa, note)."""
    mr = _mooney_rivlin(material)
    if mr is not None:
        c10, c01 = mr.c10_mpa, mr.c01_mpa
    else:
        g = float(material.shear_modulus_mpa)
        return g, g, (f"{material.name}: A = G I, the small-strain shear modulus (a "
                      "linearisation: its energy is not quadratic in the axial shear)")
    a = mooney_rivlin_modulus(nodes, elements, disp, c10, c01)
    return a, 2.0 * (c10 + c01), ("Mooney-Rivlin with the squeeze's in-plane F2 held: A = 2 C10 "
                                  "J^-2/3 I + 2 C01 J^-4/3 adj(C2), exact for the axial shear")


def _ring_edges(nodes: np.ndarray, elements: np.ndarray, center: tuple[float, float],
                radius: float, outer: bool = True) -> np.ndarray:
    """Outer- (local nodes 2, 5, 8) or inner-surface (0, 3, 6) edges (m, 3) of a quad9 polar
    mesh: the element sides whose nodes lie at ``radius`` (mm) from ``center``."""
    e = elements[:, [2, 5, 8] if outer else [0, 3, 6]]
    r = np.hypot(nodes[e, 0] - center[0], nodes[e, 1] - center[1])
    return e[np.all(np.abs(r - radius) < 1e-6 * radius, axis=1)]


@dataclass(frozen=True)
class _Section(CondensedSection):
    """The condensed section and what the length model's held end zones need."""

    coupling: HeldEnds | None = None


def _build_section(res: SqueezeResult, k: int, mu_wire: float, mu_wall: float, ends: str,
                   held_zone: str = defaults.PULLOUT_HELD_ZONE
                   ) -> tuple[_Section, float, float, float, float, str, float, Any, np.ndarray]:
    """(condensed section, factor to full section, G, S_wire, S_wall, note, in-plane ratio,
    full stiffness, contact node indices).

    The end fittings hold the tube as a rod (E_t A_t = 3 G A) fixed at both ends under a
    uniform load: midspan stiffness 8 E_t A_t / L^2 per mm. While the tube sticks on the wall
    the wall carries it and the rod's force in a long tube's middle is zero, so the rod acts
    only on the wall arc's slip: a hardening spring on each wall node, shared by tributary
    length (a section that does not touch the wall: a foundation spread over the section by
    area). Both ends: a 1e-4 G foundation by area (regulariser). The length model solves the
    zones next to held end faces itself (:mod:`exofric.simulate._shear_lag`) from the
    stiffness without either.
    """
    st = res.structure
    nodes, elements = res.nodes, res.elements
    disp = res.displacements[k]
    half = res.symmetry.startswith("half")
    fac = 2.0 if half else 1.0
    a, g, note = _modulus(res.material, nodes, elements, disp)
    K, area = antiplane_stiffness(nodes, elements, a)
    a_t = 0.25 * math.pi * (st.tube_od_mm ** 2 - st.tube_id_mm ** 2)
    k_rod = 8.0 * 3.0 * g * a_t / st.length_mm ** 2 if ends == "fixed" else 0.0
    K_free = K.tocsr()
    K = K + _diag(1e-4 * g / fac * area / area.sum())
    edges = _ring_edges(nodes, elements, st.tube_center_mm, 0.5 * st.tube_od_mm)
    x_now = nodes + disp
    w_now = nodal_weights(edges, x_now, len(nodes))
    w_ref = nodal_weights(edges, nodes, len(nodes))
    stretch = 1.0 if res.axial_stretch is None else float(res.axial_stretch[k])
    prof = res.contact.profiles[k]
    idx, cap, on_wire, length = [], [], [], []
    s = {"wire": 0.0, "wall": 0.0}
    ratio = 0.0
    for name, mu in (("wire", mu_wire), ("wall", mu_wall)):
        arc = prof[name]
        nd = np.asarray(arc["node"], dtype=int)
        p = np.asarray(arc["pressure_mpa"], dtype=float)
        fn = p * w_now[nd] * stretch  # N per mm of tube (reference length)
        s[name] = fac * float(fn.sum()) / stretch
        idx.append(nd)
        cap.append(mu * fn)
        on_wire.append(np.full(len(nd), name == "wire"))
        length.append(w_ref[nd])
        if name == "wire" and len(nd):
            tq = np.abs(np.asarray(arc["shear_mpa"], dtype=float))
            ratio = float(np.max(tq / np.maximum(mu * p, 1e-300))) if mu > 0 else 0.0
    c_idx = np.concatenate(idx)
    wire, caps, lengths = np.concatenate(on_wire), np.concatenate(cap), np.concatenate(length)
    hardening = None
    if k_rod > 0.0 and np.any(~wire):
        hardening = np.where(wire, 0.0, k_rod / fac * lengths / lengths[~wire].sum())
    elif k_rod > 0.0:
        K = K + _diag(k_rod / fac * area / area.sum())
    K = K.tocsr()
    held = HeldEnds(K_free, area, CondensedSection(np.zeros((0, 0)), wire, caps, lengths),
                    c_idx, fac, defaults.PULLOUT_EZ_OVER_G * g,
                    vector=(_vector_cached(res, k, c_idx, half)
                            if ends == "fixed" and held_zone == "vector" else None))
    sec = _Section(condense(K, c_idx), wire, caps, lengths, hardening, held)
    return sec, fac, g, s["wire"], s["wall"], note, ratio, K, c_idx


#: the vector zone's section per (squeeze result, pressure index): it does not depend on the
#: friction coefficients, which a fit (``fit-pullout``) varies over the same squeeze; an entry
#: lives as long as its squeeze result
_VECTOR_SECTIONS: dict[tuple[int, int], Any] = {}


def _vector_cached(res: SqueezeResult, k: int, contact: np.ndarray, half: bool) -> Any:
    """:func:`_vector`, once per squeeze result and pressure."""
    import weakref

    key = (id(res), k % len(res.pressure_mpa))
    if key not in _VECTOR_SECTIONS:
        _VECTOR_SECTIONS[key] = _vector(res, k, contact, half)
        weakref.finalize(res, _VECTOR_SECTIONS.pop, key, None)
    return _VECTOR_SECTIONS[key]


def _vector(res: SqueezeResult, k: int, contact: np.ndarray, half: bool) -> Any:
    """The vector zone's section (:mod:`exofric.simulate._vector_zone`) for Mooney-Rivlin
    and neo-Hookean tubes; None (the scalar zone) for the others."""
    from exofric.fe import PlaneStrainMaterial
    from exofric.simulate._vector_zone import vector_section

    material = res.material
    mr = _mooney_rivlin(material)
    if mr is None:
        return None
    nodes, elements = res.nodes, res.elements
    # the mesh's own centre (the squeeze may have moved the tube from the structure's)
    c = nodes[elements[:, [0, 3, 6, 2, 5, 8]]].reshape(-1, 2).mean(axis=0)
    bore = _ring_edges(nodes, elements, (c[0], c[1]), 0.5 * res.structure.tube_id_mm,
                       outer=False)
    sym = np.flatnonzero(np.abs(nodes[:, 0]) < 1e-9) if half else np.zeros(0, int)
    stretch = 1.0 if res.axial_stretch is None else float(res.axial_stretch[k])
    # contact normals from the obstacles into the tube: off the wire, in from the hole wall
    # (the wire rests on the hole wall: its centre is (hole - wire) / 2 from the hole's, at the
    # wire's angle from the top, as the squeeze places it)
    x = nodes[contact] + res.displacements[k][contact]
    on_wire = np.isin(contact, np.asarray(res.contact.profiles[k]["wire"]["node"], int))
    st = res.structure
    a = math.radians(float(res.setup.wire_angle_deg))
    wc = 0.5 * (st.hole_mm - st.wire_mm) * np.array([math.sin(a), math.cos(a)])
    nrm = np.where(on_wire[:, None], x - wc, -x)
    nrm = nrm / np.hypot(nrm[:, 0], nrm[:, 1])[:, None]
    return vector_section(nodes, elements, res.displacements[k], c10=mr.c10_mpa,
                          c01=mr.c01_mpa, bulk_mpa=PlaneStrainMaterial(material).bulk_modulus,
                          pressure_mpa=float(res.pressure_mpa[k]), contact=contact, bore=bore,
                          symmetry=sym, axial_stretch=stretch, tube_center=(c[0], c[1]),
                          contact_normals=nrm)


def _diag(v: np.ndarray) -> Any:
    import scipy.sparse as sp

    return sp.diags(v)


def _check_setup(setup: Any) -> None:
    if not isinstance(setup, PulloutSetup):
        raise InputError("setup must be a PulloutSetup (exofric.simulate.PulloutSetup(structure, "
                         f"material, mu_wire=..., mu_wall=..., mu_wire_wall=...)), got "
                         f"{type(setup).__name__}", param="setup")


def _squeeze_for(structure: Structure, material: Any, pressures: list[float],
                 accuracy: str | None, mesh: Any) -> SqueezeResult:
    from exofric.simulate._setup import SqueezeSetup

    return SqueezeSetup(structure, material, accuracy=accuracy, mesh=mesh,
                        keep_fields=True).solve(pressures)


def section_pullout(setup: PulloutSetup, pressure_mpa: float, *,
                    squeeze_result: SqueezeResult | None = None,
                    squeeze_index: int = -1) -> SectionPullout:
    """Axial pull of the wire through a unit length of the squeezed tube (N/mm vs mm).

    The squeeze at ``pressure_mpa`` is solved (frictionless, plane strain, at the setup's
    accuracy; or pass a ``squeeze_result`` with fields kept), then the anti-plane problem with
    Coulomb friction (module docstring) is driven by the wire displacement until the whole
    tube-wire arc slides.

    Parameters
    ----------
    setup : PulloutSetup
        Structure, material, the three interfaces' coefficients (``mu_static`` is not used
        here: the section law is kinetic), the ends (``fixed``: the tube held axially by its
        end fittings, a rod of E = 3 G to both ends acting on the wall arc's slip, so the
        tube that slides on the wall is held until the wire slides; ``free``: it may slide
        on the wall once the wall arc slides), the squeeze's accuracy and the numerics
        (``n_steps``, ``stick_penalty``, ``creep_tol_mm``).
    pressure_mpa : float
        Pressure (MPa).
    squeeze_result : SqueezeResult, optional
        A solved squeeze (fields kept) to start from instead; ``squeeze_index`` picks the
        pressure (``pressure_mpa`` is then that pressure).
    squeeze_index : int
        Index into ``squeeze_result``'s pressures.

    Returns
    -------
    SectionPullout

    Raises
    ------
    InputError
        Not a PulloutSetup, or a squeeze result without fields.

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> setup = PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
    ...                      mu_wire_wall=0.0, accuracy="draft")
    >>> s = section_pullout(setup, 0.6)
    >>> round(s.sliding_force_n_per_mm / s.wire_pressure_integral_n_per_mm, 6)
    0.3
    """
    _check_setup(setup)
    mw, mh, mww, _ = setup.friction
    ends, num = setup.ends, setup.numerics
    stick_penalty, creep_tol_mm, n_steps = num.stick_penalty, num.creep_tol_mm, num.n_steps
    if squeeze_result is None:
        squeeze_result = _squeeze_for(setup.structure, setup.material, [float(pressure_mpa)],
                                      setup.accuracy, setup.mesh)
        squeeze_index = -1
    res = squeeze_result
    if not res.displacements:
        raise InputError("squeeze_result must keep its fields (keep_fields=True)",
                         param="squeeze_result")
    p = float(res.pressure_mpa[squeeze_index])
    n_sq = float(res.squeeze_force_n_per_mm[squeeze_index])
    stretch = float(res.max_stretch[squeeze_index])
    sec, fac, g, s_wire, s_wall, note, ratio, K_full, c_idx = _build_section(
        res, squeeze_index, mw, mh, ends, num.held_zone)
    notes: list[str] = []
    cap_wire = fac * float(sec.capacity[sec.on_wire].sum())
    cap_wall = fac * float(sec.capacity[~sec.on_wire].sum())
    q_line = mww * n_sq
    if ratio > 1e-6:
        notes.append(f"the squeeze's in-plane friction uses up to {100 * ratio:.0f}% of the "
                     "wire arc's Coulomb disk; the pull assumes it relaxes as the wire slides "
                     "axially (the full mu p is available axially)")
    if not np.any(sec.on_wire) or cap_wire + q_line == 0.0:
        if not np.any(sec.on_wire):
            notes.append(f"P = {p:g} MPa is below the contact onset: the tube does not touch "
                         "the wire, zero force")
        d = np.zeros(1)
        z = np.zeros(1)
        return SectionPullout(p, d, z, z, 0.0, float("nan"), 0.0, s_wire, s_wall, n_sq,
                              np.full(1, np.nan), np.full(1, np.nan), mw, mh, mww, ends, g,
                              note, ratio, float(stick_penalty), tuple(notes),
                              max_stretch=stretch)
    on = sec.on_wire
    k0 = fac * float(sec.K[np.ix_(on, on)].sum())  # all stuck: wire nodes at 1, wall at 0
    plateau_tube = cap_wire if (ends == "fixed" or cap_wall >= cap_wire) else cap_wall
    d_est = max(cap_wire / k0, 1e-9) if k0 > 0 else 1.0
    step = 3.0 * d_est / int(n_steps)
    deltas = np.arange(int(n_steps) + 1) * step
    out = solve_friction_steps(sec, deltas, stick_penalty, creep_tol_mm)
    chunks = 0
    # extend until the wire arc slides on its whole length, or the tube slides on the wall
    # (free ends; held ends: the fittings take over from the wall, the rod's spring on the
    # wall's slip, until the wire slides: chunks long enough for that spring to reach the
    # wire's capacity)
    while (np.any(out["stick"][-1][on]) and (ends == "fixed" or np.any(out["stick"][-1][~on]))
           and chunks < 20 and cap_wire > 0 and plateau_tube == cap_wire):
        chunk = int(n_steps) * step
        if not np.any(out["stick"][-1][~on]) and sec.hardening is not None:
            slope = max(fac * float(sec.hardening.sum()), 1e-12 * k0)
            chunk = max(chunk, 1.5 * (cap_wire - fac * float(out["force"][-1])) / slope)
        more = deltas[-1] + np.arange(1, int(n_steps) + 1) * (chunk / int(n_steps))
        nxt = _continue(sec, out, deltas, more, stick_penalty, creep_tol_mm)
        deltas = np.concatenate([deltas, more])
        out = nxt
        chunks += 1
    q_tube = fac * out["force"]
    stick = out["stick"]
    lw = sec.length
    stick_wire = np.array([(lw[on] * s_[on]).sum() / lw[on].sum() for s_ in stick])
    wall_len = lw[~on].sum()
    stick_wall = (np.array([(lw[~on] * s_[~on]).sum() / wall_len for s_ in stick])
                  if wall_len > 0 else np.full(len(stick), np.nan))
    full = np.flatnonzero(stick_wire == 0.0)
    slip_d = float(deltas[full[0]]) if full.size else float("nan")
    if full.size and full[0] > 0:
        # the full-slip displacement to 1/32 of a step: re-run the monotone path with the
        # step that crossed it subdivided (the law is path-independent under monotone load)
        j = int(full[0])
        fine = np.linspace(deltas[j - 1], deltas[j], 33)[1:]
        ref = solve_friction_steps(sec, np.concatenate([deltas[:j], fine]), stick_penalty,
                                   creep_tol_mm)
        none = ~np.any(ref["stick"][j:][:, on], axis=1)
        slip_d = float(fine[int(np.argmax(none))])
    if cap_wire > 0 and not full.size:
        notes.append("the tube-wire arc did not slide on its whole length within "
                     f"{deltas[-1]:.3g} mm (the tube slides on the wall)")
    force = q_tube + np.where(deltas > 0.0, q_line, 0.0)
    # neglected reverse coupling: the axial shear g changes the in-plane stresses by ~ G |g|^2
    # (second order), against contact pressures of order S_wire / arc: measured, not applied
    j = int(full[0]) if full.size else len(deltas) - 1
    w_full = recover(K_full, c_idx, out["w"][j])
    g_max = axial_shear(res.nodes, res.elements, w_full)
    return SectionPullout(p, deltas, force, q_tube, k0, slip_d, plateau_tube + q_line,
                          s_wire, s_wall, n_sq, stick_wire, stick_wall, mw, mh, mww, ends, g,
                          note, ratio, float(stick_penalty), tuple(notes), g_max,
                          g * g_max ** 2, sec.coupling, stretch)


def _continue(sec: CondensedSection, out: dict[str, np.ndarray], deltas: np.ndarray,
              more: np.ndarray, penalty: float, tol: float) -> dict[str, np.ndarray]:
    """Re-run the path with ``more`` steps appended (the solver is cheap; keeps one code path)."""
    allsteps = np.concatenate([deltas, more])
    return solve_friction_steps(sec, allsteps, penalty, tol)


# ----------------------------------------------------------------------------------------------
# along the length: Iwan section law + shear lag


@dataclass(frozen=True)
class _Iwan:
    """Parallel Jenkins elements (stiffness N/mm^2, kinetic capacity N/mm) plus a spring.

    ``weight`` (nodes x elements, unitless) puts two laws along z (the held end zones and the
    section); ``tube`` flags the tube's sliders (default: the first ``n_tube``).
    """

    k: np.ndarray
    f: np.ndarray
    spring: float | np.ndarray
    n_tube: int
    weight: np.ndarray | None = None
    tube: np.ndarray | None = None


def _iwan(delta: np.ndarray, q: np.ndarray, line_cap: float, line_k: float) -> _Iwan:
    """Iwan model reproducing the monotone backbone q(delta) (piecewise linear, concave)."""
    d = np.asarray(delta, float)
    qq = np.asarray(q, float)
    ks: list[float] = []
    fs: list[float] = []
    spring = 0.0
    if len(d) >= 2 and qq[-1] > 0:
        s = np.diff(qq) / np.diff(d)
        s = np.clip(np.minimum.accumulate(s), 0.0, None)
        s_end = 0.0 if s[-1] <= 1e-9 * s[0] else float(s[-1])
        s_next = np.append(s[1:], s_end)
        kj = s - s_next
        keep = kj > 0
        ks += list(kj[keep])
        fs += list(kj[keep] * d[1:][keep])
        spring = s_end
    n_tube = len(ks)
    if line_cap > 0:
        ks.append(line_k)
        fs.append(line_cap)
    return _Iwan(np.array(ks), np.array(fs), spring, n_tube)


_EPS = float(np.finfo(float).eps)


def _shear_lag(law: _Iwan, ea: float, length: float, path: np.ndarray, ratio: float,
               n_z: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pulled-end force F (N) along ``path`` (mm); also u (steps, nodes) and sliding flags.

    EA u'' = q(u) on [0, L], u(0) = delta, EA u'(L) = 0 (the cable beyond the tube is free);
    linear elements, lumped q; each node carries its Jenkins sliders (static capacity ``ratio``
    x kinetic until a slider slides, kinetic while it slides).
    """
    from scipy.linalg import solve_banded

    n = int(n_z)
    h = length / n
    hl = np.full(n + 1, h)
    hl[0] = hl[-1] = 0.5 * h
    ne = len(law.k)
    pos = np.zeros((n + 1, ne))      # slider positions (mm)
    slid = np.zeros((n + 1, ne), bool)
    u = np.zeros(n + 1)
    kE = ea / h
    forces = np.zeros(len(path))
    full = np.zeros((len(path), n + 1), bool)
    us = np.zeros((len(path), n + 1))

    # per-node weights of the elements (held end zones: two laws along z), and tube sliders
    w8 = np.ones((n + 1, ne)) if law.weight is None else law.weight
    tube = ((np.arange(ne) < law.n_tube) if law.tube is None else law.tube) & (w8 > 0)
    spring = law.spring

    def q_of(u: np.ndarray, cap: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        tr = law.k * (u[:, None] - pos)
        st = np.abs(tr) <= cap
        fe = np.where(st, tr, np.sign(tr) * cap)
        return ((w8 * fe).sum(axis=1) + spring * u, (w8 * law.k * st).sum(axis=1) + spring,
                st)

    def energy(u: np.ndarray, cap: np.ndarray) -> float:
        x = u[:, None] - pos
        kx = law.k * np.abs(x)
        psi = np.where(kx <= cap, 0.5 * law.k * x * x, cap * np.abs(x) - 0.5 * cap ** 2 / law.k)
        return float(0.5 * kE * (np.diff(u) ** 2).sum()
                     + (hl * ((w8 * psi).sum(axis=1) + 0.5 * spring * u * u)).sum())

    def ku(u: np.ndarray) -> np.ndarray:
        r = np.zeros(n + 1)
        du = np.diff(u)
        r[:-1] -= kE * du
        r[1:] += kE * du
        return r

    for i, d in enumerate(path):
        kin = slid.copy()
        for _ in range(ne + 2):
            cap = np.where(kin, law.f, ratio * law.f)
            u[0] = d
            for _it in range(100):
                q, dq, st = q_of(u, cap)
                r = ku(u) + hl * q
                r[0] = 0.0
                # the load scale, or the round-off of kE du (a stiff cable: kE up to 1e10 N/mm)
                if np.abs(r[1:]).max() <= max(1e-9 * max(1.0, np.abs(hl * q).max()),
                                                64 * _EPS * kE * max(1.0, np.abs(u).max())):
                    break
                ab = np.zeros((3, n))
                ab[1] = 2 * kE + hl[1:] * dq[1:]
                ab[1, -1] = kE + hl[-1] * dq[-1]
                ab[0, 1:] = -kE
                ab[2, :-1] = -kE
                du = -solve_banded((1, 1), ab, r[1:])
                # a convex energy is minimised: Armijo backtracking stops active-set cycling
                def along(a: float, du: np.ndarray = du, cap: np.ndarray = cap) -> float:
                    return energy(np.r_[u[0], u[1:] + a * du], cap)

                step = armijo(along, float(r[1:] @ du)) * du
                u[1:] += step
                if np.abs(step).max() <= 1e-13 * max(1.0, np.abs(u).max()):
                    break                    # converged to round-off (the residual is kE eps u)
            else:
                raise ConvergenceError("pull-out along the length: Newton did not converge at "
                                       f"displacement {d:g} mm (more path steps: n_path)")
            new = ~st & ~kin
            if ratio == 1.0 or not np.any(new):
                break
            kin |= new
        q, dq, st = q_of(u, cap)
        tr = law.k * (u[:, None] - pos)
        sl = ~st
        pos = np.where(sl, u[:, None] - np.sign(tr) * cap / np.where(law.k > 0, law.k, 1.0),
                       pos)
        slid = sl
        r = ku(u) + hl * q
        forces[i] = r[0]
        full[i] = np.all(sl | ~tube, axis=1) if law.n_tube else np.all(sl, axis=1)
        us[i] = u
    return forces, us, full


def _path(d: float, cycles: int, steps: int) -> np.ndarray:
    up = np.linspace(0.0, d, steps + 1)
    legs = [up]
    for _ in range(int(cycles)):
        legs.append(np.linspace(d, -d, 2 * steps + 1)[1:])
        legs.append(np.linspace(-d, d, 2 * steps + 1)[1:])
    return np.concatenate(legs)


@overload
def pullout(setup: PulloutSetup, pressure_mpa: float, *, displacement_mm: float = ...,
            cycles: int = ..., section: Literal[False] = ..., first_loading: bool = ...,
            squeeze_result: SqueezeResult | None = ..., squeeze_index: int = ...
            ) -> PulloutResult: ...


@overload
def pullout(setup: PulloutSetup, pressure_mpa: float, *, displacement_mm: float = ...,
            cycles: int = ..., section: Literal[True], first_loading: bool = ...,
            squeeze_result: SqueezeResult | None = ..., squeeze_index: int = ...
            ) -> SectionPullout: ...


@overload
def pullout(setup: PulloutSetup, pressure_mpa: float, *, displacement_mm: float = ...,
            cycles: int = ..., section: bool = ..., first_loading: bool = ...,
            squeeze_result: SqueezeResult | None = ..., squeeze_index: int = ...
            ) -> PulloutResult | SectionPullout: ...


def pullout(
    setup: PulloutSetup,
    pressure_mpa: float,
    *,
    displacement_mm: float = 1.0,
    cycles: int = 1,
    section: bool = False,
    first_loading: bool = False,
    squeeze_result: SqueezeResult | None = None,
    squeeze_index: int = -1,
) -> PulloutResult | SectionPullout:
    """Pull the wire through the tube: F(delta) at the pulled end, breakaway, sliding (N, mm).

    Parameters
    ----------
    setup : PulloutSetup
        Structure, material, the coefficients (``mu_static`` gives the static peak: every
        slider of the section law holds ``mu_static / mu_wire`` x its kinetic capacity until
        it slides), the cable's EA (N), the ends, the squeeze's accuracy and the numerics
        (``n_z`` cable elements along L, ``n_path`` steps per amplitude, ``line_stick_rel``).
    pressure_mpa : float
        Pressure (MPa).
    displacement_mm : float
        Amplitude D of the pulled end (mm), 0 < D <= L: path 0 -> D, then ``cycles`` x
        (D -> -D -> D).
    cycles : int
        Back-and-forth cycles ([0, 100]).
    section : bool
        Return the per-unit-length :class:`SectionPullout` only.
    first_loading : bool
        Only the first leg 0 -> ``displacement_mm``, finely stepped up to past the estimated
        breakaway (``cycles`` ignored): what the knee's stiffness is read on.
    squeeze_result, squeeze_index
        A solved squeeze (fields kept) to start from, and the index of the pressure in it.

    Returns
    -------
    PulloutResult or SectionPullout

    Raises
    ------
    InputError
        Not a PulloutSetup, a displacement outside (0, L], negative cycles.

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> setup = PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
    ...                      mu_wire_wall=0.2, mu_static=0.36, accuracy="draft")
    >>> r = pullout(setup, 0.6, displacement_mm=3.0)
    >>> bool(r.static_force_n > r.sliding_force_n)
    True
    """
    _check_setup(setup)
    L = setup.structure.length_mm
    dmax = setup.travel_mm(displacement_mm)   # the one travel check (joint_stiffness too)
    if isinstance(cycles, bool) or not isinstance(cycles, int) or not 0 <= cycles <= 100:
        raise InputError(f"cycles must be an integer in [0, 100], got {cycles!r}",
                         param="cycles")
    sec = section_pullout(setup, pressure_mpa, squeeze_result=squeeze_result,
                          squeeze_index=squeeze_index)
    if section:
        return sec
    num, ea, ms = setup.numerics, float(setup.cable_ea_n), setup.friction[3]
    path = _first_loading(sec, L, ea, dmax, num.n_path) if first_loading else None
    return _length_from_section(sec, L, ea, setup.static_ratio, dmax, int(cycles),
                                num.n_z, num.n_path, num.line_stick_rel, ms, path)


def _first_loading(sec: SectionPullout, L: float, ea: float, dmax: float, n: int) -> np.ndarray:
    """The first leg 0 -> dmax (mm) with ``n`` steps up to past the estimated breakaway.

    The breakaway comes near the section's full-slip displacement plus the cable's stretch
    under the whole-length sliding force (L q_slide L / (2 EA)); K(P) is read on that branch,
    so the steps resolve it wherever it lies in [0, dmax]; ``n // 4`` steps cover the rest.
    """
    ds = sec.slip_displacement_mm if math.isfinite(sec.slip_displacement_mm) else dmax
    d_b = min(dmax, 1.5 * ds + sec.sliding_force_n_per_mm * L * L / (2.0 * ea))
    head = np.linspace(0.0, d_b, n + 1)
    if d_b >= dmax:
        return head
    return np.concatenate([head, np.linspace(d_b, dmax, max(n // 4, 2) + 1)[1:]])


def _length_from_section(sec: SectionPullout, L: float, ea: float, ratio: float, dmax: float,
                         cycles: int, n_z: int, n_path: int, line_rel: float,
                         ms: float, path: np.ndarray | None = None) -> PulloutResult:
    """The pull along the length: the cable on the section law, and with ``ends='fixed'`` the
    zones next to the held end faces on their own law (section 12, "Tube ends")."""
    line_cap = sec.mu_wire_wall * sec.squeeze_force_n_per_mm
    k0 = sec.initial_stiffness_n_per_mm2
    law = _iwan(sec.displacement_mm, sec.tube_force_n_per_mm, line_cap,
                line_rel * max(k0, 1e-12))
    if path is None:
        path = _path(dmax, cycles, n_path)
    notes = list(sec.notes)
    if law.k.size == 0:
        return PulloutResult(path, np.zeros_like(path), 0.0, 0.0, np.zeros_like(path), L, ea,
                             ms, sec, tuple(notes))
    if sec.ends == "fixed" and sec.held_ends is not None:
        law = _held_zones(sec, law, (L, float(np.abs(path).max())), (n_z, n_path),
                          (line_cap, line_rel * max(k0, 1e-12)))
        vector = sec.held_ends.vector is not None
        if sec.max_stretch >= (defaults.PULLOUT_HELD_STRETCH_NOTE if vector
                               else defaults.PULLOUT_HELD_STRETCH_NOTE_SCALAR):
            notes.append(held_stretch_note(sec.max_stretch, L, vector))
    forces, us, full = _shear_lag(law, ea, L, path, ratio, n_z)
    z = np.linspace(0.0, L, n_z + 1)
    slip_len = np.array([float(z[f].max()) + L / n_z / 2 if np.any(f) else 0.0 for f in full])
    slip_len = np.minimum(slip_len, L)
    first = slice(0, int(np.argmax(path)) + 1)
    return PulloutResult(path, forces, float(np.max(forces[first])),
                         float(L * sec.sliding_force_n_per_mm), slip_len, L, ea, ms, sec,
                         tuple(notes))


#: the start of :func:`held_stretch_note` (``joint_stiffness`` merges these notes)
HELD_STRETCH_NOTE = "held end zones too stiff"


def held_stretch_note(stretch: float, length_mm: float, vector: bool = True) -> str:
    """The note of a pull with held ends from an inflated state stretched by ``stretch``
    (largest in-plane principal stretch, unitless) on a tube of ``length_mm`` (mm), with the
    vector held zone (``vector``) or the scalar one.

    Examples
    --------
    >>> held_stretch_note(1.76, 116.0).split(":")[0]
    'held end zones too stiff'
    """
    zone = min(defaults.PULLOUT_HELD_ZONE_MM, 0.5 * length_mm)
    if vector:
        what = ("against CalculiX, 5-10 mm held tubes squeezed to a stretch of 1.76 came out "
                "2-5 % too stiff at 0.3-0.4 of their sliding force (2.3-2.8 % on 5 mm tubes, "
                "5.0 % on a 10 mm one; at 0.5-0.7 of it within 3.6 %, and at stretches up to "
                "1.47 within 3 %; sliding force within 0.6 %)")
    else:
        what = ("the scalar end-zone model does not see the inflation's in-plane stretch; "
                "against CalculiX, 5-10 mm held tubes stretched 1.47-1.76 came out 4-6 % too "
                "stiff before they slide (sliding force within 0.6 %)")
    return (f"{HELD_STRETCH_NOTE}: {what}; largest stretch {stretch:.2f} here; it applies to "
            f"the stiffness of the {zone:g} mm next to each held end face "
            "(docs/formulation.md section 12)")


def _held_zones(sec: SectionPullout, law: _Iwan, lengths: tuple[float, float],
                counts: tuple[int, int], line: tuple[float, float]) -> _Iwan:
    """The section law with the held end zones' law on the stations within
    :data:`~exofric.defaults.PULLOUT_HELD_ZONE_MM` of either end (weights by the share of each
    station's tributary length in a zone).

    Each zone is the 3-D scalar problem of :mod:`exofric.simulate._shear_lag` (held face,
    symmetry face at the zone's end; a tube of at most 2 zone lengths is two zones of half
    its length), its force per unit length an Iwan law like the section's; the held faces'
    end rows (sliding at once) join the line contact's rigid-plastic element. ``lengths``:
    the tube's length and the path's largest displacement (mm); ``counts``: n_z, n_path.
    """
    held = sec.held_ends
    if held is None:
        return law
    L, top = lengths
    n, n_path = counts
    # a tube of at most two zones: half of it, held face to the (symmetric) middle
    zone, grid = defaults.PULLOUT_HELD_ZONE_MM, defaults.PULLOUT_HELD_GRID_MM
    short = L <= 2.0 * zone
    lz = 0.5 * L if short else zone
    # the zone's law on a fixed grid (smooth in the coefficients, the same points whatever
    # the travel), quadratic (fine where the law bends most) to the grid's end in n_path / 2
    # steps, continued to the travel: force at 0.2 mm 0.35 % below 121 points; 61: 0.01 %
    m = min(max(n_path // 2, 12), 40)
    k = np.arange(int(np.ceil(m * math.sqrt(max(top, 1e-9) / grid))) + 1)
    deltas = grid * (k / m) ** 2
    f, end = zone_curve(held, lz, (True, False), deltas)
    zlaw = _iwan(deltas, (f - np.where(deltas > 0, end, 0.0)) / lz, line[0] + end / lz,
                 line[1])
    z = np.linspace(0.0, L, n + 1)
    a, b = np.clip(z - 0.5 * L / n, 0.0, L), np.clip(z + 0.5 * L / n, 0.0, L)
    inside = (np.clip(np.minimum(b, lz) - a, 0.0, None)
              + np.clip(b - np.maximum(a, L - lz), 0.0, None))
    frac = np.ones(n + 1) if short else np.clip(inside / (b - a), 0.0, 1.0)
    ones = np.ones(len(law.k))
    weight = np.hstack([np.outer(1.0 - frac, ones), np.outer(frac, np.ones(len(zlaw.k)))])
    tube = np.r_[np.arange(len(law.k)) < law.n_tube, np.arange(len(zlaw.k)) < zlaw.n_tube]
    spring = (1.0 - frac) * law.spring + frac * zlaw.spring
    return _Iwan(np.r_[law.k, zlaw.k], np.r_[law.f, zlaw.f], spring, law.n_tube + zlaw.n_tube,
                 weight, tube)
