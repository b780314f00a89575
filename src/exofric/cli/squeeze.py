"""``exofric squeeze``: tube-wire-hole contact, squeezing force N(P) (paper Figs 6-7)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import typer

from exofric import defaults
from exofric.cli._common import (
    JSON_OPTION,
    console,
    emit,
    out_file,
    parse_floats,
    plot_path,
    save_figure,
    write_outputs,
)
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

DEFAULT_P = ",".join(f"{0.05 * i:.2f}" for i in range(1, 13))


def _paper_beside(st: Any, p: list[float], n: Any) -> str:
    """The paper's N(0.6 MPa) beside ours when this is its base geometry (else "")."""
    from exofric import paper
    from exofric.geometry import BASE

    same = all(abs(getattr(st, k) - getattr(BASE, k)) < 1e-9 for k in
               ("hole_mm", "tube_od_mm", "wire_mm", "length_mm")) and \
        abs(st.tube_id_mm - BASE.tube_id_mm) < 0.01
    if not same or not any(abs(x - 0.6) < 1e-9 for x in p):
        return ""
    ours = float(n[[abs(x - 0.6) < 1e-9 for x in p].index(True)])
    theirs = paper.scalar("base_squeeze_force_at_0_6_mpa_n")
    return (f"paper (Sec 3.4, Fig 7): N = {theirs:g} N at 0.6 MPa for this base group; "
            f"exofric {ours:.2f} N ({100 * (ours / theirs - 1):+.1f} %; why: "
            "docs/paper-notes.md)")


