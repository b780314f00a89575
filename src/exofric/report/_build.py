"""The reproduction report: figures (PNG), ``results.json`` and a self-contained ``report.html``.

:func:`write_report` takes a :class:`~exofric.reproduction.ReproduceResult`, draws every figure
(with :mod:`exofric.plots`), writes them as PNG, embeds them as base64 in ``report.html``
(no network needed; responsive and printable, see :mod:`exofric.report`; the stylesheet
:data:`REPORT_CSS` is in :mod:`exofric.report` and importable from here) and writes
``results.json`` with every number of the report, the stage wall times and the software
versions. The paper's inconsistencies are read from ``docs/paper-notes*.md``.

Units: mm, N, MPa, s, Nm.

Examples
--------
``write_report(reproduce(), "exofric-report")`` writes everything (see :func:`write_report`);
the paper notes it embeds:

>>> [name for name, _ in read_notes(find_notes_dir())]
['paper-notes.md']
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from exofric import paper
from exofric._validate import checked_init
from exofric.io import jsonable, write_json, write_text
from exofric.plots import (
    plot_control_cases,
    plot_cubic_fit,
    plot_gamma_fit,
    plot_predictions,
    plot_squeeze,
    plot_squeeze_curves,
    plot_squeeze_force,
    plot_table1,
    plot_torque,
    save,
)
from exofric.report._style import REPORT_CSS
from exofric.reproduction import ReproduceResult

__all__ = ["FigureFile", "ReportFiles", "write_report", "find_notes_dir", "read_notes",
           "make_figures", "REPORT_CSS", "FIGURE_DPI", "FIGURE_MAX_PX"]

_KNEE = "knee 0-40 Nm"

#: Resolution (dpi) of the report's figures: text of ``s`` pt is shown at ``s`` x 130/96 pt
#: when the figure is shown at its natural size.
FIGURE_DPI = 130
#: Widest figure written (px). The report's figure column is ~1160 CSS px wide on a page of
#: 1280 px or more (``main`` max-width 1200 px less its padding), so a figure of at most
#: 1400 px is shown at >= 83 % of its natural width; a wider figure is written at a lower dpi.
FIGURE_MAX_PX = 1400


@checked_init
@dataclass(frozen=True)
class FigureFile:
    """One written figure: key, file, title, caption, the stage it belongs to.

    Attributes
    ----------
    key : str
        Figure key, also the file stem (``"fig7"``).
    path : Path
        The PNG file written.
    title : str
        Figure title in the report.
    caption : str
        Caption under the figure (says what is SYNTHETIC).
    stage : str
        Key of the stage whose section shows it (see :data:`exofric.reproduction.STAGES`).
    dpi : int
        Resolution it was written with (dots per inch).
    width_px : int
        Natural width of the PNG in pixels (a dimensionless count); 0 if unknown.
    min_font_pt : float or None
        Smallest visible text in the figure (pt at ``dpi``); shown at
        ``min_font_pt * dpi / 96 * displayed width / width_px`` CSS pt.

    Examples
    --------
    >>> from pathlib import Path
    >>> f = FigureFile("fig7", Path("out/fig7.png"), "Fig 7", "N(P) of the base", "squeeze")
    >>> f.to_dict()["file"], f.stage, f.dpi
    ('fig7.png', 'squeeze', 130)
    """

    key: str
    path: Path
    title: str
    caption: str
    stage: str
    dpi: int = FIGURE_DPI
    width_px: int = 0
    min_font_pt: float | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (``dpi`` in dots per inch, ``width_px`` in px, font in pt)."""
        return {"key": self.key, "file": self.path.name, "title": self.title,
                "caption": self.caption, "stage": self.stage, "dpi": self.dpi,
                "width_px": self.width_px, "min_font_pt": self.min_font_pt}


