"""Hyperelastic models (exofric.material.material_model): closed forms, energy, consistency.

References are independent of the code: closed forms of the incompressible homogeneous tests
written out here by hand (Treloar / Ogden textbook forms, e.g. Ogden, Non-linear Elastic
Deformations, 1984, Sec. 7.2), central finite differences of the strain energy along each
mode's kinematics, and identities between models. Units: MPa, stretch unitless.
"""

from __future__ import annotations

import numpy as np
import pytest

from exofric.errors import InputError
from exofric.material import HYPERELASTIC_MODELS, MODES, MooneyRivlin, material_model

L = np.linspace(0.45, 5.0, 60)  # compression and tension

# --- hand-derived nominal stresses P(l), incompressible ---------------------------------------


def nh(c10, mode, lam):
    # W = C10 (I1 - 3): P = 2 C10 (l - l^-2), (l - l^-5), (l - l^-3)
    e = {"uniaxial": -2.0, "biaxial": -5.0, "planar": -3.0}[mode]
    return 2.0 * c10 * (lam - lam**e)


def mr(c10, c01, mode, lam):
    if mode == "uniaxial":
        return 2.0 * (lam - lam**-2) * (c10 + c01 / lam)
    if mode == "biaxial":
        return 2.0 * (lam - lam**-5) * (c10 + c01 * lam**2)
    return 2.0 * (lam - lam**-3) * (c10 + c01)


def yeoh(c, mode, lam):
    i1 = {"uniaxial": lam**2 + 2.0 / lam, "biaxial": 2.0 * lam**2 + lam**-4,
          "planar": lam**2 + 1.0 + lam**-2}[mode]
    w1 = c[0] + 2.0 * c[1] * (i1 - 3.0) + 3.0 * c[2] * (i1 - 3.0) ** 2
    e = {"uniaxial": -2.0, "biaxial": -5.0, "planar": -3.0}[mode]
    return 2.0 * w1 * (lam - lam**e)


def ogden(mus, alphas, mode, lam):
    # W = sum 2 mu/a^2 (l1^a + l2^a + l3^a - 3): P = sum 2 mu/a (l^(a-1) - l^(k a - 1))
    k = {"uniaxial": -0.5, "biaxial": -2.0, "planar": -1.0}[mode]
    return sum(2.0 * m / a * (lam ** (a - 1.0) - lam ** (k * a - 1.0))
               for m, a in zip(mus, alphas, strict=True))


CASES = [
    ("neo-hookean", [0.31], lambda mode, lam: nh(0.31, mode, lam)),
    ("mooney-rivlin", [0.4, 0.07], lambda mode, lam: mr(0.4, 0.07, mode, lam)),
    ("yeoh", [0.19, -0.0019, 4.1e-5], lambda mode, lam: yeoh([0.19, -0.0019, 4.1e-5], mode, lam)),
    ("ogden1", [0.5, 2.7], lambda mode, lam: ogden([0.5], [2.7], mode, lam)),
    ("ogden2", [0.5, 1.5, 0.01, 5.0],
     lambda mode, lam: ogden([0.5, 0.01], [1.5, 5.0], mode, lam)),
    ("ogden3", [0.40, 1.3, 0.003, 5.0, -0.0098, -2.0],
     lambda mode, lam: ogden([0.40, 0.003, -0.0098], [1.3, 5.0, -2.0], mode, lam)),
]


