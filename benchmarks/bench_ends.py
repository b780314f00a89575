"""Benchmark: the cost of closed and open tube ends (generalised plane strain) against plane strain.

Times, median of ``--runs`` (default 5), single-threaded:

* free inflation of the paper's tube (OD 8.3 / ID 4.97 mm, Shore 62.5), 0.05..0.45 MPa in 9
  outputs (closed ends reach their limit pressure at 0.53 MPa), default accuracy (two nested
  meshes), ``keep_fields=False``;
* the base group's squeeze at 0.2..0.6 MPa (5 outputs), default accuracy.

Reported: CPU time (``time.process_time``, robust to a busy machine) per case, the ratio to
plane strain, Newton iterations, and the axial stretch at the last pressure. The closed/open
end's extra dof is eliminated by a Schur complement (``Assembler(border=)``); open ends also
re-evaluate each iterate after freezing the cap force (docs/formulation.md section 11).

Run: ``python benchmarks/bench_ends.py [--runs 5] [--json]``. Units: MPa, s.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from exofric.geometry import BASE  # noqa: E402
from exofric.material import MooneyRivlin  # noqa: E402
from exofric.simulate import inflate, squeeze  # noqa: E402

ENDS = ("plane-strain", "closed", "open")
INFLATION_P_MPA = np.linspace(0.05, 0.45, 9)
SQUEEZE_P_MPA = [0.2, 0.3, 0.4, 0.5, 0.6]


def _time(fn: Any, runs: int) -> tuple[float, Any]:
    """Median CPU time (s) of ``fn()`` over ``runs`` and its last result."""
    ts, res = [], None
    for _ in range(runs):
        t0 = time.process_time()
        res = fn()
        ts.append(time.process_time() - t0)
    return float(np.median(ts)), res


def run(runs: int = 5) -> dict[str, Any]:
    """Time every case; return a JSON-ready summary (times in s)."""
    mat = MooneyRivlin.from_shore(62.5)
    out: dict[str, Any] = {"runs": runs, "inflation": {}, "squeeze": {}}
    for ends in ENDS:
        t, r = _time(lambda e=ends: inflate(8.3, 4.97, mat, INFLATION_P_MPA, ends=e,
                                            keep_fields=False), runs)
        out["inflation"][ends] = {
            "cpu_time_s": t, "newton_iterations": int(r.newton_iterations.sum()),
            "dofs": r.dofs, "axial_stretch_last": float(r.axial_stretch[-1]),
            "outer_diameter_last_mm": float(r.outer_diameter_mm[-1])}
        t, r = _time(lambda e=ends: squeeze(BASE, mat, SQUEEZE_P_MPA, ends=e,
                                            keep_fields=False), runs)
        out["squeeze"][ends] = {
            "cpu_time_s": t, "newton_iterations": int(r.newton_iterations.sum()),
            "dofs": r.dofs, "axial_stretch_last": float(r.axial_stretch[-1]),
            "squeeze_force_last_n_per_mm": float(r.squeeze_force_n_per_mm[-1])}
    for kind in ("inflation", "squeeze"):
        base = out[kind]["plane-strain"]["cpu_time_s"]
        for ends in ENDS:
            out[kind][ends]["ratio_to_plane_strain"] = out[kind][ends]["cpu_time_s"] / base
    return out


def render(out: dict[str, Any]) -> str:
    """Human-readable summary."""
    lines = [f"[ends] median CPU time of {out['runs']} runs; ratio to plane strain"]
    for kind, what in (("inflation", "inflation 0.05..0.45 MPa (9 outputs)"),
                       ("squeeze", "base-group squeeze 0.2..0.6 MPa (5 outputs)")):
        lines.append(f"  {what}:")
        for ends, v in out[kind].items():
            lines.append(f"    {ends:>12}: {v['cpu_time_s'] * 1e3:7.1f} ms  "
                         f"x{v['ratio_to_plane_strain']:.2f}  {v['newton_iterations']:3d} it.  "
                         f"{v['dofs']} dofs  axial stretch {v['axial_stretch_last']:.4f}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    """Command-line entry point; prints the summary and returns it."""
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--runs", type=int, default=5, help="repetitions (median)")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--quiet", action="store_true", help="print nothing (return only)")
    args = ap.parse_args(argv)
    out = run(args.runs)
    if not args.quiet:
        print(json.dumps(out) if args.json else render(out))
    return out


if __name__ == "__main__":
    main()
