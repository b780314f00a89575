"""One reader for every measured table: rig logs, friction, tensile, ring and inflation tests.

Instruments write tables in many dialects; :func:`read_measured_table` reads them all into one
DataFrame with exofric's canonical column names (``pressure_mpa``, ``force_n``...), converted
with :mod:`pint`, and records where each column came from:

* **formats**: CSV/TSV/``;``/whitespace-separated text (``.csv``, ``.tsv``, ``.txt``, ``.dat``;
  the separator and a decimal comma are detected), LabVIEW ``.lvm`` (NI's text format: header
  blocks ending in ``***End_of_Header***``, ``Separator``, ``Decimal_Separator``,
  ``X_Columns``, ``Y_Unit_Label``, ``Delta_X``), NI ``.tdms`` (channel ``unit_string``,
  waveform ``wf_increment``/``wf_start_offset``/``wf_start_time``), Parquet and Excel ``.xlsx``
  (openpyxl: ``pip install 'exofric[xlsx]'``);
* **encodings**: UTF-8 and UTF-16 with or without a byte-order mark, else Latin-1;
* **preambles**: lines before the table (an Instron Bluehill export's specimen block, ``#``
  comments) are kept as provenance in ``attrs["metadata"]``;
* **headers with units** in any common spelling: ``pressure_kpa``, ``Pressure (kPa)``,
  ``Pressure [kPa]``, ``Pressure / kPa``, or a second header row of units (``(kPa)`` or
  ``kPa``).

A unit that a ``columns`` mapping gives for a column whose file states another unit (a TDMS
``unit_string``, a unit in the header) is an error naming both: never a silent 6.9x.
"""

from __future__ import annotations

import csv
import functools
import hashlib
import io as _io
import math
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric.errors import InputError

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["is_raw_log", "read_measured_table", "TABLE_SUFFIXES"]

#: File suffixes :func:`read_measured_table` reads.
TABLE_SUFFIXES = (".csv", ".tsv", ".txt", ".dat", ".lvm", ".tdms", ".parquet", ".pq", ".xlsx",
                  ".xlsm")

#: Unit spellings (lower case, as in a header suffix) -> pint unit. Only spellings live here;
#: every factor comes from pint.
_PINT: dict[str, str] = {
    "mpa": "megapascal", "kpa": "kilopascal", "pa": "pascal", "hpa": "hectopascal",
    "bar": "bar", "mbar": "millibar", "psi": "psi",
    "n": "newton", "kn": "kilonewton", "kgf": "kilogram_force", "lbf": "pound_force",
    "mm": "millimeter", "cm": "centimeter", "m": "meter", "um": "micrometer", "in": "inch",
    "s": "second", "ms": "millisecond", "min": "minute", "h": "hour",
    "nm": "newton * meter", "pct": "percent",
}
#: Other spellings of those units (after lower-casing, removing spaces and µ -> u).
_ALIASES = {
    "sec": "s", "secs": "s", "second": "s", "seconds": "s", "msec": "ms", "minutes": "min",
    "inch": "in", "in.": "in", "inches": "in", "%": "pct", "percent": "pct", "n·m": "nm",
    "n*m": "nm", "n.m": "nm", "micron": "um", "microns": "um", "kgf.": "kgf",
}
_NA_TOKENS = frozenset({
    "", "nan", "-nan", "+nan", "na", "n/a", "#n/a", "#n/a n/a", "#na", "-1.#ind", "-1.#qnan",
    "1.#ind", "1.#qnan", "<na>", "null", "none",
})
_BRACKET = re.compile(r"^(?P<name>.*?)\s*(?:\((?P<p>[^()]*)\)|\[(?P<b>[^\[\]]*)\])\s*$")
_SLASH = re.compile(r"^(?P<name>.*\S)\s+/\s*(?P<u>[^\s/]+)$")
_NUMBER = re.compile(r"^[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?$")
_COMMA_NUMBER = re.compile(r"^[+-]?\d+,\d+(?:[eE][+-]?\d+)?$")


# ---------------------------------------------------------------------------------------------
# Units and header spellings.


def unit_token(text: str) -> str:
    """A unit as written (``"kPa"``, ``"(sec)"``, ``"µm"``) -> its lower-case token (``"kpa"``).

    Examples
    --------
    >>> unit_token(" (kPa) "), unit_token("sec"), unit_token("µm"), unit_token("[N]")
    ('kpa', 's', 'um', 'n')
    """
    u = text.strip().strip("()[]").strip().lower().replace("µ", "u").replace("μ", "u")
    u = u.replace(" ", "")
    return _ALIASES.get(u, u)


def _norm(name: str) -> str:
    """``" Outer Diameter "`` -> ``"outer_diameter"`` (lower case, blanks and dashes -> _)."""
    return re.sub(r"[\s\-]+", "_", name.strip().lower()).strip("_")


def split_key(key: str) -> tuple[str, str | None]:
    """``"pressure_kpa"`` -> ``("pressure", "kpa")``; a key without a known unit suffix -> (key,
    None).

    Examples
    --------
    >>> split_key("squeeze_force_n"), split_key("shore"), split_key("time_stamp")
    (('squeeze_force', 'n'), ('shore', None), ('time_stamp', None))
    """
    base, _, u = key.rpartition("_")
    if base and u in _PINT:
        return base, u
    return key, None