@pytest.mark.parametrize("name,params,ref", CASES, ids=[c[0] for c in CASES])
@pytest.mark.parametrize("mode", MODES)
def test_closed_forms(name, params, ref, mode):
    """Engineering and true stress against the hand-derived forms (rounding only: 1e-12)."""
    m = material_model(name, params)
    p_ref = ref(mode, L)
    np.testing.assert_allclose(m.stress_mpa(mode, L), p_ref, rtol=1e-12, atol=1e-14)
    # Cauchy stress in the loaded direction: sigma = l P (load / deformed area)
    np.testing.assert_allclose(m.stress_mpa(mode, L, "true"), L * p_ref, rtol=1e-12, atol=1e-14)
    method = getattr(m, f"{mode}_stress_mpa")
    np.testing.assert_allclose(method(L), p_ref, rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize("name,params,ref", CASES, ids=[c[0] for c in CASES])
@pytest.mark.parametrize("mode", MODES)
def test_stress_is_the_energy_derivative(name, params, ref, mode):
    """P = dW/dl along the mode's isochoric kinematics, by central differences of W
    (equibiaxial: both in-plane stresses work, dW = 2 P dl).

    h = 1e-5: truncation ~h^2 W''' ~ 1e-10 MPa, rounding ~1e-16 W / h ~ 1e-11 MPa; 1e-7
    relative (plus 1e-9 MPa near l = 1 where P -> 0) bounds both.
    """
    m = material_model(name, params)
    kin = {"uniaxial": lambda x: (x, x**-0.5, x**-0.5), "biaxial": lambda x: (x, x, x**-2),
           "planar": lambda x: (x, np.ones_like(x), 1.0 / x)}[mode]
    h = 1e-5
    fd = (m.strain_energy_mpa(*kin(L + h)) - m.strain_energy_mpa(*kin(L - h))) / (2 * h)
    fd /= 2.0 if mode == "biaxial" else 1.0
    np.testing.assert_allclose(m.stress_mpa(mode, L), fd, rtol=1e-7, atol=1e-9)


def test_tangent_is_the_stress_derivative():
    """dP/dl (complex step) against central differences of the stress (1e-7 relative)."""
    m = material_model("ogden3", [0.40, 1.3, 0.003, 5.0, -0.0098, -2.0])
    h = 1e-6
    for mode in MODES:
        fd = (m.stress_mpa(mode, L + h) - m.stress_mpa(mode, L - h)) / (2 * h)
        np.testing.assert_allclose(m.tangent_mpa(mode, L), fd, rtol=1e-7, atol=1e-8)


def test_volumetric_term_and_bulk_convention():
    """W at pure dilatation is (J - 1)^2 / d only (the isochoric part vanishes); K = 2/d."""
    m = material_model("yeoh", [0.19, -0.0019, 4.1e-5], d=0.02)
    s = np.array([0.9, 1.0, 1.05])
    np.testing.assert_allclose(m.strain_energy_mpa(s, s, s), (s**3 - 1) ** 2 / 0.02,
                               rtol=1e-12, atol=1e-15)
    assert m.bulk_modulus_mpa == pytest.approx(100.0)
    # default d: the paper's Eq 6, d = (1 - 2 nu) / (C10 + C01) = 2 (1 - 2 nu) / mu, nu = 0.498
    assert material_model("neo-hookean", [0.3]).d_per_mpa == pytest.approx(0.004 / 0.3)


def test_ogden_reduces_to_neo_hookean_and_mooney_rivlin():
    """Ogden N=1, alpha=2 is neo-Hookean with C10 = mu/2; Ogden (2, -2) is Mooney-Rivlin
    with C10 = mu1/2, C01 = mu2/2 (sum l^-2 = I2 at J = 1); also the energies."""
    o1, n = material_model("ogden1", [0.6, 2.0]), material_model("neo-hookean", [0.3])
    o2, mrm = material_model("ogden2", [0.6, 2.0, 0.1, -2.0]), material_model(
        "mooney-rivlin", [0.3, 0.05])
    for a, b in ((o1, n), (o2, mrm)):
        assert a.shear_modulus_mpa == pytest.approx(b.shear_modulus_mpa, rel=1e-15)
        for mode in MODES:
            np.testing.assert_allclose(a.stress_mpa(mode, L), b.stress_mpa(mode, L), rtol=1e-12,
                                       atol=1e-14)
        x = (L, L**-0.3, L**-0.7)  # isochoric, non-symmetric
        np.testing.assert_allclose(a.strain_energy_mpa(*x), b.strain_energy_mpa(*x),
                                   rtol=1e-12, atol=1e-14)


def test_mooney_rivlin_class_and_model_agree():
    """MooneyRivlin.to_model keeps C10, C01, d; back again gives the same MooneyRivlin."""
    mat = MooneyRivlin.from_shore(62.5)
    m = mat.to_model()
    assert m.params == (mat.c10_mpa, mat.c01_mpa) and m.d_per_mpa == mat.d_per_mpa
    assert m.shear_modulus_mpa == pytest.approx(mat.shear_modulus, rel=1e-15)
    assert m.bulk_modulus_mpa == pytest.approx(mat.bulk_modulus, rel=1e-15)
    assert m.to_mooney_rivlin() == MooneyRivlin(mat.c10_mpa, mat.c01_mpa, mat.d_per_mpa)
    with pytest.raises(InputError, match="no Mooney-Rivlin form"):
        material_model("yeoh", [0.2, 0.0, 0.0]).to_mooney_rivlin()


def test_stability_against_the_closed_form_limit():
    """MR biaxial P = 2(l - l^-5)(C10 + C01 l^2) with C01 < 0 falls to 0 at
    l = sqrt(-C10/C01): the tangent turns negative before that; neo-Hookean is stable."""
    m = material_model("mooney-rivlin", [0.3, -0.01])
    zero = np.sqrt(0.3 / 0.01)
    check = m.stability(0.5, zero + 0.5)
    assert not check.stable
    assert 1.0 < check.unstable_from["biaxial"] < zero
    assert check.unstable_from["uniaxial"] is None or check.unstable_from["uniaxial"] > 1.0
    assert m.stability(0.5, 2.0).stable           # well below the limit
    assert material_model("neo-hookean", [0.3]).stability(0.2, 10.0).stable
    assert check.to_dict()["stable"] is False


def test_names_and_parameter_counts_are_checked():
    with pytest.raises(InputError) as e:
        material_model("arruda-boyce", [1.0])
    msg = str(e.value)
    assert "\n" not in msg and all(n in msg for n in HYPERELASTIC_MODELS)
    with pytest.raises(InputError, match=r"yeoh takes 3 parameters .*got 2"):
        material_model("yeoh", [0.2, 0.1])
    with pytest.raises(InputError, match="ogden takes 2, 4 or 6"):
        material_model("ogden", [0.2, 0.1, 0.3])
    assert material_model("Ogden", [0.2, 2.0]).name == "ogden1"
    with pytest.raises(InputError, match="shear modulus"):
        material_model("neo-hookean", [-0.1])
    with pytest.raises(InputError, match="nonzero"):
        material_model("ogden1", [0.3, 0.0])
    with pytest.raises(InputError, match="stretch"):
        material_model("neo-hookean", [0.3]).uniaxial_stress_mpa([1.0, -1.0])
    with pytest.raises(InputError, match="kind"):
        material_model("neo-hookean", [0.3]).uniaxial_stress_mpa(1.2, kind="cauchy")
    with pytest.raises(InputError, match="d must"):
        material_model("neo-hookean", [0.3], d=-1.0)


def test_to_dict_names_units():
    d = material_model("ogden2", [0.5, 1.5, 0.01, 5.0]).to_dict()
    assert d["model"] == "ogden2"
    assert list(d["params"]) == ["mu1_mpa", "alpha1", "mu2_mpa", "alpha2"]
    assert d["shear_modulus_mpa"] == pytest.approx(0.51)


# --- issue 38: Drucker-unstable parameters refused before an FE solve ------------------------

#: Unstable parameter sets per family with their hand-written stresses; the FE check covers
#: principal stretches 0.4-2.5. A neo-Hookean with mu > 0 is stable at every stretch and an
#: Ogden-1 with mu > 0 from ~2.5 on at the nearest (planar: l^(2a) = (1 + a)/(1 - a), >= e),
#: so Ogden-1 is the warning's case below.
UNSTABLE = [
    ("mooney-rivlin", [0.5, -0.3], lambda mode, lam: mr(0.5, -0.3, mode, lam)),
    ("mooney-rivlin", [-0.1, 0.4], lambda mode, lam: mr(-0.1, 0.4, mode, lam)),
    ("yeoh", [0.3, -0.1, 0.001], lambda mode, lam: yeoh([0.3, -0.1, 0.001], mode, lam)),
    ("ogden2", [1.0, 2.0, -0.6, 4.0], lambda mode, lam: ogden([1.0, -0.6], [2.0, 4.0], mode,
                                                              lam)),
    ("ogden3", [0.5, 2.0, -0.3, 4.0, 0.01, -2.0],
     lambda mode, lam: ogden([0.5, -0.3, 0.01], [2.0, 4.0, -2.0], mode, lam)),
]
FE_RANGE = {"uniaxial": (0.4, 2.5), "biaxial": (0.4**0.5, 2.5**0.5), "planar": (0.4, 2.5)}
PATH = {"uniaxial": "uniaxial", "biaxial": "equibiaxial", "planar": "planar"}


def unstable_runs(ref, mode):
    """Stretch intervals of the FE range where the hand-written P falls (central
    differences, h = 1e-6, on 20,001 stretches evenly spaced in ln l)."""
    lam = np.geomspace(*FE_RANGE[mode], 20001)
    bad = (ref(mode, lam + 1e-6) - ref(mode, lam - 1e-6)) <= 0.0
    idx = np.flatnonzero(bad)
    runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1) if idx.size else []
    return [(lam[r[0]], lam[r[-1]]) for r in runs]


