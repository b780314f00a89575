"""CalculiX (``ccx``) models of exofric's two FE problems: deck writers, runner, result parser.

Used by ``bench_peers.py`` as a third, independent code next to exofric and FElupe. Nothing
of exofric is imported: the meshes are written here, the model is CalculiX's.

Model (units mm, N, MPa, s; plane strain with thickness 1 mm, so forces are per mm depth)
----------------------------------------------------------------------------------------
* Elements: 8-node plane-strain quads ``CPE8R`` (default; ``CPE8`` allowed) on a structured
  polar mesh (every node on its circle); CalculiX expands them internally to one layer of
  20-node bricks. ``*STATIC`` with ``NLGEOM``, automatic incrementation, results at the
  requested pressures through ``*TIME POINTS`` (step time = pressure in MPa).
* Material: ``*HYPERELASTIC, MOONEY-RIVLIN`` with ``C10, C01`` and ``D1`` such that the
  volumetric energy ``(J - 1)^2 / D1`` equals exofric's ``(J - 1)^2 / d`` (``D1 = d = 2/K``).
* Load: internal pressure ``*DLOAD`` on the inner edges (face 4); in a geometrically
  nonlinear step CalculiX applies it on the deformed surface (a follower load).
* Free inflation (:func:`inflate_deck`): quarter tube, ``u_y = 0`` on y = 0, ``u_x = 0`` on
  x = 0. Result: the outer and inner diameters on the x axis.
* Squeeze (:func:`squeeze_deck`): half model x >= 0 (``u_x = 0`` on x = 0), hole (diameter D,
  centre (0, 0)) and wire (d2, centre (0, D/2 - d2/2)) as rigid bodies: one layer of
  elements whose nodes are all fixed (``*BOUNDARY``), i.e. rigid and immobile (for bodies that
  do not move this is what ``*RIGID BODY`` with a fixed reference node gives, and the summed
  nodal reactions are the contact forces), their contact faces meshed finer than the tube's
  edges there. ``*CONTACT PAIR`` (frictionless by default; node to surface, or surface to
  surface; ``PRESSURE-OVERCLOSURE=LINEAR`` penalty; slave = the tube's outer surface). The tube
  (d1, ID) starts touching the wall at the bottom; its bottom outer node on the symmetry
  line gets ``u_y = 0``. That node stays in contact with the wall (the tube only ever
  presses on it), so this is the frictionless wall contact at that point and removes the
  weightless tube's free vertical motion before it touches the wire. Result:
  ``N = 2 x`` the y-reaction on the wire's nodes (full section, N/mm), the wall's reaction
  likewise (rigid hole plus the bottom node), and the horizontal extent 2 max(x) of the
  deformed section.
* Friction (issue 15; ``squeeze_deck(..., mu_wall=, mu_wire=, stick_slope=)``): each contact
  pair gets its own interaction (``SIWALL`` tube-hole, ``SIWIRE`` tube-wire, the same normal
  penalty) with ``*FRICTION`` = ``mu, stick slope`` where mu > 0 (mu = 0 on both writes the
  frictionless deck above unchanged). CalculiX's node-to-surface friction is a tangential
  penalty (stick slope, MPa/mm, times the slave node's area) with a Coulomb return map on
  the slip accumulated over the increments, so the result follows the load path: the
  pressure ramps monotonically from 0, at most ``max_increment_mpa`` per increment. The
  stiffness matrix is then unsymmetric; ccx picks its unsymmetric SPOOLES solver itself.
  The bottom node's ``u_y = 0`` stays valid: by symmetry it does not slip. With
  ``node_forces=True`` :func:`read_squeeze` also splits each rigid circle's nodal
  reactions into normal and tangential contact force integrals. ``bench_friction_ccx.py``
  runs the cases and the convergence studies.

Runner and parser: :func:`run_ccx` writes the deck to a folder, runs ``ccx -i job`` with one
thread (``OMP_NUM_THREADS=1``, ``CCX_NPROC_EQUATION_SOLVER=1``) and returns its wall and CPU
time, the ``.dat`` and ``.sta`` texts and the number of equations; :func:`parse_dat` reads
the ``.dat`` tables (``*NODE PRINT``) by set and time, :func:`increments` summarises the
``.sta`` (increments, cutbacks, increment sizes).

Example
-------
>>> deck = inflate_deck(8.3, 4.97, (0.635, 0.0318, 0.006), [0.1, 0.2], n_radial=2, n_circ=6)
>>> "*HYPERELASTIC, MOONEY-RIVLIN" in deck.text
True
"""

from __future__ import annotations

import os
import re
import resource
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "CcxDeck",
    "CcxRun",
    "CalculixInflation",
    "CalculixSqueeze",
    "ccx_available",
    "ccx_inflate",
    "ccx_squeeze",
    "increments",
    "inflate_deck",
    "parse_dat",
    "polar_quad8",
    "read_inflation",
    "read_squeeze",
    "run_ccx",
    "squeeze_deck",
]

