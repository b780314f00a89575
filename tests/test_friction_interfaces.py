"""Interface-resolved friction (issue 15): F = mu_tube S_wire + mu_wall N_wall (+ F0).

References are independent of the code under test: statsmodels OLS on the same design matrix
(coefficients, classical / HC3 / cluster standard errors and t intervals), the closed forms of
two-column collinearity (condition number sqrt((1 + c)/(1 - c)), estimate correlation -c), and
planted truths on the virtual rig. FE-backed recovery runs on coarse meshes.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import statsmodels.api as sm

from exofric.cli import run
from exofric.errors import InputError, PlausibilityWarning
from exofric.friction import (
    IdentifiabilityWarning,
    InterfaceCurves,
    InterfaceFrictionModel,
    InterfaceTest,
    fit_interfaces,
    paper_structures,
    predict,
    simulate_interface_rig,
)
from exofric.friction import _fit as fit_module
from exofric.friction._interfaces import KAPPA_MAX

P = np.round(np.linspace(0.2, 0.6, 9), 6)


def _curves(name: str, r0: float, r1: float, scale: float = 1.0) -> InterfaceCurves:
    """Analytic FE stand-in: N = scale 600 P^2, S = r(P) N with the wrap ratio r linear in P."""
    n = scale * 600.0 * P**2
    r = r0 + (r1 - r0) * (P - P[0]) / (P[-1] - P[0])
    return InterfaceCurves(P, r * n, n, name)


THREE = (("a", 1.04, 1.10, 1.0), ("b", 1.25, 1.35, 0.7), ("c", 1.55, 1.70, 1.3))


def _noisy_tests(mu_t: float, mu_w: float, seed: int, reps: int = 1, rel: float = 0.02,
                 specs=THREE, f0: float = 0.0) -> list[InterfaceTest]:
    rng = np.random.default_rng(seed)
    out = []
    for spec in specs:
        c = _curves(*spec)
        p = np.repeat(P, reps)
        s, n, _ = c.at(p)
        f = mu_t * s + mu_w * n + f0
        out.append(InterfaceTest(c, p, f * (1 + rel * rng.standard_normal(p.size))))
    return out


def _design(tests: list[InterfaceTest], affine: bool = False):
    xs, ys, gs = [], [], []
    for i, t in enumerate(tests):
        s, n, _ = t.curves.at(t.pressure_mpa)
        cols = [s, n] + ([np.ones_like(s)] if affine else [])
        xs.append(np.column_stack(cols))
        ys.append(np.asarray(t.friction_n))
        gs += [f"{i}-{p}" for p in t.pressure_mpa]
    return np.vstack(xs), np.concatenate(ys), np.unique(gs, return_inverse=True)[1]


# -- the law and its inputs ------------------------------------------------------------------


def test_law_closed_form_and_equivalent_gamma() -> None:
    law = InterfaceFrictionModel(0.45, 0.18, f0_n=2.0)
    assert law.friction_n(120.0, 100.0) == pytest.approx(0.45 * 120 + 0.18 * 100 + 2.0)
    # gamma = mu_tube S/N + mu_wall: the paper's single coefficient this law implies
    assert law.equivalent_gamma(120.0, 100.0) == pytest.approx(0.45 * 1.2 + 0.18)
    assert law.to_dict() == {"law": "interfaces", "mu_tube": 0.45, "mu_wall": 0.18,
                             "f0_n": 2.0}


@pytest.mark.parametrize("field,kw", [
    ("mu_tube", {"mu_tube": -0.1, "mu_wall": 0.2}),
    ("mu_wall", {"mu_tube": 0.4, "mu_wall": float("nan")}),
    ("mu_tube", {"mu_tube": 2.5, "mu_wall": 0.2}),
    ("mu_wall", {"mu_tube": 0.4, "mu_wall": float("inf")}),
])
def test_bad_coefficients_are_one_line_errors_naming_the_field(field, kw) -> None:
    with pytest.raises(InputError) as exc:
        InterfaceFrictionModel(**kw)
    assert exc.value.param == field and str(exc.value).startswith(field)
    assert "\n" not in str(exc.value)


def test_coefficient_above_1_5_warns() -> None:
    with pytest.warns(PlausibilityWarning, match="mu_wall = 1.6 is above 1.5"):
        InterfaceFrictionModel(0.4, 1.6)


def test_from_squeeze_needs_the_wire_integral() -> None:
    d = {"pressure_mpa": [0.2, 0.6], "squeeze_force_n": [20.0, 240.0], "length_mm": 116.0}
    for value in (None, "absent"):
        dd = dict(d) if value == "absent" else {**d, "wire_pressure_integral_n_per_mm": value}
        with pytest.raises(InputError) as exc:
            InterfaceCurves.from_squeeze(dd)
        msg = str(exc.value)
        assert "wire_pressure_integral_n_per_mm" in msg and "exofric squeeze" in msg
        assert "--json" in msg and "\n" not in msg
    ok = InterfaceCurves.from_squeeze({**d, "wire_pressure_integral_n_per_mm": [0.2, 2.2]})
    assert ok.wire_pressure_integral_n == pytest.approx((0.2 * 116, 2.2 * 116))


def test_wire_integral_below_the_resultant_warns() -> None:
    # |integral of p n| <= integral of p: S_wire >= N for any contact pressure distribution
    with pytest.warns(PlausibilityWarning, match="at least its resultant"):
        InterfaceCurves([0.2, 0.6], [10.0, 100.0], [20.0, 240.0])


# -- the fit against statsmodels --------------------------------------------------------------


@pytest.mark.parametrize("affine", [False, True])
def test_fit_matches_statsmodels_ols_and_hc3(affine: bool) -> None:
    tests = _noisy_tests(0.42, 0.21, seed=3, f0=3.0 if affine else 0.0)
    x, y, _ = _design(tests, affine)
    ols = sm.OLS(y, x).fit()
    fit = fit_interfaces(tests, model="affine" if affine else "proportional", ci="ols")
    est = [fit.mu_tube, fit.mu_wall] + ([fit.f0_n] if affine else [])
    assert est == pytest.approx(ols.params, rel=1e-9)
    assert [fit.mu_tube_se, fit.mu_wall_se] == pytest.approx(ols.bse[:2], rel=1e-9)
    ci = ols.conf_int(0.05)
    assert fit.mu_tube_ci == pytest.approx(tuple(ci[0]), rel=1e-9)
    assert fit.mu_wall_ci == pytest.approx(tuple(ci[1]), rel=1e-9)
    cov = ols.cov_params()
    assert fit.correlation == pytest.approx(cov[0, 1] / math.sqrt(cov[0, 0] * cov[1, 1]),
                                            rel=1e-9)
    # HC3 with a t interval on n - k dof (statsmodels with use_t=True)
    hc3 = sm.OLS(y, x).fit(cov_type="HC3", use_t=True)
    fa = fit_interfaces(tests, model="affine" if affine else "proportional", ci="analytic")
    assert [fa.mu_tube_se, fa.mu_wall_se] == pytest.approx(hc3.bse[:2], rel=1e-9)
    assert fa.mu_wall_ci == pytest.approx(tuple(hc3.conf_int(0.05)[1]), rel=1e-9)
    assert fa.ci_method == "analytic" and fa.identifiable


def test_cluster_interval_matches_statsmodels_cluster(monkeypatch) -> None:
    # replicate pulls: clusters are (structure, pressure); CR1 is statsmodels' "cluster"
    monkeypatch.setattr(fit_module, "_CLUSTER_VARIANT", "cr1")
    tests = _noisy_tests(0.42, 0.21, seed=5, reps=4)
    x, y, g = _design(tests)
    ref = sm.OLS(y, x).fit(cov_type="cluster", cov_kwds={"groups": g}, use_t=True)
    fit = fit_interfaces(tests)                      # auto -> cluster with replicates
    assert fit.ci_method == "cluster" and fit.n_clusters == 27
    assert [fit.mu_tube_se, fit.mu_wall_se] == pytest.approx(ref.bse, rel=1e-9)
    assert fit.mu_tube_ci == pytest.approx(tuple(ref.conf_int(0.05)[0]), rel=1e-9)
    assert fit.lack_of_fit is not None and fit.lack_of_fit.df_pure_error == 27 * 3


def test_default_cluster_interval_covers_the_truth() -> None:
    # the default CR2 / Bell-McCaffrey covariance on replicate data: coverage over 200 seeds
    hits = 0
    for seed in range(200):
        fit = fit_interfaces(_noisy_tests(0.42, 0.21, seed=seed, reps=3))
        hits += (fit.mu_tube_ci[0] <= 0.42 <= fit.mu_tube_ci[1]
                 and fit.mu_wall_ci[0] <= 0.21 <= fit.mu_wall_ci[1])
    assert hits >= 0.88 * 200       # joint coverage of two 95 % intervals is >= 90 %


# -- identifiability ---------------------------------------------------------------------------


def test_one_structure_is_flagged_not_identifiable() -> None:
    tests = _noisy_tests(0.42, 0.21, seed=1, specs=THREE[:1], rel=0.005)
    with pytest.warns(IdentifiabilityWarning, match="not separated"):
        fit = fit_interfaces(tests)
    assert not fit.identifiable and "condition number" in fit.identifiability_reason
    x, _, _ = _design(tests)
    # closed forms for two columns of cosine c: kappa = sqrt((1 + c)/(1 - c)) after scaling,
    # and the OLS estimates' correlation is -c
    c = x[:, 0] @ x[:, 1] / (np.linalg.norm(x[:, 0]) * np.linalg.norm(x[:, 1]))
    assert fit.condition_number == pytest.approx(math.sqrt((1 + c) / (1 - c)), rel=1e-6)
    assert fit.condition_number > KAPPA_MAX
    with pytest.warns(IdentifiabilityWarning):
        fo = fit_interfaces(tests, ci="ols")
    assert fo.correlation == pytest.approx(-c, abs=1e-9)
    d = fit.to_dict()
    assert d["identifiable"] is False and d["warnings"] and d["correlation"] < -0.99
    # gamma on the same points is well determined: the combination is what one structure gives
    assert fit.gamma_pooled == pytest.approx(np.mean(np.asarray(fit.friction_n)
                                                     / np.asarray(fit.squeeze_force_n)),
                                             rel=0.02)


def test_three_structures_are_identifiable_and_recover_the_truth() -> None:
    fit = fit_interfaces(_noisy_tests(0.42, 0.21, seed=2, rel=0.005))
    assert fit.identifiable and fit.condition_number < KAPPA_MAX and not fit.warnings
    assert fit.mu_tube == pytest.approx(0.42, rel=0.03)
    assert fit.mu_wall == pytest.approx(0.21, rel=0.06)
    # the pooled single gamma cannot follow three wrap ratios: its errors are larger
    assert fit.gamma_relative_error_pct > 3 * fit.relative_error_pct


def test_proportional_columns_are_an_error() -> None:
    c = InterfaceCurves(P, 1.1 * 600 * P**2, 600 * P**2, "flat")
    with pytest.raises(InputError, match="proportional"):
        fit_interfaces([InterfaceTest(c, P, 0.6 * 600 * P**2)])


def test_negative_fit_is_warned() -> None:
    # data that only a negative wall coefficient explains: F = 0.6 S - 0.05 N (> 0 as S > N)
    tests = []
    for spec in THREE:
        c = _curves(*spec)
        s_, n_, _ = c.at(P)
        tests.append(InterfaceTest(c, P, 0.6 * s_ - 0.05 * n_))
    with pytest.warns(IdentifiabilityWarning, match="mu_wall = -0.05 is negative"):
        fit = fit_interfaces(tests)
    assert fit.mu_wall == pytest.approx(-0.05, abs=1e-9)
    assert any("negative" in w for w in fit.to_dict()["warnings"])
    with pytest.raises(InputError, match="mu_wall must be >= 0"):
        _ = fit.model


def test_result_frame_and_dict() -> None:
    fit = fit_interfaces(_noisy_tests(0.42, 0.21, seed=4))
    df = fit.to_frame()
    assert len(df) == 27 and set(df["structure"]) == {"a", "b", "c"}
    d = fit.to_dict()
    for key in ("mu_tube", "mu_wall", "mu_tube_ci", "mu_wall_ci", "correlation",
                "identifiable", "warnings", "condition_number", "per_structure"):
        assert key in d
    json.dumps(d)


def test_frame_columns_carry_units_and_plot_draws_both_laws() -> None:
    import matplotlib
    from matplotlib.figure import Figure

    backend = matplotlib.get_backend()
    fit = fit_interfaces(_noisy_tests(0.42, 0.21, seed=4))
    df = fit.to_frame()
    numeric = [c for c in df.columns if df[c].dtype.kind == "f"]
    assert numeric and all(c.endswith(("_mpa", "_n", "_pct")) for c in numeric), numeric
    np.testing.assert_array_equal(df["friction_n"], fit.friction_n)
    fig = fit.plot(Figure(), title="SYNTHETIC")
    a1, a2 = fig.axes
    # per structure: points, interface law (solid), pooled gamma (dashed); two legend proxies
    assert len(a1.lines) == 3 * 3 + 2 and len(a2.lines) == 3 * 2 + 1
    assert "kappa" in a1.get_title() and matplotlib.get_backend() == backend


def test_virtual_rig_plants_the_law() -> None:
    c = _curves("a", 1.1, 1.2)
    r = simulate_interface_rig(c, 0.5, 0.2, seed=7, repeats=2)
    s, n, _ = c.at(P)
    assert r.run.true_friction_n[:9] == pytest.approx(0.5 * s + 0.2 * n, rel=1e-12)
    assert "mu_tube=0.5 mu_wall=0.2" in r.to_csv_text()
    assert r.to_dict()["mu_wall_true"] == 0.2


# -- predict with either law -------------------------------------------------------------------


def _fake_squeeze(ratio: float = 1.12):
    def fn(s, m, p):
        n = 500.0 * np.asarray(p) ** 2
        return SimpleNamespace(pressure_mpa=p, squeeze_force_n=n, length_mm=116.0,
                               wire_pressure_integral_n_per_mm=ratio * n / 116.0)
    return fn


def test_predict_interface_law_and_side_by_side_comparison() -> None:
    from exofric.friction import MeasuredCurve

    law = InterfaceFrictionModel(0.5, 0.15)
    structs = paper_structures()[:2]
    meas = {"test 1": MeasuredCurve.of([0.3, 0.6], [60.0, 125.0])}
    r = predict(structs, law, None, [0.3, 0.6], squeeze_fn=_fake_squeeze(), measured=meas,
                compare=0.7)
    pr = r.predictions[0]
    n = 500 * np.array([0.09, 0.36])
    assert pr.predicted_friction_n == pytest.approx(0.5 * 1.12 * n + 0.15 * n)
    d = r.to_dict()
    assert d["law"] == "interfaces" and d["gamma"] is None and d["mu_tube"] == 0.5
    entry = d["structures"][0]
    # every key of the gamma law's output is still there
    for key in ("name", "structure", "gamma", "f0_n", "pressure_mpa", "squeeze_force_n",
                "predicted_friction_n", "relative_error_pct", "max_relative_error_pct",
                "max_torque_nm"):
        assert key in entry
    comp = entry["law_comparison"]
    assert comp["gamma"]["predicted_friction_n"] == pytest.approx(0.7 * n)
    assert comp["interfaces"]["relative_error_pct"] == pytest.approx(
        list(100 * (pr.predicted_friction_n - np.array([60.0, 125.0])) / [60.0, 125.0]))
    assert set(d["law_comparison"]) == {"gamma", "interfaces"}
    cols = pr.to_frame().columns
    assert {"gamma_friction_n", "interfaces_relative_error_pct"} <= set(cols)
    # gamma alone: the old output, plus "law"
    g = predict(structs, 0.7, None, [0.3, 0.6], squeeze_fn=_fake_squeeze()).to_dict()
    assert g["gamma"] == 0.7 and g["law"] == "gamma" and "law_comparison" not in g


def test_predict_interface_law_without_contact_outputs_is_an_error() -> None:
    def old(s, m, p):
        return SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * np.asarray(p))

    with pytest.raises(InputError, match="wire_pressure_integral_n_per_mm.*exofric squeeze"):
        predict(paper_structures()[:1], InterfaceFrictionModel(0.5, 0.2), None, [0.6],
                squeeze_fn=old)


# -- CLI ---------------------------------------------------------------------------------------


def _write_pair(tmp: Path, spec, mu_t: float, mu_w: float, seed: int) -> tuple[str, str]:
    c = _curves(*spec)
    sq = tmp / f"{spec[0]}.json"
    sq.write_text(json.dumps({
        "pressure_mpa": list(c.pressure_mpa), "squeeze_force_n": list(c.squeeze_force_n),
        "wire_pressure_integral_n_per_mm": [v / 116.0 for v in c.wire_pressure_integral_n],
        "length_mm": 116.0}))
    fr = tmp / f"{spec[0]}.csv"
    fr.write_text(simulate_interface_rig(c, mu_t, mu_w, seed=seed).to_csv_text())
    return str(sq), str(fr)


def _cli(capsys, *args: str) -> tuple[int, str, str]:
    code = run(list(args))
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def test_cli_fit_interfaces_three_structures(tmp_path: Path, capsys) -> None:
    args = ["fit-friction", "--law", "interfaces"]
    for i, spec in enumerate(THREE):
        sq, fr = _write_pair(tmp_path, spec, 0.42, 0.21, seed=i)
        args += ["--squeeze", sq, "--friction", fr]
    code, out, err = _cli(capsys, *args, "--json", "--plot", str(tmp_path / "fit.png"))
    assert code == 0, err
    d = json.loads(out)
    assert d["law"] == "interfaces" and d["synthetic"] is True and d["identifiable"] is True
    assert d["mu_tube"] == pytest.approx(0.42, rel=0.02)
    assert d["mu_wall"] == pytest.approx(0.21, rel=0.02)
    assert d["mu_tube_ci"][0] <= 0.42 <= d["mu_tube_ci"][1]
    assert d["mu_wall_ci"][0] <= 0.21 <= d["mu_wall_ci"][1]
    assert -1 <= d["correlation"] <= 1 and d["warnings"] == []
    assert (tmp_path / "fit.png").stat().st_size > 0
    code, out, err = _cli(capsys, *args)                  # the text view renders too
    assert code == 0 and "mu_tube" in out


def test_cli_fit_interfaces_one_structure_says_not_identifiable(tmp_path: Path, capsys) -> None:
    sq, fr = _write_pair(tmp_path, THREE[0], 0.42, 0.21, seed=0)
    code, out, err = _cli(capsys, "fit-friction", "--law", "interfaces", "--squeeze", sq,
                          "--friction", fr, "--json")
    assert code == 0, err
    d = json.loads(out)
    assert d["identifiable"] is False and any("not separated" in w for w in d["warnings"])
    assert "not separated" in err


@pytest.mark.parametrize("case,needle", [
    ("csv", "a CSV holds N(P) only"),
    ("nokey", "wire_pressure_integral_n_per_mm"),
    ("unpaired", "pairs"),
    ("gamma2", "--law interfaces"),
    ("odr", "--ci"),
])
def test_cli_fit_interfaces_bad_input(tmp_path: Path, capsys, case: str, needle: str) -> None:
    sq, fr = _write_pair(tmp_path, THREE[0], 0.42, 0.21, seed=0)
    sq2, fr2 = _write_pair(tmp_path, THREE[1], 0.42, 0.21, seed=1)
    base = ["fit-friction", "--law", "interfaces"]
    if case == "csv":
        csv = tmp_path / "n.csv"
        csv.write_text("pressure_mpa,squeeze_force_n\n0.2,1\n0.6,9\n")
        args = [*base, "--squeeze", str(csv), "--friction", fr]
    elif case == "nokey":
        old = tmp_path / "old.json"
        old.write_text(json.dumps({"pressure_mpa": [0.2, 0.6], "squeeze_force_n": [1, 9]}))
        args = [*base, "--squeeze", str(old), "--friction", fr]
    elif case == "unpaired":
        args = [*base, "--squeeze", sq, "--squeeze", sq2, "--friction", fr]
    elif case == "gamma2":
        args = ["fit-friction", "--squeeze", sq, "--friction", fr, "--squeeze", sq2,
                "--friction", fr2]
    else:
        args = [*base, "--squeeze", sq, "--friction", fr, "--ci", "odr"]
    code, out, err = _cli(capsys, *args)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert code == 2 and out == "" and len(lines) == 1 and needle in lines[0], err
    if case == "nokey":
        assert "exofric squeeze" in lines[0]


@pytest.mark.parametrize("opt,value,needle", [
    ("--mu-tube", "-0.1", "--mu-tube must be >= 0"),
    ("--mu-wall", "nan", "--mu-wall must be a finite"),
    ("--mu-tube", "2.5", "--mu-tube must be <= 2"),
])
def test_cli_predict_bad_coefficients(capsys, opt: str, value: str, needle: str) -> None:
    other = {"--mu-tube": "--mu-wall", "--mu-wall": "--mu-tube"}[opt]
    code, out, err = _cli(capsys, "predict", "--law", "interfaces", "--paper", opt, value,
                          other, "0.2")
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert code == 2 and out == "" and len(lines) == 1 and needle in lines[0], err


def test_cli_predict_law_options(capsys) -> None:
    code, _, err = _cli(capsys, "predict", "--law", "interfaces", "--paper", "--mu-tube", "0.4")
    assert code == 2 and "mu_wall" in err.replace("--mu-wall", "mu_wall")
    code, _, err = _cli(capsys, "predict", "--paper")
    assert code == 2 and "--gamma" in err
    code, _, err = _cli(capsys, "predict", "--law", "interfaces", "--paper")
    assert code == 2 and "--mu-tube" in err


def test_cli_coefficient_above_1_5_is_a_json_warning(tmp_path: Path, capsys) -> None:
    sq, _ = _write_pair(tmp_path, THREE[0], 0.42, 0.21, seed=0)
    code, out, err = _cli(capsys, "torque", "--squeeze", sq, "--mu-tube", "1.6", "--mu-wall",
                          "0.2", "--json")
    assert code == 0, err
    assert any("mu_tube = 1.6 is above 1.5" in w for w in json.loads(out)["warnings"])


# -- planted recovery through the FE (acceptance) ---------------------------------------------


def _fe_curves():
    """FE S_wire(P), N(P) of three structures of different geometry (3 x 32 meshes, ~0.5 s
    each): the base group (test 1), test 2 (6.2 mm tube, 1.1 mm wire) and the base with a
    thin-walled tube (ID 7.0 mm). The paper's structures alone cannot separate the two
    coefficients: tests 1-3 are near scalings of one another with the same S/N(P)
    (kappa ~ 138); a tube of another wall thickness changes the wrap (S/N to 1.23)."""
    from exofric.fe import MeshSpec
    from exofric.geometry import Structure
    from exofric.material import MooneyRivlin
    from exofric.simulate import squeeze

    mat = MooneyRivlin.from_shore(62.5)
    structs = paper_structures()
    out = {}
    for s in (structs[0], structs[1], Structure(10.0, 8.3, 7.0, 1.6, 116.0, "thin wall")):
        res = squeeze(s, mat, np.round(np.linspace(0.2, 0.6, 9), 4), mesh=MeshSpec(3, 32),
                      keep_fields=False)
        out[s.name] = InterfaceCurves.from_squeeze(res)
    return out


@pytest.fixture(scope="module")
def fe_curves():
    return _fe_curves()


MU_TUBE, MU_WALL = 0.45, 0.20


def test_planted_recovery_on_three_fe_structures(fe_curves) -> None:
    tests = [simulate_interface_rig(c, MU_TUBE, MU_WALL, seed=11 + i, repeats=3).to_test()
             for i, c in enumerate(fe_curves.values())]
    fit = fit_interfaces(tests)
    print(f"kappa {fit.condition_number:.1f}, corr {fit.correlation:.4f}, mu_tube "
          f"{fit.mu_tube:.5f} {fit.mu_tube_ci}, mu_wall {fit.mu_wall:.5f} {fit.mu_wall_ci}")
    assert fit.identifiable, fit.identifiability_reason
    assert fit.mu_tube == pytest.approx(MU_TUBE, rel=0.02)
    assert fit.mu_wall == pytest.approx(MU_WALL, rel=0.02)
    assert fit.mu_tube_ci[0] <= MU_TUBE <= fit.mu_tube_ci[1]
    assert fit.mu_wall_ci[0] <= MU_WALL <= fit.mu_wall_ci[1]


def test_one_fe_structure_is_not_identifiable(fe_curves) -> None:
    c = fe_curves["test 1"]
    with pytest.warns(IdentifiabilityWarning):
        fit = fit_interfaces([simulate_interface_rig(c, MU_TUBE, MU_WALL, seed=3,
                                                     repeats=3).to_test()])
    assert not fit.identifiable and fit.condition_number > KAPPA_MAX
    # and the paper's near-similar tests 1-2 together do no better: the same S/N(P)
    print(f"one structure: kappa {fit.condition_number:.1f}, corr {fit.correlation:.5f}, "
          f"mu_tube {fit.mu_tube:.4f} {fit.mu_tube_ci}, mu_wall {fit.mu_wall:.4f} "
          f"{fit.mu_wall_ci}")
    with pytest.warns(IdentifiabilityWarning):
        two = fit_interfaces([simulate_interface_rig(fe_curves[k], MU_TUBE, MU_WALL, seed=4,
                                                     repeats=3).to_test()
                              for k in ("test 1", "test 2")])
    assert not two.identifiable and two.condition_number > KAPPA_MAX


def test_cli_end_to_end_squeeze_rig_fit(tmp_path: Path, capsys) -> None:
    """`exofric squeeze --json` -> `exofric rig --law interfaces` -> `exofric fit-friction --law
    interfaces` on three structures (3 x 32 meshes): the planted pair comes back."""

    geoms = [("10", "8.3", "4.97", "1.6"), ("7.5", "6.2", "3.7125", "1.1"),
             ("10", "8.3", "7.0", "1.6")]
    fit_args = ["fit-friction", "--law", "interfaces"]
    for i, (hole, od, idd, wire) in enumerate(geoms):
        code, out, err = _cli(capsys, "squeeze", "--hole", hole, "--tube-od", od, "--tube-id",
                              idd, "--wire", wire, "--shore", "62.5", "--pressures",
                              ",".join(f"{p:g}" for p in P), "--n-radial", "3", "--n-circ",
                              "32", "--json")
        assert code == 0, err
        sq = tmp_path / f"S{i}.json"
        sq.write_text(out)
        fr = tmp_path / f"F{i}.csv"
        code, _, err = _cli(capsys, "rig", "--squeeze", str(sq), "--law", "interfaces",
                            "--mu-tube", str(MU_TUBE), "--mu-wall", str(MU_WALL), "--out",
                            str(fr), "--repeats", "3", "--seed", str(i), "--json")
        assert code == 0, err
        fit_args += ["--squeeze", str(sq), "--friction", str(fr)]
    code, out, err = _cli(capsys, *fit_args, "--json")
    assert code == 0, err
    d = json.loads(out)
    assert d["identifiable"] is True and d["n_structures"] == 3
    assert d["mu_tube"] == pytest.approx(MU_TUBE, rel=0.02)
    assert d["mu_wall"] == pytest.approx(MU_WALL, rel=0.02)
    assert d["mu_tube_ci"][0] <= MU_TUBE <= d["mu_tube_ci"][1]
    assert d["mu_wall_ci"][0] <= MU_WALL <= d["mu_wall_ci"][1]
    # the same data through the old single-structure usage still fits gamma
    code, out, err = _cli(capsys, "fit-friction", "--squeeze", str(tmp_path / "S0.json"),
                          "--friction", str(tmp_path / "F0.csv"), "--json")
    assert code == 0, err
    g = json.loads(out)
    assert g["law"] == "gamma" and "gamma_ci95" in g and 0.6 < g["gamma"] < 0.8
