"""Shared presentation helpers for CLI commands (no computation here).

Module level imports only typer: every command module imports this one, so whatever it
imports, ``exofric --help`` pays for (``tests/test_startup.py``). rich (~30 ms) is imported
when a table is first printed, so ``--json`` runs never import it.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import typer

if TYPE_CHECKING:
    from rich.console import Console
    from rich.table import Table

JSON_OPTION = typer.Option(False, "--json", help="Print exactly one JSON object on stdout.")


class _Console:
    """rich's ``Console``, made when first used (attributes and ``with`` go to it)."""

    _real: Console | None = None

    @staticmethod
    def real() -> Console:
        if _Console._real is None:
            from rich.console import Console

            _Console._real = Console()
        return _Console._real

    def __getattr__(self, name: str) -> Any:
        return getattr(self.real(), name)

    def __enter__(self) -> Console:
        return self.real().__enter__()

    def __exit__(self, *exc: Any) -> None:
        self.real().__exit__(*exc)


console: Console = _Console()  # type: ignore[assignment]


#: Every warning printed during this command (``exofric: warning: ...`` on stderr): ``--json``
#: output lists them under ``warnings``, so a script that reads only the JSON sees them too.
WARNINGS: list[str] = []


def record_warning(message: object, *args: Any, **kwargs: Any) -> None:
    """``warnings.showwarning`` of the CLI: one stderr line, also kept for ``--json``."""
    text = " ".join(str(message).split())
    WARNINGS.append(text)
    print(f"exofric: warning: {text}", file=sys.stderr)


def emit(obj: dict[str, Any], as_json: bool, render: Callable[[], None]) -> None:
    """Print ``obj`` as one JSON object if ``as_json``, else call ``render``.

    The JSON object always has a ``warnings`` list: the command's own (if ``obj`` has one) and
    every warning printed on stderr while it ran (implausible data, ranges of validity).
    """
    if as_json:
        from exofric.io import jsonable

        seen = [*obj.get("warnings", []), *WARNINGS]
        obj = {**obj, "warnings": list(dict.fromkeys(str(w) for w in seen))}
        print(json.dumps(jsonable(obj)))
    else:
        render()


def parse_floats(name: str, text: str) -> list[float]:
    """Parse ``"0.1,0.2, 0.3"`` into floats; the error names the option."""
    from exofric.errors import InputError

    out: list[float] = []
    parts = [p.strip() for p in text.split(",")]
    while parts and not parts[-1]:        # a trailing comma is forgiven
        parts.pop()
    for part in parts:
        if not part and out:   # "0.3,,0.6": a number left out, not a separator typed twice
            raise InputError(f"{name} has an empty item after {out[-1]:g} in {text!r}: give "
                             "a number between each two commas")
        if not part:
            continue
        try:
            out.append(float(part))
        except ValueError:
            raise InputError(f"{name} must be comma-separated numbers, got {part!r}") from None
    if not out:
        raise InputError(f"{name} must list at least one number")
    return out


def narrow_table(title: str, columns: list[str]) -> Table:
    """A table that reads at 80 columns: light rules, no outer padding, right-aligned numbers
    (the first column left), headers that wrap (units in them) instead of being cut."""
    from rich import box
    from rich.table import Table

    t = Table(title=title, box=box.SIMPLE_HEAD, pad_edge=False, header_style="bold",
              title_justify="left", min_width=min(len(title), 78))
    for i, c in enumerate(columns):
        t.add_column(c, justify="left" if i == 0 else "right", overflow="fold")
    return t


def kv_table(title: str, rows: list[tuple[str, str, str]]) -> Table:
    """A two/three-column rich table: quantity, value, unit."""
    from rich.table import Table

    t = Table(title=title, show_header=True, header_style="bold")
    t.add_column("quantity")
    t.add_column("value", justify="right")
    t.add_column("unit")
    for r in rows:
        t.add_row(*r)
    return t


PLOT_SUFFIXES = (".png", ".svg", ".pdf")


def plot_path(path: str | Path) -> Path:
    """The file a ``--plot PATH`` option writes: ``PATH``, or ``PATH.png`` without a suffix.

    Refuses (:class:`~exofric.errors.InputError`, exit 2) an empty path, an existing directory
    and a suffix matplotlib is not asked to write here (only .png, .svg, .pdf). Commands call
    it before computing, so a bad path costs no solve.
    """
    from exofric.errors import InputError

    text = str(path)
    if not text.strip():
        raise InputError("plot must name a file (.png, .svg or .pdf), got ''")
    p = Path(text)
    if p.is_dir():
        raise InputError(f"plot {text} is a directory; give a file such as {p / 'figure.png'}",
                         param="plot")
    if not p.suffix:
        p = p.with_name(p.name + ".png")
    if p.suffix.lower() not in PLOT_SUFFIXES:
        raise InputError(f"plot must end in .png, .svg or .pdf, got {text!r}", param="plot")
    return p


def out_file(name: str, path: str | Path) -> Path:
    """``path`` as an output file: refuses (InputError) an empty path or an existing directory.

    ``name`` is the Python parameter (``"vtu"``, ``"out"``); the CLI shows it as its flag.
    """
    from exofric.errors import InputError

    text = str(path)
    if not text.strip():
        raise InputError(f"{name} must name a file, got ''", param=name)
    p = Path(text)
    if p.is_dir():
        raise InputError(f"{name} {text} is a directory; give a file name", param=name)
    return p


def save_figure(fig: Any, path: str | Path) -> Path:
    """Write a figure drawn by :mod:`exofric.plots` to ``path`` (``--plot PATH`` options).

    The path is checked by :func:`plot_path` (``out`` becomes ``out.png``); creates the parent
    directory (as every ``--plot`` always did), then :func:`exofric.plots.save` writes the image
    atomically and closes the figure. Returns the path written.
    """
    from exofric.plots import save

    p = plot_path(path)
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
                res.contact_point_data() if hasattr(res, "contact_point_data") else None,
            )
        )
    return out
