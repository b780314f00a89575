"""``exofric fit-pullout``: friction coefficients from measured pulls (raw rig logs with
displacement; issue 39). Units: mm, N, MPa; coefficients unitless.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import typer

from exofric import defaults
from exofric.cli._common import console, emit, plot_path, save_figure
from exofric.cli._options import (
    PULLOUT_ENDS_HELP,
    MaterialOptions,
    OutputOptions,
    StructureOptions,
    grouped,
)
from exofric.cli._rawlogs import (
    COLUMNS_OPTION,
    MIN_PLATEAU_OPTION,
    PLATEAU_TOL_OPTION,
    SKIP_MM_OPTION,
    SKIP_S_OPTION,
    reduce_files,
    settings_from,
)

__all__ = ["register"]


def _fit_or_value(text: str | None) -> Any:
    """'fit' stays 'fit', a number becomes a float (checked by the library), None stays."""
    if text is None:
        return None
    t = text.strip().lower()
    if t == "fit":
        return "fit"
    try:
        return float(t)
    except ValueError:
        return text          # the library names the parameter and the allowed values


@grouped
def fit_pullout_cmd(
    logs: list[str] = typer.Argument(..., help="Raw rig log(s) with time, pressure, force and "
                                     "displacement (CSV, Parquet or TDMS)."),
    structure: StructureOptions = StructureOptions.options(),
    length: float = typer.Option(116.0, help="Tube length L (mm)."),
    material: MaterialOptions = MaterialOptions.options(),
    ends: str = typer.Option("fixed", "--ends", help=PULLOUT_ENDS_HELP),
    cable_ea: float = typer.Option(defaults.CABLE_EA_N, "--cable-ea",
                                   help="Cable axial stiffness EA (N)."),
    compliance_mm_per_n: float = typer.Option(0.0, "--compliance", help="Rig series compliance "
                                              "between the displacement sensor and the tube "
                                              "(mm/N; not fitted: measure it)."),
    mu_wall: str = typer.Option("fit", "--mu-wall", help="Coefficient tube-hole wall: a value "
                                "in [0, 2] or 'fit'."),
    mu_wire_wall: str = typer.Option("fit", "--mu-wire-wall", help="Coefficient wire-hole "
                                     "wall: a value in [0, 2] or 'fit'."),
    mu_static: str = typer.Option(None, "--mu-static", help="Static coefficient: a value "
                                  "(>= mu_wire) or 'fit'; default none (no peak)."),
    first_only: bool = typer.Option(False, "--first-only", help="Fit only the first pull of "
                                    "each pressure plateau."),
    confidence: float = typer.Option(0.95, "--confidence", help="Interval level."),
    accuracy: str = typer.Option(None, help="Squeeze accuracy: draft, standard or fine."),
    n_z: int = typer.Option(defaults.PULLOUT_Z_ELEMENTS, "--n-z",
                            help="Cable elements along the tube (model)."),
    n_path: int = typer.Option(defaults.PULLOUT_PATH_STEPS, "--n-path",
                               help="Load steps of each modelled pull."),
    max_evaluations: int = typer.Option(30, "--max-evaluations",
                                        help="Most model evaluations of the search."),
    columns: str | None = COLUMNS_OPTION,
    skip_mm: float = SKIP_MM_OPTION,
    skip_s: float = SKIP_S_OPTION,
    plateau_tol: float = PLATEAU_TOL_OPTION,
    min_plateau: float = MIN_PLATEAU_OPTION,
    out: OutputOptions = OutputOptions.options(
        plot=(Path | None, typer.Option(None, help="PNG: measured vs fitted curves, "
                                        "residuals."))),
) -> None:
    """Fit mu_wire, mu_wall, mu_wire_wall (and mu_static) to measured pulls, with intervals."""
    from exofric.friction import PullFitSettings, fit_pullout, pulls_from_reduction

    plot = None if out.plot is None else plot_path(out.plot)
    mat = material.material()
    st = structure.structure(length)
    settings = PullFitSettings(accuracy=accuracy, confidence=confidence, n_z=n_z, n_path=n_path,
                               max_evaluations=max_evaluations)
    reds, _, meta = reduce_files(logs, columns,
                                 settings_from(skip_mm, skip_s, plateau_tol, min_plateau))
    pulls = pulls_from_reduction(reds, first_only=first_only)
    fit = fit_pullout(st, mat, pulls, ends=ends, cable_ea_n=cable_ea,
                      compliance_mm_per_n=compliance_mm_per_n, mu_wall=_fit_or_value(mu_wall),
                      mu_wire_wall=_fit_or_value(mu_wire_wall),
                      mu_static=_fit_or_value(mu_static), settings=settings)
    d = fit.to_dict()
    d["logs"] = [r.source for r in reds]
    if any("SYNTHETIC" in m.upper() for m in meta):
        d["synthetic"] = True
    if plot is not None:
        d["plot"] = str(save_figure(fit.plot(), plot))

    def render() -> None:
        from exofric.cli._common import narrow_table

        t = narrow_table(f"Pull-out fit: {d['n_pulls']} pulls at "
                         + ", ".join(f"{p:.3g}" for p in fit.pressures_mpa) + " MPa",
                         ["coefficient", "estimate", f"{100 * confidence:g} % interval",
                          "status"])
        for _, row in fit.to_frame().iterrows():
            if row["status"] == "fitted":
                t.add_row(row["coefficient"], f"{row['estimate']:.4g}",
                          f"[{row['ci_low']:.4g}, {row['ci_high']:.4g}]", "fitted")
            elif row["status"] == "given":
                t.add_row(row["coefficient"], f"{row['estimate']:.4g}", "", "given")
            else:
                t.add_row(row["coefficient"], "-", "-", "not identifiable")
        console.print(t)
        console.print(f"rms residual {fit.rmse_n:.3g} N; intervals pull-clustered (CR2)")
        if fit.identifiability_reason:
            console.print(f"not identifiable: {fit.identifiability_reason}")
        for n in fit.notes:
            console.print(n)
        if "plot" in d:
            console.print(f"wrote {d['plot']}")

    emit(d, out.as_json, render)


def register(app: typer.Typer) -> None:
    """Add ``fit-pullout`` to ``app``."""
    app.command("fit-pullout")(fit_pullout_cmd)
