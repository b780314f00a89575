"""Material test files as tensile machines write them: one loading curve, converted to stretch
and stress in MPa.

Two layers:

* :func:`tensile_stress_stretch` -- pure: a DataFrame, which column plays which role
  (``stretch``, ``strain``, ``extension``, ``stress``, ``force``), the columns' units and the
  specimen's gauge length and area -> stretch and stress (MPa), with every conversion listed.
* :func:`read_stress_stretch` -- a CSV file (``,``, ``;`` or tab; ``#`` comments; a vendor
  preamble before the header row is skipped): the roles and units are read from the headers
  (``Load (N)``, ``Extension [mm]``, ``Strain (%)``, ``True Stress (MPa)``, ``stress_kpa``, ...;
  units converted with pint), ``columns`` maps odd headers, and ``# key: value`` comment lines
  may state ``stress_kind``, ``strain_kind``, ``gauge_length_mm``, ``area_mm2``, ``width_mm``,
  ``thickness_mm`` (arguments win).

Conversions (uniaxial tension, incompressible): ``stretch = 1 + extension / gauge length``,
``stretch = 1 + engineering strain``, ``stretch = exp(true strain)``; engineering stress
``P = force / area``; a true (Cauchy) stress stays true here (``stress_kind="true"``) and
:func:`exofric.material.fit_material` converts it with ``P = sigma / stretch``.
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from exofric.errors import InputError, warn_implausible

if TYPE_CHECKING:
    import pandas as pd
    import pint

__all__ = ["TENSILE_ROLES", "read_stress_stretch", "tensile_stress_stretch"]

#: Column roles of a tensile file and the unit each is converted to.
TENSILE_ROLES: dict[str, str] = {
    "stretch": "1", "strain": "1", "extension": "mm", "stress": "MPa", "force": "N",
}
_KINDS = ("engineering", "true")
_HEADER_KEYS = ("stress_kind", "strain_kind", "gauge_length_mm", "area_mm2", "width_mm",
                "thickness_mm")
_KEY_LINE = re.compile(r"^\s*#\s*([A-Za-z_][A-Za-z0-9_ ]*?)\s*[:=]\s*(\S+)\s*$")
_UNIT_IN_BRACKETS = re.compile(r"^(.*?)\s*[\(\[]\s*([^\)\]]*?)\s*[\)\]]\s*$")
_SUFFIX_UNITS = {"mpa": "MPa", "kpa": "kPa", "pa": "Pa", "gpa": "GPa", "psi": "psi",
                 "n": "N", "kn": "kN", "lbf": "lbf", "kgf": "kgf", "mm": "mm", "cm": "cm",
                 "m": "m", "in": "inch", "pct": "%", "percent": "%"}
# Strain "units" that mean a plain ratio.
_RATIO_UNITS = {"", "-", "1", "mm/mm", "m/m", "in/in", "ratio", "unitless", "dimensionless"}


def _role_of(base: str) -> tuple[str | None, str | None]:
    """Role and declared kind (engineering/true/None) of a header's name part."""
    b = base.lower().replace("_", " ").replace(".", " ").strip()
    words = set(b.split())
    kind = None
    if words & {"true", "cauchy", "log", "logarithmic", "hencky"}:
        kind = "true"
    elif words & {"engineering", "eng", "nominal"}:
        kind = "engineering"
    if "stretch" in words or b in ("lambda", "λ", "stretch ratio"):
        return "stretch", None
    if "strain" in words:
        return "strain", kind
    if "stress" in words:
        return "stress", kind
    if words & {"load", "force"}:
        return "force", None
    if words & {"extension", "displacement", "elongation", "crosshead", "deformation"}:
        return "extension", None
    return None, None


