"""The real-time control loop: fixed rate, deadline scheduling, safety, rig-log output.

Scheduling: sample k is due at ``start + k dt`` (dt = 1/rate); the loop sleeps until then,
records the jitter (actual - scheduled wake-up time), reads the device, steps the controller
with the *measured* elapsed time and writes the set-point. When a sample's work ends after the
next deadline the loop counts an *overrun* and moves to the next future grid point (skipped
samples are counted), so lateness never accumulates into drift. Timing is reported honestly:
the achieved rate (cycles run per second between the first and the last) is in the result, and
when more than 1 % of the grid points were skipped or more than 1 % of the cycles overran, a
warning (``warnings`` of the result; a :class:`~exofric.errors.PlausibilityWarning` when the
run completes) states the achieved rate against the requested one.

Safety, in this order every sample:

* watchdog -- no valid reading (a read that fails with :class:`SensorStale`, or a non-finite
  pressure or force: it could pass no limit check) or a sensor that does not change for
  ``watchdog_s`` (its sample counter where the device has one, else pressure and force both
  exactly unchanged) -> vent, stop, :class:`LoopFault` ``'watchdog'``; while readings are
  invalid no set-point is written (the last one holds until the watchdog trips);
* limits -- measured pressure above ``trip_pressure_mpa`` or force above ``max_force_n`` ->
  vent, stop, :class:`LoopFault`; commands are clipped to ``max_pressure_mpa``; a set-point
  above ``max_force_n`` (or needing a model pressure above ``max_pressure_mpa``) is refused
  before start (:class:`~exofric.errors.InputError`); a non-finite controller output is an
  error (vent, stop) and never reaches the device;
* device faults -- a :class:`~exofric.hardware.DeviceError` other than ``SensorStale`` from a
  read or a set-point write (connection lost, junk on the line, a value outside the declared
  range, a refused write): vent, stop at once, :class:`LoopFault` ``'device fault'``;
* Ctrl-C (KeyboardInterrupt) and any other exception -> vent, write the log, re-raise (with
  the run so far as the exception's ``result`` attribute).

Every stop vents (a completed run too, unless ``vent_at_end=False``); a failed vent is tried
once more on a fresh connection (the device's ``reconnect()``: Modbus re-opens its client,
serial re-opens the port and repeats the handshake), and a Ctrl-C that lands inside it does
not cut it short. The result's ``vented`` and the log's ``vented:`` line say whether the device
confirmed it; a LoopFault whose vent was not confirmed says so (the CLI exits 5, not 4).

The log (CSV, the rig-log schema of :func:`exofric.io.read_raw_log`): ``time_s``,
``pressure_mpa``, ``force_n``, ``setpoint_n``, ``command_mpa``, ``p_term_mpa``, ``i_term_mpa``,
``d_term_mpa``, ``ff_mpa``, ``jitter_ms``, with ``#`` provenance lines (device URL, controller,
gains, rate, limits, how the run ended). Rows are appended to ``<stem>.partial.csv`` as the
run goes (flushed about twice a second); at the end the complete log is written atomically
to the final path and the partial file removed -- after a hard crash the partial file remains.
"""

from __future__ import annotations

import datetime as _dt
import math
import warnings as _warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric import defaults as D
from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, PlausibilityWarning, check_range
from exofric.hardware._clock import RealClock
from exofric.hardware._device import DeviceError, LoopFault, SensorStale

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["LOG_COLUMNS", "LoopResult", "SafetyLimits", "run_loop"]

#: Columns of the loop's rig log, in order (units in the suffix).
LOG_COLUMNS = ("time_s", "pressure_mpa", "force_n", "setpoint_n", "command_mpa", "p_term_mpa",
               "i_term_mpa", "d_term_mpa", "ff_mpa", "jitter_ms")
