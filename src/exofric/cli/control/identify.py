"""``exofric control identify``: the supply's lag, dead time and gain from a step, or the valve's
conductance and the volume from charge/discharge logs."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import typer

from exofric.cli._common import (
    JSON_OPTION,
    console,
    emit,
    kv_table,
    parse_floats,
)

if TYPE_CHECKING:
    pass
from exofric.cli.control._shared import (
    GAMMA,
    STRUCTURE,
    TARGET,
    TAU_C,
    _identify_csv,
    _structure_map,
)


def register(ctl: typer.Typer) -> None:
    """Add ``identify`` to ``ctl``."""
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
        gamma: float | None = GAMMA, tau_c: float | None = TAU_C,
        columns: str | None = typer.Option(
            None, "--columns", help="Map the step CSV's headers: time_s=t,pressure_kpa=P1"
            "[,command_mpa=U] (units in the keys); 'Time (s)'-style headers need none."),
        as_json: bool = JSON_OPTION,
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
        ident = _identify_csv(csv, columns)
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
