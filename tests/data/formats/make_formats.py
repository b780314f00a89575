"""Write the real-format corpus of tests/test_io_formats.py (issue 31): one short virtual-rig log
in every dialect an instrument writes, each made with the real writer.

Run once from the repository root (``.venv/bin/python tests/data/formats/make_formats.py``);
the files are committed. Every file holds the same samples as ``plain.csv`` (time s, pressure
MPa, force N, displacement mm, rounded to 9 significant digits there), written in another
format, unit, encoding or header spelling:

=========================  =========================================================================
``plain.csv``              the reference: ``time_s,pressure_mpa,force_n,displacement_mm``
``semicolon_comma.csv``    pandas ``to_csv(sep=';', decimal=',')``, ``Name (unit)`` headers, kPa
``brackets.tsv``           tab-separated, ``Name [unit]`` headers, bar and lbf
``units_row.csv``          a second header row of units (``s, kPa, kgf, um``)
``utf16_bom.csv``          UTF-16 with a byte-order mark (Python's ``utf-16`` codec)
``utf16_nobom.txt``        UTF-16-LE without a byte-order mark, tab-separated
``latin1.csv``             Latin-1: a preamble line with ``ü`` and ``Displacement (µm)``
``bluehill.csv``           an Instron Bluehill-style export: quoted preamble, ``(sec)`` units row
``labview.lvm``            LabVIEW LVM (NI's documented layout): two header blocks ending in
                           ``***End_of_Header***``, ``Separator Tab``, ``Decimal_Separator ,``,
                           ``X_Columns One``, ``Y_Unit_Label kPa N mm``
``labview_nox.lvm``        LVM with ``X_Columns No``: time from ``X0`` and ``Delta_X``
``ni.tdms``                npTDMS ``TdmsWriter``: channels ``Pressure`` (``unit_string`` psi),
                           ``Force`` (N), ``Displacement`` (mm), waveform timing
                           (``wf_increment``, ``wf_start_offset``, ``wf_start_time``), no time
                           channel
``log.parquet``            pyarrow, ``time_ms``, ``pressure_bar``, ``force_kn``, ``displacement_m``
``excel.xlsx``             openpyxl: a title row, ``Name (unit)`` headers, MPa
=========================  =========================================================================

Unit factors come from their SI definitions (1 psi = 6894.757293168361 Pa, 1 lbf =
4.4482216152605 N, 1 kgf = 9.80665 N, 1 bar = 1e5 Pa), written here, not taken from exofric.
"""

from __future__ import annotations

import datetime as dt
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
PSI_PA = 6894.757293168361
LBF_N = 4.4482216152605
KGF_N = 9.80665
BAR_PA = 1e5
RATE_HZ = 20.0


def base_log() -> pd.DataFrame:
    """The short virtual-rig log (s, MPa, N, mm), rounded to 9 significant digits."""
    from exofric.friction import RawRigConfig, simulate_raw_log

    cfg = RawRigConfig(sample_rate_hz=RATE_HZ, replicates=1, pull_mm=5.0, settle_s=1.5,
                       rest_s=1.0)
    log = simulate_raw_log([0.2, 0.5], [80.0, 200.0], 0.7, config=cfg, seed=3).to_frame()
    out = pd.DataFrame({"time_s": np.arange(len(log)) / RATE_HZ})
    for c in ("pressure_mpa", "force_n", "displacement_mm"):
        out[c] = [float(f"{v:.9g}") for v in log[c].to_numpy()]
    return out


def _scaled(log: pd.DataFrame, t: float, p: float, f: float, d: float) -> list[np.ndarray]:
    return [log["time_s"].to_numpy() * t, log["pressure_mpa"].to_numpy() * p,
            log["force_n"].to_numpy() * f, log["displacement_mm"].to_numpy() * d]


def _rows(cols: list[np.ndarray], sep: str, decimal: str = ".") -> list[str]:
    out = []
    for row in zip(*cols, strict=True):
        cells = [repr(float(v)) for v in row]
        out.append(sep.join(c.replace(".", decimal) for c in cells))
    return out


def _lvm(cols: list[np.ndarray], decimal: str, *, x_columns: bool) -> str:
    """An LVM file as NI documents it: a file header block and a segment header block, each
    ending in ``***End_of_Header***``, then the channel-name row and the samples."""
    n = len(cols[0])
    dx = f"{1 / RATE_HZ:.6f}".replace(".", decimal)
    x0 = "0.0000000000000000E+0".replace(".", decimal)
    head = ["LabVIEW Measurement\t", "Writer_Version\t2", "Reader_Version\t2",
            "Separator\tTab", f"Decimal_Separator\t{decimal}", "Multi_Headings\tNo",
            f"X_Columns\t{'One' if x_columns else 'No'}", "Time_Pref\tRelative",
            "Operator\texofric", "Date\t2026/11/20", "Time\t10:00:00", "***End_of_Header***",
            "", "Channels\t3\t\t\t", f"Samples\t{n}\t{n}\t{n}\t",
            "Date\t2026/11/20\t2026/11/20\t2026/11/20\t",
            "Time\t10:00:00\t10:00:00\t10:00:00\t", "Y_Unit_Label\tkPa\tN\tmm\t",
            "X_Dimension\tTime\tTime\tTime\t", f"X0\t{x0}\t{x0}\t{x0}\t",
            f"Delta_X\t{dx}\t{dx}\t{dx}\t", "***End_of_Header***",
            ("X_Value\t" if x_columns else "") + "Pressure\tForce\tDisplacement\tComment"]
    return "\r\n".join(head + _rows(cols, "\t", decimal)) + "\r\n"


