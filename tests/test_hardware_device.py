"""Device layer: URLs, the register map and its codec, the simulated Modbus and serial rigs.

Register encoding is checked against hand-computed values and against pymodbus's own
converters (``ModbusClientMixin.convert_to_registers``/``convert_from_registers``) as an
independent reference; tolerance: exact for integers, float32 rounding for floats.
"""

from __future__ import annotations

import struct
import time
from pathlib import Path

import pytest

from exofric.errors import InputError
from exofric.hardware import (
    DEFAULT_MAP_PATH,
    DeviceError,
    ModbusSimServer,
    RegisterSpec,
    SensorStale,
    SerialSimDevice,
    decode_registers,
    encode_registers,
    load_register_map,
    open_device,
    parse_url,
)

pytest.importorskip("pymodbus")
pytest.importorskip("serial")


def _mixin():
    from pymodbus.client.mixin import ModbusClientMixin

    return ModbusClientMixin


@pytest.mark.parametrize(("typ", "order", "value"), [
    ("int16", "big", -1234), ("uint16", "big", 65000), ("int32", "big", -123456789),
    ("int32", "little", 2_000_000_001), ("uint32", "little", 4_000_000_000),
    ("float32", "big", 54.4), ("float32", "little", -0.2926),
])
def test_codec_matches_pymodbus_converters(typ: str, order: str, value: float) -> None:
    m = _mixin()
    spec = RegisterSpec("force", "input", 0, typ, order)
    ref = m.convert_to_registers(value, getattr(m.DATATYPE, typ.upper()), word_order=order)
    assert encode_registers(spec, value) == ref
    back = m.convert_from_registers(ref, getattr(m.DATATYPE, typ.upper()), word_order=order)
    assert decode_registers(spec, ref) == pytest.approx(back, rel=0, abs=0)


def test_codec_hand_values_scale_offset_units() -> None:
    # 0.1 kPa per count, offset -5 kPa: 0.25 MPa = 250 kPa -> raw (250 + 5)/0.1 = 2550
    s = RegisterSpec("pressure", "input", 0, "int16", scale=0.1, offset=-5.0, unit="kPa",
                     to_si=0.001)
    assert encode_registers(s, 0.25) == [2550]
    assert decode_registers(s, [2550]) == pytest.approx(0.25, abs=1e-15)
    # int16 negative: raw -100 -> 0xFF9C
    assert decode_registers(s, [0xFF9C]) == pytest.approx((-10.0 - 5.0) * 1e-3)
    # float32 1.5 = 0x3FC00000: big = [0x3FC0, 0], little = [0, 0x3FC0]
    f = RegisterSpec("force", "input", 2, "float32")
    assert encode_registers(f, 1.5) == [0x3FC0, 0]
    assert decode_registers(RegisterSpec("force", "input", 2, "float32", "little"),
                            [0, 0x3FC0]) == 1.5
    # int32 big: 70000 = 0x00011170
    i = RegisterSpec("force", "input", 2, "int32", scale=0.01)
    assert encode_registers(i, 700.0) == [0x0001, 0x1170]
    assert struct.unpack(">f", bytes.fromhex("3fc00000"))[0] == 1.5
    with pytest.raises(DeviceError, match="does not fit a uint16"):
        encode_registers(RegisterSpec("setpoint", "holding", 0, "uint16"), -1.0)


def test_default_map_is_valid_and_converts_kpa_with_pint() -> None:
    m = load_register_map()
    assert Path(m.source) == DEFAULT_MAP_PATH
    assert m.signals["pressure"].to_si == pytest.approx(1e-3, rel=1e-12)
    assert m.signals["setpoint"].table == "holding"


