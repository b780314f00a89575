"""``exofric calibrate``: Shore hardness (and tube ID) from an inflation test (paper §3.3)."""

from __future__ import annotations

from pathlib import Path

import typer

from exofric.cli._common import (
    JSON_OPTION,
    console,
    emit,
    kv_table,
    narrow_table,
    parse_floats,
    plot_path,
    save_figure,
)


def register(app: typer.Typer) -> None:
    """Add the ``calibrate`` command to ``app``."""

    @app.command("calibrate")
    def calibrate_cmd(
        data: Path = typer.Option(
            ..., "--data", help="CSV with pressure_mpa,outer_diameter_mm[,shore] (MPa, mm); "
            "with a shore column only the tube ID is fitted (known hardness).",
        ),
        tube_od: float = typer.Option(
            ..., "--tube-od", help="Undeformed tube outer diameter (mm)."
        ),
        tube_id: float | None = typer.Option(
            None, "--tube-id", help="Tube inner diameter (mm): fixed for bisection/bounded, "
            "start value for joint/known hardness.",
        ),
        fit_tube_id: bool = typer.Option(
            False, "--fit-tube-id", help="Fit the tube inner diameter too (method joint)."
        ),
        method: str | None = typer.Option(
            None, "--method", help="bisection (paper), bounded, joint or known-hardness "
            "(default: known-hardness with a shore column, joint with --fit-tube-id, else "
            "bisection).",
        ),
        bracket: str = typer.Option("60,70", "--bracket", help="Shore A bracket lo,hi."),
        tol_pct: float = typer.Option(
            0.5, "--tol-pct", help="Bisection stop: average relative diameter error (%)."
        ),
        model: str = typer.Option(
            "fe", "--model", help="Forward model: fe (2D FE), 1d (radial BVP) or paper-table1 "
            "(the paper's ANSYS columns, no simulation).",
        ),
        c10_convention: str = typer.Option(
            "eq4", "--c10-convention", help="eq4 (C10 = G/2/1.05) or paper-slip (the printed "
            "Table 2 value C10 = G/2/1.005).",
        ),
        correlation: str = typer.Option(
            "paper", "--correlation", help="Shore -> E0 correlation: paper (Eq 3), gent, qi, "
            "astm-log10.",
        ),
        plot: Path | None = typer.Option(
            None, "--plot", help="Write Fig 5b (diameter vs pressure with trial curves) here."
        ),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Identify Shore A hardness (and tube ID, mm) from inflation data. MPa, mm, %."""
        import numpy as np

        from exofric.calibration import InflationData, calibrate
        from exofric.errors import InputError
        from exofric.io import read_inflation_table

        if plot is not None:
            plot = plot_path(plot)
        lohi = parse_floats("--bracket", bracket)
        if len(lohi) != 2:
            raise InputError(f"--bracket must be two Shore A values lo,hi, got {bracket!r}")
        if c10_convention not in ("eq4", "paper-slip"):
            raise InputError(f"--c10-convention must be eq4 or paper-slip, got {c10_convention!r}")
        frame = read_inflation_table(data)
        d = InflationData.from_frame(frame)
        from exofric import paper

        paper_data = bool(np.array_equal(
            frame["outer_diameter_mm"].to_numpy(float),
            np.asarray(paper.table1()["test_outer_diameter_mm"], float)))
        res = calibrate(
            d, tube_od, tube_id_mm=tube_id, method=method, fit_tube_id=fit_tube_id,
            bracket=(lohi[0], lohi[1]), tol_pct=tol_pct, model=model, correlation=correlation,
            c10_convention=c10_convention,  # type: ignore[arg-type]
        )
        out = res.to_dict()
        if paper_data:
            t1 = paper.table1()
            out["paper_table1_average_error_pct"] = dict(
                zip((f"{x:g}" for x in t1["simulated_shore"]), t1["average_error_pct"],
                    strict=True))
        if plot is not None:
            out["plot_path"] = str(save_figure(res.plot(), plot))

        def render() -> None:
            def pm(v: float | None, se: float | None, fmt: str) -> str:
                if v is None:
                    return "known"
                return format(v, fmt) + ("" if se is None else f" ± {se:{fmt}}")

            rows = [
                ("method / model", f"{res.method} / {res.model}", ""),
                ("Shore A hardness", pm(res.shore, res.shore_stderr, ".3f"), "Shore A"),
                ("tube inner diameter", pm(res.tube_id_mm, res.tube_id_stderr_mm, ".4f"), "mm"),
                ("average error", f"{res.average_error_pct:.3f}", "%"),
                ("max error", f"{res.max_error_pct:.3f}", "%"),
                ("status", res.status, ""),
                ("model evaluations", str(res.n_model_calls), f"in {res.elapsed_s:.2f} s"),
            ]
            if res.correlation is not None:
                rows.append(("correlation(Shore, ID)", f"{res.correlation:.4f}", ""))
            if res.material is not None:
                m = res.material
                rows.append(("C10 / C01 / d",
                             f"{m.c10_mpa:.5f} / {m.c01_mpa:.6f} / {m.d_per_mpa:.6f}",
                             "MPa / MPa / 1/MPa"))
            console.print(kv_table("Calibration from inflation test", rows))
            t1 = paper.table1()
            printed = dict(zip(t1["simulated_shore"], t1["average_error_pct"], strict=True))
            beside = paper_data and abs(res.tube_od_mm - t1["tube_od_mm"]) < 1e-9
            cols = ["trial", "Shore A", "ID mm", "avg err %"] + (["Table 1 %"] if beside else [])
            h = narrow_table("History: every trial, in order", cols)
            for i, tr in enumerate(res.history):
                row = [str(i + 1), "-" if tr.shore is None else f"{tr.shore:.4g}",
                       f"{tr.tube_id_mm:.4f}", f"{tr.average_error_pct:.3f}"]
                if beside:
                    row.append(f"{printed[tr.shore]:g}" if tr.shore in printed else "")
                h.add_row(*row)
            console.print(h)
            if beside:
                console.print("Table 1 %: the paper's ANSYS average error at that Shore value "
                              "(its ID is not printed: docs/paper-notes.md)")
            for note in res.notes:
                console.print(f"note: {note}")
            if plot is not None:
                console.print(f"plot: {out['plot_path']}")

        emit(out, as_json, render)
