"""Safety review of the control loop and the device layer (issue 17 hardening).

Each test pins one hole found in review: what reaches the device (never a non-finite or
above-limit set-point), venting on every exit path (Ctrl-C inside a read, a failing log
writer, a failing first vent, a second Ctrl-C while venting), the watchdog (a constant value
with a moving heartbeat keeps running; a frozen or silent sensor trips; a non-finite reading
never disables the pressure trip), Modbus venting when one of its two writes fails, and the
serial simulator obeying the protocol's "t_ms changes only with a new sample" rule.
References: the limits and rules stated in ``exofric.hardware._loop``'s docstring and
``examples/serial-protocol.md``; exact comparisons (no numerics involved).
"""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

import pytest

from exofric.control import Controller, PIDGains
from exofric.errors import InputError
from exofric.hardware import (
    DEFAULT_MAP_PATH,
    DeviceError,
    LoopFault,
    ModbusSimServer,
    Reading,
    SafetyLimits,
    SensorStale,
    SerialSimDevice,
    SimClock,
    open_device,
    run_loop,
)
from exofric.io import read_raw_log

TARGET_N = 54.4


class FakeDevice:
    """A scripted device on a SimClock: records every set-point and vent."""

    def __init__(self, reads: Any = None) -> None:
        self.url = "fake://"
        self.clock = SimClock()
        self.writes: list[float] = []
        self.vents = 0
        self.n = 0
        self._reads = reads

    def read(self) -> Reading:
        self.n += 1
        if self._reads is not None:
            return self._reads(self.n)
        return Reading(0.1, 10.0, self.n)

    def write_setpoint_mpa(self, p: float) -> None:
        self.writes.append(p)

    def vent(self) -> None:
        self.vents += 1


def _pi() -> Controller:
    return Controller(PIDGains(0.002, 0.004))


def test_constant_values_with_moving_heartbeat_do_not_trip() -> None:
    dev = FakeDevice(lambda n: Reading(0.2, 30.0, n))       # steady rig, live sensor
    res = run_loop(dev, _pi(), 30.0, duration_s=2.0, watchdog_s=0.1)
    assert res.stopped_reason == "completed" and res.n_samples == 201


def test_frozen_heartbeat_trips_and_silent_sensor_trips() -> None:
    dev = FakeDevice(lambda n: Reading(0.2, 30.0, min(n, 20)))
    with pytest.raises(LoopFault, match="sensor unchanged"):
        run_loop(dev, _pi(), 30.0, duration_s=2.0, watchdog_s=0.1)

    def silent(n: int) -> Reading:
        if n > 20:
            raise SensorStale("fake://: no answer")
        return Reading(0.2, 30.0, n)

    dev = FakeDevice(silent)
    with pytest.raises(LoopFault, match="no valid reading") as ei:
        run_loop(dev, _pi(), 30.0, duration_s=2.0, watchdog_s=0.1)
    assert ei.value.result.vented and dev.vents >= 2


@pytest.mark.parametrize("bad", ["pressure", "force"])
def test_non_finite_reading_is_not_a_valid_reading(bad: str) -> None:
    """A NaN pressure made every limit comparison False: the trip was disabled."""
    def reads(n: int) -> Reading:
        if n <= 10:
            return Reading(0.1, 10.0, n)
        return Reading(math.nan, 10.0, n) if bad == "pressure" else Reading(0.1, math.nan, n)

    dev = FakeDevice(reads)
    with pytest.raises(LoopFault, match="no valid reading.*non-finite") as ei:
        run_loop(dev, _pi(), 30.0, duration_s=2.0, watchdog_s=0.1)
    assert ei.value.reason == "watchdog" and ei.value.result.vented
    assert len(dev.writes) == 10                 # nothing written after the bad readings
    assert all(math.isfinite(v) for v in dev.writes)


class _NaNController(Controller):
    def step(self, setpoint: float, measurement: float, dt: float) -> float:
        super().step(setpoint, measurement, dt)
        return math.nan


