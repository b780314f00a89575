"""Issue 19: the wire's angular position on the hole wall (``wire_angle_deg``, ``--wire-angle``).

An off-centre wire is solved on the full 360 deg section (no symmetry plane). References are
independent of the full model: the half model (today's, bit-identical at angle 0), the
rotational symmetry of the frictionless problem without gravity (the hole is a circle: wall
forces act through its centre, wire forces through the wire's, so the tube comes to rest
opposite the wire and the answer is the centred one turned by the angle), mirror symmetry,
and the balance of forces on the tube. Units: mm, N, MPa, deg.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from exofric.cli import app, run
from exofric.errors import InputError
from exofric.fe import MeshSpec, SqueezeProblem
from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.simulate import squeeze

MAT = MooneyRivlin.from_shore(62.5)
P = np.round(np.arange(0.05, 0.601, 0.05), 2)
MESH = MeshSpec(2, 24, grading=6.0)


@pytest.fixture(scope="module")
def half():
    return squeeze(BASE, MAT, P, mesh=MESH, keep_fields=False)


@pytest.fixture(scope="module")
def at20():
    return squeeze(BASE, MAT, P, mesh=MESH, wire_angle_deg=20.0)


def test_angle_zero_is_todays_half_model(half):
    # 0 takes today's code path: bit-identical (also checked against the code before this
    # change: every output array and every displacement, three gravities, draft level)
    r = squeeze(BASE, MAT, P, mesh=MESH, wire_angle_deg=0.0, keep_fields=False)
    np.testing.assert_array_equal(r.squeeze_force_n_per_mm, half.squeeze_force_n_per_mm)
    np.testing.assert_array_equal(r.wall_force_n_per_mm, half.wall_force_n_per_mm)
    assert r.contact_onset_pressure_mpa == half.contact_onset_pressure_mpa
    assert r.symmetry.startswith("half model") and r.wire_angle_deg == 0.0
    assert np.all(r.squeeze_force_direction_deg[r.squeeze_force_n_per_mm > 0] == 0.0)


def test_full_model_at_zero_matches_the_half_model(half):
    # The full mesh is the half mesh and its mirror image, so the full model at 0 deg has the
    # half model's solution: measured 1.6e-11 N/mm (Newton's tolerance), far inside the half
    # model's own error estimate (>= 0.1% of N). Tolerance 1e-8 N/mm.
    for acc in (None, "draft"):
        h = half if acc is None else squeeze(BASE, MAT, P, accuracy=acc, keep_fields=False)
        f = squeeze(BASE, MAT, P, mesh=None if acc else MESH, accuracy=acc, full_model=True,
                    keep_fields=False)
        assert f.symmetry.startswith("full model") and f.dofs > 1.9 * h.dofs
        np.testing.assert_allclose(f.squeeze_force_n_per_mm, h.squeeze_force_n_per_mm,
                                   rtol=0, atol=1e-8)
        np.testing.assert_allclose(f.wall_force_n_per_mm, h.wall_force_n_per_mm, rtol=0,
                                   atol=1e-8)
        np.testing.assert_allclose(f.contact.wire_contact_halfwidth_mm,
                                   h.contact.wire_contact_halfwidth_mm, rtol=0, atol=1e-9)
        np.testing.assert_allclose(f.contact.wall_contact_arc_mm, h.contact.wall_contact_arc_mm,
                                   rtol=0, atol=1e-9)
        assert f.contact_onset_pressure_mpa == pytest.approx(h.contact_onset_pressure_mpa,
                                                             abs=1e-8)
        if acc is not None:
            err = h.estimate.n_per_mm
            assert np.all(np.abs(f.squeeze_force_n_per_mm - h.squeeze_force_n_per_mm) <= err)


def test_off_centre_wire_without_gravity_is_the_centred_answer_turned(half, at20):
    # Trend (frictionless, no weight): the tube slides along the wall until it lies opposite
    # the wire, so |N| at 20 deg equals N at 0 deg and the force turns by 20 deg. Measured:
    # N(0.6 MPa) = 2.07259 N/mm at both angles (difference 1.5e-11 N/mm), direction 20 deg to
    # 1e-8 deg.
    np.testing.assert_allclose(at20.squeeze_force_n_per_mm, half.squeeze_force_n_per_mm,
                               rtol=1e-8, atol=1e-10)
    on = at20.squeeze_force_n_per_mm > 0
    np.testing.assert_allclose(at20.squeeze_force_direction_deg[on], 20.0, atol=1e-6)
    np.testing.assert_allclose(at20.wall_force_direction_deg[on], 20.0, atol=1e-6)
    assert np.all(np.isnan(at20.squeeze_force_direction_deg[~on]))
    np.testing.assert_allclose(at20.contact.wire_contact_halfwidth_mm,
                               half.contact.wire_contact_halfwidth_mm, rtol=0, atol=1e-8)
    assert at20.contact_onset_pressure_mpa == pytest.approx(half.contact_onset_pressure_mpa,
                                                            abs=1e-8)


def test_mirror_symmetry():
    plus = squeeze(BASE, MAT, P, mesh=MESH, wire_angle_deg=35.0, keep_fields=False)
    minus = squeeze(BASE, MAT, P, mesh=MESH, wire_angle_deg=-35.0, keep_fields=False)
    np.testing.assert_allclose(plus.squeeze_force_n_per_mm, minus.squeeze_force_n_per_mm,
                               rtol=0, atol=1e-6)
    on = plus.squeeze_force_n_per_mm > 0
    np.testing.assert_allclose(plus.squeeze_force_direction_deg[on],
                               -minus.squeeze_force_direction_deg[on], atol=1e-6)
    np.testing.assert_allclose(plus.wall_force_direction_deg[on],
                               -minus.wall_force_direction_deg[on], atol=1e-6)


def test_forces_on_the_tube_balance_at_every_pressure(at20):
    # The pressure's resultant on the closed cavity is zero (checked on the nodal forces P H x)
    # and the wall's and wire's resultants on the tube cancel (no weight, springs released).
    prob = SqueezeProblem(BASE, MAT, MESH, at20.penalty, at20.density, "none",
                          wire_angle_deg=20.0)
    np.testing.assert_array_equal(prob.mesh.nodes, at20.nodes)
    for p, d, n, dn, w, dw in zip(P, at20.displacements, at20.squeeze_force_n_per_mm,
                                  at20.squeeze_force_direction_deg, at20.wall_force_n_per_mm,
                                  at20.wall_force_direction_deg, strict=True):
        fp = (p * (prob.H @ (prob.X + d.ravel()))).reshape(-1, 2).sum(axis=0)
        assert np.max(np.abs(fp)) < 1e-12 * p * prob.B * prob.n_dofs
        fw, fh = prob.resultants(d.ravel())  # on the wire, on the tube
        assert np.max(np.abs(fh - fw)) < 1e-8  # tube: wall + (- on wire) = 0
        if n > 0:
            ang = np.radians([dn, dw])
            np.testing.assert_allclose(n * np.array([np.sin(ang[0]), np.cos(ang[0])]), fw,
                                       atol=1e-12)
            np.testing.assert_allclose(w * np.array([np.sin(ang[1]), np.cos(ang[1])]), fh,
                                       atol=1e-12)
        assert abs(prob.rotation(d.ravel())) < 1e-10  # the rotation spring is idle


def test_answer_does_not_depend_on_the_rotation_spring(at20):
    other = squeeze(BASE, MAT, P, mesh=MESH, wire_angle_deg=20.0, rotation_regulariser=100.0,
                    keep_fields=False)
    np.testing.assert_allclose(other.squeeze_force_n_per_mm, at20.squeeze_force_n_per_mm,
                               rtol=1e-8, atol=1e-12)
    weak = squeeze(BASE, MAT, P, mesh=MESH, wire_angle_deg=20.0, rotation_regulariser=0.01,
                   keep_fields=False)
    np.testing.assert_allclose(weak.squeeze_force_n_per_mm, at20.squeeze_force_n_per_mm,
                               rtol=1e-8, atol=1e-12)


@pytest.mark.parametrize("bad", [90.0, -90.0, 120.0, float("nan"), float("inf")])
def test_bad_angle_is_refused(bad):
    with pytest.raises(InputError, match="wire_angle_deg"):
        squeeze(BASE, MAT, [0.3], mesh=MESH, wire_angle_deg=bad)


@pytest.mark.parametrize("gravity", ["toward-wall", "toward-wire"])
def test_off_centre_wire_needs_gravity_none(gravity):
    with pytest.raises(InputError, match="gravity 'none'"):
        squeeze(BASE, MAT, [0.3], mesh=MESH, wire_angle_deg=10.0, gravity=gravity)


def _cli(*extra: str):
    args = ["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
            "--shore", "62.5", "--pressures", "0.3,0.6", "--n-radial", "2", "--n-circ", "12",
            *extra]
    return CliRunner().invoke(app, args)


def test_cli_wire_angle_json():
    r = _cli("--wire-angle", "20", "--json")
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert out["wire_angle_deg"] == 20.0
    assert out["squeeze_force_direction_deg"] == pytest.approx([20.0, 20.0], abs=1e-6)
    assert out["symmetry"].startswith("full model")
    r0 = json.loads(_cli("--json").stdout)
    assert r0["wire_angle_deg"] == 0.0
    assert out["squeeze_force_n"] == pytest.approx(r0["squeeze_force_n"], rel=1e-8)


@pytest.mark.parametrize("bad", ["90", "-91", "nan"])
def test_cli_bad_angle_one_line(bad, capsys):
    code = run(["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire",
                "1.6", "--shore", "62.5", "--pressures", "0.3", "--n-circ", "12",
                "--wire-angle", bad])
    err = capsys.readouterr().err
    lines = [ln for ln in err.strip().splitlines() if ln.strip()]
    assert code == 2 and len(lines) == 1 and "wire_angle_deg" in lines[0], err
