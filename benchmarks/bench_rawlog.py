"""Benchmark: reading raw rig logs and reducing them (``exofric reduce``; issue 14).

Run: ``python benchmarks/bench_rawlog.py [--runs 5] [--json]``.
Single-threaded. Units: s (CPU time, ``time.process_time``, medians of interleaved runs).

* ``read``: :func:`exofric.io.read_raw_log` on a 1e6-row log (time, pressure, force,
  displacement) as CSV in MPa/N/mm, as CSV in kPa/lbf/m (pint conversion) and as Parquet,
  against ``pandas.read_csv`` of the same CSV (the floor a reader that checks nothing reaches).
* ``reduce``: :func:`exofric.friction.reduce_log` on virtual-rig logs of 6 and 21 plateaus
  (500 Hz, 10 pulls per plateau), with and without the displacement column; per-sample cost.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import statistics  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from exofric.friction import RawRigConfig, reduce_log, simulate_raw_log  # noqa: E402
from exofric.io import read_raw_log, write_raw_log  # noqa: E402

LBF_N = 4.4482216152605


def _cpu(fn: Any) -> float:
    c = time.process_time()
    fn()
    return time.process_time() - c


def bench_read(runs: int, n: int = 1_000_000) -> dict[str, Any]:
    """Median CPU seconds per reader on an n-row log, and the ratio to pandas.read_csv."""
    d = Path(tempfile.mkdtemp())
    t = np.arange(n) * 0.001
    base = pd.DataFrame({"time_s": t, "pressure_mpa": 0.1 + 0.3 * np.sin(t),
                         "force_n": 5 + np.cos(t), "displacement_mm": 0.1 * t})
    other = pd.DataFrame({"time_s": t, "pressure_kpa": base.pressure_mpa * 1e3,
                          "force_lbf": base.force_n / LBF_N,
                          "displacement_m": base.displacement_mm / 1e3})
    files = {"csv MPa/N/mm": write_raw_log(d / "a.csv", base),
             "csv kPa/lbf/m": write_raw_log(d / "b.csv", other),
             "parquet MPa/N/mm": write_raw_log(d / "a.parquet", base)}
    read_raw_log(files["csv kPa/lbf/m"])                # pint's import, once
    times: dict[str, list[float]] = {k: [] for k in ["pandas.read_csv", *files]}
    for _ in range(runs):
        times["pandas.read_csv"].append(_cpu(lambda: pd.read_csv(files["csv MPa/N/mm"],
                                                                 comment="#")))
        for k, p in files.items():
            times[k].append(_cpu(lambda p=p: read_raw_log(p)))
    floor = statistics.median(times["pandas.read_csv"])
    return {"rows": n, "median_s": {k: statistics.median(v) for k, v in times.items()},
            "ratio_to_pandas": {k: statistics.median(v) / floor for k, v in times.items()}}


def bench_reduce(runs: int) -> list[dict[str, Any]]:
    """Median CPU seconds of reduce_log per log size and pull detection."""
    out = []
    p = np.linspace(0.1, 0.7, 25)
    for sweep, sp in (("up", np.linspace(0.1, 0.6, 6)), ("up-down", np.linspace(0.1, 0.6, 11))):
        log = simulate_raw_log(p, 600 * p**1.5, 0.7, sp, config=RawRigConfig(sweep=sweep),
                               seed=1).to_frame()
        for detection, frame in (("displacement", log),
                                 ("force", log.drop(columns="displacement_mm"))):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                ts = [_cpu(lambda f=frame: reduce_log(f)) for _ in range(runs)]
            m = statistics.median(ts)
            plateaus = len(sp) if sweep == "up" else 2 * len(sp) - 1
            out.append({"samples": len(frame), "plateaus": plateaus, "detection": detection,
                        "median_s": m, "us_per_sample": 1e6 * m / len(frame)})
    return out


def main() -> dict[str, Any]:
    """Print the tables; return them (``benchmarks/run.py``)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    res = {"read": bench_read(args.runs), "reduce": bench_reduce(args.runs)}
    if args.json:
        print(json.dumps(res))
        return res
    r = res["read"]
    print(f"read_raw_log, {r['rows']:.0e} rows x 4 columns (CPU s, median of {args.runs})")
    for k, v in r["median_s"].items():
        print(f"  {k:<20}{v:8.3f} s   x{r['ratio_to_pandas'][k]:.2f} pandas.read_csv")
    print("reduce_log on virtual-rig logs (500 Hz, 10 pulls per plateau)")
    for row in res["reduce"]:
        print(f"  {row['samples']:>8} samples, {row['plateaus']:>2} plateaus, pulls from the "
              f"{row['detection']:<12}{row['median_s']:7.3f} s  "
              f"({row['us_per_sample']:.2f} us/sample)")
    return res


if __name__ == "__main__":
    main()