def _split_header(header: str) -> tuple[str, str | None]:
    """``'Load (N)'`` -> ``('Load', 'N')``; ``'stress_kpa'`` -> ``('stress', 'kPa')``."""
    h = header.strip()
    m = _UNIT_IN_BRACKETS.match(h)
    if m:
        return m.group(1).strip(), m.group(2).strip()
    if "_" in h:
        base, suf = h.rsplit("_", 1)
        if suf.lower() in _SUFFIX_UNITS:
            return base, _SUFFIX_UNITS[suf.lower()]
    return h, None


@functools.lru_cache(maxsize=1)
def _ureg() -> pint.UnitRegistry:
    import pint

    return pint.UnitRegistry()


def _factor(role: str, unit: str | None, column: str, source: str) -> tuple[float, str]:
    """Factor from ``unit`` to the role's unit (pint), and the unit as shown."""
    target = TENSILE_ROLES[role]
    if unit is None:
        return 1.0, f"{target} (assumed)" if target != "1" else "ratio (assumed)"
    u = unit.strip()
    if role in ("strain", "stretch"):
        if u in ("%", "percent", "pct"):
            if role == "stretch":
                raise InputError(f"{source}: column {column!r}: a stretch is a ratio, not %")
            return 0.01, "%"
        if u.lower() in _RATIO_UNITS:
            return 1.0, "ratio"
        raise InputError(f"{source}: column {column!r}: unit {u!r} is not a strain unit "
                         "(%, mm/mm or none)")
    text = u.replace("²", "^2").replace("^", "**")
    import pint

    try:
        q = _ureg().Quantity(1.0, text)
        f = float(q.to(target).magnitude)
    except (pint.errors.PintError, AttributeError, TypeError, ValueError, AssertionError):
        raise InputError(f"{source}: column {column!r}: unit {u!r} cannot be converted to "
                         f"{target} (the {role} column)") from None
    return f, u


#: a tensile specimen's sizes: (largest possible, largest plausible), mm or mm^2; a dumbbell of
#: silicone is 2-6 mm wide, 1-3 mm thick, 20-100 mm long (ISO 37, ASTM D412)
_SIZE_LIMITS = {"gauge_length_mm": (1e4, 500.0), "width_mm": (1e3, 100.0),
                "thickness_mm": (1e3, 50.0), "area_mm2": (1e6, 1e3)}


def _check_size(name: str, value: Any) -> float | None:
    if value is None:
        return None
    if isinstance(value, (str, bytes, bool)):
        raise InputError(f"{name} must be a number, got {value!r}", param=name)
    v = float(value)
    top, plausible = _SIZE_LIMITS.get(name, (math.inf, math.inf))
    if not (math.isfinite(v) and 0.0 < v <= top):
        raise InputError(f"{name} must be in (0, {top:g}], got {value!r}", param=name)
    if v > plausible:
        warn_implausible(f"{name} = {v:g}: a tensile specimen's is below {plausible:g}")
    return v


def _check_kind(name: str, value: Any) -> str | None:
    if value is None:
        return None
    if not isinstance(value, str) or value.strip().lower() not in _KINDS:
        raise InputError(f"{name} must be engineering or true, got {value!r}", param=name)
    return value.strip().lower()


