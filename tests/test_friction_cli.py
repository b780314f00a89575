"""CLI: fit-friction, predict (error handling), invert, rig; bad files and options exit 2."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from exofric import paper
from exofric.cli import run
from exofric.friction import CubicFit

EQ8 = CubicFit(paper.eq8(), 0.2, 0.6)
CUBIC = "--cubic=-1957.4,2412.8,-251.95,-7.9531"
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    """In-process CLI run (same code path as the console script), for the many error cases."""
    code = run(list(args))
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def _one_line_error(code: int, err: str, *needles: str) -> None:
    assert code == 2
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("exofric: error:"), err
    for n in needles:
        assert n in lines[0], lines[0]


@pytest.fixture
def squeeze_csv(tmp_path: Path) -> Path:
    p = np.linspace(0.2, 0.6, 17)
    path = tmp_path / "squeeze.csv"
    rows = "\n".join(f"{a:.6f},{EQ8(a):.8f}" for a in p)
    path.write_text("pressure_mpa,squeeze_force_n\n" + rows + "\n")
    return path


@pytest.fixture
def squeeze_json(tmp_path: Path) -> Path:
    p = np.linspace(0.2, 0.6, 17)
    path = tmp_path / "squeeze.json"
    path.write_text(json.dumps({"pressure_mpa": p.tolist(), "squeeze_force_n": EQ8(p).tolist(),
                                "squeeze_force_n_per_mm": (EQ8(p) / 116).tolist()}))
    return path


def test_invert_paper_example_subprocess(cli) -> None:  # type: ignore[no-untyped-def]
    # Acceptance: Eq 9 inverse for 54.4 N is 0.293 MPa (within 0.001), not the printed 0.26.
    r = cli(["invert", "--gamma", "0.7168", CUBIC, "--target-friction", "54.4", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert d["pressure_mpa"] == pytest.approx(0.293, abs=1e-3)
    assert d["target_squeeze_force_n"] == pytest.approx(54.4 / 0.7168)
    # outside the fitted range: exit 2 with one clear line
    r2 = cli(["invert", "--gamma", "0.7168", CUBIC, "--target-friction", "250", "--json"])
    _one_line_error(r2.code, r2.err, "outside the reachable range", "N")
    assert r2.out == ""


def test_invert_options(capsys: pytest.CaptureFixture[str], squeeze_csv: Path) -> None:
    code, out, _ = _run(capsys, "invert", "--gamma", "0.7168", CUBIC, "--target-friction",
                        "54.4", "--range", "0.2,0.6", "--json")
    assert code == 0 and json.loads(out)["p_max_mpa"] == 0.6
    # exact inverse through the tabulated curve, plus the cubic fitted over --range
    code, out, _ = _run(capsys, "invert", "--gamma", "0.7168", "--squeeze", str(squeeze_csv),
                        "--target-friction", "54.4", "--json")
    d = json.loads(out)
    assert code == 0 and d["method"].startswith("curve")
    # Reference: the exact root of 0.7168 x Eq 8 = 54.4 N by np.roots (0.2926454 MPa). The
    # curve is Eq 8 sampled every 0.025 MPa: PCHIP vs the root < 1e-3 MPa; the cubic fitted to
    # those exact samples is Eq 8 again, so its inverse matches the root to 1e-6 MPa.
    c = 0.7168 * np.array(paper.eq8()) - np.array([0.0, 0.0, 0.0, 54.4])
    root = [r.real for r in np.roots(c) if abs(r.imag) < 1e-12 and 0.2 <= r.real <= 0.6]
    assert len(root) == 1
    assert d["pressure_mpa"] == pytest.approx(root[0], abs=1e-3)
    assert d["cubic_pressure_mpa"] == pytest.approx(root[0], abs=1e-6)
    assert d["cubic"]["r2"] == pytest.approx(1.0, abs=1e-9)
    code, out, _ = _run(capsys, "invert", "--gamma", "0.7168", CUBIC, "--target-friction",
                        "54.4")
    assert code == 0 and "0.2926" in out
    _one_line_error(*_run(capsys, "invert", "--gamma", "0.7168", "--cubic", "1,2,3",
                          "--target-friction", "5")[::2], "--cubic must be 4 numbers")
    _one_line_error(*_run(capsys, "invert", "--gamma", "0.7168", "--target-friction", "5")[::2],
                    "exactly one of --cubic")
    _one_line_error(*_run(capsys, "invert", "--gamma", "0.7168", CUBIC, "--target-friction",
                          "54.4", "--range", "0.6,0.2")[::2], "p_min < p_max")
    _one_line_error(*_run(capsys, "invert", "--gamma", "0.7168", CUBIC, "--target-friction",
                          "54.4", "--range", "0.2,0.9")[::2], "not monotonic")
    _one_line_error(*_run(capsys, "invert", "--gamma", "0", CUBIC, "--target-friction",
                          "54.4")[::2], "gamma")
    _one_line_error(*_run(capsys, "invert", "--gamma", "0.7", CUBIC, "--target-friction",
                          "x")[::2])


def test_rig_then_fit_round_trip(cli, tmp_path: Path, squeeze_json: Path) -> None:  # type: ignore[no-untyped-def]
    out = tmp_path / "f.csv"
    r = cli(["rig", "--squeeze", str(squeeze_json), "--gamma-true", "0.7168", "--noise-pct", "2",
             "--seed", "1", "--out", str(out), "--json"])
    assert r.code == 0, r.err
    assert r.json()["synthetic"] is True and out.read_text().startswith("# SYNTHETIC")
    png = tmp_path / "fit.png"
    r2 = cli(["fit-friction", "--squeeze", str(squeeze_json), "--friction", str(out),
              "--plot", str(png), "--json"])
    assert r2.code == 0, r2.err
    d = r2.json()
    assert abs(d["gamma"] / 0.7168 - 1) < 0.005
    assert d["gamma_ci95"][0] <= 0.7168 <= d["gamma_ci95"][1]
    assert d["n_points"] == 17 and d["synthetic"] is True and "f0_n" not in d
    assert isinstance(d["relative_error_pct"], float)
    assert png.stat().st_size > 10_000


def test_fit_friction_affine_and_tests_column(capsys: pytest.CaptureFixture[str],
                                              tmp_path: Path, squeeze_csv: Path) -> None:
    out = tmp_path / "f.csv"
    code, _, err = _run(capsys, "rig", "--squeeze", str(squeeze_csv), "--gamma-true", "0.7",
                        "--drag-n", "6", "--repeats", "3", "--seed", "2", "--out", str(out))
    assert code == 0, err
    assert out.read_text().splitlines()[3] == "test,pressure_mpa,friction_n"
    code, o, err = _run(capsys, "fit-friction", "--squeeze", str(squeeze_csv), "--friction",
                        str(out), "--model", "affine", "--ci", "bootstrap", "--json")
    d = json.loads(o)
    assert code == 0 and d["n_tests"] == 3 and d["n_points"] == 51
    assert d["f0_n"] == pytest.approx(6.0, abs=0.5)
    assert d["f0_ci95_n"][0] <= 6.0 <= d["f0_ci95_n"][1]
    code, o, _ = _run(capsys, "fit-friction", "--squeeze", str(squeeze_csv), "--friction",
                      str(out))
    assert code == 0 and "gamma" in o


@pytest.mark.parametrize(
    ("content", "needle"),
    [
        ("pressure_mpa,force_n\n0.2,1\n0.3,2\n", "missing column 'friction_n'"),
        ("pressure_mpa,friction_n\n0.2,1\n0.3,abc\n", "data row 2, column 'friction_n'"),
        ("pressure_mpa,friction_n\n0.2,1\n0.3,-2\n", "must be >= 0"),
        ("pressure_mm,friction_n\n0.2,1\n0.3,2\n", "not convertible to MPa"),
        ("pressure_mpa,friction_n\n0.2,1\n", "at least 2 data rows"),
        ("", "no header row"),
    ],
)
def test_bad_friction_csv(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                          squeeze_csv: Path, content: str, needle: str) -> None:
    bad = tmp_path / "bad.csv"
    bad.write_text(content)
    code, out, err = _run(capsys, "fit-friction", "--squeeze", str(squeeze_csv), "--friction",
                          str(bad), "--json")
    _one_line_error(code, err, needle)
    assert out == ""


def test_kpa_friction_table_is_converted(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                         squeeze_csv: Path) -> None:
    """A pressure column in kPa is read as such (issue 31): the same gamma as the MPa table
    (1 kPa = 1e-3 MPa, the SI definition), to round-off."""
    kpa, mpa = tmp_path / "kpa.csv", tmp_path / "mpa.csv"
    kpa.write_text("pressure_kpa,friction_n\n300,40\n400,80\n500,130\n")
    mpa.write_text("pressure_mpa,friction_n\n0.3,40\n0.4,80\n0.5,130\n")
    got = []
    for f in (kpa, mpa):
        code, out, _ = _run(capsys, "fit-friction", "--squeeze", str(squeeze_csv), "--friction",
                            str(f), "--json")
        assert code == 0
        got.append(json.loads(out)["gamma"])
    assert got[0] == pytest.approx(got[1], rel=1e-12)


def test_replicate_csv_fits_with_its_replicates(capsys: pytest.CaptureFixture[str],
                                                tmp_path: Path, squeeze_csv: Path) -> None:
    """Five pulls per pressure (issue 14): no 'duplicate pressure' error; the CI clusters the
    replicates and the lack-of-fit ANOVA uses them (pure error on n - G dof)."""
    ps, ns = np.loadtxt(squeeze_csv, delimiter=",", skiprows=1, unpack=True)
    rng = np.random.default_rng(3)
    p = np.repeat([0.3, 0.4, 0.5, 0.6], 5)
    f = 0.7 * np.interp(p, ps, ns) * (1 + 0.02 * rng.standard_normal(p.size))
    rep = tmp_path / "replicates.csv"
    rows = "".join(f"{a},{b:.4f}\n" for a, b in zip(p, f, strict=True))
    rep.write_text("pressure_mpa,friction_n\n" + rows)
    code, out, err = _run(capsys, "fit-friction", "--squeeze", str(squeeze_csv), "--friction",
                          str(rep), "--json")
    assert code == 0, err
    d = json.loads(out)
    assert d["n_points"] == 20 and d["n_clusters"] == 4 and d["ci_method"] == "cluster"
    assert d["lack_of_fit"]["df_pure_error"] == 16 and d["lack_of_fit"]["df_lack_of_fit"] == 3
    assert abs(d["gamma"] / 0.7 - 1) < 0.02


@pytest.mark.parametrize(
    ("name", "content", "needle"),
    [
        ("s.json", '{"pressure_mpa": [0.2, 0.3]}', "missing key 'squeeze_force_n'"),
        ("s.json", "{not json", "not valid JSON"),
        ("s.json", '{"pressure_mpa": [0.2, 0.3], "squeeze_force_n": [1]}', "equal length"),
        ("s.json", '{"pressure_mpa": [0.2, 0.2], "squeeze_force_n": [1, 2]}', "duplicate"),
        ("s.json", '[1, 2]', "JSON object"),
        ("s.csv", "pressure_mpa,squeeze_n\n0.2,1\n0.3,2\n", "missing column 'squeeze_force_n'"),
    ],
)
def test_bad_squeeze_file(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                          name: str, content: str, needle: str) -> None:
    bad = tmp_path / name
    bad.write_text(content)
    fr = tmp_path / "f.csv"
    fr.write_text("pressure_mpa,friction_n\n0.3,20\n0.4,40\n")
    _one_line_error(*_run(capsys, "fit-friction", "--squeeze", str(bad), "--friction",
                          str(fr))[::2], needle)


def test_bad_options(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                     squeeze_csv: Path) -> None:
    fr = tmp_path / "f.csv"
    fr.write_text("pressure_mpa,friction_n\n0.3,20\n0.4,40\n")
    base = ["fit-friction", "--squeeze", str(squeeze_csv), "--friction", str(fr)]
    _one_line_error(*_run(capsys, *base, "--model", "quadratic")[::2], "--model must be one of")
    _one_line_error(*_run(capsys, *base, "--ci", "jackknife")[::2], "--ci must be one of")
    _one_line_error(*_run(capsys, "fit-friction", "--squeeze", str(tmp_path / "no.csv"),
                          "--friction", str(fr))[::2], "file not found")
    _one_line_error(*_run(capsys, "rig", "--squeeze", str(squeeze_csv), "--gamma-true", "0.7",
                          "--noise-pct", "-1", "--out", str(tmp_path / "o.csv"))[::2],
                    "--noise-pct")
    _one_line_error(*_run(capsys, "rig", "--squeeze", str(squeeze_csv), "--gamma-true", "0.7",
                          "--pressures", "0.1,0.3", "--out", str(tmp_path / "o.csv"))[::2],
                    "outside the squeeze curve")
    _one_line_error(*_run(capsys, "rig", "--squeeze", str(squeeze_csv), "--gamma-true",
                          "0.7")[::2], "--out")


def test_predict_error_handling(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    # All of these fail before any FE run.
    _one_line_error(*_run(capsys, "predict", "--gamma", "0.7168")[::2], "exactly one of")
    _one_line_error(*_run(capsys, "predict", "--gamma", "0.7168", "--paper", "--structures",
                          "x.toml")[::2], "exactly one of")
    _one_line_error(*_run(capsys, "predict", "--gamma", "0.7168", "--structures",
                          str(tmp_path / "none.toml"))[::2], "file not found")
    bad = tmp_path / "bad.toml"
    bad.write_text("[[structure]\nhole_mm = 10\n")
    _one_line_error(*_run(capsys, "predict", "--gamma", "0.7168", "--structures",
                          str(bad))[::2], "not valid TOML")
    bad.write_text("[[structure]]\nhole_mm = 10\ntube_od_mm = 8.3\n")
    _one_line_error(*_run(capsys, "predict", "--gamma", "0.7168", "--structures",
                          str(bad))[::2], "missing 'wire_mm'")
    meas = tmp_path / "m.csv"
    meas.write_text("test,pressure_mpa,friction_n\n9,0.2,10\n9,0.3,20\n")
    _one_line_error(*_run(capsys, "predict", "--gamma", "0.7168", "--paper", "--measured",
                          str(meas))[::2], "test '9' matches no structure")
    _one_line_error(*_run(capsys, "predict", "--gamma", "-1", "--paper")[::2], "gamma")
    _one_line_error(*_run(capsys, "predict", "--gamma", "0.7168", "--paper", "--pressures",
                          "0.3,0.2")[::2], "strictly increasing")
    _one_line_error(*_run(capsys, "predict", "--gamma", "0.7168",
                          "--structures", str(EXAMPLES / "structures-paper.toml"),
                          "--measured", str(meas))[::2], "matches no structure")


def test_invert_at_the_papers_inputs_prints_the_papers_pressure(capsys) -> None:
    """Sec 5's 0.26 MPa beside our root of Eq 9 (issue 20; docs/paper-notes.md F1)."""
    code, out, err = _run(capsys, "invert", "--gamma", "0.7168", "--cubic",
                          "-1957.4,2412.8,-251.95,-7.9531", "--target-friction", "54.4", "--json")
    assert code == 0, err
    d = json.loads(out)
    assert d["paper_pressure_mpa"] == 0.26 and abs(d["pressure_mpa"] - 0.2926) < 1e-3