def header_key(header: str, unit: str | None = None, *, source: str = "") -> tuple[str, str | None]:
    """A header as found (and a unit stated beside it) -> (matching key, the file's unit).

    The key is lower case ``name_unit`` (``"Pressure (kPa)"`` -> ``"pressure_kpa"``), the
    file's unit the unit as written (``"kPa"``), or None when the file states none. A unit
    ``unit`` (a units row, a TDMS ``unit_string``, an LVM ``Y_Unit_Label``) that contradicts
    the header's own unit is an error naming both.

    Examples
    --------
    >>> header_key("Pressure (kPa)"), header_key("Force [N]"), header_key("time_s")
    (('pressure_kpa', 'kPa'), ('force_n', 'N'), ('time_s', 's'))
    >>> header_key("Load", "(lbf)"), header_key("P 1"), header_key("Time / s")
    (('load_lbf', 'lbf'), ('p_1', None), ('time_s', 's'))
    """
    h = header.strip()
    name, own = h, None
    m = _BRACKET.match(h)
    if m is not None and m.group("name").strip():
        u = m.group("p") if m.group("p") is not None else m.group("b")
        if u.strip():
            name, own = m.group("name"), u.strip()
    if own is None and (s := _SLASH.match(h)) is not None and unit_token(s.group("u")) in _PINT:
        name, own = s.group("name"), s.group("u")
    if own is not None:
        key = f"{_norm(name)}_{unit_token(own)}"
    else:
        key = _norm(h)
        if split_key(key)[1] is not None:
            own = h.rsplit("_", 1)[-1].strip()
    extra = unit.strip().strip("()[]").strip() if unit is not None else ""
    if extra:
        if own is not None and unit_token(extra) != unit_token(own):
            where = f"{source}: " if source else ""
            raise InputError(f"{where}column {h!r} says {own} in its name but the file gives "
                             f"its unit as {extra!r}; rename the column or fix the unit")
        if own is None:
            own = extra
            key = f"{key}_{unit_token(extra)}"
    return key, own


@functools.cache
def _registry() -> Any:
    import pint

    return pint.UnitRegistry()


def _pint_unit(token: str, written: str) -> Any:
    ureg = _registry()
    if token in _PINT:
        return ureg.Unit(_PINT[token])
    import pint

    try:
        return ureg.Unit(written.strip().strip("()[]").strip())
    except (pint.errors.PintError, ValueError, TypeError, AttributeError, SyntaxError):
        return None


def unit_factor(written: str, target: str, *, what: str) -> float:
    """Multiplier from the unit ``written`` (as in a file) to the token ``target`` (``"mpa"``).

    Raises :class:`InputError` (prefixed ``what``) for a unit pint does not know or of another
    dimension.

    Examples
    --------
    >>> round(unit_factor("kPa", "mpa", what="p"), 12), unit_factor("mm", "mm", what="d")
    (0.001, 1.0)
    """
    tok = unit_token(written)
    if tok == target:
        return 1.0
    src = _pint_unit(tok, written)
    if src is None:
        raise InputError(f"{what} has an unknown unit {written!r}")
    dst = _registry().Unit(_PINT[target])
    if src.dimensionality != dst.dimensionality:
        raise InputError(f"{what} is in {written}, which is not convertible to {_show(target)}")
    return float(_registry().Quantity(1.0, src).to(dst).magnitude)


_SHOW = {"mpa": "MPa", "kpa": "kPa", "pa": "Pa", "hpa": "hPa", "mbar": "mbar", "n": "N",
         "kn": "kN", "pct": "%", "nm": "Nm", "um": "um"}


def _show(token: str) -> str:
    return _SHOW.get(token, token)


# ---------------------------------------------------------------------------------------------
# The grid: what a format reader found, before columns are chosen.


@dataclass
class Grid:
    """A table as found: headers, the file's units, cells, metadata, and how to name a row."""

    source: str
    headers: list[str]
    keys: list[str]
    units: list[str | None]
    column: Callable[[int], Any]
    n_rows: int
    metadata: list[str] = field(default_factory=list)
    row: Callable[[int], str] = field(default=lambda i: f"row {i + 1}")
    fmt: str = "csv"
    encoding: str = ""
    group: str = ""
    waveform: dict[str, Any] = field(default_factory=dict)
    sha256: str = ""


def _read_decoded(p: Path, name: str) -> tuple[bytes, bytes, str]:
    """The file's bytes, as UTF-8 and the encoding found (see :func:`_decode`)."""
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise InputError(f"{name}: cannot read ({exc.strerror or exc.__class__.__name__})"
                         ) from None
    return (raw, *_decode(raw, name))


def _decode(raw: bytes, name: str) -> tuple[bytes, str]:
    """File bytes -> UTF-8 bytes and the encoding found (BOM, UTF-16 without BOM, Latin-1)."""
    if raw.startswith(b"\xef\xbb\xbf"):
        return raw[3:], "utf-8-sig"
    enc = ""
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        enc = "utf-16"
    else:
        head = raw[:4096]
        if len(head) >= 4 and head.count(0) > len(head) // 4:
            enc = "utf-16-le" if head[1::2].count(0) > head[0::2].count(0) else "utf-16-be"
    if enc:
        try:
            text = raw.decode(enc)
        except UnicodeDecodeError as exc:
            raise InputError(f"{name}: cannot read as {enc.upper()} text ({exc.reason})"
                             ) from None
        return text.lstrip("\ufeff").encode("utf-8"), enc
    try:
        raw.decode("utf-8")
    except UnicodeDecodeError:
        return raw.decode("latin-1").encode("utf-8"), "latin-1"
    return raw, "utf-8"


