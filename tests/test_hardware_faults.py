"""Run-time device faults (issue 30): every fault vents and exits 4; an unconfirmed vent exits 5.

Each backend gets the faults of the issue injected mid-run, through the real client code:
``sim://`` (its ``fault=KIND@T`` query), Modbus TCP (pymodbus's own server on 127.0.0.1 with an
action hook that goes silent, drops the connection, serves NaN, a railed sensor or junk
registers, or dies), Modbus RTU (pymodbus's RTU server across a pty pair) and serial (the pty
firmware simulator sending ``nan`` or a junk line after the handshake, or unplugged). The CLI
runs in process (``exofric.cli.run``: its real exit code, stdout and stderr).

Independent witnesses, never the loop's own account of itself: the simulated rig's state
(``vented``, the regulator's command, the set-points it received) says whether the vent
reached the device; the rig log read back by ``exofric.io.read_raw_log`` says which samples were
kept, checked against the sample grid k / rate (closed form, exact on the simulated clock; on
real time: contiguous rows, each before the fault's stated time). Exit codes: those stated in
the issue (2 bad input, 4 fault and vented, 5 vent not confirmed). Timing honesty: a device
whose read takes 1.5 periods runs every second grid point -- achieved rate = rate / 2 exactly
on a simulated clock, cross-checked from the log's time column. All traffic stays on
127.0.0.1 or local ptys; every wait is bounded (timeouts of 0.1-0.3 s, runs of at most 3 s).
"""

from __future__ import annotations

import math
import os
import re
import sys
import threading
import time
import tty
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from exofric.control import Controller, PIDGains
from exofric.errors import EXIT_FAULT, EXIT_INPUT, EXIT_VENT_NOT_CONFIRMED, PlausibilityWarning
from exofric.hardware import (
    DeviceFault,
    LoopFault,
    ModbusSimServer,
    Reading,
    SerialSimDevice,
    SimClock,
    SimRig,
    run_loop,
)
from exofric.io import read_raw_log

pytest.importorskip("pymodbus")
pytest.importorskip("serial")
posix_only = pytest.mark.skipif(sys.platform == "win32", reason="needs POSIX ptys")

RATE_HZ = 100.0
N_BEFORE = 25          # real-time backends: the fault starts after this many set-points
WATCHDOG_S = 0.1


def _when_running(rig: SimRig, action: Any) -> threading.Thread:
    """Call ``action()`` once the rig has received N_BEFORE set-points (mid-run, whatever
    the start-up took); gives up after 10 s."""
    def wait() -> None:
        end = time.monotonic() + 10.0
        while len(rig.setpoints) < N_BEFORE and time.monotonic() < end:
            time.sleep(0.002)
        action()

    th = threading.Thread(target=wait, daemon=True)
    th.start()
    return th


def _arm(rig: SimRig) -> threading.Thread:
    """Start the rig's injected fault mid-run (it was made with ``fault=`` and no onset)."""
    return _when_running(rig, lambda: setattr(rig, "freeze_after_s", rig.time_s))


@pytest.fixture
def cli_inproc(capsys, monkeypatch):
    """``exofric ARGS`` in this process: (exit code, stdout, stderr)."""
    from exofric.cli import run

    monkeypatch.setattr(warnings, "showwarning", warnings.showwarning)   # run() replaces it

    def call(args: list[str]) -> tuple[int, str, str]:
        code = run(args)
        cap = capsys.readouterr()
        return code, cap.out, cap.err

    return call


def _args(url: str, log: Path, *extra: str) -> list[str]:
    return ["control", "run", "--device", url, "--duration", "3", "--rate", f"{RATE_HZ:g}",
            "--watchdog", f"{WATCHDOG_S:g}", "--baseline", "0", "--log", str(log), *extra]


def _one_line(err: str) -> str:
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, err
    assert "Traceback" not in err
    return lines[0]


