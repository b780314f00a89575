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

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from exofric._validate import checked_init, unchecked
from exofric.fe._elements import lagrange_1d

__all__ = ["RigidCircle", "ContactState", "FrictionState", "nodal_weights", "evaluate_contact",
           "evaluate_friction", "polar_angle", "slip_geometry", "active_set_direction",
           "StickSlipModel", "friction_bound_change"]

#: The refined direction is kept only if rhs . d > _DESCENT_COS |rhs| |d|, i.e. it descends the
#: energy (an indefinite tangent far from equilibrium can make the active-set solution an
#: ascent direction).
_DESCENT_COS = 1e-6


@checked_init
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


@checked_init
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
        P = np.eye(2) - n[:, :, None] * n[:, None, :]
        blocks = (
            ew[:, None, None] * (grad[:, :, None] * grad[:, None, :])
            - (ew * phi * hess_sign / dist)[:, None, None] * P
        )
    return unchecked(ContactState, energy, force, blocks, gap, active)  # per iteration


@checked_init
@dataclass
class FrictionState:
    """Per-node Coulomb friction of one obstacle at a trial state (nodes = contact candidates).

    Tangential slip is measured on the rigid circle: a node's tangential gap is the arc
    ``g_t = R (theta - theta_a)`` between the polar angle ``theta`` of its projection on the
    circle and its anchor ``theta_a`` (where it sticks; carried from load step to load step).

    Parameters
    ----------
    energy : float
        Incremental pseudo-energy of the tangential penalty at the current slip bound (N mm
        per mm depth): ``eps_t w g_t^2 / 2`` sticking, ``B |g_t| - B^2 / (2 eps_t w)``
        slipping (``B = mu F_n``); its gradient is the tangential force at a fixed bound.
    force : ndarray (m, 2)
        Tangential contact force on the body at each node (N per mm depth).
    blocks : ndarray (m, 2, 2)
        Nodal tangent blocks (N/mm per mm depth); not symmetric where a node slips.
    traction : ndarray (m,)
        Signed tangential force ``T`` (N per mm depth): the force on the body is
        ``-T R grad(theta)``, i.e. ``T > 0`` opposes motion toward increasing ``theta``.
    stick : ndarray of bool (m,)
        Active nodes that stick (``|T| < mu F_n``; in slip ``|T| = mu F_n``).
    theta : ndarray (m,)
        Polar angle of each node seen from the circle's centre (rad).

    Examples
    --------
    >>> import numpy as np
    >>> hole = RigidCircle((0.0, 0.0), 5.0, inside=True)
    >>> x = np.array([[0.05, -5.01]])          # ~0.01 mm in, 0.05 mm past its anchor
    >>> n = evaluate_contact(x, np.ones(1), hole, 1e5)
    >>> f = evaluate_friction(x, np.ones(1), hole, 1e5, 1e5, 0.3, np.array([-np.pi / 2]), n)
    >>> f.stick.tolist(), round(float(f.force[0, 0]))  # slips: mu F_n = 0.3 x 1025 N/mm
    ([False], -307)
    """

    energy: float
    force: np.ndarray
    blocks: np.ndarray
    traction: np.ndarray
    stick: np.ndarray
    theta: np.ndarray


#: A node whose trial force is within this fraction of the Coulomb bound counts as slipping:
#: a node that slid in the last step sits exactly on the bound at the start of the next one
#: (its anchor is moved so), and the slip branch of the tangent lets it keep sliding where the
#: stick branch (a stiff spring) would make Newton oscillate between the two (set on the base
#: group: failed attempts and iterations fall by half).
_SLIP_TOL = 1e-6


