"""Benchmark: cost of the squeeze's accuracy levels against one solve on the former default mesh.

Run: ``python benchmarks/bench_accuracy.py [--runs 3] [--json]``.
For the seven Table 3 structures and issue 35's five thick-wall structures (0.05..0.6 MPa,
12 outputs, gravity "none"), times
``squeeze(..., accuracy=level)`` for draft, standard and fine and one solve on the 2 x 24 mesh
that was the default before the accuracy levels (an explicit mesh: one load path and the
onset bracketing, no error estimate). Reports medians of CPU time (s, the cost, insensitive to
other load on the machine) and wall time, and the ratios to the 2 x 24 solve. Where the stored
FElupe references (``tests/data/squeeze_reference_felupe.json``, thin walls, and
``squeeze_reference_felupe_onset.json``, thick walls) cover a structure, also the largest
relative error of N from the first pressure with N >= 1% of N(0.6 MPa), over all of them and
over the thick walls alone.
Single-threaded (BLAS/OpenMP threads pinned to 1 before NumPy is imported). Units: s, %.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import json  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _fe_bench import cli_main  # noqa: E402

PRESSURES_MPA = np.round(np.arange(0.05, 0.601, 0.05), 2)
LEVELS = ("former default 2 x 24", "former standard 4 x 32", "draft", "standard", "fine")
#: The "standard" level before issue 35 (one grading toward the wire over the half tube):
#: timed with the levels table swapped for this entry, to compare the cost before and after.
FORMER_STANDARD = {"n_radial": 4, "n_circ": 32, "grading": 6.0, "coarsen": (2, 2)}
REFERENCE = Path(__file__).resolve().parents[1] / "tests" / "data" / "squeeze_reference_felupe.json"
ONSET_REFERENCE = REFERENCE.with_name("squeeze_reference_felupe_onset.json")


def _reference(path: Path = REFERENCE) -> dict[str, np.ndarray]:
    """Stored FElupe N(P) (N/mm) by structure name, if the file is there."""
    if not path.exists():
        return {}
    data = json.loads(path.read_text())
    if not np.allclose(data["pressure_mpa"], PRESSURES_MPA):
        return {}
    return {name: np.asarray(s["squeeze_force_n_per_mm"], dtype=float)
            for name, s in data["structures"].items()}


def _thick_structures() -> list[Any]:
    """Issue 35's thick-wall structures as stored in the onset reference ([] without it)."""
    from exofric.geometry import Structure

    if not ONSET_REFERENCE.exists():
        return []
    data = json.loads(ONSET_REFERENCE.read_text())["structures"]
    return [Structure(d["hole_mm"], d["tube_od_mm"], d["tube_id_mm"], d["wire_mm"],
                      d["length_mm"], name) for name, d in data.items()]


def run(runs: int = 3, felupe_runs: int = 0) -> dict[str, Any]:
    """Time every level on every structure (at most 3 runs); return a JSON summary (s, %).

    ``felupe_runs`` is unused (FElupe enters through the stored reference only).
    """
    runs = max(1, min(runs, 3))
    from unittest import mock

    from exofric import defaults
    from exofric.fe import MeshSpec
    from exofric.friction import paper_structures
    from exofric.material import MooneyRivlin
    from exofric.simulate import squeeze

    mat = MooneyRivlin.from_shore(62.5)
    thick = _reference(ONSET_REFERENCE)
    refs = {**_reference(), **thick}
    structures = [*paper_structures(), *_thick_structures()]
    rows: dict[str, dict[str, Any]] = {}
    for level in LEVELS:
        kw: dict[str, Any] = ({"mesh": MeshSpec(2, 24)} if level.startswith("former default")
                              else {"accuracy": level.split()[1] if level.startswith("former")
                                    else level})
        swap = ({"standard": FORMER_STANDARD} if level.startswith("former standard")
                else {})
        cpu, wall = [], []
        err: list[float] = []
        err_thick: list[float] = []
        for k in range(runs):
            with mock.patch.object(defaults, "SQUEEZE_ACCURACY",
                                   {**defaults.SQUEEZE_ACCURACY, **swap}):
                c0, w0 = time.process_time(), time.perf_counter()
                results = [squeeze(s, mat, PRESSURES_MPA, keep_fields=False, **kw)
                           for s in structures]
                cpu.append(time.process_time() - c0)
                wall.append(time.perf_counter() - w0)
            if k == 0:
                for r in results:
                    ref = refs.get(r.structure.name)
                    if ref is not None:
                        m = ref >= 0.01 * ref[-1]
                        err.append(float(np.max(np.abs(r.squeeze_force_n_per_mm[m] / ref[m]
                                                       - 1.0)) * 100))
                        if r.structure.name in thick:
                            err_thick.append(err[-1])
        rows[level] = {"median_cpu_time_s": float(np.median(cpu)),
                       "median_wall_time_s": float(np.median(wall)),
                       "max_error_vs_felupe_pct": max(err) if err else None,
                       "max_error_thick_walls_pct": max(err_thick) if err_thick else None,
                       "structures_with_reference": len(err)}
    base = rows[LEVELS[0]]["median_cpu_time_s"]
    for r in rows.values():
        r["cpu_ratio_to_2x24"] = r["median_cpu_time_s"] / base
    return {"problem": f"squeeze of {len(structures)} structures (7 Table 3, "
                       f"{len(structures) - 7} thick walls), 0.05..0.6 MPa (12 outputs), "
                       "Shore 62.5, gravity none", "runs": runs, "levels": rows}


def render(out: dict[str, Any]) -> str:
    """Human-readable table."""
    lines = [f"[accuracy] {out['problem']}, median of {out['runs']} runs",
             f"  {'level':<24}{'CPU (s)':>9}{'wall (s)':>10}{'x 2x24':>8}"
             f"{'max err vs FElupe (%)':>24}{'thick (%)':>10}"]
    for name, r in out["levels"].items():
        e, et = r["max_error_vs_felupe_pct"], r["max_error_thick_walls_pct"]
        err = "-" if e is None else f"{e:.2f} ({r['structures_with_reference']} structures)"
        lines.append(f"  {name:<24}{r['median_cpu_time_s']:>9.2f}{r['median_wall_time_s']:>10.2f}"
                     f"{r['cpu_ratio_to_2x24']:>8.2f}{err:>24}"
                     f"{'-' if et is None else f'{et:.2f}':>10}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    """Command-line entry point; prints the summary and returns it."""
    return cli_main(run, render, __doc__, 3, argv)


if __name__ == "__main__":
    main()
