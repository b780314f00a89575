"""The tube-wire-hole squeeze: half model with two rigid circles and self-weight.

Half model x >= 0 (symmetry plane x = 0 through the hole, tube and wire centres):
``u_x = 0`` on the tube's nodes at theta = +-90 deg. The pressure has no net force
on the tube, so its vertical position is fixed by contact only; the tube's
self-weight (toward the wall, -y) regularises it physically until it touches both
the wall and the wire. The mesh is graded toward theta = +90 deg (the wire).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from exofric.fe._contact import ContactState, RigidCircle, evaluate_contact, nodal_weights
from exofric.fe._inflation import MeshSpec, PressurizedTube
from exofric.fe._mesh import polar_mesh
from exofric.geometry import Structure
from exofric.material import MooneyRivlin

__all__ = ["SqueezeProblem", "GRAVITY_MM_S2", "wire_halfwidth", "wall_arc"]

GRAVITY_MM_S2 = 9810.0


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
        Silicone density (t/mm^3) for the self-weight regulariser.

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
    ) -> None:
        s = structure
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
            center=s.tube_center_mm,
        )
        n = mesh.n_nodes
        self.outer = mesh.outer_nodes
        cd = 2 * self.outer[:, None] + np.arange(2)  # (m, 2) contact dofs
        self.contact_dofs = cd
        fixed = np.concatenate([2 * mesh.grid[:, 0], 2 * mesh.grid[:, -1]])  # on x = 0
        super().__init__(
            mesh, material, spec, fixed, ((np.repeat(cd, 2, axis=1), np.tile(cd, (1, 2))),)
        )
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
        self.f_body[1::2] = -density * GRAVITY_MM_S2 * nodal_vol

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
        energy += ch.energy + cw.energy - float(self.f_body @ u)
        K = self.tangent(st, load, ch.blocks + cw.blocks) if tangent else None
        return energy, R, K

    def limit_predictor(self, u: np.ndarray, guess: np.ndarray) -> np.ndarray:
        """Shorten a load-step predictor so that no node newly crosses into the wire.

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
            touches the wire (mm).
        """
        g0 = self.contact(u)[1].gap
        g1 = self.contact(guess)[1].gap
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
        """Weight of the whole tube per unit depth (N/mm), both halves."""
        return -2.0 * float(self.f_body[1::2].sum())

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
