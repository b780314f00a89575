"""HTML of the reproduction report: one self-contained page, no template engine, no network.

Figures are embedded as base64 PNG, the CSS is inline (responsive: tables scroll sideways on
a phone, images scale; a print style drops navigation and keeps figures whole). Every number
shown comes from the results dict that is also written to ``results.json``. The paper's
inconsistency notes (Markdown) are rendered with markdown-it (a dependency of rich), raw
HTML disabled.

This module assembles the page (:func:`render_html`): header, contents, the at-a-glance table,
the stage sections of :mod:`exofric.report`, what is synthetic, the paper's
inconsistencies and the run details. The stylesheet, number format (:func:`fmt`, importable
from here) and table helpers are in :mod:`exofric.report`.

Units: mm, N, MPa, s, Nm; differences in the row's unit, in % of the paper value, or in
percentage points (pp) for quantities already in %.
"""

from __future__ import annotations

import html
import re
from collections.abc import Sequence
from datetime import datetime, timezone
from typing import Any

from exofric.report._sections import _SECTIONS, _SHOWN_IN_SECTION
from exofric.report._style import REPORT_CSS, _cmp_table, _e, _figure, _table, fmt

__all__ = ["render_html", "fmt"]


def _slug(inner: str, seen: dict[str, int]) -> str:
    """GitHub-style heading anchor (so the notes' own ``#part-...`` links work)."""
    text = html.unescape(re.sub(r"<[^>]+>", "", inner)).strip().lower()
    slug = re.sub(r"[^\w\- ]", "", text).replace(" ", "-")
    n = seen.get(slug, 0)
    seen[slug] = n + 1
    return slug if n == 0 else f"{slug}-{n}"


def _md(text: str, seen: dict[str, int]) -> str:
    """Markdown to HTML (no raw HTML), headings shifted two levels down and given anchors."""
    from markdown_it import MarkdownIt

    out = MarkdownIt("commonmark", {"html": False}).enable("table").render(text)

    def head(m: re.Match[str]) -> str:
        lvl = min(int(m.group(1)) + 2, 6)
        return f'<h{lvl} id="{_e(_slug(m.group(2), seen))}">{m.group(2)}</h{lvl}>'

    out = re.sub(r"<h([1-6])>(.*?)</h\1>", head, out, flags=re.S)
    return out.replace("<table>", '<div class="scroll"><table>').replace(
        "</table>", "</table></div>")


def _cmps(d: dict[str, Any], stage: str) -> list[dict[str, Any]]:
    return [c for c in d["comparisons"] if c["stage"] == stage]


def _beside(d: dict[str, Any], stage: str) -> str:
    """The stage's "Paper beside exofric" table: rows its section's tables do not show."""
    shown = _SHOWN_IN_SECTION.get(stage, ())
    rows = [c for c in _cmps(d, stage) if not any(s in c["quantity"] for s in shown)]
    return f"<h3>Paper beside exofric</h3>{_cmp_table(rows)}" if rows else ""


def _pick(d: dict[str, Any], stage: str, prefix: str) -> dict[str, Any] | None:
    return next((c for c in _cmps(d, stage) if c["quantity"].startswith(prefix)), None)


_GLANCE = (("table2", "Table 2 C10"), ("calibration", "tube inner"),
           ("calibration", "Shore hardness"), ("squeeze", "squeezing force N at 0.6"),
           ("gamma", "gamma from the published"), ("gamma", "gamma (Eq 7)"),
           ("cubic", "test 5: N at 0.6"), ("cubic", "pressure for"),
           ("control", "PI: settling-time"), ("control", "PID: settling-time"),
           ("torque", "test 3 torque"))


