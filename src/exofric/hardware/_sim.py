"""Simulated rigs: in process (``sim://``), a Modbus TCP server and a serial pty device.

All three are backed by a :class:`SimRig`: a pressure plant (``pressure_mpa``,
``advance(command_mpa, dt)``; default :class:`exofric.control.PneumaticPlant`) followed by a
friction map F(P) (default: the paper's Eq 9), advanced to the current time whenever the
sensors are read or a set-point is written. Fault injection (:data:`FAULTS`): ``fault`` starts
``freeze_after_s`` seconds after the rig was made --

* ``stale`` -- the sensor freezes: the last sample again (same values, same counter);
* ``silent`` -- reads get no answer (Modbus TCP: an exception reply; writes still work);
* ``nan`` -- the load cell reads NaN (a live counter: the sensor updates but has no value);
* ``range`` -- the pressure sensor rails at :data:`RAIL_MPA` (3.2767 MPa, int16 full scale of
  0.1 kPa counts): outside the shipped map's declared range, above any trip pressure;
* ``junk`` -- answers that cannot be parsed (serial: a garbage line; Modbus: registers of
  0xDEAD, outside the declared range; ``sim://``: a :class:`DeviceFault`);
* ``drop`` -- the connection drops once (Modbus TCP: the server closes it and accepts a new
  one; serial: the pty goes away for good; ``sim://``: a DeviceFault, then reconnects);
* ``mute`` -- the device dies: no answer to anything, the vent included (Modbus TCP: requests
  are never answered; serial: no line at all; ``sim://``: reads, vents and reconnects fail).
"""

from __future__ import annotations

import asyncio
import math
import os
import select
import threading
import time
import tty
from typing import Any

from exofric.hardware._clock import RealClock, SimClock
from exofric.hardware._device import (
    DeviceBase,
    DeviceFault,
    Reading,
    SensorStale,
    default_friction_map,
)
from exofric.hardware._modbus import RegisterMap, decode_registers, encode_registers
from exofric.hardware._modbus import load_register_map as _load_map
from exofric.hardware._serial import PROTOCOL_VERSION

__all__ = ["FAULTS", "RAIL_MPA", "ModbusSimServer", "SerialSimDevice", "SimRig",
           "SimulatedDevice"]

#: The injectable faults (see the module docstring).
FAULTS = ("stale", "silent", "nan", "range", "junk", "drop", "mute")
#: Pressure in MPa the ``range`` fault reads (an int16 of 0.1 kPa counts at full scale).
RAIL_MPA = 3.2767


