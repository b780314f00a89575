"""The Device protocol, its errors, device URLs and :func:`open_device`.

A *device* is whatever sits between the control loop and the rig: it reads the tube pressure
(MPa, gauge) and the friction force (N), takes a pressure set-point (MPa) for the regulator
and can vent (open the tube to exhaust). Backends are chosen by URL:

* ``sim://?speed=1`` -- the simulated plant in process (``speed`` x real time; 0 = as fast as
  possible on a simulated clock; ``fault=KIND@T`` injects a fault T s after the start, see
  :class:`~exofric.hardware.SimRig`);
* ``modbus-tcp://HOST:PORT?unit=1`` and ``modbus-rtu:///dev/ttyX?baud=115200&unit=1`` --
  pymodbus (sync client) with a register map TOML (see :func:`load_register_map`);
* ``serial:///dev/ttyX?baud=115200`` -- pyserial, the exofric line protocol
  (``examples/serial-protocol.md``).

Errors: :class:`DeviceError` (an :class:`~exofric.errors.InputError`: the CLI exits 2) for a
device that cannot be reached or does not match its map when it is opened;
:class:`SensorStale` (a DeviceError) when a read times out or the device says its sensor is
stale -- the control loop's watchdog counts these and stops with a :class:`LoopFault` after
``watchdog_s``; :class:`DeviceFault` (a DeviceError) for what a retry will not cure: the
connection or port is gone, an answer that cannot be parsed, a value outside the sensor's
declared range. Once the loop runs, every DeviceError other than SensorStale stops it at once:
vent (retried on a fresh connection, :meth:`reconnect`), :class:`LoopFault` ``'device fault'``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable
from urllib.parse import parse_qs, urlsplit

from exofric import defaults as D
from exofric._validate import checked_init
from exofric.errors import InputError

if TYPE_CHECKING:
    from exofric.control import PressurePlant

__all__ = [
    "DEFAULT_CONNECT_TIMEOUT_S", "DEFAULT_IO_TIMEOUT_S", "Device", "DeviceError", "DeviceFault",
    "DeviceURL", "LoopFault", "Reading", "SensorStale", "VENT_NOT_CONFIRMED",
    "default_friction_map", "open_device", "parse_url",
]

#: Connect timeout in s for Modbus TCP (an unreachable host fails after this).
DEFAULT_CONNECT_TIMEOUT_S = D.DEVICE_CONNECT_TIMEOUT_S
#: Per-request read/write timeout in s (Modbus and serial; ``?timeout=`` in the URL).
DEFAULT_IO_TIMEOUT_S = D.DEVICE_IO_TIMEOUT_S
#: Default serial and Modbus RTU baud rate in bit/s.
DEFAULT_BAUD = D.DEVICE_BAUD

_SCHEMES = ("sim", "modbus-tcp", "modbus-rtu", "serial")


class DeviceError(InputError):
    """A device cannot be reached, does not answer as expected, or does not match its map.

    An :class:`~exofric.errors.InputError` (the CLI prints the one line and exits 2).

    Parameters
    ----------
    message : str
        One line naming the device URL (or map key) and what went wrong.
    param : str or None
        The parameter concerned (default ``"device"``).

    Examples
    --------
    >>> str(DeviceError("modbus-tcp://10.0.0.9:502: no answer within 2 s"))
    'modbus-tcp://10.0.0.9:502: no answer within 2 s'
    """

    def __init__(self, message: str, param: str | None = "device") -> None:
        super().__init__(message, param)


class SensorStale(DeviceError):
    """A read timed out, failed, or the device reports its sensor as stale.

    The control loop counts these toward its watchdog (``watchdog_s``); used outside the loop
    it is a :class:`DeviceError`.

    Parameters
    ----------
    message : str
        One line naming the device and the request that failed.

    Examples
    --------
    >>> isinstance(SensorStale("serial:///dev/ttyACM0: no answer to R in 0.25 s"), DeviceError)
    True
    """

    def __init__(self, message: str) -> None:
        super().__init__(message, "device")


class DeviceFault(DeviceError):
    """The device failed in a way a retry will not cure.

    The connection or the port is gone, an answer cannot be parsed (junk on the line), or a
    value lies outside the sensor's declared range. Raised while the device is opened it is a
    :class:`DeviceError` (exit 2); raised in the control loop it stops the run at once:
    vent, :class:`LoopFault` ``'device fault'`` (exit 4, or 5 when the vent is not confirmed).

    Parameters
    ----------
    message : str
        One line naming the device and what failed.

    Examples
    --------
    >>> isinstance(DeviceFault("modbus-tcp://10.0.0.9:502: connection lost"), DeviceError)
    True
    """

    def __init__(self, message: str) -> None:
        super().__init__(message, "device")


#: The end of a :class:`LoopFault` message when the vent was not confirmed.
VENT_NOT_CONFIRMED = ("NOT vented: vent not confirmed: the tube may still be pressurised; "
                      "close the supply by hand")


class LoopFault(RuntimeError):
    """The control loop stopped on a fault and vented the device.

    Reasons: ``'watchdog'`` (no valid or no new reading for ``watchdog_s``), ``'pressure
    limit'``, ``'force limit'``, ``'device fault'`` (a :class:`DeviceError` other than
    :class:`SensorStale` in the loop: connection lost, junk, a value out of the declared range).
    The CLI prints the one-line message (reason and time in s since the start) and exits 4
    (:attr:`exit_code`). The message ends in ``(vented)``, or, when ``result`` says the vent
    could not be confirmed (even on a fresh connection), in ``(NOT vented: vent not confirmed:
    the tube may still be pressurised; close the supply by hand)`` -- then the CLI exits 5.

    Parameters
    ----------
    reason : str
        ``'watchdog'``, ``'pressure limit'``, ``'force limit'`` or ``'device fault'``.
    time_s : float
        Time of the fault in s since the loop started.
    detail : str
        One line: what was seen.
    result : object or None
        The :class:`LoopResult` of the run up to the fault (log written, device vented).

    Examples
    --------
    >>> f = LoopFault("watchdog", 3.02, "sensor unchanged for 0.5 s")
    >>> str(f), f.time_s, f.exit_code
    ('watchdog at 3.020 s: sensor unchanged for 0.5 s (vented)', 3.02, 4)
    """

    def __init__(self, reason: str, time_s: float, detail: str, result: Any = None) -> None:
        vented = bool(getattr(result, "vented", True))
        how = "vented" if vented else VENT_NOT_CONFIRMED
        super().__init__(f"{reason} at {time_s:.3f} s: {detail} ({how})")
        self.reason = reason
        self.time_s = time_s
        self.detail = detail
        self.result = result

    @property
    def vent_confirmed(self) -> bool:
        """Whether the device confirmed the vent (True when there is no result)."""
        return bool(getattr(self.result, "vented", True))

    @property
    def exit_code(self) -> int:
        """The CLI's exit code: 4 (vented) or 5 (vent not confirmed); see exofric.errors."""
        from exofric.errors import EXIT_FAULT, EXIT_VENT_NOT_CONFIRMED

        return EXIT_FAULT if self.vent_confirmed else EXIT_VENT_NOT_CONFIRMED


