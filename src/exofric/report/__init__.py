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

from exofric._lazy import lazy_package

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
# each name is loaded from its module on first use.
# The TYPE_CHECKING imports above are the one list of public names: __all__ and the facade
# are derived from them (exofric._lazy.lazy_package).
__getattr__, __dir__, __all__ = lazy_package(__name__, __file__)
