"""Raw rig logs in the CLI: read, reduce and pool them (``reduce``, ``fit-friction``), and the
options that say how. Units: s, MPa, N, mm.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import typer

from exofric import defaults as D

if TYPE_CHECKING:
    import pandas as pd

    from exofric.friction import ReduceSettings, RigReduction

__all__ = ["COLUMNS_OPTION", "MIN_PLATEAU_OPTION", "PLATEAU_TOL_OPTION", "SKIP_MM_OPTION",
           "SKIP_S_OPTION", "reduce_files", "settings_from"]


def reduce_files(
    paths: list[str], columns: str | None, settings: ReduceSettings
) -> tuple[list[RigReduction], pd.DataFrame, list[str]]:
    """Read and reduce each log; return the reductions, the pooled pulls and the metadata."""
    from exofric.friction import pool_pulls, reduce_log
    from exofric.io import parse_column_map, read_raw_log

    mapping = parse_column_map(columns) if columns else None
    reds: list[RigReduction] = []
    meta: list[str] = []
    for path in paths:
        frame = read_raw_log(path, mapping)
        name = str(frame.attrs.get("source", Path(path).name))
        reds.append(reduce_log(frame, settings, source=name))
        meta += [f"{name}: {line}" for line in frame.attrs.get("metadata", [])]
    return reds, pool_pulls(reds), meta


def settings_from(skip_mm: float, skip_s: float, plateau_tol: float,
                  min_plateau: float) -> ReduceSettings:
    """ReduceSettings from the CLI options (mm, s, MPa, s)."""
    from exofric.friction import ReduceSettings

    return ReduceSettings(skip_mm=skip_mm, skip_s=skip_s, plateau_tol_mpa=plateau_tol,
                          min_plateau_s=min_plateau)


COLUMNS_OPTION = typer.Option(
    None, "--columns", help="Map your headers to exofric's: time=t,pressure_kpa=P1,force_n=Fx "
    "(units: pressure mpa/kpa/pa/bar/mbar/psi, force n/kn/kgf/lbf, displacement mm/m/um/in, "
    "time s/ms/min). Headers such as 'Time (s)', 'Pressure [kPa]' or a units row are read "
    "without it.")
SKIP_MM_OPTION = typer.Option(D.REDUCE_SKIP_MM, "--skip-mm", help="Travel in mm left out at the "
                              "start of each pull (stretch, breakaway) before the steady window.")
SKIP_S_OPTION = typer.Option(D.REDUCE_SKIP_S, "--skip-s", help="Time in s left out at the start "
                             "of each pull when the log has no displacement.")
PLATEAU_TOL_OPTION = typer.Option(D.REDUCE_PLATEAU_TOL_MPA, "--plateau-tol", help="Pressure band "
                                  "of a plateau in MPa (or 2 % of the level if larger).")
MIN_PLATEAU_OPTION = typer.Option(D.REDUCE_MIN_PLATEAU_S, "--min-plateau",
                                  help="Shortest pressure plateau in s.")
