"""Hyperelastic fits on real silicone data (issue 31), tensile files as machines write them.

Independent references, all written in this file:

* uniaxial nominal stresses in closed form (``P_uni`` below) and their tangent by central
  differences, not exofric's kernels or models;
* the admissible fit: ``scipy.optimize.least_squares`` from many random starts on those closed
  forms, with the admissibility constraints as a penalty continued to a large weight
  (``dP/dl >= 1e-3 x`` the data's secant modulus on 401 stretches over the data's range + 10 %,
  ``mu > 0``, Ogden ``|alpha| <= 30`` and ``|mu_i| <= 100 x`` the secant modulus): a different
  algorithm (penalty, finite differences, random starts) for the same problem;
* hand-computed load/extension -> stress/stretch values, and a closed-form neo-Hookean curve
  written both as engineering and as true strain/stress.

Data: the shipped Soft Robotics Materials Database extracts (Ecoflex 00-30, Dragon Skin 20,
RTV615; ODbL) and Treloar's uniaxial data. Units: MPa, mm, N; stretch unitless.
"""

from __future__ import annotations

import json
import os
import warnings

import numpy as np
import pytest
from scipy.optimize import least_squares

from exofric.cli import run
from exofric.errors import InputError, PlausibilityWarning
from exofric.io._material import read_stress_stretch, tensile_stress_stretch
from exofric.material import fit_material, material_model, silicone_uniaxial, treloar_1944

DATA = {k: silicone_uniaxial(k) for k in ("ecoflex-00-30", "dragon-skin-20", "rtv615")}
DATA["treloar-uniaxial"] = treloar_1944()["uniaxial"]
N_PAR = {"neo-hookean": 1, "mooney-rivlin": 2, "yeoh": 3, "ogden1": 2, "ogden2": 4, "ogden3": 6}


def p_uni(name, x, lam):
    """Uniaxial nominal stress (MPa), incompressible, by hand (ABAQUS conventions)."""
    if name == "neo-hookean":
        return 2 * x[0] * (lam - lam**-2)
    if name == "mooney-rivlin":
        return 2 * (lam - lam**-2) * (x[0] + x[1] / lam)
    if name == "yeoh":
        e = lam**2 + 2 / lam - 3
        return 2 * (lam - lam**-2) * (x[0] + 2 * x[1] * e + 3 * x[2] * e**2)
    out = 0.0 * lam
    for mu, a in zip(x[0::2], x[1::2], strict=True):
        out = out + 2 * mu / a * (lam ** (a - 1) - lam ** (-a / 2 - 1))
    return out


def mu_of(name, x):
    """Initial shear modulus (MPa) by hand."""
    if name == "mooney-rivlin":
        return 2 * (x[0] + x[1])
    return sum(x[0::2]) if name.startswith("ogden") else 2 * x[0]


def tangent(name, x, lam, h=1e-6):
    return (p_uni(name, x, lam + h) - p_uni(name, x, lam - h)) / (2 * h)


def admissibility(lam, p):
    """The grid, the tangent floor and the secant modulus of the constraints (by hand)."""
    secant = np.max(np.abs(p)) / np.max(np.abs(lam - 1))
    return np.linspace(1.0, lam.max() * 1.10, 401), 1e-3 * secant, secant