def tensile_stress_stretch(
    frame: pd.DataFrame,
    columns: Mapping[str, str],
    units: Mapping[str, str | None] | None = None,
    *,
    stress_kind: str | None = None,
    strain_kind: str | None = None,
    gauge_length_mm: float | None = None,
    area_mm2: float | None = None,
    source: str = "data",
) -> pd.DataFrame:
    """Stretch and stress (MPa) of a uniaxial tensile curve from the columns a machine wrote.

    Pure: no file is read. The stretch comes from, in this order, a ``stretch`` column, an
    ``extension`` column when ``gauge_length_mm`` is given, a ``strain`` column, an
    ``extension`` column (then ``gauge_length_mm`` is required); the stress from a
    ``force`` column when ``area_mm2`` is given, a ``stress`` column, a ``force`` column (then
    ``area_mm2`` is required).

    Parameters
    ----------
    frame : pandas.DataFrame
        The table, numeric columns.
    columns : mapping of str to str
        Role -> column of ``frame``: ``stretch`` (unitless), ``strain`` (ratio or %),
        ``extension`` (length, default mm), ``stress`` (pressure, default MPa), ``force``
        (default N).
    units : mapping of str to str, optional
        Column -> its unit as written (``"kN"``, ``"%"``, ``"psi"``, ``"in"``); converted with
        pint. A column without one is taken in the role's default unit (listed as assumed).
    stress_kind : {'engineering', 'true'}, optional
        Of the ``stress`` column (default engineering). A force gives engineering stress.
    strain_kind : {'engineering', 'true'}, optional
        Of the ``strain`` column (default engineering): ``stretch = 1 + e`` or ``exp(e)``.
    gauge_length_mm : float, optional
        Initial gauge length (mm), > 0: ``stretch = 1 + extension / gauge length``.
    area_mm2 : float, optional
        Initial cross-section (mm^2), > 0: ``P = force / area`` (engineering, MPa).
    source : str
        Name used in messages (the file name).

    Returns
    -------
    pandas.DataFrame
        Columns ``stretch`` (unitless) and ``stress_mpa`` (MPa, of ``attrs["stress_kind"]``);
        ``attrs``: ``stress_kind``, ``strain_kind`` (of the source column, or None),
        ``columns`` (per column: ``role``, ``column``, ``unit``, ``factor``, ``kind``,
        ``used``), ``conversion`` (one line per step) and ``source``.

    Raises
    ------
    InputError
        A missing role, a missing gauge length or area, a unit that does not convert, a bad
        kind, a stretch <= 0.

    Examples
    --------
    >>> import pandas as pd
    >>> df = pd.DataFrame({"Load": [0.0, 3.0, 6.0], "Ext": [0.0, 12.5, 25.0]})
    >>> out = tensile_stress_stretch(df, {"force": "Load", "extension": "Ext"},
    ...                              {"Load": "N", "Ext": "mm"}, gauge_length_mm=25.0,
    ...                              area_mm2=6.0)
    >>> out["stretch"].tolist(), out["stress_mpa"].tolist()
    ([1.0, 1.5, 2.0], [0.0, 0.5, 1.0])
    """
    import numpy as np
    import pandas as pd

    units = dict(units or {})
    sk = _check_kind("stress_kind", stress_kind)
    ek = _check_kind("strain_kind", strain_kind)
    gl = _check_size("gauge_length_mm", gauge_length_mm)
    area = _check_size("area_mm2", area_mm2)
    for role, col in columns.items():
        if role not in TENSILE_ROLES:
            raise InputError(f"columns: unknown role {role!r}; roles: "
                             f"{', '.join(TENSILE_ROLES)}", param="columns")
        if col not in frame.columns:
            raise InputError(f"{source}: no column {col!r} (for {role}); columns: "
                             f"{', '.join(map(str, frame.columns))}", param="columns")
    have = dict(columns)
    if "stretch" in have:
        x_role = "stretch"
    elif "extension" in have and gl is not None:
        x_role = "extension"
    elif "strain" in have:
        x_role = "strain"
    elif "extension" in have:
        raise InputError(f"gauge_length_mm is required to turn column {have['extension']!r} of "
                         f"{source} into a stretch (mm), or give a strain or stretch column",
                         param="gauge_length_mm")
    else:
        raise InputError(f"{source}: missing column 'stretch' or 'strain' (or an extension "
                         "column with a gauge length)", param="columns")
    if "force" in have and area is not None:
        y_role = "force"
    elif "stress" in have:
        y_role = "stress"
        if area is not None:
            warn_implausible(f"{source}: area_mm2 = {area:g} is not used: the stress is read "
                             f"from column {have['stress']!r}")
    elif "force" in have:
        raise InputError(f"area_mm2 is required to turn column {have['force']!r} of {source} "
                         "into a stress (mm^2; or width and thickness, mm)", param="area_mm2")
    else:
        raise InputError(f"{source}: missing column 'stress_mpa' (or another stress or a force "
                         "column)", param="columns")
    if y_role == "force" and sk == "true":
        raise InputError(f"stress_kind true does not apply to a force column ({have['force']!r}"
                         " / area is an engineering stress)", param="stress_kind")
    listing: list[dict[str, Any]] = []
    conv: list[str] = []
    vals: dict[str, Any] = {}
    for role, col in have.items():
        f, shown = _factor(role, units.get(col), col, source)
        used = role in (x_role, y_role)
        kind = (ek or "engineering") if role == "strain" else (
            (sk or "engineering") if role == "stress" else None)
        listing.append({"role": role, "column": str(col), "unit": shown, "factor": f,
                        "kind": kind, "used": used})
        if used:
            vals[role] = frame[col].to_numpy(dtype=float) * f
    x = vals[x_role]
    xcol = have[x_role]
    if x_role == "stretch":
        lam = x
        conv.append(f"stretch = column {xcol!r}")
    elif x_role == "extension":
        assert gl is not None
        lam = 1.0 + x / gl
        conv.append(f"stretch = 1 + {xcol!r} (mm) / {gl:g} mm gauge length")
    elif (ek or "engineering") == "true":
        lam = np.exp(x)
        conv.append(f"stretch = exp({xcol!r}) (true strain)")
    else:
        lam = 1.0 + x
        conv.append(f"stretch = 1 + {xcol!r} (engineering strain)")
    ycol = have[y_role]
    if y_role == "force":
        assert area is not None
        p = vals["force"] / area
        kind_out = "engineering"
        conv.append(f"stress_mpa = {ycol!r} (N) / {area:g} mm^2 (engineering)")
    else:
        p = vals["stress"]
        kind_out = sk or "engineering"
        conv.append(f"stress_mpa = {ycol!r} in MPa ({kind_out}"
                    + ("; the fit uses P = sigma / stretch)" if kind_out == "true" else ")"))
    bad = np.flatnonzero(~np.isfinite(lam) | (lam <= 0.0))
    if bad.size:
        i = int(bad[0])
        raise InputError(f"{source}: data row {i + 1}, column {xcol!r} gives stretch "
                         f"{lam[i]:g}: 'stretch' must be > 0")
    out = pd.DataFrame({"stretch": lam, "stress_mpa": p})
    out.attrs.update({"stress_kind": kind_out,
                      "strain_kind": (ek or "engineering") if x_role == "strain" else None,
                      "columns": listing, "conversion": conv, "source": source})
    return out


