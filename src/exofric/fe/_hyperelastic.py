"""Vectorised plane-strain Mooney-Rivlin (Eq 2) with a mixed u/p volumetric treatment.

Strain energy (ANSYS convention, stretch_z = 1), with ``s = |F|^2`` of the
in-plane deformation gradient F (2x2) and ``J = det F``::

    W_iso = C10 (J^-2/3 (s + 1) - 3) + C01 (J^-4/3 s + J^2/3 - 3)
    U     = (J - 1)^2 / d = K/2 (J - 1)^2,   K = 2/d

(``I1 = s + 1`` and ``I2 = s + J^2`` in plane strain). Because ``dJ/dF = cof F``
is linear in F, stress and tangent follow in closed form from the scalar
derivatives of ``W_iso(s, J)``::

    P = 2 W_s F + W_J cof F
    A = 2 W_sJ (F x cof + cof x F) + W_JJ cof x cof + 2 W_s I + W_J D(cof)

Mixed formulation (``'mixed'``): a discontinuous pressure ``p = Np . p_e``
(Np = [1, xi, eta] for quad9, i.e. Bathe's 9/3 element; [1] for quad4 = Q1/P0)
is condensed element by element. Stationarity of
``int p (J - 1) - p^2 / (2K)`` gives ``p_e = K M^-1 g``, ``g = int Np (J - 1)``,
so the volumetric energy is ``(K/2) g^T M^-1 g`` with the exact tangent
``K G^T M^-1 G + int p D(cof)``, ``G = int Np (cof : grad N)``. ``'displacement'``
evaluates U at every Gauss point instead (this locks for nu -> 0.5; kept to show it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exofric.errors import InputError
from exofric.fe._elements import ReferenceData, reference_data
from exofric.fe._mesh import TubeMesh
from exofric.material import MooneyRivlin

__all__ = ["HyperelasticBody", "mooney_rivlin_plane_strain", "DCOF"]

#: d(cof F)/dF for 2x2 F: cof = [[F11, -F10], [-F01, F00]].
DCOF = np.zeros((2, 2, 2, 2))
DCOF[0, 0, 1, 1] = DCOF[1, 1, 0, 0] = 1.0
DCOF[0, 1, 1, 0] = DCOF[1, 0, 0, 1] = -1.0


def _cof(F: np.ndarray) -> np.ndarray:
    c = np.empty_like(F)
    c[..., 0, 0], c[..., 1, 1] = F[..., 1, 1], F[..., 0, 0]
    c[..., 0, 1], c[..., 1, 0] = -F[..., 1, 0], -F[..., 0, 1]
    return c


#: cof F as a signed permutation of the flattened F = [F00, F01, F10, F11].
_COF_PERM = np.array([3, 2, 1, 0])
_COF_SIGN = np.array([1.0, -1.0, -1.0, 1.0])
_DCOF4 = DCOF.reshape(4, 4)
_I4F = np.eye(4)


def mooney_rivlin_plane_strain(
    F: np.ndarray, c10: float, c01: float, tangent: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Isochoric Mooney-Rivlin energy density, first Piola stress and tangent.

    Parameters
    ----------
    F : ndarray (..., 2, 2)
        In-plane deformation gradients (det > 0).
    c10, c01 : float
        Material constants (MPa).
    tangent : bool
        Also return ``A = dP/dF`` (..., 2, 2, 2, 2).

    Returns
    -------
    W, P, A
        Energy density (MPa = N mm/mm^3), stress (MPa), tangent (MPa).

    Examples
    --------
    >>> import numpy as np
    >>> W, P, A = mooney_rivlin_plane_strain(np.eye(2)[None], 0.6, 0.03)
    >>> float(W[0]), float(abs(P).max()) < 1e-14
    (0.0, True)
    """
    shape = F.shape[:-2]
    f = F.reshape(-1, 4)
    c = f[:, _COF_PERM] * _COF_SIGN  # cof F, flattened
    J = f[:, 0] * f[:, 3] - f[:, 1] * f[:, 2]
    s = np.einsum("pi,pi->p", f, f)
    jm13 = 1.0 / np.cbrt(J)  # J^-1/3
    j23 = jm13 * jm13  # J^-2/3
    j43 = j23 * j23  # J^-4/3
    W = c10 * (j23 * (s + 1.0) - 3.0) + c01 * (j43 * s + J * jm13 - 3.0)
    Ws = c10 * j23 + c01 * j43
    iJ = 1.0 / J
    WJ = (-2.0 / 3.0 * c10 * j23 * iJ * (s + 1.0) - 4.0 / 3.0 * c01 * j43 * iJ * s
          + 2.0 / 3.0 * c01 * jm13)
    P = 2.0 * Ws[:, None] * f + WJ[:, None] * c
    if not tangent:
        return W.reshape(shape), P.reshape(*shape, 2, 2), None
    WsJ = (-2.0 / 3.0 * c10 * j23 - 4.0 / 3.0 * c01 * j43) * iJ
    WJJ = (10.0 / 9.0 * c10 * j23 * (s + 1.0) + 28.0 / 9.0 * c01 * j43 * s) * iJ * iJ \
        - 2.0 / 9.0 * c01 * j43
    fc = f[:, :, None] * c[:, None, :]
    A = (2.0 * WsJ[:, None, None] * (fc + fc.transpose(0, 2, 1))
         + WJJ[:, None, None] * (c[:, :, None] * c[:, None, :])
         + 2.0 * Ws[:, None, None] * _I4F
         + WJ[:, None, None] * _DCOF4)
    return W.reshape(shape), P.reshape(*shape, 2, 2), A.reshape(*shape, 2, 2, 2, 2)