#: Default pressure limit in MPa: commands are clipped to it.
LOOP_MAX_PRESSURE_MPA = D.LOOP_MAX_PRESSURE_MPA
#: Default trip pressure as a multiple of the pressure limit (measured above it: vent, stop).
LOOP_TRIP_PRESSURE_FACTOR = D.LOOP_TRIP_PRESSURE_FACTOR
#: Default force limit in N (set-points above it are refused; measured above it trips).
LOOP_MAX_FORCE_N = D.LOOP_MAX_FORCE_N
#: Default watchdog in s.
LOOP_WATCHDOG_S = D.LOOP_WATCHDOG_S
#: Partial-log flush interval in samples.
_FLUSH_EVERY = 50
#: Skipped grid points (of all) or overrun cycles (of those run) above this fraction warn.
TIMING_WARN_FRACTION = 0.01


@checked_init
@dataclass(frozen=True)
class SafetyLimits:
    """Pressure and force limits of a control run.

    Parameters
    ----------
    max_pressure_mpa : float
        Commands are clipped to this pressure in MPa (and a set-point whose model pressure
        exceeds it is refused).
    max_force_n : float
        Set-points above this force in N are refused; a measured force above it trips.
    trip_pressure_mpa : float or None
        A measured pressure above this (MPa) trips; default 1.1 x ``max_pressure_mpa``.

    Examples
    --------
    >>> SafetyLimits(0.5).trip_mpa
    0.55
    """

    max_pressure_mpa: float = LOOP_MAX_PRESSURE_MPA
    max_force_n: float = LOOP_MAX_FORCE_N
    trip_pressure_mpa: float | None = None

    def __post_init__(self) -> None:
        check_range("max_pressure_mpa", self.max_pressure_mpa, 0.0, 100.0, lo_open=True,
                    unit="MPa")
        check_range("max_force_n", self.max_force_n, 0.0, 1e6, lo_open=True, unit="N")
        if self.trip_pressure_mpa is not None:
            check_range("trip_pressure_mpa", self.trip_pressure_mpa, self.max_pressure_mpa,
                        100.0, unit="MPa")

    @property
    def trip_mpa(self) -> float:
        """The measured pressure (MPa) that trips the loop."""
        t = self.trip_pressure_mpa
        return round(LOOP_TRIP_PRESSURE_FACTOR * self.max_pressure_mpa, 12) if t is None else t