def reference_fit(name, lam, p, n_starts, seed=0):
    """Best admissible RMS (MPa) from random starts, penalty continued to 1e4."""
    grid, tau, secant = admissibility(lam, p)
    n = N_PAR[name]
    lo, hi = np.full(n, -np.inf), np.full(n, np.inf)
    if name.startswith("ogden"):
        lo[1::2], hi[1::2] = -30.0, 30.0
        lo[0::2], hi[0::2] = -100 * secant, 100 * secant
    weight = [1.0]
    scale = np.sqrt(lam.size / grid.size) * np.max(np.abs(p)) / secant

    def res(x):
        with np.errstate(all="ignore"):
            r = p_uni(name, x, lam) - p
            pen = weight[0] * scale * np.minimum(0.0, tangent(name, x, grid) - tau)
            pen_mu = weight[0] * np.sqrt(lam.size) * min(0.0, mu_of(name, x))
        out = np.concatenate([r, pen, [pen_mu]])
        return np.where(np.isfinite(out), out, 1e6)

    rng = np.random.default_rng(seed)
    g = secant / 3
    best = np.inf
    for _ in range(n_starts):
        x = g * rng.uniform(-1, 1, n)
        if name.startswith("ogden"):
            x[1::2] = rng.uniform(-20, 20, n // 2)
        for w in (1.0, 1e2, 1e4):
            weight[0] = w
            x = least_squares(res, np.clip(x, lo + 1e-9, hi - 1e-9), bounds=(lo, hi),
                              xtol=1e-12, ftol=1e-12, gtol=1e-12, max_nfev=1000).x
        if np.all(tangent(name, x, grid) >= tau * (1 - 1e-3)) and mu_of(name, x) > 0:
            best = min(best, float(np.sqrt(np.mean((p_uni(name, x, lam) - p) ** 2))))
    return best


def check_against_reference(name, key, n_starts, ref=None):
    """Ours is admissible by the hand-written check and no worse than the reference by 2 %
    (the reference's RMS ``ref`` as stored, or run here when None)."""
    lam, p = DATA[key]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PlausibilityWarning)
        fit = fit_material(name, uniaxial=(lam, p))
    x = np.asarray(fit.model.params)
    grid, tau, _ = admissibility(lam, p)
    # admissible by the closed forms of this file: mu > 0, dP/dl >= the floor over the range
    # (0.1 % slack: the fit imposes the floor on its own grid, central differences here)
    assert mu_of(name, x) > 0
    assert np.min(tangent(name, x, grid) - tau) >= -1e-3 * tau
    rms = float(np.sqrt(np.mean((p_uni(name, x, lam) - p) ** 2)))
    # the reported RMS is that of the closed form at the reported parameters (1e-9 relative)
    assert fit.modes["uniaxial"].rms_mpa == pytest.approx(rms, rel=1e-9)
    if ref is None:
        ref = reference_fit(name, lam, p, n_starts)
    # within 2 % of the reference's best, or better: a lower RMS is an admissible point of the
    # same problem by the checks above (Ogden-3's landscape is flat: random starts stop high)
    assert rms <= 1.02 * ref, (name, key, rms, ref)
    return fit, rms, ref


@pytest.mark.parametrize("key", list(DATA))
@pytest.mark.parametrize("name", ["neo-hookean", "mooney-rivlin", "yeoh", "ogden1"])
def test_admissible_fit_matches_independent_multistart(name, key):
    check_against_reference(name, key, n_starts=4 if name != "ogden1" else 8)


#: The penalty reference's best admissible RMS (MPa), ``reference_fit(name, lam, p, 12)``
#: (seed 0, this file's closed forms, scipy's least_squares with finite differences): 1-30 s
#: per case, so stored here as a published number would be. ``make bench`` (EXOFRIC_FULL=1)
#: runs the reference again and checks these values (1e-6 relative; the same algorithm,
#: seed and data).
REFERENCE_RMS_MPA = {
    ("ogden2", "ecoflex-00-30"): 0.0028646075635008093,
    ("ogden2", "dragon-skin-20"): 0.011204941535419951,
    ("ogden2", "rtv615"): 0.003421154683687164,
    ("ogden2", "treloar-uniaxial"): 0.06663735717936399,
    ("ogden3", "ecoflex-00-30"): 0.00032500764934828607,
    ("ogden3", "dragon-skin-20"): 0.00360610066266379,
    ("ogden3", "rtv615"): 0.0022900073410855497,
    ("ogden3", "treloar-uniaxial"): 0.04863015511570367,
}
FULL = bool(os.environ.get("EXOFRIC_FULL"))


@pytest.mark.parametrize("name,key", list(REFERENCE_RMS_MPA))
def test_ogden_fit_matches_independent_multistart(name, key):
    """Ogden 2 and 3 on every curve: admissible by this file's checks and within 2 % of the
    stored reference's RMS or lower (issue 37: Ogden-3 fits in < 1 s, back in the suite)."""
    stored = REFERENCE_RMS_MPA[name, key]
    if FULL:  # the stored value is the reference's (12 random starts, ~1-30 s)
        lam, p = DATA[key]
        assert reference_fit(name, lam, p, 12) == pytest.approx(stored, rel=1e-6)
    check_against_reference(name, key, n_starts=12, ref=stored)


