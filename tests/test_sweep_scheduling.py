"""How a sweep is executed: the automatic choice of serial vs worker processes, identical results
either way, and the chosen mode in the summary / CLI output.

The decision is tested on given sizes and costs (no timing); the small runs use the 1 x 12 mesh
and three pressures of tests/test_sweep.py (~0.05-0.1 s per design).
"""

from __future__ import annotations

import os
import time
from types import MappingProxyType

import numpy as np
import pandas as pd
import pytest

from exofric import defaults
from exofric.design import (
    SolverSpec,
    SweepPool,
    estimate_design_time_s,
    parse_sweep,
    plan_execution,
    run_sweep,
)
from exofric.simulate import squeeze

SOLVER = {"n_radial": 1, "n_circ": 12, "grading": 6.0}
P = [0.2, 0.4, 0.6]
VOLATILE = ["solve_time_s", "task_time_s", "worker", "blas_threads", "run_id", "finished_at"]
#: 2 holes x 2 wires: 4 designs that fit
DATA = {"pressures_mpa": P, "solver": SOLVER,
        "grid": {"hole_mm": [10.0, 10.5], "wire_mm": [1.1, 1.6]}}


@pytest.fixture
def costs(monkeypatch):
    """Round cost constants, so that the expected decisions do not depend on measured ones."""
    monkeypatch.setattr(defaults, "SWEEP_POOL_START_S", MappingProxyType({
        "fork": MappingProxyType({"fixed": 0.02, "per_worker": 0.01}),
        "spawn": MappingProxyType({"fixed": 0.6, "per_worker": 0.05})}))
    monkeypatch.setattr(defaults, "SWEEP_TASK_OVERHEAD_S",
                        MappingProxyType({"processes": 1e-3, "dask": 3e-3}))
    monkeypatch.setattr(defaults, "SWEEP_MIN_GAIN_S", 0.2)
    monkeypatch.setattr(defaults, "SWEEP_MIN_GAIN_REL", 0.1)
    monkeypatch.setattr(defaults, "SWEEP_DESIGN_COST",
                        MappingProxyType({"s_per_design": 0.02, "s_per_dof_step": 1e-5}))


# --- the decision ---------------------------------------------------------------------------

def test_tiny_sweeps_stay_serial(costs):
    for n, t, cpus in [(1, 100.0, 8),     # one design: nothing to share out
                       (50, 1.0, 1),      # one CPU
                       (2, 0.05, 2),      # 0.1 s of work: a pool would save < 0.2 s
                       (4, 0.08, 4)]:     # 0.32 s of work
        plan = plan_execution(n, t, cpus, method="fork")
        assert (plan.mode, plan.workers) == ("serial", 1), (n, t, cpus, plan)
        assert plan.reason
    # a costly start-up (spawn) needs more work than fork does: 4 x 0.3 s saves 0.6 - 0.05
    # on fork, but spawning 2 workers costs 0.7 s
    assert plan_execution(4, 0.3, 2, method="fork").mode == "processes"
    assert plan_execution(4, 0.3, 2, method="spawn").mode == "serial"


def test_large_sweeps_use_every_cpu_and_predict_the_time(costs):
    plan = plan_execution(16, 0.2, 2, method="fork")
    assert (plan.mode, plan.workers) == ("processes", 2)
    # serial 16 x 0.2; parallel start 0.02 + 2 x 0.01, 8 rounds of 0.2, 16 x 1 ms dispatch
    assert plan.serial_time_s == pytest.approx(3.2)
    assert plan.parallel_time_s == pytest.approx(0.04 + 1.6 + 0.016)
    assert "16 designs" in plan.reason and "2 worker processes" in plan.reason
    big = plan_execution(1000, 1.0, 8, method="spawn")
    assert (big.mode, big.workers) == ("processes", 8)
    # never more workers than designs; 3 designs x 10 s on 8 CPUs: 3 workers
    assert plan_execution(3, 10.0, 8, method="fork").workers == 3
    # work size, not count: two long designs are worth two workers
    assert plan_execution(2, 5.0, 2, method="fork").mode == "processes"


def test_estimate_grows_with_mesh_and_load_path(costs):
    small = estimate_design_time_s(SolverSpec(n_radial=1, n_circ=12), [0.3, 0.6])
    default = estimate_design_time_s(SolverSpec(n_radial=2, n_circ=24), [0.3, 0.6])
    half_path = estimate_design_time_s(SolverSpec(n_radial=2, n_circ=24), [0.3])
    # 0.02 + 1e-5 x dofs x (0.6 / 0.025 steps): 150 and 490 dofs
    assert small == pytest.approx(0.02 + 1e-5 * 150 * 24)
    assert default == pytest.approx(0.02 + 1e-5 * 490 * 24)
    assert half_path == pytest.approx(0.02 + 1e-5 * 490 * 12)


# --- runs -----------------------------------------------------------------------------------

def comparable(frame: pd.DataFrame) -> pd.DataFrame:
    return frame.drop(columns=VOLATILE).sort_values(["design_index", "pressure_mpa"]) \
        .reset_index(drop=True)


@pytest.fixture(scope="module")
def serial_run(tmp_path_factory):
    return run_sweep(parse_sweep(DATA), tmp_path_factory.mktemp("s") / "out", serial=True)


