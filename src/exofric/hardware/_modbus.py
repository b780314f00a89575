"""Modbus devices (TCP and RTU, pymodbus sync client) and their register map.

A register map (TOML) says where each signal lives and how its raw registers become physical
units. One table per signal: ``pressure``, ``force`` (read), ``setpoint``, ``vent`` (written)
and optionally ``heartbeat`` (a counter the device increments with every sensor sample; the
watchdog uses it to tell a frozen sensor from a steady one). Keys of a signal:

* ``table`` -- ``"input"`` (input registers, function 4; read-only) or ``"holding"`` (holding
  registers, functions 3/6/16); ``setpoint`` and ``vent`` must be holding registers;
* ``address`` -- 0-based register address (0..65535);
* ``type`` -- ``int16``, ``uint16``, ``int32``, ``uint32`` or ``float32`` (bytes big-endian
  within a register, the Modbus convention);
* ``word_order`` -- ``"big"`` (high word at the lower address, default) or ``"little"``;
* ``scale``, ``offset`` -- physical = raw x scale + offset, in ``unit`` (defaults 1, 0);
* ``unit`` -- the physical unit: a pressure unit (MPa, kPa, bar, psi...) for pressure and
  setpoint, a force unit (N, kgf, lbf...) for force; converted with pint;
* ``range`` -- ``[lo, hi]`` in ``unit``: the sensor's declared range (a reading outside it
  means the map does not match the device: :class:`DeviceError`) or the regulator's set-point
  range (set-points outside it are refused);
* vent only: ``vent_value`` (written to vent, default 1) and ``run_value`` (written before the
  first set-point after venting, default 0).

The shipped default map is ``exofric/hardware/data/modbus-default.toml``
(:data:`DEFAULT_MAP_PATH`).
"""

from __future__ import annotations

import functools
import logging
import math
import struct
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from exofric._validate import checked_init
from exofric.hardware._device import (
    DEFAULT_BAUD,
    DEFAULT_CONNECT_TIMEOUT_S,
    DEFAULT_IO_TIMEOUT_S,
    DeviceBase,
    DeviceError,
    DeviceFault,
    DeviceURL,
    Reading,
    SensorStale,
)

if TYPE_CHECKING:
    import pint

__all__ = ["DEFAULT_MAP_PATH", "ModbusDevice", "RegisterMap", "RegisterSpec", "decode_registers",
           "encode_registers", "load_register_map"]

#: The shipped, documented default register map.
DEFAULT_MAP_PATH = Path(__file__).parent / "data" / "modbus-default.toml"

# pymodbus logs connection failures at ERROR level; without a handler Python's last-resort
# handler would print them to stderr beside exofric's one-line error.
logging.getLogger("pymodbus").addHandler(logging.NullHandler())

#: type -> (struct code, registers)
_TYPES: dict[str, tuple[str, int]] = {
    "int16": ("h", 1), "uint16": ("H", 1), "int32": ("i", 2), "uint32": ("I", 2),
    "float32": ("f", 2),
}
_TABLES = ("input", "holding")
_SIGNALS = ("pressure", "force", "setpoint", "vent", "heartbeat")
_REQUIRED = ("pressure", "force", "setpoint", "vent")
#: signal -> its quantity in exofric's units (None: a plain number)
_QUANTITY: dict[str, str | None] = {"pressure": "MPa", "force": "N", "setpoint": "MPa",
                                    "vent": None, "heartbeat": None}
_KEYS = {"table", "address", "type", "word_order", "scale", "offset", "unit", "range"}
_VENT_KEYS = {"table", "address", "type", "word_order", "vent_value", "run_value"}
_HEART_KEYS = {"table", "address", "type", "word_order"}
#: Most registers one read request may ask for (Modbus spec).
_MAX_READ = 125


