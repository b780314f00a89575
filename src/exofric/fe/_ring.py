"""Ring tensile test: a ring cut from the tube, pulled apart by two rigid pins (quarter model).

The ring (outer/inner diameter of the tube, axial length = the ring's *width*) lies in the
x-y plane; two rigid pins of diameter ``pin`` sit inside it on the x axis, initially touching
its inner surface (pin centres at ``+-e0``, ``e0 = ID/2 - pin/2``). The load parameter is the
increase ``delta`` (mm) of the pins' separation: the modelled pin's centre is at
``(e0 + delta/2, 0)``. Quarter model (0 <= theta <= 90 deg): ``u_y = 0`` on theta = 0 (the
pin's line of action), ``u_x = 0`` on theta = 90 deg. The pin is a
:class:`~exofric.fe.RigidCircle` with ``inside=False`` (the ring's inner surface wraps around
it), frictionless penalty contact (:func:`~exofric.fe.evaluate_contact`).

Sections (the ring's faces, normal to the tube axis, are traction-free):

* ``"plane-stress"`` (:class:`PlaneStressBody`): every quadrature point has its own
  out-of-plane stretch ``l`` with ``sigma_zz = 0``, found by a local vectorised Newton on
  ``dW/dl = 0``, ``W = W_iso(s, J, l) + K/2 (J l - 1)^2`` (``s = |F2|^2``, ``J = det F2``).
  Displacement formulation: no locking, since ``l`` takes up the incompressibility. The
  tangent condenses ``l`` statically: ``A = A_FF - a a^T / W_ll``, ``a = d2W/dF dl``.
  Exact as width/wall -> 0.
* ``"plane-strain"``: :class:`~exofric.fe.HyperelasticBody` (mixed u/p), ``l = 1``; the
  stiff bound of a very wide ring.
* ``"generalised-plane-strain"``: the same body with one uniform axial stretch ``l`` (an
  extra dof, :meth:`~exofric.fe.HyperelasticBody.evaluate_axial`) and no axial force: a wide
  ring whose faces are free on average, the wide-ring limit (plane strain also forbids the
  uniform axial contraction that nothing resists).

For the paper's tube cut 5 mm wide (width/wall = 3, 3 mm pins) a 3-D CalculiX ring is 13 %
(0.5 mm), 10 % (1 mm) and 1.6 % (3 mm) stiffer than plane stress, plane strain 31 %, 26 % and
13 % (docs/ring-test.md): the width constrains the bending at the pins, not the stretching
of the legs.

Units: mm, N, MPa; energies and forces per mm of ring width (N mm/mm, N/mm).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import scipy.sparse as sp

from exofric.errors import InputError, check_positive
from exofric.fe._assembly import Assembler
from exofric.fe._contact import (
    ContactState,
    RigidCircle,
    active_set_direction,
    evaluate_contact,
    nodal_weights,
)
from exofric.fe._hyperelastic import (
    ElementState,
    HyperelasticBody,
    PlaneStrainMaterial,
    isochoric_derivatives,
    stress_from_derivatives,
)
from exofric.fe._inflation import MeshSpec, _line_order, scatter
from exofric.fe._mesh import TubeMesh, polar_mesh
from exofric.material import HyperelasticModel, MooneyRivlin

__all__ = ["PlaneStressBody", "RingProblem", "RING_SECTIONS", "RING_MESH", "RING_PENALTY"]

#: The two sections of :class:`RingProblem` (plane stress is the default).
RING_SECTIONS = ("plane-stress", "plane-strain", "generalised-plane-strain")

#: Default ring mesh: quarter ring, 4 x 32 quad9 graded 4:1 toward the pin (theta = 0);
#: convergence study in docs/ring-test.md.
RING_MESH = MeshSpec(n_radial=4, n_circ=32, kind="quad9", grading=4.0, formulation="mixed")

#: Default contact penalty (N/mm^3, MPa of contact pressure per mm of penetration).
RING_PENALTY = 1e5


class PlaneStressBody(HyperelasticBody):
    """A meshed hyperelastic body in plane stress (out-of-plane stretch condensed per point).

    At each quadrature point the out-of-plane stretch ``l`` minimises the energy density
    ``W(s, J, l) = W_iso(s, J, l) + K/2 (J l - 1)^2`` (``sigma_zz = 0``); a vectorised Newton
    on ``W_l = 0`` from ``l = 1/J`` converges in 2-4 iterations (``W_ll ~ K J^2`` dominates).
    With the derivatives of :func:`~exofric.fe.isochoric_derivatives`::

        P = 2 W_s F + W_J cof F
        A = 4 W_ss F x F + 2 W_sJ (F x cof + cof x F) + W_JJ cof x cof + 2 W_s I + W_J Dcof
            - a x a / W_ll,   a = 2 W_sl F + W_Jl cof F

    (the last term: static condensation of ``l``). Energies and forces are per mm of
    thickness (the ring's width).

    Parameters
    ----------
    mesh : TubeMesh
        The mesh (mm).
    material : MooneyRivlin or HyperelasticModel or PlaneStrainMaterial
        Material constants (MPa, 1/MPa).
    n_gauss : int, optional
        Gauss points per direction (default 3 for quad9, 2 for quad4).

    Examples
    --------
    >>> import numpy as np
    >>> from exofric.fe import polar_mesh
    >>> from exofric.material import MooneyRivlin
    >>> body = PlaneStressBody(polar_mesh(2.485, 4.15, 2, 4), MooneyRivlin.from_shore(62.5))
    >>> body.evaluate(np.zeros(90)).energy  # undeformed (N mm per mm)
    0.0
    """

    def __init__(
        self,
        mesh: TubeMesh,
        material: MooneyRivlin | HyperelasticModel | PlaneStrainMaterial,
        n_gauss: int | None = None,
    ) -> None:
        super().__init__(mesh, material, "displacement", n_gauss)

    def _derivatives(
        self, s: np.ndarray, J: np.ndarray, lz: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Total W (isochoric + volumetric), gradient and Hessian in (s, J, l)."""
        W, G, H = isochoric_derivatives(self.model, s, J, lz)
        assert H is not None
        K = self.K
        j3 = J * lz - 1.0
        W = W + 0.5 * K * j3 * j3
        G = G.copy()
        H = H.copy()
        G[..., 1] += K * j3 * lz
        G[..., 2] += K * j3 * J
        H[..., 1, 1] += K * lz * lz
        H[..., 2, 2] += K * J * J
        hjl = K * (2.0 * J * lz - 1.0)
        H[..., 1, 2] += hjl
        H[..., 2, 1] += hjl
        return W, G, H

    def stretch_z(self, s: np.ndarray, J: np.ndarray) -> np.ndarray | None:
        """Out-of-plane stretch ``l`` (unitless) with ``sigma_zz = 0`` at each ``(s, J)``.

        Parameters
        ----------
        s, J : ndarray
            ``|F2|^2`` and ``det F2`` of the in-plane deformation gradient (unitless).

        Returns
        -------
        ndarray or None
            ``l``; None if the local Newton does not converge (the state is rejected).
        """
        lz = 1.0 / J
        for _ in range(60):
            _, G, H = self._derivatives(s, J, lz)
            dl = -G[..., 2] / H[..., 2, 2]
            bad = ~(lz + dl > 0.0)
            dl = np.where(bad, -0.5 * lz, dl)  # never through l = 0
            lz = lz + dl
            if np.all(np.abs(dl) <= 1e-14 * lz):
                return lz
        return None

    def _state(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
        """(F flattened (p, 4), s, J, l) at every quadrature point; None if inverted."""
        F = self.deformation_gradient(u)
        f = F.reshape(-1, 4)
        J = f[:, 0] * f[:, 3] - f[:, 1] * f[:, 2]
        if np.any(J <= 1e-8) or not np.all(np.isfinite(J)):
            return None
        s = np.einsum("pi,pi->p", f, f)
        lz = self.stretch_z(s, J)
        if lz is None or not np.all(np.isfinite(lz)):
            return None
        return f, s, J, lz

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
            Energy (N mm per mm thickness), element forces (N per mm), tangents (N/mm per
            mm) and a validity flag (False for an inverted element or a failed local solve).
        """
        st = self._state(u)
        if st is None:
            return ElementState(np.inf, np.empty(0), None, False)
        f, s, J, lz = st
        W, G, H = self._derivatives(s, J, lz)
        P, A, a = stress_from_derivatives(f, G, H if tangent else None)
        ne = len(self.edofs)
        w = self.ref.w
        nq = w.shape[1]
        energy = float(np.einsum("eq,eq->", w, W.reshape(ne, nq)))
        fe = (self._wBT @ P.reshape(ne, 4 * nq, 1))[..., 0]
        ke = None
        if tangent:
            assert A is not None and a is not None
            # static condensation of the local out-of-plane stretch
            A = A - (a[:, :, None] * a[:, None, :]) / H[:, 2, 2, None, None]
            BD = (A.reshape(ne, nq, 4, 4) @ self._B).reshape(ne, 4 * nq, -1)
            ke = self._wBT @ BD
        return ElementState(energy, fe, ke, True)

    def out_of_plane_stretch(self, u: np.ndarray) -> np.ndarray:
        """Out-of-plane stretch ``l`` (unitless) at every quadrature point, shape (e, q).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm).

        Returns
        -------
        ndarray (e, q)
            ``l`` (thickness ratio, unitless); NaN where the state is invalid.
        """
        st = self._state(u)
        shape = self.ref.w.shape
        if st is None:
            return np.full(shape, np.nan)
        return st[3].reshape(shape)

    def max_stretch(self, u: np.ndarray) -> float:
        """Largest principal stretch (in plane or through the thickness) at ``u``.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm).

        Returns
        -------
        float
            Largest principal stretch (unitless).
        """
        return max(super().max_stretch(u), float(np.nanmax(self.out_of_plane_stretch(u))))


class RingProblem:
    """Quarter ring pulled over a rigid pin: a :class:`~exofric.fe.Problem` for solve_path.

    The load is the pins' separation increase ``delta`` (mm); the modelled pin's centre is at
    ``(e0 + delta/2, 0)``, ``e0 = ring_id_mm/2 - pin_mm/2`` (initially touching). Energies,
    residuals and forces are per mm of ring width.

    Parameters
    ----------
    ring_od_mm, ring_id_mm : float
        Undeformed outer and inner ring diameters (mm), ``ring_id_mm < ring_od_mm``.
    pin_mm : float
        Pin diameter (mm), ``0 < pin_mm < ring_id_mm``.
    material : MooneyRivlin or HyperelasticModel or PlaneStrainMaterial
        Ring material (MPa, 1/MPa).
    section : {'plane-stress', 'plane-strain', 'generalised-plane-strain'}
        Section model (see the module docstring).
    spec : MeshSpec, optional
        Quarter-ring mesh (default :data:`RING_MESH`: ``grading`` toward the pin, theta = 0).
    penalty : float
        Contact penalty (N/mm^3), > 0.

    Raises
    ------
    InputError
        Bad sizes, section or penalty.

    Examples
    --------
    >>> from exofric.material import MooneyRivlin
    >>> p = RingProblem(8.3, 4.97, 3.0, MooneyRivlin.from_shore(62.5), spec=MeshSpec(2, 8))
    >>> p.n_dofs, round(p.e0_mm, 3)
    (170, 0.985)
    """

    def __init__(
        self,
        ring_od_mm: float,
        ring_id_mm: float,
        pin_mm: float,
        material: MooneyRivlin | HyperelasticModel | PlaneStrainMaterial,
        section: str = "plane-stress",
        spec: MeshSpec | None = None,
        penalty: float = RING_PENALTY,
    ) -> None:
        if section not in RING_SECTIONS:
            raise InputError(f"section must be one of {', '.join(RING_SECTIONS)}, got "
                             f"{section!r}", param="section")
        od, idm, pin = float(ring_od_mm), float(ring_id_mm), float(pin_mm)
        if not 0.0 < idm < od:
            raise InputError(f"ring_id_mm must be in (0, ring_od_mm = {od:g}) mm, got {idm:g}",
                             param="ring_id_mm")
        if not 0.0 < pin < idm:
            raise InputError(f"pin_mm must be in (0, ring_id_mm = {idm:g}) mm, got {pin:g}",
                             param="pin_mm")
        self.penalty = check_positive("penalty", penalty, "N/mm^3")
        self.section = section
        self.spec = spec or RING_MESH
        self.A, self.B = 0.5 * idm, 0.5 * od
        self.pin = RigidCircle((0.5 * idm - 0.5 * pin, 0.0), 0.5 * pin, inside=False, name="pin")
        self.e0_mm = float(self.pin.center[0])
        sp_ = self.spec
        mesh = polar_mesh(self.A, self.B, sp_.n_radial, sp_.n_circ, theta0=0.0,
                          theta1=0.5 * np.pi, grading=sp_.grading, grade_toward=0.0,
                          kind=sp_.kind)
        self.mesh = mesh
        self.body: HyperelasticBody = (PlaneStressBody(mesh, material)
                                       if section == "plane-stress"
                                       else HyperelasticBody(mesh, material, sp_.formulation))
        self.model = self.body.model
        n = mesh.n_nodes
        #: generalised plane strain: one uniform axial stretch l (the last dof, l - 1) with no
        #: axial force (the ring's faces are free on average)
        self.axial = section == "generalised-plane-strain"
        self.n_nodal = 2 * n
        self.n_dofs = 2 * n + int(self.axial)
        fixed = np.concatenate([2 * mesh.grid[:, 0] + 1,  # theta = 0: u_y = 0
                                2 * mesh.grid[:, -1]])  # theta = 90 deg: u_x = 0
        self.free = np.ones(self.n_dofs, dtype=bool)
        self.free[fixed] = False
        self.inner = mesh.inner_nodes
        self.contact_dofs = 2 * self.inner[:, None] + np.arange(2)
        self.w_inner = nodal_weights(mesh.boundary_edges("inner"), mesh.nodes, n)[self.inner]
        self.X = mesh.nodes.ravel()
        self._load = 0.0  # load of the last evaluate (refine_direction's pin position)
        ed = self.body.edofs
        if self.axial:
            ed = np.hstack([ed, np.full((len(ed), 1), self.n_dofs - 1)])
        k = ed.shape[1]
        cd = self.contact_dofs
        self.assembler = Assembler(
            self.n_dofs, self.free,
            [(np.repeat(ed, k, axis=1), np.tile(ed, (1, k))),
             (np.repeat(cd, 2, axis=1), np.tile(cd, (1, 2)))],
            orders=[_line_order(mesh)], border=(self.n_dofs - 1,) if self.axial else ())

    def pin_at(self, load: float) -> RigidCircle:
        """The modelled pin at separation increase ``load`` (mm): centre ``e0 + load/2``.

        Parameters
        ----------
        load : float
            Pin separation increase delta (mm).

        Returns
        -------
        RigidCircle
        """
        return RigidCircle((self.e0_mm + 0.5 * float(load), 0.0), self.pin.radius,
                           inside=False, name="pin")

    def contact(self, u: np.ndarray, load: float, tangent: bool = False) -> ContactState:
        """Contact state of the ring's inner nodes with the pin at ``load`` (mm).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm).
        load : float
            Pin separation increase delta (mm).
        tangent : bool
            Also compute the tangent blocks.

        Returns
        -------
        ContactState
            Forces per mm of width (N/mm).
        """
        x = (self.X + u[: self.n_nodal]).reshape(-1, 2)[self.inner]
        return evaluate_contact(x, self.w_inner, self.pin_at(load), self.penalty, tangent)

    def evaluate(
        self, u: np.ndarray, load: float, tangent: bool
    ) -> tuple[float, np.ndarray, sp.csc_matrix | None] | None:
        """Energy (N mm per mm), residual (N/mm) and reduced tangent at separation ``load``.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        load : float
            Pin separation increase delta (mm).
        tangent : bool
            Also assemble the reduced tangent.

        Returns
        -------
        tuple or None
            ``(energy, residual, tangent)``; None for an invalid state.
        """
        self._load = float(load)
        un = u[: self.n_nodal]
        st = (self.body.evaluate_axial(un, self.axial_stretch(u), tangent) if self.axial
              else self.body.evaluate(un, tangent))
        if not st.valid:
            return None
        R = scatter(self.body.edofs, st.fe, self.n_dofs)
        if self.axial:
            assert st.fl is not None
            R[-1] = float(st.fl.sum())  # no axial force
        cs = self.contact(u, load, tangent)
        np.subtract.at(R, self.contact_dofs.ravel(), cs.force.ravel())
        K = None
        if tangent:
            assert st.ke is not None
            ke = st.with_axial() if self.axial else st.ke
            K = self.assembler.matrix([ke, cs.blocks])
        return st.energy + cs.energy, R, K

    def axial_stretch(self, u: np.ndarray) -> float:
        """Axial (through-width) stretch of generalised plane strain (1 in the other sections).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Dofs (mm; then l - 1 in generalised plane strain).

        Returns
        -------
        float
            Unitless.
        """
        return 1.0 + float(u[-1]) if self.axial else 1.0

    def refine_direction(
        self, u: np.ndarray, K: sp.csc_matrix, rhs: np.ndarray, d: np.ndarray,
        solve: Callable[[sp.csc_matrix, np.ndarray], np.ndarray], max_iter: int,
    ) -> np.ndarray:
        """Newton direction with the pin contacts that the step itself would make.

        As :meth:`SqueezeProblem.refine_direction <exofric.fe.SqueezeProblem.refine_direction>`
        for the one pin (at the load of the last :meth:`evaluate`, which Newton calls at
        ``u`` just before): inner nodes that the linearised step runs into the pin join the
        linear model (penalty stiffness in the matrix, linearised force in the right-hand
        side) until the set is consistent; the contact arc then grows without the line
        search creeping one node per iteration. Only the direction changes.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Current displacements (mm).
        K : scipy.sparse.csc_matrix
            Reduced tangent at ``u`` (N/mm per mm width).
        rhs : ndarray (nf,)
            Minus the free residual at ``u`` (N per mm width).
        d : ndarray (nf,)
            Newton direction over the free dofs (mm).
        solve : callable
            ``solve(K, rhs)`` of the linear systems.
        max_iter : int
            Re-solves allowed.

        Returns
        -------
        ndarray (nf,)
            The refined direction (mm); ``d`` itself when no node would enter.
        """
        pin = self.pin_at(self._load)
        xo = (self.X + u[: self.n_nodal]).reshape(-1, 2)[self.inner]
        vec = xo - np.asarray(pin.center)
        dist = np.hypot(vec[:, 0], vec[:, 1])
        gaps = [(dist - pin.radius, vec / dist[:, None])]
        free = self.free
        return active_set_direction(
            gaps, self.penalty * self.w_inner, self.contact_dofs, free, rhs, d,
            lambda blocks, extra: solve(self.assembler.add(K, 1, blocks), rhs + extra[free]),
            max_iter)

    def scales(self, load: float) -> tuple[float, float]:
        """Force scale mu (B - A) max(delta / B, 1e-3) (N/mm) and length scale B (mm).

        Parameters
        ----------
        load : float
            Pin separation increase delta (mm).

        Returns
        -------
        tuple of float
            (N per mm width, mm).
        """
        wall = self.B - self.A
        return self.model.shear_modulus * wall * max(abs(load) / self.B, 1e-3), self.B

    def pin_force_n_per_mm(self, u: np.ndarray, load: float) -> float:
        """Force of one pin on the whole ring per mm of width (N/mm): 2 x the quarter's.

        The quarter model holds the upper half of the pin's contact arc; the node on theta =
        0 carries half its tributary length, so the whole arc's x-force is twice the
        model's.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Converged nodal displacements (mm).
        load : float
            Pin separation increase delta (mm).

        Returns
        -------
        float
            N per mm of ring width.
        """
        return 2.0 * float(self.contact(u, load).force[:, 0].sum())

    def strain_energy_n_mm_per_mm(self, u: np.ndarray, load: float) -> float:
        """Stored energy of the whole ring per mm of width (N mm/mm): 4 x the quarter's.

        Includes the (tiny) penalty energy of the contact, which the pin's work also stores.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm).
        load : float
            Pin separation increase delta (mm).

        Returns
        -------
        float
            N mm per mm of ring width.
        """
        out = self.evaluate(u, load, False)
        if out is None:
            return float("nan")
        return 4.0 * out[0]

    def contact_arc_deg(self, u: np.ndarray, load: float) -> float:
        """Largest reference angle (deg) of an inner node in contact with the pin.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm).
        load : float
            Pin separation increase delta (mm).

        Returns
        -------
        float
            deg from the x axis (0 without contact).
        """
        cs = self.contact(u, load)
        act = cs.active & (cs.force[:, 0] > 0.0)
        if not np.any(act):
            return 0.0
        xy = self.mesh.nodes[self.inner[act]]
        return float(np.degrees(np.arctan2(xy[:, 1], xy[:, 0])).max())