def _read_grid(p: Path) -> tuple[pd.DataFrame, dict[str, str | None], dict[str, str]]:
    """The file through the one table reader (:func:`exofric.io.read_measured_table`'s
    formats: any separator, decimal comma, encoding, preamble, units row, LVM, TDMS, Parquet,
    xlsx): its numeric columns under their headers, the units a units row gave, and the
    specimen lines ``# key: value`` (or ``key: value`` in a preamble)."""
    import numpy as np
    import pandas as pd

    from exofric.io._table import read_grids

    name = p.name
    grid = read_grids(p)[0]
    if not grid.headers:
        raise InputError(f"{name}: no header row (expected e.g. stretch,stress_mpa or "
                         "'Extension (mm),Load (N)')")
    stated: dict[str, str] = {}
    for line in grid.metadata:
        m = _KEY_LINE.match("# " + line.strip().lstrip("#").strip())
        if m:
            key = m.group(1).strip().lower().replace(" ", "_")
            if key in _HEADER_KEYS and key not in stated:
                stated[key] = m.group(2)
    cols: dict[str, np.ndarray] = {}
    units_found: dict[str, str | None] = {}
    for i, h in enumerate(grid.headers):
        raw = grid.column(i)
        vals = pd.to_numeric(pd.Series(raw), errors="coerce").to_numpy(dtype=float)
        bad = np.flatnonzero(~np.isfinite(vals))
        if bad.size:
            k = int(bad[0])
            cell = pd.Series(raw).iloc[k]
            shown = repr(cell) if isinstance(cell, str) else str(cell)   # inf, not np.float64(inf)
            what = "empty or NaN" if str(cell).strip() in ("", "nan") else \
                f"not a finite number: {shown}"
            raise InputError(f"{name}: {grid.row(k)}, column {h!r} is {what}")
        cols[h] = vals
        units_found[h] = grid.units[i] if i < len(grid.units) else None
    if not cols or len(next(iter(cols.values()))) == 0:
        raise InputError(f"{name}: no data rows under the header")
    return pd.DataFrame(cols), units_found, stated