@checked_init
@dataclass(frozen=True)
class RegisterSpec:
    """Where one signal lives and how its registers map to physical units.

    Attributes
    ----------
    name : str
        ``pressure``, ``force``, ``setpoint``, ``vent`` or ``heartbeat``.
    table : str
        ``'input'`` or ``'holding'``.
    address : int
        0-based register address.
    type : str
        ``int16``, ``uint16``, ``int32``, ``uint32`` or ``float32``.
    word_order : str
        ``'big'`` (high word first) or ``'little'``.
    scale, offset : float
        physical = raw x scale + offset, in ``unit`` (scale unitless per raw count).
    unit : str
        Physical unit of the register (``kPa``, ``N``...).
    to_si : float
        Factor from ``unit`` to exofric's unit (MPa or N; 1 for plain numbers).
    range : tuple of float or None
        Declared range (lo, hi) in ``unit``.
    vent_value, run_value : int
        Raw values written to vent and to run (vent register only).

    Examples
    --------
    >>> s = RegisterSpec("pressure", "input", 0, "int16", unit="kPa", scale=0.1, to_si=0.001)
    >>> s.count, decode_registers(s, [2500])      # 2500 x 0.1 kPa = 0.25 MPa
    (1, 0.25)
    """

    name: str
    table: str
    address: int
    type: str
    word_order: str = "big"
    scale: float = 1.0
    offset: float = 0.0
    unit: str = ""
    to_si: float = 1.0
    range: tuple[float, float] | None = None
    vent_value: int = 1
    run_value: int = 0

    @property
    def count(self) -> int:
        """Number of 16-bit registers the signal occupies."""
        return _TYPES[self.type][1]

    def describe(self) -> str:
        """``'pressure (input register 0, int16)'`` for messages."""
        return f"{self.name} ({self.table} register {self.address}, {self.type})"


@checked_init
@dataclass(frozen=True)
class RegisterMap:
    """A checked register map: one :class:`RegisterSpec` per signal.

    Attributes
    ----------
    signals : dict of str to RegisterSpec
        ``pressure``, ``force``, ``setpoint``, ``vent`` and optionally ``heartbeat``.
    source : str
        The file it came from (for messages).
    description : str
        The map's ``description`` (free text).

    Examples
    --------
    >>> m = load_register_map()
    >>> sorted(m.signals)
    ['force', 'heartbeat', 'pressure', 'setpoint', 'vent']
    """

    signals: dict[str, RegisterSpec]
    source: str
    description: str = ""


@functools.cache
def _ureg() -> pint.UnitRegistry:
    import pint

    return pint.UnitRegistry()


def _factor(unit: str, quantity: str, where: str) -> float:
    """Factor from ``unit`` to ``quantity`` (``'MPa'`` or ``'N'``) with pint."""
    if unit == quantity:
        return 1.0
    import pint

    try:
        return float(_ureg().Quantity(1.0, unit).to(quantity).magnitude)
    except (pint.errors.PintError, AttributeError, TypeError, ValueError, AssertionError):
        what = "pressure (MPa, kPa, bar, psi...)" if quantity == "MPa" else "force (N, kgf, lbf...)"
        raise DeviceError(f"{where}: unit {unit!r} is not a {what} unit", "map_path") from None


