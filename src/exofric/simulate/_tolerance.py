"""Tolerances propagated to the squeezing force N(P) (issue 19, second part; issue 37).

Real tubes, holes and wires have tolerances, and the tube's ID and hardness are uncertain (the
paper prints no ID; +-0.35 mm of ID moves N(0.3 MPa) by -25/+30 %). Each tolerance is a normal
distribution (a standard deviation around the nominal value); :func:`squeeze_tolerances`
propagates them to N(P) with scrambled Sobol quasi-Monte Carlo (``scipy.stats.qmc``) and reports
percentile bands, and ranks the tolerances by their first-order contribution to the variance of N
at each pressure (central finite differences at the nominal design times the standard
deviation: a linearisation, stated as such).

How the samples are evaluated (``method``):

* ``"grid"`` (tried first by ``"auto"``): the samples differ in a few inputs, so N is solved on a
  small grid and every sample is read off an interpolant. The hardness enters only through the
  shear modulus G of the Mooney-Rivlin material (fixed C01/C10 and Poisson's ratio, Eqs 3-6),
  and the squeeze without gravity is similar in G: N(P; G) = (G / G0) N(P G0 / G; G0) (the
  contact penalty breaks it by < 1e-6 of N, measured in ``tests/test_tolerance.py``). So the
  hardness costs no solves: the nominal material is solved at the asked pressures and a few
  more (the ends of P G0 / G over the samples) and read at P G0 / G (PCHIP in P). The size
  tolerances (at most two) get three nodes each (the nominal and the extremes of the samples:
  quadratic Lagrange interpolation, a tensor grid of 3 or 9 solves). One sample, the farthest
  from the nodes, is solved directly as well (held out): when the interpolant misses it by
  more than :data:`HELD_OUT_TOL_PCT` % of the nominal N at the highest pressure, or a node
  cannot be solved, the samples are solved one by one instead, and ``method_note`` says why.
* ``"brute-force"``: one solve per sample (and two per tolerance for the ranking).

Either way the solves run on up to ``workers`` forked processes (Linux), each warning is issued
once, and ``progress(done, total, stage)`` is called as solves finish.

Tolerance names: ``hole_mm``, ``tube_od_mm``, ``tube_id_mm``, ``wire_mm`` (mm) and ``shore``
(Shore A; the material follows Eqs 3-6 of the paper).

Units: mm, MPa, N.

Examples
--------
>>> from exofric.geometry import BASE
>>> r = squeeze_tolerances(BASE, 62.5, [0.6], {"shore": 2.0}, samples=8,
...                        accuracy="draft", workers=1)
>>> r.percentiles_n[5][0] < r.nominal_n[0] < r.percentiles_n[95][0], r.method, r.solves
(True, 'grid', 2)
"""

from __future__ import annotations

import itertools
import math
import multiprocessing
import os
import warnings
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import (
    ConvergenceError,
    InputError,
    check_positive,
    check_seed,
    warn_implausible,
    warning_key,
)
from exofric.geometry import Structure
from exofric.simulate._squeeze import squeeze

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["TOLERANCE_NAMES", "HELD_OUT_TOL_PCT", "ToleranceResult", "squeeze_tolerances"]

#: What can carry a tolerance (mm, except shore in Shore A).
TOLERANCE_NAMES = ("hole_mm", "tube_od_mm", "tube_id_mm", "wire_mm", "shore")
#: Largest miss of the grid interpolant at the held-out sample, in % of the nominal N at the
#: highest pressure: half the 1 % the bands are meant to hold (issue 37).
HELD_OUT_TOL_PCT = 0.5
#: Largest gap (MPa) between the pressures the hardness is read from (PCHIP in P between them).
DENSE_GAP_MPA = 0.1
#: Share of impossible sample designs (tube and wire not fitting, ID >= OD) that is an error
#: (above: the sd is more than 1.5 x the room its dimension has) or a warning (above
#: :data:`WARN_IMPOSSIBLE`: those designs are left out of the bands).
MAX_IMPOSSIBLE = 0.25
WARN_IMPOSSIBLE = 0.01
_PCTS = (5, 50, 95)
Progress = Callable[[int, int, str], None]