def test_non_finite_command_never_reaches_the_device() -> None:
    dev = FakeDevice()                          # a device that does not check its input
    with pytest.raises(Exception, match="non-finite command"):
        run_loop(dev, _NaNController(PIDGains(0.002, 0.004)), 30.0, duration_s=1.0)
    assert dev.writes == [] and dev.vents >= 2


def test_commands_never_exceed_max_pressure_even_with_feedforward() -> None:
    from exofric.control import ModelFeedforward

    ff = ModelFeedforward(lambda f: 0.0)        # lies: says no pressure is needed
    ctrl = Controller(PIDGains(0.5, 1.0), u_max=5.0, feedforward=ff)   # saturates high
    dev = FakeDevice(lambda n: Reading(0.1, 0.0, n))
    run_loop(dev, ctrl, 200.0, duration_s=1.0, limits=SafetyLimits(0.3, 250.0))
    assert dev.writes and max(dev.writes) == 0.3


def test_keyboard_interrupt_inside_read_vents_and_writes_the_log(tmp_path: Path) -> None:
    def reads(n: int) -> Reading:
        if n == 30:
            raise KeyboardInterrupt
        return Reading(0.1, 10.0, n)

    dev = FakeDevice(reads)
    log = tmp_path / "int.csv"
    with pytest.raises(KeyboardInterrupt):
        run_loop(dev, _pi(), 30.0, duration_s=2.0, log_path=log)
    assert dev.vents >= 2
    assert any("stopped: interrupted" in m for m in read_raw_log(log).attrs["metadata"])


def test_second_ctrl_c_while_venting_still_vents(tmp_path: Path) -> None:
    """Ctrl-C twice: the second lands inside vent(); the loop retries the vent."""
    class Dev(FakeDevice):
        def vent(self) -> None:
            if self.vents == 1 and not getattr(self, "hit", False):
                self.hit = True
                raise KeyboardInterrupt
            super().vent()

    def reads(n: int) -> Reading:
        if n == 30:
            raise KeyboardInterrupt
        return Reading(0.1, 10.0, n)

    dev = Dev(reads)
    log = tmp_path / "int2.csv"
    with pytest.raises(KeyboardInterrupt):
        run_loop(dev, _pi(), 30.0, duration_s=2.0, log_path=log)
    assert dev.vents == 2                        # start + the retried end vent
    text = log.read_text()
    assert "vented: true" in text


def test_failing_log_writer_still_vents(tmp_path: Path, monkeypatch) -> None:
    import exofric.hardware._loop as loop_mod

    calls = {"n": 0}
    real = loop_mod._fmt

    def bad_fmt(v: float) -> str:
        calls["n"] += 1
        if calls["n"] > 200:
            raise OSError(28, "No space left on device")
        return real(v)

    monkeypatch.setattr(loop_mod, "_fmt", bad_fmt)
    dev = FakeDevice()
    with pytest.raises(OSError, match="No space"):
        run_loop(dev, _pi(), 30.0, duration_s=2.0, log_path=tmp_path / "full.csv")
    assert dev.vents >= 2 and dev.writes


def test_loop_fault_says_when_the_vent_failed() -> None:
    class Dev(FakeDevice):
        def vent(self) -> None:
            self.vents += 1
            if self.vents > 1:
                raise DeviceError("fake://: no answer to V")

    dev = Dev(lambda n: Reading(0.1, 10.0, min(n, 5)))
    with pytest.raises(LoopFault) as ei:
        run_loop(dev, _pi(), 30.0, duration_s=2.0, watchdog_s=0.1)
    assert not ei.value.result.vented
    assert "(vented)" not in str(ei.value) and "NOT vented" in str(ei.value)
    assert dev.vents == 3                        # start + two attempts


def test_loop_fault_default_message_unchanged() -> None:
    assert str(LoopFault("watchdog", 3.02, "x")) == "watchdog at 3.020 s: x (vented)"


def test_dry_run_writes_nothing_even_after_baseline() -> None:
    dev = FakeDevice()
    run_loop(dev, _pi(), 30.0, duration_s=1.0, baseline_s=0.5, dry_run=True)
    assert dev.writes == []


