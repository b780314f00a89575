"""Generic file formats: unit-checked CSV tables, TOML, JSON, and atomic writes.

Every reader here returns plain validated data or raises
:class:`~exofric.errors.InputError` with one line naming the file, the row or
column and what is allowed. Column names carry their unit (``pressure_mpa``,
``outer_diameter_mm``, ``friction_n``, ``time_s``); a column with the same
quantity in another unit (``pressure_kpa``, ``Pressure (kPa)``) is converted with
pint by :func:`read_table` (through :func:`exofric.io.read_measured_table`),
never silently reinterpreted. A missing file is an :class:`OSError` for TOML and JSON
(the CLI prints it as one line) and an :class:`InputError` for tables.

Every writer is atomic: it writes a hidden temporary file in the target's
directory and renames it over the target (:func:`atomic_path`), so a crash or a
kill never leaves a partial file under the final name.
"""

from __future__ import annotations

import contextlib
import json
import os
import tomllib
import uuid
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from exofric._json import jsonable
from exofric.errors import InputError

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "atomic_path", "jsonable", "read_json", "read_table", "read_toml", "UNIT_SUFFIXES",
    "write_json", "write_text",
]

#: Unit suffixes exofric understands in column names, and their meaning.
UNIT_SUFFIXES = {"mpa": "MPa", "mm": "mm", "n": "N", "s": "s", "nm": "Nm", "pct": "%"}
def read_table(
    path: str | Path,
    required: Sequence[str],
    optional: Sequence[str] = (),
    *,
    text_columns: Sequence[str] = (),
    nonnegative: Sequence[str] | None = None,
    unique_within: tuple[str, str | None] | None = None,
    min_rows: int = 2,
    columns: Mapping[str, str] | None = None,
) -> pd.DataFrame:
    """Read a measured table (CSV and every format of :func:`read_measured_table`), check it.

    Parameters
    ----------
    path : str or Path
        A table with a header row: CSV/TSV/``;`` (decimal comma, UTF-16 or Latin-1, a vendor
        preamble and a units row are detected), LabVIEW ``.lvm``, NI ``.tdms``, Parquet or
        ``.xlsx``; ``#`` starts a comment; columns in any order; unknown columns are ignored.
    required : sequence of str
        Column names that must be present, with exofric's unit suffix (e.g. ``pressure_mpa``);
        a file column in another unit (``pressure_kpa``, ``Pressure (kPa)``, a units row) is
        converted with pint.
    optional : sequence of str
        Numeric columns read when present.
    text_columns : sequence of str
        Columns (among required/optional) kept as text, e.g. a ``test`` label.
    nonnegative : sequence of str, optional
        Columns that must be >= 0 (default: all numeric columns).
    unique_within : (column, group) or None
        ``column`` must not repeat within each value of ``group`` (or at all if
        ``group`` is None), e.g. ``("pressure_mpa", "test")``.
    min_rows : int
        Fewest data rows accepted (per group when ``unique_within`` has a group).
    columns : mapping of str to str, optional
        ``{key: header}`` for columns with other names (``{"pressure_kpa": "P1"}``; see
        :func:`exofric.io.parse_column_map`).

    Returns
    -------
    pandas.DataFrame
        Only the required and present optional columns, numeric ones as float in the unit of
        their name. ``attrs``: ``units`` and ``columns`` (canonical -> unit and header as
        found), ``metadata`` (comment and preamble lines).

    Examples
    --------
    >>> from exofric import paper
    >>> df = read_table(paper.data_path("table1_test.csv"), ["pressure_mpa", "outer_diameter_mm"])
    >>> df["outer_diameter_mm"].tolist()
    [8.53, 8.78, 9.14, 9.44]
    """
    import numpy as np
    import pandas as pd  # lazy: reading TOML/JSON or writing files must not load pandas

    from exofric.io._table import locate_columns

    df, picks, grid = _fast_numeric(path, required, optional, columns, text_columns,
                                    nonnegative)
    if df is None:   # text columns, or a cell to name: read as text, check cell by cell
        grid, picks = locate_columns(path, list(required), list(optional), columns=columns,
                                     text_columns=text_columns, text=True, comment=True)
        df = pd.DataFrame({c: pd.Series(grid.column(pk.index)).reset_index(drop=True)
                           for c, pk in picks.items()})
    name = grid.source
    keep = list(df.columns)
    numeric = [c for c in keep if c not in text_columns]
    checks = numeric if nonnegative is None else [c for c in nonnegative if c in numeric]
    for col in numeric:
        if df[col].dtype.kind == "f":   # the fast path checked it already
            continue
        raw = df[col].astype(str).str.strip()
        vals = pd.to_numeric(raw, errors="coerce").to_numpy(dtype=float)
        # vectorised checks (10^6-row tables); the first bad row is named as before
        bad_nan = np.isnan(vals)
        bad_inf = ~bad_nan & ~np.isfinite(vals)
        bad_neg = (vals < 0) if col in checks else np.zeros(vals.size, bool)
        bad = bad_nan | bad_inf | bad_neg
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            r = str(raw.iloc[i])
            row = f"data row {i + 1}"
            if bad_nan[i]:
                what = ("empty" if r == "" else
                        ("NaN" if r.lower() == "nan" else f"not a number: {r!r}"))
                raise InputError(f"{name}: {row}, column {col!r} is {what}")
            if bad_inf[i]:
                raise InputError(f"{name}: {row}, column {col!r} must be finite, got {r}")
            raise InputError(f"{name}: {row}, column {col!r} must be >= 0, got {r}")
        df[col] = vals * picks[col].factor
    for col in text_columns:
        if col in df.columns:
            df[col] = df[col].astype(str).str.strip()
    if unique_within is not None:
        col, group = unique_within
        groups = df.groupby(group, sort=False) if group and group in df.columns else [(None, df)]
        for g, sub in groups:
            dup = sub[col][sub[col].duplicated()]
            where = f" in {group} {g!r}" if g is not None else ""
            if len(dup):
                raise InputError(f"{name}: duplicate {col} {dup.iloc[0]:g}{where}")
            if len(sub) < min_rows:
                raise InputError(
                    f"{name}: needs at least {min_rows} data row{'s' * (min_rows != 1)}"
                    f"{where}, got {len(sub)}"
                )
    elif len(df) < min_rows:
        raise InputError(f"{name}: needs at least {min_rows} data row{'s' * (min_rows != 1)}, "
                         f"got {len(df)}")
    df = df.reset_index(drop=True)
    df.attrs.update({"units": {c: pk.unit for c, pk in picks.items() if pk.unit is not None},
                     "columns": {c: pk.header for c, pk in picks.items()},
                     "metadata": list(grid.metadata), "format": grid.fmt})
    return df


