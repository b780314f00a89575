"""Shared presentation helpers for CLI commands (no computation here).

Module level imports only typer and rich: every command module imports this one, so whatever
it imports, ``exofric --help`` pays for (``tests/test_startup.py``).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import typer
from rich.console import Console
from rich.table import Table

JSON_OPTION = typer.Option(False, "--json", help="Print exactly one JSON object on stdout.")

console = Console()


def emit(obj: dict[str, Any], as_json: bool, render: Callable[[], None]) -> None:
    """Print ``obj`` as one JSON object if ``as_json``, else call ``render``."""
    if as_json:
        from exofric.io import jsonable

        print(json.dumps(jsonable(obj)))
    else:
        render()


def parse_floats(name: str, text: str) -> list[float]:
    """Parse ``"0.1,0.2, 0.3"`` into floats; the error names the option."""
    from exofric.errors import InputError

    out = []
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        try:
            out.append(float(part))
        except ValueError:
            raise InputError(f"{name} must be comma-separated numbers, got {part!r}") from None
    if not out:
        raise InputError(f"{name} must list at least one number")
    return out


def kv_table(title: str, rows: list[tuple[str, str, str]]) -> Table:
    """A two/three-column rich table: quantity, value, unit."""
    t = Table(title=title, show_header=True, header_style="bold")
    t.add_column("quantity")
    t.add_column("value", justify="right")
    t.add_column("unit")
    for r in rows:
        t.add_row(*r)
    return t


def save_figure(fig: Any, path: str | Path) -> Path:
    """Write a figure drawn by :mod:`exofric.plots` to ``path`` (``--plot PATH`` options).

    Creates the parent directory (as every ``--plot`` always did), then
    :func:`exofric.plots.save` writes the image and closes the figure.
    """
    from exofric.plots import save

    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    return save(fig, p)


def write_outputs(
    res: Any, plot: Path | None, vtu: Path | None, draw: Callable[[Any], Any]
) -> dict[str, str]:
    """Write the optional PNG (the figure ``draw(res)``, see :func:`save_figure`) and the VTU of
    the last state of an FE result (``nodes``, ``elements``, ``displacements``,
    ``von_mises_mpa``); return their paths."""
    out: dict[str, str] = {}
    if plot is not None:
        out["plot"] = str(save_figure(draw(res), plot))
    if vtu is not None:
        from exofric.io import write_vtu

        out["vtu"] = str(
            write_vtu(
                vtu,
                res.nodes,
                res.elements,
                res.displacements[-1],
                {"von_mises_mpa": res.von_mises_mpa[-1]},
            )
        )
    return out
