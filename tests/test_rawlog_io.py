"""Raw rig logs (exofric.io.read_raw_log): unit conversion against defined constants, round trips
through CSV, Parquet and TDMS, the --columns mapping, metadata, and one line per bad log.

References: the exact/defined SI values of the units (NIST SP 811 appendix B; 1 lbf = 0.45359237
kg x 9.80665 m/s^2, 1 in = 25.4 mm, 1 psi = 1 lbf/in^2, 1 bar = 1e5 Pa), written here as
literals, never taken from pint. Tolerance 1e-12 relative (float round-off only).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from exofric.defaults import RAWLOG_MIN_SAMPLES
from exofric.errors import InputError
from exofric.io import RAW_QUANTITIES, parse_column_map, read_raw_log, write_raw_log
from exofric.io._rawlog import _factor

PSI_PA = 6894.757293168361
LBF_N = 4.4482216152605
KGF_N = 9.80665
BAR_PA = 1e5
IN_MM = 25.4
RTOL = 1e-12


def _log(n: int = 200, step: float = 0.01, displacement: bool = True) -> pd.DataFrame:
    """A log in exofric's units: a pressure ramp with ripple, a force following it."""
    t = np.round(np.arange(n) * step, 10)
    p = 0.05 + 0.4 * t / t[-1] + 0.003 * np.sin(7.0 * t)
    cols = {"time_s": t, "pressure_mpa": p, "force_n": 3.0 + 25.0 * p ** 1.3}
    if displacement:
        cols["displacement_mm"] = 0.5 + 0.2 * np.cos(3.0 * t)
    return pd.DataFrame(cols)


def _converted(base: pd.DataFrame, time: str, pressure: str, force: str,
               disp: str) -> pd.DataFrame:
    """``base`` converted by hand with the literal constants above."""
    t = {"s": 1.0, "ms": 1e3, "min": 1 / 60}[time]
    pr = {"mpa": 1.0, "kpa": 1e3, "pa": 1e6, "bar": 1e6 / BAR_PA, "mbar": 1e9 / BAR_PA,
          "psi": 1e6 / PSI_PA}[pressure]
    f = {"n": 1.0, "kn": 1e-3, "kgf": 1 / KGF_N, "lbf": 1 / LBF_N}[force]
    d = {"mm": 1.0, "m": 1e-3, "um": 1e3, "in": 1 / IN_MM}[disp]
    return pd.DataFrame({
        f"time_{time}": base["time_s"] * t, f"pressure_{pressure}": base["pressure_mpa"] * pr,
        f"force_{force}": base["force_n"] * f, f"displacement_{disp}": base["displacement_mm"] * d,
    })


def _assert_same(df: pd.DataFrame, base: pd.DataFrame) -> None:
    assert list(df.columns) == list(base.columns)
    assert all(df[c].dtype == np.float64 for c in df.columns)
    for c in base.columns:
        np.testing.assert_allclose(df[c].to_numpy(), base[c].to_numpy(), rtol=RTOL, atol=0,
                                   err_msg=c)


def _one_line_error(path: Path, match: str, **kw) -> str:
    with pytest.raises(InputError, match=match) as exc:
        read_raw_log(path, **kw)
    msg = str(exc.value)
    assert "\n" not in msg and msg.startswith(path.name), msg
    return msg


# ---------------------------------------------------------------------------------------------
# Units.


@pytest.mark.parametrize("quantity,unit,expected", [
    ("pressure", "psi", PSI_PA * 1e-6), ("pressure", "bar", BAR_PA * 1e-6),
    ("pressure", "mbar", BAR_PA * 1e-9), ("pressure", "kpa", 1e-3), ("pressure", "pa", 1e-6),
    ("force", "lbf", LBF_N), ("force", "kgf", KGF_N), ("force", "kn", 1e3),
    ("displacement", "in", IN_MM), ("displacement", "m", 1e3), ("displacement", "um", 1e-3),
    ("time", "ms", 1e-3), ("time", "min", 60.0),
])
def test_pint_factors_match_defined_constants(quantity, unit, expected):
    assert _factor(quantity, unit) == pytest.approx(expected, rel=RTOL, abs=0)