def _spec(name: str, raw: Any, where: str) -> RegisterSpec:
    w = f"{where}: [{name}]"
    if not isinstance(raw, dict):
        raise DeviceError(f"{w} must be a table", "map_path")
    allowed = _VENT_KEYS if name == "vent" else _HEART_KEYS if name == "heartbeat" else _KEYS
    extra = sorted(set(raw) - allowed)
    if extra:
        raise DeviceError(f"{w}: unknown key(s) {', '.join(extra)} (known: "
                          f"{', '.join(sorted(allowed))})", "map_path")
    for key in ("table", "address", "type"):
        if key not in raw:
            raise DeviceError(f"{w}: missing key {key!r}", "map_path")
    table = raw["table"]
    if table not in _TABLES:
        raise DeviceError(f"{w}.table must be 'input' or 'holding', got {table!r}", "map_path")
    if name in ("setpoint", "vent") and table != "holding":
        raise DeviceError(f"{w}.table must be 'holding' (it is written), got {table!r}",
                          "map_path")
    addr = raw["address"]
    if isinstance(addr, bool) or not isinstance(addr, int) or not 0 <= addr <= 65535:
        raise DeviceError(f"{w}.address must be an integer in 0..65535, got {addr!r}",
                          "map_path")
    typ = raw["type"]
    if typ not in _TYPES:
        raise DeviceError(f"{w}.type must be one of {', '.join(_TYPES)}, got {typ!r}",
                          "map_path")
    if addr + _TYPES[typ][1] - 1 > 65535:
        raise DeviceError(f"{w}: {typ} at address {addr} runs past register 65535", "map_path")
    if name in ("vent", "heartbeat") and typ == "float32":
        raise DeviceError(f"{w}.type must be an integer type, got 'float32'", "map_path")
    order = raw.get("word_order", "big")
    if order not in ("big", "little"):
        raise DeviceError(f"{w}.word_order must be 'big' or 'little', got {order!r}",
                          "map_path")

    def num(key: str, default: float) -> float:
        v = raw.get(key, default)
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            raise DeviceError(f"{w}.{key} must be a finite number, got {v!r}", "map_path")
        return float(v)

    quantity = _QUANTITY[name]
    if quantity is None:
        ints = {}
        for key, default in (("vent_value", 1), ("run_value", 0)):
            v = raw.get(key, default)
            if isinstance(v, bool) or not isinstance(v, int):
                raise DeviceError(f"{w}.{key} must be an integer, got {v!r}", "map_path")
            ints[key] = v
        if ints["vent_value"] == ints["run_value"]:
            raise DeviceError(f"{w}: vent_value and run_value must differ", "map_path")
        spec = RegisterSpec(name, table, addr, typ, order, vent_value=ints["vent_value"],
                            run_value=ints["run_value"])
        for key in ("vent_value", "run_value"):
            if name == "vent":
                _int_raw(spec, getattr(spec, key), f"{w}.{key}")
        return spec
    scale = num("scale", 1.0)
    if scale == 0.0:
        raise DeviceError(f"{w}.scale must not be 0", "map_path")
    unit = raw.get("unit", quantity)
    if not isinstance(unit, str) or not unit.strip():
        raise DeviceError(f"{w}.unit must be a unit name such as {quantity!r}", "map_path")
    rng = raw.get("range")
    range_: tuple[float, float] | None = None
    if rng is not None:
        ok = (isinstance(rng, list) and len(rng) == 2
              and all(isinstance(v, int | float) and not isinstance(v, bool)
                      and math.isfinite(v) for v in rng) and rng[0] < rng[1])
        if not ok:
            raise DeviceError(f"{w}.range must be [lo, hi] with lo < hi (in {unit}), got "
                              f"{rng!r}", "map_path")
        range_ = (float(rng[0]), float(rng[1]))
    return RegisterSpec(name, table, addr, typ, order, scale, num("offset", 0.0), unit.strip(),
                        _factor(unit.strip(), quantity, f"{w}.unit"), range_)


def load_register_map(path: str | Path | None = None) -> RegisterMap:
    """Read and check a register map TOML (default: the shipped ``modbus-default.toml``).

    Parameters
    ----------
    path : str, Path or None
        The TOML file; None for :data:`DEFAULT_MAP_PATH`.

    Returns
    -------
    RegisterMap

    Raises
    ------
    DeviceError
        One line naming the file and the key: not TOML, unknown keys, a missing signal,
        a bad table/type/address/unit/range, two signals whose registers overlap.
    OSError
        The file cannot be read.

    Examples
    --------
    >>> m = load_register_map()
    >>> m.signals["pressure"].describe(), m.signals["pressure"].unit
    ('pressure (input register 0, int16)', 'kPa')
    """
    p = Path(path) if path is not None else DEFAULT_MAP_PATH
    where = p.name
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise DeviceError(f"{where}: not valid TOML ({exc})", "map_path") from None
    except UnicodeDecodeError:
        raise DeviceError(f"{where}: not UTF-8 text", "map_path") from None
    extra = sorted(set(data) - {*_SIGNALS, "description"})
    if extra:
        raise DeviceError(f"{where}: unknown key(s) {', '.join(extra)} (known: description, "
                          f"{', '.join(_SIGNALS)})", "map_path")
    missing = [s for s in _REQUIRED if s not in data]
    if missing:
        raise DeviceError(f"{where}: missing signal table(s) {', '.join(missing)} (needs "
                          f"[{'], ['.join(_REQUIRED)}])", "map_path")
    desc = data.get("description", "")
    if not isinstance(desc, str):
        raise DeviceError(f"{where}: description must be a string", "map_path")
    signals = {name: _spec(name, data[name], where) for name in _SIGNALS if name in data}
    used: dict[tuple[str, int], str] = {}
    for spec in signals.values():
        for a in range(spec.address, spec.address + spec.count):
            other = used.get((spec.table, a))
            if other is not None:
                raise DeviceError(f"{where}: [{spec.name}] overlaps [{other}] at {spec.table} "
                                  f"register {a}", "map_path")
            used[(spec.table, a)] = spec.name
    return RegisterMap(signals, str(p), desc)


