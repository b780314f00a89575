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

**Full model** (``wire_angle_deg != 0``, issue 19): the wire centre sits on the circle of
radius D/2 - d2/2 at the angle ``a`` from the top (positive toward +x), so no symmetry plane is
left. The whole ring is meshed (``2 n_circ`` elements, graded toward the wire's direction
seen from the tube, polar angle 90 deg - a: the half model's mesh and its mirror image,
turned by a), with no symmetry constraint. Its in-plane floating modes:

* the two translations: with ``gravity="none"`` a spring on both dofs of the outer node
  opposite the wire (stiffness ``spring_rel x mu``), taken out like the half model's once the
  tube bears on wall and wire; with gravity the weight and the curved wall hold them;
* the rotation of the tube about its own axis, a zero-energy mode of the continuum (the
  annulus is isotropic and frictionless contact exerts no torque about its centre): a
  rotational spring ``k_rot omega^2 / 2`` on the rotation ``omega`` of the radial segment
  from the inner to the outer node opposite the wire (reference direction -> current
  direction), kept on. Without gravity the frictionless tube slides along the wall until it
  lies opposite the wire (wall forces act through the hole centre, wire forces through the
  wire centre: two forces in equilibrium are collinear), so the solution is the a = 0 one
  rotated by a about the hole centre, in which that segment keeps its reference direction:
  ``omega = 0`` exactly and the spring carries no force. With gravity the spring's couple is
  the mesh's (discretisation-level) resistance to the rotation mode.

Without gravity the tube starts opposite the wire (where it comes to rest anyway). With
gravity toward the wall it starts at the bottom of the hole (turned so that a node sits there,
lowered by the penetration that carries its weight) and slides along the wall as the wire
pushes it; that slide is resisted only by the weight (tangential stiffness ~W/R ~ 1e-4 N/mm
per mm against the contact's 1e5), and load control loses it on coarse meshes (2 x 24 graded,
2 x 16) or with a stiff rotation spring: :func:`exofric.simulate.squeeze` therefore accepts an
off-centre wire only without gravity. Gravity toward the wire with an off-centre wire is
refused here (the hanging tube need not fit).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import scipy.sparse as sp

from exofric import defaults
from exofric.errors import InputError, check_positive
from exofric.fe._assembly import Assembler
from exofric.fe._contact import (
    ContactState,
    FrictionState,
    RigidCircle,
    StickSlipModel,
    active_set_direction,
    evaluate_contact,
    evaluate_friction,
    friction_bound_change,
    nodal_weights,
    polar_angle,
)
from exofric.fe._inflation import MeshSpec, PressurizedTube
from exofric.fe._mesh import TubeMesh, polar_mesh, two_sided_angles
from exofric.geometry import Structure
from exofric.material import MooneyRivlin

__all__ = ["SqueezeProblem", "GRAVITY_MM_S2", "MU_MAX", "MU_WARN", "GRAVITY_OPTIONS",
           "ROTATION_SPRING_REL", "half_boundaries", "patch_edge",
           "wire_halfwidth", "wall_arc", "ring_wire_halfwidth", "ring_wall_arc"]

#: Standard gravity (mm/s^2) for the tube's weight (``gravity="toward-wall"`` or
#: ``"toward-wire"``).
GRAVITY_MM_S2 = 9810.0

#: Largest Coulomb coefficient accepted (unitless); above :data:`MU_WARN` it is implausible
#: for silicone on metal (a warning where users give it).
MU_MAX = 2.0
#: Coulomb coefficient (unitless) above which a given coefficient draws a warning as
#: implausible for silicone on metal (accepted up to :data:`MU_MAX`).
MU_WARN = 1.5

#: Orientations of gravity in the squeeze: none (regulariser only), toward the hole wall the
#: tube rests on, or toward the wire (the device upside down).
GRAVITY_OPTIONS = ("none", "toward-wall", "toward-wire")