def _split_fields(line: str, sep: str | None) -> list[str]:
    if sep is None:
        return line.split()
    try:
        return [f.strip() for f in next(csv.reader([line], delimiter=sep))]
    except (csv.Error, StopIteration):
        return [f.strip() for f in line.split(sep)]


def _is_num(cell: str, decimal: str) -> bool:
    c = cell.strip().strip('"')
    if decimal == ",":
        c = c.replace(",", ".")
    return bool(_NUMBER.match(c)) or c.lower() in ("nan", "inf", "-inf", "+inf")


def _data_like(fields: list[str], decimal: str) -> bool:
    cells = [f for f in fields if f.strip().strip('"')]
    num = sum(_is_num(f, decimal) for f in cells)
    return num >= 1 and num >= len(cells) - num


def _units_row(fields: list[str]) -> bool:
    cells = [f.strip().strip('"') for f in fields]
    cells = [c for c in cells if c]
    if not cells:
        return False
    for c in cells:
        tok = unit_token(c)
        if tok in _PINT or tok in ("-", "1", "v", "mv", "degc", "°c", "c"):
            continue
        if any(ch.isdigit() for ch in c) or len(c) > 12:
            return False
        if not (c.startswith(("(", "[")) and c.endswith((")", "]"))):
            return False
    return True


def _choose_sep(samples: list[str]) -> str | None:
    """Tab, ``;`` or ``,``: the one whose most common field count (>= 2) covers most lines
    (ties in that order: a decimal-comma file splits on ``;`` consistently, on ``,`` not)."""
    from collections import Counter

    best: tuple[int, str | None] = (0, None)
    for sep in ("\t", ";", ","):
        counts = Counter(n for n in (len(_split_fields(s, sep)) for s in samples) if n >= 2)
        if counts and (cover := counts.most_common(1)[0][1]) > best[0]:
            best = (cover, sep)
    return best[1]


def _locate(rows: list[list[str]], decimal: str) -> tuple[int, int | None, int]:
    """(header, units row or None, first data row) among the content rows.

    The data are the longest run of number-like rows that follows a row that is not (a
    preamble's ``Width, 5`` lines make short runs); the row above is the header, or the units
    row under the header.
    """
    like = [_data_like(r, decimal) for r in rows]
    best, best_len = -1, 0
    i = 0
    while i < len(rows):
        if like[i] and (i == 0 or not like[i - 1]):
            j = i
            while j < len(rows) and like[j]:
                j += 1
            if j - i > best_len:
                best, best_len = i, j - i
            i = j
        else:
            i += 1
    if best <= 0:
        return 0, None, 1
    h = best - 1
    if h >= 1 and _units_row(rows[h]) and not _units_row(rows[h - 1]):
        return h - 1, h, best
    return h, None, best


# ---------------------------------------------------------------------------------------------
# Text formats.

_WS_LINE = re.compile(rb"\n[ \t]+(?=\n|$)")
_LEADING_WS_LINE = re.compile(rb"[ \t]+(?:\n|$)")


def _meta_line(line: str) -> str:
    body = line.strip()[1:]
    return (body[1:] if body.startswith(" ") else body).rstrip()


def _drop_comments(text: bytes) -> tuple[bytes, list[str]]:
    """``text`` without its ``#`` lines, and those lines, in order (one scan of the ``#``s)."""
    pieces: list[bytes] = []
    meta: list[str] = []
    start = 0
    pos = text.find(b"#")
    while pos != -1:
        ls = text.rfind(b"\n", 0, pos) + 1
        le = text.find(b"\n", pos)
        le = len(text) if le == -1 else le
        if not text[ls:pos].strip(b" \t"):
            meta.append(_meta_line(text[ls:le].decode("utf-8")))
            pieces.append(text[start:ls])
            start = le + 1
        pos = text.find(b"#", le)
    pieces.append(text[start:])
    return b"".join(pieces), meta


def _fix_decimal(series: pd.Series) -> pd.Series:
    """Decimal-comma cells ("0,25") -> "0.25"; other cells as they are."""
    s = series.astype("string")
    m = s.str.strip().str.fullmatch(_COMMA_NUMBER.pattern).fillna(False)
    return s.where(~m, s.str.replace(",", ".", regex=False)).astype(object)


def _frame_from_text(data: bytes, sep: str | None, decimal: str, n_cols: int, name: str,
                     row: Callable[[int], str], text: bool, comment: bool) -> pd.DataFrame:
    import pandas as pd

    kw: dict[str, Any] = {"dtype": str, "keep_default_na": False} if text else {}
    if decimal == "," and not text:
        kw["decimal"] = ","
    try:
        df = pd.read_csv(_io.BytesIO(data), sep=sep or r"\s+", header=None,
                         names=list(range(n_cols)), skipinitialspace=True, encoding="utf-8",
                         comment="#" if comment else None, **kw)
    except pd.errors.EmptyDataError:
        df = pd.DataFrame({i: pd.Series([], dtype=float) for i in range(n_cols)})
    except pd.errors.ParserError as exc:
        msg = str(exc).strip().splitlines()[-1]
        found = re.search(r"line (\d+), saw (\d+)", msg)
        if found:
            try:
                where = row(int(found.group(1)) - 1)
            except IndexError:
                where = ""
            if where:
                raise InputError(f"{name}: malformed CSV: {where} has {found.group(2)} fields, "
                                 f"the header has {n_cols}") from None
        raise InputError(f"{name}: malformed CSV ({msg})") from None
    if text and decimal == ",":
        for c in df.columns:
            df[c] = _fix_decimal(df[c])
    return df


