"""Benchmark: CalculiX reference of the ring tensile test (plane stress, rigid pin).

Run: ``python benchmarks/bench_ring_ccx.py [--quick] [--out PATH]``. Writes
``tests/data/ccx_ring.json`` (not with ``--quick``, unless ``--out`` is given).

Problem (units mm, N, MPa, s): the CLI example, a ring cut from the paper's tube (OD 8.3,
ID 4.97 mm) 5 mm wide, pulled over two rigid pins of 3 mm diameter that start touching the
bore; ``MooneyRivlin.from_shore(62.5)`` for C10, C01, d only. Output: the force of one pin on
the ring (N) at pin separation increases 0.5, 1, ..., 3 mm.

Model (CalculiX 2.20, nothing of exofric's FE): quarter ring 0..90 deg, graded 4:1 toward
the pin, ``*HYPERELASTIC, MOONEY-RIVLIN`` C10, C01, D1 = d, ``NLGEOM``, symmetry ``u_y = 0``
on y = 0 and ``u_x = 0`` on x = 0. The pin: one layer of stiff elastic elements (a
three-quarter annulus facing the bore) whose nodes all get the prescribed motion
``u_x = delta/2, u_y = 0`` (a rigid body moved by ``*BOUNDARY``, ramped over the step: step
time = delta in mm); node-to-surface linear penalty contact (1e4 MPa/mm), slave = the ring's
bore; increments <= 0.01 mm (0.05 mm diverged near 1.3-1.9 mm). Force of one pin = 2 x the
x-reaction summed over the pin's nodes (the quarter holds half the pin's contact arc).

Runs stored in the JSON (``runs``; the reference ``force_n`` is ``plane_stress_8x64``):

* ``plane_stress_4x32``, ``plane_stress_8x64``: ``CPS8R`` of thickness ``THIN_MM`` = 0.1 mm,
  forces scaled to the 5 mm width. CalculiX expands a CPS element into one layer of 20-node
  bricks with free faces: for a thin layer that is plane stress (a homogeneous CPS8R element
  gives the closed-form uniaxial stress exactly), for a thick one a coarse 3-D model
  (``layer_3d_width5_4x32``: the true 5 mm thickness, +15 % at 1 mm; 1 mm: +1.9 %).
* ``plane_stress_4x32_penalty1e5``: the penalty of exofric (diverged in ccx: stored as error).
* ``plane_strain_4x32``: ``CPE8R``, the plane-strain bound.
* ``solid_3d_4x32x4``: ``C3D20R`` bricks, the quarter ring over half the width (4 layers,
  symmetry ``u_z = 0`` on the mid-plane, faces free), forces x 4: the 3-D ring that plane
  stress and plane strain bracket.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import platform
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from calculix_models import (  # noqa: E402
    _fmt_elements,
    _fmt_nodes,
    _fmt_set,
    ccx_available,
    parse_dat,
    polar_quad8,
    run_ccx,
)

OD, ID, WIDTH, PIN = 8.3, 4.97, 5.0, 3.0
DISPLACEMENTS_MM = np.array([0.5, 1.0, 1.5, 2.0, 2.5, 3.0])
#: Thickness of CalculiX's plane-stress layer (mm); forces are scaled to WIDTH. CalculiX
#: expands a CPS element into one layer of 20-node bricks with free faces, which is plane
#: stress only as the layer gets thin: at the true width (5 mm) it is a coarse 3-D model of the
#: wide ring (stored as ``layer_3d_width5_4x32``), at 0.1 mm it is plane stress to ~2e-4
#: (1 mm: +1.9 %, 5 mm: +15 % at 1 mm pin displacement; 0.01 mm: ccx's contact diverges).
THIN_MM = 0.1
OUT = Path(__file__).resolve().parents[1] / "tests" / "data" / "ccx_ring.json"


def ring_deck(material: tuple[float, float, float], displacements_mm: np.ndarray, *,
              n_radial: int = 4, n_circ: int = 32, grading: float = 4.0,
              element: str = "CPS8", penalty: float = 1e5, pin_elements: int = 96,
              max_increment_mm: float = 0.01, width_mm: float = WIDTH,
              contact: str = "NODE TO SURFACE") -> tuple[str, dict[str, object]]:
    """The deck text and its description."""
    c10, c01, d = material
    a, b = 0.5 * ID, 0.5 * OD
    rp = 0.5 * PIN
    e0 = a - rp
    dmax = float(displacements_mm[-1])
    nodes, elems, grid = polar_quad8(a, b, n_radial, n_circ, 0.0, 0.5 * np.pi,
                                     n_circ0=n_circ, grading0=grading)
    for k in grid[:, -1]:
        if k:
            nodes[k] = (0.0, nodes[k][1])
    for k in grid[:, 0]:
        if k:
            nodes[k] = (nodes[k][0], 0.0)
    n_next, e_next = max(nodes) + 1, max(elems) + 1
    pn, pe, _ = polar_quad8(0.6 * rp, rp, 1, pin_elements, -0.5 * np.pi, np.pi,
                            center=(e0, 0.0), first_node=n_next, first_element=e_next)
    inner = set(int(k) for k in grid[0] if k)
    inner_elems = [e for e, c in elems.items() if c[0] in inner]
    y0 = [int(k) for k in grid[:, 0] if k]
    x0 = [int(k) for k in grid[:, -1] if k]
    tp = "".join(f"{v:.10g},\n" for v in displacements_mm)
    text = ("** exofric benchmark: ring tensile test, quarter ring, plane stress (mm, N, MPa)\n"
            "*NODE, NSET=NALL\n" + _fmt_nodes(nodes) + _fmt_nodes(pn)
            + f"*ELEMENT, TYPE={element}, ELSET=RING\n" + _fmt_elements(elems)
            + f"*ELEMENT, TYPE={element}, ELSET=PIN\n" + _fmt_elements(pe)
            + "*NSET, NSET=NY0\n" + _fmt_set(y0) + "*NSET, NSET=NX0\n" + _fmt_set(x0)
            + "*NSET, NSET=NPIN\n" + _fmt_set(sorted(pn))
            + "*MATERIAL, NAME=SILICONE\n*HYPERELASTIC, MOONEY-RIVLIN\n"
            + f"{c10:.12g}, {c01:.12g}, {d:.12g}\n"
            + f"*SOLID SECTION, ELSET=RING, MATERIAL=SILICONE\n{width_mm:.12g}\n"
            + "*MATERIAL, NAME=RIGID\n*ELASTIC\n2.0e5, 0.3\n"
            + f"*SOLID SECTION, ELSET=PIN, MATERIAL=RIGID\n{width_mm:.12g}\n"
            + "*SURFACE, NAME=SRING, TYPE=ELEMENT\n"
            + "".join(f"{e}, S4\n" for e in inner_elems)
            + "*SURFACE, NAME=SPIN, TYPE=ELEMENT\n" + "".join(f"{e}, S2\n" for e in pe)
            + "*SURFACE INTERACTION, NAME=SI\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
            + f"{penalty:.6g}\n"
            + f"*CONTACT PAIR, INTERACTION=SI, TYPE={contact}\nSRING, SPIN\n"
            + f"*TIME POINTS, NAME=OUT\n{tp}"
            + "*STEP, NLGEOM, INC=10000\n*STATIC\n"
            + f"{max_increment_mm:.6g}, {dmax:.10g}, {1e-7 * dmax:.3g}, {max_increment_mm:.6g}\n"
            + "*BOUNDARY\nNY0, 2, 2\nNX0, 1, 1\nNPIN, 2, 2\n"
            + f"NPIN, 1, 1, {0.5 * dmax:.12g}\n"
            + "*NODE PRINT, NSET=NPIN, TOTALS=ONLY, TIME POINTS=OUT\nRF\n"
            + "*END STEP\n")
    desc = {"element": element, "n_radial": n_radial, "n_circ": n_circ, "grading": grading,
            "penalty_mpa_per_mm": penalty, "pin_elements": pin_elements,
            "max_increment_mm": max_increment_mm, "width_mm": width_mm, "contact": contact}
    return text, desc


def _extrude(nodes: dict[int, tuple[float, float]], grid: np.ndarray, depth: float, nz: int,
             first: int, first_element: int,
             ) -> tuple[dict[int, tuple[float, float, float]], dict[int, list[int]], dict]:
    """20-node bricks: the 8-node quad grid extruded over 0 <= z <= depth in nz layers."""
    ni, nj = grid.shape
    nk = 2 * nz + 1
    zs = np.linspace(0.0, depth, nk)
    idx: dict[tuple[int, int, int], int] = {}
    out: dict[int, tuple[float, float, float]] = {}
    n = first
    for k in range(nk):
        for i in range(ni):
            for j in range(nj):
                if not grid[i, j] or (k % 2 == 1 and (i % 2 == 1 or j % 2 == 1)):
                    continue
                x, y = nodes[int(grid[i, j])]
                idx[(i, j, k)] = n
                out[n] = (x, y, float(zs[k]))
                n += 1
    elems: dict[int, list[int]] = {}
    e = first_element
    for k in range(0, nk - 1, 2):
        for j in range(0, nj - 1, 2):
            for i in range(0, ni - 1, 2):
                c = [(i, j), (i + 2, j), (i + 2, j + 2), (i, j + 2)]
                m = [(i + 1, j), (i + 2, j + 1), (i + 1, j + 2), (i, j + 1)]
                elems[e] = ([idx[(a, b, k)] for a, b in c] + [idx[(a, b, k + 2)] for a, b in c]
                            + [idx[(a, b, k)] for a, b in m]
                            + [idx[(a, b, k + 2)] for a, b in m]
                            + [idx[(a, b, k + 1)] for a, b in c])
                e += 1
    return out, elems, idx


def ring_deck_3d(material: tuple[float, float, float], displacements_mm: np.ndarray, *,
                 n_radial: int = 4, n_circ: int = 32, n_width: int = 4, grading: float = 4.0,
                 penalty: float = 1e4, pin_elements: int = 96,
                 max_increment_mm: float = 0.02) -> tuple[str, dict[str, object]]:
    """3-D deck (C3D20R): quarter ring over half the width (symmetry u_z = 0 on z = 0)."""
    c10, c01, d = material
    a, b = 0.5 * ID, 0.5 * OD
    rp = 0.5 * PIN
    e0 = a - rp
    dmax = float(displacements_mm[-1])
    n2, _, g2 = polar_quad8(a, b, n_radial, n_circ, 0.0, 0.5 * np.pi, n_circ0=n_circ,
                            grading0=grading)
    for k in g2[:, -1]:
        if k:
            n2[k] = (0.0, n2[k][1])
    for k in g2[:, 0]:
        if k:
            n2[k] = (n2[k][0], 0.0)
    p2, _, pg = polar_quad8(0.6 * rp, rp, 1, pin_elements, -0.5 * np.pi, np.pi,
                            center=(e0, 0.0))
    half = 0.5 * WIDTH
    rn, re_, ridx = _extrude(n2, g2, half, n_width, 1, 1)
    pn, pe, _ = _extrude(p2, pg, half, n_width, max(rn) + 1, max(re_) + 1)
    y0 = [n for (i, j, k), n in ridx.items() if j == 0]
    x0 = [n for (i, j, k), n in ridx.items() if j == g2.shape[1] - 1]
    z0 = [n for (i, j, k), n in ridx.items() if k == 0]
    bore = [e for e, c in re_.items() if c[0] in {n for (i, j, k), n in ridx.items() if i == 0}
            and c[3] in {n for (i, j, k), n in ridx.items() if i == 0}]
    tp = "".join(f"{v:.10g},\n" for v in displacements_mm)

    def fmt3(nodes: dict[int, tuple[float, float, float]]) -> str:
        return "".join(f"{k}, {x:.12g}, {y:.12g}, {z:.12g}\n" for k, (x, y, z) in nodes.items())

    def fmte(el: dict[int, list[int]]) -> str:
        out = ""
        for k, c in el.items():
            out += f"{k}, " + ", ".join(str(v) for v in c[:15]) + ",\n"
            out += ", ".join(str(v) for v in c[15:]) + "\n"
        return out

    text = ("** exofric benchmark: ring tensile test, 3-D quarter ring, half width (mm, N, MPa)\n"
            "*NODE, NSET=NALL\n" + fmt3(rn) + fmt3(pn)
            + "*ELEMENT, TYPE=C3D20R, ELSET=RING\n" + fmte(re_)
            + "*ELEMENT, TYPE=C3D20R, ELSET=PIN\n" + fmte(pe)
            + "*NSET, NSET=NY0\n" + _fmt_set(sorted(y0)) + "*NSET, NSET=NX0\n"
            + _fmt_set(sorted(x0)) + "*NSET, NSET=NZ0\n" + _fmt_set(sorted(z0))
            + "*NSET, NSET=NPIN\n" + _fmt_set(sorted(pn))
            + "*MATERIAL, NAME=SILICONE\n*HYPERELASTIC, MOONEY-RIVLIN\n"
            + f"{c10:.12g}, {c01:.12g}, {d:.12g}\n"
            + "*SOLID SECTION, ELSET=RING, MATERIAL=SILICONE\n"
            + "*MATERIAL, NAME=RIGID\n*ELASTIC\n2.0e5, 0.3\n"
            + "*SOLID SECTION, ELSET=PIN, MATERIAL=RIGID\n"
            + "*SURFACE, NAME=SRING, TYPE=ELEMENT\n" + "".join(f"{e}, S6\n" for e in bore)
            + "*SURFACE, NAME=SPIN, TYPE=ELEMENT\n" + "".join(f"{e}, S4\n" for e in pe)
            + "*SURFACE INTERACTION, NAME=SI\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
            + f"{penalty:.6g}\n"
            + "*CONTACT PAIR, INTERACTION=SI, TYPE=NODE TO SURFACE\nSRING, SPIN\n"
            + f"*TIME POINTS, NAME=OUT\n{tp}"
            + "*STEP, NLGEOM, INC=10000\n*STATIC\n"
            + f"{max_increment_mm:.6g}, {dmax:.10g}, {1e-7 * dmax:.3g}, {max_increment_mm:.6g}\n"
            + "*BOUNDARY\nNY0, 2, 2\nNX0, 1, 1\nNZ0, 3, 3\nNPIN, 2, 3\n"
            + f"NPIN, 1, 1, {0.5 * dmax:.12g}\n"
            + "*NODE PRINT, NSET=NPIN, TOTALS=ONLY, TIME POINTS=OUT\nRF\n"
            + "*END STEP\n")
    desc = {"element": "C3D20R", "n_radial": n_radial, "n_circ": n_circ, "n_width": n_width,
            "grading": grading, "penalty_mpa_per_mm": penalty, "pin_elements": pin_elements,
            "max_increment_mm": max_increment_mm, "width_mm": WIDTH, "half_width": True}
    return text, desc


def solve(material: tuple[float, float, float], **mesh: object) -> dict[str, object]:
    """Run one deck: forces of one pin (N) at DISPLACEMENTS_MM, CPU time."""
    text, desc = ring_deck(material, DISPLACEMENTS_MM, **mesh)  # type: ignore[arg-type]
    run = run_ccx(text)
    if run.returncode != 0 or not run.dat:
        tail = "\n".join(run.stdout.strip().splitlines()[-8:])
        raise RuntimeError(f"CalculiX failed (exit {run.returncode}):\n{tail}")
    tables = parse_dat(run.dat)
    times = sorted(t for (q, s, t) in tables if q == "total force" and s == "NPIN")
    force = []
    for dk in DISPLACEMENTS_MM:
        k = int(np.argmin(np.abs(np.array(times) - dk)))
        if abs(times[k] - dk) > 1e-6:
            raise RuntimeError(f"CalculiX stopped before {dk:g} mm")
        fx = float(tables[("total force", "NPIN", times[k])]["total"][0])
        force.append(2.0 * fx * WIDTH / float(desc["width_mm"]))  # type: ignore[arg-type]
    return {"mesh": desc, "force_n": force, "cpu_time_s": run.cpu_time_s,
            "equations": run.equations}


def solve_3d(material: tuple[float, float, float], **mesh: object) -> dict[str, object]:
    """Run the 3-D deck: forces of one pin (N) = 4 x the quarter/half-width model's."""
    text, desc = ring_deck_3d(material, DISPLACEMENTS_MM, **mesh)  # type: ignore[arg-type]
    run = run_ccx(text, timeout_s=3600.0)
    if run.returncode != 0 or not run.dat:
        tail = "\n".join(run.stdout.strip().splitlines()[-8:])
        raise RuntimeError(f"CalculiX failed (exit {run.returncode}):\n{tail}")
    tables = parse_dat(run.dat)
    force = []
    for dk in DISPLACEMENTS_MM:
        fx = [v["total"][0] for (q, s, tm), v in tables.items()
              if q == "total force" and s == "NPIN" and abs(tm - dk) <= 1e-6]
        if not fx:
            raise RuntimeError(f"CalculiX stopped before {dk:g} mm")
        force.append(4.0 * float(fx[0]))
    return {"mesh": desc, "force_n": force, "cpu_time_s": run.cpu_time_s,
            "equations": run.equations}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="coarse mesh only")
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args(argv)
    ccx = ccx_available()
    if ccx is None:
        print("ccx not found", file=sys.stderr)
        return 1
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
    from exofric.material import MooneyRivlin

    m = MooneyRivlin.from_shore(62.5)
    mat = (float(m.c10_mpa), float(m.c01_mpa), float(m.d_per_mpa))
    base = {"element": "CPS8R", "penalty": 1e4}
    runs = {"plane_stress_4x32": solve(mat, **base, width_mm=THIN_MM)}
    def attempt(name: str, **kw: object) -> None:
        try:
            runs[name] = solve(mat, **kw)  # type: ignore[arg-type]
        except RuntimeError as exc:
            runs[name] = {"error": str(exc).splitlines()[0], "mesh": kw}

    if not args.quick:
        runs["plane_stress_8x64"] = solve(mat, **base, width_mm=THIN_MM, n_radial=8,
                                          n_circ=64, pin_elements=192)
        attempt("plane_stress_4x32_penalty1e5", element="CPS8R", penalty=1e5,
                width_mm=THIN_MM)
        attempt("plane_strain_4x32", element="CPE8R", penalty=1e4)
        attempt("layer_3d_width5_4x32", **base)
        try:
            runs["solid_3d_4x32x4"] = solve_3d(mat, n_radial=4, n_circ=32, n_width=4)
        except RuntimeError as exc:
            runs["solid_3d_4x32x4"] = {"error": str(exc).splitlines()[0]}
    for k, r in runs.items():
        print(k, r.get("error") or (np.round(r["force_n"], 5).tolist(),
                                     f"{r['cpu_time_s']:.1f} s CPU"), flush=True)
    ref = "plane_stress_8x64" if "plane_stress_8x64" in runs else "plane_stress_4x32"
    out = {
        "description": "CalculiX reference of the ring tensile test (plane stress, CPS8, rigid "
                       "pin by prescribed motion, node-to-surface penalty contact): force of "
                       "one pin vs pin separation increase",
        "provenance": {"command": "python benchmarks/bench_ring_ccx.py",
                       "date_utc": _dt.datetime.now(_dt.UTC).isoformat(
                           timespec="seconds"),
                       "ccx": ccx, "ccx_version": "2.20", "threads": 1,
                       "python": platform.python_version(), "machine": platform.machine()},
        "units": {"length": "mm", "force": "N (one pin, whole ring width)", "time": "s"},
        "geometry": {"ring_od_mm": OD, "ring_id_mm": ID, "width_mm": WIDTH, "pin_mm": PIN},
        "material": {"model": "MooneyRivlin.from_shore(62.5)", "c10_mpa": mat[0],
                     "c01_mpa": mat[1], "d_per_mpa": mat[2]},
        "displacement_mm": DISPLACEMENTS_MM.tolist(),
        "reference": ref,
        "force_n": runs[ref]["force_n"],
        "runs": runs,
    }
    if not args.quick or args.out is not None:
        path = args.out or OUT
        path.write_text(json.dumps(out, indent=1) + "\n")
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