def read_stress_stretch(
    path: str | Path,
    stress_kind: str | None = None,
    *,
    strain_kind: str | None = None,
    gauge_length_mm: float | None = None,
    area_mm2: float | None = None,
    width_mm: float | None = None,
    thickness_mm: float | None = None,
    columns: Mapping[str, str] | None = None,
) -> pd.DataFrame:
    """Read a uniaxial (or biaxial/planar) test file: stretch and stress in MPa, checked.

    A delimited text file (``,``, ``;`` or tab; a decimal comma with ``;`` or tab) with a
    header row; ``#`` lines are comments; lines before the header row (a machine's preamble)
    are skipped: the header is the row just above the first row of numbers. Roles come from the
    headers: ``stretch``; ``strain`` (``Strain (%)``, ``True Strain``, ``Engineering Strain``,
    ``strain_pct``); ``stress`` (``Stress (MPa)``/``(kPa)``/``(psi)``, ``True Stress``,
    ``stress_mpa``); ``force`` (``Load (N)``, ``Force [kN]``, ``force_n``); ``extension``
    (``Extension [mm]``, ``Displacement (mm)``, ``extension_mm``). ``true``/``log``/``Hencky``
    or ``engineering``/``nominal`` in a header declares the measure; with both in the file,
    the declared kind (else engineering) is used and the other listed as unused. Units in
    brackets or as a suffix are converted with pint; a column without a unit is taken in MPa,
    N, mm or as a ratio. The curve must be one loading curve: stretch strictly monotonic.

    Parameters
    ----------
    path : str or Path
        The file.
    stress_kind, strain_kind : {'engineering', 'true'} or None
        The stress / strain measure; None: the header's word, else a ``# stress_kind:`` /
        ``# strain_kind:`` line, else engineering. An argument that contradicts a header is an
        error.
    gauge_length_mm : float, optional
        Gauge length (mm) for an extension column (else a ``# gauge_length_mm:`` line).
    area_mm2 : float, optional
        Initial cross-section (mm^2) for a force column (else ``width_mm`` x
        ``thickness_mm``, else ``# area_mm2:`` or ``# width_mm:`` and ``# thickness_mm:``).
    width_mm, thickness_mm : float, optional
        Specimen width and thickness (mm): the area is their product.
    columns : mapping of str to str, optional
        Role -> header for odd headers, e.g. ``{"force": "Kraft", "extension": "Weg"}``
        (``exofric.io.parse_column_map`` parses ``"force=Kraft,extension=Weg"``). A header's
        unit is read from it when it has one.

    Returns
    -------
    pandas.DataFrame
        Columns ``stretch`` (unitless) and ``stress_mpa`` (MPa); ``attrs``: ``stress_kind``,
        ``strain_kind``, ``columns`` (every column: role, None for a column of no role such
        as time; header, unit, factor, kind, used), ``conversion`` (the formulas applied),
        ``gauge_length_mm`` and ``area_mm2`` when used, and ``source`` (the file name).

    Raises
    ------
    InputError
        One line naming the file and the row or column: no header or data, a missing column,
        a missing gauge length or area, a unit that does not convert, a kind that contradicts a
        header, stretch <= 0, a stretch that does not keep rising (or falling).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "ux.csv"
    >>> _ = p.write_text("# stress_kind: true\\nstrain,stress_mpa\\n0.1,0.2\\n0.5,0.9\\n")
    >>> df = read_stress_stretch(p)
    >>> df["stretch"].tolist(), df.attrs["stress_kind"]
    ([1.1, 1.5], 'true')
    >>> _ = p.write_text("Time (s);Extension (mm);Load (N)\\n0;0;0\\n1;12,5;3\\n2;25;6\\n")
    >>> df = read_stress_stretch(p, gauge_length_mm=25, width_mm=2, thickness_mm=3)
    >>> df["stretch"].tolist(), df["stress_mpa"].tolist()
    ([1.0, 1.5, 2.0], [0.0, 0.5, 1.0])
    """
    p = Path(path)
    name = p.name
    frame, units_found, stated = _read_grid(p)
    found = _header_roles(list(frame.columns), units_found)
    if columns:
        _map_columns(found, columns, name)
    sk = _check_kind("stress_kind", stress_kind)
    ek = _check_kind("strain_kind", strain_kind)
    _check_stated_kinds(stated, sk, ek, name)
    chosen, kinds, unused = _choose_columns(found.roles, sk, ek, stated)
    gl, a, area_note = _specimen_sizes(stated, name, gauge_length_mm, area_mm2, width_mm,
                                       thickness_mm)
    out = tensile_stress_stretch(
        frame, chosen, found.units, stress_kind=kinds.get("stress"),
        strain_kind=kinds.get("strain"),
        gauge_length_mm=_num(gl, "gauge_length_mm", name) if gl is not None else None,
        area_mm2=_num(a, "area_mm2", name) if a is not None else None, source=name)
    listing = out.attrs["columns"]
    _list_other_columns(listing, unused, found)
    if area_note and _uses(listing, "force"):
        out.attrs["conversion"].insert(1, area_note)
    lam = out["stretch"].to_numpy()
    _check_monotonic(lam, listing, frame, name)
    _warn_strain_unit(lam, listing, name)
    out.attrs["gauge_length_mm"] = (float(_num(gl, "gauge_length_mm", name))
                                    if gl is not None and _uses(listing, "extension") else None)
    out.attrs["area_mm2"] = (float(_num(a, "area_mm2", name))
                             if a is not None and _uses(listing, "force") else None)
    return out


