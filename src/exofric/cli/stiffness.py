"""``exofric stiffness``: the locked knee, stiffness K(P) (Nm/rad) and breakaway torque
T_break(P) (Nm) of the wire pulled through the tube (issue 39). Units: Nm, rad, m, mm, MPa."""

from __future__ import annotations

from pathlib import Path

import typer

from exofric import defaults
from exofric.cli._common import console, emit, parse_floats, plot_path, save_figure
from exofric.cli._friction_inputs import pullout_setup
from exofric.cli._options import (
    PULLOUT_ENDS_HELP,
    ContactFrictionOptions,
    MaterialOptions,
    OutputOptions,
    StructureOptions,
    grouped,
)

__all__ = ["register"]


@grouped
def stiffness_cmd(
    structure: StructureOptions = StructureOptions.options(),
    length: float = typer.Option(116.0, help="Tube length L (mm)."),
    pressures: str = typer.Option("0.1,0.2,0.3,0.4,0.5,0.6", help="Pressures (MPa)."),
    radius: float = typer.Option(..., help="Pulley radius / lever arm R (m)."),
    wrap_deg: float = typer.Option(0.0, "--wrap-deg", help="Wrap on the knee arc (deg)."),
    mu_arc: float = typer.Option(0.0, "--mu-arc", help="Coefficient wire-arc (capstan)."),
    friction: ContactFrictionOptions = ContactFrictionOptions.options(),
    cable_ea: float = typer.Option(defaults.CABLE_EA_N, "--cable-ea", help="Cable EA (N)."),
    ends: str = typer.Option("fixed", "--ends", help=PULLOUT_ENDS_HELP),
    displacement: float = typer.Option(3.0, help="Pulled-end travel (mm) of each pull "
                                       "(must pass the breakaway)."),
    material: MaterialOptions = MaterialOptions.options(),
    accuracy: str = typer.Option(None, help="Squeeze accuracy: draft, standard or fine."),
    out: OutputOptions = OutputOptions.options(
        plot=(Path | None, typer.Option(None, help="PNG: K(P) and T_break(P)."))),
) -> None:
    """The locked knee: stiffness K(P) (Nm/rad) and breakaway torque T_break(P) (Nm)."""
    from exofric.friction import joint_stiffness

    plot = None if out.plot is None else plot_path(out.plot)
    p = parse_floats("--pressures", pressures)
    setup = pullout_setup(structure.structure(length), material, friction, cable_ea, ends,
                          accuracy)
    res = joint_stiffness(setup, p, radius_m=radius, wrap_deg=wrap_deg, mu_arc=mu_arc,
                          displacement_mm=displacement)
    d = res.to_dict()
    if plot is not None:
        d["plot"] = str(save_figure(res.plot().figure, plot))

    def render() -> None:
        from exofric.cli._common import narrow_table

        t = narrow_table(f"Locked joint, R = {radius:g} m", ["P (MPa)", "K (Nm/rad)",
                                                             "T_break (Nm)", "T_slide (Nm)"])
        for i, pp in enumerate(res.pressure_mpa):
            t.add_row(f"{pp:g}", f"{res.stiffness_nm_per_rad[i]:.4g}",
                      f"{res.breakaway_torque_nm[i]:.3f}", f"{res.sliding_torque_nm[i]:.3f}")
        console.print(t)
        console.print("K: secant stiffness at half the breakaway torque")
        for n in res.notes:
            console.print(n)
        if "plot" in d:
            console.print(f"wrote {d['plot']}")

    emit(d, out.as_json, render)


def register(app: typer.Typer) -> None:
    """Add the ``stiffness`` command."""
    app.command("stiffness")(stiffness_cmd)
