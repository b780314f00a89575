"""The axial (anti-plane) problem of the squeezed tube section and its frictional contacts.

With the in-plane deformation F2 of the squeeze held, an axial displacement w(X) of the tube
gives F = [[F2, 0], [grad_X w^T, 1]], det F = det F2 = J, and (docs/formulation.md, 4f)

    I1 = I1_plane + |g|^2,        I2 = I2_plane + g^T adj(C2) g,        g = grad_X w,

with C2 = F2^T F2 and adj(C2) = tr(C2) I - C2. The isochoric Mooney-Rivlin energy
C10 (J^-2/3 I1 - 3) + C01 (J^-4/3 I2 - 3) is therefore *quadratic* in g: the axial problem is a
linear, anisotropic, heterogeneous scalar problem on the reference section,

    div_X (A grad_X w) = 0,       A = 2 C10 J^-2/3 I + 2 C01 J^-4/3 adj(C2)      (MPa),

exact for neo-Hookean and Mooney-Rivlin given F2 (at F2 = I: A = 2 (C10 + C01) I = G I).
Models with other invariant dependence (Yeoh, Ogden) use their small-strain shear modulus,
A = G I (a linearisation, stated on the result). Units: mm, MPa, N/mm (per unit tube length).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.linalg import lu_factor, lu_solve

from exofric.errors import ConvergenceError
from exofric.fe import reference_data

__all__ = ["CondensedSection", "antiplane_stiffness", "axial_shear", "condense", "recover",
           "solve_friction_steps"]


def antiplane_stiffness(nodes: np.ndarray, elements: np.ndarray,
                        modulus: np.ndarray | float) -> tuple[sp.csr_matrix, np.ndarray]:
    """Stiffness matrix (N/mm per mm of tube) of div(A grad w) = 0 on quad9 elements.

    Parameters
    ----------
    nodes : ndarray (n, 2)
        Reference node coordinates (mm).
    elements : ndarray (e, 9)
        quad9 connectivity.
    modulus : float or ndarray (e, q, 2, 2)
        The anti-plane modulus A (MPa): a scalar shear modulus G (A = G I) or one 2x2 matrix
        per quadrature point (3 x 3 Gauss points).

    Returns
    -------
    K : scipy.sparse.csr_matrix (n, n)
        Stiffness (N/mm per mm).
    mass : ndarray (n,)
        Lumped nodal areas (mm^2), row sums of the consistent mass.

    Examples
    --------
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(1.0, 2.0, 2, 8, theta1=2 * np.pi)
    >>> K, a = antiplane_stiffness(m.nodes, m.elements, 1.0)
    >>> bool(abs(K @ np.ones(m.n_nodes)).max() < 1e-10), round(float(a.sum()), 2)  # 3 pi
    (True, 9.42)
    """
    rd = reference_data(nodes, elements, 2, 3)
    dN = rd.dNdX  # (e, q, n, 2)
    if isinstance(modulus, (int, float)):
        ke = float(modulus) * np.einsum("eq,eqai,eqbi->eab", rd.w, dN, dN)
    else:
        A = np.asarray(modulus, dtype=float)
        ke = np.einsum("eq,eqai,eqij,eqbj->eab", rd.w, dN, A, dN)
    rows = np.repeat(elements, elements.shape[1], axis=1).ravel()
    cols = np.tile(elements, (1, elements.shape[1])).ravel()
    n = len(nodes)
    K = sp.csr_matrix((ke.ravel(), (rows, cols)), shape=(n, n))
    mass = np.zeros(n)
    np.add.at(mass, elements, np.einsum("eq,qa->ea", rd.w, rd.N))
    return K, mass


def mooney_rivlin_modulus(nodes: np.ndarray, elements: np.ndarray, displacement: np.ndarray,
                          c10: float, c01: float) -> np.ndarray:
    """A = 2 C10 J^-2/3 I + 2 C01 J^-4/3 adj(C2) (MPa) at each quadrature point (e, q, 2, 2).

    Parameters
    ----------
    nodes, elements : ndarray
        Reference mesh (mm, quad9).
    displacement : ndarray (n, 2)
        In-plane displacement of the squeeze state (mm).
    c10, c01 : float
        Mooney-Rivlin constants (MPa).

    Returns
    -------
    ndarray (e, q, 2, 2)

    Examples
    --------
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(1.0, 2.0, 1, 2)
    >>> A = mooney_rivlin_modulus(m.nodes, m.elements, 0 * m.nodes, 0.5, 0.1)
    >>> A[0, 0].round(6).tolist()  # 2 (C10 + C01) I at F2 = I
    [[1.2, 0.0], [0.0, 1.2]]
    """
    rd = reference_data(nodes, elements, 2, 3)
    F = np.eye(2) + np.einsum("eai,eqaj->eqij", displacement[elements], rd.dNdX)
    C = np.einsum("eqki,eqkj->eqij", F, F)
    J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
    tr = C[..., 0, 0] + C[..., 1, 1]
    adj = tr[..., None, None] * np.eye(2) - C
    return (2.0 * c10 * J[..., None, None] ** (-2.0 / 3.0) * np.eye(2)
            + 2.0 * c01 * J[..., None, None] ** (-4.0 / 3.0) * adj)


@dataclass(frozen=True)
class CondensedSection:
    """The section's stiffness condensed on its contact nodes (N/mm per mm of tube).

    Attributes
    ----------
    K : ndarray (c, c)
        Schur complement of the anti-plane stiffness on the contact nodes.
    on_wire : ndarray of bool (c,)
        True for a tube-wire node, False for a tube-wall node.
    capacity : ndarray (c,)
        Coulomb capacity mu x (normal force) of each node (N per mm of tube).
    length : ndarray (c,)
        Reference tributary length of each node (mm): stick penalties scale with it.
    hardening : ndarray (c,), optional
        A spring on each node's slip, in parallel with its Coulomb slider (N/mm per mm of
        slip, per mm of tube): the end fittings holding a tube that slides on the wall
        (docs/formulation.md section 12, "Tube ends"). None: no spring.
    """

    K: np.ndarray
    on_wire: np.ndarray
    capacity: np.ndarray
    length: np.ndarray
    hardening: np.ndarray | None = None


def condense(K: sp.csr_matrix, contact: np.ndarray) -> np.ndarray:
    """Schur complement K_cc - K_ci K_ii^-1 K_ic on the nodes ``contact`` (dense).

    Parameters
    ----------
    K : sparse (n, n)
        SPD stiffness (N/mm per mm).
    contact : ndarray of int (c,)
        Kept nodes.

    Returns
    -------
    ndarray (c, c)

    Examples
    --------
    >>> K = sp.csr_matrix(np.array([[2.0, -1, 0], [-1, 2, -1], [0, -1, 2]]))
    >>> condense(K, np.array([0, 2])).round(3).tolist()
    [[1.5, -0.5], [-0.5, 1.5]]
    """
    n = K.shape[0]
    inner = np.setdiff1d(np.arange(n), contact)
    Kcc = K[contact][:, contact].toarray()
    if inner.size == 0:
        return Kcc
    Kic = K[inner][:, contact].toarray()
    Kii = K[inner][:, inner].tocsc()
    X = spla.splu(Kii).solve(Kic)
    S = Kcc - Kic.T @ X
    return np.asarray(0.5 * (S + S.T))


def recover(K: sp.csr_matrix, contact: np.ndarray, w_contact: np.ndarray) -> np.ndarray:
    """The full field (mm) from the contact nodes' values: K_ii w_i = -K_ic w_c.

    Examples
    --------
    >>> K = sp.csr_matrix(np.array([[2.0, -1, 0], [-1, 2, -1], [0, -1, 2]]))
    >>> recover(K, np.array([0, 2]), np.array([1.0, 1.0])).tolist()
    [1.0, 1.0, 1.0]
    """
    n = K.shape[0]
    inner = np.setdiff1d(np.arange(n), contact)
    w = np.zeros(n)
    w[contact] = w_contact
    if inner.size:
        rhs = -(K[inner][:, contact] @ w_contact)
        w[inner] = spla.splu(K[inner][:, inner].tocsc()).solve(rhs)
    return w


def axial_shear(nodes: np.ndarray, elements: np.ndarray, w: np.ndarray) -> float:
    """Largest |grad_X w| (unitless) over the quadrature points of a quad9 mesh.

    Examples
    --------
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(1.0, 2.0, 1, 4)
    >>> round(axial_shear(m.nodes, m.elements, 0.1 * m.nodes[:, 0]), 6)  # w = 0.1 x
    0.1
    """
    rd = reference_data(nodes, elements, 2, 3)
    g = np.einsum("ea,eqai->eqi", w[elements], rd.dNdX)
    return float(np.sqrt((g ** 2).sum(axis=-1)).max())


def solve_friction_steps(sec: CondensedSection, deltas: np.ndarray, penalty: float,
                         creep_tol_mm: float = 1e-10, max_newton: int = 60,
                         max_al: int = 200) -> dict[str, np.ndarray]:
    """Impose wire displacements ``deltas`` (mm) step by step; Coulomb friction on the arcs.

    Stick is a penalty ``penalty`` (N/mm^3) augmented by a Lagrange multiplier (Uzawa): at each
    step Newton solves the penalised problem (slipping nodes carry their Coulomb force and
    have zero tangent: the exact, consistent tangent), then the multipliers take the nodal
    tractions and the step is re-solved until every sticking node's elastic slip is below
    ``creep_tol_mm``: true stick, independent of the penalty. A node with a ``hardening``
    spring h (``sec.hardening``) carries its Coulomb force plus h times its accumulated slip
    (a slider in parallel with a spring, behind the stick penalty: linear kinematic
    hardening; its slipping tangent is penalty h / (penalty + h)). Each step starts from the
    last two steps' solutions extrapolated linearly in the wire displacement: the step's
    problem is convex, so the start changes the iterations (about half of them, and a third of
    the time, on the held zones), not the answer.

    Parameters
    ----------
    sec : CondensedSection
        The condensed section.
    deltas : ndarray (m,)
        Wire displacements (mm), the load path.
    penalty : float
        Stick penalty (N/mm^3: N per mm of tube per mm of slip per mm of arc).
    creep_tol_mm : float
        Largest elastic slip of a sticking node accepted (mm).
    max_newton, max_al : int
        Iteration limits.

    Returns
    -------
    dict
        ``force`` (m,): friction force of the tube on the wire (N/mm of tube, the model's
        section); ``wall_force`` (m,); ``stick`` (m, c) bool; ``w`` (m, c) contact-node axial
        displacements (mm); ``iterations`` (m,).

    Examples
    --------
    >>> sec = CondensedSection(np.array([[1.0, -1.0], [-1.0, 1.0]]), np.array([True, False]),
    ...                        np.array([0.5, 1.0]), np.array([1.0, 1.0]))
    >>> out = solve_friction_steps(sec, np.array([0.0, 0.25, 1.0]), 1e4)
    >>> out["force"].round(6).tolist()   # elastic (k = 1 N/mm^2 in series) to 0.5 N/mm
    [0.0, 0.25, 0.5]
    """
    c = len(sec.capacity)
    law = _NodeLaws(sec, penalty)
    knorm = float(np.abs(sec.K).max(initial=0.0)) + float(law.kp.max(initial=0.0))
    w = np.zeros(c)
    m = len(deltas)
    force, wall, iters = np.zeros(m), np.zeros(m), np.zeros(m, int)
    stick_out = np.zeros((m, c), bool)
    w_out = np.zeros((m, c))
    tangent = _Tangent(sec.K, law)
    for k, d in enumerate(deltas):
        n_it = 0
        if k >= 2 and deltas[k - 1] != deltas[k - 2]:  # the secant predictor
            w = w + (w_out[k - 1] - w_out[k - 2]) * ((d - deltas[k - 1])
                                                     / (deltas[k - 1] - deltas[k - 2]))
        for _ in range(max_al):
            w, n = _newton(sec.K, law, tangent, w, float(d), knorm, max_newton)
            n_it += n
            t, st = law.traction(w, d)
            slip_el = (t - law.lam) / law.kp  # elastic slip of the penalty
            if not np.any(st) or np.abs(slip_el[st]).max() <= creep_tol_mm:
                break
            law.update_multipliers(t, st)
        else:
            raise ConvergenceError(f"pull-out section: augmented Lagrangian did not converge at "
                                   f"displacement {d:g} mm")
        law.commit(w, float(d), t, st)
        force[k] = float((t * law.e).sum())
        wall[k] = float((t * (1 - law.e)).sum())
        stick_out[k] = st
        w_out[k] = w
        iters[k] = n_it
    return {"force": force, "wall_force": wall, "stick": stick_out, "w": w_out,
            "iterations": iters}


class _NodeLaws:
    """The contact nodes' laws and state (N/mm of tube, mm): stick penalty kp, Coulomb capacity,
    hardening spring h, the multipliers ``lam``, the committed reference ``s`` and the springs'
    forces ``back``. A node's trial force is y = lam + kp (d e - w - s) (e: 1 on the wire)."""

    def __init__(self, sec: CondensedSection, penalty: float) -> None:
        c = len(sec.capacity)
        self.e = sec.on_wire.astype(float)
        self.kp = penalty * sec.length
        self.cap = sec.capacity
        self.h = np.zeros(c) if sec.hardening is None else np.asarray(sec.hardening, float)
        self.hard = self.h > 0.0
        self.lam, self.s, self.back = np.zeros(c), np.zeros(c), np.zeros(c)

    def trial(self, w: np.ndarray, d: float) -> np.ndarray:
        return self.lam + self.kp * (d * self.e - w - self.s)

    def traction(self, w: np.ndarray, d: float) -> tuple[np.ndarray, np.ndarray]:
        """The nodes' forces on the tube and their stick flags."""
        tr = self.trial(w, d)
        z = tr - self.back
        st = np.abs(z) <= self.cap
        over = np.abs(z) - self.cap
        h, kp = self.h, self.kp
        return np.where(st, tr, self.back + np.sign(z) * (self.cap + h * over / (kp + h))), st

    def energy(self, w: np.ndarray, d: float) -> float:
        """The trial force's potential: Huber, with a quadratic tail where hardening."""
        y = self.trial(w, d)
        z = y - self.back
        cap, h, kp = self.cap, self.h, self.kp
        over = np.abs(z) - cap
        hub = np.where(over <= 0.0, 0.5 * z * z,
                       cap * np.abs(z) - 0.5 * cap * cap + 0.5 * h * over * over / (kp + h))
        return float(((hub + self.back * y) / kp).sum())

    def stiffness(self, st: np.ndarray) -> np.ndarray:
        """The nodes' tangent (N/mm per mm): kp sticking, kp h / (kp + h) slipping."""
        return self.kp * np.where(st, 1.0, self.h / (self.kp + self.h))

    def update_multipliers(self, t: np.ndarray, st: np.ndarray) -> None:
        """Uzawa: the multipliers take the tractions; a slipping node with a spring keeps the
        step's start (its trial force is the spring's reference; a Coulomb node saturates)."""
        self.lam = np.where(st | ~self.hard, t, self.lam)

    def commit(self, w: np.ndarray, d: float, t: np.ndarray, st: np.ndarray) -> None:
        """End of a step: the springs take the step's slip behind the penalty, the multipliers
        the tractions, the reference the relative displacement (sticking: < creep_tol_mm)."""
        z = self.trial(w, d) - self.back
        slip = np.sign(z) * np.clip(np.abs(z) - self.cap, 0.0, None) / (self.kp + self.h)
        self.back = self.back + np.where(st, 0.0, self.h * slip)
        self.lam = t.copy()
        self.s = d * self.e - w


