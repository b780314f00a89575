"""``exofric reduce``: raw friction-rig logs in, one row per pull and a friction curve out.

Units: time s, pressure MPa, force N, displacement mm (logs in kPa, bar, psi, kgf, lbf, m, ...
are converted on reading). Logs are CSV (unit-suffixed headers, ``#`` metadata lines), Parquet
or NI TDMS; ``--columns`` maps other headers.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import typer

from exofric.cli._common import JSON_OPTION, console, emit, out_file, plot_path, save_figure
from exofric.cli._rawlogs import (
    COLUMNS_OPTION,
    MIN_PLATEAU_OPTION,
    PLATEAU_TOL_OPTION,
    SKIP_MM_OPTION,
    SKIP_S_OPTION,
    reduce_files,
    settings_from,
)

if TYPE_CHECKING:
    import pandas as pd

    from exofric.friction import RigReduction

__all__ = ["register"]


def _plot_paths(plot: str, reds: list[RigReduction]) -> list[Path]:
    base = plot_path(plot)
    if len(reds) == 1:
        return [base]
    return [base.with_name(f"{base.stem}-{Path(r.source).stem}{base.suffix}") for r in reds]


def _pulls_csv(df: pd.DataFrame, meta: list[str], logs: list[str]) -> str:
    synthetic = any("SYNTHETIC" in m.upper() for m in meta)
    head = [f"# exofric reduce: one row per pull of {', '.join(logs)}; units MPa, N, s, mm"]
    if synthetic:
        head.append("# SYNTHETIC: reduced from a virtual-rig log (NOT measured)")
    head += [f"# {m}" for m in meta]
    return "\n".join(head) + "\n" + df.to_csv(index=False, float_format="%.10g")


def register(app: typer.Typer) -> None:
    """Add ``reduce`` to ``app``."""

    @app.command("reduce")
    def reduce_cmd(
        logs: list[str] = typer.Argument(..., help="Raw rig log(s): CSV, Parquet or TDMS with "
                                         "time_s, pressure_<unit>, force_<unit> "
                                         "[, displacement_<unit>]."),
        columns: str | None = COLUMNS_OPTION,
        out: str | None = typer.Option(None, help="Write the per-pull table (CSV; input of "
                                       "`exofric fit-friction --friction`)."),
        plot: str | None = typer.Option(None, help="PNG of each log with the plateaus, pulls "
                                        "and averaging windows shaded (NAME-<log>.png for "
                                        "several logs)."),
        skip_mm: float = SKIP_MM_OPTION,
        skip_s: float = SKIP_S_OPTION,
        plateau_tol: float = PLATEAU_TOL_OPTION,
        min_plateau: float = MIN_PLATEAU_OPTION,
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Reduce raw friction-rig logs: static and kinetic friction per pull, curve. MPa, N, s."""
        from exofric.friction import friction_curve
        from exofric.io import write_text

        if out is not None:
            out_file("out", out)
        if plot:
            plot_path(plot)
        settings = settings_from(skip_mm, skip_s, plateau_tol, min_plateau)
        reds, pulls, meta = reduce_files(logs, columns, settings)
        curve, hyst = friction_curve(pulls, settings)
        skipped = [{**sk, "log": r.source} for r in reds for sk in r.skipped]
        d: dict[str, Any] = {
            "logs": [{"source": r.source, "n_samples": int(r.time_s.size),
                      "duration_s": float(r.time_s[-1] - r.time_s[0]),
                      "pull_detection": r.pull_detection, "n_plateaus": len(r.plateaus),
                      "n_pulls": len(r.pulls), "n_skipped": len(r.skipped),
                      "plateaus": list(r.plateaus)} for r in reds],
            "pulls": pulls.to_dict("records"),
            "curve": curve,
            "hysteresis": list(hyst),
            "skipped": skipped,
            "synthetic": any("SYNTHETIC" in m.upper() for m in meta),
            "settings": settings.to_dict(),
        }
        if out is not None:
            write_text(Path(out), _pulls_csv(pulls, meta, [r.source for r in reds]))
            d["out"] = str(out)
        if plot:
            d["plot"] = [str(save_figure(r.plot(), p))
                         for r, p in zip(reds, _plot_paths(plot, reds), strict=True)]

        def render() -> None:
            from rich.table import Table

            t = Table(title="Friction per set point (MPa, N; sd = between pulls)")
            for c in ("P (MPa)", "branch", "pulls", "kinetic (N)", "sd (N)", "static (N)",
                      "bias (N)"):
                t.add_column(c, justify="right")
            for i in range(len(curve["pressure_mpa"])):
                b = curve["bias_n"][i]
                sd = curve["kinetic_sd_n"][i]
                t.add_row(f"{curve['pressure_mpa'][i]:.4f}", curve["branch"][i],
                          str(curve["n_pulls"][i]), f"{curve['kinetic_n'][i]:.2f}",
                          "-" if sd != sd else f"{sd:.2f}", f"{curve['static_n'][i]:.2f}",
                          "-" if b != b else f"{b:.2f}")
            console.print(t)
            if hyst:
                h = Table(title="Hysteresis, down - up branch (MPa, N, %)")
                for c in ("P (MPa)", "up (N)", "down (N)", "down - up (N)", "(%)"):
                    h.add_column(c, justify="right")
                for row in hyst:
                    h.add_row(f"{row['pressure_mpa']:.4f}", f"{row['kinetic_up_n']:.2f}",
                              f"{row['kinetic_down_n']:.2f}", f"{row['hysteresis_n']:+.2f}",
                              f"{row['hysteresis_pct']:+.1f}")
                console.print(h)
            for r in reds:
                console.print(f"{r.source}: {len(r.plateaus)} plateaus, {len(r.pulls)} pulls "
                              f"used, {len(r.skipped)} skipped (found in the "
                              f"{r.pull_detection})")
            for sk in skipped:
                console.print(f"  skipped pull {sk['pull']} of {sk['log']} "
                              f"({sk['t_start_s']:.2f}-{sk['t_end_s']:.2f} s): {sk['reason']}",
                              soft_wrap=False)
            for f in ([d["out"]] if "out" in d else []) + d.get("plot", []):
                console.print(f"written: {f}")

        emit(d, as_json, render)
