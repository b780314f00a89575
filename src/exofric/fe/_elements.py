"""Lagrange quadrilaterals (quad4, quad9), Gauss quadrature and reference gradients.

Everything is evaluated once per mesh and kept: shape-function gradients with
respect to the undeformed coordinates and the quadrature weights times the
reference Jacobian, for all elements and quadrature points at once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exofric._validate import checked_init
from exofric.errors import InputError

__all__ = ["ReferenceData", "reference_data", "lagrange_1d", "shape_2d", "pressure_basis"]


def lagrange_1d(order: int, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """1D Lagrange shape functions on [-1, 1] with equispaced nodes and derivatives.

    Returns ``(N, dN)`` of shape ``(order + 1, len(x))``.

    Parameters
    ----------
    order : {1, 2}
        Polynomial order (2 nodes or 3 nodes).
    x : array-like
        Points in the reference coordinate, in [-1, 1] (unitless).

    Returns
    -------
    N, dN : ndarray (order + 1, len(x))
        Shape functions and their derivatives d/dx.

    Examples
    --------
    >>> import numpy as np
    >>> N, dN = lagrange_1d(2, np.array([0.0]))
    >>> N.ravel().tolist()
    [-0.0, 1.0, 0.0]
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

    Parameters
    ----------
    order : {1, 2}
        Element order (quad4 or quad9).
    xi, eta : ndarray (q,)
        Reference coordinates of the points, in [-1, 1] (unitless).

    Returns
    -------
    N : ndarray (q, n)
    dN : ndarray (q, n, 2)
        Derivatives w.r.t. (xi, eta).

    Examples
    --------
    >>> import numpy as np
    >>> N, dN = shape_2d(2, np.array([0.0]), np.array([0.0]))
    >>> N.shape, dN.shape, float(N[0, 4])
    ((1, 9), (1, 9, 2), 1.0)
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
    """Discontinuous pressure basis at points: ``[1, xi, eta]`` (order 2) or ``[1]`` (order 1).

    Parameters
    ----------
    order : {1, 2}
        Element order of the displacement field.
    xi, eta : ndarray (q,)
        Reference coordinates of the points, in [-1, 1] (unitless).

    Returns
    -------
    ndarray (q, m)
        Basis values, ``m = 3`` (order 2) or 1 (order 1).

    Examples
    --------
    >>> import numpy as np
    >>> pressure_basis(2, np.array([0.5]), np.array([0.25])).tolist()
    [[1.0, 0.5, 0.25]]
    """
    one = np.ones_like(np.asarray(xi, dtype=float))
    return np.stack([one, xi, eta], axis=1) if order == 2 else one[:, None]


@checked_init
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

    Examples
    --------
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(2.485, 4.15, 2, 4)
    >>> reference_data(m.nodes, m.elements, 2, 3).w.shape
    (8, 9)
    """

    dNdX: np.ndarray
    w: np.ndarray
    N: np.ndarray
    Np: np.ndarray
    Minv: np.ndarray


def reference_data(
    nodes: np.ndarray, elements: np.ndarray, order: int, n_gauss: int
) -> ReferenceData:
    """Gradients, weights and pressure mass matrices for all elements (vectorised).

    Parameters
    ----------
    nodes : ndarray (n, 2)
        Undeformed node coordinates (mm).
    elements : ndarray (e, (order + 1)^2)
        Element connectivity.
    order : {1, 2}
        Element order (quad4 or quad9).
    n_gauss : int
        Gauss points per direction (>= 1).

    Returns
    -------
    ReferenceData

    Raises
    ------
    InputError
        If an element is inverted or degenerate.

    Examples
    --------
    >>> import math
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(2.485, 4.15, 2, 4)  # quarter annulus
    >>> rd = reference_data(m.nodes, m.elements, 2, 3)
    >>> bool(abs(rd.w.sum() - math.pi / 4 * (4.15**2 - 2.485**2)) < 1e-3)  # area (mm^2)
    True
    """
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