def _fault_time(line: str) -> float:
    m = re.search(r"(watchdog|pressure limit|force limit|device fault) at (\d+\.\d+) s: ", line)
    assert m, line
    return float(m.group(2))


def _check_log_up_to(log: Path, t_fault: float) -> Any:
    """Every sample up to the fault: rows from t = 0, one per period (no gap of a whole
    period: the loop skips none on an idle machine; tolerance 0.9 period for a loaded one,
    which would show as a skipped-cycle count in the footer), all before the fault's time. Read
    back with a wide gap tolerance: a stall of a loaded machine is a gap in a real-time log,
    which the skipped-cycle count accounts for (checked below), not a broken file."""
    df = read_raw_log(log, max_gap_factor=1e4)
    t = df["time_s"].to_numpy()
    meta = "\n".join(df.attrs["metadata"])
    skipped = int(re.search(r"skipped: (\d+)", meta).group(1))
    assert len(t) >= N_BEFORE - 1                           # the run got going first
    assert t[0] == pytest.approx(0.0, abs=0.05)
    if skipped == 0:
        assert np.all(np.diff(t) < 1.9 / RATE_HZ), np.diff(t).max()
    assert t[-1] <= t_fault
    assert not log.with_name(f"{log.stem}.partial{log.suffix}").exists()
    return df


def _rig_vented_after_running(rig: SimRig) -> None:
    """The device itself saw set-points, then a vent (the witness is the rig, not the loop)."""
    assert rig.setpoints and max(rig.setpoints) > 0.0      # it was pressurised mid-run
    assert rig.vented and rig.command_mpa == 0.0


# --------------------------------------------------------------------------------- sim://

@pytest.fixture
def sim_rigs(monkeypatch) -> list[SimRig]:
    """Every SimRig made during the test (the CLI opens its own sim:// device)."""
    made: list[SimRig] = []
    init = SimRig.__init__

    def spy(self: SimRig, *a: Any, **k: Any) -> None:
        init(self, *a, **k)
        made.append(self)

    monkeypatch.setattr(SimRig, "__init__", spy)
    return made


@pytest.mark.parametrize(("kind", "reason"), [
    ("nan", "watchdog"), ("silent", "watchdog"), ("range", "pressure limit"),
    ("junk", "device fault"), ("drop", "device fault"),
])
def test_sim_fault_mid_run_vents_exits_4_and_keeps_every_sample(
        kind: str, reason: str, cli_inproc, sim_rigs, tmp_path: Path) -> None:
    """On the simulated clock the sample grid is exact: a fault at 1.0 s at 100 Hz leaves the
    rows k / 100 s for k = 0..99 (100 rows), and the stop is at 1.0 s (immediate faults) or
    at the first period at least ``watchdog`` after the last good sample 0.99 s."""
    log = tmp_path / f"{kind}.csv"
    code, out, err = cli_inproc(_args(f"sim://?speed=0&fault={kind}@1.0", log))
    assert code == EXIT_FAULT, err
    line = _one_line(err)
    assert line.startswith("exofric: stopped: ") and line.endswith("(vented)")
    assert f"{reason} at " in line
    t_stop = _fault_time(line)
    period = 1.0 / RATE_HZ
    if reason == "watchdog":
        last_good = 1.0 - period
        assert last_good + WATCHDOG_S - 1e-9 <= t_stop <= last_good + WATCHDOG_S + period
    else:
        assert t_stop == pytest.approx(1.0, abs=1e-9)
    (rig,) = sim_rigs
    _rig_vented_after_running(rig)
    df = read_raw_log(log)
    n = round(1.0 * RATE_HZ)
    np.testing.assert_allclose(df["time_s"].to_numpy(), np.arange(n) / RATE_HZ, atol=1e-9)
    meta = "\n".join(df.attrs["metadata"])
    assert f"stopped: {reason} at" in meta and "vented: true" in meta


