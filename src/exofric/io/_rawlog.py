"""Raw rig logs: time series of pressure, force and displacement from CSV, Parquet or NI TDMS.

A raw log is what the rig's logger wrote: one row per sample, a ``time_<unit>`` column, a
``pressure_<unit>`` and a ``force_<unit>`` column and optionally ``displacement_<unit>``, with
the unit in the header suffix (case-insensitive): pressure in MPa, kPa, Pa, bar, mbar or psi;
force in N, kN, kgf or lbf; displacement in mm, m, um or in; time in s, ms or min. Other columns
(setpoints, command terms) are ignored but listed. A ``--columns`` mapping
(:func:`parse_column_map`) names the columns of a log whose headers say something else.

:func:`read_raw_log` converts every channel to exofric's units (s, MPa, N, mm) with :mod:`pint`
(no hand-written factors) and refuses a bad log with one line that starts with the file name and
names the column and the time range: an unknown unit, a missing or doubled quantity, a
non-numeric cell, NaN/empty/infinite samples, time that does not increase, a gap in time. Nothing
is silently dropped or repaired. Lines starting with ``#`` (CSV), the key/value metadata
(Parquet) or the properties (TDMS) are kept as provenance in ``attrs["metadata"]``.

:func:`write_raw_log` writes a log (CSV or Parquet) that reads back bit for bit.
"""

from __future__ import annotations

import csv
import functools
import io as _io
import json
import math
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric.defaults import RAWLOG_MAX_GAP_FACTOR, RAWLOG_MIN_SAMPLES
from exofric.errors import InputError
from exofric.io._files import atomic_path

if TYPE_CHECKING:
    import pandas as pd
    import pint

__all__ = ["RAW_QUANTITIES", "parse_column_map", "read_raw_log", "write_raw_log"]

#: The columns :func:`read_raw_log` returns and their units (exofric's units: s, MPa, N, mm).
RAW_QUANTITIES: dict[str, str] = {
    "time_s": "s", "pressure_mpa": "MPa", "force_n": "N", "displacement_mm": "mm",
}

#: quantity -> unit spelling (lower case, as in a header suffix) -> (unit as shown, pint unit).
#: Only spellings live here; every conversion factor comes from pint.
_UNITS: dict[str, dict[str, tuple[str, str]]] = {
    "time": {"s": ("s", "second"), "ms": ("ms", "millisecond"), "min": ("min", "minute")},
    "pressure": {
        "mpa": ("MPa", "megapascal"), "kpa": ("kPa", "kilopascal"), "pa": ("Pa", "pascal"),
        "bar": ("bar", "bar"), "mbar": ("mbar", "millibar"), "psi": ("psi", "psi"),
    },
    "force": {
        "n": ("N", "newton"), "kn": ("kN", "kilonewton"), "kgf": ("kgf", "kilogram_force"),
        "lbf": ("lbf", "pound_force"),
    },
    "displacement": {
        "mm": ("mm", "millimeter"), "m": ("m", "meter"), "um": ("um", "micrometer"),
        "in": ("in", "inch"),
    },
}
#: quantity -> the column :func:`read_raw_log` returns it in (a key of RAW_QUANTITIES).
_CANONICAL = {"time": "time_s", "pressure": "pressure_mpa", "force": "force_n",
              "displacement": "displacement_mm"}
_REQUIRED = ("time", "pressure", "force")
_READ_SUFFIXES = (".csv", ".txt", ".parquet", ".pq", ".tdms")
_WRITE_SUFFIXES = (".csv", ".txt", ".parquet", ".pq")
#: Parquet schema-metadata key holding the metadata lines (a JSON list of strings).
_META_KEY = b"exofric.metadata"
#: Cells read as NaN (lower case; pandas' defaults): reported as NaN samples, not as text.
_NA_TOKENS = frozenset({
    "", "nan", "-nan", "+nan", "na", "n/a", "#n/a", "#n/a n/a", "#na", "-1.#ind", "-1.#qnan",
    "1.#ind", "1.#qnan", "<na>", "null", "none",
})
_EXAMPLE = "--columns time=t,pressure_kpa=P1,force_n=Fx"


class _MissingColumn(InputError):
    """A required quantity or a mapped header is absent (a TDMS reader tries the next group)."""


@dataclass(frozen=True)
class _Channel:
    """One resolved column: its quantity, unit spelling (``"kpa"``) and header as found."""

    quantity: str
    unit: str
    header: str
    index: int


