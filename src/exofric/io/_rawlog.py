"""Raw rig logs: time series of pressure, force and displacement, in any format a logger writes.

A raw log is what the rig's logger wrote: one row per sample, a time column, a pressure and a
force column and optionally a displacement column, each with its unit in the header in any
common spelling (``pressure_kpa``, ``Pressure (kPa)``, ``Pressure [kPa]``, a units row, a TDMS
``unit_string``, an LVM ``Y_Unit_Label``; case-insensitive): pressure in MPa, kPa, Pa, bar, mbar
or psi; force in N, kN, kgf or lbf; displacement in mm, m, um or in; time in s, ms or min.
Other columns (setpoints, command terms) are ignored but listed. A ``columns`` mapping
(:func:`parse_column_map`; ``--columns`` at the command line) names the columns of a log whose
headers say something else. The file is read by :mod:`exofric.io._table` (one reader for every
measured table: CSV/TSV/``;`` with decimal commas, UTF-16/Latin-1, vendor preambles, LabVIEW
LVM, NI TDMS, Parquet, xlsx).

:func:`read_raw_log` converts every channel to exofric's units (s, MPa, N, mm) with :mod:`pint`
(no hand-written factors) and refuses a bad log with one line that starts with the file name and
names the column and the time range: an unknown unit, a missing or doubled quantity, a
``columns`` unit that contradicts the file's, a non-numeric cell, NaN/empty/infinite samples,
time that does not increase, a gap in time, a pressure or force too large for its unit (naming
the probable unit), a unit change inside the log. Nothing is silently dropped or repaired.
Comment and preamble lines, the key/value metadata (Parquet) or the properties (TDMS, LVM) are
kept as provenance in ``attrs["metadata"]``.

:func:`write_raw_log` writes a log (CSV or Parquet) that reads back bit for bit.
"""

from __future__ import annotations

import functools
import io as _io
import json
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from exofric import defaults as D
from exofric.defaults import RAWLOG_MAX_GAP_FACTOR, RAWLOG_MIN_SAMPLES
from exofric.errors import InputError
from exofric.io._files import atomic_path
from exofric.io._table import (
    TABLE_SUFFIXES,
    Grid,
    file_sha256,
    numeric_column,
    read_grids,
    split_key,
    unit_token,
)

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
_READ_SUFFIXES = TABLE_SUFFIXES
_WRITE_SUFFIXES = (".csv", ".txt", ".parquet", ".pq")
#: Parquet schema-metadata key holding the metadata lines (a JSON list of strings).
_META_KEY = b"exofric.metadata"
_EXAMPLE = "time=t,pressure_kpa=P1,force_n=Fx"


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
# Column names and the columns mapping.


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
                         "pressure_<unit>, force_<unit>, displacement_<unit>)", param="columns")
    q, u = parts
    if u is None:
        if q != "time":
            raise InputError(f"{where}: {item!r} needs a unit: {q}_<unit> with unit one of "
                             f"{_known(q)}", param="columns")
        u = "s"
    if u not in _UNITS[q]:
        raise InputError(f"{where}: unknown {q} unit {u!r} in {item!r} (known: {_known(q)})",
                         param="columns")
    return q, u


def _table_key(key: str, item: str, columns: Sequence[str]) -> tuple[str, str]:
    """A mapping key for a table with canonical ``columns`` -> (name, unit token or "")."""
    k = key.strip().lower()
    bases = {split_key(c)[0]: split_key(c)[1] for c in columns}
    base, unit = split_key(k)
    if base not in bases:
        base, unit = k, None
    if base not in bases:
        keys = ", ".join(b if u is None else f"{b}_<unit>" for b, u in bases.items())
        raise InputError(f"columns: unknown column in {item!r} (keys: {keys})",
                         param="columns")
    if bases[base] is not None and unit is None:
        raise InputError(f"columns: {item!r} needs a unit: {base}_<unit>, e.g. "
                         f"{base}_{bases[base]}", param="columns")
    if bases[base] is None and unit is not None:
        raise InputError(f"columns: {item!r}: {base} has no unit", param="columns")
    return base, unit or ""


