"""Presentation of the reproduction report: its stylesheet, number format and HTML blocks.

* :data:`REPORT_CSS` -- the inline stylesheet of ``report.html``: responsive (tables scroll
  sideways on a phone or turn into labelled cards, images scale) with a print style that
  drops navigation and keeps figures whole.
* :func:`fmt` -- how every number of the report is printed (significant digits, '-' for
  missing).
* :func:`comparison_cells` -- how a paper-beside-ours row is printed (the paper's digits; the
  difference only where it means something: in % of the paper value, in percentage points
  for quantities already in %, none for p-values); ``exofric reproduce`` prints it too.
* The HTML building blocks of the page and its sections: escaped text, signed differences,
  tables, the paper-beside-ours comparison table and base64-embedded figures.

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
import math
from collections.abc import Sequence
from typing import Any

__all__ = ["REPORT_CSS", "comparison_cells", "fmt"]

#: The report's stylesheet (inline in report.html): responsive, with a print style.
REPORT_CSS = """
:root{--fg:#1b1f24;--muted:#57606a;--line:#d0d7de;--accent:#0a58ca;--synth:#f4ecff;
--synthb:#6f42c1;--warn:#fff8e6;--head:#f6f8fa}
*{box-sizing:border-box}
html{-webkit-text-size-adjust:100%}
body{margin:0;color:var(--fg);background:#fff;
font:16px/1.5 system-ui,-apple-system,"Segoe UI",Roboto,"Helvetica Neue",Arial,sans-serif}
main{max-width:1200px;margin:0 auto;padding:1rem 1.2rem 3rem}
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
td.u,table.cmp th{white-space:nowrap}
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


def _fixed(v: Any, decimals: int) -> tuple[str, str]:
    """A right-aligned table cell: ``v`` with ``decimals`` decimals ('-' for None or NaN)."""
    if v is None or (isinstance(v, float) and v != v):
        return ("n", "-")
    return ("n", f"{float(v):.{decimals}f}")


def _table(headers: Sequence[str], rows: Sequence[Sequence[Any]],
           row_class: Sequence[str] | None = None, cards: bool = False,
           table_class: str = "") -> str:
    """An HTML table in a horizontal-scroll wrapper; numbers right-aligned.

    ``cards``: on narrow screens each row is shown as a labelled card instead of scrolling.
    ``table_class``: extra class of the table element.
    Cells may be ``("html", markup)``, ``("n", text)`` (right-aligned text), ``("d", text)``
    (a difference: right-aligned, class ``diff``) or ``("u", text)`` (a unit: not wrapped).
    """
    th = "".join(f"<th>{_e(h)}</th>" for h in headers)
    body = []
    for i, r in enumerate(rows):
        cells = []
        for h, c in zip(headers, r, strict=True):
            lab = f' data-label="{_e(h)}"' if cards else ""
            if isinstance(c, tuple) and len(c) == 2 and c[0] == "html":
                cells.append(f"<td{lab}>{c[1]}</td>")
            elif isinstance(c, tuple) and len(c) == 2 and c[0] in ("n", "d", "u"):
                kind = {"n": "n", "d": "n diff", "u": "u"}[c[0]]
                cells.append(f'<td class="{kind}"{lab}>{_e(c[1])}</td>')
            elif isinstance(c, bool) or not isinstance(c, int | float):
                long = ' class="long"' if isinstance(c, str) and len(c) > 40 else ""
                cells.append(f"<td{long}{lab}>{_e(fmt(c))}</td>")
            else:
                cells.append(f'<td class="n"{lab}>{_e(fmt(c))}</td>')
        cls = f' class="{row_class[i]}"' if row_class and row_class[i] else ""
        body.append(f"<tr{cls}>{''.join(cells)}</tr>")
    classes = " ".join(c for c in ("cards" if cards else "", table_class) if c)
    tcls = f' class="{classes}"' if classes else ""
    return (f'<div class="scroll"><table{tcls}><thead><tr>{th}</tr></thead>'
            f"<tbody>{''.join(body)}</tbody></table></div>")


def _at(v: float, decimals: int) -> str:
    """``v`` with ``decimals`` decimals, or more so that two significant figures show."""
    if v == 0.0 or v != v or abs(v) == float("inf"):
        return fmt(v)
    two_sig = 1 - math.floor(math.log10(abs(v)))
    return f"{v:.{max(decimals, min(two_sig, 12))}f}"


def _pct(x: float) -> str:
    """A relative difference in % with the digits it deserves (+0.11 %, -10.8 %, +38 %... )."""
    a = abs(x)
    return f"{x:+.0f} %" if a >= 100 else f"{x:+.1f} %" if a >= 1 else f"{x:+.2f} %"


def comparison_cells(c: dict[str, Any]) -> tuple[str, str, str]:
    """Paper value, our value and the difference of one paper-beside-ours row, as text.

    Values are rounded to the decimals the paper printed (``c["decimals"]``; ours with at
    least two significant figures). The difference (ours - paper) is shown as
    ``c["difference_kind"]`` says (the kinds of :class:`exofric.reproduction.Comparison`):
    ``relative`` -- in the row's unit and in % of the paper value; ``points`` -- the row is in
    %, so the difference is in percentage points (``pp``); ``absolute`` -- in the unit only;
    ``none`` -- '-' (p-values, fitted coefficients, a missing value).

    Parameters
    ----------
    c : dict
        A row as :meth:`exofric.reproduction.Comparison.to_dict` gives it (``results.json``
        holds them): ``paper_value``, ``our_value``, ``difference``, ``difference_pct``,
        ``difference_kind``, ``decimals``; units those of the row (mm, N, MPa, s, Nm, %).

    Returns
    -------
    tuple of str
        ``(paper, ours, difference)``.

    Examples
    --------
    >>> from exofric.reproduction import Comparison
    >>> comparison_cells(Comparison("N at 0.6 MPa", "N", 268.55, 239.557).to_dict())
    ('268.55', '239.56', '-28.99 (-10.8 %)')
    >>> comparison_cells(Comparison("PI reduction", "%", 26.0, 32.673).to_dict())
    ('26', '33', '+7 pp')
    >>> comparison_cells(Comparison("test 7: ANOVA p-value", "", 0.0075, 0.6631).to_dict())
    ('0.0075', '0.6631', '-')
    """
    pv, ov, dec = c["paper_value"], c["our_value"], c.get("decimals")
    kind = c.get("difference_kind", "relative")
    if dec is None:   # no paper value: ours as the report prints any number
        return fmt(pv), fmt(ov), "-"
    paper = f"{pv:.{dec}f}" if isinstance(pv, float) else fmt(pv)
    ours = "-" if ov is None else _at(float(ov), dec)
    d = c["difference"]
    if kind == "none" or d is None:
        return paper, ours, "-"
    if round(d, dec) == 0.0:
        return paper, ours, "0"   # equal to the digits the paper printed
    diff = f"{d:+.{dec}f}"
    if kind == "points":
        return paper, ours, f"{diff} pp"
    if kind == "relative" and c["difference_pct"] is not None:
        return paper, ours, f"{diff} ({_pct(c['difference_pct'])})"
    return paper, ours, diff


def _cmp_table(rows: Sequence[dict[str, Any]], ours_label: str = "exofric") -> str:
    """Paper value beside ours with the difference (see :func:`comparison_cells`)."""
    head = ["quantity", "unit", "paper", ours_label, "ours - paper", "note"]
    out, cls = [], []
    for c in rows:
        q = _e(c["quantity"]) + (' <span class="badge">SYNTHETIC</span>' if c["synthetic"]
                                 else "")
        paper, ours, diff = comparison_cells(c)
        out.append([("html", q), ("u", c["unit"] or "-"), ("n", paper), ("n", ours), ("d", diff),
                    c["note"]])
        cls.append("synthetic" if c["synthetic"] else "")
    return _table(head, out, cls, cards=True, table_class="cmp")


def _figure(fig: Any) -> str:
    data = base64.b64encode(fig.path.read_bytes()).decode("ascii")
    return (f'<figure id="fig-{_e(fig.key)}"><img src="data:image/png;base64,{data}" '
            f'alt="{_e(fig.title)}" loading="eager"><figcaption><b>{_e(fig.title)}.</b> '
            f"{_e(fig.caption)} <span class=\"muted\">({_e(fig.path.name)})</span>"
            "</figcaption></figure>")