class SimRig:
    """A simulated rig: plant + friction map, advanced in time, thread-safe, with faults.

    Parameters
    ----------
    plant : object or None
        ``pressure_mpa`` attribute and ``advance(command_mpa, dt)``; default
        ``PneumaticPlant(PneumaticParams())`` (a proportional regulator on a 0.6 MPa supply,
        1 m of 4 mm hose and the base tube; see :mod:`exofric.control`).
    friction : callable or None
        F(P): MPa -> N; default the paper's Eq 9 map.
    clock : Clock or None
        Time source (default real time).
    freeze_after_s : float or None
        The fault starts this many seconds (on ``clock``) after the rig was made.
    fault : str
        One of :data:`FAULTS` (see the module docstring); default ``'stale'``.

    Examples
    --------
    >>> rig = SimRig(clock=SimClock())
    >>> rig.set_command(0.3); rig.clock.advance(5.0); r = rig.sample()
    >>> round(r.pressure_mpa, 3), r.sample_id
    (0.3, 1)
    """

    def __init__(self, plant: Any | None = None, friction: Any | None = None, *,
                 clock: Any | None = None, freeze_after_s: float | None = None,
                 fault: str = "stale") -> None:
        if plant is None:        # the physical plant: regulator, hose and tube (ISO 6358)
            from exofric.control import PneumaticParams, PneumaticPlant

            plant = PneumaticPlant(PneumaticParams())
        if fault not in FAULTS:
            raise ValueError(f"fault must be one of {', '.join(FAULTS)}, got {fault!r}")
        self.plant = plant
        self.friction = friction if friction is not None else default_friction_map()
        self.clock = clock if clock is not None else RealClock()
        self.freeze_after_s = freeze_after_s
        self.fault = fault
        self.lock = threading.RLock()
        self.command_mpa = 0.0
        self.vented = True
        self.setpoints: list[float] = []
        self.vents = 0
        self._t0 = self.clock.now()
        self._t = self._t0
        self._count = 0
        self._last: Reading | None = None
        self._sample_t = self._t0

    @property
    def time_s(self) -> float:
        """Rig time in s since it was made."""
        return self._t - self._t0

    def _advance(self) -> None:
        t = self.clock.now()
        dt = t - self._t
        if dt > 1e-9:
            self.plant.advance(self.command_mpa, dt)
            self._t = t

    @property
    def sample_time_s(self) -> float:
        """Rig time in s of the newest sensor sample (a frozen sensor's stays put)."""
        return self._sample_t - self._t0

    @property
    def frozen(self) -> bool:
        """True once the injected fault is active."""
        f = self.freeze_after_s
        return f is not None and self.clock.now() - self._t0 >= f

    def sample(self) -> Reading | None:
        """The sensors now: pressure (MPa), force (N), sample counter; None when silent."""
        with self.lock:
            self._advance()
            faulty = self.frozen and self._last is not None
            if faulty and self.fault in ("stale", "silent", "mute"):
                return None if self.fault != "stale" else self._last
            p = float(self.plant.pressure_mpa)
            self._count += 1
            self._sample_t = self._t
            self._last = Reading(p, float(self.friction(p)), self._count)
            if faulty and self.fault == "nan":
                return Reading(p, math.nan, self._count)
            if faulty and self.fault == "range":
                return Reading(RAIL_MPA, self._last.force_n, self._count)
            return self._last

    def set_command(self, pressure_mpa: float) -> None:
        """Regulator set-point in MPa (from now on; leaves the vented state).

        Parameters
        ----------
        pressure_mpa : float
            Set-point in MPa.
        """
        with self.lock:
            self._advance()
            self.command_mpa = float(pressure_mpa)
            self.vented = False
            self.setpoints.append(self.command_mpa)

    def vent(self) -> None:
        """Set-point 0 and the vented state (counted in :attr:`vents`)."""
        with self.lock:
            self._advance()
            self.command_mpa = 0.0
            self.vented = True
            self.vents += 1


class SimulatedDevice(DeviceBase):
    """The in-process simulated device of ``sim://?speed=S``.

    Parameters
    ----------
    plant, friction : object or None
        Pressure plant (MPa) and friction map F(P) (MPa -> N); see :class:`SimRig`.
    speed : float
        Simulated seconds per real second (0: as fast as possible, on a :class:`SimClock`
        that the control loop advances).
    url : str
        The URL it was opened with.
    freeze_after_s : float or None
        The injected fault starts after this many simulated seconds (see :class:`SimRig`).
    fault : str
        The fault's kind, one of :data:`FAULTS` (``sim://?fault=KIND@T``).

    Examples
    --------
    >>> dev = SimulatedDevice(speed=0)
    >>> dev.write_setpoint_mpa(0.3); dev.clock.advance(10.0)
    >>> round(dev.read().force_n, 1)
    57.9
    """

    def __init__(self, plant: Any | None = None, friction: Any | None = None, *,
                 speed: float = 1.0, url: str = "sim://", freeze_after_s: float | None = None,
                 fault: str = "stale") -> None:
        self.url = url
        self.clock: Any = SimClock() if speed == 0 else RealClock(speed)
        self.rig = SimRig(plant, friction, clock=self.clock, freeze_after_s=freeze_after_s,
                          fault=fault)
        self._dropped = False

    def _dead(self) -> bool:
        return self.rig.frozen and self.rig.fault == "mute"

    def read(self) -> Reading:
        """Pressure (MPa) and force (N) now; SensorStale or DeviceFault when a fault is on."""
        rig = self.rig
        if rig.frozen and rig.fault in ("junk", "drop") and not self._dropped:
            self._dropped = rig.fault == "drop"
            raise DeviceFault(f"{self.url}: " + ("connection lost (injected)"
                                                  if rig.fault == "drop" else
                                                  "unparseable answer (injected junk)"))
        r = rig.sample()
        if r is None:
            raise SensorStale(f"{self.url}: no answer (injected {rig.fault} sensor)")
        return r

    def write_setpoint_mpa(self, pressure_mpa: float) -> None:
        """Set-point in MPa to the simulated regulator.

        Parameters
        ----------
        pressure_mpa : float
            Set-point in MPa (>= 0).
        """
        p = self._check_setpoint(pressure_mpa)
        if self._dead():
            raise SensorStale(f"{self.url}: no answer to the set-point (injected dead device)")
        self.rig.set_command(p)

    def vent(self) -> None:
        """Vent the simulated tube (DeviceFault when the injected ``mute`` fault is on)."""
        if self._dead():
            raise DeviceFault(f"{self.url}: no answer to the vent (injected dead device)")
        self.rig.vent()

    def reconnect(self) -> None:
        """Nothing to reopen (DeviceFault when the injected ``mute`` fault is on)."""
        if self._dead():
            raise DeviceFault(f"{self.url}: reconnect refused (injected dead device)")

    def describe(self) -> str:
        """The URL and the plant behind it."""
        return f"{self.url} ({_plant_text(self.rig.plant)})"

    def close(self) -> None:
        """Nothing to release."""


