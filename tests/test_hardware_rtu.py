"""Modbus RTU end to end: pymodbus's own serial server on a pty pair, exofric's RTU client.

Two pseudo-terminals bridged by a thread form a null-modem cable; pymodbus's
``ModbusSerialServer`` (RTU framing) serves the simulated rig on one end, ``open_device(
"modbus-rtu://...")`` opens the other. This runs the RTU path (framing, CRC, unit id, timeouts)
the TCP tests cannot, and a non-default register map (signed int32 with a negative raw value,
little-endian words, kgf and bar converted by pint, the heartbeat in the holding table)
through both ends. References: the rig's own state (set-point written, vent), the physical
values the simulator put in; tolerance one raw count of each register's scale.
"""

from __future__ import annotations

import asyncio
import os
import select
import sys
import threading
import time
import tty
from pathlib import Path

import pytest

from exofric.control import Controller, PIDGains
from exofric.hardware import (
    DEFAULT_MAP_PATH,
    DeviceError,
    LoopFault,
    ModbusSimServer,
    load_register_map,
    open_device,
    run_loop,
)

pytest.importorskip("pymodbus")
pytest.importorskip("serial")
pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="needs POSIX ptys")


class PtyBridge:
    """Two pty pairs whose masters are copied into each other: a virtual null-modem cable."""

    def __init__(self) -> None:
        self.m1, self.s1 = os.openpty()
        self.m2, self.s2 = os.openpty()
        for fd in (self.s1, self.s2):
            tty.setraw(fd)
        self.server_path, self.client_path = os.ttyname(self.s1), os.ttyname(self.s2)
        self._run = True
        self._thread = threading.Thread(target=self._pump, daemon=True)
        self._thread.start()

    def _pump(self) -> None:
        other = {self.m1: self.m2, self.m2: self.m1}
        while self._run:
            try:
                ready, _, _ = select.select(list(other), [], [], 0.02)
                for fd in ready:
                    os.write(other[fd], os.read(fd, 4096))
            except OSError:
                return

    def close(self) -> None:
        self._run = False
        self._thread.join(1.0)
        for fd in (self.m1, self.s1, self.m2, self.s2):
            try:
                os.close(fd)
            except OSError:
                pass


class RtuSimServer(ModbusSimServer):
    """The simulated rig behind pymodbus's RTU serial server on ``path``."""

    def __init__(self, path: str, **kwargs) -> None:
        self._path = path
        super().__init__(**kwargs)

    def _serve(self) -> None:
        from pymodbus import FramerType
        from pymodbus.server import ModbusSerialServer

        async def main() -> None:
            self._loop = asyncio.get_running_loop()
            self._stop = asyncio.Event()
            server = ModbusSerialServer(self._device(), port=self._path, baudrate=115200,
                                        framer=FramerType.RTU)
            await server.serve_forever(background=True)
            self._ready.set()
            await self._stop.wait()
            await server.shutdown()

        try:
            asyncio.run(main())
        except BaseException as exc:  # noqa: BLE001 - reported by __init__
            self._error = exc
            self._ready.set()


@pytest.fixture
def bridge():
    b = PtyBridge()
    yield b
    b.close()


def _url(b: PtyBridge, extra: str = "") -> str:
    return f"modbus-rtu://{b.client_path}?baud=115200&unit=1&timeout=0.3{extra}"


ODD_MAP = """
description = "odd rig: signed int32 little-endian kPa with an offset, kgf, bar set-point"
[pressure]
table = "input"
address = 10
type = "int32"
word_order = "little"
scale = 0.001
offset = 10.0
unit = "kPa"
range = [-100.0, 1000.0]
[force]
table = "input"
address = 12
type = "int16"
scale = 0.01
unit = "kgf"
[heartbeat]
table = "holding"
address = 20
type = "uint16"
[setpoint]
table = "holding"
address = 0
type = "uint32"
word_order = "little"
scale = 0.0001
unit = "bar"
range = [0.0, 9.0]
[vent]
table = "holding"
address = 2
type = "int16"
vent_value = -1
run_value = 0
"""


def test_rtu_round_trip_vent_and_map_mismatch(bridge: PtyBridge, tmp_path: Path) -> None:
    with RtuSimServer(bridge.server_path) as srv:
        with open_device(_url(bridge)) as dev:
            dev.write_setpoint_mpa(0.3)
            assert srv.rig.command_mpa == pytest.approx(0.3, abs=1e-4)
            assert not srv.rig.vented
            time.sleep(0.3)
            r1, r2 = dev.read(), dev.read()
            assert r1.pressure_mpa > 0.1 and r2.sample_id != r1.sample_id
        assert srv.rig.vented and srv.rig.command_mpa == 0.0          # `with` vents
        bad = tmp_path / "bad.toml"
        bad.write_text(DEFAULT_MAP_PATH.read_text(encoding="utf-8")
                       .replace("address = 4", "address = 40"), encoding="utf-8")
        with pytest.raises(DeviceError, match="illegal data address.*does not match"):
            open_device(_url(bridge), bad)


def test_rtu_odd_register_map_round_trips_signed_words_and_units(bridge: PtyBridge,
                                                                 tmp_path: Path) -> None:
    path = tmp_path / "odd.toml"
    path.write_text(ODD_MAP, encoding="utf-8")
    m = load_register_map(path)
    with RtuSimServer(bridge.server_path, register_map=m) as srv:
        with open_device(_url(bridge), path) as dev:
            r0 = dev.read()                # at rest: 0 MPa is raw -10000 (negative, int32)
            assert r0.pressure_mpa == pytest.approx(0.0, abs=1e-9)
            dev.write_setpoint_mpa(0.25)   # 2.5 bar = raw 25000 (uint32, little words)
            assert srv.rig.command_mpa == pytest.approx(0.25, abs=1e-5)
            time.sleep(0.4)
            r = dev.read()
            truth = srv.rig._last            # what the simulator encoded
            assert r.pressure_mpa == pytest.approx(truth.pressure_mpa, abs=1e-6)
            kgf = 9.80665
            assert r.force_n == pytest.approx(truth.force_n, abs=0.01 * kgf / 2 + 1e-9)
            assert r.sample_id == truth.sample_id % 65536
        assert srv.rig.vented and srv.rig.command_mpa == 0.0


def test_rtu_loop_frozen_sensor_trips_and_vents(bridge: PtyBridge) -> None:
    with RtuSimServer(bridge.server_path, freeze_after_s=1.0) as srv, \
            open_device(_url(bridge)) as dev:
        with pytest.raises(LoopFault, match="watchdog.*sensor unchanged") as ei:
            run_loop(dev, Controller(PIDGains(0.002, 0.004)), 54.4, duration_s=5.0,
                     rate_hz=50.0, watchdog_s=0.3)
        assert ei.value.result.vented and srv.rig.vented and srv.rig.command_mpa == 0.0
        assert 1.0 <= ei.value.time_s < 2.5
