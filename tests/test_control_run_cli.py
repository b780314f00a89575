"""``exofric control run`` and ``control identify --charge`` (issue 17), end to end.

The CLI runs in a subprocess against real client code paths: the in-process simulated plant
(``sim://``) and a pymodbus TCP server on 127.0.0.1 started by the test (the physical
pneumatic plant behind it). References: the set-point (settling within 2 %), the exit codes
stated in the issue (2 for bad input and unreachable devices, 4 for a watchdog stop), the log
read back by ``exofric.io.read_raw_log``, and planted valve/volume values for the charge fit.
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from exofric.control import Orifice, PneumaticParams, simulate_charge
from exofric.hardware import ModbusSimServer
from exofric.io import read_raw_log


def test_run_on_the_simulated_plant_settles_and_logs(cli, tmp_path: Path) -> None:
    log = tmp_path / "run.csv"
    r = cli(["control", "run", "--device", "sim://?speed=0", "--controller", "pi",
             "--feedforward", "--target", "54.4", "--duration", "10", "--log", str(log),
             "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert abs(d["final_friction_n"] / 54.4 - 1) < 0.02
    assert d["vented"] is True and d["stopped_reason"] == "completed"
    for key in ("settling_time_s", "overshoot_pct", "steady_state_error_n", "jitter_p50_ms",
                "jitter_p99_ms", "overruns", "log_path"):
        assert key in d
    frame = read_raw_log(log)                 # the rig-log schema reads back
    assert len(frame) == d["n_samples"] and "setpoint_n" in frame.attrs["ignored_columns"]
    # exofric reduce finds the run as one pull after the vented 1 s baseline (its tare); its
    # steady window, once the loop has settled, is the friction the loop held
    red = cli(["reduce", str(log), "--skip-s", "8", "--json"])
    assert red.code == 0, red.err
    assert red.json()["curve"]["kinetic_n"][0] == pytest.approx(54.4, rel=0.02)
    # and control identify reads its pressure and command columns (closed-loop data: it warns)
    r2 = cli(["control", "identify", str(log), "--json"])
    assert r2.code == 0, r2.err


def test_run_with_scheduling_and_a_dry_run(cli) -> None:
    r = cli(["control", "run", "--device", "sim://?speed=0", "--schedule", "--duration", "6",
             "--json"])
    assert r.code == 0, r.err
    assert r.json()["schedule"] is True
    r = cli(["control", "run", "--device", "sim://?speed=0", "--dry-run", "--duration", "1",
             "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert d["dry_run"] is True and d["final_friction_n"] == pytest.approx(0.0, abs=1e-9)


def test_run_against_the_modbus_test_server_in_real_time(cli) -> None:
    with ModbusSimServer() as srv:
        r = cli(["control", "run", "--device", srv.url, "--controller", "pi", "--feedforward",
                 "--duration", "10", "--rate", "100", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert abs(d["final_friction_n"] / 54.4 - 1) < 0.02
    assert d["jitter_p99_ms"] < 50.0          # a sanity bound only: a loaded CI machine varies


def test_frozen_sensor_vents_and_exits_4_with_the_time(cli) -> None:
    with ModbusSimServer(freeze_after_s=1.0) as srv:
        r = cli(["control", "run", "--device", srv.url, "--duration", "5", "--watchdog",
                 "0.3"])
        assert srv.rig.vented
    assert r.code == 4, r.err
    lines = [ln for ln in r.err.splitlines() if ln.strip()]
    assert len(lines) == 1 and "watchdog at" in lines[0] and " s" in lines[0]


def test_unreachable_device_is_one_line_exit_2_within_seconds(cli) -> None:
    t0 = time.monotonic()
    r = cli(["control", "run", "--device", "modbus-tcp://127.0.0.1:1", "--duration", "2"])
    assert r.code == 2 and time.monotonic() - t0 < 8.0
    assert len([ln for ln in r.err.splitlines() if ln.strip()]) == 1


def test_setpoint_above_the_limit_is_refused_before_start(cli) -> None:
    r = cli(["control", "run", "--device", "sim://?speed=0", "--target", "400",
             "--max-force", "250"])
    assert r.code == 2 and "Traceback" not in r.err


def test_identify_charge_recovers_planted_conductance_and_volume(cli, tmp_path: Path) -> None:
    """Two runs, one with a known 10 cm^3 reservoir added: C and V both identifiable (a single
    volume gives only C / V). Planted: C fill 0.08, vent 0.05 dm^3/(s bar); V = line + tube."""
    base = PneumaticParams(fill=Orifice(0.08), vent=Orifice(0.05), valve="on-off")
    big = PneumaticParams(fill=Orifice(0.08), vent=Orifice(0.05), valve="on-off",
                          line_volume_mm3=base.line_volume_mm3 + 10_000.0)
    paths = []
    for k, pp in enumerate((base, big)):
        df = simulate_charge(pp, duration_s=3.0, noise_mpa=0.002, seed=k)
        path = tmp_path / f"charge{k}.csv"
        df[["time_s", "pressure_mpa", "command_mpa"]].to_csv(path, index=False)
        paths.append(path)
    r = cli(["control", "identify", "--charge", str(paths[0]), "--charge", str(paths[1]),
             "--added-volume", "0,10000", "--supply", "0.6", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    v_true = base.total_volume_mm3(0.0)
    assert d["c_fill_dm3_per_s_bar"] == pytest.approx(0.08, rel=0.05)
    assert d["c_vent_dm3_per_s_bar"] == pytest.approx(0.05, rel=0.05)
    assert d["volume_mm3"] == pytest.approx(v_true, rel=0.05)
    # one log alone: C and V are not separable, and the error says what to add
    r1 = cli(["control", "identify", "--charge", str(paths[0])])
    assert r1.code == 2 and ("volume" in r1.err and "conductance" in r1.err.lower()
                             or "c_dm3" in r1.err)


def test_ctrl_c_during_a_run_vents_and_exits_130(tmp_path: Path) -> None:
    """SIGINT to a running `control run`: one line, exit 130, the log has the vented stop."""
    import signal
    import subprocess
    import sys

    log = tmp_path / "int.csv"
    p = subprocess.Popen([sys.executable, "-m", "exofric", "control", "run", "--device",
                          "sim://?speed=1", "--duration", "20", "--log", str(log)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(3.0)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=30)
    assert p.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    text = log.read_text()
    assert "stopped: interrupted" in text and "vented: true" in text


def test_modbus_rig_whose_gain_is_not_the_models_ends_within_half_a_percent(cli) -> None:
    """Issue 30's acceptance: a rig behind a Modbus TCP server on 127.0.0.1 whose supply has a
    static gain of 0.9 (the controller's model assumes 1), PI with the 2-DOF model feedforward:
    the integral must remove the offset, so the friction ends within 0.5 % of 54.4 N (before the
    fix the 2-DOF reference carried the model's error into the set-point). The offset decays
    with the loop's closed-loop time (about 2 s per e-fold from the feedforward's -10 %; the
    simulation of the same loop: -0.9 % at 9 s, -0.03 % at 15 s), so the run lasts 15 s."""
    from exofric.control import PlantParams, PressurePlant

    plant = PressurePlant(PlantParams(gain=0.9, time_constant_s=0.35, delay_s=0.08))
    with ModbusSimServer(plant=plant) as srv:
        r = cli(["control", "run", "--device", srv.url, "--controller", "pi", "--feedforward",
                 "--duration", "15", "--rate", "100", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert abs(d["final_friction_n"] / 54.4 - 1) < 0.005, d["final_friction_n"]