def parse_column_map(text: str, columns: Sequence[str] | None = None) -> dict[str, str]:
    """Parse a ``columns`` mapping: which header of a raw log holds which quantity, in which unit.

    The text is what ``--columns`` takes at the command line; messages name ``columns``.

    Parameters
    ----------
    text : str
        Comma-separated ``KEY=HEADER`` items, e.g. ``"time=t,pressure_kpa=P1,force_n=Fx"``. A
        key is ``time`` (seconds), ``time_<unit>``, ``pressure_<unit>``, ``force_<unit>`` or
        ``displacement_<unit>`` (case-insensitive; units as in :func:`read_raw_log`). A header
        is written as in the file (spaces allowed, stripped around it; no ``,`` or ``=``). An
        empty text is an empty mapping.
    columns : sequence of str, optional
        For a table other than a raw log: its canonical columns (e.g. ``["pressure_mpa",
        "friction_n", "test"]``); a key is then one of their names with any unit (``friction_kn``,
        ``pressure_psi``; no unit for a unitless column such as ``test``).

    Returns
    -------
    dict of str to str
        Canonical lower-case key (``time`` becomes ``time_s``) -> header, in the given order.

    Raises
    ------
    InputError
        One line starting with ``columns:`` naming the item: a malformed item (no ``=``,
        empty key or header), an unknown quantity or unit, a pressure/force/displacement key
        without a unit, a repeated key, two keys for one quantity, one header named twice.

    Examples
    --------
    >>> parse_column_map("time=t, pressure_kPa = P 1 ,force_n=Fx")
    {'time_s': 't', 'pressure_kpa': 'P 1', 'force_n': 'Fx'}
    >>> parse_column_map("Friction_kN=F, pressure_bar=P", ["pressure_mpa", "friction_n"])
    {'friction_kn': 'F', 'pressure_bar': 'P'}
    >>> parse_column_map("pressure=P1")
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: columns: 'pressure=P1' needs a unit: pressure_<unit> with unit \
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
            raise InputError(f"columns: malformed item {item!r} (expected KEY=HEADER, e.g. "
                             "pressure_kpa=P1)", param="columns")
        if columns is not None:
            q, u = _table_key(key, item, columns)
            canon = f"{q}_{u}" if u else q
        else:
            q, u = _key(key, item, "columns")
            canon = f"{q}_{u}"
        header = value.strip()
        if canon in out:
            raise InputError(f"columns: key {canon!r} is given twice ({item!r})",
                             param="columns")
        if q in by_quantity:
            raise InputError(f"columns: {item!r}: {q} is already mapped by "
                             f"{by_quantity[q]!r}; give one column per quantity", param="columns")
        if header in by_header:
            raise InputError(f"columns: {item!r}: header {header!r} is already mapped by "
                             f"{by_header[header]!r}", param="columns")
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
            raise InputError(f"{name}: columns: {item!r}: {q} is already mapped",
                             param="columns")
        if not str(header).strip():
            raise InputError(f"{name}: columns: {item!r} names no header", param="columns")
        out[q] = (u, str(header).strip())
    return out


def _resolve(headers: Sequence[str], mapping: dict[str, tuple[str, str]], name: str,
             need: Sequence[str] = _REQUIRED, what: str = "column",
             keys: Sequence[str] | None = None, units: Sequence[str | None] | None = None
             ) -> tuple[dict[str, _Channel], list[str]]:
    """Find each quantity's column: mapped ones by header, the others by their unit (``keys``:
    ``name_unit`` per column from :func:`exofric.io._table.header_key`; ``units``: the unit the
    file states for each column, which a mapping must not contradict)."""
    found = [h.strip() for h in headers]
    keys = list(keys) if keys is not None else [h.lower() for h in found]
    channels: dict[str, _Channel] = {}
    for q, (u, header) in mapping.items():
        idx = [i for i, h in enumerate(found) if h == header]
        if not idx:
            idx = [i for i, h in enumerate(found) if h.lower() == header.lower()]
        if len(idx) != 1:
            how = "is not in the file" if not idx else "is in the file more than once"
            raise _MissingColumn(f"{name}: {what} {header!r} (columns: named by {q}_{u}="
                                 f"{header}) {how} ({what}s found: {_headers_text(found)})",
                                 param="columns")
        own = units[idx[0]] if units is not None else None
        if own is not None and unit_token(own) != u:
            src = "unit_string" if what == "channel" else "unit"
            raise InputError(f"{name}: columns: {q}_{u}={header} says {_UNITS[q][u][0]} but "
                             f"the file's {src} of {what} {found[idx[0]]!r} is {own!r}: "
                             f"which is it? (with {own!r} right, drop the mapping or write "
                             f"{q}_{unit_token(own)}={header})", param="columns")
        channels[q] = _Channel(q, u, found[idx[0]], idx[0])
    used = {c.index for c in channels.values()}
    for q in _UNITS:
        if q in channels:
            continue
        good: list[tuple[int, str]] = []
        bad: list[tuple[int, str]] = []
        for i, key in enumerate(keys):
            parts = _split(key)
            if i in used or parts is None or parts[0] != q or parts[1] is None:
                continue
            (good if parts[1] in _UNITS[q] else bad).append((i, parts[1]))
        same = [i for i, _ in good if found[i].lower() == found[good[0][0]].lower()]
        if len(same) > 1:  # one header twice: a columns mapping cannot choose between them
            raise InputError(f"{name}: {what} {found[same[0]]!r} is in the file "
                             f"{len(same)} times ({what}s {', '.join(str(i + 1) for i in same)}"
                             f"); rename all but one")
        if len(good) > 1:
            names = " and ".join(repr(found[i]) for i, _ in good)
            raise InputError(f"{name}: two {q} {what}s, {names}: keep one, or choose one "
                             f"(columns: e.g. {found[good[0][0]].lower()}="
                             f"{found[good[0][0]]})", param="columns")
        if good:
            i, u = good[0]
            channels[q] = _Channel(q, u, found[i], i)
        elif bad:
            i, u = bad[0]
            raise InputError(f"{name}: {what} {found[i]!r} has an unknown {q} unit {u!r} "
                             f"(known: {_known(q)}); columns: a mapping "
                             f"{q}_<unit>={found[i]} names its unit", param="columns")
    for q in need:
        if q not in channels:
            raise _MissingColumn(
                f"{name}: no {q} {what} (a name {q}_<unit>, unit one of {_known(q)}; "
                f"{what}s found: {_headers_text(found)}); columns: name the {what}s, "
                f"e.g. {_EXAMPLE}", param="columns")
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
    for q in ("pressure", "force"):
        _unit_change(raw, q, out, name, label(q), dec)
    for q, top, typical in (("pressure", D.RAWLOG_MAX_PRESSURE_MPA,
                             D.RAWLOG_TYPICAL_PRESSURE_MPA),
                            ("force", D.RAWLOG_MAX_FORCE_N, D.RAWLOG_TYPICAL_FORCE_N)):
        _too_large(raw, q, out[_CANONICAL[q]], top, typical, name, label(q))
    return out


def _show_unit(q: str, unit: str) -> str:
    return _UNITS[q][unit][0]


def _too_large(raw: _Raw, q: str, vals: np.ndarray, top: float, typical: float, name: str,
               label: str) -> None:
    """A pressure above RAWLOG_MAX_PRESSURE_MPA or a force above RAWLOG_MAX_FORCE_N is an error
    naming the unit the numbers probably are in (the one that puts them nearest the typical
    level)."""
    peak = float(np.max(np.abs(vals)))
    if peak <= top:
        return
    unit = raw.channels[q].unit
    file_vals = np.abs(raw.values[q])
    lo, hi = float(np.percentile(file_vals, 5)), float(np.max(file_vals))
    best, dist = None, math.inf
    for cand in _UNITS[q]:
        conv = hi * _factor(q, cand)
        if cand == unit or not 0.0 < conv <= top:
            continue
        d = abs(math.log10(conv / typical))
        if d < dist:
            best, dist = cand, d
    canon = _CANONICAL[q]
    shown = _show_unit(q, unit)
    what = "tube pressure" if q == "pressure" else "friction force"
    hint = (f"; they look like {_show_unit(q, best)}: name the column {q}_{best} (columns: "
            f"or map it, e.g. {q}_{best}={raw.channels[q].header})") if best else ""
    raise InputError(f"{name}: values {lo:.4g}-{hi:.4g} under {raw.channels[q].header} "
                     f"({shown}) reach {peak:.4g} {RAW_QUANTITIES[canon]} in {label}, not a "
                     f"plausible {what} (limit {top:g} {RAW_QUANTITIES[canon]}){hint}",
                     param="columns" if best else None)


def _unit_change(raw: _Raw, q: str, out: dict[str, np.ndarray], name: str, label: str,
                 dec: int) -> None:
    """A level that jumps within one sample by a factor between units (1000, 6.895, 4.448...)
    and stays steady on both sides is a unit change inside the log: an error with its time
    range (from the jump to the jump back, or to the end of the log)."""
    from numpy.lib.stride_tricks import sliding_window_view

    v = out[_CANONICAL[q]]
    t = out["time_s"]
    n = v.size
    w = max(3, min(25, n // 40))
    if n < 2 * w + 2:
        return
    # candidates: one-sample steps by a factor >= 2 between samples of one sign (cheap, O(n))
    x0, x1 = np.abs(v[w - 1:n - w]), np.abs(v[w:n - w + 1])
    same = np.sign(v[w - 1:n - w]) == np.sign(v[w:n - w + 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        step = np.maximum(x0, x1) / np.minimum(x0, x1)
    i = w - 1 + np.flatnonzero(same & (step >= 2.0) & np.isfinite(step))
    if not i.size:
        return
    win = sliding_window_view(v, w)  # a view: only the candidates' windows are reduced
    before, after = win[i - w + 1], win[i + 1]  # the w samples up to i and the w after it
    ma, mb = before.mean(axis=1), after.mean(axis=1)
    ok = (ma * mb > 0) & (np.ptp(before, axis=1) <= 0.1 * np.abs(ma)) \
        & (np.ptp(after, axis=1) <= 0.1 * np.abs(mb))
    ok &= np.abs(v[i + 1] - v[i]) >= 0.5 * np.abs(mb - ma)  # the step is one sample
    factors = np.asarray(D.RAWLOG_UNIT_JUMP_FACTORS, dtype=float)
    k = np.flatnonzero(ok)
    am, bm = np.abs(ma[k]), np.abs(mb[k])
    r = np.maximum(am, bm) / np.minimum(am, bm)
    hit = np.any(np.abs(r[:, None] / factors[None, :] - 1.0) <= D.RAWLOG_UNIT_JUMP_RTOL, axis=1)
    jumps = [(int(i[j]), float(ma[j]), float(mb[j])) for j in k[hit]]
    if not jumps:
        return
    j0, x0, y0 = jumps[0]
    back = next((j for j, x, y in jumps[1:]
                 if math.isclose(y / x, x0 / y0, rel_tol=2 * D.RAWLOG_UNIT_JUMP_RTOL)), None)
    end = f"{t[back]:.{dec}f} s" if back is not None else f"the end ({t[-1]:.{dec}f} s)"
    unit = RAW_QUANTITIES[_CANONICAL[q]]
    raise InputError(f"{name}: {label} jumps from {x0:.4g} to {y0:.4g} {unit} (x{y0 / x0:.4g}, "
                     f"a factor between units) between {t[j0]:.{dec}f} s and "
                     f"{t[j0 + 1]:.{dec}f} s and stays there: the unit changed inside the log, "
                     f"from {t[j0 + 1]:.{dec}f} s to {end}; split the log or fix the unit")


# ---------------------------------------------------------------------------------------------
# Formats: every file goes through exofric.io._table's grid (one reader for every measured
# table); here the grid's columns become quantities.


def _from_grid(grid: Grid, mapping: dict[str, tuple[str, str]], need: Sequence[str] = _REQUIRED,
               what: str = "column") -> tuple[dict[str, _Channel], list[str]]:
    return _resolve(grid.headers, mapping, grid.source, need=need, what=what, keys=grid.keys,
                    units=grid.units)


def _waveform_time(grid: Grid, channels: dict[str, _Channel], values: dict[str, np.ndarray],
                   name: str) -> None:
    """Add a time channel from the waveform timing (TDMS ``wf_*`` properties, LVM Delta_X)."""
    if grid.fmt == "lvm":
        wf = grid.waveform
        if not wf:
            raise InputError(f"{name}: no time column (X_Columns No and no Delta_X); columns: "
                             "name one, e.g. time=NAME", param="columns")
        n = len(values["pressure"])
        channels["time"] = _Channel("time", "s", wf["label"], -1)
        values["time"] = float(wf["start_offset"]) + float(wf["increment"]) * np.arange(
            n, dtype=np.float64)
        return
    chans = grid.waveform["channels"]
    pressure = chans[channels["pressure"].index]
    props = pressure.properties
    group = grid.group
    if "wf_increment" not in props:
        raise InputError(
            f"{name}: group {group!r} has no time channel (time_<unit>, unit one of "
            f"{_known('time')}) and pressure channel {pressure.name!r} has no waveform "
            "timing (wf_increment); add a time channel (columns: or name one, e.g. "
            "time=NAME)",
            param="columns")
    for q in ("force", "displacement"):
        if q not in channels:
            continue
        other = chans[channels[q].index].properties
        for key in ("wf_increment", "wf_start_time", "wf_start_offset"):
            if key in other and key in props and other[key] != props[key]:
                raise InputError(f"{name}: {q} channel {chans[channels[q].index].name!r} has "
                                 f"{key} {other[key]} but pressure channel {pressure.name!r} "
                                 f"has {props[key]}: the channels are not sampled together; "
                                 "add a time channel")
    if "wf_start_offset" in props:
        t = np.asarray(pressure.time_track(), dtype=np.float64)
    else:
        t = float(props["wf_increment"]) * np.arange(len(pressure), dtype=np.float64)
    xunit = unit_token(str(props.get("wf_xunit_string", "s")) or "s") or "s"
    if xunit not in _UNITS["time"]:
        raise InputError(f"{name}: channel {pressure.name!r} has an unknown time unit "
                         f"{xunit!r} in wf_xunit_string (known: {_known('time')})")
    channels["time"] = _Channel("time", xunit, f"{pressure.name} waveform time", -1)
    values["time"] = t


def _read(p: Path, name: str, mapping: dict[str, tuple[str, str]]) -> tuple[_Raw, Grid]:
    grids = read_grids(p)
    if grids and grids[0].fmt == "tdms":
        missing: list[InputError] = []
        for grid in grids:
            try:
                channels, ignored = _from_grid(grid, mapping, need=("pressure", "force"),
                                               what="channel")
            except _MissingColumn as exc:
                missing.append(exc)
                continue
            break
        else:
            if len(missing) == 1:
                raise missing[0]
            listing = "; ".join(f"{g.group!r}: {_headers_text(g.headers, 8)}" for g in grids)
            raise InputError(f"{name}: no TDMS group has pressure and force channels (groups: "
                             f"{listing or 'none'}); columns: name the channels, e.g. "
                             f"{_EXAMPLE}", param="columns")
    else:
        grid = grids[0]
        need = _REQUIRED if not (grid.fmt == "lvm" and grid.waveform) else ("pressure", "force")
        channels, ignored = _from_grid(grid, mapping, need=need)
    values: dict[str, np.ndarray] = {}
    for q, c in channels.items():
        col = grid.column(c.index)
        if grid.fmt == "tdms" and np.asarray(col).dtype.kind not in "fiu":
            raise InputError(f"{name}: channel {c.header!r} is not numeric "
                             f"({np.asarray(col).dtype})")
        values[q] = numeric_column(col, c.header, name, grid.row)
    if "time" not in channels:
        _waveform_time(grid, channels, values, name)
    lengths = {channels[q].header: len(v) for q, v in values.items()}
    if len(set(lengths.values())) > 1:
        raise InputError(f"{name}: channels have different lengths: "
                         + ", ".join(f"{h} {n}" for h, n in lengths.items()))
    return _Raw(channels, values, ignored, list(grid.metadata), grid.row), grid


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


def _memory_estimate(p: Path) -> int:
    """Bytes of memory reading the log at ``p`` takes at its peak (an estimate, no data read).

    Text/LVM/TDMS: the file's size times ``RAWLOG_MEMORY_PER_FILE_BYTE["text"]``; xlsx: times
    ``["xlsx"]``; Parquet (compressed): rows x columns x 8 bytes x 3, from its metadata.
    """
    size = p.stat().st_size
    suffix = p.suffix.lower()
    if suffix in (".parquet", ".pq"):
        try:
            import pyarrow.parquet as pq

            md = pq.read_metadata(p)
            return int(md.num_rows) * int(md.num_columns) * 8 * 3
        except Exception:  # noqa: BLE001 - a damaged file: its reader says what is wrong
            return size * 3
    kind = "xlsx" if suffix in (".xlsx", ".xlsm") else "text"
    return int(size * D.RAWLOG_MEMORY_PER_FILE_BYTE[kind])


def _physical_memory() -> int | None:
    """The machine's physical memory in bytes (None where the OS does not say)."""
    import os

    try:
        return int(os.sysconf("SC_PAGE_SIZE")) * int(os.sysconf("SC_PHYS_PAGES"))
    except (ValueError, OSError, AttributeError):
        return None


