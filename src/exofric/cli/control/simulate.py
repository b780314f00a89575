"""``exofric control``: simulate one friction step (PD/PI/PID, with or without the model)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import typer

from exofric.cli._common import (
    console,
    emit,
    kv_table,
    plot_path,
)

if TYPE_CHECKING:
    pass
from exofric.cli._options import OutputOptions, grouped
from exofric.cli.control._shared import (
    PLOT,
    LoopOptions,
    _fmt,
    _opt,
    _plot_cases,
    _stuck_note,
)


def register(ctl: typer.Typer) -> None:
    """Add the group's default action (one simulated step) to ``ctl``."""
    @ctl.callback(invoke_without_command=True)
    @grouped
    def control(
        ctx: typer.Context,
        controller: str = _opt("pid", "Controller: pd, pi or pid."),
        kp: float | None = _opt(None, "Proportional gain in MPa/N (default: IMC/SIMC rule)."),
        ki: float | None = _opt(None, "Integral gain in MPa/(N s) (default: rule; 0 for PD)."),
        kd: float | None = _opt(None, "Derivative gain in MPa s/N (default: rule; 0 for PI)."),
        feedforward: bool = typer.Option(False, "--feedforward",
                                         help="Add the model feedforward P_ff = g^-1(F)."),
        tuning: str = _opt("rule", "Gains: rule (IMC/SIMC) or itae (optimised, saturated loop)."),
        loop: LoopOptions = LoopOptions.options(),
        out: OutputOptions = OutputOptions.options(plot=PLOT),
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

        plot, as_json, band = out.plot, out.as_json, loop.band
        if plot:
            plot_path(plot)

        kind = controller.lower()
        if kind not in CONTROLLERS:
            raise InputError(f"--controller must be pd, pi or pid, got {controller!r}")
        setup = loop.setup()
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