def _slice_stand_in(st, mat, p, **kw):  # type: ignore[no-untyped-def]
    """A closed-form squeeze of one section (N/mm), similar in G like the FE's, for the CLI's
    plumbing: the numbers of the tolerance study are checked in tests/test_tolerance.py."""
    from types import SimpleNamespace

    g = mat.shear_modulus
    n = g * st.wire_mm * (np.asarray(p, float) / g) ** 2 * st.wall_mm / (1 + st.clearance_mm)
    return SimpleNamespace(squeeze_force_n_per_mm=n, squeeze_force_n=st.length_mm * n)


ONE = ["predict", "--gamma", "0.7168", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97",
       "--wire", "1.6"]


def test_predict_one_structure_with_clearance_scatter_and_tolerances(capsys, monkeypatch
                                                                     ) -> None:
    """predict with a clearance sd and tolerances (issue 19): per structure friction_n and its
    5/50/95 % bands, p05 <= p50 <= p95, the nominal inside the band, how they were computed;
    the clearance's truncation warning once (issue 34); a repeated --tolerance, an unknown
    name and a negative sd are one-line errors (issue 38)."""
    monkeypatch.setattr("exofric.simulate._clearance.squeeze", _slice_stand_in)
    code, out, err = _run(capsys, *ONE, "--pressures", "0.5,0.6", "--clearance-sd", "0.1",
                          "--tolerance", "tube_id=0.05", "--tolerance", "shore=2",
                          "--samples", "16", "--json")
    assert code == 0, err
    d = json.loads(out)
    s = d["structures"][0]
    for k in ("friction_n", "friction_n_p05", "friction_n_p50", "friction_n_p95",
              "squeeze_force_n_p50"):
        assert len(s[k]) == 2
    assert s["friction_n_p05"][-1] <= s["friction_n_p50"][-1] <= s["friction_n_p95"][-1]
    assert s["friction_n_p05"][-1] <= s["friction_n"][-1] <= s["friction_n_p95"][-1]
    assert s["tolerance_method"]["method"] == "grid" and s["tolerance_method"]["solves"] == 4
    trunc = [w for w in d["warnings"] if "below 0.001 mm" in w]
    assert len(trunc) == 1 and err.count("below 0.001 mm") == 1, err
    twice = _run(capsys, *ONE, "--tolerance", "shore=2", "--tolerance", "shore=3")
    _one_line_error(twice[0], twice[2], "--tolerance", "shore is given twice (2 and 3)")
    _one_line_error(*_run(capsys, *ONE, "--tolerance", "colour=1")[::2], "tolerance")
    _one_line_error(*_run(capsys, *ONE, "--clearance-sd", "-0.1")[::2], "clearance")


