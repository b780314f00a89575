"""Newton with line search, and load stepping with cutback.

(The sparse assembly and banded solve are in ``_assembly``, the work statistics in ``_stats``.)

Convergence (stated tolerances): a load step is converged when the infinity norm
of the free residual is below ``tol_r * force_scale`` (default 1e-9 relative,
force_scale = pressure x size) AND the last Newton increment is below
``tol_u * length_scale`` (default 1e-10 relative). A step that does not converge
in ``max_iter`` iterations is cut back (halved) up to ``max_cutbacks`` times;
then :class:`~exofric.errors.ConvergenceError` names the last load reached.
Never is an unconverged state returned.
"""

from __future__ import annotations

import contextlib
import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Protocol

import numpy as np
import scipy.sparse as sp
from scipy.linalg import LinAlgError
from scipy.sparse.linalg import MatrixRankWarning, splu
from threadpoolctl import ThreadpoolController

from exofric import defaults
from exofric._validate import checked_init
from exofric.errors import ConvergenceError
from exofric.fe._assembly import Assembler
from exofric.fe._divergence import explain_failure
from exofric.fe._stats import collecting, record_attempt

__all__ = ["Problem", "NewtonSettings", "solve_path", "PathPoint"]


class Problem(Protocol):
    """What :func:`solve_path` needs from a discretised problem.

    Attributes
    ----------
    n_dofs : int
        Number of dofs (2 per node).
    free : ndarray of bool (n_dofs,)
        True for unknown (unconstrained) dofs.

    Examples
    --------
    >>> from exofric.fe import InflationProblem, MeshSpec
    >>> from exofric.material import MooneyRivlin
    >>> p: Problem = InflationProblem(8.3, 4.97, MooneyRivlin.from_shore(62.5), MeshSpec())
    >>> p.n_dofs
    130
    """

    n_dofs: int
    free: np.ndarray

    def evaluate(
        self, u: np.ndarray, load: float, tangent: bool
    ) -> tuple[float, np.ndarray, sp.csc_matrix | None] | None:
        """(energy, full residual, reduced tangent or None); None if the state is invalid.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        load : float
            Load level (MPa for pressure).
        tangent : bool
            Also assemble the reduced tangent matrix.
        """
        ...

    def scales(self, load: float) -> tuple[float, float]:
        """(force scale in N per mm depth, length scale in mm) for the tolerances.

        Parameters
        ----------
        load : float
            Load level (MPa for pressure).
        """
        ...


