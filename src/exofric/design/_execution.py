"""How a sweep's designs are solved: in this process, on local worker processes, or on Dask.

Units: s (times), dofs (degrees of freedom), MPa (pressures).

:func:`plan_execution` is the rule of ``exofric sweep``'s default (``executor="auto"``): it
compares the predicted wall time of the solves in this process (designs x the cost of one)
with that of a pool of k worker processes (start-up + rounds of k designs + dispatch), and
starts workers only when they save at least :data:`exofric.defaults.SWEEP_MIN_GAIN_S` and
:data:`exofric.defaults.SWEEP_MIN_GAIN_REL` of the serial time. The cost of one design is
estimated from the mesh size and load path (:func:`estimate_design_time_s`) before anything
was solved, and replaced by the measured time of the designs solved so far once there is one
(a sweep that started serially re-plans after every design, and moves the rest to workers
as soon as that pays).

The local pool (:class:`SweepPool`) is a :class:`concurrent.futures.ProcessPoolExecutor`
whose workers are forked from this process on Linux (they inherit its imports: starting two
costs ~0.03 s, against ~0.65 s + 0.2 s to start and close a Dask ``LocalCluster``), live for
the whole sweep, run one BLAS/OpenMP thread each and ignore Ctrl-C (the parent stops them).
Elsewhere the ``spawn`` start method is used, whose workers import exofric once each.
A Dask cluster is used only when asked for (``--scheduler``, ``executor="dask"``): on one
machine its start-up and per-task costs are strictly larger than the pool's.
"""

from __future__ import annotations

import contextlib
import math
import multiprocessing
import os
import re
import signal
import sys
import warnings
from collections.abc import Callable, Generator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import asdict, dataclass
from typing import Any

from exofric import defaults
from exofric._validate import checked_init
from exofric.design._spec import SolverSpec
from exofric.errors import InputError

__all__ = ["EXECUTORS", "ExecutionPlan", "plan_execution", "estimate_design_time_s",
           "available_cpus", "start_method", "SweepPool", "check_scheduler", "probe_scheduler"]

#: Values of ``run_sweep(executor=...)`` / ``exofric sweep --executor``.
EXECUTORS = ("auto", "serial", "processes", "dask")

#: Environment of every worker process: one BLAS/OpenMP thread each.
BLAS_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}


