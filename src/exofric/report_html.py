"""HTML of the reproduction report: one self-contained page, no template engine, no network.

Figures are embedded as base64 PNG, the CSS is inline (responsive: tables scroll sideways on
a phone, images scale; a print style drops navigation and keeps figures whole). Every number
shown comes from the results dict that is also written to ``results.json``. The paper's
inconsistency notes (Markdown) are rendered with markdown-it (a dependency of rich), raw
HTML disabled.

Units: mm, N, MPa, s, Nm; differences in %.
"""

from __future__ import annotations

import base64
import html
import re
from collections.abc import Sequence
from datetime import datetime, timezone
from typing import Any

__all__ = ["render_html", "fmt"]



def _e(x: Any) -> str:
    return html.escape(str(x), quote=True)


def fmt(v: Any, digits: int = 5) -> str:
    """Format a number for the report (``digits`` significant; None -> '-').

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


def _pick(d: dict[str, Any], stage: str, prefix: str) -> dict[str, Any] | None:
    return next((c for c in _cmps(d, stage) if c["quantity"].startswith(prefix)), None)


# ----------------------------------------------------------------------------- sections


def _s_table2(d: dict[str, Any]) -> str:
    s = d["stages"]["table2"]
    rows = [[r["quantity"], r["unit"] or "-", r["paper_value"], r["eq_value"], r["slip_value"],
             r["eq_matches_printed"], r["slip_matches_printed"]] for r in s["rows"]]
    return ("<p>Eqs 3-6 at the paper's Shore 62.5, computed exactly, beside the printed Table 2. "
            "E0 and G match as printed; C10, C01 and d do not: the printed C10 is G/2/1.005 "
            "instead of G/2/1.05 (a slip), and C01 and d follow the slipped C10. exofric uses "
            "Eqs 3-6 exactly; the last column applies the slip to show it reproduces the "
            "printed values.</p>"
            + _table(["parameter", "unit", "paper (printed)", "exofric, Eqs 3-6",
                      "with the C10 slip", "Eqs match printed", "slip matches printed"],
                     rows, cards=True))


def _s_calibration(d: dict[str, Any]) -> str:
    s = d["stages"]["calibration"]
    cols = s["columns"]
    p = cols[0]["pressure_mpa"]
    head = ["P (MPa)"]
    for c in cols:
        head += [f"{c['shore']:g} Hs paper", f"{c['shore']:g} Hs exofric", "diff. %"]
    head.append("test")
    test = d["stages"]["calibration"]["bisection"]["points"]
    rows: list[list[Any]] = []
    for i, pv in enumerate(p):
        row: list[Any] = [pv]
        for c in cols:
            row += [c["paper_outer_diameter_mm"][i], c["our_outer_diameter_mm"][i],
                    ("n", _signed(c["difference_pct"][i], 3))]
        row.append(test[i]["measured_outer_diameter_mm"])
        rows.append(row)
    avg: list[Any] = ["average error (%)"]
    for c in cols:
        avg += [c["paper_average_error_pct"], c["our_average_error_pct"], ""]
    avg.append("")
    rows.append(avg)
    bis, bnd = s["bisection"], s["bounded"]
    hist = ", ".join(f"{a:g} ({b:.2f}%)" for a, b in zip(bis["history_shore"],
                                                          bis["history_average_error_pct"],
                                                          strict=True))
    notes = "".join(f"<li>{_e(n)}</li>" for n in bis["notes"] + bnd["notes"])
    maxdiff = max(c["max_abs_difference_pct"] for c in cols)
    return (
        f"<p>The paper does not print the tube's inner diameter. Fitting it to the 16 printed "
        f"ANSYS diameters (each column at its own hardness, Eq 4 constants) gives "
        f"<b>{fmt(s['tube_id_mm'])} mm</b> (standard error {fmt(s['tube_id_stderr_mm'], 2)} mm; "
        f"with the printed, slipped constants {fmt(s['tube_id_slip_mm'])} mm). With it our FE "
        f"reproduces every printed ANSYS diameter within <b>{maxdiff:.2f}%</b>.</p>"
        f"<p>The paper's bisection on the test column with that ID: Shore "
        f"<b>{fmt(s['shore'], 4)}</b> (average error {fmt(bis['average_error_pct'], 3)}%); "
        f"a bounded minimisation of the average error gives {fmt(s['shore_bounded'], 4)} "
        f"({fmt(bnd['average_error_pct'], 3)}%). Trials: {_e(hist)}.</p>"
        f"<ul>{notes}</ul>"
        "<h3>Table 1: outer diameters (mm)</h3>" + _table(head, rows)
    )


def _s_squeeze(d: dict[str, Any]) -> str:
    s = d["stages"]["squeeze"]
    q = s["squeeze"]
    st = q["structure"]
    rows = [[q["pressure_mpa"][i], q["squeeze_force_n"][i], q["squeeze_force_n_per_mm"][i],
             q["wall_force_n"][i], q["wire_contact_halfwidth_mm"][i],
             q["max_penetration_mm"][i], q["newton_iterations"][i]]
            for i in range(len(q["pressure_mpa"]))]
    sens = [[v["variant"], v["n_at_0_6_mpa_n"], ("n", _signed(v["change_pct"], 3, " %"))]
            for v in s["sensitivity"]]
    slip = next(v for v in s["sensitivity"] if v["variant"].startswith("printed"))
    pen = next(v for v in s["sensitivity"] if v["variant"].startswith("contact"))
    n06 = s["n_at_0_6_mpa_n"]
    cal = d["stages"]["calibration"]
    cancel = ("the slip shifts the fitted ID and the two effects nearly cancel"
              if abs(slip["change_pct"]) < 2.0 else "the slip does not explain the gap alone")
    return (
        f"<p>Base group D = {fmt(st['hole_mm'])} mm, d1 = {fmt(st['tube_od_mm'])} mm, "
        f"calibrated ID = {fmt(st['tube_id_mm'])} mm, d2 = {fmt(st['wire_mm'])} mm, "
        f"L = {fmt(st['length_mm'])} mm; Shore {fmt(q['material']['shore'], 4)} (Eq 4 "
        f"constants). Plane strain, half model, {q['dofs']} dofs, mesh "
        f"{q['mesh']['n_radial']} x {q['mesh']['n_circ']} quad9 graded "
        f"{fmt(q['mesh']['grading'])}:1; frictionless penalty contact; contact with the wire "
        f"starts at {fmt(q['contact_onset_pressure_mpa'], 3)} MPa.</p>"
        f"<p>Our N at 0.6 MPa is <b>{fmt(n06)} N</b>, the paper's 268.55 N. "
        "Why they may differ:</p><ul>"
        f"<li><b>The unprinted tube ID.</b> dN/dID = {fmt(s['dn_did_n_per_mm'], 3)} N/mm; "
        f"268.55 N would need an ID of about {fmt(s['id_to_match_paper_mm'], 3)} mm, while the "
        f"paper's own Table 1 columns give {fmt(cal['tube_id_mm'])} mm (standard error "
        f"{fmt(cal['tube_id_stderr_mm'], 2)} mm).</li>"
        f"<li><b>The C10 slip.</b> With the printed Table 2 constants (4.5% stiffer) and the ID "
        f"that fits Table 1 under them, N changes by {_signed(slip['change_pct'], 3, ' %')}: "
        f"{cancel}.</li>"
        f"<li><b>Contact settings.</b> A 10x softer penalty changes N by "
        f"{_signed(pen['change_pct'], 3, ' %')}. The paper does not say whether ANSYS used "
        "friction between tube, wire and wall, how the initial gap (0.1 mm) was closed, or how "
        "'the vertical component of the contact force' was summed; each can move N by more "
        "than our discretisation does.</li>"
        "<li><b>Model.</b> Plane strain over L = 116 mm ignores the tube ends; the paper's "
        "ANSYS inflation curves are also less convex than exact plane-strain inflation (see "
        "the calibration notes).</li></ul>"
        "<h3>N(P), base group</h3>"
        + _table(["P (MPa)", "N (N)", "N (N/mm)", "wall force (N)", "wire contact half-width "
                  "(mm)", "max penetration (mm)", "Newton iterations"], rows)
        + "<h3>What moves N at 0.6 MPa</h3><p class=\"muted\">On the sensitivity mesh "
        f"({d['config']['sensitivity_mesh']['n_radial']} x "
        f"{d['config']['sensitivity_mesh']['n_circ']}); differences from its baseline.</p>"
        + _table(["variant", "N at 0.6 MPa (N)", "change"], sens, cards=True)
    )


def _s_gamma(d: dict[str, Any]) -> str:
    g = d["stages"]["gamma"]
    f = g["fit"]
    rig = g["rig"]["config"]
    return (
        '<div class="box synthetic"><span class="badge">SYNTHETIC</span> The paper publishes no '
        "raw friction curve. The base group's 'measured' friction here comes from exofric's "
        f"virtual rig with gamma_true = {fmt(g['gamma_true'])} planted on our N(P) "
        f"({rig['noise_pct']:g}% load-cell noise per sample, averaged over each sliding window, "
        f"seed {g['rig']['seed']}). "
        "Recovering gamma checks the pipeline; it does not reproduce the paper's fit.</div>"
        f"<p>Fitted gamma = <b>{fmt(f['gamma'])}</b> (95% CI {fmt(f['gamma_ci95'][0])} to "
        f"{fmt(f['gamma_ci95'][1])}, {f['ci_method']}), mean |relative error| "
        f"{fmt(f['relative_error_pct'], 3)}%, max {fmt(f['max_relative_error_pct'], 3)}%, "
        f"relative RMS {fmt(f['rms_relative_error_pct'], 3)}%, {f['n_points']} points.</p>"
        f"<p>The one gamma that rests on a measured number of the paper: its base friction "
        f"180.49 N at 0.6 MPa divided by our N(0.6 MPa) gives <b>"
        f"{fmt(g['gamma_published_point'], 4)}</b>; divided by its own 268.55 N it gives "
        f"{fmt(g['gamma_paper_pair'], 4)}, not 0.7168 (the fit used the whole curve).</p>"
    )


def _s_prediction(d: dict[str, Any]) -> str:
    s = d["stages"]["prediction"]
    geo, err = [], []
    for r in s["rows"]:
        st = r["structure"]
        geo.append([f"{r['test']} ({r['group']})", st["hole_mm"], st["tube_od_mm"],
                    st["tube_id_mm"], st["wire_mm"], r["clearance_mm"],
                    r["contact_onset_pressure_mpa"], r["paper_deviation_printed_pct"],
                    r["paper_deviation_pct"], r["tube_ref_deviation_pct"], r["deviation_pct"],
                    r["in_validated_region"]])
        err.append([f"test {r['test']}", r["n_rig_points"], r["paper_max_relative_error_pct"],
                    r["max_relative_error_pct"], r["paper_p_value"], r["p_value"]])
    warn = "".join(f"<li>{_e(w)}</li>" for w in s["warnings"])
    return (
        '<div class="box synthetic"><span class="badge">SYNTHETIC</span> Every structure\'s '
        "'tested' curve comes from the virtual rig with the same gamma_true and no "
        "per-structure effect: it is what the data would look like if the Coulomb model held "
        "exactly. The paper's maximum errors (-12% to +189%) and Table 4 p-values come from "
        "unpublished curves and <b>cannot be reproduced</b>; ours show the noise floor.</div>"
        "<p>Tube IDs are not printed for tests 2-7; they are the base ID scaled with d1. "
        "Deviation readings (%): printed; 100 max|s - 1|; 100 max|s - s_d1|; exofric's "
        "100 (max s / min s - 1) with the 20% validated limit (s: diameters / base "
        "diameters).</p><h3>Geometry and deviation</h3>"
        + _table(["test (group)", "D (mm)", "d1 (mm)", "ID (mm)", "d2 (mm)", "gap (mm)",
                  "onset (MPa)", "dev. printed", "max|s-1|", "max|s-s_d1|", "exofric dev.",
                  "within 20%"], geo)
        + "<h3>Prediction errors and ANOVA (SYNTHETIC)</h3>"
        + _table(["test", "rig points", "max error, paper (%)", "max error, ours (%)",
                  "p-value, paper", "p-value, ours"], err, cards=True)
        + (f"<p class=\"muted\">Warnings:</p><ul>{warn}</ul>" if warn else "")
    )


def _s_cubic(d: dict[str, Any]) -> str:
    c = d["stages"]["cubic"]
    inv = c["inverse_mpa"]
    rows = [["paper, as printed (Sec 5)", inv["paper_printed_mpa"]],
            ["Eq 9 inverted (the paper's own equation)", inv["eq9_mpa"]],
            ["Eq 8 inverted without gamma (explains the 0.26)", inv["eq8_without_gamma_mpa"]],
            ["exofric cubic with our gamma", inv["our_cubic_mpa"]],
            ["exofric FE curve, exact inverse, our gamma", inv["our_exact_curve_mpa"]]]
    return (
        "<p>Least-squares cubic of our test-5 N(P) on 0.2-0.6 MPa beside Eq 8. The cubic "
        "coefficients are ill-conditioned (they trade off against each other), so compare "
        "the curves and N values rather than single coefficients.</p>"
        f"<h3>Pressure for {fmt(d['config']['target_friction_n'])} N (MPa)</h3>"
        + _table(["route", "pressure (MPa)"], rows, cards=True)
    )


def _s_control(d: dict[str, Any]) -> str:
    c = d["stages"]["control"]
    ours = {(k["controller"], k["feedforward"]): k for k in c["our_map"]["cases"]}
    rows = []
    for k in c["paper_map"]["cases"]:
        o = ours[(k["controller"], k["feedforward"])]
        rows.append([k["controller"].upper() + (" + model" if k["feedforward"] else ""),
                     k["paper_settling_time_s"], k["settling_time_s"], k["overshoot_pct"],
                     k["final_friction_n"], o["settling_time_s"], o["final_friction_n"]])
    red = c["paper_map"]["settling_reduction_pct"]
    red_o = c["our_map"]["settling_reduction_pct"]
    return (
        "<p>The paper prints no plant parameters and no gains. exofric assumes a small "
        "pneumatic supply (lag 0.8 s, dead time 0.2 s, 0-0.6 MPa) and tunes PD/PI/PID by the "
        "IMC/SIMC rule with the same gains with and without the model (2-DOF feedforward); "
        "see the control notes in docs/paper-notes*.md. Settling band 2%.</p>"
        + _table(["case", "paper settling (s)", "exofric settling (s), Eq 9",
                  "overshoot (%)", "final F (N)", "exofric settling (s), our test-5 FE curve",
                  "final F (N), our FE curve"], rows, cards=True)
        + f"<p>Settling-time reduction with the model: PI {fmt(red['pi'], 3)}% (paper 26%), "
        f"PID {fmt(red['pid'], 3)}% (paper 29%); on our test-5 FE curve with our gamma: PI "
        f"{fmt(red_o['pi'], 3)}%, PID {fmt(red_o['pid'], 3)}%. '-' = never settles within "
        "the 2% band.</p>"
    )


def _s_torque(d: dict[str, Any]) -> str:
    tr = d["stages"]["torque"]["rows"]
    rows = [[r["name"], r["friction_n"], r["arm_radius_m"], r["torque_nm"], r["coverage_pct"],
             r["meets_max"]] for r in tr]
    reach = [r["name"] for r in tr if r["meets_max"]]
    best = max(tr, key=lambda r: r["torque_nm"])
    verdict = (f"{', '.join(reach)} reach(es) 40 Nm at 0.6 MPa" if reach else
               f"none of the seven structures reaches 40 Nm at 0.6 MPa (largest: {best['name']}, "
               f"{fmt(best['torque_nm'], 3)} Nm)")
    return ("<p>Predicted friction at 0.6 MPa (gamma N) times the 0.10 m arm, against the "
            f"knee's 0-40 Nm (paper ref [32]): {verdict}. The paper's own largest, 30 Nm "
            "(test 3, measured friction), covers 75% of the range.</p>"
            + _table(["structure", "F at 0.6 MPa (N)", "arm (m)", "T (Nm)",
                      "covers 0-40 Nm (%)", "reaches 40 Nm"], rows, cards=True))


_SECTIONS = {"table2": _s_table2, "calibration": _s_calibration, "squeeze": _s_squeeze,
             "gamma": _s_gamma, "prediction": _s_prediction, "cubic": _s_cubic,
             "control": _s_control, "torque": _s_torque}

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
    from .reproduce import STAGES

    seen = {k: 1 for k in ("glance", "synthetic", "inconsistencies", "run",
                           *(key for key, _ in STAGES))}
    for name, text in notes:
        out += f'<h3 id="{_e(name)}">{_e(name)}</h3><div class="notes">{_md(text, seen)}</div>'
    return out


def _run_details(d: dict[str, Any]) -> str:
    def sec(v: float | None) -> tuple[str, str]:
        return ("n", "-" if v is None else f"{v:.2f}")

    rows = [[t["title"], sec(t["wall_time_s"])] for t in d["stage_times"]]
    rows.append(["figures and report", sec(d.get("report_time_s"))])
    rows.append(["total computation (stages 1-8)", sec(d["wall_time_s"])])
    cfg = d["config"]
    mesh = [["mode", "fast (coarse meshes)" if cfg["fast"] else "default (converged meshes)"],
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
    >>> data = json.loads(Path("exofric-report/results.json").read_text())  # doctest: +SKIP
    >>> render_html(data, [], [])[:15]                                     # doctest: +SKIP
    '<!DOCTYPE html>'
    """
    from .report import REPORT_CSS
    from .reproduce import STAGES

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
            f"<h3>Paper beside exofric</h3>{_cmp_table(_cmps(data, key))}{figs}</section>")
    when = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")  # noqa: UP017
    mode = "fast (coarse meshes)" if data["config"]["fast"] else "default (converged meshes)"
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
curves are unpublished).</p>
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