@checked_init
@dataclass(frozen=True)
class NewtonSettings:
    """Solver settings (tolerances are relative to the problem's scales).

    Defaults: :data:`exofric.defaults.NEWTON`.

    Parameters
    ----------
    tol_r : float
        Residual tolerance (unitless), relative to the problem's force scale (N/mm), > 0.
    tol_u : float
        Increment tolerance (unitless), relative to the problem's length scale (mm), > 0.
    max_iter : int
        Newton iterations per sub-step before a cut-back, >= 1.
    max_cutbacks : int
        Halvings of a failed sub-step before :class:`~exofric.errors.ConvergenceError`.
    max_step : float
        Largest load sub-step, in ``load_unit`` (MPa for pressure), > 0.
    min_step : float
        Smallest load sub-step, in ``load_unit`` (MPa for pressure), > 0.
    line_search_halvings : int
        Line-search evaluations allowed after the full Newton step (halvings, or steps of
        the bracketing search for the energy minimum along the step), >= 0.
    extrapolate : bool
        Start each sub-step from a secant predictor (not for frictional problems). An
        attempt from the predictor takes full Newton steps only, with at most two active-set
        re-solves per direction; when it fails, the sub-step is retried from the last
        converged state and the rest of the path goes without the predictor.
    active_set_iterations : int
        Re-solves of a Newton direction allowed to a problem with contact
        (``refine_direction``): nodes that the linearised step would run into an obstacle
        join the tangent and the direction is solved again, >= 0 (0: plain Newton).
    stagnation_ratio : float
        An attempt whose last two steps were damped and whose residual fell by less than
        this factor over them is abandoned (cut back) at once, in [0, 1) (0: never).
    chord_step : float
        Newton steps no longer than this (unitless, relative to the problem's length scale,
        mm) are taken to be in the terminal phase, where the tangent barely changes: the
        next direction reuses the last factorisation (a chord step) while each such step cuts
        the residual at least tenfold, >= 0 (0: a fresh tangent every iteration).
    threads : int
        BLAS/OpenMP threads the solve may use (:func:`solve_path` limits the thread pools
        with threadpoolctl while it runs), >= 1; 0 leaves the pools as they are.
    load_name, load_unit : str
        Name and unit of the load in messages (``"pressure"``, ``"MPa"``).

    Examples
    --------
    >>> NewtonSettings(max_step=0.025).max_step
    0.025
    """

    tol_r: float = defaults.NEWTON["tol_r"]
    tol_u: float = defaults.NEWTON["tol_u"]
    max_iter: int = defaults.NEWTON["max_iter"]
    max_cutbacks: int = defaults.NEWTON["max_cutbacks"]
    max_step: float = defaults.NEWTON["max_step"]
    min_step: float = defaults.NEWTON["min_step"]
    line_search_halvings: int = defaults.NEWTON["line_search_halvings"]
    extrapolate: bool = defaults.NEWTON["extrapolate"]
    active_set_iterations: int = defaults.NEWTON["active_set_iterations"]
    stagnation_ratio: float = defaults.NEWTON["stagnation_ratio"]
    chord_step: float = defaults.NEWTON["chord_step"]
    threads: int = defaults.BLAS_THREADS
    load_name: str = "pressure"
    load_unit: str = "MPa"


@checked_init
@dataclass
class PathPoint:
    """A converged state at one requested load.

    Parameters
    ----------
    load : float
        The requested load (MPa for pressure).
    u : ndarray (n_dofs,)
        Converged nodal displacements (mm).
    iterations : int
        Newton iterations spent reaching it (all sub-steps).
    steps : int
        Load sub-steps taken from the previous requested load.
    info : dict of str to float
        Extra diagnostics (problem-specific; empty by default).

    Examples
    --------
    >>> import numpy as np
    >>> PathPoint(0.2, np.zeros(4), 5, 1).load
    0.2
    """

    load: float
    u: np.ndarray
    iterations: int
    steps: int
    info: dict[str, float] = field(default_factory=dict)


def _accept(e_t: float, r_t: float, e0: float, r0: float, slope: float, r_tol: float) -> bool:
    """Line-search acceptance.

    For a descent direction (``slope = alpha R.d < 0``) the energy must decrease (Armijo,
    c = 1e-4): the energy then is a Lyapunov function and Newton cannot cycle between
    contact active sets. Where energy differences drown in round-off (converged states), or
    the direction is not a descent direction, a decrease of the residual norm is accepted.
    """
    if r0 <= r_tol:
        return True
    noise = 1e-13 * max(1.0, abs(e0))
    if slope < 0.0 and abs(slope) > noise:
        return e_t <= e0 + 1e-4 * slope
    return r_t < r0


#: Curvature condition of the bracketing search (strong Wolfe): a shortened step is accepted
#: only where |R(u + a d) . d| <= _WOLFE_ETA |R(u) . d|, i.e. near the minimum along the line.
#: 0.1: before a contact kink s(a) ~ s(0) (1 - a), so a step short of the kink is refused
#: unless it is within 10% of the full one (see _line_search).
_WOLFE_ETA = 0.1

#: What Problem.evaluate returns: (energy N mm per mm, residual N per mm, tangent or None).
_Evaluation = tuple[float, np.ndarray, sp.csc_matrix | None]


