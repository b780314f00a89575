"""`exofric reproduce --fast`: results.json against a schema and the key numbers of the paper.

One `--fast` run (subprocess, the real CLI) is shared by this module and
tests/test_report_browser.py through :func:`fast_report_dir` (cached in pytest's session temp
directory, with a file lock so xdist workers reuse it too).
"""

from __future__ import annotations

import fcntl
import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from exofric.reproduction import Comparison, paper_checks, printed_decimals


def fast_report_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Run `exofric reproduce --fast --json --out DIR` once per session; return DIR.

    DIR also holds ``cli.json`` = {"code", "stdout", "stderr"} of that run.
    """
    base = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        base = base.parent  # shared by the workers of this session
    out = base / "exofric-reproduce-fast"
    with open(base / "exofric-reproduce-fast.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        record = out / "cli.json"
        if not record.exists():
            proc = subprocess.run(
                [sys.executable, "-m", "exofric", "reproduce", "--fast", "--json", "--out",
                 str(out)], capture_output=True, text=True, timeout=600)
            out.mkdir(parents=True, exist_ok=True)
            record.write_text(json.dumps({"code": proc.returncode, "stdout": proc.stdout,
                                          "stderr": proc.stderr}))
    return out


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict[str, Any], dict[str, Any]]:
    out = fast_report_dir(tmp_path_factory)
    cli = json.loads((out / "cli.json").read_text())
    assert cli["code"] == 0, cli["stderr"]
    return out, cli, json.loads((out / "results.json").read_text())


# ------------------------------------------------------------------------------- schema

NUM = (int, float)
OPT_NUM = (int, float, type(None))
CMP = {"quantity": str, "unit": str, "paper_value": OPT_NUM, "our_value": OPT_NUM,
       "difference": OPT_NUM, "difference_pct": OPT_NUM, "difference_kind": str,
       "decimals": OPT_NUM, "note": str, "synthetic": bool}
SCHEMA: dict[str, Any] = {
    "exofric_version": str,
    "config": {"fast": bool, "pressures_mpa": [NUM], "gamma_true": NUM, "seed": int,
               "squeeze_mesh": {"n_radial": int, "n_circ": int}},
    "stages": {
        "table2": {"shore": NUM, "rows": [{"key": str, "paper_value": NUM, "eq_value": NUM,
                                          "slip_value": NUM, "eq_matches_printed": bool}],
                   "comparisons": [CMP]},
        "calibration": {"tube_id_mm": NUM, "tube_id_slip_mm": NUM, "shore": NUM,
                        "columns": [{"shore": NUM, "paper_outer_diameter_mm": [NUM],
                                     "our_outer_diameter_mm": [NUM], "difference_pct": [NUM],
                                     "our_average_error_pct": NUM}],
                        "comparisons": [CMP]},
        "squeeze": {"n_at_0_6_mpa_n": NUM, "dn_did_n_per_mm": NUM,
                    "squeeze": {"pressure_mpa": [NUM], "squeeze_force_n": [NUM]},
                    "sensitivity": [{"variant": str, "n_at_0_6_mpa_n": NUM, "change_pct": NUM}],
                    "comparisons": [CMP]},
        "gamma": {"synthetic": bool, "gamma": NUM, "gamma_true": NUM,
                  "gamma_published_point": NUM, "fit": {"gamma_ci95": [NUM]},
                  "comparisons": [CMP]},
        "prediction": {"synthetic": bool, "rows": [{"test": int, "deviation_pct": NUM,
                                                    "max_relative_error_pct": NUM}],
                       "comparisons": [CMP]},
        "cubic": {"ours": {"coefficients": [NUM], "r2": NUM},
                  "inverse_mpa": {"eq9_mpa": NUM, "paper_printed_mpa": NUM,
                                  "our_exact_curve_mpa": NUM},
                  "comparisons": [CMP]},
        "control": {"paper_map": {"cases": [{"controller": str, "feedforward": bool}]},
                    "comparisons": [CMP]},
        "torque": {"rows": [{"name": str, "torque_nm": NUM, "coverage_pct": NUM}],
                   "comparisons": [CMP]},
    },
    "comparisons": [{"stage": str, **CMP}],
    "paper_checks": [CMP],
    "stage_times": [{"key": str, "title": str, "wall_time_s": NUM}],
    "wall_time_s": NUM,
    "versions": {"python": str, "numpy": str, "scipy": str, "exofric": str},
    "figures": [{"key": str, "file": str, "title": str, "stage": str}],
    "notes_files": [str],
    "report_time_s": NUM,
}


def check_schema(obj: Any, schema: Any, path: str = "$") -> list[str]:
    """Errors of ``obj`` against ``schema`` (dict: required keys; [s]: list of s; type(s))."""
    if isinstance(schema, dict):
        if not isinstance(obj, dict):
            return [f"{path}: expected object, got {type(obj).__name__}"]
        errs = []
        for k, sub in schema.items():
            if k not in obj:
                errs.append(f"{path}.{k}: missing")
            else:
                errs += check_schema(obj[k], sub, f"{path}.{k}")
        return errs
    if isinstance(schema, list):
        if not isinstance(obj, list) or not obj:
            return [f"{path}: expected a non-empty list"]
        return [e for i, x in enumerate(obj) for e in check_schema(x, schema[0], f"{path}[{i}]")]
    types = schema if isinstance(schema, tuple) else (schema,)
    if isinstance(obj, bool) and bool not in types:
        return [f"{path}: bool where {types} expected"]
    if not isinstance(obj, types):
        return [f"{path}: expected {types}, got {type(obj).__name__}"]
    if isinstance(obj, float) and not math.isfinite(obj):
        return [f"{path}: not finite"]
    return []


def test_schema_checker_catches_errors() -> None:
    # the checker itself must fail on missing keys, wrong types and empty lists
    assert check_schema({"a": 1}, {"a": str, "b": int}) == [
        "$.a: expected (<class 'str'>,), got int", "$.b: missing"]
    assert check_schema({"a": []}, {"a": [int]}) == ["$.a: expected a non-empty list"]
    assert check_schema(True, NUM) != []


def test_results_json_schema_and_cli_json(run) -> None:  # type: ignore[no-untyped-def]
    out, cli, res = run
    assert check_schema(res, SCHEMA) == []
    # --json: exactly one JSON object on stdout, the same numbers plus the file list
    d = json.loads(cli["stdout"])
    assert d["stages"]["squeeze"]["n_at_0_6_mpa_n"] == res["stages"]["squeeze"]["n_at_0_6_mpa_n"]
    assert Path(d["files"]["report_html"]) == out / "report.html"
    assert res["config"]["fast"] is True
    assert [t["key"] for t in res["stage_times"]] == [
        "table2", "calibration", "squeeze", "gamma", "prediction", "cubic", "control", "torque"]
    for f in res["figures"]:
        assert (out / f["file"]).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(res["figures"]) >= 11
    # every comparison row follows Comparison's sign convention, difference = ours - paper
    # (a consistency check of the table the report prints; the convention itself is checked
    # by hand arithmetic in test_comparison_and_printed_decimals)
    for c in res["comparisons"]:
        if c["paper_value"] is not None and c["our_value"] is not None:
            assert c["difference"] == pytest.approx(c["our_value"] - c["paper_value"], abs=1e-12)


def test_table2_exact(run) -> None:  # type: ignore[no-untyped-def]
    rows = {r["key"]: r for r in run[2]["stages"]["table2"]["rows"]}
    # independent reference: Eqs 3-6 by hand at 62.5 Shore, nu = 0.498 (exact arithmetic)
    e0 = (2.15 * 62.5 + 15.75) / (100.0 - 62.5)
    g = e0 / 3.0
    c10 = g / 2.0 / 1.05
    want = {"e0_mpa": e0, "g_mpa": g, "c10_mpa": c10, "c01_mpa": 0.05 * c10,
            "d_per_mpa": (1.0 - 2.0 * 0.498) / (1.05 * c10), "shore": 62.5, "poisson": 0.498}
    for k, v in want.items():
        assert rows[k]["eq_value"] == pytest.approx(v, rel=1e-14), k
    printed = {"shore": 62.5, "e0_mpa": 4.0033, "g_mpa": 1.3344, "c01_mpa": 0.0332,
               "c10_mpa": 0.6639, "poisson": 0.498, "d_per_mpa": 0.00575}
    assert {k: r["paper_value"] for k, r in rows.items()} == printed
    matches = {k for k, r in rows.items() if r["eq_matches_printed"]}
    assert matches == {"shore", "e0_mpa", "g_mpa", "poisson"}   # the C10 slip breaks the rest
    # the slip (C10 = G/2/1.005) reproduces the printed C10 and C01 to their printed digits
    assert rows["c10_mpa"]["slip_value"] == pytest.approx(g / 2.0 / 1.005, rel=1e-14)
    assert rows["c10_mpa"]["slip_matches_printed"] and rows["c01_mpa"]["slip_matches_printed"]


def test_table1_columns_within_half_percent(run) -> None:  # type: ignore[no-untyped-def]
    cal = run[2]["stages"]["calibration"]
    cols = cal["columns"]
    assert [c["shore"] for c in cols] == [60.0, 65.0, 70.0, 62.5]
    for c in cols:
        ours, theirs = np.array(c["our_outer_diameter_mm"]), np.array(c["paper_outer_diameter_mm"])
        # acceptance: each of the 16 printed ANSYS diameters within 0.5% (notes: max 0.42%)
        assert np.all(np.abs(ours / theirs - 1.0) < 0.005), c["shore"]
        # consistency: the printed column is what its name says (not a correctness check)
        assert c["difference_pct"] == pytest.approx((100 * (ours / theirs - 1)).tolist())
    # the paper's bisection on the test column gives 62.5 Shore; ours lands within 0.2 of it
    # (same tolerance as tests/test_calibrate.py). The fitted tube ID and Shore themselves are
    # regression pins: tests/test_regression_reproduce.py.
    assert abs(cal["shore"] - 62.5) < 0.2


def test_inverse_0293_not_026(run) -> None:  # type: ignore[no-untyped-def]
    inv = run[2]["stages"]["cubic"]["inverse_mpa"]
    # independent reference: the root of 0.7168 x Eq 8 = 54.40 N in [0.2, 0.6] by np.roots
    c = 0.7168 * np.array([-1957.4, 2412.8, -251.95, -7.9531]) - np.array([0, 0, 0, 54.40])
    r = [x.real for x in np.roots(c) if abs(x.imag) < 1e-12 and 0.2 <= x.real <= 0.6]
    assert len(r) == 1
    assert inv["eq9_mpa"] == pytest.approx(r[0], abs=1e-9)
    assert round(inv["eq9_mpa"], 3) == 0.293
    assert inv["paper_printed_mpa"] == 0.26
    assert round(inv["eq8_without_gamma_mpa"], 2) == 0.26       # the slip: gamma left out


def test_squeeze_gamma_and_synthetic_labels(run) -> None:  # type: ignore[no-untyped-def]
    st = run[2]["stages"]
    sq = st["squeeze"]
    assert sq["n_at_0_6_mpa_n"] == sq["squeeze"]["squeeze_force_n"][-1]
    assert sq["squeeze"]["pressure_mpa"][-1] == 0.6
    assert np.all(np.diff(sq["squeeze"]["squeeze_force_n"]) >= 0)
    # planted truth: the rig planted gamma_true; 9 points, ~0.1% noise per point -> 1%
    g = st["gamma"]
    assert g["gamma"] == pytest.approx(g["gamma_true"], rel=0.01)
    assert g["gamma_published_point"] == pytest.approx(180.49 / sq["n_at_0_6_mpa_n"], rel=1e-12)
    syn = {c["quantity"] for c in run[2]["comparisons"] if c["synthetic"]}
    assert "gamma (Eq 7)" in syn
    assert all(c["synthetic"] for c in st["prediction"]["comparisons"]
               if "error" in c["quantity"] or "p-value" in c["quantity"])
    assert all(not c["synthetic"] for c in st["table2"]["comparisons"])
    # the torque row equals gamma x N(0.6) x 0.10 m
    t1 = next(r for r in st["torque"]["rows"] if r["name"] == "test 1")
    assert t1["torque_nm"] == pytest.approx(g["gamma"] * sq["n_at_0_6_mpa_n"] * 0.10, rel=1e-9)


def test_paper_checks_arithmetic() -> None:
    rows = {c.quantity: c for c in paper_checks()}
    pi = next(c for q, c in rows.items() if q.startswith("Sec 5 PI "))
    assert pi.our_value == pytest.approx((5.73 - 4.20) / 5.73 * 100, rel=1e-12)
    f026 = next(c for q, c in rows.items() if "printed 0.26" in q)
    p = 0.26
    assert f026.our_value == pytest.approx(0.7168 * (-1957.4 * p**3 + 2412.8 * p**2
                                                     - 251.95 * p - 7.9531), rel=1e-12)


def test_comparison_and_printed_decimals() -> None:
    c = Comparison("x", "N", 200.0, 150.0)
    assert (c.difference, c.difference_pct) == (-50.0, -25.0)
    assert Comparison("x", "", None, 1.0).difference is None
    assert Comparison("x", "", 0.0, 1.0).difference_pct is None
    assert [printed_decimals(v) for v in (4.0033, 0.00575, 62.5, 30.0, 1e-05)] == [4, 5, 1, 0, 5]


def test_difference_shown_only_where_it_means_something() -> None:
    from exofric.report import comparison_cells

    def cells(*args: Any, **kw: Any) -> tuple[str, str, str]:
        return comparison_cells(Comparison(*args, **kw).to_dict())

    # relative: by hand, 239.557 - 268.55 = -28.993 N, 100 x -28.993 / 268.55 = -10.796 %
    assert cells("N", "N", 268.55, 239.557) == ("268.55", "239.56", "-28.99 (-10.8 %)")
    # already in %: percentage points, to the paper's 0 decimals (32.673 - 26 = 6.673 pp)
    c = Comparison("PI reduction", "%", 26.0, 32.673)
    assert (c.difference_kind, c.difference_pct) == ("points", None)
    assert cells("PI reduction", "%", 26.0, 32.673) == ("26", "33", "+7 pp")
    # p-values (the issue's +8.74e+03 %) and fitted cubic coefficients: no difference
    p = Comparison("test 7: ANOVA p-value vs base (Table 4)", "", 0.0075, 0.6631)
    assert (p.difference_kind, p.difference_pct) == ("none", None)
    assert cells("test 7: ANOVA p-value", "", 0.0075, 0.6631) == ("0.0075", "0.6631", "-")
    assert cells("Eq 8 coefficient c0", "N", -7.9531, 88.396)[2] == "-"
    # opposite signs: a ratio means nothing, the difference in the unit does (3 - -5 = 8)
    assert cells("x", "N", -5.0, 3.0) == ("-5", "3.0", "+8")
    # equal to the digits the paper printed (Table 2 E0 = 4.00333 vs 4.0033)
    assert cells("E0", "MPa", 4.0033, 4.0033333)[2] == "0"
    # ours keeps two significant figures where the paper's digits would hide it
    assert cells("max error", "%", -12.0, 0.3568) == ("-12", "0.36", "+12 pp")
    # the paper's digits, at most 5 significant figures of a value its equations give
    assert Comparison("x", "N", 152.04130000000006, 1.0).decimals == 2
    assert Comparison("x", "1/MPa", 0.00575, 1.0).decimals == 5
    assert Comparison("x", "N", None, 1.0).decimals is None
    assert Comparison("x", "N", 10.0, 12.0, kind="points").difference_pct is None
    with pytest.raises(ValueError, match="kind"):
        Comparison("x", "N", 1.0, 2.0, kind="ratio")


def test_report_difference_rules_and_no_repeated_tables(run) -> None:  # type: ignore[no-untyped-def]
    out, _, res = run
    for c in res["comparisons"] + res["paper_checks"]:
        q = c["quantity"]
        if "p-value" in q or "coefficient" in q or c["paper_value"] is None:
            assert c["difference_kind"] == "none", q
        elif c["unit"] == "%":
            assert c["difference_kind"] == "points" and c["difference_pct"] is None, q
        if c["difference_pct"] is not None:
            assert abs(c["difference_pct"]) < 1000, q
    html = (out / "report.html").read_text(encoding="utf-8")
    # the stage tables already show Table 1, Table 2 and the prediction rows: not repeated
    assert "Table 1 OD" not in html and "Table 2 E0" not in html
    assert "ANOVA p-value vs base" not in html
    diffs = re.findall(r'<td class="n diff"[^>]*>([^<]*)</td>', html)
    assert len(diffs) > 20 and not [d for d in diffs if re.search(r"\de[-+]", d)], diffs


def test_cli_summary_reads_at_80_columns(fast_result, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    import io
    from types import SimpleNamespace

    from rich.console import Console

    import exofric.cli.reproduce as cli_reproduce

    con = Console(width=80, file=io.StringIO(), record=True, color_system=None)
    monkeypatch.setattr(cli_reproduce, "console", con)
    files = SimpleNamespace(report_time_s=1.0, report_html=Path("r/report.html"),
                            out_dir=Path("r"))
    cli_reproduce._summary(fast_result, files, 2.0)
    text = con.export_text()
    lines = text.splitlines()
    assert max(len(line) for line in lines) <= 80 and "\u2026" not in text   # no ellipsis
    # one line per row (nothing wrapped), differences as the rules say
    for _, label in cli_reproduce._PICKS:
        assert sum(label in line for line in lines) == 1, label
    pi = next(line for line in lines if line.lstrip().startswith("PI:"))
    assert pi.rstrip().endswith("pp") and "%" not in pi.split()[-1]
    n06 = next(line for line in lines if "N at 0.6 MPa, base" in line)
    assert n06.rstrip().endswith("%)")


def test_cli_out_is_a_file_gives_one_line_error(cli, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    f = tmp_path / "not-a-dir"
    f.write_text("x")
    r = cli(["reproduce", "--fast", "--json", "--out", str(f)])
    assert r.code == 2 and r.out == ""
    assert len(r.err.strip().splitlines()) == 1 and "--out" in r.err