def _synthetic(d: dict[str, Any]) -> str:
    cfg = d["config"]
    return (
        '<div class="box synthetic"><ul>'
        f"<li><span class=\"badge\">SYNTHETIC</span> Base-group friction (Fig 4, Eq 7): the "
        f"virtual rig with gamma_true = {fmt(cfg['gamma_true'])}, {cfg['rig']['noise_pct']:g}% "
        f"noise, seed {cfg['seed']}, set points {fmt(cfg['rig_pressures_mpa'][0])}-"
        f"{fmt(cfg['rig_pressures_mpa'][-1])} MPa where N &gt; 0. The fitted gamma and its "
        "errors are therefore planted, not measured.</li>"
        "<li><span class=\"badge\">SYNTHETIC</span> Friction of tests 2-7 (Figs 8-10, Table 4): "
        "the same rig, same gamma_true, seeds seed + test; no per-structure effect, so the "
        "paper's maximum errors and p-values are not reproduced.</li>"
        "<li>Assumed, not printed: the tube inner diameter (fitted to the paper's ANSYS "
        "columns), the tube IDs of tests 2-7 (scaled with d1), frictionless contact, the "
        "control plant (lag, dead time, supply) and gains.</li>"
        "<li>Everything else is computed from the paper's printed inputs: Table 2, Table 1, "
        "the FE squeeze N(P), the cubic fit, the inverses and the torque.</li></ul></div>"
    )


def _inconsistencies(d: dict[str, Any], notes: Sequence[tuple[str, str]]) -> str:
    rows = d["paper_checks"]
    out = ("<p>Printed numbers against the same quantity recomputed from the paper's own "
           "equations and numbers (this run):</p>"
           + _cmp_table(rows, ours_label="recomputed from the paper"))
    if not notes:
        return out + "<p class=\"muted\">docs/paper-notes*.md not found.</p>"
    out += ("<p>The notes below give the arithmetic for every inconsistency found while "
            "building exofric (from <code>docs/paper-notes*.md</code>).</p>")
    from exofric.reproduction import STAGES

    seen = {k: 1 for k in ("glance", "synthetic", "inconsistencies", "run",
                           *(key for key, _ in STAGES))}
    for name, text in notes:
        out += f'<h3 id="{_e(name)}">{_e(name)}</h3><div class="notes">{_md(text, seen)}</div>'
    return out


def _mode_label(cfg: dict[str, Any]) -> str:
    """The squeeze accuracy the run used, named as ``exofric squeeze --accuracy`` names it.

    The report's N(P) comes from one mesh (no two-mesh estimate); it is stated with its level
    and that level's documented error (defaults.SQUEEZE_ACCURACY), never as "converged".
    """
    from exofric import defaults

    m = cfg["squeeze_mesh"]
    level = next((k for k, v in defaults.SQUEEZE_ACCURACY.items()
                  if all(m.get(key) == val for key, val in v.items() if key != "coarsen")), None)
    # largest error against the independent FElupe reference, Table 3 structures, from the
    # first pressure where N >= 1 % of N(0.6 MPa) (defaults.SQUEEZE_ACCURACY)
    err = {"draft": "0.81 %", "standard": "0.47 %", "fine": "0.16 %"}
    mesh = f"{m['n_radial']} x {m['n_circ']} quad9"
    head = "fast" if cfg["fast"] else "default"
    if level is None:
        return f"{head}: squeeze mesh {mesh} (no --accuracy level; no error estimate)"
    std = defaults.SQUEEZE_ACCURACY["standard"]
    return (f"{head}: the {level} accuracy's squeeze mesh ({mesh}; N as `exofric squeeze "
            f"--accuracy {level}` gives it with the calibrated tube ID and Shore, within "
            f"{err[level]} of the independent reference; no error estimate); exofric squeeze "
            f"defaults to standard ({std['n_radial']} x {std['n_circ']}, {err['standard']})")


