"""Frictionless penalty contact of a deformable surface with rigid circles.

Contact points are the surface nodes (nodal quadrature: Simpson weights
``L/6, 2L/3, L/6`` on quadratic edges, ``L/2, L/2`` on linear ones), so the
initially touching node is always a contact point. For a node at ``x`` with
tributary reference length ``w`` and gap ``g`` (negative = penetration), the
penalty energy ``1/2 eps w <-g>^2`` gives the force ``eps w <-g> (-grad g)`` and
the exact tangent ``eps w (grad g grad g^T - <-g> grad^2 g)`` with
``grad^2 |x - c| = (I - n n^T) / |x - c|``. A node with ``g <= 0`` is active
(equality included, so a node that exactly touches already carries stiffness).

Units: mm, N per mm depth; ``eps`` in N/mm^3 (contact pressure MPa per mm of
penetration).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exofric.fe._elements import lagrange_1d

__all__ = ["RigidCircle", "ContactState", "nodal_weights", "evaluate_contact"]


@dataclass(frozen=True)
class RigidCircle:
    """A rigid circular obstacle.

    Attributes
    ----------
    center : tuple of float
        Centre (mm).
    radius : float
        Radius (mm).
    inside : bool
        True if the body is inside the circle (the hole), False if outside (the wire).
    name : str
        Label.

    Examples
    --------
    >>> hole = RigidCircle((0.0, 0.0), 5.0, inside=True, name="hole")
    >>> hole.radius
    5.0
    """

    center: tuple[float, float]
    radius: float
    inside: bool
    name: str = ""


@dataclass
class ContactState:
    """Per-node contact results for one obstacle (nodes = the contact candidates).

    Parameters
    ----------
    energy : float
        Penalty energy (N mm per mm depth, i.e. N).
    force : ndarray (m, 2)
        Contact force on the body at each node (N per mm depth).
    blocks : ndarray (m, 2, 2)
        Nodal tangent blocks (N/mm per mm depth).
    gap : ndarray (m,)
        Signed gap (mm); negative is penetration.
    active : ndarray of bool (m,)
        Nodes in contact (gap < 0).

    Examples
    --------
    >>> import numpy as np
    >>> hole = RigidCircle((0.0, 0.0), 5.0, inside=True)
    >>> st = evaluate_contact(np.array([[0.0, 5.01]]), np.array([1.0]), hole, 1e5)
    >>> st.active.tolist(), round(float(st.force[0, 1]))
    ([True], -1000)
    """

    energy: float
    force: np.ndarray  # (m, 2) force ON the body (N per mm depth)
    blocks: np.ndarray  # (m, 2, 2) tangent blocks (N/mm per mm depth)
    gap: np.ndarray  # (m,) signed gap (mm), negative = penetration
    active: np.ndarray  # (m,) bool


def nodal_weights(edges: np.ndarray, nodes: np.ndarray, n_nodes: int) -> np.ndarray:
    """Tributary reference lengths (mm) of every node of the given boundary edges.

    Exact integrals ``int N_a ds`` of the edge shape functions (Gauss rule, 4 points).

    Parameters
    ----------
    edges : ndarray (m, order + 1)
        Node indices of each boundary edge.
    nodes : ndarray (n, 2)
        Undeformed node coordinates (mm).
    n_nodes : int
        Length of the result (all nodes; nodes off the edges get 0).

    Returns
    -------
    ndarray (n_nodes,)
        Tributary lengths (mm).

    Examples
    --------
    >>> import math
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(2.485, 4.15, 2, 4)  # quarter annulus
    >>> w = nodal_weights(m.boundary_edges("outer"), m.nodes, m.n_nodes)
    >>> bool(abs(w.sum() - math.pi / 2 * 4.15) < 1e-3)  # the quarter arc (mm)
    True
    """
    order = edges.shape[1] - 1
    g, gw = np.polynomial.legendre.leggauss(4)
    N, dN = lagrange_1d(order, g)
    X = nodes[edges]  # (m, k, 2)
    dX = np.einsum("mka,kq->mqa", X, dN)
    jac = np.hypot(dX[..., 0], dX[..., 1])  # (m, q)
    w_edge = np.einsum("q,kq,mq->mk", gw, N, jac)
    return np.bincount(edges.ravel(), weights=w_edge.ravel(), minlength=n_nodes)


def evaluate_contact(
    x: np.ndarray, weights: np.ndarray, circle: RigidCircle, eps: float, tangent: bool = True
) -> ContactState:
    """Penalty contact of points ``x`` (m, 2) with tributary ``weights`` (m,) against ``circle``.

    Parameters
    ----------
    x : ndarray (m, 2)
        Current coordinates of the candidate nodes (mm).
    weights : ndarray (m,)
        Tributary lengths of the nodes (mm), from :func:`nodal_weights`.
    circle : RigidCircle
        The obstacle.
    eps : float
        Penalty stiffness (N/mm^3: contact pressure in MPa per mm of penetration), > 0.
    tangent : bool
        Also compute the tangent blocks (otherwise ``blocks`` is zeros).

    Returns
    -------
    ContactState

    Examples
    --------
    >>> import numpy as np
    >>> hole = RigidCircle((0.0, 0.0), 5.0, inside=True)
    >>> st = evaluate_contact(np.array([[0.0, 5.01], [0.0, 4.0]]), np.ones(2), hole, 1e5)
    >>> st.gap.round(3).tolist(), st.active.tolist()
    ([-0.01, 1.0], [True, False])
    """
    d = x - np.asarray(circle.center)
    dist = np.hypot(d[:, 0], d[:, 1])
    n = d / dist[:, None]
    if circle.inside:
        gap = circle.radius - dist
        grad = -n
        hess_sign = -1.0  # grad^2 g = -(I - nn)/|d|
    else:
        gap = dist - circle.radius
        grad = n
        hess_sign = 1.0
    active = gap <= 0.0
    phi = np.where(active, -gap, 0.0)
    ew = eps * weights * active
    energy = 0.5 * float(np.sum(ew * phi**2))
    force = (ew * phi)[:, None] * grad  # -dE/dx = eps w phi grad(g)
    blocks = np.zeros((len(x), 2, 2))
    if tangent:
        P = np.eye(2) - np.einsum("mi,mj->mij", n, n)
        blocks = (
            ew[:, None, None] * np.einsum("mi,mj->mij", grad, grad)
            - (ew * phi * hess_sign / dist)[:, None, None] * P
        )
    return ContactState(energy, force, blocks, gap, active)