def test_raw_quantities():
    assert RAW_QUANTITIES == {"time_s": "s", "pressure_mpa": "MPa", "force_n": "N",
                              "displacement_mm": "mm"}


UNIT_SETS = [("s", "mpa", "n", "mm"), ("s", "kpa", "lbf", "m"), ("ms", "bar", "kgf", "in"),
             ("min", "psi", "kn", "um"), ("s", "mbar", "n", "mm"), ("s", "pa", "n", "mm")]


@pytest.mark.parametrize("suffix", [".csv", ".txt", ".parquet", ".pq"])
@pytest.mark.parametrize("units", UNIT_SETS, ids="/".join)
def test_round_trip_in_other_units(tmp_path, suffix, units):
    base = _log()
    df = read_raw_log(write_raw_log(tmp_path / f"log{suffix}", _converted(base, *units)))
    _assert_same(df, base)
    time, pressure, force, disp = units
    assert df.attrs["units"] == {
        "time_s": {"s": "s", "ms": "ms", "min": "min"}[time],
        "pressure_mpa": {"mpa": "MPa", "kpa": "kPa", "pa": "Pa", "bar": "bar", "mbar": "mbar",
                         "psi": "psi"}[pressure],
        "force_n": {"n": "N", "kn": "kN", "kgf": "kgf", "lbf": "lbf"}[force],
        "displacement_mm": {"mm": "mm", "m": "m", "um": "um", "in": "in"}[disp]}


def test_kpa_lbf_and_mpa_n_logs_give_the_same_frame(tmp_path):
    base = _log(displacement=False)
    a = read_raw_log(write_raw_log(tmp_path / "a.csv", base))
    other = pd.DataFrame({"time_s": base["time_s"], "pressure_kpa": base["pressure_mpa"] * 1e3,
                          "force_lbf": base["force_n"] / LBF_N})
    b = read_raw_log(write_raw_log(tmp_path / "b.csv", other))
    assert list(a.columns) == ["time_s", "pressure_mpa", "force_n"]
    np.testing.assert_allclose(b.to_numpy(), a.to_numpy(), rtol=1e-12, atol=0)


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_write_read_is_bit_exact(tmp_path, suffix):
    base = _log()
    df = read_raw_log(write_raw_log(tmp_path / f"x{suffix}", base))
    assert np.array_equal(df.to_numpy(), base.to_numpy())


def test_header_case_spaces_order_and_extra_columns(tmp_path):
    base = _log(displacement=False)
    frame = pd.DataFrame({" Force_LBF ": base["force_n"] / LBF_N, "setpoint_mpa": 0.3,
                          "Time_s": base["time_s"], "PRESSURE_kPa": base["pressure_mpa"] * 1e3,
                          "pressure_setpoint_mpa": 0.2, "time_stamp": "x"})
    df = read_raw_log(write_raw_log(tmp_path / "c.csv", frame))
    _assert_same(df, base)
    assert df.attrs["columns"] == {"time_s": "Time_s", "pressure_mpa": "PRESSURE_kPa",
                                   "force_n": "Force_LBF"}
    assert df.attrs["ignored_columns"] == ["setpoint_mpa", "pressure_setpoint_mpa", "time_stamp"]
    assert df.attrs["source"] == "c.csv"


@pytest.mark.parametrize("sep", ["\t", ";", " "])
def test_other_separators(tmp_path, sep):
    base = _log(n=30, displacement=False)
    text = sep.join(base.columns) + "\n" + "\n".join(
        sep.join(repr(float(v)) for v in row) for row in base.to_numpy()) + "\n"
    p = tmp_path / "s.txt"
    p.write_text(text)
    assert np.array_equal(read_raw_log(p).to_numpy(), base.to_numpy())


# ---------------------------------------------------------------------------------------------
# --columns and metadata.


def test_column_map_parsing():
    assert parse_column_map("time=t,pressure_kpa=P1,force_n=Fx") == {
        "time_s": "t", "pressure_kpa": "P1", "force_n": "Fx"}
    assert parse_column_map(" Time_ms = clock (ms) , Displacement_IN=x ") == {
        "time_ms": "clock (ms)", "displacement_in": "x"}
    assert parse_column_map("") == {} and parse_column_map("  ") == {}