def _line_search(
    problem: Problem, u: np.ndarray, step: np.ndarray, load: float, energy: float,
    rnorm: float, s0: float, r_tol: float, budget: int, tangent: bool = True,
) -> tuple[float, _Evaluation] | None:
    """(alpha, evaluation at ``u + alpha step``) accepted by the line search, or None.

    1. The full Newton step (evaluated with the tangent if ``tangent``: the caller expects
       it to be the next iterate and to need one) is taken when :func:`_accept` holds
       (Armijo). Invalid states (inverted elements) and steps that neither decrease the
       energy nor bracket its minimum along the line are halved. Shortened trials are
       evaluated without a tangent.
    2. When a step fails Armijo but the directional derivative s(a) = R(u + a d) . d has
       changed sign (s(0) < 0 < s(a)), the energy's minimum along the line lies in (0, a).
       A bracketing search then looks for a step satisfying Armijo AND the curvature
       condition |s| <= ``_WOLFE_ETA`` |s(0)| (strong Wolfe), i.e. near that minimum.

    Why not the first Armijo point (plain backtracking, or the secant shortening used
    before): when the full step runs a node that is not yet in contact into an obstacle
    (the linearised problem does not see that contact), the penalty makes s(a) kink sharply
    upward where the node touches, and the energy's minimum along the line sits just past
    that kink. A secant through s(0) and s(1) lands far short of it, where Armijo already
    holds; the node stays out of contact, the next Newton step aims at the same point
    again, and the iteration creeps a few per cent per step to the iteration limit (fine
    meshes at P = 0, whose nodes next to the first contact are close to the wall). The
    curvature condition takes the step to the minimum, past the kink: the next tangent
    contains the new contact and Newton converges quadratically again. The energy still
    decreases at every accepted step (Armijo), so Newton cannot cycle between active sets.

    The search's proposals model the energy along the line as the Newton quadratic
    e0 + s0 a - s0 a^2 / 2 (its curvature d.K.d = -s0) plus one penalty term
    k/2 (a - a_c)^2 switching on at a kink a_c; k and a_c follow from the energy and slope
    at the bracket's upper end, and the proposal is the model's root of s. For one node
    entering contact the model is exact up to the curvature of the gap, and one evaluation
    lands at the minimum. Proposals outside the bracket, or after a step that did not halve
    it, are bisections, so the bracket shrinks at least by half every two evaluations. At
    most ``budget`` evaluations follow the full step; if they run out, the lowest-energy
    Armijo point seen is taken.
    """
    free = problem.free
    d = step[free]
    noise = 1e-13 * max(1.0, abs(energy))
    descent = s0 < 0.0 and abs(s0) > noise
    evals = 0

    def trial(alpha: float, tangent: bool) -> tuple[_Evaluation | None, float, float]:
        """Evaluation at ``u + alpha step``, its residual norm and s(alpha) (nan if invalid)."""
        nonlocal evals
        evals += 1
        t = problem.evaluate(u + alpha * step, load, tangent)
        if t is None:
            return None, np.nan, np.nan
        rt = t[1][free]
        r_t = float(np.max(np.abs(rt))) if rt.size else 0.0
        return t, r_t, float(rt @ d)

    alpha = 1.0
    while True:
        t, r_t, s_hi = trial(alpha, alpha == 1.0 and tangent)
        if t is not None and np.isfinite(r_t):
            if _accept(t[0], r_t, energy, rnorm, alpha * s0, r_tol):
                return alpha, t
            if descent and s_hi > 0.0:
                break  # the line minimum is bracketed by (0, alpha)
        if evals > budget:
            return None
        alpha *= 0.5

    # bracketing search on s(a) in (lo, hi), proposals from the kink model (docstring)
    lo, hi, e_hi = 0.0, alpha, t[0] if t is not None else np.inf
    best: tuple[float, _Evaluation] | None = None
    bisect = False
    while evals <= budget:
        a = np.nan
        delta = s_hi - s0 * (1.0 - hi)  # slope above the Newton model's (> 0 here)
        excess = e_hi - (energy + s0 * hi * (1.0 - 0.5 * hi))  # energy above it (> 0)
        if not bisect and delta > 0.0 and excess > 0.0:
            k = delta * delta / (2.0 * excess)
            a_c = hi - 2.0 * excess / delta
            a = (k * a_c - s0) / (k - s0)
        if not lo < a < hi:
            a = 0.5 * (lo + hi)
        width = hi - lo
        t, _, s_t = trial(a, False)
        if t is None or not np.isfinite(s_t):
            hi, s_hi, e_hi = a, np.nan, np.inf  # an invalid state: bisect towards lo
            continue
        if t[0] <= energy + 1e-4 * a * s0:
            if abs(s_t) <= _WOLFE_ETA * abs(s0):
                return a, t
            if best is None or t[0] < best[1][0]:
                best = (a, t)
        if s_t > 0.0:
            hi, s_hi, e_hi = a, s_t, t[0]
        else:
            lo = a
        bisect = hi - lo > 0.5 * width
    return best


