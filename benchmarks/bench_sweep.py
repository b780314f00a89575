"""Benchmark of ``exofric sweep``: whole-process wall time serial vs 1 and 2 worker processes vs
the automatic choice (and the Dask LocalCluster used before issue 22) on a 16-design sweep.

Run: ``.venv/bin/python benchmarks/bench_sweep.py [--runs 5] [--no-dask] [--mesh 4x32] [--json]``.

* The sweep is ``benchmarks/sweep-16.toml``: ``examples/sweep-small.toml`` doubled by a second
  hardness, 24 designs of which 16 are solved (2 x 24 quad9 mesh, 490 dofs, 12 pressures).
* Each mode is a fresh ``python -m exofric sweep sweep-16.toml --out TMP --json`` process
  (imports, start-up, solves, Parquet writes, close-down: everything a user waits for) into a
  new directory; the modes are interleaved (run 1 of every mode, then run 2, ... with the order
  rotated) and the medians reported, with the CPU time of the process tree (user + sys of the
  finished children), the sweep's own ``wall_time_s`` (``run_sweep`` alone: no interpreter
  start-up, imports or exit) and the 1-minute load average before each run: the machine is
  shared, so compare the ratios of one session, not absolute times across sessions.
  ``--mesh 4x32`` runs the same designs on another mesh (costlier solves). The processes use
  cached byte code as an installation does (:func:`process_env`; before 2026-11-27 they
  compiled exofric's sources in every run where ``PYTHONDONTWRITEBYTECODE`` was set).
  :func:`ratio_2_vs_1` measures only the target's pair (``benchmarks/run.py``).
* Then, in this process: the start-up of the local worker pool (fork, every worker up) and of a
  Dask LocalCluster (start + close), and the dispatch cost per design with an instant stand-in
  solver (worker pool vs the serial loop), i.e. the inputs of ``exofric.design.plan_execution``
  (``exofric.defaults.SWEEP_POOL_START_S``, ``SWEEP_TASK_OVERHEAD_S``).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import logging  # noqa: E402
import resource  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402
from types import SimpleNamespace  # noqa: E402
from typing import Any  # noqa: E402

HERE = Path(__file__).resolve().parent
CONFIG = HERE / "sweep-16.toml"
#: mode -> extra ``exofric sweep`` arguments
MODES: dict[str, list[str]] = {
    "serial": ["--serial"],
    "workers1": ["--workers", "1"],
    "workers2": ["--workers", "2"],
    "auto": [],
    "dask1": ["--executor", "dask", "--workers", "1"],
    "dask2": ["--executor", "dask", "--workers", "2"],
}
LABELS = {"serial": "--serial", "workers1": "--workers 1", "workers2": "--workers 2",
          "auto": "(default: auto)", "dask1": "Dask LocalCluster, 1 worker (before)",
          "dask2": "Dask LocalCluster, 2 workers (before)"}


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def process_env() -> dict[str, str]:
    """The sweep processes' environment: byte code cached as in any installation (even where
    ``PYTHONDONTWRITEBYTECODE`` is set: compiling exofric's sources in every process is ~0.2 s
    of serial time no user pays), in ``$TMPDIR/exofric-bench-pycache``."""
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPYCACHEPREFIX"] = str(Path(tempfile.gettempdir()) / "exofric-bench-pycache")
    return env


def ratio_2_vs_1(runs: int = 5, config: Path = CONFIG) -> dict[str, Any]:
    """The 2-worker speed-up: ``runs`` interleaved pairs of ``--workers 1`` / ``--workers 2``
    whole processes; the ratio of each pair (wall s of 1 worker / of 2), their median and range.
    """
    res = whole_process(["workers1", "workers2"], runs, config)
    w1 = [r["wall_s"] for r in res["workers1"]]
    w2 = [r["wall_s"] for r in res["workers2"]]
    ratios = [a / b for a, b in zip(w1, w2, strict=True)]
    return {"workers1_wall_s": w1, "workers2_wall_s": w2, "ratios": ratios,
            "ratio_of_medians": statistics.median(w1) / statistics.median(w2),
            "load": [r["load"] for m in res.values() for r in m]}


def run_cli(args: list[str], config: Path = CONFIG) -> dict[str, Any]:
    """One whole ``exofric sweep`` process into a fresh directory: wall and CPU (s), summary."""
    with tempfile.TemporaryDirectory() as tmp:
        load = os.getloadavg()[0]
        cpu0, t0 = _children_cpu(), time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "exofric", "sweep", str(config), "--out",
                               str(Path(tmp) / "out"), "--json", *args],
                              capture_output=True, text=True, timeout=900, env=process_env())
        wall = time.perf_counter() - t0
        cpu = _children_cpu() - cpu0
    if proc.returncode != 0:
        raise RuntimeError(f"exofric sweep {' '.join(args)} failed: {proc.stderr[-2000:]}")
    summary = json.loads(proc.stdout)
    if summary["computed"] != 16 or summary["failed"] != 0:
        raise RuntimeError(f"unexpected sweep summary: {summary}")
    return {"wall_s": wall, "cpu_s": cpu, "load": load, "summary": summary}


def whole_process(modes: list[str], runs: int, config: Path = CONFIG
                  ) -> dict[str, list[dict[str, Any]]]:
    """``runs`` interleaved whole-process runs of every mode (order rotated each round)."""
    out: dict[str, list[dict[str, Any]]] = {m: [] for m in modes}
    run_cli(MODES["serial"], config)  # warm the file cache (imports), not counted
    for r in range(runs):
        order = modes[r % len(modes):] + modes[:r % len(modes)]
        for m in order:
            out[m].append(run_cli(MODES[m], config))
    return out


def with_mesh(mesh: str, folder: Path) -> Path:
    """``sweep-16.toml`` with the mesh ``"NRxNC"`` (e.g. ``"4x32"``), written into ``folder``."""
    nr, nc = (int(x) for x in mesh.lower().split("x"))
    text = CONFIG.read_text().replace("n_radial = 2", f"n_radial = {nr}")
    path = folder / f"sweep-16-{nr}x{nc}.toml"
    path.write_text(text.replace("n_circ = 24", f"n_circ = {nc}"))
    return path


def in_process(n_overhead: int = 200) -> dict[str, float]:
    """Pool and LocalCluster start-up (s) and dispatch cost per design (ms), in this process."""
    from exofric.design import BLAS_ENV, SweepPool, parse_sweep, run_sweep

    out: dict[str, float] = {}
    starts: dict[int, list[float]] = {1: [], 2: []}
    for _ in range(5):
        for k in (1, 2):
            t0 = time.perf_counter()
            with SweepPool(k):
                starts[k].append(time.perf_counter() - t0)
    for k in (1, 2):
        out[f"pool{k}_start_s"] = statistics.median(starts[k])
    try:
        from distributed import Client, LocalCluster

        t0 = time.perf_counter()
        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                          dashboard_address=None, silence_logs=logging.ERROR,
                          env=dict(BLAS_ENV)) as cluster, Client(cluster) as client:
            client.wait_for_workers(2)
            out["dask2_start_s"] = time.perf_counter() - t0
            t0 = time.perf_counter()
        out["dask2_close_s"] = time.perf_counter() - t0
    except ImportError:  # the [dask] extra is not installed
        pass
    spec = parse_sweep({"pressures_mpa": [0.1, 0.2], "solver": {"n_radial": 1, "n_circ": 12},
                        "grid": {"hole_mm": [10.0 + 0.001 * i for i in range(n_overhead)]}})
    n = len(spec.runnable)
    times = {}
    for key, kw in (("serial", {"serial": True}), ("processes", {"workers": 1})):
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            run_sweep(spec, tmp, solve_fn=instant_squeeze, **kw)
            times[key] = time.perf_counter() - t0
    out["bookkeeping_per_design_ms"] = times["serial"] / n * 1e3
    out["dispatch_per_design_ms"] = max(0.0, times["processes"] - times["serial"]
                                        - out["pool1_start_s"]) / n * 1e3
    return out


class _Result:
    """A precomputed squeeze result (stand-in solver for the overhead measurement)."""

    def __init__(self, n: int) -> None:
        self.pressure_mpa = self.squeeze_force_n = self.squeeze_force_n_per_mm = \
            self.wall_force_n = [0.1 * i for i in range(1, n + 1)]
        self.contact = SimpleNamespace(max_penetration_mm=self.pressure_mpa)
        self.newton_iterations = [5] * n
        self.contact_onset_pressure_mpa = 0.1
        self.dofs = 490
        self.solve_time_s = 0.0


def instant_squeeze(structure: Any, material: Any, pressures_mpa: Any, **kw: Any) -> _Result:
    """Stand-in for exofric.simulate.squeeze that costs nothing."""
    return _Result(len(pressures_mpa))


def main(runs: int = 5, dask: bool = True, mesh: str = "2x24") -> dict[str, Any]:
    """Whole-process sweep times (medians of interleaved runs), ratios, start-up costs."""
    modes = [m for m in MODES if dask or not m.startswith("dask")]
    nr, nc = (int(x) for x in mesh.lower().split("x"))
    dofs = 2 * (2 * nr + 1) * (2 * nc + 1)
    load0 = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        res = whole_process(modes, runs, with_mesh(mesh, Path(tmp)))
    load1 = os.getloadavg()
    out: dict[str, Any] = {"config": CONFIG.name, "designs_solved": 16,
                           "mesh": f"{nr} x {nc} quad9", "dofs": dofs, "pressures": 12,
                           "runs": runs,
                           "cpus": os.cpu_count() or 1, "load_average_1min_start": load0[0],
                           "load_average_1min_end": load1[0]}
    for m in modes:
        out[f"{m}_wall_s"] = statistics.median(r["wall_s"] for r in res[m])
        out[f"{m}_wall_min_s"] = min(r["wall_s"] for r in res[m])
        out[f"{m}_cpu_s"] = statistics.median(r["cpu_s"] for r in res[m])
        out[f"{m}_sweep_s"] = statistics.median(r["summary"]["wall_time_s"] for r in res[m])
        out[f"{m}_load_median"] = statistics.median(r["load"] for r in res[m])
    auto = res["auto"][-1]["summary"]
    out["auto_execution"] = auto["execution"]
    out["auto_workers"] = auto["workers"]
    out["auto_reason"] = auto["execution_reason"]
    out["speedup_workers2_vs_workers1"] = out["workers1_wall_s"] / out["workers2_wall_s"]
    out["speedup_workers2_vs_serial"] = out["serial_wall_s"] / out["workers2_wall_s"]
    out["speedup_auto_vs_serial"] = out["serial_wall_s"] / out["auto_wall_s"]
    out["sweep_only_speedup_workers2_vs_workers1"] = (out["workers1_sweep_s"]
                                                      / out["workers2_sweep_s"])
    if dask:
        out["speedup_dask2_vs_dask1"] = out["dask1_wall_s"] / out["dask2_wall_s"]
        out["speedup_workers2_vs_dask2"] = out["dask2_wall_s"] / out["workers2_wall_s"]
    out.update(in_process())

    print(f"exofric sweep benchmark: {CONFIG.name}, 16 designs solved x 12 pressures, mesh "
          f"{out['mesh']} ({dofs} dofs); whole process, median of {runs} interleaved runs; "
          f"{out['cpus']} CPUs, load average {load0[0]:.2f} -> {load1[0]:.2f} (shared machine)")
    print(f"  {'mode':40s} {'wall s':>7s} {'min s':>7s} {'CPU s':>7s} {'sweep s':>7s} "
          f"{'load':>5s} {'x serial':>8s}")
    for m in modes:
        print(f"  {LABELS[m]:40s} {out[m + '_wall_s']:7.2f} {out[m + '_wall_min_s']:7.2f} "
              f"{out[m + '_cpu_s']:7.2f} {out[m + '_sweep_s']:7.2f} "
              f"{out[m + '_load_median']:5.2f} {out['serial_wall_s'] / out[m + '_wall_s']:8.2f}")
    print(f"  2 workers vs 1 worker: x{out['speedup_workers2_vs_workers1']:.2f} whole process "
          f"(target >= 1.6), x{out['sweep_only_speedup_workers2_vs_workers1']:.2f} run_sweep "
          f"alone; 2 workers vs --serial: x{out['speedup_workers2_vs_serial']:.2f}")
    print(f"  auto chose {out['auto_execution']} ({out['auto_workers']}): {out['auto_reason']}")
    line = (f"  start-up: worker pool (fork) 1 / 2 workers {out['pool1_start_s'] * 1e3:.0f} / "
            f"{out['pool2_start_s'] * 1e3:.0f} ms")
    if "dask2_start_s" in out:
        line += (f"; Dask LocalCluster(2) start {out['dask2_start_s']:.2f} s, close "
                 f"{out['dask2_close_s']:.2f} s")
    print(line)
    print(f"  per design with an instant solver: bookkeeping (Parquet, cache) "
          f"{out['bookkeeping_per_design_ms']:.1f} ms, worker dispatch on top "
          f"{out['dispatch_per_design_ms']:.2f} ms")
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5, help="interleaved runs per mode")
    ap.add_argument("--no-dask", action="store_true", help="skip the Dask LocalCluster modes")
    ap.add_argument("--mesh", default="2x24", help="NRxNC mesh of the designs (default 2x24)")
    ap.add_argument("--json", action="store_true", help="print the results as JSON at the end")
    a = ap.parse_args()
    result = main(a.runs, not a.no_dask, a.mesh)
    if a.json:
        print(json.dumps(result, default=str))