@checked_init
@dataclass(frozen=True)
class LoopResult(DisplayMixin):
    """What a control run did: timing, how it stopped, step metrics, the samples.

    Attributes
    ----------
    device : str
        The device URL.
    rate_hz : float
        Loop rate in Hz.
    duration_s : float
        Time in s from the first sample to the last.
    n_samples : int
        Samples logged.
    jitter_p50_ms, jitter_p99_ms, jitter_max_ms : float
        Wake-up lateness (actual - scheduled) in ms: median, 99th percentile, maximum.
    overruns : int
        Samples whose work ended after the next deadline.
    skipped : int
        Grid points skipped to catch up after overruns.
    stopped_reason : str
        ``'completed'``, ``'watchdog'``, ``'pressure limit'``, ``'force limit'``,
        ``'device fault'``, ``'interrupted'`` or ``'error'``.
    stopped_at_s : float
        Time in s of the stop (since the first sample).
    vented : bool
        Whether the device was vented at the end (False: the vent failed twice, or
        ``vent_at_end=False``).
    dry_run : bool
        No set-points were written.
    metrics : StepMetrics or None
        Settling time (2 %), overshoot, steady-state error (N) of the force against the final
        set-point; None when not measurable.
    log_path : str or None
        The log written.
    samples : dict of str to ndarray
        The log's columns (see ``LOG_COLUMNS``; s, MPa, N, ms).
    cycles : int
        Loop cycles run (grid points not skipped; a cycle without a valid reading logs no row).
    achieved_rate_hz : float
        Cycles per second actually run: (cycles - 1) / (time of the last cycle - time of the
        first), in Hz; NaN with fewer than two cycles.
    warnings : tuple of str
        Timing warnings (skipped or overrun cycles above 1 %, with the achieved rate).
    plant : str
        What the device is: its URL and what is behind it (``device.describe()``).

    Examples
    --------
    >>> from exofric.hardware import open_device, run_loop
    >>> from exofric.control import Controller, PIDGains
    >>> with open_device("sim://?speed=0") as dev:
    ...     res = run_loop(dev, Controller(PIDGains(0.002, 0.004)), 54.4, duration_s=1.0)
    >>> res.n_samples, res.stopped_reason, res.overruns
    (101, 'completed', 0)
    """

    device: str
    rate_hz: float
    duration_s: float
    n_samples: int
    jitter_p50_ms: float
    jitter_p99_ms: float
    jitter_max_ms: float
    overruns: int
    skipped: int
    stopped_reason: str
    stopped_at_s: float
    vented: bool
    dry_run: bool
    metrics: Any
    log_path: str | None
    samples: dict[str, np.ndarray] = field(repr=False)
    cycles: int = 0
    achieved_rate_hz: float = math.nan
    warnings: tuple[str, ...] = ()
    plant: str = ""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (the CLI's ``--json``): metrics, jitter (ms), overruns, vented,
        the achieved rate (Hz) and the timing warnings."""
        m = self.metrics.to_dict() if self.metrics is not None else {}
        return {
            "device": self.device, "rate_hz": self.rate_hz, "duration_s": self.duration_s,
            "n_samples": self.n_samples,
            "settling_time_s": m.get("settling_time_s"),
            "overshoot_pct": m.get("overshoot_pct"),
            "steady_state_error_n": m.get("steady_state_error_n"),
            "final_friction_n": m.get("final_friction_n"),
            "target_friction_n": m.get("target_friction_n"),
            "jitter_p50_ms": self.jitter_p50_ms, "jitter_p99_ms": self.jitter_p99_ms,
            "jitter_max_ms": self.jitter_max_ms, "overruns": self.overruns,
            "skipped": self.skipped, "cycles": self.cycles,
            "achieved_rate_hz": (None if math.isnan(self.achieved_rate_hz)
                                 else self.achieved_rate_hz),
            "stopped_reason": self.stopped_reason,
            "stopped_at_s": self.stopped_at_s, "vented": self.vented, "dry_run": self.dry_run,
            "log_path": self.log_path, "plant": self.plant, "warnings": list(self.warnings),
        }

    def to_frame(self) -> pd.DataFrame:
        """The samples as a DataFrame (columns ``LOG_COLUMNS``: s, MPa, N, ms)."""
        import pandas as pd

        return pd.DataFrame({c: self.samples[c] for c in LOG_COLUMNS})


def _partial_path(path: Path) -> Path:
    return path.with_name(f"{path.stem}.partial{path.suffix}")


def _fmt(v: float) -> str:
    return "" if v != v else repr(float(v))


#: Vent attempts at the end of a run (a failed vent is retried on a fresh connection).
_VENT_ATTEMPTS = 2


def _safe_vent(device: Any) -> tuple[bool, KeyboardInterrupt | None]:
    """Vent, retrying once on a fresh connection (``device.reconnect()`` where there is one);
    (vented, a Ctrl-C that arrived meanwhile, to re-raise)."""
    interrupt: KeyboardInterrupt | None = None
    for attempt in range(_VENT_ATTEMPTS):
        try:
            if attempt > 0 and hasattr(device, "reconnect"):
                device.reconnect()
            device.vent()
            return True, interrupt
        except KeyboardInterrupt as exc:  # a second Ctrl-C must not cut the vent short
            interrupt = exc
        except Exception:  # noqa: BLE001, S112 - not vented: retried, then reported
            continue
    return False, interrupt


def _plant_of(device: Any) -> str:
    """``device.describe()`` (its URL and what is behind it), else its URL."""
    url = str(getattr(device, "url", type(device).__name__))
    describe = getattr(device, "describe", None)
    try:
        return str(describe()) if callable(describe) else url
    except Exception:  # noqa: BLE001 - a description must never stop a run
        return url


def _terms(controller: Any, u: float) -> tuple[float, float, float, float]:
    """(p, i, d, ff) terms in MPa from the controller's state, NaN where not available."""
    st = controller.state() if hasattr(controller, "state") else {}
    i = float(st.get("integral_mpa", math.nan))
    d = float(st.get("derivative_mpa", math.nan))
    ff = float(st.get("feedforward_mpa", math.nan))
    p = st.get("proportional_mpa")
    if p is None:
        gains, e = getattr(controller, "gains", None), getattr(controller, "_e_prev", None)
        p = gains.kp * e if gains is not None and e is not None else math.nan
    return float(p), i, d, ff


def _describe(controller: Any) -> list[str]:
    lines = [f"controller: {type(controller).__name__}"]
    gains = getattr(controller, "gains", None)
    if gains is not None and hasattr(gains, "to_dict"):
        lines.append("gains: " + ", ".join(f"{k}={v:g}" for k, v in gains.to_dict().items()))
    ff = getattr(controller, "feedforward", None)
    if ff is not None:
        lines.append(f"feedforward: {'2-DOF' if getattr(ff, 'two_dof', False) else 'static'}")
    return lines


def run_loop(
    device: Any,
    controller: Any,
    setpoint: float | Callable[[float], float],
    *,
    duration_s: float,
    rate_hz: float = 100.0,
    limits: SafetyLimits | None = None,
    watchdog_s: float = LOOP_WATCHDOG_S,
    log_path: str | Path | None = None,
    dry_run: bool = False,
    clock: Any | None = None,
    metadata: Sequence[str] = (),
    vent_at_end: bool = True,
    baseline_s: float = 0.0,
) -> LoopResult:
    """Run the control loop on a device at a fixed rate (see the module docstring).

    Parameters
    ----------
    device : Device
        An open device (:func:`open_device`); vented at the start.
    controller : object
        ``step(setpoint_n, measurement_n, dt_s) -> command_mpa`` (e.g.
        :class:`exofric.control.Controller`); ``reset()`` is called at the start, ``state()``
        gives the logged terms when it has it.
    setpoint : float or callable
        Friction set-point in N, or a function of the time since the start (s) -> N.
    duration_s : float
        Run length in s (> 0).
    rate_hz : float
        Sample rate in Hz.
    limits : SafetyLimits or None
        Pressure and force limits (default ``SafetyLimits()``).
    watchdog_s : float
        Sensor silence/staleness in s that vents and stops.
    log_path : str, Path or None
        CSV log to write (``.csv`` or ``.txt``); None for no log.
    dry_run : bool
        Read and run the controller but never write set-points (the device stays vented).
    clock : Clock or None
        Time source; default the device's own ``clock`` (``sim://``) or real time.
    metadata : sequence of str
        Extra provenance lines for the log.
    vent_at_end : bool
        Vent when the run completes (faults and interrupts always vent).
    baseline_s : float
        Seconds logged vented before the step (controller idle, set-point 0 N): the rest
        window ``exofric reduce`` tares with; step metrics are taken from the step on.

    Returns
    -------
    LoopResult

    Raises
    ------
    InputError
        Bad arguments, or a set-point above the limits (refused before start).
    LoopFault
        Watchdog, limit or device fault (device vented -- or ``.vent_confirmed`` False --, log
        written; ``.result`` holds the run).
    KeyboardInterrupt
        Ctrl-C, after venting and writing the log (``.result`` holds the run).

    Examples
    --------
    >>> from exofric.control import Controller, PIDGains
    >>> from exofric.hardware import open_device
    >>> with open_device("sim://?speed=0") as dev:
    ...     r = run_loop(dev, Controller(PIDGains(0.002, 0.004)), 54.4, duration_s=0.5)
    >>> r.to_dict()["vented"], r.jitter_max_ms
    (True, 0.0)
    """
    lim = limits if limits is not None else SafetyLimits()
    check_range("duration_s", duration_s, 0.0, 1e6, lo_open=True, unit="s")
    check_range("rate_hz", rate_hz, 0.0, 1e4, lo_open=True, unit="Hz")
    dt = 1.0 / float(rate_hz)
    check_range("watchdog_s", watchdog_s, dt, 1e4, unit="s")
    base = check_range("baseline_s", baseline_s, 0.0, 1e4, unit="s")
    sp = _setpoint_function(setpoint)
    _check_targets(sp, setpoint, controller, lim, duration_s, rate_hz)
    log = Path(log_path) if log_path is not None else None
    if log is not None and log.suffix.lower() not in (".csv", ".txt"):
        raise InputError(f"log_path must end in .csv or .txt, got {log.name!r}")
    clk = clock if clock is not None else getattr(device, "clock", None) or RealClock()
    plant = _plant_of(device)
    head = ["exofric control run (rig log)",
            f"started: {_dt.datetime.now(_dt.UTC).isoformat(timespec='seconds')}",
            f"device: {getattr(device, 'url', type(device).__name__)}", f"plant: {plant}",
            *_describe(controller),
            f"rate_hz: {rate_hz:g}", f"duration_s: {duration_s:g}",
            f"limits: max_pressure_mpa={lim.max_pressure_mpa:g}, trip_pressure_mpa="
            f"{lim.trip_mpa:g}, max_force_n={lim.max_force_n:g}", f"watchdog_s: {watchdog_s:g}",
            f"dry_run: {str(bool(dry_run)).lower()}", *[str(m) for m in metadata]]
    run = _LoopRun(device, controller, sp, lim, dt, base, watchdog_s, dry_run, clk, plant,
                   log, head)
    run.execute(int(round((float(duration_s) + base) * rate_hz)))
    return run.finish(rate_hz, vent_at_end)


def _setpoint_function(setpoint: float | Callable[[float], float]) -> Callable[[float], float]:
    """The set-point as a function of the time since the step (s) -> N."""
    if callable(setpoint):
        return setpoint
    value = float(setpoint)

    def sp(_t: float) -> float:
        return value

    return sp


def _check_targets(sp: Callable[[float], float], setpoint: Any, controller: Any,
                   lim: SafetyLimits, duration_s: float, rate_hz: float) -> None:
    """Refuse before the start a set-point that is not finite, negative, above the force limit
    or (by the controller's model) above the pressure limit."""
    dt = 1.0 / float(rate_hz)
    # a constant set-point is checked once (not once per sample of a long run)
    targets = (np.array([float(sp(k * dt)) for k in range(int(round(duration_s * rate_hz)) + 1)])
               if callable(setpoint) else np.array([float(setpoint)]))
    if not np.all(np.isfinite(targets)) or targets.min() < 0.0:
        raise InputError("setpoint_n must be finite and >= 0 N")
    if targets.max() > lim.max_force_n:
        raise InputError(f"setpoint_n {targets.max():g} N is above the force limit max_force_n "
                         f"{lim.max_force_n:g} N: refused before start")
    ff = getattr(controller, "feedforward", None)
    if ff is not None and hasattr(ff, "pressure_for_friction"):
        p_ff = float(ff.pressure_for_friction(float(targets.max())))
        if p_ff > lim.max_pressure_mpa:
            raise InputError(f"setpoint_n {targets.max():g} N needs {p_ff:.4g} MPa by the model, "
                             f"above the pressure limit max_pressure_mpa "
                             f"{lim.max_pressure_mpa:g} MPa: refused before start")


_Fault = tuple[str, float, str]


class _LoopRun:
    """One run of :func:`run_loop`: its state, one method per part of a cycle, the finish."""

    def __init__(self, device: Any, controller: Any, sp: Callable[[float], float],
                 lim: SafetyLimits, dt: float, base: float, watchdog_s: float, dry_run: bool,
                 clk: Any, plant: str, log: Path | None, head: list[str]) -> None:
        self.device, self.controller, self.sp, self.lim = device, controller, sp, lim
        self.dt, self.base, self.watchdog_s, self.dry_run = dt, base, watchdog_s, dry_run
        self.clk, self.log, self.head = clk, log, head
        self.rows: list[tuple[float, ...]] = []
        self.state: dict[str, Any] = {"reason": "completed", "t_stop": 0.0, "overruns": 0,
                                      "skipped": 0, "cycles": 0, "t_first": math.nan,
                                      "t_last": math.nan, "plant": plant}
        self.fault: _Fault | None = None
        self.failure: BaseException | None = None
        self.start = 0.0
        self.last_fresh = 0.0
        self.last_sig: Any = None
        self.last_err = ""
        self.t_prev: float | None = None
        self.in_base = base > 0.0
        self.partial: Path | None = None
        self.fh: Any = None
        if log is not None:
            log.parent.mkdir(parents=True, exist_ok=True)
            self.partial = _partial_path(log)
            self.fh = self.partial.open("w", encoding="utf-8")
            self.fh.write("".join(f"# {h}\n" for h in head) + ",".join(LOG_COLUMNS) + "\n")
            self.fh.flush()

    # -- the loop --------------------------------------------------------------------------

    def execute(self, n_last: int) -> None:
        """Vent, reset, then run cycles 0..n_last on the deadline grid until a fault."""
        clk = self.clk
        try:
            self.device.vent()
            if hasattr(self.controller, "reset"):
                self.controller.reset()
            self.start = self.last_fresh = clk.now()
            k = 0
            while k <= n_last:
                self.fault = self._cycle(k)
                if self.fault is not None:
                    break
                k = self._next_cycle(k + 1)
        except BaseException as exc:  # noqa: BLE001 - vent first, re-raised by finish()
            self.failure = exc
            self.state["reason"] = ("interrupted" if isinstance(exc, KeyboardInterrupt)
                                    else "error")
            self.state["t_stop"] = clk.now() - self.start
        if self.fault is not None:
            self.state["reason"], self.state["t_stop"] = self.fault[0], self.fault[1]

    def _next_cycle(self, k: int) -> int:
        """The next grid point after cycle k - 1 ended: k, or a later one after an overrun."""
        t_end = self.clk.now()
        if t_end > self.start + k * self.dt:
            self.state["overruns"] += 1
            k_next = int(math.floor((t_end - self.start) / self.dt)) + 1
            self.state["skipped"] += k_next - k
            return k_next
        return k

    def _cycle(self, k: int) -> _Fault | None:
        """Cycle k: wait for its deadline, read, check, control, log; a fault or None."""
        st, clk = self.state, self.clk
        t_sched = self.start + k * self.dt
        clk.sleep_until(t_sched)
        t_now = clk.now()
        t_rel = t_now - self.start
        st["t_stop"] = t_rel
        st["cycles"] += 1
        if st["cycles"] == 1:
            st["t_first"] = t_now
        st["t_last"] = t_now
        r, fault = self._read()
        if fault is not None:
            return fault
        fault = self._watchdog(r, t_now)
        if fault is None and r is not None:
            fault = self._limits(r, t_rel)
        if fault is not None or r is None:
            return fault
        out = self._control(r, t_rel, t_now)
        if isinstance(out[0], str):                      # a device fault on the write
            return out
        target, cmd, terms = out
        row = (t_rel, r.pressure_mpa, r.force_n, target, cmd, *terms,
               1000.0 * (t_now - t_sched))
        self.rows.append(row)
        if self.fh is not None:
            self.fh.write(",".join(_fmt(v) for v in row) + "\n")
            if len(self.rows) % _FLUSH_EVERY == 0:
                self.fh.flush()
        return None

    def _read(self) -> tuple[Any, _Fault | None]:
        """(reading or None when stale/non-finite, device fault or None)."""
        try:
            r = self.device.read()
        except SensorStale as exc:
            r, self.last_err = None, str(exc)
        except DeviceError as exc:      # connection lost, junk, out of range: stop now
            return None, ("device fault", self.clk.now() - self.start,
                          " ".join(str(exc).split()))
        if r is not None and not (math.isfinite(r.pressure_mpa) and math.isfinite(r.force_n)):
            # NaN compares False with every limit: it must not pass as a reading
            self.last_err = (f"non-finite reading: pressure {r.pressure_mpa} MPa, force "
                             f"{r.force_n} N")
            r = None
        return r, None

    def _watchdog(self, r: Any, t_now: float) -> _Fault | None:
        """The watchdog: no fresh valid reading for ``watchdog_s``."""
        t_read = self.clk.now()      # after the read: a read that timed out took its time
        if r is not None:
            sig = r.sample_id if r.sample_id is not None else (r.pressure_mpa, r.force_n)
            if sig != self.last_sig:
                self.last_fresh, self.last_sig = t_now, sig
        quiet = t_read - self.last_fresh
        if quiet < self.watchdog_s:
            return None
        why = (f"no valid reading for {quiet:.3g} s ({self.last_err})"
               if r is None else f"sensor unchanged for {quiet:.3g} s")
        return "watchdog", t_read - self.start, why

    def _limits(self, r: Any, t_rel: float) -> _Fault | None:
        """The pressure trip and the force limit."""
        lim = self.lim
        if r.pressure_mpa > lim.trip_mpa:
            return "pressure limit", t_rel, (f"pressure {r.pressure_mpa:.4g} MPa above the trip "
                                             f"pressure {lim.trip_mpa:g} MPa")
        if r.force_n > lim.max_force_n:
            return "force limit", t_rel, (f"force {r.force_n:.4g} N above the force limit "
                                          f"{lim.max_force_n:g} N")
        return None

    def _control(self, r: Any, t_rel: float, t_now: float) -> tuple[Any, ...]:
        """(target N, command MPa, logged terms) of this cycle, or a device fault."""
        if t_rel < self.base:
            # baseline: vented, controller idle; the log's rest window (tare)
            return 0.0, 0.0, (0.0, 0.0, 0.0, 0.0)
        ctrl = self.controller
        if self.in_base:
            self.in_base = False
            if hasattr(ctrl, "reset"):
                ctrl.reset()
        target = float(self.sp(t_rel - self.base))
        u = float(ctrl.step(target, r.force_n, self.dt if self.t_prev is None
                            else max(t_now - self.t_prev, 1e-9)))
        self.t_prev = t_now
        if not math.isfinite(u):
            raise InputError(f"the controller returned a non-finite command {u} MPa at "
                             f"{t_rel:.3f} s (set-point {target:g} N, force {r.force_n:g} N): "
                             "stopped and vented")
        cmd = min(max(u, 0.0), self.lim.max_pressure_mpa)
        if not self.dry_run:
            try:
                self.device.write_setpoint_mpa(cmd)
            except DeviceError as exc:      # not confirmed: stop now
                return ("device fault", self.clk.now() - self.start,
                        " ".join(str(exc).split()))
        return target, cmd, tuple(_terms(ctrl, u))

    # -- the end ---------------------------------------------------------------------------

    def finish(self, rate_hz: float, vent_at_end: bool) -> LoopResult:
        """Vent (every stop but a completed run with ``vent_at_end=False``), write the log,
        return the result or raise the failure / :class:`LoopFault`."""
        st, fault, failure = self.state, self.fault, self.failure
        vented = False
        if failure is not None or fault is not None or vent_at_end or self.dry_run:
            vented, interrupt = _safe_vent(self.device)
            if interrupt is not None and failure is None:
                failure = interrupt
                st["reason"] = "interrupted"
        if self.fh is not None:
            try:
                self.fh.close()
            except OSError:     # e.g. a full disk: the final write below reports it
                pass
        result = _result(self.device, self.rows, rate_hz, st, vented, self.dry_run, self.log,
                         self.base)
        if self.log is not None and self.partial is not None:
            self._write_log(result, vented, failure)
        if failure is not None:
            try:
                failure.result = result      # type: ignore[attr-defined]  # the run so far
            except AttributeError:           # pragma: no cover - an exception with __slots__
                pass
            raise failure
        if fault is not None:
            raise LoopFault(fault[0], fault[1], fault[2], result)
        for w in result.warnings:            # a completed run: say it on stderr too
            _warnings.warn(w, PlausibilityWarning, stacklevel=3)
        return result

    def _write_log(self, result: LoopResult, vented: bool,
                   failure: BaseException | None) -> None:
        """The final log (atomic), its footer, and the partial file removed."""
        st, fault = self.state, self.fault
        assert self.log is not None and self.partial is not None
        tail = [f"stopped: {st['reason']} at {st['t_stop']:.3f} s"
                + (f" ({fault[2]})" if fault else ""),
                f"vented: {str(vented).lower()}", f"samples: {result.n_samples}",
                f"jitter_ms: p50={result.jitter_p50_ms:.3f}, p99={result.jitter_p99_ms:.3f}, "
                f"max={result.jitter_max_ms:.3f}",
                f"overruns: {result.overruns}, skipped: {result.skipped}, cycles: "
                f"{result.cycles}, achieved_rate_hz: {result.achieved_rate_hz:.4g}",
                *[f"warning: {w}" for w in result.warnings]]
        try:
            from exofric.io import write_raw_log

            write_raw_log(self.log, result.to_frame(), [*self.head, *tail])
            self.partial.unlink(missing_ok=True)
        except Exception:
            if failure is None:
                raise


def _result(device: Any, rows: list[tuple[float, ...]], rate_hz: float, state: dict[str, Any],
            vented: bool, dry_run: bool, log: Path | None, baseline_s: float = 0.0
            ) -> LoopResult:
    arr = np.array(rows, dtype=float).reshape(-1, len(LOG_COLUMNS))
    samples = {c: arr[:, i].copy() for i, c in enumerate(LOG_COLUMNS)}
    jit = samples["jitter_ms"]
    pct = (np.percentile(jit, [50.0, 99.0]) if jit.size else np.array([math.nan, math.nan]))
    metrics = None
    run = samples["time_s"] >= baseline_s          # step metrics from the step on
    t, f, r = (samples["time_s"][run] - baseline_s, samples["force_n"][run],
               samples["setpoint_n"][run])
    if t.size >= 2 and float(r[-1]) != float(f[0]):
        from exofric.control import step_metrics

        try:
            metrics = step_metrics(t, f, float(r[-1]))
        except InputError:
            metrics = None
    cycles = int(state.get("cycles", 0))
    span = float(state.get("t_last", math.nan)) - float(state.get("t_first", math.nan))
    achieved = (cycles - 1) / span if cycles >= 2 and span > 0.0 else math.nan
    skipped, overruns = int(state["skipped"]), int(state["overruns"])
    warns: list[str] = []
    if cycles and (skipped > TIMING_WARN_FRACTION * (cycles + skipped)
                   or overruns > TIMING_WARN_FRACTION * cycles):
        got = "-" if math.isnan(achieved) else f"{achieved:.4g}"
        warns.append(f"control loop ran at {got} Hz of the requested {rate_hz:g} Hz: "
                     f"{skipped} of {cycles + skipped} cycles skipped, {overruns} of {cycles} "
                     "overran their period (the machine is loaded or the device is slow; "
                     "lower the rate or free the machine)")
    url = str(getattr(device, "url", type(device).__name__))
    plant = str(state.get("plant") or _plant_of(device))
    return LoopResult(
        device=url, rate_hz=float(rate_hz),
        duration_s=float(t[-1] - t[0]) if t.size else 0.0,
        n_samples=int(samples["time_s"].size),
        jitter_p50_ms=float(pct[0]), jitter_p99_ms=float(pct[1]),
        jitter_max_ms=float(jit.max()) if jit.size else math.nan,
        overruns=int(state["overruns"]), skipped=int(state["skipped"]),
        stopped_reason=str(state["reason"]), stopped_at_s=float(state["t_stop"]),
        vented=bool(vented), dry_run=bool(dry_run), metrics=metrics,
        log_path=None if log is None else str(log), samples=samples, cycles=cycles,
        achieved_rate_hz=float(achieved), warnings=tuple(warns), plant=plant)
