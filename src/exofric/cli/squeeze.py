"""``exofric squeeze``: tube-wire-hole contact, squeezing force N(P) (paper Figs 6-7)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, ClassVar

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
from exofric.cli._options import MaterialOptions, OptionGroup, StructureOptions, grouped

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

class _Mesh(OptionGroup):
    """An explicit mesh (elements through the wall and around the half tube, grading) and the
    contact penalty (N/mm^3)."""

    n_radial: int | None
    n_circ: int | None
    grading: float
    penalty: float
    OPTIONS: ClassVar[dict[str, Any]] = {
        "n_radial": typer.Option(None, help="Explicit mesh: elements through the wall (no error "
                                 "estimate)."),
        "n_circ": typer.Option(None, help="Explicit mesh: elements around the half tube."),
        "grading": typer.Option(defaults.SQUEEZE_MESH["grading"],
                                help="Explicit mesh: element size ratio toward the wire."),
        "penalty": typer.Option(defaults.CONTACT_PENALTY_N_PER_MM3,
                                help="Contact penalty (N/mm^3)."),
    }

    def spec(self) -> Any:
        """The :class:`~exofric.fe.MeshSpec` asked for, or None (the accuracy level's)."""
        if self.n_radial is None and self.n_circ is None:
            return None
        from exofric.fe import MeshSpec

        return MeshSpec(defaults.SQUEEZE_MESH["n_radial"] if self.n_radial is None
                        else self.n_radial,
                        defaults.SQUEEZE_MESH["n_circ"] if self.n_circ is None else self.n_circ,
                        grading=self.grading)


class _SectionFriction(OptionGroup):
    """Coulomb friction in the section's plane (unitless): tube-hole wall and tube-wire."""

    mu_wall: float
    mu_wire: float
    OPTIONS: ClassVar[dict[str, Any]] = {
        "mu_wall": typer.Option(
            0.0, "--mu-wall", help="Coulomb friction coefficient tube-hole wall (silicone on "
            "aluminium) in the section's plane, [0, 2]; 0: frictionless (the paper)."),
        "mu_wire": typer.Option(
            0.0, "--mu-wire", help="Coulomb friction coefficient tube-wire (silicone on steel) "
            "in the section's plane, [0, 2]; 0: frictionless (the paper)."),
    }


class _Files(OptionGroup):
    """What squeeze writes: figures (PNG), the VTU of the last state, and --json."""

    plot: Path | None
    contact_plot: Path | None
    vtu: Path | None
    as_json: bool
    OPTIONS: ClassVar[dict[str, Any]] = {
        "plot": typer.Option(None, help="PNG: deformed sections (Fig 6) and N(P) (Fig 7)."),
        "contact_plot": typer.Option(
            None, "--contact-plot", help="PNG: contact pressure (and friction traction) along "
            "the wire's and the wall's contact arcs at the last pressure (MPa vs mm)."),
        "vtu": typer.Option(None, help="VTU of the half section at the last pressure "
                            "(with contact pressures as point data)."),
        "as_json": JSON_OPTION,
    }


def _render(res: Any, st: Any, p: list[float], out: dict[str, Any]) -> None:
    """The human-readable answer of ``squeeze``."""
    from rich.table import Table

    m = res.mesh
    t = Table(
        title=f"Squeeze: D={st.hole_mm:g} d1={st.tube_od_mm:g} ID={st.tube_id_mm:g} "
        f"d2={st.wire_mm:g} mm, L={st.length_mm:g} mm; {res.estimate.accuracy} "
        f"({m.n_radial} x {m.n_circ} mesh, {res.dofs} dofs, {res.solve_time_s:.2f} s); "
        f"gravity {res.gravity}"
        + (f"; wire at {res.wire_angle_deg:g} deg" if res.wire_angle_deg else "")
    )
    ndir = res.squeeze_force_direction_deg if res.wire_angle_deg else None
    est = res.estimate.pct
    unreliable = set(res.estimate.unreliable_outputs)
    cols = ["P (MPa)", "N (N)", "N (N/mm)", "wall (N)", "wire half-width (mm)"]
    if ndir is not None:
        cols.append("N dir. (deg)")
    fric = res.mu_wall > 0.0 or res.mu_wire > 0.0
    s_wire = res.contact.wire_pressure_integral_n_per_mm
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
            f"{res.contact.wire_contact_halfwidth_mm[i]:.3f}",
        ]
        if ndir is not None:
            row.append("-" if not math.isfinite(ndir[i]) else f"{ndir[i]:.2f}")
        if s_wire is not None:
            row.append(f"{s_wire[i]:.4f}")
        if fric:
            for sf in (res.contact.stick_fraction_wire, res.contact.stick_fraction_wall):
                v = float("nan") if sf is None else float(sf[i])
                row.append("-" if not math.isfinite(v) else f"{100 * v:.0f}%")
        if axial:
            assert res.axial_stretch is not None
            row.append(f"{res.axial_stretch[i]:.4f}")
        if est is not None:
            row.append("-" if res.squeeze_force_n_per_mm[i] == 0.0 and est[i] == 0.0
                       else f"{est[i]:.2g}" + ("*" if i in unreliable else ""))
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
        cm = res.estimate.mesh
        assert cm is not None
        console.print(f"[dim]error estimate: 3 x |N - N({cm.n_radial} x {cm.n_circ} "
                      "nested mesh)| (two-grid GCI); --accuracy fine for less.[/dim]")
        if unreliable:
            console.print(f"* estimate unreliable at {len(unreliable)} pressure(s): the "
                          "nested mesh does not resolve the wire contact patch (or only one "
                          "mesh touches the wire); the error may be larger: --accuracy fine.")
    for k in ("plot", "contact_plot", "vtu"):
        if k in out:
            console.print(f"wrote {out[k]}")


