"""Benchmark of design-space sweeps: designs per second with 1 and 2 Dask workers, and the
per-design overhead of Dask against a plain in-process loop.

Run: ``.venv/bin/python benchmarks/bench_sweep.py [--designs 12] [--small]``.

* ``plain loop``: :func:`exofric.simulate.squeeze` called design after design (no I/O).
* ``serial sweep``: :func:`exofric.design.run_sweep` with ``serial=True`` (adds the Parquet
  writes, the cache bookkeeping and the post-processing).
* ``dask k``: a warm ``LocalCluster`` with k processes x 1 thread (workers have already
  imported exofric and solved designs), reached through ``scheduler=``, so cluster
  start-up is excluded; the start-up is timed on its own.
* overhead: the same sweeps with an instant stand-in solver (a precomputed result), so
  that only the bookkeeping is timed: per design, serial sweep (Parquet write, cache,
  post-processing) vs a bare loop, and Dask (1 worker) vs the serial sweep (pickling,
  scheduling, result transfer). Being CPU-light, it is little disturbed by other load.
"""

from __future__ import annotations

import argparse
import logging
import os
import tempfile
import time
from dataclasses import replace
from typing import Any

from exofric.design import BLAS_ENV, SweepSpec, parse_sweep, run_sweep
from exofric.simulate import squeeze


def make_spec(n_designs: int, small: bool) -> SweepSpec:
    """``n_designs`` valid designs (hole x wire grid around the base), 12 pressures."""
    holes = [10.0 + 0.05 * i for i in range(-(-n_designs // 3))]
    data: dict[str, Any] = {
        "name": "bench",
        "pressures_mpa": [round(0.05 * i, 2) for i in range(1, 13)],
        "grid": {"hole_mm": holes, "wire_mm": [1.1, 1.35, 1.6]},
    }
    if small:
        data["solver"] = {"n_radial": 1, "n_circ": 12, "grading": 6.0}
    spec = parse_sweep(data)
    return replace(spec, designs=spec.designs[:n_designs])


def _plain(spec: SweepSpec) -> float:
    t0 = time.perf_counter()
    for d in spec.runnable:
        squeeze(d.structure(), spec.material.material(d.shore), list(spec.pressures_mpa),
                mesh=spec.solver.mesh(), penalty=spec.solver.penalty_n_per_mm3,
                density=spec.solver.density_t_per_mm3, settings=spec.solver.newton(),
                keep_fields=False)
    return time.perf_counter() - t0


class _Result:
    """A precomputed squeeze result (stand-in solver for the overhead measurement)."""

    def __init__(self, n: int) -> None:
        self.pressure_mpa = self.squeeze_force_n = self.squeeze_force_n_per_mm = \
            self.wall_force_n = self.max_penetration_mm = [0.1 * i for i in range(1, n + 1)]
        self.newton_iterations = [5] * n
        self.contact_onset_pressure_mpa = 0.1
        self.dofs = 490
        self.solve_time_s = 0.0


def instant_squeeze(structure: Any, material: Any, pressures_mpa: Any, **kw: Any) -> _Result:
    """Stand-in for exofric.simulate.squeeze that costs nothing."""
    return _Result(len(pressures_mpa))


def _cluster(workers: int) -> Any:
    from distributed import LocalCluster

    return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                        host="127.0.0.1", dashboard_address=None, silence_logs=logging.ERROR,
                        env=dict(BLAS_ENV))


def _timed_sweep(spec: SweepSpec, **kw: Any) -> float:
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        run = run_sweep(spec, tmp, **kw)
        wall = time.perf_counter() - t0
    assert run.summary.computed == len(spec.runnable) and run.summary.failed == 0
    return wall


def main(n_designs: int = 12, small: bool = False, n_overhead: int = 200) -> dict[str, float]:
    """Time FE sweeps (plain loop, serial, warm 1- and 2-worker LocalClusters) and overheads."""
    from distributed import Client

    spec = make_spec(n_designs, small)
    warm = replace(spec, designs=spec.designs[:2])
    n = len(spec.runnable)
    _plain(warm)                                        # imports and first-call costs
    out: dict[str, float] = {"designs": float(n), "cpus": float(os.cpu_count() or 1),
                             "load_average_1min": os.getloadavg()[0]}
    out["plain_loop_s"] = _plain(spec)
    out["serial_sweep_s"] = _timed_sweep(spec, serial=True)
    many = make_spec(n_overhead, True)
    t0 = time.perf_counter()
    for d in many.runnable:
        instant_squeeze(d.structure(), None, many.pressures_mpa)
    bare = time.perf_counter() - t0
    out["bookkeeping_serial_ms"] = (_timed_sweep(many, serial=True, solve_fn=instant_squeeze)
                                    - bare) / len(many.runnable) * 1e3
    for k in (1, 2):
        t0 = time.perf_counter()
        with _cluster(k) as cluster, Client(cluster) as client:
            client.wait_for_workers(k)
            out[f"dask{k}_startup_s"] = time.perf_counter() - t0
            addr = cluster.scheduler_address
            _timed_sweep(warm, scheduler=addr)
            out[f"dask{k}_s"] = _timed_sweep(spec, scheduler=addr)
            if k == 1:
                serial = _timed_sweep(many, serial=True, solve_fn=instant_squeeze)
                dask = _timed_sweep(many, scheduler=addr, solve_fn=instant_squeeze)
                out["dask_overhead_per_design_ms"] = (dask - serial) / len(many.runnable) * 1e3
    for key in ("plain_loop", "serial_sweep", "dask1", "dask2"):
        out[f"{key}_designs_per_s"] = n / out[f"{key}_s"]
    out["speedup_2_vs_1_workers"] = out["dask1_s"] / out["dask2_s"]
    mesh = "1 x 12 quad9 (small)" if small else "2 x 24 quad9 (default)"
    print(f"exofric sweep benchmark: {n} designs x 12 pressures, mesh {mesh}, "
          f"{out['cpus']:.0f} CPUs, load average {out['load_average_1min']:.1f} at start")
    for key, label in (("plain_loop", "plain loop (squeeze only)"),
                       ("serial_sweep", "serial sweep (+ Parquet, cache)"),
                       ("dask1", "Dask, 1 worker (warm)"), ("dask2", "Dask, 2 workers (warm)")):
        print(f"  {label:34s}: {out[key + '_s']:7.2f} s  {out[key + '_designs_per_s']:6.2f} "
              "designs/s")
    print(f"  LocalCluster start-up, 1 / 2 workers: {out['dask1_startup_s']:.2f} / "
          f"{out['dask2_startup_s']:.2f} s")
    print(f"  scaling 1 -> 2 workers             : x{out['speedup_2_vs_1_workers']:.2f}")
    print(f"  per-design overhead ({len(many.runnable)} instant designs): serial sweep "
          f"bookkeeping {out['bookkeeping_serial_ms']:.1f} ms, Dask on top "
          f"{out['dask_overhead_per_design_ms']:.1f} ms")
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--designs", type=int, default=12)
    ap.add_argument("--small", action="store_true", help="1 x 12 mesh instead of the default")
    ap.add_argument("--overhead-designs", type=int, default=200)
    a = ap.parse_args()
    main(a.designs, a.small, a.overhead_designs)