def test_sim_dead_device_exits_5_with_a_loud_line(cli_inproc, sim_rigs, tmp_path: Path) -> None:
    """``mute``: reads, the vent and the reconnect all fail: exit 5, the rig is not vented."""
    log = tmp_path / "mute.csv"
    code, out, err = cli_inproc(_args("sim://?speed=0&fault=mute@1.0", log))
    assert code == EXIT_VENT_NOT_CONFIRMED, err
    line = _one_line(err)
    assert line.startswith("exofric: VENT NOT CONFIRMED: ")
    assert "the tube may still be pressurised" in line and "watchdog at" in line
    (rig,) = sim_rigs
    assert not rig.vented and rig.command_mpa > 0.0         # really left pressurised
    assert "vented: false" in "\n".join(read_raw_log(log).attrs["metadata"])


def test_sim_fault_json_names_the_fault_and_the_plant(cli_inproc, tmp_path: Path) -> None:
    code, out, err = cli_inproc(_args("sim://?speed=0&fault=junk@0.5", tmp_path / "j.csv",
                                      "--json"))
    assert code == EXIT_FAULT
    import json

    d = json.loads(out)
    assert d["stopped_reason"] == "device fault" and d["vented"] is True
    assert d["stopped_at_s"] == pytest.approx(0.5, abs=1e-9) and d["exit_code"] == 4
    assert "junk" in d["fault"] and d["plant"].startswith("sim://")
    assert d["n_samples"] == round(0.5 * RATE_HZ) and isinstance(d["warnings"], list)


@pytest.mark.parametrize("bad", ["fault=bogus@1", "fault=nan@-1", "fault=nan@x"])
def test_bad_sim_fault_query_is_bad_input_exit_2(bad: str, cli_inproc, tmp_path) -> None:
    code, _, err = cli_inproc(_args(f"sim://?speed=0&{bad}", tmp_path / "b.csv"))
    assert code == EXIT_INPUT
    assert "fault must be KIND@T" in _one_line(err)


def test_completed_run_reports_the_plant(cli_inproc) -> None:
    import json

    code, out, err = cli_inproc(["control", "run", "--device", "sim://?speed=0", "--duration",
                                 "1", "--json"])
    assert code == 0, err
    d = json.loads(out)
    assert d["plant"].startswith("sim://?speed=0 (physical pneumatic plant")
    assert d["achieved_rate_hz"] == pytest.approx(100.0, rel=1e-9) and d["warnings"] == []
    code, out, err = cli_inproc(["control", "run", "--device", "sim://?speed=0", "--duration",
                                 "1"])
    assert code == 0 and "physical pneumatic plant" in out


# ----------------------------------------------------------------------------- Modbus TCP

@pytest.mark.parametrize(("kind", "reason"), [
    ("silent", "watchdog"), ("nan", "watchdog"), ("drop", "device fault"),
    ("range", "device fault"), ("junk", "device fault"),
])
def test_modbus_tcp_fault_mid_run_vents_and_exits_4(kind: str, reason: str, cli_inproc,
                                                    tmp_path: Path) -> None:
    """silent: exception replies to reads; nan: the float32 load cell reads NaN; drop: the
    server closes the connection (the vent goes out on a fresh one); range: the pressure
    rails at 3276.7 kPa, outside the map's declared [-50, 1000] kPa; junk: 0xDEAD in every
    register read (-853.1 kPa, also outside it)."""
    log = tmp_path / f"mb-{kind}.csv"
    with ModbusSimServer(fault=kind) as srv:
        _arm(srv.rig)
        code, out, err = cli_inproc(_args(srv.url + "&timeout=0.1", log))
        rig = srv.rig
    assert code == EXIT_FAULT, err
    line = _one_line(err)
    assert f"{reason} at " in line and line.endswith("(vented)")
    if kind == "drop":
        assert "connection lost" in line
    if kind in ("range", "junk"):
        assert "outside its declared range" in line
    _rig_vented_after_running(rig)
    _check_log_up_to(log, _fault_time(line))


