"""Presentation of the reproduction report: its stylesheet, number format and HTML blocks.

* :data:`REPORT_CSS` -- the inline stylesheet of ``report.html``: responsive (tables scroll
  sideways on a phone or turn into labelled cards, images scale) with a print style that
  drops navigation and keeps figures whole.
* :func:`fmt` -- how every number of the report is printed (significant digits, '-' for
  missing).
* The HTML building blocks shared by :mod:`exofric.report` and
  :mod:`exofric.report`: escaped text, signed differences, tables, the paper-beside-ours
  comparison table and base64-embedded figures.

``REPORT_CSS`` is also importable from :mod:`exofric.report`, ``fmt`` from
:mod:`exofric.report`. Units: whatever the formatted values carry (mm, N, MPa, s, Nm, %).

Examples
--------
>>> fmt(0.29261234), _signed(-1.5, 3, " %")
('0.29261', '-1.5 %')
"""

from __future__ import annotations

import base64
import html
from collections.abc import Sequence
from typing import Any

__all__ = ["REPORT_CSS", "fmt"]

#: The report's stylesheet (inline in report.html): responsive, with a print style.
REPORT_CSS = """
:root{--fg:#1b1f24;--muted:#57606a;--line:#d0d7de;--accent:#0a58ca;--synth:#f4ecff;
--synthb:#6f42c1;--warn:#fff8e6;--head:#f6f8fa}
*{box-sizing:border-box}
html{-webkit-text-size-adjust:100%}
body{margin:0;color:var(--fg);background:#fff;
font:16px/1.5 system-ui,-apple-system,"Segoe UI",Roboto,"Helvetica Neue",Arial,sans-serif}
main{max-width:1100px;margin:0 auto;padding:1rem 1.2rem 3rem}
h1{font-size:1.6rem;line-height:1.25;margin:.4rem 0}
h2{font-size:1.3rem;margin:2.2rem 0 .6rem;padding-top:.6rem;border-top:2px solid var(--line)}
h3{font-size:1.08rem;margin:1.4rem 0 .4rem}
h4,h5{font-size:1rem;margin:1rem 0 .3rem}
p,li{max-width:75ch}
a{color:var(--accent)}
.muted{color:var(--muted);font-size:.9rem}
.scroll{overflow-x:auto;-webkit-overflow-scrolling:touch;margin:.5rem 0 1rem;
border:1px solid var(--line);border-radius:6px}
table{border-collapse:collapse;width:100%;font-size:.88rem}
th,td{padding:.32rem .55rem;border-bottom:1px solid var(--line);text-align:left;
vertical-align:top}
th{background:var(--head);font-weight:600}
td.long{min-width:15rem}
td.n{text-align:right;white-space:nowrap;font-variant-numeric:tabular-nums}
tr.synthetic td{background:var(--synth)}
tr:last-child td{border-bottom:none}
.badge{display:inline-block;font-size:.72rem;font-weight:700;letter-spacing:.03em;
padding:.05rem .4rem;border-radius:4px;background:var(--synthb);color:#fff;vertical-align:middle}
.box{background:var(--warn);border-left:4px solid #d4a72c;padding:.6rem .9rem;margin:1rem 0;
border-radius:4px}
.box.synthetic{background:var(--synth);border-left-color:var(--synthb)}
figure{margin:1.2rem 0}
figure img{display:block;max-width:100%;height:auto;border:1px solid var(--line);
border-radius:4px;background:#fff}
figcaption{font-size:.86rem;color:var(--muted);margin-top:.3rem}
nav.toc{background:var(--head);border:1px solid var(--line);border-radius:6px;
padding:.5rem 1rem;margin:1rem 0}
nav.toc ol{margin:.3rem 0;padding-left:1.4rem}
.notes{border-left:3px solid var(--line);padding-left:.9rem}
.notes pre,pre{overflow-x:auto;background:var(--head);padding:.5rem;border-radius:4px;
font-size:.8rem}
code{font-size:.88em;overflow-wrap:anywhere}
p,li,h2,h3,h4,figcaption{overflow-wrap:anywhere}
.time{float:right;font-size:.8rem;color:var(--muted);font-weight:400}
@media (max-width:640px){body{font-size:15px}main{padding:.6rem .7rem 2rem}
h1{font-size:1.3rem}h2{font-size:1.15rem}th,td{padding:.25rem .4rem}
.time{float:none;display:block}
table.cards thead{display:none}
table.cards tr{display:block;border-bottom:2px solid var(--line);padding:.35rem 0}
table.cards td{display:grid;grid-template-columns:6.8rem 1fr;gap:.5rem;border:none;
padding:.1rem .55rem;text-align:left;white-space:normal;min-width:0}
table.cards td::before{content:attr(data-label);font-weight:600;color:var(--muted)}
table.cards td:first-child{display:block;font-weight:600}
table.cards td:first-child::before{content:none}}
@media print{nav.toc{display:none}body{font-size:10.5pt}main{max-width:none;padding:0}
.scroll{overflow:visible;border:none}table{font-size:8.5pt}
figure,tr,.box{break-inside:avoid}h2,h3{break-after:avoid}a{color:inherit;
text-decoration:none}}
"""


