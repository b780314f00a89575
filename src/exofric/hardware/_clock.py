"""Clocks for the control loop: real (monotonic), scaled, and simulated.

A clock has ``now()`` (s, monotonic, arbitrary origin) and ``sleep_until(t)`` (s, on the same
scale). The loop schedules on it; tests and ``sim://?speed=0`` use a :class:`SimClock` whose
``sleep_until`` just moves time forward.
"""

from __future__ import annotations

import time
from typing import Protocol, runtime_checkable

__all__ = ["Clock", "RealClock", "SimClock"]


@runtime_checkable
class Clock(Protocol):
    """A monotonic clock the loop can sleep on (times in s).

    Examples
    --------
    >>> isinstance(SimClock(), Clock)
    True
    """

    def now(self) -> float:
        """The current time in s."""

    def sleep_until(self, t: float) -> None:
        """Return at (or as soon as possible after) time ``t`` in s.

        Parameters
        ----------
        t : float
            Wake-up time in s on this clock's scale.
        """


class RealClock:
    """Wall time (``time.perf_counter``) divided by ``speed``-up: 1 = real time.

    Parameters
    ----------
    speed : float
        Time runs ``speed`` times faster than real time (> 0, unitless).

    Examples
    --------
    >>> c = RealClock()
    >>> t = c.now(); c.sleep_until(t + 0.001); c.now() - t >= 0.001
    True
    """

    def __init__(self, speed: float = 1.0) -> None:
        self.speed = float(speed)
        self._t0 = time.perf_counter()

    def now(self) -> float:
        """Seconds since the clock was made (scaled by ``speed``)."""
        return (time.perf_counter() - self._t0) * self.speed

    def sleep_until(self, t: float) -> None:
        """Sleep until ``t`` (s); returns at once when ``t`` is past.

        Parameters
        ----------
        t : float
            Wake-up time in s.
        """
        while True:
            rest = (t - self.now()) / self.speed
            if rest <= 0.0:
                return
            time.sleep(rest)


class SimClock:
    """Simulated time: ``sleep_until`` jumps there; ``advance`` models time spent working.

    Parameters
    ----------
    t0_s : float
        Start time in s.

    Examples
    --------
    >>> c = SimClock()
    >>> c.sleep_until(0.5); c.advance(0.01); c.now()
    0.51
    """

    def __init__(self, t0_s: float = 0.0) -> None:
        self.t = float(t0_s)

    def now(self) -> float:
        """The simulated time in s."""
        return self.t

    def sleep_until(self, t: float) -> None:
        """Jump to ``t`` (s) if it is ahead.

        Parameters
        ----------
        t : float
            Wake-up time in s.
        """
        if t > self.t:
            self.t = float(t)

    def advance(self, dt_s: float) -> None:
        """Let ``dt_s`` s pass (e.g. a slow device call in a test).

        Parameters
        ----------
        dt_s : float
            Elapsed time in s (>= 0).
        """
        self.t += float(dt_s)
