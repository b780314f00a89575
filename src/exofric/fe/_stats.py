"""Where the Newton work of a solve went: :class:`SolverStats` and :func:`collect_stats`.

:func:`exofric.fe.solve_path` reports each Newton attempt to every collector active in the
current context (thread or task); collectors nest.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from contextvars import ContextVar
from dataclasses import asdict, dataclass
from typing import Any

from exofric._validate import checked_init

__all__ = ["SolverStats", "StatsCollector", "collect_stats", "collecting", "record_attempt"]


@checked_init
@dataclass(frozen=True)
class SolverStats:
    """Where a solve's Newton work went (accumulated by :func:`collect_stats`).

    An *attempt* is one Newton iteration sequence at one load (a sub-step, a probe of the
    contact onset, a release of the regulariser); a failed attempt ends in a cut-back or a
    retry from the last converged state, so its time is wasted.

    Parameters
    ----------
    attempts : int
        Newton attempts.
    failed_attempts : int
        Attempts that did not converge.
    iterations : int
        Newton iterations (tangent evaluations), failed attempts included.
    linear_solves : int
        Linear solves (factorisations), the active-set re-solves included.
    time_s : float
        Wall time in Newton attempts (s).
    failed_time_s : float
        Wall time in failed attempts (s).

    Examples
    --------
    >>> SolverStats(attempts=4, failed_attempts=1, time_s=2.0, failed_time_s=0.5).failed_time_pct
    25.0
    """

    attempts: int = 0
    failed_attempts: int = 0
    iterations: int = 0
    linear_solves: int = 0
    time_s: float = 0.0
    failed_time_s: float = 0.0

    @property
    def failed_time_pct(self) -> float:
        """Share of the Newton time spent in failed attempts (%)."""
        return 100.0 * self.failed_time_s / self.time_s if self.time_s > 0.0 else 0.0

    def to_dict(self) -> dict[str, float]:
        """The counts and times, plus ``failed_time_pct`` (%).

        Examples
        --------
        >>> SolverStats(attempts=2).to_dict()["attempts"]
        2
        """
        return {**asdict(self), "failed_time_pct": self.failed_time_pct}


class _Tally:
    """Mutable counters behind :func:`collect_stats`."""

    def __init__(self) -> None:
        self.counts = dict.fromkeys(("attempts", "failed_attempts", "iterations",
                                     "linear_solves"), 0)
        self.times = {"time_s": 0.0, "failed_time_s": 0.0}

    def stats(self) -> SolverStats:
        c, t = self.counts, self.times
        return SolverStats(c["attempts"], c["failed_attempts"], c["iterations"],
                           c["linear_solves"], t["time_s"], t["failed_time_s"])


_TALLIES: ContextVar[tuple[_Tally, ...]] = ContextVar("exofric_solver_tallies", default=())


class StatsCollector:
    """Handle of :func:`collect_stats`; :attr:`stats` reads the counts so far.

    Parameters
    ----------
    tally : object
        The (private) counters that :func:`solve_path` adds to while the ``with`` block runs.

    Examples
    --------
    >>> with collect_stats() as c:
    ...     pass
    >>> c.stats.attempts
    0
    """

    def __init__(self, tally: Any) -> None:  # a _Tally (private)
        self._tally = tally

    @property
    def stats(self) -> SolverStats:
        """The statistics accumulated so far."""
        return self._tally.stats()


@contextlib.contextmanager
def collect_stats() -> Iterator[StatsCollector]:
    """Count the Newton work of every :func:`solve_path` call inside the ``with`` block.

    Collectors nest (each counts everything inside it) and are per context (thread or task).

    Yields
    ------
    StatsCollector
        Its ``stats`` (:class:`SolverStats`) hold the counts and times so far.

    Examples
    --------
    >>> from exofric.fe import InflationProblem, MeshSpec, solve_path
    >>> from exofric.material import MooneyRivlin
    >>> p = InflationProblem(8.3, 4.97, MooneyRivlin.from_shore(62.5), MeshSpec())
    >>> with collect_stats() as c:
    ...     _ = solve_path(p, [0.2])
    >>> c.stats.attempts >= 1, c.stats.failed_attempts
    (True, 0)
    """
    tally = _Tally()
    token = _TALLIES.set((*_TALLIES.get(), tally))
    try:
        yield StatsCollector(tally)
    finally:
        _TALLIES.reset(token)


def record_attempt(ok: bool, iterations: int, solves: int, dt: float) -> None:
    """Add one Newton attempt to every active collector."""
    for t in _TALLIES.get():
        t.counts["attempts"] += 1
        t.counts["failed_attempts"] += not ok
        t.counts["iterations"] += iterations
        t.counts["linear_solves"] += solves
        t.times["time_s"] += dt
        if not ok:
            t.times["failed_time_s"] += dt


def collecting() -> bool:
    """Whether any collector is active here (the solver skips its timing otherwise)."""
    return bool(_TALLIES.get())