#: Full model (off-centre wire): stiffness of the rotation spring relative to mu B^2 (see
#: :data:`exofric.defaults.ROTATION_SPRING_REL`).
ROTATION_SPRING_REL = defaults.ROTATION_SPRING_REL


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
    wire_angle_deg : float
        Angle of the wire centre from the top of the hole (deg, positive toward +x,
        |a| < 90). 0 is the half model; any other value the full model.
    rotation_rel : float
        Full model: stiffness of the rotation spring relative to ``mu B^2`` (unitless).
    full : bool, optional
        Force the full model (True, also at angle 0: for checks against the half model) or
        the half one (False: angle 0 only); default: full iff the angle is not 0.
    mu_wall, mu_wire : float
        Coulomb coefficients (unitless, [0, 2]) of the tube on the hole wall and on the wire,
        in the section's plane; 0: frictionless (see :func:`exofric.fe.evaluate_friction`).
    friction_penalty : float, optional
        Tangential penalty eps_t (N/mm^3); default:
        :data:`exofric.defaults.FRICTION_PENALTY_REL` x ``penalty``.
    frictional : bool, optional
        Run the frictional machinery (anchors, bounds, commits); default: iff a mu > 0
        (True with mu = 0 checks it against the frictionless solver).
    ends : {'plane-strain', 'closed', 'open'}
        Axial condition of the tube (:class:`~exofric.fe.PressurizedTube`): plane strain
        (the paper's), or a uniform axial stretch with closed or open ends. The contacts are
        frictionless along the axis. Forces are then per unit *reference* length.

    Attributes
    ----------
    spring_k : float
        Current stiffness of the floating-mode spring (N/mm per mm depth; 0 with gravity).
    full : bool
        True for the full (360 deg, unconstrained) model of an off-centre wire.
    rot_k : float
        Full model: stiffness of the rotation spring (N mm per mm depth per rad^2).

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

    #: Semismooth stick/slip classes in :meth:`refine_direction` (issue 37; False: only the
    #: nodes entering contact, as before; for checks).
    stick_slip_switches: bool = True

    def __init__(
        self,
        structure: Structure,
        material: MooneyRivlin,
        spec: MeshSpec,
        penalty: float,
        density: float,
        gravity: str = "toward-wall",
        spring_rel: float = 1.0,
        wire_angle_deg: float = 0.0,
        rotation_rel: float = ROTATION_SPRING_REL,
        full: bool | None = None,
        mu_wall: float = 0.0,
        mu_wire: float = 0.0,
        friction_penalty: float | None = None,
        frictional: bool | None = None,
        ends: str = "plane-strain",
    ) -> None:
        for name, m in (("mu_wall", mu_wall), ("mu_wire", mu_wire)):
            if not (np.isfinite(m) and 0.0 <= m <= MU_MAX):
                raise InputError(f"{name} must be a friction coefficient in [0, {MU_MAX:g}], "
                                 f"got {m:g}", param=name)
        self.mu = (float(mu_wall), float(mu_wire))
        self.frictional = (mu_wall > 0.0 or mu_wire > 0.0) if frictional is None \
            else bool(frictional)
        if gravity not in GRAVITY_OPTIONS:
            raise InputError(
                f"gravity must be one of {', '.join(GRAVITY_OPTIONS)}, got {gravity!r}",
                param="gravity")
        a = float(wire_angle_deg)
        if not (np.isfinite(a) and abs(a) < 90.0):
            raise InputError(f"wire_angle_deg must be a number in (-90, 90) deg, got {a:g}",
                             param="wire_angle_deg")
        self.full = a != 0.0 if full is None else bool(full)
        if a != 0.0 and not self.full:
            raise InputError("the half model needs wire_angle_deg = 0", param="wire_angle_deg")
        self.wire_angle_deg = a
        self.rot_k = 0.0
        self._eps_t = friction_penalty
        if self.full:
            self._init_full(structure, material, spec, penalty, density, gravity, spring_rel,
                            np.radians(a), rotation_rel, ends)
            return
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
            boundaries=half_boundaries(spec),
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
            ((np.repeat(cd, 2, axis=1), np.tile(cd, (1, 2))), (sd, sd)), ends=ends,
        )
        self.spring_k = spring_rel * material.shear_modulus if gravity == "none" else 0.0
        self.w_outer = nodal_weights(mesh.boundary_edges("outer"), mesh.nodes, n)[self.outer]
        self.hole = RigidCircle((0.0, 0.0), 0.5 * s.hole_mm, inside=True, name="hole")
        self.wire = RigidCircle(s.wire_center_mm, 0.5 * s.wire_mm, inside=False, name="wire")
        self.penalty = float(penalty)
        self._init_friction(friction_penalty)
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

    def _init_full(self, s: Structure, material: MooneyRivlin, spec: MeshSpec, penalty: float,
                   density: float, gravity: str, spring_rel: float, a: float,
                   rotation_rel: float, ends: str = "plane-strain") -> None:
        """Full model of the wire at the angle ``a`` (rad) from the top (module docstring)."""
        if gravity == "toward-wire":
            raise InputError("gravity 'toward-wire' needs the wire at the top "
                             "(wire_angle_deg = 0): a tube hanging on an off-centre wire "
                             "need not fit in the hole", param="wire_angle_deg")
        check_positive("rotation_rel", rotation_rel)
        self.gravity = gravity
        self.sign = -1.0
        self.structure = s
        self.A, self.B = 0.5 * s.tube_id_mm, 0.5 * s.tube_od_mm
        e = np.array([np.sin(a), np.cos(a)])  # unit vector from the hole centre to the wire
        rc = 0.5 * (s.hole_mm - s.tube_od_mm)
        # no weight: the tube starts opposite the wire, where it comes to rest; with weight at
        # the bottom of the hole, where it rests until the wire pushes it
        c = -rc * e if gravity == "none" else np.array([0.0, -rc])
        tw = 0.5 * np.pi - a  # polar angle of e: from the tube (opposite the wire) to the wire
        nc = 2 * spec.n_circ
        half = half_boundaries(spec)

        def ring(tw: float, cx: float, cy: float) -> TubeMesh:
            # the half model's angles (turned so that the wire is at tw) and their mirror image
            bounds = None if half is None else tw + np.concatenate(
                [half - 0.5 * np.pi, (0.5 * np.pi - half)[::-1][1:]])
            return polar_mesh(self.A, self.B, spec.n_radial, nc, theta0=tw - np.pi,
                              theta1=tw + np.pi, grading=spec.grading, grade_toward=tw,
                              kind=spec.kind, center=(cx, cy), boundaries=bounds)

        mesh = ring(tw, float(c[0]), float(c[1]))
        if gravity != "none":
            # resting on the wall under its weight: turned so that a node sits at the bottom
            # (at most half an element from the wire's direction) and lowered by the penalty
            # penetration that carries the weight, so that the contact holds it from the start
            ang = mesh.angles[:-1]
            j = int(np.argmin(np.abs(np.angle(np.exp(1j * (ang + 0.5 * np.pi))))))
            tw += float(np.angle(np.exp(1j * (-0.5 * np.pi - ang[j]))))
            mesh = ring(tw, float(c[0]), float(c[1]))
            w = nodal_weights(mesh.boundary_edges("outer"), mesh.nodes, mesh.n_nodes)
            weight = density * GRAVITY_MM_S2 * np.pi * (self.B**2 - self.A**2)
            pen = weight / (penalty * float(w[mesh.grid[-1, j]])) + 1e-12
            mesh = ring(tw, float(c[0]), float(c[1]) - pen)
        n = mesh.n_nodes
        self.outer = mesh.outer_nodes[:-1]  # the closed ring's last line is its first
        cd = 2 * self.outer[:, None] + np.arange(2)
        self.contact_dofs = cd
        wall_node = int(mesh.grid[-1, 0])  # outer node opposite the wire (angle tw - pi)
        self.spring_dofs = np.array([2 * wall_node, 2 * wall_node + 1])
        self.spring_dof = int(self.spring_dofs[1])
        sd = self.spring_dofs
        # rotation of the radial segment inner -> outer node at angle tw - pi
        i0 = int(mesh.grid[0, 0])
        self.rot_dofs = np.array([2 * i0, 2 * i0 + 1, 2 * wall_node, 2 * wall_node + 1])
        d = mesh.nodes[wall_node] - mesh.nodes[i0]
        self.rot_c = np.array([d[1], -d[0], -d[1], d[0]]) / float(d @ d)
        rd = self.rot_dofs
        extra = ((np.repeat(cd, 2, axis=1), np.tile(cd, (1, 2))),
                 (np.repeat(sd, 1), np.repeat(sd, 1)),
                 (np.repeat(rd, 4), np.tile(rd, 4)))
        PressurizedTube.__init__(self, mesh, material, spec, np.zeros(0, dtype=int), extra,
                                 ends=ends)
        # the closed ring's narrowest band: its lines folded pairwise (the line at angle tw - pi,
        # then tw - pi +- one line, ...), the two halves side by side
        nt = mesh.grid.shape[1] - 1
        seq = [0] + [j for k in range(1, nt // 2 + 1) for j in dict.fromkeys((k, nt - k))]
        fold = (2 * mesh.grid[:, seq].T.ravel()[:, None] + np.arange(2)).ravel()
        ed = self.body.edofs
        k = ed.shape[1]
        self.assembler = Assembler(
            self.n_dofs, self.free,
            [(np.repeat(ed, k, axis=1), np.tile(ed, (1, k))), (self.H.row, self.H.col), *extra],
            orders=[fold])
        mu = material.shear_modulus
        self.spring_k = spring_rel * mu if gravity == "none" else 0.0
        self.rot_k = rotation_rel * mu * self.B**2
        self.w_outer = nodal_weights(mesh.boundary_edges("outer"), mesh.nodes, n)[self.outer]
        self.hole = RigidCircle((0.0, 0.0), 0.5 * s.hole_mm, inside=True, name="hole")
        wc = (0.5 * s.hole_mm - 0.5 * s.wire_mm) * e
        self.wire = RigidCircle((float(wc[0]), float(wc[1])), 0.5 * s.wire_mm, inside=False,
                                name="wire")
        self.penalty = float(penalty)
        self._init_friction(self._eps_t)
        r = self.body.ref
        nodal_vol = np.bincount(
            mesh.elements.ravel(), weights=np.einsum("eq,qa->ea", r.w, r.N).ravel(), minlength=n
        )
        self.f_body = np.zeros(self.n_dofs)
        self.f_body[1::2] = self.sign * density * GRAVITY_MM_S2 * nodal_vol
        self._weight = density * GRAVITY_MM_S2 * float(nodal_vol.sum())
        if gravity == "none":
            self.f_body[:] = 0.0

    def _init_friction(self, friction_penalty: float | None) -> None:
        """Tangential penalty and the anchors of the outer nodes (their reference angles)."""
        eps_t = (defaults.FRICTION_PENALTY_REL * self.penalty if friction_penalty is None
                 else float(friction_penalty))
        check_positive("friction_penalty", eps_t)
        self.penalty_t = eps_t
        xo = self.X.reshape(-1, 2)[self.outer]
        self.anchors = (polar_angle(xo, self.hole), polar_angle(xo, self.wire))
        #: frozen slip bounds mu F_n of the outer nodes (hole, wire) (N per mm depth)
        self.bounds = (np.zeros(len(xo)), np.zeros(len(xo)))
        self._refreshed = (np.zeros(self.n_dofs), self.bounds)  # last refresh: u, old bounds
        #: frictional dissipation of each committed sub-step (N mm per mm depth, full model's
        #: section; the half model's is doubled), in order
        self.dissipation: list[float] = []

    def friction(self, u: np.ndarray, normal: tuple[ContactState, ContactState] | None = None,
                 tangent: bool = False, frozen: bool = False
                 ) -> tuple[FrictionState, FrictionState] | None:
        """Friction states (hole, wire) of the outer nodes at ``u`` (None if frictionless).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        normal : tuple of ContactState, optional
            The normal contact states at ``u`` (computed if not given).
        tangent : bool
            Also compute the tangent blocks.
        frozen : bool
            Use the frozen slip bounds :attr:`bounds` (the solver's Tresca iterations; see
            :meth:`refresh`) instead of ``mu F_n`` at ``u``.
        """
        if not self.frictional:
            return None
        if normal is None:
            normal = self.contact(u, tangent)
        xo = self.nodal(u)[self.outer]
        bounds = self.bounds if frozen else (None, None)
        return tuple(  # type: ignore[return-value]
            evaluate_friction(xo, self.w_outer, c, self.penalty, self.penalty_t, m, a, n,
                              tangent, b)
            for c, m, a, n, b in zip((self.hole, self.wire), self.mu, self.anchors, normal,
                                     bounds, strict=True))

    def refresh(self, u: np.ndarray) -> float:
        """Set the frozen slip bounds to ``mu F_n`` at ``u``; return their largest change.

        The solver's Newton iterations solve the Tresca problem of the frozen bounds (an
        exact potential: its energy drives the line search); this fixed point on the bound
        then makes the converged state satisfy Coulomb's law ``|T| <= mu F_n``.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            A converged state of the frozen-bound problem (mm).

        Returns
        -------
        float
            Largest change of a node's bound (N per mm depth); 0 if frictionless. With open
            ends, also the change of the frozen cap area (mm^2; see
            :meth:`PressurizedTube.refresh`).
        """
        cap = PressurizedTube.refresh(self, u)
        if not self.frictional:
            return cap
        # mu F_n = mu eps w <-g> (the norm of evaluate_contact's force), without its states
        xo = self.nodal(u)[self.outer]
        new = []
        for m, c in zip(self.mu, (self.hole, self.wire), strict=True):
            dist = np.hypot(*(xo - np.asarray(c.center)).T)
            gap = c.radius - dist if c.inside else dist - c.radius
            new.append(m * self.penalty * self.w_outer * np.maximum(-gap, 0.0))
        change = max(float(np.max(np.abs(n - b))) for n, b in zip(new, self.bounds,
                                                                   strict=True))
        self._refreshed = (u, self.bounds)  # for patch_refreshed: the state, the old bounds
        self.bounds = (new[0], new[1])
        return max(change, cap)

    def patch_refreshed(self, evaluation: tuple[float, np.ndarray, sp.csc_matrix | None]
                        ) -> tuple[float, np.ndarray, sp.csc_matrix | None] | None:
        """The evaluation at the state just refreshed, updated for its new frozen bounds.

        Friction (issue 37): only the friction terms of the outer nodes depend on the bounds,
        so the energy, residual and tangent held for the state of the last :meth:`refresh`
        (under the bounds before it) are corrected by the difference of those terms under the
        new and the old bounds, instead of evaluating the whole body again. Open ends: the cap
        term as well (:meth:`PressurizedTube.patch_refreshed`). None if that cannot be done.

        Parameters
        ----------
        evaluation : tuple
            ``(energy, residual, tangent)`` (N mm, N and N/mm per mm depth) at that state
            under the old bounds (and cap area).

        Returns
        -------
        tuple or None
            The evaluation under the new bounds.
        """
        if self.ends == "open":
            patched = PressurizedTube.patch_refreshed(self, evaluation)
            if patched is None:
                return None
            evaluation = patched
        if not self.frictional:
            return evaluation if self.ends == "open" else None
        u, old = self._refreshed
        energy, R, K = evaluation
        tangent = K is not None
        xo = self.nodal(u)[self.outer]
        force = np.zeros((len(xo), 2))
        blocks = np.zeros((len(xo), 2, 2))
        for c, m, a, b0, b1 in zip((self.hole, self.wire), self.mu, self.anchors, old,
                                   self.bounds, strict=True):
            if np.array_equal(b0, b1):
                continue  # e.g. no contact with that obstacle yet
            de, df, db = friction_bound_change(xo, self.w_outer, c, self.penalty,
                                               self.penalty_t, m, a, (b0, b1), tangent)
            energy += de
            force += df
            blocks += db
        R = R.copy()
        np.subtract.at(R, self.contact_dofs.ravel(), force.ravel())
        return energy, R, self.assembler.add(K, 2, blocks) if K is not None else None

    def commit(self, u: np.ndarray) -> None:
        """Accept the converged state ``u``: move each node's anchor by its slip.

        A sticking node keeps its anchor; a slipping one's moves so that its force is the
        Coulomb bound (``theta_a = theta - T / (eps_t w R)``); a node out of contact is
        anchored where it is (where it will touch). The frictional work of the step,
        ``sum |T| R |delta theta_a|`` (>= 0 by construction of the return map), is appended to
        :attr:`dissipation`.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Converged nodal displacements (mm).
        """
        fr = self.friction(u)
        if fr is None:
            return
        work = 0.0
        new = []
        for f, c, a in zip(fr, (self.hole, self.wire), self.anchors, strict=True):
            na = f.theta - f.traction / (self.penalty_t * self.w_outer * c.radius)
            slip = c.radius * np.angle(np.exp(1j * (na - a)))
            work += float(np.sum(f.traction * slip))
            new.append(na)
        self.anchors = (new[0], new[1])
        self.dissipation.append(work if self.full else 2.0 * work)

    def friction_state(self) -> tuple[np.ndarray, ...]:
        """Anchors (hole, wire; rad) and frozen bounds (hole, wire; N/mm) of the outer nodes:
        the path's friction memory."""
        return tuple(a.copy() for a in (*self.anchors, *self.bounds))

    def set_friction_state(self, state: tuple[np.ndarray, ...]) -> None:
        """Restore a state saved by :meth:`friction_state` (re-solves from a stored state).

        Parameters
        ----------
        state : tuple of ndarray
            Anchors (hole, wire; rad) and bounds (hole, wire; N/mm) of the outer nodes.
        """
        self.anchors = (state[0].copy(), state[1].copy())
        self.bounds = (state[2].copy(), state[3].copy())

    def rotation(self, u: np.ndarray) -> float:
        """Full model: rotation (rad) held by the rotation spring (0 for the half model).

        The linearised rotation of the radial segment from the inner to the outer node
        opposite the wire, ``d x (u_out - u_in) / |d|^2`` with ``d`` its reference vector;
        it is zero whenever the segment keeps its reference direction.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        """
        return float(self.rot_c @ u[self.rot_dofs]) if self.full else 0.0

    def contact(self, u: np.ndarray, tangent: bool = False) -> tuple[ContactState, ContactState]:
        """Contact states (hole, wire) of the outer nodes at displacement ``u``.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        tangent : bool
            Also compute the contact tangent blocks.
        """
        xo = self.nodal(u)[self.outer]
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
        fr = self.friction(u, (ch, cw), tangent, frozen=True)
        blocks = ch.blocks + cw.blocks
        if fr is not None:
            fh, fw = fr
            np.subtract.at(R, self.contact_dofs.ravel(), (fh.force + fw.force).ravel())
            energy += fh.energy + fw.energy
            blocks = blocks + fh.blocks + fw.blocks
        if self.full:
            sd, rd, c = self.spring_dofs, self.rot_dofs, self.rot_c
            us = u[sd]
            om = float(c @ u[rd])
            R[sd] += self.spring_k * us
            R[rd] += self.rot_k * om * c
            energy += (ch.energy + cw.energy - float(self.f_body @ u)
                       + 0.5 * self.spring_k * float(us @ us) + 0.5 * self.rot_k * om**2)
            K = (self.tangent(st, load, blocks, np.full(2, self.spring_k),
                              self.rot_k * np.outer(c, c).ravel()) if tangent else None)
            return energy, R, K
        uy = float(u[self.spring_dof])
        R[self.spring_dof] += self.spring_k * uy
        energy += ch.energy + cw.energy - float(self.f_body @ u) + 0.5 * self.spring_k * uy**2
        K = (self.tangent(st, load, blocks, np.array([self.spring_k]))
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

        With friction (issue 37, :attr:`stick_slip_switches`), the nodes in contact whose
        stick/slip class the step would change (:class:`~exofric.fe._contact.StickSlipModel`)
        are put in that class in the linear model too: a slipping node that the step runs back
        through its stick zone, or a sticking one past its bound, no longer stops the line
        search (base group, mu 0.3 on both, default accuracy: 392 -> 258 iterations, 79 -> 0
        damped steps, 6 -> 0 failed attempts).

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
        xo = self.nodal(u)[self.outer]
        cd = self.contact_dofs
        lin = []
        for c in (self.hole, self.wire):
            vec = xo - np.asarray(c.center)
            dist = np.hypot(vec[:, 0], vec[:, 1])
            n = vec / dist[:, None]
            lin.append((c.radius - dist, -n) if c.inside else (dist - c.radius, n))
        kw = self.penalty * self.w_outer
        # friction of nodes entering contact: mu and s R grad(theta) (s: the sense of the
        # node's trial slip from its anchor), or None without friction on that obstacle
        fric: list[tuple[float | None, np.ndarray]] = []
        # the stick/slip law of the nodes in contact (issue 37): classes the step would change
        switches: list[StickSlipModel] = []
        for c, m, a, b, (g, _) in zip((self.hole, self.wire), self.mu, self.anchors,
                                      self.bounds, lin, strict=True):
            if not (self.frictional and m > 0.0):
                fric.append((None, np.zeros((len(kw), 2))))
                continue
            sw = StickSlipModel(xo, self.w_outer, c, self.penalty, self.penalty_t, m, a,
                                g <= 0.0, b)
            geo = sw.geometry
            fric.append((m, (np.sign(geo.gt) * c.radius)[:, None] * geo.gth))
            if self.stick_slip_switches:
                switches.append(sw)
        free = self.free
        return active_set_direction(
            lin, kw, cd, free, rhs, d,
            lambda blocks, extra: solve(self.assembler.add(K, 2, blocks), rhs + extra[free]),
            max_iter, fric, switches)

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
        if self.full:
            return -self.spring_k * float(u[self.spring_dof])
        return -2.0 * self.spring_k * float(u[self.spring_dof])

    def contact_extent(self, u: np.ndarray) -> tuple[float, float]:
        """Half-width of the contact arc on the wire and hole-wall arc in contact (mm).

        Full section (:func:`wire_halfwidth` and :func:`wall_arc` for the half model,
        :func:`ring_wire_halfwidth` and :func:`ring_wall_arc` for the full one).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        """
        ch, cw = self.contact(u)
        xo = self.nodal(u)[self.outer]
        if self.full:
            return (ring_wire_halfwidth(xo, cw.gap, self.wire.center, self.wire.radius),
                    ring_wall_arc(xo, ch.active, self.hole.radius))
        return (wire_halfwidth(xo, cw.gap, self.wire.center, self.wire.radius),
                wall_arc(xo, ch.active, self.hole.radius))

    def contact_forces(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Contact force (normal plus friction) of the hole and of the wire on each outer node.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.

        Returns
        -------
        tuple of ndarray (m, 2)
            ``(hole, wire)`` forces on the tube's outer nodes (N per mm depth).
        """
        ch, cw = self.contact(u)
        fr = self.friction(u, (ch, cw))
        if fr is None:
            return ch.force, cw.force
        return ch.force + fr[0].force, cw.force + fr[1].force

    def resultants(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Force of the tube on the wire and of the hole wall on the tube (N/mm), full section.

        Normal and friction forces. The half model's are vertical by symmetry (twice its
        half's vertical components).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.

        Returns
        -------
        tuple of ndarray (2,)
            ``(on_wire, wall_on_tube)``, (x, y) components (N per mm depth).
        """
        fh, fw = self.contact_forces(u)
        if self.full:
            return -fw.sum(axis=0) + 0.0, fh.sum(axis=0) + 0.0
        return (np.array([0.0, -2.0 * fw[:, 1].sum() + 0.0]),
                np.array([0.0, 2.0 * fh[:, 1].sum() + 0.0]))

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


def half_boundaries(spec: MeshSpec) -> np.ndarray | None:
    """Half model's element boundary angles (rad, -90..90 deg) of a two-sided ``spec``.

    None when ``spec.wall_elements`` is 0 (one grading toward the wire, as before issue 35).
    Otherwise ``wall_elements`` elements over -90..0 deg graded toward the wall (-90 deg,
    ``wall_grading``) and the rest over 0..90 deg graded toward the wire (``grading``).

    Parameters
    ----------
    spec : MeshSpec
        The half model's mesh.

    Returns
    -------
    ndarray (n_circ + 1,) or None
        Element boundary angles (rad), increasing, or None for the one-sided grading.

    Examples
    --------
    >>> half_boundaries(MeshSpec(1, 4, grading=1.0, wall_elements=2)).round(4).tolist()
    [-1.5708, -0.7854, 0.0, 0.7854, 1.5708]
    """
    if spec.wall_elements == 0:
        return None
    return two_sided_angles(-0.5 * np.pi, 0.5 * np.pi, 0.0, spec.n_circ, spec.wall_elements,
                            spec.wall_grading, spec.grading)


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
    if not np.any(gap <= 0.0):
        return 0.0
    ang = np.arctan2(xo[:, 0] - center[0], center[1] - xo[:, 1])  # 0 at the wire's bottom
    # nodes run from the bottom (theta = -90) to the top (+90, the patch centre) of the tube
    return float(radius * patch_edge(np.abs(ang[::-1]), gap[::-1]))


def patch_edge(phi: np.ndarray, gap: np.ndarray) -> float:
    """Edge (rad) of a contact patch from its nodes, centre first, outward (issue 35).

    Where the pressure goes to zero, interpolated from the pressure distribution rather than
    the last node in contact. The penalty pressure at a node is eps (-gap); near the edge of
    a Hertz-like patch p^2 is linear in x^2 (p ~ sqrt(a^2 - x^2)), so the two outermost
    nodes in contact give a^2 = x1^2 + p1^2 (x1^2 - x2^2) / (p2^2 - p1^2). With one node in
    contact the gap outside (~ (x - a)^(3/2)) of the first two free nodes is extrapolated to
    zero instead. The edge is kept between the last node in contact and the first free one.

    Parameters
    ----------
    phi : ndarray (m,)
        Angle (rad) of each node from the patch centre, increasing (node 0 in contact).
    gap : ndarray (m,)
        Signed gap (mm) at those nodes, <= 0 in contact.

    Returns
    -------
    float
        Angle (rad) of the patch edge.

    Examples
    --------
    >>> import numpy as np
    >>> x = np.array([0.0, 0.1, 0.2, 0.3])
    >>> round(patch_edge(x, -np.sqrt(np.maximum(0.25**2 - x**2, 0)) + 1e-9), 4)  # Hertz
    0.25
    """
    inside = np.cumprod(gap <= 0.0).astype(bool)  # the contiguous run from the centre
    k = int(inside.sum()) - 1
    if k + 1 >= phi.size:
        return float(phi[-1])
    lo, hi = float(phi[k]), float(phi[k + 1])
    edge = lo - gap[k] / (gap[k + 1] - gap[k]) * (hi - lo)  # linear in the gap
    p1, p2 = -gap[k], -gap[k - 1] if k >= 1 else 0.0
    if k >= 1 and p2 > p1 >= 0.0:
        x1, x2 = phi[k], phi[k - 1]
        edge = float(np.sqrt(x1**2 + p1**2 * (x1**2 - x2**2) / (p2**2 - p1**2)))
    elif k + 2 < phi.size and gap[k + 2] > gap[k + 1] > 0.0 and phi[k + 2] > hi:
        s1, s2 = gap[k + 1] ** (2.0 / 3.0), gap[k + 2] ** (2.0 / 3.0)
        edge = float(phi[k + 1] - s1 * (phi[k + 2] - phi[k + 1]) / (s2 - s1))
    return float(np.clip(edge, lo, hi))


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


def ring_wire_halfwidth(
    xo: np.ndarray, gap: np.ndarray, center: tuple[float, float], radius: float
) -> float:
    """Arc half-width (mm) on the wire of the contact zone of a closed ring of outer nodes.

    Half the angle (about the wire centre) between the two ends of the contiguous active arc,
    each end interpolated to where the gap crosses zero, times the wire radius; angles are
    measured from the direction of the hole centre (the origin) seen from the wire.

    Parameters
    ----------
    xo : ndarray (m, 2)
        Current coordinates (mm) of the ring's outer nodes, in ring order (closed).
    gap : ndarray (m,)
        Signed gap to the wire (mm), negative in contact.
    center : tuple of float
        Wire centre (x, y) (mm), not at the origin.
    radius : float
        Wire radius (mm).

    Returns
    -------
    float
        Half-width of the contact arc (mm); 0 without contact.

    Examples
    --------
    >>> import numpy as np
    >>> xo = np.array([[-0.1, 3.4], [0.0, 3.4], [0.1, 3.4], [0.0, -4.0]])
    >>> gap = np.array([0.1, -0.01, 0.1, 8.0])
    >>> round(ring_wire_halfwidth(xo, gap, (0.0, 4.2), 0.8), 4)   # ends interpolated: 0.8 x 0.0113
    0.009
    """
    act = gap <= 0.0
    if not np.any(act):
        return 0.0
    c = np.asarray(center, dtype=float)
    down = -c / np.hypot(c[0], c[1])  # from the wire toward the hole centre
    v = xo - c
    ang = np.arctan2(down[0] * v[:, 1] - down[1] * v[:, 0], v @ down)
    if np.all(act):  # every node in contact
        return float(np.pi * radius)
    k = int(np.flatnonzero(act)[np.argmin(np.abs(ang[act]))])  # the patch centre node
    idx = np.roll(np.arange(len(gap)), -k)  # from the centre one way round, then the other
    sides = [idx, np.concatenate([idx[:1], idx[1:][::-1]])]
    edges = [patch_edge(np.abs(np.unwrap(ang[i] - ang[k])), gap[i]) for i in sides]
    return float(0.5 * radius * (edges[0] + edges[1]))


def ring_wall_arc(xo: np.ndarray, active: np.ndarray, radius: float) -> float:
    """Hole-wall arc length (mm) in contact along a closed ring of outer nodes.

    Parameters
    ----------
    xo : ndarray (m, 2)
        Current coordinates (mm) of the ring's outer nodes, in ring order (closed).
    active : ndarray of bool (m,)
        Nodes in contact with the hole wall.
    radius : float
        Hole radius (mm).

    Returns
    -------
    float
        Contact arc length (mm).

    Examples
    --------
    >>> import numpy as np
    >>> xo = np.array([[5.0, 0.0], [0.0, 5.0], [-5.0, 0.0]])
    >>> round(ring_wall_arc(xo, np.array([True, True, False]), 5.0), 4)  # pi/2 x 5 mm
    7.854
    """
    th = np.arctan2(xo[:, 1], xo[:, 0])
    dth = np.abs(np.angle(np.exp(1j * (np.roll(th, -1) - th))))
    both = active & np.roll(active, -1)
    return float(radius * np.sum(dth[both]))
