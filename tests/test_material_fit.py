"""Fitting hyperelastic models (exofric.material.fit_material), the Treloar data, the CSV
reader and ``exofric material --fit/--treloar``.

Independent references: planted parameters; ordinary least squares by statsmodels for the
models that are linear in their parameters (neo-Hookean, Mooney-Rivlin, Yeoh: P = X beta with
hand-written columns), which gives the same minimum, standard errors and correlations;
Treloar's values in kgf/cm^2 as FElupe quotes them; Ogden's (1972) published Treloar fit;
FElupe's own fit on the same data (when FElupe is installed). Units: MPa, stretch unitless.
"""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest

from exofric.cli import run
from exofric.errors import InputError, PlausibilityWarning
from exofric.io import read_stress_stretch
from exofric.material import (
    MaterialRangeWarning,
    fit_material,
    material_model,
    treloar_1944,
)

T = treloar_1944()


def yeoh_columns(mode, lam):
    """Columns of P = X (C10, C20, C30) for Yeoh, by hand (I1 per mode)."""
    i1 = {"uniaxial": lam**2 + 2 / lam, "biaxial": 2 * lam**2 + lam**-4,
          "planar": lam**2 + 1 + lam**-2}[mode]
    g = 2 * (lam - lam ** {"uniaxial": -2.0, "biaxial": -5.0, "planar": -3.0}[mode])
    return np.column_stack([g, 2 * g * (i1 - 3), 3 * g * (i1 - 3) ** 2])


def test_treloar_data_units_against_felupe_kgf_table():
    """Uniaxial points FElupe quotes from Treloar in kgf/cm^2, x 0.0981 -> MPa: the shipped
    values agree to 0.1 % (the tabulations round differently)."""
    kgf = {1.24: 2.30, 1.585: 4.16, 2.18: 6.00, 3.02: 8.80, 4.03: 12.5, 4.76: 16.2,
           5.75: 23.6, 7.6: 64.4}
    lam, p = T["uniaxial"]
    for stretch, value in kgf.items():
        i = int(np.argmin(np.abs(lam - stretch)))
        assert lam[i] == pytest.approx(stretch, abs=1e-9)
        assert p[i] == pytest.approx(value * 0.0980665, rel=1e-3)
    assert [T[m][0].size for m in ("uniaxial", "biaxial", "planar")] == [24, 16, 13]


@pytest.mark.parametrize("name,params", [
    ("yeoh", [0.19, -0.0019, 4.1e-5]),
    ("ogden2", [0.004, 5.0, 0.45, 1.6]),           # terms come back exponent-descending
    ("ogden3", [0.003, 5.0, 0.40, 1.3, 0.0098, -2.0]),
])
def test_planted_parameters_are_recovered(name, params):
    """Noise-free data of a known model, three modes: the fit returns it (1e-5 relative)."""
    true = material_model(name, params)
    data = {m: (np.linspace(1.05, 4.0, 15), None) for m in ("uniaxial", "biaxial", "planar")}
    data = {m: (lam, true.stress_mpa(m, lam)) for m, (lam, _) in data.items()}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PlausibilityWarning)
        fit = fit_material(name, **data)
    np.testing.assert_allclose(fit.model.params, params, rtol=1e-5, atol=1e-9)
    for m in fit.modes.values():
        assert m.r2 == pytest.approx(1.0, abs=1e-10) and m.rms_mpa < 1e-8


