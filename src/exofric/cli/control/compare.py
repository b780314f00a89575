"""``exofric control compare``: the six cases of Fig 12 beside the paper's settling times."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import typer

from exofric.cli._common import (
    console,
    emit,
    narrow_table,
    plot_path,
)

if TYPE_CHECKING:
    from exofric.reproduction import CompareResult
from exofric.cli._options import OutputOptions, grouped
from exofric.cli.control._shared import (
    PLOT,
    LoopOptions,
    _fmt,
    _plot_cases,
    _stuck_note,
)


def register(ctl: typer.Typer) -> None:
    """Add ``compare`` to ``ctl``."""
    @ctl.command("compare")
    @grouped
    def compare_cmd(
        loop: LoopOptions = LoopOptions.options(),
        out: OutputOptions = OutputOptions.options(plot=PLOT),
    ) -> None:
        """The six cases of Fig 12 (PD, PI, PID; without/with the model) beside the paper."""
        from exofric.reproduction import compare

        plot, as_json = out.plot, out.as_json
        if plot:
            plot_path(plot)
        setup = loop.setup()
        res: CompareResult = compare(setup)
        written = (_plot_cases(list(res.cases), plot, f"target {setup.target_n:g} N")
                   if plot else None)
        d = res.to_dict()
        d["plant"] = setup.plant_description()
        if written:
            d["plot"] = written

        for c in d["cases"]:
            c["feedforward_share_pct"] = _ff_share(c)
        notes = [n for c in d["cases"] if (n := _stuck_note(c, setup.target_n))]
        ff_note = _feedforward_note(d["cases"], setup.plant.mismatch, setup.ff_mode)
        if ff_note:
            notes.append(ff_note)
        if notes:
            d["notes"] = notes

        def render() -> None:
            t = narrow_table(f"Fig 12: target {setup.target_n:g} N, mismatch "
                             f"{setup.plant.mismatch:g}, feedforward {setup.ff_mode}",
                             ["case", "settle s", "paper s", "OS %", "ss err N", "F N",
                              "P MPa", "FF %"])
            for c in d["cases"]:
                t.add_row(f"{c['controller'].upper()} {'+ model' if c['feedforward'] else ''}",
                          _fmt(c["settling_time_s"], ".2f"),
                          _fmt(c["paper_settling_time_s"], ".2f"),
                          f"{c['overshoot_pct']:.1f}", f"{c['steady_state_error_n']:.3f}",
                          f"{c['final_friction_n']:.2f}", f"{c['final_pressure_mpa']:.4f}",
                          _fmt(c["feedforward_share_pct"], ".0f"))
            console.print(t)
            red, pred = d["settling_reduction_pct"], d["paper_settling_reduction_pct"]
            for k in ("pi", "pid"):
                console.print(f"{k.upper()}: settling reduced by {_fmt(red[k], '.1f')} % with "
                              f"the model (paper: {pred[k]:g} %)")
            console.print("settle: 2 % settling time; paper: Fig 12 as printed; OS: overshoot; "
                          "ss err: steady-state error; F, P: final friction and pressure; FF: "
                          "the model feedforward's share of the final pressure. The rows "
                          "without the model are the feedback-only comparison.")
            console.print(f"plant: {d['plant']}")
            for n in notes:
                console.print(n)

        emit(d, as_json, render)


def _ff_share(case: dict[str, Any]) -> float | None:
    """The feedforward pressure as a % of the final pressure (None without feedforward)."""
    ff, p = case.get("feedforward_pressure_mpa"), case.get("final_pressure_mpa")
    if ff is None or not p:
        return None
    return 100.0 * float(ff) / float(p)


def _feedforward_note(cases: list[dict[str, Any]], mismatch: float, ff_mode: str) -> str:
    """Why PD, PI and PID with the model settle alike (the 2-DOF feedforward does the work)."""
    with_model = [c for c in cases if c["feedforward"]]
    times = {None if c["settling_time_s"] is None else round(c["settling_time_s"], 2)
             for c in with_model}
    if ff_mode != "2dof" or len(with_model) < 2 or len(times) != 1 or None in times:
        return ""
    share = min((c["feedforward_share_pct"] or 0.0) for c in with_model)
    return (f"with the model, PD, PI and PID settle alike ({times.pop():.2f} s): the 2-DOF "
            f"feedforward gives {share:.0f} % of the final pressure and the feedback acts only "
            "on the deviation from the model-predicted friction, which "
            + ("is zero with an exact model (mismatch 0)" if mismatch == 0 else
               "stays small here")
            + ". The feedback-only rows compare the controllers; --mismatch 0.2 shows them "
            "correcting a wrong model.")