# --- read_stress_stretch's steps -----------------------------------------------------------
# roles and kinds from the headers and the mapping -> the column of each role -> the specimen
# sizes -> the conversion (tensile_stress_stretch) -> the listing of the other columns ->
# monotonicity and plausibility checks


@dataclass
class _HeaderRoles:
    """What the headers say: per role its candidate columns ``(header, kind)``, each column's
    unit as written (None: none given) and the columns of no role."""

    headers: list[str]
    roles: dict[str, list[tuple[str, str | None]]]
    units: dict[str, str | None]
    ignored: list[str]


def _header_roles(headers: list[str], units_found: dict[str, str | None]) -> _HeaderRoles:
    """Roles, kinds and units from the headers (a units row's unit where the header has none)."""
    roles: dict[str, list[tuple[str, str | None]]] = {}
    units: dict[str, str | None] = {}
    ignored: list[str] = []
    for h in headers:
        base, unit = _split_header(h)
        role, kind = _role_of(base)
        units[h] = unit or units_found.get(h)
        if role is not None:
            roles.setdefault(role, []).append((h, kind))
        else:
            ignored.append(h)
    return _HeaderRoles(headers, roles, units, ignored)


def _map_columns(found: _HeaderRoles, columns: Mapping[str, str], name: str) -> None:
    """Apply the explicit role -> header mapping (case-insensitive headers) to ``found``."""
    lower = {h.lower(): h for h in found.headers}
    for role, want in columns.items():
        if role not in TENSILE_ROLES:
            raise InputError(f"columns: unknown role {role!r}; roles: "
                             f"{', '.join(TENSILE_ROLES)}", param="columns")
        hdr = lower.get(str(want).strip().lower())
        if hdr is None:
            raise InputError(f"columns: {name} has no column {want!r} (for {role}); "
                             f"columns: {', '.join(found.headers)}", param="columns")
        found.roles[role] = [(hdr, _role_of(_split_header(hdr)[0])[1])]
        if hdr in found.ignored:
            found.ignored.remove(hdr)


