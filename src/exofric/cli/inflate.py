"""``exofric inflate``: free inflation of the air tube (FE), beside the closed form."""

from __future__ import annotations

from pathlib import Path

import typer

from exofric import defaults
from exofric.cli._common import (
    JSON_OPTION,
    console,
    emit,
    out_file,
    parse_floats,
    plot_path,
    write_outputs,
)
from exofric.cli._options import (
    C01_OPTION,
    C10_OPTION,
    D_OPTION,
    MODEL_OPTION,
    PARAMS_OPTION,
    SHORE_OPTION,
    TUBE_ID_OPTION,
    TUBE_OD_OPTION,
    material_from_options,
)


def register(app: typer.Typer) -> None:
    """Add the ``inflate`` command."""

    @app.command("inflate")
    def inflate_cmd(
        tube_od: float = TUBE_OD_OPTION,
        tube_id: float = TUBE_ID_OPTION,
        shore: float = SHORE_OPTION,
        pressures: str = typer.Option(
            "0.1,0.2,0.3,0.4,0.5,0.6", help="Comma-separated increasing pressures (MPa)."
        ),
        c10: float = C10_OPTION,
        c01: float = C01_OPTION,
        d: float = D_OPTION,
        model: str = MODEL_OPTION,
        params: str = PARAMS_OPTION,
        accuracy: str = typer.Option(
            None, help="Accuracy level: draft, standard or fine (two nested meshes, error "
            f"estimate of the diameters; default {defaults.ACCURACY}). Not with --n-radial."),
        n_radial: int = typer.Option(None, help="Explicit mesh: elements through the wall."),
        n_circ: int = typer.Option(None, help="Explicit mesh: elements around the quarter."),
        plot: Path = typer.Option(None, help="Write a PNG of the deformed section and OD(P)."),
        vtu: Path = typer.Option(None, help="Write the deformed mesh at the last pressure (VTU)."),
        ends: str = typer.Option(
            "plane-strain", "--ends", help="Tube ends: plane-strain (axial stretch 1, the "
            "paper's model), closed (end caps carry P x cavity area) or open (no axial force)."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Free inflation (FE, quarter model): diameters, axial stretch vs pressure (mm, MPa)."""
        from exofric.fe import MeshSpec
        from exofric.geometry import check_size_mm
        from exofric.simulate import inflate

        plot = None if plot is None else plot_path(plot)
        vtu = None if vtu is None else out_file("vtu", vtu)
        check_size_mm("tube_od_mm", tube_od, "tube outer diameter d1")
        check_size_mm("tube_id_mm", tube_id, "tube inner diameter")
        mat = material_from_options(shore, c10, c01, d, model=model, params=params)
        p = parse_floats("--pressures", pressures)
        mesh = None
        if n_radial is not None or n_circ is not None:
            mesh = MeshSpec(defaults.INFLATION_MESH["n_radial"] if n_radial is None else n_radial,
                            defaults.INFLATION_MESH["n_circ"] if n_circ is None else n_circ)
        res = inflate(tube_od, tube_id, mat, p, accuracy=accuracy, mesh=mesh, ends=ends)
        out = res.to_dict()
        from exofric import paper
        from exofric.plots import plot_inflation

        # the paper's tube: Table 1's measured diameters beside ours (table, JSON, plot)
        t1 = paper.table1()
        table1: dict[float, float] = {}
        measured = None
        if abs(tube_od - float(t1["tube_od_mm"])) < 1e-9:
            table1 = dict(zip(t1["pressure_mpa"], t1["test_outer_diameter_mm"], strict=True))
            measured = (t1["pressure_mpa"], t1["test_outer_diameter_mm"], "test, paper Table 1")
            out["paper_table1_test_outer_diameter_mm"] = {f"{k:g}": v for k, v in table1.items()}
        out.update(write_outputs(res, plot, vtu,
                                 lambda r: plot_inflation(r, measured=measured)))

        def render() -> None:
            from rich.table import Table

            t = Table(
                title=f"Free inflation, tube {tube_od:g}/{tube_id:g} mm ({res.dofs} dofs, "
                f"{res.solve_time_s * 1e3:.0f} ms)"
            )
            est = res.outer_diameter_error_estimate_mm
            cols = ["P (MPa)", "OD FE (mm)", "ID FE (mm)", "OD closed form (mm)"]
            cols += ["OD error est. (mm)"] if est is not None else ["Newton it."]
            axial = res.ends != "plane-strain"
            if axial:
                cols += ["axial stretch"]
            if table1:
                cols += ["OD Table 1 test (mm)"]
            for c in cols:
                t.add_column(c, justify="right")
            for i, row in enumerate(zip(
                out["pressure_mpa"],
                out["outer_diameter_mm"],
                out["inner_diameter_mm"],
                out["analytic_outer_diameter_mm"],
                out["newton_iterations"],
                strict=True,
            )):
                last = f"{est[i]:.1e}" if est is not None else str(row[4])
                cells = [f"{row[0]:g}", f"{row[1]:.4f}", f"{row[2]:.4f}", f"{row[3]:.4f}", last]
                if axial:
                    cells.append(f"{out['axial_stretch'][i]:.5f}")
                if table1:
                    cells.append(next((f"{v:g}" for k, v in table1.items()
                                       if abs(k - row[0]) < 1e-9), "-"))
                t.add_row(*cells)
            console.print(t)
            ref = ("incompressible (J = 1), plane strain" if not axial else
                   f"incompressible thick tube, {res.ends} ends (semi-analytic)")
            console.print(f"[dim]{res.symmetry}; ends: {res.ends}. Closed form: {ref}.[/dim]")
            for k in ("plot", "vtu"):
                if k in out:
                    console.print(f"wrote {out[k]}")

        emit(out, as_json, render)
