"""CalculiX check of the held end zone's scalar kinematics on an axisymmetric annulus (issue 39).

exofric's held end zones (``exofric.simulate._shear_lag``) solve only the axial displacement
w of the tube, with the section's anti-plane modulus in the plane and a rod modulus E_z = 3 G
along z (the laterally free, incompressible rod): the in-plane displacements that the axial
gradients drive next to a held face are not modelled. This script measures what that
kinematic restriction costs on a geometry where both answers come from the same code, mesh and
elements, so only the kinematics differ (nothing of exofric is used):

* an annulus r_i <= r <= r_o, 0 <= z <= L (axisymmetric ``CAX8`` elements, linear, small
  strain, ``*STATIC`` without NLGEOM), its end faces held axially (u_z = 0, u_r free: the
  end fittings of the 3-D tube decks), the outer surface bonded to a rigid sleeve that moves
  axially by delta over a <= z <= L - a (the wire arc, stuck), the inner surface bonded to
  the immobile ground over the same length (the wall arc, stuck); the gaps a keep the corners
  where a moving bond meets a held face out (there the force diverges like log(1 / h));
* ``"3d"``: isotropic, shear modulus G, Poisson's ratio ``nu`` (0.4995: nearly incompressible;
  CAX8R reduced integration by default, which does not lock);
* ``"scalar"``: the same mesh with u_r = 0 at every node and an orthotropic material with
  D_zzzz = E_z and D_rzrz = G: the equation G (w_rr + w_r / r) + E_z w_zz = 0 of the zone
  model (the other moduli do not enter, their strains are zero);
* the force on the sleeve F (N) of each, and the same with the end faces periodic instead of
  held (the section far from the ends: both kinematics give 2 pi G / ln(r_o / r_i) per mm).
  The end zones' share is F - F_section; its ratio scalar / 3-D is the scalar kinematics'
  excess.

Inflated first (``--inflated``, session 45; stored under ``inflated``): the same held annulus in
the "axial only, wire alone" variant, but hyperelastic (exofric's Mooney-Rivlin constants of
Shore 62.5, ``*HYPERELASTIC``, NLGEOM, ``CAX8R``) and brought first to an inflated state: step
1 pushes the outer surface out radially by ``ur0`` (mm; the hole that the inflating tube fills,
the inner hoop stretch then sqrt(1 + ((r_o + ur0)^2 - r_o^2) / r_i^2)) with the bore pressure P
(follower) and u_z = 0 on the sleeve and the end faces; step 2 pulls the sleeve by delta with
P held, everything else kept. The incremental force per delta against ``ur0`` and P shows what
the inflated state does to the held zone in 3-D; exofric's scalar zone, written in the
reference configuration with A = G I (neo-Hookean exact) and E_z = 3 G, gives the same force
at every ``ur0`` and P (its equation and boundary data there do not change). Measured (ccx
2.20, 2026-11-27): the 3-D force falls from 211.96 / 251.32 N/mm (5 / 10 mm) unstretched to
172.15 / 184.46 at a bore stretch of 1.50 and 153.94 / 160.43 at 1.84, while P = 0.6 MPa moves
it by -0.05 % unstretched and +2.1 / +3.7 % at 1.50; the scalar zone's 171.35 / 183.35 (E_z = 3
G) equals the 3-D force at 1.50; 16 x 250 elements: -1.8 % at 1.50 (docs/formulation.md section
12, "The cause").

Run: ``python benchmarks/calculix_heldzone.py [--inflated] [--json] [--out PATH]`` (24 runs of a
few seconds, ``--inflated`` 26 more of 5-40 s; stored in
``tests/data/ccx_pullout_heldzone.json``, ``--out`` keeps what the file has and replaces the
part that was run). Measured (ccx 2.20): scalar / 3-D
force 0.63 / 0.60 (5 / 10 mm) with wire and wall stuck in every direction, 0.81 / 0.84 with
only the axial displacement held on the sleeve and no ground; the 3-D force falls 1.4-1.8 %
from the 8 x 20-per-mm mesh to 16 x 50-per-mm, the scalar 0.3 %; nu 0.499: 0.5 %.
Units: mm, N, MPa.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import calculix_models as ccxm  # noqa: E402

#: the base group's tube (exofric.geometry.BASE: ID 4.97, OD 8.3 mm), Shore 62.5 (G, MPa)
R_IN_MM, R_OUT_MM = 2.485, 4.15
SHEAR_MPA = 1.333


def _mesh(r_in: float, r_out: float, length: float, nr: int, nz: int
          ) -> tuple[np.ndarray, np.ndarray, dict[tuple[int, int], int]]:
    """Structured 8-node quads (r, z): node coordinates, connectivity, (i, j) -> node id."""
    rr = np.linspace(r_in, r_out, 2 * nr + 1)
    zz = np.linspace(0.0, length, 2 * nz + 1)
    ids: dict[tuple[int, int], int] = {}
    xy = []
    for j, z in enumerate(zz):
        for i, r in enumerate(rr):
            if i % 2 and j % 2:
                continue
            ids[(i, j)] = len(xy) + 1
            xy.append((r, z))
    els = []
    for ez in range(nz):
        for er in range(nr):
            i, j = 2 * er, 2 * ez
            els.append([ids[(i, j)], ids[(i + 2, j)], ids[(i + 2, j + 2)], ids[(i, j + 2)],
                        ids[(i + 1, j)], ids[(i + 2, j + 1)], ids[(i + 1, j + 2)],
                        ids[(i, j + 1)]])
    return np.array(xy), np.array(els), ids


def deck(kind: str, *, length_mm: float = 5.0, gap_mm: float = 0.5, nr: int = 8,
         nz: int = 100, nu: float = 0.4995, ez_over_g: float = 3.0, ends: str = "held",
         element: str = "CAX8R", delta_mm: float = 1e-3, r_in: float = R_IN_MM,
         r_out: float = R_OUT_MM, g: float = SHEAR_MPA, radial: str = "bonded",
         ground: bool = True) -> tuple[str, list[int]]:
    """The deck (text) and the sleeve's nodes; ``kind`` ``"3d"`` or ``"scalar"``, ``ends``
    ``"held"`` (u_z = 0 on both end faces) or ``"periodic"`` (back face = front face)."""
    xy, els, ids = _mesh(r_in, r_out, length_mm, nr, nz)
    nzn = 2 * nz
    top = [ids[(2 * nr, j)] for j in range(nzn + 1)
           if gap_mm - 1e-9 <= xy[ids[(2 * nr, j)] - 1, 1] <= length_mm - gap_mm + 1e-9]
    bottom = [ids[(0, j)] for j in range(nzn + 1)
              if gap_mm - 1e-9 <= xy[ids[(0, j)] - 1, 1] <= length_mm - gap_mm + 1e-9]
    front = [ids[(i, 0)] for i in range(2 * nr + 1)]
    back = [ids[(i, nzn)] for i in range(2 * nr + 1)]
    out = ["*NODE, NSET=NALL\n"]
    out += [f"{k + 1}, {r:.12g}, {z:.12g}\n" for k, (r, z) in enumerate(xy)]
    out.append(f"*ELEMENT, TYPE={element}, ELSET=TUBE\n")
    out += [f"{e + 1}, " + ", ".join(str(v) for v in c) + "\n" for e, c in enumerate(els)]
    for name, s in (("NTOP", top), ("NBOT", bottom), ("NFRONT", front), ("NBACK", back)):
        out += [f"*NSET, NSET={name}\n", ccxm._fmt_set(s)]
    if kind == "3d":
        e = 2.0 * g * (1.0 + nu)
        out.append(f"*MATERIAL, NAME=M\n*ELASTIC\n{e:.12g}, {nu:.12g}\n")
    else:
        ez, big = ez_over_g * g, 3.0 * g
        # D1111 D1122 D2222 D1133 D2233 D3333 D1212 D1313 / D2323 (1 = r, 2 = z, 3 = theta)
        out.append(f"*MATERIAL, NAME=M\n*ELASTIC, TYPE=ORTHO\n{big:.12g}, 0, {ez:.12g}, 0, 0, "
                   f"{big:.12g}, {g:.12g}, {g:.12g},\n{g:.12g}\n")
    out.append("*SOLID SECTION, ELSET=TUBE, MATERIAL=M\n")
    if ends == "periodic":
        rows = [f"2\n{b}, {dof}, 1.0, {f}, {dof}, -1.0\n" for b, f in zip(back, front, strict=True)
                for dof in (1, 2) if not (kind == "scalar" and dof == 1)]
        out.append("*EQUATION\n" + "".join(rows))
    out.append("*STEP\n*STATIC\n*BOUNDARY\n" + f"NTOP, 2, 2, {delta_mm:.12g}\n")
    if radial == "bonded":
        out.append("NTOP, 1, 1\n" + ("NBOT, 1, 1\n" if ground else ""))
    if ground:
        out.append("NBOT, 2, 2\n")
    if ends == "held":
        out.append("NFRONT, 2, 2\nNBACK, 2, 2\n")
    if kind == "scalar":
        out.append("NALL, 1, 1\n")
    out.append("*NODE PRINT, NSET=NTOP, TOTALS=ONLY\nRF\n*END STEP\n")
    return "".join(out), top


def force(kind: str, **options: Any) -> float:
    """Axial force on the sleeve per delta (N/mm; CalculiX's axisymmetric reactions are those
    of a 2 degree segment, times 180: the whole annulus; checked against 2 pi G L / ln(r_o /
    r_i) of the bonded annulus, 1e-6)."""
    text, _ = deck(kind, **options)
    run = ccxm.run_ccx(text, timeout_s=600.0)
    if run.returncode != 0 or not run.dat:
        raise RuntimeError(run.stdout[-2000:])
    tab = ccxm.parse_dat(run.dat)
    key = next(k for k in tab if k[0] == "total force")
    delta = float(options.get("delta_mm", 1e-3))
    return float(180.0 * tab[key]["total"][1] / delta)


#: the contact variants: (name, radial, ground): the wire and wall arcs stuck in every
#: direction (u_r = 0 there too), or holding only the axial displacement, without the wall
VARIANTS = (("stuck, wire and wall", "bonded", True), ("axial only, wire alone", "axial", False))


def study(length_mm: float = 5.0, gap_mm: float = 0.5) -> dict[str, Any]:
    """Scalar against 3-D for each variant (held ends), their mesh convergence, and the
    section's closed form (bonded, periodic-free ends without gaps) (N/mm per mm of delta)."""
    res: dict[str, Any] = {"length_mm": length_mm, "gap_mm": gap_mm, "r_in_mm": R_IN_MM,
                           "r_out_mm": R_OUT_MM, "shear_mpa": SHEAR_MPA, "nu": 0.4995,
                           "variants": []}
    closed = 2.0 * math.pi * SHEAR_MPA / math.log(R_OUT_MM / R_IN_MM) * length_mm
    res["unit_check_scalar_over_closed_form"] = force("scalar", length_mm=length_mm,
                                                      gap_mm=0.0, ends="free") / closed
    nz = int(round(20 * length_mm))
    for name, radial, ground in VARIANTS:
        row: dict[str, Any] = {"variant": name}
        for label, (nr, z) in (("mesh", (8, nz)), ("fine_mesh", (16, int(2.5 * nz)))):
            for kind in ("3d", "scalar"):
                row[f"{kind}_{label}"] = force(kind, length_mm=length_mm, gap_mm=gap_mm,
                                               radial=radial, ground=ground, nr=nr, nz=z)
        row["3d_nu_0.499"] = force("3d", length_mm=length_mm, gap_mm=gap_mm, radial=radial,
                                   ground=ground, nr=8, nz=nz, nu=0.499)
        row["scalar_ez_g"] = force("scalar", length_mm=length_mm, gap_mm=gap_mm,
                                   radial=radial, ground=ground, nr=8, nz=nz, ez_over_g=1.0)
        row["scalar_over_3d"] = row["scalar_fine_mesh"] / row["3d_fine_mesh"]
        res["variants"].append(row)
    return res


