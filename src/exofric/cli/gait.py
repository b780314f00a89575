"""``exofric gait``: the knee lock through a gait cycle (walking data, pneumatics, controllers).

Units: time s, torque Nm, pressure MPa, radius m, wrap deg, volumes mm^3, sonic conductance
dm^3/(s bar), air normal litres. The model is in :mod:`exofric.control._gait` and
``docs/gait.md``.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import typer

from exofric.cli._common import JSON_OPTION, console, emit, narrow_table
from exofric.cli._options import MaterialOptions, OptionGroup, StructureOptions, grouped

__all__ = ["register"]

_CONTROLLERS = ("pid", "ff", "preview", "ilc", "mpc")


class _GaitStructure(StructureOptions):
    """The lock's structure (mm), optional: given, the friction map and the tube volume come
    from the FE squeeze instead of the paper's Eq 9."""

    length: float
    OPTIONS: ClassVar[dict[str, Any]] = {
        "hole": typer.Option(None, help="Structure for an FE friction map: hole diameter D in "
                             "mm (with --tube-od, --tube-id, --wire, --shore, --gamma; "
                             "default: the paper's Eq 9 map)."),
        "tube_od": typer.Option(None, help="Structure: tube OD d1 in mm."),
        "tube_id": typer.Option(None, help="Structure: tube ID in mm."),
        "wire": typer.Option(None, help="Structure: wire diameter d2 in mm."),
        "length": typer.Option(116.0, help="Structure: tube length L in mm."),
    }

    def given(self) -> bool:
        """True when any of the four diameters was given."""
        return any(v is not None for v in (self.hole, self.tube_od, self.tube_id, self.wire))


class _Pneumatics(OptionGroup):
    """Valve and line (the physical plant): supply MPa, sonic conductances dm^3/(s bar), line
    volume mm^3, valve kind."""

    supply: float
    fill_c: float
    vent_c: float
    line_volume: float
    valve: str
    OPTIONS: ClassVar[dict[str, Any]] = {
        "supply": typer.Option(0.6, help="Supply pressure in MPa (gauge)."),
        "fill_c": typer.Option(0.05, "--fill-c", help="Sonic conductance C of the fill port "
                               "in dm^3/(s bar)."),
        "vent_c": typer.Option(0.05, "--vent-c", help="Sonic conductance C of the vent port "
                               "in dm^3/(s bar)."),
        "line_volume": typer.Option(12566.0, "--line-volume", help="Hose and fittings volume "
                                    "in mm^3 (default 1 m of 4 mm ID hose)."),
        "valve": typer.Option("regulator", help="regulator (proportional) or on-off."),
    }


def _friction(struct: _GaitStructure, mat: MaterialOptions, gamma: float | None,
              p_max: float) -> tuple[Any, Any, str]:
    """(friction map, tube table or None, description)."""
    if not struct.given():
        _nothing_for_the_map(struct, mat)
        return None, None, "paper Eq 9 (gamma x Eq 8 cubic)"
    import numpy as np

    from exofric import defaults
    from exofric.control import CurveFrictionMap, tube_volume_table
    from exofric.errors import InputError
    from exofric.simulate import squeeze

    if None in (struct.hole, struct.tube_od, struct.tube_id, struct.wire):
        raise InputError("give all four of --hole, --tube-od, --tube-id and --wire (mm)",
                         param="hole")
    material = mat.material() if (mat.shore, mat.c10, mat.model) != (None, None, None) else \
        MaterialOptions(62.5, None, None, None, None, None).material()
    p = np.linspace(0.05 * p_max, p_max, 12)
    res = squeeze(struct.structure(struct.length), material, list(p), keep_fields=True)
    g = defaults.PAPER_GAMMA if gamma is None else gamma
    fmap = CurveFrictionMap(tuple(map(float, res.pressure_mpa)),
                            tuple(map(float, res.squeeze_force_n)), g)
    return fmap, tube_volume_table(res), f"FE squeeze curve x gamma {g:g}"


def _nothing_for_the_map(struct: _GaitStructure, mat: MaterialOptions) -> None:
    """Without a structure the map is the paper's Eq 9: a material or a length given would be
    ignored silently (issue 38), so it is an error naming the option."""
    from exofric.errors import InputError

    given = [f"--{k.replace('_', '-')}" for k in ("shore", "c10", "c01", "d", "model", "params")
             if getattr(mat, k) is not None]
    given += ["--length"] if struct.length != 116.0 else []
    if given:
        raise InputError(f"{given[0]} sets the FE friction map's tube: give it with --hole, "
                         "--tube-od, --tube-id and --wire (without them the map is the "
                         "paper's Eq 9)", param=given[0].lstrip("-"))


def _fig12() -> dict[str, Any]:
    """The paper's Fig 12 settling times (s) of a constant target, for comparison."""
    from exofric import paper

    keys = ("pd_model", "pi", "pi_model", "pid", "pid_model")
    return {k: paper.scalar(f"settling_{k}_s") for k in keys}