@checked_init
@dataclass(frozen=True)
class Reading:
    """One sample of the rig's sensors.

    Attributes
    ----------
    pressure_mpa : float
        Tube pressure in MPa (gauge).
    force_n : float
        Friction (load cell) force in N.
    sample_id : int or None
        The device's sample counter or timestamp (serial: its ``t_ms``; Modbus: the
        ``heartbeat`` register); it changes with every new sensor sample. None when the device
        has none (then the watchdog looks at the values themselves).

    Examples
    --------
    >>> Reading(0.25, 40.1, 1200).pressure_mpa
    0.25
    """

    pressure_mpa: float
    force_n: float
    sample_id: int | None = None


@runtime_checkable
class Device(Protocol):
    """What the control loop needs from a rig (all backends satisfy it).

    Units: pressure MPa (gauge), force N. A context manager: leaving the ``with`` block
    vents and closes. Optional, used by the loop where present (the backends have both):
    ``reconnect()`` -- drop the connection and open a fresh one (the vent's retry after a
    fault); ``describe()`` -- a short line naming the URL and what is behind it.

    Examples
    --------
    >>> with open_device("sim://?speed=0") as dev:
    ...     dev.write_setpoint_mpa(0.3)
    ...     r = dev.read()
    ...     isinstance(dev, Device), r.pressure_mpa >= 0.0
    (True, True)
    """

    url: str

    def read(self) -> Reading:
        """One sample of pressure (MPa) and force (N); SensorStale on a timeout."""

    def read_pressure_mpa(self) -> float:
        """Tube pressure in MPa (gauge)."""

    def read_force_n(self) -> float:
        """Friction force in N."""

    def write_setpoint_mpa(self, pressure_mpa: float) -> None:
        """Send a pressure set-point in MPa to the regulator.

        Parameters
        ----------
        pressure_mpa : float
            Set-point in MPa (gauge, >= 0).
        """

    def vent(self) -> None:
        """Open the tube to exhaust (set-point 0 and the vent valve, where there is one)."""

    def close(self) -> None:
        """Release the connection (does not vent by itself; ``with`` does)."""

    def __enter__(self) -> Device: ...

    def __exit__(self, et: type[BaseException] | None, ev: BaseException | None,
                 tb: TracebackType | None) -> None: ...


