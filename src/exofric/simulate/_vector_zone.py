"""The held end zone as the 3-D incremental problem about the squeeze (issue 39, "vector zone").

The scalar zone (:mod:`exofric.simulate._shear_lag`) solves only the axial displacement w next
to a held end face, with a rod modulus E_z = 3 G written in the reference configuration: it
does not see the squeeze's in-plane stretch, which in 3-D makes the zone softer (the held
annulus inflated first loses a fifth to a third of its stiffness; docs/formulation.md section
12). This module solves the zone as the linearised 3-D problem about the squeezed state instead.

**The state.** The squeeze gives the in-plane deformation F2 (and the axial stretch l, 1 in
plane strain) and the mixed pressure p0 at every quadrature point: F0 = diag(F2, l).

**The increment.** A displacement (U_x, U_y, W)(X, z) with gradient H (3 x 3, reference) has the
energy density 1/2 H : (A_iso + p0 d2J) : H plus the mixed volumetric part K/2 g^T M^-1 g with
g = int N_p cof F0 : H (the squeeze's Q2-P1 pressure, condensed per element), and the bore
pressure P, a follower load, adds -P times the second variation of the enclosed volume. A_iso
is the full 3-D tangent of the isochoric Mooney-Rivlin energy C10 (J^-2/3 I1 - 3) + C01
(J^-4/3 I2 - 3) at F0 (closed form). F0 has no z shear, so the tangent couples the components
H_ab, H_zz only among themselves and H_az, H_za only among themselves (z-reflection symmetry).

**Along z.** W at the nodes of linear elements (lumped mass M), U and the pressure per element
(element lengths h): W_,z = D W per element and U_,z = -M^-1 D^T diag(h) U at the nodes. The
singular value decomposition diag(h)^1/2 D M^-1/2 = P S Q^T decouples the stations exactly:
mode j has W = M^-1/2 Q_j w_j(X), U = diag(h)^-1/2 P_j u_j(X), and its energy is that of the
section with

    H = [[grad u, -s_j u], [grad w^T, s_j w]]      (rows x, y, z; columns X, Y, z)

(s_j the singular value, the mode's wavenumber, 1/mm). So each mode is a plane problem in
(u_x, u_y, w) with matrices K0 + s K1 + s^2 K2; it is condensed onto the contact nodes' w and
the modes recombine as in the scalar zone. At s -> 0 the w block is the section's
anti-plane problem (div A grad w) and the u block the squeeze's own tangent.

**Boundary conditions.** Held face: W = 0 (U free, its traction zero); the zone's far face:
W_,z = 0 and U = 0 (the section far from the face, or the middle of a short tube held at both
ends, where U is odd). In the plane: the half model's symmetry line (u_x = 0); the contact
nodes' in-plane displacement held (stuck: the isotropic Coulomb disk holds them while the
axial slip has not started there; holding their normal only, by a penalty, lowered the held
tubes' secants by 0.6-1.8 %, measured once in session 46).
The bore pressure's volume term couples W_,z with the bore's normal displacement: -P int W_,z
u.n dl dz (exact second variation of the enclosed volume, integrated by parts along the
closed bore and along z with the boundary conditions above; end caps neglected).

Checks (tests/test_vector_zone.py): the tangent against differences of the energy; the long
wave against Young's modulus; at s -> 0 the squeeze's tangent and the anti-plane modulus; the
held annulus inflated first against CalculiX (within 1.6 % at bore stretches 1-1.84, where the
scalar zone is -19 to +11 %); the squeezed tube itself, its contacts held and its wire arc
pulled along a prescribed profile, against a 3-D FElupe model on the same mesh extruded
(within 1.4 %, base group and Table 3 test 3 at 0.2-0.6 MPa); the normal-force change next to
the held faces of the 5 mm tube against CalculiX's (within 20 % of the face's, tested).

Neglected: the change of the contact pressures during the pull (the friction capacities are
the squeeze's, as in the section). :func:`normal_force_change` computes it: up next to the held
face the wire moves away from, down next to the other (as in 3-D), up to 20 % of the normal
force at 0.6 MPa; fed into the capacities with the two faces' opposite signs it moves the
zone's force at the first secant by -0.03 / -0.36 / -0.38 % at 0.2 / 0.4 / 0.6 MPa (measured
once, session 46), so it is not fed back. Also neglected: the contact's curvature terms, and
the Ogden and Yeoh tangents (those materials keep the scalar zone).

Units: mm, N, MPa.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from exofric.fe import reference_data
from exofric.simulate._antiplane import CondensedSection, condense

__all__: list[str] = []


def mooney_rivlin_tangent(F: np.ndarray, c10: float, c01: float) -> np.ndarray:
    """d2W/dF dF (MPa) of the isochoric Mooney-Rivlin energy at 3 x 3 deformation gradients.

    W = C10 (J^-2/3 I1 - 3) + C01 (J^-4/3 I2 - 3), I1 = F : F, I2 = (I1^2 - C : C) / 2.

    Parameters
    ----------
    F : ndarray (..., 3, 3)
        Deformation gradients (unitless).
    c10, c01 : float
        Constants (MPa).

    Returns
    -------
    ndarray (..., 3, 3, 3, 3)
        A[..., i, J, k, L] = d2W / dF_iJ dF_kL (MPa).

    Examples
    --------
    >>> A = mooney_rivlin_tangent(np.eye(3), 0.5, 0.1)
    >>> H = np.zeros((3, 3)); H[0, 1] = H[1, 0] = 0.01   # simple shear, small
    >>> round(float(np.einsum("ij,ijkl,kl", H, A, H)) / 0.01 ** 2 / 4, 6)  # G = 2 (C10 + C01)
    1.2
    """
    eye = np.eye(3)
    Fi = np.linalg.inv(F)
    J = np.linalg.det(F)[..., None, None, None, None]
    C = np.einsum("...ki,...kj->...ij", F, F)
    B = np.einsum("...ik,...jk->...ij", F, F)
    I1 = np.einsum("...ij,...ij->...", F, F)[..., None, None, None, None]
    cc = np.einsum("...ij,...ij->...", C, C)[..., None, None, None, None]
    I2 = 0.5 * (I1 ** 2 - cc)
    dJ = J[..., 0, 0] * np.swapaxes(Fi, -1, -2)  # cof F
    d2J = volume_hessian(F)
    dI1 = 2.0 * F
    d2I1 = 2.0 * np.einsum("ik,jl->ijkl", eye, eye)
    FC = np.einsum("...ik,...kj->...ij", F, C)
    dI2 = 2.0 * I1[..., 0, 0] * F - 2.0 * FC
    d2I2 = (4.0 * np.einsum("...ij,...kl->...ijkl", F, F) + I1 * d2I1
            - 2.0 * (np.einsum("ik,...jl->...ijkl", eye, C)
                     + np.einsum("...il,...kj->...ijkl", F, F)
                     + np.einsum("...ik,jl->...ijkl", B, eye)))

    def scaled(a: float, dI: np.ndarray, d2I: np.ndarray, inv: np.ndarray) -> np.ndarray:
        """d2 (J^a I)."""
        g = J ** a
        g1 = a * J ** (a - 1.0)
        g2 = a * (a - 1.0) * J ** (a - 2.0)
        return (g * d2I + g1 * (np.einsum("...ij,...kl->...ijkl", dJ, dI)
                                + np.einsum("...ij,...kl->...ijkl", dI, dJ))
                + inv * (g2 * np.einsum("...ij,...kl->...ijkl", dJ, dJ) + g1 * d2J))

    return c10 * scaled(-2.0 / 3.0, dI1, d2I1, I1) + c01 * scaled(-4.0 / 3.0, dI2, d2I2, I2)


def volume_hessian(F: np.ndarray) -> np.ndarray:
    """d2J / dF dF (unitless) at 3 x 3 deformation gradients, shape (..., 3, 3, 3, 3).

    Examples
    --------
    >>> H = np.diag([0.1, 0.2, 0.3])
    >>> round(float(np.einsum("ij,ijkl,kl", H, volume_hessian(np.eye(3)), H)), 6)  # 2 e2(H)
    0.22
    """
    Fi = np.linalg.inv(F)
    J = np.linalg.det(F)[..., None, None, None, None]
    return J * (np.einsum("...ji,...lk->...ijkl", Fi, Fi)
                - np.einsum("...li,...jk->...ijkl", Fi, Fi))


@dataclass(frozen=True)
class VectorSection:
    """The section's matrices of the vector zone: mode s has K0 + s K1 + s^2 K2 (N/mm per mm).

    Attributes
    ----------
    K0, K1, K2 : sparse (m, m)
        On the free dofs (m of the 3 n nodal dofs u_x, u_y, w).
    contact_w : ndarray of int (c,)
        The contact nodes' w among the free dofs, in the section's contact order.
    R : (R0, R1, R2) of sparse (2 c, m)
        The rows of the contact nodes' (u_x, u_y), held (node-major), so that their in-plane
        reaction in mode s is (R0 + s R1 + s^2 R2) x (N/mm per mm).
    normals : ndarray (c, 2), optional
        Unit normals of the contacts at those nodes, from the obstacle into the tube (the
        reactions' compressive part; :func:`normal_force_change`).
    """

    K0: sp.csr_matrix
    K1: sp.csr_matrix
    K2: sp.csr_matrix
    contact_w: np.ndarray
    R: tuple[sp.csr_matrix, ...]
    normals: np.ndarray | None = None
    #: the zones' contact stiffness and station lengths by (element lengths, held): they do
    #: not depend on the friction coefficients, which a fit varies (:func:`vector_zone_stiffness`)
    zones: dict[tuple[bytes, tuple[bool, bool]], tuple[np.ndarray, np.ndarray]] = field(
        default_factory=dict, repr=False, compare=False)

    def mode(self, s: float) -> np.ndarray:
        """The mode of wavenumber ``s`` (1/mm) condensed on the contact nodes' w (c, c)."""
        return condense((self.K0 + s * self.K1 + (s * s) * self.K2).tocsr(), self.contact_w)


def _assemble(elements: np.ndarray, ke: np.ndarray, n_dofs: int) -> sp.csr_matrix:
    dofs = (3 * elements[:, :, None] + np.arange(3)).reshape(len(elements), -1)
    k = dofs.shape[1]
    rows = np.repeat(dofs, k, axis=1).ravel()
    cols = np.tile(dofs, (1, k)).ravel()
    return sp.csr_matrix((ke.ravel(), (rows, cols)), shape=(n_dofs, n_dofs))


def _bore_coupling(x: np.ndarray, bore: np.ndarray, center: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(rows w, cols u, values) of int N_a N_b n dl on the bore edges (current geometry)."""
    from exofric.fe import lagrange_1d

    g, wq = np.polynomial.legendre.leggauss(4)
    N, dN = lagrange_1d(bore.shape[1] - 1, g)  # (a, q)
    xe = x[bore]  # (m, a, 2)
    t = np.einsum("maj,aq->mqj", xe, dN)  # dx/dxi
    ndl = np.stack([t[..., 1], -t[..., 0]], axis=-1)  # (m, q, 2) times dxi
    mid = np.einsum("maj,aq->mqj", xe, N)
    sign = np.sign(np.einsum("mqj,mqj->mq", ndl, mid - center).sum(axis=1))
    ndl = ndl * sign[:, None, None]  # pointing away from the tube's axis (out of the air)
    vals = np.einsum("q,aq,bq,mqj->mabj", wq, N, N, ndl)
    m, a = bore.shape
    rows = np.broadcast_to((3 * bore + 2)[:, :, None, None], (m, a, a, 2))
    cols = (3 * bore[:, None, :, None] + np.arange(2)) * np.ones((m, a, 1, 1), int)
    return rows.ravel(), cols.ravel(), vals.ravel()


def vector_section(nodes: np.ndarray, elements: np.ndarray, displacement: np.ndarray, *,
                   c10: float, c01: float, bulk_mpa: float, pressure_mpa: float,
                   contact: np.ndarray, bore: np.ndarray, symmetry: np.ndarray,
                   axial_stretch: float = 1.0,
                   tube_center: tuple[float, float] = (0.0, 0.0),
                   mixed_pressure: np.ndarray | None = None,
                   contact_normals: np.ndarray | None = None) -> VectorSection:
    """The vector zone's section matrices about a squeeze state (module docstring).

    Parameters
    ----------
    nodes, elements : ndarray
        The squeeze's reference quad9 mesh (mm).
    displacement : ndarray (n, 2)
        The squeeze's in-plane displacement (mm).
    c10, c01, bulk_mpa : float
        Mooney-Rivlin constants and bulk modulus K (MPa) of the squeeze's energy.
    pressure_mpa : float
        Bore pressure P (MPa).
    contact : ndarray of int (c,)
        Contact nodes, in the order of the section's capacities; held in the plane (stuck).
    bore : ndarray of int (m, 3)
        The bore's edges (quad9 edge nodes).
    symmetry : ndarray of int
        Nodes on the half model's symmetry line (u_x = 0); empty for a full model.
    axial_stretch : float
        The squeeze's axial stretch (1: plane strain).
    tube_center : (float, float)
        A point inside the bore (mm), to orient its normal.
    mixed_pressure : ndarray (e, q), optional
        The state's hydrostatic pressure p0 (MPa, tension positive) at the 3 x 3 Gauss points;
        default: the squeeze's, K M^-1 int Np (J - 1) (for a state that is not the mixed
        solver's, e.g. a closed-form incompressible one).
    contact_normals : ndarray (c, 2), optional
        Unit normals from the obstacles into the tube at the contact nodes, kept for
        :func:`normal_force_change`.

    Returns
    -------
    VectorSection

    Examples
    --------
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(1.0, 2.0, 2, 16, theta1=2 * np.pi)
    >>> bore = m.boundary_edges("inner")
    >>> vs = vector_section(m.nodes, m.elements, 0 * m.nodes, c10=0.5, c01=0.0, bulk_mpa=1e3,
    ...                     pressure_mpa=0.0, contact=m.outer_nodes[:-1], bore=bore,
    ...                     symmetry=np.zeros(0, int))
    >>> # s -> 0: the anti-plane block is G times the Laplacian: w = 1 costs nothing
    >>> bool(abs(vs.mode(1e-9).sum()) < 1e-6)
    True
    """
    rd = reference_data(nodes, elements, 2, 3)
    ne, nq, na = rd.dNdX.shape[:3]
    F = np.zeros((ne, nq, 3, 3))
    F[..., :2, :2] = np.eye(2) + np.einsum("eai,eqaj->eqij", displacement[elements], rd.dNdX)
    F[..., 2, 2] = axial_stretch
    J = np.linalg.det(F)
    cof = J[..., None, None] * np.swapaxes(np.linalg.inv(F), -1, -2)
    # the squeeze's mixed pressure (tension positive): p = K M^-1 int Np (J - 1)
    gp = np.einsum("eq,qm,eq->em", rd.w, rd.Np, J - 1.0)
    p0 = (bulk_mpa * np.einsum("emk,ek->em", rd.Minv, gp)) @ rd.Np.T  # (e, q)
    if mixed_pressure is not None:
        p0 = np.asarray(mixed_pressure, float)
    A = (mooney_rivlin_tangent(F, c10, c01)
         + p0[..., None, None, None, None] * volume_hessian(F)).reshape(ne, nq, 9, 9)
    # B0: H at s = 0 (grad u in rows x, y; grad w in row z); B1: the s-parts (H_az = -u_a,
    # H_zz = w); element dofs node-major (3 a + component)
    B0 = np.zeros((ne, nq, 9, 3 * na))
    B1 = np.zeros((nq, 9, 3 * na))
    for i in range(3):
        for j in range(2):
            B0[:, :, 3 * i + j, i::3] = rd.dNdX[..., j]
    B1[:, 8, 2::3] = rd.N
    B1[:, 2, 0::3] = -rd.N
    B1[:, 5, 1::3] = -rd.N
    B1 = np.broadcast_to(B1, B0.shape)
    AB0 = np.einsum("eqij,eqjb->eqib", A, B0)
    AB1 = np.einsum("eqij,eqjb->eqib", A, B1)
    k0 = np.einsum("eq,eqia,eqib->eab", rd.w, B0, AB0)
    k1 = np.einsum("eq,eqia,eqib->eab", rd.w, B0, AB1)
    k1 = k1 + k1.transpose(0, 2, 1)
    k2 = np.einsum("eq,eqia,eqib->eab", rd.w, B1, AB1)
    # mixed volumetric part: K (G0 + s G1)^T M^-1 (G0 + s G1), G = int Np cof : B
    cf = cof.reshape(ne, nq, 9)
    G0 = np.einsum("eq,qm,eqi,eqia->ema", rd.w, rd.Np, cf, B0)
    G1 = np.einsum("eq,qm,eqi,eqia->ema", rd.w, rd.Np, cf, B1)
    MG0 = np.einsum("emk,eka->ema", rd.Minv, G0)
    MG1 = np.einsum("emk,eka->ema", rd.Minv, G1)
    k0 = k0 + bulk_mpa * np.einsum("ema,emb->eab", G0, MG0)
    v1 = bulk_mpa * np.einsum("ema,emb->eab", G0, MG1)
    k1 = k1 + v1 + v1.transpose(0, 2, 1)
    k2 = k2 + bulk_mpa * np.einsum("ema,emb->eab", G1, MG1)
    n = len(nodes)
    nd = 3 * n
    K0, K1, K2 = (_assemble(elements, k, nd) for k in (k0, k1, k2))
    if pressure_mpa != 0.0:
        from exofric.fe import area_hessian

        x = nodes + displacement
        H2 = area_hessian(bore, n).tocoo()
        if 0.5 * float(x.ravel() @ (H2 @ x.ravel())) < 0.0:
            H2 = -H2
        # in-plane: the squeeze's load stiffness -P l H on the (u_x, u_y) dofs
        r, c = H2.row, H2.col
        K0 = K0 + sp.csr_matrix((-pressure_mpa * axial_stretch * H2.data,
                                 (3 * (r // 2) + r % 2, 3 * (c // 2) + c % 2)), shape=(nd, nd))
        rw, cu, v = _bore_coupling(x, bore, np.asarray(tube_center, float))
        Kc = sp.csr_matrix((-pressure_mpa * v, (rw, cu)), shape=(nd, nd))
        K1 = K1 + Kc + Kc.T
    contact = np.asarray(contact, int)
    held = (3 * contact[:, None] + np.arange(2)).ravel()  # in-plane: stuck
    keep = np.ones(nd, bool)
    keep[np.concatenate([3 * np.asarray(symmetry, int), held])] = False
    pos = np.cumsum(keep) - 1
    R = tuple(K[held][:, keep].tocsr() for K in (K0, K1, K2))
    K0, K1, K2 = (K[keep][:, keep].tocsr() for K in (K0, K1, K2))
    kept = None if contact_normals is None else np.asarray(contact_normals, float)
    return VectorSection(K0, K1, K2, pos[3 * contact + 2], R, kept)


def _z_svd(h: np.ndarray, held: tuple[bool, bool]) -> tuple[np.ndarray, np.ndarray,
                                                             np.ndarray, np.ndarray]:
    """(s, M^1/2 Q, lumped station lengths, diag(h)^1/2 P): :func:`z_modes` and the element
    basis that turns a mode's in-plane force into the elements' forces (N)."""
    h = np.asarray(h, float)
    n = len(h)
    D = np.zeros((n, n + 1))
    D[np.arange(n), np.arange(n)] = -1.0 / h
    D[np.arange(n), np.arange(n) + 1] = 1.0 / h
    m = np.zeros(n + 1)
    np.add.at(m, np.arange(n), 0.5 * h)
    np.add.at(m, np.arange(n) + 1, 0.5 * h)
    keep = np.ones(n + 1, bool)
    keep[0], keep[-1] = not held[0], not held[1]
    D, m = D[:, keep], m[keep]
    P, s, Qt = np.linalg.svd(np.sqrt(h)[:, None] * D / np.sqrt(m)[None, :],
                             full_matrices=False)
    order = np.argsort(s)
    return (s[order], np.sqrt(m)[:, None] * Qt[order].T, m,
            np.sqrt(h)[:, None] * P[:, order])


def z_modes(h: np.ndarray, held: tuple[bool, bool]) -> tuple[np.ndarray, np.ndarray,
                                                              np.ndarray]:
    """(wavenumbers s (1/mm), M^1/2 Q (mm^1/2), lumped station lengths (mm)) of the staggered
    z discretisation: W at the free nodes of linear elements ``h`` (mm), U per element.

    Examples
    --------
    >>> s, MQ, m = z_modes(np.full(40, 0.125), (True, False))
    >>> round(float(s[0]) / (np.pi / 2 / 5.0), 4)   # the slowest mode: sin(pi z / 2 L)
    0.9999
    """
    s, MQ, m, _ = _z_svd(h, held)
    return s, MQ, m


def vector_zone_stiffness(vs: VectorSection, section: CondensedSection, h: np.ndarray,
                          held: tuple[bool, bool]) -> CondensedSection:
    """The zone's contact stiffness (stations x contact nodes, N/mm per mm) and capacities (N)
    for the vector zone (the scalar zone's :func:`~exofric.simulate._shear_lag.zone_stiffness`
    with the modes of this module).

    Examples
    --------
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(1.0, 2.0, 2, 16, theta1=2 * np.pi)
    >>> c = m.outer_nodes[:-1]
    >>> vs = vector_section(m.nodes, m.elements, 0 * m.nodes, c10=0.5, c01=0.0, bulk_mpa=1e3,
    ...                     pressure_mpa=0.0, contact=c, bore=m.boundary_edges("inner"),
    ...                     symmetry=np.zeros(0, int))
    >>> sec = CondensedSection(np.zeros((0, 0)), np.ones(len(c), bool), np.ones(len(c)),
    ...                        np.ones(len(c)))
    >>> vector_zone_stiffness(vs, sec, np.full(4, 0.5), (True, False)).K.shape
    (128, 128)
    """
    key = (np.asarray(h, float).tobytes(), (bool(held[0]), bool(held[1])))
    if key not in vs.zones:
        s, MQ, m = z_modes(h, held)
        kc = np.stack([vs.mode(float(sj)) for sj in s])
        ns, nc = MQ.shape[0], len(vs.contact_w)
        C = np.einsum("aj,bj,jpq->apbq", MQ, MQ, kc).reshape(ns * nc, ns * nc)
        C = 0.5 * (C + C.T)
        C.setflags(write=False)  # shared by every pull from this squeeze
        vs.zones[key] = (C, m)
    C, m = vs.zones[key]
    ns = len(m)
    return CondensedSection(C, np.tile(section.on_wire, ns), np.kron(m, section.capacity),
                            np.kron(m, section.length))


def normal_force_change(vs: VectorSection, h: np.ndarray, held: tuple[bool, bool],
                        w: np.ndarray) -> np.ndarray:
    """The change of each contact node's normal force per z element during the pull (N, the
    model section; compressive positive; elements x contact nodes), from the contact nodes'
    axial displacements ``w`` (mm, stations x contact nodes, as the zone's friction solve
    returns them). The friction solve holds the squeeze's normal forces; this is what the
    vector zone says they become (linear in w).

    Examples
    --------
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(1.0, 2.0, 2, 16, theta1=2 * np.pi)
    >>> c = m.outer_nodes[:-1]
    >>> x = m.nodes[c]
    >>> vs = vector_section(m.nodes, m.elements, 0 * m.nodes, c10=0.5, c01=0.0, bulk_mpa=1e3,
    ...                     pressure_mpa=0.0, contact=c, bore=m.boundary_edges("inner"),
    ...                     symmetry=np.zeros(0, int), contact_normals=-x / 2.0)
    >>> h = np.full(4, 0.5)
    >>> dn = normal_force_change(vs, h, (True, False), np.ones((4, len(c)))).sum(axis=1)
    >>> # a sleeve pulled away from a held face stretches the tube there along z, which then
    >>> # contracts in the plane: the sleeve's normal force falls next to that face
    >>> dn.shape, bool(dn[0] < 0)
    ((4,), True)
    """
    import scipy.sparse.linalg as spla

    if vs.normals is None:
        raise ValueError("normal_force_change needs the contact normals "
                         "(vector_section(..., contact_normals=...))")
    s, MQ, _, HP = _z_svd(h, held)
    nc = len(vs.contact_w)
    inner = np.ones(vs.K0.shape[0], bool)
    inner[vs.contact_w] = False
    W = np.asarray(w, float).reshape(MQ.shape[0], nc)
    rj = np.zeros((len(s), nc))
    for j, sj in enumerate(s):
        wj = MQ[:, j] @ W
        K = (vs.K0 + sj * vs.K1 + (sj * sj) * vs.K2).tocsr()
        x = np.zeros(K.shape[0])
        x[vs.contact_w] = wj
        x[inner] = -spla.splu(K[inner][:, inner].tocsc()).solve(K[inner][:, vs.contact_w] @ wj)
        r = ((vs.R[0] + sj * vs.R[1] + (sj * sj) * vs.R[2]) @ x).reshape(nc, 2)
        rj[j] = np.einsum("pi,pi->p", vs.normals, r)
    return HP @ rj