def _text_grid(p: Path, name: str, *, text: bool = False, comment: bool = False) -> Grid:
    """A CSV/TSV/``;``/whitespace table with an optional preamble and units row."""
    raw, data, enc = _read_decoded(p, name)
    if b"\r" in data:  # Windows (or old Mac) line ends
        data = data.replace(b"\r\n", b"\n").replace(b"\r", b"\n")
    # the first lines (at most 64 kB, 300 content lines) decide the layout
    head = data[:65536].decode("utf-8", "replace").split("\n")
    if len(data) > 65536:
        head = head[:-1]
    content: list[tuple[int, str]] = []  # (line index, text) of non-blank, non-# lines
    for k, line in enumerate(head):
        s = line.strip()
        if s and not s.startswith("#"):
            content.append((k, line))
            if len(content) >= 300:
                break
    if not content:
        raise InputError(f"{name}: no header row: the file is empty or holds only # comments "
                         "(expected a row of column names with units, e.g. pressure_mpa)")
    sep = _choose_sep([c[1] for c in content])
    rows = [_split_fields(c[1], sep) for c in content]
    flat = [f for r in rows[-20:] for f in r]
    decimal = "," if sep != "," and any(_COMMA_NUMBER.match(f.strip('"')) for f in flat) \
        else "."
    h, u, _ = _locate(rows, decimal)
    head_idx = content[h][0]
    start_idx = content[u][0] + 1 if u is not None else head_idx + 1
    metadata: list[str] = []
    for k in range(head_idx):
        s = head[k].strip()
        if s.startswith("#"):
            metadata.append(_meta_line(s))
        elif s:
            metadata.append(", ".join(f for f in _split_fields(s, sep) if f) if sep else s)
    headers = [f.strip().strip('"') for f in rows[h]]
    units_row: list[str | None] = [None] * len(headers)
    if u is not None:
        cells = rows[u] + [""] * max(0, len(headers) - len(rows[u]))
        units_row = [c.strip().strip('"') or None for c in cells[:len(headers)]]
    keys_units = [header_key(hd, un, source=name) for hd, un in zip(headers, units_row,
                                                                     strict=True)]
    # byte offset of the first data line
    off = 0
    for _ in range(start_idx):
        nl = data.find(b"\n", off)
        off = len(data) if nl == -1 else nl + 1
    between = [_meta_line(head[k]) for k in range(head_idx + 1, start_idx)
               if head[k].strip().startswith("#")]
    body = data[off:]
    metadata += between
    stripped, more = _drop_comments(body)
    metadata += more
    while (lead := _LEADING_WS_LINE.match(stripped)) is not None and lead.end() > 0:
        stripped = stripped[lead.end():]
    if _WS_LINE.search(stripped):
        stripped = _WS_LINE.sub(b"", stripped)
    first_line = start_idx + 1

    @functools.cache
    def lines() -> list[int]:  # file line of each data row, computed only for a message
        return [first_line + k for k, line in enumerate(body.split(b"\n"))
                if line.strip(b" \t") and not line.lstrip(b" \t").startswith(b"#")]

    def row(i: int) -> str:
        return f"data row {i + 1} (line {lines()[i]})"

    df = _frame_from_text(stripped, sep, decimal, len(headers), name, row, text, comment)
    return Grid(source=name, headers=headers, keys=[k for k, _ in keys_units],
                units=[v for _, v in keys_units], column=lambda i: df[i], n_rows=len(df),
                metadata=metadata, row=row, fmt="csv", encoding=enc,
                sha256=hashlib.sha256(raw).hexdigest())


