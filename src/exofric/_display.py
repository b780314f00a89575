"""A compact display of result objects: ``summary()`` (text) and ``_repr_html_`` (notebooks).

Every public result class mixes in :class:`DisplayMixin`. Both views are built from the
result's own ``to_dict()`` (the JSON the CLI prints), so they show the same names, with their
units in the names (``_mm``, ``_n``, ``_mpa``, ``_s``, ``_pct``...) and a unit column read off
them: scalars and short arrays as they are, long arrays as their size, first and last value,
minimum and maximum, nested records one level deep (``deviation.deviation_pct``), the paper's
numbers where the result carries them (``paper_...``). Nothing here computes.
"""

from __future__ import annotations

import html
import math
import re
from collections.abc import Iterator, Mapping
from typing import Any

__all__ = ["DisplayMixin", "HtmlReprMixin", "display_rows", "unit_of"]

#: Unit suffixes of exofric's names, longest first (``squeeze_force_n_per_mm`` -> N/mm).
_UNITS: tuple[tuple[str, str], ...] = (
    ("_n_per_mm3", "N/mm^3"), ("_t_per_mm3", "t/mm^3"), ("_n_per_mm2", "N/mm^2"),
    ("_n_per_mpa", "N/MPa"), ("_n_per_mm", "N/mm"), ("_nm_per_rad", "Nm/rad"),
    ("_n_per_s", "N/s"), ("_mpa_per_s", "MPa/s"), ("_mm_per_s", "mm/s"),
    ("_per_mpa", "1/MPa"), ("_mm2", "mm^2"), ("_mm3", "mm^3"), ("_mpa_s", "MPa s"),
    ("_mm", "mm"), ("_mpa", "MPa"), ("_kpa", "kPa"), ("_nm", "Nm"), ("_n", "N"), ("_s", "s"),
    ("_ms", "ms"), ("_hz", "Hz"), ("_pct", "%"), ("_deg", "deg"), ("_rad", "rad"),
    ("_m", "m"), ("_j", "J"), ("_l", "L"),
)
#: Arrays longer than this are summarised (size, ends, range).
SHORT = 6
#: At most this many rows; the rest are counted.
MAX_ROWS = 40


def unit_of(name: str) -> str:
    """The unit an exofric name carries in its suffix ('' when none).

    Examples
    --------
    >>> unit_of("squeeze_force_n"), unit_of("slope_n_per_mpa"), unit_of("gamma")
    ('N', 'N/MPa', '')
    >>> unit_of("penalty_n_per_mm3"), unit_of("ki_mpa_per_n_s")       # listed; not listed
    ('N/mm^3', '')
    """
    last = name.rsplit(".", 1)[-1]
    for suffix, unit in _UNITS:
        if "_per_" in suffix and last.endswith(suffix):
            return unit
    if re.search(r"_per_[a-z0-9_]+$", last):     # a ratio not listed: say nothing, not half
        return ""
    for suffix, unit in _UNITS:
        if "_per_" not in suffix and last.endswith(suffix):
            return unit
    return ""