def polar_angle(x: np.ndarray, circle: RigidCircle) -> np.ndarray:
    """Polar angle (rad) of points ``x`` (m, 2) seen from the centre of ``circle``.

    Parameters
    ----------
    x : ndarray (m, 2)
        Points (mm).
    circle : RigidCircle
        The circle whose centre is the origin of the angles.

    Returns
    -------
    ndarray (m,)
        Angles in (-pi, pi] (rad).

    Examples
    --------
    >>> import numpy as np
    >>> polar_angle(np.array([[0.0, -1.0]]), RigidCircle((0.0, 0.0), 5.0, True)).tolist()
    [-1.5707963267948966]
    """
    d = x - np.asarray(circle.center)
    return np.arctan2(d[:, 1], d[:, 0])


def evaluate_friction(
    x: np.ndarray, weights: np.ndarray, circle: RigidCircle, eps: float, eps_t: float,
    mu: float, anchor: np.ndarray, normal: ContactState, tangent: bool = True,
    bound: np.ndarray | None = None, coupled: bool = True,
) -> FrictionState:
    """Coulomb friction (penalty regularised, return map) of points ``x`` on ``circle``.

    The trial force ``T* = eps_t w g_t`` (``g_t = R (theta - theta_a)``, the arc from the
    anchor; angles wrapped to (-pi, pi]) is returned to the Coulomb cone ``|T| <= mu F_n``
    (``F_n = eps w <-g>`` the node's normal force from ``normal``): stick ``T = T*`` if
    ``|T*| <= mu F_n``, else slip ``T = mu F_n sign(T*)``. The force on the body is
    ``f = -T R grad(theta)`` with ``grad(theta) = t / r`` (``t`` the unit tangent
    toward increasing theta, ``r`` the distance from the centre). The tangent blocks
    ``d(-f)/dx`` are exact (consistent):

    * stick: ``eps_t w R^2 grad(theta) grad(theta)^T + T R H``;
    * slip: ``mu sign(T*) R grad(theta) dF_n/dx^T + T R H`` (not symmetric),

    with ``H`` the Hessian of theta and ``dF_n/dx = -eps w grad(g)``.

    Parameters
    ----------
    x : ndarray (m, 2)
        Current coordinates of the candidate nodes (mm).
    weights : ndarray (m,)
        Tributary lengths (mm).
    circle : RigidCircle
        The obstacle.
    eps : float
        Normal penalty of ``normal`` (N/mm^3).
    eps_t : float
        Tangential penalty (N/mm^3: shear traction MPa per mm of elastic slip), > 0.
    mu : float
        Coulomb coefficient (unitless, >= 0).
    anchor : ndarray (m,)
        Anchor angles theta_a (rad) carried from the last converged state.
    normal : ContactState
        The normal contact of the same nodes (:func:`evaluate_contact` with ``tangent`` as
        here), giving ``F_n``, the gap gradient and the active set.
    tangent : bool
        Also compute the tangent blocks (otherwise zeros).
    bound : ndarray (m,), optional
        A given slip bound per node (N per mm depth) instead of ``mu F_n``: the Tresca
        problem of one fixed-point iteration on the bound. Friction then acts wherever the
        bound is positive, the energy is an exact potential of the force (convex in the
        slip) and, unless ``coupled``, the blocks are symmetric (no ``dF_n/dx`` term).
    coupled : bool
        Include the ``dF_n/dx`` slip term in the blocks also with a given ``bound``: the
        Coulomb problem's consistent tangent at a state whose bound is ``mu F_n`` (the
        solver's base points; see :meth:`exofric.fe.SqueezeProblem.refresh`).

    Returns
    -------
    FrictionState

    Examples
    --------
    >>> import numpy as np
    >>> wire = RigidCircle((0.0, 4.0), 0.8, inside=False)
    >>> x = np.array([[0.0, 3.2005]])                # 0.0005 mm into the wire, at its anchor
    >>> n = evaluate_contact(x, np.ones(1), wire, 1e5)
    >>> f = evaluate_friction(x, np.ones(1), wire, 1e5, 1e5, 0.3, np.array([-np.pi / 2]), n)
    >>> f.stick.tolist(), float(f.traction[0])       # no slip yet: sticks without force
    ([True], 0.0)
    """
    frozen = bound is not None
    if bound is None:
        on, bound = normal.active, mu * np.linalg.norm(normal.force, axis=1)  # mu eps w <-g>
    else:
        on = bound > 0.0  # nodes that can carry friction
    geo = _SlipGeometry(x, weights, circle, eps, eps_t, anchor, normal.active, tangent)
    energy, force, blocks, T, stick = geo.terms(mu if coupled or not frozen else 0.0, bound, on)
    return unchecked(FrictionState, energy, force, blocks, T, stick, geo.theta)