class DeviceBase:
    """Shared parts of the backends: the convenience reads and the context manager."""

    url: str = ""

    def read(self) -> Reading:  # pragma: no cover - overridden
        raise NotImplementedError

    def write_setpoint_mpa(self, pressure_mpa: float) -> None:  # pragma: no cover
        raise NotImplementedError

    def vent(self) -> None:  # pragma: no cover - overridden
        raise NotImplementedError

    def close(self) -> None:  # pragma: no cover - overridden
        raise NotImplementedError

    def reconnect(self) -> None:
        """Open a fresh connection (default: nothing to do)."""

    def describe(self) -> str:
        """The URL (backends add what is behind it)."""
        return self.url

    def read_pressure_mpa(self) -> float:
        """Tube pressure in MPa (one :meth:`read`)."""
        return self.read().pressure_mpa

    def read_force_n(self) -> float:
        """Friction force in N (one :meth:`read`)."""
        return self.read().force_n

    def _check_setpoint(self, pressure_mpa: float) -> float:
        p = float(pressure_mpa)
        if not (math.isfinite(p) and p >= 0.0):
            raise InputError(f"pressure set-point must be a finite number >= 0 MPa, got {p}")
        return p

    def __enter__(self) -> DeviceBase:
        return self

    def __exit__(self, et: type[BaseException] | None, ev: BaseException | None,
                 tb: TracebackType | None) -> None:
        try:
            self.vent()
        except Exception:  # noqa: BLE001 - already failing or gone: closing matters more
            if et is None:
                raise
        finally:
            self.close()