@pytest.mark.parametrize("name,params,ref", UNSTABLE, ids=[f"{c[0]}-{c[1]}" for c in UNSTABLE])
def test_fe_stability_names_parameters_and_unstable_range(name, params, ref):
    """The refusal names the model, every parameter and, per path, the unstable stretches,
    which agree with the hand-written forms' (3 significant digits as printed; the check's
    801-point grid spaces stretches 0.23 % apart, so 0.5 % relative)."""
    import re

    m = material_model(name, params)
    with pytest.raises(InputError) as e:
        m.check_fe_stability()
    msg = str(e.value)
    assert e.value.param == "params" and "\n" not in msg and msg.startswith(f"params: {name} (")
    for n in m.param_names:
        assert (n[:-4].upper() if n.startswith("c") else n.removesuffix("_mpa")) in msg
    for mode in MODES:
        runs = unstable_runs(ref, mode)
        num = r"\d+(?:\.\d+)?(?:e[+-]?\d+)?"
        clause = re.search(rf"{PATH[mode]} at stretch ({num}-{num}(?: and {num}-{num})*)", msg)
        assert (clause is None) == (not runs), (mode, runs, msg)
        if runs:
            printed = [tuple(float(v) for v in part.split("-"))
                       for part in clause.group(1).split(" and ")]
            assert len(printed) == len(runs), (printed, runs)
            np.testing.assert_allclose(np.ravel(printed), np.ravel(runs), rtol=5e-3)