@dataclass
class _Raw:
    """What a format reader found, before conversion and checks."""

    channels: dict[str, _Channel]
    values: dict[str, np.ndarray]
    ignored: list[str]
    metadata: list[str]
    row: Callable[[int], str] = field(default=lambda i: f"row {i + 1}")


# ---------------------------------------------------------------------------------------------
# Column names and the --columns mapping.


def _known(quantity: str) -> str:
    return ", ".join(_UNITS[quantity])


def _split(name: str) -> tuple[str, str | None] | None:
    """``"Pressure_kPa"`` -> ``("pressure", "kpa")``; ``"time"`` -> ``("time", None)``;
    a name whose part before the last ``_`` is not a quantity -> None."""
    k = name.strip().lower()
    if k in _UNITS:
        return k, None
    q, _, u = k.rpartition("_")
    return (q, u) if q in _UNITS else None


def _key(key: str, item: str, where: str) -> tuple[str, str]:
    """A mapping key -> (quantity, unit spelling), or InputError naming ``item``."""
    parts = _split(key)
    if parts is None:
        raise InputError(f"{where}: unknown quantity in {item!r} (keys: time, time_<unit>, "
                         "pressure_<unit>, force_<unit>, displacement_<unit>)")
    q, u = parts
    if u is None:
        if q != "time":
            raise InputError(f"{where}: {item!r} needs a unit: {q}_<unit> with unit one of "
                             f"{_known(q)}")
        u = "s"
    if u not in _UNITS[q]:
        raise InputError(f"{where}: unknown {q} unit {u!r} in {item!r} (known: {_known(q)})")
    return q, u


def parse_column_map(text: str) -> dict[str, str]:
    """Parse a ``--columns`` mapping: which header of a raw log holds which quantity, in which unit.

    Parameters
    ----------
    text : str
        Comma-separated ``KEY=HEADER`` items, e.g. ``"time=t,pressure_kpa=P1,force_n=Fx"``. A
        key is ``time`` (seconds), ``time_<unit>``, ``pressure_<unit>``, ``force_<unit>`` or
        ``displacement_<unit>`` (case-insensitive; units as in :func:`read_raw_log`). A header
        is written as in the file (spaces allowed, stripped around it; no ``,`` or ``=``). An
        empty text is an empty mapping.

    Returns
    -------
    dict of str to str
        Canonical lower-case key (``time`` becomes ``time_s``) -> header, in the given order.

    Raises
    ------
    InputError
        One line starting with ``--columns:`` naming the item: a malformed item (no ``=``,
        empty key or header), an unknown quantity or unit, a pressure/force/displacement key
        without a unit, a repeated key, two keys for one quantity, one header named twice.

    Examples
    --------
    >>> parse_column_map("time=t, pressure_kPa = P 1 ,force_n=Fx")
    {'time_s': 't', 'pressure_kpa': 'P 1', 'force_n': 'Fx'}
    >>> parse_column_map("pressure=P1")
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: --columns: 'pressure=P1' needs a unit: pressure_<unit> with unit \
one of mpa, kpa, pa, bar, mbar, psi
    """
    out: dict[str, str] = {}
    if not text.strip():
        return out
    by_quantity: dict[str, str] = {}
    by_header: dict[str, str] = {}
    for raw in text.split(","):
        item = raw.strip()
        key, eq, value = item.partition("=")
        if not eq or not key.strip() or not value.strip():
            raise InputError(f"--columns: malformed item {item!r} (expected KEY=HEADER, e.g. "
                             "pressure_kpa=P1)")
        q, u = _key(key, item, "--columns")
        canon = f"{q}_{u}"
        header = value.strip()
        if canon in out:
            raise InputError(f"--columns: key {canon!r} is given twice ({item!r})")
        if q in by_quantity:
            raise InputError(f"--columns: {item!r}: {q} is already mapped by "
                             f"{by_quantity[q]!r}; give one column per quantity")
        if header in by_header:
            raise InputError(f"--columns: {item!r}: header {header!r} is already mapped by "
                             f"{by_header[header]!r}")
        out[canon] = header
        by_quantity[q] = item
        by_header[header] = item
    return out


def _headers_text(headers: Sequence[str], limit: int = 20) -> str:
    shown = ", ".join(repr(h) for h in headers[:limit]) or "none"
    return shown + (f" ... ({len(headers) - limit} more)" if len(headers) > limit else "")