_STAGNATION_WINDOW = 4


def _stagnating(history: Sequence[tuple[float, float]], rnorm: float, ratio: float) -> bool:
    """True when Newton creeps: damped steps that no longer reduce the residual.

    ``history`` holds (residual norm, accepted step length) of the iterations so far and
    ``rnorm`` is the current residual norm. Stagnation: the last ``_STAGNATION_WINDOW``
    steps were all damped by the line search (step length < 1) and the residual is above
    ``ratio`` times the one before them. Newton's quadratic (or, with an inexact tangent,
    fast linear) phase takes full steps, so it is never cut; a creeping attempt is stopped
    after a few iterations instead of running to ``max_iter`` (and, from the predictor, a
    second time from the last state). ``ratio`` 0 disables the test. The window (4) and the
    ratio (0.5) are the best of those tried on the base group's squeeze from 2 x 24 to
    8 x 128 (windows 2-4, ratios 0.25-0.8): a shorter window also stopped attempts that
    would have converged.

    Examples
    --------
    >>> _stagnating([(9.0, 0.1), (8.0, 0.2), (7.0, 0.1), (6.0, 0.3)], 5.0, 0.5)
    True
    >>> _stagnating([(9.0, 0.1), (8.0, 1.0), (7.0, 0.1), (6.0, 0.3)], 5.0, 0.5)
    False
    """
    if ratio <= 0.0 or len(history) < _STAGNATION_WINDOW:
        return False
    last = history[-_STAGNATION_WINDOW:]
    return all(a < 1.0 for _, a in last) and rnorm > ratio * last[0][0]


