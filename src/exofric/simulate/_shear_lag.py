"""Held tube ends: the tube's axial field along z next to the end fittings (issue 39).

The section law (``_pullout``) is the tube far from its ends. Where a fitting holds the tube's
end face (u_z = 0 over the face), the axial field w(x, y, z) varies along z over a length of
the order of the wall thickness, and the tube is much stiffer there (docs/formulation.md,
section 12, "Held end zones"). This module solves that zone as a 3-D scalar problem:

    div_X (A grad_X w) + E_z d2w/dz2 = 0   in the tube,   E_z = 3 G (a rod's axial modulus),

with the section's anti-plane modulus A in the plane, Coulomb friction on the tube-wire and
tube-wall arcs at every station (the section's capacities), the wire rigid (displacement
delta), w = 0 on a held end face and dw/dz = 0 on a symmetry face. Along z: linear elements
graded from a held face, lumped mass; the eigenvectors of (K_z, M_z) decouple the stations: mode j
is the section with a foundation E_z lambda_j (area-weighted, as the squeeze's nodal areas),
condensed onto the contact nodes; the modes recombine into one dense contact stiffness
(stations x contact nodes) for :func:`exofric.simulate._antiplane.solve_friction_steps`.
On a held face the wire-arc nodes are held against the moving wire: they slide at once and
carry their Coulomb capacity over half an element (rigid-plastic; it vanishes as h -> 0).

This scalar zone is the ``held_zone="scalar"`` option. It neglects the in-plane displacements
that axial gradients drive (E_z = 3 G is the laterally free rod; E_z = G gives a 15-18 % softer
secant) and is written in the reference configuration, so it does not see the inflation's
stretch: on the held annulus inflated first (CalculiX) it is 19-27 % below 3-D unstretched and
up to 11 % above it at a bore stretch of 1.84. The default is the vector zone
(:mod:`exofric.simulate._vector_zone`, the 3-D incremental problem about the squeeze; within
1.6 % of that annulus at every stretch): :func:`zone_stiffness` takes it from
``HeldEnds.vector`` and returns the same condensed contact stiffness, so the friction solve
and the Iwan law below do not change (docs/formulation.md section 12).

Units: mm, N, MPa.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from exofric import defaults
from exofric.simulate._antiplane import CondensedSection, condense, solve_friction_steps
from exofric.simulate._vector_zone import VectorSection, vector_zone_stiffness, z_modes

__all__: list[str] = []


@dataclass(frozen=True)
class HeldEnds:
    """What the end-zone model needs from the section (half or full model; see ``fac``).

    Attributes
    ----------
    K : sparse (n, n)
        Anti-plane stiffness of the section without any foundation (N/mm per mm of tube).
    area : ndarray (n,)
        Nodal areas (mm^2).
    section : CondensedSection
        Contact nodes' flags, Coulomb capacities (N/mm) and tributary lengths (mm).
    contact : ndarray of int (c,)
        The contact nodes.
    fac : float
        Full section / model (2 for the half model).
    ez_mpa : float
        Rod modulus along z (MPa).
    penalty, creep_tol_mm : float
        The section solve's stick penalty (N/mm^3) and creep tolerance (mm).
    """

    K: sp.csr_matrix
    area: np.ndarray
    section: CondensedSection
    contact: np.ndarray
    fac: float
    ez_mpa: float
    penalty: float = 1e3
    creep_tol_mm: float = 1e-9
    vector: VectorSection | None = None


def z_elements(length: float, first: float | None = None,
               growth: float | None = None) -> np.ndarray:
    """Element lengths (mm) from a held face: ``first`` x ``growth`` ** k, scaled to fit
    (defaults :data:`exofric.defaults.PULLOUT_HELD_DZ_MM` and ``PULLOUT_HELD_DZ_GROWTH``).

    Examples
    --------
    >>> z_elements(5.0).round(3).tolist()
    [0.117, 0.147, 0.184, 0.229, 0.287, 0.358, 0.448, 0.56, 0.7, 0.875, 1.094]
    """
    first = defaults.PULLOUT_HELD_DZ_MM if first is None else first
    growth = defaults.PULLOUT_HELD_DZ_GROWTH if growth is None else growth
    sizes = first * growth ** np.arange(64)
    n = int(np.searchsorted(np.cumsum(sizes), length - 1e-12)) + 1
    sizes = sizes[:n]
    return sizes * (length / sizes.sum())


def _z_modes(h: np.ndarray, held: tuple[bool, bool]) -> tuple[np.ndarray, np.ndarray,
                                                             np.ndarray]:
    """(lambda (1/mm^2), M V (mm), tributary lengths (mm)) of the free stations along z for
    linear elements of lengths ``h`` (mm), lumped: the generalised eigenpairs of (K_z, M_z),
    K_z = D^T diag(h) D, are the squared singular values and M^1/2 Q of the vector zone's
    :func:`~exofric.simulate._vector_zone.z_modes` (one owner)."""
    s, MQ, m = z_modes(np.asarray(h, float), held)
    return s * s, MQ, m


def zone_stiffness(ends: HeldEnds, h: np.ndarray, held: tuple[bool, bool]) -> CondensedSection:
    """The zone's contact stiffness (stations x contact nodes, N/mm per mm) and capacities (N).

    Examples
    --------
    >>> import scipy.sparse as sp
    >>> K = sp.csr_matrix(np.array([[1.0, -1.0], [-1.0, 1.0]]))
    >>> sec = CondensedSection(np.eye(1), np.array([True]), np.array([1.0]), np.array([1.0]))
    >>> he = HeldEnds(K, np.array([0.0, 1.0]), sec, np.array([0]), 1.0, 3.0)
    >>> # one station (mass 1), lambda 2: foundation 3 x 2 x 1 on the inner node: 1 - 1/7
    >>> zone_stiffness(he, np.array([1.0, 1.0]), (True, True)).K.round(6).tolist()
    [[0.857143]]
    """
    if ends.vector is not None:
        return vector_zone_stiffness(ends.vector, ends.section, h, held)
    lam, MV, mz = _z_modes(np.asarray(h, float), held)

    kc = np.stack([condense((ends.K + sp.diags(ends.ez_mpa * lj * ends.area)).tocsr(),
                            ends.contact) for lj in lam])
    ns, nc = MV.shape[0], len(ends.contact)
    C = np.einsum("aj,bj,jpq->apbq", MV, MV, kc).reshape(ns * nc, ns * nc)
    s = ends.section
    return CondensedSection(0.5 * (C + C.T), np.tile(s.on_wire, ns),
                            np.kron(mz, s.capacity), np.kron(mz, s.length))


def zone_curve(ends: HeldEnds, length: float, held: tuple[bool, bool],
               deltas: np.ndarray) -> tuple[np.ndarray, float]:
    """Force (N, full section) of a rigid wire pulled by ``deltas`` (mm, monotone) through a
    tube zone of ``length`` (mm), each end held (True) or a symmetry face (False); and the
    held faces' rigid-plastic end-row force (N, included in the force for delta > 0).

    Examples
    --------
    >>> import scipy.sparse as sp
    >>> K = sp.csr_matrix(np.array([[1.0, -1.0], [-1.0, 1.0]]))
    >>> sec = CondensedSection(np.eye(1), np.array([True]), np.array([10.0]), np.array([1.0]))
    >>> he = HeldEnds(K, np.array([0.0, 1.0]), sec, np.array([0]), 1.0, 3.0)
    >>> f, end = zone_curve(he, 2.0, (True, True), np.array([0.0, 100.0]))
    >>> round(float(f[-1]), 6)   # all sliding: capacity 10 N/mm x 2 mm, end rows included
    20.0
    """
    h = z_elements(length)
    if held[1]:  # held at both ends: graded toward both
        half = z_elements(0.5 * length)
        h = np.r_[half, half[::-1]]
    zs = zone_stiffness(ends, h, held)
    out = solve_friction_steps(zs, np.asarray(deltas, float), ends.penalty, ends.creep_tol_mm)
    s = ends.section
    end = 0.5 * h[0] * float(s.capacity[s.on_wire].sum()) * sum(held)
    d = np.asarray(deltas, float)
    return ends.fac * (out["force"] + np.where(d > 0.0, end, 0.0)), ends.fac * end
