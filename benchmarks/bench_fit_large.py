"""Benchmark: gamma's fit and interval on 10^6 friction points (issue 31).

Run: ``python benchmarks/bench_fit_large.py [--points 1000000] [--runs 3] [--cli-runs 1]
[--no-cli] [--json]``. Single-threaded. Units: s (wall clock, medians), MB (2^20 bytes).

A synthetic friction table of ``--points`` pulls at 9 set pressures 0.2-0.6 MPa (exact
repeats, so 9 pressure clusters of ~111,000 pulls; 1 % plateau and 2 % pull scatter, planted
gamma 0.7) on the squeeze curve N = 600 P^1.5 N. Before issue 31 the default (CR2) interval
formed an n_g x n_g matrix per cluster: 92 GB each here.

* ``fit_gamma`` in-process, per interval: median wall time of ``--runs`` and the
  ``tracemalloc`` peak of one more run (NumPy's buffers and Python objects: the result
  keeps every point as a tuple of floats);
* ``read_friction_table`` on the CSV (the reader's share of the CLI time);
* ``exofric fit-friction --squeeze S.csv --friction F.csv`` [``--json``] as a whole process:
  wall time and peak resident memory (``ru_maxrss`` of the child).

Targets: 10^6 points in < 10 s and < 1 GiB peak, for ``fit_gamma`` and for the CLI.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
import tracemalloc  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from exofric.friction import _fit, fit_gamma  # noqa: E402
from exofric.io import read_friction_table  # noqa: E402

GAMMA = 0.7
SET_P = np.round(np.linspace(0.2, 0.6, 9), 3)
CURVE_P = np.linspace(0.1, 0.7, 25)
CURVE_N = 600.0 * CURVE_P**1.5
TIME_MAX_S = 10.0
PEAK_MAX_MB = 1024.0
#: (label, fit_gamma keywords, cluster variant): the interval paths of fit_gamma
CASES: list[tuple[str, dict[str, Any], str]] = [
    ("auto = CR2 + BM, proportional", {}, "cr2bm"),
    ("auto = CR2 + BM, affine", {"model": "affine"}, "cr2bm"),
    ("cluster CR1", {"ci": "cluster"}, "cr1"),
    ("cluster CR3", {"ci": "cluster"}, "cr3"),
    ("analytic (HC3)", {"ci": "analytic"}, "cr2bm"),
    ("ols", {"ci": "ols"}, "cr2bm"),
    ("odr", {"ci": "odr", "pressure_sd_mpa": 0.002, "friction_sd_n": 2.0}, "cr2bm"),
    ("bootstrap, 100 resamples", {"ci": "bootstrap", "n_boot": 100}, "cr2bm"),
]
# whole-process runner: wall time, ru_maxrss (KB on Linux) and exit code of one child
_CHILD = ("import json, resource, subprocess, sys, time\n"
          "t = time.perf_counter()\n"
          "r = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL)\n"
          "print(json.dumps([time.perf_counter() - t,\n"
          "                  resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss,\n"
          "                  r.returncode]))")


def make_data(points: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Pressures (MPa) and friction forces (N) of ``points`` synthetic pulls."""
    rng = np.random.default_rng(seed)
    code = rng.integers(0, SET_P.size, points)
    p = SET_P[code]
    plateau = 1.0 + 0.01 * rng.normal(0.0, 1.0, SET_P.size)
    f = GAMMA * 600.0 * p**1.5 * plateau[code] * (1.0 + 0.02 * rng.normal(0.0, 1.0, points))
    return p, f


def write_files(folder: Path, p: np.ndarray, f: np.ndarray) -> tuple[Path, Path]:
    """The friction table and the squeeze curve as CSV files in ``folder``."""
    fric, sq = folder / "friction.csv", folder / "squeeze.csv"
    np.savetxt(fric, np.column_stack([p, f]), delimiter=",", fmt=["%.4f", "%.6f"],
               header="pressure_mpa,friction_n", comments="")
    np.savetxt(sq, np.column_stack([CURVE_P, CURVE_N]), delimiter=",", fmt="%.10g",
               header="pressure_mpa,squeeze_force_n", comments="")
    return fric, sq