class _Linear:
    """The linear algebra of one Newton attempt: the last tangent, its factors, the counts.

    ``counter[1]`` counts factorisations (the active-set re-solves included); a chord step
    (:func:`_newton_attempt`) solves with the stored factors and adds none, nor does an
    active-set re-solve done as a low-rank update of them (:meth:`solve`).
    """

    def __init__(self, problem: Problem, counter: list[int]) -> None:
        asm = getattr(problem, "assembler", None)
        self._factorize: Callable[[sp.csc_matrix], _Factor] = (
            asm.factorize if isinstance(asm, Assembler) else _superlu)
        self._counter = counter
        self.K: sp.csc_matrix | None = None  # the tangent behind ``factor``
        self.factor: _Factor | None = None

    def set_tangent(self, K: sp.csc_matrix) -> None:
        """Factorise a new tangent (N/mm per mm depth) for the next solves."""
        self.factor = None
        self._counter[1] += 1
        self.factor = self._factorize(K)
        self.K = K

    def solve(self, A: sp.csc_matrix, b: np.ndarray) -> np.ndarray:
        """Solve with a matrix of its own (the active-set re-solves): a low-rank update of the
        tangent's factors where ``A`` differs from the tangent in a few dofs, else factorised."""
        x = self._update_solve(A, b)
        if x is not None:
            return x
        self._counter[1] += 1
        return self._factorize(A).solve(b)

    def _update_solve(self, A: sp.csc_matrix, b: np.ndarray) -> np.ndarray | None:
        """``A x = b`` by the Woodbury identity on the tangent's factors, or None.

        ``A = K + U C U^T`` with ``U`` the unit columns of the p dofs whose rows or columns
        differ (a node entering contact, a stick/slip switch: 2 dofs a node) and ``C`` the
        difference there; then ``x = x0 - Z C (I + Z_J C)^-1 x0_J`` with ``x0 = K^-1 b``,
        ``Z = K^-1 U`` (one sweep of the factors with p + 1 right-hand sides; a single one
        costs ~1/15-1/30 of a factorisation on the squeeze's meshes) and ``_J`` the rows of
        those dofs. None (factorise instead) for another pattern, more than ``_UPDATE_DOFS``
        dofs, or a solution whose residual is above ``_UPDATE_RTOL`` of ``|A| |x| + |b|`` (an
        ill-conditioned update).
        """
        K, f = self.K, self.factor
        if (K is None or f is None or A.shape != K.shape or A.nnz != K.nnz
                or not (A.indptr is K.indptr or np.array_equal(A.indptr, K.indptr))
                or not (A.indices is K.indices or np.array_equal(A.indices, K.indices))):
            return None
        diff = A.data - K.data
        nz = np.flatnonzero(diff)
        rows = A.indices[nz]
        cols = np.searchsorted(A.indptr, nz, side="right") - 1
        dofs = np.union1d(rows, cols)
        if dofs.size > _UPDATE_DOFS:
            return None
        C = np.zeros((dofs.size, dofs.size))
        np.add.at(C, (np.searchsorted(dofs, rows), np.searchsorted(dofs, cols)), diff[nz])
        rhs = np.zeros((b.size, dofs.size + 1))  # b and the unit columns: one sweep
        rhs[:, 0] = b
        rhs[dofs, np.arange(1, dofs.size + 1)] = 1.0
        sol = f.solve(rhs)
        x0, Z = sol[:, 0], sol[:, 1:]
        try:
            y = np.linalg.solve(np.eye(dofs.size) + Z[dofs] @ C, x0[dofs])
        except LinAlgError:
            return None
        x = x0 - Z @ (C @ y)
        scale = float(np.max(np.abs(A.data))) * float(np.max(np.abs(x))) + float(
            np.max(np.abs(b)))
        if not (np.all(np.isfinite(x)) and np.max(np.abs(A @ x - b)) <= _UPDATE_RTOL * scale):
            return None
        return x


#: Largest number of dofs in which an active-set matrix may differ from the factorised tangent
#: for a low-rank update (:meth:`_Linear.solve`; 7 nodes: p + 1 solves cost about one
#: factorisation on the 8 x 128 mesh, far less on coarser ones), and the residual it must reach
#: relative to ``|A| |x| + |b|`` (a direct solve reaches ~1e-16 x the condition number).
_UPDATE_DOFS = 14
_UPDATE_RTOL = 1e-11


class _Factor(Protocol):
    """A factorised matrix: ``solve(rhs)``."""

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solution for ``rhs``."""
        ...


def _superlu(K: sp.csc_matrix) -> _Factor:
    """SuperLU factors (problems without an :class:`Assembler`); RuntimeError if singular."""
    return splu(sp.csc_matrix(K))


#: Chord steps (the factorisation of an earlier tangent reused): a Newton step no longer than
#: ``chord_step`` (relative to the length scale) is evaluated without a tangent, and the next
#: direction solved with the factors already in hand, as long as each such step cuts the
#: residual by at least this factor (else a tangent is assembled at once).
_CHORD_CONTRACTION = 0.1

#: ... and not in the last iterations an attempt is allowed (``max_iter``): a chord step
#: converges linearly, and an attempt that needs all its iterations must not fail for it
#: (8 x 128 mesh, 0.25 MPa: 15 iterations, converged after the 15th with chord steps).
_CHORD_MARGIN = 3


def _newton(
    problem: Problem, u: np.ndarray, load: float, s: NewtonSettings, predicted: bool = False
) -> tuple[np.ndarray, int] | None:
    """Newton iterations at a fixed load from ``u``: (converged u, iterations) or None.

    ``predicted``: ``u`` is a load-step predictor. Such an attempt takes full Newton steps
    only, the first step the line search would have to shorten ends it, and its directions
    get at most ``_PREDICTED_ACTIVE_SET`` active-set re-solves; the caller then retries from
    the last converged state, whose first Newton step is the tangent predictor. Each call is
    one attempt in the statistics of :func:`collect_stats`.
    """
    if predicted:
        s = replace(s, line_search_halvings=0, active_set_iterations=min(
            s.active_set_iterations, _PREDICTED_ACTIVE_SET))
    t0 = time.perf_counter()
    counter = [0, 0]  # iterations, linear solves
    out = _newton_attempt(problem, u, load, s, counter)
    if collecting():
        record_attempt(out is not None, counter[0], counter[1], time.perf_counter() - t0)
    return out


def _direction(problem: Problem, u: np.ndarray, rf: np.ndarray, K: sp.csc_matrix | None,
               lin: _Linear, s: NewtonSettings) -> np.ndarray | None:
    """Newton direction over the free dofs (mm): with the tangent ``K`` if given (factorised
    into ``lin``), else with ``lin``'s factors (a chord step); None if singular."""
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("error", MatrixRankWarning)
        try:
            if K is not None:
                lin.set_tangent(K)
            assert lin.factor is not None and lin.K is not None
            d = lin.factor.solve(-rf)
            refine = getattr(problem, "refine_direction", None)
            if refine is not None and s.active_set_iterations > 0 and np.all(np.isfinite(d)):
                d = refine(u, lin.K, -rf, d, lin.solve, s.active_set_iterations)
        except (MatrixRankWarning, RuntimeError, LinAlgError):
            return None
    return d if np.all(np.isfinite(d)) else None


