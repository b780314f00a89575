"""``exofric rig``: the virtual friction rig, SYNTHETIC friction data with planted truths.

Units: pressure MPa, forces N, speeds mm/s, rates Hz. Squeeze curves are read by
:mod:`exofric.io` (``exofric squeeze --json`` output or a ``pressure_mpa,squeeze_force_n``
CSV); friction CSVs and raw logs are written by it.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, ClassVar

import typer

from exofric.cli._common import JSON_OPTION, console, emit, kv_table, out_file, parse_floats
from exofric.cli._friction_inputs import choice, interface_curves, squeeze_curve
from exofric.cli._options import FrictionLawOptions, OptionGroup, grouped

__all__ = ["register"]

#: rig's wording of the friction-law group (the planted law)
_LAW = FrictionLawOptions.options(
    law=typer.Option("gamma", help="Planted law: gamma (F = gamma_true N) or interfaces (F = "
                     "mu_tube S_wire + mu_wall N; not with --raw)."),
    mu_tube=typer.Option(None, "--mu-tube", help="Planted wire-on-tube coefficient (unitless), "
                         "--law interfaces."),
    mu_wall=typer.Option(None, "--mu-wall", help="Planted wire-on-wall coefficient (unitless), "
                         "--law interfaces."),
)


class _Logger(OptionGroup):
    """The load cell, pressure sensor and logger of the rig, the pull and the repeats (None:
    the default of the friction table or of the raw log, which differ)."""

    noise_pct: float | None
    noise_n: float | None
    offset_n: float | None
    drift: float | None
    drag_n: float
    pressure_noise: float | None
    sample_rate: float | None
    pull_speed: float
    repeats: int | None
    OPTIONS: ClassVar[dict[str, Any]] = {
        "noise_pct": typer.Option(None, help="Load-cell noise, % of force (1 sigma; default 2, "
                                  "raw 0.3)."),
        "noise_n": typer.Option(None, help="Load-cell noise in N (1 sigma; default 0, raw "
                                "0.1)."),
        "offset_n": typer.Option(None, help="Load-cell zero offset in N (tared; default 0, raw "
                                 "5)."),
        "drift": typer.Option(None, help="Load-cell drift in N/s (default 0, raw 0.01)."),
        "drag_n": typer.Option(0.0, help="Pressure-independent drag F0 in N."),
        "pressure_noise": typer.Option(None, help="Pressure sensor noise in MPa (default 0, "
                                       "raw 0.002)."),
        "sample_rate": typer.Option(None, help="Logger rate in Hz (default 100, raw 500)."),
        "pull_speed": typer.Option(2.0, help="Wire speed in mm/s."),
        "repeats": typer.Option(None, help="Repeated tests (adds a test column); raw: pulls "
                                "per direction and plateau (default 5)."),
    }

    def given(self) -> dict[str, Any]:
        """The sensor settings given (config names), both kinds of rig take them."""
        return {k: v for k, v in {
            "noise_pct": self.noise_pct, "noise_n": self.noise_n,
            "drift_n_per_s": self.drift, "pressure_noise_mpa": self.pressure_noise,
            "sample_rate_hz": self.sample_rate}.items() if v is not None}


class _RawLog(OptionGroup):
    """What only the raw time series (--raw) plants: pulls, branches, stick-slip, scatter."""

    directions: str
    sweep: str
    static_ratio: float
    stick_slip_pct: float
    bias_n: float
    hysteresis_pct: float
    noise_tau: float
    pull_scatter_pct: float
    plateau_scatter_pct: float
    OPTIONS: ClassVar[dict[str, Any]] = {
        "directions": typer.Option("both", help="raw: both (forward and backward pulls) or "
                                   "forward."),
        "sweep": typer.Option("up", help="raw: up, or up-down (two branches)."),
        "static_ratio": typer.Option(1.3, help="raw: static / kinetic friction."),
        "stick_slip_pct": typer.Option(1.0, help="raw: stick-slip amplitude, % of friction."),
        "bias_n": typer.Option(1.5, "--bias-n", help="raw: force of constant sign while moving "
                               "(gravity) in N."),
        "hysteresis_pct": typer.Option(0.0, help="raw: down-branch friction above the up "
                                       "branch, %."),
        "noise_tau": typer.Option(0.02, help="raw: load-cell noise correlation time in s."),
        "pull_scatter_pct": typer.Option(1.5, help="raw: per-pull friction scatter (1 sigma), "
                                         "%."),
        "plateau_scatter_pct": typer.Option(1.0, help="raw: per-plateau friction scatter "
                                            "(1 sigma), %."),
    }


def _planted_law(law: FrictionLawOptions, gamma_true: float | None, raw: bool,
                 squeeze: str) -> tuple[Any, Any]:
    """The interface curves and planted interface law of --law interfaces ((None, None) for
    --law gamma), after checking that the planted coefficients fit the law."""
    from exofric.errors import InputError

    if law.law == "interfaces":
        from exofric.friction import InterfaceFrictionModel

        if gamma_true is not None:
            raise InputError("gamma_true is for --law gamma; --law interfaces plants "
                             "--mu-tube and --mu-wall", param="gamma_true")
        if law.mu_tube is None or law.mu_wall is None:
            raise InputError("mu_tube and mu_wall are required with --law interfaces",
                             param="mu_tube" if law.mu_tube is None else "mu_wall")
        planted = InterfaceFrictionModel(law.mu_tube, law.mu_wall)
        if raw:
            raise InputError("raw logs plant gamma only; drop --raw for --law interfaces",
                             param="raw")
        return interface_curves(squeeze, set()), planted
    if gamma_true is None:
        raise InputError("gamma_true is required with --law gamma", param="gamma_true")
    if law.mu_tube is not None or law.mu_wall is not None:
        raise InputError("mu_tube and mu_wall go with --law interfaces", param="mu_tube")
    return None, None


def _raw_log(op: Path, out: str, ps: Any, ns: Any, gamma_true: float, sp: list[float] | None,
             logger: _Logger, rl: _RawLog, seed: int, as_json: bool) -> None:
    """``rig --raw``: the raw time series and its truths (OUT-stem.truth.json)."""
    from exofric.errors import InputError
    from exofric.friction import RawRigConfig, simulate_raw_log
    from exofric.io import write_json, write_raw_log

    if op.suffix.lower() not in (".csv", ".parquet"):
        raise InputError(f"out must end in .csv or .parquet with --raw, got {out!r}",
                         param="out")
    given = logger.given()
    if logger.offset_n is not None:
        given["tare_offset_n"] = logger.offset_n
    choice("--directions", rl.directions, ("both", "forward"))
    choice("--sweep", rl.sweep, ("up", "up-down"))
    rcfg = RawRigConfig(
        pull_speed_mm_per_s=logger.pull_speed,
        replicates=5 if logger.repeats is None else logger.repeats,
        directions=rl.directions, sweep=rl.sweep,  # type: ignore[arg-type]
        static_ratio=rl.static_ratio, stick_slip_pct=rl.stick_slip_pct, bias_n=rl.bias_n,
        drag_n=logger.drag_n, hysteresis_pct=rl.hysteresis_pct, noise_tau_s=rl.noise_tau,
        pull_scatter_pct=rl.pull_scatter_pct, plateau_scatter_pct=rl.plateau_scatter_pct,
        **given)
    log = simulate_raw_log(ps, ns, gamma_true, sp, config=rcfg, seed=seed)
    truth_path = op.with_name(op.stem + ".truth.json")
    try:
        write_raw_log(op, log.to_frame(), log.metadata())
        write_json(log.to_dict(), truth_path)
    except OSError as exc:
        why = " ".join(str(exc.strerror or exc).split())
        raise InputError(f"--out {out}: cannot write ({why})") from None
    d = {k: v for k, v in log.to_dict().items() if k != "pulls"}
    d.update({"n_pulls": log.n_pulls, "out": str(op), "truth": str(truth_path)})

    def render_raw() -> None:
        console.print(kv_table("Virtual rig, raw log (SYNTHETIC)", [
            ("gamma_true", f"{gamma_true:g}", ""),
            ("plateaus / pulls", f"{len(log.setpoints_mpa)} / {log.n_pulls}", ""),
            ("samples logged", str(d["n_samples"]), ""),
            ("duration", f"{d['duration_s']:.1f}", "s"),
            ("log written", str(op), ""),
            ("truths written", str(truth_path), "")]))

    emit(d, as_json, render_raw)


@grouped
def rig(
    squeeze: str = typer.Option(..., help="Squeeze curve N(P) (JSON or CSV; --law "
                                "interfaces: the JSON of `exofric squeeze --json`)."),
    gamma_true: float | None = typer.Option(None, help="Planted equivalent coefficient "
                                            "gamma (--law gamma)."),
    friction_law: FrictionLawOptions = _LAW,
    out: str = typer.Option(..., help="Output: friction CSV, or with --raw a raw log "
                            "(.csv or .parquet) plus OUT-stem.truth.json (labelled "
                            "SYNTHETIC)."),
    pressures: str | None = typer.Option(None, help="Set points in MPa (default: the "
                                         "curve's pressures with N > 0)."),
    raw: bool = typer.Option(False, "--raw", help="Write the raw time series (time, "
                             "pressure, force, displacement) with planted truths."),
    logger: _Logger = _Logger.options(),
    raw_log: _RawLog = _RawLog.options(),
    seed: int = typer.Option(0, help="RNG seed (deterministic output)."),
    as_json: bool = JSON_OPTION,
) -> None:
    """Virtual friction rig: SYNTHETIC friction data F = gamma_true N(P) + errors. MPa, N.

    With --law interfaces the planted friction is F = mu_tube S_wire(P) + mu_wall N(P).
    """
    from exofric.errors import InputError, check_seed
    from exofric.friction import RigConfig, simulate_rig
    from exofric.io import write_text

    check_seed("seed", seed)
    choice("--law", friction_law.law, ("gamma", "interfaces"))
    op = out_file("out", out)
    curves, planted = _planted_law(friction_law, gamma_true, raw, squeeze)
    ps, ns = (None, None) if curves is not None else squeeze_curve(squeeze)
    sp = parse_floats("--pressures", pressures) if pressures else None
    if raw:
        _raw_log(op, out, ps, ns, gamma_true, sp, logger, raw_log,  # type: ignore[arg-type]
                 seed, as_json)
        return
    given = logger.given()
    if logger.offset_n is not None:
        given["offset_n"] = logger.offset_n
    cfg = RigConfig(drag_n=logger.drag_n, pull_speed_mm_per_s=logger.pull_speed, **given)
    repeats = 1 if logger.repeats is None else logger.repeats
    if curves is not None:
        from exofric.friction import simulate_interface_rig

        irun = simulate_interface_rig(curves, planted.mu_tube, planted.mu_wall, sp,
                                      config=cfg, seed=seed, repeats=repeats)
        run, text, d = irun.run, irun.to_csv_text(), irun.to_dict()
        what = ("mu_tube, mu_wall", f"{planted.mu_tube:g}, {planted.mu_wall:g}")
    else:
        run = simulate_rig(ps, ns, gamma_true, sp, config=cfg,  # type: ignore[arg-type]
                           seed=seed, repeats=repeats)
        text, d = run.to_csv_text(), run.to_dict()
        what = ("gamma_true", f"{gamma_true:g}")
    try:
        write_text(op, text)
    except OSError as exc:
        why = " ".join(str(exc.strerror or exc).split())
        raise InputError(f"--out {out}: cannot write ({why})") from None
    d["out"] = str(op)
    d["law"] = friction_law.law

    def render() -> None:
        console.print(kv_table("Virtual rig (SYNTHETIC)", [
            (what[0], what[1], ""),
            ("points", str(len(run.pressure_mpa)), ""),
            ("samples logged", str(d["n_samples"]), ""),
            ("written", str(op), "")]))

    emit(d, as_json, render)


def register(app: typer.Typer) -> None:
    """Add the ``rig`` command."""
    app.command("rig")(rig)
