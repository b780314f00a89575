"""One table reader for every measured file (issue 31): real-format files and silent unit errors.

The corpus in tests/data/formats/ was written by the real writers (npTDMS ``TdmsWriter``,
openpyxl, pandas ``to_csv(sep=';', decimal=',')``, pyarrow, Python's UTF-16 and Latin-1
codecs, NI's documented LVM layout) by ``make_formats.py`` beside it. Every file holds the samples
of ``plain.csv`` in another format, unit, encoding or header spelling, converted there with
the SI definitions of the units (1 psi = 6894.757293168361 Pa, 1 lbf = 4.4482216152605 N,
1 kgf = 9.80665 N, 1 bar = 1e5 Pa), not with exofric. References:

* samples: ``plain.csv`` read by pandas (a different reader), tolerance 1e-12 relative (the
  round-off of one multiplication by a unit factor and back);
* pulls: :func:`reduce_log` of ``plain.csv``; each format must give the same pulls to 1e-9
  (relative and absolute: the samples differ by float round-off only, and the reduction's
  sums amplify that by at most ~1e3);
* each silent error of the issue is now an error or a warning naming the unit or time range.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from exofric.errors import InputError
from exofric.friction import pool_pulls, reduce_log
from exofric.io import (
    parse_column_map,
    read_friction_table,
    read_measured_table,
    read_raw_log,
    read_table,
)
from exofric.io._table import header_key

DATA = Path(__file__).parent / "data" / "formats"
PLAIN = DATA / "plain.csv"

#: file -> (columns mapping, the units the file states, format, encoding)
FORMATS = {
    "semicolon_comma.csv": (None, ("s", "kPa", "N", "mm"), "csv", "utf-8"),
    "brackets.tsv": (None, ("s", "bar", "lbf", "mm"), "csv", "utf-8"),
    "units_row.csv": (None, ("s", "kPa", "kgf", "um"), "csv", "utf-8"),
    "utf16_bom.csv": (None, ("s", "MPa", "N", "mm"), "csv", "utf-16"),
    "utf16_nobom.txt": (None, ("s", "MPa", "N", "mm"), "csv", "utf-16-le"),
    "latin1.csv": (None, ("s", "MPa", "N", "um"), "csv", "latin-1"),
    "bluehill.csv": ("force_n=Load,displacement_mm=Extension", ("s", "kPa", "N", "mm"), "csv",
                     "utf-8"),
    "labview.lvm": (None, ("s", "kPa", "N", "mm"), "lvm", "utf-8"),
    "labview_nox.lvm": (None, ("s", "kPa", "N", "mm"), "lvm", "utf-8"),
    "ni.tdms": (None, ("s", "psi", "N", "mm"), "tdms", ""),
    "log.parquet": (None, ("ms", "bar", "kN", "m"), "parquet", ""),
    "excel.xlsx": (None, ("s", "MPa", "N", "mm"), "xlsx", ""),
}
COLS = ["time_s", "pressure_mpa", "force_n", "displacement_mm"]


@pytest.fixture(scope="module")
def plain() -> pd.DataFrame:
    return pd.read_csv(PLAIN)


@pytest.fixture(scope="module")
def plain_pulls() -> pd.DataFrame:
    return reduce_log(read_raw_log(PLAIN)).to_frame()


def _numbers(df: pd.DataFrame) -> np.ndarray:
    return df.select_dtypes("number").to_numpy(dtype=float)


def test_corpus_files_are_small_and_complete():
    files = {p.name for p in DATA.iterdir() if p.is_file() and p.suffix != ".py"}
    assert files == set(FORMATS) | {"plain.csv"}
    assert all((DATA / f).stat().st_size < 50_000 for f in files)


@pytest.mark.parametrize("fname", sorted(FORMATS))
def test_every_format_reads_the_same_samples_and_pulls(fname, plain, plain_pulls):
    columns, units, fmt, encoding = FORMATS[fname]
    df = read_raw_log(DATA / fname, parse_column_map(columns) if columns else None)
    assert list(df.columns) == COLS and len(df) == len(plain)
    np.testing.assert_allclose(df.to_numpy(), plain[COLS].to_numpy(), rtol=1e-12, atol=1e-12)
    assert tuple(df.attrs["units"][c] for c in COLS) == units
    assert (df.attrs["format"], df.attrs["encoding"]) == (fmt, encoding)
    pulls = reduce_log(df).to_frame()
    assert len(pulls) == len(plain_pulls) == 4
    assert pulls[["direction", "branch"]].equals(plain_pulls[["direction", "branch"]])
    np.testing.assert_allclose(_numbers(pulls), _numbers(plain_pulls), rtol=1e-9, atol=1e-9)


def test_preambles_and_properties_are_kept_as_provenance():
    blue = read_raw_log(DATA / "bluehill.csv", parse_column_map("force_n=Load,"
                                                                "displacement_mm=Extension"))
    assert blue.attrs["metadata"][:3] == ["Results Table 1", "Specimen label, ring-A",
                                          "Test date, 2026-11-20"]
    assert blue.attrs["columns"]["time_s"] == "Time"
    assert read_raw_log(DATA / "latin1.csv").attrs["metadata"] == ["Operator: Müller", "Rig: B2"]
    meta = read_raw_log(DATA / "ni.tdms").attrs["metadata"]
    assert "Rig/Pressure/unit_string: psi" in meta
    assert any(m.startswith("Rig/Pressure/wf_start_time: 2026-11-20") for m in meta)
    lvm = read_raw_log(DATA / "labview.lvm").attrs["metadata"]
    assert "Decimal_Separator: ," in lvm and "segment/Y_Unit_Label: kPa N mm" in lvm


def test_measured_table_reader_on_the_corpus(plain):
    # the one public reader: canonical names, units converted, any format
    for fname in ("semicolon_comma.csv", "excel.xlsx", "ni.tdms", "labview.lvm"):
        df = read_measured_table(DATA / fname, ["pressure_mpa", "force_n"])
        np.testing.assert_allclose(df.to_numpy(), plain[["pressure_mpa", "force_n"]].to_numpy(),
                                   rtol=1e-12, atol=1e-12)
        assert len(df.attrs["sha256"]) == 64


@pytest.mark.parametrize("header,unit,expected", [
    ("pressure_kpa", None, ("pressure_kpa", "kpa")),
    ("Pressure (kPa)", None, ("pressure_kpa", "kPa")),
    ("Pressure [kPa]", None, ("pressure_kpa", "kPa")),
    ("Pressure / kPa", None, ("pressure_kpa", "kPa")),
    ("Time (sec)", None, ("time_s", "sec")),
    ("Displacement (µm)", None, ("displacement_um", "µm")),
    ("Pressure", "(psi)", ("pressure_psi", "psi")),
    ("Outer diameter", "mm", ("outer_diameter_mm", "mm")),
    ("test", None, ("test", None)),
])
def test_header_spellings(header, unit, expected):
    assert header_key(header, unit) == expected


def test_a_units_row_contradicting_the_header_is_an_error(tmp_path):
    p = tmp_path / "c.csv"
    p.write_text("Time (s),Pressure (kPa),Force (N)\ns,psi,N\n" + "".join(
        f"{i * 0.1:.1f},{200 + i},{5 + i}\n" for i in range(25)))
    with pytest.raises(InputError, match=r"'Pressure \(kPa\)' says kPa .* unit as 'psi'"):
        read_raw_log(p)


# ---------------------------------------------------------------------------------------------
# The silent cases of issue 31.


def test_tdms_unit_string_psi_with_a_kpa_mapping_names_both():
    with pytest.raises(InputError) as exc:
        read_raw_log(DATA / "ni.tdms", parse_column_map("pressure_kpa=Pressure"))
    msg = str(exc.value)
    assert "\n" not in msg and msg.startswith("ni.tdms:")
    assert "kPa" in msg and "'psi'" in msg and "unit_string" in msg
    # the matching mapping is fine and reads psi (the reference: 1 psi = 6894.757293168361 Pa)
    df = read_raw_log(DATA / "ni.tdms", parse_column_map("pressure_psi=Pressure"))
    assert df.attrs["units"]["pressure_mpa"] == "psi"


def test_a_header_unit_contradicted_by_columns_is_an_error():
    with pytest.raises(InputError, match=r"says psi but the file's unit of column "
                                         r"'Pressure \(kPa\)' is 'kPa'"):
        read_raw_log(DATA / "semicolon_comma.csv", {"pressure_psi": "Pressure (kPa)"})


def _write(plain: pd.DataFrame, path: Path, **cols: np.ndarray) -> Path:
    frame = plain[COLS].copy()
    for k, v in cols.items():
        frame[k] = v
    frame.to_csv(path, index=False, float_format="%.17g")
    return path


def test_kpa_values_under_a_mpa_header_name_kpa(tmp_path, plain):
    p = _write(plain, tmp_path / "k.csv", pressure_mpa=plain["pressure_mpa"] * 1e3)
    with pytest.raises(InputError) as exc:
        read_raw_log(p)
    msg = str(exc.value)
    assert "look like kPa" in msg and "pressure_kpa" in msg and "\n" not in msg
    hi = plain["pressure_mpa"].max() * 1e3
    assert f"{hi:.4g}" in msg  # the largest value as written in the file


def test_n_values_under_a_kn_header_name_n(tmp_path, plain):
    frame = plain[COLS].rename(columns={"force_n": "force_kn"})
    p = tmp_path / "f.csv"
    frame.to_csv(p, index=False, float_format="%.17g")
    with pytest.raises(InputError, match=r"force_kn \(kN\) reach .* not a plausible friction "
                                         r"force .* they look like N"):
        read_raw_log(p)


def test_a_unit_change_inside_a_log_names_its_time_range(tmp_path, plain, plain_pulls):
    # kPa header; from the middle of the second plateau on the logger writes MPa
    red = reduce_log(read_raw_log(PLAIN))
    pl = red.plateaus[1]
    t = plain["time_s"].to_numpy()
    k = int(np.searchsorted(t, 0.5 * (pl["t_start_s"] + pl["t_end_s"])))
    kpa = plain["pressure_mpa"].to_numpy() * 1e3
    kpa[k:] /= 1e3
    p = _write(plain, tmp_path / "u.csv", pressure_mpa=kpa)
    text = p.read_text().replace("pressure_mpa", "pressure_kpa", 1)
    p.write_text(text)
    with pytest.raises(InputError) as exc:
        read_raw_log(p)
    msg = str(exc.value)
    assert "the unit changed inside the log" in msg
    assert f"from {t[k]:.2f} s to the end ({t[-1]:.2f} s)" in msg
    assert "x0.001" in msg


def test_plateau_logs_do_not_trip_the_unit_change_check(plain):
    # pressure steps of x2.5 and force pulls from a rest level are not unit changes
    df = read_raw_log(PLAIN)
    assert len(df) == len(plain)


def _ramp(t: np.ndarray) -> np.ndarray:
    """0.30 -> 0.35 MPa at a steady 3 kPa/s: slower than the plateau band (2 %, 6 kPa) per
    min_plateau_s, so every second looks steady, but it is never held (issue 31: such a log was
    one plateau holding all its pulls)."""
    return 0.30 + 0.05 * t / t[-1]


def test_a_steadily_ramping_pressure_is_not_one_plateau(plain):
    t = plain["time_s"].to_numpy()
    log = plain[COLS].copy()
    log["pressure_mpa"] = _ramp(t)
    with pytest.raises(InputError, match=r"pressure ramps steadily .* never held"):
        reduce_log(log)


def test_cli_reduce_steady_ramp_exits_2(cli, tmp_path, plain):
    t = plain["time_s"].to_numpy()
    p = _write(plain, tmp_path / "ramp.csv", pressure_mpa=_ramp(t))
    r = cli(["reduce", str(p)])
    assert r.code == 2 and "pressure ramps steadily" in r.err and "Traceback" not in r.err


def test_the_same_log_twice_is_an_error():
    a = reduce_log(read_raw_log(PLAIN))
    b = reduce_log(read_raw_log(DATA / "utf16_bom.csv"))  # same samples, another file
    with pytest.raises(InputError, match=r"utf16_bom.csv and plain.csv are the same log"):
        pool_pulls([a, b])
    c = reduce_log(read_raw_log(DATA / "brackets.tsv"))  # round-off differs: another log
    assert len(pool_pulls([a, c])) == 8


def test_tdms_channels_with_other_waveform_timing_are_refused(tmp_path):
    # wf_increment is honoured: channels sampled at different rates cannot be paired by index
    from nptdms import ChannelObject, TdmsWriter

    x = np.linspace(1.0, 2.0, 50)
    with TdmsWriter(tmp_path / "w.tdms") as w:
        w.write_segment([
            ChannelObject("G", "pressure_kpa", x, properties={"wf_increment": 0.01}),
            ChannelObject("G", "force_n", x, properties={"wf_increment": 0.02}),
        ])
    with pytest.raises(InputError, match=r"force channel 'force_n' has wf_increment 0.02 but "
                                         r"pressure channel 'pressure_kpa' has 0.01"):
        read_raw_log(tmp_path / "w.tdms")


def test_a_table_mapping_contradicting_the_header_names_both(tmp_path):
    p = tmp_path / "f.csv"
    p.write_text("Pressure (kPa),Friction (N)\n200,40\n400,80\n")
    with pytest.raises(InputError, match=r"the columns mapping says 'Pressure \(kPa\)' is in "
                                         r"psi but the file says kPa"):
        read_friction_table(p, {"pressure_psi": "Pressure (kPa)"})


def test_one_line_errors_survive_other_formats(tmp_path, plain):
    # duplicated timestamps, NaN bursts and one-sample logs in a ;-separated decimal-comma file
    frame = plain[COLS].iloc[:40].copy()
    frame.columns = ["Zeit (s)", "Druck (kPa)", "Kraft (N)", "Weg (mm)"]
    dup = frame.copy()
    dup.iloc[5, 0] = dup.iloc[4, 0]
    p = tmp_path / "d.csv"
    dup.to_csv(p, sep=";", decimal=",", index=False)
    with pytest.raises(InputError, match=r"is not increasing: it repeats from 0.20 s"):
        read_raw_log(p, parse_column_map("time=Zeit (s),pressure_kpa=Druck (kPa),"
                                         "force_n=Kraft (N)"))
    nan = frame.copy()
    nan.iloc[10:13, 2] = np.nan
    nan.to_csv(p, sep=";", decimal=",", index=False)
    with pytest.raises(InputError, match=r"NaN in 1 burst \(3 samples\), from 0.50 s to 0.60 s"):
        read_raw_log(p, {"time_s": "Zeit (s)", "pressure_kpa": "Druck (kPa)",
                         "force_n": "Kraft (N)"})
    frame.iloc[:1].to_csv(p, sep=";", decimal=",", index=False)
    with pytest.raises(InputError, match=r"needs at least 20 samples, got 1"):
        read_raw_log(p, {"time_s": "Zeit (s)", "pressure_kpa": "Druck (kPa)",
                         "force_n": "Kraft (N)"})


# ---------------------------------------------------------------------------------------------
# Friction tables and the other readers.


def _squeeze(tmp_path: Path) -> tuple[Path, np.ndarray, np.ndarray]:
    p_mpa = np.array([0.1, 0.2, 0.3, 0.4, 0.5])
    n_n = np.array([30.0, 75.0, 118.0, 166.0, 210.0])
    sq = tmp_path / "sq.csv"
    sq.write_text("pressure_mpa,squeeze_force_n\n"
                  + "".join(f"{a},{b}\n" for a, b in zip(p_mpa, n_n, strict=True)))
    return sq, p_mpa, n_n


def test_cli_fit_friction_reads_a_tsv_friction_table(cli, tmp_path):
    # friction exactly 0.7 x N(P) at the squeeze pressures: the proportional least-squares
    # gamma is exactly 0.7 (closed form sum(F N) / sum(N^2)); tolerance 1e-9 (round-off)
    sq, p_mpa, n_n = _squeeze(tmp_path)
    f = tmp_path / "friction.tsv"
    f.write_text("pressure_mpa\tfriction_n\n" + "".join(
        f"{a}\t{float(0.7 * b)!r}\n" for a, b in zip(p_mpa, n_n, strict=True)))
    r = cli(["fit-friction", "--squeeze", str(sq), "--friction", str(f), "--json"])
    assert r.code == 0, r.err
    assert abs(r.json()["gamma"] - 0.7) < 1e-9


def test_friction_tables_in_other_dialects(tmp_path):
    # ; with decimal commas, Name (unit) headers in kN: the same points as the plain table
    a = tmp_path / "a.csv"
    a.write_text("# SYNTHETIC\nPressure (kPa);Friction (kN);test\n200;0,0405;A\n400;0,081;A\n")
    df = read_friction_table(a)
    assert df["pressure_mpa"].tolist() == pytest.approx([0.2, 0.4], rel=1e-12)
    assert df["friction_n"].tolist() == pytest.approx([40.5, 81.0], rel=1e-12)
    assert df.attrs["synthetic"] and df.attrs["kind"] == "points"
    # a per-pull table written as TSV is still a pull table (kinetic_n is the friction)
    b = tmp_path / "b.tsv"
    b.write_text("pressure_mpa\tkinetic_n\tplateau\n0.2\t40\t1\n0.2\t41\t1\n0.4\t80\t2\n")
    df = read_friction_table(b)
    assert df.attrs["kind"] == "pulls" and df["group"].tolist() == ["plateau 1"] * 2 + [
        "plateau 2"]
    # --columns for a friction table
    c = tmp_path / "c.csv"
    c.write_text("P,F\n0.2,40\n0.4,80\n")
    m = parse_column_map("pressure_mpa=P,friction_n=F", ["pressure_mpa", "friction_n", "test"])
    assert read_friction_table(c, m)["friction_n"].tolist() == [40.0, 80.0]


def test_read_table_handles_xlsx_and_inline_comments(tmp_path):
    from openpyxl import Workbook

    wb = Workbook()
    ws = wb.active
    for row in (["Inflation test, tube 3"], ["Pressure (bar)", "Outer diameter (mm)"],
                [2.0, 8.5], [4.0, 8.8]):
        ws.append(row)
    wb.save(tmp_path / "t.xlsx")
    df = read_table(tmp_path / "t.xlsx", ["pressure_mpa", "outer_diameter_mm"])
    assert df["pressure_mpa"].tolist() == pytest.approx([0.2, 0.4], rel=1e-12)  # 1 bar = 0.1 MPa
    assert df.attrs["metadata"] == ["Inflation test, tube 3"]


def test_xlsx_without_openpyxl_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "openpyxl", None)
    with pytest.raises(InputError, match=r"excel.xlsx: reading Excel needs openpyxl: pip install "
                                         r"'exofric\[xlsx\]'$"):
        read_raw_log(DATA / "excel.xlsx")


def test_no_warning_on_the_clean_corpus():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        reduce_log(read_raw_log(DATA / "labview.lvm"))