def register(app: typer.Typer) -> None:
    """Add the ``squeeze`` command."""

    @app.command("squeeze")
    def squeeze_cmd(
        hole: float = HOLE_OPTION,
        tube_od: float = TUBE_OD_OPTION,
        tube_id: float = TUBE_ID_OPTION,
        wire: float = WIRE_OPTION,
        shore: float = SHORE_OPTION,
        c10: float = C10_OPTION,
        c01: float = C01_OPTION,
        d: float = D_OPTION,
        model: str = MODEL_OPTION,
        params: str = PARAMS_OPTION,
        length: float = typer.Option(116.0, help="Tube length L (mm) for total forces."),
        pressures: str = typer.Option(DEFAULT_P, help="Increasing pressures (MPa)."),
        accuracy: str = typer.Option(
            None, help="Accuracy level: draft, standard or fine (two nested meshes, error "
            f"estimate per pressure; default {defaults.ACCURACY}). Not with --n-radial/--n-circ."),
        gravity: str = typer.Option(
            defaults.GRAVITY, help="The tube's weight: none, toward-wall (resting on the hole "
            "wall) or toward-wire (hanging on the wire)."),
        n_radial: int = typer.Option(None, help="Explicit mesh: elements through the wall "
                                     "(no error estimate)."),
        n_circ: int = typer.Option(None, help="Explicit mesh: elements around the half tube."),
        grading: float = typer.Option(defaults.SQUEEZE_MESH["grading"],
                                      help="Explicit mesh: element size ratio toward the wire."),
        penalty: float = typer.Option(defaults.CONTACT_PENALTY_N_PER_MM3,
                                      help="Contact penalty (N/mm^3)."),
        wire_angle: float = typer.Option(
            0.0, "--wire-angle", help="Wire position: degrees from the top of the hole (opposite "
            "the tube's contact with the wall), |angle| < 90, positive toward +x; 0 is the half "
            "model, any other angle the full section (2-3x the CPU time; gravity none only). "
            "N is then the magnitude of the tube's resultant force on the wire; its direction "
            "is reported."),
        mu_wall: float = typer.Option(
            0.0, "--mu-wall", help="Coulomb friction coefficient tube-hole wall (silicone on "
            "aluminium) in the section's plane, [0, 2]; 0: frictionless (the paper)."),
        mu_wire: float = typer.Option(
            0.0, "--mu-wire", help="Coulomb friction coefficient tube-wire (silicone on steel) "
            "in the section's plane, [0, 2]; 0: frictionless (the paper)."),
        ends: str = typer.Option(
            "plane-strain", "--ends", help="Tube ends: plane-strain (the paper's), closed (end "
            "caps carry P x cavity area) or open (no axial force); closed/open add a uniform "
            "axial stretch and give forces per mm of tube in the hole."),
        plot: Path = typer.Option(None, help="PNG: deformed sections (Fig 6) and N(P) (Fig 7)."),
        contact_plot: Path = typer.Option(
            None, "--contact-plot", help="PNG: contact pressure (and friction traction) along "
            "the wire's and the wall's contact arcs at the last pressure (MPa vs mm)."),
        vtu: Path = typer.Option(None, help="VTU of the half section at the last pressure "
                                 "(with contact pressures as point data)."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Squeezing force between tube and wire vs pressure (N, N/mm, MPa, mm)."""
        from exofric.fe import MeshSpec
        from exofric.geometry import Structure
        from exofric.simulate import squeeze

        plot = None if plot is None else plot_path(plot)
        contact_plot = None if contact_plot is None else plot_path(contact_plot)
        vtu = None if vtu is None else out_file("vtu", vtu)
        mat = material_from_options(shore, c10, c01, d, model=model, params=params)
        st = Structure(hole, tube_od, tube_id, wire, length)
        p = parse_floats("--pressures", pressures)
        mesh = None
        if n_radial is not None or n_circ is not None:
            mesh = MeshSpec(defaults.SQUEEZE_MESH["n_radial"] if n_radial is None else n_radial,
                            defaults.SQUEEZE_MESH["n_circ"] if n_circ is None else n_circ,
                            grading=grading)
        res = squeeze(st, mat, p, accuracy=accuracy, mesh=mesh, gravity=gravity,
                      penalty=penalty, wire_angle_deg=wire_angle, mu_wall=mu_wall,
                      mu_wire=mu_wire, ends=ends)
        out = res.to_dict()
        if _paper_beside(st, p, res.squeeze_force_n):
            from exofric import paper

            out["paper_squeeze_force_at_0_6_mpa_n"] = paper.scalar(
                "base_squeeze_force_at_0_6_mpa_n")
        from exofric.plots import plot_squeeze

        out.update(write_outputs(res, plot, vtu, plot_squeeze))
        if contact_plot is not None:
            from exofric.plots import plot_contact_pressure

            out["contact_plot"] = str(save_figure(plot_contact_pressure(res).figure,
                                                  contact_plot))

        def render() -> None:
            from rich.table import Table

            m = res.mesh
            t = Table(
                title=f"Squeeze: D={hole:g} d1={tube_od:g} ID={tube_id:g} d2={wire:g} mm, "
                f"L={length:g} mm; {res.accuracy} ({m.n_radial} x {m.n_circ} mesh, "
                f"{res.dofs} dofs, {res.solve_time_s:.2f} s); gravity {res.gravity}"
                + (f"; wire at {res.wire_angle_deg:g} deg" if res.wire_angle_deg else "")
            )
            ndir = res.squeeze_force_direction_deg if res.wire_angle_deg else None
            est = res.n_error_estimate_pct
            cols = ["P (MPa)", "N (N)", "N (N/mm)", "wall (N)", "wire half-width (mm)"]
            if ndir is not None:
                cols.append("N dir. (deg)")
            fric = res.mu_wall > 0.0 or res.mu_wire > 0.0
            s_wire = res.wire_pressure_integral_n_per_mm
            if s_wire is not None:
                cols.append("S_wire (N/mm)")
            if fric:
                cols += ["stick wire", "stick wall"]
            axial = res.ends != "plane-strain" and res.axial_stretch is not None
            if axial:
                cols.append("axial stretch")
            if est is not None:
                cols.append("N error est. (%)")
            for c in cols:
                t.add_column(c, justify="right")
            for i in range(len(p)):
                row = [
                    f"{p[i]:g}",
                    f"{res.squeeze_force_n[i]:.2f}",
                    f"{res.squeeze_force_n_per_mm[i]:.4f}",
                    f"{res.wall_force_n[i]:.2f}",
                    f"{res.wire_contact_halfwidth_mm[i]:.3f}",
                ]
                if ndir is not None:
                    row.append("-" if not math.isfinite(ndir[i]) else f"{ndir[i]:.2f}")
                if s_wire is not None:
                    row.append(f"{s_wire[i]:.4f}")
                if fric:
                    for sf in (res.stick_fraction_wire, res.stick_fraction_wall):
                        v = float("nan") if sf is None else float(sf[i])
                        row.append("-" if not math.isfinite(v) else f"{100 * v:.0f}%")
                if axial:
                    assert res.axial_stretch is not None
                    row.append(f"{res.axial_stretch[i]:.4f}")
                if est is not None:
                    row.append("-" if res.squeeze_force_n_per_mm[i] == 0.0 and est[i] == 0.0
                               else f"{est[i]:.2g}")
                t.add_row(*row)
            console.print(t)
            if fric:
                console.print(f"Coulomb friction in the section: mu_wall {res.mu_wall:g} "
                              f"(tube-hole), mu_wire {res.mu_wire:g} (tube-wire); S_wire = "
                              "integral of the tube-wire contact pressure over the arc")
            onset = res.contact_onset_pressure_mpa
            if axial:
                console.print(f"{res.ends} ends: uniform axial stretch (generalised plane "
                              "strain); forces per mm of deformed tube, the length in the hole")
            console.print(
                f"contact onset: {onset:.4f} MPa (bracketed to 2e-4 MPa)"
                if onset is not None
                else "the tube does not reach the wire in this pressure range"
            )
            paper_n = _paper_beside(st, p, res.squeeze_force_n)
            if paper_n:
                console.print(paper_n)
            if est is not None:
                cm = res.estimate_mesh
                assert cm is not None
                console.print(f"[dim]error estimate: 3 x |N - N({cm.n_radial} x {cm.n_circ} "
                              "nested mesh)| (two-grid GCI); --accuracy fine for less.[/dim]")
            for k in ("plot", "contact_plot", "vtu"):
                if k in out:
                    console.print(f"wrote {out[k]}")

        emit(out, as_json, render)