def _checked_mapping(columns: Mapping[str, str] | None, name: str) -> dict[str, tuple[str, str]]:
    """A user mapping -> {quantity: (unit, header)}; bad keys -> InputError naming the file."""
    out: dict[str, tuple[str, str]] = {}
    for key, header in (columns or {}).items():
        item = f"{key}={header}"
        q, u = _key(str(key), item, f"{name}: columns")
        if q in out:
            raise InputError(f"{name}: columns: {item!r}: {q} is already mapped")
        if not str(header).strip():
            raise InputError(f"{name}: columns: {item!r} names no header")
        out[q] = (u, str(header).strip())
    return out


def _resolve(headers: Sequence[str], mapping: dict[str, tuple[str, str]], name: str,
             need: Sequence[str] = _REQUIRED, what: str = "column"
             ) -> tuple[dict[str, _Channel], list[str]]:
    """Find each quantity's column: mapped ones by header, the others by their unit suffix."""
    found = [h.strip() for h in headers]
    channels: dict[str, _Channel] = {}
    for q, (u, header) in mapping.items():
        idx = [i for i, h in enumerate(found) if h == header]
        if not idx:
            idx = [i for i, h in enumerate(found) if h.lower() == header.lower()]
        if len(idx) != 1:
            how = "is not in the file" if not idx else "is in the file more than once"
            raise _MissingColumn(f"{name}: {what} {header!r} (named by --columns {q}_{u}="
                                 f"{header}) {how} ({what}s found: {_headers_text(found)})")
        channels[q] = _Channel(q, u, found[idx[0]], idx[0])
    used = {c.index for c in channels.values()}
    for q in _UNITS:
        if q in channels:
            continue
        good: list[tuple[int, str]] = []
        bad: list[tuple[int, str]] = []
        for i, h in enumerate(found):
            parts = _split(h)
            if i in used or parts is None or parts[0] != q or parts[1] is None:
                continue
            (good if parts[1] in _UNITS[q] else bad).append((i, parts[1]))
        same = [i for i, _ in good if found[i].lower() == found[good[0][0]].lower()]
        if len(same) > 1:  # one header twice: --columns cannot choose between them
            raise InputError(f"{name}: {what} {found[same[0]]!r} is in the file "
                             f"{len(same)} times ({what}s {', '.join(str(i + 1) for i in same)}"
                             f"); rename all but one")
        if len(good) > 1:
            names = " and ".join(repr(found[i]) for i, _ in good)
            raise InputError(f"{name}: two {q} {what}s, {names}: keep one, or choose one with "
                             f"--columns, e.g. --columns {found[good[0][0]].lower()}="
                             f"{found[good[0][0]]}")
        if good:
            i, u = good[0]
            channels[q] = _Channel(q, u, found[i], i)
        elif bad:
            i, u = bad[0]
            raise InputError(f"{name}: {what} {found[i]!r} has an unknown {q} unit {u!r} "
                             f"(known: {_known(q)}; or name the {what} with --columns)")
    for q in need:
        if q not in channels:
            raise _MissingColumn(
                f"{name}: no {q} {what} (a name {q}_<unit>, unit one of {_known(q)}; "
                f"{what}s found: {_headers_text(found)}); name the {what}s with --columns, "
                f"e.g. {_EXAMPLE}")
    used = {c.index for c in channels.values()}
    return channels, [h for i, h in enumerate(found) if i not in used]


# ---------------------------------------------------------------------------------------------
# Units (pint, loaded on first use: importing it takes a noticeable fraction of a second).


@functools.cache
def _registry() -> pint.UnitRegistry:
    import pint

    return pint.UnitRegistry()


@functools.cache
def _factor(quantity: str, unit: str) -> float:
    """Multiplier from ``unit`` (a spelling of ``_UNITS[quantity]``) to exofric's unit, by pint."""
    ureg = _registry()
    src = ureg.Unit(_UNITS[quantity][unit][1])
    dst = ureg.Unit(RAW_QUANTITIES[_CANONICAL[quantity]])
    if src.dimensionality != dst.dimensionality:  # a wrong entry in _UNITS, not user input
        raise InputError(f"{quantity} unit {unit!r} is not a {quantity} "
                         f"({src.dimensionality} vs {dst.dimensionality})")
    return float(ureg.Quantity(1.0, src).to(dst).magnitude)


def _to_canonical(quantity: str, unit: str, values: np.ndarray) -> np.ndarray:
    if _CANONICAL[quantity] == f"{quantity}_{unit}":  # already in exofric's unit: no pint
        return values.astype(np.float64, copy=True)
    return values.astype(np.float64) * _factor(quantity, unit)


