"""Sparse assembly, Newton with line search, and load stepping with cutback.

Convergence (stated tolerances): a load step is converged when the infinity norm
of the free residual is below ``tol_r * force_scale`` (default 1e-9 relative,
force_scale = pressure x size) AND the last Newton increment is below
``tol_u * length_scale`` (default 1e-10 relative). A step that does not converge
in ``max_iter`` iterations is cut back (halved) up to ``max_cutbacks`` times;
then :class:`~exofric.errors.ConvergenceError` names the last load reached.
Never is an unconverged state returned.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
import scipy.sparse as sp
from scipy.linalg import LinAlgError, solve_banded
from scipy.sparse.csgraph import reverse_cuthill_mckee
from scipy.sparse.linalg import MatrixRankWarning, spsolve

from exofric import defaults
from exofric.errors import ConvergenceError

__all__ = ["Assembler", "Problem", "NewtonSettings", "solve_path", "PathPoint"]


class Assembler:
    """Assembles element blocks into a reduced (free-dof) sparse matrix.

    The sparsity pattern, the map of every block entry to its slot in the CSC
    data array, and the reduction to free dofs are computed once; each
    assembly is then one ``np.bincount``.

    Parameters
    ----------
    n_dofs : int
        Number of dofs of the full system.
    free : ndarray of bool (n_dofs,)
        True for unknown dofs.
    patterns : sequence of (rows, cols)
        Index arrays of the blocks that will be assembled, in call order.

    Examples
    --------
    >>> import numpy as np
    >>> a = Assembler(2, np.array([True, True]), [(np.array([0, 1]), np.array([0, 1]))])
    >>> K = a.matrix([np.array([2.0, 4.0])])  # diag(2, 4)
    >>> a.solve(K, np.array([2.0, 2.0])).tolist()
    [1.0, 0.5]
    """

    def __init__(
        self, n_dofs: int, free: np.ndarray, patterns: Sequence[tuple[np.ndarray, np.ndarray]]
    ) -> None:
        self.n_dofs = n_dofs
        self.free = np.asarray(free, dtype=bool)
        self.red = np.full(n_dofs, -1)
        self.red[self.free] = np.arange(int(self.free.sum()))
        self.nf = int(self.free.sum())
        rr = np.concatenate([self.red[np.asarray(r).ravel()] for r, _ in patterns])
        cc = np.concatenate([self.red[np.asarray(c).ravel()] for _, c in patterns])
        self.sizes = [np.asarray(r).size for r, _ in patterns]
        self.keep = (rr >= 0) & (cc >= 0)
        lin = cc[self.keep].astype(np.int64) * self.nf + rr[self.keep]
        uniq, self.inv = np.unique(lin, return_inverse=True)
        self.nnz = uniq.size
        self.indices = (uniq % self.nf).astype(np.int32)
        cols = uniq // self.nf
        self.indptr = np.searchsorted(cols, np.arange(self.nf + 1)).astype(np.int32)

        # Reverse Cuthill-McKee ordering of the pattern: the thin structured meshes of the
        # tube then have a narrow band, and LAPACK's banded LU (gbsv, partial pivoting) beats
        # SuperLU's general sparse LU by ~2x at these sizes (a few hundred to a few thousand
        # dofs). Each CSC slot's place in the band is precomputed.
        pattern = sp.csc_matrix((np.ones(self.nnz), self.indices, self.indptr),
                                shape=(self.nf, self.nf))
        self.perm = reverse_cuthill_mckee(pattern.tocsr(), symmetric_mode=True)
        iperm = np.empty_like(self.perm)
        iperm[self.perm] = np.arange(self.nf)
        rows = iperm[self.indices]
        colsp = iperm[np.repeat(np.arange(self.nf), np.diff(self.indptr))]
        self.band = int(np.max(np.abs(rows - colsp))) if self.nnz else 0
        self.band_slot = (self.band + rows - colsp) * self.nf + colsp

    def solve(self, K: sp.csc_matrix, rhs: np.ndarray) -> np.ndarray:
        """Solve ``K x = rhs`` for a matrix from :meth:`matrix` (banded LU after RCM).

        Falls back to SuperLU when the band is wider than 1/4 of the system. Raises
        ``LinAlgError`` for a singular matrix.

        Parameters
        ----------
        K : scipy.sparse.csc_matrix (nf, nf)
            Matrix of the free dofs, as returned by :meth:`matrix` (same pattern).
        rhs : ndarray (nf,)
            Right-hand side over the free dofs.

        Returns
        -------
        ndarray (nf,)
        """
        if 4 * self.band > self.nf:
            return np.asarray(spsolve(K, rhs))
        ab = np.zeros((2 * self.band + 1, self.nf))
        ab.ravel()[self.band_slot] = K.data
        x = np.empty(self.nf)
        x[self.perm] = solve_banded((self.band, self.band), ab, rhs[self.perm],
                                    check_finite=False)
        return x

    def matrix(self, blocks: Sequence[np.ndarray]) -> sp.csc_matrix:
        """CSC matrix of the free dofs from block values given in pattern order.

        Parameters
        ----------
        blocks : sequence of ndarray
            Values of each pattern's entries, in the order and shapes of ``patterns``;
            entries on fixed dofs are dropped, repeated entries summed.

        Returns
        -------
        scipy.sparse.csc_matrix (nf, nf)
        """
        vals = np.concatenate([np.asarray(b).ravel() for b in blocks])[self.keep]
        data = np.bincount(self.inv, weights=vals, minlength=self.nnz)
        return sp.csc_matrix((data, self.indices, self.indptr), shape=(self.nf, self.nf))


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
        Backtracking halvings of a Newton step, >= 0.
    extrapolate : bool
        Start each sub-step from a secant predictor.
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
    load_name: str = "pressure"
    load_unit: str = "MPa"


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


def _newton(
    problem: Problem, u: np.ndarray, load: float, s: NewtonSettings
) -> tuple[np.ndarray, int] | None:
    free = problem.free
    fscale, lscale = problem.scales(load)
    du_norm = np.inf
    cached: tuple[float, np.ndarray, sp.csc_matrix | None] | None = None
    for it in range(1, s.max_iter + 1):
        # the accepted full-step trial of the previous iteration already has the tangent
        out = cached if cached is not None else problem.evaluate(u, load, True)
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
        assert K is not None
        with np.errstate(all="ignore"):
            import warnings

            with warnings.catch_warnings():
                warnings.simplefilter("error", MatrixRankWarning)
                try:
                    asm = getattr(problem, "assembler", None)
                    d = asm.solve(K, -rf) if isinstance(asm, Assembler) else spsolve(K, -rf)
                except (MatrixRankWarning, RuntimeError, LinAlgError):
                    return None
        if not np.all(np.isfinite(d)):
            return None
        step = np.zeros_like(u)
        step[free] = d
        # Line search on the energy along the Newton direction: try the full step; if
        # neither the energy nor the residual decreased, take the secant root of the
        # directional derivative s(a) = R(u + a d) . d (s(0) < 0), which lands next to
        # the kink of a contact active-set change instead of halving towards it.
        s0 = float(rf @ d)
        alpha = 1.0
        for _ in range(s.line_search_halvings + 1):
            trial = u + alpha * step
            t = problem.evaluate(trial, load, alpha == 1.0)
            if t is None:
                alpha *= 0.5
                continue
            e_t, R_t, _ = t
            r_t = float(np.max(np.abs(R_t[free]))) if rf.size else 0.0
            if np.isfinite(r_t) and _accept(e_t, r_t, energy, rnorm, alpha * s0, s.tol_r * fscale):
                cached = t if t[2] is not None else None
                break
            s_t = float(R_t[free] @ d)
            if s0 < 0.0 < s_t:
                alpha *= min(0.9, max(0.05, s0 / (s0 - s_t)))
            else:
                alpha *= 0.5
        else:
            return None
        u = trial
        du_norm = alpha * float(np.max(np.abs(d))) if d.size else 0.0
        if rnorm <= s.tol_r * fscale and du_norm <= s.tol_u * lscale:
            # residual was already converged and the correction is negligible
            return u, it
    return None


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
    u = np.zeros(problem.n_dofs) if u0 is None else u0.copy()
    lam = float(load0)
    u_prev: np.ndarray | None = None
    lam_prev = lam
    step = s.max_step
    out: list[PathPoint] = []
    # equilibrium at the starting load first (e.g. the squeezed tube under its own weight at
    # P = 0): a requested load equal to it must not return an unsolved state
    start = _newton(problem, u, lam, s)
    if start is None:
        raise ConvergenceError(
            f"Newton failed at the starting {s.load_name} {lam:.6g} {s.load_unit}", reached=None)
    u, iters_start = start
    for target in loads:
        iters = iters_start
        iters_start = 0
        nsteps = 0
        cut = 0
        while lam < target - 1e-15:
            h = min(step, target - lam)
            trial_lam = lam + h
            guess = u
            if s.extrapolate and u_prev is not None and lam > lam_prev:
                # secant predictor (a Newton failure from it is retried from the last state)
                guess = u + (u - u_prev) * (h / (lam - lam_prev))
                limit = getattr(problem, "limit_predictor", None)
                if limit is not None:  # e.g. stop the predictor where a new contact begins
                    guess = limit(u, guess)
            res = _newton(problem, guess, trial_lam, s)
            if res is None and guess is not u:
                res = _newton(problem, u, trial_lam, s)
            if res is None:
                cut += 1
                step = h * 0.5
                if cut > s.max_cutbacks or step < s.min_step:
                    raise ConvergenceError(
                        f"Newton failed at {s.load_name} {trial_lam:.6g} {s.load_unit} after "
                        f"{cut - 1} cutbacks; last converged {s.load_name} {lam:.6g} "
                        f"{s.load_unit}",
                        reached=lam,
                    )
                continue
            u_prev, lam_prev = u, lam
            u, k = res
            lam = trial_lam
            iters += k
            nsteps += 1
            cut = 0
            step = min(s.max_step, h * 1.5)
            if on_step is not None:
                on_step(lam, u)
        out.append(PathPoint(float(target), u.copy(), iters, nsteps))
    return out