@checked_init
@dataclass(frozen=True)
class ReportFiles:
    """Paths written by :func:`write_report` and the time spent (s).

    Attributes
    ----------
    out_dir : Path
        The output directory.
    report_html : Path
        The self-contained ``report.html``.
    results_json : Path
        ``results.json`` (every number of the report, units in the keys).
    figures : tuple of FigureFile
        The PNG figures, in report order.
    notes : tuple of str
        Names of the ``paper-notes*.md`` files included.
    report_time_s : float
        Wall time of :func:`write_report` (s).

    Examples
    --------
    >>> from pathlib import Path
    >>> out = Path("exofric-report")
    >>> files = ReportFiles(out, out / "report.html", out / "results.json", (), (), 2.5)
    >>> files.to_dict()["report_html"], files.to_dict()["report_time_s"]
    ('exofric-report/report.html', 2.5)
    """

    out_dir: Path
    report_html: Path
    results_json: Path
    figures: tuple[FigureFile, ...]
    notes: tuple[str, ...]
    report_time_s: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (paths as strings, s)."""
        return {"out_dir": str(self.out_dir), "report_html": str(self.report_html),
                "results_json": str(self.results_json),
                "figures": [str(f.path) for f in self.figures], "notes_files": list(self.notes),
                "report_time_s": self.report_time_s}


def find_notes_dir(start: Path | None = None) -> Path | None:
    """The ``docs`` directory holding ``paper-notes*.md`` (cwd, then the source tree), or None.

    The notes shipped as package data come first, then ``start/docs``, then the source
    tree's ``docs``.

    Parameters
    ----------
    start : Path, optional
        Directory whose ``docs`` subdirectory is searched (default the working directory).

    Returns
    -------
    Path or None
        The first candidate holding a ``paper-notes*.md``, None if none does.

    Examples
    --------
    >>> d = find_notes_dir()
    >>> d is None or any(d.glob("paper-notes*.md"))
    True
    """
    here = Path(__file__).resolve()
    # the notes ship as package data (docs/paper-notes.md links to them)
    for cand in (paper.notes_path().parent, (start or Path.cwd()) / "docs",
                 here.parents[3] / "docs"):
        if cand.is_dir() and any(cand.glob("paper-notes*.md")):
            return cand
    return None


def read_notes(notes_dir: Path | None) -> list[tuple[str, str]]:
    """``(file name, markdown text)`` of every ``paper-notes*.md`` (``paper-notes.md`` first).

    Parameters
    ----------
    notes_dir : Path or None
        Directory holding the notes (e.g. from :func:`find_notes_dir`); None gives ``[]``.

    Returns
    -------
    list of (str, str)

    Examples
    --------
    >>> read_notes(None)
    []
    """
    if notes_dir is None:
        return []
    files = sorted(notes_dir.glob("paper-notes*.md"), key=lambda p: (p.name != "paper-notes.md",
                                                                       p.name))
    return [(p.name, p.read_text(encoding="utf-8")) for p in files]


# ----------------------------------------------------------------------------- figures


def _fig_table1(r: ReproduceResult) -> Any:
    return plot_table1(r.calibration, paper.table1())


def _fig_squeeze_n(r: ReproduceResult) -> Any:
    s = r.squeeze.result
    n_paper = paper.scalar("base_squeeze_force_at_0_6_mpa_n")
    shore = getattr(s.material, "shore", None)  # the reproduction's material is Mooney-Rivlin
    mat = f"Shore {shore:.2f}" if shore is not None else str(getattr(s.material, "name", ""))
    return plot_squeeze_force(
        s, reference=(0.6, n_paper, f"paper (Fig 7): {n_paper:g} N"),
        label="exofric FE, base group",
        title=f"Fig 7: tube ID {s.structure.tube_id_mm:.4f} mm, {mat}")


def _fig_all_curves(r: ReproduceResult) -> Any:
    return plot_squeeze_curves(r.prediction.squeezes,
                               title="exofric FE N(P) for the Table 3 structures")


def _fig_predictions(r: ReproduceResult, names: tuple[str, ...], fig_no: int) -> Any:
    preds = [p for p in r.prediction.predictions.predictions if p.structure.name in names]
    e = paper.load()["max_relative_error"]
    printed = {f"test {t}": v for t, v in zip(e["test"], e["max_relative_error_pct"], strict=True)}
    return plot_predictions(preds, f"Fig {fig_no}: SYNTHETIC 'tested' curves (virtual rig)",
                            paper_max_error_pct=printed,
                            data_label="synthetic (virtual rig)")


def _fig_cubic(r: ReproduceResult) -> Any:
    cu = r.cubic
    return plot_cubic_fit(cu.pressure_mpa, cu.squeeze_force_n, cu.ours, cu.paper_eq8,
                          cu.inverse, r.config.target_friction_n)


def _fig_control(r: ReproduceResult) -> Any:
    return plot_control_cases(r.control.paper_map.cases)      # the CLI's design


def _fig_torque(r: ReproduceResult) -> Any:
    rows = r.torque.rows
    ref = ([0, 2], [paper.scalar("base_friction_moment_nm"), paper.scalar("test3_torque_nm")],
           "paper (measured friction x 0.10 m)")
    return plot_torque([t["name"] for t in rows], [t["torque_nm"] for t in rows],
                       reference=ref, limit_nm=paper.scalar("knee_torque_max_nm"),
                       limit_label=_KNEE + " (max)")


def _root_figure(fig: Any) -> Any:
    """The figure of a Figure or an Axes (what :func:`exofric.plots.save` writes)."""
    root = fig if hasattr(fig, "savefig") else fig.figure
    return getattr(root, "figure", None) or root


def _min_font_pt(fig: Any) -> float | None:
    """Smallest font size (pt) of the visible, non-empty texts of a drawn figure."""
    root = _root_figure(fig)
    texts = root.findobj(lambda a: hasattr(a, "get_fontsize") and hasattr(a, "get_text"))
    sizes = [float(t.get_fontsize()) for t in texts
             if t.get_visible() and str(t.get_text()).strip()]
    return min(sizes) if sizes else None


def _png_width(path: Path) -> int:
    """Width (px) from a PNG's IHDR chunk; 0 if the file is not a PNG."""
    head = path.read_bytes()[:24]
    return int.from_bytes(head[16:20], "big") if head[:8] == b"\x89PNG\r\n\x1a\n" else 0