def _newton_attempt(
    problem: Problem, u: np.ndarray, load: float, s: NewtonSettings, counter: list[int]
) -> tuple[np.ndarray, int] | None:
    """The iterations of :func:`_newton`; ``counter`` gets [iterations, linear solves].

    Work saved (issue 37): the line search's trials are evaluated without a tangent unless
    the full step is likely the next iterate that needs one (see :func:`_line_search`), the
    trial it accepts is kept for the next iteration, and where the step was short (at most
    ``chord_step`` times the length scale: Newton's terminal phase, where the tangent barely
    changes) the next direction reuses the last factorisation (a chord step) instead of
    assembling and factorising a tangent, for as long as every chord step cuts the residual
    at least tenfold, except in the last ``_CHORD_MARGIN`` iterations allowed. The convergence
    test is unchanged, so is the converged state (to the tolerances).
    """
    free = problem.free
    fscale, lscale = problem.scales(load)
    du_norm = np.inf
    cached: _Evaluation | None = None
    history: list[tuple[float, float]] = []  # (residual norm, accepted step length)
    lin = _Linear(problem, counter)
    chord, r_prev = False, np.inf  # may the last factors serve (a short full step before)
    refresh = getattr(problem, "refresh", None)
    patch = getattr(problem, "patch_refreshed", None)
    for it in range(1, s.max_iter + 1):
        if refresh is not None and refresh(u) > 0.0:
            # friction: slip bounds frozen at u, so the trial's are stale; a problem that can
            # update the trial's evaluation itself (open tube ends: a constant shift of the
            # energy and the axial residual; friction: the outer nodes' friction terms under
            # the new bounds) spares the re-evaluation
            cached = patch(cached) if patch is not None and cached is not None else None
        out = cached if cached is not None else problem.evaluate(u, load, not chord)
        cached = None
        if out is None:
            return None
        energy, R, K = out
        rf = R[free]
        rnorm = float(np.max(np.abs(rf))) if rf.size else 0.0
        if not np.isfinite(rnorm):
            return None
        if rnorm <= s.tol_r * fscale and du_norm <= s.tol_u * lscale:
            return u, it - 1
        if _stagnating(history, rnorm, s.stagnation_ratio):
            return None  # cut back now rather than creep to max_iter
        if K is None and not (chord and rnorm <= _CHORD_CONTRACTION * r_prev):
            out = problem.evaluate(u, load, True)  # the same state, now with its tangent
            if out is None:
                return None
            energy, R, K = out
        counter[0] += 1
        d = _direction(problem, u, rf, K, lin, s)
        if d is None:
            return None
        step = np.zeros_like(u)
        step[free] = d
        d_max = float(np.max(np.abs(d))) if d.size else 0.0
        # no chord steps near the iteration limit: there, quadratic convergence counts
        short = d_max <= s.chord_step * lscale and it < s.max_iter - _CHORD_MARGIN
        ls = _line_search(problem, u, step, load, energy, rnorm, float(rf @ d),
                          s.tol_r * fscale, s.line_search_halvings, not short)
        if ls is None:
            if K is None:  # a chord direction failed (e.g. a contact changed): a tangent now
                chord = False
                continue
            return None
        alpha, cached = ls
        history.append((rnorm, alpha))
        chord, r_prev = short and alpha == 1.0, rnorm
        u = u + alpha * step
        du_norm = alpha * d_max
        if rnorm <= s.tol_r * fscale and du_norm <= s.tol_u * lscale:
            # residual was already converged and the correction is negligible
            return u, it
    return None


