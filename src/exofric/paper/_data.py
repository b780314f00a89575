"""The paper's reported numbers as data, with provenance.

Everything printed in Ma et al. (2021) that exofric reproduces or checks lives in
``exofric/paper/data/paper.toml`` (tables, scalars, Eq 8) and two CSVs (Table 1
test and simulated columns). This module loads them; nothing here computes.

Examples
--------
>>> from exofric import paper
>>> paper.scalar("gamma")
0.7168
>>> paper.table3()[0]["hole_mm"]
10.0
"""

from __future__ import annotations

import math
from functools import lru_cache
from importlib.resources import files
from pathlib import Path
from typing import TYPE_CHECKING, Any

from exofric.errors import InputError

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "data_path",
    "load",
    "scalar",
    "table1",
    "table1_points",
    "table2",
    "table3",
    "table4",
    "eq8",
    "to_dict",
    "notes_path",
]


def data_path(name: str) -> Path:
    """Path of a shipped paper data file, e.g. ``'table1_test.csv'``.

    Parameters
    ----------
    name : str
        File name inside ``exofric/paper/data`` (``'paper.toml'``, ``'table1_test.csv'``,
        ``'table1_simulated.csv'``).

    Returns
    -------
    pathlib.Path

    Raises
    ------
    FileNotFoundError
        If no such file is shipped.

    Examples
    --------
    >>> data_path("table1_test.csv").name
    'table1_test.csv'
    """
    p = Path(str(files("exofric.paper") / "data" / name))
    if not p.is_file():
        raise FileNotFoundError(f"no shipped paper data file {name!r}")
    return p


def notes_path() -> Path:
    """Path of the shipped paper notes (``paper-notes.md``): every discrepancy we found.

    Examples
    --------
    >>> notes_path().name
    'paper-notes.md'
    """
    return Path(str(files("exofric.paper") / "paper-notes.md"))


@lru_cache(maxsize=1)
def load() -> dict[str, Any]:
    """The whole ``paper.toml`` as a dict (cached; do not mutate).

    Examples
    --------
    >>> sorted(load())[:3]
    ['eq8', 'max_relative_error', 'scalars']
    """
    from exofric.io import read_toml  # lazy: exofric.io imports pandas

    return read_toml(data_path("paper.toml"))


def scalar(name: str) -> float:
    """A reported scalar by key (see ``[scalars]`` in paper.toml), in its unit.

    Parameters
    ----------
    name : str
        Key in ``[scalars]``; its suffix is the unit (``tube_length_mm`` in mm,
        ``base_friction_moment_nm`` in Nm; ``gamma`` is unitless).

    Returns
    -------
    float
        The printed value, in the unit its key names.

    Raises
    ------
    KeyError
        For an unknown key (the message lists the known ones).

    Examples
    --------
    >>> scalar("gamma"), scalar("tube_length_mm")
    (0.7168, 116.0)
    """
    sc = load()["scalars"]
    if name not in sc:
        raise KeyError(f"unknown paper scalar {name!r}; known: {', '.join(sorted(sc))}")
    return float(sc[name]["value"])


def table1() -> dict[str, Any]:
    """Table 1: pressures (MPa), test and simulated outer diameters (mm), errors (%).

    Examples
    --------
    >>> table1()["pressure_mpa"]
    [0.1, 0.2, 0.3, 0.4]
    """
    return dict(load()["table1"])


def table1_points(kind: str = "test") -> pd.DataFrame:
    """Table 1 as inflation points from the shipped CSVs: ``kind`` ``'test'`` or ``'simulated'``.

    ``'test'``: the measured column, ``pressure_mpa`` (MPa) and ``outer_diameter_mm`` (mm);
    ``'simulated'``: the four ANSYS columns with their ``shore`` (Shore A) per row. Read with
    :func:`exofric.io.read_inflation_table` (``attrs["source"]`` is the CSV's name).

    Parameters
    ----------
    kind : {'test', 'simulated'}
        Which Table 1 columns to read.

    Returns
    -------
    pandas.DataFrame
        One row per point; ``pressure_mpa`` (MPa), ``outer_diameter_mm`` (mm) and, for
        ``'simulated'``, ``shore`` (Shore A).

    Examples
    --------
    >>> table1_points("test")["outer_diameter_mm"].tolist()
    [8.53, 8.78, 9.14, 9.44]
    >>> sorted(set(table1_points("simulated")["shore"]))
    [60.0, 62.5, 65.0, 70.0]
    """
    from exofric.io import read_inflation_table

    if kind not in ("test", "simulated"):
        raise InputError(f"kind must be 'test' or 'simulated', got {kind!r}")
    return read_inflation_table(data_path(f"table1_{kind}.csv"))


def table2() -> dict[str, float]:
    """Table 2 as printed (MPa, 1/MPa), including its C10 slip.

    Examples
    --------
    >>> table2()["c10_mpa"], table2()["c01_mpa"]
    (0.6639, 0.0332)
    """
    return {k: v for k, v in load()["table2"].items() if k != "provenance"}


def table3() -> list[dict[str, Any]]:
    """Table 3: one dict per test with hole/tube/wire diameters (mm) and deviation (%).

    Examples
    --------
    >>> row = table3()[0]
    >>> row["test"], row["hole_mm"], row["tube_od_mm"], row["wire_mm"]
    (1, 10.0, 8.3, 1.6)
    """
    t = load()["table3"]
    keys = ["test", "group", "hole_mm", "tube_od_mm", "wire_mm", "max_relative_deviation_pct"]
    rows = []
    for i in range(len(t["test"])):
        row = {k: t[k][i] for k in keys}
        dev = row["max_relative_deviation_pct"]
        row["max_relative_deviation_pct"] = None if math.isnan(dev) else dev
        rows.append(row)
    return rows


def table4() -> dict[int, float]:
    """Table 4: ANOVA p-value (unitless) per test number.

    Examples
    --------
    >>> table4()[6]
    0.0164
    """
    t = load()["table4"]
    return {int(n): float(p) for n, p in zip(t["test"], t["p_value"], strict=True)}


def eq8() -> tuple[float, float, float, float]:
    """Eq 8 cubic coefficients (c3, c2, c1, c0): N [N] as a function of P [MPa].

    Units: c3 in N/MPa^3, c2 in N/MPa^2, c1 in N/MPa, c0 in N.

    Examples
    --------
    >>> eq8()
    (-1957.4, 2412.8, -251.95, -7.9531)
    """
    c = load()["eq8"]["coefficients"]
    return (float(c[0]), float(c[1]), float(c[2]), float(c[3]))


def _clean(obj: Any) -> Any:
    if isinstance(obj, float) and math.isnan(obj):
        return None
    if isinstance(obj, dict):
        return {k: _clean(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_clean(v) for v in obj]
    return obj


def to_dict() -> dict[str, Any]:
    """All paper data, JSON-ready (NaN -> None); scalars flattened to ``{key: value}``.

    Examples
    --------
    >>> d = to_dict()
    >>> d["scalars"]["tube_length_mm"], d["table3"]["test"][:3]
    (116.0, [1, 2, 3])
    """
    raw = load()
    out: dict[str, Any] = {k: _clean(v) for k, v in raw.items() if k != "scalars"}
    out["scalars"] = {k: v["value"] for k, v in raw["scalars"].items()}
    out["provenance"] = {k: v["provenance"] for k, v in raw["scalars"].items()}
    return out
