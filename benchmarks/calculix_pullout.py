"""CalculiX (``ccx``) 3-D models of the wire pulled through the inflated tube (issue 39).

Independent of exofric: nothing of exofric is imported; the meshes, the contact and the
friction are CalculiX's. ``bench_pullout_ccx.py`` runs the cases and the convergence studies;
``tests/test_pullout_reference.py`` compares exofric with the stored results.

Model (units mm, N, MPa, s; half model x >= 0)
----------------------------------------------
* Tube: 20-node bricks (``C3D20R`` by default) extruded along z from the structured polar
  8-node quad mesh of ``calculix_models.polar_quad8`` (every node on its circle, angles graded
  toward the wire), ``*HYPERELASTIC, MOONEY-RIVLIN`` (C10, C01, D1 = exofric's d), NLGEOM.
* Hole and wire: rigid, as one extruded layer of elements whose nodes are all prescribed
  (``*BOUNDARY``): the hole immobile, the wire immobile in x, y and moved along z by the pull
  delta in step 2. The summed nodal reactions of a rigid part are its contact forces. The
  wire reaches ``delta_max + margin`` beyond the tube on the side it comes from, so no tube
  node loses its master face during the pull. Node-to-surface penalty contact (linear
  pressure-overclosure), slave = the tube's outer surface, one interaction per pair
  (``SIWALL``, ``SIWIRE``) with ``*FRICTION`` (mu, stick slope).
* Step 1 (inflation): the bore pressure ``*DLOAD`` (face S6; a follower load in an NLGEOM
  step) ramped 0 -> P; the friction coefficient is ``MU_INFLATION`` (1e-6: effectively
  frictionless; CalculiX only lets a step change a friction that exists from the start), so
  the squeeze is exofric's frictionless plane-strain squeeze; the tube's axial rigid motion is
  held (slice: u_z = 0 on the front face; tube: u_z = 0 at both ends anyway).
* Step 2 (pull): ``*CHANGE FRICTION`` to mu_wire / mu_wall, the pressure held (the ``*DLOAD``
  stays), the wire moved along +z by delta = step time (0 -> delta_max), outputs at
  ``*TIME POINTS``: the z-reaction of the wire's nodes (the pull force) and of the hole's, the
  radial parts of the wire's and wall's nodal reactions (the normal-force integrals S_wire,
  S_wall: how much the pull changes the contact pressures, the reduced model's neglected
  reverse coupling), all x 2 for the full section.
* Kinds (:func:`pullout_deck`):

  - ``"slice"``: thickness ``thickness_mm`` (``n_z`` elements), periodic along z: every node of
    the back face is tied to its front-face partner for all three components by
    ``*EQUATION`` (back face dependent), except the components already prescribed on both
    (u_x on the symmetry plane, u_y on the bottom line). The tube's state is then z-uniform
    (the problem is invariant along z, quadratic bricks represent it exactly), i.e. the
    generalised plane strain + anti-plane kinematics of a section far from the ends, with
    the full nonlinear coupling. Its pull force per mm = 2 x R_z / thickness.
  - ``"tube"``: length ``length_mm`` (``n_z`` elements graded toward both ends), the end
    fittings hold the tube axially: u_z = 0 on both end faces, in-plane free (the fitting
    lets the section deform as inside; the plane-strain squeeze is then the exact inflated
    state); the wire (rigid, i.e. an infinitely stiff cable) pulled through it. Pull force
    F = 2 x R_z (N). ``ends="free"``: the end faces are free (only the front face's u_z held
    in step 1).

  Element proportions matter: a 30 mm tube with 8 or 10 graded elements of 2-6 mm along z
  (in-plane 0.1-0.25 mm at the wire: aspect ratios 10-40) stalled in the inflation (the
  node-to-surface contact set chattering between ~50 and ~200 elements, increments cut to
  1e-6, "increment size smaller than minimum"), with the rigid faces 0.5 mm long as well; a
  1 mm tube with two elements converged like the slice, and so did 5 mm tubes with 0.25-1 mm
  elements. A 30 mm tube with 20 elements graded from 0.68 mm (held faces) to 2.7 mm stalled
  the same way past 0.65 P. ``bench_pullout_ccx.py`` therefore uses elements of at most 1 mm
  along z and short tubes (5 and 10 mm).
* The pull's first increment is 1e-5 mm: with ~1e-3 mm ccx 2.20 lost the contact on the
  2 x 20 and 3 x 30 meshes (residual ~1e3 N, the contact elements doubling then vanishing).
* Bottom line: the tube's outer nodes at -90 deg (on the symmetry line, pressed on the wall)
  get u_y = 0 (as the plane-strain decks: removes the weightless tube's vertical motion
  before it touches the wire; frictionless in-plane contact at that line).

Example
-------
>>> d = pullout_deck((10.0, 8.3, 4.97, 1.6), (0.635, 0.0318, 0.006), 0.4, 0.3, 0.5,
...                  n_radial=1, n_circ=8, rigid_elements=8, delta_max_mm=0.5)
>>> "*CHANGE FRICTION" in d.text and "*EQUATION" in d.text
True
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import calculix_models as ccxm  # noqa: E402

__all__ = ["CcxPullout", "PulloutDeck", "ccx_pullout", "pullout_deck", "read_pullout"]

#: friction coefficient during the inflation step (CalculiX rejects mu = 0 in *FRICTION and
#: only changes a friction that exists from the first step): effectively frictionless
MU_INFLATION = 1e-6
STICK_SLOPE = 1.0e3   # MPa/mm, as calculix_models.STICK_SLOPE
PENALTY = 1.0e4       # MPa/mm, normal penalty
FIRST_INCREMENT_MM = 1e-5  # first increment of the pull (mm)


@dataclass(frozen=True)
class PulloutDeck:
    """A 3-D pull-out deck and what is needed to read it.

    Attributes
    ----------
    text : str
        The ``.inp`` text.
    kind : str
        ``"slice"`` or ``"tube"``.
    depth_mm : float
        Slice thickness or tube length (mm).
    deltas_mm : ndarray
        Output wire displacements of step 2 (mm).
    wire_center, hole_center : (float, float)
        Centres of the rigid circles (mm).
    rigid_xy : dict
        ``"wire"``/``"hole"`` -> {node: (x, y)} (mm).
    mesh : dict
        Mesh and contact description.
    nodes : int
        Nodes of the model.
    """

    text: str
    kind: str
    depth_mm: float
    deltas_mm: np.ndarray
    wire_center: tuple[float, float]
    hole_center: tuple[float, float]
    rigid_xy: dict[str, dict[int, tuple[float, float]]]
    mesh: dict[str, Any]
    nodes: int


# ---------------------------------------------------------------------------- extrusion
def _corners(grid: np.ndarray) -> set[int]:
    return {int(grid[i, j]) for i in range(0, grid.shape[0], 2)
            for j in range(0, grid.shape[1], 2) if grid[i, j]}


def _extrude(nodes2: dict[int, tuple[float, float]], elems2: dict[int, list[int]],
             corners: set[int], zb: np.ndarray, offset: int, first_element: int
             ) -> tuple[dict[int, tuple[float, float, float]], dict[int, list[int]], int]:
    """C3D20 bricks from quad8s over the z boundaries ``zb``; node id = level x offset + id.

    Levels 0, 2, ..., 2 n_z are the element boundaries (all quad8 nodes), the odd ones the
    mid-planes (corner nodes only). Returns (nodes, elements, offset).
    """
    zl = np.empty(2 * len(zb) - 1)
    zl[0::2] = zb
    zl[1::2] = 0.5 * (zb[1:] + zb[:-1])
    nodes: dict[int, tuple[float, float, float]] = {}
    for lev, z in enumerate(zl):
        for n, (x, y) in nodes2.items():
            if lev % 2 == 0 or n in corners:
                nodes[lev * offset + n] = (x, y, float(z))
    elems: dict[int, list[int]] = {}
    e = first_element
    for k in range(len(zb) - 1):
        l0, lm, l1 = 2 * k * offset, (2 * k + 1) * offset, (2 * k + 2) * offset
        for _, c in sorted(elems2.items()):
            elems[e] = ([l0 + v for v in c[:4]] + [l1 + v for v in c[:4]]
                        + [l0 + v for v in c[4:]] + [l1 + v for v in c[4:]]
                        + [lm + v for v in c[:4]])
            e += 1
    return nodes, elems, offset


def _graded(length: float, n: int, ratio: float, growth: float | None = None) -> np.ndarray:
    """n elements over [0, length], smallest at both ends, largest/smallest = ratio.

    Without ``growth`` the sizes grow geometrically from each end to the middle; with it they
    grow by ``growth`` per element from each end until they reach ``ratio`` x the smallest,
    then stay at that size (a uniform middle: long tubes keep their largest elements at an
    aspect ratio the contact tolerates). Element boundaries (mm)."""
    if n < 2 or ratio == 1.0:
        return np.linspace(0.0, length, n + 1)
    h = n // 2
    if growth is None:
        q = ratio ** (1.0 / max(h - 1, 1))
        half = q ** np.arange(h)
    else:
        if not growth > 1.0:
            raise ValueError(f"z growth must be > 1, got {growth}")
        half = np.minimum(growth ** np.arange(h), ratio)
    sizes = np.concatenate([half, [half[-1]] if n % 2 else [], half[::-1]])
    return np.concatenate([[0.0], np.cumsum(sizes)]) / sizes.sum() * length


def _fmt3(nodes: dict[int, tuple[float, float, float]]) -> str:
    return "".join(f"{k}, {x:.12g}, {y:.12g}, {z:.12g}\n" for k, (x, y, z) in nodes.items())


def _fmt_elems(elems: dict[int, list[int]]) -> str:
    # C3D20: 20 node numbers, at most 16 per line
    out = []
    for k, c in elems.items():
        out.append(f"{k}, " + ", ".join(str(v) for v in c[:15]) + ",\n"
                   + ", ".join(str(v) for v in c[15:]) + "\n")
    return "".join(out)


def _time_points(delta_max: float, n_out: int) -> np.ndarray:
    """Output displacements: geometric from delta_max / 2000 (initial stiffness), then even."""
    small = delta_max * np.array([5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2])
    even = np.linspace(0.0, delta_max, n_out + 1)[1:]
    return np.unique(np.round(np.concatenate([small, even]), 12))


# -------------------------------------------------------------------------------- deck
def pullout_deck(
    structure: tuple[float, float, float, float],
    material: Any,
    pressure_mpa: float,
    mu_wire: float,
    mu_wall: float,
    *,
    kind: str = "slice",
    depth_mm: float = 1.0,
    n_z: int = 2,
    z_grading: float = 1.0,
    z_growth: float | None = None,
    ends: str = "fixed",
    n_radial: int = 2,
    n_circ: int = 30,
    grading: float = 10.0,
    rigid_elements: int = 32,
    element: str = "C3D20R",
    penalty: float = PENALTY,
    stick_slope: float = STICK_SLOPE,
    delta_max_mm: float = 2.0,
    n_out: int = 40,
    max_increment_mm: float = 0.02,
    max_increment_inflation: float = 0.05,
    contact: str = "NODE TO SURFACE",
    rigid_dz_mm: float | None = None,
) -> PulloutDeck:
    """Deck of the 3-D pull-out (module docstring): inflation, then the wire pulled along z.

    Parameters
    ----------
    structure : (hole_mm, tube_od_mm, tube_id_mm, wire_mm)
        Diameters (mm).
    material : object with ``c10_mpa, c01_mpa, d_per_mpa`` or (c10, c01, d)
        Mooney-Rivlin constants (MPa, MPa, 1/MPa).
    pressure_mpa : float
        Bore pressure (MPa), held during the pull.
    mu_wire, mu_wall : float
        Coulomb coefficients tube-wire and tube-hole in the pull (> 0).
    kind : {"slice", "tube"}
        Periodic slice or a tube of length ``depth_mm`` held at its ends.
    depth_mm, n_z, z_grading : float, int, float
        Slice thickness / tube length (mm), elements along z, largest / smallest element
        length along z (tube: smallest at both ends).
    z_growth : float, optional
        Tube only: sizes grow by this factor per element from each end up to ``z_grading`` x
        the smallest, a uniform middle beyond (default: geometric to the middle).
    ends : {"fixed", "free"}
        Tube only: end faces u_z = 0 (end fittings) or free.
    n_radial, n_circ, grading : int, int, float
        Tube elements through the wall and over the half circumference; largest (wall) /
        smallest (wire) element angle.
    rigid_elements : int
        Elements over the half circles of hole and wire.
    element : str
        ``C3D20R`` or ``C3D20`` (ccx 2.20 has no hybrid ``C3D20H``).
    penalty, stick_slope : float
        Normal penalty and friction stick slope (MPa/mm).
    delta_max_mm, n_out : float, int
        Pull travel (mm) and the number of evenly spaced outputs (plus small ones near 0).
    max_increment_mm, max_increment_inflation : float
        Largest increment of the pull (mm) and of the inflation (fraction of P).
    contact : str
        ``NODE TO SURFACE`` or ``SURFACE TO SURFACE``.
    rigid_dz_mm : float, optional
        Length along z of the rigid layers' elements (their master faces; default the tube's
        largest element length, at least 0.25 mm).

    Returns
    -------
    PulloutDeck
    """
    if kind not in ("slice", "tube"):
        raise ValueError(f"kind must be 'slice' or 'tube', got {kind!r}")
    if ends not in ("fixed", "free"):
        raise ValueError(f"ends must be 'fixed' or 'free', got {ends!r}")
    if not (mu_wire > 0 and mu_wall > 0):
        raise ValueError("mu_wire and mu_wall must be > 0")
    c10, c01, d = ccxm._constants(material)
    hole, od, idm, wire = (float(v) for v in structure)
    a, b = 0.5 * idm, 0.5 * od
    yc = -(0.5 * hole - b)
    half = 0.5 * math.pi
    t2, e2, g2 = ccxm.polar_quad8(a, b, n_radial, n_circ, -half, half, grading=grading,
                                  center=(0.0, yc))
    for k in np.concatenate([g2[:, 0], g2[:, -1]]):
        if k:
            t2[k] = (0.0, t2[k][1])
    rh, rw = 0.5 * hole, 0.5 * wire
    wc = (0.0, 0.5 * hole - rw)
    h2, he2, hg2 = ccxm.polar_quad8(rh, rh * 1.1, 1, rigid_elements, -half, half,
                                    first_node=max(t2) + 1, first_element=1)
    w2, we2, wg2 = ccxm.polar_quad8(0.5 * rw, rw, 1, rigid_elements, -half, half, center=wc,
                                    first_node=max(h2) + 1, first_element=1)
    offset = 10 ** (len(str(max(w2))) + 0)
    L = float(depth_mm)
    zb = (_graded(L, int(n_z), z_grading, z_growth) if kind == "tube"
          else np.linspace(0.0, L, n_z + 1))
    tn, te, _ = _extrude(t2, e2, _corners(g2), zb, offset, 1)
    # rigid parts: z boundaries over [-(delta_max + margin), L + margin], about the tube's
    # element length
    margin = max(0.5, 0.1 * L)
    z0, z1 = -(delta_max_mm + margin), L + margin
    dz_r = float(rigid_dz_mm) if rigid_dz_mm else max(float(np.diff(zb).max()), 0.25)
    zr = np.linspace(z0, z1, max(2, int(math.ceil((z1 - z0) / dz_r))) + 1)
    zh = np.linspace(-margin, z1, max(2, int(math.ceil((z1 + margin) / dz_r))) + 1)
    hn, he, _ = _extrude(h2, he2, _corners(hg2), zh, offset, max(te) + 1)
    wn, we, _ = _extrude(w2, we2, _corners(wg2), zr, offset, max(he) + 1)
    n_lev_t = 2 * len(zb) - 1
    front = {n for n in tn if n < offset}
    back = {n for n in tn if n // offset == n_lev_t - 1}
    sym2 = {int(k) for k in np.concatenate([g2[:, 0], g2[:, -1]]) if k}
    sym = sorted(n for n in tn if n % offset in sym2)
    bottom2 = int(g2[-1, 0])
    bottom = sorted(n for n in tn if n % offset == bottom2)
    inner2 = {int(k) for k in g2[0] if k}
    outer2 = {int(k) for k in g2[-1] if k}
    inner_e = [e for e, c in te.items() if c[0] % offset in inner2]
    outer_e = [e for e, c in te.items() if c[1] % offset in outer2]
    text = ["** exofric benchmark: 3-D wire pull-out, half model x >= 0 (mm, N, MPa)\n",
            "*NODE, NSET=NALL\n", _fmt3(tn), _fmt3(hn), _fmt3(wn),
            f"*ELEMENT, TYPE={element}, ELSET=TUBE\n", _fmt_elems(te),
            f"*ELEMENT, TYPE={element}, ELSET=HOLE\n", _fmt_elems(he),
            f"*ELEMENT, TYPE={element}, ELSET=WIRE\n", _fmt_elems(we),
            "*NSET, NSET=NSYM\n", ccxm._fmt_set(sym),
            "*NSET, NSET=NBOTTOM\n", ccxm._fmt_set(bottom),
            "*NSET, NSET=NHOLE\n", ccxm._fmt_set(sorted(hn)),
            "*NSET, NSET=NWIRE\n", ccxm._fmt_set(sorted(wn)),
            "*NSET, NSET=NFRONT\n", ccxm._fmt_set(sorted(front)),
            "*NSET, NSET=NBACK\n", ccxm._fmt_set(sorted(back))]
    if kind == "slice":
        text.append(_periodic(back, offset * (n_lev_t - 1), set(sym), set(bottom)))
    text += [f"*MATERIAL, NAME=SILICONE\n*HYPERELASTIC, MOONEY-RIVLIN\n"
             f"{c10:.12g}, {c01:.12g}, {d:.12g}\n"
             "*SOLID SECTION, ELSET=TUBE, MATERIAL=SILICONE\n",
             "*MATERIAL, NAME=RIGID\n*ELASTIC\n2.0e5, 0.3\n"
             "*SOLID SECTION, ELSET=HOLE, MATERIAL=RIGID\n"
             "*SOLID SECTION, ELSET=WIRE, MATERIAL=RIGID\n",
             "*SURFACE, NAME=STUBE, TYPE=ELEMENT\n", "".join(f"{e}, S4\n" for e in outer_e),
             "*SURFACE, NAME=SHOLE, TYPE=ELEMENT\n", "".join(f"{e}, S6\n" for e in he),
             "*SURFACE, NAME=SWIRE, TYPE=ELEMENT\n", "".join(f"{e}, S4\n" for e in we)]
    for name, pair in (("SIWALL", "SHOLE"), ("SIWIRE", "SWIRE")):
        text.append(f"*SURFACE INTERACTION, NAME={name}\n"
                    f"*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{penalty:.6g}\n"
                    f"*FRICTION\n{MU_INFLATION:.6g}, {stick_slope:.6g}\n"
                    f"*CONTACT PAIR, INTERACTION={name}, TYPE={contact}\nSTUBE, {pair}\n")
    held_z = "NEND" if (kind == "tube" and ends == "fixed") else None
    if kind == "tube":
        ends_set = sorted(front | back)
        text += ["*NSET, NSET=NEND\n", ccxm._fmt_set(ends_set)]
    deltas = _time_points(delta_max_mm, n_out)
    text.append(_steps(deltas, held_z, inner_e, pressure_mpa, (mu_wire, mu_wall, stick_slope),
                       delta_max_mm, max_increment_mm, max_increment_inflation))
    mesh = {"kind": kind, "element": element, "n_radial": n_radial, "n_circ": n_circ,
            "grading": grading, "n_z": n_z, "z_grading": z_grading, "depth_mm": L,
            "z_growth": z_growth, "z_boundaries_mm": [float(v) for v in zb],
            "rigid_elements": rigid_elements, "penalty_mpa_per_mm": penalty,
            "stick_slope_mpa_per_mm": stick_slope, "contact": contact,
            "delta_max_mm": delta_max_mm, "max_increment_mm": max_increment_mm,
            "max_increment_inflation": max_increment_inflation,
            "mu_inflation": MU_INFLATION, "ends": ends if kind == "tube" else "periodic",
            "rigid_dz_mm": dz_r}
    rigid = {"wire": {k: v[:2] for k, v in wn.items()},
             "hole": {k: v[:2] for k, v in hn.items()}}
    return PulloutDeck("".join(text), kind, L, deltas, wc, (0.0, 0.0), rigid, mesh,
                       len(tn) + len(hn) + len(wn))


def _steps(deltas: np.ndarray, held_z: str | None, inner_e: list[int], pressure_mpa: float,
           friction: tuple[float, float, float], delta_max_mm: float, max_increment_mm: float,
           max_increment_inflation: float) -> str:
    """Output time points, step 1 (inflation) and step 2 (pull) of :func:`pullout_deck`;
    ``friction`` = (mu_wire, mu_wall, stick slope)."""
    mu_wire, mu_wall, stick_slope = friction
    tp = "".join(f"{v:.12g},\n" for v in deltas)
    fixed = "NSYM, 1, 1\nNBOTTOM, 2, 2\nNHOLE, 1, 3\nNWIRE, 1, 2\n"
    step1 = ("*STEP, NLGEOM, INC=10000\n*STATIC\n"
             f"{max_increment_inflation:.6g}, 1.0, 1e-6, {max_increment_inflation:.6g}\n"
             "*BOUNDARY\n" + fixed + "NWIRE, 3, 3\n"
             + ("NFRONT, 3, 3\n" if held_z is None else f"{held_z}, 3, 3\n")
             + "*DLOAD\n" + "".join(f"{e}, P6, {pressure_mpa:.10g}\n" for e in inner_e)
             + "*NODE PRINT, NSET=NWIRE, TOTALS=ONLY, TIME POINTS=INF\nRF\n"
             + "*NODE PRINT, NSET=NWIRE, TIME POINTS=INF\nRF\n"
             + "*NODE PRINT, NSET=NHOLE, TIME POINTS=INF\nRF\n"
             + "*NODE PRINT, NSET=NBOTTOM, TIME POINTS=INF\nRF\n*END STEP\n")
    # a small first increment: a first increment of ~1e-3 mm made ccx 2.20 lose the contact
    # (residual ~1e3 N, the contact elements doubling then vanishing) on the 2 x 20 and
    # 3 x 30 meshes; from 1e-5 mm the automatic incrementation grows it without trouble
    first = min(max_increment_mm, deltas[0], FIRST_INCREMENT_MM)
    step2 = ("*STEP, NLGEOM, INC=100000\n*STATIC\n"
             f"{first:.6g}, {delta_max_mm:.10g}, {min(1e-6 * delta_max_mm, 0.1 * first):.3g}, "
             f"{max_increment_mm:.6g}\n"
             f"*CHANGE FRICTION, INTERACTION=SIWALL\n*FRICTION\n{mu_wall:.6g}, "
             f"{stick_slope:.6g}\n"
             f"*CHANGE FRICTION, INTERACTION=SIWIRE\n*FRICTION\n{mu_wire:.6g}, "
             f"{stick_slope:.6g}\n"
             "*BOUNDARY, OP=NEW\n" + fixed + f"NWIRE, 3, 3, {delta_max_mm:.10g}\n"
             + (f"{held_z}, 3, 3\n" if held_z else "")
             + "*NODE PRINT, NSET=NWIRE, TOTALS=ONLY, TIME POINTS=OUT\nRF\n"
             + "*NODE PRINT, NSET=NHOLE, TOTALS=ONLY, TIME POINTS=OUT\nRF\n"
             + "*NODE PRINT, NSET=NWIRE, TIME POINTS=OUT\nRF\n"
             + "*NODE PRINT, NSET=NHOLE, TIME POINTS=OUT\nRF\n"
             + "*NODE PRINT, NSET=NBOTTOM, TIME POINTS=OUT\nRF\n*END STEP\n")
    return f"*TIME POINTS, NAME=INF\n1.0,\n*TIME POINTS, NAME=OUT\n{tp}" + step1 + step2


def _periodic(back: set[int], shift: int, sym: set[int], bottom: set[int]) -> str:
    """``*EQUATION``: back-face node (dependent) = front-face partner, per component,
    except the components prescribed on both (u_x on the symmetry plane, u_y on the bottom
    line)."""
    rows = []
    for n in sorted(back):
        f = n - shift
        for dof in (1, 2, 3):
            if (dof == 1 and n in sym) or (dof == 2 and n in bottom):
                continue
            rows.append(f"2\n{n}, {dof}, 1.0, {f}, {dof}, -1.0\n")
    return "*EQUATION\n" + "".join(rows)


# ----------------------------------------------------------------------------- results
@dataclass(frozen=True)
class CcxPullout:
    """3-D pull-out results (full section: 2 x the half model).

    Attributes
    ----------
    delta_mm : ndarray
        Wire displacement (mm) of the outputs.
    force_n : ndarray
        Pull force on the wire (N): the slice's per its thickness, the tube's total.
    force_per_mm : ndarray
        Force per mm of tube (N/mm): force_n / depth.
    wall_force_n : ndarray
        Axial force of the hole wall on the tube (N).
    wire_normal_n_per_mm, wall_normal_n_per_mm : ndarray
        Normal-force integrals S_wire, S_wall per mm (N/mm) at each output.
    inflated_wire_normal_n_per_mm, inflated_wall_normal_n_per_mm : float
        S_wire, S_wall at the end of the inflation (N/mm).
    squeeze_force_n_per_mm : float
        y-force of the tube on the wire at the end of the inflation (N/mm).
    run : dict
        Times, equations, incrementation.
    mesh : dict
    """

    delta_mm: np.ndarray
    force_n: np.ndarray
    force_per_mm: np.ndarray
    wall_force_n: np.ndarray
    wire_normal_n_per_mm: np.ndarray
    wall_normal_n_per_mm: np.ndarray
    inflated_wire_normal_n_per_mm: float
    inflated_wall_normal_n_per_mm: float
    squeeze_force_n_per_mm: float
    run: dict[str, Any] = field(default_factory=dict)
    mesh: dict[str, Any] = field(default_factory=dict)


def _normal(rows: dict[int | str, np.ndarray], xy: dict[int, tuple[float, float]],
            center: tuple[float, float], sign: float) -> float:
    ids = [k for k in xy if k in rows]
    er = np.array([xy[k] for k in ids]) - np.asarray(center)
    er /= np.linalg.norm(er, axis=1)[:, None]
    f = np.array([rows[k][:2] for k in ids])
    return float(2.0 * sign * np.einsum("nj,nj->", f, er))


def read_pullout(deck: PulloutDeck, run: ccxm.CcxRun) -> CcxPullout:
    """Forces and normal integrals from a run of :func:`pullout_deck`."""
    if run.returncode != 0 or not run.dat:
        tail = "\n".join(run.stdout.strip().splitlines()[-12:])
        raise RuntimeError(f"CalculiX failed (exit {run.returncode}):\n{tail}")
    tab = ccxm.parse_dat(run.dat)
    times = sorted({t for (q, s, t) in tab if q == "total force" and s == "NWIRE"})
    # step 1 writes its last increment at total time 1.0; step 2's step times are deltas
    # (CalculiX prints the total time: 1 + delta)
    t_inf = 1.0
    if t_inf not in times:
        raise RuntimeError("CalculiX wrote no inflation result")
    depth = deck.depth_mm
    bottom1 = tab[("forces", "NBOTTOM", t_inf)]
    s_wire0 = _normal(tab[("forces", "NWIRE", t_inf)], deck.rigid_xy["wire"],
                      deck.wire_center, 1.0) / depth
    s_wall0 = (_normal(tab[("forces", "NHOLE", t_inf)], deck.rigid_xy["hole"],
                       deck.hole_center, -1.0)
               + 2.0 * sum(float(v[1]) for v in bottom1.values())) / depth
    n0 = -2.0 * float(tab[("total force", "NWIRE", t_inf)]["total"][1]) / depth
    out_d, f, fw, sw, sh = [], [], [], [], []
    for d in deck.deltas_mm:
        t = 1.0 + float(d)
        k = min(times, key=lambda v: abs(v - t))
        # the .dat prints times with 7 significant digits (1e-6 at total times 1-3)
        if abs(k - t) > 2e-6 * max(1.0, t):
            break
        out_d.append(float(d))
        f.append(2.0 * float(tab[("total force", "NWIRE", k)]["total"][2]))
        fw.append(-2.0 * float(tab[("total force", "NHOLE", k)]["total"][2]))
        sw.append(_normal(tab[("forces", "NWIRE", k)], deck.rigid_xy["wire"],
                          deck.wire_center, 1.0) / depth)
        b = tab[("forces", "NBOTTOM", k)]
        sh.append((_normal(tab[("forces", "NHOLE", k)], deck.rigid_xy["hole"],
                           deck.hole_center, -1.0)
                   + 2.0 * sum(float(v[1]) for v in b.values())) / depth)
    if len(out_d) < len(deck.deltas_mm):
        raise RuntimeError(f"CalculiX stopped before delta = {deck.deltas_mm[len(out_d)]:g} "
                           f"mm (last output at {out_d[-1] if out_d else 0.0:g} mm)")
    fa = np.array(f)
    info = {"wall_time_s": run.wall_time_s, "cpu_time_s": run.cpu_time_s,
            "equations": run.equations, "incrementation": ccxm.increments(run.sta)}
    return CcxPullout(np.array(out_d), fa, fa / depth, np.array(fw), np.array(sw),
                      np.array(sh), s_wire0, s_wall0, n0, info, deck.mesh)


def ccx_pullout(structure: tuple[float, float, float, float], material: Any,
                pressure_mpa: float, mu_wire: float, mu_wall: float, *, ccx: str = "ccx",
                workdir: str | Path | None = None, timeout_s: float = 3600.0,
                **options: Any) -> CcxPullout:
    """Write, run and read one 3-D pull-out (see :func:`pullout_deck`)."""
    deck = pullout_deck(structure, material, pressure_mpa, mu_wire, mu_wall, **options)
    return read_pullout(deck, ccxm.run_ccx(deck.text, workdir, ccx=ccx, timeout_s=timeout_s))
