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

Run: ``python benchmarks/calculix_heldzone.py [--json] [--out PATH]`` (24 runs of a few
seconds; stored in ``tests/data/ccx_pullout_heldzone.json``). Measured (ccx 2.20): scalar / 3-D
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


def main(argv: list[str] | None = None) -> dict[str, Any]:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--out", type=Path, default=None,
                    help="write the JSON here (tests/data/ccx_pullout_heldzone.json)")
    args = ap.parse_args(argv)
    out: dict[str, Any] = {f"L{L:g}": study(L) for L in (5.0, 10.0)}
    if args.out is not None:
        args.out.write_text(json.dumps({"description": __doc__.splitlines()[0],
                                        "units": "force per delta: N/mm", **out}, indent=1))
    if args.json:
        print(json.dumps(out, indent=1))
    else:
        for k, r in out.items():
            for v in r["variants"]:
                print(k, v["variant"], {a: round(b, 4) for a, b in v.items()
                                        if isinstance(b, float)})
    return out


if __name__ == "__main__":
    main()
