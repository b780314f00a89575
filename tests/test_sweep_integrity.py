"""Nothing lost, nothing trusted blindly: fault injection on a finished sweep folder.

A small sweep (1 x 12 mesh, three pressures, two solvable designs and one impossible) is run
once; each test damages a copy of its folder (truncated file, flipped byte, altered value in
a file without checksum, deleted manifest, a path that cannot be replaced) and checks that
the next run recovers (the damaged design is quarantined, named in one warning line and
solved again, giving the clean run's values) or stops with one clean error line. Also
``exofric sweep --verify`` and the checks of the cluster and search options.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import warnings
from pathlib import Path

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from exofric.cli import run as cli_run
from exofric.design import SCHEMA, SweepSpec, parse_sweep, run_sweep, verify_sweep
from exofric.simulate import squeeze

DATA = {"pressures_mpa": [0.2, 0.4, 0.6], "solver": {"n_radial": 1, "n_circ": 12},
        "grid": {"wire_mm": [1.1, 1.6, 2.0]}}           # d2 = 2.0 mm does not fit: skipped
CONFIG = ('pressures_mpa = [0.2, 0.4, 0.6]\n[solver]\nn_radial = 1\nn_circ = 12\n'
          '[grid]\nwire_mm = [1.1, 1.6, 2.0]\n')
VOLATILE = ["solve_time_s", "task_time_s", "worker", "blas_threads", "run_id", "finished_at"]
CALLS: list[str] = []


def counting_squeeze(structure, material, pressures_mpa, **kw):
    CALLS.append(structure.name)
    return squeeze(structure, material, pressures_mpa, **kw)


def comparable(frame: pd.DataFrame) -> pd.DataFrame:
    return frame.drop(columns=VOLATILE).reset_index(drop=True)


@pytest.fixture(scope="module")
def spec() -> SweepSpec:
    return parse_sweep(DATA)


@pytest.fixture(scope="module")
def clean(spec, tmp_path_factory):
    """The finished, undamaged sweep (serial)."""
    return run_sweep(spec, tmp_path_factory.mktemp("clean") / "out", serial=True)


@pytest.fixture
def folder(clean, tmp_path) -> Path:
    """A copy of the clean sweep folder, to damage."""
    out = tmp_path / "out"
    shutil.copytree(clean.summary.out, out)
    return out


def ok_files(out: Path) -> list[Path]:
    return sorted(out.glob("design-*-ok.parquet"))


def rerun(spec, out):
    """Run the sweep again in this process, counting solves; return (run, warning lines)."""
    CALLS.clear()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = run_sweep(spec, out, serial=True, solve_fn=counting_squeeze)
    return run, [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)]


def strip_checksum(f: Path) -> None:
    """Rewrite ``f`` as a file of an exofric without checksums (no ``exofric.sha256``)."""
    t = pq.read_table(f)
    meta = {k: v for k, v in (t.schema.metadata or {}).items() if k != b"exofric.sha256"}
    pq.write_table(t.replace_schema_metadata(meta), f)


def assert_recovered(spec, clean, out, victim: Path, *reasons: str) -> None:
    """The damaged ``victim`` is quarantined with one of ``reasons``, solved again, values
    equal."""
    run, warned = rerun(spec, out)
    assert len(warned) == 1 and victim.name in warned[0], warned
    assert any(r in warned[0] for r in reasons), warned
    assert list(run.warnings) == warned and run.to_dict()["warnings"] == warned
    assert len(CALLS) == 1 and run.summary.computed == 1 and run.summary.cached == 1
    assert (out / "_quarantine" / victim.name).exists() and victim.exists()
    # deterministic solver, same inputs: the recomputed design equals the clean run
    pd.testing.assert_frame_equal(comparable(run.frame), comparable(clean.frame),
                                  check_exact=False, rtol=1e-12)
    assert verify_sweep(out).ok
    assert len(pd.read_parquet(out)) == len(clean.frame)   # quarantine not read by pyarrow


def test_clean_folder_verifies_and_files_carry_checksums(clean):
    from exofric.io._store import content_sha256

    out = Path(clean.summary.out)
    check = verify_sweep(out)
    assert check.ok and check.exit_code == 0 and check.manifest == "ok"
    assert check.counts == {"ok": 3, "quarantined": 0, "missing": 0}
    for f in out.glob("design-*.parquet"):
        recorded = pq.read_metadata(f).metadata[b"exofric.sha256"].decode()
        assert recorded == content_sha256(pq.read_table(f, schema=SCHEMA))
    assert sorted(x.name for x in out.iterdir() if not x.name.startswith("design-")) == \
        ["_sweep.json"]
    assert clean.warnings == () and clean.to_dict()["warnings"] == []


def test_truncated_file_is_quarantined_and_recomputed(spec, clean, folder):
    victim = ok_files(folder)[0]
    victim.write_bytes(victim.read_bytes()[: victim.stat().st_size // 2])
    assert_recovered(spec, clean, folder, victim, "not a readable Parquet file")


def test_truncated_file_without_checksum_is_unreadable_and_recomputed(spec, clean, folder):
    victim = ok_files(folder)[0]
    strip_checksum(victim)
    victim.write_bytes(victim.read_bytes()[:100])
    assert_recovered(spec, clean, folder, victim, "not a readable Parquet file")


@pytest.mark.parametrize("where", [0.1, 0.3, 0.5, 0.7, 0.9])
def test_flipped_byte_anywhere_never_gives_wrong_data(spec, clean, folder, where):
    # either the damage reaches the rows (then the file is quarantined and solved again) or
    # it hit bytes that decode to the same rows (statistics, padding): the values are right
    victim = ok_files(folder)[1]
    data = bytearray(victim.read_bytes())
    data[int(len(data) * where)] ^= 0x10
    victim.write_bytes(bytes(data))
    run, warned = rerun(spec, folder)
    assert len(warned) == len(CALLS) <= 1 and all(victim.name in w for w in warned)
    assert (folder / "_quarantine" / victim.name).exists() == bool(warned)
    pd.testing.assert_frame_equal(comparable(run.frame), comparable(clean.frame),
                                  check_exact=False, rtol=1e-12)


def test_flipped_bit_in_the_squeeze_force_is_caught_by_the_checksum(spec, clean, folder):
    # the attack: one bit of one stored force changes, friction and torque keep old values
    import struct

    victim = ok_files(folder)[0]
    force = pq.read_table(victim).column("squeeze_force_n").to_pylist()[1]
    old = struct.pack("<d", force)
    new = struct.pack("<d", struct.unpack("<d", bytes([old[0] ^ 1]) + old[1:])[0] * 1.0)
    data = victim.read_bytes()
    assert data.count(old) == 1
    victim.write_bytes(data.replace(old, new))
    assert pq.read_table(victim).column("squeeze_force_n").to_pylist()[1] != force
    assert_recovered(spec, clean, folder, victim, "checksum mismatch")


def test_altered_force_in_a_file_without_checksum_fails_the_derived_check(spec, clean,
                                                                          folder):
    # a file of an older sweep (no checksum) whose squeeze force changed, friction kept
    victim = ok_files(folder)[0]
    t = pq.read_table(victim)
    force = t.column("squeeze_force_n").to_numpy().copy()
    force[1] *= 1.0 + 2.0 ** -40                     # a flipped low mantissa bit or so
    t = t.set_column(t.schema.get_field_index("squeeze_force_n"), "squeeze_force_n",
                     pa.array(force))
    pq.write_table(t, victim)
    strip_checksum(victim)
    assert_recovered(spec, clean, folder, victim, "friction_n disagrees")


def test_files_without_checksums_are_still_trusted_when_consistent(spec, clean, folder):
    for f in folder.glob("design-*.parquet"):         # a folder written before checksums
        strip_checksum(f)
    run, warned = rerun(spec, folder)
    assert warned == [] and CALLS == [] and run.summary.cached == 2
    pd.testing.assert_frame_equal(comparable(run.frame), comparable(clean.frame))


def test_deleted_manifest_is_reported_by_verify_and_rewritten(spec, clean, folder, capsys):
    (folder / "_sweep.json").unlink()
    check = verify_sweep(folder)
    assert check.manifest == "missing" and check.exit_code == 1
    assert check.counts == {"ok": 3, "quarantined": 0, "missing": 0}
    assert cli_run(["sweep", "--verify", str(folder), "--json"]) == 1
    run, warned = rerun(spec, folder)
    assert warned == [] and CALLS == [] and (folder / "_sweep.json").exists()
    assert verify_sweep(folder).ok


def test_unreplaceable_design_path_is_quarantined_and_recomputed(spec, clean, folder):
    # a design file replaced by a (non-empty) directory: unreadable and not replaceable
    victim = ok_files(folder)[0]
    victim.unlink()
    victim.mkdir()
    (victim / "x").write_text("not parquet")
    assert_recovered(spec, clean, folder, victim, "cannot be read")


def test_unwritable_manifest_is_one_clean_error_line(cli, folder):
    (folder / "_sweep.json").unlink()
    (folder / "_sweep.json").mkdir()                  # os.replace onto it fails
    (folder / "_sweep.json" / "x").write_text("")
    cfg = folder.parent / "s.toml"
    cfg.write_text(CONFIG)
    r = cli(["sweep", str(cfg), "--out", str(folder), "--serial", "--json"])
    assert r.code == 2 and r.out == "" and "Traceback" not in r.err
    assert len(r.err.strip().splitlines()) == 1 and "cannot write _sweep.json" in r.err


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0,
                    reason="root writes into read-only folders: the test would be meaningless")
def test_read_only_folder_with_a_damaged_file_is_one_clean_error_line(cli, folder):
    victim = ok_files(folder)[0]
    victim.write_bytes(b"garbage")
    cfg = folder.parent / "s.toml"
    cfg.write_text(CONFIG)
    folder.chmod(0o555)
    try:
        r = cli(["sweep", str(cfg), "--out", str(folder), "--serial", "--json"])
    finally:
        folder.chmod(0o755)
    assert r.code == 2 and "Traceback" not in r.err and len(r.err.strip().splitlines()) == 1


def test_cli_sweep_and_design_report_a_damaged_file_once(cli, clean, folder):
    victim = ok_files(folder)[0]
    victim.write_bytes(victim.read_bytes()[:-7])
    cfg = folder.parent / "s.toml"
    cfg.write_text(CONFIG)
    r = cli(["sweep", str(cfg), "--out", str(folder), "--serial", "--json"])
    assert r.code == 0, r.err
    lines = r.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("exofric: warning: ") and \
        victim.name in lines[0] and "not a readable Parquet file" in lines[0]
    d = r.json()
    assert d["computed"] == 1 and d["cached"] == 1 and len(d["warnings"]) == 1
    # design reuses the valid files and solves the damaged one again
    victim2 = ok_files(folder)[1]
    victim2.write_bytes(b"PAR1")
    r = cli(["design", str(cfg), "--target-torque", "5", "--arm", "0.1", "--pmax", "0.6",
             "--out", str(folder), "--serial", "--no-plot", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert len(r.err.strip().splitlines()) == 1 and victim2.name in r.err
    assert d["warnings"] == [r.err.strip().removeprefix("exofric: warning: ")]
    assert d["sweep"]["computed"] == 1 and d["evaluated"] == 2


def test_verify_cli_on_damaged_folder_and_without_dask(folder):
    bad = ok_files(folder)[0]
    bad.write_bytes(bad.read_bytes()[:50])
    gone = ok_files(folder)[1]
    gone.unlink()
    code = ("import sys\nfrom exofric.cli import exit_process, run\n"
            f"rc = run(['sweep', '--verify', {str(folder)!r}, '--json'])\n"
            "print('dask-imported' if {'dask', 'distributed'} & set(sys.modules) else 'no-dask',"
            " file=sys.stderr)\nexit_process(rc)\n")   # as the console script ends
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 1
    err = proc.stderr.strip().splitlines()
    assert err[-1] == "no-dask" and len(err) == 2 and bad.name in err[0]
    import json

    d = json.loads(proc.stdout)
    assert d["ok"] is False and d["counts"] == {"ok": 1, "quarantined": 1, "missing": 1}
    states = {x["key"]: x for x in d["designs"]}
    key_bad, key_gone = bad.name.split("-")[1], gone.name.split("-")[1]
    assert states[key_bad]["state"] == "quarantined"
    assert "not a readable Parquet file" in states[key_bad]["reason"]
    assert states[key_gone]["state"] == "missing"
    assert (folder / "_quarantine" / bad.name).exists()


def test_verify_clean_and_not_a_sweep_folder(clean, tmp_path, capsys):
    assert cli_run(["sweep", "--verify", clean.summary.out]) == 0
    assert "all designs verified" in capsys.readouterr().out
    empty = tmp_path / "empty"
    empty.mkdir()
    for target in (empty, tmp_path / "absent"):
        assert cli_run(["sweep", "--verify", str(target), "--json"]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "is not a sweep folder" in err[0]


@pytest.mark.parametrize(("args", "needle"), [
    (["--scheduler", "localhost"], "--scheduler must look like tcp://host:port"),
    (["--scheduler", "tcp://127.0.0.1"], "--scheduler must look like tcp://host:port"),
    (["--scheduler", "::garbage::"], "--scheduler must look like tcp://host:port"),
    (["--scheduler", "tcp://127.0.0.1:70000"], "port 1-65535"),
    (["--timeout", "nan"], "--timeout must be a finite number of seconds > 0"),
    (["--timeout", "-1"], "--timeout must be a finite number of seconds > 0"),
    (["--timeout", "inf"], "--timeout must be a finite number of seconds > 0"),
])
def test_bad_cluster_options_are_one_line_exit_2(args, needle, tmp_path, capsys):
    cfg = tmp_path / "s.toml"
    cfg.write_text(CONFIG)
    for cmd in (["sweep", str(cfg), "--out", str(tmp_path / "o")],
                ["design", str(cfg), "--out", str(tmp_path / "o"), "--no-plot"]):
        assert cli_run([*cmd, *args, "--json"]) == 2
        cap = capsys.readouterr()
        assert cap.out == "" and "Traceback" not in cap.err
        assert len(cap.err.strip().splitlines()) == 1 and needle in cap.err, cap.err
    assert not (tmp_path / "o").exists()               # rejected before any work


def test_unreachable_scheduler_fails_fast_naming_the_address(tmp_path, capsys):
    import socket

    with socket.socket() as s:                         # a port where nothing listens
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    cfg = tmp_path / "s.toml"
    cfg.write_text(CONFIG)
    address = f"tcp://127.0.0.1:{port}"
    # default --timeout (60 s): the TCP probe answers first, with its own message
    assert cli_run(["sweep", str(cfg), "--out", str(tmp_path / "o"), "--scheduler", address,
                    "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and address in err[0] and "nothing reachable there" in err[0]


@pytest.mark.parametrize(("args", "needle"), [
    (["--top", "-1"], "--top must be >= 1"),
    (["--top", "0"], "--top must be >= 1"),
    (["--pmax", "100"], "--pmax must be in (0, 2] MPa"),
    (["--pmax", "0.9"], "--pmax 0.9 MPa is above the sweep's largest pressure 0.6 MPa"),
    (["--pmax", "nan"], "--pmax"),
    (["--f0", "nan"], "--f0"),
])
def test_bad_design_options_fail_before_any_work(args, needle, tmp_path, capsys):
    out = tmp_path / "o"
    # no CONFIG: the default design space (12 designs), which must not be solved
    assert cli_run(["design", "--target-torque", "10", "--out", str(out), "--no-plot",
                    *args, "--json"]) == 2
    cap = capsys.readouterr()
    assert cap.out == "" and len(cap.err.strip().splitlines()) == 1 and needle in cap.err
    assert not out.exists()