def _check_memory(p: Path, name: str) -> None:
    """Refuse (InputError, with the estimate) a log too large to read in this machine's memory.

    The limit is ``RAWLOG_MEMORY_FRACTION`` of the physical memory: reading, checking and
    reducing a log holds it whole (3-4 copies of its samples at the peak).
    """
    ram = _physical_memory()
    if ram is None:
        return
    need = _memory_estimate(p)
    if need > D.RAWLOG_MEMORY_FRACTION * ram:
        gib = 2.0**30
        raise InputError(
            f"{name}: too large to read: about {need / gib:.1f} GiB of memory for this "
            f"{p.stat().st_size / gib:.2f} GiB file, over {D.RAWLOG_MEMORY_FRACTION:.0%} of "
            f"this machine's {ram / gib:.1f} GiB; split the log (e.g. one file per test) and "
            "reduce the parts")


def read_raw_log(path: str | Path, columns: Mapping[str, str] | None = None, *,
                 max_gap_factor: float = RAWLOG_MAX_GAP_FACTOR) -> pd.DataFrame:
    """Read a raw rig log (text, LVM, TDMS, Parquet, xlsx), check it, convert to s, MPa, N, mm.

    Columns are recognised by their header (stripped, case-insensitive) ``<quantity>_<unit>``
    or ``Quantity (unit)``, ``Quantity [unit]``, ``Quantity / unit`` or a units row:
    ``time`` s, ms, min; ``pressure`` mpa, kpa, pa, bar, mbar, psi; ``force`` n, kn, kgf,
    lbf; optional ``displacement`` mm, m, um, in. Units are converted with :mod:`pint`. Other
    columns are ignored (listed in ``attrs["ignored_columns"]``), and so is a column with an
    unknown unit when its quantity has another column with a known one. Text (``.csv``,
    ``.tsv``, ``.txt``, ``.dat``; comma, tab, semicolon or whitespace separated, decimal
    commas, UTF-8/UTF-16/Latin-1): lines starting with ``#`` and lines before the table are
    metadata. LabVIEW ``.lvm``: the channel names, ``Y_Unit_Label`` units and the X column (or
    ``X0``/``Delta_X``). TDMS: the first group with pressure and force channels, units from
    ``unit_string``; without a time channel the pressure channel's waveform timing
    (``wf_increment``, ``wf_start_offset``; the force channel's must agree) is used.

    Parameters
    ----------
    path : str or Path
        The log: ``.csv``, ``.tsv``, ``.txt``, ``.dat``, ``.lvm``, ``.tdms``, ``.parquet``,
        ``.pq``, ``.xlsx`` or ``.xlsm``.
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
        as found), ``"ignored_columns"`` (the other headers), ``"format"`` (``csv``, ``lvm``,
        ``tdms``, ``parquet``, ``xlsx``), ``"encoding"`` (text files) and ``"sha256"`` (of the
        file's bytes).

    Raises
    ------
    InputError
        One line starting with the file name: unsupported suffix, missing file, unknown unit,
        missing or doubled quantity, a ``columns`` header not in the file, fewer than
        ``RAWLOG_MIN_SAMPLES`` rows, a non-numeric cell (row and column), NaN/empty/infinite
        samples (the bursts and their time range), time not increasing (the two times and the
        row), a gap (its time range), TDMS without npTDMS or xlsx without openpyxl installed;
        a file whose estimated reading memory is over ``RAWLOG_MEMORY_FRACTION`` of the
        machine's physical memory (the estimate in GiB; nothing is read);
        ``max_gap_factor <= 1``; a ``columns`` unit contradicting the file's; a pressure above
        ``RAWLOG_MAX_PRESSURE_MPA`` or a force above ``RAWLOG_MAX_FORCE_N`` (naming the
        probable unit); a level jump by a factor between units (a unit change inside the log,
        with its time range).

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
    _check_memory(p, name)
    raw, grid = _read(p, name, mapping)
    out = _check(raw, name, gap)
    df = pd.DataFrame(out)
    df.attrs["source"] = name
    df.attrs["metadata"] = raw.metadata
    df.attrs["units"] = {_CANONICAL[q]: _UNITS[q][raw.channels[q].unit][0]
                         for q in _UNITS if q in raw.channels}
    df.attrs["columns"] = {_CANONICAL[q]: raw.channels[q].header
                           for q in _UNITS if q in raw.channels}
    df.attrs["ignored_columns"] = raw.ignored
    df.attrs["format"] = grid.fmt
    df.attrs["encoding"] = grid.encoding
    df.attrs["sha256"] = grid.sha256 or file_sha256(p)
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