def test_modbus_tcp_dead_device_and_refused_reconnect_exit_5(cli_inproc,
                                                             tmp_path: Path) -> None:
    """The server goes away mid-run: the read fails (connection lost), the vent fails, the
    reconnect is refused: exit 5 and the loud line; the log still has the run."""
    log = tmp_path / "mb-dead.csv"
    srv = ModbusSimServer()
    _when_running(srv.rig, srv.stop)
    try:
        t0 = time.monotonic()
        code, out, err = cli_inproc(_args(srv.url + "&timeout=0.1", log))
        assert time.monotonic() - t0 < 10.0
    finally:
        srv.stop()
    assert code == EXIT_VENT_NOT_CONFIRMED, err
    line = _one_line(err)
    assert line.startswith("exofric: VENT NOT CONFIRMED: ") and "device fault at" in line
    assert "may still be pressurised" in line
    assert not srv.rig.vented                      # the vent never reached the rig
    _check_log_up_to(log, _fault_time(line))


def test_modbus_tcp_mute_device_exits_5(cli_inproc, tmp_path: Path) -> None:
    """``mute``: the server accepts connections but answers nothing (the vent included)."""
    with ModbusSimServer(fault="mute") as srv:
        _arm(srv.rig)
        code, out, err = cli_inproc(_args(srv.url + "&timeout=0.1", tmp_path / "m.csv"))
        assert not srv.rig.vented
    assert code == EXIT_VENT_NOT_CONFIRMED, err
    assert _one_line(err).startswith("exofric: VENT NOT CONFIRMED: watchdog at ")


# ----------------------------------------------------------------------------- Modbus RTU

@pytest.fixture
def rtu():
    """(bridge, server class) of tests/test_hardware_rtu.py: a null-modem pty pair."""
    from test_hardware_rtu import PtyBridge, RtuSimServer

    b = PtyBridge()
    yield b, RtuSimServer
    b.close()


@posix_only
@pytest.mark.parametrize(("kind", "reason"), [
    ("silent", "watchdog"), ("nan", "watchdog"), ("range", "device fault"),
    ("junk", "device fault"),
])
def test_modbus_rtu_fault_mid_run_vents_and_exits_4(kind: str, reason: str, rtu, cli_inproc,
                                                    tmp_path: Path) -> None:
    bridge, server = rtu
    log = tmp_path / f"rtu-{kind}.csv"
    with server(bridge.server_path, fault=kind) as srv:
        _arm(srv.rig)
        url = f"modbus-rtu://{bridge.client_path}?baud=115200&unit=1&timeout=0.2"
        code, out, err = cli_inproc(_args(url, log))
        rig = srv.rig
    assert code == EXIT_FAULT, err
    line = _one_line(err)
    assert f"{reason} at " in line and line.endswith("(vented)")
    _rig_vented_after_running(rig)
    _check_log_up_to(log, _fault_time(line))


@posix_only
def test_modbus_rtu_cable_pulled_exits_5(rtu, cli_inproc, tmp_path: Path) -> None:
    """The bridge stops relaying mid-run (cable pulled for good): nothing is answered, the
    port re-opens but the vent is never confirmed: exit 5."""
    bridge, server = rtu
    with server(bridge.server_path) as srv:
        _when_running(srv.rig, lambda: setattr(bridge, "_run", False))
        url = f"modbus-rtu://{bridge.client_path}?baud=115200&unit=1&timeout=0.1"
        code, out, err = cli_inproc(_args(url, tmp_path / "pulled.csv"))
        assert not srv.rig.vented
    assert code == EXIT_VENT_NOT_CONFIRMED, err
    assert _one_line(err).startswith("exofric: VENT NOT CONFIRMED: watchdog at ")


# --------------------------------------------------------------------------------- serial