# ---------------------------------------------------------------------------------------------
# Cell values.


def _numeric(series: pd.Series, header: str, name: str, row: Callable[[int], str]
             ) -> np.ndarray:
    """A column as float64 (NaN for empty/NaN cells); a text cell -> InputError naming it."""
    import pandas as pd

    kind = series.dtype.kind
    if kind in "fiu":
        return series.to_numpy(dtype=np.float64, na_value=np.nan)
    text = series.astype("string").str.strip()
    num = pd.to_numeric(text, errors="coerce")
    bad = (num.isna() & text.notna() & ~text.str.lower().isin(_NA_TOKENS)).to_numpy(
        dtype=bool, na_value=False)
    if kind == "b" or bad.any():
        i = int(np.flatnonzero(bad)[0]) if bad.any() else 0
        raise InputError(f"{name}: {row(i)}, column {header!r} is not a number: "
                         f"{str(series.iloc[i])!r}")
    return num.to_numpy(dtype=np.float64, na_value=np.nan)


def _runs(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start and end (inclusive) indices of the runs of True in ``mask``."""
    edges = np.diff(np.concatenate(([0], mask.astype(np.int8), [0])))
    return np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1


def _time_decimals(t: np.ndarray) -> int:
    """Decimals that resolve the median time step (2 to 9)."""
    d = np.diff(t[np.isfinite(t)])
    d = d[d > 0]
    if not d.size:
        return 2
    step = float(np.median(d))
    dec = math.ceil(-math.log10(step) - 1e-6)
    if not math.isclose(step * 10.0**dec, round(step * 10.0**dec), rel_tol=1e-6):
        dec += 1
    return min(max(dec, 2), 9)


def _plural(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def _check(raw: _Raw, name: str, max_gap_factor: float) -> dict[str, np.ndarray]:
    """Convert to exofric's units and refuse NaN bursts, short logs, time going back, gaps."""
    n = len(raw.values["time"])
    if n < RAWLOG_MIN_SAMPLES:
        raise InputError(f"{name}: needs at least {RAWLOG_MIN_SAMPLES} samples, got {n}")
    out = {_CANONICAL[q]: _to_canonical(q, raw.channels[q].unit, raw.values[q])
           for q in _UNITS if q in raw.channels}
    t = out["time_s"]
    dec = _time_decimals(t)

    def label(q: str) -> str:
        h = raw.channels[q].header
        return _CANONICAL[q] + ("" if h.lower() == _CANONICAL[q] else f" (column {h!r})")

    for canon, vals in out.items():
        q = canon.split("_")[0]
        bad = ~np.isfinite(vals)
        if not bad.any():
            continue
        starts, ends = _runs(bad)
        inf = np.isinf(vals[bad])
        kind = "infinite" if inf.all() else ("NaN or infinite" if inf.any() else "NaN")
        s, e = int(starts[0]), int(ends[0])
        if q == "time":
            where = raw.row(s) if s == e else f"{raw.row(s)} to {raw.row(e)}"
        else:
            where = (f"{t[s]:.{dec}f} s" if s == e else f"{t[s]:.{dec}f} s to {t[e]:.{dec}f} s")
        first = ("the first" if len(starts) > 1 else "") + (" at " if s == e else " from ")
        raise InputError(f"{name}: {label(q)} is {kind} in {_plural(len(starts), 'burst')} "
                         f"({_plural(int(bad.sum()), 'sample')}), {first.strip()} {where}")
    dt = np.diff(t)
    back = np.flatnonzero(dt <= 0)
    if back.size:
        i = int(back[0])
        how = "repeats" if dt[i] == 0 else "decreases"
        raise InputError(f"{name}: {label('time')} is not increasing: it {how} from "
                         f"{t[i]:.{dec}f} s to {t[i + 1]:.{dec}f} s at {raw.row(i + 1)}"
                         f"{f' ({back.size} places)' if back.size > 1 else ''}")
    med = float(np.median(dt))
    gaps = np.flatnonzero(dt > max_gap_factor * med)
    if gaps.size:
        i = int(gaps[0])
        more = f"; the first of {gaps.size} gaps" if gaps.size > 1 else ""
        raise InputError(f"{name}: gap in time_s from {t[i]:.{dec}f} s to {t[i + 1]:.{dec}f} s "
                         f"({dt[i]:.4g} s; median step {med:.4g} s; a step over max_gap_factor "
                         f"{max_gap_factor:g} x the median is a gap{more})")
    return out


# ---------------------------------------------------------------------------------------------
# Formats.


def _meta_line(line: bytes) -> str:
    """A ``#`` comment line without the ``#`` and one following space."""
    body = line.strip()[1:]
    return (body[1:] if body.startswith(b" ") else body).rstrip().decode("utf-8")


#: A line of spaces/tabs after a newline (pandas skips empty lines itself but reads some of
#: these as NaN rows). The literal "\n" prefix makes the search fast: 0.05 s for 76 MB, where a
#: ``^`` pattern in MULTILINE mode takes 0.3 s.
_WS_LINE = re.compile(rb"\n[ \t]+(?=\n|$)")
_LEADING_WS_LINE = re.compile(rb"[ \t]+(?:\n|$)")
_HEADER_LINE = re.compile(rb"^[ \t]*[^#\s][^\n]*", re.MULTILINE)


def _drop_comments(text: bytes) -> tuple[bytes, list[str]]:
    """``text`` without its ``#`` lines, and those lines (:func:`_meta_line`), in order.

    Looks only at the ``#`` characters (bytes.find, no per-line loop): a log of a million rows
    and no comments costs one scan.
    """
    pieces: list[bytes] = []
    meta: list[str] = []
    start = 0
    pos = text.find(b"#")
    while pos != -1:
        ls = text.rfind(b"\n", 0, pos) + 1
        le = text.find(b"\n", pos)
        le = len(text) if le == -1 else le
        if not text[ls:pos].strip(b" \t"):
            meta.append(_meta_line(text[ls:le]))
            pieces.append(text[start:ls])
            start = le + 1
        pos = text.find(b"#", le)
    pieces.append(text[start:])
    return b"".join(pieces), meta


def _read_csv(p: Path, name: str, mapping: dict[str, tuple[str, str]]) -> _Raw:
    # Bytes, not str: pandas parses a BytesIO about twice as fast as a StringIO (no re-encoding)
    import pandas as pd

    try:
        text = p.read_bytes().removeprefix(b"\xef\xbb\xbf")
    except OSError as exc:
        raise InputError(f"{name}: cannot read ({exc.strerror or exc.__class__.__name__})"
                         ) from None
    if b"\r" in text:  # Windows (or old Mac) line ends
        text = text.replace(b"\r\n", b"\n").replace(b"\r", b"\n")
    m = _HEADER_LINE.search(text)  # the first line that is neither blank nor a comment
    if m is None:
        raise InputError(f"{name}: no header row (expected time_s, pressure_<unit>, "
                         "force_<unit>)")
    head_line = text.count(b"\n", 0, m.start()) + 1
    body = text[m.end() + 1:]
    try:
        header = m.group(0).decode("utf-8")
        metadata = _drop_comments(text[:m.start()])[1]
        data, more = _drop_comments(body)
    except UnicodeDecodeError as exc:
        raise InputError(f"{name}: cannot read as UTF-8 text ({exc.reason})") from None
    metadata += more
    while (lead := _LEADING_WS_LINE.match(data)) is not None and lead.end() > 0:
        data = data[lead.end():]
    if _WS_LINE.search(data):
        data = _WS_LINE.sub(b"", data)
    sep = next((s for s in (",", "\t", ";") if s in header), None)
    headers = next(csv.reader([header], delimiter=sep)) if sep else header.split()
    channels, ignored = _resolve(headers, mapping, name)

    @functools.cache
    def lines() -> list[int]:  # file line of each data row, computed only for a message
        return [head_line + 1 + k for k, line in enumerate(body.split(b"\n"))
                if line.strip(b" \t") and not line.lstrip(b" \t").startswith(b"#")]

    def row(i: int) -> str:
        return f"data row {i + 1} (line {lines()[i]})"

    try:
        df = pd.read_csv(_io.BytesIO(data), sep=sep or r"\s+", header=None,
                         names=list(range(len(headers))), skipinitialspace=True,
                         encoding="utf-8")
    except pd.errors.EmptyDataError:
        df = pd.DataFrame({i: pd.Series([], dtype=float) for i in range(len(headers))})
    except UnicodeDecodeError as exc:
        raise InputError(f"{name}: cannot read as UTF-8 text ({exc.reason})") from None
    except pd.errors.ParserError as exc:
        msg = str(exc).strip().splitlines()[-1]
        found = re.search(r"line (\d+), saw (\d+)", msg)
        if found and int(found.group(1)) <= len(lines()):
            raise InputError(f"{name}: {row(int(found.group(1)) - 1)} has {found.group(2)} "
                             f"fields, the header has {len(headers)}") from None
        raise InputError(f"{name}: malformed CSV ({msg})") from None
    values = {q: _numeric(df[c.index], c.header, name, row) for q, c in channels.items()}
    return _Raw(channels, values, ignored, metadata, row)


def _read_parquet(p: Path, name: str, mapping: dict[str, tuple[str, str]]) -> _Raw:
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        raise InputError(f"{name}: reading Parquet needs pyarrow: pip install pyarrow") from None
    try:
        schema = pq.read_schema(p)
        headers = [str(c) for c in schema.names]
        channels, ignored = _resolve(headers, mapping, name)
        table = pq.read_table(p, columns=[schema.names[c.index] for c in channels.values()])
    except (pa.ArrowException, OSError) as exc:
        msg = (str(exc).strip().splitlines() or [exc.__class__.__name__])[0]
        raise InputError(f"{name}: not a readable Parquet file ({msg})") from None
    metadata: list[str] = []
    for key, value in (schema.metadata or {}).items():
        if key == _META_KEY:
            metadata.extend(str(s) for s in json.loads(value.decode("utf-8")))
        elif key not in (b"pandas", b"ARROW:schema"):
            metadata.append(f"{key.decode('utf-8', 'replace')}: "
                            f"{value.decode('utf-8', 'replace')}")
    values = {q: _numeric(table.column(schema.names[c.index]).to_pandas(), c.header, name,
                          lambda i: f"row {i + 1}") for q, c in channels.items()}
    return _Raw(channels, values, ignored, metadata)


def _one_line(value: Any) -> str:
    return " ".join(str(value).split("\n"))


def _read_tdms(p: Path, name: str, mapping: dict[str, tuple[str, str]]) -> _Raw:
    try:
        import nptdms
    except ImportError:
        raise InputError(f"{name}: reading TDMS needs npTDMS: pip install 'exofric[tdms]'"
                         ) from None
    try:
        tdms = nptdms.TdmsFile.read(p)
    except Exception as exc:  # npTDMS raises ValueError, KeyError, struct.error... on bad files
        raise InputError(f"{name}: not a readable TDMS file ({exc.__class__.__name__}: "
                         f"{_one_line(exc)})") from None
    groups = tdms.groups()
    missing: list[_MissingColumn] = []
    for group in groups:
        chans = group.channels()
        try:
            channels, ignored = _resolve([c.name for c in chans], mapping, name,
                                         need=("pressure", "force"), what="channel")
        except _MissingColumn as exc:
            missing.append(exc)
            continue
        break
    else:
        if len(missing) == 1:
            raise missing[0]
        listing = "; ".join(f"{g.name!r}: {_headers_text([c.name for c in g.channels()], 8)}"
                            for g in groups)
        raise InputError(f"{name}: no TDMS group has pressure and force channels (groups: "
                         f"{listing or 'none'}); name the channels with --columns, e.g. "
                         f"{_EXAMPLE}")
    values: dict[str, np.ndarray] = {}
    for q, c in channels.items():
        data = np.asarray(chans[c.index][:])
        if data.dtype.kind not in "fiu":
            raise InputError(f"{name}: channel {c.header!r} is not numeric ({data.dtype})")
        values[q] = data
    pressure = chans[channels["pressure"].index]
    if "time" not in channels:
        props = pressure.properties
        if "wf_increment" not in props:
            raise InputError(
                f"{name}: group {group.name!r} has no time channel (time_<unit>, unit one of "
                f"{_known('time')}) and pressure channel {pressure.name!r} has no waveform "
                "timing (wf_increment); add a time channel or name one with --columns time=NAME")
        if "wf_start_offset" in props:
            t = np.asarray(pressure.time_track(), dtype=np.float64)
        else:
            t = float(props["wf_increment"]) * np.arange(len(pressure), dtype=np.float64)
        xunit = str(props.get("wf_xunit_string", "s")).strip().lower() or "s"
        if xunit not in _UNITS["time"]:
            raise InputError(f"{name}: channel {pressure.name!r} has an unknown time unit "
                             f"{xunit!r} in wf_xunit_string (known: {_known('time')})")
        channels["time"] = _Channel("time", xunit, f"{pressure.name} waveform time", -1)
        values["time"] = t
    lengths = {channels[q].header: len(v) for q, v in values.items()}
    if len(set(lengths.values())) > 1:
        raise InputError(f"{name}: channels have different lengths: "
                         + ", ".join(f"{h} {n}" for h, n in lengths.items()))
    metadata = [f"{k}: {_one_line(v)}" for k, v in tdms.properties.items()]
    metadata += [f"{group.name}/{k}: {_one_line(v)}" for k, v in group.properties.items()]
    for q in _UNITS:
        if q in channels and channels[q].index >= 0:
            ch = chans[channels[q].index]
            metadata += [f"{group.name}/{ch.name}/{k}: {_one_line(v)}"
                         for k, v in ch.properties.items()]
    return _Raw(channels, values, ignored, metadata)


def _check_gap_factor(max_gap_factor: float) -> float:
    try:
        f = float(max_gap_factor)
    except (TypeError, ValueError):
        raise InputError(f"max_gap_factor must be a number > 1, got {max_gap_factor!r}"
                         ) from None
    if not f > 1.0:  # NaN too
        raise InputError(f"max_gap_factor must be > 1 (a multiple of the median time step), "
                         f"got {max_gap_factor!r}")
    return f


def read_raw_log(path: str | Path, columns: Mapping[str, str] | None = None, *,
                 max_gap_factor: float = RAWLOG_MAX_GAP_FACTOR) -> pd.DataFrame:
    """Read a raw rig log (CSV, Parquet or NI TDMS), check it and convert it to s, MPa, N, mm.

    Columns are recognised by their header (stripped, case-insensitive) ``<quantity>_<unit>``:
    ``time_`` s, ms, min; ``pressure_`` mpa, kpa, pa, bar, mbar, psi; ``force_`` n, kn, kgf,
    lbf; optional ``displacement_`` mm, m, um, in. Units are converted with :mod:`pint`. Other
    columns are ignored (listed in ``attrs["ignored_columns"]``), and so is a column with an
    unknown unit when its quantity has another column with a known one. CSV (``.csv``,
    ``.txt``; comma, tab, semicolon or whitespace separated): lines starting with ``#`` are
    metadata. TDMS: the first group with pressure and force channels; without a time channel
    the pressure channel's waveform timing (``wf_increment``, ``wf_start_offset``) is used.

    Parameters
    ----------
    path : str or Path
        The log: ``.csv``, ``.txt``, ``.parquet``, ``.pq`` or ``.tdms``.
    columns : mapping of str to str, optional
        Canonical key -> header for logs whose headers say something else, as returned by
        :func:`parse_column_map` (e.g. ``{"time_s": "t", "pressure_kpa": "P1"}``); the key's
        unit is the column's unit. Quantities not named are found by their headers.
    max_gap_factor : float
        A time step longer than this multiple of the median time step (unitless, > 1) is a gap.

    Returns
    -------
    pandas.DataFrame
        Float64 columns ``time_s`` (s), ``pressure_mpa`` (MPa), ``force_n`` (N) and, when the
        log has one, ``displacement_mm`` (mm), in file order. ``attrs``: ``"source"`` (file
        name), ``"metadata"`` (list of str: ``#`` lines without the ``#``, Parquet key/value
        metadata or TDMS properties as ``key: value``), ``"units"`` (canonical column -> unit
        as found, e.g. ``{"pressure_mpa": "kPa"}``), ``"columns"`` (canonical column -> header
        as found) and ``"ignored_columns"`` (the other headers).

    Raises
    ------
    InputError
        One line starting with the file name: unsupported suffix, missing file, unknown unit,
        missing or doubled quantity, a ``columns`` header not in the file, fewer than
        ``RAWLOG_MIN_SAMPLES`` rows, a non-numeric cell (row and column), NaN/empty/infinite
        samples (the bursts and their time range), time not increasing (the two times and the
        row), a gap (its time range), TDMS without npTDMS installed; ``max_gap_factor <= 1``.

    Examples
    --------
    >>> import tempfile, numpy as np, pandas as pd
    >>> t = np.arange(25) * 0.01
    >>> log = pd.DataFrame({"time_s": t, "pressure_kpa": 100.0 + 10 * t, "force_lbf": 2.0 + t})
    >>> p = write_raw_log(Path(tempfile.mkdtemp()) / "run1.csv", log, ["rig: B2"])
    >>> df = read_raw_log(p)
    >>> list(df.columns), df.loc[0, ["pressure_mpa", "force_n"]].round(9).tolist()
    (['time_s', 'pressure_mpa', 'force_n'], [0.1, 8.896443231])
    >>> df.attrs["units"], df.attrs["metadata"]
    ({'time_s': 's', 'pressure_mpa': 'kPa', 'force_n': 'lbf'}, ['rig: B2'])
    >>> log.loc[5:7, "force_lbf"] = np.nan
    >>> read_raw_log(write_raw_log(p, log))
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: run1.csv: force_n (column 'force_lbf') is NaN in 1 burst \
(3 samples), from 0.05 s to 0.07 s
    """
    import pandas as pd

    gap = _check_gap_factor(max_gap_factor)
    p = Path(path)
    name = p.name
    suffix = p.suffix.lower()
    if suffix not in _READ_SUFFIXES:
        raise InputError(f"{name}: unsupported raw log type {p.suffix or '(no suffix)'!r} "
                         f"(supported: {', '.join(_READ_SUFFIXES)})")
    if not p.is_file():
        raise InputError(f"{path}: file not found")
    mapping = _checked_mapping(columns, name)
    reader = {".tdms": _read_tdms, ".parquet": _read_parquet, ".pq": _read_parquet}.get(
        suffix, _read_csv)
    raw = reader(p, name, mapping)
    out = _check(raw, name, gap)
    df = pd.DataFrame(out)
    df.attrs["source"] = name
    df.attrs["metadata"] = raw.metadata
    df.attrs["units"] = {_CANONICAL[q]: _UNITS[q][raw.channels[q].unit][0]
                         for q in _UNITS if q in raw.channels}
    df.attrs["columns"] = {_CANONICAL[q]: raw.channels[q].header
                           for q in _UNITS if q in raw.channels}
    df.attrs["ignored_columns"] = raw.ignored
    return df


def write_raw_log(path: str | Path, frame: pd.DataFrame, metadata: Sequence[str] = ()) -> Path:
    """Write a raw log atomically: CSV (``#`` metadata lines, header, rows) or Parquet.

    Columns are written as they are (unit-suffixed names such as ``pressure_kpa``; no
    conversion), without the index. CSV floats are written with ``%.17g``, so
    :func:`read_raw_log` gets the same bits back; NaN is an empty cell. Parquet keeps the
    metadata lines in the schema metadata, where :func:`read_raw_log` finds them.

    Parameters
    ----------
    path : str or Path
        The file: ``.csv`` or ``.txt`` (CSV) or ``.parquet`` or ``.pq``; parent directories
        are created.
    frame : pandas.DataFrame
        The samples, one row each; column names carry their unit (``time_s``,
        ``pressure_kpa``, ``force_lbf``...).
    metadata : sequence of str
        Provenance lines (no line breaks), written as ``# <line>`` at the top of a CSV.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    InputError
        Another suffix, or a metadata line with a line break.

    Examples
    --------
    >>> import tempfile, pandas as pd
    >>> log = pd.DataFrame({"time_s": [0.0, 0.1], "pressure_mpa": [0.1, 0.2], "force_n": [1, 2]})
    >>> p = write_raw_log(Path(tempfile.mkdtemp()) / "log.csv", log, ["operator: A"])
    >>> print(p.read_text(), end="")
    # operator: A
    time_s,pressure_mpa,force_n
    0,0.10000000000000001,1
    0.10000000000000001,0.20000000000000001,2
    """
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix not in _WRITE_SUFFIXES:
        raise InputError(f"{p.name}: write_raw_log writes {', '.join(_WRITE_SUFFIXES)}, "
                         f"not {p.suffix or '(no suffix)'!r}")
    lines = [str(m) for m in metadata]
    for i, line in enumerate(lines):
        if "\n" in line or "\r" in line:
            raise InputError(f"{p.name}: metadata line {i + 1} contains a line break: {line!r}")
    if suffix in (".csv", ".txt"):
        buf = _io.StringIO()
        for line in lines:
            buf.write(f"# {line}\n")
        frame.to_csv(buf, index=False, float_format="%.17g", lineterminator="\n")
        with atomic_path(p) as tmp:
            tmp.write_text(buf.getvalue(), encoding="utf-8")
        return p
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = pa.Table.from_pandas(frame, preserve_index=False)
    meta = dict(table.schema.metadata or {})
    meta[_META_KEY] = json.dumps(lines).encode("utf-8")
    with atomic_path(p) as tmp:
        pq.write_table(table.replace_schema_metadata(meta), tmp)
    return p