def _fast_numeric(path: str | Path, required: Sequence[str], optional: Sequence[str],
                  columns: Mapping[str, str] | None, text_columns: Sequence[str],
                  nonnegative: Sequence[str] | None) -> tuple[Any, Any, Any]:
    """(DataFrame, picks, grid) when every column read is numeric, finite and within the
    checks (a 10^6-row table in a C parse), else (None, ...) and the caller reads it as text to
    name the offending cell; converted to the unit of each column's name."""
    import numpy as np
    import pandas as pd

    from exofric.io._table import locate_columns

    grid, picks = locate_columns(path, list(required), list(optional), columns=columns,
                                 text_columns=text_columns, comment=True)
    if any(c in picks for c in text_columns):
        return None, picks, grid
    out = {}
    for c, pk in picks.items():
        vals = np.asarray(grid.column(pk.index))
        if vals.dtype.kind not in "fiu":
            return None, picks, grid
        vals = vals.astype(float)
        if not np.all(np.isfinite(vals)):
            return None, picks, grid
        if (nonnegative is None or c in nonnegative) and np.any(vals < 0):
            return None, picks, grid
        out[c] = vals * pk.factor
    return pd.DataFrame(out), picks, grid


@contextlib.contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it onto ``path`` when the block succeeds.

    The temporary file is ``.<name>.<random>.tmp`` in the same directory (so the final
    :func:`os.replace` is atomic on one file system); parent directories are created. If the
    block raises, the temporary file is deleted and ``path`` is left as it was (absent or the
    previous complete version). A killed process can leave a ``.<name>.*.tmp`` file, never a
    partial ``path``.

    Parameters
    ----------
    path : str or Path
        The final file.

    Yields
    ------
    Path
        The temporary file to write (it does not exist yet).

    Examples
    --------
    >>> import tempfile
    >>> target = Path(tempfile.mkdtemp()) / "out.txt"
    >>> with atomic_path(target) as tmp:
    ...     _ = tmp.write_text("done")
    >>> target.read_text(), sorted(p.name for p in target.parent.iterdir())
    ('done', ['out.txt'])
    """
    final = Path(path)
    final.parent.mkdir(parents=True, exist_ok=True)
    tmp = final.parent / f".{final.name}.{uuid.uuid4().hex}.tmp"
    try:
        yield tmp
        os.replace(tmp, final)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def write_text(path: str | Path, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically (see :func:`atomic_path`); return the path.

    Parameters
    ----------
    path : str or Path
        The file to write (parent directories are created).
    text : str
        Its whole content.

    Examples
    --------
    >>> import tempfile
    >>> write_text(Path(tempfile.mkdtemp()) / "rig.csv", "pressure_mpa,friction_n\\n").name
    'rig.csv'
    """
    p = Path(path)
    with atomic_path(p) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return p


