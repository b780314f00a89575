"""The tube-wire-hole squeeze problem users ask for (paper §3.4, Figs 6-7).

Units: mm, N, MPa; forces per unit depth in
N/mm, totals = per depth x tube length.
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from exofric import defaults
from exofric.errors import (
    ConvergenceError,
    check_pressures,
)
from exofric.fe import (
    MeshSpec,
    NewtonSettings,
    SqueezeProblem,
    collect_stats,
    nodal_weights,
    solve_path,
    von_mises,
    wall_arc,
    wire_halfwidth,
)
from exofric.geometry import Structure
from exofric.material import HyperelasticModel, MooneyRivlin
from exofric.simulate._common import (
    resolve_accuracy,
)
from exofric.simulate._setup import SqueezeSetup
from exofric.simulate._squeeze_result import ContactOutputs, ErrorEstimate, SqueezeResult
from exofric.simulate._stretch import check_stretch

if TYPE_CHECKING:
    pass

__all__ = ["SqueezeResult", "resolve_accuracy", "squeeze"]



def _direction_deg(f: np.ndarray) -> np.ndarray:
    """Directions (deg from +y, positive toward +x) of the forces ``f`` (k, 2); NaN for 0."""
    f = np.asarray(f, dtype=float).reshape(-1, 2)
    ang = np.degrees(np.arctan2(f[:, 0], f[:, 1])) + 0.0
    return np.where(np.hypot(f[:, 0], f[:, 1]) > 0.0, ang, np.nan)



class _MeshSolution:
    """One squeeze solve on one mesh: the per-pressure outputs and the states behind them."""

    def __init__(self, prob: SqueezeProblem, p: np.ndarray, states: list[np.ndarray],
                 iterations: np.ndarray, path: list[tuple[float, np.ndarray]],
                 fstates: list[tuple[np.ndarray, ...]] | None = None,
                 path_fstates: dict[float, tuple[np.ndarray, ...]] | None = None) -> None:
        self.prob, self.p, self.states, self.iterations = prob, p, states, iterations
        self.path = path
        self.fstates = fstates
        self.path_fstates = path_fstates or {}
        #: per state: 1 / axial stretch, which turns forces per unit reference length (the
        #: problem's) into forces per unit deformed length of tube (what the hole's length
        #: multiplies); 1 in plane strain
        self.per_length = np.array([1.0 / prob.axial_stretch(u) for u in states])
        self.axial_stretch = 1.0 / self.per_length
        self.interfaces = np.array([self._interfaces(u, k) for k, u in enumerate(states)]
                                   ).reshape(-1, 6)
        self.interfaces[:, :4] *= self.per_length[:, None]
        self.profiles = [self._profiles(u, k) for k, u in enumerate(states)]
        #: per output: nodes of the wire's contact patch from its centre to one edge, the
        #: centre included (the half model's count; the full model's both sides folded)
        self.patch_nodes: list[int] = []
        if prob.full:
            self._full_outputs(states)
            return
        rows = []
        for k, u in enumerate(states):
            ch, cw = prob.contact(u)
            self._use(k)
            fh, fw = prob.contact_forces(u)
            xo = prob.nodal(u)[prob.outer]
            rows.append((
                -2.0 * fw[:, 1].sum() + 0.0,  # + 0.0: no negative zero
                2.0 * fh[:, 1].sum() + 0.0,
                wire_halfwidth(xo, cw.gap, prob.wire.center, prob.wire.radius),
                wall_arc(xo, ch.active, prob.hole.radius),
                max(0.0, -float(ch.gap.min()), -float(cw.gap.min())),
            ))
            self.patch_nodes.append(int(cw.active.sum()))
        self.arr = np.array(rows).reshape(-1, 5)
        self.arr[:, :2] *= self.per_length[:, None]
        self.stretch = np.array([prob.body.max_stretch(u) for u in states])
        self.n_dir = np.where(self.arr[:, 0] > 0.0, 0.0, np.nan)
        self.wall_dir = np.where(self.arr[:, 1] > 0.0, 0.0, np.nan)

    def _use(self, k: int) -> None:
        """Give the problem the friction state of output ``k`` (its anchors and bounds)."""
        if self.fstates is not None:
            self.prob.set_friction_state(self.fstates[k])

    def _interfaces(self, u: np.ndarray, k: int) -> tuple[float, ...]:
        """Per-interface integrals at output ``k`` (full section, N/mm; stick fractions).

        ``(S_wire, S_wall, T_wire, T_wall, stick_wire, stick_wall)``: the integrals of the
        normal contact pressure over the wire's and the wall's contact arcs, those of the
        magnitude of the tangential traction, and the share of each contact arc (by
        tributary length) that sticks (NaN without contact or without friction).
        """
        prob = self.prob
        self._use(k)
        ch, cw = prob.contact(u)
        fr = prob.friction(u, (ch, cw))
        half = 1.0 if prob.full else 2.0
        out = [half * float(np.linalg.norm(c.force, axis=1).sum()) for c in (cw, ch)]
        if fr is None:
            return (*out, 0.0, 0.0, np.nan, np.nan)
        out += [half * float(np.abs(f.traction).sum()) for f in (fr[1], fr[0])]
        for f, c in ((fr[1], cw), (fr[0], ch)):
            w = prob.w_outer * c.active
            out.append(float((w * f.stick).sum() / w.sum()) if w.sum() > 0 else np.nan)
        return tuple(out)

    def _profiles(self, u: np.ndarray, k: int) -> dict[str, dict[str, list[float]]]:
        """Contact profiles of output ``k`` along each arc (see :attr:`SqueezeResult.contact`)."""
        prob = self.prob
        self._use(k)
        ch, cw = prob.contact(u)
        fr = prob.friction(u, (ch, cw))
        xo = prob.nodal(u)[prob.outer]
        wc, hc = np.asarray(prob.wire.center), np.asarray(prob.hole.center)
        e = (wc - hc) / np.hypot(*(wc - hc))
        ref = float(np.arctan2(-e[1], -e[0]))       # both arcs centre on the side facing away
        # current tributary lengths: pressures are true (deformed-surface) tractions
        xa = prob.nodal(u)
        w_now = nodal_weights(prob.mesh.boundary_edges("outer"), xa, len(xa))[prob.outer]
        out = {}
        for name, c, f in (("wire", cw, None if fr is None else fr[1]),
                           ("wall", ch, None if fr is None else fr[0])):
            circ = prob.wire if name == "wire" else prob.hole
            d = xo - np.asarray(circ.center)
            ang = np.angle(np.exp(1j * (np.arctan2(d[:, 1], d[:, 0]) - ref)))
            i = np.flatnonzero(c.active)
            i = i[np.argsort(ang[i])]
            w = w_now[i] * prob.axial_stretch(u)  # deformed area per unit reference length
            t = np.zeros(len(i)) if f is None else f.traction[i] / w
            st = np.zeros(len(i), bool) if f is None else f.stick[i]
            out[name] = {"node": prob.outer[i].tolist(),
                         "arc_mm": (circ.radius * ang[i]).tolist(),
                         "angle_deg": np.degrees(ang[i]).tolist(),
                         "pressure_mpa": (np.linalg.norm(c.force[i], axis=1) / w).tolist(),
                         "shear_mpa": t.tolist(), "stick": st.astype(bool).tolist()}
        return out

    def _full_outputs(self, states: list[np.ndarray]) -> None:
        """Outputs of the full model: resultant magnitudes and directions."""
        prob = self.prob
        rows, on_wire, on_tube = [], [], []
        for k, u in enumerate(states):
            self._use(k)
            fw, fh = prob.resultants(u)
            ch, cw = prob.contact(u)
            on_wire.append(fw)
            on_tube.append(fh)
            self.patch_nodes.append((int(cw.active.sum()) + 1) // 2)
            rows.append((float(np.hypot(*fw)), float(np.hypot(*fh)), *prob.contact_extent(u),
                         max(0.0, -float(ch.gap.min()), -float(cw.gap.min()))))
        self.arr = np.array(rows).reshape(-1, 5)
        self.arr[:, :2] *= self.per_length[:, None]
        self.stretch = np.array([prob.body.max_stretch(u) for u in states])
        self.n_dir = _direction_deg(np.array(on_wire))
        self.wall_dir = _direction_deg(np.array(on_tube))

    @property
    def n(self) -> np.ndarray:
        """Squeeze force per depth (N/mm), full section."""
        return self.arr[:, 0]


def _newton_at(prob: SqueezeProblem, u: np.ndarray, p: float, lam0: float,
               s: NewtonSettings) -> np.ndarray:
    """Equilibrium at pressure ``p`` (MPa) from the state ``u`` converged at ``lam0`` (MPa)."""
    return solve_path(prob, [p], s, u0=u, load0=lam0)[0].u


def _release(prob: SqueezeProblem, u: np.ndarray, p: float, s: NewtonSettings,
             fstate: tuple[np.ndarray, ...] | None = None) -> np.ndarray:
    """gravity "none": the equilibrium at ``p`` (MPa) without the floating-mode spring.

    Before the tube bears on both the wall and the wire the spring's force is zero at
    equilibrium (nothing pushes the tube vertically), so the state is kept; after, the spring
    is removed and Newton re-converges from the state (the contacts hold the tube).
    """
    if prob.spring_k == 0.0 or prob.bearing_gap(u) > 0.0:
        return u
    k = prob.spring_k
    if fstate is not None:
        prob.set_friction_state(fstate)
    try:
        prob.spring_k = 0.0
        return _newton_at(prob, u, p, p, s)
    finally:
        prob.spring_k = k


def _solve_mesh(setup: SqueezeSetup, p: np.ndarray, spec: MeshSpec, settings: NewtonSettings,
                release: bool = True) -> _MeshSolution:
    """Follow the load path on one mesh; release the regulariser at each output (gravity none).

    With ``release``, the floating-mode spring is also taken out of the path itself at the
    first sub-step where the tube bears on wall and wire (the contacts hold it from there):
    later sub-steps converge without it, so only the outputs up to that sub-step need a
    release solve (one Newton attempt each; they were ~15% of a default squeeze's attempts).
    """
    # SqueezeProblem reads only shear_modulus (and its body the kernel): either type serves
    prob = SqueezeProblem(setup.structure, cast(MooneyRivlin, setup.fe_material), spec,
                          setup.penalty, setup.density, setup.gravity, setup.regulariser,
                          setup.angle_deg, setup.rotation_regulariser, setup.full,
                          mu_wall=setup.mu[0], mu_wire=setup.mu[1],
                          friction_penalty=setup.friction_penalty, ends=setup.ends)
    path: list[tuple[float, np.ndarray]] = []
    spring = prob.spring_k
    freed_at = np.inf  # the load (MPa) of the sub-step after which the spring is out
    fric = prob.frictional
    path_fstates: dict[float, tuple[np.ndarray, ...]] = {}
    if fric:
        path_fstates[0.0] = prob.friction_state()

    def record(lam: float, u: np.ndarray) -> None:
        nonlocal freed_at
        path.append((lam, u.copy()))
        if fric:
            path_fstates[lam] = prob.friction_state()
        if release and prob.spring_k != 0.0 and prob.bearing_gap(u) <= 0.0:
            prob.spring_k, freed_at = 0.0, lam

    try:
        pts = solve_path(prob, p, settings, on_step=record)
    finally:
        prob.spring_k = spring
    if p[0] == 0.0:
        path.insert(0, (0.0, pts[0].u.copy()))
    states = [pt.u for pt in pts]
    fstates = [_nearest(path_fstates, float(pt.load)) for pt in pts] if fric else None
    if setup.gravity == "none" and release:
        out = []
        for k, pt in enumerate(pts):
            if pt.load <= freed_at + 1e-12:
                out.append(_release(prob, pt.u, float(pt.load), settings,
                                    None if fstates is None else fstates[k]))
                if fstates is not None:
                    fstates[k] = prob.friction_state()
            else:
                out.append(pt.u)
        states = out
    return _MeshSolution(prob, p, states, np.array([pt.iterations for pt in pts]), path,
                         fstates, path_fstates)


def _nearest(states: dict[float, tuple[np.ndarray, ...]], lam: float) -> tuple[np.ndarray, ...]:
    """The friction state recorded at the sub-step nearest to the load ``lam`` (MPa)."""
    key = min(states, key=lambda k: abs(k - lam))
    return states[key]


def _start_state(prob: SqueezeProblem, s: NewtonSettings) -> np.ndarray:
    """Equilibrium at P = 0 (mm)."""
    return solve_path(prob, [0.0], s)[0].u


def _bracket_onset(sol: _MeshSolution, s: NewtonSettings, tol_mpa: float) -> float | None:
    """Pressure (MPa) where the tube first bears on both wall and wire, bracketed to ``tol_mpa``.

    The gap to the obstacle touched last (:meth:`SqueezeProblem.bearing_gap`) of the
    equilibrium is positive before the squeeze and zero or negative (penalty penetration)
    after, and continuous in P, so Brent's method on it converges to the touch. The bracket
    is the first pair of converged path sub-steps across which the gap changes sign; each
    probe starts Newton from the linear interpolation of the two bracketing states. (With
    gravity "none" the floating-mode spring carries no force before the touch, so the path's
    states are the unregularised ones there.)
    """
    from exofric._roots import brentq  # not scipy.optimize: 0.15 s of start-up

    prob = sol.prob
    path = [(lam, u) for lam, u in sol.path if lam <= sol.p[-1] + 1e-15]
    k = next((i for i, (_, u) in enumerate(path) if prob.bearing_gap(u) <= 0.0), None)
    if k is None:
        return None
    if k == 0 and path[0][0] > 0.0:  # bracket from the start (P = 0), not a recorded sub-step
        path.insert(0, (0.0, _start_state(prob, s)))
        k = 0 if prob.bearing_gap(path[0][1]) <= 0.0 else 1
    if k == 0:
        return 0.0
    lam_a, u_a = path[k - 1]
    lam_b, u_b = path[k]
    ends = {lam_a: prob.bearing_gap(u_a), lam_b: prob.bearing_gap(u_b)}

    start = _nearest(sol.path_fstates, lam_a) if prob.frictional else None

    def g(lam: float) -> float:
        if lam in ends:
            return ends[lam]
        guess = u_a + (lam - lam_a) / (lam_b - lam_a) * (u_b - u_a)
        if start is not None:  # friction: the probe continues the path from lam_a
            prob.set_friction_state(start)
        try:
            u = _newton_at(prob, guess, lam, lam, s)
        except ConvergenceError:  # along the path from the last state below
            if start is not None:
                prob.set_friction_state(start)
            u = _newton_at(prob, u_a, lam, lam_a, s)
        return prob.bearing_gap(u)

    return float(brentq(g, lam_a, lam_b, xtol=tol_mpa, rtol=1e-12, maxiter=60))


def _relative_pct(fine: np.ndarray, coarse: np.ndarray) -> np.ndarray:
    """|fine - coarse| / fine in %; 0 where both are 0, 100 where only the coarse is > 0."""
    diff = np.abs(fine - coarse)
    with np.errstate(divide="ignore", invalid="ignore"):
        pct = np.where(fine > 0.0, 100.0 * diff / np.where(fine > 0.0, fine, 1.0),
                       np.where(diff > 0.0, 100.0, 0.0))
    return np.asarray(pct)


def _solve_levels(
    setup: SqueezeSetup, p: np.ndarray, spec: MeshSpec, coarse_spec: MeshSpec | None,
    s: NewtonSettings,
) -> tuple[_MeshSolution, float | None, dict[str, Any]]:
    """(solution, onset MPa, the :class:`ErrorEstimate` fields from the nested mesh)."""
    sol = _solve_mesh(setup, p, spec, s)
    if coarse_spec is None:
        return sol, _bracket_onset(sol, s, setup.onset_tol_mpa), {}
    # The coarse mesh only serves the estimate: its states keep the floating-mode spring
    # (a share ~ spring / contact stiffness ~ 1e-4 of N, far below the estimate's size),
    # and it brackets the onset, which is geometric (the free tube spanning wall to wire):
    # the two meshes' onsets agree to ~1e-5 MPa, bracketed to onset_tol_mpa on the cheaper.
    # its N enters only the estimate (% level): Newton to 1e-7 instead of 1e-9 suffices
    loose = replace(s, tol_r=max(s.tol_r, 1e-7), tol_u=max(s.tol_u, 1e-8))
    coarse = _solve_mesh(setup, p, coarse_spec, loose, release=False)
    onset = _bracket_onset(coarse, s, setup.onset_tol_mpa)
    patch = np.array(coarse.patch_nodes)
    est_pct, reliable = _estimate(p, sol.n, coarse.n, patch)
    est_abs = np.where(sol.n > 0.0, 0.01 * est_pct * sol.n,
                       defaults.ESTIMATE_SAFETY_FACTOR * np.abs(sol.n - coarse.n))
    # the friction force along the wire's arc (issue 35): the same two-mesh estimate of its
    # own (it converges far more slowly than N: a traction, not a resultant, on 2-5 nodes)
    t, t_coarse = sol.interfaces[:, 2], coarse.interfaces[:, 2]
    t_pct = (_estimate(p, t, t_coarse, patch)[0]
             if np.any(t > 0.0) or np.any(t_coarse > 0.0) else None)
    return sol, onset, {"pct": est_pct, "n_per_mm": est_abs, "coarse_n_per_mm": coarse.n.copy(),
                        "reliable": reliable, "wire_tangential_pct": t_pct}


def _estimate(p: np.ndarray, n: np.ndarray, n_coarse: np.ndarray,
              coarse_patch: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(error estimate of N in %, reliable?) per pressure from the two meshes' N (N/mm).

    Fs |N - N_coarse| / N (Fs = :data:`~exofric.defaults.ESTIMATE_SAFETY_FACTOR`), then the
    largest of it over the outputs within :data:`~exofric.defaults.ESTIMATE_WINDOW_MPA` that
    have contact (the difference oscillates in sign as the patch edges pass the nodes, so its
    amplitude, not its value at one pressure, measures the error), at least
    :data:`~exofric.defaults.ESTIMATE_FLOOR_PCT` where N > 0, at most 100. Unreliable where
    the coarse mesh's wire patch has fewer than
    :data:`~exofric.defaults.ESTIMATE_MIN_PATCH_NODES` nodes (it cannot resolve the patch:
    the two meshes are not both in the range where their difference scales like the error),
    or where one mesh has wire contact and the other not.
    """
    fs, floor = defaults.ESTIMATE_SAFETY_FACTOR, defaults.ESTIMATE_FLOOR_PCT
    raw = np.minimum(fs * _relative_pct(n, n_coarse), 100.0)
    near = np.abs(p[:, None] - p[None, :]) <= defaults.ESTIMATE_WINDOW_MPA + 1e-12
    near &= (n > 0.0)[None, :]
    pct = np.where(n > 0.0, np.max(np.where(near, raw[None, :], 0.0), axis=1), raw)
    pct = np.where(n > 0.0, np.clip(pct, floor, 100.0), pct)
    reliable = ((n > 0.0) == (n_coarse > 0.0)) & (
        (n == 0.0) | (coarse_patch >= defaults.ESTIMATE_MIN_PATCH_NODES))
    return pct, reliable


def squeeze(
    structure: Structure,
    material: MooneyRivlin | HyperelasticModel,
    pressures_mpa: np.ndarray | list[float],
    *,
    accuracy: str | None = None,
    mesh: MeshSpec | None = None,
    gravity: str = defaults.GRAVITY,
    penalty: float = defaults.CONTACT_PENALTY_N_PER_MM3,
    density: float = defaults.SILICONE_DENSITY_T_PER_MM3,
    settings: NewtonSettings | None = None,
    keep_fields: bool = True,
    onset_tol_mpa: float = 2e-4,
    regulariser: float = defaults.REGULARISER_SPRING_REL,
    wire_angle_deg: float = 0.0,
    rotation_regulariser: float = defaults.ROTATION_SPRING_REL,
    full_model: bool = False,
    mu_wall: float = 0.0,
    mu_wire: float = 0.0,
    friction_penalty: float | None = None,
    ends: str = "plane-strain",
) -> SqueezeResult:
    """Squeezing force N(P) between the inflated tube and the wire (paper §3.4, Figs 6-7).

    Plane strain, half model through the line of centres, large deformation,
    mixed u/p Mooney-Rivlin tube, follower pressure, frictionless penalty contact
    with the rigid hole and wire.

    With a named ``accuracy`` the problem is solved on two nested meshes
    (:data:`exofric.defaults.SQUEEZE_ACCURACY`, graded toward both contacts); the finer
    one's answer is returned and three times their relative difference (Roache's two-grid
    GCI), at its largest over the outputs within 0.05 MPa, is the error estimate
    ``n_error_estimate_pct``, which bounds the returned answer's discretisation error in the
    mesh studies of docs/formulation.md section 6. Where the coarse mesh does not resolve the
    wire's contact patch (typically the first output after the onset) the estimate is
    flagged unreliable (``estimate.reliable``). With an explicit ``mesh`` one solve is made
    and no estimate is given.

    Parameters
    ----------
    structure : Structure
        Hole, tube and wire (mm) and tube length (mm).
    material : MooneyRivlin or HyperelasticModel
        Tube material: Mooney-Rivlin constants, or a neo-Hookean, Mooney-Rivlin, Yeoh or
        Ogden model from :func:`~exofric.material.material_model`.
    pressures_mpa : array-like
        Strictly increasing pressures (MPa), in [0, 2].
    accuracy : {'draft', 'standard', 'fine'}, optional
        Named accuracy level (default :data:`exofric.defaults.ACCURACY`, ``'standard'``:
        within 1% of the mesh-converged N from the first pressure where N >= 1% of
        N(0.6 MPa) on the paper's structures). Not together with ``mesh``.
    mesh : MeshSpec, optional
        An explicit half-tube mesh instead of a named level (no error estimate).
    gravity : {'none', 'toward-wall', 'toward-wire'}
        The tube's weight (``density`` x g) left out (default), pulling it onto the hole
        wall, or onto the wire (N then includes the weight).
    penalty : float
        Contact penalty (N/mm^3), > 0.
    density : float
        Tube density (t/mm^3), > 0: the weight with gravity on (unused with ``'none'``).
    settings : NewtonSettings, optional
        Solver settings (default: :data:`exofric.defaults.SQUEEZE_NEWTON`).
    keep_fields : bool
        Keep displacements and stresses for plots/export.
    onset_tol_mpa : float
        Tolerance (MPa) of the bracketed contact-onset pressure, > 0.
    regulariser : float
        With gravity ``'none'``: stiffness of the spring that holds the floating tube before
        it bears on wall and wire, relative to the shear modulus (unitless, > 0). The
        spring carries no force at the reported states, so N does not depend on it.
    wire_angle_deg : float
        Angle of the wire centre from the top of the hole, i.e. from the position opposite
        the tube's contact with the wall (deg, |a| < 90, positive toward +x). 0 (default) is
        the half model; any other angle solves the full 360 deg section, 1.9-3.1 x the
        CPU time (docs/formulation.md section 4); only with ``gravity="none"``. Without
        gravity the frictionless tube slides along the wall until it lies opposite the wire,
        so N is the centred wire's and only its direction turns by the angle.
    rotation_regulariser : float
        Full model: stiffness of the spring on the tube's rotation about its own axis (a
        zero-energy mode), relative to mu B^2 (unitless, > 0). It carries no force at the
        reported states, so N does not depend on it.
    full_model : bool
        Solve the full section also at angle 0 (a check against the half model; the mesh is
        the half model's and its mirror image, ``2 n_circ`` elements around).

    mu_wall, mu_wire : float
        Coulomb friction coefficients (unitless, [0, 2]; a warning above 1.5) of the tube on
        the hole wall and on the wire, in the plane of the section (issue 15; see
        ``docs/formulation.md`` 4a). 0 (default): frictionless, as in the paper.
    friction_penalty : float, optional
        Tangential penalty (N/mm^3: MPa of shear traction per mm of elastic slip); default:
        :data:`exofric.defaults.FRICTION_PENALTY_REL` x ``penalty`` (1e3 N/mm^3).
    ends : {'plane-strain', 'closed', 'open'}
        The tube's axial condition: plane strain (default, the paper's model), closed ends
        (the caps carry P times the deformed cavity area) or open ends (no axial force),
        with one uniform axial stretch (generalised plane strain; frictionless along the
        axis). Forces are then per unit *deformed* length, the length inside the hole.

    Returns
    -------
    SqueezeResult

    Raises
    ------
    InputError
        Bad pressures, an unknown ``accuracy`` or ``gravity``, or both ``accuracy`` and
        ``mesh``.
    ConvergenceError
        If the solver cannot reach a pressure (the message names it).

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.3, 0.6], keep_fields=False)
    >>> [round(float(n), 1) for n in r.squeeze_force_n]
    [47.8, 240.5]
    >>> r.estimate.accuracy, r.mesh.n_circ, bool(r.estimate.pct[-1] < 1.0)  # % of N
    ('standard', 32, True)
    """

    return SqueezeSetup(
        structure, material, ends=ends, mu_wall=mu_wall, mu_wire=mu_wire,
        friction_penalty=friction_penalty, accuracy=accuracy, mesh=mesh, gravity=gravity,
        wire_angle_deg=wire_angle_deg, full_model=full_model, penalty=penalty, density=density,
        settings=settings, onset_tol_mpa=onset_tol_mpa, regulariser=regulariser,
        rotation_regulariser=rotation_regulariser, keep_fields=keep_fields,
    ).solve(pressures_mpa)


def _contact_outputs(sol: _MeshSolution, prob: SqueezeProblem) -> ContactOutputs:
    """The contact group of a solved mesh: arcs, penetration, integrals, friction, profiles."""
    arr, itf = sol.arr, sol.interfaces
    return ContactOutputs(
        wire_contact_halfwidth_mm=arr[:, 2],
        wall_contact_arc_mm=arr[:, 3],
        max_penetration_mm=arr[:, 4],
        friction_penalty=prob.penalty_t,
        wire_pressure_integral_n_per_mm=itf[:, 0],
        wall_pressure_integral_n_per_mm=itf[:, 1],
        wire_tangential_force_n_per_mm=itf[:, 2],
        wall_tangential_force_n_per_mm=itf[:, 3],
        stick_fraction_wire=itf[:, 4],
        stick_fraction_wall=itf[:, 5],
        profiles=tuple(sol.profiles),
        friction_dissipation_n_per_mm=(np.asarray(prob.dissipation, float)
                                       if prob.frictional else None),
    )


def solve_setup(setup: SqueezeSetup, pressures_mpa: Any) -> SqueezeResult:
    """:meth:`SqueezeSetup.solve`: the squeeze of a validated setup at pressures (MPa)."""
    p = check_pressures("pressures_mpa", pressures_mpa, max_mpa=2.0)
    structure, angle = setup.structure, setup.angle_deg
    level, spec, coarse_spec = setup.levels()
    t0 = time.perf_counter()
    with collect_stats() as counted:
        sol, onset, est = _solve_levels(setup, p, spec, coarse_spec, setup.newton)
    dt = time.perf_counter() - t0
    prob = sol.prob
    L = structure.length_mm
    arr = sol.arr
    check_stretch(sol.stretch, p, f"squeeze of {structure.name or 'the structure'}")
    disp: tuple[np.ndarray, ...] = ()
    vm: tuple[np.ndarray, ...] = ()
    if setup.keep_fields:
        n2 = prob.n_nodal
        disp = tuple(u[:n2].reshape(-1, 2).copy() for u in sol.states)
        vm = tuple(von_mises(prob.body.cauchy_stress(u[:n2], prob.axial_stretch(u))).mean(axis=1)
                   for u in sol.states)
    weight = prob.weight_per_mm() if setup.gravity != "none" else 0.0
    return SqueezeResult(
        pressure_mpa=p,
        squeeze_force_n_per_mm=arr[:, 0],
        squeeze_force_n=arr[:, 0] * L,
        wall_force_n_per_mm=arr[:, 1],
        wall_force_n=arr[:, 1] * L,
        max_stretch=sol.stretch,
        newton_iterations=sol.iterations,
        contact_onset_pressure_mpa=onset,
        weight_n_per_mm=weight,
        dofs=prob.n_dofs,
        solve_time_s=dt,
        setup=setup,
        mesh=spec,
        symmetry=("half model: u_x = 0 on the plane x = 0 through the hole, tube and wire centres"
                  if not prob.full else f"full model (no symmetry): wire at {angle:g} deg from "
                  "the top; translations held by the contacts, rotation by a spring"),
        nodes=prob.mesh.nodes.copy(),
        elements=prob.mesh.elements.copy(),
        displacements=disp,
        von_mises_mpa=vm,
        estimate=ErrorEstimate(accuracy=level, mesh=coarse_spec, **est),
        solver_stats=counted.stats,
        squeeze_force_direction_deg=sol.n_dir,
        wall_force_direction_deg=sol.wall_dir,
        contact=_contact_outputs(sol, prob),
        axial_stretch=sol.axial_stretch,
    )
