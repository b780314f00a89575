"""Benchmark of the command line's start-up: whole-process wall time of short commands.

Run: ``.venv/bin/python benchmarks/bench_startup.py [--runs 7] [--json]``.

Each row is a fresh process (``subprocess.run``, output captured), timed with
``time.perf_counter`` around it (wall) and by the CPU time (user + sys) of the finished child
(the number to read on a loaded machine: one thread, so on an idle machine wall ~ CPU); the
rows are run interleaved (round-robin, ``--runs`` rounds) so that a burst of load from other
processes hits every row alike, and the median and the range (min-max) are reported.
``python -c pass`` is the floor (the interpreter alone); "over floor" is the median minus it.

* ``import exofric``: the lazy facade (every Dask worker and the CLI pay it).
* ``exofric --help``: typer/click/rich and the command modules' option definitions only.
* ``exofric material --shore 62.5``: the lightest computing command (no NumPy, no pydantic).
* ``exofric squeeze ... --accuracy draft`` and the default (standard) squeeze of the base
  group: the imports the solve needs (NumPy, scipy.sparse/linalg, threadpoolctl) plus the
  solve itself; nothing else heavy before it (no pandas, pyarrow, matplotlib, pydantic,
  scipy.optimize).

Targets (issue 37): ``material`` <= 0.2 s, default ``squeeze`` <= 0.6 s (whole process; judged
on the CPU time). BLAS/OpenMP
are pinned to one thread in the children; byte-code caching is on (as in any installation, even
where ``PYTHONDONTWRITEBYTECODE`` is set), with the ``.pyc`` files in a temporary
``PYTHONPYCACHEPREFIX`` written by a warm-up run of every row. On a shared machine the absolute
times vary; the difference to the floor is the number to compare.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
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
    ("exofric squeeze (base), default accuracy", SQUEEZE, 0.6),
]
MATERIAL_ROW, SQUEEZE_ROW = ROWS[3][0], ROWS[5][0]


def _env(pycache: str) -> dict[str, str]:
    env = dict(os.environ)
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        env[var] = "1"
    # byte-compiled modules as in any installation (the warm-up run writes them), kept in a
    # temporary directory, not next to the sources
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPYCACHEPREFIX"] = pycache
    return env


def measure(runs: int = 7, labels: list[str] | None = None) -> dict[str, Any]:
    """Median whole-process wall and CPU time (s) of every row over ``runs`` interleaved rounds.

    ``labels`` selects rows (default all; the floor is always measured). Each row has
    ``wall_s`` and ``cpu_s`` (every run), their medians, minima and maxima.
    """
    rows = [r for r in ROWS if labels is None or r[0] in labels or r is ROWS[0]]
    with tempfile.TemporaryDirectory(prefix="exofric-pycache-") as pycache:
        return _measure(runs, _env(pycache), rows)


def _child_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def _measure(runs: int, env: dict[str, str],
             rows: list[tuple[str, list[str], float | None]]) -> dict[str, Any]:
    times: dict[str, list[float]] = {label: [] for label, _, _ in rows}
    cpus: dict[str, list[float]] = {label: [] for label, _, _ in rows}
    failed: dict[str, str] = {}
    for label, argv, _ in rows:  # warm-up: file cache, .pyc files; a failing row is reported
        r = subprocess.run(argv, capture_output=True, env=env)
        if r.returncode != 0:
            failed[label] = f"exit {r.returncode}: {r.stderr.decode().strip()[-300:]}"
    for _ in range(runs):
        for label, argv, _ in rows:
            if label in failed:
                continue
            c0, t0 = _child_cpu(), time.perf_counter()
            subprocess.run(argv, capture_output=True, env=env, check=True)
            times[label].append(time.perf_counter() - t0)
            cpus[label].append(_child_cpu() - c0)
    floor = statistics.median(times[ROWS[0][0]])
    out: dict[str, Any] = {"runs": runs, "rows": {}}
    for label, _, target in rows:
        if label in failed:
            out["rows"][label] = {"error": failed[label], "target_s": target}
            continue
        med, cpu = statistics.median(times[label]), statistics.median(cpus[label])
        out["rows"][label] = {
            "median_s": med, "min_s": min(times[label]), "max_s": max(times[label]),
            "cpu_median_s": cpu, "cpu_min_s": min(cpus[label]), "cpu_max_s": max(cpus[label]),
            "wall_s": times[label], "cpu_s": cpus[label],
            "over_floor_s": med - floor,
            "target_s": target,
            "meets_target": None if target is None else cpu <= target,
        }
    return out


def report(res: dict[str, Any]) -> None:
    """Print the table of :func:`measure`'s result."""
    print(f"CLI start-up, whole process, median of {res['runs']} interleaved runs (s)")
    print(f"{'command':<44} {'wall':>6} {'min-max':>11} {'CPU':>6} {'min-max':>11} "
          f"{'over floor':>10} {'target':>7}")
    for label, r in res["rows"].items():
        if "error" in r:
            print(f"{label:<44} FAILED ({r['error'].splitlines()[-1]})")
            continue
        tgt = "" if r["target_s"] is None else (
            f"<= {r['target_s']:g}" + ("" if r["meets_target"] else " !"))
        print(f"{label:<44} {r['median_s']:6.3f} {r['min_s']:5.3f}-{r['max_s']:<5.3f} "
              f"{r['cpu_median_s']:6.3f} {r['cpu_min_s']:5.3f}-{r['cpu_max_s']:<5.3f} "
              f"{r['over_floor_s']:10.3f} {tgt:>7}")
    print("(squeeze includes the solve; targets judged on the CPU time; '!' marks a miss)")


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