@grouped
def squeeze_cmd(
    structure: StructureOptions = StructureOptions.options(),
    material: MaterialOptions = MaterialOptions.options(),
    length: float = typer.Option(116.0, help="Tube length L (mm) for total forces."),
    pressures: str = typer.Option(DEFAULT_P, help="Increasing pressures (MPa)."),
    accuracy: str = typer.Option(
        None, help="Accuracy level: draft, standard or fine (two nested meshes, error "
        f"estimate per pressure; default {defaults.ACCURACY}). Not with --n-radial/--n-circ."),
    gravity: str = typer.Option(
        defaults.GRAVITY, help="The tube's weight: none, toward-wall (resting on the hole "
        "wall) or toward-wire (hanging on the wire)."),
    mesh: _Mesh = _Mesh.options(),
    wire_angle: float = typer.Option(
        0.0, "--wire-angle", help="Wire position: degrees from the top of the hole (opposite "
        "the tube's contact with the wall), |angle| < 90, positive toward +x; 0 is the half "
        "model, any other angle the full section (2-3x the CPU time; gravity none only). "
        "N is then the magnitude of the tube's resultant force on the wire; its direction "
        "is reported."),
    friction: _SectionFriction = _SectionFriction.options(),
    ends: str = typer.Option(
        "plane-strain", "--ends", help="Tube ends: plane-strain (the paper's), closed (end "
        "caps carry P x cavity area) or open (no axial force); closed/open add a uniform "
        "axial stretch and give forces per mm of tube in the hole."),
    files: _Files = _Files.options(),
) -> None:
    """Squeezing force between tube and wire vs pressure (N, N/mm, MPa, mm)."""
    from exofric.simulate import squeeze

    plot = None if files.plot is None else plot_path(files.plot)
    contact_plot = None if files.contact_plot is None else plot_path(files.contact_plot)
    vtu = None if files.vtu is None else out_file("vtu", files.vtu)
    mat = material.material()
    st = structure.structure(length)
    p = parse_floats("--pressures", pressures)
    res = squeeze(st, mat, p, accuracy=accuracy, mesh=mesh.spec(), gravity=gravity,
                  penalty=mesh.penalty, wire_angle_deg=wire_angle, mu_wall=friction.mu_wall,
                  mu_wire=friction.mu_wire, ends=ends)
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
    emit(out, files.as_json, lambda: _render(res, st, p, out))


def register(app: typer.Typer) -> None:
    """Add the ``squeeze`` command."""
    app.command("squeeze")(squeeze_cmd)