def test_column_map_reads_a_log_with_other_headers(tmp_path):
    base = _log(displacement=False)
    frame = pd.DataFrame({"t": base["time_s"], "P 1": base["pressure_mpa"] * 1e3,
                          "Fx": base["force_n"], "spare": 1.0, "pressure_bar": 9.9})
    p = write_raw_log(tmp_path / "m.csv", frame)
    df = read_raw_log(p, parse_column_map("time=t,pressure_kpa=P 1,force_n=Fx"))
    _assert_same(df, base)
    assert df.attrs["columns"] == {"time_s": "t", "pressure_mpa": "P 1", "force_n": "Fx"}
    assert df.attrs["units"] == {"time_s": "s", "pressure_mpa": "kPa", "force_n": "N"}
    assert df.attrs["ignored_columns"] == ["spare", "pressure_bar"]
    # only pressure mapped: time and force are still found by their headers
    frame2 = frame.rename(columns={"t": "time_s", "Fx": "force_n"}).drop(columns="pressure_bar")
    df2 = read_raw_log(write_raw_log(tmp_path / "m2.csv", frame2), {"pressure_kpa": "P 1"})
    _assert_same(df2, base)


def test_csv_metadata_lines_kept_in_order(tmp_path):
    base = _log(n=25, displacement=False)
    body = base.to_csv(index=False, float_format="%.17g").splitlines()
    lines = ["# rig: B2", "#operator: A", body[0], *body[1:10], "  # valve swapped at 0.09 s",
             "", *body[10:], "# end"]
    p = tmp_path / "meta.csv"
    p.write_text("\n".join(lines) + "\n")
    df = read_raw_log(p)
    assert np.array_equal(df.to_numpy(), base.to_numpy())
    assert df.attrs["metadata"] == ["rig: B2", "operator: A", "valve swapped at 0.09 s", "end"]


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_metadata_round_trip(tmp_path, suffix):
    meta = ["rig: B2", "", "  indented: kept", "gain: 0.5 # not a comment", "ünïcode µm"]
    df = read_raw_log(write_raw_log(tmp_path / f"m{suffix}", _log(n=25), meta))
    expected = meta if suffix == ".parquet" else [m.rstrip() for m in meta]
    assert df.attrs["metadata"] == expected


def test_parquet_foreign_key_value_metadata(tmp_path):
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = pa.Table.from_pandas(_log(n=25), preserve_index=False)
    table = table.replace_schema_metadata({b"logger": b"cRIO-9040", b"rate_hz": b"100"})
    p = tmp_path / "f.pq"
    pq.write_table(table, p)
    assert read_raw_log(p).attrs["metadata"] == ["logger: cRIO-9040", "rate_hz: 100"]


# ---------------------------------------------------------------------------------------------
# TDMS.

nptdms = pytest.importorskip("nptdms")


def _write_tdms(path: Path, groups: dict[str, dict[str, np.ndarray]],
                channel_props: dict[str, dict] | None = None,
                file_props: dict | None = None) -> Path:
    from nptdms import ChannelObject, GroupObject, RootObject, TdmsWriter

    objs: list = [RootObject(properties=file_props or {})]
    for g, chans in groups.items():
        objs.append(GroupObject(g, properties={"rig": "B2"}))
        for c, data in chans.items():
            objs.append(ChannelObject(g, c, np.asarray(data),
                                      properties=(channel_props or {}).get(c, {})))
    with TdmsWriter(path) as w:
        w.write_segment(objs)
    return path


def test_tdms_round_trip_with_time_channel(tmp_path):
    base = _log()
    conv = _converted(base, "ms", "psi", "lbf", "in")
    p = _write_tdms(tmp_path / "a.tdms",
                    {"Setup": {"temperature_c": np.ones(5)},
                     "Run": {c: conv[c].to_numpy() for c in conv.columns} | {
                         "setpoint_mpa": np.zeros(len(base))}},
                    file_props={"operator": "A"})
    df = read_raw_log(p)
    _assert_same(df, base)
    assert df.attrs["ignored_columns"] == ["setpoint_mpa"]
    assert df.attrs["metadata"][:2] == ["operator: A", "Run/rig: B2"]