def test_mooney_rivlin_on_silicone_is_admissible_and_flagged():
    """Issue 31: the unconstrained optimum has C10 + C01 < 0 (refused before); now the fit is
    admissible, C10 + C01 > 0, and says it is constrained; the unconstrained fit still fails."""
    for key in ("ecoflex-00-30", "dragon-skin-20", "rtv615"):
        lam, p = DATA[key]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", PlausibilityWarning)
            fit = fit_material("mooney-rivlin", uniaxial=(lam, p))
        c10, c01 = fit.model.params
        assert c10 + c01 > 0 and fit.constrained and fit.admissible
        assert fit.active_constraints and fit.to_dict()["constrained"] is True
        a = np.column_stack([2 * (lam - lam**-2), 2 * (lam - lam**-2) / lam])
        free = np.linalg.lstsq(a, p, rcond=None)[0]  # the unconstrained optimum, by hand
        assert free.sum() < 0
        with pytest.raises(InputError):
            fit_material("mooney-rivlin", uniaxial=(lam, p), constrain=False)


def test_unmeasured_mode_instability_warns_not_refuses():
    """Yeoh on Dragon Skin 20 uniaxial data: stable in uniaxial tension, unstable in
    equibiaxial tension (never measured) -> a warning and the report says so; the check of
    that stretch by hand: the biaxial P = 2 (l - l^-5) W1 (Yeoh) falls there."""
    lam, p = DATA["dragon-skin-20"]
    with pytest.warns(PlausibilityWarning, match="biaxial \\(not measured\\)"):
        fit = fit_material("yeoh", uniaxial=(lam, p))
    rep = fit.stability_report
    assert rep["uniaxial"].measured and rep["uniaxial"].stable
    assert not rep["biaxial"].measured and not rep["biaxial"].stable
    c10, c20, c30 = fit.model.params
    lb = rep["biaxial"].unstable_from

    def p_bi(x):
        e = 2 * x**2 + x**-4 - 3
        return 2 * (x - x**-5) * (c10 + 2 * c20 * e + 3 * c30 * e**2)

    assert p_bi(lb + 1e-3) < p_bi(lb - 1e-3) or p_bi(lb + 2e-2) < p_bi(lb)
    # a report range inside the stable part: no such warning
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        fit2 = fit_material("yeoh", uniaxial=(lam, p), stability_range=(1.0, 0.9 * lb))
    assert fit2.stability_report["biaxial"].stable
    assert not any("not measured" in str(w.message) for w in caught)


def test_multistart_reported():
    lam, p = DATA["rtv615"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PlausibilityWarning)
        fit = fit_material("ogden", uniaxial=(lam, p), terms=2)
    ms = fit.multistart
    assert fit.model.name == "ogden2" and ms["n_starts"] >= 10
    assert ms["rms_min_mpa"] <= ms["rms_median_mpa"] <= ms["rms_max_mpa"]
    assert ms["rms_min_mpa"] == pytest.approx(fit.modes["uniaxial"].rms_mpa, rel=1e-3)
    with pytest.raises(InputError, match="terms"):
        fit_material("yeoh", uniaxial=(lam, p), terms=2)
    with pytest.raises(InputError, match="terms"):
        fit_material("ogden", uniaxial=(lam, p), terms=4)


