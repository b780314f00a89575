"""Hyperelastic models in the FE (issue 16): neo-Hookean, Mooney-Rivlin, Yeoh, Ogden kernels.

* One element under homogeneous plane-strain deformations: the body's nodal forces equal those
  of the closed-form first Piola stress of the same model, written here by hand from W and,
  independently, from finite differences of :meth:`HyperelasticModel.strain_energy_mpa`.
* Element tangents against central finite differences of the element forces.
* Mooney-Rivlin's path unchanged; neo-Hookean = Mooney-Rivlin with C01 = 0 and Yeoh with
  C20 = C30 = 0 = neo-Hookean, through the whole squeeze; Ogden with exponents 2 and -2 is
  Mooney-Rivlin (mu1 = 2 C10, mu2 = 2 C01), also at and near equal stretches.
"""

from __future__ import annotations

import numpy as np
import pytest

from exofric.errors import InputError
from exofric.fe import (
    HyperelasticBody,
    MeshSpec,
    PlaneStrainMaterial,
    mooney_rivlin_plane_strain,
    ogden_plane_strain,
    polar_mesh,
    yeoh_plane_strain,
)
from exofric.geometry import BASE
from exofric.material import MooneyRivlin, material_model
from exofric.simulate import inflate, squeeze

D = 0.02  # 1/MPa: K = 100 MPa, large enough that the volumetric part matters but stays O(1)
MODELS = {
    "neo-hookean": material_model("neo-hookean", [0.4], d=D),
    "mooney-rivlin": material_model("mooney-rivlin", [0.35, 0.05], d=D),
    "yeoh": material_model("yeoh", [0.4, -0.02, 0.004], d=D),
    "ogden3": material_model("ogden", [0.63, 1.3, 0.0012, 5.0, -0.01, -2.0], d=D),
}


def _one_element(kind: str = "quad9"):
    return polar_mesh(2.485, 4.15, 1, 1, kind=kind)  # one curved element


def _u_homogeneous(mesh, F):
    return (mesh.nodes @ (F - np.eye(2)).T).ravel()


def _dW_dl_hand(name, p, l1, l2):
    """dW/dl1, dW/dl2 (MPa) of W = W_iso + (J-1)^2/d at in-plane stretches l1, l2 and l3 = 1,
    written by hand: Ib1 = J^-2/3 (l1^2 + l2^2 + 1), Ib2 = J^-4/3 (l1^2 + l2^2 + l1^2 l2^2)."""
    J = l1 * l2
    if name.startswith("ogden"):  # sum 2 mu / a^2 (J^-a/3 (l1^a + l2^a + 1) - 3)
        out = []
        for li, lo in ((l1, l2), (l2, l1)):
            g = sum(2.0 * mu / al**2 * J ** (-al / 3.0)
                    * (al * li ** (al - 1.0) - al / 3.0 / li * (li**al + lo**al + 1.0))
                    for mu, al in zip(p[0::2], p[1::2], strict=True))
            out.append(g + 2.0 * (J - 1.0) * lo / D)
        return np.array(out)
    s = l1 * l1 + l2 * l2
    a = J ** (-2.0 / 3.0)
    x = a * (s + 1.0) - 3.0
    out = []
    for li, lo in ((l1, l2), (l2, l1)):
        dx = a * (2.0 * li - 2.0 / 3.0 * (s + 1.0) / li)  # d Ib1 / d li
        if name == "yeoh":
            w1 = p[0] + 2.0 * p[1] * x + 3.0 * p[2] * x * x
        else:
            w1 = p[0]
        g = w1 * dx
        if name == "mooney-rivlin":
            i2 = s + J * J
            dy = J ** (-4.0 / 3.0) * (2.0 * li + 2.0 * li * lo * lo - 4.0 / 3.0 * i2 / li)
            g = g + p[1] * dy
        out.append(g + 2.0 * (J - 1.0) * lo / D)
    return np.array(out)


