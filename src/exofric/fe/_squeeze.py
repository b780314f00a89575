"""The tube-wire-hole squeeze: half model with two rigid circles and a vertical body force.

Half model x >= 0 (symmetry plane x = 0 through the hole, tube and wire centres):
``u_x = 0`` on the tube's nodes at theta = +-90 deg. The pressure has no net force
on the tube, so its vertical position is fixed by contact only.

* ``gravity="toward-wall"`` / ``"toward-wire"``: the tube's weight (``density x g``), a
  physical body force, holds it on the wall (or hangs it on the wire) until it touches
  the other obstacle.
* ``gravity="none"``: no body force. A vertical spring on the outer node at the wall
  (theta = -90 deg) holds the floating mode. Until the tube touches the wire, nothing
  pushes the tube vertically, so the spring's force is exactly zero at every converged
  state (the node stays on the wall without penetrating it); once the wire squeezes the
  tube, :func:`exofric.simulate.squeeze` removes the spring (:attr:`spring_k` = 0, the
  wall and wire contacts then hold the tube) before any output is read. The regulariser
  therefore never enters a reported force.

The mesh is graded toward theta = +90 deg (the wire).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import scipy.sparse as sp

from exofric.errors import InputError
from exofric.fe._contact import ContactState, RigidCircle, evaluate_contact, nodal_weights
from exofric.fe._inflation import MeshSpec, PressurizedTube
from exofric.fe._mesh import polar_mesh
from exofric.geometry import Structure
from exofric.material import MooneyRivlin

__all__ = ["SqueezeProblem", "GRAVITY_MM_S2", "GRAVITY_OPTIONS", "wire_halfwidth", "wall_arc"]

GRAVITY_MM_S2 = 9810.0

#: Orientations of gravity in the squeeze: none (regulariser only), toward the hole wall the
#: tube rests on, or toward the wire (the device upside down).
GRAVITY_OPTIONS = ("none", "toward-wall", "toward-wire")


#: Angle test of a refined direction d (``refine_direction``): kept only if
#: rhs . d > _DESCENT_COS |rhs| |d|, i.e. it descends the energy (an indefinite tangent far from
#: equilibrium can make the active-set solution an ascent direction).
_DESCENT_COS = 1e-6


class SqueezeProblem(PressurizedTube):
    """Discretised squeeze problem (see module docstring).

    Parameters
    ----------
    structure : Structure
        Hole, tube and wire (mm).
    material : MooneyRivlin
        Tube material.
    spec : MeshSpec
        Mesh of the half tube (``n_circ`` over 180 deg, graded toward the wire).
    penalty : float
        Contact penalty eps (N/mm^3: MPa of contact pressure per mm of penetration).
    density : float
        Silicone density (t/mm^3) of the weight (unused with ``gravity="none"``).
    gravity : {'none', 'toward-wall', 'toward-wire'}
        Orientation of gravity. ``'none'`` and ``'toward-wall'`` start with the tube on
        the wall, ``'toward-wire'`` hanging on the wire.
    spring_rel : float
        Stiffness of the floating-mode spring of ``gravity="none"`` relative to the
        shear modulus (unitless; the spring is ``spring_rel x mu`` N/mm per mm depth).

    Attributes
    ----------
    spring_k : float
        Current stiffness of the floating-mode spring (N/mm per mm depth; 0 with gravity).

    Examples
    --------
    >>> import numpy as np
    >>> from exofric import defaults
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> p = SqueezeProblem(BASE, MooneyRivlin.from_shore(62.5),
    ...                    MeshSpec(**defaults.SQUEEZE_MESH), 1e5, 1.1e-9)
    >>> round(p.wire_gap(np.zeros(p.n_dofs)), 3)  # the clearance (mm)
    0.1
    """

    def __init__(
        self,
        structure: Structure,
        material: MooneyRivlin,
        spec: MeshSpec,
        penalty: float,
        density: float,
        gravity: str = "toward-wall",
        spring_rel: float = 1.0,
    ) -> None:
        if gravity not in GRAVITY_OPTIONS:
            raise InputError(
                f"gravity must be one of {', '.join(GRAVITY_OPTIONS)}, got {gravity!r}",
                param="gravity")
        s = structure
        self.gravity = gravity
        # +1: the body force points to +y (the wire); -1: to -y (the wall the tube rests on)
        self.sign = 1.0 if gravity == "toward-wire" else -1.0
        center = s.tube_center_mm
        if gravity == "toward-wire":  # hanging on the wire: tube top at the wire's bottom,
            # 1e-12 mm into it so that round-off cannot leave the touching node inactive
            wy, rw = s.wire_center_mm[1], 0.5 * s.wire_mm
            center = (0.0, wy - rw - 0.5 * s.tube_od_mm + 1e-12)
        self.structure = s
        self.A, self.B = 0.5 * s.tube_id_mm, 0.5 * s.tube_od_mm
        mesh = polar_mesh(
            self.A,
            self.B,
            spec.n_radial,
            spec.n_circ,
            theta0=-0.5 * np.pi,
            theta1=0.5 * np.pi,
            grading=spec.grading,
            grade_toward=0.5 * np.pi,
            kind=spec.kind,
            center=center,
        )
        n = mesh.n_nodes
        self.outer = mesh.outer_nodes
        cd = 2 * self.outer[:, None] + np.arange(2)  # (m, 2) contact dofs
        self.contact_dofs = cd
        fixed = np.concatenate([2 * mesh.grid[:, 0], 2 * mesh.grid[:, -1]])  # on x = 0
        self.spring_dof = int(2 * mesh.grid[-1, 0] + 1)  # u_y of the outer node at -90 deg
        sd = np.array([self.spring_dof])
        super().__init__(
            mesh, material, spec, fixed,
            ((np.repeat(cd, 2, axis=1), np.tile(cd, (1, 2))), (sd, sd)),
        )
        self.spring_k = spring_rel * material.shear_modulus if gravity == "none" else 0.0
        self.w_outer = nodal_weights(mesh.boundary_edges("outer"), mesh.nodes, n)[self.outer]
        self.hole = RigidCircle((0.0, 0.0), 0.5 * s.hole_mm, inside=True, name="hole")
        self.wire = RigidCircle(s.wire_center_mm, 0.5 * s.wire_mm, inside=False, name="wire")
        self.penalty = float(penalty)
        # self-weight: f_a = int N_a b dV with b = (0, -rho g) (N/mm^3)
        r = self.body.ref
        nodal_vol = np.bincount(
            mesh.elements.ravel(), weights=np.einsum("eq,qa->ea", r.w, r.N).ravel(), minlength=n
        )
        self.f_body = np.zeros(self.n_dofs)
        self.f_body[1::2] = self.sign * density * GRAVITY_MM_S2 * nodal_vol
        self._weight = 2.0 * density * GRAVITY_MM_S2 * float(nodal_vol.sum())
        if gravity == "none":
            self.f_body[:] = 0.0

    def contact(self, u: np.ndarray, tangent: bool = False) -> tuple[ContactState, ContactState]:
        """Contact states (hole, wire) of the outer nodes at displacement ``u``.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        tangent : bool
            Also compute the contact tangent blocks.
        """
        xo = (self.X + u).reshape(-1, 2)[self.outer]
        return (
            evaluate_contact(xo, self.w_outer, self.hole, self.penalty, tangent),
            evaluate_contact(xo, self.w_outer, self.wire, self.penalty, tangent),
        )

    def evaluate(
        self, u: np.ndarray, load: float, tangent: bool
    ) -> tuple[float, np.ndarray, sp.csc_matrix | None] | None:
        """Energy (N mm per mm), residual (N per mm) and reduced tangent at pressure ``load``.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        load : float
            Internal pressure (MPa).
        tangent : bool
            Also assemble the reduced tangent.
        """
        out = self.pressurized(u, load, tangent)
        if out is None:
            return None
        st, energy, R = out
        ch, cw = self.contact(u, tangent)
        R -= self.f_body
        np.subtract.at(R, self.contact_dofs.ravel(), (ch.force + cw.force).ravel())
        uy = float(u[self.spring_dof])
        R[self.spring_dof] += self.spring_k * uy
        energy += ch.energy + cw.energy - float(self.f_body @ u) + 0.5 * self.spring_k * uy**2
        K = (self.tangent(st, load, ch.blocks + cw.blocks, np.array([self.spring_k]))
             if tangent else None)
        return energy, R, K

    def refine_direction(
        self, u: np.ndarray, K: sp.csc_matrix, rhs: np.ndarray, d: np.ndarray,
        solve: Callable[[sp.csc_matrix, np.ndarray], np.ndarray], max_iter: int,
    ) -> np.ndarray:
        """Newton direction with the contacts that the step itself would make (active set).

        The tangent at ``u`` only knows the nodes in contact at ``u``. A node outside that the
        linearised step ``d`` runs into an obstacle (linearised gap g + grad g . d < 0) is
        unseen: the line search must stop the step near where it touches, and as the contact
        arcs grow with pressure, Newton creeps one node per iteration (fine meshes stagnated
        and cut back; issue 22). Here such nodes join the linear model, with the penalty
        stiffness ``eps w grad g grad g^T`` in the matrix and their linearised force
        ``-eps w g grad g`` in the right-hand side, and the direction is solved again, until
        the nodes in the model are exactly those the direction runs in (a semismooth Newton
        step on the piecewise-linear contact model; at most ``max_iter`` re-solves). Such a
        consistent direction descends the energy when the tangent is positive definite. The
        last direction is returned if it descends (angle test), else the plain one (an
        indefinite tangent far from equilibrium can make it an ascent direction). Measured on
        the base group, 2 x 24 to 8 x 128 meshes: line searches nearly vanish and the
        iterations per attempt fall, 6 x 96 from 4.1 to 2.0 s CPU. Only the direction
        changes: the residual, hence the converged state, is the same.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Current displacements (mm).
        K : scipy.sparse.csc_matrix
            Reduced tangent at ``u`` (N/mm per mm depth).
        rhs : ndarray (nf,)
            Minus the free residual at ``u`` (N per mm depth).
        d : ndarray (nf,)
            Newton direction ``K d = rhs`` over the free dofs (mm).
        solve : callable
            ``solve(K, rhs)`` of the linear systems (the assembler's).
        max_iter : int
            Re-solves allowed.

        Returns
        -------
        ndarray (nf,)
            The refined direction (mm); ``d`` itself when no node would enter.
        """
        xo = (self.X + u).reshape(-1, 2)[self.outer]
        cd = self.contact_dofs
        lin = []
        for c in (self.hole, self.wire):
            vec = xo - np.asarray(c.center)
            dist = np.hypot(vec[:, 0], vec[:, 1])
            n = vec / dist[:, None]
            lin.append((c.radius - dist, -n) if c.inside else (dist - c.radius, n))
        kw = self.penalty * self.w_outer
        free = self.free
        step = np.zeros(self.n_dofs)
        plain = d
        used = [np.zeros(len(kw), dtype=bool) for _ in lin]  # entering nodes in the model
        for it in range(max_iter + 1):
            step[free] = d
            dn = step[cd]
            nxt = [(g > 0.0) & (g + np.einsum("mi,mi->m", grad, dn) < 0.0) for g, grad in lin]
            if all(np.array_equal(n_, us) for n_, us in zip(nxt, used, strict=True)):
                break  # consistent: exactly the nodes it runs into are in its model
            if it == max_iter:
                break  # the last set is kept if it descends (the test below)
            used = nxt
            blocks = np.zeros((len(kw), 2, 2))
            extra = np.zeros(self.n_dofs)
            for (g, grad), e in zip(lin, used, strict=True):
                ke = np.where(e, kw, 0.0)
                blocks += ke[:, None, None] * np.einsum("mi,mj->mij", grad, grad)
                np.add.at(extra, cd.ravel(), (-(ke * g)[:, None] * grad).ravel())
            d = solve(self.assembler.add(K, 2, blocks), rhs + extra[free])
            if not np.all(np.isfinite(d)):
                return plain
        if d is plain or float(rhs @ d) > _DESCENT_COS * float(np.linalg.norm(rhs)
                                                              * np.linalg.norm(d)):
            return d
        return plain

    def limit_predictor(self, u: np.ndarray, guess: np.ndarray) -> np.ndarray:
        """Shorten a load-step predictor so that no node newly crosses into the last obstacle.

        A secant predictor that jumps past the first touch of the wire starts Newton far
        inside the stiff penalty; stopping it at the touch (the whole increment scaled, so
        the mesh stays consistent) lets Newton engage the contact gradually.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Converged displacements (mm) at the last load.
        guess : ndarray (n_dofs,)
            Predicted displacements (mm) at the next load.

        Returns
        -------
        ndarray (n_dofs,)
            ``guess``, or the point on the segment ``u -> guess`` where a node first
            touches the wire (the wall when hanging on the wire) (mm).
        """
        k = 0 if self.gravity == "toward-wire" else 1  # the obstacle touched last
        g0 = self.contact(u)[k].gap
        g1 = self.contact(guess)[k].gap
        cross = (g0 > 0.0) & (g1 < 0.0)
        if not np.any(cross):
            return guess
        t = float(np.min(g0[cross] / (g0[cross] - g1[cross])))
        return u + t * (guess - u)

    def scales(self, load: float) -> tuple[float, float]:
        """Force scale (N/mm) with a floor for P -> 0, and length scale (mm).

        Parameters
        ----------
        load : float
            Internal pressure (MPa); floored at 0.01 MPa.
        """
        return max(load, 0.01) * self.B, self.B

    def weight_per_mm(self) -> float:
        """Weight of the whole tube per unit depth (N/mm), both halves, at ``density``."""
        return self._weight

    def spring_force(self, u: np.ndarray) -> float:
        """Force of the floating-mode spring on the tube (N/mm), full section (0 with gravity).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        """
        return -2.0 * self.spring_k * float(u[self.spring_dof])

    def bearing_gap(self, u: np.ndarray) -> float:
        """Smallest gap (mm) to the obstacle the tube touches last: where the squeeze begins.

        The wire when the tube starts on the wall (``gravity`` none or toward the wall),
        the hole wall when it starts hanging on the wire.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        """
        ch, cw = self.contact(u)
        return float((ch if self.gravity == "toward-wire" else cw).gap.min())

    def wire_gap(self, u: np.ndarray) -> float:
        """Smallest gap (mm) between the tube's outer nodes and the wire.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        """
        return float(self.contact(u)[1].gap.min())


def wire_halfwidth(
    xo: np.ndarray, gap: np.ndarray, center: tuple[float, float], radius: float
) -> float:
    """Arc half-width (mm) on the wire of the contact zone (gap zero crossing interpolated).

    Parameters
    ----------
    xo : ndarray (m, 2)
        Current coordinates (mm) of the tube's outer nodes, from the bottom to the top.
    gap : ndarray (m,)
        Signed gap to the wire (mm), negative in contact.
    center : tuple of float
        Wire centre (x, y) (mm).
    radius : float
        Wire radius (mm).

    Returns
    -------
    float
        Half-width of the contact arc (mm); 0 without contact.

    Examples
    --------
    >>> import numpy as np
    >>> wire_halfwidth(np.zeros((2, 2)), np.array([0.1, 0.2]), (0.0, 4.2), 0.8)
    0.0
    """
    act = np.flatnonzero(gap <= 0.0)
    if act.size == 0:
        return 0.0
    ang = np.arctan2(xo[:, 0] - center[0], center[1] - xo[:, 1])  # 0 at the wire's bottom
    k = int(act.min())  # nodes run from the bottom (theta = -90) to the top (+90) of the tube
    phi = ang[k]
    if k > 0 and gap[k - 1] > 0.0:  # interpolate to where the gap crosses zero
        t = gap[k - 1] / (gap[k - 1] - gap[k])
        phi = ang[k - 1] + t * (ang[k] - ang[k - 1])
    return float(radius * abs(phi))


def wall_arc(xo: np.ndarray, active: np.ndarray, radius: float) -> float:
    """Hole-wall arc length (mm) in contact, full section (2 x the half model).

    Parameters
    ----------
    xo : ndarray (m, 2)
        Current coordinates (mm) of the tube's outer nodes.
    active : ndarray of bool (m,)
        Nodes in contact with the hole wall.
    radius : float
        Hole radius (mm).

    Returns
    -------
    float
        Contact arc length (mm), both halves.

    Examples
    --------
    >>> import numpy as np
    >>> xo = np.array([[5.0, 0.0], [0.0, 5.0]])  # a quarter of the wall, both nodes active
    >>> round(wall_arc(xo, np.array([True, True]), 5.0), 4)  # 2 x (pi/2 x 5 mm)
    15.708
    """
    th = np.arctan2(xo[:, 1], xo[:, 0])
    both = active[:-1] & active[1:]
    return float(2.0 * radius * np.sum(np.abs(np.diff(th))[both]))