def make_figures(r: ReproduceResult, out_dir: Path) -> tuple[FigureFile, ...]:
    """Draw and save every report figure as PNG in ``out_dir`` (11 figures, sized for the page).

    Each is written at :data:`FIGURE_DPI` (130 dpi), or at the dpi that makes it
    :data:`FIGURE_MAX_PX` wide if it is wider, so the page shows it at >= 80 % of its natural
    width; its smallest text (pt) is recorded.

    Parameters
    ----------
    r : ReproduceResult
        Output of :func:`exofric.reproduction.reproduce`.
    out_dir : Path
        Existing directory the PNG files are written to (``<key>.png``).

    Returns
    -------
    tuple of FigureFile
        In report order, each with the stage it belongs to.

    Examples
    --------
    >>> figs = make_figures(fast_result, tmp_dir)   # reproduce(ReproduceConfig.for_mode(True))
    >>> [f.path.name for f in figs][:2]
    ['table1.png', 'fig6.png']
    """
    gm = r.gamma
    specs: list[tuple[str, str, str, str, Callable[[], Any] | None]] = [
        ("table1", "Table 1 and Fig 5b: calibration", "calibration",
         "Left: the paper's ANSYS diameters (markers) and ours (lines) at the fitted tube ID. "
         "Right: Shore from the test column with that ID.", lambda: _fig_table1(r)),
        ("fig6", "Figs 6-7: deformed base section and N(P)", "squeeze",
         "Deformed sections coloured by von Mises stress (MPa) at 0.2, 0.4, 0.6 MPa; hole "
         "(circle) and wire (grey disc); right: N(P).", None),  # drawn by plot_squeeze
        ("fig7", "Fig 7: squeezing force of the base group", "squeeze",
         "exofric's N(P) with the paper's 268.55 N at 0.6 MPa.", lambda: _fig_squeeze_n(r)),
        ("fig4", "Fig 4 / Eq 7: gamma fit (SYNTHETIC data)", "gamma",
         f"SYNTHETIC virtual-rig friction, gamma_true = {gm.gamma_true:g}, on exofric's base "
         "N(P); the fit, residuals (N) and relative errors (%).",
         lambda: plot_gamma_fit(
             gm.fit, f"SYNTHETIC rig data, gamma_true = {gm.gamma_true:g}",
             data_label="synthetic (virtual rig)",
             paper_point=(0.6, paper.scalar("base_friction_at_0_6_mpa_n"),
                          "paper, Sec 3.2"))),
        ("squeeze_all", "N(P) of the seven Table 3 structures", "prediction",
         "exofric FE squeezing force for tests 1-7 (tube IDs scaled with d1).",
         lambda: _fig_all_curves(r)),
        ("fig8", "Fig 8: tests 2 and 3 (first group)", "prediction",
         "Predicted (black) vs SYNTHETIC tested (red) friction and the relative error.",
         lambda: _fig_predictions(r, ("test 2", "test 3"), 8)),
        ("fig9", "Fig 9: tests 4 and 5 (second group)", "prediction",
         "Predicted (black) vs SYNTHETIC tested (red) friction and the relative error.",
         lambda: _fig_predictions(r, ("test 4", "test 5"), 9)),
        ("fig10", "Fig 10: tests 6 and 7 (third group)", "prediction",
         "Predicted (black) vs SYNTHETIC tested (red) friction and the relative error.",
         lambda: _fig_predictions(r, ("test 6", "test 7"), 10)),
        ("fig11", "Fig 11: cubic fit for test 5 and the inverse", "cubic",
         "exofric FE points and cubic, the paper's Eq 8, and the pressures for 54.40 N.",
         lambda: _fig_cubic(r)),
        ("fig12", "Fig 12: friction control, PD / PI / PID", "control",
         "Step to 54.40 N on Eq 9 with the assumed plant; red without, blue with the model; "
         "grey band: 2%.", lambda: _fig_control(r)),
        ("torque", "Torque at 0.6 MPa per structure", "torque",
         "T = gamma N(0.6 MPa) x 0.10 m against the knee's 40 Nm.", lambda: _fig_torque(r)),
    ]
    out = []
    for key, title, stage, caption, draw in specs:
        path = out_dir / f"{key}.png"
        fig = plot_squeeze(r.squeeze.result) if draw is None else draw()
        dpi = FIGURE_DPI
        save(fig, path, dpi=dpi)   # draws the figure (tick labels get their text), then closes
        width = _png_width(path)
        if width > FIGURE_MAX_PX:  # too wide for the page: again at a lower dpi (a closed
            dpi = max(50, int(dpi * FIGURE_MAX_PX / width))   # figure still saves)
            save(fig, path, dpi=dpi)
            width = _png_width(path)
        out.append(FigureFile(key, path, title, caption, stage, dpi, width, _min_font_pt(fig)))
    return tuple(out)