def _check_stated_kinds(stated: dict[str, str], sk: str | None, ek: str | None,
                        name: str) -> None:
    """A ``# stress_kind:`` / ``# strain_kind:`` line not overridden must name a kind."""
    for key, where in (("stress_kind", sk), ("strain_kind", ek)):
        if where is None and key in stated:
            kind_line = stated[key].strip().lower()
            if kind_line not in _KINDS:
                raise InputError(f"{name}: '# {key}:' line must be engineering or true, got "
                                 f"{stated[key]!r}")


def _pick_kind(role: str, cands: list[tuple[str, str | None]], opt: str | None,
               stated: dict[str, str]) -> tuple[str, str]:
    """The stress or strain column and its kind: the argument's kind, else the one declared
    by a lone column's header, else the ``# <role>_kind:`` line, else engineering."""
    declared = {k for _, k in cands if k is not None}
    want_kind = opt or (next(iter(declared)) if len(cands) == 1 and declared else None)
    want_kind = want_kind or _check_kind(f"{role}_kind", stated.get(f"{role}_kind")) \
        or "engineering"
    pick = [c for c in cands if c[1] == want_kind] or [c for c in cands if c[1] is None]
    if not pick:
        col0, kind0 = cands[0]
        raise InputError(f"{role}_kind {want_kind} contradicts column {col0!r} "
                         f"({kind0} {role})", param=f"{role}_kind")
    return pick[0][0], want_kind


def _choose_columns(roles: dict[str, list[tuple[str, str | None]]], sk: str | None,
                    ek: str | None, stated: dict[str, str],
                    ) -> tuple[dict[str, str], dict[str, str | None],
                               list[tuple[str, str, str | None]]]:
    """The column of each role, the stress and strain kinds, and the candidates not used
    ``(role, header, kind)``."""
    chosen: dict[str, str] = {}
    kinds: dict[str, str | None] = {"stress": sk, "strain": ek}
    unused: list[tuple[str, str, str | None]] = []
    for role, cands in roles.items():
        if role in ("stress", "strain"):
            chosen[role], kinds[role] = _pick_kind(role, cands, sk if role == "stress" else ek,
                                                   stated)
            unused += [(role, h, k) for h, k in cands if h != chosen[role]]
        else:
            chosen[role] = cands[0][0]
            unused += [(role, h, None) for h, _ in cands[1:]]
    return chosen, kinds, unused


