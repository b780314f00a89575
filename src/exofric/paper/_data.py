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
import tomllib
from functools import lru_cache
from importlib.resources import files
from pathlib import Path
from typing import Any

__all__ = [
    "data_path",
    "load",
    "scalar",
    "table1",
    "table2",
    "table3",
    "table4",
    "eq8",
    "to_dict",
    "notes_path",
]


def data_path(name: str) -> Path:
    """Path of a shipped paper data file, e.g. ``'table1_test.csv'``."""
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
    """The whole ``paper.toml`` as a dict (cached; do not mutate)."""
    with data_path("paper.toml").open("rb") as fh:
        return tomllib.load(fh)


def scalar(name: str) -> float:
    """A reported scalar by key (see ``[scalars]`` in paper.toml), in its unit."""
    sc = load()["scalars"]
    if name not in sc:
        raise KeyError(f"unknown paper scalar {name!r}; known: {', '.join(sorted(sc))}")
    return float(sc[name]["value"])


def table1() -> dict[str, Any]:
    """Table 1: pressures (MPa), test and simulated outer diameters (mm), errors (%)."""
    return dict(load()["table1"])


def table2() -> dict[str, float]:
    """Table 2 as printed (MPa, 1/MPa), including its C10 slip."""
    return {k: v for k, v in load()["table2"].items() if k != "provenance"}


def table3() -> list[dict[str, Any]]:
    """Table 3: one dict per test with hole/tube/wire diameters (mm) and deviation (%)."""
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
    """Table 4: ANOVA p-value per test number."""
    t = load()["table4"]
    return {int(n): float(p) for n, p in zip(t["test"], t["p_value"], strict=True)}


def eq8() -> tuple[float, float, float, float]:
    """Eq 8 cubic coefficients (c3, c2, c1, c0): N [N] as a function of P [MPa]."""
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
    """All paper data, JSON-ready (NaN -> None); scalars flattened to ``{key: value}``."""
    raw = load()
    out: dict[str, Any] = {k: _clean(v) for k, v in raw.items() if k != "scalars"}
    out["scalars"] = {k: v["value"] for k, v in raw["scalars"].items()}
    out["provenance"] = {k: v["provenance"] for k, v in raw["scalars"].items()}
    return out