@posix_only
@pytest.mark.parametrize(("kind", "reason", "said"), [
    ("nan", "watchdog", "force nan N"), ("junk", "device fault", "malformed answer"),
    ("silent", "watchdog", "no answer to 'R'"), ("range", "pressure limit", "3.277 MPa"),
])
def test_serial_fault_mid_run_vents_and_exits_4(kind: str, reason: str, said: str,
                                                cli_inproc, tmp_path: Path) -> None:
    """After the handshake the simulated firmware sends ``D <t> <p> nan``, a junk line, no
    line, or a railed pressure; the host vents over the same port."""
    log = tmp_path / f"ser-{kind}.csv"
    with SerialSimDevice(fault=kind) as sim:
        _arm(sim.rig)
        code, out, err = cli_inproc(_args(sim.url + "?timeout=0.1", log))
        rig = sim.rig
        assert sim.lines[-1] == "V"                 # the last command it got was the vent
    assert code == EXIT_FAULT, err
    line = _one_line(err)
    assert f"{reason} at " in line and said in line and line.endswith("(vented)")
    _rig_vented_after_running(rig)
    _check_log_up_to(log, _fault_time(line))


class ReplugSerialSim(SerialSimDevice):
    """Unplugged at the fault, back at once on a new pty behind the same symlink (as udev's
    /dev/serial/by-id/ links do): the host must re-open the port to vent."""

    def __init__(self, link: Path, **kwargs: Any) -> None:
        self.link = link
        self.replugged = threading.Event()
        super().__init__(**kwargs)
        os.symlink(self.port, link)

    @property
    def url(self) -> str:
        return f"serial://{self.link}"

    def _close_fds(self) -> None:
        if self._running and not self.replugged.is_set():
            old = (self._master, self._slave)
            self._master, self._slave = os.openpty()      # the new port exists first
            tty.setraw(self._slave)
            self.port = os.ttyname(self._slave)
            tmp = self.link.with_suffix(".new")
            os.symlink(self.port, tmp)
            os.replace(tmp, self.link)
            self.rig.freeze_after_s = None                # plugged back in: fault over
            for fd in old:
                os.close(fd)
            self.replugged.set()
            return
        super()._close_fds()

    def _serve(self) -> None:
        super()._serve()                                  # returns at the unplug
        if self._running and self.replugged.is_set():
            super()._serve()


@posix_only
def test_serial_unplugged_and_replugged_vents_on_the_reopened_port(cli_inproc,
                                                                   tmp_path: Path) -> None:
    log = tmp_path / "replug.csv"
    with ReplugSerialSim(tmp_path / "ttyRIG", fault="drop") as sim:
        _arm(sim.rig)
        code, out, err = cli_inproc(_args(sim.url + "?timeout=0.1", log))
        assert sim.replugged.is_set()
        rig = sim.rig
        assert sim.lines[-2:] == ["?", "V"]         # handshake on the new port, then vent
    assert code == EXIT_FAULT, err
    line = _one_line(err)
    assert "device fault at" in line and "port failed" in line and line.endswith("(vented)")
    _rig_vented_after_running(rig)
    _check_log_up_to(log, _fault_time(line))


@posix_only
def test_serial_unplugged_for_good_exits_5(cli_inproc, tmp_path: Path) -> None:
    with SerialSimDevice(fault="drop") as sim:
        _arm(sim.rig)
        code, out, err = cli_inproc(_args(sim.url + "?timeout=0.1", tmp_path / "gone.csv"))
        assert not sim.rig.vented
    assert code == EXIT_VENT_NOT_CONFIRMED, err
    line = _one_line(err)
    assert line.startswith("exofric: VENT NOT CONFIRMED: device fault at ")
    assert "port failed" in line