#: Active-set re-solves allowed to an attempt from the load-step predictor (the settings'
#: ``active_set_iterations`` otherwise), which also takes no damped step (:func:`_newton`).
#: The predictor starts deep in the contact penalty (on the 8 x 128 base squeeze its residual
#: is ~1e4 x the unpredicted start's): a predictor that needs damping has left Newton's basin,
#: and its re-solves (factorisations on fine meshes) are what a failed attempt cost. Issue 37,
#: base squeeze, 2 x 24 .. 8 x 128: failed-attempt time at most 6.3-8.2 % -> 1.6-3.3 %; on the
#: standard accuracy of the seven Table 3 structures +1 to +3 iterations on five, one failed
#: predicted attempt more on tests 6 and 7 (1.1-2.5 % of their time), N the same to 1e-6.
_PREDICTED_ACTIVE_SET = 2

#: A sub-step within this fraction of the rest of the way to the requested load takes all of it.
_SNAP = 1e-9


def solve_path(
    problem: Problem,
    loads: Sequence[float] | np.ndarray,
    settings: NewtonSettings | None = None,
    u0: np.ndarray | None = None,
    load0: float = 0.0,
    on_step: Callable[[float, np.ndarray], None] | None = None,
) -> list[PathPoint]:
    """Follow the equilibrium path through increasing ``loads`` (e.g. pressures in MPa).

    Sub-steps are at most ``settings.max_step``; a failed step is halved and
    retried; the step grows again after successes. Returns one converged state per
    requested load.

    Parameters
    ----------
    problem : Problem
        The discretised problem (e.g. :class:`InflationProblem`, :class:`SqueezeProblem`).
    loads : sequence of float
        Increasing loads to report (MPa for pressure), each > ``load0``.
    settings : NewtonSettings, optional
        Solver settings (default ``NewtonSettings()``).
    u0 : ndarray (n_dofs,), optional
        Starting displacements (mm); default zero.
    load0 : float
        Starting load (MPa for pressure).
    on_step : callable, optional
        Called as ``on_step(load, u)`` after every converged sub-step (load in MPa, u in mm).

    Returns
    -------
    list of PathPoint
        One per requested load.

    Raises
    ------
    ConvergenceError
        When a step cannot be converged even after the allowed cutbacks; the
        message names the last load reached and the load attempted.

    Examples
    --------
    >>> from exofric.fe import InflationProblem, MeshSpec
    >>> from exofric.material import MooneyRivlin
    >>> p = InflationProblem(8.3, 4.97, MooneyRivlin.from_shore(62.5), MeshSpec())
    >>> [pt] = solve_path(p, [0.2])
    >>> round(p.body.max_stretch(pt.u), 3)
    1.134
    """
    s = settings or NewtonSettings()
    with _thread_limit(s.threads):
        return _follow(problem, loads, s, u0, load0, on_step)


_CONTROLLER: ThreadpoolController | None = None