@pytest.mark.parametrize("props,offset,scale", [
    ({"wf_increment": 0.01, "wf_start_offset": 0.5}, 0.5, 1.0),
    ({"wf_increment": 0.01}, 0.0, 1.0),
    ({"wf_increment": 10.0, "wf_start_offset": 0.0, "wf_xunit_string": "ms"}, 0.0, 1e-3),
])
def test_tdms_waveform_without_time_channel(tmp_path, props, offset, scale):
    base = _log(displacement=False)
    p = _write_tdms(tmp_path / "w.tdms",
                    {"G": {"P1": base["pressure_mpa"] * 1e3, "Fx": base["force_n"] / KGF_N}},
                    channel_props={"P1": props})
    df = read_raw_log(p, parse_column_map("pressure_kpa=P1,force_kgf=Fx"))
    inc = props["wf_increment"]
    expected_t = (offset + inc * np.arange(len(base))) * scale
    np.testing.assert_allclose(df["time_s"], expected_t, rtol=RTOL, atol=1e-15)
    np.testing.assert_allclose(df[["pressure_mpa", "force_n"]],
                               base[["pressure_mpa", "force_n"]], rtol=RTOL, atol=0)
    assert df.attrs["columns"]["time_s"] == "P1 waveform time"
    assert "G/P1/wf_increment: " + str(inc) in df.attrs["metadata"]


def test_tdms_errors(tmp_path):
    base = _log(displacement=False)
    chans = {"pressure_kpa": base["pressure_mpa"] * 1e3, "force_n": base["force_n"]}
    p = _write_tdms(tmp_path / "nt.tdms", {"G": chans})
    msg = _one_line_error(p, "no time channel")
    assert "'pressure_kpa' has no waveform timing (wf_increment)" in msg
    p2 = _write_tdms(tmp_path / "ng.tdms", {"A": {"x": np.ones(3)}, "B": {"y": np.ones(3)}})
    msg = _one_line_error(p2, "no TDMS group has pressure and force channels")
    assert "'A': 'x'" in msg and "'B': 'y'" in msg and "; columns: name the channels" in msg
    p3 = _write_tdms(tmp_path / "len.tdms", {"G": {"time_s": base["time_s"], **chans,
                                                   "force_n": base["force_n"][:-1]}})
    _one_line_error(p3, "channels have different lengths: time_s 200, pressure_kpa 200, "
                        "force_n 199")
    p4 = tmp_path / "bad.tdms"
    p4.write_bytes(b"not a tdms file at all" * 10)
    _one_line_error(p4, "not a readable TDMS file")


def test_tdms_without_nptdms(tmp_path, monkeypatch):
    p = tmp_path / "a.tdms"
    p.write_bytes(b"")
    monkeypatch.setitem(sys.modules, "nptdms", None)
    msg = _one_line_error(p, "reading TDMS needs npTDMS")
    assert msg.endswith("pip install 'exofric[tdms]'")


# ---------------------------------------------------------------------------------------------
# Bad logs: one line, starting with the file name, naming the column and the time range.


def _csv(tmp_path: Path, frame: pd.DataFrame, name: str = "bad.csv") -> Path:
    return write_raw_log(tmp_path / name, frame)


def _long(n: int = 2001) -> pd.DataFrame:
    t = np.round(np.arange(n) * 0.01, 10)
    return pd.DataFrame({"time_s": t, "pressure_kpa": 100.0 + t, "force_n": 5.0 + t})


def test_nan_bursts_name_the_time_range(tmp_path):
    log = _long()
    t = log["time_s"]
    for lo, hi in ((12.30, 12.55), (14.00, 14.19), (15.00, 15.10)):
        log.loc[(t >= lo - 1e-9) & (t <= hi + 1e-9), "force_n"] = np.nan
    assert log["force_n"].isna().sum() == 57
    msg = _one_line_error(_csv(tmp_path, log), "force_n")
    assert msg == ("bad.csv: force_n is NaN in 3 bursts (57 samples), the first from 12.30 s "
                   "to 12.55 s")