#: exofric's Mooney-Rivlin constants of Shore 62.5 (``MooneyRivlin.from_shore(62.5)``:
#: C10, C01 (MPa), D1 (1/MPa); G = 2 (C10 + C01) = 1.3344 MPa)
MR_SHORE_62_5 = (0.6354497354497354, 0.03177248677248677, 0.005995004163197341)


def inner_stretch(ur0: float, r_in: float = R_IN_MM, r_out: float = R_OUT_MM) -> float:
    """Hoop stretch of the bore when the outer surface is pushed out by ``ur0`` (mm) in plane
    strain (incompressible: the wall's area is kept).

    Examples
    --------
    >>> round(inner_stretch(0.85), 3)   # the base tube filling the 10 mm hole
    1.503
    """
    return math.sqrt((r_out + ur0) ** 2 - r_out ** 2 + r_in ** 2) / r_in


def inflated_deck(pressure_mpa: float, ur0_mm: float, *, length_mm: float = 5.0,
                  gap_mm: float = 0.5, nr: int = 8, nz: int = 100, delta_mm: float = 1e-3,
                  constants: tuple[float, float, float] = MR_SHORE_62_5) -> str:
    """The inflated held annulus (module docstring): step 1 inflates (outer surface out by
    ``ur0_mm``, bore pressure ``pressure_mpa``), step 2 pulls the sleeve by ``delta_mm``."""
    xy, els, ids = _mesh(R_IN_MM, R_OUT_MM, length_mm, nr, nz)
    nzn = 2 * nz
    outer = [ids[(2 * nr, j)] for j in range(nzn + 1)]
    top = [n for n in outer if gap_mm - 1e-9 <= xy[n - 1, 1] <= length_mm - gap_mm + 1e-9]
    front = [ids[(i, 0)] for i in range(2 * nr + 1)]
    back = [ids[(i, nzn)] for i in range(2 * nr + 1)]
    bore = [e + 1 for e in range(len(els)) if e % nr == 0]  # face 4 (nodes 4-1) at r_in
    out = ["*NODE, NSET=NALL\n"]
    out += [f"{k + 1}, {r:.12g}, {z:.12g}\n" for k, (r, z) in enumerate(xy)]
    out.append("*ELEMENT, TYPE=CAX8R, ELSET=TUBE\n")
    out += [f"{e + 1}, " + ", ".join(str(v) for v in c) + "\n" for e, c in enumerate(els)]
    for name, s in (("NOUT", outer), ("NTOP", top), ("NFRONT", front), ("NBACK", back)):
        out += [f"*NSET, NSET={name}\n", ccxm._fmt_set(s)]
    out.append(ccxm._material(*constants, "TUBE"))
    out.append("*STEP, NLGEOM, INC=10000\n*STATIC\n0.05, 1.0, 1e-6, 0.1\n*BOUNDARY\n"
               f"NOUT, 1, 1, {ur0_mm:.12g}\nNTOP, 2, 2, 0\nNFRONT, 2, 2\nNBACK, 2, 2\n")
    if pressure_mpa > 0.0:
        out.append("*DLOAD\n" + "".join(f"{e}, P4, {pressure_mpa:.10g}\n" for e in bore))
    out.append("*NODE PRINT, NSET=NTOP, TOTALS=ONLY\nRF\n*END STEP\n")
    out.append("*STEP, NLGEOM, INC=10000\n*STATIC\n1.0, 1.0\n*BOUNDARY\n"
               f"NTOP, 2, 2, {delta_mm:.12g}\n*NODE PRINT, NSET=NTOP, TOTALS=ONLY\nRF\n"
               "*END STEP\n")
    return "".join(out)