class _Tangent:
    """Solves with K + diag(node stiffness) (one per stick set): an LU of one stick set, and
    for a set that differs from it at a few nodes the Sherman-Morrison-Woodbury identity on
    those nodes (k solves with the LU and a k x k system instead of a new factorisation)."""

    #: largest number of changed nodes solved by Woodbury rather than a new factorisation
    MAX_CHANGED = 8

    def __init__(self, K: np.ndarray, law: _NodeLaws) -> None:
        self.K, self.law = K, law
        self.st: np.ndarray | None = None
        self.diag = np.zeros(len(K))
        self.lu: Any = None
        self.update: tuple[np.ndarray, np.ndarray, Any] | None = None
        self.update_key: bytes | None = None

    def solve(self, st: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        diag = self.law.stiffness(st)
        changed = np.flatnonzero(st != self.st) if self.st is not None else None
        if changed is None or len(changed) > self.MAX_CHANGED:
            self.lu = lu_factor(self.K + np.diag(diag), check_finite=False)
            self.st, self.diag, self.update, self.update_key = st.copy(), diag, None, None
            changed = np.zeros(0, int)
        y = lu_solve(self.lu, rhs, check_finite=False)
        if not len(changed):
            return np.asarray(y)
        key = st.tobytes()
        if key != self.update_key:
            E = np.zeros((len(st), len(changed)))
            E[changed, np.arange(len(changed))] = 1.0
            Z = lu_solve(self.lu, E, check_finite=False)
            cap = np.diag(1.0 / (diag[changed] - self.diag[changed])) + Z[changed]
            self.update, self.update_key = (changed, Z, lu_factor(cap, check_finite=False)), key
        assert self.update is not None
        idx, Z, cap_lu = self.update
        return np.asarray(y - Z @ lu_solve(cap_lu, y[idx], check_finite=False))


def _newton(K: np.ndarray, law: _NodeLaws, tangent: _Tangent, w: np.ndarray, d: float,
            knorm: float, max_newton: int) -> tuple[np.ndarray, int]:
    """Newton on K w = t(w) at wire displacement ``d`` (mm), Armijo backtracking on the convex
    energy (elastic + the friction potential), which stops the active-set cycling; (w,
    iterations)."""
    prev = np.inf
    for it in range(1, max_newton + 1):
        t, st = law.traction(w, d)
        kw = K @ w
        r = kw - t
        scale = max(1.0, float(np.abs(t).max(initial=0.0)))
        # 1e-8 of the largest traction: the Schur complement's round-off on a near-rigid tube
        # motion (free ends) leaves residuals of ~1e-9 N/mm
        res = float(np.abs(r).max())
        if res <= max(1e-8 * scale, 1e-13 * knorm * max(1.0, float(np.abs(w).max()))):
            return w, it
        if res <= 1e-6 * scale and res >= 0.999 * prev:  # stalled at round-off
            return w, it
        prev = res
        dw = tangent.solve(st, -r)
        kdw = K @ dw
        w = w + _armijo(law, w, dw, d, (w @ kw, w @ kdw, dw @ kdw), float(r @ dw)) * dw
    raise ConvergenceError(f"pull-out section: Newton did not converge at displacement {d:g} mm")


def _armijo(law: _NodeLaws, w: np.ndarray, dw: np.ndarray, d: float,
            quad: tuple[float, float, float], slope: float) -> float:
    """Backtracking step length on the energy along w + a dw; ``quad`` = (w K w, w K dw,
    dw K dw) gives the elastic part in O(c) a trial. Near convergence the energy's decrease is
    below round-off: a full step."""
    wkw, wkd, dkd = (float(v) for v in quad)

    def energy(a: float) -> float:
        return 0.5 * (wkw + a * (2.0 * wkd + a * dkd)) + law.energy(w + a * dw, d)

    return armijo(energy, slope)


def armijo(energy: Callable[[float], float], slope: float) -> float:
    """Step length a along a Newton direction by backtracking (halving from 1) until the
    convex ``energy(a)`` falls by 1e-4 a ``slope`` (``slope``: the energy's derivative at 0,
    negative); below 1e-6 the decrease is under round-off (near convergence): a full step.

    Examples
    --------
    >>> armijo(lambda a: (a - 0.2) ** 2, -0.4)   # the full step overshoots; 1/4 is accepted
    0.25
    """
    e0, alpha = energy(0.0), 1.0
    while alpha > 1e-6 and energy(alpha) > e0 + 1e-4 * alpha * slope:
        alpha *= 0.5
    return alpha if alpha > 1e-6 else 1.0