def _int_raw(spec: RegisterSpec, value: int, what: str) -> int:
    code, n = _TYPES[spec.type]
    lo, hi = (-(1 << (16 * n - 1)), (1 << (16 * n - 1)) - 1) if code.islower() else (
        0, (1 << (16 * n)) - 1)
    if not lo <= value <= hi:
        raise DeviceError(f"{what} = {value} does not fit a {spec.type} register "
                          f"({lo}..{hi})", "map_path")
    return value


def encode_registers(spec: RegisterSpec, value: float, *, raw: bool = False) -> list[int]:
    """Registers (16-bit unsigned ints, in address order) holding a physical value.

    raw = (value / to_si - offset) / scale, rounded to the nearest integer for integer types.

    Parameters
    ----------
    spec : RegisterSpec
        The signal.
    value : float
        The value in exofric's unit (MPa for pressure/setpoint, N for force); with
        ``raw=True`` the raw register value itself.
    raw : bool
        Encode ``value`` as the raw number (no scale, offset or unit).

    Returns
    -------
    list of int

    Raises
    ------
    DeviceError
        The raw value does not fit the register type.

    Examples
    --------
    >>> s = RegisterSpec("force", "input", 2, "float32", word_order="little")
    >>> encode_registers(s, 1.5)            # 0x3FC00000, low word first
    [0, 16320]
    """
    code, n = _TYPES[spec.type]
    x = float(value) if raw else (float(value) / spec.to_si - spec.offset) / spec.scale
    if code == "f":
        try:
            b = struct.pack(">f", x)
        except OverflowError:
            raise DeviceError(f"{spec.describe()}: cannot encode {value} (beyond float32)"
                              ) from None
    else:
        if not math.isfinite(x):
            raise DeviceError(f"{spec.describe()}: cannot encode {value}")
        b = struct.pack(f">{code}", _int_raw(spec, round(x), f"{spec.name} raw value"))
    regs = [int.from_bytes(b[2 * i:2 * i + 2], "big") for i in range(n)]
    return regs[::-1] if spec.word_order == "little" else regs


def decode_registers(spec: RegisterSpec, registers: list[int], *, raw: bool = False) -> float:
    """The physical value (MPa or N) that registers hold: (raw x scale + offset) x to_si.

    Parameters
    ----------
    spec : RegisterSpec
        The signal.
    registers : list of int
        ``spec.count`` 16-bit register values in address order.
    raw : bool
        Return the raw number (no scale, offset or unit).

    Returns
    -------
    float

    Examples
    --------
    >>> s = RegisterSpec("pressure", "input", 0, "int32", scale=0.001, unit="kPa", to_si=0.001)
    >>> decode_registers(s, [0xFFFF, 0xFF38])       # raw -200 -> -0.2 kPa -> -0.0002 MPa
    -0.0002
    """
    code, n = _TYPES[spec.type]
    regs = list(registers)[:n]
    if spec.word_order == "little":
        regs = regs[::-1]
    x = float(struct.unpack(f">{code}", b"".join(r.to_bytes(2, "big") for r in regs))[0])
    if raw:
        return x
    return (x * spec.scale + spec.offset) * spec.to_si


def _in_unit(spec: RegisterSpec, value_si: float) -> float:
    return value_si / spec.to_si


def _reason(exc: BaseException) -> str:
    """pymodbus's message cut to its clause: no 'Modbus Error:', tags, client repr (<= 80).

    >>> _reason(Exception("Modbus Error: [Input/Output] No response received after 0 "
    ...                   "retries, continue with next request"))
    'No response received after 0 retries'
    """
    import re

    text = " ".join(str(exc).split())
    text = re.sub(r"^Modbus Error:\s*", "", text)
    text = re.sub(r"\[(Input/Output|Connection|Invalid Message|Parameter|Not implemented|"
                  r"Modbus IO|No Such Slave|Invalid State)\]\s*", "", text)
    text = re.sub(r"\[?\b\w*Client\b[^\]]*\]?", "", text)    # [ModbusTcpClient 1.2.3.4:502]
    text = re.sub(r",?\s*continue with next request", "", text).strip(" .:,")
    return text if len(text) <= 80 else text[:77] + "..."