@checked_init
@dataclass(frozen=True)
class ToleranceResult(DisplayMixin):
    """Percentile bands of N(P) under tolerances, and which tolerance matters most.

    Attributes
    ----------
    pressure_mpa : tuple of float
        Pressures (MPa).
    nominal_n : tuple of float
        N(P) of the nominal design (N, total over the length).
    percentiles_n : dict of int -> tuple of float
        5th, 50th and 95th percentiles of N(P) over the samples (N).
    samples_n : ndarray
        N(P) of every sample (N), shape (samples, pressures).
    ranking : tuple of (str, tuple of float)
        Tolerances by decreasing first-order share of the variance of N at the highest pressure,
        with their share (0-1) at each pressure.
    tolerances : dict of str -> float
        The standard deviations (mm or Shore A).
    failed : int
        Samples whose squeeze did not converge or whose geometry was impossible (left out).
    method : str
        ``"grid"`` (interpolated, verified at a held-out sample) or ``"brute-force"``.
    method_note : str
        Why brute force was used, or the grid's size and held-out miss.
    held_out_error_pct : float or None
        Grid: the interpolant's largest miss at the held-out sample (% of the nominal N at the
        highest pressure).
    solves : int
        Calls of the squeeze (or of ``solver``) made.
    nominal_onset_mpa : float or None
        Contact-onset pressure of the nominal design (MPa), when the solver reports one.

    Examples
    --------
    >>> ToleranceResult.__name__
    'ToleranceResult'
    """

    pressure_mpa: tuple[float, ...]
    nominal_n: tuple[float, ...]
    percentiles_n: dict[int, tuple[float, ...]]
    samples_n: NDArray[np.float64]
    ranking: tuple[tuple[str, tuple[float, ...]], ...]
    tolerances: dict[str, float]
    failed: int
    method: str = "brute-force"
    method_note: str = ""
    held_out_error_pct: float | None = None
    solves: int = 0
    nominal_onset_mpa: float | None = field(default=None)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``squeeze_force_n`` (nominal) and ``squeeze_force_n_p05/p50/p95`` (N)."""
        d: dict[str, Any] = {"pressure_mpa": list(self.pressure_mpa),
                             "squeeze_force_n": list(self.nominal_n)}
        for q, v in self.percentiles_n.items():
            d[f"squeeze_force_n_p{q:02d}"] = list(v)
        d["sensitivity"] = [{"tolerance": k, "variance_share": list(v)}
                            for k, v in self.ranking]
        d["tolerances"] = dict(self.tolerances)
        d["samples"] = int(self.samples_n.shape[0])
        d["failed"] = self.failed
        d["method"] = self.method
        d["method_note"] = self.method_note
        d["held_out_error_pct_of_n"] = self.held_out_error_pct
        d["solves"] = self.solves
        return d

    def to_frame(self) -> pd.DataFrame:
        """One row per pressure: nominal N and its percentiles (N).

        Returns
        -------
        pandas.DataFrame
        """
        import pandas as pd

        cols = {"pressure_mpa": self.pressure_mpa, "squeeze_force_n": self.nominal_n}
        cols.update({f"squeeze_force_n_p{q:02d}": v for q, v in self.percentiles_n.items()})
        return pd.DataFrame(cols)


# --------------------------------------------------------------------------- evaluation
@dataclass(frozen=True)
class _Outcome:
    """One solve's N (N) and contact onset (MPa), or its error; the warnings it raised."""

    n: NDArray[np.float64] | None
    onset: float | None
    error: tuple[type[BaseException], tuple[Any, ...], dict[str, Any]] | None
    caught: tuple[tuple[type[Warning], str], ...]

    def raise_error(self) -> None:
        """Re-raise the solve's InputError or ConvergenceError (same type and message)."""
        if self.error is not None:
            cls, args, attrs = self.error
            exc = cls.__new__(cls)
            exc.args = args
            exc.__dict__.update(attrs)
            raise exc