def _specimen_sizes(stated: dict[str, str], name: str, gauge_length_mm: Any, area_mm2: Any,
                    width_mm: Any, thickness_mm: Any) -> tuple[Any, Any, str | None]:
    """Gauge length (mm) and area (mm^2), from the arguments else the header lines (text,
    checked later), and a conversion line when the area is width x thickness."""
    gl = gauge_length_mm if gauge_length_mm is not None else stated.get("gauge_length_mm")
    w = width_mm if width_mm is not None else stated.get("width_mm")
    t = thickness_mm if thickness_mm is not None else stated.get("thickness_mm")
    a: Any = area_mm2 if area_mm2 is not None else None
    if a is not None and (width_mm is not None or thickness_mm is not None):
        raise InputError("area_mm2: give the area or width and thickness, not both",
                         param="area_mm2")
    area_note = None
    if a is None and (w is not None or t is not None):
        if w is None or t is None:
            missing = "thickness_mm" if t is None else "width_mm"
            raise InputError(f"{missing} is required with "
                             f"{'width_mm' if t is None else 'thickness_mm'} (the area is "
                             "their product, mm^2)", param=missing)
        wv, tv = _check_size("width_mm", _num(w, "width_mm", name)), \
            _check_size("thickness_mm", _num(t, "thickness_mm", name))
        assert wv is not None and tv is not None
        a = wv * tv
        area_note = f"area {a:g} mm^2 = {wv:g} mm x {tv:g} mm"
    if a is None and "area_mm2" in stated:
        a = stated["area_mm2"]
    return gl, a, area_note


def _list_other_columns(listing: list[dict[str, Any]], unused: list[tuple[str, str, str | None]],
                        found: _HeaderRoles) -> None:
    """Add to the listing the candidates not used and the columns of no role (time, cycle,
    ...): listed, not used."""
    for role, col_u, kind_u in unused:
        listing.append({"role": role, "column": col_u, "unit": found.units.get(col_u) or "-",
                        "factor": None, "kind": kind_u, "used": False})
    mapped = {c["column"] for c in listing}
    for col_i in found.ignored:
        if col_i not in mapped:
            listing.append({"role": None, "column": col_i,
                            "unit": found.units.get(col_i) or "-", "factor": None,
                            "kind": None, "used": False})


def _uses(listing: list[dict[str, Any]], role: str) -> bool:
    """Whether a column of this role was used in the conversion."""
    return any(c["used"] and c["role"] == role for c in listing)


def _check_monotonic(lam: Any, listing: list[dict[str, Any]], frame: pd.DataFrame,
                     name: str) -> None:
    """One loading curve: the stretch (unitless) strictly rising or falling, else an
    InputError naming the data row and the source column."""
    import numpy as np

    xcol = next(c["column"] for c in listing if c["used"] and c["role"] in
                ("stretch", "strain", "extension"))
    step = np.diff(lam)
    if step.size and not (np.all(step > 0.0) or np.all(step < 0.0)):
        sign = 1.0 if step[0] > 0 else -1.0
        i = int(np.flatnonzero(sign * step <= 0.0)[0]) + 1
        raise InputError(f"{name}: data row {i + 1}, column {xcol!r} is not monotonic "
                         f"({frame[xcol].iloc[i - 1]:g} then {frame[xcol].iloc[i]:g}): give "
                         "one loading curve per file")


def _warn_strain_unit(lam: Any, listing: list[dict[str, Any]], name: str) -> None:
    """Warn when a strain column without a unit, read as a ratio, reaches a stretch over 31
    (unitless): likely a strain in %."""
    import numpy as np

    strain_col = next((c for c in listing if c["used"] and c["role"] == "strain"), None)
    if strain_col is not None and strain_col["unit"].startswith("ratio (assumed") \
            and float(np.max(lam)) > 31.0:
        warn_implausible(f"{name}: column {strain_col['column']!r} (no unit) is read as a ratio "
                         f"and reaches stretch {float(np.max(lam)):.3g}: is it in %? Write "
                         "'Strain (%)' or strain_pct")


def _num(value: Any, key: str, name: str) -> float:
    """A size from an argument (number) or a header line (text)."""
    if isinstance(value, str):
        try:
            v = float(value)
        except ValueError:
            raise InputError(f"{name}: '# {key}:' line must be a number, got {value!r}") from None
        if not (math.isfinite(v) and v > 0):
            raise InputError(f"{name}: '# {key}:' line must be > 0, got {value!r}")
        return v
    v2 = _check_size(key, value)
    assert v2 is not None
    return v2
