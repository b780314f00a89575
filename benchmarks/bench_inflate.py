"""Benchmark: exofric's free-inflation sweep (12 pressures) vs the same problem in FElupe.

Run: ``python benchmarks/bench_inflate.py [--runs 7] [--felupe-runs 3] [--json]``.
Single-threaded (BLAS/OpenMP threads pinned to 1 before NumPy is imported).
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

from exofric.material import MooneyRivlin  # noqa: E402
from exofric.simulate import (  # noqa: E402
    compressible_inflation,
    inflate,
)

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _fe_bench import cli_main, target_line  # noqa: E402

OD_MM, ID_MM, SHORE = 8.3, 4.97, 62.5
PRESSURES_MPA = np.linspace(0.05, 0.6, 12)
TARGET_TIME_S, TARGET_RATIO = 0.1, 3.0
MESH_TOL = 1e-4  # the benchmarked mesh must be within 0.01% of the 1D reference


def run(runs: int = 7, felupe_runs: int = 3) -> dict[str, Any]:
    """Time both codes; return a JSON-ready summary (times in s, diameters in mm)."""
    mat = MooneyRivlin.from_shore(SHORE)
    ref = compressible_inflation(OD_MM, ID_MM, mat, PRESSURES_MPA).outer_diameter_mm
    solve_t, wall_t = [], []
    res = None
    for _ in range(runs):
        t0 = time.perf_counter()
        res = inflate(OD_MM, ID_MM, mat, PRESSURES_MPA, keep_fields=False)
        wall_t.append(time.perf_counter() - t0)
        solve_t.append(res.solve_time_s)
    assert res is not None
    mesh_err = float(np.max(np.abs(res.outer_diameter_mm / ref - 1.0)))
    if mesh_err > MESH_TOL:
        raise RuntimeError(f"exofric mesh error {mesh_err:.2e} exceeds {MESH_TOL:.0e}")
    out: dict[str, Any] = {
        "problem": "free inflation, quarter model, OD 8.3 / ID 4.97 mm, Shore 62.5, "
        "0.05..0.6 MPa (12 outputs)",
        "exofric": {
            "dofs": res.dofs,
            "newton_iterations": int(res.newton_iterations.sum()),
            "mesh": res.mesh.to_dict(),
            "max_rel_error_vs_1d_reference": mesh_err,
            "median_solve_time_s": float(np.median(solve_t)),
            "median_wall_time_s": float(np.median(wall_t)),
            "runs": runs,
        },
        "target_time_s": TARGET_TIME_S,
        "target_ratio": TARGET_RATIO,
    }
    try:
        from felupe_models import felupe_inflate
    except ImportError as exc:  # felupe is an optional (GPL) extra
        out["felupe"] = f"skipped: {exc}"
        return out
    f_solve, f_wall = [], []
    fr = None
    for _ in range(felupe_runs):
        t0 = time.perf_counter()
        fr = felupe_inflate(res.nodes, res.elements, mat, PRESSURES_MPA)
        f_wall.append(time.perf_counter() - t0)
        f_solve.append(fr.solve_time_s)
    assert fr is not None
    ratio = float(np.median(f_solve) / np.median(solve_t))
    out["felupe"] = {
        "dofs": fr.dofs,
        "newton_iterations": int(fr.newton_iterations.sum()),
        "median_solve_time_s": float(np.median(f_solve)),
        "median_wall_time_s": float(np.median(f_wall)),
        "runs": felupe_runs,
        "max_rel_od_difference_vs_exofric": float(
            np.max(np.abs(fr.outer_diameter_mm / res.outer_diameter_mm - 1.0))
        ),
    }
    out["ratio_felupe_over_exofric"] = ratio
    out["meets_targets"] = bool(out["exofric"]["median_solve_time_s"] <= TARGET_TIME_S
                                and ratio >= TARGET_RATIO)
    return out


def render(out: dict[str, Any]) -> str:
    """Human-readable summary."""
    e = out["exofric"]
    lines = [
        f"[inflate] {out['problem']}",
        f"  exofric: {e['dofs']} dofs, {e['newton_iterations']} Newton iterations, "
        f"median solve {e['median_solve_time_s'] * 1e3:.1f} ms (wall "
        f"{e['median_wall_time_s'] * 1e3:.1f} ms, {e['runs']} runs), max OD error vs 1D "
        f"reference {e['max_rel_error_vs_1d_reference']:.1e}",
    ]
    f = out["felupe"]
    if isinstance(f, str):
        lines.append(f"  felupe: {f}")
    else:
        lines += [
            f"  felupe:  {f['dofs']} dofs, {f['newton_iterations']} Newton iterations, "
            f"median solve {f['median_solve_time_s'] * 1e3:.1f} ms (wall "
            f"{f['median_wall_time_s'] * 1e3:.1f} ms, {f['runs']} runs), max OD difference "
            f"{f['max_rel_od_difference_vs_exofric']:.1e}",
            target_line(out),
        ]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    """Command-line entry point; prints the summary and returns it."""
    return cli_main(run, render, __doc__, 3, argv)


if __name__ == "__main__":
    main()
