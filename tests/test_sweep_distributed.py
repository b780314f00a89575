"""A real distributed deployment: ``dask scheduler`` + two ``dask worker`` processes on
127.0.0.1, a sweep through ``exofric sweep --scheduler``, then everything is stopped.

Every subprocess is bounded in time and killed (its whole process group) in ``finally``.
"""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from exofric.design import parse_sweep, run_sweep

DASK = Path(sys.executable).parent / "dask"
CONFIG = """
name = "dist"
pressures_mpa = [0.3, 0.6]
[solver]
n_radial = 1
n_circ = 12
grading = 6.0
[grid]
hole_mm = [10.0, 10.5]
wire_mm = [1.1, 1.6, 2.0]
"""


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def stop(proc: subprocess.Popen) -> None:
    """SIGTERM the process group, SIGKILL after 10 s."""
    if proc.poll() is not None:
        return
    for sig, wait in ((signal.SIGTERM, 10), (signal.SIGKILL, 10)):
        try:
            os.killpg(proc.pid, sig)
        except ProcessLookupError:
            return
        try:
            proc.wait(timeout=wait)
            return
        except subprocess.TimeoutExpired:
            continue


def wait_for_workers(address: str, n: int, procs: list[subprocess.Popen]) -> None:
    from distributed import Client

    deadline = time.monotonic() + 90
    while time.monotonic() < deadline:
        for p in procs:
            assert p.poll() is None, f"dask process {p.args} exited with {p.returncode}"
        try:
            with Client(address, timeout="5s") as c:
                c.wait_for_workers(n, timeout=60)
                return
        except (OSError, TimeoutError):
            time.sleep(0.5)
    raise AssertionError(f"{n} dask workers did not register at {address} within 90 s")


@pytest.mark.skipif(not DASK.exists(), reason="dask CLI not installed in this environment")
def test_sweep_on_dask_scheduler_and_two_workers(tmp_path, cli):
    cfg = tmp_path / "dist.toml"
    cfg.write_text(CONFIG)
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
           "MKL_NUM_THREADS": "1"}
    logs = [open(tmp_path / f"{n}.log", "w") for n in ("scheduler", "w1", "w2")]  # noqa: SIM115
    procs: list[subprocess.Popen] = []
    try:
        procs.append(subprocess.Popen(
            [str(DASK), "scheduler", "--host", "127.0.0.1", "--port", str(port),
             "--no-dashboard", "--no-show"],
            stdout=logs[0], stderr=subprocess.STDOUT, env=env, start_new_session=True))
        for i in (1, 2):
            # --no-nanny: the worker runs in this very process, so its pid identifies it
            procs.append(subprocess.Popen(
                [str(DASK), "worker", address, "--host", "127.0.0.1", "--nthreads", "1",
                 "--no-nanny", "--no-dashboard", "--name", f"w{i}", "--death-timeout", "60"],
                stdout=logs[i], stderr=subprocess.STDOUT, env=env, start_new_session=True))
        wait_for_workers(address, 2, procs)
        r = cli(["sweep", str(cfg), "--out", str(tmp_path / "out"), "--scheduler", address,
                 "--json"])
        assert r.code == 0, r.err
        d = r.json()
        assert (d["designs"], d["computed"], d["skipped"], d["failed"]) == (6, 5, 1, 0)
        assert d["scheduler"] == address and d["workers"] == 2
        frame = pd.read_parquet(tmp_path / "out")
        ok = frame[frame["status"] == "ok"]
        # solved on the two external worker processes only
        pids = {int(w.rsplit(":", 1)[1]) for w in ok["worker"]}
        assert pids <= {procs[1].pid, procs[2].pid} and pids
        assert set(ok["blas_threads"]) == {"omp=1,openblas=1,mkl=1"}
        # same numbers as in this process, serially (deterministic solver, see test_sweep)
        ref = run_sweep(parse_sweep(tomllib.loads(CONFIG)),
                        tmp_path / "ref", serial=True).frame
        ref_ok = ref[ref["status"] == "ok"].set_index(["key", "pressure_mpa"]).sort_index()
        got = ok.set_index(["key", "pressure_mpa"]).sort_index()
        np.testing.assert_allclose(got["squeeze_force_n"], ref_ok["squeeze_force_n"],
                                   rtol=1e-12, atol=1e-12)
        np.testing.assert_array_equal(got["newton_iterations"], ref_ok["newton_iterations"])
    finally:
        for p in reversed(procs):
            stop(p)
        for f in logs:
            f.close()
    assert all(p.poll() is not None for p in procs)


def test_unreachable_scheduler_is_one_line_error(cli, tmp_path):
    cfg = tmp_path / "dist.toml"
    cfg.write_text(CONFIG)
    r = cli(["sweep", str(cfg), "--out", str(tmp_path / "o"), "--scheduler",
             f"tcp://127.0.0.1:{free_port()}", "--timeout", "2", "--json"])
    assert r.code == 2 and r.out == ""
    assert "--scheduler" in r.err and len(r.err.strip().splitlines()) == 1
