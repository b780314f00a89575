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

from exofric.report._build import (
    FigureFile,
    ReportFiles,
    find_notes_dir,
    make_figures,
    read_notes,
    write_report,
)
from exofric.report._html import render_html
from exofric.report._style import REPORT_CSS, fmt

__all__ = [
    "FigureFile", "find_notes_dir", "fmt", "make_figures", "read_notes", "render_html",
    "REPORT_CSS", "ReportFiles", "write_report",
]
