"""Material calibration from inflation tests (issue 5; paper §3.3, Table 1, Fig 5).

References used here: the paper's printed Table 1 errors and bisection order, the
printed Table 2 constants, planted truths, scipy's brentq, a dense grid search and
statsmodels OLS (for the least-squares standard errors).
"""

from __future__ import annotations

import numpy as np
import pytest
import statsmodels.api as sm
from scipy.optimize import brentq

from exofric import paper
from exofric.calibration import (
    CachedModel,
    InflationData,
    calibrate,
    make_model,
    material_for,
    paper_table1_model,
)
from exofric.cli import run
from exofric.errors import InputError
from exofric.io import read_inflation_table

TEST = InflationData.paper_test()
SIM = InflationData.paper_simulated()
# Tube ID (mm) used as the fixed input of the Table 1 test-data fits below: what the
# known-hardness fit returns on the paper's columns with the FE model and Eq 4 constants
# (a regression pin of that fit is in tests/test_regression_calibrate.py).
ID_EQ4 = 4.9666


@pytest.fixture(scope="module")
def fe() -> CachedModel:
    """One memoised FE model shared by the tests of this module (8.3 mm tube, Eq 4)."""
    return make_model("fe", 8.3)


# ---------------------------------------------------------------- the paper's own bisection
def test_bisection_replays_paper_sequence_with_paper_columns() -> None:
    r = calibrate(TEST, 8.3, tube_id_mm=5.0, model="paper-table1")
    t1 = paper.table1()
    assert [t.shore for t in r.history] == t1["bisection_order"]  # 60, 65, 70, 62.5
    # Printed errors are 2-decimal roundings computed from unrounded ANSYS diameters; from
    # the printed (rounded, 0.01 mm) columns they come out within 0.02 %-points (the issue's
    # tolerance): 1.453/0.878/2.485/0.456 vs 1.47/0.87/2.47/0.46.
    got = [t.average_error_pct for t in r.history]
    assert got == pytest.approx(t1["average_error_pct"], abs=0.02)
    assert r.shore == 62.5 and r.converged
    assert r.average_error_pct < t1["stop_tolerance_pct"]
    assert r.n_model_calls == 4


def test_average_error_is_relative_to_tested_diameter() -> None:
    # Hand arithmetic for the 62.5 Hs column: |0|/8.53, 0.01/8.78, 0.04/9.14, 0.12/9.44.
    hand = 100 * np.mean([0, 0.01 / 8.78, 0.04 / 9.14, 0.12 / 9.44])
    r = calibrate(TEST, 8.3, tube_id_mm=5.0, model="paper-table1", bracket=(62.5, 62.6),
                  tol_pct=5.0)
    assert r.history[0].average_error_pct == pytest.approx(hand, rel=1e-12)


def test_bounded_matches_dense_grid_on_paper_columns() -> None:
    # Independent reference: brute-force grid (0.001 Shore) of the same objective.
    r = calibrate(TEST, 8.3, tube_id_mm=5.0, model="paper-table1", method="bounded",
                  xtol=1e-4)
    m = paper_table1_model()
    grid = np.arange(60.0, 70.0, 0.001)
    err = [np.mean(np.abs(m(s, 5.0, TEST.pressure_mpa) / TEST.outer_diameter_mm - 1)) * 100
           for s in grid]
    assert r.average_error_pct == pytest.approx(min(err), abs=1e-4)
    assert r.shore == pytest.approx(grid[int(np.argmin(err))], abs=0.01)


# ----------------------------------------------------------------------- models and caching
def test_paper_slip_convention_matches_printed_table2() -> None:
    m = material_for(62.5, c10_convention="paper-slip")
    t2 = paper.table2()
    # printed to 4 significant digits; d printed 0.00575 vs 0.004/0.6971 = 0.005738 (0.2%)
    assert m.c10_mpa == pytest.approx(t2["c10_mpa"], abs=5e-5)
    assert m.c01_mpa == pytest.approx(t2["c01_mpa"], abs=5e-5)
    assert m.d_per_mpa == pytest.approx(t2["d_per_mpa"], rel=3e-3)
    e = material_for(62.5)
    assert m.shear_modulus / e.shear_modulus == pytest.approx(1.05 / 1.005, rel=1e-12)
    with pytest.raises(InputError, match="c10_convention"):
        material_for(62.5, c10_convention="x")  # type: ignore[arg-type]