def _run_details(d: dict[str, Any]) -> str:
    def sec(v: float | None) -> tuple[str, str]:
        return ("n", "-" if v is None else f"{v:.2f}")

    rows = [[t["title"], sec(t["wall_time_s"])] for t in d["stage_times"]]
    rows.append(["figures and report", sec(d.get("report_time_s"))])
    rows.append(["total computation (stages 1-8)", sec(d["wall_time_s"])])
    cfg = d["config"]
    mesh = [["mode", _mode_label(cfg)],
            ["squeeze mesh", f"{cfg['squeeze_mesh']['n_radial']} x "
             f"{cfg['squeeze_mesh']['n_circ']} quad9, grading {cfg['squeeze_mesh']['grading']}"],
            ["inflation mesh", f"{cfg['inflation_mesh']['n_radial']} x "
             f"{cfg['inflation_mesh']['n_circ']} quad9"],
            ["squeeze pressures (MPa)", ", ".join(fmt(p) for p in cfg["pressures_mpa"])]]
    vers = [[k, v] for k, v in d["versions"].items()]
    return ("<h3>Wall time per stage (s)</h3>" + _table(["stage", "wall time (s)"], rows)
            + "<h3>Settings</h3>" + _table(["setting", "value"], mesh)
            + "<h3>Software</h3>" + _table(["package", "version"], vers))


def render_html(data: dict[str, Any], figures: Sequence[Any],
                notes: Sequence[tuple[str, str]]) -> str:
    """The whole report page (UTF-8 HTML string).

    Parameters
    ----------
    data : dict
        ``ReproduceResult.to_dict()`` made JSON-ready (what ``results.json`` holds).
    figures : sequence of FigureFile
        Written PNG figures (embedded as base64).
    notes : sequence of (name, markdown)
        The paper-notes files.

    Examples
    --------
    >>> from exofric.io import jsonable     # results.json holds jsonable(result.to_dict())
    >>> render_html(jsonable(fast_result.to_dict()), [], [])[:15]
    '<!DOCTYPE html>'
    """
    from exofric.reproduction import STAGES

    times = {t["key"]: t["wall_time_s"] for t in data["stage_times"]}
    glance = [c for st, pre in _GLANCE if (c := _pick(data, st, pre)) is not None]
    toc = "".join(f'<li><a href="#{k}">{_e(t)}</a></li>' for k, t in STAGES)
    toc += ('<li><a href="#synthetic">What is synthetic or assumed</a></li>'
            '<li><a href="#inconsistencies">The paper\'s inconsistencies</a></li>'
            '<li><a href="#run">Run details</a></li>')
    body = []
    for i, (key, title) in enumerate(STAGES, start=1):
        figs = "".join(_figure(f) for f in figures if f.stage == key)
        body.append(
            f'<section id="{key}"><h2>{i}. {_e(title)}<span class="time">stage wall time '
            f"{times.get(key, float('nan')):.2f} s</span></h2>{_SECTIONS[key](data)}"
            f"{_beside(data, key)}{figs}</section>")
    when = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")  # noqa: UP017
    mode = _mode_label(data["config"])
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<link rel="icon" href="data:,">
<title>exofric: Ma et al. (2021) reproduced</title>
<style>{REPORT_CSS}</style></head>
<body><main>
<h1>Friction prediction of a variable-stiffness exosuit, reproduced with open tools</h1>
<p class="muted">Ma et al., <i>Friction Prediction and Validation of a Variable Stiffness Lower
Limb Exosuit Based on Finite Element Analysis</i>, Actuators 2021. exofric
{_e(data['exofric_version'])}, {mode}, generated {when}; stages took
{data['wall_time_s']:.1f} s. Units: mm, N, MPa, s, Nm. Rows marked
<span class="badge">SYNTHETIC</span> rest on virtual-rig data (the paper's raw friction
curves are unpublished). Paper beside exofric: values to the digits the paper printed;
"ours - paper" in the row's unit with its % of the paper value, in percentage points (pp)
for quantities already in %, and '-' where a difference means nothing (p-values, fitted
cubic coefficients).</p>
<nav class="toc"><b>Contents</b><ol>{toc}</ol></nav>
<h2 id="glance">At a glance</h2>
{_cmp_table(glance)}
{''.join(body)}
<section id="synthetic"><h2>What is synthetic or assumed</h2>{_synthetic(data)}</section>
<section id="inconsistencies"><h2>The paper's inconsistencies</h2>
{_inconsistencies(data, notes)}</section>
<section id="run"><h2>Run details</h2>{_run_details(data)}</section>
<p class="muted">All numbers are also in results.json next to this file.</p>
</main></body></html>
"""