def time_fit(p: np.ndarray, f: np.ndarray, kw: dict[str, Any], variant: str,
             runs: int) -> dict[str, Any]:
    """Median wall time of ``runs`` fits and the tracemalloc peak of one more."""
    saved = _fit._CLUSTER_VARIANT
    _fit._CLUSTER_VARIANT = variant  # type: ignore[assignment]
    try:
        times = []
        for _ in range(runs):
            t = time.perf_counter()
            fit = fit_gamma(p, f, CURVE_P, CURVE_N, **kw)
            times.append(time.perf_counter() - t)
        del fit
        tracemalloc.start()
        try:
            fit = fit_gamma(p, f, CURVE_P, CURVE_N, **kw)
            peak = tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()
    finally:
        _fit._CLUSTER_VARIANT = saved
    return {"median_s": statistics.median(times), "peak_mb": peak / 2**20,
            "gamma_ci95": list(fit.gamma_ci95), "ci_note": fit.ci_note}


def time_cli(args: list[str], runs: int) -> dict[str, Any]:
    """Median wall time and the largest peak RSS of ``runs`` whole ``exofric`` processes."""
    walls, rss = [], []
    for _ in range(runs):
        out = subprocess.run([sys.executable, "-c", _CHILD, sys.executable, "-m", "exofric",
                              *args], capture_output=True, text=True, check=True)
        wall, kb, rc = json.loads(out.stdout)
        if rc != 0:
            raise RuntimeError(f"exofric {' '.join(args)} exited with {rc}")
        walls.append(wall)
        rss.append(kb / 1024.0)
    return {"median_s": statistics.median(walls), "peak_rss_mb": max(rss)}


def main() -> dict[str, Any]:
    """Print the table; return the measurements (``benchmarks/run.py``)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=1_000_000)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--cli-runs", type=int, default=1)
    ap.add_argument("--no-cli", action="store_true")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    p, f = make_data(args.points)
    fit_gamma(p[:1000], f[:1000], CURVE_P, CURVE_N)        # imports (SciPy) outside the timing
    res: dict[str, Any] = {"points": args.points, "clusters": int(SET_P.size), "fit_gamma": {}}
    for label, kw, variant in CASES:
        res["fit_gamma"][label] = time_fit(p, f, kw, variant, args.runs)
    with tempfile.TemporaryDirectory() as tmp:
        fric, sq = write_files(Path(tmp), p, f)
        res["csv_mb"] = fric.stat().st_size / 2**20
        t = time.perf_counter()
        read_friction_table(fric)
        res["read_friction_table_s"] = time.perf_counter() - t
        if not args.no_cli:
            base = ["fit-friction", "--squeeze", str(sq), "--friction", str(fric)]
            res["cli"] = {"table": time_cli(base, args.cli_runs),
                          "--json": time_cli([*base, "--json"], args.cli_runs)}
    ok_fit = all(v["median_s"] < TIME_MAX_S and v["peak_mb"] < PEAK_MAX_MB
                 for k, v in res["fit_gamma"].items() if k.startswith("auto"))
    res["fit_target_met"] = ok_fit
    if "cli" in res:
        res["cli_target_met"] = all(v["median_s"] < TIME_MAX_S and v["peak_rss_mb"] < PEAK_MAX_MB
                                    for v in res["cli"].values())
    if args.json:
        print(json.dumps(res))
        return res
    print(f"fit_gamma on {args.points:,} points in {SET_P.size} pressure clusters "
          f"(medians of {args.runs}; peak by tracemalloc)")
    print(f"{'interval':<32}{'time s':>9}{'peak MB':>10}")
    for label, v in res["fit_gamma"].items():
        print(f"{label:<32}{v['median_s']:>9.2f}{v['peak_mb']:>10.0f}")
    print(f"read_friction_table ({res['csv_mb']:.0f} MB CSV): {res['read_friction_table_s']:.2f} s")
    if "cli" in res:
        for label, v in res["cli"].items():
            print(f"exofric fit-friction ({label}): {v['median_s']:.2f} s, peak RSS "
                  f"{v['peak_rss_mb']:.0f} MB")
    print(f"target (< {TIME_MAX_S:g} s, < {PEAK_MAX_MB:g} MB): fit_gamma "
          f"{'met' if ok_fit else 'NOT met'}"
          + ("" if "cli" not in res else
             f"; CLI {'met' if res['cli_target_met'] else 'NOT met'}"))
    return res


if __name__ == "__main__":
    main()
