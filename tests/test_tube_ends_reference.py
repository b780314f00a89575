"""The incompressible closed/open-end tube reference (``tube_inflation``) against independent ones.

``tube_inflation`` solves the generalised-plane-strain inflation of an incompressible thick tube
(uniform axial stretch l_z; closed ends: wall axial force P pi a^2, open ends: 0). Each test
compares it with a reference that does not share its code path:

1. plane strain: the existing closed form ``incompressible_inflation`` (1e-8 relative: both are
   solved to ~1e-14; the margin covers root-finder tolerances);
2. small pressure: the linear Lame thick cylinder with nu = 0.5 (E = 3 mu);
3. thin wall: the closed-end membrane (hoop P r/t, axial P r/(2t)) solved here separately;
4. closed ends stretch the tube (l_z > 1) and feel C01 at fixed C10 + C01; plane strain does not;
5. Ogden with one term alpha = 2 is neo-Hookean with C10 = mu/2;
6. the equilibrium integrals recomputed by adaptive quadrature from finite differences of the
   material's own ``strain_energy_mpa`` (not the reference's closed-form derivatives);
7. bad inputs raise InputError, pressures past the limit ConvergenceError.

Units: mm, MPa.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import fsolve

from exofric.errors import ConvergenceError, InputError
from exofric.material import MooneyRivlin, material_model
from exofric.simulate._analytic import (
    TubeInflationCurve,
    incompressible_inflation,
    tube_inflation,
)

OD, ID = 8.3, 4.97  # the paper's tube (mm)
A, B = ID / 2, OD / 2
PAPER = MooneyRivlin.from_shore(62.5)  # C10 = 0.6354, C01 = 0.03177 MPa (mu = 1.3344 MPa)
P4 = [0.1, 0.2, 0.3, 0.4]


# --- 1. plane strain = the exact closed form ---------------------------------------------------


@pytest.mark.parametrize("material", [material_model("neo-hookean", [0.5]), PAPER],
                         ids=["neo-hookean", "mooney-rivlin"])
def test_plane_strain_equals_closed_form(material) -> None:
    mu = (material.to_model() if isinstance(material, MooneyRivlin) else material
          ).shear_modulus_mpa
    p = [0.0, 0.05, 0.2, 0.3]
    ref = incompressible_inflation(OD, ID, mu, p)
    got = tube_inflation(OD, ID, material, p, ends="plane-strain")
    np.testing.assert_allclose(got.outer_diameter_mm, ref.outer_diameter_mm, rtol=1e-8)
    np.testing.assert_allclose(got.inner_diameter_mm, ref.inner_diameter_mm, rtol=1e-8)
    assert np.all(got.axial_stretch == 1.0)


# --- 2. small pressure: the Lame cylinder, nu = 0.5 ----------------------------------------------


def test_linear_limit_matches_lame_cylinder() -> None:
    """P = 1e-4 mu: the nonlinear terms are O(P/mu) ~ 1e-4 relative, so 1e-3 holds with margin.

    Lame (E = 3 mu, nu = 1/2): sigma_r = C - D/r^2, sigma_t = C + D/r^2 with
    C = P A^2/(B^2 - A^2), D = C B^2. Closed ends sigma_z = C gives eps_z = 0 exactly (the
    axial strain is second order) and u(B) = 1.5 D / (E B); open ends sigma_z = 0 gives
    eps_z = -C/E and u(B) = B (0.5 C + 1.5 D/B^2) / E.
    """
    mat = material_model("neo-hookean", [0.5])
    mu = 1.0
    E = 3.0 * mu
    p = 1e-4 * mu
    C = p * A**2 / (B**2 - A**2)
    D = C * B**2
    closed = tube_inflation(OD, ID, mat, [p], ends="closed")
    u_closed = closed.outer_diameter_mm[0] / 2 - B
    assert u_closed == pytest.approx(1.5 * D / (E * B), rel=1e-3)
    # linear eps_z = 0: what remains is O((P/mu)^2) ~ 1e-8, far below the linear scale C/E
    assert abs(closed.axial_stretch[0] - 1.0) < 1e-3 * C / E
    opened = tube_inflation(OD, ID, mat, [p], ends="open")
    u_open = opened.outer_diameter_mm[0] / 2 - B
    assert u_open == pytest.approx(B * (0.5 * C + 1.5 * D / B**2) / E, rel=1e-3)
    assert opened.axial_stretch[0] - 1.0 == pytest.approx(-C / E, rel=1e-3)


# --- 3. thin wall: the closed-end membrane ---------------------------------------------------


def _membrane(c10: float, R: float, T: float, pressures: np.ndarray) -> np.ndarray:
    """Closed-end neo-Hookean membrane: (l_t, l_z) per pressure from sigma_t = P r/t and
    sigma_z = P r/(2t), continued from the undeformed state.

    Deformed radius r = l_t R, thickness t = T l_r, l_r = 1/(l_t l_z); plane stress
    (sigma_r = 0): sigma_t = 2 C10 (l_t^2 - l_r^2), sigma_z = 2 C10 (l_z^2 - l_r^2).
    """

    def eqs(x: np.ndarray, p: float) -> list[float]:
        lt, lz = np.exp(x)
        lr = 1.0 / (lt * lz)
        hoop = p * lt * R / (T * lr)
        return [2 * c10 * (lt**2 - lr**2) / hoop - 1.0,
                2 * c10 * (lz**2 - lr**2) / (0.5 * hoop) - 1.0]

    out, x = [], np.zeros(2)
    for p in pressures:
        x = fsolve(eqs, x, args=(p,), xtol=1e-13)
        assert np.max(np.abs(eqs(x, p))) < 1e-10
        out.append(np.exp(x))
    return np.array(out)


def test_thin_wall_closed_ends_match_membrane() -> None:
    """A = 10, B = 10.01 mm (t/R = 1e-3), well into the nonlinear range (l_t up to 1.34).

    Stretches: l_t at the mid-surface ((a + b)/2 over (A + B)/2) and l_z. Thick and membrane
    differ by O(t/R) in general, but at the mid-surface the first-order term cancels:
    measured 2-5e-7 relative in l_t - 1 and l_z - 1, asserted to 2e-5 (O((t/R)^2) with
    margin; far tighter than the O(t/R) = 1e-3 a membrane is guaranteed to). Stresses: the
    wall-mean hoop and axial Cauchy stresses of the thick solution, P a/(b - a) and
    P a^2/(b^2 - a^2) by global equilibrium, against P r/t and P r/(2t) at the membrane's
    mid-surface: they differ by a vs r = O(t/R), so 2e-3.
    """
    c10 = 0.5
    a0, b0 = 10.0, 10.01
    Rm, T = 0.5 * (a0 + b0), b0 - a0
    p = np.array([2e-4, 4e-4, 6e-4, 6.8e-4])  # MPa; mu t/R = 1e-3 MPa
    thick = tube_inflation(2 * b0, 2 * a0, material_model("neo-hookean", [c10]), p)
    memb = _membrane(c10, Rm, T, p)
    a = thick.inner_diameter_mm / 2
    b = thick.outer_diameter_mm / 2
    for i, pi in enumerate(p):
        lt_m, lz_m = memb[i]
        lt = 0.5 * (a[i] + b[i]) / Rm
        assert lt - 1.0 == pytest.approx(lt_m - 1.0, rel=2e-5)
        assert thick.axial_stretch[i] - 1.0 == pytest.approx(lz_m - 1.0, rel=2e-5)
        r, t = lt_m * Rm, T / (lt_m * lz_m)
        assert pi * a[i] / (b[i] - a[i]) == pytest.approx(pi * r / t, rel=2e-3)
        assert pi * a[i] ** 2 / (b[i] ** 2 - a[i] ** 2) == pytest.approx(pi * r / (2 * t),
                                                                          rel=2e-3)
    assert memb[-1, 0] > 1.3  # a real large-strain check


# --- 4. closed ends: axial stretch and the role of C01 ---------------------------------------


def test_closed_ends_stretch_the_paper_tube() -> None:
    c = tube_inflation(OD, ID, PAPER, [0.2, 0.3, 0.4], ends="closed")
    # measured: l_z = 1.0043, 1.0123, 1.0304 at 0.2, 0.3, 0.4 MPa
    assert np.all(c.axial_stretch > 1.0) and np.all(np.diff(c.axial_stretch) > 0)
    o = tube_inflation(OD, ID, PAPER, [0.2, 0.3, 0.4], ends="open")
    assert np.all(o.axial_stretch < 1.0)  # open ends shorten (Poisson-like)
    # closed ends inflate less than plane strain at the same pressure (the tube lengthens)
    ps = tube_inflation(OD, ID, PAPER, [0.2, 0.3, 0.4], ends="plane-strain")
    assert np.all(c.outer_diameter_mm < ps.outer_diameter_mm)
    assert np.all(o.outer_diameter_mm > ps.outer_diameter_mm)


def test_c01_matters_with_closed_ends_only() -> None:
    """Incompressible plane strain sees only C10 + C01 (I1 = I2 there); closed ends do not.

    Measured at 0.4 MPa, same mu = 2 (C10 + C01) = 1.3344 MPa, closed ends:

    * C01 = 0 (neo-Hookean):          OD 9.50076 mm, l_z 1.03430;
    * C01 = 0.05 C10 (the paper's):   OD 9.50115 mm, l_z 1.03039 (+0.0004 mm, +0.004 %: ten
      times below the FE acceptance of 0.05 %, so the paper's small C01 hardly matters);
    * C01 = C10:                      OD 9.57616 mm, l_z 1 exactly (+0.0754 mm, +0.79 %).

    Plane strain: OD 9.57616 mm for all three, to 1e-10. C10 = C01 is a closed-form check:
    then t_i = 2 C10 (l_i^2 - l_i^-2) and at l_z = 1, l_r = 1/l_t, the integrand
    2 (t_z - t_r) - (t_t - t_r) vanishes pointwise, so the closed-end tube stays at l_z = 1 and
    equals plane strain (1e-9: both from root finders at ~1e-12).
    """
    s = PAPER.c10_mpa + PAPER.c01_mpa
    mats = [PAPER.to_model(), material_model("mooney-rivlin", [s, 0.0]),
            material_model("mooney-rivlin", [0.5 * s, 0.5 * s])]
    ps = [tube_inflation(OD, ID, m, P4, ends="plane-strain").outer_diameter_mm for m in mats]
    np.testing.assert_allclose(ps[1], ps[0], rtol=1e-10)
    np.testing.assert_allclose(ps[2], ps[0], rtol=1e-10)
    cl = [tube_inflation(OD, ID, m, P4, ends="closed") for m in mats]
    od = [c.outer_diameter_mm for c in cl]
    assert od[1][-1] == pytest.approx(9.50076, abs=2e-5)
    assert od[0][-1] == pytest.approx(9.50115, abs=2e-5)
    np.testing.assert_allclose(od[2], ps[0], rtol=1e-9)
    np.testing.assert_allclose(cl[2].axial_stretch, 1.0, atol=1e-9)
    # more C01 -> larger OD and less axial stretch with closed ends, at every pressure
    assert np.all(od[1] < od[0]) and np.all(od[0] < od[2])
    assert np.all(cl[1].axial_stretch > cl[0].axial_stretch)


# --- 5. Ogden alpha = 2 is neo-Hookean ---------------------------------------------------------


@pytest.mark.parametrize("ends", ["closed", "open", "plane-strain"])
def test_ogden_alpha2_is_neo_hookean(ends: str) -> None:
    mu = 1.3344
    og = tube_inflation(OD, ID, material_model("ogden1", [mu, 2.0]), P4, ends=ends)
    nh = tube_inflation(OD, ID, material_model("neo-hookean", [mu / 2]), P4, ends=ends)
    np.testing.assert_allclose(og.outer_diameter_mm, nh.outer_diameter_mm, rtol=1e-9)
    np.testing.assert_allclose(og.axial_stretch, nh.axial_stretch, rtol=1e-9)


# --- 6. the equilibrium integrals from the material's own energy -------------------------------


@pytest.mark.parametrize("model", [
    material_model("yeoh", [0.6, -0.01, 0.001]),
    material_model("ogden3", [0.63, 1.3, 0.0012, 5.0, -0.01, -2.0]),
    PAPER.to_model(),
], ids=["yeoh", "ogden3", "mooney-rivlin"])
@pytest.mark.parametrize("ends", ["closed", "open"])
def test_solution_satisfies_equilibrium_from_strain_energy(model, ends: str) -> None:
    """Recompute P and the reduced axial force F = pi int (2 s_zz - s_tt - s_rr) r dr at the
    solution by ``quad`` in r, with s_tt - s_rr = dW/d(ln l_t) and s_zz - s_rr = dW/d(ln l_z)
    along incompressible paths by central differences (h = 1e-5: error ~1e-9 relative) of
    ``HyperelasticModel.strain_energy_mpa``. Closed ends: F = 0; open: F = -P pi a^2.
    Tolerance 1e-7 of P and of mu pi (B^2 - A^2).
    """
    p = 0.2
    c = tube_inflation(OD, ID, model, [p], ends=ends)
    a, b, lz = c.inner_diameter_mm[0] / 2, c.outer_diameter_mm[0] / 2, c.axial_stretch[0]
    h = 1e-5

    def w(lr: float, lt: float, lzz: float) -> float:
        return float(model.strain_energy_mpa(lr, lt, lzz))

    def diffs(r: float) -> tuple[float, float]:
        R = np.sqrt(A * A + lz * (r * r - a * a))
        lt = r / R
        dt = (w(1 / (lt * lz * np.exp(h)), lt * np.exp(h), lz)
              - w(1 / (lt * lz * np.exp(-h)), lt * np.exp(-h), lz)) / (2 * h)
        dz = (w(1 / (lt * lz * np.exp(h)), lt, lz * np.exp(h))
              - w(1 / (lt * lz * np.exp(-h)), lt, lz * np.exp(-h))) / (2 * h)
        return dt, dz

    pq = quad(lambda r: diffs(r)[0] / r, a, b, epsabs=0, epsrel=1e-10)[0]
    f_scale = model.shear_modulus_mpa * np.pi * (B**2 - A**2)
    fq = np.pi * quad(lambda r: (2 * diffs(r)[1] - diffs(r)[0]) * r, a, b,
                      epsabs=1e-10 * f_scale, epsrel=1e-10)[0]
    assert pq == pytest.approx(p, rel=1e-7)
    target = 0.0 if ends == "closed" else -p * np.pi * a * a
    assert abs(fq - target) < 1e-7 * f_scale


# --- 7. inputs, limit pressure, result API ---------------------------------------------------


@pytest.mark.parametrize(("kwargs", "field"), [
    ({"tube_id_mm": 8.3}, "tube_id_mm"),
    ({"tube_id_mm": 9.0}, "tube_id_mm"),
    ({"tube_od_mm": -1.0}, "tube_od_mm"),
    ({"pressures_mpa": [-0.1, 0.2]}, "pressures_mpa"),
    ({"pressures_mpa": [0.3, 0.2]}, "pressures_mpa"),
    ({"pressures_mpa": []}, "pressures_mpa"),
    ({"ends": "capped"}, "ends"),
    ({"material": 1.4}, "material"),
])
def test_bad_inputs_raise_input_error(kwargs: dict, field: str) -> None:
    args = {"tube_od_mm": OD, "tube_id_mm": ID, "material": PAPER, "pressures_mpa": [0.1]}
    args.update(kwargs)
    ends = args.pop("ends", "closed")
    with pytest.raises(InputError) as err:
        tube_inflation(**args, ends=ends)
    msg = str(err.value)
    assert "\n" not in msg and msg.startswith(field)


def test_past_the_limit_pressure_raises_convergence_error() -> None:
    # closed-end limit of the paper's tube: ~0.529 MPa at a/A ~ 2.0 (plane strain: 0.684)
    assert tube_inflation(OD, ID, PAPER, [0.52]).outer_diameter_mm[0] > 10.0
    with pytest.raises(ConvergenceError, match="0.6 MPa") as err:
        tube_inflation(OD, ID, PAPER, [0.2, 0.6])
    assert err.value.reached is not None and 0.5 < err.value.reached < 0.53


def test_result_api() -> None:
    c = tube_inflation(OD, ID, PAPER, [0.0, 0.1], ends="open")
    assert isinstance(c, TubeInflationCurve) and c.ends == "open"
    d = c.to_dict()
    assert set(d) == {"method", "ends", "pressure_mpa", "outer_diameter_mm",
                      "inner_diameter_mm", "axial_stretch"}
    assert d["outer_diameter_mm"][0] == pytest.approx(OD, rel=1e-14)
    assert d["axial_stretch"][0] == 1.0
    df = c.to_frame()
    assert list(df.columns) == ["pressure_mpa", "outer_diameter_mm", "inner_diameter_mm",
                                "axial_stretch"]
    assert len(df) == 2