@checked_init
@dataclass(frozen=True)
class DeviceURL:
    """A parsed device URL.

    Attributes
    ----------
    scheme : str
        ``sim``, ``modbus-tcp``, ``modbus-rtu`` or ``serial``.
    host : str
        Host name or address (modbus-tcp), else empty.
    port : int or None
        TCP port (modbus-tcp; default 502).
    path : str
        Serial port path (modbus-rtu, serial), else empty.
    query : dict of str to str
        The query parameters (``speed``, ``unit``, ``baud``, ``timeout`` in s).
    text : str
        The URL as given.

    Examples
    --------
    >>> u = parse_url("modbus-tcp://127.0.0.1:5020?unit=3")
    >>> u.scheme, u.host, u.port, u.query["unit"]
    ('modbus-tcp', '127.0.0.1', 5020, '3')
    """

    scheme: str
    host: str
    port: int | None
    path: str
    query: dict[str, str]
    text: str

    def number(self, key: str, default: float, lo: float, hi: float, unit: str = "") -> float:
        """A numeric query parameter within [lo, hi] (DeviceError naming it otherwise).

        Parameters
        ----------
        key : str
            The query key (``speed``, ``baud``, ``timeout``...).
        default : float
            Value when absent (in ``unit``).
        lo, hi : float
            Allowed range (in ``unit``).
        unit : str
            Unit for the message (``s``, ``bit/s``...).

        Returns
        -------
        float

        Examples
        --------
        >>> parse_url("sim://?speed=4").number("speed", 1.0, 0.0, 1e3)
        4.0
        """
        raw = self.query.get(key)
        if raw is None:
            return default
        try:
            v = float(raw)
        except ValueError:
            v = math.nan
        if not (math.isfinite(v) and lo <= v <= hi):
            u = f" {unit}" if unit else ""
            raise DeviceError(f"{self.text}: {key} must be a number in [{lo:g}, {hi:g}]{u}, "
                              f"got {raw!r}")
        return v


_KEYS = {"sim": {"speed", "fault"}, "modbus-tcp": {"unit", "timeout"},
         "modbus-rtu": {"unit", "baud", "timeout", "parity", "stopbits"},
         "serial": {"baud", "timeout"}}


def parse_url(url: str) -> DeviceURL:
    """Parse and check a device URL (scheme, host/port or path, known query keys).

    Parameters
    ----------
    url : str
        ``sim://?speed=1``, ``modbus-tcp://HOST:PORT?unit=1``,
        ``modbus-rtu:///dev/ttyX?baud=115200&unit=1`` or ``serial:///dev/ttyX?baud=115200``.

    Returns
    -------
    DeviceURL

    Raises
    ------
    DeviceError
        One line naming the URL: unknown scheme, missing host or path, unknown or repeated
        query key.

    Examples
    --------
    >>> parse_url("serial:///dev/ttyACM0?baud=115200").path
    '/dev/ttyACM0'
    """
    text = str(url).strip()
    try:
        parts = urlsplit(text)
        port = parts.port
    except ValueError as exc:
        raise DeviceError(f"{text}: malformed device URL ({exc})") from None
    scheme = parts.scheme.lower()
    if scheme not in _SCHEMES:
        raise DeviceError(f"{text}: unknown device scheme {parts.scheme or '(none)'!r} (known: "
                          "sim://, modbus-tcp://HOST:PORT, modbus-rtu:///dev/ttyX, "
                          "serial:///dev/ttyX)")
    q = parse_qs(parts.query, keep_blank_values=True)
    query: dict[str, str] = {}
    for k, v in q.items():
        if k not in _KEYS[scheme]:
            raise DeviceError(f"{text}: unknown query key {k!r} for {scheme}:// (known: "
                              f"{', '.join(sorted(_KEYS[scheme]))})")
        if len(v) > 1:
            raise DeviceError(f"{text}: query key {k!r} is given {len(v)} times")
        query[k] = v[0]
    host = parts.hostname or ""
    path = parts.path
    if scheme == "modbus-tcp":
        if not host:
            raise DeviceError(f"{text}: modbus-tcp:// needs a host (modbus-tcp://HOST:PORT)")
        port = 502 if port is None else port
    elif scheme in ("modbus-rtu", "serial"):
        if parts.netloc:   # serial://COM3 (Windows): the port was read as a host
            path = parts.netloc + path
        if not path or path == "/":
            raise DeviceError(f"{text}: {scheme}:// needs a port path ({scheme}:///dev/ttyX)")
    return DeviceURL(scheme, host, port, path, query, text)