@pytest.mark.parametrize("cell,kind", [("", "NaN"), ("nan", "NaN"), ("NA", "NaN"),
                                       ("inf", "infinite"), ("-inf", "infinite")])
def test_empty_nan_and_inf_cells(tmp_path, cell, kind):
    text = "time_s,pressure_mpa,force_lbf\n" + "".join(
        f"{i * 0.1:.1f},0.2,{cell if i == 7 else 1.5}\n" for i in range(25))
    p = tmp_path / "c.csv"
    p.write_text(text)
    msg = _one_line_error(p, "force_n")
    assert msg == f"c.csv: force_n (column 'force_lbf') is {kind} in 1 burst (1 sample), at 0.70 s"


def test_nan_time_names_rows(tmp_path):
    log = _long(50)
    log.loc[[4, 5], "time_s"] = np.nan
    msg = _one_line_error(_csv(tmp_path, log), "time_s is NaN")
    assert msg.endswith("in 1 burst (2 samples), from data row 5 (line 6) to data row 6 (line 7)")


@pytest.mark.parametrize("new,how", [(0.19, "repeats"), (0.15, "decreases")])
def test_time_not_increasing(tmp_path, new, how):
    log = _long(50)
    log.loc[20, "time_s"] = new
    msg = _one_line_error(_csv(tmp_path, log), "not increasing")
    assert msg == (f"bad.csv: time_s is not increasing: it {how} from 0.19 s to {new:.2f} s at "
                   "data row 21 (line 22)")


def test_gap_names_the_time_range(tmp_path):
    log = _long(1001)
    log = pd.concat([log, _long(51).assign(time_s=lambda d: d["time_s"] + 12.5)],
                    ignore_index=True)
    msg = _one_line_error(_csv(tmp_path, log), "gap")
    assert msg.startswith("bad.csv: gap in time_s from 10.00 s to 12.50 s (2.5 s; median step "
                          "0.01 s;")
    assert "max_gap_factor 10" in msg
    assert len(read_raw_log(tmp_path / "bad.csv", max_gap_factor=300.0)) == 1052


@pytest.mark.parametrize("factor", [1.0, 0.5, -3.0, float("nan"), "ten"])
def test_max_gap_factor_must_exceed_one(tmp_path, factor):
    with pytest.raises(InputError, match="max_gap_factor must be") as exc:
        read_raw_log(_csv(tmp_path, _long(30)), max_gap_factor=factor)
    assert "\n" not in str(exc.value)


@pytest.mark.parametrize("header,match", [
    ("time_s,pressure_atm,force_n", r"column 'pressure_atm' has an unknown pressure unit 'atm' "
                                    r"\(known: mpa, kpa, pa, bar, mbar, psi"),
    ("time_s,pressure_mpa,force_oz", r"column 'force_oz' has an unknown force unit 'oz' "
                                     r"\(known: n, kn, kgf, lbf"),
    ("time_h,pressure_mpa,force_n", r"unknown time unit 'h' \(known: s, ms, min"),
    ("time_s,pressure_mpa,displacement_ft", r"unknown displacement unit 'ft'"),
    ("time_s,pressure_kpa,pressure_bar", r"two pressure columns, 'pressure_kpa' and "
                                         r"'pressure_bar': keep one, or choose one \(columns: "
                                         r"e.g. pressure_kpa=pressure_kpa\)$"),
    ("time_s,p_kpa,force_n", r"no pressure column .*columns found: 'time_s', 'p_kpa', "
                             r"'force_n'\); columns: name the columns, e.g. time=t,"),
    ("t,pressure_mpa,force_n", r"no time column .*columns: name the columns, e.g. time=t,"),
    ("time_s,pressure_mpa,weight_n", r"no force column"),
])
def test_bad_headers(tmp_path, header, match):
    p = tmp_path / "h.csv"
    p.write_text(header + "\n" + "".join(f"{i},1,2\n" for i in range(25)))
    _one_line_error(p, match)


@pytest.mark.parametrize("header", ["time_s,pressure_mpa,force_n,force_n",
                                    "time_s,pressure_mpa,force_n,Force_N"])