def test_kernels_against_models_and_finite_differences():
    """The fit's vectorised stresses equal HyperelasticModel's principal-stretch forms (1e-12)
    and their Jacobians central differences (1e-6)."""
    from exofric.material._kernels import stress_jac

    lam = np.linspace(0.6, 5.0, 40)
    for name, x in (("mooney-rivlin", [0.2, 0.05]), ("yeoh", [0.19, -0.0019, 4.1e-5]),
                    ("ogden3", [0.4, 1.3, 0.003, 5.0, -0.01, -2.0])):
        m = material_model(name, x)
        for mode in ("uniaxial", "biaxial", "planar"):
            p, jac = stress_jac(name, mode, lam, np.array(x))
            np.testing.assert_allclose(p, m.stress_mpa(mode, lam), rtol=1e-12, atol=1e-14)
            for k in range(len(x)):
                h = 1e-6 * max(1.0, abs(x[k]))
                d = np.zeros(len(x))
                d[k] = h
                fd = (stress_jac(name, mode, lam, np.array(x) + d)[0]
                      - stress_jac(name, mode, lam, np.array(x) - d)[0]) / (2 * h)
                np.testing.assert_allclose(jac[:, k], fd, rtol=1e-6, atol=1e-9)


# --- tensile files as machines write them ---------------------------------------------------


def test_load_extension_by_hand(tmp_path):
    """Load 3 N on 6 mm^2 = 0.5 MPa; 12.5 mm on a 25 mm gauge = stretch 1.5 (by hand)."""
    f = tmp_path / "machine.csv"
    f.write_text("Instron Bluehill export\nSpecimen;ASTM D412\n\n"
                 "Time (s);Extension [mm];Load (kN)\n0;0;0\n1;12,5;0,003\n2;25;0,006\n")
    df = read_stress_stretch(f, gauge_length_mm=25, area_mm2=6)
    np.testing.assert_allclose(df["stretch"], [1.0, 1.5, 2.0], rtol=1e-15)
    np.testing.assert_allclose(df["stress_mpa"], [0.0, 0.5, 1.0], rtol=1e-12)
    assert df.attrs["stress_kind"] == "engineering"
    roles = {c["role"]: c for c in df.attrs["columns"]}
    assert roles["force"]["unit"] == "kN" and roles["force"]["factor"] == pytest.approx(1000)
    assert any("25 mm gauge length" in c for c in df.attrs["conversion"])
    # width x thickness = area; a '# key:' line supplies a size the options do not
    g = tmp_path / "sizes.csv"
    g.write_text("# gauge_length_mm: 20\nextension_mm,force_n\n0,0\n10,4\n")
    df = read_stress_stretch(g, width_mm=2, thickness_mm=4)
    np.testing.assert_allclose(df["stretch"], [1.0, 1.5])
    np.testing.assert_allclose(df["stress_mpa"], [0.0, 0.5])


@pytest.mark.parametrize("header,values,stretch,stress", [
    ("Strain (%),Stress (kPa)", "50,100", 1.5, 0.1),
    ("strain_pct,stress_psi", "100,145.0377", 2.0, 1.0),     # 145.0377 psi = 1.000000 MPa
    ("Engineering Strain,Engineering Stress (MPa)", "0.25,2", 1.25, 2.0),
    ("True Strain,True Stress (N/mm^2)", f"{float(np.log(2.0))!r},3", 2.0, 3.0),
])
def test_header_units_and_kinds(tmp_path, header, values, stretch, stress):
    f = tmp_path / "u.csv"
    f.write_text(f"{header}\n0,0\n{values}\n")
    df = read_stress_stretch(f)
    assert df["stretch"].iloc[-1] == pytest.approx(stretch, rel=1e-12)
    assert df["stress_mpa"].iloc[-1] == pytest.approx(stress, rel=1e-6)
    assert df.attrs["stress_kind"] == ("true" if "True" in header else "engineering")