def write_report(
    result: ReproduceResult,
    out_dir: str | Path = "exofric-report",
    *,
    notes_dir: Path | None = None,
) -> ReportFiles:
    """Write figures (PNG), ``results.json`` and ``report.html`` into ``out_dir``.

    Parameters
    ----------
    result : ReproduceResult
        Output of :func:`exofric.reproduction.reproduce`.
    out_dir : str or Path
        Output directory (created).
    notes_dir : Path, optional
        Directory of ``paper-notes*.md`` (default: :func:`find_notes_dir`).

    Returns
    -------
    ReportFiles

    Examples
    --------
    >>> files = write_report(fast_result, tmp_dir)   # reproduce(ReproduceConfig.for_mode(True))
    >>> files.report_html.name, files.results_json.name, len(files.figures)
    ('report.html', 'results.json', 11)
    """
    from exofric.report._html import render_html

    t0 = time.perf_counter()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    figs = make_figures(result, out)
    nd = notes_dir if notes_dir is not None else find_notes_dir()
    notes = read_notes(nd)
    data: dict[str, Any] = jsonable(result.to_dict())
    data["figures"] = [f.to_dict() for f in figs]
    data["notes_files"] = [name for name, _ in notes]
    data["report_time_s"] = time.perf_counter() - t0   # figures; the HTML adds milliseconds
    html_path = out / "report.html"
    html_path = write_text(html_path, render_html(data, figs, notes))  # atomic
    json_path = write_json(data, out / "results.json")
    return ReportFiles(out, html_path, json_path, figs, tuple(data["notes_files"]),
                       time.perf_counter() - t0)