def _dW_dl_fd(model, l1, l2):
    """dW/dl1, dW/dl2 from the material module's own W, by 4th-order central differences
    (truncation ~h^4 W^(5) ~ 1e-13, round-off ~eps W / h ~ 1e-12 for h = 1e-3)."""
    h = 1e-3

    def W(a, b):
        return float(model.strain_energy_mpa(a, b, 1.0))

    def d(f):
        return (-f(2 * h) + 8 * f(h) - 8 * f(-h) + f(-2 * h)) / (12 * h)

    return np.array([d(lambda e: W(l1 + e, l2)), d(lambda e: W(l1, l2 + e))])


def _rot(t):
    return np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])


# in-plane stretch states: uniaxial-like, equibiaxial (equal stretches: Ogden's series branch),
# nearly equibiaxial, compression, and a rotated one
STATES = [(1.3, 0.9, 0.0), (1.2, 1.2, 0.0), (1.2, 1.2001, 0.3), (0.8, 1.05, 0.0),
          (1.25, 0.85, 0.7)]


@pytest.mark.parametrize("name", list(MODELS))
@pytest.mark.parametrize("l1,l2,theta", STATES)
@pytest.mark.parametrize("formulation", ["mixed", "displacement"])
def test_one_element_equals_closed_form(name, l1, l2, theta, formulation):
    model = MODELS[name]
    mesh = _one_element()
    body = HyperelasticBody(mesh, model, formulation)
    R = _rot(theta)
    F = R @ np.diag([l1, l2])
    st = body.evaluate(_u_homogeneous(mesh, F))
    # P = R diag(dW/dl) (objectivity): closed form by hand and from W by differences
    hand = _dW_dl_hand(name, model.params, l1, l2)
    fd = _dW_dl_fd(model, l1, l2)
    np.testing.assert_allclose(hand, fd, rtol=0, atol=1e-9)
    P = R @ np.diag(hand)
    r = body.ref
    f_closed = np.einsum("eq,ij,eqaj->eai", r.w, P, r.dNdX).reshape(1, -1)
    scale = np.abs(f_closed).max()
    assert np.abs(st.fe - f_closed).max() <= 1e-8 * scale
    # the condensed pressure of a homogeneous state is K (J - 1) everywhere
    np.testing.assert_allclose(body.element_pressure(_u_homogeneous(mesh, F)),
                               2.0 / D * (l1 * l2 - 1.0), rtol=1e-10)


@pytest.mark.parametrize("name", list(MODELS))
def test_cauchy_szz_is_the_stretch_derivative(name):
    """sigma_zz = l3 dW/dl3 / J at l3 = 1, from the material module's W by differences."""
    model = MODELS[name]
    mesh = _one_element()
    body = HyperelasticBody(mesh, model)
    l1, l2 = 1.3, 0.9
    u = _u_homogeneous(mesh, np.diag([l1, l2]))
    szz = body.cauchy_stress(u)[..., 3]
    h = 1e-3

    def W(e):
        return float(model.strain_energy_mpa(l1, l2, 1.0 + e))

    dW3 = (-W(2 * h) + 8 * W(h) - 8 * W(-h) + W(-2 * h)) / (12 * h)
    np.testing.assert_allclose(szz, dW3 / (l1 * l2), rtol=1e-8)


@pytest.mark.parametrize("name", list(MODELS))
@pytest.mark.parametrize("kind,formulation", [("quad9", "mixed"), ("quad9", "displacement"),
                                              ("quad4", "mixed")])