def _ms(v: float | None) -> str:
    """A latency in ms, or '-' when the lock never engaged (released) in that stride."""
    return "-" if v is None or not math.isfinite(v) else f"{v:.0f}"


def _render(out: dict[str, Any]) -> None:
    t = narrow_table(f"knee lock, assist {out['setup']['assist']:g}, peak demand "
                     f"{out['peak_demand_nm']:.1f} Nm, window {out['window']}",
                     ["ctrl", "stride", "RMS Nm", "RMS %", "peak Nm", "on/off ms", "air NL",
                      "P MPa", "duty", "J"])
    t.collapse_padding = True              # 10 short columns in 80: one space between
    for col in t.columns:                  # short cells: none wraps
        col.no_wrap = True
    for row in out["table"]:
        t.add_row(row["controller"], str(row["after_strides"]),
                  f"{row['rms_error_nm']:.2f}", f"{row['rms_error_pct']:.0f}",
                  f"{row['peak_error_nm']:.1f}",
                  f"{_ms(row['engage_latency_ms'])}/{_ms(row['release_latency_ms'])}",
                  f"{row['air_nl']:.3f}", f"{row['peak_pressure_mpa']:.2f}",
                  f"{row['valve_duty']:.2f}", f"{row['energy_dissipated_j']:.2f}")
    console.print(t)
    console.print("RMS and peak: torque error over the demand (Nm, % of the peak demand); on/off: "
                  "engagement and release latency (ms); air per stride (normal litres); P: peak "
                  "tube pressure; duty: valve duty; J: energy the lock absorbed per stride")
    wrong = [r["controller"] for r in out["table"] if r["wrong_direction"]]
    console.print("lock resisted in the wrong direction: " + (", ".join(wrong) if wrong
                                                               else "never"))
    console.print(f"data: {out['data']['source']}; plant: {out['plant']}; friction: "
                  f"{out['friction']}; supply model K {out['model']['gain']:.3g}, tau "
                  f"{1e3 * out['model']['time_constant_s']:.0f} ms, dead time "
                  f"{1e3 * out['model']['delay_s']:.0f} ms")
    for c, sz in out.get("sizing", {}).items():
        best = sz["smallest_conductance"]
        rows = ", ".join(f"{cc:g}: {e:.0f} %" for cc, e in
                         zip(sz["conductance_dm3_per_s_bar"], sz["rms_error_pct"], strict=True))
        console.print(f"sizing {c}: RMS error <= {sz['target_rms_pct']:g} % needs C >= "
                      f"{best:g} dm3/(s bar)" if best is not None else
                      f"sizing {c}: no swept C meets {sz['target_rms_pct']:g} %")
        console.print(f"  (C dm3/(s bar): RMS % of peak) {rows}")
    fig12 = out["paper_fig12_settling_s"]
    console.print(f"paper Fig 12 (a constant target): settling {min(fig12.values()):.2f}-"
                  f"{max(fig12.values()):.2f} s; here a stride is {out['stride_s']:.2f} s and "
                  f"the demand lasts {out['demand_s']:.2f} s")