def test_fe_stability_passes_stable_models_and_covers_the_fe_entry():
    """Stable parameter sets (the published ones of this file, the paper's Mooney-Rivlin, a
    neo-Hookean) pass; an unstable one is refused where every FE problem takes its material
    (SqueezeSetup: no solve), and a MooneyRivlin is refused naming c10 and c01."""
    from exofric.geometry import BASE
    from exofric.simulate import SqueezeSetup

    for name, params, _ in CASES:
        material_model(name, params).check_fe_stability()
    MooneyRivlin.from_shore(62.5).check_fe_stability()
    with pytest.raises(InputError, match=r"params: ogden2 \(mu1 = 1 MPa, alpha1 = 2"):
        SqueezeSetup(BASE, material_model("ogden2", [1.0, 2.0, -0.6, 4.0]))
    with pytest.raises(InputError, match=r"c10, c01: mooney-rivlin \(C10 = 0.5 MPa, "
                                         r"C01 = -0.3 MPa\).*uniaxial at stretch 0.4-0.74"):
        SqueezeSetup(BASE, MooneyRivlin(0.5, -0.3, 0.005))
    with pytest.raises(InputError, match="stretch_max"):
        material_model("neo-hookean", [0.3]).check_fe_stability(stretch_max=1.0)


def test_fe_stability_warns_beyond_the_validated_range():
    """Ogden-1 with alpha = 0.5: planar P = 4 mu (l^-0.5 - l^-1.5) peaks at l = 3 (by hand:
    dP/dl = 0 at l^-1 = 1/3), beyond 2.5: not refused, a warning names that stretch (or
    1/3, the same planar state)."""
    from exofric.errors import PlausibilityWarning

    with pytest.warns(PlausibilityWarning, match=r"planar stretch (3\.0|2\.99|0\.33)"):
        material_model("ogden1", [0.6, 0.5]).check_fe_stability()


@pytest.mark.parametrize("args,flag", [
    (["--model", "ogden", "--params", "1,2,-0.6,4"], "--params"),
    (["--model", "yeoh", "--params", "0.3,-0.1,0.001"], "--params"),
    (["--c10", "0.5", "--c01", "-0.3", "--d", "0.005"], "--c10, --c01"),
])
def test_cli_unstable_params_exit_2_one_line(args, flag, capsys):
    """Issue 38: `squeeze --model ... --params ...` with Drucker-unstable constants stops at
    once with one line naming the option and the unstable stretches (exit 2), not a Newton
    failure."""
    from exofric.cli import run

    code = run(["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire",
                "1.6", "--accuracy", "draft", *args])
    out, err = capsys.readouterr()
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert code == 2 and out == "" and len(lines) == 1, err
    assert f"{flag}: " in lines[0] and "Drucker-unstable" in lines[0] and "at stretch" in lines[0]
