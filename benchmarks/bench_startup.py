"""Benchmark of the command line's start-up: whole-process wall time of short commands.

Run: ``.venv/bin/python benchmarks/bench_startup.py [--runs 7] [--json]``.

Each row is a fresh process (``subprocess.run``, output captured), timed with
``time.perf_counter`` around it; the rows are run interleaved (round-robin, ``--runs`` rounds)
so that a burst of load from other processes hits every row alike, and the median is reported.
``python -c pass`` is the floor (the interpreter alone); "over floor" is the median minus it.

* ``import exofric``: the lazy facade (every Dask worker and the CLI pay it).
* ``exofric --help``: typer/click/rich and the command modules' option definitions only.
* ``exofric material --shore 62.5``: the lightest computing command (no SciPy).
* ``exofric squeeze ... --accuracy draft`` and the default (standard) squeeze of the base
  group: the imports the solve needs (NumPy, scipy.sparse/linalg, threadpoolctl) plus the
  solve itself; nothing else heavy before it (no pandas, pyarrow, matplotlib).

Targets: ``material`` <= 0.2 s, default ``squeeze`` <= 0.45 s (whole process). BLAS/OpenMP
are pinned to one thread in the children; byte-code caching is on (as in any installation, even
where ``PYTHONDONTWRITEBYTECODE`` is set), with the ``.pyc`` files in a temporary
``PYTHONPYCACHEPREFIX`` written by a warm-up run of every row. On a shared machine the absolute
times vary; the difference to the floor is the number to compare.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

PY = sys.executable
EXOFRIC = str(Path(PY).with_name("exofric"))
SQUEEZE = [EXOFRIC, "squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97",
           "--wire", "1.6", "--shore", "62.5"]

#: (label, argv, target in s or None)
ROWS: list[tuple[str, list[str], float | None]] = [
    ("python -c pass (floor)", [PY, "-c", "pass"], None),
    ("python -c 'import exofric'", [PY, "-c", "import exofric"], None),
    ("exofric --help", [EXOFRIC, "--help"], 0.2),
    ("exofric material --shore 62.5", [EXOFRIC, "material", "--shore", "62.5"], 0.2),
    ("exofric squeeze (base) --accuracy draft", [*SQUEEZE, "--accuracy", "draft"], None),
    ("exofric squeeze (base), default accuracy", SQUEEZE, 0.45),
]


def _env(pycache: str) -> dict[str, str]:
    env = dict(os.environ)
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        env[var] = "1"
    # byte-compiled modules as in any installation (the warm-up run writes them), kept in a
    # temporary directory, not next to the sources
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPYCACHEPREFIX"] = pycache
    return env


def measure(runs: int = 7) -> dict[str, Any]:
    """Median whole-process wall time (s) of every row over ``runs`` interleaved rounds."""
    with tempfile.TemporaryDirectory(prefix="exofric-pycache-") as pycache:
        return _measure(runs, _env(pycache))


def _measure(runs: int, env: dict[str, str]) -> dict[str, Any]:
    times: dict[str, list[float]] = {label: [] for label, _, _ in ROWS}
    failed: dict[str, str] = {}
    for label, argv, _ in ROWS:  # warm-up: file cache, .pyc files; a failing row is reported
        r = subprocess.run(argv, capture_output=True, env=env)
        if r.returncode != 0:
            failed[label] = f"exit {r.returncode}: {r.stderr.decode().strip()[-300:]}"
    for _ in range(runs):
        for label, argv, _ in ROWS:
            if label in failed:
                continue
            t0 = time.perf_counter()
            subprocess.run(argv, capture_output=True, env=env, check=True)
            times[label].append(time.perf_counter() - t0)
    floor = statistics.median(times[ROWS[0][0]])
    out: dict[str, Any] = {"runs": runs, "rows": {}}
    for label, _, target in ROWS:
        if label in failed:
            out["rows"][label] = {"error": failed[label], "target_s": target}
            continue
        med = statistics.median(times[label])
        out["rows"][label] = {
            "median_s": med,
            "min_s": min(times[label]),
            "over_floor_s": med - floor,
            "target_s": target,
            "meets_target": None if target is None else med <= target,
        }
    return out


def report(res: dict[str, Any]) -> None:
    """Print the table of :func:`measure`'s result."""
    print(f"CLI start-up, whole process, median of {res['runs']} interleaved runs (wall, s)")
    print(f"{'command':<44} {'median':>7} {'min':>7} {'over floor':>10} {'target':>7}")
    for label, r in res["rows"].items():
        if "error" in r:
            print(f"{label:<44} FAILED ({r['error'].splitlines()[-1]})")
            continue
        tgt = "" if r["target_s"] is None else (
            f"<= {r['target_s']:g}" + ("" if r["meets_target"] else " !"))
        print(f"{label:<44} {r['median_s']:7.3f} {r['min_s']:7.3f} {r['over_floor_s']:10.3f} "
              f"{tgt:>7}")
    print("(squeeze includes the solve; '!' marks a missed target)")


def main(argv: list[str] | None = None) -> dict[str, Any]:
    """Run the start-up benchmark, print its table and return the numbers."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("--runs", type=int, default=7, help="interleaved rounds (default 7)")
    ap.add_argument("--json", action="store_true", help="print the result as JSON")
    args = ap.parse_args(argv)
    res = measure(args.runs)
    if args.json:
        print(json.dumps(res))
    else:
        report(res)
    return res


if __name__ == "__main__":
    main()