def _e(x: Any) -> str:
    return html.escape(str(x), quote=True)


def fmt(v: Any, digits: int = 5) -> str:
    """Format a number for the report (``digits`` significant; None -> '-').

    Parameters
    ----------
    v : object
        The value: a float (``digits`` significant figures; NaN -> '-', round-off zero ->
        '0'), an int, a bool ('yes'/'no'), None ('-') or anything else (``str``).
    digits : int
        Significant figures of a float.

    Returns
    -------
    str

    Examples
    --------
    >>> fmt(4.0033333), fmt(None), fmt(True), fmt(268.55), fmt(0.005995004)
    ('4.0033', '-', 'yes', '268.55', '0.005995')
    """
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if v != v:
            return "-"
        if abs(v) < 1e-12:   # round-off zero (e.g. a touching gap of 4e-16 mm)
            return "0"
        return f"{v:.{digits}g}"
    return str(v)


def _signed(v: Any, digits: int = 3, unit: str = "") -> str:
    if v is None:
        return "-"
    return f"{v:+.{digits}g}{unit}"


def _table(headers: Sequence[str], rows: Sequence[Sequence[Any]],
           row_class: Sequence[str] | None = None, cards: bool = False) -> str:
    """An HTML table in a horizontal-scroll wrapper; numbers right-aligned.

    ``cards``: on narrow screens each row is shown as a labelled card instead of scrolling.
    Cells may be ``("html", markup)`` or ``("n", text)`` (right-aligned text).
    """
    th = "".join(f"<th>{_e(h)}</th>" for h in headers)
    body = []
    for i, r in enumerate(rows):
        cells = []
        for h, c in zip(headers, r, strict=True):
            lab = f' data-label="{_e(h)}"' if cards else ""
            if isinstance(c, tuple) and len(c) == 2 and c[0] == "html":
                cells.append(f"<td{lab}>{c[1]}</td>")
            elif isinstance(c, tuple) and len(c) == 2 and c[0] == "n":
                cells.append(f'<td class="n"{lab}>{_e(c[1])}</td>')
            elif isinstance(c, bool) or not isinstance(c, int | float):
                long = ' class="long"' if isinstance(c, str) and len(c) > 40 else ""
                cells.append(f"<td{long}{lab}>{_e(fmt(c))}</td>")
            else:
                cells.append(f'<td class="n"{lab}>{_e(fmt(c))}</td>')
        cls = f' class="{row_class[i]}"' if row_class and row_class[i] else ""
        body.append(f"<tr{cls}>{''.join(cells)}</tr>")
    tcls = ' class="cards"' if cards else ""
    return (f'<div class="scroll"><table{tcls}><thead><tr>{th}</tr></thead>'
            f"<tbody>{''.join(body)}</tbody></table></div>")


def _cmp_table(rows: Sequence[dict[str, Any]], ours_label: str = "exofric") -> str:
    """Paper value beside ours with the difference, synthetic rows marked."""
    head = ["quantity", "unit", "paper", ours_label, "difference", "diff. %", "note"]
    out, cls = [], []
    for c in rows:
        q = _e(c["quantity"]) + (' <span class="badge">SYNTHETIC</span>' if c["synthetic"]
                                 else "")
        out.append([
            ("html", q), c["unit"] or "-", c["paper_value"], c["our_value"],
            ("n", _signed(c["difference"], 4)), ("n", _signed(c["difference_pct"], 3, " %")),
            c["note"]])
        cls.append("synthetic" if c["synthetic"] else "")
    return _table(head, out, cls, cards=True)


def _figure(fig: Any) -> str:
    data = base64.b64encode(fig.path.read_bytes()).decode("ascii")
    return (f'<figure id="fig-{_e(fig.key)}"><img src="data:image/png;base64,{data}" '
            f'alt="{_e(fig.title)}" loading="eager"><figcaption><b>{_e(fig.title)}.</b> '
            f"{_e(fig.caption)} <span class=\"muted\">({_e(fig.path.name)})</span>"
            "</figcaption></figure>")