def test_predict_with_a_measured_clearance_profile(capsys, monkeypatch, tmp_path: Path
                                                   ) -> None:
    """--clearance-profile: a CSV position_mm,clearance_mm over the tube; a profile that does
    not cover the length, or clearances impossible in the 10 mm hole (50 mm; issue 38), are
    refused with one line; an implausible one (2 mm against the base's 0.1 mm) warns, also in
    --json; so does a clearance sd that puts impossible clearances in the hole."""
    monkeypatch.setattr("exofric.simulate._clearance.squeeze", _slice_stand_in)
    prof = tmp_path / "prof.csv"
    prof.write_text("position_mm,clearance_mm\n0,0.1\n58,0.3\n116,0.1\n")
    code, out, err = _run(capsys, *ONE, "--pressures", "0.6", "--clearance-profile", str(prof),
                          "--json")
    assert code == 0, err
    assert json.loads(out)["clearance"] == {"profile": str(prof)}
    short = tmp_path / "short.csv"
    short.write_text("position_mm,clearance_mm\n0,0.1\n50,0.3\n")
    _one_line_error(*_run(capsys, *ONE, "--clearance-profile", str(short))[::2],
                    "not the tube's 0-116 mm")
    huge = tmp_path / "huge.csv"
    huge.write_text("position_mm,clearance_mm\n0,50\n116,50\n")
    _one_line_error(*_run(capsys, *ONE, "--clearance-profile", str(huge))[::2],
                    "100 % of the length has a clearance >= 3.43 mm", "10 mm hole")
    _one_line_error(*_run(capsys, *ONE, "--clearance-sd", "50")[::2], "3.43 mm")
    odd = tmp_path / "odd.csv"
    odd.write_text("position_mm,clearance_mm\n0,2\n116,2\n")
    code, out, err = _run(capsys, *ONE, "--pressures", "0.6", "--clearance-profile", str(odd),
                          "--json")
    assert code == 0, err
    assert any("clearance above 0.932 mm" in w for w in json.loads(out)["warnings"])
