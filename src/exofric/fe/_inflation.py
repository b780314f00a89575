"""Free inflation of the tube: quarter model with follower pressure on the cavity."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from exofric import defaults
from exofric._validate import checked_init
from exofric.errors import InputError, check_range
from exofric.fe._assembly import Assembler
from exofric.fe._hyperelastic import ElementState, HyperelasticBody
from exofric.fe._loads import area_hessian
from exofric.fe._mesh import TubeMesh, polar_mesh
from exofric.material import MooneyRivlin

__all__ = ["ENDS", "MeshSpec", "InflationProblem", "PressurizedTube", "check_ends"]


@checked_init
@dataclass(frozen=True)
class MeshSpec:
    """Mesh resolution of the tube.

    Attributes
    ----------
    n_radial : int
        Elements through the wall.
    n_circ : int
        Elements around the modelled sector (a quarter for free inflation, a half
        for the squeeze problem).
    kind : {'quad9', 'quad4'}
        Element type (quad9 = quadratic geometry and displacement).
    grading : float
        Circumferential size ratio largest/smallest (unitless), toward the wire in the
        squeeze's half model; the free inflation's quarter model is uniform and ignores it.
    formulation : {'mixed', 'displacement'}
        Volumetric treatment ('displacement' locks; kept for demonstration).
    wall_elements : int
        Squeeze's half model: how many of the ``n_circ`` elements lie on the hole wall's
        side of the tube (-90..0 deg), graded toward the wall (ratio ``wall_grading``); the
        others (0..90 deg) keep ``grading`` toward the wire. 0 (default): one grading toward
        the wire over the whole half (issue 35: the wall's contact patch is ~7x wider than the
        wire's and needs resolving at contact onset too).
    wall_grading : float
        Largest / smallest element on the wall's side (unitless, >= 1).

    Examples
    --------
    >>> from exofric import defaults
    >>> MeshSpec(**defaults.SQUEEZE_MESH).to_dict()["n_circ"]
    24
    """

    n_radial: int = defaults.INFLATION_MESH["n_radial"]
    n_circ: int = defaults.INFLATION_MESH["n_circ"]
    kind: str = defaults.INFLATION_MESH["kind"]
    grading: float = defaults.INFLATION_MESH["grading"]
    formulation: str = defaults.INFLATION_MESH["formulation"]
    wall_elements: int = 0
    wall_grading: float = 1.0

    def __post_init__(self) -> None:
        """Refuse meshes that are not integers >= 1 or too large to solve (InputError)."""
        import numbers

        caps = (("n_radial", self.n_radial, defaults.MESH_MAX_N_RADIAL),
                ("n_circ", self.n_circ, defaults.MESH_MAX_N_CIRC))
        for name, v, cap in caps:
            if isinstance(v, bool) or not isinstance(v, numbers.Integral):
                raise InputError(f"{name} must be an integer in [1, {cap}], got {v!r}")
            if v < 1:
                raise InputError(f"{name} must be an integer in [1, {cap}], got {v}")
        n_el = int(self.n_radial) * int(self.n_circ)
        too_big = [f"{name} <= {cap}" for name, v, cap in caps if v > cap]
        if too_big or n_el > defaults.MESH_MAX_ELEMENTS:
            def gib(n: int) -> float:
                return (defaults.MESH_BYTES_FIXED + defaults.MESH_BYTES_PER_ELEMENT * n) / 2**30

            limits = ", ".join([*too_big, f"n_radial x n_circ <= {defaults.MESH_MAX_ELEMENTS}"])
            raise InputError(
                f"mesh {self.n_radial} x {self.n_circ} ({n_el} elements) would need about "
                f"{gib(n_el):.3g} GiB of memory; allowed: {limits} elements "
                f"(about {gib(defaults.MESH_MAX_ELEMENTS):.2g} GiB)",
                param="n_circ" if self.n_circ > defaults.MESH_MAX_N_CIRC or
                self.n_radial <= defaults.MESH_MAX_N_RADIAL else "n_radial")
        if self.kind not in ("quad9", "quad4"):
            raise InputError(f"kind must be 'quad9' or 'quad4', got {self.kind!r}")
        if self.formulation not in ("mixed", "displacement"):
            raise InputError(
                f"formulation must be 'mixed' or 'displacement', got {self.formulation!r}")
        check_range("grading", self.grading, 1.0, defaults.MESH_MAX_GRADING)
        check_range("wall_grading", self.wall_grading, 1.0, defaults.MESH_MAX_GRADING)
        if not (isinstance(self.wall_elements, numbers.Integral)
                and 0 <= self.wall_elements < self.n_circ):
            raise InputError(f"wall_elements must be an integer in [0, n_circ - 1 = "
                             f"{self.n_circ - 1}], got {self.wall_elements!r}")

    def coarsened(self, radial: int = 1, circ: int = 2) -> MeshSpec:
        """The nested mesh with ``radial`` x ``circ`` times fewer elements.

        Radial element boundaries are uniform, so every ``radial``-th one is kept. The
        circumferential grading is geometric (per-element ratio r = grading^(1/(n-1))), so
        merging ``circ`` neighbours gives again a geometric grading, with ratio r^circ: the
        coarse mesh's boundaries are a subset of this mesh's (nested meshes).

        Parameters
        ----------
        radial, circ : int
            Coarsening factors (>= 1) through the wall and around the tube; they must divide
            ``n_radial`` and ``n_circ``.

        Returns
        -------
        MeshSpec

        Examples
        --------
        >>> c = MeshSpec(2, 48, grading=6.0).coarsened(1, 2)
        >>> c.n_radial, c.n_circ, round(c.grading, 4)
        (2, 24, 5.7756)
        """
        if radial < 1 or circ < 1 or self.n_radial % radial or self.n_circ % circ:
            raise InputError(
                f"mesh {self.n_radial} x {self.n_circ} cannot be coarsened by {radial} x {circ}",
                param="mesh")
        nw = self.wall_elements
        if nw % circ:
            raise InputError(f"wall_elements = {nw} cannot be coarsened by {circ}", param="mesh")

        def merged(g: float, m: int) -> float:  # grading of m elements merged circ-wise
            return 1.0 if m <= circ else g ** (circ * (m // circ - 1) / (m - 1))

        return MeshSpec(self.n_radial // radial, self.n_circ // circ, self.kind,
                        merged(self.grading, self.n_circ - nw), self.formulation,
                        nw // circ, merged(self.wall_grading, nw))

    def to_dict(self) -> dict[str, object]:
        """JSON-ready dict."""
        return {
            "n_radial": self.n_radial,
            "n_circ": self.n_circ,
            "kind": self.kind,
            "grading": self.grading,
            "formulation": self.formulation,
            "wall_elements": self.wall_elements,
            "wall_grading": self.wall_grading,
        }


def scatter(edofs: np.ndarray, fe: np.ndarray, n: int) -> np.ndarray:
    """Sum element vectors ``fe (e, k)`` into a global vector of length ``n``."""
    return np.bincount(edofs.ravel(), weights=fe.ravel(), minlength=n)


def _line_order(mesh: TubeMesh) -> np.ndarray:
    """Dofs angle-major: the nodes of one radial line after the other (first occurrence)."""
    nodes = mesh.grid.T.ravel()
    _, first = np.unique(nodes, return_index=True)
    nodes = nodes[np.sort(first)]
    return (2 * nodes[:, None] + np.arange(2)).ravel()


#: The tube's ends: plane strain (axial stretch 1, the paper's model), or generalised plane
#: strain with one uniform axial stretch, closed (end caps carry P times the deformed cavity
#: area) or open (no axial force).
ENDS = ("plane-strain", "closed", "open")


def check_ends(ends: str) -> str:
    """``ends`` if it is one of :data:`ENDS`, else a one-line :class:`InputError`.

    Parameters
    ----------
    ends : str
        ``'plane-strain'``, ``'closed'`` or ``'open'``.

    Returns
    -------
    str

    Examples
    --------
    >>> check_ends("closed")
    'closed'
    """
    if not isinstance(ends, str) or ends not in ENDS:
        raise InputError(f"ends must be one of {', '.join(ENDS)}, got {ends!r}", param="ends")
    return ends


class PressurizedTube:
    """A meshed tube under internal follower pressure: what both FE problems share.

    Holds the hyperelastic body, the symmetry constraints (``fixed`` dofs), the
    cavity-area Hessian of the pressure potential ``-P * A_cavity`` and the assembler
    (element blocks, the pressure Hessian, then any ``extra_patterns``).

    With ``ends`` ``'closed'`` or ``'open'`` (generalised plane strain) the last dof is the
    axial strain ``l - 1`` (unitless), uniform over the section; energies and forces are then
    per unit *reference* length. Closed ends: the pressure potential is ``-P l A(x)`` (the
    cavity volume per unit reference length), whose l-derivative puts the end-cap force
    ``P A`` on the wall. Open ends: the pressure does the work ``P l dA`` on the wall only
    and the axial force is zero; that load is not conservative, so the Newton iterations
    solve the problem with the cap force frozen at ``P A*`` (:meth:`refresh` sets
    ``A* = A(x)`` at each iterate; an exact potential for the line search) with the tangent of
    the open-end residual (not symmetric: the banded LU solves it). The axial dof is
    coupled to every node and is eliminated by a Schur complement (``Assembler(border=)``).

    Parameters
    ----------
    mesh : TubeMesh
        The tube mesh (mm).
    material : MooneyRivlin
        Tube material.
    spec : MeshSpec
        Mesh settings (its ``formulation`` is used).
    fixed : ndarray of int
        Constrained dofs (symmetry planes).
    extra_patterns : tuple of (rows, cols)
        Further block patterns (e.g. contact) assembled after the pressure Hessian.
    ends : {'plane-strain', 'closed', 'open'}
        Axial condition (see above).

    Examples
    --------
    >>> import numpy as np
    >>> from exofric.fe import polar_mesh
    >>> from exofric.material import MooneyRivlin
    >>> m = polar_mesh(2.485, 4.15, 2, 4)
    >>> tube = PressurizedTube(m, MooneyRivlin.from_shore(62.5), MeshSpec(), np.array([1]))
    >>> tube.n_dofs, int(tube.free.sum())
    (90, 89)
    """

    def __init__(
        self,
        mesh: TubeMesh,
        material: MooneyRivlin,
        spec: MeshSpec,
        fixed: np.ndarray,
        extra_patterns: tuple[tuple[np.ndarray, np.ndarray], ...] = (),
        ends: str = "plane-strain",
    ) -> None:
        self.mesh = mesh
        self.ends = check_ends(ends)
        self.axial = ends != "plane-strain"
        self.body = HyperelasticBody(mesh, material, spec.formulation)
        n = mesh.n_nodes
        self.n_nodal = 2 * n
        self.n_dofs = 2 * n + int(self.axial)
        self.free = np.ones(self.n_dofs, dtype=bool)
        self.free[fixed] = False
        self.H = area_hessian(mesh.boundary_edges("inner"), n).tocoo()
        self.X = mesh.nodes.ravel()
        #: open ends: the frozen cavity area A* (mm^2) of the cap force (see :meth:`refresh`)
        self.area_star = 0.0
        self._area_shift = 0.0
        self._load: float | None = None  # pressure of the last evaluation (MPa)
        self._hx: tuple[np.ndarray, float] | None = None
        ed = self.body.edofs
        k = ed.shape[1]
        border: tuple[int, ...] = ()
        if self.axial:
            ld = self.n_dofs - 1
            ed = np.hstack([ed, np.full((len(ed), 1), ld)])
            k += 1
            self.hx_dofs = np.unique(self.H.row)
            lrow = np.full(self.hx_dofs.size, ld)
            axial_patterns: tuple[tuple[np.ndarray, np.ndarray], ...] = (
                (self.hx_dofs, lrow), (lrow, self.hx_dofs))
            border = (ld,)
        else:
            axial_patterns = ()
        self.edofs_ext = ed
        self.assembler = Assembler(
            self.n_dofs,
            self.free,
            [
                (np.repeat(ed, k, axis=1), np.tile(ed, (1, k))),
                (self.H.row, self.H.col),
                *extra_patterns,
                *axial_patterns,  # last: the extra patterns keep their indices (2, 3, ...)
            ],
            orders=[_line_order(mesh)],
            border=border,
        )

    def nodal(self, u: np.ndarray) -> np.ndarray:
        """Current node coordinates (n, 2) in mm from the dofs ``u`` (mm; axial dof dropped).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Dofs: nodal displacements (mm), then the axial strain (ends closed or open).
        """
        return (self.X + u[: self.n_nodal]).reshape(-1, 2)

    def axial_stretch(self, u: np.ndarray) -> float:
        """Axial stretch l (unitless; 1 in plane strain).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Dofs: nodal displacements (mm), then the axial strain (ends closed or open).
        """
        return 1.0 + float(u[-1]) if self.axial else 1.0

    def cavity_area(self, u: np.ndarray) -> float:
        """Deformed cavity area of the modelled sector (mm^2).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Dofs: nodal displacements (mm), then the axial strain (ends closed or open).
        """
        x = self.X + u[: self.n_nodal]
        return 0.5 * float(x @ (self.H @ x))

    def refresh(self, u: np.ndarray) -> float:
        """Open ends: freeze the cap force's area ``A* = A(x)`` at ``u``; return its change.

        The Newton iterations then solve a conservative problem whose residual at ``u`` is the
        open-end one (see the class docstring). Other ends: nothing to freeze (0).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Dofs: nodal displacements (mm), then the axial strain.

        Returns
        -------
        float
            |change of A*| (mm^2).
        """
        if self.ends != "open":
            return 0.0
        a = self.cavity_area(u)
        self._area_shift = a - self.area_star
        self.area_star = a
        return abs(self._area_shift)

    def patch_refreshed(self, evaluation: tuple[float, np.ndarray, sp.csc_matrix | None]
                        ) -> tuple[float, np.ndarray, sp.csc_matrix | None] | None:
        """The evaluation at the state just refreshed, updated for the new frozen cap area.

        Open ends: the cap term ``P A* l`` shifts the energy by ``P dA* l`` and the axial
        residual by ``P dA*``; the tangent does not depend on A*. Called by the solver with the
        evaluation (energy, residual, tangent) it holds for the state of the last
        :meth:`refresh` (at the load of the last evaluation); None if that cannot be patched.

        Parameters
        ----------
        evaluation : tuple
            ``(energy, residual, tangent)`` at that state under the old A*.

        Returns
        -------
        tuple or None
            The evaluation under the new A*.
        """
        if self.ends != "open" or self._hx is None or self._load is None:
            return None
        d = self._load * self._area_shift
        energy, R, K = evaluation
        R = R.copy()
        R[-1] += d
        return energy + d * self._hx[1], R, K

    def pressurized(
        self, u: np.ndarray, load: float, tangent: bool
    ) -> tuple[ElementState, float, np.ndarray] | None:
        """Body state, energy (N mm per mm) and residual (N per mm) under pressure ``load``.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]`` (then the axial
            strain with ends closed or open).
        load : float
            Internal pressure (MPa).
        tangent : bool
            Also compute the element tangents.

        Returns
        -------
        tuple or None
            ``(state, energy, residual)``; None if an element is inverted.
        """
        un = u[: self.n_nodal]
        lz = self.axial_stretch(u)
        st = self.body.evaluate_axial(un, lz, tangent) if self.axial else \
            self.body.evaluate(un, tangent)
        if not st.valid:
            return None
        x = self.X + un
        Hx = self.H @ x
        self._hx = (Hx, lz)
        self._load = float(load)
        area2 = float(x @ Hx)
        if not self.axial:
            R = scatter(self.body.edofs, st.fe, self.n_dofs) - load * Hx
            return st, st.energy - 0.5 * load * area2, R
        R = np.zeros(self.n_dofs)
        R[: self.n_nodal] = scatter(self.body.edofs, st.fe, self.n_nodal) - load * lz * Hx
        assert st.fl is not None
        cap = load * self.area_star if self.ends == "open" else 0.0
        R[-1] = float(st.fl.sum()) - 0.5 * load * area2 + cap
        return st, st.energy - 0.5 * load * lz * area2 + cap * lz, R

    def tangent(self, st: ElementState, load: float, *extra_blocks: np.ndarray) -> sp.csc_matrix:
        """Reduced tangent: element blocks, ``-P H`` and the extra blocks (pattern order).

        Parameters
        ----------
        st : ElementState
            Body state with tangents (from :meth:`pressurized` with ``tangent=True``).
        load : float
            Internal pressure (MPa).
        *extra_blocks : ndarray
            Values of the ``extra_patterns`` blocks (N/mm per mm depth), in order.
        """
        assert st.ke is not None
        if not self.axial:
            return self.assembler.matrix([st.ke, -load * self.H.data, *extra_blocks])
        assert self._hx is not None
        Hx, lz = self._hx
        ke = st.with_axial()
        c = -load * Hx[self.hx_dofs]
        # closed ends: symmetric; open ends: the axial residual has no pressure term
        lx = c if self.ends == "closed" else np.zeros_like(c)
        return self.assembler.matrix([ke, -load * lz * self.H.data, *extra_blocks, c, lx])


class InflationProblem(PressurizedTube):
    """Quarter tube (0 <= theta <= 90 deg) under internal follower pressure.

    Symmetry: ``u_y = 0`` on theta = 0 and ``u_x = 0`` on theta = 90 deg. The pressure
    acts through the potential ``-P * A_cavity`` (see :mod:`exofric.fe`).

    Parameters
    ----------
    tube_od_mm, tube_id_mm : float
        Undeformed outer and inner tube diameters (mm), ``tube_id_mm < tube_od_mm``.
    material : MooneyRivlin
        Tube material.
    spec : MeshSpec
        Quarter-tube mesh (``n_circ`` elements over 90 deg).
    ends : {'plane-strain', 'closed', 'open'}
        Axial condition (:class:`PressurizedTube`); default plane strain (the paper's).

    Examples
    --------
    >>> from exofric.material import MooneyRivlin
    >>> p = InflationProblem(8.3, 4.97, MooneyRivlin.from_shore(62.5), MeshSpec())
    >>> p.n_dofs, p.scales(0.2)[1]  # dofs, length scale B (mm)
    (130, 4.15)
    """

    def __init__(
        self, tube_od_mm: float, tube_id_mm: float, material: MooneyRivlin, spec: MeshSpec,
        ends: str = "plane-strain",
    ) -> None:
        self.A, self.B = 0.5 * tube_id_mm, 0.5 * tube_od_mm
        mesh = polar_mesh(
            self.A,
            self.B,
            spec.n_radial,
            spec.n_circ,
            theta0=0.0,
            theta1=0.5 * np.pi,
            kind=spec.kind,
        )
        fixed = np.concatenate(
            [
                2 * mesh.grid[:, 0] + 1,  # theta = 0: u_y = 0
                2 * mesh.grid[:, -1],
            ]
        )  # theta = 90 deg: u_x = 0
        super().__init__(mesh, material, spec, fixed, ends=ends)

    def evaluate(
        self, u: np.ndarray, load: float, tangent: bool
    ) -> tuple[float, np.ndarray, sp.csc_matrix | None] | None:
        """Energy (N mm per mm depth), residual (N/mm) and reduced tangent at pressure ``load``.

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
        return energy, R, (self.tangent(st, load) if tangent else None)

    def scales(self, load: float) -> tuple[float, float]:
        """Force scale P*B (N/mm) with a floor, and length scale B (mm).

        Parameters
        ----------
        load : float
            Internal pressure (MPa); floored at 1e-3 MPa.
        """
        return max(load, 1e-3) * self.B, self.B
