"""Sweeps on local workers vs a plain loop, streaming, resume after deletion or a kill, failures.

Small meshes (1 x 12 quad9, 150 dofs) and three pressures keep each solve ~0.3-0.5 s.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from exofric.design import SweepSpec, parse_sweep, run_sweep, sweep
from exofric.errors import ConvergenceError
from exofric.simulate import squeeze

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SOLVER = {"n_radial": 1, "n_circ": 12, "grading": 6.0}
P = [0.2, 0.4, 0.6]
#: Columns that legitimately differ between runs (timings, where and when it ran).
VOLATILE = ["solve_time_s", "task_time_s", "worker", "blas_threads", "run_id", "finished_at"]


def small_data() -> dict:
    """examples/sweep-small.toml (12 designs, 4 impossible) with a small mesh."""
    data = tomllib.loads((EXAMPLES / "sweep-small.toml").read_text())
    data["solver"] = SOLVER
    data["pressures_mpa"] = P
    return data


def comparable(frame: pd.DataFrame) -> pd.DataFrame:
    return frame.drop(columns=VOLATILE).sort_values(["design_index", "pressure_mpa"]) \
        .reset_index(drop=True)


CALLS: list[str] = []


def counting_squeeze(structure, material, pressures_mpa, **kw):
    """A solver hook that counts calls (in-process runs only)."""
    CALLS.append(structure.name)
    return squeeze(structure, material, pressures_mpa, **kw)


def failing_squeeze(structure, material, pressures_mpa, **kw):
    """Fails for the 10.5 mm hole with 1.1 mm wire, solves the others."""
    CALLS.append(structure.name)
    if structure.hole_mm == 10.5 and structure.wire_mm == 1.1:
        raise ConvergenceError("no convergence at 0.4 MPa (planted)", reached=0.2)
    return squeeze(structure, material, pressures_mpa, **kw)


@pytest.fixture(scope="module")
def spec() -> SweepSpec:
    return parse_sweep(small_data())


@pytest.fixture(scope="module")
def cluster_run(spec, tmp_path_factory):
    """The 12-design sweep on 2 local worker processes (``workers=2``)."""
    out = tmp_path_factory.mktemp("cluster") / "out"
    return run_sweep(spec, out, workers=2)


def test_local_workers_match_plain_serial_loop(spec, cluster_run):
    s = cluster_run.summary
    assert (s.designs, s.computed, s.cached, s.skipped, s.failed) == (12, 8, 0, 4, 0)
    assert s.workers == 2 and s.execution == "processes" and "processes(2" in s.scheduler
    f = cluster_run.frame
    ok = f[f["status"] == "ok"]
    assert len(ok) == 8 * len(P) and len(f) == 8 * len(P) + 4
    # both worker processes solved designs, none in this process, one BLAS thread each
    workers = set(ok["worker"])
    assert len(workers) == 2 and not any(w.endswith(f":{os.getpid()}") for w in workers)
    assert set(ok["blas_threads"]) == {"omp=1,openblas=1,mkl=1"}
    # reference: exofric.simulate.squeeze called directly, one design after the other.
    # Tolerance: same deterministic algorithm on the same inputs; only a different BLAS
    # thread count could reorder floating-point sums (1e-12 relative); in practice equal.
    for d in spec.runnable:
        ref = squeeze(d.structure(), spec.material.material(d.shore), P,
                      mesh=spec.solver.mesh(), penalty=spec.solver.penalty_n_per_mm3,
                      density=spec.solver.density_t_per_mm3, settings=spec.solver.newton(),
                      keep_fields=False)
        rows = ok[ok["key"] == d.key]
        np.testing.assert_allclose(rows["pressure_mpa"], P, rtol=0, atol=0)
        for col, want in (("squeeze_force_n", ref.squeeze_force_n),
                          ("wall_force_n", ref.wall_force_n),
                          ("max_penetration_mm", ref.contact.max_penetration_mm),
                          ("max_stretch", ref.max_stretch)):
            np.testing.assert_allclose(rows[col], want, rtol=1e-12, atol=1e-12)
        np.testing.assert_array_equal(rows["newton_iterations"], ref.newton_iterations)
        assert rows["contact_onset_pressure_mpa"].iloc[0] == pytest.approx(
            ref.contact_onset_pressure_mpa, rel=1e-12)
        # friction and torque from the sweep's gamma and arm: F = gamma N, T = F R
        np.testing.assert_allclose(rows["friction_n"], 0.7168 * ref.squeeze_force_n, rtol=1e-12)
        np.testing.assert_allclose(rows["torque_nm"], 0.07168 * ref.squeeze_force_n, rtol=1e-12)


def test_dataset_is_streamed_parquet_one_file_per_design(cluster_run):
    out = Path(cluster_run.summary.out)
    files = sorted(out.glob("design-*.parquet"))
    assert len(files) == 12
    assert sum(f.name.endswith("-skipped.parquet") for f in files) == 4
    whole = pd.read_parquet(out)           # readable as one dataset by pandas/pyarrow
    assert len(whole) == len(cluster_run.frame)
    finished = pd.to_datetime(whole.drop_duplicates("key")["finished_at"])
    assert finished.nunique() > 1           # written design by design, not at the end


def test_skipped_designs_carry_reasons(cluster_run):
    sk = cluster_run.frame[cluster_run.frame["status"] == "skipped"]
    assert len(sk) == 4 and sk["pressure_mpa"].isna().all()
    assert all("tube and wire do not fit" in e for e in sk["error"])
    reasons = cluster_run.to_dict()["skipped_designs"]
    assert {r["name"] for r in reasons} == set(sk["name"])


def test_resume_after_deleting_part_recomputes_only_the_missing(cluster_run, tmp_path):
    out = tmp_path / "out"
    shutil.copytree(cluster_run.summary.out, out)
    victims = sorted(out.glob("design-*-ok.parquet"))[:3]
    for f in victims:
        f.unlink()
    CALLS.clear()
    run = run_sweep(parse_sweep(small_data()), out, serial=True, solve_fn=counting_squeeze)
    assert len(CALLS) == 3                  # solver calls: only the deleted designs
    s = run.summary
    assert (s.computed, s.cached, s.skipped) == (3, 5, 4)
    first = cluster_run.summary.run_id
    per_design = run.frame.drop_duplicates("key").set_index("key")["run_id"]
    deleted = {f.name.split("-")[1] for f in victims}
    assert all(per_design[k] == s.run_id for k in deleted)
    assert all(per_design[k] == first for k in per_design.index if k not in deleted)
    pd.testing.assert_frame_equal(comparable(run.frame), comparable(cluster_run.frame),
                                  check_exact=False, rtol=1e-12)
    # a third run solves nothing
    CALLS.clear()
    again = run_sweep(parse_sweep(small_data()), out, serial=True, solve_fn=counting_squeeze)
    assert CALLS == [] and again.summary.computed == 0 and again.summary.cached == 8


def test_killed_sweep_resumes_without_recomputing(cluster_run, tmp_path):
    cfg = tmp_path / "small.toml"
    text = (EXAMPLES / "sweep-small.toml").read_text()
    text = text.replace("n_radial = 2", "n_radial = 1").replace("n_circ = 24", "n_circ = 12")
    text = text.replace(text[text.index("pressures_mpa = "):text.index("\ngamma")],
                        "pressures_mpa = [0.2, 0.4, 0.6]")
    cfg.write_text(text)
    assert parse_sweep(tomllib.loads(text)).designs == parse_sweep(small_data()).designs
    out = tmp_path / "out"
    proc = subprocess.Popen(
        [sys.executable, "-m", "exofric", "sweep", str(cfg), "--out", str(out),
         "--workers", "1", "--json"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        deadline = time.monotonic() + 90
        while len(list(out.glob("design-*-ok.parquet"))) < 2:
            assert proc.poll() is None, "sweep ended before it could be killed"
            assert time.monotonic() < deadline, "no design finished within 90 s"
            time.sleep(0.05)
        os.killpg(proc.pid, signal.SIGKILL)  # the CLI, its LocalCluster and its workers
        proc.wait(timeout=30)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(timeout=30)
    survivors = {f.name.split("-")[1]: f.stat().st_mtime_ns
                 for f in out.glob("design-*-ok.parquet")}
    assert 2 <= len(survivors) < 8
    old_ids = pd.read_parquet(out).drop_duplicates("key").set_index("key")["run_id"]
    CALLS.clear()
    run = run_sweep(parse_sweep(small_data()), out, serial=True, solve_fn=counting_squeeze)
    assert len(CALLS) == 8 - len(survivors) == run.summary.computed
    for key, mtime in survivors.items():   # finished files untouched, same run id
        assert (out / f"design-{key}-ok.parquet").stat().st_mtime_ns == mtime
    ids = run.frame.drop_duplicates("key").set_index("key")["run_id"]
    assert all(ids[k] == old_ids[k] for k in survivors)
    pd.testing.assert_frame_equal(comparable(run.frame), comparable(cluster_run.frame),
                                  check_exact=False, rtol=1e-12)


def test_failed_solve_is_recorded_and_does_not_stop_the_others(tmp_path):
    data = {"pressures_mpa": [0.3, 0.6], "solver": SOLVER,
            "grid": {"hole_mm": [10.0, 10.5], "wire_mm": [1.1, 1.6]}}
    CALLS.clear()
    frame = sweep(data, tmp_path / "out", serial=True, solve_fn=failing_squeeze)
    summary = frame.attrs["summary"]
    assert (summary["computed"], summary["failed"], summary["skipped"]) == (4, 1, 0)
    bad = frame[frame["status"] == "failed"]
    assert len(bad) == 1 and bad["error"].iloc[0] == \
        "ConvergenceError: no convergence at 0.4 MPa (planted)"
    assert bad["name"].iloc[0] == "D=10.5 d2=1.1" and np.isnan(bad["squeeze_force_n"].iloc[0])
    assert (frame["status"] == "ok").sum() == 3 * 2
    # rerun: the failure is cached (not retried) unless asked
    CALLS.clear()
    again = run_sweep(parse_sweep(data), tmp_path / "out", serial=True, solve_fn=failing_squeeze)
    assert CALLS == [] and again.summary.failed == 1 and again.summary.cached == 4
    retry = run_sweep(parse_sweep(data), tmp_path / "out", serial=True, retry_failed=True)
    assert retry.summary.computed == 1 and retry.summary.failed == 0
    assert len(list((tmp_path / "out").glob("*-failed.parquet"))) == 0


def test_new_gamma_and_arm_reuse_the_cache(cluster_run, tmp_path):
    out = tmp_path / "out"
    shutil.copytree(cluster_run.summary.out, out)
    data = small_data() | {"gamma": 0.5, "f0_n": 2.0, "arm_radius_m": 0.2}
    run = run_sweep(parse_sweep(data), out, serial=True)
    assert run.summary.computed == 0 and run.summary.cached == 8
    ok = run.frame[run.frame["status"] == "ok"]
    np.testing.assert_allclose(ok["friction_n"], 0.5 * ok["squeeze_force_n"] + 2.0, rtol=1e-12)
    np.testing.assert_allclose(ok["torque_nm"], 0.2 * ok["friction_n"], rtol=1e-12)


def test_cli_sweep_json_summary_and_bad_input(cli, cluster_run, tmp_path):
    cfg = tmp_path / "s.toml"
    cfg.write_text('pressures_mpa = [0.3, 0.6]\n[solver]\nn_radial = 1\nn_circ = 12\n'
                   '[grid]\nwire_mm = [1.6, 2.0]\n')
    r = cli(["sweep", str(cfg), "--out", str(tmp_path / "o"), "--serial", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert {"designs", "computed", "cached", "skipped", "failed", "out", "wall_time_s"} <= set(d)
    assert (d["designs"], d["computed"], d["cached"], d["skipped"], d["failed"]) == (2, 1, 0, 1, 0)
    assert d["out"] == str(tmp_path / "o") and d["wall_time_s"] > 0
    assert "do not fit" in d["skipped_designs"][0]["reason"]
    cfg.write_text("pressures_mpa = [0.3, 0.6]\n[grid]\nwire = [1.6]\n")
    bad = cli(["sweep", str(cfg), "--out", str(tmp_path / "o"), "--json"])
    assert bad.code == 2 and bad.out == "" and len(bad.err.strip().splitlines()) == 1
    assert "unknown key 'wire'" in bad.err


def test_validated_region_needs_small_deviation_and_the_base_hardness(tmp_path):
    data = {"pressures_mpa": [0.6], "solver": SOLVER, "design": [
        {"name": "base"},
        {"name": "test 6", "hole_mm": 12.3, "tube_od_mm": 9.2, "wire_mm": 1.6},
        {"name": "soft base", "shore": 55.0}]}
    run = run_sweep(parse_sweep(data), tmp_path / "out", serial=True)
    f = run.frame.set_index("name")
    # test 6 scales: D 1.23, d1 9.2/8.3, d2 1.0 -> 100 (1.23 / 1 - 1) = 23 % (paper: 23.0 %)
    assert f.loc["test 6", "deviation_pct"] == pytest.approx(23.0, abs=1e-9)
    assert f.loc["base", "deviation_pct"] == 0.0 and f.loc["soft base", "deviation_pct"] == 0.0
    assert f["in_validated_region"].to_dict() == {"base": True, "test 6": False,
                                                  "soft base": False}
    # a softer tube squeezes harder at the same pressure (lower shear modulus, Eqs 3-6)
    assert f.loc["soft base", "squeeze_force_n"] > f.loc["base", "squeeze_force_n"]


def test_progress_bar_on_a_terminal_even_with_json_but_not_with_quiet(monkeypatch) -> None:
    """Progress goes to stderr (stdout stays one JSON object): shown on a terminal with --json,
    left out with --quiet or when stderr is not a terminal (issue 20)."""
    import io
    import sys

    from exofric.cli import sweep as sweep_cli

    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    monkeypatch.setattr(sys, "stderr", Tty())
    with sweep_cli._progress(False) as bar:
        assert callable(bar)
    with sweep_cli._progress(True) as bar:
        assert bar is None
    monkeypatch.setattr(sys, "stderr", io.StringIO())
    with sweep_cli._progress(False) as bar:
        assert bar is None