def _simulate(walk: Any, setup: Any, names: tuple[str, ...], fric: tuple[Any, Any, str],
              pneu: _Pneumatics, size_target: float | None) -> tuple[dict[str, Any], Any]:
    """Run the controllers (and the sizing sweep): the JSON object and the first result."""
    from exofric.control import Orifice, PneumaticParams, compare_gait, size_valve

    fmap, table, fdesc = fric
    params = PneumaticParams(
        supply_mpa=pneu.supply, fill=Orifice(pneu.fill_c), vent=Orifice(pneu.vent_c),
        line_volume_mm3=pneu.line_volume, valve=pneu.valve,
        tube_table_pressure_mpa=() if table is None else tuple(map(float, table[0])),
        tube_table_volume_mm3=() if table is None else tuple(map(float, table[1])))
    comp = compare_gait(walk, setup, controllers=names, plant=params, friction=fmap)
    first = comp.results[0]
    out: dict[str, Any] = {
        "data": {"source": walk.source, "body_mass_kg": walk.body_mass_kg,
                 "samples": walk.n_samples, "knee_work_j": walk.knee_work_j},
        "setup": setup.to_dict(), "plant": first.plant, "friction": fdesc,
        "model": first.model.to_dict(), "window": first.window,
        "peak_demand_nm": first.peak_demand_nm,
        "stride_s": first.time_s.size // len(first.strides) * first.dt_s,
        "demand_s": float(abs(first.demand_nm[: first.time_s.size // len(first.strides)])
                          .astype(bool).sum() * first.dt_s),
        "controllers": {r.controller: r.to_dict() for r in comp.results},
        "table": comp.to_frame().to_dict(orient="records"),
        "paper_fig12_settling_s": _fig12(),
        "warnings": sorted({w for r in comp.results for w in r.warnings}),
    }
    if size_target is not None:
        out["sizing"] = {c: size_valve(walk, setup, target_rms_pct=size_target, controller=c,
                                       base=params, friction=fmap).to_dict() for c in names}
    out["_results"] = comp.results
    return out, first


def register(app: typer.Typer) -> None:
    """Add ``gait`` to ``app``."""

    @app.command("gait")
    @grouped
    def gait_cmd(
        data: str | None = typer.Option(None, help="Walking data: OpenSim .sto/.mot or a table "
                                        "(time, knee angle deg/rad, knee moment Nm); default "
                                        "the shipped OpenSim stride."),
        moment_data: str | None = typer.Option(None, "--moment-data", help="Second file with "
                                               "the knee moment (OpenSim inverse dynamics "
                                               ".sto) when --data holds the angles (.mot)."),
        assist: float = typer.Option(0.3, help="Share of the biological knee moment demanded "
                                     "(0-1), in the loading-response window."),
        controller: str = typer.Option("all", help="pid, ff, preview, ilc, mpc or all."),
        strides: int = typer.Option(10, help="Strides simulated (1-200)."),
        cadence_hz: float | None = typer.Option(None, "--cadence", help="Stride frequency in "
                                                "Hz (0.3-2; default the data's own)."),
        radius_m: float = typer.Option(0.10, "--radius", help="Pulley radius R in m."),
        wrap_deg: float = typer.Option(0.0, "--wrap-deg", help="Wrap of the wire on the knee "
                                       "arc in deg."),
        mu_arc: float = typer.Option(0.0, "--mu-arc", help="Wire-on-arc coefficient."),
        mu_static: float | None = typer.Option(None, "--mu-static", help="Static coefficient "
                                               "of the lock (>= gamma): it holds mu_static / "
                                               "gamma x the kinetic capacity when stuck."),
        gamma: float | None = typer.Option(None, help="Kinetic equivalent coefficient of the "
                                           "FE map (default the paper's 0.7168)."),
        dt_s: float = typer.Option(0.002, "--dt", help="Control sample and simulation step "
                                   "in s."),
        sensor_delay_s: float = typer.Option(0.002, "--sensor-delay", help="Age of the force "
                                           "and pressure measurements in s."),
        precharge_mpa: float = typer.Option(0.0, "--precharge", help="Lowest pressure command "
                                            "in MPa (hold the tube near contact onset between "
                                            "demands)."),
        struct: _GaitStructure = _GaitStructure.options(),
        mat: MaterialOptions = MaterialOptions.options(),
        pneu: _Pneumatics = _Pneumatics.options(),
        size_target: float | None = typer.Option(None, "--size-target", help="Also size the "
                                                 "valve: the smallest fill = vent sonic "
                                                 "conductance (0.02-0.4 dm^3/(s bar)) whose RMS "
                                                 "torque error is at most this % of the peak "
                                                 "demand, per controller."),
        plot: str | None = typer.Option(None, help="Write the figure to PATH (one controller: "
                                        "torque, pressure, valve and knee angle over the last "
                                        "strides; several: their last strides compared)."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """The knee lock through walking: demand vs delivered torque per controller. Nm, MPa, s.

        The knee angle of the data drives the wire (radius R); the lock is a brake (it only
        resists motion) whose capacity follows the tube pressure of a physical pneumatic
        plant; each controller (the one `control run` steps on hardware, plus preview, ILC
        and MPC) tracks assist x the biological moment in early stance.
        """
        from exofric import defaults
        from exofric.cli._common import plot_path, save_figure
        from exofric.control import GaitSetup
        from exofric.errors import InputError
        from exofric.io import gait_data_path, read_gait

        names = _CONTROLLERS if controller == "all" else (controller,)
        if controller != "all" and controller not in _CONTROLLERS:
            raise InputError(f"controller must be one of {', '.join(_CONTROLLERS)} or all, got "
                             f"{controller!r}", param="controller")
        if plot is not None:
            plot_path(plot)
        kinetic = defaults.PAPER_GAMMA if gamma is None else gamma
        if mu_static is not None and mu_static < kinetic:
            raise InputError(f"mu_static must be >= the kinetic coefficient {kinetic:g}, got "
                             f"{mu_static:g}", param="mu_static")
        walk = read_gait(data if data is not None else gait_data_path(),
                         moment_path=moment_data)
        setup = GaitSetup(assist=assist, cadence_hz=cadence_hz, strides=strides,
                          radius_m=radius_m,
                          wrap_deg=wrap_deg, mu_arc=mu_arc,
                          static_ratio=1.0 if mu_static is None else mu_static / kinetic,
                          dt_s=dt_s, sensor_delay_s=sensor_delay_s,
                          p_max_mpa=pneu.supply, precharge_mpa=precharge_mpa)
        out, first = _simulate(walk, setup, names, _friction(struct, mat, gamma, pneu.supply),
                               pneu, size_target)
        if plot is not None:
            from exofric.plots import plot_gait_compare

            fig = first.plot() if len(names) == 1 else plot_gait_compare(out.pop("_results"))
            out["plot"] = str(save_figure(fig, plot))
        out.pop("_results", None)
        emit(out, as_json, lambda: _render(out))
