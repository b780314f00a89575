"""``exofric squeeze``: tube-wire-hole contact, squeezing force N(P) (paper Figs 6-7)."""

from __future__ import annotations

from pathlib import Path

import typer

from exofric import defaults
from exofric.cli._common import JSON_OPTION, console, emit, parse_floats, write_outputs
from exofric.cli.inflate import material_from_options

DEFAULT_P = ",".join(f"{0.05 * i:.2f}" for i in range(1, 13))


def register(app: typer.Typer) -> None:
    """Add the ``squeeze`` command."""

    @app.command("squeeze")
    def squeeze_cmd(
        hole: float = typer.Option(..., help="Hole diameter D (mm)."),
        tube_od: float = typer.Option(..., help="Tube outer diameter d1 (mm)."),
        tube_id: float = typer.Option(..., help="Tube inner diameter (mm)."),
        wire: float = typer.Option(..., help="Wire diameter d2 (mm)."),
        shore: float = typer.Option(None, help="Shore A hardness (Eqs 3-6)."),
        c10: float = typer.Option(None, help="Override C10 (MPa)."),
        c01: float = typer.Option(None, help="Override C01 (MPa)."),
        d: float = typer.Option(None, help="Override d (1/MPa)."),
        length: float = typer.Option(116.0, help="Tube length L (mm) for total forces."),
        pressures: str = typer.Option(DEFAULT_P, help="Increasing pressures (MPa)."),
        n_radial: int = typer.Option(defaults.SQUEEZE_MESH["n_radial"],
                                     help="Elements through the wall."),
        n_circ: int = typer.Option(defaults.SQUEEZE_MESH["n_circ"],
                                   help="Elements around the half tube."),
        grading: float = typer.Option(defaults.SQUEEZE_MESH["grading"],
                                      help="Element size ratio, graded toward the wire."),
        penalty: float = typer.Option(defaults.CONTACT_PENALTY_N_PER_MM3,
                                      help="Contact penalty (N/mm^3)."),
        plot: Path = typer.Option(None, help="PNG: deformed sections (Fig 6) and N(P) (Fig 7)."),
        vtu: Path = typer.Option(None, help="VTU of the half section at the last pressure."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Squeezing force between tube and wire vs pressure (N, N/mm, MPa, mm)."""
        from exofric.fe import MeshSpec
        from exofric.geometry import Structure
        from exofric.simulate import squeeze

        mat = material_from_options(shore, c10, c01, d)
        st = Structure(hole, tube_od, tube_id, wire, length)
        p = parse_floats("--pressures", pressures)
        res = squeeze(st, mat, p, mesh=MeshSpec(n_radial, n_circ, grading=grading), penalty=penalty)
        out = res.to_dict()
        from exofric.plots import plot_squeeze

        out.update(write_outputs(res, plot, vtu, plot_squeeze))

        def render() -> None:
            from rich.table import Table

            t = Table(
                title=f"Squeeze: D={hole:g} d1={tube_od:g} ID={tube_id:g} d2={wire:g} mm, "
                f"L={length:g} mm ({res.dofs} dofs, {res.solve_time_s:.2f} s)"
            )
            for c in (
                "P (MPa)",
                "N (N)",
                "N (N/mm)",
                "wall (N)",
                "wire half-width (mm)",
                "penetration (mm)",
                "Newton it.",
            ):
                t.add_column(c, justify="right")
            for i in range(len(p)):
                t.add_row(
                    f"{p[i]:g}",
                    f"{res.squeeze_force_n[i]:.2f}",
                    f"{res.squeeze_force_n_per_mm[i]:.4f}",
                    f"{res.wall_force_n[i]:.2f}",
                    f"{res.wire_contact_halfwidth_mm[i]:.3f}",
                    f"{res.max_penetration_mm[i]:.1e}",
                    str(res.newton_iterations[i]),
                )
            console.print(t)
            onset = res.contact_onset_pressure_mpa
            console.print(
                f"contact onset: {onset:.4f} MPa"
                if onset is not None
                else "the tube does not reach the wire in this pressure range"
            )
            for k in ("plot", "vtu"):
                if k in out:
                    console.print(f"wrote {out[k]}")

        emit(out, as_json, render)
