"""``exofric control run``: the friction loop on a device at a fixed rate, safely."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, NoReturn

import typer

from exofric import defaults as D
from exofric.cli._common import (
    JSON_OPTION,
    console,
    emit,
    kv_table,
    out_file,
)

if TYPE_CHECKING:
    pass
from exofric.cli.control._shared import (
    FF_MODE,
    GAMMA,
    STEP_CSV,
    STRUCTURE,
    TAU_C,
    _fmt,
    _opt,
    _setup,
)


def run_cmd(
    device: str = typer.Option(..., "--device", help="sim://?speed=1, modbus-tcp://HOST:PORT"
                               "?unit=1, modbus-rtu:///dev/ttyX?baud=115200 or "
                               "serial:///dev/ttyX?baud=115200."),
    map_path: str | None = typer.Option(None, "--map", help="Modbus register map TOML "
                                        "(default: the shipped map; see `exofric.hardware"
                                        ".DEFAULT_MAP_PATH`)."),
    controller: str = _opt("pi", "Controller: pd, pi or pid (gains: IMC/SIMC rule)."),
    feedforward: bool = typer.Option(False, "--feedforward", help="Add the model's inverse "
                                     "as feedforward."),
    schedule: bool = typer.Option(False, "--schedule", help="Schedule the gains on the "
                                  "local slope dF/dP of the friction map."),
    target: float = typer.Option(54.40, "--target-friction", help="Friction set-point in "
                                 "N (the flag `exofric control` takes too)."),
    target_old: float | None = typer.Option(None, "--target", hidden=True,
                                            help="Deprecated spelling of --target-friction."),
    duration: float = typer.Option(10.0, "--duration", help="Run length in s."),
    rate: float = typer.Option(100.0, "--rate", help="Loop rate in Hz."),
    log: str | None = typer.Option(None, "--log", help="Write the run log (rig-log schema "
                                   "CSV; `exofric reduce` and `control identify` read it)."),
    max_pressure: float = typer.Option(D.LOOP_MAX_PRESSURE_MPA, "--max-pressure",
                                       help="Pressure limit in MPa (commands clipped; "
                                       "10 % above it trips)."),
    max_force: float = typer.Option(D.LOOP_MAX_FORCE_N, "--max-force",
                                    help="Force limit in N."),
    watchdog: float = typer.Option(D.LOOP_WATCHDOG_S, "--watchdog",
                                   help="Vent when a sensor is stale this long, s."),
    dry_run: bool = typer.Option(False, "--dry-run", help="Read sensors and run the "
                                 "controller, never actuate."),
    baseline: float = typer.Option(1.0, "--baseline", help="Seconds logged vented before "
                                   "the step (the rest window `exofric reduce` tares with)."),
    structure: str = STRUCTURE, gamma: float | None = GAMMA, tau_c: float | None = TAU_C,
    step_csv: str | None = STEP_CSV, ff_mode: str = FF_MODE,
    as_json: bool = JSON_OPTION,
) -> None:
    """Run the friction loop on a device at a fixed rate, safely (vents on faults). N, MPa.

    Gains: the IMC/SIMC rule on the paper's supply; --step-csv tunes on your own.
    Exit codes: 0 done; 2 bad input (before the loop); 4 a run-time fault stopped the run
    and the tube was vented; 5 the vent was not confirmed (the tube may still be
    pressurised); 130 Ctrl-C (vented).
    """
    from exofric.control import Controller, ScheduledController, local_slope
    from exofric.errors import InputError, check_range
    from exofric.hardware import LoopFault, SafetyLimits, open_device, run_loop

    if target_old is not None:   # the old flag keeps working, and says so
        import warnings

        warnings.warn("--target is deprecated: use --target-friction (same meaning, N)",
                      stacklevel=1)
        target = target_old
    kind = controller.lower()
    if kind not in ("pd", "pi", "pid"):
        raise InputError(f"--controller must be pd, pi or pid, got {controller!r}")
    check_range("--rate (Hz)", rate, 1.0, 2000.0)
    check_range("--duration (s)", duration, 0.0, 1e5, lo_open=True)
    if log is not None:
        out_file("log", log)
    limits = SafetyLimits(max_pressure_mpa=max_pressure, max_force_n=max_force)
    setup = _setup(target, structure, gamma, None, step_csv, None, tau_c, ff_mode,
                   "back-calculation", 1.0 / rate, duration, 2.0)
    gains = setup.tuning(kind).gains
    ff = setup.make_feedforward() if feedforward else None
    if schedule:
        fmap = setup.model_map
        ctrl: Controller = ScheduledController(
            gains, fmap, slope_ref_n_per_mpa=local_slope(fmap, fmap.inverse(target)),
            u_max=max_pressure, feedforward=ff)
    else:
        ctrl = Controller(gains, u_max=max_pressure, feedforward=ff)
    meta = [f"exofric control run: device {device}, {kind.upper()}"
            f"{' + model feedforward' if feedforward else ''}"
            f"{' + gain scheduling' if schedule else ''}, target {target:g} N, "
            f"{rate:g} Hz, kp {gains.kp:.4g} MPa/N, ki {gains.ki:.4g} MPa/(N s), "
            f"kd {gains.kd:.4g} MPa s/N"]
    dev = open_device(device, map_path)
    try:
        res = run_loop(dev, ctrl, target, duration_s=duration, rate_hz=rate, limits=limits,
                       watchdog_s=watchdog, log_path=log, dry_run=dry_run, metadata=meta,
                       baseline_s=baseline)
    except LoopFault as exc:        # vented (or not confirmed) and logged by the loop
        _run_fault(exc, device, as_json)
    except BaseException as exc:
        _run_failed(exc, dev)
        raise
    finally:
        _quiet_close(dev)
    d = res.to_dict()
    d.update({"device": device, "controller": kind, "feedforward": feedforward,
              "schedule": schedule, "target_n": target})

    def render() -> None:
        rows = [("device", str(d.get("plant") or device), ""),
                ("controller", f"{kind.upper()}{' + model' if feedforward else ''}"
                 f"{' + scheduling' if schedule else ''}", ""),
                ("target friction", f"{target:g}", "N"),
                ("final friction", _fmt(d.get("final_friction_n"), ".2f"), "N"),
                ("settling time (2 %)", _fmt(d.get("settling_time_s"), ".2f"), "s"),
                ("overshoot", _fmt(d.get("overshoot_pct"), ".1f"), "%"),
                ("steady-state error", _fmt(d.get("steady_state_error_n"), ".3f"), "N"),
                ("loop rate / samples", f"{rate:g} / {d.get('n_samples')}", "Hz / -"),
                ("achieved rate", _fmt(d.get("achieved_rate_hz"), ".4g"), "Hz"),
                ("jitter p50 / p99 / max", f"{d['jitter_p50_ms']:.3f} / "
                 f"{d['jitter_p99_ms']:.3f} / {d['jitter_max_ms']:.3f}", "ms"),
                ("overruns / skipped", f"{d.get('overruns')} / {d.get('skipped')}", ""),
                ("stopped", f"{d.get('stopped_reason')} at "
                 f"{_fmt(d.get('stopped_at_s'), '.2f')}", "s"),
                ("vented", str(d.get("vented")), ""),
                ("dry run", str(dry_run), "")]
        if d.get("log_path"):
            rows.append(("log", str(d["log_path"]), ""))
        console.print(kv_table(f"control run on {device}", rows))

    emit(d, as_json, render)
    if not res.vented:
        _vent_not_confirmed(f"the run ended ({res.stopped_reason} at "
                            f"{res.stopped_at_s:.3f} s) but the device did not confirm the "
                            "vent (tried twice, the second time on a fresh connection)")


def register(ctl: typer.Typer) -> None:
    """Add ``run`` to ``ctl``."""
    ctl.command("run")(run_cmd)


def _vent_not_confirmed(what: str) -> NoReturn:
    """One loud line on stderr and exit 5 (exofric.errors.EXIT_VENT_NOT_CONFIRMED)."""
    import sys

    from exofric.errors import EXIT_VENT_NOT_CONFIRMED

    print(f"exofric: VENT NOT CONFIRMED: {what}: the tube may still be pressurised; close the "
          "supply by hand", file=sys.stderr)
    raise typer.Exit(EXIT_VENT_NOT_CONFIRMED)


def _run_fault(exc: Any, device: str, as_json: bool) -> NoReturn:
    """A LoopFault: the run's JSON (``--json``), one stderr line, exit 4 or 5."""
    import sys

    res = exc.result
    if as_json and res is not None:
        d = res.to_dict()
        d.update({"device": device, "fault": " ".join(str(exc).split()),
                  "exit_code": exc.exit_code})
        emit(d, True, lambda: None)
    msg = " ".join(str(exc).split())
    head = "stopped" if exc.vent_confirmed else "VENT NOT CONFIRMED"
    print(f"exofric: {head}: {msg}", file=sys.stderr)
    raise typer.Exit(exc.exit_code)


def _run_failed(exc: BaseException, dev: Any) -> None:
    """Another exception out of run_loop: vent when the loop never started (it vents itself
    once started); a Ctrl-C whose vent was not confirmed exits 5 instead of 130."""
    res = getattr(exc, "result", None)
    if res is None:                  # refused before the start: vent as `with` would
        try:
            dev.vent()
        except Exception:  # noqa: BLE001, S110 - the original error is the one to report
            pass
        return
    if isinstance(exc, KeyboardInterrupt) and not res.vented:
        _vent_not_confirmed(f"interrupted at {res.stopped_at_s:.3f} s and the device did not "
                            "confirm the vent")


def _quiet_close(dev: Any) -> None:
    try:
        dev.close()
    except Exception:  # noqa: BLE001, S110 - closing a dead connection must not hide the run
        pass