def test_element_tangent_against_finite_differences(name, kind, formulation):
    """K = d fe / du against central differences (h = 1e-6 mm): truncation ~h^2 f''' and
    round-off ~eps |f| / h are both ~1e-9 relative to |K|; 1e-6 leaves a wide margin."""
    model = MODELS[name]
    mesh = polar_mesh(2.485, 4.15, 2, 2, kind=kind)
    body = HyperelasticBody(mesh, model, formulation)
    rng = np.random.default_rng(7)
    # a large homogeneous stretch plus a nodal perturbation (not homogeneous)
    u = (_u_homogeneous(mesh, np.array([[1.3, 0.2], [-0.1, 0.85]]))
         + 0.03 * rng.standard_normal(2 * mesh.n_nodes))
    st = body.evaluate(u)
    assert st.valid
    n = len(u)
    K = np.zeros((n, n))
    np.add.at(K, (body.edofs[:, :, None], body.edofs[:, None, :]), st.ke)
    h = 1e-6
    Kfd = np.zeros((n, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = h
        fp = np.zeros(n)
        fm = np.zeros(n)
        np.add.at(fp, body.edofs, body.evaluate(u + e, tangent=False).fe)
        np.add.at(fm, body.edofs, body.evaluate(u - e, tangent=False).fe)
        Kfd[:, j] = (fp - fm) / (2 * h)
    assert np.abs(K - Kfd).max() <= 1e-6 * np.abs(K).max()
    # the energy is the potential of the forces (first derivative, same differences)
    f = np.zeros(n)
    np.add.at(f, body.edofs, st.fe)
    j = int(np.argmax(np.abs(f)))
    e = np.zeros(n)
    e[j] = h
    dE = (body.evaluate(u + e, False).energy - body.evaluate(u - e, False).energy) / (2 * h)
    assert abs(dE - f[j]) <= 1e-6 * abs(f[j])


@pytest.mark.parametrize("coeffs", [(0.4, -0.02, 0.004), (0.3, 0.0, 0.0), (0.2, 0.05, -0.01)])
def test_yeoh_kernel_tangent_pointwise(coeffs):
    rng = np.random.default_rng(3)
    F = np.eye(2) + 0.3 * rng.standard_normal((6, 2, 2))
    W, P, A = yeoh_plane_strain(F, *coeffs)
    assert A is not None
    h = 1e-6
    for i in range(2):
        for j in range(2):
            E = np.zeros((2, 2))
            E[i, j] = h
            Wp, Pp, _ = yeoh_plane_strain(F + E, *coeffs, tangent=False)
            Wm, Pm, _ = yeoh_plane_strain(F - E, *coeffs, tangent=False)
            np.testing.assert_allclose((Wp - Wm) / (2 * h), P[:, i, j], atol=1e-8)
            np.testing.assert_allclose((Pp - Pm) / (2 * h), A[:, :, :, i, j], atol=1e-7)


def test_mooney_rivlin_path_is_unchanged():
    """The MR kernel is the one the body always used: bit-identical forces and tangents for a
    MooneyRivlin and its HyperelasticModel, and equal to the kernel called directly."""
    mr = MooneyRivlin.from_shore(62.5)
    mesh = polar_mesh(2.485, 4.15, 2, 3)
    rng = np.random.default_rng(1)
    u = (_u_homogeneous(mesh, np.array([[1.2, 0.1], [0.05, 0.9]]))
         + 0.03 * rng.standard_normal(2 * mesh.n_nodes))
    a = HyperelasticBody(mesh, mr).evaluate(u)
    b = HyperelasticBody(mesh, mr.to_model()).evaluate(u)
    assert a.valid and b.valid
    assert a.energy == b.energy
    assert np.array_equal(a.fe, b.fe) and np.array_equal(a.ke, b.ke)
    body = HyperelasticBody(mesh, mr, "displacement")
    F = body.deformation_gradient(u)
    W, P, A = mooney_rivlin_plane_strain(F, mr.c10_mpa, mr.c01_mpa)
    J = np.linalg.det(F)
    W = W + 0.5 * mr.bulk_modulus * (J - 1.0) ** 2
    assert body.evaluate(u).energy == pytest.approx(float(np.einsum("eq,eq->", body.ref.w, W)),
                                                    rel=1e-14)


def test_mooney_rivlin_squeeze_same_through_the_model():
    mr = MooneyRivlin.from_shore(62.5)
    spec = MeshSpec(2, 12)
    a = squeeze(BASE, mr, [0.3, 0.6], mesh=spec, keep_fields=False)
    b = squeeze(BASE, mr.to_model(), [0.3, 0.6], mesh=spec, keep_fields=False)
    np.testing.assert_allclose(b.squeeze_force_n, a.squeeze_force_n, rtol=1e-14, atol=0)
    assert a.to_dict()["material"] == mr.to_dict()
    assert b.to_dict()["material"] == mr.to_model().to_dict()


def test_neo_hookean_is_mooney_rivlin_without_c01_through_the_squeeze():
    c10, d = 0.4, 0.05
    spec = MeshSpec(2, 12)
    p = [0.2, 0.4, 0.6]
    a = squeeze(BASE, MooneyRivlin(c10, 0.0, d), p, mesh=spec, keep_fields=False)
    b = squeeze(BASE, material_model("neo-hookean", [c10], d=d), p, mesh=spec, keep_fields=False)
    c = squeeze(BASE, material_model("yeoh", [c10, 0.0, 0.0], d=d), p, mesh=spec,
                keep_fields=False)
    np.testing.assert_allclose(b.squeeze_force_n, a.squeeze_force_n, rtol=1e-12, atol=0)
    np.testing.assert_allclose(b.contact.wire_contact_halfwidth_mm,
                               a.contact.wire_contact_halfwidth_mm, rtol=1e-12, atol=0)
    np.testing.assert_allclose(c.squeeze_force_n, b.squeeze_force_n, rtol=1e-12, atol=0)
    assert b.contact_onset_pressure_mpa == pytest.approx(a.contact_onset_pressure_mpa, abs=1e-12)


def test_yeoh_inflation_and_dict():
    m = material_model("yeoh", [0.5, -0.01, 0.001])
    r = inflate(8.3, 4.97, m, [0.1, 0.3], mesh=MeshSpec(2, 6), keep_fields=False)
    assert np.all(np.diff(r.outer_diameter_mm) > 0)
    out = r.to_dict()
    assert out["material"]["model"] == "yeoh"
    assert out["material"]["params"]["c20_mpa"] == -0.01


def test_other_material_types_are_refused():
    with pytest.raises(InputError, match="MooneyRivlin or a HyperelasticModel"):
        PlaneStrainMaterial(0.5)
    with pytest.raises(InputError, match="MooneyRivlin or a HyperelasticModel"):
        squeeze(BASE, 0.5, [0.3], mesh=MeshSpec(2, 12))  # type: ignore[arg-type]


def _strained(n=300):
    rng = np.random.default_rng(5)
    F = np.eye(2) + 0.3 * rng.standard_normal((n, 2, 2))
    F = F[np.linalg.det(F) > 0.2]
    extra = [s * _rot(t) @ np.diag([1.0, 1.0 + e]) for s, t, e in
             [(1.0, 0.0, 0.0), (1.1, 0.4, 0.0), (0.9, 1.0, 1e-9), (1.2, 2.0, 1e-5),
              (1.2, 0.2, 0.01), (1.2, 0.2, 0.0101), (1.3, 0.0, 0.3)]]
    return np.concatenate([F, np.array(extra)])


def test_ogden_kernel_equals_mooney_rivlin_and_neo_hookean():
    """Ogden a = 2 is neo-Hookean (mu = 2 C10) and a = -2 the C01 term (mu = 2 C01), at equal,
    nearly equal (both branches of the series switch) and general stretches."""
    F = _strained()
    for (W, P, A), (W0, P0, A0) in [
        (ogden_plane_strain(F, (0.8,), (2.0,)), yeoh_plane_strain(F, 0.4, 0.0, 0.0)),
        (ogden_plane_strain(F, (0.7, 0.1), (2.0, -2.0)), mooney_rivlin_plane_strain(F, 0.35, 0.05)),
    ]:
        assert A is not None and A0 is not None
        np.testing.assert_allclose(W, W0, rtol=0, atol=1e-12)
        np.testing.assert_allclose(P, P0, rtol=0, atol=1e-12 * np.abs(P0).max())
        np.testing.assert_allclose(A, A0, rtol=0, atol=1e-12 * np.abs(A0).max())


@pytest.mark.parametrize("mus,alphas", [((0.63, 0.0012, -0.01), (1.3, 5.0, -2.0)),
                                        ((0.5,), (7.3,)), ((0.4,), (-1.1,))])
def test_ogden_kernel_tangent_pointwise(mus, alphas):
    """Central differences (h = 1e-6) of W and P, also at and near equal stretches."""
    F = _strained(100)
    W, P, A = ogden_plane_strain(F, mus, alphas)
    assert A is not None
    h = 1e-6
    for i in range(2):
        for j in range(2):
            E = np.zeros((2, 2))
            E[i, j] = h
            Wp, Pp, _ = ogden_plane_strain(F + E, mus, alphas, tangent=False)
            Wm, Pm, _ = ogden_plane_strain(F - E, mus, alphas, tangent=False)
            np.testing.assert_allclose((Wp - Wm) / (2 * h), P[:, i, j],
                                       atol=1e-8 * np.abs(P).max())
            np.testing.assert_allclose((Pp - Pm) / (2 * h), A[:, :, :, i, j],
                                       atol=1e-7 * np.abs(A).max())


def test_ogden_squeeze_equals_mooney_rivlin():
    """Ogden (2 C10, 2, 2 C01, -2) through the whole squeeze: MR to Newton's round-off."""
    mr = MooneyRivlin.from_shore(62.5)
    og = material_model("ogden2", [2 * mr.c10_mpa, 2.0, 2 * mr.c01_mpa, -2.0], d=mr.d)
    spec = MeshSpec(2, 12)
    a = squeeze(BASE, mr, [0.3, 0.6], mesh=spec, keep_fields=False)
    b = squeeze(BASE, og, [0.3, 0.6], mesh=spec, keep_fields=False)
    np.testing.assert_allclose(b.squeeze_force_n, a.squeeze_force_n, rtol=1e-9)
    assert b.to_dict()["material"]["model"] == "ogden2"


@pytest.mark.parametrize("cmd", ["inflate", "squeeze"])
@pytest.mark.parametrize(
    "extra,needle",
    [
        (["--model", "yeo", "--params", "1"], "--model must be one of"),
        (["--model", "yeoh", "--params", "0.5,1"], "--params: yeoh takes 3 parameters"),
        (["--model", "yeoh", "--params", "0.5,-0.01,0.001", "--shore", "60"], "--model"),
        (["--model", "yeoh", "--params", "0.5,-0.01,0.001", "--c10", "0.3"], "--model"),
        (["--params", "0.5"], "--params needs --model"),
        (["--model", "yeoh"], "--params"),
        (["--model", "ogden", "--params", "0.5,2,1"], "--params: ogden takes 2, 4 or 6"),
        (["--model", "yeoh", "--params", "0.5,x,1"], "--params"),
    ],
)
def test_cli_model_errors_are_one_line_exit_2(cmd, extra, needle, capsys):
    from exofric.cli import run

    base = {"inflate": ["inflate", "--tube-od", "8.3", "--tube-id", "4.97"],
            "squeeze": ["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97",
                        "--wire", "1.6"]}[cmd]
    code = run([*base, *extra])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and needle in lines[0] and "Traceback" not in err


def test_cli_inflate_with_yeoh(capsys):
    import json

    from exofric.cli import run

    code = run(["inflate", "--tube-od", "8.3", "--tube-id", "4.97", "--pressures", "0.1,0.2",
                "--model", "yeoh", "--params", "0.5,-0.01,0.001", "--n-radial", "2",
                "--n-circ", "6", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    assert out["material"]["model"] == "yeoh"
    assert out["material"]["params"] == {"c10_mpa": 0.5, "c20_mpa": -0.01, "c30_mpa": 0.001}