def test_yeoh_fit_equals_ordinary_least_squares_with_its_errors():
    """Yeoh is linear in (C10, C20, C30): statsmodels OLS on hand-built columns gives the same
    minimum, standard errors and correlations (1e-6 relative; the optimiser stops at
    ftol=xtol=1e-15, so the gap is the optimiser's, far below 1e-6)."""
    sm = pytest.importorskip("statsmodels.api")
    fit = fit_material("yeoh", **T)
    x = np.vstack([yeoh_columns(m, T[m][0]) for m in T])
    y = np.concatenate([T[m][1] for m in T])
    ols = sm.OLS(y, x).fit()
    np.testing.assert_allclose(fit.model.params, ols.params, rtol=1e-6)
    np.testing.assert_allclose(fit.stderr, ols.bse, rtol=1e-5)
    cov = ols.cov_params()
    corr = cov / np.sqrt(np.outer(np.diag(cov), np.diag(cov)))
    np.testing.assert_allclose(fit.correlation, corr, rtol=1e-5, atol=1e-8)
    # per-mode R^2 and RMS from the frame, by their definitions
    df = fit.to_frame()
    for mode, g in df.groupby("mode"):
        res = g["fitted_mpa"] - g["stress_mpa"]
        assert fit.modes[mode].rms_mpa == pytest.approx(np.sqrt(np.mean(res**2)), rel=1e-12)
        ss_tot = np.sum((g["stress_mpa"] - g["stress_mpa"].mean()) ** 2)
        assert fit.modes[mode].r2 == pytest.approx(1 - np.sum(res**2) / ss_tot, rel=1e-12)


def test_relative_residuals_equal_weighted_least_squares():
    """Relative residuals = OLS with rows divided by the measured stress (neo-Hookean)."""
    fit = fit_material("neo-hookean", **T, residuals="relative")
    x = np.concatenate([yeoh_columns(m, T[m][0])[:, 0] / T[m][1] for m in T])
    beta = np.sum(x) / np.sum(x * x)        # min sum (x beta - 1)^2
    assert fit.model.params[0] == pytest.approx(beta, rel=1e-8)