@dataclass(frozen=True)
class _Job:
    """The solves of one tolerance study: (changed values, pressures MPa) per task."""

    structure: Structure
    shore: float
    solver: Callable[..., Any] | None
    options: dict[str, Any]
    tasks: tuple[tuple[dict[str, float], NDArray[np.float64]], ...]

    def design(self, values: dict[str, float]) -> tuple[Structure, Any]:
        """The structure and material with ``values`` changed (InputError if impossible)."""
        from exofric.material import MooneyRivlin

        changes: dict[str, Any] = {k: v for k, v in values.items() if k != "shore"}
        st = replace(self.structure, **changes) if changes else self.structure
        return st, MooneyRivlin.from_shore(values.get("shore", self.shore))

    def run(self, i: int) -> _Outcome:
        """Task ``i``, with its warnings recorded (re-issued once by the caller)."""
        values, p = self.tasks[i]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                st, mat = self.design(values)
                r = (self.solver(st, mat, p) if self.solver is not None
                     else squeeze(st, mat, p, **self.options))
                n = np.asarray(r.squeeze_force_n, dtype=float)
                onset = getattr(r, "contact_onset_pressure_mpa", None)
                out = _Outcome(n, None if onset is None else float(onset), None, ())
            except (InputError, ConvergenceError) as exc:
                out = _Outcome(None, None, (type(exc), exc.args, dict(vars(exc))), ())
        return replace(out, caught=tuple((w.category, str(w.message)) for w in caught))


#: The job forked workers run (set just before the pool starts; workers inherit it).
_JOB: _Job | None = None


def _run_task(i: int) -> _Outcome:
    """Worker side of :func:`_solve_all`."""
    assert _JOB is not None
    return _JOB.run(i)


def _workers(workers: int | None, n_tasks: int) -> int:
    """Processes to use: ``workers`` (default: the CPUs this process may use), at most one per
    task; 1 where forking is not possible (not Linux, or inside a pool's worker)."""
    if workers is None:
        workers = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else 1
    if not isinstance(workers, int) or isinstance(workers, bool) or not 1 <= workers <= 64:
        raise InputError(f"workers must be an integer in [1, 64], got {workers!r}")
    if (not hasattr(os, "fork") or "fork" not in multiprocessing.get_all_start_methods()
            or multiprocessing.current_process().daemon):
        return 1
    return max(1, min(workers, n_tasks))


def _solve_all(job: _Job, workers: int, progress: Progress | None, stage: str
               ) -> list[_Outcome]:
    """Every task of ``job``, on ``workers`` forked processes (1: in this one), in order."""
    global _JOB
    n = len(job.tasks)
    out: list[_Outcome | None] = [None] * n
    if progress is not None:
        progress(0, n, stage)
    if workers <= 1 or n <= 1:
        for i in range(n):
            out[i] = job.run(i)
            if progress is not None:
                progress(i + 1, n, stage)
        return [o for o in out if o is not None]
    _JOB = job
    try:
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", message=r".*use of fork\(\) may lead to deadlocks")
            with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork")
                                     ) as ex:
                futures = {ex.submit(_run_task, i): i for i in range(n)}
                for done, fut in enumerate(as_completed(futures), 1):
                    out[futures[fut]] = fut.result()
                    if progress is not None:
                        progress(done, n, stage)
    finally:
        _JOB = None
    return [o for o in out if o is not None]


def _warn_once(outcomes: Sequence[_Outcome]) -> None:
    """Issue each kind of warning of the solves once (issue 34: not once per sample): the
    first of the messages that differ only in their measured numbers (a sample's clearance,
    say; :func:`exofric.errors.warning_key`)."""
    seen: dict[tuple[type[Warning], str], str] = {}
    for o in outcomes:
        for category, message in o.caught:
            seen.setdefault(warning_key(category, message), message)
    for (category, _), message in seen.items():
        warnings.warn(message, category, stacklevel=4)