def test_cached_model_memoises_and_1d_factory_matches_reference() -> None:
    from exofric.simulate import compressible_inflation

    m = make_model("1d", 8.3)
    p = np.array([0.1, 0.3])
    a = m(62.5, 5.0, p)
    b = m(62.5, 5.0, p)
    assert (m.calls, m.hits) == (1, 1)
    # wiring, not accuracy: the "1d" factory is compressible_inflation (that solver is checked
    # against the closed form and the FE in tests/test_fe_inflate.py)
    ref = compressible_inflation(8.3, 5.0, material_for(62.5), p).outer_diameter_mm
    np.testing.assert_array_equal(a, ref)
    np.testing.assert_array_equal(a, b)
    b[0] = 0.0  # callers get copies: the cache cannot be corrupted
    assert m(62.5, 5.0, p)[0] == ref[0]
    with pytest.raises(InputError, match="model must be one of"):
        make_model("ansys")


# ---------------------------------------------------- known hardness: the paper's ANSYS tube ID
@pytest.mark.parametrize("convention", ["eq4", "paper-slip"])
def test_known_hardness_reproduces_paper_columns(convention, paper_columns_fits) -> None:
    # The fitted IDs and errors themselves are regression pins (test_regression_calibrate.py).
    r = paper_columns_fits[convention]
    assert r.method == "known-hardness" and r.shore is None and r.converged
    # acceptance: with the fitted ID the FE reproduces every printed ANSYS value within 0.5%
    assert np.all(np.abs(r.residuals_pct) < 0.5)
    assert np.asarray(r.residuals_pct).size == 16          # 4 columns x 4 pressures
    assert r.tube_id_stderr_mm is not None and 0 < r.tube_id_stderr_mm < 0.05
    assert r.correlation is None


# ------------------------------------------------------------- Table 1 test data, ID fixed
def test_bisection_on_test_data_is_root_of_signed_error(fe) -> None:
    r = calibrate(TEST, 8.3, tube_id_mm=ID_EQ4, model=fe)
    assert [t.shore for t in r.history[:4]] == [60.0, 65.0, 70.0, 62.5]
    # Our model cannot reach the 0.5% criterion with this ID (the paper's columns differ
    # from ours by up to 0.42%), so the bisection runs until the bracket closes (0.01).
    assert not r.converged and "never fell below" in r.notes[0]

    # Independent reference: brentq on the mean signed error, to 1e-6 Shore.
    def signed(s: float) -> float:
        return float(np.mean(fe(s, ID_EQ4, TEST.pressure_mpa) / TEST.outer_diameter_mm - 1))

    root = brentq(signed, 60.0, 65.0, xtol=1e-6)
    assert r.shore == pytest.approx(root, abs=0.01)
    assert abs(r.shore - 62.5) < 0.2  # the paper's 62.5, see the notes file


def test_bounded_on_test_data(fe) -> None:
    r = calibrate(TEST, 8.3, tube_id_mm=ID_EQ4, model=fe, method="bounded")
    # Minimum of the average error: reference = a 0.1-Shore grid around it (its curvature
    # is small, so the minimum value must agree to 0.002 %-points).
    grid = np.arange(63.5, 64.51, 0.1)
    err = [100 * np.mean(np.abs(fe(s, ID_EQ4, TEST.pressure_mpa) / TEST.outer_diameter_mm - 1))
           for s in grid]
    assert r.average_error_pct == pytest.approx(min(err), abs=0.002)
    assert 63.5 < r.shore < 64.5


def test_joint_on_test_data_reports_both_with_stderrs(fe) -> None:
    r = calibrate(TEST, 8.3, tube_id_mm=ID_EQ4, model=fe, method="joint")
    assert r.shore_stderr is not None and r.tube_id_stderr_mm is not None
    assert np.isfinite(r.shore_stderr) and np.isfinite(r.tube_id_stderr_mm)
    assert r.correlation is not None and abs(r.correlation) > 0.99
    assert any("cannot separate hardness and wall thickness" in n for n in r.notes)
    d = r.to_dict()
    for key in ("shore", "tube_id_mm", "shore_stderr", "tube_id_stderr_mm", "correlation"):
        assert isinstance(d[key], float)


# -------------------------------------------------------------------------- planted truth
def test_joint_recovers_planted_truth_noise_free(fe) -> None:
    p = np.linspace(0.04, 0.4, 10)
    data = InflationData(p, fe(57.0, 5.3, p))
    r = calibrate(data, 8.3, method="joint", model=fe)
    assert r.shore == pytest.approx(57.0, abs=0.05)  # issue tolerances
    assert r.tube_id_mm == pytest.approx(5.3, abs=0.005)
    assert r.correlation > 0.99
    assert any("nearly interchangeable" in n for n in r.notes)