def write_all() -> list[Path]:
    log = base_log()
    written: list[Path] = []

    def put(name: str, data: bytes) -> None:
        (HERE / name).write_bytes(data)
        written.append(HERE / name)

    # the reference
    plain = log.to_csv(index=False, lineterminator="\n", float_format="%.17g")
    put("plain.csv", plain.encode())
    # pandas with ; and decimal commas, Name (unit) headers, kPa
    kpa = pd.DataFrame(dict(zip(["Time (s)", "Pressure (kPa)", "Force (N)",
                                 "Displacement (mm)"], _scaled(log, 1, 1e3, 1, 1), strict=True)))
    put("semicolon_comma.csv", kpa.to_csv(index=False, sep=";", decimal=",",
                                          lineterminator="\n", float_format="%.17g").encode())
    # tab, Name [unit], bar and lbf
    bar = _scaled(log, 1, 1e6 / BAR_PA, 1 / LBF_N, 1)
    put("brackets.tsv", ("Time [s]\tPressure [bar]\tForce [lbf]\tDisplacement [mm]\n"
                         + "\n".join(_rows(bar, "\t")) + "\n").encode())
    # units row: s, kPa, kgf, um
    kgf = _scaled(log, 1, 1e3, 1 / KGF_N, 1e3)
    put("units_row.csv", ("Time,Pressure,Force,Displacement\ns,kPa,kgf,um\n"
                          + "\n".join(_rows(kgf, ",")) + "\n").encode())
    # UTF-16 with and without BOM
    put("utf16_bom.csv", plain.replace("time_s", "Time (s)").encode("utf-16"))
    tsv = log.to_csv(index=False, sep="\t", lineterminator="\r\n", float_format="%.17g")
    put("utf16_nobom.txt", tsv.encode("utf-16-le"))
    # Latin-1: a preamble with a non-ASCII name, displacement in µm
    um = _scaled(log, 1, 1, 1, 1e3)
    text = ("Operator: Müller\nRig: B2\n\nTime (s),Pressure (MPa),Force (N),Displacement (µm)\n"
            + "\n".join(_rows(um, ",")) + "\n")
    put("latin1.csv", text.encode("latin-1"))
    # Instron Bluehill-style export: quoted metadata block, header, units row in parentheses
    cols = _scaled(log, 1, 1e3, 1, 1)
    lines = ['"Results Table 1"', '"Specimen label","ring-A"', '"Test date","2026-11-20"',
             '"Rate 1","2.00000","mm/s"', "", '"Time","Pressure","Load","Extension"',
             '"(sec)","(kPa)","(N)","(mm)"']
    lines += [",".join(f'"{c}"' for c in r.split(",")) for r in _rows(cols, ",")]
    put("bluehill.csv", ("\r\n".join(lines) + "\r\n").encode())
    # LabVIEW LVM (tab separated): X_Columns One with decimal commas; X_Columns No (time from
    # X0 + i Delta_X) with decimal points
    lvm_cols = _scaled(log, 1, 1e3, 1, 1)
    put("labview.lvm", _lvm(lvm_cols, ",", x_columns=True).encode())
    put("labview_nox.lvm", _lvm(lvm_cols[1:], ".", x_columns=False).encode())
    # NI TDMS, no time channel: waveform timing; pressure in psi by unit_string
    from nptdms import ChannelObject, GroupObject, RootObject, TdmsWriter

    wf = {"wf_increment": 1 / RATE_HZ, "wf_start_offset": 0.0,
          "wf_start_time": np.datetime64(dt.datetime(2026, 11, 20, 10, 0, 0)),
          "wf_xunit_string": "s"}
    psi, force, disp = _scaled(log, 1, 1e6 / PSI_PA, 1, 1)[1:]
    with TdmsWriter(HERE / "ni.tdms") as w:
        w.write_segment([
            RootObject(properties={"operator": "exofric", "rig": "B2"}),
            GroupObject("Rig", properties={"set points": "0.2, 0.5 MPa"}),
            ChannelObject("Rig", "Pressure", psi, properties={**wf, "unit_string": "psi"}),
            ChannelObject("Rig", "Force", force, properties={**wf, "unit_string": "N"}),
            ChannelObject("Rig", "Displacement", disp, properties={**wf, "unit_string": "mm"}),
        ])
    written.append(HERE / "ni.tdms")
    # Parquet: ms, bar, kN, m
    pq = pd.DataFrame(dict(zip(["time_ms", "pressure_bar", "force_kn", "displacement_m"],
                               _scaled(log, 1e3, 1e6 / BAR_PA, 1e-3, 1e-3), strict=True)))
    pq.to_parquet(HERE / "log.parquet", index=False)
    written.append(HERE / "log.parquet")
    # Excel through openpyxl: a title row, then Name (unit) headers
    from openpyxl import Workbook

    wb = Workbook()
    ws = wb.active
    ws.append(["Friction rig B2, virtual log"])
    ws.append([])
    ws.append(["Time (s)", "Pressure (MPa)", "Force (N)", "Displacement (mm)"])
    for row in zip(*_scaled(log, 1, 1, 1, 1), strict=True):
        ws.append([float(v) for v in row])
    wb.save(HERE / "excel.xlsx")
    written.append(HERE / "excel.xlsx")
    return written


if __name__ == "__main__":
    for p in write_all():
        print(f"{p.name}: {p.stat().st_size} bytes")