def test_one_header_twice_says_rename_not_columns(tmp_path, header):
    # a columns mapping cannot choose between two columns of one name: the message must not
    # offer it
    p = tmp_path / "h.csv"
    p.write_text(header + "\n" + "".join(f"{i},1,2,3\n" for i in range(25)))
    msg = _one_line_error(p, r"column 'force_n' is in the file 2 times \(columns 3, 4\); "
                             r"rename all but one$")
    assert "columns:" not in msg and "--columns" not in msg


def test_unknown_unit_beside_a_known_one_is_ignored_and_listed(tmp_path):
    frame = _long(30).assign(pressure_atm=1.0)
    assert read_raw_log(_csv(tmp_path, frame)).attrs["ignored_columns"] == ["pressure_atm"]


def test_mapping_header_not_in_file(tmp_path):
    p = _csv(tmp_path, _long(30))
    msg = _one_line_error(p, r"column 'P1' \(columns: named by pressure_kpa=P1\) is not in "
                             r"the file",
                          columns={"pressure_kpa": "P1"})
    assert "columns found: 'time_s', 'pressure_kpa', 'force_n'" in msg
    _one_line_error(p, "columns: unknown quantity", columns={"temp_c": "T"})


def test_too_few_samples(tmp_path):
    _one_line_error(_csv(tmp_path, _long(RAWLOG_MIN_SAMPLES - 1)),
                    f"needs at least {RAWLOG_MIN_SAMPLES} samples, got {RAWLOG_MIN_SAMPLES - 1}")
    p = tmp_path / "empty.csv"
    p.write_text("# only metadata\ntime_s,pressure_mpa,force_n\n")
    _one_line_error(p, "got 0")
    p.write_text("# only metadata\n\n")
    _one_line_error(p, "no header row")


def test_non_numeric_cell_names_row_line_and_column(tmp_path):
    text = "# rig\ntime_s,pressure_mpa,force_n,note\n" + "".join(
        f"{i * 0.1:.1f},{'0.2x' if i == 12 else '0.2 '},1,ok\n" for i in range(25))
    p = tmp_path / "n.csv"
    p.write_text(text)
    msg = _one_line_error(p, "not a number")
    assert msg == "n.csv: data row 13 (line 15), column 'pressure_mpa' is not a number: '0.2x'"


@pytest.mark.parametrize("newline,bom", [("\n", b""), ("\r\n", b""), ("\r\n", b"\xef\xbb\xbf")])
def test_line_numbers_with_blank_comment_and_whitespace_lines(tmp_path, newline, bom):
    rows = [f"{i * 0.1:.1f}\t0.2\t{'x1' if i == 22 else '1'}" for i in range(25)]
    lines = ["# rig", "", "time_s\tpressure_mpa\tforce_n", *rows[:5], " \t ", "", "  # note",
             *rows[5:]]
    p = tmp_path / "w.txt"
    p.write_bytes(bom + newline.join(lines).encode() + newline.encode())
    msg = _one_line_error(p, "not a number")
    assert msg == "w.txt: data row 23 (line 29), column 'force_n' is not a number: 'x1'"
    rows[22] = "2.2\t0.2\t1"
    p.write_bytes(bom + newline.join(lines[:3] + rows[:5] + lines[8:11] + rows[5:]).encode())
    df = read_raw_log(p)
    assert len(df) == 25 and df.attrs["metadata"] == ["rig", "note"]


def test_row_with_extra_fields(tmp_path):
    text = "time_s,pressure_mpa,force_n\n" + "".join(
        f"{i},0.2,1{',9' if i == 3 else ''}\n" for i in range(25))
    p = tmp_path / "x.csv"
    p.write_text(text)
    _one_line_error(p, r"data row 4 \(line 5\) has 4 fields, the header has 3")


def test_short_row_is_reported_as_nan_not_dropped(tmp_path):
    text = "time_s,pressure_mpa,force_n\n" + "".join(
        f"{i},0.2{',1' if i != 24 else ''}\n" for i in range(25))
    p = tmp_path / "s.csv"
    p.write_text(text)
    _one_line_error(p, r"force_n is NaN in 1 burst \(1 sample\), at 24.00 s")