# --------------------------------------------------------------------------- inputs
def _check_inputs(structure: Structure, shore: float, tolerances: dict[str, float]
                  ) -> tuple[list[str], dict[str, float], dict[str, float]]:
    """Names, nominal values and sds of the tolerances (module docstring), checked."""
    if not isinstance(structure, Structure):
        raise InputError(f"structure must be a Structure, got {type(structure).__name__}",
                         param="structure")
    if not isinstance(tolerances, dict) or not tolerances:
        raise InputError("tolerances must name at least one of " + ", ".join(TOLERANCE_NAMES),
                         param="tolerances")
    names = list(tolerances)
    for k in names:
        if k not in TOLERANCE_NAMES:
            raise InputError(f"tolerances: unknown name {k!r} (known: "
                             f"{', '.join(TOLERANCE_NAMES)})", param="tolerances")
    nominal = {k: (float(shore) if k == "shore" else float(getattr(structure, k))) for k in names}
    sd = {}
    for k in names:
        sd[k] = check_positive(f"tolerance {k}", tolerances[k])
        if sd[k] >= nominal[k]:
            raise InputError(f"tolerance {k} = {sd[k]:g} is not smaller than the value "
                             f"{nominal[k]:g}", param="tolerances")
    _check_against_dimensions(structure, float(shore), sd)
    return names, nominal, sd


def _check_against_dimensions(structure: Structure, shore: float, sd: dict[str, float]) -> None:
    """Each tolerance against the room its dimension has (issue 38): the share of normal
    samples that are impossible -- the clearance D - d1 - d2 < 0, the wall d1 - ID <= 0, the
    hardness outside (0, 100) Shore A -- is an error above a quarter (the sd exceeds 1.5 x
    the room), a warning above 1 %."""
    from scipy.stats import norm

    g = {k: sd.get(k, 0.0) for k in TOLERANCE_NAMES}
    checks = [
        ("the clearance D - d1 - d2", structure.clearance_mm,
         math.hypot(g["hole_mm"], g["tube_od_mm"], g["wire_mm"]), "hole_mm, tube_od_mm, wire_mm",
         "mm"),
        ("the wall d1 - ID", structure.tube_od_mm - structure.tube_id_mm,
         math.hypot(g["tube_od_mm"], g["tube_id_mm"]), "tube_od_mm, tube_id_mm", "mm"),
        ("the hardness's distance to 0 or 100", min(shore, 100.0 - shore), g["shore"], "shore",
         "Shore A"),
    ]
    for what, room, spread, which, unit in checks:
        if spread <= 0.0:
            continue
        share = float(norm.sf(room / spread))
        msg = (f"tolerances ({which}) leave {what} = {room:.3g} {unit} against a spread of "
               f"{spread:.3g} {unit} (1 sd): {100 * share:.1f} % of the sampled designs are "
               "impossible")
        if share > MAX_IMPOSSIBLE:
            raise InputError(msg + f" (at most {100 * MAX_IMPOSSIBLE:.0f} % allowed)",
                             param="tolerances")
        if share > WARN_IMPOSSIBLE:
            warn_implausible(msg + " and left out: the bands describe the designs that fit")


def _sobol_values(names: list[str], nominal: dict[str, float], sd: dict[str, float],
                  samples: int, seed: int) -> NDArray[np.float64]:
    """The sampled values, shape (samples, names): nominal + sd x normal Sobol points."""
    from scipy.stats import norm, qmc

    u = qmc.Sobol(d=len(names), scramble=True, seed=seed).random(samples)
    z = norm.ppf(np.clip(u, 1e-12, 1 - 1e-12))
    return np.array([nominal[k] for k in names]) + z * np.array([sd[k] for k in names])


