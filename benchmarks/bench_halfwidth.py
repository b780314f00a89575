"""Benchmark: convergence of the wire's contact half-width, interpolated edge vs node counting.

Run: ``python benchmarks/bench_halfwidth.py [--json]`` (about a minute of CPU, single thread).

Issue 35 item 4: the contact half-width reported by ``squeeze`` (``contact.wire_contact_
halfwidth_mm``) is the interpolated edge of the contact patch (``exofric.fe.patch_edge``:
the gap's zero crossing fitted between the last node in contact and the first one out),
not the arc position of the last node in contact (node counting, which jumps in element-sized
steps). This benchmark solves the base group (hole 10, tube OD 8.3 / ID 4.97, wire 1.6 mm,
Shore 62.5, weightless, frictionless) on a sequence of meshes, each with twice the elements of
the last in both directions (2 x 16 .. 16 x 128, graded toward both contacts like the accuracy
levels), and reports both half-widths (mm) at 0.15, 0.2, 0.3 and 0.6 MPa, with each one's
change from the finest mesh's interpolated edge (the reference of the study; its own change
from the next coarser mesh is in the table too). Nothing is stored.

Measured 2026-11-27 (largest |change| over the four pressures, interpolated / counted): 2 x 16
12.0 / 32.9 %, 4 x 32 5.8 / 11.1 %, 8 x 64 2.7 / 11.0 %, 16 x 128 0 / 2.4 % (node counting
stays a node spacing short even on the finest mesh; the interpolated edge at 0.2 MPa oscillates,
+5.8 % then -2.7 %, as the edge passes the nodes, but within 3 % from 8 x 64 on).

Units: mm, MPa, s.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _fe_bench import cli_main  # noqa: E402

PRESSURES_MPA = (0.15, 0.2, 0.3, 0.6)
#: (n_radial, n_circ, wall_elements): each twice the last; gradings as the accuracy levels
MESHES = ((2, 16, 5), (4, 32, 10), (8, 64, 20), (16, 128, 40))


def run(runs: int = 1, felupe_runs: int = 0) -> dict[str, Any]:
    """Solve every mesh once; half-widths (mm) interpolated and by node counting."""
    from exofric.fe import MeshSpec
    from exofric.geometry import BASE
    from exofric.material import MooneyRivlin
    from exofric.simulate import squeeze

    mat = MooneyRivlin.from_shore(62.5)
    rows = []
    for nr, nc, nw in MESHES:
        spec = MeshSpec(n_radial=nr, n_circ=nc, grading=6.0, wall_elements=nw, wall_grading=4.0)
        c0 = time.process_time()
        r = squeeze(BASE, mat, list(PRESSURES_MPA), gravity="none", mesh=spec)
        counted = [max((abs(a) for a in prof["wire"]["arc_mm"]), default=0.0)
                   for prof in r.contact.profiles]
        rows.append({"mesh": f"{nr} x {nc}", "cpu_time_s": time.process_time() - c0,
                     "interpolated_mm": [float(x) for x in r.contact.wire_contact_halfwidth_mm],
                     "node_counting_mm": [float(x) for x in counted],
                     "wire_patch_nodes": [len(prof["wire"]["arc_mm"])
                                          for prof in r.contact.profiles]})
    ref = np.array(rows[-1]["interpolated_mm"])  # the finest mesh's interpolated edge
    for row in rows:
        for key in ("interpolated", "node_counting"):
            row[f"{key}_change_pct"] = (100 * (np.array(row[f"{key}_mm"]) / ref - 1)).tolist()
    return {"problem": "base group, weightless, frictionless", "pressure_mpa": PRESSURES_MPA,
            "runs": 1, "meshes": rows}


def render(out: dict[str, Any]) -> str:
    """Human-readable table: per mesh and pressure, both half-widths and their changes."""
    p = out["pressure_mpa"]
    lines = [f"[halfwidth] {out['problem']}: wire contact half-width (mm), interpolated edge "
             "vs node counting; change (%) from the finest mesh's interpolated edge",
             f"  {'mesh':<10}{'P (MPa)':>8}{'interp.':>9}{'chg %':>8}{'counted':>9}{'chg %':>8}"
             f"{'nodes':>6}"]
    for row in out["meshes"]:
        for k, pk in enumerate(p):
            lines.append(f"  {row['mesh']:<10}{pk:>8g}{row['interpolated_mm'][k]:>9.4f}"
                         f"{row['interpolated_change_pct'][k]:>8.1f}"
                         f"{row['node_counting_mm'][k]:>9.4f}"
                         f"{row['node_counting_change_pct'][k]:>8.1f}"
                         f"{row['wire_patch_nodes'][k]:>6d}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    """Command-line entry point; prints the summary and returns it."""
    return cli_main(run, render, __doc__, 1, argv)


if __name__ == "__main__":
    main()