def _plant_text(plant: Any) -> str:
    """A short description of a simulated plant."""
    p = getattr(plant, "params", None)
    name = type(plant).__name__
    if name == "PneumaticPlant" and p is not None:
        return (f"physical pneumatic plant: {p.valve} on a {p.supply_mpa:g} MPa supply, "
                f"{p.line_volume_mm3 + p.tube_volume_mm3:.0f} mm^3 line and tube")
    if name == "PressurePlant" and p is not None:
        return (f"first-order plant: tau {p.time_constant_s:g} s, dead time {p.delay_s:g} s, "
                f"p_max {p.p_max_mpa:g} MPa")
    return f"simulated plant {name}"


#: Modbus function codes that write (their read-back of the new values is not a sensor read).
_WRITE_CODES = frozenset({5, 6, 15, 16, 22, 23})


def _table_of(func_code: int) -> str:
    return "input" if func_code == 4 else "holding"


class ModbusSimServer:
    """pymodbus's own async Modbus TCP server on 127.0.0.1, backed by a :class:`SimRig`.

    Serves the register map (default: the shipped one) from a background thread; the rig
    advances in real time between requests. Writing the set-point register commands the
    plant; writing ``vent_value`` to the vent register vents it.

    Parameters
    ----------
    register_map : RegisterMap or None
        The map to serve (default :func:`load_register_map`).
    plant, friction : object or None
        Pressure plant (MPa) and friction map F(P) (MPa -> N); see :class:`SimRig`.
    port : int
        TCP port (0: a free one; see :attr:`port`).
    unit : int
        Modbus unit (device) id served.
    freeze_after_s : float or None
        The injected fault starts after this many seconds of serving (see :class:`SimRig`).
    fault : str
        One of :data:`FAULTS`: ``stale`` registers, ``silent`` (an exception reply to reads:
        gateway target failed to respond), ``nan`` (float32 force NaN), ``range`` (pressure
        at :data:`RAIL_MPA`), ``junk`` (0xDEAD in every register read), ``drop`` (the server
        closes the connection once), ``mute`` (no request is answered any more).

    Examples
    --------
    >>> with ModbusSimServer() as srv:
    ...     srv.url.startswith("modbus-tcp://127.0.0.1:")
    True
    """

    def __init__(self, register_map: RegisterMap | None = None, *, plant: Any | None = None,
                 friction: Any | None = None, port: int = 0, unit: int = 1,
                 freeze_after_s: float | None = None, fault: str = "stale") -> None:
        self.map = register_map if register_map is not None else _load_map()
        self.unit = unit
        self.rig = SimRig(plant, friction, freeze_after_s=freeze_after_s, fault=fault)
        self.port = port
        self.requests = 0
        self._dropped = False
        self._server: Any = None
        self._ready = threading.Event()
        self._error: BaseException | None = None
        self._loop: asyncio.AbstractEventLoop | None = None
        self._stop: asyncio.Event | None = None
        self._thread = threading.Thread(target=self._serve, name="ModbusSimServer", daemon=True)
        self._thread.start()
        if not self._ready.wait(10.0) or self._error is not None:
            raise RuntimeError(f"the Modbus test server did not start: {self._error}")

    @property
    def url(self) -> str:
        """``modbus-tcp://127.0.0.1:PORT?unit=U``."""
        return f"modbus-tcp://127.0.0.1:{self.port}?unit={self.unit}"

    def _device(self) -> Any:
        from pymodbus.simulator import DataType, SimData, SimDevice

        blocks: dict[str, list[Any]] = {"input": [], "holding": []}
        for table in blocks:
            specs = [s for s in self.map.signals.values() if s.table == table]
            if specs:
                lo = min(s.address for s in specs)
                hi = max(s.address + s.count for s in specs)
                blocks[table] = [SimData(lo, count=hi - lo, values=0,
                                         datatype=DataType.REGISTERS)]
            else:   # pymodbus needs a block per table: one register far away
                blocks[table] = [SimData(65535, values=0, datatype=DataType.REGISTERS)]
        bits = [SimData(0, values=[False] * 16, datatype=DataType.BITS)]
        return SimDevice(self.unit, simdata=(bits, list(bits), blocks["holding"],
                                             blocks["input"]), action=self._action)

    async def _action(self, func_code: int, start: int, address: int, count: int,
                      registers: list[int], set_values: Any) -> Any:
        from pymodbus.constants import ExcCodes

        self.requests += 1
        table = _table_of(func_code)
        sig = self.map.signals
        rig = self.rig
        if rig.frozen and rig.fault == "mute" and self._stop is not None:
            await self._stop.wait()         # a dead device: never answered, nothing applied
            return ExcCodes.DEVICE_FAILURE
        if rig.frozen and rig.fault == "drop" and not self._dropped and self._server:
            self._dropped = True            # the connection drops once; new ones are served
            for conn in list(self._server.active_connections.values()):
                conn.close()
            return None
        if set_values is not None and len(set_values):
            regs = list(registers)
            off = address - start
            regs[off:off + len(set_values)] = [int(v) for v in set_values]

            def value(name: str, raw: bool = False) -> float:
                s = sig[name]
                return decode_registers(s, regs[s.address - start:s.address - start + s.count],
                                        raw=raw)

            touched = range(address, address + len(set_values))
            v, s = sig["vent"], sig["setpoint"]
            if v.table == table and any(a in touched for a in range(v.address,
                                                                     v.address + v.count)):
                if int(value("vent", raw=True)) == v.vent_value:
                    rig.vent()
            if s.table == table and any(a in touched for a in range(s.address,
                                                                     s.address + s.count)):
                vented = (v.table == table
                          and int(value("vent", raw=True)) == v.vent_value)
                p = value("setpoint")
                if vented:
                    rig.vent()
                else:
                    rig.set_command(max(p, 0.0))
            return None
        if func_code in _WRITE_CODES:       # pymodbus reads back what a write set: no sample
            return None
        reading = rig.sample()
        if reading is None:
            return ExcCodes.GATEWAY_NO_RESPONSE
        junk = rig.frozen and rig.fault == "junk"
        for name, val in (("pressure", reading.pressure_mpa), ("force", reading.force_n),
                          ("heartbeat", reading.sample_id)):
            spec = sig.get(name)
            if spec is None or spec.table != table or val is None:
                continue
            s = spec
            off = s.address - start
            if junk:
                registers[off:off + s.count] = [0xDEAD] * s.count
            elif name == "heartbeat":
                registers[off:off + s.count] = encode_registers(s, int(val) % 65536, raw=True)
            else:
                registers[off:off + s.count] = encode_registers(s, float(val))
        return None

    def _serve(self) -> None:
        from pymodbus.server import ModbusTcpServer

        async def main() -> None:
            self._loop = asyncio.get_running_loop()
            self._stop = asyncio.Event()
            server = ModbusTcpServer(self._device(), address=("127.0.0.1", self.port))
            self._server = server
            await server.serve_forever(background=True)
            self.port = int(server.transport.sockets[0].getsockname()[1])  # type: ignore
            self._ready.set()
            await self._stop.wait()
            await server.shutdown()

        try:
            asyncio.run(main())
        except BaseException as exc:  # noqa: BLE001 - reported by __init__
            self._error = exc
            self._ready.set()

    def stop(self) -> None:
        """Stop the server and join its thread."""
        if self._loop is not None and self._stop is not None and self._thread.is_alive():
            self._loop.call_soon_threadsafe(self._stop.set)
            self._thread.join(5.0)

    def __enter__(self) -> ModbusSimServer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()