def _ranking_points(names: list[str], nominal: dict[str, float], sd: dict[str, float]
                    ) -> NDArray[np.float64]:
    """Nominal, then nominal -+ sd/2 of each tolerance (rows), for the central differences."""
    base = np.array([nominal[k] for k in names])
    rows = [base]
    for j, k in enumerate(names):
        for sign in (-1.0, 1.0):
            row = base.copy()
            row[j] += sign * 0.5 * sd[k]
            rows.append(row)
    return np.array(rows)


def _ranking(names: list[str], points_n: NDArray[np.float64]
             ) -> tuple[tuple[str, tuple[float, ...]], ...]:
    """First-order variance shares from N at the ranking points (rows of nan: not solved)."""
    lo, hi = points_n[1::2], points_n[2::2]
    c = np.where(np.isfinite(hi - lo), hi - lo, 0.0) ** 2
    total = c.sum(axis=0)
    share = np.divide(c, total, out=np.zeros_like(c), where=total > 0)
    order = np.argsort(-share[:, -1], kind="stable")
    return tuple((names[i], tuple(share[i].tolist())) for i in order)


def _feasible(job: _Job, names: list[str], values: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Which sampled designs exist (tube and wire fit, ID < OD, hardness in range)."""
    ok = np.ones(len(values), dtype=bool)
    for i, row in enumerate(values):
        try:
            job.design(dict(zip(names, row.tolist(), strict=True)))
        except InputError:
            ok[i] = False
    return ok


# --------------------------------------------------------------------------- methods
@dataclass(frozen=True)
class _Answer:
    """What a method found: sample and ranking-point N (N), nominal N and onset, solves."""

    samples_n: NDArray[np.float64]
    points_n: NDArray[np.float64]
    nominal_n: NDArray[np.float64]
    onset: float | None
    failed: int
    method: str
    note: str
    held_out_error_pct: float | None
    outcomes: tuple[_Outcome, ...]


def _shear_ratio(names: list[str], rows: NDArray[np.float64], shore: float
                 ) -> NDArray[np.float64]:
    """G0 / G of each row (G: small-strain shear modulus of the row's hardness, MPa)."""
    from exofric.material import MooneyRivlin

    if "shore" not in names:
        return np.ones(len(rows))
    col = rows[:, names.index("shore")]
    g0 = MooneyRivlin.from_shore(shore).shear_modulus
    return np.array([g0 / MooneyRivlin.from_shore(float(s)).shear_modulus for s in col])


def _lagrange3(t: NDArray[np.float64]) -> NDArray[np.float64]:
    """Quadratic Lagrange weights at nodes -1, 0, 1 for each entry of ``t``: shape (..., 3)."""
    return np.stack([0.5 * t * (t - 1.0), 1.0 - t * t, 0.5 * t * (t + 1.0)], axis=-1)


@dataclass(frozen=True)
class _Grid:
    """The interpolant's nodes: each size tolerance (columns ``geo``) at centre + half x
    (-1, 0, 1), the nominal hardness, N on the pressures ``p_dense`` (MPa)."""

    geo: tuple[int, ...]
    centre: NDArray[np.float64]
    half: NDArray[np.float64]
    p_dense: NDArray[np.float64]

    @property
    def index(self) -> list[tuple[int, ...]]:
        """Node positions in units of ``half`` (-1, 0, 1 per size tolerance)."""
        return list(itertools.product((-1, 0, 1), repeat=len(self.geo)))

    def nodes(self, names: list[str]) -> list[dict[str, float]]:
        """The changed values of every node (the nominal node: ``{}`` changes nothing)."""
        return [{names[j]: float(self.centre[k] + i[k] * self.half[k])
                 for k, j in enumerate(self.geo)} for i in self.index]

    def coords(self, rows: NDArray[np.float64]) -> NDArray[np.float64]:
        """Rows' size values in units of ``half`` around the centre, shape (rows, geo)."""
        return (rows[:, list(self.geo)] - self.centre) / self.half

    def evaluate(self, node_n: NDArray[np.float64], rows: NDArray[np.float64],
                 ratio: NDArray[np.float64], p: NDArray[np.float64]) -> NDArray[np.float64]:
        """N (N) of ``rows`` at ``p`` (MPa): Lagrange in size, similarity in hardness
        (N = N_nodes(P G0/G) G/G0, PCHIP in P)."""
        from scipy.interpolate import PchipInterpolator

        q = np.clip(p[None, :] * ratio[:, None], self.p_dense[0], self.p_dense[-1])
        if self.p_dense.size > 1:
            v = PchipInterpolator(self.p_dense, node_n, axis=1)(q)    # (nodes, rows, p)
        else:
            v = np.broadcast_to(node_n[:, None, :], (node_n.shape[0], *q.shape))
        lw = _lagrange3(self.coords(rows))                              # (rows, geo, 3)
        w = np.ones((len(rows), len(self.index)))
        for n, i in enumerate(self.index):
            for k, ik in enumerate(i):
                w[:, n] *= lw[:, k, ik + 1]
        return np.einsum("rn,nrp->rp", w, v) / ratio[:, None]


def _plan_grid(names: list[str], nominal: dict[str, float], rows: NDArray[np.float64],
               ratio: NDArray[np.float64], p: NDArray[np.float64]) -> _Grid | str:
    """The grid for ``rows`` (samples and ranking points), or why there is none."""
    geo = tuple(j for j, k in enumerate(names) if k != "shore")
    if len(geo) > 2:
        return (f"{len(geo)} size tolerances would need a grid of {3 ** len(geo)} solves "
                "(at most 2 are interpolated)")
    centre = np.array([nominal[names[j]] for j in geo])
    half = np.abs(rows[:, list(geo)] - centre).max(axis=0) if geo else np.zeros(0)
    p_dense = p
    if "shore" in names:
        p_dense = _dense_pressures(p, float(p.min() * ratio.min()), float(p.max() * ratio.max()))
    return _Grid(geo, centre, half, p_dense)


def _dense_pressures(p: NDArray[np.float64], lo: float, hi: float) -> NDArray[np.float64]:
    """The asked pressures with the ends lo, hi (MPa) of the hardness' range, gaps over 1.5 x
    :data:`DENSE_GAP_MPA` (or a sixth of the range, if smaller) halved: each added pressure
    costs a squeeze about 10 % (measured), so as few as PCHIP needs (<= 0.2 % of N(0.6 MPa)
    with the README's six pressures and Shore +-2, against a 45-pressure solve)."""
    x = np.union1d(p, [lo, hi])
    h = 1.5 * min(DENSE_GAP_MPA, (hi - lo) / 6.0)
    while True:
        gaps = np.diff(x)
        wide = gaps > h
        if not wide.any():
            return x
        x = np.union1d(x, x[:-1][wide] + 0.5 * gaps[wide])


def _held_out(grid: _Grid, rows: NDArray[np.float64], ratio: NDArray[np.float64]) -> int:
    """The row farthest from the nodes (in units of the node spacing; the hardness breaks
    ties: the largest |ln G/G0| tests the similarity hardest)."""
    t = np.abs(grid.coords(rows))
    dist = np.minimum(t, np.abs(1.0 - t)).sum(axis=1)
    lr = np.abs(np.log(ratio))
    return int(np.argmax(dist + 0.5 * lr / max(float(lr.max()), 1e-300)))


def _by_grid(job: _Job, names: list[str], nominal: dict[str, float],
             rows: NDArray[np.float64], n_samples: int, p: NDArray[np.float64],
             run: Callable[[_Job, str], list[_Outcome]]) -> _Answer | str:
    """Samples and ranking points (``rows``, the first ``n_samples`` are samples) read off the
    grid interpolant, verified at a held-out sample; or why not."""
    ratio = _shear_ratio(names, rows, job.shore)
    grid = _plan_grid(names, nominal, rows, ratio, p)
    if isinstance(grid, str):
        return grid
    if len(grid.index) + 1 >= n_samples:
        return f"the grid's {len(grid.index) + 1} solves save nothing over {n_samples} samples"
    held = _held_out(grid, rows[:n_samples], ratio[:n_samples])
    tasks = [(v, grid.p_dense) for v in grid.nodes(names)]
    tasks.append((dict(zip(names, rows[held].tolist(), strict=True)), p))
    outs = run(replace(job, tasks=tuple(tasks)), "grid")
    centre = len(grid.index) // 2                          # the nominal node
    outs[centre].raise_error()                             # the nominal design's own error
    bad = next((o for o in outs if o.n is None), None)
    if bad is not None:
        assert bad.error is not None
        return f"a grid node or the held-out sample did not solve ({bad.error[1][0]})"
    node_n = np.array([o.n for o in outs[:-1]])
    n_all = grid.evaluate(node_n, rows, ratio, p)
    nom = node_n[centre][np.searchsorted(grid.p_dense, p)]
    direct = outs[-1].n
    assert direct is not None
    scale = max(float(np.abs(nom).max()), 1e-300)
    err = 100.0 * float(np.abs(n_all[held] - direct).max()) / scale
    if err > HELD_OUT_TOL_PCT:
        return (f"the grid interpolant misses the held-out sample by {err:.2f} % of N at "
                f"{p[-1]:g} MPa (limit {HELD_OUT_TOL_PCT:g} %)")
    n_all[held] = direct
    n_all[n_samples] = nom
    note = (f"{len(grid.index)} grid nodes (sizes: 3 each; hardness: similarity in "
            f"G), held-out sample missed by {err:.3f} % of N at {p[-1]:g} MPa")
    return _Answer(n_all[:n_samples], n_all[n_samples:], nom, outs[centre].onset, 0, "grid",
                   note, err, tuple(outs))


def _by_brute_force(job: _Job, names: list[str], rows: NDArray[np.float64], n_samples: int,
                    p: NDArray[np.float64], run: Callable[[_Job, str], list[_Outcome]],
                    note: str) -> _Answer:
    """One solve per row (ranking points first: the nominal's error reaches the caller)."""
    order = list(range(n_samples, len(rows))) + list(range(n_samples))
    tasks = [(dict(zip(names, rows[i].tolist(), strict=True)), p) for i in order]
    tasks[0] = ({}, p)                                     # the nominal design itself
    outs = run(replace(job, tasks=tuple(tasks)), "brute force")
    outs[0].raise_error()
    n_pts = len(rows) - n_samples
    pts = np.array([np.full(p.shape, np.nan) if o.n is None else o.n for o in outs[:n_pts]])
    got = [o.n for o in outs[n_pts:] if o.n is not None]
    arr = np.array(got) if got else np.zeros((0, p.size))
    nom = outs[0].n
    assert nom is not None
    return _Answer(arr, pts, nom, outs[0].onset, n_samples - len(got), "brute-force", note,
                   None, tuple(outs))


def squeeze_tolerances(
    structure: Structure,
    shore: float,
    pressures_mpa: ArrayLike,
    tolerances: dict[str, float],
    *,
    samples: int = 64,
    seed: int = 0,
    solver: Callable[..., Any] | None = None,
    method: str = "auto",
    workers: int | None = None,
    progress: Progress | None = None,
    **squeeze_options: Any,
) -> ToleranceResult:
    """Propagate normal tolerances on the sizes and the hardness to N(P) (module docstring).

    Parameters
    ----------
    structure : Structure
        The nominal design (mm).
    shore : float
        Nominal Shore A hardness (the material follows the paper's Eqs 3-6).
    pressures_mpa : array_like
        Strictly increasing pressures (MPa).
    tolerances : dict
        Standard deviation per name in :data:`TOLERANCE_NAMES` (mm, Shore A), > 0, smaller
        than the nominal value, and leaving at most a quarter of the sampled designs impossible
        (a warning above 1 %).
    samples : int
        Quasi-Monte Carlo samples (8-4096; a power of 2 keeps the Sobol sequence balanced).
    seed : int
        Seed of the scrambled Sobol sequence.
    solver : callable, optional
        ``solver(structure, material, pressures_mpa)`` returning an object with
        ``squeeze_force_n`` (N), used instead of :func:`squeeze` (e.g. a clearance distribution
        around each sample's nominal clearance, :func:`squeeze_with_clearance`). It must be
        similar in the shear modulus like the squeeze (no gravity); the held-out sample checks
        that.
    method : {"auto", "brute-force"}
        ``"auto"``: the grid interpolant when its held-out check passes, else brute force
        (module docstring); ``"brute-force"``: one solve per sample.
    workers : int, optional
        Processes for the solves (1-64; default: the CPUs available; 1 inside a pool worker or
        where processes cannot be forked).
    progress : callable, optional
        ``progress(done, total, stage)`` before the first solve (``done = 0``) and after every
        solve (``stage``: ``"grid"`` or ``"brute force"``).
    **squeeze_options
        Passed to :func:`exofric.simulate.squeeze`.

    Returns
    -------
    ToleranceResult

    Raises
    ------
    InputError
        Unknown tolerance names, a non-positive sd, an sd not smaller than the nominal value
        or making most designs impossible, an impossible nominal design, or fewer than 4
        samples that solve.
    ConvergenceError
        The nominal design's squeeze does not converge.

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> try:
    ...     squeeze_tolerances(BASE, 62.5, [0.6], {"colour": 1.0})
    ... except ValueError as exc:
    ...     print(str(exc)[:38])
    tolerances: unknown name 'colour' (kno
    """
    names, nominal, sd = _check_inputs(structure, shore, tolerances)
    if not isinstance(samples, int) or isinstance(samples, bool) or not 8 <= samples <= 4096:
        raise InputError(f"samples must be an integer in [8, 4096], got {samples!r}")
    seed = check_seed("seed", seed)
    if method not in ("auto", "brute-force"):
        raise InputError(f"method must be 'auto' or 'brute-force', got {method!r}")
    if progress is not None and not callable(progress):
        raise InputError("progress must be a callable progress(done, total, stage)")
    p = np.asarray(pressures_mpa, dtype=float).ravel()
    squeeze_options.setdefault("keep_fields", False)
    job = _Job(structure, float(shore), solver, squeeze_options, ())
    job.design({})                              # an impossible nominal design: InputError
    values = _sobol_values(names, nominal, sd, samples, seed)
    ok = _feasible(job, names, values)
    rows = np.vstack([values[ok], _ranking_points(names, nominal, sd)])
    n_ok = int(ok.sum())
    n_workers = _workers(workers, n_ok)

    def run(j: _Job, stage: str) -> list[_Outcome]:
        return _solve_all(j, min(n_workers, len(j.tasks)), progress, stage)

    ans: _Answer | str = "brute force asked for"
    if method == "auto" and n_ok >= 4:
        ans = _by_grid(job, names, nominal, rows, n_ok, p, run)
    if isinstance(ans, str):
        ans = _by_brute_force(job, names, rows, n_ok, p, run, ans)
    _warn_once(ans.outcomes)
    arr = ans.samples_n
    if len(arr) < 4:
        raise InputError(f"only {len(arr)} of {samples} samples solved: the tolerances make "
                         "most designs impossible (tube and wire must fit the hole)")
    pct = {q: tuple(np.percentile(arr, q, axis=0).tolist()) for q in _PCTS}
    return ToleranceResult(
        tuple(p.tolist()), tuple(ans.nominal_n.tolist()), pct, arr,
        _ranking(names, ans.points_n), {k: sd[k] for k in names},
        ans.failed + samples - n_ok, ans.method, ans.note, ans.held_out_error_pct,
        len(ans.outcomes), ans.onset)