def inflated_force(pressure_mpa: float, ur0_mm: float, **options: Any) -> float:
    """Incremental axial force on the sleeve per delta (N/mm, whole annulus) after the
    inflation: (F(end of step 2) - F(end of step 1)) / delta."""
    delta = float(options.get("delta_mm", 1e-3))
    run = ccxm.run_ccx(inflated_deck(pressure_mpa, ur0_mm, **options), timeout_s=1800.0)
    if run.returncode != 0 or not run.dat:
        raise RuntimeError(run.stdout[-2000:])
    tab = ccxm.parse_dat(run.dat)
    keys = sorted((k for k in tab if k[0] == "total force"), key=lambda k: k[2])
    f = [180.0 * tab[k]["total"][1] for k in keys]
    return (f[-1] - f[0]) / delta


#: outer-surface push-outs (mm) of the inflated study: inner hoop stretch 1 ... 1.84 (the base
#: tube's largest in-plane stretch in the squeeze is 1.18 / 1.47 / 1.76 at 0.2 / 0.4 / 0.6 MPa)
INFLATED_UR0_MM = (0.0, 0.3, 0.6, 0.85, 1.2, 1.5)


def inflated_study() -> dict[str, Any]:
    """The held annulus (sleeve pulled, no ground) inflated first: 3-D force per delta (N/mm)
    against the push-out ``ur0`` (P = 0) and against P (``ur0`` 0 and 0.85 mm), for L = 5 and
    10 mm; the scalar zone's force on the same mesh for E_z / G = 3, 2.5, 2, 1.5, 1 (P- and
    ur0-independent in the reference configuration); a finer mesh at one stretched point."""
    g = 2.0 * (MR_SHORE_62_5[0] + MR_SHORE_62_5[1])
    res: dict[str, Any] = {"r_in_mm": R_IN_MM, "r_out_mm": R_OUT_MM, "shear_mpa": g,
                           "constants_c10_c01_d1": list(MR_SHORE_62_5), "gap_mm": 0.5,
                           "variant": "axial only, wire alone", "lengths": []}
    for length in (5.0, 10.0):
        nz = int(round(20 * length))
        row: dict[str, Any] = {"length_mm": length, "mesh": [8, nz]}
        row["scalar_by_ez_over_g"] = {
            f"{ez:g}": force("scalar", length_mm=length, gap_mm=0.5, nz=nz, ez_over_g=ez,
                             radial="bonded", ground=False, g=g)
            for ez in (3.0, 2.5, 2.0, 1.5, 1.0)}
        row["ur0_mm"] = list(INFLATED_UR0_MM)
        row["inner_stretch"] = [inner_stretch(u) for u in INFLATED_UR0_MM]
        row["force_by_ur0"] = [inflated_force(0.0, u, length_mm=length, nz=nz)
                               for u in INFLATED_UR0_MM]
        row["pressures_mpa"] = [0.0, 0.2, 0.4, 0.6]
        row["force_by_pressure"] = {
            f"{u:g}": [inflated_force(p, u, length_mm=length, nz=nz) for p in (0.0, 0.2, 0.4, 0.6)]
            for u in (0.0, 0.85)}
        res["lengths"].append(row)
    res["fine_mesh_check"] = {"length_mm": 5.0, "ur0_mm": 0.85, "mesh": [16, 250],
                              "force": inflated_force(0.0, 0.85, nr=16, nz=250),
                              "force_mesh": res["lengths"][0]["force_by_ur0"][3]}
    return res


