"""Follower pressure on the cavity as the potential ``-P * A(x)``.

The area enclosed by the deformed inner surface, ``A = 1/2 oint (x dy - y dx)``,
is for Lagrange edges an exact quadratic form of the current nodal coordinates:
``A = 1/2 x^T H x`` with a constant, symmetric, sparse ``H``. The pressure force is
therefore ``P H x`` and its consistent tangent ``-P H`` is exact and symmetric
(the load is conservative). Segments on symmetry lines through the origin add
nothing to the integral, so ``A`` of a quarter or half model is the quarter or
half cavity area when the origin lies on the symmetry planes.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from exofric.fe._elements import lagrange_1d

__all__ = ["area_hessian", "enclosed_area"]


def _edge_matrix(order: int) -> np.ndarray:
    """S = 1/2 (Q - Q^T) with Q_ab = int_{-1}^{1} N_a N_b' dxi (exact Gauss rule)."""
    g, w = np.polynomial.legendre.leggauss(order + 1)
    N, dN = lagrange_1d(order, g)
    Q = np.einsum("q,aq,bq->ab", w, N, dN)
    return 0.5 * (Q - Q.T)


def area_hessian(edges: np.ndarray, n_nodes: int) -> sp.csr_matrix:
    """Constant Hessian H (2n x 2n) with ``A = 1/2 x^T H x`` for edges ordered counter-clockwise.

    Parameters
    ----------
    edges : ndarray (m, order + 1)
        Node indices of each boundary edge, oriented so the enclosed region is on the left.
    n_nodes : int
        Number of nodes (dofs are ``2 node + component``).

    Returns
    -------
    scipy.sparse.csr_matrix (2 n_nodes, 2 n_nodes)
        H (unitless); ``1/2 x^T H x`` is in mm^2 for ``x`` in mm.

    Examples
    --------
    >>> import math
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(2.485, 4.15, 2, 4)  # quarter annulus
    >>> H = area_hessian(m.boundary_edges("outer"), m.n_nodes)
    >>> abs(enclosed_area(H, m.nodes.ravel()) - math.pi / 4 * 4.15**2) < 1e-2  # mm^2
    True
    """
    order = edges.shape[1] - 1
    S = _edge_matrix(order)
    xa = 2 * edges  # x dofs
    ya = 2 * edges + 1
    rows = [
        xa[:, :, None] * np.ones_like(ya[:, None, :]),
        ya[:, :, None] * np.ones_like(xa[:, None, :]),
    ]
    cols = [
        np.ones_like(xa[:, :, None]) * ya[:, None, :],
        np.ones_like(ya[:, :, None]) * xa[:, None, :],
    ]
    vals = [
        np.broadcast_to(S, (len(edges),) + S.shape),
        np.broadcast_to(S.T, (len(edges),) + S.shape),
    ]
    r = np.concatenate([a.ravel() for a in rows])
    c = np.concatenate([a.ravel() for a in cols])
    v = np.concatenate([a.ravel() for a in vals])
    return sp.csr_matrix((v, (r, c)), shape=(2 * n_nodes, 2 * n_nodes))


def enclosed_area(H: sp.csr_matrix, x: np.ndarray) -> float:
    """Area ``1/2 x^T H x`` (mm^2) for the flattened current coordinates ``x``.

    Parameters
    ----------
    H : scipy.sparse.csr_matrix
        The constant Hessian from :func:`area_hessian`.
    x : ndarray (2 n,)
        Flattened current node coordinates (mm).

    Returns
    -------
    float
        Area (mm^2) swept by the edges from the origin (the cavity area when the edges
        close it together with the symmetry planes).

    Examples
    --------
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(2.485, 4.15, 2, 4)
    >>> H = area_hessian(m.boundary_edges("outer"), m.n_nodes)
    >>> round(enclosed_area(H, m.nodes.ravel()), 2)
    13.53
    """
    return 0.5 * float(x @ (H @ x))