@pytest.mark.parametrize("how", ["completed", "interrupted"])
def test_unconfirmed_vent_after_a_completed_or_interrupted_run_exits_5(
        how: str, cli_inproc, monkeypatch) -> None:
    """Not only faults: a run that completes (or is Ctrl-C'd) and whose final vent the device
    never confirms (the vent and the reconnect fail) exits 5, not 0 or 130."""
    from exofric.hardware import SimulatedDevice

    calls = {"vent": 0, "read": 0, "reconnect": 0}
    real_read = SimulatedDevice.read

    def vent(self: Any) -> None:
        calls["vent"] += 1
        if calls["vent"] > 1:                       # the start vent works, later ones do not
            raise DeviceFault(f"{self.url}: no answer to the vent")

    def reconnect(self: Any) -> None:
        calls["reconnect"] += 1
        raise DeviceFault(f"{self.url}: reconnect refused")

    def read(self: Any) -> Reading:
        calls["read"] += 1
        if how == "interrupted" and calls["read"] == 50:
            raise KeyboardInterrupt
        return real_read(self)

    monkeypatch.setattr(SimulatedDevice, "vent", vent)
    monkeypatch.setattr(SimulatedDevice, "reconnect", reconnect)
    monkeypatch.setattr(SimulatedDevice, "read", read)
    code, out, err = cli_inproc(["control", "run", "--device", "sim://?speed=0", "--duration",
                                 "1", "--baseline", "0"])
    assert code == EXIT_VENT_NOT_CONFIRMED, err
    line = _one_line(err)
    assert line.startswith("exofric: VENT NOT CONFIRMED: ")
    assert "may still be pressurised" in line
    assert ("the run ended (completed" if how == "completed" else "interrupted at") in line
    # the start vent, the end vent, then its retry: a reconnect that is refused
    assert (calls["vent"], calls["reconnect"]) == (2, 1)


# ---------------------------------------------------------------- the loop (Python API)

class ScriptedDevice:
    """A device on a SimClock whose vent fails until it is reconnected (or for good)."""

    def __init__(self, *, reconnect_ok: bool = True, read_s: Any = None) -> None:
        self.url = "scripted://"
        self.clock = SimClock()
        self.n = 0
        self.events: list[str] = []
        self.broken = False
        self.reconnect_ok = reconnect_ok
        self.read_s = read_s

    def read(self) -> Reading:
        self.n += 1
        if self.read_s is not None:
            self.clock.advance(self.read_s(self.n))
        if self.n == 30:
            self.broken = True
            raise DeviceFault("scripted://: connection lost")
        return Reading(0.1, 10.0, self.n)

    def write_setpoint_mpa(self, p: float) -> None:
        self.events.append("S")

    def vent(self) -> None:
        self.events.append("V")
        if self.broken:
            raise DeviceFault("scripted://: no answer to the vent")

    def reconnect(self) -> None:
        self.events.append("reconnect")
        if not self.reconnect_ok:
            raise DeviceFault("scripted://: reconnect refused")
        self.broken = False


def _pi() -> Controller:
    return Controller(PIDGains(0.002, 0.004))


def test_vent_is_retried_on_a_fresh_connection() -> None:
    dev = ScriptedDevice()
    with pytest.raises(LoopFault) as ei:
        run_loop(dev, _pi(), 30.0, duration_s=2.0)
    assert dev.events[-3:] == ["V", "reconnect", "V"]
    assert ei.value.reason == "device fault" and ei.value.vent_confirmed
    assert ei.value.exit_code == EXIT_FAULT and ei.value.result.n_samples == 29


def test_refused_reconnect_means_vent_not_confirmed() -> None:
    dev = ScriptedDevice(reconnect_ok=False)
    with pytest.raises(LoopFault) as ei:
        run_loop(dev, _pi(), 30.0, duration_s=2.0)
    assert dev.events[-2:] == ["V", "reconnect"]
    assert not ei.value.vent_confirmed and ei.value.exit_code == EXIT_VENT_NOT_CONFIRMED
    assert "the tube may still be pressurised" in str(ei.value)


# ------------------------------------------------------------------------ timing honesty

class SlowDevice:
    """A steady rig on a SimClock whose read takes ``read_s(n)`` seconds (n = call count)."""

    def __init__(self, read_s: Any) -> None:
        self.url = "slow://"
        self.clock = SimClock()
        self.n = 0
        self.read_s = read_s

    def read(self) -> Reading:
        self.n += 1
        self.clock.advance(self.read_s(self.n))
        return Reading(0.1, 10.0, self.n)

    def write_setpoint_mpa(self, p: float) -> None:
        pass

    def vent(self) -> None:
        pass


