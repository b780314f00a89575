"""Benchmark: hyperelastic fits on real silicone data (``exofric material --fit``; issue 31).

Run: ``python benchmarks/bench_material_fit.py [--runs 5] [--points 1000] [--json]``.
Single-threaded. Units: s (wall clock, ``time.perf_counter``, and CPU, ``time.process_time``:
the one to read on a loaded machine; medians of ``--runs``), MPa.

Data: the shipped Ecoflex 00-30 uniaxial curve (Soft Robotics Materials Database extract, 102
points, stretch 1.07-17.1) interpolated linearly onto ``--points`` stretches (default 1,000),
and the shipped curve itself. Every model (neo-Hookean, Mooney-Rivlin, Yeoh, Ogden 1-3) is
fitted with :func:`exofric.material.fit_material` (admissible fit, multi-start for Ogden);
reported per model: the median fit time, the RMS (MPa), whether the fit is constrained, and
for Ogden the number of starts and their RMS spread. Target (issue 37): Ogden-3 under 2 s on
1,000 points, multi-start included (before the vectorised multi-start: 0.9-1.5 s CPU, 2-3 s wall
on the loaded 2-core machine; the issue measured 44-175 s with an earlier version).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from exofric.material import fit_material, silicone_uniaxial  # noqa: E402

MODELS = ("neo-hookean", "mooney-rivlin", "yeoh", "ogden1", "ogden2", "ogden3")
TARGET_OGDEN3_S = 2.0


def curve(points: int) -> tuple[np.ndarray, np.ndarray]:
    """The Ecoflex 00-30 curve on ``points`` stretches (linear interpolation of the shipped
    data; ``points <= 0``: the shipped 102 points)."""
    lam, p = silicone_uniaxial("ecoflex-00-30")
    if points <= 0:
        return lam, p
    grid = np.linspace(lam[0], lam[-1], points)
    return grid, np.interp(grid, lam, p)


def bench(points: int, runs: int) -> dict[str, Any]:
    lam, p = curve(points)
    out: dict[str, Any] = {"points": int(lam.size), "runs": runs, "models": {}}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fit_material("neo-hookean", uniaxial=(lam, p))  # imports (scipy), once
        for name in MODELS:
            times, cpu = [], []
            fit = None
            for _ in range(runs):
                t0, c0 = time.perf_counter(), time.process_time()
                fit = fit_material(name, uniaxial=(lam, p))
                times.append(time.perf_counter() - t0)
                cpu.append(time.process_time() - c0)
            assert fit is not None
            row = {"time_s": statistics.median(times), "cpu_s": statistics.median(cpu),
                   "rms_mpa": fit.modes["uniaxial"].rms_mpa,
                   "constrained": fit.constrained, "admissible": fit.admissible}
            if name.startswith("ogden"):
                ms = fit.multistart
                row.update({"n_starts": ms["n_starts"], "start_rms_min_mpa": ms["rms_min_mpa"],
                            "start_rms_median_mpa": ms["rms_median_mpa"],
                            "start_rms_max_mpa": ms["rms_max_mpa"]})
            out["models"][name] = row
    return out


def main(argv: list[str] | None = None) -> dict[str, Any]:
    """Run the benchmark, print a table, return the summary."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--points", type=int, default=1000)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    res = {"interpolated": bench(args.points, args.runs), "shipped": bench(0, args.runs)}
    ogden3 = res["interpolated"]["models"]["ogden3"]["time_s"]
    ogden3_cpu = res["interpolated"]["models"]["ogden3"]["cpu_s"]
    res["target_ogden3_s"] = TARGET_OGDEN3_S
    # judged on CPU time: on a loaded machine the wall clock measures the other processes
    res["target_met"] = bool(ogden3_cpu < TARGET_OGDEN3_S)
    if args.json:
        print(json.dumps(res))
        return res
    for key, r in res.items():
        if not isinstance(r, dict):
            continue
        print(f"Ecoflex 00-30, {key}: {r['points']} points, median of {r['runs']} runs")
        print(f"  {'model':14s} {'time (s)':>9s} {'CPU (s)':>8s} {'RMS (MPa)':>11s} "
              f"{'constr.':>8s} {'starts':>7s} {'start RMS min/median/max (MPa)':>32s}")
        for name, m in r["models"].items():
            spread = (f"{m['start_rms_min_mpa']:.3g}/{m['start_rms_median_mpa']:.3g}/"
                      f"{m['start_rms_max_mpa']:.3g}" if "n_starts" in m else "")
            print(f"  {name:14s} {m['time_s']:9.3f} {m['cpu_s']:8.3f} {m['rms_mpa']:11.4g} "
                  f"{'yes' if m['constrained'] else 'no':>8s} {m.get('n_starts', 1):7d} "
                  f"{spread:>32s}")
    print(f"Ogden-3 on {res['interpolated']['points']} points: {ogden3:.2f} s wall, "
          f"{ogden3_cpu:.2f} s CPU (target < "
          f"{TARGET_OGDEN3_S:g} s CPU: {'met' if res['target_met'] else 'NOT met'})")
    return res


if __name__ == "__main__":
    main()
