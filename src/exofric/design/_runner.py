"""Design-space sweeps of the squeeze simulation, cached and resumable, serial or parallel.

Units: mm, MPa, N, s; torque in Nm, arm radius in m.

:func:`run_sweep` solves every design of a :class:`~exofric.design.SweepSpec` with
:func:`exofric.simulate.squeeze` and streams one Parquet file per finished design into the
output directory (:mod:`exofric.design`), so that

* by default (``executor="auto"``) it solves in this process or on local worker processes,
  whichever :func:`~exofric.design.plan_execution` predicts to be faster for the work size
  (designs x the estimated, then measured, cost of one; worker start-up and dispatch costs);
  ``workers=k`` asks for k local worker processes, ``serial=True`` for a plain in-process
  loop; the workers (:class:`~exofric.design.SweepPool`) stay up for the whole sweep, one
  BLAS/OpenMP thread each;
* with ``scheduler="tcp://host:8786"`` the same code runs on any Dask cluster (``dask
  scheduler`` + ``dask worker``, dask-jobqueue on SLURM...); ``executor="dask"`` without a
  scheduler starts an embedded ``LocalCluster``;
* designs already in the directory (same cache key: inputs + solver settings) are not
  solved again: a killed sweep resumes losing nothing that had finished;
* nothing stored is trusted blindly: every design file is checked against its SHA-256 and
  its derived columns when read (:meth:`~exofric.design.SweepStore.load`); a damaged one is
  moved to ``OUT/_quarantine/``, reported (one warning line each, :attr:`SweepRun.warnings`)
  and solved again;
* a design whose solve raises is recorded (status ``failed``, the error message) and the
  others go on; impossible designs are recorded as ``skipped`` with the reason.

Rows come back as a pandas DataFrame, one row per design and pressure; friction
F = gamma N + F0 (N), torque T = F R (Nm), the deviation from the base (%) and the design's
sizes, wall and clearance (mm) are recomputed from the sweep's current gamma, F0, R, base
and designs (:func:`postprocess`), so changing those reuses the cache and no stored derived
value can disagree with the stored squeeze force. The summary says which execution mode was
used and why.
"""

from __future__ import annotations

import contextlib
import logging
import math
import multiprocessing
import os
import socket
import time
import uuid
import warnings
from collections.abc import Callable, Generator, Mapping, Sequence
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from exofric._display import DisplayMixin, HtmlReprMixin
from exofric._validate import checked_init
from exofric.design._execution import (
    BLAS_ENV,
    ExecutionPlan,
    SweepPool,
    available_cpus,
    check_executor,
    check_scheduler,
    design_dofs,
    estimate_design_time_s,
    plan_execution,
    probe_scheduler,
)
from exofric.design._spec import Design, MaterialSpec, SolverSpec, SweepSpec, parse_sweep
from exofric.design._store import SweepStore, load_sweep
from exofric.errors import InputError

__all__ = ["SweepSummary", "SweepRun", "run_sweep", "sweep", "solve_design", "BLAS_ENV"]

#: ``progress(done, total, label)`` is called once with done = 0, then after each design.
ProgressFn = Callable[[int, int, str], None]
SolveFn = Callable[..., Any]


