"""The reproduction report: figures (PNG), ``results.json`` and a self-contained ``report.html``.

:func:`write_report` takes a :class:`~exofric.reproduce.ReproduceResult`, draws every figure
(matplotlib, Agg), writes them as PNG, embeds them as base64 in ``report.html`` (no network
needed; responsive and printable, see :mod:`exofric.report`; the stylesheet
:data:`REPORT_CSS` is in :mod:`exofric.report` and importable from here) and writes
``results.json`` with every number of the report, the stage wall times and the software
versions. The paper's inconsistencies are read from ``docs/paper-notes*.md``.

Units: mm, N, MPa, s, Nm.

Examples
--------
>>> from exofric.reproduce import reproduce, ReproduceConfig      # doctest: +SKIP
>>> files = write_report(reproduce(ReproduceConfig.for_mode(fast=True)), "out")  # doctest: +SKIP
>>> files.report_html.name                                                        # doctest: +SKIP
'report.html'
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from exofric import paper
from exofric.io import jsonable, write_json
from exofric.plots import plot_gamma_fit, plot_predictions, plot_squeeze, save
from exofric.report._style import REPORT_CSS
from exofric.reproduce import ReproduceResult

__all__ = ["FigureFile", "ReportFiles", "write_report", "find_notes_dir", "read_notes",
           "make_figures", "REPORT_CSS"]

_KNEE = "knee 0-40 Nm"


def _plt() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


@dataclass(frozen=True)
class FigureFile:
    """One written figure: key, file, title, caption, the stage it belongs to."""

    key: str
    path: Path
    title: str
    caption: str
    stage: str

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"key": self.key, "file": self.path.name, "title": self.title,
                "caption": self.caption, "stage": self.stage}


@dataclass(frozen=True)
class ReportFiles:
    """Paths written by :func:`write_report` and the time spent (s)."""

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
    plt = _plt()
    cal = r.calibration
    t1 = paper.table1()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4.2))
    for i, col in enumerate(cal.columns):
        c = f"C{i}"
        a1.plot(col["pressure_mpa"], col["paper_outer_diameter_mm"], "o", color=c,
                label=f"paper ANSYS {col['shore']:g} Hs")
        a1.plot(col["pressure_mpa"], col["our_outer_diameter_mm"], "-", color=c,
                label=f"exofric FE {col['shore']:g} Hs")
    a1.set_title(f"Table 1 columns; tube ID fitted = {cal.tube_id_mm:.4f} mm", fontsize=10)
    for res, lab, sty in ((cal.bisection, "bisection", "-"), (cal.bounded, "bounded", "--")):
        a2.plot(res.data.pressure_mpa, res.simulated_mm, sty,
                label=f"exofric {lab}: Shore {res.shore:.2f} ({res.average_error_pct:.2f}%)")
    a2.plot(t1["pressure_mpa"], t1["simulated_outer_diameter_mm"][3], "s", mfc="none",
            color="0.4", label="paper ANSYS 62.5 Hs (0.46%)")
    a2.plot(t1["pressure_mpa"], t1["test_outer_diameter_mm"], "o", color="tab:red",
            label="test (Table 1)")
    a2.set_title("Shore from the test column (Fig 5b)", fontsize=10)
    for ax in (a1, a2):
        ax.set_xlabel("pressure P (MPa)")
        ax.set_ylabel("tube outer diameter (mm)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def _fig_squeeze_n(r: ReproduceResult) -> Any:
    plt = _plt()
    s = r.squeeze.result
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot(s.pressure_mpa, s.squeeze_force_n, "o-", label="exofric FE, base group")
    ax.plot([0.6], [paper.scalar("base_squeeze_force_at_0_6_mpa_n")], "*", ms=12,
            color="tab:red", label="paper (Fig 7): 268.55 N")
    if s.contact_onset_pressure_mpa is not None:
        ax.axvline(s.contact_onset_pressure_mpa, color="0.6", ls=":", label="contact onset")
    ax.set_xlabel("pressure P (MPa)")
    ax.set_ylabel("squeezing force N (N, L = 116 mm)")
    ax.set_title(f"Fig 7: tube ID {s.structure.tube_id_mm:.4f} mm, Shore "
                 f"{s.material.shore:.2f}", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def _fig_all_curves(r: ReproduceResult) -> Any:
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for res in r.prediction.squeezes:
        ax.plot(res.pressure_mpa, res.squeeze_force_n, "o-", ms=3, label=res.structure.name)
    ax.set_xlabel("pressure P (MPa)")
    ax.set_ylabel("squeezing force N (N)")
    ax.set_title("exofric FE N(P) for the Table 3 structures", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def _fig_predictions(r: ReproduceResult, names: tuple[str, ...], fig_no: int) -> Any:
    preds = [p for p in r.prediction.predictions.predictions if p.structure.name in names]
    return plot_predictions(preds, f"Fig {fig_no}: SYNTHETIC 'tested' curves (virtual rig)")


def _fig_cubic(r: ReproduceResult) -> Any:
    plt = _plt()
    cu = r.cubic
    pp = np.linspace(cu.ours.p_min_mpa, cu.ours.p_max_mpa, 101)
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot(cu.pressure_mpa, cu.squeeze_force_n, "o", label="exofric FE, test 5")
    ax.plot(pp, cu.ours(pp), "-", label=f"exofric cubic (R^2 = {cu.ours.r2:.5f})")
    ax.plot(pp, cu.paper_eq8(pp), "k--", label="paper Eq 8")
    tgt = r.config.target_friction_n
    for key, lab, col in (("eq9_mpa", "Eq 9 inverse", "k"), ("paper_printed_mpa",
                          "paper's printed 0.26", "tab:red"),
                          ("our_exact_curve_mpa", "ours (FE + our gamma)", "tab:blue")):
        ax.axvline(cu.inverse[key], color=col, ls=":", lw=1,
                   label=f"{tgt:g} N: {lab} {cu.inverse[key]:.4f} MPa")
    ax.set_xlabel("pressure P (MPa)")
    ax.set_ylabel("squeezing force N (N)")
    ax.set_title("Fig 11: cubic fit for test 5", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def _fig_control(r: ReproduceResult) -> Any:
    plt = _plt()
    res = r.control.paper_map
    kinds = ("pd", "pi", "pid")
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8), sharey=True)
    for ax, kind in zip(axes, kinds, strict=True):
        for c in (c for c in res.cases if c.controller == kind):
            s = c.simulation
            ts = c.metrics.settling_time_s
            lab = "with model" if c.feedforward else "without model"
            ax.plot(s.time_s, s.friction_n, color="tab:blue" if c.feedforward else "tab:red",
                    label=f"{lab}: " + (f"{ts:.2f} s" if ts is not None else "not settled"))
        tgt = res.target_n
        ax.axhline(tgt, color="k", lw=1)
        ax.axhspan(tgt * 0.98, tgt * 1.02, color="0.88")
        paper_t = [c.paper_settling_time_s for c in res.cases if c.controller == kind]
        ptxt = ", ".join("-" if v is None else f"{v:g} s" for v in paper_t)
        ax.set_title(f"{kind.upper()} (paper: {ptxt})", fontsize=10)
        ax.set_xlabel("time (s)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower right")
    axes[0].set_ylabel("friction F (N)")
    fig.tight_layout()
    return fig


def _fig_torque(r: ReproduceResult) -> Any:
    plt = _plt()
    rows = r.torque.rows
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    x = np.arange(len(rows))
    ax.bar(x, [t["torque_nm"] for t in rows], color="tab:blue", label="exofric (predicted)")
    ax.plot([0, 2], [paper.scalar("base_friction_moment_nm"), paper.scalar("test3_torque_nm")],
            "*", ms=12, color="tab:red", label="paper (measured friction x 0.10 m)")
    ax.axhline(paper.scalar("knee_torque_max_nm"), color="k", ls="--", label=_KNEE + " (max)")
    ax.set_xticks(x, [t["name"] for t in rows], rotation=30)
    ax.set_ylabel("torque T = F R at 0.6 MPa (Nm)")
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def make_figures(r: ReproduceResult, out_dir: Path) -> tuple[FigureFile, ...]:
    """Draw and save every report figure as PNG in ``out_dir`` (11 figures, 130 dpi).

    Examples
    --------
    >>> figs = make_figures(reproduce(ReproduceConfig.for_mode(True)), out)  # doctest: +SKIP
    >>> [f.path.name for f in figs][:2]                                       # doctest: +SKIP
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
         lambda: plot_gamma_fit(gm.fit, f"SYNTHETIC rig data, gamma_true = {gm.gamma_true:g}")),
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
        if draw is None:
            plot_squeeze(r.squeeze.result, path)
        else:
            save(draw(), path)
        out.append(FigureFile(key, path, title, caption, stage))
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
        Output of :func:`exofric.reproduce.reproduce`.
    out_dir : str or Path
        Output directory (created).
    notes_dir : Path, optional
        Directory of ``paper-notes*.md`` (default: :func:`find_notes_dir`).

    Returns
    -------
    ReportFiles
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
    html_path.write_text(render_html(data, figs, notes), encoding="utf-8")
    json_path = write_json(data, out / "results.json")
    return ReportFiles(out, html_path, json_path, figs, tuple(data["notes_files"]),
                       time.perf_counter() - t0)