@dataclass
class ElementState:
    """Element-level results of one evaluation (internal to the solver)."""

    energy: float
    fe: np.ndarray  # (e, 2n) element internal forces (N per mm depth)
    ke: np.ndarray | None  # (e, 2n, 2n) element tangents (N/mm per mm depth)
    valid: bool  # False if any J <= 0 (inverted element)


class HyperelasticBody:
    """A meshed Mooney-Rivlin body in plane strain (precomputed element data).

    Parameters
    ----------
    mesh : TubeMesh
        The mesh (mm).
    material : MooneyRivlin
        Constants C10, C01 (MPa) and d (1/MPa).
    formulation : {'mixed', 'displacement'}
        Mixed u/p (default; locking-free) or plain displacement (locks).
    n_gauss : int, optional
        Gauss points per direction (default 3 for quad9, 2 for quad4).

    Examples
    --------
    >>> import numpy as np
    >>> from exofric.fe import polar_mesh
    >>> from exofric.material import MooneyRivlin
    >>> body = HyperelasticBody(polar_mesh(2.485, 4.15, 2, 4), MooneyRivlin.from_shore(62.5))
    >>> body.max_stretch(np.zeros(2 * 45))  # undeformed (unitless)
    1.0
    """

    def __init__(
        self,
        mesh: TubeMesh,
        material: MooneyRivlin,
        formulation: str = "mixed",
        n_gauss: int | None = None,
    ) -> None:
        if formulation not in ("mixed", "displacement"):
            raise InputError(f"formulation must be 'mixed' or 'displacement', got {formulation!r}")
        self.mesh = mesh
        self.material = material
        self.formulation = formulation
        ng = n_gauss or (3 if mesh.order == 2 else 2)
        self.ref: ReferenceData = reference_data(mesh.nodes, mesh.elements, mesh.order, ng)
        n = mesh.elements.shape[1]
        self.n_local = n
        self.edofs = (2 * mesh.elements[:, :, None] + np.arange(2)).reshape(-1, 2 * n)
        self.K = material.bulk_modulus
        # Reshaped gradients so every contraction below is one batched matmul.
        d = self.ref.dNdX  # (e, q, n, 2)
        ne, nq = d.shape[:2]
        self._dN_nqj = np.ascontiguousarray(d.transpose(0, 2, 1, 3).reshape(ne, n, 2 * nq))
        # Constant B-matrix (total Lagrangian): dF[2i+j] = sum_{b,k} B[2i+j, 2b+k] du[2b+k]
        # with B[2i+j, 2b+k] = delta_ik dN_b/dX_j; wBT carries the quadrature weights.
        B = np.zeros((ne, nq, 4, 2 * n))
        for i in range(2):
            for j in range(2):
                B[:, :, 2 * i + j, i::2] = d[:, :, :, j]
        self._B = B
        self._wBT = np.ascontiguousarray(
            (B * self.ref.w[:, :, None, None]).transpose(0, 3, 1, 2).reshape(ne, 2 * n, 4 * nq))
        self._wNp = np.ascontiguousarray(
            (self.ref.w[:, :, None] * self.ref.Np[None]).transpose(0, 2, 1))  # (e, m, q)

    def deformation_gradient(self, u: np.ndarray) -> np.ndarray:
        """F at every element and quadrature point, shape (e, q, 2, 2).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.

        Returns
        -------
        ndarray (e, q, 2, 2)
            Deformation gradient (unitless).
        """
        ne, n = len(self.edofs), self.n_local
        ue = u[self.edofs].reshape(ne, n, 2).transpose(0, 2, 1)  # (e, i, n)
        g = (ue @ self._dN_nqj).reshape(ne, 2, -1, 2).transpose(0, 2, 1, 3)  # (e, q, i, j)
        return np.eye(2) + g

    def evaluate(self, u: np.ndarray, tangent: bool = True) -> ElementState:
        """Energy, element forces and element tangents at displacement ``u`` (mm).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        tangent : bool
            Also compute the element tangent matrices.

        Returns
        -------
        ElementState
            Energy (N mm per mm depth), element forces (N per mm depth), tangents
            (N/mm per mm depth) and a validity flag (False for an inverted element).
        """
        r = self.ref
        F = self.deformation_gradient(u)
        J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        if np.any(J <= 1e-8) or not np.all(np.isfinite(J)):
            return ElementState(np.inf, np.empty(0), None, False)
        m = self.material
        W, P, A = mooney_rivlin_plane_strain(F, m.c10_mpa, m.c01_mpa, tangent)
        cof = _cof(F)
        ne = len(self.edofs)
        ke = None
        if self.formulation == "mixed":
            g = np.einsum("eq,qm,eq->em", r.w, r.Np, J - 1.0)
            pe = self.K * np.einsum("emk,ek->em", r.Minv, g)
            p = pe @ r.Np.T  # (e, q)
            e_vol = 0.5 * self.K * float(np.einsum("em,em->", g, pe / self.K))
            P = P + p[..., None, None] * cof
            if tangent:
                assert A is not None
                A = A + p[..., None, None, None, None] * DCOF
                cofB = cof.reshape(ne, -1, 1, 4) @ self._B  # (e, q, 1, 2n): dJ/du
                G = self._wNp @ cofB[:, :, 0, :]  # (e, m, 2n)
                ke = self.K * (G.transpose(0, 2, 1) @ (r.Minv @ G))
        else:
            e_vol = float(np.einsum("eq,eq->", r.w, 0.5 * self.K * (J - 1.0) ** 2))
            P = P + (self.K * (J - 1.0))[..., None, None] * cof
            if tangent:
                assert A is not None
                A = A + self.K * (
                    np.einsum("...ij,...kl->...ijkl", cof, cof)
                    + (J - 1.0)[..., None, None, None, None] * DCOF
                )
        energy = float(np.einsum("eq,eq->", r.w, W)) + e_vol
        nq = P.shape[1]
        fe = (self._wBT @ P.reshape(ne, 4 * nq, 1))[..., 0]  # sum_q w B^T P
        if tangent:
            assert A is not None
            BD = (A.reshape(ne, nq, 4, 4) @ self._B).reshape(ne, 4 * nq, -1)
            kk = self._wBT @ BD  # sum_q w B^T A B
            ke = kk if ke is None else ke + kk
        return ElementState(energy, fe, ke, True)

    def max_stretch(self, u: np.ndarray) -> float:
        """Largest in-plane principal stretch over all quadrature points at ``u``.

        From the eigenvalues of C = F^T F (2x2, closed form): lambda^2 = (tr C + sqrt(tr C^2
        - 4 det C)) / 2 with det C = J^2.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.

        Returns
        -------
        float
            Largest principal stretch (unitless).
        """
        F = self.deformation_gradient(u)
        C = np.einsum("...ki,...kj->...ij", F, F)
        tr = C[..., 0, 0] + C[..., 1, 1]
        det = C[..., 0, 0] * C[..., 1, 1] - C[..., 0, 1] * C[..., 1, 0]
        lam2 = 0.5 * (tr + np.sqrt(np.maximum(tr * tr - 4.0 * det, 0.0)))
        return float(np.sqrt(lam2.max()))

    def element_pressure(self, u: np.ndarray) -> np.ndarray:
        """Hydrostatic pressure field p (MPa, tension positive) at quadrature points (e, q).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        """
        F = self.deformation_gradient(u)
        J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        r = self.ref
        if self.formulation == "mixed":
            g = np.einsum("eq,qm,eq->em", r.w, r.Np, J - 1.0)
            return (self.K * np.einsum("emk,ek->em", r.Minv, g)) @ r.Np.T
        return self.K * (J - 1.0)

    def cauchy_stress(self, u: np.ndarray) -> np.ndarray:
        """Cauchy stress (MPa) at quadrature points: (e, q, 4) = [sxx, syy, sxy, szz].

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        """
        F = self.deformation_gradient(u)
        J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        s = np.einsum("...ij,...ij->...", F, F)
        m = self.material
        _, P, _ = mooney_rivlin_plane_strain(F, m.c10_mpa, m.c01_mpa, tangent=False)
        p = self.element_pressure(u)
        P = P + p[..., None, None] * _cof(F)
        sig = np.einsum("...ij,...kj->...ik", P, F) / J[..., None, None]
        j23, j43 = J ** (-2.0 / 3.0), J ** (-4.0 / 3.0)
        szz = (
            m.c10_mpa * j23 * (2.0 - 2.0 / 3.0 * (s + 1.0))
            + m.c01_mpa * j43 * (2.0 * s - 4.0 / 3.0 * (s + J**2))
        ) / J + p
        return np.stack([sig[..., 0, 0], sig[..., 1, 1], sig[..., 0, 1], szz], axis=-1)


def von_mises(stress: np.ndarray) -> np.ndarray:
    """Von Mises stress (MPa) from ``[sxx, syy, sxy, szz]`` in the last axis.

    Parameters
    ----------
    stress : ndarray (..., 4)
        Cauchy stress components ``[sxx, syy, sxy, szz]`` (MPa).

    Returns
    -------
    ndarray (...)
        Von Mises stress (MPa).

    Examples
    --------
    >>> import numpy as np
    >>> float(von_mises(np.array([1.0, 0.0, 0.0, 0.0])))  # uniaxial 1 MPa
    1.0
    """
    sxx, syy, sxy, szz = np.moveaxis(stress, -1, 0)
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * sxy**2)
