"""``exofric control``: friction force control by inflation pressure (paper §5, Fig 12).

``exofric control`` simulates one case (PD/PI/PID, with or without the model feedforward);
``exofric control compare`` the six cases of Fig 12 beside the paper's settling times;
``exofric control identify STEP.csv`` fits the supply's lag and dead time to a step response.
Units: friction N, pressure MPa, time s; gains kp MPa/N, ki MPa/(N s), kd MPa s/N.
Plant TOMLs, squeeze curves and step CSVs are read by :mod:`exofric.io`.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

import typer

from exofric import defaults as D
from exofric.cli._common import (
    JSON_OPTION,
    console,
    emit,
    kv_table,
    narrow_table,
    out_file,
    parse_floats,
    plot_path,
    save_figure,
)

if TYPE_CHECKING:
    from exofric.reproduction import CaseResult, CompareResult, ControlSetup

_COMMON_HELP = "Units: N, MPa, s."


def _stuck_note(case: dict[str, Any], target_n: float) -> str:
    """Why a case ends far from its target at zero friction (e.g. PD without the model)."""
    f, p = case.get("final_friction_n"), case.get("final_pressure_mpa")
    if f is None or p is None or abs(f) > 0.01 * abs(target_n):
        return ""
    name = f"{case.get('controller', '').upper()}{' + model' if case.get('feedforward') else ''}"
    return (f"{name}: the pressure settles at {p:.3f} MPa, where the friction map gives "
            f"{f:.2f} N: below contact onset the friction does not respond to pressure, and "
            "without integral action the loop never reaches contact. Add the model "
            "(--feedforward) or use PI/PID.")


def _opt(default: Any, help_: str) -> Any:
    return typer.Option(default, help=help_)


# Options shared by the default action and `compare` (declared once, used twice).
TARGET = _opt(54.40, "Target friction in N (paper: 54.40 N).")
STRUCTURE = _opt("test5", "Friction map: 'test5' (Eq 9) or a JSON file from "
                 "`exofric squeeze --json` (pressure_mpa, squeeze_force_n).")
GAMMA = _opt(None, "Equivalent coefficient gamma of the model (default: the paper's 0.7168).")
PLANT = _opt(None, "Plant TOML file with a plant table (see data/examples/plant-default.toml).")
STEP_CSV = _opt(None, "Step-response CSV (time_s, pressure_mpa[, command_mpa]): use the "
                "identified gain, lag and delay.")
MISMATCH = _opt(None, "Model mismatch: true gamma = (1 + mismatch) x model gamma, in (-0.9, 10).")
TAU_C = _opt(None, "Closed-loop time constant of the IMC/SIMC rule in s (default tau + theta).")
FF_MODE = _opt("2dof", "Feedforward structure: 2dof (feedback on the deviation from the "
               "model-predicted friction) or static (P_ff added to the PID output).")
ANTIWINDUP = _opt("back-calculation", "Anti-windup: back-calculation, clamping or none.")
DT = _opt(None, "Sample time in s (default 0.01 s, or the plant's PWM period).")
DURATION = _opt(15.0, "Simulated time in s.")
BAND = _opt(2.0, "Settling band in % of the step.")
PLOT = _opt(None, "Write a PNG plot of the response(s) to this path.")


def _plant_from_file(path: str) -> dict[str, Any]:
    from exofric.errors import InputError
    from exofric.io import read_toml

    p = Path(path)
    if not p.is_file():
        raise InputError(f"--plant {path}: file not found")
    try:
        data = read_toml(p)
    except InputError as exc:
        raise InputError(f"--plant {exc}") from None
    extra = sorted(set(data) - {"plant"})
    if extra:
        raise InputError(f"--plant {p.name}: unknown table(s) {', '.join(extra)}; expected [plant]")
    table = data.get("plant", {})
    if not isinstance(table, dict):
        raise InputError(f"--plant {p.name}: [plant] must be a table")
    return dict(table)


def _structure_map(structure: str, gamma: float) -> Any:
    from exofric import paper
    from exofric.control import CubicFrictionMap, CurveFrictionMap
    from exofric.errors import InputError
    from exofric.friction import CubicFit
    from exofric.io import read_squeeze_curve

    if structure.lower() == "test5":
        lo, hi = paper.load()["eq8"]["fit_range_mpa"]
        return CubicFrictionMap(CubicFit(paper.eq8(), lo, hi), gamma)
    p = Path(structure)
    if not p.is_file():
        raise InputError(f"--structure must be 'test5' or an existing JSON file, got {structure!r}")
    try:
        curve = read_squeeze_curve(p)
    except InputError as exc:
        raise InputError(f"--structure {exc}") from None
    pres = tuple(float(v) for v in curve["pressure_mpa"])
    force = tuple(float(v) for v in curve["squeeze_force_n"])
    return CurveFrictionMap(pres, force, gamma)


def _identify_csv(path: str) -> Any:
    from exofric.control import identify_step
    from exofric.io import read_step_response

    df = read_step_response(path)
    cmd = df["command_mpa"].to_numpy() if "command_mpa" in df.columns else None
    return identify_step(df["time_s"].to_numpy(), df["pressure_mpa"].to_numpy(), cmd)


def _setup(target: float, structure: str, gamma: float | None, plant: str | None,
           step_csv: str | None, mismatch: float | None, tau_c: float | None, ff_mode: str,
           antiwindup: str, dt: float | None, duration: float, band_pct: float) -> ControlSetup:
    from exofric import paper
    from exofric.control import PlantParams
    from exofric.errors import InputError, check_range
    from exofric.reproduction import ControlSetup

    params = _plant_from_file(plant) if plant else {}
    source = f"from {Path(plant).name}" if plant else "exofric's default (an assumption)"
    if step_csv:
        source = f"identified from {Path(step_csv).name}"
        ident = _identify_csv(step_csv)
        params.update(gain=ident.gain, time_constant_s=ident.time_constant_s,
                      delay_s=ident.delay_s)
    if mismatch is not None:
        params["mismatch"] = mismatch
    pp = PlantParams.from_mapping(params)
    if ff_mode not in ("2dof", "static"):
        raise InputError(f"--ff-mode must be 2dof or static, got {ff_mode!r}")
    if antiwindup not in ("back-calculation", "clamping", "none"):
        raise InputError(f"--antiwindup must be back-calculation, clamping or none, got "
                         f"{antiwindup!r}")
    if dt is None:
        dt = pp.pwm_period_s if pp.pwm_period_s > 0 else 0.01
    band = check_range("--band (settling band, %)", band_pct, 0.0, 50.0, lo_open=True) / 100.0
    g = paper.scalar("gamma") if gamma is None else gamma
    setup = ControlSetup(pp, _structure_map(structure, g), target_n=target, dt=dt,
                         duration_s=duration, ff_mode=ff_mode,  # type: ignore[arg-type]
                         tau_c_s=tau_c, band=band, antiwindup=antiwindup,  # type: ignore[arg-type]
                         plant_source=source)
    p_ff = setup.feedforward_pressure()
    if p_ff > pp.p_max_mpa:
        raise InputError(f"--target-friction {target:g} N needs {p_ff:.3f} MPa, above the plant's "
                         f"p_max_mpa {pp.p_max_mpa:g} MPa")
    return setup


def _plot_cases(cases: list[CaseResult], path: str, title: str) -> str:
    """Write the response plot; return the path written (``out`` -> ``out.png``)."""
    from exofric.plots import plot_control_cases

    return str(save_figure(plot_control_cases(cases, title=title), path))


def _fmt(v: float | None, spec: str) -> str:
    return "-" if v is None else format(v, spec)


def register(app: typer.Typer) -> None:
    """Add the ``control`` command group to ``app``."""
    ctl = typer.Typer(help="Friction force control by inflation pressure (paper Section 5, "
                      "Fig 12): PD/PI/PID with and without the model feedforward. "
                      + _COMMON_HELP, no_args_is_help=False)

    @ctl.callback(invoke_without_command=True)
    def control(
        ctx: typer.Context,
        controller: str = _opt("pid", "Controller: pd, pi or pid."),
        kp: float | None = _opt(None, "Proportional gain in MPa/N (default: IMC/SIMC rule)."),
        ki: float | None = _opt(None, "Integral gain in MPa/(N s) (default: rule; 0 for PD)."),
        kd: float | None = _opt(None, "Derivative gain in MPa s/N (default: rule; 0 for PI)."),
        feedforward: bool = typer.Option(False, "--feedforward",
                                         help="Add the model feedforward P_ff = g^-1(F)."),
        tuning: str = _opt("rule", "Gains: rule (IMC/SIMC) or itae (optimised, saturated loop)."),
        target_friction: float = TARGET, structure: str = STRUCTURE,
        gamma: float | None = GAMMA, plant: str | None = PLANT, step_csv: str | None = STEP_CSV,
        mismatch: float | None = MISMATCH, tau_c: float | None = TAU_C, ff_mode: str = FF_MODE,
        antiwindup: str = ANTIWINDUP, dt: float | None = DT, duration: float = DURATION,
        band: float = BAND, plot: str | None = PLOT, as_json: bool = JSON_OPTION,
    ) -> None:
        """Simulate one friction step (default: PID without the model, 54.40 N, test 5)."""
        from exofric.errors import InputError

        if ctx.invoked_subcommand is not None:
            given = [p for p in ctx.params
                     if getattr(ctx.get_parameter_source(p), "name", "") == "COMMANDLINE"]
            if given:
                raise InputError(f"options {', '.join('--' + g.replace('_', '-') for g in given)}"
                                 f" go after '{ctx.invoked_subcommand}', not before it")
            return
        from dataclasses import replace

        from exofric.control import CONTROLLERS, PIDGains, itae_gains
        from exofric.reproduction import run_case

        if plot:
            plot_path(plot)

        kind = controller.lower()
        if kind not in CONTROLLERS:
            raise InputError(f"--controller must be pd, pi or pid, got {controller!r}")
        setup = _setup(target_friction, structure, gamma, plant, step_csv, mismatch, tau_c,
                       ff_mode, antiwindup, dt, duration, band)
        rule = setup.tuning(kind)
        if tuning == "itae":
            rule = itae_gains(rule, replace(setup.plant, mismatch=0.0), setup.model_map,
                              setup.target_n, duration_s=setup.duration_s, dt=setup.dt)
        elif tuning != "rule":
            raise InputError(f"--tuning must be rule or itae, got {tuning!r}")
        g = rule.gains
        if kind == "pd" and ki:
            raise InputError("--ki must be 0 for a PD controller")
        if kind == "pi" and kd:
            raise InputError("--kd must be 0 for a PI controller")
        gains = PIDGains(g.kp if kp is None else kp, g.ki if ki is None else ki,
                         g.kd if kd is None else kd)
        res = run_case(setup, kind, feedforward=feedforward,
                       gains=None if gains == rule.gains and tuning == "rule" else gains)
        if tuning == "itae":
            res = replace(res, tuning=replace(rule, gains=gains))
        written = _plot_cases([res], plot, f"target {setup.target_n:g} N") if plot else None
        d = res.to_dict()
        d["plant"] = setup.plant_description()
        if written:
            d["plot"] = written
        note = _stuck_note(d, setup.target_n)
        if note:
            d["notes"] = [note]

        def render() -> None:
            gd = d["gains"]
            console.print(kv_table(
                f"{kind.upper()} {'with' if feedforward else 'without'} the model, target "
                f"{setup.target_n:g} N (mismatch {setup.plant.mismatch:g})",
                [("settling time (2% band)" if band == 2.0 else "settling time",
                  _fmt(d["settling_time_s"], ".2f"), "s"),
                 ("rise time (10-90%)", _fmt(d["rise_time_s"], ".2f"), "s"),
                 ("overshoot", f"{d['overshoot_pct']:.1f}", "%"),
                 ("steady-state error", f"{d['steady_state_error_n']:.3f}", "N"),
                 ("final friction", f"{d['final_friction_n']:.2f}", "N"),
                 ("final pressure", f"{d['final_pressure_mpa']:.4f}", "MPa"),
                 ("kp", f"{gd['kp_mpa_per_n']:.5g}", "MPa/N"),
                 ("ki", f"{gd['ki_mpa_per_n_s']:.5g}", "MPa/(N s)"),
                 ("kd", f"{gd['kd_mpa_s_per_n']:.5g}", "MPa s/N"),
                 ("paper settling time", _fmt(d["paper_settling_time_s"], ".2f"), "s")]))
            console.print(f"plant: {d['plant']}")
            if note:
                console.print(note)

        emit(d, as_json, render)

    @ctl.command("compare")
    def compare_cmd(
        target_friction: float = TARGET, structure: str = STRUCTURE,
        gamma: float | None = GAMMA, plant: str | None = PLANT, step_csv: str | None = STEP_CSV,
        mismatch: float | None = MISMATCH, tau_c: float | None = TAU_C, ff_mode: str = FF_MODE,
        antiwindup: str = ANTIWINDUP, dt: float | None = DT, duration: float = DURATION,
        band: float = BAND, plot: str | None = PLOT, as_json: bool = JSON_OPTION,
    ) -> None:
        """The six cases of Fig 12 (PD, PI, PID; without/with the model) beside the paper."""
        from exofric.reproduction import compare

        if plot:
            plot_path(plot)
        setup = _setup(target_friction, structure, gamma, plant, step_csv, mismatch, tau_c,
                       ff_mode, antiwindup, dt, duration, band)
        res: CompareResult = compare(setup)
        written = (_plot_cases(list(res.cases), plot, f"target {setup.target_n:g} N")
                   if plot else None)
        d = res.to_dict()
        d["plant"] = setup.plant_description()
        if written:
            d["plot"] = written

        notes = [n for c in d["cases"] if (n := _stuck_note(c, setup.target_n))]
        if notes:
            d["notes"] = notes

        def render() -> None:
            t = narrow_table(f"Fig 12: target {setup.target_n:g} N, mismatch "
                             f"{setup.plant.mismatch:g}, feedforward {setup.ff_mode}",
                             ["case", "settle s", "paper s", "OS %", "ss err N", "F N",
                              "P MPa"])
            for c in d["cases"]:
                t.add_row(f"{c['controller'].upper()} {'+ model' if c['feedforward'] else ''}",
                          _fmt(c["settling_time_s"], ".2f"),
                          _fmt(c["paper_settling_time_s"], ".2f"),
                          f"{c['overshoot_pct']:.1f}", f"{c['steady_state_error_n']:.3f}",
                          f"{c['final_friction_n']:.2f}", f"{c['final_pressure_mpa']:.4f}")
            console.print(t)
            red, pred = d["settling_reduction_pct"], d["paper_settling_reduction_pct"]
            for k in ("pi", "pid"):
                console.print(f"{k.upper()}: settling reduced by {_fmt(red[k], '.1f')} % with "
                              f"the model (paper: {pred[k]:g} %)")
            console.print("settle: 2 % settling time; paper: Fig 12 as printed; OS: overshoot; "
                          "ss err: steady-state error; F, P: final friction and pressure.")
            console.print(f"plant: {d['plant']}")
            for n in notes:
                console.print(n)

        emit(d, as_json, render)

    @ctl.command("identify")
    def identify_cmd(
        csv: str | None = typer.Argument(None, help="Step response CSV: time_s, pressure_mpa"
                                         "[, command_mpa] (step at t = 0 without "
                                         "command_mpa)."),
        charge: list[str] = typer.Option([], "--charge", help="Charge/discharge log(s) of the "
                                         "on/off valve: time_s, pressure_mpa, command_mpa "
                                         "(> 0 fills). Fits the valve's sonic conductance C "
                                         "and the volume (repeat for several runs)."),
        supply: float = typer.Option(0.6, "--supply", help="--charge: supply pressure (gauge) "
                                     "in MPa."),
        volume: float | None = typer.Option(None, "--volume", help="--charge: known total "
                                            "volume in mm^3 (then C is fitted)."),
        conductance: float | None = typer.Option(None, "--conductance", help="--charge: known "
                                                 "sonic conductance C of the fill port in "
                                                 "dm^3/(s bar) (then the volume is fitted)."),
        added_volume: str | None = typer.Option(None, "--added-volume", help="--charge: known "
                                                "volume added in each run, mm^3, comma-"
                                                "separated (two different values identify C "
                                                "and the volume together)."),
        target_friction: float = TARGET, structure: str = STRUCTURE,
        gamma: float | None = GAMMA, tau_c: float | None = TAU_C, as_json: bool = JSON_OPTION,
    ) -> None:
        """Identify the pressure supply: lag + dead time from a step (CSV), or the valve's
        sonic conductance and the volume from charge/discharge logs (--charge)."""
        from exofric import paper
        from exofric.control import CONTROLLERS, local_slope, rule_gains
        from exofric.errors import InputError

        if charge:
            if csv is not None:
                raise InputError("give a step CSV or --charge logs, not both", param="charge")
            _identify_charge(charge, supply, volume, conductance, added_volume, as_json)
            return
        if csv is None:
            raise InputError("control identify needs a step-response CSV or --charge LOG",
                             param="csv")
        ident = _identify_csv(csv)
        fmap = _structure_map(structure, paper.scalar("gamma") if gamma is None else gamma)
        slope = local_slope(fmap, fmap.inverse(target_friction)) * ident.gain
        gains = {k: rule_gains(k, slope, ident.time_constant_s, ident.delay_s,
                               tau_c_s=tau_c).to_dict() for k in CONTROLLERS}
        d = {"plant": ident.to_dict(), "target_friction_n": target_friction, "tuning": gains}

        def render() -> None:
            i = d["plant"]
            console.print(kv_table(f"Identified supply from {Path(csv).name}", [
                ("gain", f"{i['gain']:.4g}" + (" (assumed)" if i["gain_assumed"] else ""),
                 "MPa/MPa"),
                ("time constant", f"{i['time_constant_s']:.4g} +/- "
                 f"{i['stderr_time_constant_s']:.2g}", "s"),
                ("dead time", f"{i['delay_s']:.4g} +/- {i['stderr_delay_s']:.2g}", "s"),
                ("R^2", f"{i['r2']:.5f}", ""), ("RMSE", f"{i['rmse_mpa']:.3g}", "MPa")]))
            for k, v in gains.items():
                g = v["gains"]
                console.print(f"{k.upper()}: kp {g['kp_mpa_per_n']:.5g} MPa/N, ki "
                              f"{g['ki_mpa_per_n_s']:.5g} MPa/(N s), kd "
                              f"{g['kd_mpa_s_per_n']:.5g} MPa s/N (tau_c {v['tau_c_s']:.3g} s)")

        emit(d, as_json, render)

    _register_run(ctl)
    app.add_typer(ctl, name="control")


def _identify_charge(logs: list[str], supply: float, volume: float | None,
                     conductance: float | None, added: str | None, as_json: bool) -> None:
    """``control identify --charge``: C and the volume from charge/discharge logs."""
    from exofric.control import identify_charge
    from exofric.errors import InputError
    from exofric.io import read_table

    # gauge pressure: a vented log reads slightly below zero with sensor noise
    frames = [read_table(p, ["time_s", "pressure_mpa", "command_mpa"], nonnegative=[],
                         unique_within=("time_s", None), min_rows=10) for p in logs]
    adds = parse_floats("--added-volume", added) if added else [0.0] * len(frames)
    if len(adds) != len(frames):
        raise InputError(f"--added-volume needs one value per --charge log ({len(frames)}), "
                         f"got {len(adds)}", param="added_volume")
    fit = identify_charge([f["time_s"].to_numpy(float) for f in frames],
                          [f["pressure_mpa"].to_numpy(float) for f in frames],
                          command_mpa=[f["command_mpa"].to_numpy(float) for f in frames],
                          supply_mpa=supply, volume_mm3=volume, c_dm3_per_s_bar=conductance,
                          added_volume_mm3=adds)
    d = fit.to_dict()
    d["logs"] = [str(p) for p in logs]

    def render() -> None:
        rows = [("fill port C", f"{fit.c_fill_dm3_per_s_bar:.4g} +/- {fit.stderr_c_fill:.2g}",
                 "dm^3/(s bar)"),
                ("vent port C", f"{fit.c_vent_dm3_per_s_bar:.4g} +/- {fit.stderr_c_vent:.2g}",
                 "dm^3/(s bar)"),
                ("volume", f"{fit.volume_mm3:.5g} +/- {fit.stderr_volume_mm3:.2g}", "mm^3"),
                ("critical ratio b", f"{fit.critical_ratio:.3g}"
                 + ("" if fit.b_fitted else " (fixed)"), ""),
                ("valve dead time", f"{fit.delay_s:.3g} +/- {fit.stderr_delay_s:.2g}", "s"),
                ("R^2 / RMSE", f"{fit.r2:.5f} / {fit.rmse_mpa:.3g}", "- / MPa")]
        if fit.fixed:
            rows.append(("given, not fitted", ", ".join(fit.fixed), ""))
        if fit.fopdt is not None:
            rows.append(("beside: lag + dead time fit", f"tau {fit.fopdt.time_constant_s:.3g} s,"
                         f" theta {fit.fopdt.delay_s:.3g} s, R^2 {fit.fopdt.r2:.3f}", ""))
        console.print(kv_table("ISO 6358 valve and volume from charge logs", rows))

    emit(d, as_json, render)


def _register_run(ctl: typer.Typer) -> None:
    @ctl.command("run")
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
        target: float = typer.Option(54.40, "--target", help="Friction set-point in N."),
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
                    ("stopped", f"{d.get('stopped_reason')} at {d.get('stopped_at_s')}", "s"),
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