def _thread_limit(threads: int) -> contextlib.AbstractContextManager[object]:
    """Context limiting the BLAS/OpenMP pools to ``threads`` (0: no limit).

    The controller inspects the loaded libraries once (numpy's and scipy's OpenBLAS are loaded
    with this module); ``threadpool_limits`` would rescan them on every call (~2 ms, about
    a Newton iteration on the default mesh).
    """
    global _CONTROLLER
    if threads <= 0:
        return contextlib.nullcontext()
    if _CONTROLLER is None:
        _CONTROLLER = ThreadpoolController()
    return _CONTROLLER.limit(limits=int(threads))


def _follow(
    problem: Problem,
    loads: Sequence[float] | np.ndarray,
    s: NewtonSettings,
    u0: np.ndarray | None,
    load0: float,
    on_step: Callable[[float, np.ndarray], None] | None,
) -> list[PathPoint]:
    """The load stepping of :func:`solve_path` (within its thread limit)."""
    u = np.zeros(problem.n_dofs) if u0 is None else u0.copy()
    lam = float(load0)
    u_prev: np.ndarray | None = None
    lam_prev = lam
    step = s.max_step
    # secant predictor; not for frictional problems: it extrapolates the displacements but
    # not the slip state, and the sliding wall arc is predicted past its edge (base group,
    # mu 0.3: failed attempts 16 -> 4 of ~80, iterations -20 %)
    predict = s.extrapolate and not getattr(problem, "frictional", False)
    out: list[PathPoint] = []
    # equilibrium at the starting load first (e.g. the squeezed tube under its own weight at
    # P = 0): a requested load equal to it must not return an unsolved state
    start = _newton(problem, u, lam, s)
    if start is None:
        raise ConvergenceError(
            f"Newton failed at the starting {s.load_name} {lam:.6g} {s.load_unit}. To try: a "
            "finer mesh, or check that the geometry is feasible (tube and wire fit the hole)",
            reached=None)
    u, iters_start = start
    commit = getattr(problem, "commit", None)  # path-dependent problems (friction) keep state
    if commit is not None:
        commit(u)
    for target in loads:
        iters = iters_start
        iters_start = 0
        nsteps = 0
        cut = 0
        while lam < target - 1e-15:
            # the last sub-step to a target lands on it exactly (no sliver of round-off left
            # to step over, from a step shrunk to that sliver)
            rest = target - lam
            h = rest if rest <= step * (1.0 + _SNAP) else step
            trial_lam = target if h == rest else lam + h
            guess = u
            if predict and u_prev is not None and lam > lam_prev:
                guess = u + (u - u_prev) * (h / (lam - lam_prev))
                limit = getattr(problem, "limit_predictor", None)
                if limit is not None:  # e.g. stop the predictor where a new contact begins
                    guess = limit(u, guess)
            res = _newton(problem, guess, trial_lam, s, predicted=guess is not u)
            if res is None and guess is not u:
                # retried from the last state; the rest of the path goes without the
                # predictor: where it has failed once (e.g. a contact edge running over a fine
                # mesh's nodes) it tends to fail again (8 x 128 base squeeze: 4 more failures)
                predict = False
                res = _newton(problem, u, trial_lam, s)
            if res is None:
                cut += 1
                step = h * 0.5
                if cut > s.max_cutbacks or step < s.min_step:
                    raise explain_failure(problem, u, ConvergenceError(  # the material's?
                        f"Newton failed at {s.load_name} {trial_lam:.6g} {s.load_unit} after "
                        f"{cut - 1} cutbacks; last converged {s.load_name} {lam:.6g} "
                        f"{s.load_unit}. To try: a finer mesh, smaller load steps (max_step), "
                        "or a thicker wall / lower load if the tube is near its limit",
                        reached=lam,
                    ))
                continue
            u_prev, lam_prev = u, lam
            u, k = res
            lam = trial_lam
            iters += k
            nsteps += 1
            cut = 0
            # grow the step after a success; a step shortened only to land on the target
            # does not shrink the next one
            step = min(s.max_step, max(h * 1.5, step if h == rest else 0.0))
            if commit is not None:
                commit(u)
            if on_step is not None:
                on_step(lam, u)
        out.append(PathPoint(float(target), u.copy(), iters, nsteps))
    return out