def test_serial_sim_stale_sensor_keeps_t_ms_and_trips_the_watchdog() -> None:
    """Protocol rule: t_ms changes only with a new sample. The simulator's stale fault
    answered the old values with a *new* t_ms, so the host's watchdog never tripped."""
    with SerialSimDevice(freeze_after_s=0.3, fault="stale") as sim, \
            open_device(sim.url + "?timeout=0.1") as dev:
        time.sleep(0.4)
        a, b = dev.read(), dev.read()
        assert a.sample_id == b.sample_id
        with pytest.raises(LoopFault, match="sensor unchanged"):
            run_loop(dev, _pi(), TARGET_N, duration_s=3.0, rate_hz=50.0, watchdog_s=0.2)
        assert sim.rig.vented


def test_modbus_vent_writes_zero_set_point_even_if_the_vent_register_fails(
        tmp_path: Path) -> None:
    bad = tmp_path / "map.toml"
    text = DEFAULT_MAP_PATH.read_text(encoding="utf-8")
    bad.write_text(text.replace('[vent]                # exhaust valve: vent_value opens the '
                                'tube to atmosphere\ntable = "holding"\naddress = 1',
                                '[vent]\ntable = "holding"\naddress = 40'), encoding="utf-8")
    with ModbusSimServer() as srv:
        dev = open_device(srv.url, bad)
        srv.rig.set_command(0.3)
        with pytest.raises(DeviceError, match="vent"):
            dev.vent()
        assert srv.rig.command_mpa == 0.0         # the set-point 0 still went out
        dev.close()


def test_modbus_non_finite_float_reading_is_stale() -> None:
    from exofric.hardware import RegisterSpec, decode_registers, encode_registers

    s = RegisterSpec("force", "input", 2, "float32")
    assert math.isnan(decode_registers(s, encode_registers(s, math.nan)))
    with pytest.raises(DeviceError, match="cannot encode"):
        encode_registers(s, 1e40)                 # beyond float32
    broken = {"on": False}

    def friction(p: float) -> float:              # the load cell answers NaN once broken
        return math.nan if broken["on"] else 100.0 * p

    with ModbusSimServer(friction=friction) as srv, open_device(srv.url) as dev:
        dev.read()
        broken["on"] = True
        with pytest.raises(SensorStale, match="reads nan"):
            dev.read()


def test_serial_protocol_example_session_replays_on_the_simulator() -> None:
    """The doc's example session, line by line, against the simulated firmware."""
    import re

    doc = (Path(__file__).parents[1] / "examples" / "serial-protocol.md").read_text()
    session = doc.split("## Example session", 1)[1].split("```")[1].strip().splitlines()
    pairs = [(a[2:], b[2:]) for a, b in zip(session[::2], session[1::2], strict=True)]
    with SerialSimDevice() as sim, open_device(sim.url) as dev:
        for cmd, want in pairs:
            got = dev._command(cmd)
            if want.startswith("D "):
                assert re.fullmatch(r"D \d+ -?\d+\.\d{6} -?\d+\.\d{4}", got), got
            elif want.startswith("EXOFRIC-RIG"):
                assert got.split()[:2] == want.split()[:2]
            else:
                assert got == want
        for bad, err in (("S abc", "ERR bad set-point"), ("S nan", "ERR"),
                         ("S 99", "ERR set-point out of range"), ("W x", "ERR bad watchdog")):
            with pytest.raises(DeviceError, match="refused"):
                dev._command(bad)
            assert sim._answer(bad).startswith(err)
        assert sim.rig.vented                      # the session ended with V; refusals kept it


def test_constant_setpoint_is_checked_once_not_per_sample() -> None:
    """The pre-start check built a Python list of one value per sample: a 1e5 s run at
    2 kHz (the CLI's limits) meant 2e8 calls and 1.6 GB before the first sample."""
    dev = FakeDevice()            # (a regression shows as a test that hangs for minutes)
    with pytest.raises(InputError, match="above the force limit"):
        run_loop(dev, _pi(), 300.0, duration_s=1e5, rate_hz=2000.0)
    assert dev.vents == 0 and dev.n == 0                         # refused before start