def _lvm_grid(p: Path, name: str, *, text: bool = False) -> Grid:
    """LabVIEW measurement file (NI's LVM text format), one segment."""
    raw, data, enc = _read_decoded(p, name)
    lines = data.decode("utf-8").replace("\r\n", "\n").replace("\r", "\n").split("\n")
    ends = [k for k, ln in enumerate(lines) if ln.strip().startswith("***End_of_Header***")]
    if not lines or not lines[0].startswith("LabVIEW Measurement") or len(ends) < 2:
        raise InputError(f"{name}: not a LabVIEW measurement file (expected 'LabVIEW "
                         "Measurement' and two ***End_of_Header*** lines)")
    if len(ends) > 2:
        raise InputError(f"{name}: {len(ends) - 1} segments; exofric reads LVM files with one "
                         "segment (export each segment, or log with one header)")

    def block(a: int, b: int, sep: str) -> dict[str, list[str]]:
        out: dict[str, list[str]] = {}
        for ln in lines[a:b]:
            parts = ln.split(sep) if sep in ln else ln.split("\t")
            if parts and parts[0].strip():
                out[parts[0].strip()] = [x.strip() for x in parts[1:]]
        return out

    file_head = block(1, ends[0], "\t")
    sep_name = (file_head.get("Separator", ["Tab"]) or ["Tab"])[0].lower()
    sep = {"tab": "\t", "comma": ","}.get(sep_name)
    if sep is None:
        raise InputError(f"{name}: unknown LVM Separator {sep_name!r} (Tab or Comma)")
    file_head = block(1, ends[0], sep)
    decimal = (file_head.get("Decimal_Separator", ["."]) or ["."])[0] or "."
    if decimal not in (".", ","):
        raise InputError(f"{name}: unknown LVM Decimal_Separator {decimal!r}")
    xcols = (file_head.get("X_Columns", ["One"]) or ["One"])[0].lower()
    seg = block(ends[0] + 1, ends[1], sep)
    k = ends[1] + 1
    while k < len(lines) and not lines[k].strip():
        k += 1
    if k >= len(lines):
        raise InputError(f"{name}: no column names after the segment header")
    headers = [h.strip() for h in lines[k].split(sep)]
    if headers and headers[-1].lower() in ("comment", ""):
        headers = headers[:-1]
    ylab = seg.get("Y_Unit_Label", [])
    xdim = (seg.get("X_Dimension", [""]) or [""])[0]
    units: list[str | None] = []
    ch = 0
    for i, h in enumerate(headers):
        if h.lower() == "x_value":
            units.append("s" if xdim.lower() == "time" else None)
            if xdim.lower() == "time" and "Time" not in headers[:i]:
                headers[i] = "Time"
        else:
            units.append(ylab[ch] if ch < len(ylab) and ylab[ch] else None)
            ch += 1
    keys_units = [header_key(hd, un, source=name) for hd, un in zip(headers, units, strict=True)]
    metadata = [f"{key}: {' '.join(v)}".rstrip() for key, v in file_head.items()]
    metadata += [f"segment/{key}: {' '.join(v)}".rstrip() for key, v in seg.items()]
    first = k + 1
    body = "\n".join(lines[first:]).encode("utf-8")
    line_of = [first + 1 + j for j, ln in enumerate(lines[first:]) if ln.strip()]

    def row(i: int) -> str:
        return f"data row {i + 1} (line {line_of[i]})"

    n_file = len(lines[k].split(sep))
    df = _frame_from_text(body, sep, decimal, n_file, name, row, text, False)
    waveform: dict[str, Any] = {}
    if xcols == "no":
        dx = [float(v) for v in seg.get("Delta_X", []) if v]
        x0 = [float(v) for v in seg.get("X0", []) if v]
        if dx:
            waveform = {"increment": dx[0], "start_offset": x0[0] if x0 else 0.0,
                        "unit": "s", "label": "LVM Delta_X"}
    return Grid(source=name, headers=headers, keys=[kk for kk, _ in keys_units],
                units=[v for _, v in keys_units], column=lambda i: df[i], n_rows=len(df),
                metadata=metadata, row=row, fmt="lvm", encoding=enc, waveform=waveform,
                sha256=hashlib.sha256(raw).hexdigest())


def _excel_grid(p: Path, name: str) -> Grid:
    import pandas as pd

    try:
        import openpyxl  # noqa: F401
    except ImportError:
        raise InputError(f"{name}: reading Excel needs openpyxl: pip install 'exofric[xlsx]'"
                         ) from None
    try:
        sheet = pd.read_excel(p, header=None, dtype=object, engine="openpyxl")
    except Exception as exc:  # openpyxl raises zipfile, KeyError, ValueError... on bad files
        raise InputError(f"{name}: not a readable Excel file ({exc.__class__.__name__}: "
                         f"{' '.join(str(exc).split())})") from None

    def cell(v: Any) -> str:
        if v is None or (isinstance(v, float) and math.isnan(v)):
            return ""
        return repr(v) if isinstance(v, float) else str(v)

    all_rows = [[cell(v) for v in r] for r in sheet.itertuples(index=False, name=None)]
    numbered = [(k, r) for k, r in enumerate(all_rows) if any(c.strip() for c in r)]
    content = [(k, r) for k, r in numbered if not r[0].strip().startswith("#")]
    if not content:
        raise InputError(f"{name}: no header row")
    rows = [r for _, r in content]
    h, u, d = _locate(rows, ".")
    headers = [c.strip() for c in rows[h]]
    while headers and not headers[-1]:
        headers.pop()
    units_row: list[str | None] = [None] * len(headers)
    if u is not None:
        units_row = [c.strip() or None for c in (rows[u] + [""] * len(headers))[:len(headers)]]
    keys_units = [header_key(hd, un, source=name) for hd, un in zip(headers, units_row,
                                                                     strict=True)]
    metadata = [_meta_line(r[0]) if r[0].strip().startswith("#") else
                ", ".join(c for c in r if c.strip()) for k, r in numbered if k < content[h][0]]
    start = content[u][0] + 1 if u is not None else content[h][0] + 1
    body = [(k, r) for k, r in numbered if k >= start and not r[0].strip().startswith("#")]
    df = pd.DataFrame([r[:len(headers)] for _, r in body], columns=range(len(headers)),
                      dtype=object) if body else pd.DataFrame(
        {i: pd.Series([], dtype=object) for i in range(len(headers))})
    excel_rows = [k + 1 for k, _ in body]

    def row(i: int) -> str:
        return f"data row {i + 1} (sheet row {excel_rows[i]})"

    return Grid(source=name, headers=headers, keys=[k for k, _ in keys_units],
                units=[v for _, v in keys_units], column=lambda i: df[i], n_rows=len(df),
                metadata=metadata, row=row, fmt="xlsx", encoding="")


