"""``exofric ring``: the ring tensile test by FE (force vs pin displacement)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import typer

from exofric.cli._common import console, emit, narrow_table, plot_path, save_figure
from exofric.cli._options import MaterialOptions, OutputOptions, grouped

#: Most load steps the CLI accepts (each a converged output point).
MAX_STEPS = 200


def _sizes(ring_od: float, ring_id: float, width: float, pin: float) -> tuple[float, ...]:
    """The ring's and the pins' sizes (mm), checked: ID < OD, pin < ID."""
    from exofric.errors import InputError
    from exofric.geometry import check_size_mm

    od_ = check_size_mm("ring_od", ring_od, "ring outer diameter")
    id_mm = check_size_mm("ring_id", ring_id, "ring inner diameter")
    w = check_size_mm("width", width, "ring width")
    pin_ = check_size_mm("pin", pin, "pin diameter")
    if id_mm >= od_:
        raise InputError(f"ring_id must be < --od ({od_:g} mm), got {id_mm:g}",
                         param="ring_id")
    if pin_ >= id_mm:
        raise InputError(f"pin must be < --id ({id_mm:g} mm), got {pin_:g}",
                         param="pin")
    return od_, id_mm, w, pin_


def _render(res: Any, out: dict[str, Any]) -> None:
    """The human-readable answer of ``ring``."""
    g = res.geometry
    t = narrow_table(
        f"Ring test {g['ring_od_mm']:g}/{g['ring_id_mm']:g} mm x {g['width_mm']:g} mm, "
        f"pins {g['pin_mm']:g} mm, {res.section} ({res.dofs} dofs, "
        f"{res.solve_time_s:.1f} s)",
        ["pin displacement (mm)", "force (N)", "energy (N mm)", "max stretch",
         "contact arc (deg)"])
    for row in zip(out["displacement_mm"], out["force_n"], out["strain_energy_n_mm"],
                   out["max_stretch"], out["contact_arc_deg"], strict=True):
        t.add_row(f"{row[0]:g}", f"{row[1]:.4g}", f"{row[2]:.4g}", f"{row[3]:.3f}",
                  f"{row[4]:.1f}")
    console.print(t)
    if "measured" in out:
        console.print(f"measured vs FE: RMS deviation "
                      f"{out['measured']['rms_deviation_n']:.3g} N")
    console.print(f"[dim]width/wall = {g['width_to_wall']:.2f}; force = one pin's "
                  "load on the ring.[/dim]")
    if "plot" in out:
        console.print(f"wrote {out['plot']}")


@grouped
def ring_cmd(
    ring_od: float = typer.Option(..., "--od", help="Ring (tube) outer diameter (mm)."),
    ring_id: float = typer.Option(..., "--id", help="Ring (tube) inner diameter (mm)."),
    width: float = typer.Option(..., "--width", help="Ring width: its axial length (mm)."),
    pin: float = typer.Option(..., "--pin", help="Pin diameter (mm), < --id."),
    material: MaterialOptions = MaterialOptions.options(),
    section: str = typer.Option(
        "plane-stress", help="plane-stress (default: the ring's faces are free; exact for a "
        "narrow ring), generalised-plane-strain (a wide ring: one uniform axial stretch, "
        "no axial force) or plane-strain (a stiffer bound still)."),
    max_displacement: float = typer.Option(
        3.0, help="Largest pin displacement: increase of the pins' separation (mm)."),
    steps: int = typer.Option(
        12, help=f"Output points up to --max-displacement (1..{MAX_STEPS})."),
    data: Path = typer.Option(
        None, help="Measured test (CSV: displacement_mm,force_n): computed at its "
        "displacements, compared and plotted."),
    columns: str = typer.Option(
        None, "--columns", help="Map --data's headers: displacement_mm=Ext,force_n=Load "
        "(units in the keys, e.g. force_kn); headers such as 'Load (N)' need none."),
    n_radial: int = typer.Option(None, help="Mesh: elements through the wall."),
    n_circ: int = typer.Option(None, help="Mesh: elements around the quarter ring."),
    out: OutputOptions = OutputOptions.options(
        plot=(Path | None, typer.Option(None, help="Write a PNG of force vs pin displacement."))),
) -> None:
    """Ring tensile test by FE: force (N) vs pin displacement (mm), quarter model."""
    import numpy as np

    from exofric.errors import InputError, check_range
    from exofric.fe import RING_MESH, RING_SECTIONS, MeshSpec
    from exofric.simulate import ring_test

    plot = None if out.plot is None else plot_path(out.plot)
    od_, id_mm, w, pin_ = _sizes(ring_od, ring_id, width, pin)
    if section not in RING_SECTIONS:
        raise InputError(f"section must be one of {', '.join(RING_SECTIONS)}, got "
                         f"{section!r}", param="section")
    if isinstance(steps, bool) or not 1 <= steps <= MAX_STEPS:
        raise InputError(f"steps must be an integer in [1, {MAX_STEPS}], got {steps}",
                         param="steps")
    mat = material.material()
    measured = None
    md = mf = np.empty(0)
    if data is not None:
        from exofric.io import parse_column_map, read_ring_test

        mapping = (parse_column_map(columns, columns=("displacement_mm", "force_n"))
                   if columns else None)
        md, mf = read_ring_test(data, mapping)
        measured = (md.tolist(), mf.tolist())
        disp = md[md > 0.0] if np.any(md > 0.0) else md
    else:
        check_range("max_displacement", max_displacement, 0.0, 2.0 * od_, lo_open=True)
        disp = np.linspace(0.0, max_displacement, steps + 1)[1:]
    mesh = None
    if n_radial is not None or n_circ is not None:
        mesh = MeshSpec(RING_MESH.n_radial if n_radial is None else n_radial,
                        RING_MESH.n_circ if n_circ is None else n_circ,
                        grading=RING_MESH.grading)
    res = ring_test(od_, id_mm, w, pin_, disp, mat, section=section, mesh=mesh)
    d = res.to_dict()
    if measured is not None:
        fe_at = np.interp(md, np.concatenate([[0.0], res.displacement_mm]),
                          np.concatenate([[0.0], res.force_n]))
        dev = fe_at - mf
        d["measured"] = {"displacement_mm": md.tolist(),
                         "force_n": mf.tolist(),
                         "fe_force_n": fe_at.tolist(),
                         "rms_deviation_n": float(np.sqrt(np.mean(dev**2)))}
    if plot is not None:
        from exofric.plots import plot_ring_test

        d["plot"] = str(save_figure(plot_ring_test(res, measured=measured).figure, plot))
    emit(d, out.as_json, lambda: _render(res, d))


def register(app: typer.Typer) -> None:
    """Add the ``ring`` command."""
    app.command("ring")(ring_cmd)
