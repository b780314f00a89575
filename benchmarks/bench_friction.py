"""Benchmark of Coulomb friction in the squeeze (issues 15, 37): CPU time of the base group's sweep
(12 pressures 0.05..0.6 MPa) frictionless and with mu = 0.3 on the wall, the wire and both, on
the 2 x 24 sweep mesh, the default accuracy (4 x 32 + 2 x 16 estimate) and, with ``--fine``, the
8 x 128 mesh; the cases interleaved round by round, the ratio to the frictionless solve of the
same round (median and range; issue 37 target: at most 2x), Newton attempts, failed attempts
and their share of the Newton time, iterations, and N(0.6 MPa).

Run: ``.venv/bin/python benchmarks/bench_friction.py [--repeats 5] [--fine] [--json]``.

Measured 2026-11-27 (issue 37; the shared 2-core machine, load 5-6, CPU time; "before" is the
solver of commit 971dae7, both measured interleaved in alternating processes):

=====================  ===========================  =============================
both 0.3 / none        before                       after
=====================  ===========================  =============================
standard, CPU ratio    3.45x (2.3-5.7), 8 pairs     1.8-2.2x (1.4-2.4), 3 runs
standard, Newton       392 iterations, 6 failed     258 iterations, 0 failed
                       (21 % of the time)           (frictionless: 253, 0)
8 x 128, CPU ratio     1.55x (1.37-1.72)            1.01x (0.97-1.04)
8 x 128, Newton        244 iterations, 1 failed     190 iterations, 0 failed
=====================  ===========================  =============================

Where the 3x went (profile, default accuracy): 3.5x the frictionless evaluations (1144 against
328): every iteration evaluated the full step without a tangent and then the same state again
with one after the slip bounds' refresh, and 79 damped steps (a slipping node that the linear
step runs back through its stick zone, or a sticking one past its bound: the tangent knows only
the node's class at the iterate) with their line searches, and 6 failed attempts. Now the stick/
slip classes the step would change enter the direction (``StickSlipModel``, the semismooth step
of ``refine_direction``) and the refreshed bounds patch the held evaluation
(``SqueezeProblem.patch_refreshed``): as many iterations and evaluations as frictionless; what
remains is the friction terms' cost per iteration (~1.5 ms of ~3 ms on the default mesh).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from exofric import defaults  # noqa: E402
from exofric.fe import MeshSpec  # noqa: E402
from exofric.geometry import BASE  # noqa: E402
from exofric.material import MooneyRivlin  # noqa: E402
from exofric.simulate import squeeze  # noqa: E402

CASES = {"frictionless": (0.0, 0.0), "wall 0.3": (0.3, 0.0), "wire 0.3": (0.0, 0.3),
         "both 0.3": (0.3, 0.3)}


_SETTINGS: dict[str, dict[str, Any]] = {
    "sweep (2 x 24 mesh)": {"mesh": MeshSpec(**defaults.SQUEEZE_MESH)},
    "squeeze standard (4 x 32 + 2 x 16 estimate)": {},
    "8 x 128 mesh": {"mesh": MeshSpec(8, 128)},
}


def _measure(kw: dict[str, Any], repeats: int) -> dict[str, Any]:
    """The cases of one mesh setting, interleaved (case after case, ``repeats`` rounds)."""
    mat = MooneyRivlin.from_shore(62.5)
    p = np.round(np.arange(1, 13) * 0.05, 2)
    times: dict[str, list[float]] = {name: [] for name in CASES}
    rows: dict[str, Any] = {}
    for _ in range(repeats):
        for name, (mw, mr) in CASES.items():
            t0 = time.process_time()
            r = squeeze(BASE, mat, p, mu_wall=mw, mu_wire=mr, keep_fields=False, **kw)
            times[name].append(time.process_time() - t0)
            st = r.solver_stats.to_dict()
            rows[name] = {"attempts": st.get("attempts"),
                          "failed_attempts": st.get("failed_attempts"),
                          "failed_time_pct": st.get("failed_time_pct"),
                          "iterations": st.get("iterations"),
                          "n_at_0_6_mpa_n_per_mm": float(r.squeeze_force_n_per_mm[-1])}
    for name, v in rows.items():
        v["cpu_s_median"] = statistics.median(times[name])
        # ratio per round (the frictionless solve of the same round), then its median and range
        ratios = sorted(a / b for a, b in zip(times[name], times["frictionless"], strict=True))
        v["ratio_to_frictionless"] = statistics.median(ratios)
        v["ratio_range"] = [ratios[0], ratios[-1]]
    return rows


def main(argv: list[str] | None = None) -> dict[str, Any]:
    """Run the benchmark; return and print its summary."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--fine", action="store_true", help="also the 8 x 128 mesh (minutes)")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    out = {label: _measure(kw, args.repeats) for label, kw in _SETTINGS.items()
           if args.fine or "128" not in label}
    if args.json:
        print(json.dumps(out, indent=2))
        return out
    for label, rows in out.items():
        print(label)
        print(f"  {'case':14s} {'CPU s':>7s} {'ratio':>6s} {'range':>11s} {'attempts':>9s} "
              f"{'failed':>7s} {'fail %':>7s} {'iters':>6s} {'N(0.6) N/mm':>12s}")
        for k, v in rows.items():
            lo, hi = v["ratio_range"]
            print(f"  {k:14s} {v['cpu_s_median']:7.2f} {v['ratio_to_frictionless']:6.2f} "
                  f"{lo:5.2f}-{hi:5.2f} {v['attempts']:9d} {v['failed_attempts']:7d} "
                  f"{v['failed_time_pct']:7.1f} {v['iterations']:6d} "
                  f"{v['n_at_0_6_mpa_n_per_mm']:12.4f}")
    return out


if __name__ == "__main__":
    main()