def test_engineering_and_true_round_trip(tmp_path):
    """One closed-form neo-Hookean curve (C10 = 0.3 MPa) written as engineering strain/stress
    and as true strain/stress (ln l, sigma = l P): both files fit to C10 = 0.3 (1e-9)."""
    lam = np.linspace(1.05, 4.0, 30)
    p = 2 * 0.3 * (lam - lam**-2)
    eng, tru = tmp_path / "eng.csv", tmp_path / "true.csv"
    eng.write_text("strain,stress_mpa\n" + "".join(f"{a - 1:.17g},{b:.17g}\n"
                                                   for a, b in zip(lam, p, strict=True)))
    tru.write_text("True Strain,True Stress (MPa)\n" + "".join(
        f"{np.log(a):.17g},{a * b:.17g}\n" for a, b in zip(lam, p, strict=True)))
    a, b = read_stress_stretch(eng), read_stress_stretch(tru)
    np.testing.assert_allclose(b["stretch"], lam, rtol=1e-14)
    assert b.attrs["stress_kind"] == "true" and b.attrs["strain_kind"] == "true"
    fa = fit_material("neo-hookean", uniaxial=(a["stretch"], a["stress_mpa"]))
    fb = fit_material("neo-hookean", uniaxial=(b["stretch"], b["stress_mpa"]),
                      stress_kind=b.attrs["stress_kind"])
    assert fa.model.params[0] == pytest.approx(0.3, rel=1e-9)
    assert fb.model.params[0] == pytest.approx(0.3, rel=1e-9)
    # declaring the opposite of the header is an error, not a silent reinterpretation
    with pytest.raises(InputError, match="contradicts"):
        read_stress_stretch(tru, "engineering")


def test_pure_conversion_and_errors():
    import pandas as pd

    df = pd.DataFrame({"F": [0.0, 2.0], "e": [0.0, 0.5]})
    out = tensile_stress_stretch(df, {"force": "F", "strain": "e"}, {"F": "N"}, area_mm2=4.0)
    assert out["stress_mpa"].tolist() == [0.0, 0.5] and out["stretch"].tolist() == [1.0, 1.5]
    with pytest.raises(InputError, match="area_mm2 is required"):
        tensile_stress_stretch(df, {"force": "F", "strain": "e"})
    with pytest.raises(InputError, match="cannot be converted"):
        tensile_stress_stretch(df, {"force": "F", "strain": "e"}, {"F": "kg"}, area_mm2=1.0)
    with pytest.raises(InputError, match="stress_kind true does not apply"):
        tensile_stress_stretch(df, {"force": "F", "strain": "e"}, area_mm2=1.0,
                               stress_kind="true")


def test_columns_mapping_for_odd_headers(tmp_path):
    f = tmp_path / "odd.csv"
    f.write_text("Kraft (N),Weg (mm)\n0,0\n6,10\n")
    with pytest.raises(InputError, match="'stretch' or 'strain'"):
        read_stress_stretch(f, area_mm2=6)
    df = read_stress_stretch(f, area_mm2=6, gauge_length_mm=20,
                             columns={"force": "Kraft (N)", "extension": "weg (mm)"})
    np.testing.assert_allclose(df["stress_mpa"], [0.0, 1.0])
    np.testing.assert_allclose(df["stretch"], [1.0, 1.5])


def test_cli_ogden3_on_load_extension_file(capsys, tmp_path):
    """The issue's command on a load/extension file: ogden3 from load (N) and extension (mm),
    the columns listed in --json, the parameters those of the API on hand-converted data."""
    true = material_model("ogden3", [0.004, 5.0, 0.4, 1.3, 0.0098, -2.0])
    lam = np.linspace(1.02, 5.0, 60)
    force = true.uniaxial_stress_mpa(lam) * 6.0          # N on 6 mm^2
    ext = (lam - 1.0) * 25.0                              # mm on a 25 mm gauge
    f = tmp_path / "curve.csv"
    f.write_text("Time (s),Extension (mm),Load (N)\n" + "".join(
        f"{i * 0.1:.1f},{e:.12g},{v:.12g}\n" for i, (e, v) in enumerate(zip(ext, force,
                                                                            strict=True))))
    code = run(["material", "--fit", str(f), "--model", "ogden", "--terms", "3",
                "--gauge-length", "25", "--area", "6", "--json"])
    d = json.loads(capsys.readouterr().out)
    assert code == 0 and d["model"] == "ogden3"
    used = {c["role"]: c for c in d["columns"]["uniaxial"] if c["used"]}
    assert used["force"]["column"] == "Load (N)"
    assert used["extension"]["column"] == "Extension (mm)"
    ux = d["modes"]["uniaxial"]
    assert ux["gauge_length_mm"] == 25 and ux["area_mm2"] == 6
    assert d["modes"]["uniaxial"]["rms_mpa"] < 1e-6                 # noise-free planted data
    for k in ("constrained", "admissible", "stability_modes", "multistart"):
        assert k in d
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ext_r = np.array([float(f"{e:.12g}") for e in ext])
        force_r = np.array([float(f"{v:.12g}") for v in force])
        api = fit_material("ogden3", uniaxial=(1 + ext_r / 25, force_r / 6))
    assert list(d["params"].values()) == pytest.approx(list(api.model.params), rel=1e-6)