def _parquet_grid(p: Path, name: str) -> Grid:
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        raise InputError(f"{name}: reading Parquet needs pyarrow: pip install pyarrow") from None
    try:
        table = pq.read_table(p)
    except (pa.ArrowException, OSError) as exc:
        msg = (str(exc).strip().splitlines() or [exc.__class__.__name__])[0]
        raise InputError(f"{name}: not a readable Parquet file ({msg})") from None
    headers = [str(c) for c in table.schema.names]
    keys_units = [header_key(hd, source=name) for hd in headers]
    metadata: list[str] = []
    for key, value in (table.schema.metadata or {}).items():
        if key == b"exofric.metadata":
            import json

            metadata.extend(str(s) for s in json.loads(value.decode("utf-8")))
        elif key not in (b"pandas", b"ARROW:schema"):
            metadata.append(f"{key.decode('utf-8', 'replace')}: "
                            f"{value.decode('utf-8', 'replace')}")
    return Grid(source=name, headers=headers, keys=[k for k, _ in keys_units],
                units=[v for _, v in keys_units],
                column=lambda i: table.column(i).to_pandas(), n_rows=table.num_rows,
                metadata=metadata, fmt="parquet")


def _one_line(value: Any) -> str:
    return " ".join(str(value).split("\n"))


def tdms_grids(p: Path, name: str) -> list[Grid]:
    """One grid per TDMS group: channel names, ``unit_string`` units and waveform timing."""
    try:
        import nptdms
    except ImportError:
        raise InputError(f"{name}: reading TDMS needs npTDMS: pip install 'exofric[tdms]'"
                         ) from None
    from exofric.io._thirdparty import library_log_as_warning

    try:  # npTDMS's own stderr log lines become one exofric warning (issue 38)
        with library_log_as_warning("nptdms", name, "the TDMS file looks truncated or damaged"):
            tdms = nptdms.TdmsFile.read(p)
    except Exception as exc:  # npTDMS raises ValueError, KeyError, struct.error... on bad files
        raise InputError(f"{name}: not a readable TDMS file ({exc.__class__.__name__}: "
                         f"{_one_line(exc)})") from None
    root = [f"{k}: {_one_line(v)}" for k, v in tdms.properties.items()]
    out = []
    for group in tdms.groups():
        chans = group.channels()
        headers = [c.name for c in chans]
        units = [str(c.properties["unit_string"]) if str(c.properties.get("unit_string", ""))
                 .strip() else None for c in chans]
        keys_units = [header_key(hd, un, source=name) for hd, un in zip(headers, units,
                                                                         strict=True)]
        meta = root + [f"{group.name}/{k}: {_one_line(v)}" for k, v in group.properties.items()]
        meta += [f"{group.name}/{c.name}/{k}: {_one_line(v)}" for c in chans
                 for k, v in c.properties.items()]

        def column(i: int, chans: Any = chans) -> Any:
            return np.asarray(chans[i][:])

        out.append(Grid(source=name, headers=headers, keys=[k for k, _ in keys_units],
                        units=[v for _, v in keys_units], column=column,
                        n_rows=max((len(c) for c in chans), default=0), metadata=meta,
                        fmt="tdms", group=group.name,
                        waveform={"channels": chans}))
    return out


def read_grids(path: str | Path, *, text: bool = False, comment: bool = False,
               strict: bool = False) -> list[Grid]:
    """The grid(s) of a file by its suffix (TDMS: one per group; others: one); another suffix is
    read as text (an error when ``strict``).

    The last two files read are kept (keyed by path, size and modification time): a reader
    that looks at the header first and then at the columns parses a file once.
    """
    p = Path(path)
    try:
        st = p.stat()
    except OSError:
        return _read_grids(p, text=text, comment=comment, strict=strict)
    cached = _read_grids_cached(str(p.resolve()), st.st_size, st.st_mtime_ns, st.st_ino,
                                text, comment, strict)
    # each caller gets its own copies of the columns: the kept grid is never changed
    return [replace(g, column=functools.partial(_copied, g.column)) for g in cached]


def _copied(column: Callable[[int], Any], i: int) -> Any:
    """Column ``i`` of a kept grid, copied."""
    values = column(i)
    return values.copy() if hasattr(values, "copy") else values


@functools.lru_cache(maxsize=2)
def _read_grids_cached(path: str, size: int, mtime_ns: int, inode: int, text: bool,
                       comment: bool, strict: bool) -> tuple[Grid, ...]:
    """:func:`read_grids` of one version of a file (the key changes when the file does)."""
    return tuple(_read_grids(Path(path), text=text, comment=comment, strict=strict))


def _read_grids(p: Path, *, text: bool, comment: bool, strict: bool) -> list[Grid]:
    name = p.name
    suffix = p.suffix.lower()
    if suffix not in TABLE_SUFFIXES and strict:
        raise InputError(f"{name}: unsupported table type {p.suffix or '(no suffix)'!r} "
                         f"(supported: {', '.join(TABLE_SUFFIXES)})")
    if not p.is_file():
        raise InputError(f"{p}: file not found")
    if suffix == ".tdms":
        return tdms_grids(p, name)
    if suffix in (".parquet", ".pq"):
        return [_parquet_grid(p, name)]
    if suffix in (".xlsx", ".xlsm"):
        return [_unique_headers(_excel_grid(p, name))]
    if suffix == ".lvm":
        return [_lvm_grid(p, name, text=text)]
    return [_unique_headers(_text_grid(p, name, text=text, comment=comment))]