@checked_init
@dataclass(frozen=True)
class ExecutionPlan:
    """Where a sweep's designs are solved, and why.

    Attributes
    ----------
    mode : {'serial', 'processes', 'dask'}
        In this process, on local worker processes, or on a Dask cluster.
    workers : int
        Worker processes (1 for ``serial``; for ``dask``, the workers asked for, 0 = unknown).
    reason : str
        One sentence: the option that asked for it, or the predicted times that decided.
    design_time_s : float
        Cost of one design's solve used for the decision (s; NaN when not needed).
    serial_time_s : float
        Predicted wall time of the solves in this process (s; NaN when not predicted).
    parallel_time_s : float
        Predicted wall time on ``workers`` processes, start-up included (s; NaN when not
        predicted).

    Examples
    --------
    >>> p = ExecutionPlan("serial", 1, "requested: serial, in this process")
    >>> p.mode, p.to_dict()["workers"]
    ('serial', 1)
    """

    mode: str
    workers: int
    reason: str
    design_time_s: float = math.nan
    serial_time_s: float = math.nan
    parallel_time_s: float = math.nan

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (times in s, NaN where not predicted)."""
        return asdict(self)


def available_cpus() -> int:
    """CPUs this process may run on (its affinity mask where the OS has one), at least 1.

    Returns
    -------
    int

    Examples
    --------
    >>> available_cpus() >= 1
    True
    """
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):  # not on Linux
        return max(1, os.cpu_count() or 1)


def start_method() -> str:
    """How local workers are started: ``"fork"`` on Linux (cheap, inherits this process'
    imports), ``"spawn"`` elsewhere (fork is unsafe with macOS system libraries).

    Returns
    -------
    str

    Examples
    --------
    >>> start_method() in ("fork", "spawn")
    True
    """
    return "fork" if sys.platform.startswith("linux") else "spawn"


def design_dofs(solver: SolverSpec) -> int:
    """Degrees of freedom of the quad9 half-tube mesh: 2 (2 n_radial + 1) (2 n_circ + 1)."""
    return 2 * (2 * solver.n_radial + 1) * (2 * solver.n_circ + 1)


def estimate_design_time_s(solver: SolverSpec, pressures_mpa: Sequence[float]) -> float:
    """A-priori cost of one design's squeeze solve (s), from the mesh size and the load path.

    ``s_per_design + s_per_dof_step x dofs x (largest pressure / max_step_mpa)`` with the
    coefficients of :data:`exofric.defaults.SWEEP_DESIGN_COST` (fitted on one machine; the
    sweep replaces this guess by measured times as soon as one design is solved).

    Parameters
    ----------
    solver : SolverSpec
        Mesh (``n_radial`` x ``n_circ`` quad9) and largest pressure sub-step (MPa).
    pressures_mpa : sequence of float
        The sweep's output pressures (MPa); the load path runs up to the largest.

    Returns
    -------
    float
        Estimated CPU time of one design (s).

    Examples
    --------
    >>> from exofric.design import SolverSpec
    >>> t = estimate_design_time_s(SolverSpec(n_radial=2, n_circ=24), [0.3, 0.6])
    >>> 0.01 < t < 10.0                           # 490 dofs x 24 steps of 0.025 MPa
    True
    """
    c = defaults.SWEEP_DESIGN_COST
    steps = max(1.0, max(pressures_mpa, default=0.0) / solver.max_step_mpa)
    return float(c["s_per_design"] + c["s_per_dof_step"] * design_dofs(solver) * steps)


def _pool_start_s(method: str, workers: int) -> float:
    c = defaults.SWEEP_POOL_START_S.get(method, defaults.SWEEP_POOL_START_S["spawn"])
    return float(c["fixed"] + c["per_worker"] * workers)


def plan_execution(
    designs: int,
    design_time_s: float,
    cpus: int,
    *,
    method: str | None = None,
    basis: str = "estimated",
) -> ExecutionPlan:
    """Serial or local worker processes for ``designs`` solves of ``design_time_s`` each.

    Predicted wall times: serial ``designs x t``; on k workers (2 <= k <= min(cpus,
    designs)) ``start(k) + ceil(designs / k) x t + designs x dispatch``, with the measured
    start-up ``start(k) = fixed + per_worker x k`` of :data:`exofric.defaults.SWEEP_POOL_START_S`
    for the start method and the per-task dispatch cost of
    :data:`exofric.defaults.SWEEP_TASK_OVERHEAD_S`. The fastest k is chosen if it saves at
    least ``max(SWEEP_MIN_GAIN_S, SWEEP_MIN_GAIN_REL x serial)``; otherwise serial. No
    timing happens here: the inputs decide.

    Parameters
    ----------
    designs : int
        Designs still to solve.
    design_time_s : float
        Cost of one design (s), estimated or measured.
    cpus : int
        CPUs available (:func:`available_cpus`).
    method : str, optional
        Start method of the workers (default :func:`start_method`).
    basis : str
        How ``design_time_s`` was obtained, quoted in the reason (e.g. ``"measured"``).

    Returns
    -------
    ExecutionPlan

    Examples
    --------
    >>> plan_execution(2, 0.01, cpus=2).mode               # 2 quick designs: not worth it
    'serial'
    >>> p = plan_execution(64, 0.5, cpus=2)                # 32 s of work
    >>> p.mode, p.workers, p.parallel_time_s < 0.6 * p.serial_time_s
    ('processes', 2, True)
    """
    method = method or start_method()
    t = max(0.0, float(design_time_s))
    serial = designs * t
    if designs <= 1:
        return ExecutionPlan("serial", 1, f"{designs} design to solve: nothing to share out",
                             t, serial)
    if cpus <= 1:
        return ExecutionPlan("serial", 1, "1 CPU available", t, serial)
    task_s = float(defaults.SWEEP_TASK_OVERHEAD_S["processes"])
    best_k, best = 1, serial
    for k in range(2, min(cpus, designs) + 1):
        par = _pool_start_s(method, k) + math.ceil(designs / k) * t + designs * task_s
        if par < best:
            best_k, best = k, par
    need = max(float(defaults.SWEEP_MIN_GAIN_S), float(defaults.SWEEP_MIN_GAIN_REL) * serial)
    work = f"{designs} designs x {t:.3g} s ({basis})"
    if best_k > 1 and serial - best >= need:
        return ExecutionPlan("processes", best_k,
                             f"{work}: {best_k} worker processes ({method}) predicted "
                             f"{best:.2f} s vs {serial:.2f} s in this process", t, serial, best)
    k = min(cpus, designs)
    par = _pool_start_s(method, k) + math.ceil(designs / k) * t + designs * task_s
    return ExecutionPlan("serial", 1,
                         f"{work}: {serial:.2f} s in this process; {k} worker processes would "
                         f"save {max(0.0, serial - par):.2f} s < {need:.2f} s", t, serial, par)


# --- the local pool -------------------------------------------------------------------------

def _init_worker(env: dict[str, str]) -> None:
    """Worker set-up, once per process: one BLAS thread, no Ctrl-C, fresh stdout/stderr."""
    os.environ.update(env)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent stops the pool on Ctrl-C
    # A forked worker inherits the parent's stream objects, whose locks another thread of the
    # parent (a progress bar) may have held at the fork: write through fresh ones.
    for name, fd in (("stdout", 1), ("stderr", 2)):
        with contextlib.suppress(OSError):
            setattr(sys, name, open(fd, "w", closefd=False, buffering=1))  # noqa: SIM115
    try:
        from threadpoolctl import threadpool_limits

        threadpool_limits(1)
    except Exception:  # pragma: no cover - threadpoolctl is a dependency; never fatal
        pass


class SweepPool:
    """Local worker processes that stay warm for a whole sweep (one BLAS thread each).

    A :class:`~concurrent.futures.ProcessPoolExecutor` started with :func:`start_method`; every
    worker is started at once, before any task runs. :meth:`results` submits tasks in order
    and yields ``(item, result)`` as they finish. If a worker dies (killed, out of memory,
    crash) the pool is started again once for the unfinished items; if it dies again, those
    items get ``on_error(item, message)`` as their result.

    Parameters
    ----------
    workers : int
        Worker processes (>= 1).
    method : str, optional
        Start method (default :func:`start_method`).

    Examples
    --------
    >>> with SweepPool(1) as pool:
    ...     sorted(r for _, r in pool.results(abs, [-2, 1], lambda x, m: -1))
    [1, 2]
    """

    #: How many times a pool whose worker died is started again.
    RESTARTS = 1

    def __init__(self, workers: int, method: str | None = None) -> None:
        if workers < 1:
            raise InputError(f"workers must be >= 1, got {workers}")
        self.workers = workers
        self.method = method or start_method()
        self._ex: ProcessPoolExecutor | None = None

    @property
    def label(self) -> str:
        """E.g. ``"processes(2 x 1 thread, fork)"``."""
        return f"processes({self.workers} x 1 thread, {self.method})"

    def _start(self) -> ProcessPoolExecutor:
        ctx = multiprocessing.get_context(self.method)
        ex = ProcessPoolExecutor(self.workers, mp_context=ctx, initializer=_init_worker,
                                 initargs=(dict(BLAS_ENV),))
        self._ex = ex
        with warnings.catch_warnings():
            # Python >= 3.12 warns when forking a process that runs other threads (a progress
            # bar, pyarrow's pool); the workers only solve and write through fresh streams.
            warnings.filterwarnings("ignore", message=r".*use of fork\(\) may lead to deadlocks",
                                    category=DeprecationWarning)
            ex.submit(int).result()  # start every worker (fork: all at once) and wait
        return ex

    def __enter__(self) -> SweepPool:
        self._start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.close(cancel=exc[0] is not None)

    def close(self, cancel: bool = False) -> None:
        """Stop the workers (idempotent).

        Parameters
        ----------
        cancel : bool
            Terminate them at once, dropping queued and running tasks (default: let the
            submitted tasks finish first).
        """
        ex, self._ex = self._ex, None
        if ex is None:
            return
        if cancel:
            for p in list(getattr(ex, "_processes", {}).values()):
                p.terminate()
        ex.shutdown(wait=True, cancel_futures=cancel)

    def results(self, fn: Callable[..., Any], items: Sequence[Any],
                on_error: Callable[[Any, str], Any], *args: Any
                ) -> Generator[tuple[Any, Any], None, None]:
        """Run ``fn(item, *args)`` for every item; yield ``(item, result)`` as they finish.

        Parameters
        ----------
        fn : callable
            A picklable function (run in the workers).
        items : sequence
            Its first arguments, submitted in this order.
        on_error : callable
            ``on_error(item, message)`` is the result of an item whose task raised (``fn``
            itself, or pickling) or whose worker died in the restarted pool too.
        *args
            Further arguments of ``fn``, the same for every item.

        Yields
        ------
        tuple
            ``(item, result)`` in the order the tasks finish.
        """
        pending = dict(enumerate(items))
        for attempt in range(self.RESTARTS + 1):
            ex = self._ex or self._start()
            futs: dict[Future[Any], int] = {ex.submit(fn, it, *args): i
                                            for i, it in pending.items()}
            broken = ""
            while futs and not broken:
                done, _ = wait(list(futs), return_when=FIRST_COMPLETED)
                for fut in done:
                    exc = fut.exception()
                    if isinstance(exc, BrokenProcessPool):
                        broken = f"BrokenProcessPool: a worker process died ({exc})"
                        continue
                    it = pending.pop(futs.pop(fut))
                    yield it, (fut.result() if exc is None else
                               on_error(it, f"{type(exc).__name__}: {exc}"))
            if not broken:
                return
            for fut in [f for f in futs if f.done() and f.exception() is None]:
                yield pending.pop(futs.pop(fut)), fut.result()  # finished before the break
            self.close(cancel=True)
            if attempt == self.RESTARTS:
                for it in pending.values():
                    yield it, on_error(it, broken)


def check_executor(executor: str) -> str:
    """``executor`` if it is one of :data:`EXECUTORS`, else :class:`InputError`."""
    if executor not in EXECUTORS:
        raise InputError(f"executor must be one of {', '.join(EXECUTORS)}, got {executor!r}")
    return executor


_ADDRESS = re.compile(r"^(?:(?P<proto>[a-z]+)://)?(?P<host>\[[0-9A-Fa-f:.]+\]|[^\s:/\[\]]+)"
                      r":(?P<port>[0-9]{1,5})/?$")


def check_scheduler(address: str) -> tuple[str, int]:
    """``(host, port)`` of a Dask scheduler address ``tcp://host:port`` (or ``host:port``).

    ``tls://`` is accepted too (also TCP). Anything else (no port, a port outside 1-65535,
    another protocol, spaces) is an :class:`InputError` naming ``scheduler``.

    Parameters
    ----------
    address : str
        The address given to ``--scheduler`` / ``run_sweep(scheduler=...)``.

    Returns
    -------
    tuple of (str, int)
        Host name or IP (IPv6 without brackets) and port.

    Examples
    --------
    >>> check_scheduler("tcp://10.0.0.1:8786"), check_scheduler("[::1]:8786")
    (('10.0.0.1', 8786), ('::1', 8786))
    >>> try:
    ...     check_scheduler("tcp://10.0.0.1")            # no port
    ... except InputError as exc:
    ...     print(str(exc)[:46])
    scheduler must look like tcp://host:port (port
    """
    m = _ADDRESS.match(address.strip())
    proto = m.group("proto") if m else None
    if m is None or proto not in (None, "tcp", "tls") or not 0 < int(m.group("port")) < 65536:
        raise InputError(f"scheduler must look like tcp://host:port (port 1-65535), e.g. "
                         f"tcp://10.0.0.1:8786, got {address!r}")
    return m.group("host").strip("[]"), int(m.group("port"))


def probe_scheduler(address: str, timeout_s: float | None = None) -> None:
    """Fail fast when nothing listens at a scheduler address: one TCP connect, then close.

    Waits at most ``timeout_s`` (default :data:`exofric.defaults.SWEEP_SCHEDULER_CONNECT_S`,
    s), instead of Dask's whole ``--timeout`` for an address where nothing listens; raises
    :class:`InputError` naming ``scheduler`` and the address.
    """
    import socket

    host, port = check_scheduler(address)
    wait = defaults.SWEEP_SCHEDULER_CONNECT_S if timeout_s is None else timeout_s
    try:
        with socket.create_connection((host, port), timeout=wait):
            pass
    except (OSError, TimeoutError) as exc:
        why = "no answer" if isinstance(exc, TimeoutError) else (exc.strerror or str(exc))
        raise InputError(f"scheduler {address}: nothing reachable there ({why} within "
                         f"{wait:g} s); is `dask scheduler` running and the port open?",
                         param="scheduler") from None
