"""Hardware: devices (sim, Modbus, serial), simulated test rigs and the real-time control loop.

* :func:`open_device` -- a :class:`Device` from a URL: ``sim://?speed=1``,
  ``modbus-tcp://HOST:PORT?unit=1``, ``modbus-rtu:///dev/ttyX?baud=115200&unit=1``,
  ``serial:///dev/ttyX?baud=115200``; :class:`Reading` is one sample (MPa, N).
* :func:`load_register_map`, :class:`RegisterMap`, :class:`RegisterSpec`,
  :func:`encode_registers`, :func:`decode_registers` -- the Modbus register map (TOML; the
  shipped default is :data:`DEFAULT_MAP_PATH`).
* :func:`run_loop` -- fixed-rate, deadline-scheduled control loop with limits
  (:class:`SafetyLimits`), a watchdog, venting on faults and Ctrl-C (retried on a fresh
  connection), a rig-log CSV and honest timing (achieved rate; a warning above 1 % skipped or
  overrun cycles); returns a :class:`LoopResult`. :class:`RealClock`, :class:`SimClock` are
  its clocks.
* :class:`SimulatedDevice`, :class:`ModbusSimServer`, :class:`SerialSimDevice`,
  :class:`SimRig` -- simulated rigs backed by a pressure plant and a friction map, with
  fault injection (stale, silent, nan, range, junk, drop, mute; ``sim://?fault=nan@2.0``).
* Errors: :class:`DeviceError` (an InputError: exit 2 when the device is opened),
  :class:`SensorStale` (counted by the watchdog), :class:`DeviceFault` (connection lost,
  junk, out of range: in the loop it stops the run at once), :class:`LoopFault` (watchdog,
  limit or device fault, after venting).

Exit codes of ``exofric control run`` (defined in :data:`exofric.errors.EXIT_CODES`):

* 0 -- the run completed and the device confirmed the vent;
* 2 -- bad input found before the loop starts: bad option, URL or register map, an
  unreachable device, a refused handshake, a set-point above the limits;
* 3 -- (not used by ``control run``) a solver did not converge;
* 4 -- a run-time fault stopped the run and the tube was vented: watchdog (silent or frozen
  sensor, NaN readings), pressure or force limit, device fault (connection dropped, junk or
  out-of-range values, a refused write); one line on stderr names the fault and the time in s
  since the start; the log keeps every sample up to it;
* 5 -- the vent could not be confirmed, even on a fresh connection: the tube may still be
  pressurised (close the supply by hand); one loud line on stderr;
* 130 -- Ctrl-C: vented (5 instead when the vent was not confirmed), log written.

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

from exofric._lazy import lazy_package

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.hardware._clock import Clock, RealClock, SimClock
    from exofric.hardware._device import (
        Device,
        DeviceError,
        DeviceFault,
        DeviceURL,
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
# The TYPE_CHECKING imports above are the one list of public names: __all__ and the facade
# are derived from them (exofric._lazy.lazy_package).
__getattr__, __dir__, __all__ = lazy_package(__name__, __file__)
