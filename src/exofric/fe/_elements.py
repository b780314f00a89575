"""Lagrange quadrilaterals (quad4, quad9), Gauss quadrature and reference gradients.

Everything is evaluated once per mesh and kept: shape-function gradients with
respect to the undeformed coordinates and the quadrature weights times the
reference Jacobian, for all elements and quadrature points at once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exofric.errors import InputError

__all__ = ["ReferenceData", "reference_data", "lagrange_1d", "shape_2d", "pressure_basis"]


def lagrange_1d(order: int, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """1D Lagrange shape functions on [-1, 1] with equispaced nodes and derivatives.

    Returns ``(N, dN)`` of shape ``(order + 1, len(x))``.
    """
    x = np.asarray(x, dtype=float)
    if order == 1:
        return (np.stack([0.5 * (1 - x), 0.5 * (1 + x)]), np.stack([-0.5 + 0 * x, 0.5 + 0 * x]))
    if order == 2:
        return (
            np.stack([0.5 * x * (x - 1), 1 - x**2, 0.5 * x * (x + 1)]),
            np.stack([x - 0.5, -2 * x, x + 0.5]),
        )
    raise InputError(f"element order must be 1 or 2, got {order}")


def shape_2d(order: int, xi: np.ndarray, eta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Tensor-product shape functions ``N (q, n)`` and gradients ``dN (q, n, 2)``.

    Local node ``a = (order + 1) j + i``: ``i`` along xi, ``j`` along eta.
    """
    Nx, dNx = lagrange_1d(order, xi)
    Ny, dNy = lagrange_1d(order, eta)
    n1 = order + 1
    N = np.stack([Nx[i] * Ny[j] for j in range(n1) for i in range(n1)], axis=1)
    dN = np.stack(
        [np.stack([dNx[i] * Ny[j], Nx[i] * dNy[j]], axis=-1) for j in range(n1) for i in range(n1)],
        axis=1,
    )
    return N, dN


def pressure_basis(order: int, xi: np.ndarray, eta: np.ndarray) -> np.ndarray:
    """Discontinuous pressure basis at points: ``[1, xi, eta]`` (order 2) or ``[1]`` (order 1)."""
    one = np.ones_like(np.asarray(xi, dtype=float))
    return np.stack([one, xi, eta], axis=1) if order == 2 else one[:, None]


@dataclass(frozen=True)
class ReferenceData:
    """Per-mesh constants of the element integrals.

    Attributes
    ----------
    dNdX : ndarray (e, q, n, 2)
        Shape-function gradients w.r.t. undeformed coordinates (1/mm).
    w : ndarray (e, q)
        Quadrature weight times reference Jacobian (mm^2 per unit depth).
    N : ndarray (q, n)
        Shape functions at the quadrature points.
    Np : ndarray (q, m)
        Pressure basis at the quadrature points.
    Minv : ndarray (e, m, m)
        Inverse pressure mass matrices (1/mm^2).
    """

    dNdX: np.ndarray
    w: np.ndarray
    N: np.ndarray
    Np: np.ndarray
    Minv: np.ndarray


def reference_data(
    nodes: np.ndarray, elements: np.ndarray, order: int, n_gauss: int
) -> ReferenceData:
    """Gradients, weights and pressure mass matrices for all elements (vectorised)."""
    g, gw = np.polynomial.legendre.leggauss(n_gauss)
    XI, ETA = np.meshgrid(g, g, indexing="xy")
    xi, eta = XI.ravel(), ETA.ravel()
    wq = np.outer(gw, gw).ravel()
    N, dN = shape_2d(order, xi, eta)
    X = nodes[elements]  # (e, n, 2)
    Jac = np.einsum("ena,qnb->eqab", X, dN)  # dX_a / dxi_b
    det = Jac[..., 0, 0] * Jac[..., 1, 1] - Jac[..., 0, 1] * Jac[..., 1, 0]
    if np.any(det <= 0):
        raise InputError("mesh has inverted or degenerate elements (non-positive Jacobian)")
    inv = np.empty_like(Jac)
    inv[..., 0, 0], inv[..., 1, 1] = Jac[..., 1, 1] / det, Jac[..., 0, 0] / det
    inv[..., 0, 1], inv[..., 1, 0] = -Jac[..., 0, 1] / det, -Jac[..., 1, 0] / det
    dNdX = np.einsum("qnb,eqba->eqna", dN, inv)
    w = det * wq
    Np = pressure_basis(order, xi, eta)
    M = np.einsum("eq,qm,qk->emk", w, Np, Np)
    return ReferenceData(dNdX, w, N, Np, np.linalg.inv(M))