def test_files_and_suffixes(tmp_path):
    _one_line_error(tmp_path / "log.xls", r"unsupported raw log type '.xls' \(supported: "
                                          r".csv, .tsv, .txt, .dat, .lvm, .tdms, .parquet, .pq, "
                                          r".xlsx, .xlsm\)")
    with pytest.raises(InputError, match="file not found"):
        read_raw_log(tmp_path / "none.csv")
    p = tmp_path / "latin.csv"  # not UTF-8: read as Latin-1 (issue 31), so the cell is named
    p.write_bytes(b"time_s,pressure_mpa,force_n\n1,2,\xe9\n")
    _one_line_error(p, "data row 1 \\(line 2\\), column 'force_n' is not a number: '\u00e9'")
    q = tmp_path / "broken.parquet"
    q.write_bytes(b"PAR1 not really")
    _one_line_error(q, "not a readable Parquet file")


def test_parquet_text_column(tmp_path):
    frame = _long(30)
    frame["force_n"] = [("n/a?" if i == 3 else f"{v!r}") for i, v in enumerate(frame["force_n"])]
    _one_line_error(_csv(tmp_path, frame, "t.parquet"),
                    "row 4, column 'force_n' is not a number: 'n/a\\?'")


@pytest.mark.parametrize("text,match", [
    ("pressure=P1", r"'pressure=P1' needs a unit: pressure_<unit> with unit one of mpa"),
    ("force=Fx", r"'force=Fx' needs a unit"),
    ("displacement=x", r"'displacement=x' needs a unit"),
    ("temp_c=T", r"unknown quantity in 'temp_c=T'"),
    ("pressure_atm=P", r"unknown pressure unit 'atm' in 'pressure_atm=P' \(known: mpa, kpa"),
    ("time=t,time_s=u", r"key 'time_s' is given twice \('time_s=u'\)"),
    ("pressure_kpa=P1,pressure_bar=P2", r"'pressure_bar=P2': pressure is already mapped by "
                                        r"'pressure_kpa=P1'"),
    ("pressure_kpa=X,force_n=X", r"header 'X' is already mapped"),
    ("time", r"malformed item 'time' \(expected KEY=HEADER"),
    ("time=t,,force_n=F", r"malformed item ''"),
    ("time=", r"malformed item 'time='"),
    ("=t", r"malformed item '=t'"),
])
def test_column_map_errors(text, match):
    with pytest.raises(InputError, match=match) as exc:
        parse_column_map(text)
    # the library names the Python parameter (the CLI shows it as --columns)
    assert str(exc.value).startswith("columns: ") and "\n" not in str(exc.value)
    assert exc.value.param == "columns"


def test_write_errors(tmp_path):
    with pytest.raises(InputError, match=r"log.tdms: write_raw_log writes .csv, .txt, .parquet"):
        write_raw_log(tmp_path / "log.tdms", _long(3))
    with pytest.raises(InputError, match="metadata line 2 contains a line break"):
        write_raw_log(tmp_path / "log.csv", _long(3), ["a", "b\nc"])
    assert not list(tmp_path.iterdir())


# ---------------------------------------------------------------------------------------------
# Start-up: the names are light; pint loads only when a unit needs converting.


def _modules(body: str) -> set[str]:
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    code = f"import json, sys\n{body}\nprint(json.dumps(sorted(sys.modules)))"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                       timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    return set(json.loads(r.stdout.splitlines()[-1]))


def test_import_and_column_map_do_not_load_pint_or_pandas():
    mods = _modules("from exofric.io import parse_column_map, read_raw_log\n"
                    "parse_column_map('time=t,pressure_kpa=P1,force_n=Fx')")
    assert not {"pint", "pandas", "pyarrow", "nptdms"} & mods


def test_pint_only_when_converting(tmp_path):
    p = write_raw_log(tmp_path / "mpa.csv", _log(n=30))
    mods = _modules(f"from exofric.io import read_raw_log\nread_raw_log({str(p)!r})")
    assert "pint" not in mods and "pandas" in mods
    q = write_raw_log(tmp_path / "kpa.csv", _converted(_log(n=30), "s", "kpa", "n", "mm"))
    assert "pint" in _modules(f"from exofric.io import read_raw_log\nread_raw_log({str(q)!r})")