def test_every_read_taking_one_and_a_half_periods_halves_the_rate_and_warns(
        tmp_path: Path) -> None:
    """Closed form: each cycle ends 1.5 periods after its start, so the next one runs at the
    second grid point: 1 s at 100 Hz runs the 51 even grid points, every one overruns and
    skips one; achieved rate 50 Hz exactly, also from the log's time column."""
    dt = 0.01
    log = tmp_path / "slow.csv"
    with pytest.warns(PlausibilityWarning, match=r"ran at 50 Hz of the requested 100 Hz"):
        res = run_loop(SlowDevice(lambda n: 1.5 * dt), _pi(), 30.0, duration_s=1.0,
                       rate_hz=100.0, log_path=log)
    assert (res.cycles, res.overruns, res.skipped) == (51, 51, 51)
    assert res.achieved_rate_hz == pytest.approx(50.0, rel=1e-9)
    t = read_raw_log(log)["time_s"].to_numpy()
    assert (len(t) - 1) / (t[-1] - t[0]) == pytest.approx(50.0, rel=1e-9)
    d = res.to_dict()
    assert d["achieved_rate_hz"] == pytest.approx(50.0) and len(d["warnings"]) == 1
    assert "51 of 102 cycles skipped" in d["warnings"][0]


@pytest.mark.parametrize(("slow_every", "cycles", "slow", "warns"),
                         [(150, 399, 2, False), (60, 395, 6, True)])
def test_timing_warning_threshold_is_one_percent(slow_every: int, cycles: int, slow: int,
                                                 warns: bool) -> None:
    """4 s at 100 Hz = 401 grid points; a read of 1.5 periods every ``slow_every``-th cycle
    overruns and skips one grid point. By hand: s skips leave 401 - s cycles, of which
    floor((401 - s) / every) are slow = s: every 150 -> s = 2 (0.5 %, no warning), every 60
    -> s = 6 of 395 (1.5 %, a warning); the last cycle (4.0 s) is never a slow one."""
    dt = 0.01
    dev = SlowDevice(lambda n: 1.5 * dt if n % slow_every == 0 else 0.0)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        res = run_loop(dev, _pi(), 30.0, duration_s=4.0, rate_hz=100.0)
    assert (res.cycles, res.overruns, res.skipped) == (cycles, slow, slow)
    assert bool(res.warnings) is warns
    assert any(issubclass(w.category, PlausibilityWarning) for w in rec) is warns
    want = (cycles - 1) / 4.0                               # first cycle at 0, last at 4.0 s
    assert res.achieved_rate_hz == pytest.approx(want, rel=1e-9)
    if warns:
        assert f"ran at {want:.4g} Hz of the requested 100 Hz" in res.warnings[0]


def test_cli_json_carries_the_timing_warning(cli_inproc, monkeypatch) -> None:
    """A sim:// device made slow (each read 15 ms on its simulated clock at 100 Hz): the
    warning is on stderr and in ``--json`` ``warnings``; achieved 50 Hz (every second point)."""
    import json

    from exofric.hardware import SimulatedDevice

    real = SimulatedDevice.read

    def slow_read(self: Any) -> Reading:
        self.clock.advance(0.015)
        return real(self)

    monkeypatch.setattr(SimulatedDevice, "read", slow_read)
    code, out, err = cli_inproc(["control", "run", "--device", "sim://?speed=0", "--duration",
                                 "1", "--baseline", "0", "--json"])
    assert code == 0, err
    d = json.loads(out)
    assert d["achieved_rate_hz"] == pytest.approx(50.0, rel=1e-9)
    assert any("ran at 50 Hz of the requested 100 Hz" in w for w in d["warnings"])
    assert "exofric: warning: control loop ran at 50 Hz" in err
    assert math.isfinite(d["jitter_p99_ms"])