def _unique_headers(grid: Grid) -> Grid:
    """``grid``, or an InputError if two columns have the same (non-empty) header, case aside:
    which one a reader took would be a silent choice (issue 38)."""
    keys = [h.strip().lower() for h in grid.headers]
    for i, key in enumerate(keys):
        same = [j for j, k in enumerate(keys) if k == key]
        if key and len(same) > 1:
            raise InputError(f"{grid.source}: column {grid.headers[i]!r} is in the file "
                             f"{len(same)} times (columns {', '.join(str(j + 1) for j in same)}"
                             "); rename all but one")
    return grid


def file_sha256(path: str | Path) -> str:
    """SHA-256 of a file's bytes (hex), for provenance and to refuse one file given twice."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


# ---------------------------------------------------------------------------------------------
# Choosing and converting columns.


@dataclass(frozen=True)
class _Pick:
    canonical: str
    index: int
    header: str
    unit: str | None     # as found (file or mapping), None for a unitless column
    factor: float


def _pick(grid: Grid, want: Sequence[str], optional: Sequence[str],
          columns: Mapping[str, str] | None, unitless: Sequence[str]) -> dict[str, _Pick]:
    name = grid.source
    found = grid.headers
    out: dict[str, _Pick] = {}
    mapped: dict[str, tuple[str, str | None]] = {}  # canonical -> (header, unit token)
    bases = {split_key(c)[0]: c for c in list(want) + list(optional)}
    for key, header in (columns or {}).items():
        kb, ku = split_key(str(key).strip().lower())
        if kb not in bases:
            raise InputError(f"{name}: columns: unknown column {key!r} (this file's columns: "
                             f"{', '.join(bases.values())})")
        mapped[bases[kb]] = (str(header).strip(), ku)
    used: set[int] = set()
    for canon in list(want) + list(optional):
        base, tok = split_key(canon)
        text_col = canon in unitless
        if canon in mapped:
            header, mtok = mapped[canon]
            idx = [i for i, h in enumerate(found) if h == header] or \
                [i for i, h in enumerate(found) if h.lower() == header.lower()]
            if len(idx) != 1:
                how = "is not in the file" if not idx else "is in the file more than once"
                raise InputError(f"{name}: column {header!r} (named by the columns mapping) "
                                 f"{how} (columns found: {', '.join(repr(h) for h in found)})",
                                 param="columns")
            i = idx[0]
            own = grid.units[i]
            if own is not None and mtok is not None and unit_token(own) != mtok:
                raise InputError(f"{name}: the columns mapping says {header!r} is in "
                                 f"{_show(mtok)} but the file says {own}; correct the mapping "
                                 "or the file", param="columns")
            unit = own if mtok is None else _show(mtok)
        else:
            cands = [i for i, k in enumerate(grid.keys)
                     if i not in used and (split_key(k)[0] == base or k == canon)]
            if not cands:
                if canon in want:
                    alt = f"; or name it in the columns mapping ({canon}=<header>)"
                    raise InputError(f"{name}: missing column {canon!r} (required: "
                                     f"{', '.join(want)}; found: "
                                     f"{', '.join(found) or 'none'}){alt}")
                continue
            exact = [i for i in cands if grid.keys[i] == canon]
            if len(cands) > 1 and len(exact) == 1:
                cands = exact  # pressure_mpa beside pressure_kpa: the one in exofric's unit
            if len(cands) > 1:
                names = " and ".join(repr(found[i]) for i in cands)
                raise InputError(f"{name}: two {base} columns, {names}: keep one, or choose one "
                                 "in the columns mapping", param="columns")
            i = cands[0]
            unit = grid.units[i]
        used.add(i)
        header = found[i]
        if tok is None or text_col:
            if unit is not None and not text_col and unit_token(unit) not in ("-", "1"):
                raise InputError(f"{name}: column {header!r} has a unit ({unit}); exofric "
                                 f"expects {canon!r} without one")
            out[canon] = _Pick(canon, i, header, None, 1.0)
            continue
        if unit is None:
            raise InputError(f"{name}: column {header!r} has no unit; write it as {canon!r} or "
                             f"'{base} ({_show(tok)})', or give it in the columns mapping")
        fac = unit_factor(unit, tok, what=f"{name}: column {header!r}")
        out[canon] = _Pick(canon, i, header, unit, fac)
    return out


def numeric_column(values: Any, header: str, name: str, row: Callable[[int], str]
                   ) -> np.ndarray:
    """A column as float64 (NaN for empty/NaN cells); a text cell -> InputError naming it."""
    import pandas as pd

    series = values if isinstance(values, pd.Series) else pd.Series(values)
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


def locate_columns(path: str | Path, required: Sequence[str], optional: Sequence[str] = (), *,
                   columns: Mapping[str, str] | None = None,
                   text_columns: Sequence[str] = (), text: bool = False,
                   comment: bool = False) -> tuple[Grid, dict[str, _Pick]]:
    """The grid of ``path`` and, per canonical column, where it is and its unit factor."""
    grids = read_grids(path, text=text, comment=comment)
    errors: list[InputError] = []
    for g in grids:
        try:
            return g, _pick(g, required, optional, columns, text_columns)
        except InputError as exc:
            errors.append(exc)
    if len(errors) == 1:
        raise errors[0]
    name = Path(path).name
    listing = "; ".join(f"{g.group!r}: {', '.join(g.headers[:8])}" for g in grids) or "none"
    raise InputError(f"{name}: no TDMS group has the columns {', '.join(required)} (groups: "
                     f"{listing})")


def read_measured_table(path: str | Path, required: Sequence[str],
                        optional: Sequence[str] = (), *,
                        columns: Mapping[str, str] | None = None,
                        text_columns: Sequence[str] = ()) -> pd.DataFrame:
    """Read a measured table in any common format into exofric's columns and units.

    Parameters
    ----------
    path : str or Path
        The file: ``.csv``, ``.tsv``, ``.txt``, ``.dat`` (separator, decimal comma, encoding,
        preamble and units row detected), ``.lvm`` (LabVIEW), ``.tdms`` (NI; the first group
        with the columns), ``.parquet``/``.pq`` or ``.xlsx``/``.xlsm`` (first sheet).
    required : sequence of str
        Canonical columns with their unit suffix, e.g. ``["pressure_mpa", "friction_n"]``. A
        file column matches by name (case, blanks and dashes ignored) with its unit in any
        spelling (``pressure_kpa``, ``Pressure (kPa)``, ``Pressure [kPa]``, a units row, a TDMS
        ``unit_string``) and is converted with pint.
    optional : sequence of str
        Columns read when present.
    columns : mapping of str to str, optional
        ``{key: header}`` for columns with other names; the key is a canonical column in any
        unit (``{"pressure_kpa": "P1"}``). A unit here that contradicts the file's own unit
        for that column is an error naming both.
    text_columns : sequence of str
        Columns kept as text (labels such as ``test``), stripped.

    Returns
    -------
    pandas.DataFrame
        The required and present optional columns, numbers as float64 in the canonical unit
        (NaN for empty cells). ``attrs``: ``source`` (file name), ``columns`` (canonical ->
        header as found), ``units`` (canonical -> unit as found), ``metadata`` (preamble and
        comment lines, TDMS/LVM properties), ``ignored_columns``, ``format``, ``encoding``,
        ``sha256``.

    Raises
    ------
    InputError
        One line naming the file: unsupported suffix, missing file or column, unknown unit or
        a unit of another dimension, a contradiction between ``columns`` and the file, a
        non-numeric cell (naming its row), Excel without openpyxl, TDMS without npTDMS.

    Examples
    --------
    >>> import tempfile
    >>> p = Path(tempfile.mkdtemp()) / "f.csv"
    >>> _ = p.write_text("Rig: B2\\n\\nPressure (kPa);Friction [N]\\n200;40,5\\n400;81\\n",
    ...                  encoding="utf-16")
    >>> df = read_measured_table(p, ["pressure_mpa", "friction_n"])
    >>> df["pressure_mpa"].tolist(), df["friction_n"].tolist()
    ([0.2, 0.4], [40.5, 81.0])
    >>> df.attrs["units"], df.attrs["metadata"], df.attrs["encoding"]
    ({'pressure_mpa': 'kPa', 'friction_n': 'N'}, ['Rig: B2'], 'utf-16')
    """
    import pandas as pd

    grid, picks = locate_columns(path, required, optional, columns=columns,
                                 text_columns=text_columns)
    name = grid.source
    out: dict[str, Any] = {}
    for canon, pk in picks.items():
        vals = grid.column(pk.index)
        if canon in text_columns:
            out[canon] = pd.Series(vals).astype(str).str.strip().to_numpy(dtype=object)
            continue
        v = numeric_column(vals, pk.header, name, grid.row)
        out[canon] = v * pk.factor if pk.factor != 1.0 else v
    df = pd.DataFrame(out)
    used = {pk.index for pk in picks.values()}
    df.attrs.update({
        "source": name, "columns": {c: pk.header for c, pk in picks.items()},
        "units": {c: pk.unit for c, pk in picks.items() if pk.unit is not None},
        "metadata": list(grid.metadata),
        "ignored_columns": [h for i, h in enumerate(grid.headers) if i not in used],
        "format": grid.fmt, "encoding": grid.encoding,
        "sha256": grid.sha256 or file_sha256(path),
    })
    return df


def is_raw_log(path: str | Path, columns: str | None = None) -> bool:
    r"""Whether ``path`` is a raw rig log (a time series) rather than a table of results.

    True for TDMS files, when a ``columns`` mapping names time, force or displacement, or when
    the file's header (any separator, encoding and spelling :func:`read_measured_table` reads)
    has a time column. An unreadable file gives False: the table reader then names the problem.

    Parameters
    ----------
    path : str or Path
        The file.
    columns : str or None
        A ``columns`` mapping (``name=header,...``; ``--columns`` on the command line).

    Returns
    -------
    bool

    Examples
    --------
    >>> import tempfile, os
    >>> d = tempfile.mkdtemp()
    >>> f = os.path.join(d, "log.tsv")
    >>> _ = open(f, "w").write("Time (s)\tPressure (kPa)\tForce [N]\n0\t1\t2\n0.1\t1\t2\n")
    >>> is_raw_log(f), is_raw_log(f, "friction_n=Force")
    (True, True)
    """
    if Path(path).suffix.lower() == ".tdms":
        return True
    keys = {k.split("=")[0].strip().lower() for k in (columns or "").split(",") if "=" in k}
    if any(k == "time" or split_key(k)[0] in ("time", "force", "displacement") for k in keys):
        return True
    try:
        grid = read_grids(path)[0]
    except (InputError, OSError):
        return False
    return any(split_key(k)[0] == "time" or k == "time" for k in grid.keys)