def test_ogden3_near_ogden_1972():
    """Ogden (1972, Proc. R. Soc. A 326, 565) fitted Treloar by hand: mu_p = 6.3, 0.012, -0.1
    kgf/cm^2 (his W = sum mu_p/a_p (...)), a_p = 1.3, 5.0, -2.0; in ABAQUS's convention
    mu_i = mu_p a_p / 2 -> shear modulus 4.22 kgf/cm^2 = 0.414 MPa. A least-squares fit with
    relative residuals lands near it: shear modulus within 2 %, alpha1, alpha2 within 10 %."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PlausibilityWarning)
        fit = fit_material("ogden3", **T, residuals="relative")
    mu = sum(m * a / 2 for m, a in ((6.3, 1.3), (0.012, 5.0), (-0.1, -2.0))) * 0.0980665
    assert fit.model.shear_modulus_mpa == pytest.approx(mu, rel=0.02)
    p = fit.model.params  # terms exponent-descending: (mu, 5.0), (mu, 1.3), (mu, -2.0)
    assert p[3] == pytest.approx(1.3, rel=0.1) and p[1] == pytest.approx(5.0, rel=0.1)
    assert fit.stability.stable


def test_felupe_fits_the_same_minimum():
    """FElupe's ConstitutiveMaterial.optimize on Treloar uniaxial + equibiaxial, incompressible,
    same residuals (absolute and relative). FElupe 11.3 pairs its predictions and the data by
    position, in different orders (ux, ps, bx vs ux, bx, ps), when planar data are given, so the
    comparison uses the two modes where the orders agree. Neo-Hookean and Yeoh have a single
    minimum: parameters to 1e-6. Ogden-3's six parameters are correlated to |r| ~ 1: both reach
    the same cost to 1e-3 and parameters to 2e-3 relative, their curves to 1e-3 MPa."""
    fem = pytest.importorskip("felupe")
    pytest.importorskip("tensortrax")
    ux, bx = ([T[m][0], T[m][1]] for m in ("uniaxial", "biaxial"))
    tol = dict(xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=20000)
    for rel in (False, True):
        cases = [
            ("neo-hookean", fem.Hyperelastic(fem.neo_hooke, mu=0.5), lambda x: [x[0] / 2]),
            ("yeoh", fem.Hyperelastic(fem.yeoh, C10=0.2, C20=-0.001, C30=1e-5), list),
            ("ogden3", fem.Hyperelastic(fem.ogden, mu=[0.4, 0.003, 0.008],
                                        alpha=[1.3, 5.0, -2.0]),
             lambda x: [x[0], x[3], x[1], x[4], x[2], x[5]]),
        ]
        for name, umat, to_ours in cases:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                _, res = umat.optimize(ux=ux, bx=bx, incompressible=True, relative=rel, **tol)
                ours = fit_material(name, uniaxial=ux, biaxial=bx,
                                    residuals="relative" if rel else "absolute")
            theirs = np.asarray(to_ours(res.x))
            if name == "ogden3":  # the terms in one order (exponent descending; ours is)
                order = np.argsort(-theirs[1::2])
                theirs = np.concatenate([theirs[2 * i:2 * i + 2] for i in order])
                assert ours.cost == pytest.approx(res.cost, rel=1e-3)
                np.testing.assert_allclose(ours.model.params, theirs, rtol=2e-3, atol=1e-5)
                other = material_model("ogden3", theirs)
                for m, lam in (("uniaxial", ux[0]), ("biaxial", bx[0])):
                    np.testing.assert_allclose(ours.model.stress_mpa(m, lam),
                                               other.stress_mpa(m, lam), atol=1e-3)
            else:
                np.testing.assert_allclose(ours.model.params, theirs, rtol=1e-6)


def unstable_biaxial():
    """Equibiaxial data of Mooney-Rivlin C10 = 0.2, C01 = -0.01 MPa to stretch 4.5: by the hand
    form P = 2 (l - l^-5)(C10 + C01 l^2), dP/dl = 2 (1 + 5 l^-6)(C10 + C01 l^2)
    + 4 C01 l (l - l^-5), which turns negative near 2.6, inside the data."""
    lam = np.linspace(1.05, 4.5, 20)
    c10, c01 = 0.2, -0.01
    p = 2 * (lam - lam**-5) * (c10 + c01 * lam**2)
    dp = 2 * (1 + 5 * lam**-6) * (c10 + c01 * lam**2) + 4 * c01 * lam * (lam - lam**-5)
    assert dp[0] > 0 and dp[-1] < 0
    return lam, p, float(lam[np.argmax(dp <= 0)])


def test_unstable_fit_is_refused_unless_allowed():
    """Unconstrained, the planted unstable model is recovered and refused (instability inside
    the measured range); allowed, it warns; by default the fit is constrained to a stable one."""
    lam, p, first = unstable_biaxial()
    with pytest.raises(InputError, match="Drucker-unstable") as e:
        fit_material("mooney-rivlin", biaxial=(lam, p), constrain=False)
    assert "\n" not in str(e.value)
    with pytest.warns(PlausibilityWarning, match="Drucker"):
        fit = fit_material("mooney-rivlin", biaxial=(lam, p), allow_unstable=True)
    np.testing.assert_allclose(fit.model.params, [0.2, -0.01], rtol=1e-8)
    assert not fit.stability.stable and not fit.admissible
    assert fit.stability.unstable_from["biaxial"] <= first
    assert any("Drucker" in w for w in fit.warnings)
    with pytest.warns(PlausibilityWarning, match="constrained"):
        fit = fit_material("mooney-rivlin", biaxial=(lam, p))
    c10, c01 = fit.model.params
    grid = np.linspace(1.0, 4.5 * 1.1, 401)  # the data's range + 10 %, by the hand form
    dp = 2 * (1 + 5 * grid**-6) * (c10 + c01 * grid**2) + 4 * c01 * grid * (grid - grid**-5)
    assert fit.constrained and fit.admissible and np.all(dp > 0)


def test_treloar_mooney_rivlin_is_stable_on_each_modes_range():
    """Mooney-Rivlin on all of Treloar has C01 < 0; its equibiaxial dP/dl turns negative only
    near stretch 7 (hand form above), beyond the equibiaxial data (4.45) + 10 %: admissible
    without a constraint (before issue 31 the uniaxial range was applied to every mode)."""
    fit = fit_material("mooney-rivlin", **T)
    c10, c01 = fit.model.params
    grid = np.linspace(1.0, 4.45 * 1.1, 401)
    dp = 2 * (1 + 5 * grid**-6) * (c10 + c01 * grid**2) + 4 * c01 * grid * (grid - grid**-5)
    assert c01 < 0 and np.all(dp > 0) and not fit.constrained and fit.stability.stable


def test_true_stress_data_and_extrapolation_warning():
    lam, p = T["planar"]
    a = fit_material("yeoh", planar=(lam, p))
    b = fit_material("yeoh", planar=(lam, p * lam), stress_kind="true")  # sigma = l P
    np.testing.assert_allclose(a.model.params, b.model.params, rtol=1e-9)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        a.stress_mpa("planar", [1.0, 2.0, 4.9])                # inside: no warning
    with pytest.warns(MaterialRangeWarning, match="extrapolates"):
        a.stress_mpa("planar", [6.0])
    with pytest.warns(MaterialRangeWarning, match="no uniaxial data"):
        a.stress_mpa("uniaxial", [2.0])


@pytest.mark.parametrize("kwargs,needle", [
    (dict(uniaxial=([1.0, -1.2, 1.5], [0, 0.1, 0.2])), "stretch must be > 0"),
    (dict(uniaxial=([1.1, 1.3, 1.2, 1.5], [0.1, 0.2, 0.3, 0.4])), "strictly monotonic"),
    (dict(uniaxial=([1.1, 1.2], [0.1])), "same length"),
    (dict(), "at least one mode"),
    (dict(uniaxial=([1.0, 1.2, 1.4], [0.0, 0.1, 0.2]), residuals="relative"), "relative"),
])
def test_bad_data_one_line(kwargs, needle):
    with pytest.raises(InputError, match=needle) as e:
        fit_material("neo-hookean", **kwargs)
    assert "\n" not in str(e.value)
    with pytest.raises(InputError, match="must be one of"):
        fit_material("gent", uniaxial=T["uniaxial"])
    with pytest.raises(InputError, match="at least 6 data points"):
        fit_material("ogden3", uniaxial=([1.1, 1.2], [0.1, 0.2]))


def test_result_dict_and_frame():
    fit = fit_material("yeoh", **T)
    d = fit.to_dict()
    for key in ("model", "params", "stderr", "param_units", "correlation", "modes", "stability",
                "warnings", "shear_modulus_mpa", "d_per_mpa", "residuals"):
        assert key in d
    assert d["param_units"] == {"c10_mpa": "MPa", "c20_mpa": "MPa", "c30_mpa": "MPa"}
    assert set(d["modes"]["uniaxial"]) >= {"r2", "rms_mpa", "n_points", "stretch_min"}
    assert list(fit.to_frame().columns) == ["mode", "stretch", "stress_mpa", "fitted_mpa",
                                            "residual_mpa"]
    json.dumps(d)


# --- CSV reader -------------------------------------------------------------------------------


def test_reader_strain_header_kind_and_option_wins(tmp_path):
    f = tmp_path / "u.csv"
    f.write_text("# stress_kind: true\nstrain,stress_mpa\n0.0,0\n0.5,0.4\n1.0,1.1\n")
    df = read_stress_stretch(f)
    assert df["stretch"].tolist() == [1.0, 1.5, 2.0] and df.attrs["stress_kind"] == "true"
    assert read_stress_stretch(f, "engineering").attrs["stress_kind"] == "engineering"


@pytest.mark.parametrize("text,needle", [
    ("stretch,stress_mpa\n1.0,0\n-0.5,0.1\n", "'stretch' must be > 0"),
    ("strain,stress_mpa\n0.0,0\n0.2,0.1\n0.1,0.2\n", "not monotonic"),
    ("stretch,Stress (kg)\n1.0,0\n1.5,100\n", "cannot be converted"),
    ("stress_mpa\n0\n0.1\n", "'stretch' or 'strain'"),
    ("# stress_kind: cauchy\nstretch,stress_mpa\n1.0,0\n1.5,0.1\n", "stress_kind"),
])
def test_reader_errors_name_the_file_and_field(tmp_path, text, needle):
    f = tmp_path / "bad.csv"
    f.write_text(text)
    with pytest.raises(InputError, match=needle) as e:
        read_stress_stretch(f)
    assert "\n" not in str(e.value)


# --- CLI ----------------------------------------------------------------------------------------


def test_cli_treloar_json(capsys, tmp_path):
    png = tmp_path / "fit.png"
    assert run(["material", "--model", "yeoh", "--treloar", "--plot", str(png), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    api = fit_material("yeoh", **T).to_dict()
    assert d["model"] == "yeoh" and d["params"] == pytest.approx(api["params"])
    assert set(d["modes"]) == {"uniaxial", "biaxial", "planar"}
    assert d["stability"]["stable"] is True and "Treloar" in d["data_source"]
    assert png.is_file() and d["plot"] == str(png)
    assert isinstance(d["warnings"], list)


def test_cli_fit_files_and_header_kind(capsys, tmp_path):
    true = material_model("yeoh", [0.19, -0.0019, 4.1e-5])
    lam = np.linspace(1.1, 4.0, 12)
    u, p = tmp_path / "u.csv", tmp_path / "p.csv"
    u.write_text("stretch,stress_mpa\n" + "".join(
        f"{a:.17g},{b:.17g}\n" for a, b in zip(lam, true.uniaxial_stress_mpa(lam), strict=True)))
    p.write_text("# stress_kind: true\nstrain,stress_mpa\n" + "".join(
        f"{a - 1:.17g},{b:.17g}\n"
        for a, b in zip(lam, true.planar_stress_mpa(lam, "true"), strict=True)))
    assert run(["material", "--model", "yeoh", "--fit", str(u), "--fit-planar", str(p),
                "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert list(d["params"].values()) == pytest.approx([0.19, -0.0019, 4.1e-5], rel=1e-5)
    assert d["modes"]["planar"]["stress_kind"] == "true"
    assert d["modes"]["uniaxial"]["source"] == "u.csv"


@pytest.mark.parametrize("args,needle", [
    (["--model", "yeoh", "--fit", "{neg}"], "'stretch' must be > 0"),
    (["--model", "yeoh", "--fit", "{nonmono}"], "not monotonic"),
    (["--model", "gent", "--treloar"], "--model"),
    (["--treloar"], "--model"),
    (["--model", "mooney-rivlin", "--fit-biaxial", "{unstable}", "--unconstrained"],
     "Drucker-unstable"),
    (["--model", "yeoh", "--treloar", "--stress-kind", "cauchy"], "--stress-kind"),
    (["--model", "yeoh", "--treloar", "--shore", "60"], "--shore"),
    (["--shore", "60", "--model", "yeoh"], "--model"),
    ([], "--shore"),
])
def test_cli_bad_input_one_line_exit_2(args, needle, capsys, tmp_path):
    (tmp_path / "neg.csv").write_text("stretch,stress_mpa\n1.0,0\n0.0,0.1\n")
    (tmp_path / "nonmono.csv").write_text("stretch,stress_mpa\n1.0,0\n1.5,0.1\n1.2,0.2\n")
    lam, p, _ = unstable_biaxial()
    (tmp_path / "unstable.csv").write_text("stretch,stress_mpa\n" + "".join(
        f"{a!r},{b!r}\n" for a, b in zip(lam.tolist(), p.tolist(), strict=True)))
    args = [a.format(neg=tmp_path / "neg.csv", nonmono=tmp_path / "nonmono.csv",
                     unstable=tmp_path / "unstable.csv") for a in args]
    code = run(["material", *args])
    out, err = capsys.readouterr()
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert code == 2 and out == "" and len(lines) == 1 and needle in lines[0], err


def test_cli_allow_unstable_warns(capsys, tmp_path):
    lam, p, _ = unstable_biaxial()
    f = tmp_path / "unstable.csv"
    f.write_text("stretch,stress_mpa\n" + "".join(
        f"{a!r},{b!r}\n" for a, b in zip(lam.tolist(), p.tolist(), strict=True)))
    assert run(["material", "--model", "mooney-rivlin", "--fit-biaxial", str(f),
                "--allow-unstable", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["stability"]["stable"] is False and d["admissible"] is False
    assert any("Drucker" in w for w in d["warnings"])
    assert run(["material", "--model", "mooney-rivlin", "--fit-biaxial", str(f), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["stability"]["stable"] is True and d["constrained"] is True


# --- issue 37: the fit's analytic Jacobians, vectorised variable projection, batched LM -------

KERNEL_CASES = [("neo-hookean", [0.3]), ("mooney-rivlin", [0.2, 0.05]),
                ("yeoh", [0.19, -0.0019, 4.1e-5]), ("ogden1", [0.5, 2.7]),
                ("ogden2", [0.5, 1.5, 0.01, 5.0]), ("ogden3", [0.4, 1.3, 0.003, 5.0, -0.01, -2.0])]


@pytest.mark.parametrize("name,x", KERNEL_CASES, ids=[c[0] for c in KERNEL_CASES])
def test_kernel_jacobians_against_finite_differences(name, x):
    """Every model, every mode: the stress Jacobian dP/dx, the tangent dP/dl and its Jacobian
    d(dP/dl)/dx against central differences (h = 1e-6 relative; truncation ~h^2 P''' and
    rounding ~1e-16 P / h: 1e-6 relative plus 1e-9 MPa), and the stress against the model's
    principal-stretch form (1e-12)."""
    from exofric.material._kernels import stress_jac, tangent_jac

    lam = np.linspace(0.5, 5.0, 37)
    x = np.array(x)
    m = material_model(name, x)
    for mode in ("uniaxial", "biaxial", "planar"):
        p, jac = stress_jac(name, mode, lam, x)
        np.testing.assert_allclose(p, m.stress_mpa(mode, lam), rtol=1e-12, atol=1e-14)
        t, tjac = tangent_jac(name, mode, lam, x)
        h = 1e-6
        fd_t = (stress_jac(name, mode, lam + h, x)[0] - stress_jac(name, mode, lam - h, x)[0])
        np.testing.assert_allclose(t, fd_t / (2 * h), rtol=1e-6, atol=1e-9)
        for k in range(x.size):
            d = np.zeros(x.size)
            d[k] = h * max(1.0, abs(x[k]))
            fd = (stress_jac(name, mode, lam, x + d)[0] - stress_jac(name, mode, lam, x - d)[0])
            np.testing.assert_allclose(jac[:, k], fd / (2 * d[k]), rtol=1e-6, atol=1e-9)
            fd = tangent_jac(name, mode, lam, x + d)[0] - tangent_jac(name, mode, lam, x - d)[0]
            np.testing.assert_allclose(tjac[:, k], fd / (2 * d[k]), rtol=1e-6, atol=1e-9)


def hand_psi(mode, lam, a):
    """Ogden's column psi = (2/a)(l^(a-1) - l^(c a - 1)), written out here."""
    c = {"uniaxial": -0.5, "biaxial": -2.0, "planar": -1.0}[mode]
    return 2.0 / a * (lam ** (a - 1.0) - lam ** (c * a - 1.0))


def test_variable_projection_batch_against_bounded_least_squares():
    """All rows at once: mu equals scipy's bounded linear least squares (lsq_linear, BVLS)
    on hand-built columns, with |mu| <= mu_max active on some rows and a column 1e20 times
    another's (exponent 24 at stretch 7.6); the cost is half the squared residual; where no mu
    is at its bound, Kaufman's Jacobian gives the exact gradient of the cost (central
    differences, h = 1e-6)."""
    from scipy.optimize import lsq_linear

    from exofric.material._fit import _setup

    lam, p = T["uniaxial"]
    setup = _setup("ogden3", {"uniaxial": (lam, p)}, "absolute", 0.1)
    prob = setup.prob
    rows = np.array([[1.3, 5.0, -2.0], [24.0, 1.58, -10.6], [2.3, 2.35, 2.4],
                     [2.0, 2.0000001, -1.0], [0.5, 9.0, -12.0]])
    cost, res, jac, mu = prob.vp_batch(rows)
    for i, a in enumerate(rows):
        cols = np.column_stack([hand_psi("uniaxial", lam, v) for v in a])
        scale = np.linalg.norm(cols, axis=0)  # lsq_linear on unit columns, as well scaled
        ref = lsq_linear(cols / scale, p, bounds=(-prob.mu_max * scale, prob.mu_max * scale),
                         method="bvls", tol=1e-14).x / scale
        r_ref = cols @ ref - p
        # the same minimum: cost to 1e-9 relative (mu itself is ill-determined on the row of
        # nearly equal exponents, so compared through the cost)
        assert cost[i] == pytest.approx(0.5 * r_ref @ r_ref, rel=1e-9), i
        if i in (0, 1, 4):
            np.testing.assert_allclose(mu[i], ref, rtol=1e-6, atol=1e-12 * prob.mu_max)
    assert np.any(np.abs(mu[2]) >= prob.mu_max * (1 - 1e-9))  # a bound active
    for i in (0, 4):
        grad = jac[i].T @ res[i]
        for k in range(3):
            d = np.zeros(3)
            d[k] = 1e-6
            fd = (prob.vp_batch(rows[i] + d)[0][0] - prob.vp_batch(rows[i] - d)[0][0]) / 2e-6
            assert grad[k] == pytest.approx(fd, rel=1e-5, abs=1e-9)


def test_batched_levenberg_marquardt_on_rosenbrock():
    """The batched LM on Rosenbrock's residuals (10 (y - x^2), 1 - x) from four starts at
    once: the minimum (1, 1) to 1e-6; with the bound x <= 0.5 the bounded minimum is
    (0.5, 0.25), cost 0.5 (1 - 0.5)^2 = 0.125 (by hand)."""
    from exofric.material._fit import _lm_batch

    def fun(z):
        res = np.stack([10 * (z[:, 1] - z[:, 0] ** 2), 1 - z[:, 0]], axis=1)
        jac = np.zeros((z.shape[0], 2, 2))
        jac[:, 0, 0], jac[:, 0, 1], jac[:, 1, 0] = -20 * z[:, 0], 10.0, -1.0
        return 0.5 * np.sum(res**2, axis=1), res, jac

    starts = np.array([[-1.2, 1.0], [0.0, 0.0], [2.0, -1.0], [-2.0, 3.0]])
    x, cost = _lm_batch(fun, starts, -np.inf, np.inf, tol=1e-14, crawl=0.0)
    np.testing.assert_allclose(x, 1.0, atol=1e-6)
    x, cost = _lm_batch(fun, starts, np.array([-np.inf, -np.inf]), np.array([0.5, np.inf]),
                        tol=1e-14, crawl=0.0)
    np.testing.assert_allclose(x, [[0.5, 0.25]] * 4, atol=1e-6)
    np.testing.assert_allclose(cost, 0.125, rtol=1e-9)