def test_least_squares_stderrs_match_statsmodels_on_linear_model() -> None:
    # A model linear in (shore, ID): relative residuals are then exactly linear and the
    # Gauss-Newton covariance equals OLS's; statsmodels is the independent reference.
    p = np.linspace(0.05, 0.5, 8)

    def lin(shore: float, tid: float, pr: np.ndarray) -> np.ndarray:
        return 8.3 + 0.05 * shore * pr - 0.3 * tid * pr**2

    rng = np.random.default_rng(7)
    meas = lin(50.0, 4.0, p) * (1 + 1e-3 * rng.standard_normal(p.size))
    r = calibrate(InflationData(p, meas), 8.3, method="joint", model=lin, tube_id_mm=4.5)
    X = np.column_stack([0.05 * p / meas, -0.3 * p**2 / meas])
    y = 1 - 8.3 / meas
    ols = sm.OLS(y, X).fit()
    np.testing.assert_allclose([r.shore, r.tube_id_mm], ols.params, rtol=1e-6)
    np.testing.assert_allclose([r.shore_stderr, r.tube_id_stderr_mm], ols.bse, rtol=1e-5)
    cov = ols.cov_params()
    assert r.correlation == pytest.approx(cov[0, 1] / np.sqrt(cov[0, 0] * cov[1, 1]), rel=1e-6)


# ---------------------------------------------------------------------- input validation
BAD_CSVS = {
    "missing": ("pressure_mpa,diameter_mm\n0.1,8.5\n0.2,8.7\n", "missing column"),
    "non-numeric": ("pressure_mpa,outer_diameter_mm\n0.1,8.5\n0.2,abc\n",
                    "data row 2, column 'outer_diameter_mm' is not a number"),
    "negative": ("pressure_mpa,outer_diameter_mm\n-0.1,8.5\n0.2,8.7\n", "must be >= 0"),
    "nan": ("pressure_mpa,outer_diameter_mm\n0.1,nan\n0.2,8.7\n", "is NaN"),
    "duplicate": ("pressure_mpa,outer_diameter_mm\n0.1,8.5\n0.1,8.7\n",
                  "duplicate pressure_mpa 0.1"),
    "duplicate-shore": ("pressure_mpa,outer_diameter_mm,shore\n0.1,8.5,60\n0.2,8.7,60\n"
                        "0.1,8.4,65\n0.1,8.6,65\n", "duplicate pressure_mpa 0.1 in shore 65"),
    "one-point": ("pressure_mpa,outer_diameter_mm\n0.1,8.5\n", "at least 2 data rows"),
    "one-point-shore": ("pressure_mpa,outer_diameter_mm,shore\n0.1,8.5,60\n0.2,8.7,60\n"
                        "0.1,8.4,65\n", "at least 2 data rows in shore 65"),
    "wrong-unit": ("pressure_mm,outer_diameter_mm\n100,8.5\n200,8.7\n", "not convertible to MPa"),
    "zero-diameter": ("pressure_mpa,outer_diameter_mm\n0.1,0\n0.2,8.7\n", "must be > 0 mm"),
}


@pytest.mark.parametrize("kind", sorted(BAD_CSVS))
def test_bad_csv_one_line_error_and_exit_2(kind, tmp_path, capsys) -> None:
    text, msg = BAD_CSVS[kind]
    f = tmp_path / f"{kind}.csv"
    f.write_text(text)
    with pytest.raises(InputError, match=msg):
        InflationData.from_frame(read_inflation_table(f))
    code = run(["calibrate", "--data", str(f), "--tube-od", "8.3", "--tube-id", "5", "--json"])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and msg in err


def test_csv_columns_any_order_comments_extra(tmp_path) -> None:
    f = tmp_path / "ok.csv"
    f.write_text("# rig 3\nnote,outer_diameter_mm,pressure_mpa\nx,8.78,0.2\ny,8.53,0.1\n")
    d = InflationData.from_frame(read_inflation_table(f))
    assert d.pressure_mpa.tolist() == [0.1, 0.2] and d.outer_diameter_mm.tolist() == [8.53, 8.78]


@pytest.mark.parametrize(
    ("args", "msg"),
    [
        (["--method", "bisection"], "needs --tube-id"),
        (["--tube-id", "5", "--method", "bounded", "--fit-tube-id"], "needs method 'joint'"),
        (["--tube-id", "9", "--method", "bisection"], "--tube-id must be < --tube-od"),
        (["--tube-id", "5", "--bracket", "70,60"], "lo < hi"),
        (["--tube-id", "5", "--bracket", "60"], "two Shore A values"),
        (["--tube-id", "5", "--method", "newton"], "method must be one of"),
        (["--tube-id", "5", "--model", "ansys"], "model must be one of"),
        (["--tube-id", "5", "--tol-pct", "0"], "--tol-pct must be > 0"),
    ],
)
def test_bad_options_exit_2(args, msg, capsys) -> None:
    code = run(["calibrate", "--data", str(paper.data_path("table1_test.csv")),
                "--tube-od", "8.3", *args])
    out, err = capsys.readouterr()
    assert code == 2 and msg in err and len(err.strip().splitlines()) == 1


