"""Walking data: knee flexion angle and knee moment over time, from OpenSim files or tables.

:func:`read_gait` reads

* OpenSim storage files (``.sto``, ``.mot``): a header up to ``endheader`` (``inDegrees=yes``
  or ``no``; older files say ``Angles are in degrees.``), then a tab-separated table with a
  ``time`` column in s, coordinates (``knee_angle_r`` or ``/jointset/walker_knee_r/
  knee_angle_r/value``) and inverse-dynamics moments (``knee_angle_r_moment``) in Nm. OpenSim
  writes angles (``.mot`` from IK) and moments (``.sto`` from ID) to two files: give the
  second as ``moment_path``;
* tables (CSV, TSV, ... any format of :func:`~exofric.io.read_measured_table`, the project's
  one table reader) with time, knee angle in deg or rad and knee moment in Nm, the unit in the
  header in any spelling (``time_s``, ``Knee angle (deg)``, ``knee_moment [N m]``), converted
  with pint.

It returns a frozen :class:`GaitData`: time (s, from 0), knee flexion angle (rad, **flexion
positive**) and knee moment (Nm, about the same axis: positive = flexion moment), so that the
joint power is moment x angular velocity (W, > 0 when the muscles generate). Data in the
flexion-negative convention of OpenSim's gait2354/gait2392 models (``knee_angle_r`` from about
-120 to 10 deg) are detected (the angle spends most of its range below zero) and both signals
are negated; ``flexion_sign`` overrides the detection.

The shipped stride (:func:`gait_data_path`) is one right-leg stride of OpenSim's Moco
``example3DWalking`` data (Apache-2.0; ``exofric/data/gait/PROVENANCE.md``).

Units: s, rad (deg in files), Nm, kg.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib.resources import files
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError
from exofric.io._table import (
    Grid,
    _pint_unit,
    _registry,
    header_key,
    numeric_column,
    read_grids,
    split_key,
    unit_factor,
    unit_token,
)

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["GaitData", "GAIT_DATA_FILE", "gait_data_path", "read_gait"]

#: The shipped stride (package data ``exofric/data/gait/``).
GAIT_DATA_FILE = "walking_stride_opensim.csv"
#: Canonical column keys of :func:`read_gait`'s ``columns`` mapping.
GAIT_COLUMNS = ("time", "knee_angle", "knee_moment")
_STORAGE = (".sto", ".mot")
_ANGLE = re.compile(r"^knee(?:_angle|_flexion)?(?:_(?P<side>[rl]))?$")
_MOMENT = re.compile(r"^knee(?:_angle|_flexion)?(?:_(?P<side>[rl]))?_(?:moment|torque)$")
_MIN_SAMPLES = 10


@checked_init
@dataclass(frozen=True)
class GaitData(DisplayMixin):
    """Knee flexion angle and moment over time (walking data), as read by :func:`read_gait`.

    Attributes
    ----------
    time_s : ndarray
        Time in s, strictly increasing, from 0.
    knee_angle_rad : ndarray
        Knee flexion angle in rad (flexion positive).
    knee_moment_nm : ndarray
        Net knee moment in Nm about the flexion axis (positive = flexion moment).
    source : str
        Where the data came from (file name(s), columns, conversions).
    body_mass_kg : float or None
        The subject's mass in kg when the file states it (``# body_mass_kg: 85.27``).
    stance_fraction : float or None
        Stance (heel strike to toe-off) as a fraction of the stride when the file states it
        (``# stance_fraction: 0.661``); the data must then start at a heel strike.
    metadata : tuple of str
        Header and comment lines of the file(s).

    Examples
    --------
    >>> import numpy as np
    >>> g = GaitData(np.linspace(0.0, 1.0, 11), np.zeros(11), np.ones(11), "demo")
    >>> g.duration_s, g.n_samples
    (1.0, 11)
    """

    time_s: NDArray[np.float64]
    knee_angle_rad: NDArray[np.float64]
    knee_moment_nm: NDArray[np.float64]
    source: str
    body_mass_kg: float | None = None
    stance_fraction: float | None = None
    metadata: tuple[str, ...] = field(default=())

    @property
    def n_samples(self) -> int:
        """Number of samples."""
        return int(self.time_s.size)

    @property
    def duration_s(self) -> float:
        """Last time minus first time in s."""
        return float(self.time_s[-1] - self.time_s[0])

    @property
    def knee_work_j(self) -> float:
        """Net knee work over the data in J: the integral of moment d(angle) (trapezoidal);
        negative when the knee absorbs (as over a walking stride)."""
        return float(np.trapezoid(self.knee_moment_nm, self.knee_angle_rad))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the three series (s, deg, Nm) and the provenance."""
        return {"source": self.source, "body_mass_kg": self.body_mass_kg,
                "stance_fraction": self.stance_fraction,
                "time_s": self.time_s.tolist(),
                "knee_angle_deg": np.degrees(self.knee_angle_rad).tolist(),
                "knee_moment_nm": self.knee_moment_nm.tolist()}

    def to_frame(self) -> pd.DataFrame:
        """Columns ``time_s``, ``knee_angle_deg``, ``knee_angle_rad``, ``knee_moment_nm``."""
        import pandas as pd

        df = pd.DataFrame({"time_s": self.time_s,
                           "knee_angle_deg": np.degrees(self.knee_angle_rad),
                           "knee_angle_rad": self.knee_angle_rad,
                           "knee_moment_nm": self.knee_moment_nm})
        df.attrs["source"] = self.source
        return df


def gait_data_path(name: str = GAIT_DATA_FILE) -> Path:
    """Path of a shipped walking data file (default: the OpenSim stride).

    Parameters
    ----------
    name : str
        File name inside ``exofric/data/gait`` (``walking_stride_opensim.csv``,
        ``PROVENANCE.md``, ``LICENSE-Apache-2.0.txt``).

    Returns
    -------
    pathlib.Path

    Raises
    ------
    InputError
        No such shipped file.

    Examples
    --------
    >>> gait_data_path().name
    'walking_stride_opensim.csv'
    """
    p = Path(str(files("exofric") / "data" / "gait" / name))
    if not p.is_file():
        raise InputError(f"no shipped gait data file {name!r}", param="name")
    return p


# ---- columns --------------------------------------------------------------------------------


def _coordinate(header: str) -> str:
    """The name without its unit: ``/jointset/walker_knee_r/knee_angle_r/value`` ->
    ``knee_angle_r``, ``Knee moment [kN m]`` -> ``knee_moment``, ``knee_angle_deg`` ->
    ``knee_angle``."""
    h = header.strip()
    if "/" in h and not h.startswith("Time /"):
        parts = [p for p in h.split("/") if p.strip()]
        if len(parts) >= 2 and parts[-1] in ("value", "speed"):
            return parts[-2].lower() if parts[-1] == "value" else parts[-2].lower() + "_speed"
    key, own = header_key(h)
    if own is not None:
        tok = unit_token(own)
        if key.endswith("_" + tok):
            key = key[: -len(tok) - 1]
    return re.sub(r"_(deg|degrees|rad|radians)$", "", split_key(key)[0])


def _find(grid: Grid, pattern: re.Pattern[str], side: str, what: str,
          columns: Mapping[str, str], key: str) -> int:
    """Index of the one column of ``what`` (by ``columns[key]`` or by name)."""
    heads = grid.headers
    if key in columns:
        want = columns[key].strip()
        idx = [i for i, h in enumerate(heads) if h.strip() == want] or \
            [i for i, h in enumerate(heads) if h.strip().lower() == want.lower()]
        if len(idx) != 1:
            how = "is not in the file" if not idx else "is in the file more than once"
            raise InputError(f"{grid.source}: column {want!r} (columns[{key!r}]) {how} "
                             f"(columns found: {', '.join(heads[:12])})", param="columns")
        return idx[0]
    hits: list[tuple[int, str | None]] = []
    for i, h in enumerate(heads):
        m = pattern.match(_coordinate(h))
        if m is not None:
            hits.append((i, m.group("side")))
    if len(hits) > 1:
        hits = [hc for hc in hits if hc[1] == side] or hits
    if not hits:
        raise InputError(f"{grid.source}: no knee {what} column (looked for names like "
                         f"{'knee_angle_r' if what == 'angle' else 'knee_angle_r_moment'}; "
                         f"found: {', '.join(heads[:12])}); name it with columns="
                         f"{{{key!r}: <header>}}", param="columns")
    if len(hits) > 1:
        names = " and ".join(repr(heads[i]) for i, _ in hits)
        raise InputError(f"{grid.source}: several knee {what} columns, {names}: choose one with "
                         f"columns={{{key!r}: <header>}}", param="columns")
    return hits[0][0]


def _unit_of(grid: Grid, i: int) -> str | None:
    own = grid.units[i]
    if own is not None:
        return own
    m = re.search(r"_(deg|degrees|rad|radians)$", grid.headers[i].strip().lower())
    return m.group(1) if m else None


def _storage_angle_unit(grid: Grid) -> str | None:
    """'deg' / 'rad' from an OpenSim header (``inDegrees=``, 'Angles are in degrees')."""
    for line in grid.metadata:
        s = line.strip().lower().replace(" ", "")
        if s.startswith("indegrees="):
            return "deg" if s.endswith("yes") else "rad"
        if "anglesareindegrees" in s:
            return "deg"
        if "anglesareinradians" in s:
            return "rad"
    return None


def _angle_factor(unit: str, where: str) -> float:
    """Multiplier from ``unit`` (as written) to rad, by pint."""
    tok = unit_token(unit)
    src = _pint_unit(tok, unit)
    ureg = _registry()
    if src is None or src.dimensionality != ureg.Unit("radian").dimensionality:
        raise InputError(f"{where} is in {unit!r}, which is not an angle (deg or rad)",
                         param="columns")
    return float(ureg.Quantity(1.0, src).to("radian").magnitude)


def _series(grid: Grid, i: int) -> NDArray[np.float64]:
    v = numeric_column(grid.column(i), grid.headers[i], grid.source, grid.row)
    if not np.all(np.isfinite(v)):
        k = int(np.flatnonzero(~np.isfinite(v))[0])
        what = "empty or NaN" if np.isnan(v[k]) else f"not finite: {v[k]:g}"
        raise InputError(f"{grid.source}: {grid.row(k)}, column {grid.headers[i]!r} is {what}")
    return v


def _time(grid: Grid, columns: Mapping[str, str], storage: bool) -> NDArray[np.float64]:
    if "time" in columns:
        i = _find(grid, re.compile(r"^$"), "", "time", columns, "time")
    else:
        cands = [i for i, k in enumerate(grid.keys) if split_key(k)[0] in ("time", "t")]
        if len(cands) != 1:
            raise InputError(f"{grid.source}: {'no' if not cands else 'more than one'} time "
                             f"column (found: {', '.join(grid.headers[:12])}); name it with "
                             "columns={'time': <header>}", param="columns")
        i = cands[0]
    unit = grid.units[i] or ("s" if storage else None)
    if unit is None:
        raise InputError(f"{grid.source}: column {grid.headers[i]!r} has no unit; write it as "
                         "'time_s' or 'time (ms)'", param="columns")
    t = _series(grid, i) * unit_factor(unit, "s", what=f"{grid.source}: column "
                                                       f"{grid.headers[i]!r}")
    bad = np.flatnonzero(np.diff(t) <= 0.0)
    if bad.size:
        k = int(bad[0])
        raise InputError(f"{grid.source}: time must increase strictly (s), got "
                         f"{t[k]:g} then {t[k + 1]:g} at {grid.row(k + 1)}", param="time_s")
    if t.size < _MIN_SAMPLES:
        raise InputError(f"{grid.source}: at least {_MIN_SAMPLES} samples are needed, got "
                         f"{t.size}")
    return t


def _angle(grid: Grid, columns: Mapping[str, str], side: str, storage: bool,
           angle_unit: str | None) -> NDArray[np.float64]:
    i = _find(grid, _ANGLE, side, "angle", columns, "knee_angle")
    unit = angle_unit or _unit_of(grid, i) or (_storage_angle_unit(grid) if storage else None)
    where = f"{grid.source}: column {grid.headers[i]!r}"
    if unit is None:
        raise InputError(f"{where} states no unit: write 'knee_angle_deg' or "
                         "'knee angle (rad)', or give angle_unit='deg' or 'rad'",
                         param="angle_unit")
    fac = _angle_factor(unit, where)
    a = _series(grid, i) * fac
    span = float(np.degrees(a.max() - a.min()))
    if span > 180.0:
        raise InputError(f"{where}: the knee angle spans {span:.0f} deg when read as "
                         f"{unit} (> 180 deg, beyond any knee): wrong unit? (degrees labelled "
                         "as radians)", param="angle_unit")
    return a


def _moment(grid: Grid, columns: Mapping[str, str], side: str,
            storage: bool) -> NDArray[np.float64]:
    i = _find(grid, _MOMENT, side, "moment", columns, "knee_moment")
    unit = grid.units[i] or ("N m" if storage else None)
    where = f"{grid.source}: column {grid.headers[i]!r}"
    if unit is None:
        raise InputError(f"{where} has no unit; write it as 'knee_moment_nm' or "
                         "'knee moment (N m)'", param="columns")
    if "kg" in unit.lower():
        raise InputError(f"{where} is in {unit} (normalised to body mass): give the moment in "
                         "Nm", param="columns")
    return _series(grid, i) * unit_factor(unit, "nm", what=where)


def _meta_number(lines: list[str], names: str) -> float | None:
    """A number stated as ``name: value`` (or ``name = value``) on a header/comment line."""
    for line in lines:
        m = re.match(rf"^\s*(?:{names})\s*[:=]\s*([0-9.eE+-]+)\s*(?:kg)?\s*$", line,
                     re.IGNORECASE)
        if m:
            return float(m.group(1))
    return None


def _check_columns(columns: Mapping[str, str] | None) -> dict[str, str]:
    out: dict[str, str] = {}
    for k, v in (columns or {}).items():
        base = str(k).strip().lower()
        base = re.sub(r"_(s|ms|deg|rad|nm)$", "", base)
        if base not in GAIT_COLUMNS:
            raise InputError(f"columns: unknown key {k!r} (allowed: {', '.join(GAIT_COLUMNS)})",
                             param="columns")
        out[base] = str(v)
    return out


def _grid(path: str | Path) -> tuple[Grid, bool]:
    p = Path(path)
    grids = read_grids(p)
    return grids[0], p.suffix.lower() in _STORAGE


def read_gait(
    path: str | Path,
    columns: Mapping[str, str] | None = None,
    *,
    moment_path: str | Path | None = None,
    side: str = "r",
    angle_unit: str | None = None,
    flexion_sign: int | None = None,
) -> GaitData:
    """Read walking data: time, knee flexion angle and knee moment (see the module docstring).

    Parameters
    ----------
    path : str or Path
        An OpenSim ``.sto``/``.mot`` file or a table (CSV, TSV, ...) with time, the knee angle
        (deg or rad, by the header's unit or OpenSim's ``inDegrees``) and, unless
        ``moment_path`` is given, the knee moment (Nm).
    columns : mapping of str to str, optional
        ``{key: header}`` for columns with other names; keys ``time``, ``knee_angle``,
        ``knee_moment`` (e.g. ``{"knee_angle": "/jointset/knee_l/knee_angle_l/value"}``).
    moment_path : str or Path, optional
        A second file with the knee moment (OpenSim's inverse-dynamics ``.sto``): the moment is
        interpolated linearly onto the angle's times over the overlap of the two files.
    side : {'r', 'l'}
        Which knee when the file has both (``knee_angle_r``, ``knee_angle_l``).
    angle_unit : {'deg', 'rad'} or None
        The angle's unit when the file states none.
    flexion_sign : {1, -1} or None
        Sign that makes flexion positive (applied to angle and moment); None: detected (-1
        when the angle lies mostly below zero, as in OpenSim's gait2392 models).

    Returns
    -------
    GaitData

    Raises
    ------
    InputError
        One line naming the file: no knee angle or moment column (or several), an unknown or
        non-angle unit, an angle spanning more than 180 deg (wrong unit), time not strictly
        increasing, fewer than 10 samples, files that do not overlap in time.

    Examples
    --------
    >>> g = read_gait(gait_data_path())
    >>> g.n_samples, round(g.duration_s, 3), g.body_mass_kg
    (1144, 1.143, 85.27)
    >>> round(float(np.degrees(g.knee_angle_rad.max())), 1), round(g.knee_work_j, 1)
    (72.0, -22.4)
    """
    if side not in ("r", "l"):
        raise InputError(f"side must be 'r' or 'l', got {side!r}", param="side")
    if flexion_sign not in (None, 1, -1):
        raise InputError(f"flexion_sign must be 1, -1 or None, got {flexion_sign!r}",
                         param="flexion_sign")
    cols = _check_columns(columns)
    grid, storage = _grid(path)
    t = _time(grid, cols, storage)
    a = _angle(grid, cols, side, storage, angle_unit)
    meta = list(grid.metadata)
    names = [grid.source]
    if moment_path is None:
        m = _moment(grid, cols, side, storage)
    else:
        g2, st2 = _grid(moment_path)
        t2 = _time(g2, {k: v for k, v in cols.items() if k != "time"}, st2)
        m2 = _moment(g2, cols, side, st2)
        lo, hi = max(t[0], t2[0]), min(t[-1], t2[-1])
        keep = (t >= lo - 1e-9) & (t <= hi + 1e-9)
        if int(keep.sum()) < _MIN_SAMPLES:
            raise InputError(f"{grid.source} ({t[0]:g}-{t[-1]:g} s) and {g2.source} "
                             f"({t2[0]:g}-{t2[-1]:g} s) overlap in fewer than {_MIN_SAMPLES} "
                             "samples", param="moment_path")
        t, a = t[keep], a[keep]
        m = np.interp(t, t2, m2)
        meta += list(g2.metadata)
        names.append(g2.source)
    sign = flexion_sign
    if sign is None:
        sign = -1 if float(np.median(a)) < 0.0 and float(a.max()) < np.radians(30.0) else 1
    note = "" if sign == 1 else " (flexion-negative convention: angle and moment negated)"
    stance = _meta_number(meta, "stance_fraction")
    if stance is not None and not 0.2 <= stance <= 0.9:
        raise InputError(f"{grid.source}: stance_fraction must be in 0.2-0.9, got {stance:g}",
                         param="stance_fraction")
    return GaitData(t - t[0], sign * a, sign * m, " + ".join(names) + note,
                    _meta_number(meta, "body_?mass(?:_kg)?|mass_kg"), stance, tuple(meta))