def main(argv: list[str] | None = None) -> dict[str, Any]:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--out", type=Path, default=None,
                    help="write the JSON here (tests/data/ccx_pullout_heldzone.json)")
    ap.add_argument("--inflated", action="store_true",
                    help="the inflated-first study alone (stored under 'inflated')")
    args = ap.parse_args(argv)
    out: dict[str, Any] = ({"inflated": inflated_study()} if args.inflated
                           else {f"L{L:g}": study(L) for L in (5.0, 10.0)})
    if args.out is not None:
        old = json.loads(args.out.read_text()) if args.out.exists() else {}
        old.update({"description": __doc__.splitlines()[0], "units": "force per delta: N/mm",
                    **out})
        tmp = args.out.with_suffix(".tmp")
        tmp.write_text(json.dumps(old, indent=1))
        tmp.replace(args.out)
    if args.json:
        print(json.dumps(out, indent=1))
    else:
        for k, r in out.items():
            if k == "inflated":
                for row in r["lengths"]:
                    print(f"L {row['length_mm']:g} mm: 3-D force / delta (N/mm) by inner "
                          "stretch:", {round(s, 3): round(f, 2) for s, f in
                                       zip(row["inner_stretch"], row["force_by_ur0"],
                                           strict=True)})
                    print("   by P (ur0 0 / 0.85 mm):", {u: [round(f, 2) for f in v] for u, v
                                                         in row["force_by_pressure"].items()})
                    print("   scalar by E_z / G:", {e: round(f, 2) for e, f in
                                                    row["scalar_by_ez_over_g"].items()})
                continue
            for v in r["variants"]:
                print(k, v["variant"], {a: round(b, 4) for a, b in v.items()
                                        if isinstance(b, float)})
    return out


if __name__ == "__main__":
    main()