@pytest.mark.parametrize("args,needle", [
    (["--area", "6"], "--gauge-length is required"),
    (["--gauge-length", "25"], "--area is required"),
    (["--gauge-length", "25", "--area", "6", "--width", "2"], "--area"),
    (["--gauge-length", "25", "--area", "6", "--terms", "2"], "--terms"),
    (["--gauge-length", "25", "--area", "6", "--columns", "force"], "--columns"),
    (["--gauge-length", "25", "--area", "6", "--stability-range", "3,1"], "--stability-range"),
])
def test_cli_tensile_errors_one_line(args, needle, capsys, tmp_path):
    f = tmp_path / "c.csv"
    f.write_text("Extension (mm),Load (N)\n0,0\n5,1\n10,2\n20,3\n")
    code = run(["material", "--fit", str(f), "--model", "yeoh", *args])
    out, err = capsys.readouterr()
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert code == 2 and out == "" and len(lines) == 1 and needle in lines[0], err


def test_both_measures_in_one_file(tmp_path):
    """A database file with a preamble and both measures (the Soft Robotics Materials Database
    layout): engineering by default, true when declared; the same stretches either way
    (ln(1 + e) = true strain by hand), the unused pair and the time column listed."""
    e = np.array([0.1, 0.5, 1.0])
    s = np.array([0.05, 0.2, 0.4])
    f = tmp_path / "db.csv"
    f.write_text("PARAMETER;INFO;;;\nSpecimen Width (mm);6;;;\n;;;;\n"
                 "Time (s);True Strain;True Stress (MPa);Engineering Strain;"
                 "Engineering Stress (MPa)\n" + "".join(
                     f"{i};{float(np.log1p(a))!r};{b * (1 + a)!r};{a!r};{b!r}\n"
                     for i, (a, b) in enumerate(zip(e.tolist(), s.tolist(), strict=True))))
    eng = read_stress_stretch(f)
    tru = read_stress_stretch(f, "true", strain_kind="true")
    np.testing.assert_allclose(eng["stretch"], 1 + e, rtol=1e-15)
    np.testing.assert_allclose(tru["stretch"], 1 + e, rtol=1e-14)
    np.testing.assert_allclose(tru["stress_mpa"] / tru["stretch"], s, rtol=1e-14)
    used = {c["column"]: c["used"] for c in eng.attrs["columns"]}
    assert used == {"Engineering Strain": True, "Engineering Stress (MPa)": True,
                    "True Strain": False, "True Stress (MPa)": False, "Time (s)": False}


def test_specimen_sizes_are_bounded_and_an_unused_area_is_said() -> None:
    # issue 38: `material --fit f.csv --area 1e300` exited 0 and ignored the area. A size
    # beyond any specimen is an error naming it; an area with a stress column is not used:
    # a warning says so; the stress is read as written.
    import warnings

    import pandas as pd

    from exofric.io import tensile_stress_stretch

    f = pd.DataFrame({"stretch": [1.0, 1.5, 2.0], "stress_mpa": [0.0, 0.5, 1.0]})
    cols = {"stretch": "stretch", "stress": "stress_mpa"}
    with pytest.raises(InputError, match=r"area_mm2 must be in \(0, 1e\+06\]") as exc:
        tensile_stress_stretch(f, cols, area_mm2=1e300)
    assert exc.value.param == "area_mm2"
    with pytest.raises(InputError, match="gauge_length_mm"):
        tensile_stress_stretch(f, cols, gauge_length_mm=-1.0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = tensile_stress_stretch(f, cols, area_mm2=6.0)
    assert out["stress_mpa"].tolist() == [0.0, 0.5, 1.0]
    assert any(issubclass(w.category, PlausibilityWarning) and "not used" in str(w.message)
               for w in caught)
