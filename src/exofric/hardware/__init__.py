"""Hardware: devices (sim, Modbus, serial), simulated test rigs and the real-time control loop.

* :func:`open_device` -- a :class:`Device` from a URL: ``sim://?speed=1``,
  ``modbus-tcp://HOST:PORT?unit=1``, ``modbus-rtu:///dev/ttyX?baud=115200&unit=1``,
  ``serial:///dev/ttyX?baud=115200``; :class:`Reading` is one sample (MPa, N).
* :func:`load_register_map`, :class:`RegisterMap`, :class:`RegisterSpec`,
  :func:`encode_registers`, :func:`decode_registers` -- the Modbus register map (TOML; the
  shipped default is :data:`DEFAULT_MAP_PATH`).
* :func:`run_loop` -- fixed-rate, deadline-scheduled control loop with limits
  (:class:`SafetyLimits`), a watchdog, venting on faults and Ctrl-C, and a rig-log CSV;
  returns a :class:`LoopResult`. :class:`RealClock`, :class:`SimClock` are its clocks.
* :class:`SimulatedDevice`, :class:`ModbusSimServer`, :class:`SerialSimDevice`,
  :class:`SimRig` -- simulated rigs backed by a pressure plant and a friction map, with
  sensor-fault injection (for tests and dry runs).
* Errors: :class:`DeviceError` (an InputError: exit 2), :class:`SensorStale`,
  :class:`LoopFault` (watchdog or limit: the CLI exits 4).

Units: pressure MPa (gauge), force N, time s (jitter in ms).

Examples
--------
>>> from exofric.hardware import open_device
>>> with open_device("sim://?speed=0") as dev:
...     dev.read().pressure_mpa
0.0
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from exofric._lazy import facade

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.hardware._clock import Clock, RealClock, SimClock
    from exofric.hardware._device import (
        Device,
        DeviceError,
        LoopFault,
        Reading,
        SensorStale,
        default_friction_map,
        open_device,
        parse_url,
    )
    from exofric.hardware._loop import LoopResult, SafetyLimits, run_loop
    from exofric.hardware._modbus import (
        DEFAULT_MAP_PATH,
        RegisterMap,
        RegisterSpec,
        decode_registers,
        encode_registers,
        load_register_map,
    )
    from exofric.hardware._serial import PROTOCOL_VERSION
    from exofric.hardware._sim import ModbusSimServer, SerialSimDevice, SimRig, SimulatedDevice

# Lazy facade (PEP 562): pymodbus and pyserial load only with the backend that needs them.
_MODULES: dict[str, tuple[str, ...]] = {
    "_clock": ("Clock", "RealClock", "SimClock"),
    "_device": ("Device", "DeviceError", "LoopFault", "Reading", "SensorStale",
                "default_friction_map", "open_device", "parse_url"),
    "_loop": ("LoopResult", "SafetyLimits", "run_loop"),
    "_modbus": ("DEFAULT_MAP_PATH", "RegisterMap", "RegisterSpec", "decode_registers",
                "encode_registers", "load_register_map"),
    "_serial": ("PROTOCOL_VERSION",),
    "_sim": ("ModbusSimServer", "SerialSimDevice", "SimRig", "SimulatedDevice"),
}
_HOME = {name: mod for mod, names in _MODULES.items() for name in names}

__all__ = [
    "Clock", "DEFAULT_MAP_PATH", "decode_registers", "default_friction_map", "Device",
    "DeviceError", "encode_registers", "load_register_map", "LoopFault", "LoopResult",
    "ModbusSimServer", "open_device", "parse_url", "PROTOCOL_VERSION", "Reading", "RealClock",
    "RegisterMap", "RegisterSpec", "run_loop", "SafetyLimits", "SensorStale",
    "SerialSimDevice", "SimClock", "SimRig", "SimulatedDevice",
]

__getattr__, __dir__ = facade(__name__, _HOME, __all__)