def _num(v: Any) -> str:
    if isinstance(v, bool) or v is None:
        return str(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else f"{v:.6g}"
    return str(v)


def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _value(v: Any) -> str:
    """One cell: a scalar, a short list as it is, a long one summarised."""
    if hasattr(v, "tolist") and not isinstance(v, (str, bytes)):
        v = v.tolist()
    if isinstance(v, (list, tuple)):
        if len(v) <= SHORT and all(not isinstance(x, (list, tuple, dict)) for x in v):
            return "[" + ", ".join(_num(x) for x in v) + "]"
        if v and all(_is_number(x) or x is None for x in v):
            nums = [float(x) for x in v if x is not None and not math.isnan(float(x))]
            if not nums:
                return f"{len(v)} values, none finite"
            return (f"{len(v)} values: {_num(v[0])} ... {_num(v[-1])} "
                    f"(min {_num(min(nums))}, max {_num(max(nums))})")
        kind = "records" if v and all(isinstance(x, dict) for x in v) else "items"
        return f"{len(v)} {kind}"
    if isinstance(v, Mapping):
        return f"{len(v)} entries"
    text = _num(v)
    return text if len(text) <= 80 else text[:77] + "..."


def display_rows(data: Mapping[str, Any], depth: int = 1) -> Iterator[tuple[str, str, str]]:
    """``(name, value, unit)`` rows of a ``to_dict()``, nested dicts ``depth`` levels deep.

    Examples
    --------
    >>> list(display_rows({"gamma": 0.7168, "ci": {"lo": 0.7, "hi": 0.73}}))
    [('gamma', '0.7168', ''), ('ci.lo', '0.7', ''), ('ci.hi', '0.73', '')]
    >>> list(display_rows({"pressure_mpa": [0.1 * i for i in range(1, 13)]}))[0][1]
    '12 values: 0.1 ... 1.2 (min 0.1, max 1.2)'
    """
    for key, v in data.items():
        name = str(key)
        if isinstance(v, Mapping) and depth > 0 and v:
            for sub, val, unit in display_rows(v, depth - 1):
                yield f"{name}.{sub}", val, unit
        else:
            yield name, _value(v), unit_of(name)


class HtmlReprMixin:
    """``_repr_html_`` (a notebook's table) for a result with ``to_dict()``; for a result
    that has a field named ``summary`` (which :class:`DisplayMixin`'s method would shadow as
    a dataclass default)."""

    def _display_rows(self) -> tuple[list[tuple[str, str, str]], int]:
        try:
            data = self.to_dict()  # type: ignore[attr-defined]
        except Exception as exc:   # a display never raises: say why instead  # noqa: BLE001
            return [("to_dict()", f"unavailable: {type(exc).__name__}: {exc}", "")], 0
        rows = list(display_rows(data))
        rows.sort(key=lambda r: "." in r[0])     # the result's own numbers before nested ones
        return rows[:MAX_ROWS], max(0, len(rows) - MAX_ROWS)

    def _display_title(self) -> str:
        doc = (type(self).__doc__ or "").strip().splitlines()
        return f"{type(self).__name__}: {doc[0]}" if doc else type(self).__name__

    def _repr_html_(self) -> str:
        rows, more = self._display_rows()
        esc = html.escape
        body = "".join(f"<tr><td style='text-align:left'><code>{esc(n)}</code></td>"
                       f"<td style='text-align:right'>{esc(v)}</td><td>{esc(u)}</td></tr>"
                       for n, v, u in rows)
        if more:
            body += f"<tr><td colspan='3'>... {more} more (<code>to_dict()</code>)</td></tr>"
        return (f"<div><strong>{esc(self._display_title())}</strong>"
                "<table><thead><tr><th>name</th><th>value</th><th>unit</th></tr></thead>"
                f"<tbody>{body}</tbody></table></div>")


class DisplayMixin(HtmlReprMixin):
    """``summary()`` and ``_repr_html_`` for a result with ``to_dict()``.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Fit(DisplayMixin):
    ...     '''A fit (N).'''
    ...     gamma: float
    ...     friction_n: tuple[float, ...]
    ...     def to_dict(self):
    ...         return {"gamma": self.gamma, "friction_n": list(self.friction_n)}
    >>> print(Fit(0.7168, (10.0, 20.0)).summary())
    Fit: A fit (N).
      gamma        0.7168
      friction_n   [10, 20]  N
    >>> "<table" in Fit(0.7168, (10.0,))._repr_html_()
    True
    """

    def summary(self) -> str:
        """A short text table of this result: name, value, unit (from ``to_dict()``)."""
        rows, more = self._display_rows()
        w = max((len(r[0]) for r in rows), default=0)
        lines = [self._display_title()]
        lines += [f"  {n:<{w}}   {v}" + (f"  {u}" if u else "") for n, v, u in rows]
        if more:
            lines.append(f"  ... {more} more (to_dict())")
        return "\n".join(lines)
