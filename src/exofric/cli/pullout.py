"""``exofric pullout`` and ``exofric stiffness``: the wire pulled through the tube (issue 39)."""

from __future__ import annotations

from pathlib import Path

import typer

from exofric import defaults
from exofric.cli._common import JSON_OPTION, console, emit, parse_floats, plot_path, save_figure
from exofric.cli._options import (
    C01_OPTION,
    C10_OPTION,
    D_OPTION,
    HOLE_OPTION,
    MODEL_OPTION,
    PARAMS_OPTION,
    SHORE_OPTION,
    TUBE_ID_OPTION,
    TUBE_OD_OPTION,
    WIRE_OPTION,
    material_from_options,
)

ENDS_HELP = ("Tube ends: fixed (end fittings hold the tube axially) or free (the tube may slide "
             "on the hole wall once its wall arc slides).")


def register(app: typer.Typer) -> None:
    """Add the ``pullout`` and ``stiffness`` commands."""

    @app.command("pullout")
    def pullout_cmd(
        hole: float = HOLE_OPTION,
        tube_od: float = TUBE_OD_OPTION,
        tube_id: float = TUBE_ID_OPTION,
        wire: float = WIRE_OPTION,
        length: float = typer.Option(116.0, help="Tube length L (mm)."),
        pressure: float = typer.Option(..., help="Tube pressure P (MPa)."),
        mu_wire: float = typer.Option(..., "--mu-wire", help="Kinetic Coulomb coefficient "
                                      "tube-wire (axial), [0, 2]."),
        mu_wall: float = typer.Option(..., "--mu-wall", help="Coulomb coefficient tube-hole "
                                      "wall, [0, 2]."),
        mu_wire_wall: float = typer.Option(..., "--mu-wire-wall", help="Coulomb coefficient "
                                           "wire-hole wall (line contact), [0, 2]."),
        mu_static: float = typer.Option(None, "--mu-static", help="Static coefficient of the "
                                        "wire's interfaces (>= --mu-wire): breakaway peak."),
        cable_ea: float = typer.Option(defaults.CABLE_EA_N, "--cable-ea",
                                       help="Cable axial stiffness EA (N); default: 1.6 mm 7x7 "
                                       "steel, ~110 GPa on ~1.2 mm^2."),
        ends: str = typer.Option("fixed", "--ends", help=ENDS_HELP),
        displacement: float = typer.Option(1.0, help="Pulled-end amplitude D (mm), <= L."),
        cycles: int = typer.Option(1, help="Back-and-forth cycles D -> -D -> D."),
        section: bool = typer.Option(False, "--section", help="Only the per-unit-length "
                                     "problem (N/mm vs mm)."),
        shore: float = SHORE_OPTION,
        c10: float = C10_OPTION,
        c01: float = C01_OPTION,
        d: float = D_OPTION,
        model: str = MODEL_OPTION,
        params: str = PARAMS_OPTION,
        accuracy: str = typer.Option(None, help="Squeeze accuracy: draft, standard or fine."),
        plot: Path = typer.Option(None, help="PNG: force against displacement."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Pull the wire through the inflated tube: breakaway, sliding, hysteresis (N, mm)."""
        from exofric.geometry import Structure
        from exofric.simulate import pullout

        plot = None if plot is None else plot_path(plot)
        mat = material_from_options(shore, c10, c01, d, model=model, params=params)
        st = Structure(hole, tube_od, tube_id, wire, length)
        res = pullout(st, mat, pressure, mu_wire=mu_wire, mu_wall=mu_wall,
                      mu_wire_wall=mu_wire_wall, mu_static=mu_static, cable_ea_n=cable_ea,
                      ends=ends, displacement_mm=displacement, cycles=cycles, section=section,
                      accuracy=accuracy)
        out = res.to_dict()
        if plot is not None:
            out["plot"] = str(save_figure(res.plot().figure, plot))

        def render() -> None:
            if section:
                s = out
                console.print(f"section at P = {pressure:g} MPa: initial stiffness "
                              f"{s['initial_stiffness_n_per_mm2']:.4g} N/mm per mm, sliding "
                              f"{s['sliding_force_n_per_mm']:.4g} N/mm, full slip at "
                              + ("(not reached)" if s["slip_displacement_mm"] is None
                                 else f"{s['slip_displacement_mm']:.4g} mm"))
            else:
                console.print(f"P = {pressure:g} MPa, L = {length:g} mm: breakaway "
                              f"{out['static_force_n']:.2f} N, whole length sliding "
                              f"{out['sliding_force_n']:.2f} N (EA {cable_ea:.3g} N)")
            for n in out.get("notes", []):
                console.print(n)
            if "plot" in out:
                console.print(f"wrote {out['plot']}")

        emit(out, as_json, render)

    @app.command("stiffness")
    def stiffness_cmd(
        hole: float = HOLE_OPTION,
        tube_od: float = TUBE_OD_OPTION,
        tube_id: float = TUBE_ID_OPTION,
        wire: float = WIRE_OPTION,
        length: float = typer.Option(116.0, help="Tube length L (mm)."),
        pressures: str = typer.Option("0.1,0.2,0.3,0.4,0.5,0.6", help="Pressures (MPa)."),
        radius: float = typer.Option(..., help="Pulley radius / lever arm R (m)."),
        wrap_deg: float = typer.Option(0.0, "--wrap-deg", help="Wrap on the knee arc (deg)."),
        mu_arc: float = typer.Option(0.0, "--mu-arc", help="Coefficient wire-arc (capstan)."),
        mu_wire: float = typer.Option(..., "--mu-wire", help="Kinetic coefficient tube-wire."),
        mu_wall: float = typer.Option(..., "--mu-wall", help="Coefficient tube-hole wall."),
        mu_wire_wall: float = typer.Option(..., "--mu-wire-wall", help="Coefficient wire-wall."),
        mu_static: float = typer.Option(None, "--mu-static", help="Static coefficient."),
        cable_ea: float = typer.Option(defaults.CABLE_EA_N, "--cable-ea", help="Cable EA (N)."),
        ends: str = typer.Option("fixed", "--ends", help=ENDS_HELP),
        displacement: float = typer.Option(3.0, help="Pulled-end travel (mm) of each pull "
                                           "(must pass the breakaway)."),
        shore: float = SHORE_OPTION,
        c10: float = C10_OPTION,
        c01: float = C01_OPTION,
        d: float = D_OPTION,
        model: str = MODEL_OPTION,
        params: str = PARAMS_OPTION,
        accuracy: str = typer.Option(None, help="Squeeze accuracy: draft, standard or fine."),
        plot: Path = typer.Option(None, help="PNG: K(P) and T_break(P)."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """The locked knee: stiffness K(P) (Nm/rad) and breakaway torque T_break(P) (Nm)."""
        from exofric.friction import joint_stiffness
        from exofric.geometry import Structure

        plot = None if plot is None else plot_path(plot)
        mat = material_from_options(shore, c10, c01, d, model=model, params=params)
        st = Structure(hole, tube_od, tube_id, wire, length)
        p = parse_floats("--pressures", pressures)
        res = joint_stiffness(st, mat, p, radius_m=radius, wrap_deg=wrap_deg, mu_arc=mu_arc,
                              mu_wire=mu_wire, mu_wall=mu_wall, mu_wire_wall=mu_wire_wall,
                              mu_static=mu_static, cable_ea_n=cable_ea, ends=ends,
                              displacement_mm=displacement, accuracy=accuracy)
        out = res.to_dict()
        if plot is not None:
            out["plot"] = str(save_figure(res.plot().figure, plot))

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
            if "plot" in out:
                console.print(f"wrote {out['plot']}")

        emit(out, as_json, render)