#: Environment that pins CalculiX (and its BLAS/SPOOLES) to one thread.
ONE_THREAD = {"OMP_NUM_THREADS": "1", "CCX_NPROC_EQUATION_SOLVER": "1",
              "CCX_NPROC_RESULTS": "1", "CCX_NPROC_STIFFNESS": "1",
              "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}

_TIME_FMT = "{:.10g}"


def ccx_available(ccx: str = "ccx") -> str | None:
    """Path of the CalculiX executable, or None if it is not on PATH."""
    return shutil.which(ccx)


def _constants(material: Any) -> tuple[float, float, float]:
    """(c10, c01, d) from an object with those attributes or a 3-sequence."""
    if hasattr(material, "c10"):
        return float(material.c10_mpa), float(material.c01_mpa), float(material.d_per_mpa)
    c10, c01, d = material
    return float(c10), float(c01), float(d)


# ------------------------------------------------------------------------------ meshes
def _sizes(n: int, ratio: float) -> np.ndarray:
    """``n`` sizes decreasing geometrically by ``ratio`` (first/last) from first to last."""
    q = ratio ** (1.0 / max(n - 1, 1))
    return q ** np.arange(n)[::-1]


def polar_quad8(
    inner_radius: float,
    outer_radius: float,
    n_radial: int,
    n_circ: int,
    theta0: float,
    theta1: float,
    *,
    grading: float = 1.0,
    center: tuple[float, float] = (0.0, 0.0),
    first_node: int = 1,
    first_element: int = 1,
    n_circ0: int = 0,
    grading0: float = 1.0,
    radial_grading: float = 1.0,
) -> tuple[dict[int, tuple[float, float]], dict[int, list[int]], np.ndarray]:
    """Structured 8-node quad mesh of an annular sector (CalculiX ``CPE8`` node order).

    Element angles shrink geometrically toward ``theta1`` (largest/smallest = ``grading``);
    with ``n_circ0 > 0`` the first ``n_circ0`` elements shrink toward ``theta0`` instead
    (ratio ``grading0``). Every node lies on its circle; mid-nodes at mid-radius/mid-angle.
    ``radial_grading`` > 1: the rings' widths shrink geometrically from the inner to the outer
    radius (largest/smallest); 1 (default): uniform.

    Returns
    -------
    nodes : dict
        Node number -> (x, y) (mm).
    elements : dict
        Element number -> 8 node numbers: corners counter-clockwise (inner-start,
        outer-start, outer-end, inner-end), then the mid-nodes of the edges 1-2, 2-3, 3-4,
        4-1. Face 2 is the outer arc, face 4 the inner arc.
    grid : ndarray of int (2 n_radial + 1, 2 n_circ + 1)
        Node number per (radial line, angular line), 0 where no node (element centres).
    """
    if n_circ0 > 0:
        sizes = np.concatenate([_sizes(n_circ0, grading0)[::-1],
                                _sizes(n_circ - n_circ0, grading)])
    else:
        sizes = _sizes(n_circ, grading)
    tb = theta0 + np.concatenate([[0.0], np.cumsum(sizes)]) / sizes.sum() * (theta1 - theta0)
    if radial_grading == 1.0:
        rb = np.linspace(inner_radius, outer_radius, n_radial + 1)
    else:
        w = _sizes(n_radial, radial_grading)
        rb = inner_radius + np.concatenate([[0.0], np.cumsum(w)]) / w.sum() * (
            outer_radius - inner_radius)
    radii = np.sort(np.concatenate([rb, 0.5 * (rb[1:] + rb[:-1])]))
    angles = np.sort(np.concatenate([tb, 0.5 * (tb[1:] + tb[:-1])]))
    grid = np.zeros((radii.size, angles.size), dtype=int)
    nodes: dict[int, tuple[float, float]] = {}
    n = first_node
    for i, r in enumerate(radii):
        for j, t in enumerate(angles):
            if i % 2 == 1 and j % 2 == 1:
                continue  # element centre: no node in an 8-node quad
            grid[i, j] = n
            nodes[n] = (center[0] + r * np.cos(t), center[1] + r * np.sin(t))
            n += 1
    elements: dict[int, list[int]] = {}
    e = first_element
    for j in range(0, angles.size - 1, 2):
        for i in range(0, radii.size - 1, 2):
            g = grid
            elements[e] = [g[i, j], g[i + 2, j], g[i + 2, j + 2], g[i, j + 2],
                           g[i + 1, j], g[i + 2, j + 1], g[i + 1, j + 2], g[i, j + 1]]
            e += 1
    return nodes, elements, grid


def _fmt_nodes(nodes: dict[int, tuple[float, float]]) -> str:
    return "".join(f"{k}, {x:.12g}, {y:.12g}\n" for k, (x, y) in nodes.items())


def _fmt_elements(elements: dict[int, list[int]]) -> str:
    return "".join(f"{k}, " + ", ".join(str(v) for v in conn) + "\n"
                   for k, conn in elements.items())


def _fmt_set(ids: Any) -> str:
    ids = [int(i) for i in ids]
    return "".join(", ".join(str(i) for i in ids[k:k + 12]) + ",\n" for k in range(0, len(ids), 12))


def _material(c10: float, c01: float, d: float, elset: str) -> str:
    return (f"*MATERIAL, NAME=SILICONE\n*HYPERELASTIC, MOONEY-RIVLIN\n"
            f"{c10:.12g}, {c01:.12g}, {d:.12g}\n"
            f"*SOLID SECTION, ELSET={elset}, MATERIAL=SILICONE\n1.0\n")


def _step(pressures: np.ndarray, max_increment: float, body: str,
          controls: tuple[float, float] | None = None) -> str:
    p = np.asarray(pressures, dtype=float)
    first = min(max_increment, float(p[0]))
    tp = "".join(_TIME_FMT.format(v) + ",\n" for v in p)
    return (f"*TIME POINTS, NAME=OUT\n{tp}"
            f"*STEP, NLGEOM, INC=10000\n*STATIC\n"
            f"{first:.6g}, {p[-1]:.10g}, {1e-7 * p[-1]:.3g}, {max_increment:.6g}\n"
            + _controls(controls) + body + "*END STEP\n")


def _controls(controls: tuple[float, float] | None) -> str:
    # CalculiX's Newton criteria: residual <= R_n x average force and correction <= C_n x
    # largest increment of the displacements (defaults 0.005 and 0.01)
    if controls is None:
        return ""
    return ("*CONTROLS, PARAMETERS=FIELD, FIELD=DISPLACEMENT\n"
            f"{controls[0]:.6g}, {controls[1]:.6g}\n")


def _ramp_pressure(elements: list[int], face: int, p_end: float) -> str:
    # static step: loads ramp linearly over the step; step time runs 0 .. p_end (MPa)
    return "*DLOAD\n" + "".join(f"{e}, P{face}, {p_end:.10g}\n" for e in elements)


@dataclass(frozen=True)
class CcxDeck:
    """A CalculiX input deck and the node numbers needed to read its results.

    Attributes
    ----------
    text : str
        The ``.inp`` text.
    pressures_mpa : ndarray
        Output pressures (MPa) = output step times.
    mesh : dict
        Mesh description (element type, n_radial, n_circ, grading ...).
    nodes_2d : int
        Nodes of the 2-D mesh (tube, plus the rigid parts for the squeeze).
    tube_dofs_2d : int
        2 x the tube's nodes (the plane-strain unknowns before CalculiX's expansion).
    probes : dict
        Named node numbers (``out``/``in``: outer/inner node on the x axis for the
        inflation; ``bottom`` for the squeeze).
    initial_xy : dict
        Node number -> initial (x, y) of the probe and outer-surface nodes (mm).
    rigid : dict
        Squeeze only: ``"wire"``/``"hole"`` -> ``{"center": (x, y), "xy": {node: (x, y)}}``,
        the rigid circles' centres and nodes (mm).
    """

    text: str
    pressures_mpa: np.ndarray
    mesh: dict[str, Any]
    nodes_2d: int
    tube_dofs_2d: int
    probes: dict[str, int] = field(default_factory=dict)
    initial_xy: dict[int, tuple[float, float]] = field(default_factory=dict)
    rigid: dict[str, Any] = field(default_factory=dict)


def inflate_deck(
    tube_od_mm: float,
    tube_id_mm: float,
    material: Any,
    pressures_mpa: np.ndarray | list[float],
    *,
    n_radial: int = 2,
    n_circ: int = 6,
    element: str = "CPE8R",
    max_increment_mpa: float = 0.05,
    controls: tuple[float, float] | None = None,
) -> CcxDeck:
    """Deck of the free plane-strain inflation of a quarter tube (0..90 deg).

    Parameters
    ----------
    tube_od_mm, tube_id_mm : float
        Undeformed diameters (mm).
    material : object with ``c10, c01, d`` or (c10, c01, d)
        Mooney-Rivlin constants (MPa, MPa, 1/MPa).
    pressures_mpa : array-like
        Increasing output pressures (MPa).
    n_radial, n_circ : int
        Elements through the wall and over the quarter.
    element : str
        ``CPE8R`` (reduced integration) or ``CPE8``.
    max_increment_mpa : float
        Largest pressure increment of CalculiX's automatic incrementation (MPa).

    Returns
    -------
    CcxDeck
    """
    c10, c01, d = _constants(material)
    p = np.asarray(pressures_mpa, dtype=float)
    a, b = 0.5 * tube_id_mm, 0.5 * tube_od_mm
    nodes, elems, grid = polar_quad8(a, b, n_radial, n_circ, 0.0, 0.5 * np.pi)
    for k in grid[:, -1]:
        if k:
            nodes[k] = (0.0, nodes[k][1])  # exactly on x = 0
    for k in grid[:, 0]:
        if k:
            nodes[k] = (nodes[k][0], 0.0)
    inner_elems = [e for e, c in elems.items() if c[0] in set(grid[0])]
    y0 = [k for k in grid[:, 0] if k]
    x0 = [k for k in grid[:, -1] if k]
    probes = {"out": int(grid[-1, 0]), "in": int(grid[0, 0])}
    body = ("*BOUNDARY\nNY0, 2, 2\nNX0, 1, 1\n"
            + _ramp_pressure(inner_elems, 4, float(p[-1]))
            + "*NODE PRINT, NSET=NPROBE, TIME POINTS=OUT\nU\n")
    text = ("** exofric benchmark: free plane-strain inflation, quarter tube (mm, N, MPa)\n"
            "*NODE, NSET=NALL\n" + _fmt_nodes(nodes)
            + f"*ELEMENT, TYPE={element}, ELSET=TUBE\n" + _fmt_elements(elems)
            + "*NSET, NSET=NY0\n" + _fmt_set(y0) + "*NSET, NSET=NX0\n" + _fmt_set(x0)
            + "*NSET, NSET=NPROBE\n" + _fmt_set(sorted(probes.values()))
            + _material(c10, c01, d, "TUBE")
            + _step(p, max_increment_mpa, body, controls))
    return CcxDeck(text, p, {"element": element, "n_radial": n_radial, "n_circ": n_circ,
                             "controls": controls},
                   len(nodes), 2 * len(nodes), probes,
                   {k: nodes[k] for k in probes.values()})


#: Default stick slope of ``*FRICTION`` (MPa/mm): a tenth of the default normal penalty
#: (1e4 MPa/mm); see :func:`squeeze_deck` and ``bench_friction_ccx.py`` (its convergence).
STICK_SLOPE = 1.0e3


def _interactions(penalty: float, contact: str, mu_wall: float, mu_wire: float,
                  stick_slope: float) -> str:
    """``*SURFACE INTERACTION`` and ``*CONTACT PAIR`` cards of the squeeze.

    Frictionless (both mu 0): one interaction ``SI`` for both pairs (the deck as before
    friction existed). Otherwise one interaction per pair, ``SIWALL`` (tube-hole) and
    ``SIWIRE`` (tube-wire), the same linear penalty, and ``*FRICTION`` (mu, stick slope)
    where mu > 0 (CalculiX rejects mu = 0 in ``*FRICTION``).
    """
    def behavior(name: str, mu: float) -> str:
        out = (f"*SURFACE INTERACTION, NAME={name}\n"
               "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
               f"{penalty:.6g}\n")
        if mu > 0.0:
            out += f"*FRICTION\n{mu:.6g}, {stick_slope:.6g}\n"
        return out

    if mu_wall == 0.0 and mu_wire == 0.0:
        return (behavior("SI", 0.0)
                + f"*CONTACT PAIR, INTERACTION=SI, TYPE={contact}\nSTUBE, SHOLE\n"
                + f"*CONTACT PAIR, INTERACTION=SI, TYPE={contact}\nSTUBE, SWIRE\n")
    return (behavior("SIWALL", mu_wall) + behavior("SIWIRE", mu_wire)
            + f"*CONTACT PAIR, INTERACTION=SIWALL, TYPE={contact}\nSTUBE, SHOLE\n"
            + f"*CONTACT PAIR, INTERACTION=SIWIRE, TYPE={contact}\nSTUBE, SWIRE\n")


def squeeze_deck(
    pressures_mpa: np.ndarray | list[float],
    material: Any,
    *,
    hole_mm: float = 10.0,
    tube_od_mm: float = 8.3,
    tube_id_mm: float = 4.97,
    wire_mm: float = 1.6,
    n_radial: int = 4,
    n_circ: int = 40,
    grading: float = 10.0,
    element: str = "CPE8R",
    penalty: float = 1e4,
    max_increment_mpa: float = 0.05,
    rigid_elements: int = 32,
    contact: str = "NODE TO SURFACE",
    controls: tuple[float, float] | None = None,
    mu_wall: float = 0.0,
    mu_wire: float = 0.0,
    stick_slope: float = STICK_SLOPE,
    node_forces: bool = False,
    radial_grading: float = 1.0,
) -> CcxDeck:
    """Deck of the tube-wire-hole squeeze, half model x >= 0, rigid hole and wire.

    Parameters
    ----------
    pressures_mpa : array-like
        Increasing output pressures (MPa).
    material : object with ``c10, c01, d`` or (c10, c01, d)
        Mooney-Rivlin constants (MPa, MPa, 1/MPa).
    hole_mm, tube_od_mm, tube_id_mm, wire_mm : float
        Hole diameter D, tube outer/inner diameter, wire diameter d2 (mm).
    n_radial, n_circ : int
        Tube elements through the wall and over the half circumference (180 deg).
    grading : float
        Largest (at the wall, -90 deg) / smallest (at the wire, +90 deg) element angle.
    element : str
        ``CPE8R`` or ``CPE8``.
    penalty : float
        Slope of the linear pressure-overclosure law (MPa/mm).
    max_increment_mpa : float
        Largest pressure increment (MPa).
    rigid_elements : int
        Elements over the half circle of the hole and of the wire (their contact faces).
    contact : str
        ``NODE TO SURFACE`` (3-5x faster here) or ``SURFACE TO SURFACE``.
    controls : (float, float), optional
        CalculiX's Newton criteria (residual, correction; default 0.005, 0.01).
    mu_wall, mu_wire : float
        Coulomb friction coefficients of the tube-hole wall and the tube-wire contact
        (>= 0). Both 0 (default): the frictionless deck (one interaction ``SI`` for both
        pairs). Otherwise each pair gets its own interaction (``SIWALL``, ``SIWIRE``: the
        same penalty) and a pair with mu > 0 a ``*FRICTION`` card ``mu, stick_slope``.
    stick_slope : float
        CalculiX's stick slope: shear stress per tangential elastic slip (MPa/mm), used
        where mu > 0.
    node_forces : bool
        Also print the reaction of every hole and wire node (``*NODE PRINT ... RF``), from
        which :func:`read_squeeze` splits each contact into its normal and tangential parts
        (radial and circumferential about the circle's centre). (``*CONTACT PRINT`` does
        not give them for node-to-surface contact: its ``CF`` statistics are zero there and
        ccx 2.20 crashed after four outputs; ``CSTR`` gives stresses without areas.)
    radial_grading : float
        Widest (at the bore) / narrowest (at the outer surface) ring of elements through the
        wall; 1 (default): uniform.

    Returns
    -------
    CcxDeck
    """
    c10, c01, d = _constants(material)
    p = np.asarray(pressures_mpa, dtype=float)
    for name, mu in (("mu_wall", mu_wall), ("mu_wire", mu_wire)):
        if not (np.isfinite(mu) and mu >= 0.0):
            raise ValueError(f"{name} must be a finite number >= 0, got {mu!r}")
    if (mu_wall > 0.0 or mu_wire > 0.0) and not (np.isfinite(stick_slope)
                                                   and stick_slope > 0.0):
        raise ValueError(f"stick_slope must be a finite number > 0, got {stick_slope!r}")
    a, b = 0.5 * tube_id_mm, 0.5 * tube_od_mm
    yc = -(0.5 * hole_mm - b)
    half = 0.5 * np.pi
    nodes, elems, grid = polar_quad8(a, b, n_radial, n_circ, -half, half, grading=grading,
                                     center=(0.0, yc), radial_grading=radial_grading)
    for k in np.concatenate([grid[:, 0], grid[:, -1]]):
        if k:
            nodes[k] = (0.0, nodes[k][1])
    n_next, e_next = max(nodes) + 1, max(elems) + 1
    rh = 0.5 * hole_mm
    hn, he, hg = polar_quad8(rh, rh * 1.1, 1, rigid_elements, -half, half,
                             first_node=n_next, first_element=e_next)
    n_next, e_next = max(hn) + 1, max(he) + 1
    rw = 0.5 * wire_mm
    wc = (0.0, 0.5 * hole_mm - rw)
    wn, we, wg = polar_quad8(0.5 * rw, rw, 1, rigid_elements, -half, half, center=wc,
                             first_node=n_next, first_element=e_next)
    inner_set = set(int(k) for k in grid[0] if k)
    outer_set = set(int(k) for k in grid[-1] if k)
    inner_elems = [e for e, c in elems.items() if c[0] in inner_set]
    outer_elems = [e for e, c in elems.items() if c[1] in outer_set]
    sym = [int(k) for k in np.concatenate([grid[:, 0], grid[:, -1]]) if k]
    bottom = int(grid[-1, 0])
    contact_block = ("*SURFACE, NAME=STUBE, TYPE=ELEMENT\n"
                     + "".join(f"{e}, S2\n" for e in outer_elems)
                     + "*SURFACE, NAME=SHOLE, TYPE=ELEMENT\n"
                     + "".join(f"{e}, S4\n" for e in he)
                     + "*SURFACE, NAME=SWIRE, TYPE=ELEMENT\n"
                     + "".join(f"{e}, S2\n" for e in we)
                     + _interactions(penalty, contact, mu_wall, mu_wire, stick_slope))
    body = ("*BOUNDARY\nNSYM, 1, 1\nNBOTTOM, 2, 2\nNHOLE, 1, 2\nNWIRE, 1, 2\n"
            + _ramp_pressure(inner_elems, 4, float(p[-1]))
            + "*NODE PRINT, NSET=NWIRE, TOTALS=ONLY, TIME POINTS=OUT\nRF\n"
            + "*NODE PRINT, NSET=NHOLE, TOTALS=ONLY, TIME POINTS=OUT\nRF\n"
            + "*NODE PRINT, NSET=NBOTTOM, TIME POINTS=OUT\nRF\n"
            + "*NODE PRINT, NSET=NOUTER, TIME POINTS=OUT\nU\n"
            + ("*NODE PRINT, NSET=NWIRE, TIME POINTS=OUT\nRF\n"
               "*NODE PRINT, NSET=NHOLE, TIME POINTS=OUT\nRF\n" if node_forces else ""))
    text = ("** exofric benchmark: tube-wire-hole squeeze, half model (mm, N, MPa)\n"
            "*NODE, NSET=NALL\n" + _fmt_nodes(nodes) + _fmt_nodes(hn) + _fmt_nodes(wn)
            + f"*ELEMENT, TYPE={element}, ELSET=TUBE\n" + _fmt_elements(elems)
            + f"*ELEMENT, TYPE={element}, ELSET=HOLE\n" + _fmt_elements(he)
            + f"*ELEMENT, TYPE={element}, ELSET=WIRE\n" + _fmt_elements(we)
            + "*NSET, NSET=NSYM\n" + _fmt_set(sym)
            + f"*NSET, NSET=NBOTTOM\n{bottom},\n"
            + "*NSET, NSET=NOUTER\n" + _fmt_set(sorted(outer_set))
            + "*NSET, NSET=NHOLE\n" + _fmt_set(sorted(hn))
            + "*NSET, NSET=NWIRE\n" + _fmt_set(sorted(wn))
            + _material(c10, c01, d, "TUBE")
            + "*MATERIAL, NAME=RIGID\n*ELASTIC\n2.0e5, 0.3\n"
            + "*SOLID SECTION, ELSET=HOLE, MATERIAL=RIGID\n1.0\n"
            + "*SOLID SECTION, ELSET=WIRE, MATERIAL=RIGID\n1.0\n"
            + contact_block
            + _step(p, max_increment_mpa, body, controls))
    mesh = {"element": element, "n_radial": n_radial, "n_circ": n_circ, "grading": grading,
            "penalty": penalty, "rigid_elements": rigid_elements, "contact": contact,
            "controls": controls}
    if radial_grading != 1.0:
        mesh["radial_grading"] = float(radial_grading)
    if mu_wall > 0.0 or mu_wire > 0.0:
        mesh.update(mu_wall=float(mu_wall), mu_wire=float(mu_wire),
                    stick_slope=float(stick_slope))
    rigid = {"wire": {"center": wc, "xy": wn}, "hole": {"center": (0.0, 0.0), "xy": hn}}
    return CcxDeck(text, p, mesh, len(nodes) + len(hn) + len(wn), 2 * len(nodes),
                   {"bottom": bottom}, {k: nodes[k] for k in sorted(outer_set)}, rigid)


# ------------------------------------------------------------------------ run and parse
@dataclass(frozen=True)
class CcxRun:
    """One CalculiX run.

    Attributes
    ----------
    wall_time_s, cpu_time_s : float
        Wall clock and CPU time (user + system) of the ``ccx`` process (s).
    ccx_time_s : float or None
        CalculiX's own "Total CalculiX Time" (s), if printed.
    equations : int or None
        Number of equations CalculiX reported (its expanded 3-D system).
    dat : str
        The ``.dat`` file.
    stdout : str
        Its standard output.
    returncode : int
    sta : str
        The ``.sta`` file (one line per increment attempt; see :func:`increments`).
    """

    wall_time_s: float
    cpu_time_s: float
    ccx_time_s: float | None
    equations: int | None
    dat: str
    stdout: str
    returncode: int
    sta: str = ""


def run_ccx(deck: CcxDeck | str, workdir: str | Path | None = None, *, ccx: str = "ccx",
            jobname: str = "job", timeout_s: float = 600.0) -> CcxRun:
    """Write the deck, run ``ccx -i job`` on one thread, return times and results.

    Parameters
    ----------
    deck : CcxDeck or str
        The deck (or its text).
    workdir : path, optional
        Folder for the job files (default: a temporary folder, removed afterwards).
    ccx : str
        CalculiX executable.
    jobname : str
        Job name (``<jobname>.inp``).
    timeout_s : float
        Kill the run after this many seconds.

    Returns
    -------
    CcxRun
    """
    text = deck.text if isinstance(deck, CcxDeck) else deck
    tmp = None
    if workdir is None:
        tmp = tempfile.TemporaryDirectory(prefix="exofric-ccx-")
        workdir = tmp.name
    try:
        wd = Path(workdir)
        wd.mkdir(parents=True, exist_ok=True)
        (wd / f"{jobname}.inp").write_text(text)
        env = {**os.environ, **ONE_THREAD}
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        proc = subprocess.run([ccx, "-i", jobname], cwd=wd, env=env, capture_output=True,
                              text=True, timeout=timeout_s, check=False)
        wall = time.perf_counter() - t0
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
        dat_path = wd / f"{jobname}.dat"
        dat = dat_path.read_text() if dat_path.exists() else ""
        sta_path = wd / f"{jobname}.sta"
        sta = sta_path.read_text() if sta_path.exists() else ""
    finally:
        if tmp is not None:
            tmp.cleanup()
    out = proc.stdout
    m = re.search(r"Total CalculiX Time:\s*([0-9.eE+-]+)", out)
    eq = re.findall(r"number of equations\s*\n?\s*(\d+)", out)
    return CcxRun(wall, cpu, float(m.group(1)) if m else None,
                  int(eq[-1]) if eq else None, dat, out + proc.stderr, proc.returncode, sta)


def increments(sta: str) -> dict[str, Any]:
    """Summary of CalculiX's automatic incrementation from a ``.sta`` file.

    Returns
    -------
    dict
        ``increments`` (converged), ``cutbacks`` (attempts that did not converge, marked
        ``U``), ``iterations`` (Newton iterations of all attempts), ``min_increment`` and
        ``max_increment`` (step time of the converged increments = MPa in the squeeze).
    """
    done: list[float] = []
    cut = iters = 0
    for line in sta.splitlines():
        parts = line.split()
        if len(parts) != 7 or not parts[0].isdigit():
            continue
        iters += int(parts[3])
        if parts[2].endswith("U"):
            cut += 1
        else:
            done.append(float(parts[6]))
    return {"increments": len(done), "cutbacks": cut, "iterations": iters,
            "min_increment": min(done) if done else None,
            "max_increment": max(done) if done else None}


_HEADER = re.compile(r"^\s*(.+?)\s*\(([^)]*)\)\s*for set\s+(\S+)\s+and time\s+(\S+)")


def parse_dat(text: str) -> dict[tuple[str, str, float], dict[int | str, np.ndarray]]:
    """Tables of a CalculiX ``.dat`` file.

    Returns
    -------
    dict
        ``(quantity, SET, time) -> {node: values}``; ``quantity`` is e.g.
        ``"displacements"``, ``"forces"`` or ``"total force"``; for totals the key is
        ``"total"``.
    """
    out: dict[tuple[str, str, float], dict[int | str, np.ndarray]] = {}
    current: dict[int | str, np.ndarray] | None = None
    is_total = False
    for line in text.splitlines():
        m = _HEADER.match(line)
        if m:
            name = m.group(1).strip()
            is_total = name.startswith("total")
            current = out.setdefault((name, m.group(3).upper(), float(m.group(4))), {})
            continue
        parts = line.split()
        if current is None or not parts:
            continue
        try:
            vals = [float(v) for v in parts]
        except ValueError:
            current = None
            continue
        if is_total:
            current["total"] = np.array(vals)
        else:
            current[int(vals[0])] = np.array(vals[1:])
    return out


def _times(tables: dict[tuple[str, str, float], Any], name: str, nset: str) -> list[float]:
    return sorted(t for (q, s, t) in tables if q == name and s == nset)


def _at(tables: dict[tuple[str, str, float], Any], name: str, nset: str,
        p: np.ndarray) -> list[dict[int | str, np.ndarray]]:
    times = np.array(_times(tables, name, nset))
    rows = []
    for pk in p:
        if times.size == 0:
            raise RuntimeError(f"CalculiX wrote no '{name}' for set {nset}")
        k = int(np.argmin(np.abs(times - pk)))
        if abs(times[k] - pk) > 1e-6 * max(1.0, abs(pk)):
            raise RuntimeError(f"CalculiX stopped before P = {pk:g} MPa "
                               f"(last output at {times.max():g} MPa)")
        rows.append(tables[(name, nset, float(times[k]))])
    return rows


@dataclass(frozen=True)
class CalculixInflation:
    """CalculiX free inflation results (mm, MPa, s).

    Attributes
    ----------
    pressure_mpa, outer_diameter_mm, inner_diameter_mm : ndarray
        Pressures and deformed diameters on the x axis.
    equations : int or None
        Size of CalculiX's (expanded) system.
    tube_dofs_2d : int
        2 x the 2-D nodes.
    run : CcxRun
        Times and raw output.
    mesh : dict
        Mesh description.
    """

    pressure_mpa: np.ndarray
    outer_diameter_mm: np.ndarray
    inner_diameter_mm: np.ndarray
    equations: int | None
    tube_dofs_2d: int
    run: CcxRun = field(repr=False)
    mesh: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class CalculixSqueeze:
    """CalculiX squeeze results per requested pressure (full section, N/mm).

    Attributes
    ----------
    pressure_mpa : ndarray
        Pressures (MPa).
    squeeze_force_n_per_mm : ndarray
        y-force of the tube on the wire (N/mm), 2 x the half model.
    wall_force_n_per_mm : ndarray
        y-force of the wall (rigid hole plus the bottom node's support) on the tube (N/mm).
    outer_diameter_mm : ndarray
        Horizontal extent of the deformed outer surface, 2 max(x) (mm).
    equations : int or None
        Size of CalculiX's (expanded) system.
    tube_dofs_2d : int
        2 x the tube's 2-D nodes.
    run : CcxRun
        Times and raw output.
    mesh : dict
        Mesh and contact description.
    contact_integrals : dict or None
        With ``squeeze_deck(..., node_forces=True)``: per interface (``"wire"``, ``"wall"``)
        ``{"normal_n_per_mm": ndarray, "tangential_n_per_mm": ndarray}``: the sums over the
        rigid circle's nodes of the normal (radial, pressing on the tube: > 0) and tangential
        (circumferential, > 0 counter-clockwise about the circle's centre, i.e. on the half
        x >= 0 pushing the tube away from the symmetry line at the bottom of the circle)
        parts of its nodal force on the tube, full section (2 x the half model; the wall's
        normal sum includes the bottom node's support). The normal sum is the integral of
        the contact pressure over the contact arc (N/mm), the tangential one that of the
        friction stress (0 up to discretisation when frictionless). Signed sums, because
        the quadratic master faces share a slave node's force among their three nodes with
        weights that can be negative.
    """

    pressure_mpa: np.ndarray
    squeeze_force_n_per_mm: np.ndarray
    wall_force_n_per_mm: np.ndarray
    outer_diameter_mm: np.ndarray
    equations: int | None
    tube_dofs_2d: int
    run: CcxRun = field(repr=False)
    mesh: dict[str, Any] = field(default_factory=dict)
    contact_integrals: dict[str, dict[str, np.ndarray]] | None = None


def _check(run: CcxRun) -> dict[tuple[str, str, float], dict[int | str, np.ndarray]]:
    if run.returncode != 0 or not run.dat:
        tail = "\n".join(run.stdout.strip().splitlines()[-8:])
        raise RuntimeError(f"CalculiX failed (exit {run.returncode}):\n{tail}")
    return parse_dat(run.dat)


def read_inflation(deck: CcxDeck, run: CcxRun) -> CalculixInflation:
    """Diameters at the output pressures from a run of :func:`inflate_deck`."""
    tables = _check(run)
    rows = _at(tables, "displacements", "NPROBE", deck.pressures_mpa)
    o, i = deck.probes["out"], deck.probes["in"]
    od = np.array([2.0 * (deck.initial_xy[o][0] + r[o][0]) for r in rows])
    idm = np.array([2.0 * (deck.initial_xy[i][0] + r[i][0]) for r in rows])
    return CalculixInflation(deck.pressures_mpa, od, idm, run.equations, deck.tube_dofs_2d,
                             run, deck.mesh)


def read_squeeze(deck: CcxDeck, run: CcxRun) -> CalculixSqueeze:
    """Forces and outer diameter at the output pressures from a run of :func:`squeeze_deck`."""
    tables = _check(run)
    p = deck.pressures_mpa
    wire = _at(tables, "total force", "NWIRE", p)
    hole = _at(tables, "total force", "NHOLE", p)
    bottom = _at(tables, "forces", "NBOTTOM", p)
    outer = _at(tables, "displacements", "NOUTER", p)
    b = deck.probes["bottom"]
    # the supports' reactions on the fixed wire nodes balance the tube's force on the wire;
    # those on the hole nodes and on the bottom node are the wall's force on the tube
    n = np.array([-2.0 * r["total"][1] for r in wire])
    wall = np.array([2.0 * (hr["total"][1] + br[b][1])
                     for hr, br in zip(hole, bottom, strict=True)])
    od = np.array([2.0 * max(deck.initial_xy[k][0] + r[k][0] for k in deck.initial_xy)
                   for r in outer])
    integrals = None
    if deck.rigid and any(q == "forces" and s == "NWIRE" for (q, s, _) in tables):
        integrals = {}
        for name, nset in (("wire", "NWIRE"), ("hole", "NHOLE")):
            rows = _at(tables, "forces", nset, p)
            rig = deck.rigid[name]
            ids = sorted(rig["xy"])
            er = np.array([rig["xy"][k] for k in ids]) - np.asarray(rig["center"])
            er /= np.linalg.norm(er, axis=1)[:, None]
            et = np.column_stack([-er[:, 1], er[:, 0]])
            f = np.array([[r[k][:2] for k in ids] for r in rows])  # (pressures, nodes, 2)
            # the wire pushes the tube away from its centre, the hole toward its centre
            sign = 1.0 if name == "wire" else -1.0
            normal = 2.0 * sign * np.einsum("pnj,nj->p", f, er)
            tangential = 2.0 * np.einsum("pnj,nj->p", f, et)
            if name == "hole":
                name = "wall"
                normal = normal + 2.0 * np.array([br[b][1] for br in bottom])
            integrals[name] = {"normal_n_per_mm": normal, "tangential_n_per_mm": tangential}
    return CalculixSqueeze(p, n, wall, od, run.equations, deck.tube_dofs_2d, run, deck.mesh,
                           integrals)


def ccx_inflate(tube_od_mm: float, tube_id_mm: float, material: Any,
                pressures_mpa: np.ndarray | list[float], *, ccx: str = "ccx",
                workdir: str | Path | None = None, **mesh: Any) -> CalculixInflation:
    """Write, run and read the CalculiX free inflation (see :func:`inflate_deck`)."""
    deck = inflate_deck(tube_od_mm, tube_id_mm, material, pressures_mpa, **mesh)
    return read_inflation(deck, run_ccx(deck, workdir, ccx=ccx))


def ccx_squeeze(pressures_mpa: np.ndarray | list[float], material: Any, *, ccx: str = "ccx",
                workdir: str | Path | None = None, **setup: Any) -> CalculixSqueeze:
    """Write, run and read the CalculiX squeeze (see :func:`squeeze_deck`)."""
    deck = squeeze_deck(pressures_mpa, material, **setup)
    return read_squeeze(deck, run_ccx(deck, workdir, ccx=ccx))