class ModbusDevice(DeviceBase):
    """A rig behind a Modbus TCP or RTU slave (pymodbus sync client) and a register map.

    Opening connects (about 2 s at most for TCP), then reads every signal once: an address the
    device refuses or a value outside the declared sensor range means the map does not match
    the device (:class:`DeviceError`). Reads group the signals of one table into one request
    when they lie within 125 registers.

    Parameters
    ----------
    url : DeviceURL
        ``modbus-tcp://HOST:PORT?unit=1&timeout=0.25`` or
        ``modbus-rtu:///dev/ttyX?baud=115200&unit=1&parity=N&stopbits=1``.
    register_map : RegisterMap
        From :func:`load_register_map`.

    Examples
    --------
    >>> from exofric.hardware import ModbusSimServer, open_device
    >>> with ModbusSimServer() as srv, open_device(srv.url) as dev:
    ...     dev.write_setpoint_mpa(0.2)
    ...     round(dev.read().pressure_mpa, 1) >= 0.0
    True
    """

    def __init__(self, url: DeviceURL, register_map: RegisterMap) -> None:
        self.url = url.text
        self.map = register_map
        self.unit_id = int(url.number("unit", 1, 0, 255))
        self.timeout_s = url.number("timeout", DEFAULT_IO_TIMEOUT_S, 0.001, 60.0, "s")
        self._vented = False
        self._heartbeat: int | None = None
        if url.scheme == "modbus-tcp":
            from pymodbus.client import ModbusTcpClient

            self.client: Any = ModbusTcpClient(url.host, port=url.port or 502,
                                               timeout=DEFAULT_CONNECT_TIMEOUT_S, retries=0,
                                               reconnect_delay=0)
        else:
            from pymodbus.client import ModbusSerialClient

            parity = url.query.get("parity", "N").upper()
            if parity not in ("N", "E", "O"):
                raise DeviceError(f"{url.text}: parity must be N, E or O, got {parity!r}")
            self.client = ModbusSerialClient(
                url.path, baudrate=int(url.number("baud", DEFAULT_BAUD, 50, 4e6, "bit/s")),
                parity=parity, stopbits=int(url.number("stopbits", 1, 1, 2)),
                timeout=self.timeout_s, retries=0, reconnect_delay=0)
        if not self.client.connect():
            self.client.close()
            how = (f"no connection within {DEFAULT_CONNECT_TIMEOUT_S:g} s or refused"
                   if url.scheme == "modbus-tcp" else "cannot open the port")
            raise DeviceError(f"{self.url}: {how}")
        self.client.comm_params.timeout_connect = self.timeout_s
        self._groups = self._read_groups()
        try:
            self.read()
        except SensorStale as exc:
            self.client.close()
            why = str(exc).removeprefix(f"{self.url}: ")    # the device is named once
            raise DeviceError(f"{self.url}: the device does not answer reads ({why})") from None
        except DeviceError:
            self.client.close()
            raise

    def _read_groups(self) -> list[tuple[str, int, int, list[RegisterSpec]]]:
        """(table, first address, count, specs) per read request."""
        out: list[tuple[str, int, int, list[RegisterSpec]]] = []
        for table in _TABLES:
            specs = [self.map.signals[n] for n in ("pressure", "force", "heartbeat")
                     if n in self.map.signals and self.map.signals[n].table == table]
            if not specs:
                continue
            lo = min(s.address for s in specs)
            hi = max(s.address + s.count for s in specs)
            if hi - lo <= _MAX_READ:
                out.append((table, lo, hi - lo, specs))
            else:
                out.extend((table, s.address, s.count, [s]) for s in specs)
        return out

    def _request(self, what: str, call: Any, *args: Any, **kwargs: Any) -> Any:
        from pymodbus.exceptions import ConnectionException, ModbusException

        try:
            rr = call(*args, device_id=self.unit_id, **kwargs)
        except ConnectionException as exc:       # closed by the peer, refused, unplugged
            raise DeviceFault(f"{self.url}: {what}: connection lost ({_reason(exc)})"
                              ) from None
        except ModbusException as exc:           # no answer in time, a garbled frame
            why = _reason(exc)
            why = "" if why.startswith("No response received") else f" ({why})"
            raise SensorStale(f"{self.url}: {what}: no valid answer within {self.timeout_s:g} s"
                              f"{why}") from None
        except (OSError, ValueError, struct.error) as exc:   # the port or a frame broke
            raise DeviceFault(f"{self.url}: {what}: {type(exc).__name__}: {_reason(exc)}"
                              ) from None
        if rr.isError():
            code = getattr(rr, "exception_code", None)
            if code == 2:
                raise DeviceError(f"{self.url}: {what}: the device refuses the address (illegal "
                                  f"data address): the register map {Path(self.map.source).name}"
                                  " does not match the device")
            raise SensorStale(f"{self.url}: {what}: the device answered exception code {code}")
        return rr

    def read(self) -> Reading:
        """Pressure (MPa), force (N) and the heartbeat, in one request per table.

        Returns
        -------
        Reading

        Raises
        ------
        SensorStale
            No valid answer within the timeout, a non-finite float, or a device exception other
            than an illegal address.
        DeviceFault
            The connection is lost, or a value lies outside the declared sensor range (the map
            does not match the device, or the sensor sends garbage).
        DeviceError
            Illegal address (the map does not match the device).
        """
        values: dict[str, float] = {}
        for table, lo, count, specs in self._groups:
            call = (self.client.read_input_registers if table == "input"
                    else self.client.read_holding_registers)
            names = "+".join(s.name for s in specs)
            rr = self._request(f"reading {names} ({table} registers {lo}..{lo + count - 1})",
                               call, lo, count=count)
            regs = list(rr.registers)
            if len(regs) < count:
                raise SensorStale(f"{self.url}: short answer reading {names}")
            for s in specs:
                off = s.address - lo
                values[s.name] = decode_registers(s, regs[off:off + s.count],
                                                  raw=s.name == "heartbeat")
        for name in ("pressure", "force"):
            s = self.map.signals[name]
            v = _in_unit(s, values[name])
            if not math.isfinite(v):        # a float32 NaN/inf: the sensor has no value
                raise SensorStale(f"{self.url}: {s.describe()} reads {v} (no valid value)")
            if s.range is not None and not s.range[0] <= v <= s.range[1]:
                raise DeviceFault(f"{self.url}: {s.describe()} reads {v:g} {s.unit}, outside its "
                                  f"declared range [{s.range[0]:g}, {s.range[1]:g}] {s.unit}: "
                                  f"the register map {Path(self.map.source).name} does not "
                                  "match the device")
        hb = values.get("heartbeat")
        return Reading(values["pressure"], values["force"], None if hb is None else int(hb))

    def _write(self, spec: RegisterSpec, regs: list[int]) -> None:
        what = f"writing {spec.describe()}"
        if len(regs) == 1:
            self._request(what, self.client.write_register, spec.address, regs[0])
        else:
            self._request(what, self.client.write_registers, spec.address, regs)

    def write_setpoint_mpa(self, pressure_mpa: float) -> None:
        """Write the pressure set-point (MPa) to the ``setpoint`` register(s).

        After :meth:`vent`, the vent register gets ``run_value`` first.

        Parameters
        ----------
        pressure_mpa : float
            Set-point in MPa, within the map's set-point ``range``.
        """
        p = self._check_setpoint(pressure_mpa)
        s = self.map.signals["setpoint"]
        if s.range is not None and not s.range[0] <= _in_unit(s, p) <= s.range[1]:
            raise DeviceError(f"pressure set-point {p:g} MPa is outside the regulator's range "
                              f"[{s.range[0]:g}, {s.range[1]:g}] {s.unit} ({s.describe()})",
                              "pressure_mpa")
        if self._vented:
            v = self.map.signals["vent"]
            self._write(v, encode_registers(v, v.run_value, raw=True))
            self._vented = False
        self._write(s, encode_registers(s, p))

    def vent(self) -> None:
        """Write the vent register's ``vent_value`` and a zero set-point.

        Both writes are attempted even when the first fails (a refused vent register must
        not leave the regulator at its last set-point); the first error is then raised.

        Raises
        ------
        DeviceError
            A write failed (:class:`SensorStale` for no answer).
        """
        v = self.map.signals["vent"]
        s = self.map.signals["setpoint"]
        error: DeviceError | None = None
        for spec, value, raw in ((v, float(v.vent_value), True), (s, 0.0, False)):
            try:
                self._write(spec, encode_registers(spec, value, raw=raw))
            except DeviceError as exc:
                error = error or exc
        if error is not None:
            raise error
        self._vented = True

    def reconnect(self) -> None:
        """Close the connection (TCP socket or serial port) and open a fresh one.

        Raises
        ------
        DeviceFault
            The device refuses the new connection (or the port cannot be opened).
        """
        try:
            self.client.close()
        except Exception:  # noqa: BLE001, S110 - the old connection is dead anyway
            pass
        if not self.client.connect():
            raise DeviceFault(f"{self.url}: reconnect refused (no connection within "
                              f"{self.timeout_s:g} s)")

    def describe(self) -> str:
        """The URL and the register map."""
        return f"{self.url} (register map {Path(self.map.source).name})"

    def close(self) -> None:
        """Close the connection."""
        self.client.close()