def write_json(obj: Any, path: str | Path, *, indent: int = 2) -> Path:
    """Write ``obj`` (see :func:`jsonable`) as indented JSON atomically; return the path.

    Parameters
    ----------
    obj : Any
        Dicts, lists, numbers, strings, NumPy values; NaN and infinities are written as null.
    path : str or Path
        The file to write (parent directories are created).
    indent : int
        Spaces per indentation level.

    Examples
    --------
    >>> import tempfile
    >>> p = write_json({"gamma": 0.7168, "f0_n": float("nan")}, Path(tempfile.mkdtemp()) / "r.json")
    >>> read_json(p)
    {'gamma': 0.7168, 'f0_n': None}
    """
    return write_text(path, json.dumps(jsonable(obj), indent=indent) + "\n")


def _read_text(p: Path) -> str:
    """UTF-8 text of ``p``; OSError (missing file...) passes through, bad bytes -> InputError."""
    try:
        return p.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(f"{p}: cannot read as UTF-8 text ({exc.reason})") from None


def read_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML file into a dict.

    Parameters
    ----------
    path : str or Path
        A UTF-8 TOML file.

    Returns
    -------
    dict
        The document's tables and values.

    Raises
    ------
    InputError
        A syntax error (one line naming the file, the line and the column) or text that is
        not UTF-8.
    OSError
        The file is missing or unreadable (:class:`FileNotFoundError` for a missing file).

    Examples
    --------
    >>> from exofric import paper
    >>> read_toml(paper.data_path("paper.toml"))["scalars"]["gamma"]["value"]
    0.7168
    """
    p = Path(path)
    text = _read_text(p)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        msg = str(exc).splitlines()[0]
        if msg.endswith("(at end of document)"):
            lines = text.split("\n")
            msg = (msg.removesuffix("(at end of document)")
                   + f"(at end of document, line {len(lines)}, column {len(lines[-1]) + 1})")
        raise InputError(f"{p}: not valid TOML: {msg}") from None


def read_json(path: str | Path) -> Any:
    """Read a JSON file.

    Parameters
    ----------
    path : str or Path
        A UTF-8 JSON file.

    Returns
    -------
    Any
        The decoded value (usually a dict).

    Raises
    ------
    InputError
        Invalid JSON (one line naming the file, the line and the column) or text that is
        not UTF-8.
    OSError
        The file is missing or unreadable.

    Examples
    --------
    >>> import tempfile
    >>> read_json(write_json({"pressure_mpa": [0.2, 0.4]}, Path(tempfile.mkdtemp()) / "a.json"))
    {'pressure_mpa': [0.2, 0.4]}
    """
    p = Path(path)
    text = _read_text(p)
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"{p.name}: not valid JSON ({exc.msg} at line {exc.lineno}, column "
                         f"{exc.colno})") from None