def default_friction_map() -> Any:
    """The paper's friction map: Eq 9 = gamma 0.7168 x the Eq 8 cubic N(P) (N vs MPa).

    Returns
    -------
    exofric.control.CubicFrictionMap

    Examples
    --------
    >>> round(default_friction_map().inverse(54.4), 4)     # MPa for the paper's 54.4 N target
    0.2926
    """
    from exofric import paper
    from exofric.control import CubicFrictionMap
    from exofric.friction import CubicFit

    return CubicFrictionMap(CubicFit(paper.eq8(), *paper.load()["eq8"]["fit_range_mpa"]),
                            paper.scalar("gamma"))


def _sim_fault(u: DeviceURL) -> tuple[str, float | None]:
    """``sim://?fault=KIND@T`` -> (KIND, T in s); ('stale', None) without ``fault``."""
    from exofric.hardware._sim import FAULTS

    raw = u.query.get("fault")
    if raw is None:
        return "stale", None
    kind, _, at = raw.partition("@")
    try:
        t = float(at) if at else 0.0
    except ValueError:
        t = math.nan
    if kind not in FAULTS or not (math.isfinite(t) and 0.0 <= t <= 1e6):
        raise DeviceError(f"{u.text}: fault must be KIND@T with KIND one of {', '.join(FAULTS)}"
                          f" and T in [0, 1e6] s (e.g. fault=nan@2.0), got {raw!r}")
    return kind, t


def open_device(
    url: str,
    map_path: str | Path | None = None,
    *,
    plant: PressurePlant | Any | None = None,
    friction: Any | None = None,
) -> Any:
    """Open the device a URL names (see the module docstring for the schemes).

    Parameters
    ----------
    url : str
        Device URL: ``sim://?speed=1`` (``&fault=nan@2.0``: inject a fault, see
        :class:`~exofric.hardware.SimRig`), ``modbus-tcp://HOST:PORT?unit=1&timeout=0.25``,
        ``modbus-rtu:///dev/ttyX?baud=115200&unit=1``, ``serial:///dev/ttyX?baud=115200``
        (``timeout`` in s per request).
    map_path : str, Path or None
        Register map TOML for Modbus (default: the shipped ``modbus-default.toml``); refused
        for the other schemes.
    plant : object or None
        ``sim://`` only: the pressure plant (``pressure_mpa``, ``advance(command_mpa, dt)``);
        default ``PressurePlant(PlantParams())``.
    friction : callable or None
        ``sim://`` only: friction map F(P), MPa -> N; default :func:`default_friction_map`.

    Returns
    -------
    Device
        Connected and checked (Modbus: one read of every signal; serial: the handshake).

    Raises
    ------
    DeviceError
        Bad URL, unreachable device (within about 2 s), a map that does not match the device.

    Examples
    --------
    >>> dev = open_device("sim://?speed=0")
    >>> dev.url, dev.read().force_n
    ('sim://?speed=0', 0.0)
    >>> dev.close()
    """
    u = parse_url(url)
    if map_path is not None and not u.scheme.startswith("modbus"):
        raise DeviceError(f"{u.text}: a register map is for modbus-tcp:// and modbus-rtu:// "
                          "devices only", "map_path")
    if u.scheme != "sim" and (plant is not None or friction is not None):
        raise DeviceError(f"{u.text}: plant and friction are for sim:// only")
    if u.scheme == "sim":
        from exofric.hardware._sim import SimulatedDevice

        kind, at_s = _sim_fault(u)
        return SimulatedDevice(plant=plant, friction=friction,
                               speed=u.number("speed", 1.0, 0.0, 1e4), url=u.text,
                               freeze_after_s=at_s, fault=kind)
    if u.scheme.startswith("modbus"):
        from exofric.hardware._modbus import ModbusDevice, load_register_map

        return ModbusDevice(u, load_register_map(map_path))
    from exofric.hardware._serial import SerialDevice

    return SerialDevice(u)