def test_shore_column_forbids_other_methods() -> None:
    with pytest.raises(InputError, match="known-hardness"):
        calibrate(SIM, 8.3, method="joint", model="paper-table1")


def test_bracket_without_sign_change_is_an_input_error() -> None:
    # the paper's columns: every trial in [65, 70] is stiffer than the test (all below it)
    with pytest.raises(InputError, match="does not contain the hardness"):
        calibrate(TEST, 8.3, tube_id_mm=5.0, model="paper-table1", bracket=(65, 70))


# ----------------------------------------------------------------------------- CLI and plot
def test_cli_json_and_plot(cli, tmp_path) -> None:
    png = tmp_path / "fig5b.png"
    res = cli(["calibrate", "--data", str(paper.data_path("table1_test.csv")), "--tube-od",
               "8.3", "--tube-id", "4.97", "--model", "paper-table1", "--plot", str(png),
               "--json"])
    assert res.code == 0, res.err
    d = res.json()
    assert d["method"] == "bisection" and d["shore"] == 62.5
    # hand arithmetic for the 62.5 Hs column (as in test_average_error_is_relative_...)
    hand = 100 * np.mean([0, 0.01 / 8.78, 0.04 / 9.14, 0.12 / 9.44])     # 0.4557 %
    assert d["average_error_pct"] == pytest.approx(hand, rel=1e-9)
    assert d["max_error_pct"] == pytest.approx(100 * 0.12 / 9.44, rel=1e-9)
    assert [h["shore"] for h in d["history"]] == [60.0, 65.0, 70.0, 62.5]
    assert set(d["history"][0]) >= {"shore", "tube_id_mm", "average_error_pct"}
    assert "shore_stderr" not in d  # joint only
    assert png.stat().st_size > 10_000 and d["plot_path"] == str(png)


def test_cli_joint_fe(cli) -> None:
    res = cli(["calibrate", "--data", str(paper.data_path("table1_test.csv")), "--tube-od",
               "8.3", "--fit-tube-id", "--json"])
    assert res.code == 0, res.err
    d = res.json()
    assert d["method"] == "joint" and d["model"] == "fe"
    assert {"shore_stderr", "tube_id_stderr_mm", "correlation"} <= set(d)
    assert any("cannot separate" in n for n in d["notes"])


def test_failed_trials_count_as_too_soft_and_total_failure_is_reraised() -> None:
    # Toy model with a closed-form answer: D = 8.3 (1 + P (100 - S)/100); it "fails" (like
    # a tube above its limit pressure) for S < 40. Truth S = 55 at ID-independent data.
    def toy(shore: float, tid: float, p: np.ndarray) -> np.ndarray:
        if shore < 40:
            raise InputError("pressure above the tube's limit pressure")
        return 8.3 * (1 + p * (100 - shore) / 100)

    p = np.array([0.1, 0.2, 0.4])
    data = InflationData(p, toy(55.0, 5.0, p))
    r = calibrate(data, 8.3, tube_id_mm=5.0, model=toy, bracket=(20, 70), tol_pct=1e-3)
    assert r.history[0].shore == 20 and r.history[0].note.startswith("model failed")
    assert r.to_dict()["history"][0]["average_error_pct"] is None  # inf -> JSON null
    assert r.shore == pytest.approx(55.0, abs=0.01) and r.converged
    # every trial fails (pressures outside the paper's 0.1-0.4 MPa columns): re-raised
    far = InflationData(np.array([0.5, 0.6]), np.array([9.8, 10.0]))
    with pytest.raises(InputError, match="pressures must be in"):
        calibrate(far, 8.3, tube_id_mm=5.0, model="paper-table1")


def test_calibrate_accepts_a_mapping_and_refuses_other_types() -> None:
    """calibrate({...}) used to raise AttributeError (issue 20): a mapping of lists is the data;
    anything else is one InputError naming `data`."""
    from exofric.calibration import InflationData, calibrate
    from exofric.errors import InputError

    d = InflationData.paper_test()
    as_map = {"pressure_mpa": list(d.pressure_mpa), "outer_diameter_mm": list(d.outer_diameter_mm)}
    a = calibrate(as_map, 8.3, tube_id_mm=4.97, model="paper-table1")
    b = calibrate(d, 8.3, tube_id_mm=4.97, model="paper-table1")
    assert a.shore == b.shore
    with pytest.raises(InputError, match="data must be InflationData"):
        calibrate([1, 2, 3], 8.3, tube_id_mm=4.97)  # type: ignore[arg-type]
    with pytest.raises(InputError, match="outer_diameter_mm"):
        calibrate({"pressure_mpa": [0.1, 0.2]}, 8.3, tube_id_mm=4.97)