class _SlipGeometry:
    """What the return map of :func:`evaluate_friction` needs of the nodes' positions, once.

    ``theta`` (rad), ``gt = R (theta - theta_a)`` (mm), ``gth = grad(theta)`` (1/mm),
    ``kw = eps_t w`` (N/mm^2) and, with ``tangent``, the Hessian ``hess`` of theta (1/mm^2)
    and ``dfn = dF_n/dx = -eps w grad(g)`` on the ``active`` nodes (N/mm^2).
    """

    def __init__(self, x: np.ndarray, weights: np.ndarray, circle: RigidCircle, eps: float,
                 eps_t: float, anchor: np.ndarray, active: np.ndarray, tangent: bool) -> None:
        d = x - np.asarray(circle.center)
        self.theta, dth, self.gth = slip_geometry(x, circle, anchor)
        self.rc = circle.radius
        self.gt = self.rc * dth
        self.kw = eps_t * weights
        self.tangent = tangent
        if tangent:
            self.hess = _theta_hessian(d)
            self.dfn = -(eps * weights * active)[:, None] * _gap_grad(d, circle)

    def terms(self, mu_b: float, bound: np.ndarray, on: np.ndarray
              ) -> tuple[float, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(energy, force, blocks, traction, stick) of the return map at the slip bounds
        ``bound`` on the nodes ``on``; ``mu_b`` the coefficient of the coupled slip block."""
        gt, gth, kw, rc = self.gt, self.gth, self.kw, self.rc
        trial = kw * gt
        stick = on & (np.abs(trial) < (1.0 - _SLIP_TOL) * bound)
        sgn = np.sign(trial)
        T = np.where(stick, trial, np.where(on, bound * sgn, 0.0))
        force = -(T * rc)[:, None] * gth
        slip = on & ~stick
        energy = float(np.sum(np.where(stick, 0.5 * kw * gt**2, 0.0))
                       + np.sum(np.where(slip, bound * np.abs(gt) - bound**2 / (2.0 * kw), 0.0)))
        if not self.tangent:
            return energy, force, np.zeros((len(gt), 2, 2)), T, stick
        # stick: kw rc^2 gth gth^T; slip: mu_b sgn rc gth dfn^T; both: T rc hess(theta)
        c_stick = np.where(stick, kw * rc**2, 0.0)[:, None]
        c_slip = np.where(slip, mu_b * sgn * rc, 0.0)[:, None]
        blocks = gth[:, :, None] * (c_stick * gth + c_slip * self.dfn)[:, None, :]
        blocks += (T * rc)[:, None, None] * self.hess
        return energy, force, blocks, T, stick


def friction_bound_change(
    x: np.ndarray, weights: np.ndarray, circle: RigidCircle, eps: float, eps_t: float,
    mu: float, anchor: np.ndarray, bounds: tuple[np.ndarray, np.ndarray], tangent: bool,
) -> tuple[float, np.ndarray, np.ndarray]:
    """Change of the frozen-bound friction terms when the bounds change (issue 37).

    :func:`evaluate_friction` with ``bound=bounds[1]`` minus with ``bound=bounds[0]`` (the
    coupled tangent), at the same positions: what a refresh of the bounds does to an
    evaluation (:meth:`exofric.fe.SqueezeProblem.patch_refreshed`), with the geometry
    computed once.

    Parameters
    ----------
    x : ndarray (m, 2)
        Current coordinates of the candidate nodes (mm).
    weights : ndarray (m,)
        Tributary lengths (mm).
    circle : RigidCircle
        The obstacle.
    eps, eps_t : float
        Normal and tangential penalties (N/mm^3).
    mu : float
        Coulomb coefficient (unitless).
    anchor : ndarray (m,)
        Anchor angles (rad).
    bounds : tuple of ndarray (m,)
        The old and the new slip bounds (N per mm depth).
    tangent : bool
        Also the change of the tangent blocks (otherwise zeros).

    Returns
    -------
    energy : float
        Change of the energy (N mm per mm depth).
    force : ndarray (m, 2)
        Change of the friction force on the body (N per mm depth).
    blocks : ndarray (m, 2, 2)
        Change of the tangent blocks (N/mm per mm depth).

    Examples
    --------
    >>> import numpy as np
    >>> hole = RigidCircle((0.0, 0.0), 5.0, inside=True)
    >>> x = np.array([[0.05, -5.01]])            # slipping: its force is the bound
    >>> de, df, _ = friction_bound_change(x, np.ones(1), hole, 1e5, 1e5, 0.3,
    ...                                   np.array([-np.pi / 2]),
    ...                                   (np.array([300.0]), np.array([310.0])), False)
    >>> round(float(np.hypot(*df[0])), 2)        # 10 N/mm more bound, times R / r
    9.98
    """
    d = x - np.asarray(circle.center)
    dist = np.hypot(d[:, 0], d[:, 1])
    active = (circle.radius - dist if circle.inside else dist - circle.radius) <= 0.0
    geo = _SlipGeometry(x, weights, circle, eps, eps_t, anchor, active, tangent)
    e0, f0, b0, _, _ = geo.terms(mu, bounds[0], bounds[0] > 0.0)
    e1, f1, b1, _, _ = geo.terms(mu, bounds[1], bounds[1] > 0.0)
    return e1 - e0, f1 - f0, b1 - b0


def slip_geometry(x: np.ndarray, circle: RigidCircle, anchor: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Polar angle, angle from the anchor and its gradient of points on a rigid circle.

    Parameters
    ----------
    x : ndarray (m, 2)
        Points (mm).
    circle : RigidCircle
        The circle (angles seen from its centre).
    anchor : ndarray (m,)
        Anchor angles (rad).

    Returns
    -------
    theta, dtheta, grad_theta : ndarray (m,), (m,), (m, 2)
        ``theta`` (rad), ``theta - anchor`` wrapped to (-pi, pi] (rad) and ``grad(theta)``
        (1/mm).

    Examples
    --------
    >>> import numpy as np
    >>> c = RigidCircle((0.0, 0.0), 1.0, True)
    >>> th, dth, g = slip_geometry(np.array([[0.0, -1.0]]), c, np.array([-np.pi / 2]))
    >>> float(dth[0]), g[0].tolist()
    (0.0, [1.0, 0.0])
    """
    d = x - np.asarray(circle.center)
    r2 = d[:, 0] ** 2 + d[:, 1] ** 2
    theta = np.arctan2(d[:, 1], d[:, 0])
    dth = _wrap(theta - anchor)
    return theta, dth, np.column_stack([-d[:, 1], d[:, 0]]) / r2[:, None]


def _wrap(a: np.ndarray) -> np.ndarray:
    """Angles ``a`` (rad) wrapped to (-pi, pi] (as ``np.angle(np.exp(1j a))``, without the
    complex exponential)."""
    w = np.remainder(a + np.pi, 2.0 * np.pi) - np.pi
    return np.where(w == -np.pi, np.pi, w)


def _gap_grad(d: np.ndarray, circle: RigidCircle) -> np.ndarray:
    """Gradient of the signed gap (unitless) at points ``d`` relative to the centre."""
    n = d / np.hypot(d[:, 0], d[:, 1])[:, None]
    return -n if circle.inside else n



class StickSlipModel:
    """Linearised stick/slip law of one obstacle's contact nodes at a state (frozen bounds).

    The semismooth Newton step on the return map (:func:`evaluate_friction` with a given
    ``bound``, issue 37): the tangent at ``u`` treats each node in the class it is in at
    ``u`` (stick: the stiff tangential spring; slip: the force ``B s`` on the bound). A node
    whose linearised trial force after the step, ``T*(d) = eps_t w (g_t + R grad(theta) . d)``
    against the linearised bound ``B + mu dF_n/dx . d``, would leave that class (a sticking
    node beyond the bound, a slipping one back inside it) is put in its predicted class in the
    linear model (:meth:`correction`), and :func:`active_set_direction` solves the direction
    again, until the classes it predicts are those it was solved with. A slipping node that
    would slide the other way is predicted to stick first: it passes through the stick zone
    on its way, and the model of the opposite slip alone would push it back (the classes
    would alternate between the two slips).

    Parameters
    ----------
    x : ndarray (m, 2)
        Current coordinates of the candidate nodes (mm).
    weights : ndarray (m,)
        Tributary lengths (mm).
    circle : RigidCircle
        The obstacle.
    eps, eps_t : float
        Normal and tangential penalties (N/mm^3).
    mu : float
        Coulomb coefficient (unitless) of the coupled slip block (as in
        :func:`evaluate_friction`).
    anchor : ndarray (m,)
        Anchor angles (rad).
    active : ndarray of bool (m,)
        The nodes in (normal) contact at ``x``.
    bound : ndarray (m,)
        The frozen slip bounds (N per mm depth); friction acts where > 0.

    Attributes
    ----------
    cls0 : ndarray of int (m,)
        Class of each node at ``x``: 0 no friction, 2 stick, +1 / -1 slip with the trial
        force's sign.
    geometry : _SlipGeometry
        The nodes' slip geometry (``gt`` mm, ``gth`` 1/mm, ...).

    Examples
    --------
    >>> import numpy as np
    >>> hole = RigidCircle((0.0, 0.0), 5.0, inside=True)
    >>> x = np.array([[0.0, -5.01]])           # 0.01 mm in, at its anchor: sticks
    >>> m = StickSlipModel(x, np.ones(1), hole, 1e5, 1e5, 0.3, np.array([-np.pi / 2]),
    ...                    np.array([True]), np.array([300.0]))
    >>> m.cls0.tolist(), m.classify(np.array([[0.01, 0.0]])).tolist()  # 0.01 mm on: slips
    ([2], [1])
    """

    def __init__(self, x: np.ndarray, weights: np.ndarray, circle: RigidCircle, eps: float,
                 eps_t: float, mu: float, anchor: np.ndarray, active: np.ndarray,
                 bound: np.ndarray) -> None:
        self.geometry = _SlipGeometry(x, weights, circle, eps, eps_t, anchor, active, True)
        self.bound = bound
        self.mu = mu
        self.cls0 = self._classes(self.geometry.kw * self.geometry.gt, bound)
        self.t0 = self._traction(self.cls0)

    def _classes(self, trial: np.ndarray, bound: np.ndarray) -> np.ndarray:
        """Classes (0 none, 2 stick, +-1 slip) of the trial forces against the bounds (N per
        mm depth)."""
        on = self.bound > 0.0
        stick = on & (np.abs(trial) < (1.0 - _SLIP_TOL) * bound)
        return np.where(stick, 2, np.where(on, np.sign(trial), 0.0)).astype(int)

    def _traction(self, cls: np.ndarray) -> np.ndarray:
        """Tangential force T (N per mm depth) at the state of each node in class ``cls``."""
        g = self.geometry
        return np.where(cls == 2, g.kw * g.gt, self.bound * cls)

    def _blocks(self, cls: np.ndarray, t: np.ndarray) -> np.ndarray:
        """Tangent blocks (N/mm per mm depth) of the nodes in classes ``cls``, forces ``t``."""
        g = self.geometry
        gg = g.gth[:, :, None]
        stick = (g.kw * g.rc**2)[:, None, None] * (gg * g.gth[:, None, :])
        slip = (self.mu * np.where(cls == 2, 0, cls) * g.rc)[:, None, None] * (
            gg * g.dfn[:, None, :])
        return (np.where((cls == 2)[:, None, None], stick, slip)
                + (t * g.rc)[:, None, None] * g.hess)

    def classify(self, dn: np.ndarray) -> np.ndarray:
        """Classes the nodes would be in after the nodal step ``dn`` (m, 2) (mm), linearised.

        Parameters
        ----------
        dn : ndarray (m, 2)
            Displacement increments of the nodes (mm).

        Returns
        -------
        ndarray of int (m,)
            0 no friction, 2 stick, +1 / -1 slip.
        """
        g = self.geometry
        trial = g.kw * (g.gt + g.rc * np.einsum("mi,mi->m", g.gth, dn))
        cls = self._classes(trial, self.bound + self.mu * np.einsum("mi,mi->m", g.dfn, dn))
        return np.where(cls * self.cls0 == -1, 2, cls)  # a reversal sticks first

    def correction(self, cls: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Change of the linear model when the nodes are in the classes ``cls`` instead.

        Parameters
        ----------
        cls : ndarray of int (m,)
            Classes (from :meth:`classify`).

        Returns
        -------
        blocks : ndarray (m, 2, 2)
            Tangent blocks to add (N/mm per mm depth).
        shift : ndarray (m, 2)
            Change of the nodes' residual at the state (N per mm depth): the right-hand
            side ``-R`` gets ``-shift``.
        """
        changed = cls != self.cls0
        t = np.where(changed, self._traction(cls), self.t0)
        blocks = np.where(changed[:, None, None],
                          self._blocks(cls, t) - self._blocks(self.cls0, self.t0), 0.0)
        return blocks, ((t - self.t0) * self.geometry.rc)[:, None] * self.geometry.gth


def _theta_hessian(d: np.ndarray) -> np.ndarray:
    """Hessian (1/mm^2) of the polar angle theta = atan2(dy, dx) at points ``d`` (m, 2):
    ``[[2 dx dy, dy^2 - dx^2], [dy^2 - dx^2, -2 dx dy]] / r^4``."""
    dx, dy = d[:, 0], d[:, 1]
    r4 = (dx**2 + dy**2) ** 2
    H = np.empty((len(d), 2, 2))
    H[:, 0, 0] = 2.0 * dx * dy / r4
    H[:, 1, 1] = -H[:, 0, 0]
    H[:, 0, 1] = H[:, 1, 0] = (dy**2 - dx**2) / r4
    return H


def active_set_direction(
    gaps: Sequence[tuple[np.ndarray, np.ndarray]],
    kw: np.ndarray,
    contact_dofs: np.ndarray,
    free: np.ndarray,
    rhs: np.ndarray,
    d: np.ndarray,
    solve_with: Callable[[np.ndarray, np.ndarray], np.ndarray],
    max_iter: int,
    friction: Sequence[tuple[float | None, np.ndarray]] | None = None,
    switches: Sequence[StickSlipModel] = (),
) -> np.ndarray:
    """Newton direction with the contacts the step itself would make (semismooth active set).

    The tangent only knows the nodes in contact at the current state. A node outside that the
    linearised step ``d`` runs into an obstacle (``g + grad g . d < 0``) joins the linear
    model, with the penalty stiffness ``eps w grad g grad g^T`` in the matrix and its
    linearised force ``-eps w g grad g`` in the right-hand side, and the direction is solved
    again, until the nodes in the model are exactly those the direction runs into (at most
    ``max_iter`` re-solves). The last direction is returned if it descends (``rhs . d >
    1e-6 |rhs| |d|``), else the plain one. Only the direction changes, never the residual.
    With ``switches`` (friction), the nodes in contact whose stick/slip class the step would
    change are also put in their predicted class (:meth:`StickSlipModel.correction`), and the
    loop runs until both the entering nodes and the classes are consistent with the step.

    Parameters
    ----------
    gaps : sequence of (ndarray (m,), ndarray (m, 2))
        Per obstacle: the gaps g (mm) of the m contact nodes and their gradients.
    kw : ndarray (m,)
        Penalty times tributary length of each node (N/mm^2 per mm depth).
    contact_dofs : ndarray (m, 2)
        The nodes' dofs.
    free : ndarray of bool (n_dofs,)
        Free dofs.
    rhs : ndarray (nf,)
        Minus the free residual (N per mm depth).
    d : ndarray (nf,)
        The plain Newton direction (mm).
    solve_with : callable
        ``solve_with(blocks, extra)``: the direction of the tangent plus the contact blocks
        ``(m, 2, 2)`` (N/mm per mm depth) for the right-hand side ``rhs + extra[free]``.
    max_iter : int
        Re-solves allowed.
    friction : sequence of (float or None, ndarray (m, 2)), optional
        Per obstacle: mu (None: frictionless) and ``s R grad(theta)`` of a node entering while
        sliding (its linearised friction ``mu s R F_n grad(theta)``).
    switches : sequence of StickSlipModel, optional
        The stick/slip law of the obstacles with friction at the current state.

    Returns
    -------
    ndarray (nf,)
        The refined direction (mm); ``d`` itself when no node would enter.

    Examples
    --------
    >>> import numpy as np
    >>> gaps = [(np.array([1.0]), np.array([[0.0, 1.0]]))]  # 1 mm away, gap grows with +y
    >>> d = active_set_direction(gaps, np.array([10.0]), np.array([[0, 1]]),
    ...                          np.ones(2, bool), np.zeros(2), np.array([0.0, 0.5]),
    ...                          lambda b, e: np.zeros(2), 3)
    >>> d.tolist()  # the step does not reach the obstacle: unchanged (mm)
    [0.0, 0.5]
    """
    n_dofs = free.size
    m = len(kw)
    fric = friction if friction is not None else [(None, np.zeros((m, 2))) for _ in gaps]
    step = np.zeros(n_dofs)
    plain = d
    used = [np.zeros(m, dtype=bool) for _ in gaps]  # entering nodes in the model
    classes = [sw.cls0 for sw in switches]  # stick/slip classes in the model
    for it in range(max_iter + 1):
        step[free] = d
        dn = step[contact_dofs]
        nxt = [(g > 0.0) & (g + np.einsum("mi,mi->m", grad, dn) < 0.0) for g, grad in gaps]
        cls = [sw.classify(dn) for sw in switches]
        if all(np.array_equal(a, b) for a, b in zip([*nxt, *cls], [*used, *classes],
                                                    strict=True)):
            break  # consistent: exactly the nodes it runs into are in its model
        if it == max_iter:
            break  # the last set is kept if it descends (the test below)
        used, classes = nxt, cls
        blocks = np.zeros((m, 2, 2))
        extra = np.zeros(n_dofs)
        for sw, c in zip(switches, classes, strict=True):
            b, shift = sw.correction(c)
            blocks += b
            extra[contact_dofs.ravel()] -= shift.ravel()
        for (g, grad), e, (mf, slip_dir) in zip(gaps, used, fric, strict=True):
            ke = np.where(e, kw, 0.0)
            blocks += ke[:, None, None] * np.einsum("mi,mj->mij", grad, grad)
            np.add.at(extra, contact_dofs.ravel(), (-(ke * g)[:, None] * grad).ravel())
            if mf is not None:
                # friction of an entering node, sliding (its bound starts at 0): residual
                # mu s R F_n grad(theta) with F_n = -eps w (g + grad g . d), linearised
                fk = mf * ke
                blocks -= fk[:, None, None] * np.einsum("mi,mj->mij", slip_dir, grad)
                np.add.at(extra, contact_dofs.ravel(), ((fk * g)[:, None] * slip_dir).ravel())
        d = solve_with(blocks, extra)
        if not np.all(np.isfinite(d)):
            return plain
    if d is plain or float(rhs @ d) > _DESCENT_COS * float(np.linalg.norm(rhs)
                                                          * np.linalg.norm(d)):
        return d
    return plain