@checked_init
@dataclass(frozen=True)
class SweepSummary(DisplayMixin):
    """What one :func:`run_sweep` call did.

    ``designs`` = ``computed`` + ``cached`` + ``skipped``; ``computed`` counts the solves run
    now (successful or not), ``cached`` the designs found finished in ``out``, ``failed``
    the designs whose solve failed (now or cached).

    Attributes
    ----------
    designs : int
        Designs in the sweep.
    computed : int
        Solves run by this call (successful or failed).
    cached : int
        Designs found finished in ``out`` and not solved again.
    skipped : int
        Impossible designs (never solved).
    failed : int
        Designs whose solve failed, now or in a cached run.
    out : str
        The result directory.
    wall_time_s : float
        Wall time of the call (s).
    scheduler : str
        Where the solves ran: ``"serial"``, the worker pool (``"processes(2 x 1 thread,
        fork)"``), the LocalCluster description or the scheduler address.
    workers : int
        Worker processes used (1 when serial, 0 when nothing was solved).
    run_id : str
        Random id of this call, stored in its rows.
    execution : str
        Execution mode: ``"serial"``, ``"processes"``, ``"dask"`` or ``"none"`` (nothing to
        solve).
    execution_reason : str
        Why: the option that asked for it, or the predicted times (s) that decided.

    Examples
    --------
    >>> s = SweepSummary(3, 1, 1, 1, 0, "out", 12.5, "serial", 1, "0123456789ab")
    >>> s.computed + s.cached + s.skipped == s.designs, s.to_dict()["wall_time_s"]
    (True, 12.5)
    """

    designs: int
    computed: int
    cached: int
    skipped: int
    failed: int
    out: str
    wall_time_s: float
    scheduler: str
    workers: int
    run_id: str
    execution: str = "serial"
    execution_reason: str = ""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (times in s)."""
        return {"designs": self.designs, "computed": self.computed, "cached": self.cached,
                "skipped": self.skipped, "failed": self.failed, "out": self.out,
                "wall_time_s": self.wall_time_s, "scheduler": self.scheduler,
                "workers": self.workers, "run_id": self.run_id, "execution": self.execution,
                "execution_reason": self.execution_reason}


@checked_init
@dataclass(frozen=True)
class SweepRun(HtmlReprMixin):
    """Summary and rows (one per design and pressure) of a sweep.

    Attributes
    ----------
    summary : SweepSummary
        What the run did (counts, directory, wall time in s, scheduler).
    frame : pandas.DataFrame
        The rows, one per design and pressure (one row for a skipped or failed design);
        columns of :data:`exofric.design.SCHEMA` (mm, MPa, N, N/mm, Nm, m, %, s).
    warnings : tuple of str
        One line per stored design file that failed verification and was quarantined
        (and solved again), e.g. ``"OUT/design-<key>-ok.parquet: checksum mismatch ...;
        moved to OUT/_quarantine/..."``; empty when everything stored was sound.

    Examples
    --------
    >>> import tempfile
    >>> spec = parse_sweep({"pressures_mpa": [0.6], "grid": {"wire_mm": [1.6, 2.0]},
    ...                     "solver": {"n_radial": 1, "n_circ": 12}})   # coarse mesh
    >>> run = run_sweep(spec, tempfile.mkdtemp(), serial=True)
    >>> run.summary.computed, run.summary.skipped, list(run.frame["status"])
    (1, 1, ['ok', 'skipped'])
    >>> run.to_dict()["skipped_designs"][0]["name"]
    'd2=2'
    """

    summary: SweepSummary
    frame: pd.DataFrame = field(repr=False)
    warnings: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """Summary plus the failed (``failures``) and impossible (``skipped_designs``) ones
        and the quarantined files (``warnings``)."""
        one = self.frame.drop_duplicates("key")
        bad = one[one["status"] == "failed"]
        skip = one[one["status"] == "skipped"]
        return {**self.summary.to_dict(),
                "rows": int(len(self.frame)),
                "failures": [{"name": n, "error": e} for n, e in zip(bad["name"], bad["error"],
                                                                    strict=True)],
                "skipped_designs": [{"name": n, "reason": e} for n, e in
                                    zip(skip["name"], skip["error"], strict=True)],
                "warnings": list(self.warnings)}

    def to_frame(self) -> pd.DataFrame:
        """The sweep rows as a DataFrame (a copy of :attr:`frame`): one row per design and
        pressure (a single row for a skipped or failed design).

        Columns: see :data:`exofric.design.SCHEMA` (``pressure_mpa``, ``squeeze_force_n``,
        ``friction_n``, ``torque_nm``, the design sizes in mm, ...; mm, MPa, N, N/mm, Nm, m,
        %, s).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> import tempfile
        >>> from exofric.design import parse_sweep
        >>> spec = parse_sweep({"pressures_mpa": [0.3, 0.6], "grid": {},
        ...                     "solver": {"n_radial": 1, "n_circ": 12}})
        >>> df = run_sweep(spec, tempfile.mkdtemp(), serial=True).to_frame()
        >>> len(df), list(df["pressure_mpa"])
        (2, [0.3, 0.6])
        """
        return self.frame.copy()


def _threads() -> str:
    return ",".join(f"{k.split('_')[0].lower()}={os.environ.get(k, '')}" for k in BLAS_ENV)


def solve_design(
    design: Design,
    pressures_mpa: Sequence[float],
    material: MaterialSpec,
    solver: SolverSpec,
    solve_fn: SolveFn | None = None,
    *,
    raise_errors: bool = False,
) -> dict[str, Any]:
    """Solve one design (runs on a Dask worker); a failed solve is recorded, not raised.

    Parameters
    ----------
    design : Design
        Sizes (mm) and Shore A hardness.
    pressures_mpa : sequence of float
        Increasing pressures (MPa).
    material, solver : MaterialSpec, SolverSpec
        Shore-to-material options and solver settings.
    solve_fn : callable, optional
        Replacement for :func:`exofric.simulate.squeeze` (same signature; tests).
    raise_errors : bool
        Raise the solve's exception (e.g. :class:`~exofric.errors.ConvergenceError`) instead
        of recording it as ``status="failed"`` (a single design outside a sweep).

    Returns
    -------
    dict
        ``status`` (``ok``/``failed``), ``error``, the squeeze arrays (N, N/mm, mm),
        onset (MPa), Newton iterations, dofs, ``solve_time_s``/``task_time_s`` (s),
        ``worker`` (host:pid) and ``blas_threads``.

    Examples
    --------
    >>> from exofric.design import parse_sweep
    >>> spec = parse_sweep({"pressures_mpa": [0.6], "grid": {},
    ...                     "solver": {"n_radial": 1, "n_circ": 12}})
    >>> r = solve_design(spec.designs[0], spec.pressures_mpa, spec.material, spec.solver)
    >>> r["status"], round(r["squeeze_force_n"][0])
    ('ok', 241)
    """
    t0 = time.perf_counter()
    out: dict[str, Any] = {"status": "ok", "error": "", "worker":
                           f"{socket.gethostname()}:{os.getpid()}", "blas_threads": _threads()}
    try:
        if solve_fn is None:
            from exofric.simulate import squeeze

            solve_fn = squeeze
        mat = material.material(design.shore)
        out.update(c10_mpa=mat.c10_mpa, c01_mpa=mat.c01_mpa, d_per_mpa=mat.d_per_mpa)
        res = solve_fn(design.structure(), mat, list(pressures_mpa), mesh=solver.mesh(),
                       penalty=solver.penalty_n_per_mm3, density=solver.density_t_per_mm3,
                       gravity=solver.gravity,
                       settings=solver.newton(), keep_fields=False)
        for k in ("pressure_mpa", "squeeze_force_n", "squeeze_force_n_per_mm", "wall_force_n",
                  "newton_iterations"):
            out[k] = np.asarray(getattr(res, k)).tolist()
        out["max_penetration_mm"] = np.asarray(res.contact.max_penetration_mm).tolist()
        # largest principal stretch (> 2.5: beyond the model's validated strain range)
        out["max_stretch"] = np.asarray(
            getattr(res, "max_stretch", np.full(len(out["pressure_mpa"]), np.nan))).tolist()
        onset = res.contact_onset_pressure_mpa
        out.update(contact_onset_pressure_mpa=np.nan if onset is None else float(onset),
                   dofs=int(res.dofs), solve_time_s=float(res.solve_time_s))
    except Exception as exc:  # recorded, never fatal for the sweep
        if raise_errors:
            raise
        msg = " ".join(str(exc).split()) or "(no message)"
        out.update(status="failed", error=f"{type(exc).__name__}: {msg}")
    out["task_time_s"] = time.perf_counter() - t0
    return out


def _deviation(d: Design, spec: SweepSpec) -> tuple[float, bool]:
    """Deviation from the base (%) and whether ``d`` is in the validated region."""
    from exofric.friction import deviation

    m = deviation(d.structure(), spec.base, spec.threshold_pct)
    return m.deviation_pct, bool(m.in_validated_region and abs(d.shore - spec.base_shore) < 1e-9)


def _friction_n(force_n: np.ndarray, ok: np.ndarray, spec: SweepSpec) -> np.ndarray:
    """F = gamma N + F0 (N) where the solve succeeded, NaN elsewhere."""
    return np.where(ok, spec.gamma * force_n + spec.f0_n, np.nan)


def _rows(d: Design, status: str, res: Mapping[str, Any], run_id: str,
          spec: SweepSpec) -> pd.DataFrame:
    """One design's dataset rows (see :data:`exofric.design.SCHEMA`), post-processed.

    The derived columns are those :func:`postprocess` gives (``postprocess(rows, spec)``
    returns the same rows), computed for this one design only: the cost does not grow with
    the number of designs in the sweep.
    """
    n = len(res["pressure_mpa"]) if status == "ok" else 1

    def col(k: str, default: Any = np.nan) -> list[Any]:
        v = res.get(k, default)
        return list(v) if isinstance(v, list) else [v] * n

    force = np.asarray(col("squeeze_force_n"), dtype=float)
    friction = _friction_n(force, np.full(n, status == "ok"), spec)
    dev, valid = (np.nan, False) if status == "skipped" else _deviation(d, spec)
    rows = {
        "key": [d.key] * n, "design_index": [d.index] * n, "name": [d.name] * n,
        "family": [d.family] * n, "status": [status] * n, "error": [res.get("error", "")] * n,
        "hole_mm": [d.hole_mm] * n, "tube_od_mm": [d.tube_od_mm] * n,
        "tube_id_mm": [d.tube_id_mm] * n, "wire_mm": [d.wire_mm] * n,
        "length_mm": [d.length_mm] * n, "wall_mm": [0.5 * (d.tube_od_mm - d.tube_id_mm)] * n,
        "clearance_mm": [d.hole_mm - d.tube_od_mm - d.wire_mm] * n, "shore": [d.shore] * n,
        "c10_mpa": col("c10_mpa"), "c01_mpa": col("c01_mpa"), "d_per_mpa": col("d_per_mpa"),
        "pressure_mpa": col("pressure_mpa"), "squeeze_force_n": col("squeeze_force_n"),
        "squeeze_force_n_per_mm": col("squeeze_force_n_per_mm"),
        "wall_force_n": col("wall_force_n"), "friction_n": friction,
        "torque_nm": friction * spec.arm_radius_m,
        "gamma": [spec.gamma] * n, "f0_n": [spec.f0_n] * n,
        "arm_radius_m": [spec.arm_radius_m] * n, "deviation_pct": [float(dev)] * n,
        "in_validated_region": [valid] * n,
        "contact_onset_pressure_mpa": col("contact_onset_pressure_mpa"),
        "max_penetration_mm": col("max_penetration_mm"), "max_stretch": col("max_stretch"),
        "newton_iterations": col("newton_iterations", 0), "dofs": col("dofs", 0),
        "solve_time_s": col("solve_time_s"), "task_time_s": col("task_time_s"),
        "worker": col("worker", ""), "blas_threads": col("blas_threads", ""),
        "run_id": [run_id] * n, "finished_at": [datetime.now(UTC).isoformat()] * n,
    }
    frame = pd.DataFrame(rows)
    frame["design_index"] = frame["design_index"].astype("int64")
    if not frame["pressure_mpa"].is_monotonic_increasing:  # the solver keeps the given order
        frame = frame.sort_values("pressure_mpa", kind="stable").reset_index(drop=True)
    return frame


def postprocess(frame: pd.DataFrame, spec: SweepSpec) -> pd.DataFrame:
    """Friction (N), torque (Nm), deviation (%) and labels from ``spec``, rows in design order.

    ``in_validated_region`` is True when the geometric deviation from ``spec.base`` is at
    most ``spec.threshold_pct`` (:func:`exofric.friction.deviation`) *and* the
    hardness equals the base's (the paper validated one material only).

    Only the solved (primary) columns are taken from ``frame``: labels, sizes (mm), Shore,
    wall and clearance (mm), friction (N), torque (Nm), deviation (%) and the validated flag
    are derived again from ``spec`` and the squeeze force, so a stored derived value can
    never disagree with its primary one.
    """
    by_key = {d.key: d for d in spec.designs}
    f = frame[frame["key"].isin(list(by_key))].copy()
    f["design_index"] = f["key"].map(lambda k: by_key[k].index).astype("int64")
    for col in ("name", "family", "hole_mm", "tube_od_mm", "tube_id_mm", "wire_mm",
                "length_mm", "shore"):
        f[col] = f["key"].map(lambda k, c=col: getattr(by_key[k], c))
    f["wall_mm"] = 0.5 * (f["tube_od_mm"] - f["tube_id_mm"])
    f["clearance_mm"] = f["hole_mm"] - f["tube_od_mm"] - f["wire_mm"]
    ok = (f["status"] == "ok").to_numpy()
    n = f["squeeze_force_n"].to_numpy(dtype=float)
    f["friction_n"] = _friction_n(n, ok, spec)
    f["torque_nm"] = f["friction_n"] * spec.arm_radius_m
    f["gamma"], f["f0_n"], f["arm_radius_m"] = spec.gamma, spec.f0_n, spec.arm_radius_m
    dev: dict[str, tuple[float, bool]] = {}
    for key in f.loc[f["status"] != "skipped", "key"].unique():
        dev[key] = _deviation(by_key[key], spec)
    f["deviation_pct"] = f["key"].map(lambda k: dev.get(k, (np.nan, False))[0]).astype(float)
    f["in_validated_region"] = f["key"].map(lambda k: dev.get(k, (np.nan, False))[1])
    f["in_validated_region"] = f["in_validated_region"].astype(bool)
    return f.sort_values(["design_index", "pressure_mpa"], kind="stable").reset_index(drop=True)


def _failed(design: Design, message: str) -> dict[str, Any]:
    """The result of a design whose task could not run to the end (e.g. its worker died)."""
    return {"status": "failed", "error": message}


def _dask_results(todo: Sequence[Design], args: tuple[Any, ...], workers: int | None,
                  scheduler: str | None, timeout_s: float, info: dict[str, Any]
                  ) -> Generator[tuple[Design, dict[str, Any]], None, None]:
    """Submit ``todo`` to Dask and yield (design, result) as they finish."""
    from distributed import Client, LocalCluster, as_completed

    with contextlib.ExitStack() as stack:
        if scheduler:
            probe_scheduler(scheduler)      # seconds, not Dask's whole timeout, for a dead address
            try:
                client = stack.enter_context(Client(scheduler, timeout=f"{timeout_s}s"))
                client.wait_for_workers(1, timeout=timeout_s)
            except (OSError, TimeoutError) as exc:
                raise InputError(f"scheduler {scheduler}: cannot reach a scheduler with "
                                 f"workers ({type(exc).__name__}: {exc})") from None
            info["scheduler"] = scheduler
        else:
            n = max(1, min(workers or available_cpus(), len(todo)))
            cluster = stack.enter_context(LocalCluster(
                n_workers=n, threads_per_worker=1, processes=True, host="127.0.0.1",
                dashboard_address=":0", silence_logs=logging.ERROR, env=dict(BLAS_ENV)))
            client = stack.enter_context(Client(cluster))
            info["scheduler"] = f"LocalCluster({n} processes x 1 thread)"
        info["workers"] = len(client.scheduler_info(n_workers=-1)["workers"])
        futs = {client.submit(solve_design, d, *args, key=f"exofric-design-{d.key}",
                              pure=False): d for d in todo}
        for fut in as_completed(list(futs)):
            d = futs.pop(fut)
            try:
                res = fut.result()
            except Exception as exc:  # e.g. KilledWorker: recorded like a failed solve
                res = {"status": "failed", "error": f"{type(exc).__name__}: {exc}"}
            fut.release()
            yield d, res


def _explicit_plan(n_todo: int, workers: int | None, scheduler: str | None, serial: bool,
                   executor: str) -> ExecutionPlan | None:
    """The plan an explicit option asks for (None: decide by the work size)."""
    if n_todo == 0:
        return ExecutionPlan("none", 0, "nothing to solve (all designs cached or impossible)")
    if serial or executor == "serial":
        return ExecutionPlan("serial", 1, "requested: serial, in this process")
    if scheduler:
        return ExecutionPlan("dask", 0, f"requested: the Dask scheduler at {scheduler}")
    if executor == "dask":
        k = max(1, min(workers or available_cpus(), n_todo))
        return ExecutionPlan("dask", k, f"requested: Dask, a LocalCluster of {k}")
    if workers is not None:
        k = min(workers, n_todo)
        return ExecutionPlan("processes", k, f"requested: {workers} worker processes, at most "
                             "one per design to solve")
    if executor == "processes":
        k = max(1, min(available_cpus(), n_todo))
        return ExecutionPlan("processes", k, "requested: worker processes, one per CPU, at "
                             "most one per design to solve")
    return None


def _auto_plan(spec: SweepSpec, n_todo: int, cpus: int) -> ExecutionPlan:
    """The plan for ``n_todo`` designs of ``spec`` from the a-priori cost estimate."""
    est = estimate_design_time_s(spec.solver, spec.pressures_mpa)
    steps = max(spec.pressures_mpa) / spec.solver.max_step_mpa
    return plan_execution(n_todo, est, cpus, basis=f"estimated from {design_dofs(spec.solver)} "
                          f"dofs x {steps:.0f} load steps")


def _adaptive_results(todo: Sequence[Design], args: tuple[Any, ...], cpus: int,
                      info: dict[str, Any], stack: contextlib.ExitStack
                      ) -> Generator[tuple[Design, dict[str, Any]], None, None]:
    """Solve here, re-planning after every design with the measured mean time; move the
    remaining designs to worker processes as soon as that is predicted to pay."""
    spent = 0.0
    for i, d in enumerate(todo):
        if i and cpus > 1 and len(todo) - i > 1:
            plan = plan_execution(len(todo) - i, spent / i, cpus,
                                  basis=f"measured, mean of the first {i} solved here")
            if plan.mode == "processes":
                pool = stack.enter_context(SweepPool(plan.workers))
                info.update(execution="processes", workers=plan.workers, scheduler=pool.label,
                            execution_reason=f"{i} solved here, then {plan.reason}")
                yield from pool.results(solve_design, todo[i:], _failed, *args)
                return
            info["execution_reason"] = plan.reason
        t0 = time.perf_counter()
        res = solve_design(d, *args)
        spent += time.perf_counter() - t0
        yield d, res


def run_sweep(
    spec: SweepSpec,
    out: str | Path,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    serial: bool = False,
    executor: str = "auto",
    retry_failed: bool = False,
    progress: ProgressFn | None = None,
    solve_fn: SolveFn | None = None,
    timeout_s: float = 60.0,
) -> SweepRun:
    """Run (or resume) a sweep and return its summary and rows.

    Parameters
    ----------
    spec : SweepSpec
        Designs, pressures (MPa), friction model and solver settings.
    out : str or Path
        Result directory (Parquet dataset); created if missing, reused as the cache.
    workers : int, optional
        Local worker processes (at most one per design to solve); with ``executor="dask"``
        the LocalCluster's. Default: decided by the work size (``executor="auto"``).
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://host:8786``); ``workers`` is ignored.
    serial : bool
        Solve in this process in a plain loop (same as ``executor="serial"``).
    executor : {'auto', 'serial', 'processes', 'dask'}
        ``auto``: serial or local worker processes, whichever
        :func:`~exofric.design.plan_execution` predicts faster (re-planned with measured
        times while solving serially); ``processes``: one worker per CPU; ``dask``: a
        LocalCluster (or ``scheduler``).
    retry_failed : bool
        Solve again designs recorded as failed (default: keep their cached error).
    progress : callable, optional
        ``progress(done, total, label)`` after each design.
    solve_fn : callable, optional
        Replacement for :func:`exofric.simulate.squeeze` (must be picklable for workers).
    timeout_s : float
        How long to wait for ``scheduler`` and its first worker (s), finite and > 0. Before
        that, one TCP connect (at most :data:`exofric.defaults.SWEEP_SCHEDULER_CONNECT_S`)
        checks that something listens at the address.

    Returns
    -------
    SweepRun
        ``summary.execution`` and ``summary.execution_reason`` say how it ran and why;
        ``warnings`` lists the stored files that failed verification (each also issued as a
        :class:`RuntimeWarning`), which were moved to ``out/_quarantine/`` and solved again.

    Raises
    ------
    InputError
        ``workers`` < 1, an unknown ``executor``, ``timeout_s`` not finite and > 0,
        ``scheduler`` not ``tcp://host:port``, or no scheduler with workers reachable at
        ``scheduler``.

    Examples
    --------
    >>> import tempfile
    >>> spec = parse_sweep({"pressures_mpa": [0.3, 0.6], "grid": {"wire_mm": [1.6, 2.0]},
    ...                     "solver": {"n_radial": 1, "n_circ": 12}})
    >>> run = run_sweep(spec, tempfile.mkdtemp(), serial=True)
    >>> run.summary.computed, run.summary.skipped, len(run.frame), run.summary.execution
    (1, 1, 3, 'serial')
    """
    check_executor(executor)
    if workers is not None and workers < 1:
        raise InputError(f"workers must be >= 1, got {workers}")
    if not (isinstance(timeout_s, int | float) and math.isfinite(timeout_s) and timeout_s > 0):
        raise InputError(f"timeout_s must be a finite number of seconds > 0, got {timeout_s}")
    if scheduler:
        check_scheduler(scheduler)
    t0 = time.perf_counter()
    run_id = uuid.uuid4().hex[:12]
    store = SweepStore(out)
    store.remove_temporary()
    store.write_manifest(spec, {"run_id": run_id})
    cached, bad = store.load([d.key for d in spec.designs])
    problems = [q.message() for q in bad]
    for msg in problems:
        warnings.warn(msg, RuntimeWarning, stacklevel=2)
    have = {k: status for k, (status, _) in cached.items()}
    done_ok = ("ok",) if retry_failed else ("ok", "failed")
    todo = [d for d in spec.runnable if have.get(d.key) not in done_ok]
    args = (spec.pressures_mpa, spec.material, spec.solver, solve_fn)
    cpus = available_cpus()
    plan = _explicit_plan(len(todo), workers, scheduler, serial, executor)
    auto = plan is None
    if plan is None:
        plan = _auto_plan(spec, len(todo), cpus)
    if plan.mode == "processes" and multiprocessing.current_process().daemon:
        plan = ExecutionPlan("serial", 1, "this process is a daemonic worker, which may not "
                             f"start processes (wanted: {plan.reason})")
        auto = False
    info: dict[str, Any] = {"scheduler": {"none": "none (nothing to solve)"}.get(plan.mode,
                                                                            plan.mode),
                            "workers": plan.workers, "execution": plan.mode,
                            "execution_reason": plan.reason}
    with contextlib.ExitStack() as stack:
        results: Generator[tuple[Design, dict[str, Any]], None, None]
        if plan.mode == "processes":
            # workers start (fork) before this process writes Parquet or shows progress
            pool = stack.enter_context(SweepPool(plan.workers))
            info["scheduler"] = pool.label
            results = pool.results(solve_design, todo, _failed, *args)
        elif plan.mode == "dask":
            results = _dask_results(todo, args, workers, scheduler, timeout_s, info)
        elif plan.mode == "serial" and auto:
            results = _adaptive_results(todo, args, cpus, info, stack)
        else:
            results = ((d, solve_design(d, *args)) for d in todo)
        results = stack.enter_context(contextlib.closing(results))
        written: list[str] = []
        for d in spec.skipped:
            if have.get(d.key) != "skipped":
                store.write(d.key, "skipped", _rows(d, "skipped", {"error": d.skip_reason},
                                                    run_id, spec))
                written.append(d.key)
        if progress:
            progress(0, len(todo), "")
        for i, (d, res) in enumerate(results, 1):
            store.write(d.key, res["status"], _rows(d, res["status"], res, run_id, spec))
            written.append(d.key)
            if progress:
                progress(i, len(todo), f"{d.name} ({res['status']})")
    fresh, bad_now = store.load(written)    # read back and verified like the cached ones
    for q in bad_now:
        problems.append(q.message())
        warnings.warn(q.message(), RuntimeWarning, stacklevel=2)
    tables = {**{k: t for k, (_, t) in cached.items()}, **{k: t for k, (_, t) in fresh.items()}}
    frame = postprocess(store.frame(tables[d.key] for d in spec.designs if d.key in tables),
                        spec)
    status = frame.drop_duplicates("key")["status"]
    summary = SweepSummary(
        designs=len(spec.designs), computed=len(todo),
        cached=len(spec.runnable) - len(todo), skipped=len(spec.skipped),
        failed=int((status == "failed").sum()), out=str(Path(out)),
        wall_time_s=time.perf_counter() - t0, scheduler=str(info["scheduler"]),
        workers=int(info["workers"]), run_id=run_id, execution=str(info["execution"]),
        execution_reason=str(info["execution_reason"]))
    return SweepRun(summary, frame, tuple(problems))


def sweep(
    config: str | Path | Mapping[str, Any] | SweepSpec,
    out: str | Path,
    **kwargs: Any,
) -> pd.DataFrame:
    """Python twin of ``exofric sweep CONFIG --out DIR``: the rows as a DataFrame.

    ``config`` is a sweep TOML path, a parsed TOML mapping or a :class:`SweepSpec`;
    ``kwargs`` are those of :func:`run_sweep`. The summary (``designs``, ``computed``,
    ``cached``, ``skipped``, ``failed``, ``out``, ``wall_time_s``) is in
    ``frame.attrs["summary"]``. Columns: see :data:`exofric.design.SCHEMA`
    (mm, MPa, N, N/mm, Nm, m, %, s).

    Parameters
    ----------
    config : str, Path, mapping or SweepSpec
        Sweep TOML file (:func:`exofric.design.load_sweep`), its parsed content
        (:func:`parse_sweep`) or a parsed spec.
    out : str or Path
        Result directory (Parquet dataset), reused as the cache.
    **kwargs
        Keyword arguments of :func:`run_sweep` (``workers``, ``scheduler``, ``serial``,
        ``executor``, ``retry_failed``, ``progress``, ``solve_fn``, ``timeout_s`` in s).

    Returns
    -------
    pandas.DataFrame
        :attr:`SweepRun.frame`, with the summary in ``attrs["summary"]``.

    Examples
    --------
    >>> import tempfile
    >>> f = sweep({"pressures_mpa": [0.6], "grid": {"hole_mm": [10.0, 9.0]},
    ...            "solver": {"n_radial": 1, "n_circ": 12}}, tempfile.mkdtemp(), serial=True)
    >>> f.attrs["summary"]["skipped"], round(float(f["torque_nm"].iloc[0]), 1)
    (1, 17.2)
    """
    if isinstance(config, SweepSpec):
        spec = config
    elif isinstance(config, Mapping):
        spec = parse_sweep(config)
    else:
        spec = load_sweep(config)
    run = run_sweep(spec, out, **kwargs)
    frame = run.frame
    frame.attrs["summary"] = run.summary.to_dict()
    return frame