class SerialSimDevice:
    """A rig on a pseudo-terminal speaking the exofric line protocol, backed by a SimRig.

    ``os.openpty()``: a thread answers on the master side; :attr:`port` is the slave tty path
    to open as ``serial://<port>``. Implements ``?``, ``R``, ``S``, ``V`` and ``W`` (the device
    watchdog vents when no command arrives in time).

    Parameters
    ----------
    plant, friction : object or None
        Pressure plant (MPa) and friction map F(P) (MPa -> N); see :class:`SimRig`.
    freeze_after_s : float or None
        The injected fault starts after this many seconds (see :class:`SimRig`).
    fault : str
        One of :data:`FAULTS`: ``R`` answers the last sample again (``stale``), gets no answer
        (``silent``), ``nan`` for the force (``nan``), the pressure at :data:`RAIL_MPA`
        (``range``), a garbage line (``junk``); ``drop`` closes the pty (the port is gone);
        ``mute`` answers nothing at all.

    Examples
    --------
    >>> with SerialSimDevice() as sim:
    ...     sim.url.startswith("serial:///dev/")
    True
    """

    def __init__(self, plant: Any | None = None, friction: Any | None = None, *,
                 freeze_after_s: float | None = None, fault: str = "stale") -> None:
        self.rig = SimRig(plant, friction, freeze_after_s=freeze_after_s, fault=fault)
        self._master, self._slave = os.openpty()
        tty.setraw(self._slave)
        self.port = os.ttyname(self._slave)
        self.watchdog_ms = 0
        self.lines: list[str] = []
        self._last_cmd = time.monotonic()
        self._running = True
        self._thread = threading.Thread(target=self._serve, name="SerialSimDevice",
                                        daemon=True)
        self._thread.start()

    @property
    def url(self) -> str:
        """``serial://<slave tty path>``."""
        return f"serial://{self.port}"

    def _answer(self, line: str) -> str | None:
        words = line.split()
        if not words:
            return "ERR empty command"
        cmd, rig = words[0], self.rig
        if rig.frozen and rig.fault == "mute":
            return None
        if cmd == "R" and rig.frozen and rig.fault == "junk":
            return "D 12?4 0.2.9 #~!"
        if cmd == "?":
            from exofric import __version__

            return f"EXOFRIC-RIG {PROTOCOL_VERSION} exofric-sim {__version__}"
        if cmd == "R":
            r = rig.sample()
            if r is None:
                return None
            # t_ms of the sample itself: it must not move while the sensor is stale
            return (f"D {int(round(rig.sample_time_s * 1000.0))} {r.pressure_mpa:.6f} "
                    f"{r.force_n:.4f}")
        if cmd == "S" and len(words) == 2:
            try:
                p = float(words[1])
            except ValueError:
                return "ERR bad set-point"
            if not 0.0 <= p <= 10.0:
                return "ERR set-point out of range"
            rig.set_command(p)
            return "OK"
        if cmd == "V" and len(words) == 1:
            rig.vent()
            return "OK"
        if cmd == "W" and len(words) == 2:
            if not words[1].isdigit():
                return "ERR bad watchdog time"
            self.watchdog_ms = int(words[1])
            return "OK"
        return f"ERR unknown command {cmd!r}"

    def _serve(self) -> None:
        buf = b""
        while self._running:
            try:
                ready, _, _ = select.select([self._master], [], [], 0.02)
            except (OSError, ValueError):
                return
            now = time.monotonic()
            if (self.watchdog_ms and not self.rig.vented
                    and now - self._last_cmd > self.watchdog_ms / 1000.0):
                self.rig.vent()
            if self.rig.frozen and self.rig.fault == "drop":
                self._close_fds()           # unplugged: the port is gone for good
                return
            if not ready:
                continue
            try:
                chunk = os.read(self._master, 4096)
            except OSError:
                return
            if not chunk:
                return
            buf += chunk
            while b"\n" in buf:
                raw, buf = buf.split(b"\n", 1)
                line = raw.decode("ascii", "replace").strip()
                self.lines.append(line)
                self._last_cmd = time.monotonic()
                answer = self._answer(line)
                if answer is not None:
                    try:
                        os.write(self._master, answer.encode("ascii") + b"\n")
                    except OSError:
                        return

    def stop(self) -> None:
        """Stop answering and close the pty pair."""
        self._running = False
        self._thread.join(2.0)
        self._close_fds()

    def _close_fds(self) -> None:
        for fd in (self._master, self._slave):
            try:
                os.close(fd)
            except OSError:
                pass
        self._master = self._slave = -1

    def __enter__(self) -> SerialSimDevice:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()
