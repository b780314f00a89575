"""``exofric pullout``: the wire pulled through the tube (issue 39). Units: N, mm, MPa."""

from __future__ import annotations

from pathlib import Path

import typer

from exofric import defaults
from exofric.cli._common import console, emit, plot_path, save_figure
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
def pullout_cmd(
    structure: StructureOptions = StructureOptions.options(),
    length: float = typer.Option(116.0, help="Tube length L (mm)."),
    pressure: float = typer.Option(..., help="Tube pressure P (MPa)."),
    friction: ContactFrictionOptions = ContactFrictionOptions.options(),
    cable_ea: float = typer.Option(defaults.CABLE_EA_N, "--cable-ea",
                                   help="Cable axial stiffness EA (N); default: 1.6 mm 7x7 "
                                   "steel, ~110 GPa on ~1.2 mm^2."),
    ends: str = typer.Option("fixed", "--ends", help=PULLOUT_ENDS_HELP),
    displacement: float = typer.Option(1.0, help="Pulled-end amplitude D (mm), <= L."),
    cycles: int = typer.Option(1, help="Back-and-forth cycles D -> -D -> D."),
    section: bool = typer.Option(False, "--section", help="Only the per-unit-length "
                                 "problem (N/mm vs mm)."),
    material: MaterialOptions = MaterialOptions.options(),
    accuracy: str = typer.Option(None, help="Squeeze accuracy: draft, standard or fine."),
    out: OutputOptions = OutputOptions.options(
        plot=(Path | None, typer.Option(None, help="PNG: force against displacement."))),
) -> None:
    """Pull the wire through the inflated tube: breakaway, sliding, hysteresis (N, mm)."""
    from exofric.simulate import pullout

    plot = None if out.plot is None else plot_path(out.plot)
    setup = pullout_setup(structure.structure(length), material, friction, cable_ea, ends,
                          accuracy)
    res = pullout(setup, pressure, displacement_mm=displacement, cycles=cycles, section=section)
    d = res.to_dict()
    if plot is not None:
        d["plot"] = str(save_figure(res.plot().figure, plot))

    def render() -> None:
        if section:
            console.print(f"section at P = {pressure:g} MPa: initial stiffness "
                          f"{d['initial_stiffness_n_per_mm2']:.4g} N/mm per mm, sliding "
                          f"{d['sliding_force_n_per_mm']:.4g} N/mm, full slip at "
                          + ("(not reached)" if d["slip_displacement_mm"] is None
                             else f"{d['slip_displacement_mm']:.4g} mm"))
        else:
            console.print(f"P = {pressure:g} MPa, L = {length:g} mm: breakaway "
                          f"{d['static_force_n']:.2f} N, whole length sliding "
                          f"{d['sliding_force_n']:.2f} N (EA {cable_ea:.3g} N)")
        for n in d.get("notes", []):
            console.print(n)
        if "plot" in d:
            console.print(f"wrote {d['plot']}")

    emit(d, out.as_json, render)


def register(app: typer.Typer) -> None:
    """Add the ``pullout`` command."""
    app.command("pullout")(pullout_cmd)
