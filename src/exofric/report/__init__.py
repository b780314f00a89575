"""The reproduction report: figures (PNG), ``results.json`` and a self-contained ``report.html``.

:func:`write_report` takes a :class:`~exofric.reproduction.ReproduceResult`, draws every figure,
writes them as PNG, embeds them as base64 in ``report.html`` (no network needed; responsive and
printable) and writes ``results.json`` with every number of the report, the stage wall times and
the software versions. The paper's inconsistencies are read from the shipped paper notes.

Units: mm, N, MPa, s, Nm.

Examples
--------
>>> from exofric.report import fmt
>>> fmt(268.55)
'268.55'
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from exofric._lazy import facade

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.report._build import (
        FigureFile,
        ReportFiles,
        find_notes_dir,
        make_figures,
        read_notes,
        write_report,
    )
    from exofric.report._html import render_html
    from exofric.report._style import REPORT_CSS, comparison_cells, fmt

# Lazy facade (PEP 562): ``fmt`` and the HTML helpers do not load the figures and the pipeline;
# each name is loaded from its module on first use (exofric/__init__.py does the same one level
# up).
_MODULES: dict[str, tuple[str, ...]] = {
    "_build": (
        "FigureFile", "ReportFiles", "find_notes_dir", "make_figures", "read_notes",
        "write_report",
    ),
    "_html": ("render_html",),
    "_style": ("REPORT_CSS", "comparison_cells", "fmt"),
}
_HOME = {name: mod for mod, names in _MODULES.items() for name in names}

__all__ = [
    "comparison_cells", "FigureFile", "find_notes_dir", "fmt", "make_figures", "read_notes",
    "render_html", "REPORT_CSS", "ReportFiles", "write_report",
]

__getattr__, __dir__ = facade(__name__, _HOME, __all__)
