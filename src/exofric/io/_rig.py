"""Readers of rig and curve files: inflation tests, squeeze curves, friction runs, step responses.

Each returns a validated :class:`pandas.DataFrame` with unit-suffixed columns (MPa, mm, N, s)
and ``attrs["source"]`` (the file name, for messages); domain classes build themselves from
the frame (e.g. ``InflationData.from_frame``). Bad files raise
:class:`~exofric.errors.InputError` with one line naming the file and the problem.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from exofric.errors import InputError
from exofric.io._files import read_json, read_table
from exofric.io._table import read_grids, split_key

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "read_friction_table",
    "read_inflation_table",
    "read_squeeze_curve",
    "read_step_response",
]


def _named(df: pd.DataFrame, path: str | Path) -> pd.DataFrame:
    df.attrs["source"] = Path(path).name
    return df


def read_inflation_table(path: str | Path, columns: Mapping[str, str] | None = None
                         ) -> pd.DataFrame:
    """Inflation test CSV: ``pressure_mpa``, ``outer_diameter_mm`` and an optional ``shore``.

    Columns in any order, extra columns ignored, ``#`` comments allowed. Pressures (MPa) and
    diameters (mm) must be numbers >= 0; pressures must not repeat (within a shore value),
    and there must be at least two points (per shore value). Any format and header spelling
    of :func:`exofric.io.read_measured_table` (other units converted).

    Parameters
    ----------
    path : str or Path
        The table (CSV, TSV, LVM, TDMS, Parquet, xlsx).
    columns : mapping of str to str, optional
        ``{key: header}`` for columns with other names (``{"pressure_kpa": "P"}``).

    Returns
    -------
    pandas.DataFrame
        Columns ``pressure_mpa``, ``outer_diameter_mm`` (and ``shore``, Shore A, when
        present), in file order; ``attrs["source"]`` is the file name.

    Raises
    ------
    InputError
        Missing file or column, a non-numeric/empty/NaN/negative cell (naming the row),
        duplicate pressures, fewer than two points.

    Examples
    --------
    >>> from exofric import paper
    >>> df = read_inflation_table(paper.data_path("table1_test.csv"))
    >>> df["outer_diameter_mm"].tolist(), df.attrs["source"]
    ([8.53, 8.78, 9.14, 9.44], 'table1_test.csv')
    """
    df = read_table(path, ("pressure_mpa", "outer_diameter_mm"), ("shore",),
                    unique_within=("pressure_mpa", "shore"), min_rows=2, columns=columns)
    return _named(df, path)


def _curve_from_json(p: Path) -> tuple[np.ndarray, np.ndarray]:
    if not p.is_file():
        raise InputError(f"{p}: file not found")
    obj = read_json(p)
    if not isinstance(obj, dict):
        raise InputError(f"{p.name}: expected a JSON object with pressure_mpa, squeeze_force_n")
    for key in ("pressure_mpa", "squeeze_force_n"):
        if key not in obj:
            raise InputError(f"{p.name}: missing key {key!r} (need pressure_mpa, "
                             "squeeze_force_n)")
    try:
        pr = np.asarray(obj["pressure_mpa"], dtype=float).ravel()
        n = np.asarray(obj["squeeze_force_n"], dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{p.name}: pressure_mpa and squeeze_force_n must be number "
                         "lists") from None
    if pr.size != n.size or pr.size < 2:
        raise InputError(f"{p.name}: pressure_mpa and squeeze_force_n need >= 2 entries of "
                         f"equal length, got {pr.size} and {n.size}")
    if not (np.all(np.isfinite(pr)) and np.all(np.isfinite(n))):
        raise InputError(f"{p.name}: pressure_mpa and squeeze_force_n must be finite")
    if np.any(pr < 0):
        raise InputError(f"{p.name}: pressure_mpa must be >= 0")
    return pr, n


def read_squeeze_curve(path: str | Path, columns: Mapping[str, str] | None = None
                       ) -> pd.DataFrame:
    """Squeeze curve N(P): pressure (MPa) and total squeezing force (N), from JSON or CSV.

    JSON (suffix ``.json``): one object with lists ``pressure_mpa`` and ``squeeze_force_n``
    (as printed by ``exofric squeeze --json``; other keys ignored). Otherwise a CSV with
    columns ``pressure_mpa,squeeze_force_n``. Pressures must be >= 0 and distinct.

    Parameters
    ----------
    path : str or Path
        The JSON file, or a table in any format of :func:`exofric.io.read_measured_table`.
    columns : mapping of str to str, optional
        ``{key: header}`` for table columns with other names.

    Returns
    -------
    pandas.DataFrame
        Columns ``pressure_mpa``, ``squeeze_force_n``, sorted by pressure (strictly
        increasing); ``attrs["source"]`` is the file name.

    Raises
    ------
    InputError
        Missing file, invalid JSON/CSV, missing key or column, unequal lengths, fewer than
        two points, non-finite or negative pressures, a repeated pressure.

    Examples
    --------
    >>> import json, tempfile
    >>> from pathlib import Path
    >>> f = Path(tempfile.mkdtemp()) / "n.json"
    >>> _ = f.write_text(json.dumps({"pressure_mpa": [0.4, 0.2], "squeeze_force_n": [60, 20]}))
    >>> read_squeeze_curve(f)["pressure_mpa"].tolist()
    [0.2, 0.4]
    """
    import pandas as pd

    p = Path(path)
    if p.suffix.lower() == ".json":
        pr, n = _curve_from_json(p)
    else:
        df = read_table(p, ["pressure_mpa", "squeeze_force_n"],
                        unique_within=("pressure_mpa", None), columns=columns)
        pr = df["pressure_mpa"].to_numpy(float)
        n = df["squeeze_force_n"].to_numpy(float)
    o = np.argsort(pr, kind="stable")
    pr, n = pr[o], n[o]
    if np.any(np.diff(pr) <= 0):
        raise InputError(f"{p.name}: duplicate pressure_mpa {pr[1:][np.diff(pr) <= 0][0]:g}")
    return _named(pd.DataFrame({"pressure_mpa": pr, "squeeze_force_n": n}), p)


def _header(path: str | Path) -> tuple[list[str], list[str]]:
    """(matching keys of the header row, metadata lines); empty if unreadable."""
    try:
        grid = read_grids(path, text=True, comment=True)[0]
    except (InputError, OSError):
        return [], []
    return list(grid.keys), list(grid.metadata)


def read_friction_table(path: str | Path, columns: Mapping[str, str] | None = None
                        ) -> pd.DataFrame:
    """Friction CSV: friction points or the per-pull table of ``exofric reduce`` (MPa, N).

    Two layouts are read (columns in any order, extra columns ignored, ``#`` comments allowed):

    * points: ``pressure_mpa,friction_n`` and an optional ``test`` label;
    * pulls (what ``exofric reduce`` writes): ``pressure_mpa``, ``kinetic_n`` and optionally
      ``static_n``, ``direction``, ``branch``, ``plateau`` (int), ``pull`` (int), ``test``;
      when there is no ``friction_n`` column, the kinetic friction ``kinetic_n`` is the
      friction.

    Pressures may repeat, also within one test: repeated pulls at one pressure are
    replicates, which :func:`exofric.friction.fit_gamma` treats as clusters.

    Any format and header spelling of :func:`exofric.io.read_measured_table` (a TSV, a
    ``;`` file with decimal commas, ``Friction (N)``, other units converted).

    Parameters
    ----------
    path : str or Path
        The table.
    columns : mapping of str to str, optional
        ``{key: header}`` for columns with other names (``{"friction_n": "F"}``).

    Returns
    -------
    pandas.DataFrame
        In file order: ``pressure_mpa`` (MPa), ``friction_n`` (N), ``test`` (text; ``""``
        without a test column), ``group`` (the replicate cluster label: ``"plateau <k>"`` from
        a ``plateau`` column, prefixed ``"<test>|"`` when the test is not empty, else
        ``"<test>|<pressure:g>"``) and ``branch`` (text; ``""`` without a branch column).
        ``attrs["source"]`` is the file name, ``attrs["synthetic"]`` is True when a ``#``
        comment line says SYNTHETIC (files written by ``exofric rig``) and ``attrs["kind"]``
        is ``"pulls"`` (a ``kinetic_n`` or ``pull`` column) or ``"points"``.

    Raises
    ------
    InputError
        Missing file or column (``friction_n``, or ``kinetic_n`` for a pull table), a bad cell
        (naming the row), fewer than two points per test.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> f = Path(tempfile.mkdtemp()) / "f.csv"
    >>> _ = f.write_text("# SYNTHETIC\\npressure_mpa,friction_n\\n0.3,20\\n0.4,40\\n0.4,41\\n")
    >>> df = read_friction_table(f)
    >>> df["friction_n"].tolist(), df["test"].tolist(), df.attrs["synthetic"]
    ([20.0, 40.0, 41.0], ['', '', ''], True)
    >>> df["group"].tolist(), df.attrs["kind"]
    (['|0.3', '|0.4', '|0.4'], 'points')
    """
    keys, comments = _header(path)
    bases = {split_key(k)[0] for k in keys}
    mapped = {split_key(str(k).lower())[0] for k in (columns or {})}
    force = "friction_n" if "friction" in bases | mapped or "kinetic" not in bases | mapped \
        else "kinetic_n"
    cols = bases | mapped
    text = ["test", "branch"]
    try:
        df = read_table(path, ["pressure_mpa", force], optional=["test", "branch", "plateau"],
                        text_columns=text, min_rows=2, columns=columns)
    except InputError as exc:
        if "missing column 'friction_n'" not in str(exc):
            raise
        raise InputError(f"{exc}; a per-pull table (exofric reduce) has kinetic_n "
                         "instead") from None
    name = Path(path).name
    if force != "friction_n":
        df = df.rename(columns={force: "friction_n"})
    for col in text:
        if col not in df.columns:
            df[col] = ""
    sizes = df.groupby("test", sort=False).size()
    if (sizes < 2).any():
        t = sizes.index[int((sizes < 2).to_numpy().argmax())]
        raise InputError(f"{name}: needs at least 2 data rows in test {t!r}, got 1")
    prefix = df["test"] + "|"
    if "plateau" in df.columns:
        k = df["plateau"].to_numpy(float)
        if not np.all(k == np.round(k)):
            row = int(np.flatnonzero(k != np.round(k))[0]) + 1
            raise InputError(f"{name}: data row {row}, column 'plateau' must be an integer, "
                             f"got {k[row - 1]:g}")
        import pandas as pd

        lab = "plateau " + pd.Series(k.astype(np.int64), index=df.index).astype(str)
        df["group"] = (df["test"] + "|").where(df["test"] != "", "") + lab
    else:
        # the pressures' distinct values formatted once each (10^6-row tables)
        pv = df["pressure_mpa"].to_numpy(float)
        uniq, inv = np.unique(pv, return_inverse=True)
        df["group"] = prefix + np.array([f"{v:g}" for v in uniq], dtype=object)[inv]
    df = df[["pressure_mpa", "friction_n", "test", "group", "branch"]]
    _named(df, path)
    df.attrs["synthetic"] = any("SYNTHETIC" in ln.upper() for ln in comments)
    df.attrs["kind"] = "pulls" if ("kinetic" in cols or "pull" in cols) else "points"
    return df


def read_step_response(path: str | Path, columns: Mapping[str, str] | None = None
                       ) -> pd.DataFrame:
    """Pressure step response CSV: ``time_s``, ``pressure_mpa`` and optional ``command_mpa``.

    Times (s) must be distinct; pressures and commands (MPa) >= 0; at least 10 samples.

    Parameters
    ----------
    path : str or Path
        The table (any format of :func:`exofric.io.read_measured_table`).
    columns : mapping of str to str, optional
        ``{key: header}`` for columns with other names (``{"time_ms": "t"}``).

    Returns
    -------
    pandas.DataFrame
        Columns ``time_s``, ``pressure_mpa`` (and ``command_mpa`` when present), in file
        order; ``attrs["source"]`` is the file name.

    Raises
    ------
    InputError
        Missing file or column, a bad cell (naming the row), a repeated time, fewer than
        10 samples.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> f = Path(tempfile.mkdtemp()) / "step.csv"
    >>> rows = "\\n".join(f"{0.1 * i:.1f},{min(i, 5) * 0.05:.2f}" for i in range(12))
    >>> _ = f.write_text("time_s,pressure_mpa\\n" + rows)
    >>> df = read_step_response(f)
    >>> len(df), list(df.columns)
    (12, ['time_s', 'pressure_mpa'])
    """
    df = read_table(path, ["time_s", "pressure_mpa"], ["command_mpa"],
                    nonnegative=["pressure_mpa", "command_mpa"], unique_within=("time_s", None),
                    min_rows=10, columns=columns)
    return _named(df, path)