def _write_map(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "map.toml"
    p.write_text(text, encoding="utf-8")
    return p


BASE = DEFAULT_MAP_PATH.read_text(encoding="utf-8")


@pytest.mark.parametrize(("edit", "match"), [
    (lambda s: s.replace("[vent]", "[ventt]"), r"unknown key\(s\) ventt"),
    (lambda s: s.replace('offset = 0.0\nunit = "N"', 'offst = 0.0\nunit = "N"'),
     r"\[force\]: unknown key\(s\) offst"),
    (lambda s: s.replace("address = 2\ntype = \"float32\"", "address = 0\ntype = \"float32\""),
     r"\[force\] overlaps \[pressure\] at input register 0"),
    (lambda s: s.replace('unit = "N"', 'unit = "kPa"'), r"\[force\]\.unit: unit 'kPa' is not a "
                                                        "force"),
    (lambda s: s.split("[setpoint]")[0], r"missing signal table\(s\) setpoint, vent"),
    (lambda s: s.replace('type = "int16"', 'type = "int8"'), r"\[pressure\]\.type must be"),
])
def test_bad_maps_give_one_line_naming_the_key(tmp_path: Path, edit, match: str) -> None:
    with pytest.raises(DeviceError, match=match) as ei:
        load_register_map(_write_map(tmp_path, edit(BASE)))
    assert "\n" not in str(ei.value) and str(ei.value).startswith("map.toml: ")


def test_urls() -> None:
    assert parse_url("modbus-rtu:///dev/ttyUSB0?baud=9600&unit=2").path == "/dev/ttyUSB0"
    for bad, match in [("http://x", "unknown device scheme"), ("modbus-tcp://", "needs a host"),
                       ("serial://", "needs a port path"), ("sim://?sped=1", "unknown query"),
                       ("sim://?speed=-1", "speed must be")]:
        with pytest.raises(DeviceError, match=match):
            open_device(bad)
    with pytest.raises(DeviceError, match="register map is for modbus"):
        open_device("sim://", DEFAULT_MAP_PATH)


def test_unreachable_host_fails_fast_with_one_line() -> None:
    import socket

    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()                                   # nothing listens there now
    for url in (f"modbus-tcp://127.0.0.1:{port}", "modbus-tcp://10.255.255.1:502"):
        t0 = time.monotonic()
        with pytest.raises(DeviceError) as ei:
            open_device(url)
        assert time.monotonic() - t0 < 5.0
        assert "\n" not in str(ei.value) and url in str(ei.value)
    with pytest.raises(DeviceError, match="cannot open the port"):
        open_device("serial:///dev/does-not-exist")


def test_map_that_does_not_match_the_device(tmp_path: Path) -> None:
    wrong_addr = _write_map(tmp_path, BASE.replace("address = 4", "address = 40"))
    bad_scale = tmp_path / "scale.toml"
    bad_scale.write_text(BASE.replace("type = \"float32\"", "type = \"int32\""), encoding="utf-8")
    with ModbusSimServer() as srv:
        with pytest.raises(DeviceError, match="illegal data address.*does not match") as ei:
            open_device(srv.url, wrong_addr)
        assert "\n" not in str(ei.value)
        with open_device(srv.url) as dev:       # force 0 N now; make it large and float32
            dev.write_setpoint_mpa(0.5)
            time.sleep(1.5)
        with pytest.raises(DeviceError, match="outside its declared range"):
            open_device(srv.url, bad_scale)


def test_modbus_round_trip_and_vent() -> None:
    with ModbusSimServer() as srv:
        with open_device(srv.url) as dev:
            dev.write_setpoint_mpa(0.3)
            assert srv.rig.command_mpa == pytest.approx(0.3, abs=1e-4)   # 0.1 kPa counts
            assert not srv.rig.vented
            r1 = dev.read()
            time.sleep(0.3)
            r2 = dev.read()
            assert r2.pressure_mpa > r1.pressure_mpa >= 0.0
            assert r2.sample_id != r1.sample_id
            with pytest.raises(DeviceError, match="outside the regulator's range"):
                dev.write_setpoint_mpa(1.0)
        assert srv.rig.vented and srv.rig.command_mpa == 0.0     # `with` vents


def test_serial_round_trip_errors_and_device_watchdog() -> None:
    with SerialSimDevice() as sim:
        dev = open_device(sim.url + "?timeout=0.2")
        dev.write_setpoint_mpa(0.25)
        assert sim.rig.command_mpa == 0.25 and sim.watchdog_ms == 1000
        with pytest.raises(InputError):
            dev.write_setpoint_mpa(float("nan"))
        time.sleep(1.3)                          # host silent > 1 s: the firmware vents
        assert sim.rig.vented
        dev.close()
    with SerialSimDevice(freeze_after_s=0.0, fault="silent") as sim:
        dev = open_device(sim.url + "?timeout=0.1")
        dev.read()                              # the last sample before the sensor froze
        with pytest.raises(SensorStale, match="no answer to 'R'"):
            dev.read()
        dev.close()