def test_worker_processes_give_the_serial_results(serial_run, tmp_path):
    s = serial_run.summary
    assert (s.execution, s.workers, s.scheduler) == ("serial", 1, "serial")
    assert "requested" in s.execution_reason
    run = run_sweep(parse_sweep(DATA), tmp_path / "out", workers=2)
    r = run.summary
    assert (r.execution, r.workers, r.computed) == ("processes", 2, 4)
    assert r.scheduler.startswith("processes(2 x 1 thread")
    ok = run.frame[run.frame["status"] == "ok"]
    assert not any(w.endswith(f":{os.getpid()}") for w in ok["worker"])  # not in this process
    assert set(ok["blas_threads"]) == {"omp=1,openblas=1,mkl=1"}
    # same deterministic solver, same inputs, one BLAS thread: bit for bit the same rows
    pd.testing.assert_frame_equal(comparable(run.frame), comparable(serial_run.frame),
                                  check_exact=True)
    # and the serial run agrees with squeeze() called directly
    spec = parse_sweep(DATA)
    d = spec.runnable[0]
    ref = squeeze(d.structure(), spec.material.material(d.shore), P, mesh=spec.solver.mesh(),
                  penalty=spec.solver.penalty_n_per_mm3, density=spec.solver.density_t_per_mm3,
                  settings=spec.solver.newton(), keep_fields=False)
    rows = serial_run.frame[serial_run.frame["key"] == d.key]
    np.testing.assert_array_equal(rows["squeeze_force_n"], ref.squeeze_force_n)


def slow_squeeze(structure, material, pressures_mpa, **kw):
    """squeeze() plus 0.3 s of waiting: a design costly enough for workers (wall-clock based,
    so independent of the machine's load)."""
    time.sleep(0.3)
    return squeeze(structure, material, pressures_mpa, **kw)


def test_auto_starts_serially_and_moves_to_workers_once_measured(costs, monkeypatch, tmp_path,
                                                                 serial_run):
    import exofric.design._runner as runner

    monkeypatch.setattr(runner, "available_cpus", lambda: 2)
    # a-priori estimate ~0: 4 designs stay serial ...
    monkeypatch.setattr(defaults, "SWEEP_DESIGN_COST",
                        MappingProxyType({"s_per_design": 0.0, "s_per_dof_step": 0.0}))
    run = run_sweep(parse_sweep(DATA), tmp_path / "out", solve_fn=slow_squeeze)
    s = run.summary
    # ... until the first design measured >= 0.3 s: 3 x 0.3 s serially vs ~0.64 s on 2
    assert (s.execution, s.workers) == ("processes", 2), s.execution_reason
    assert s.execution_reason.startswith("1 solved here, then 3 designs x")
    assert "measured" in s.execution_reason
    first = run.frame[run.frame["design_index"] == 0]["worker"].iloc[0]
    assert first.endswith(f":{os.getpid()}")
    pd.testing.assert_frame_equal(comparable(run.frame), comparable(serial_run.frame),
                                  check_exact=True)


def test_auto_keeps_a_tiny_sweep_serial(costs, tmp_path):
    data = {"pressures_mpa": [0.6], "solver": SOLVER, "grid": {"wire_mm": [1.1, 1.6]}}
    s = run_sweep(parse_sweep(data), tmp_path / "out").summary
    assert (s.execution, s.workers, s.scheduler) == ("serial", 1, "serial")
    assert "in this process" in s.execution_reason
    again = run_sweep(parse_sweep(data), tmp_path / "out").summary   # all cached
    assert (again.execution, again.workers, again.computed) == ("none", 0, 0)


def crashing_solve(structure, material, pressures_mpa, **kw):
    """Kills its worker process for the 1.6 mm wire (as an out-of-memory kill would)."""
    if structure.wire_mm == 1.6:
        os._exit(3)
    return squeeze(structure, material, pressures_mpa, **kw)


def test_a_dying_worker_fails_only_its_design(tmp_path):
    data = {"pressures_mpa": [0.6], "solver": SOLVER, "grid": {"wire_mm": [1.1, 1.35, 1.6]}}
    run = run_sweep(parse_sweep(data), tmp_path / "out", workers=1, solve_fn=crashing_solve)
    one = run.frame.drop_duplicates("key").set_index("wire_mm")
    assert list(one["status"]) == ["ok", "ok", "failed"]
    assert one.loc[1.6, "error"].startswith("BrokenProcessPool")
    assert run.summary.failed == 1


def test_pool_runs_tasks_in_warm_workers():
    with SweepPool(2) as pool:
        started = set(pool.results(_pid, [0, 1], lambda it, m: -1))
        pids = {r for _, r in pool.results(_pid, list(range(8)), lambda it, m: -1)}
        pids |= {r for _, r in started}
    assert os.getpid() not in pids and 1 <= len(pids) <= 2  # two processes serve every task


def _pid(_: object) -> int:
    return os.getpid()


# --- CLI ------------------------------------------------------------------------------------

def test_cli_reports_the_execution_mode(cli, tmp_path):
    cfg = tmp_path / "s.toml"
    cfg.write_text("pressures_mpa = [0.3, 0.6]\n[solver]\nn_radial = 1\nn_circ = 12\n"
                   "[grid]\nwire_mm = [1.1, 1.6]\n")
    r = cli(["sweep", str(cfg), "--out", str(tmp_path / "a"), "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert (d["execution"], d["workers"], d["scheduler"]) == ("serial", 1, "serial")
    assert "in this process" in d["execution_reason"]
    r = cli(["sweep", str(cfg), "--out", str(tmp_path / "b"), "--workers", "2"])
    assert r.code == 0, r.err
    assert "processes: processes(2 x 1 thread" in r.out and "requested: 2 worker processes" in r.out
    bad = cli(["sweep", str(cfg), "--out", str(tmp_path / "c"), "--executor", "gpu", "--json"])
    assert bad.code == 2 and bad.out == "" and len(bad.err.strip().splitlines()) == 1
    assert "--executor" in bad.err
