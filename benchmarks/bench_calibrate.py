"""Benchmark: joint material calibration with the FE model in the loop, and CLI input rejection.

Run: ``python benchmarks/bench_calibrate.py [--runs 3] [--json]``.
Single-threaded (BLAS/OpenMP threads pinned to 1 before NumPy is imported). Units: s.

* ``joint``: ``calibrate(InflationData.paper_test(), 8.3, method="joint", model="fe",
  tube_id_mm=4.97)`` (Shore and tube ID from the Table 1 test data), a fresh FE cache each
  run; median wall time, FE solves per run. Target (issue 5): < 10 s (measured ~1.5 s).
* ``bad input``: the slowest of the bad-input cases of ``tests/test_cli_contract.py`` run
  through ``exofric.cli.run`` in process (each must be rejected before any solve or sweep).
  Target: < 1 s each (a solve or a sweep takes seconds).

These two speed claims used to be wall-clock asserts in the tests; they live here instead.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import contextlib  # noqa: E402
import io  # noqa: E402
import json  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402
from typing import Any  # noqa: E402

from exofric.calibration import InflationData, calibrate  # noqa: E402
from exofric.cli import run as cli_run  # noqa: E402

TARGET_JOINT_S = 10.0
TARGET_REJECT_S = 1.0
#: The bad-input cases of tests/test_cli_contract.py (each exits 2 with one line).
BAD_INPUT = [
    ["calibrate", "--data", "nope.csv", "--tube-od", "8.3"],
    ["sweep", "nope.toml", "--out", "/tmp/exofric-x"],
    ["control", "--controller", "xyz", "--target-friction", "54.4"],
    ["invert", "--gamma", "0.7168", "--cubic", "1,2", "--target-friction", "54.4"],
    ["design", "--target-torque", "-4"],
    ["design", "--objective", "foo"],
    ["reproduce", "--out", "/dev/null/x"],
    ["predict", "--gamma", "-1", "--paper"],
    ["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
     "--shore", "62.5", "--length", "-5"],
    ["inflate", "--shore", "62.5", "--tube-od", "8.3", "--tube-id", "4.97", "--pressures",
     "0.1,nan"],
]


def run(runs: int = 3) -> dict[str, Any]:
    """Time the joint calibration and the CLI's bad-input rejections (s)."""
    times, calls = [], 0
    for _ in range(runs):
        t0 = time.perf_counter()
        r = calibrate(InflationData.paper_test(), 8.3, method="joint", model="fe",
                      tube_id_mm=4.97)
        times.append(time.perf_counter() - t0)
        calls = r.n_model_calls
    reject: dict[str, float] = {}
    for args in BAD_INPUT:
        sink = io.StringIO()
        t0 = time.perf_counter()
        with contextlib.redirect_stdout(sink), contextlib.redirect_stderr(sink):
            code = cli_run(args)
        reject[" ".join(args[:2])] = time.perf_counter() - t0
        if code != 2:
            raise RuntimeError(f"{args}: exit {code}, expected 2")
    slowest = max(reject, key=reject.__getitem__)
    return {"joint_median_s": statistics.median(times), "joint_runs": runs,
            "joint_fe_solves": calls, "joint_target_s": TARGET_JOINT_S,
            "joint_meets_target": statistics.median(times) < TARGET_JOINT_S,
            "reject_max_s": reject[slowest], "reject_slowest": slowest,
            "reject_target_s": TARGET_REJECT_S,
            "reject_meets_target": reject[slowest] < TARGET_REJECT_S}


def main() -> dict[str, Any]:
    """Command line: ``--runs N`` (median of N joint calibrations), ``--json``."""
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--runs", type=int, default=3, help="joint calibrations (median)")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    a = ap.parse_args()
    out = run(a.runs)
    if a.json:
        print(json.dumps(out))
        return out
    print("exofric calibration benchmark (one thread)")
    print(f"  joint calibration, Table 1 test data, FE : {out['joint_median_s']:6.2f} s "
          f"(median of {out['joint_runs']}, {out['joint_fe_solves']} FE solves; "
          f"target < {TARGET_JOINT_S:g} s: {'met' if out['joint_meets_target'] else 'MISSED'})")
    print(f"  slowest bad-input rejection ({out['reject_slowest']}) : "
          f"{out['reject_max_s']:6.3f} s (target < {TARGET_REJECT_S:g} s: "
          f"{'met' if out['reject_meets_target'] else 'MISSED'})")
    return out


if __name__ == "__main__":
    main()
