"""Pull-out of the wire through the inflated tube (issue 39): closed forms and convergence."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from exofric.errors import InputError
from exofric.fe import polar_mesh
from exofric.friction import joint_stiffness
from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.simulate import (
    PulloutNumerics,
    PulloutSetup,
    SqueezeSetup,
    pullout,
    section_pullout,
)
from exofric.simulate._antiplane import (
    CondensedSection,
    antiplane_stiffness,
    condense,
    solve_friction_steps,
)
from exofric.simulate._pullout import _Iwan, _shear_lag

MAT = MooneyRivlin.from_shore(62.5)
MU = {"mu_wire": 0.3, "mu_wall": 0.5, "mu_wire_wall": 0.2}


def setup(structure=BASE, **kw):
    """The base pull-out (MU) with ``kw`` replacing coefficients or options."""
    return PulloutSetup(structure, MAT, **{**MU, **kw})


@pytest.fixture(scope="module")
def sq():
    """One frictionless squeeze at 0.3 and 0.6 MPa (draft mesh), fields kept."""
    return SqueezeSetup(BASE, MAT, accuracy="draft").solve([0.3, 0.6])


def test_annulus_full_stick_matches_closed_form():
    # anti-plane shear of a concentric annulus, inner surface displaced by 1, outer held:
    # force per length 2 pi G / ln(ro/ri). quad9 on the polar mesh: geometry and field errors
    # are O(h^3); 1e-4 relative is 10x the error measured on this mesh.
    ri, ro, g = 1.0, 2.5, 1.3
    m = polar_mesh(ri, ro, 8, 24, theta1=2 * np.pi)
    K, _ = antiplane_stiffness(m.nodes, m.elements, g)
    inner, outer = np.unique(m.inner_nodes), np.unique(m.outer_nodes)
    Kc = condense(K, np.concatenate([inner, outer]))
    k = Kc[: len(inner), : len(inner)].sum()
    assert k == pytest.approx(2 * math.pi * g / math.log(ro / ri), rel=1e-4)


def test_shear_lag_linear_law_matches_tanh():
    # EA u'' = k u, u(0) = d, u'(L) = 0: F = EA beta tanh(beta L) d, beta = sqrt(k / EA).
    # Linear elements with lumped q: O((beta h)^2) error, ~2e-5 here; tolerance 1e-3.
    ea, k, L, d = 100.0, 1.0, 50.0, 0.1
    law = _Iwan(np.array([k]), np.array([1e30]), 0.0, 1)
    f, _, _ = _shear_lag(law, ea, L, np.array([0.0, d]), 1.0, 400)
    beta = math.sqrt(k / ea)
    assert f[-1] == pytest.approx(ea * beta * math.tanh(beta * L) * d, rel=1e-3)


@pytest.mark.parametrize("ea", [1e5, 1e9])
def test_whole_length_sliding_force_is_length_times_section_plateau(ea):
    # Once the whole length slides, every station carries the section's plateau: F = L q_slide
    # (a conservation of the axial force), whatever the cable's stiffness. A rigid cable (EA
    # 1e9 N: kE = EA/h ~ 8e9 N/mm) once stopped Newton at a residual scaled by kE, biasing F
    # by +2.2 % (found by the 3-D check); tolerance 1e-6.
    from dataclasses import replace

    st = replace(BASE, length_mm=30.0)
    sq30 = SqueezeSetup(st, MAT, accuracy="draft").solve([0.6])
    sec = section_pullout(setup(st), 0.6, squeeze_result=sq30)
    r = pullout(setup(st, cable_ea_n=ea), 0.6, displacement_mm=3.0, cycles=0,
                squeeze_result=sq30)
    assert r.force_n[-1] == pytest.approx(st.length_mm * sec.sliding_force_n_per_mm, rel=1e-6)


def test_held_zone_modes_match_bessel_closed_form():
    # The held end zones' 3-D scalar model (section x z, E_z d2w/dz2, modal assembly) on a
    # concentric annulus, held at both end faces: the wire surface displaced by sin(pi z / L),
    # the outer surface held. w = sin(pi z / L) R(r), R'' + R'/r = kappa^2 R, kappa = (pi / L)
    # sqrt(E_z / G): R from I0, K0, force per length -2 pi r_i G R'(r_i) at every station.
    # Error: the linear z elements' O((pi h / L)^2) (measured 9.5e-4 with h = L/16, 1.4e-4
    # with L/32; the section's quad9 error is ~1e-5): tolerance 2e-3.
    from scipy.special import i0, i1, k0, k1

    from exofric.simulate._shear_lag import HeldEnds, zone_stiffness

    ri, ro, g, ez, L, n = 1.0, 2.5, 1.3, 3.9, 4.0, 16
    m = polar_mesh(ri, ro, 4, 16, theta1=2 * np.pi)
    K, area = antiplane_stiffness(m.nodes, m.elements, g)
    inner, outer = np.unique(m.inner_nodes), np.unique(m.outer_nodes)
    c = np.concatenate([inner, outer])
    on = np.r_[np.ones(len(inner), bool), np.zeros(len(outer), bool)]
    sec = CondensedSection(np.zeros((0, 0)), on, np.ones(len(c)), np.ones(len(c)))
    zs = zone_stiffness(HeldEnds(K.tocsr(), area, sec, c, 1.0, ez), np.full(n, L / n),
                        (True, True))
    zm = np.arange(1, n) * L / n
    f = (zs.K @ np.kron(np.sin(np.pi * zm / L), on)).reshape(n - 1, len(c))[:, on].sum(axis=1)
    kap = math.pi / L * math.sqrt(ez / g)
    D = i0(kap * ri) * k0(kap * ro) - k0(kap * ri) * i0(kap * ro)
    dR = kap * (i1(kap * ri) * k0(kap * ro) + k1(kap * ri) * i0(kap * ro)) / D
    per_mm = f / (L / n * np.sin(np.pi * zm / L))
    assert per_mm == pytest.approx(np.full(n - 1, -2 * math.pi * ri * g * dR), rel=2e-3)


def test_short_held_tube_slides_at_length_times_plateau():
    # A 5 mm tube held at both end faces: the held zones' law replaces the section's on every
    # station; once the whole length slides the force is L q_slide (the held faces' end rows
    # carry their Coulomb capacity, the zones' stations theirs: together the section's), 1e-6.
    # The zones make the tube stiffer than the section law alone (the end faces hold it).
    from dataclasses import replace

    st = replace(BASE, length_mm=5.0)
    sq5 = SqueezeSetup(st, MAT, accuracy="draft").solve([0.6])
    r = pullout(setup(st, mu_wire_wall=0.0), 0.6, displacement_mm=2.0, cycles=0,
                squeeze_result=sq5)
    assert r.force_n[-1] == pytest.approx(5.0 * r.section.sliding_force_n_per_mm, rel=1e-6)
    k_sec = 5.0 * r.section.initial_stiffness_n_per_mm2
    assert r.force_n[1] / r.displacement_mm[1] > k_sec


def test_zero_friction_gives_zero_force(sq):
    s = section_pullout(setup(mu_wire=0.0, mu_wall=0.0, mu_wire_wall=0.0), 0.6,
                        squeeze_result=sq)
    assert np.all(s.force_n_per_mm == 0.0)


def test_full_sliding_equals_coulomb_sum(sq):
    # at full sliding q = mu_wire S_wire + mu_wire_wall N with S_wire and N as the squeeze
    # reports them (its own integrals of the contact forces, not our nodal reconstruction):
    # agreement to 1e-6 relative (the reconstruction differs only by round-off).
    s = section_pullout(setup(), 0.6, squeeze_result=sq)
    ref = (0.3 * sq.contact.wire_pressure_integral_n_per_mm[-1]
           + 0.2 * sq.squeeze_force_n_per_mm[-1])
    assert math.isfinite(s.slip_displacement_mm)
    assert s.force_n_per_mm[-1] == pytest.approx(ref, rel=1e-6)
    assert s.sliding_force_n_per_mm == pytest.approx(ref, rel=1e-6)
    # the tube-wire arc sticks first, then slip spreads: monotone force, stick share falls
    assert np.all(np.diff(s.force_n_per_mm) >= -1e-12)
    assert s.stick_fraction_wire[1] == 1.0 and s.stick_fraction_wire[-1] == 0.0


def test_free_ends_weak_wall_plateau_is_wall_capacity(sq):
    # the tube slides on the wall first when mu_wall S_wall < mu_wire S_wire: then the plateau
    # is mu_wall S_wall + mu_ww N (Coulomb on the wall arc, the squeeze's S_wall)
    s = section_pullout(setup(mu_wire=0.8, mu_wall=0.05, mu_wire_wall=0.0, ends="free"), 0.6,
                        squeeze_result=sq)
    assert s.sliding_force_n_per_mm == pytest.approx(
        0.05 * sq.contact.wall_pressure_integral_n_per_mm[-1], rel=1e-6)
    # the last step: the wall capacity plus the free tube's regularising foundation
    # (1e-4 G N/mm^2 x the tube's ~5 mm travel ~ 8e-4 N/mm, 0.4%): 1% tolerance
    assert s.force_n_per_mm[-1] == pytest.approx(s.sliding_force_n_per_mm, rel=1e-2)
    assert any("slides on the wall" in n for n in s.notes)


def test_converged_in_steps_and_penalty(sq):
    # the force at a fixed displacement does not depend on the load steps (monotone path,
    # exact return mapping) nor on the stick penalty (augmented Lagrangian): 1e-6 relative
    base = section_pullout(setup(), 0.6, squeeze_result=sq)
    d = 0.5 * base.slip_displacement_mm
    q0 = np.interp(d, base.displacement_mm, base.force_n_per_mm)
    for kw in ({"n_steps": 80}, {"stick_penalty": 1e5}, {"stick_penalty": 30.0}):
        s = section_pullout(setup(numerics=PulloutNumerics(**kw)), 0.6, squeeze_result=sq)
        q = np.interp(d, s.displacement_mm, s.force_n_per_mm)
        if "n_steps" in kw:  # linear interpolation between steps of a curved law
            assert q == pytest.approx(q0, rel=5e-3)
        else:
            assert q == pytest.approx(q0, rel=1e-6)


def test_mesh_convergence_initial_stiffness():
    # draft (2 x 24) vs standard (4 x 32) squeeze meshes: section stiffness and plateau
    # within 5% (measured: see the report); the plateau is the squeeze's S_wire's
    a = section_pullout(setup(accuracy="draft"), 0.6)
    b = section_pullout(setup(accuracy="standard"), 0.6)
    assert a.initial_stiffness_n_per_mm2 == pytest.approx(b.initial_stiffness_n_per_mm2,
                                                          rel=0.05)
    assert a.sliding_force_n_per_mm == pytest.approx(b.sliding_force_n_per_mm, rel=0.05)


def test_zero_creep_under_held_load():
    # a held wire displacement below breakaway: the contact nodes do not move (< 1e-6 mm)
    sec = CondensedSection(np.array([[2.0, -1.0], [-1.0, 2.0]]), np.array([True, False]),
                           np.array([0.5, 0.4]), np.array([0.2, 0.2]))
    d = np.array([0.0, 0.1, 0.2] + [0.2] * 20)
    out = solve_friction_steps(sec, d, 1e3)
    assert np.abs(out["w"][3:] - out["w"][2]).max() < 1e-6


def test_zero_creep_held_section(sq):
    s = section_pullout(setup(), 0.6, squeeze_result=sq)
    d = 0.5 * s.slip_displacement_mm
    from exofric.simulate._pullout import _build_section

    sec = _build_section(sq, -1, 0.3, 0.5, "fixed")[0]
    out = solve_friction_steps(sec, np.concatenate([np.linspace(0, d, 11), [d] * 10]), 1e3)
    assert np.abs(out["w"][11:] - out["w"][10]).max() < 1e-6


def test_static_peak_and_hysteresis(sq):
    kw = dict(squeeze_result=sq, displacement_mm=3.0, cycles=1)
    r = pullout(setup(mu_static=0.36), 0.6, **kw)
    k = pullout(setup(), 0.6, **kw)
    L = BASE.length_mm
    # whole length sliding: F = L q_slide (every station on its plateau), 0.5%
    assert k.force_n[60] == pytest.approx(L * k.section.sliding_force_n_per_mm, rel=5e-3)
    assert r.static_force_n > k.static_force_n
    # closed loop: back at +D after -D the force returns to the sliding value; the loop
    # encloses a positive area (dissipation)
    assert r.force_n[-1] == pytest.approx(k.force_n[60], rel=5e-3)
    area = np.trapezoid(k.force_n[60:], k.displacement_mm[60:])
    assert area > 0


def test_line_stick_penalty_convergence(sq):
    # the joint's secant stiffness converges as the wire-wall stick spring stiffens: 2%
    from exofric.simulate._pullout import _length_from_section

    s = section_pullout(setup(), 0.6, squeeze_result=sq)
    a = _length_from_section(s, BASE.length_mm, 1.3e5, 1.0, 2.0, 0, 232, 60, 1e3, 0.3)
    b = _length_from_section(s, BASE.length_mm, 1.3e5, 1.0, 2.0, 0, 232, 60, 1e4, 0.3)
    fa = np.interp(0.5, a.displacement_mm, a.force_n)
    fb = np.interp(0.5, b.displacement_mm, b.force_n)
    assert fa == pytest.approx(fb, rel=0.02)


def test_joint_stiffness_torque_is_force_times_radius():
    j = joint_stiffness(setup(accuracy="draft"), [0.3, 0.6], radius_m=0.1)
    assert np.all(j.breakaway_torque_nm == pytest.approx(j.breakaway_force_n * 0.1))
    assert np.all(np.diff(j.stiffness_nm_per_rad) > 0)
    assert j.to_frame().shape == (2, 5)


@pytest.mark.parametrize("kw", [{"mu_wire": -0.1}, {"mu_wall": float("nan")},
                                {"mu_static": 0.1}, {"ends": "glued"}, {"cable_ea_n": 0.0},
                                {"numerics": {"n_z": 10}}])
def test_bad_setup(kw):
    with pytest.raises(InputError) as exc:
        setup(accuracy="draft", **kw)
    assert exc.value.param == next(iter(kw))


@pytest.mark.parametrize("kw", [{"displacement_mm": 500.0}, {"displacement_mm": "far"},
                                {"cycles": -1}, {"cycles": 1.5}])
def test_bad_path(kw):
    # checked before any solve: a travel beyond the tube (116 mm), a non-integer cycle count
    with pytest.raises(InputError) as exc:
        pullout(setup(accuracy="draft"), 0.6, **kw)
    assert exc.value.param == next(iter(kw))


def test_not_a_setup():
    with pytest.raises(InputError, match="PulloutSetup"):
        pullout(BASE, 0.6)  # type: ignore[arg-type]
    with pytest.raises(InputError, match="PulloutSetup"):
        joint_stiffness(MU, [0.6], radius_m=0.1)  # type: ignore[arg-type]


def test_below_onset_zero_force():
    s = section_pullout(setup(accuracy="draft"), 0.02)
    assert np.all(s.force_n_per_mm == 0.0) and s.notes


def test_cli_section_json_and_errors(capsys):
    from exofric.cli import app, run

    base = ["pullout", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
            "--pressure", "0.6", "--mu-wire", "0.3", "--mu-wall", "0.5", "--mu-wire-wall", "0.2",
            "--shore", "62.5", "--accuracy", "draft"]
    r = CliRunner().invoke(app, [*base, "--section", "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    for key in ("displacement_mm", "force_n_per_mm", "initial_stiffness_n_per_mm2",
                "slip_displacement_mm", "sliding_force_n_per_mm",
                "wire_pressure_integral_n_per_mm"):
        assert key in out
    r = CliRunner().invoke(app, [*base, "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert {"displacement_mm", "force_n", "static_force_n", "sliding_force_n"} <= set(out)
    capsys.readouterr()
    assert run([*base, "--mu-static", "0.1"]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_example_runs():
    import runpy
    from pathlib import Path

    runpy.run_path(str(Path(__file__).parents[1] / "examples" / "pullout_knee.py"),
                   run_name="not_main")


def test_invariants_of_axial_shear_match_direct_3d():
    # I1 = I1_plane + |g|^2 and I2 = I2_plane + g^T adj(C2) g (docs/formulation.md 12), against
    # the invariants of the 3x3 F = [[F2, 0], [g^T, 1]] computed directly: 1e-12
    rng = np.random.default_rng(3)
    for _ in range(5):
        F2 = np.eye(2) + 0.3 * rng.standard_normal((2, 2))
        g = 0.5 * rng.standard_normal(2)
        F = np.zeros((3, 3))
        F[:2, :2], F[2, :2], F[2, 2] = F2, g, 1.0
        C = F.T @ F
        i1, i2 = np.trace(C), 0.5 * (np.trace(C) ** 2 - np.trace(C @ C))
        C2 = F2.T @ F2
        P = np.zeros((3, 3))
        P[:2, :2], P[2, 2] = F2, 1.0
        Cp = P.T @ P
        i1p, i2p = np.trace(Cp), 0.5 * (np.trace(Cp) ** 2 - np.trace(Cp @ Cp))
        adj = np.trace(C2) * np.eye(2) - C2
        assert i1 == pytest.approx(i1p + g @ g, rel=1e-12)
        assert i2 == pytest.approx(i2p + g @ adj @ g, rel=1e-12)
        assert np.linalg.det(F) == pytest.approx(np.linalg.det(F2), rel=1e-12)


def test_mooney_rivlin_modulus_is_the_energy_hessian():
    # A = d^2 W / dg^2 of W = C10 J^-2/3 I1 + C01 J^-4/3 I2 (the g-dependent part), by central
    # differences of the direct 3D invariants on a deformed quarter annulus
    from exofric.fe import reference_data
    from exofric.simulate._antiplane import mooney_rivlin_modulus

    m = polar_mesh(1.0, 2.0, 1, 2)
    u = np.stack([0.1 * m.nodes[:, 0] ** 2, -0.05 * m.nodes[:, 0] * m.nodes[:, 1]], axis=1)
    c10, c01 = 0.5, 0.2
    A = mooney_rivlin_modulus(m.nodes, m.elements, u, c10, c01)
    rd = reference_data(m.nodes, m.elements, 2, 3)
    F2 = np.eye(2) + np.einsum("ai,aj->ij", u[m.elements[0]], rd.dNdX[0, 0])
    J = np.linalg.det(F2)

    def W(g):
        F = np.zeros((3, 3))
        F[:2, :2], F[2, :2], F[2, 2] = F2, g, 1.0
        C = F.T @ F
        return (c10 * J ** (-2 / 3) * np.trace(C)
                + c01 * J ** (-4 / 3) * 0.5 * (np.trace(C) ** 2 - np.trace(C @ C)))

    h = 1e-4
    H = np.zeros((2, 2))
    for i in range(2):
        for j in range(2):
            ei, ej = h * np.eye(2)[i], h * np.eye(2)[j]
            H[i, j] = (W(ei + ej) - W(ei - ej) - W(-ei + ej) + W(-ei - ej)) / (4 * h * h)
    # central differences: O(h^2) = 1e-8 absolute error against entries of ~1: abs 1e-7
    assert A[0, 0] == pytest.approx(H, abs=1e-7)
    assert abs(A[0, 0, 0, 1]) > 1e-3  # the C01 term makes A anisotropic here


def test_joint_stiffness_converged_in_path_steps(sq):
    # K (secant at half the breakaway) and T_break with 60 and 240 steps on the first
    # loading: measured 0.7% and 0.3% apart (first order in the step); tolerance 2%
    def knee(n_path, **kw):
        s = setup(mu_static=0.36, accuracy="draft", numerics=PulloutNumerics(n_path=n_path))
        return joint_stiffness(s, [0.6], radius_m=0.1, **kw)

    a = knee(60)
    b = knee(240)
    assert a.stiffness_nm_per_rad[0] == pytest.approx(b.stiffness_nm_per_rad[0], rel=0.02)
    assert a.breakaway_torque_nm[0] == pytest.approx(b.breakaway_torque_nm[0], rel=0.02)
    # the travel does not matter once it passes the breakaway
    c = knee(60, displacement_mm=5.0)
    assert c.stiffness_nm_per_rad[0] == pytest.approx(a.stiffness_nm_per_rad[0], rel=1e-9)


def _kinematic_hardening_1d(path, k, cap, h):
    """Closed form of a spring k in series with a Coulomb slider (capacity cap) in parallel
    with a spring h (linear kinematic hardening; Simo & Hughes, Computational Inelasticity,
    Box 1.4, exact for a piecewise-linear path): the force (N) along ``path`` (mm)."""
    s, out = 0.0, []
    for d in path:
        f = k * (d - s)
        z = f - h * s
        if abs(z) > cap:
            s += (abs(z) - cap) * np.sign(z) / (k + h)
            f = k * (d - s)
        out.append(f)
    return np.array(out)


def test_hardening_slider_matches_the_kinematic_hardening_closed_form():
    # A tube of stiffness k = 2 N/mm between the wire (stuck: capacity 1e3 N) and one wall
    # node (capacity 0.5 N, a spring h = 0.3 N/mm on its slip: the fittings' rod), pulled to
    # 1 mm, back to -1 mm and to 1 mm again (a piecewise-linear path in fine steps, so the
    # closed form's steps are exact). The penalty (1e5 N/mm^3 x 1 mm) leaves an error of
    # order h / penalty (3e-6): 2e-5 relative (1e3: 3e-5 measured; 1e7 is past what the
    # Newton's round-off tolerance of the stiff penalty accepts).
    K = 2.0 * np.array([[1.0, -1.0], [-1.0, 1.0]])
    sec = CondensedSection(K, np.array([True, False]), np.array([1e3, 0.5]),
                           np.array([1.0, 1.0]), np.array([0.0, 0.3]))
    path = np.concatenate([np.linspace(0.0, 1.0, 41), np.linspace(1.0, -1.0, 81)[1:],
                           np.linspace(-1.0, 1.0, 81)[1:]])
    out = solve_friction_steps(sec, path, 1e5)
    want = _kinematic_hardening_1d(path, 2.0, 0.5, 0.3)
    assert np.abs(out["force"] - want).max() < 2e-5 * np.abs(want).max()
    # the hysteresis is the hardening's: slope k h / (k + h) while the wall slides
    assert out["force"][40] == pytest.approx(0.5 + 0.3 * (2.0 - 0.5) / 2.3, rel=2e-5)


def test_held_section_equals_the_free_one_while_the_wall_holds(sq):
    # mu_wall S_wall > mu_wire S_wire: the wall arc holds the tube, so the fittings' rod
    # carries no force in the section (a long tube's middle is a periodic slice): with every
    # arc stuck the held and free sections coincide (both carry only the 1e-4 G regulariser),
    # 1e-9; along the pull the wall arc's edge nodes slip a little, where the rod's spring
    # acts: within 1e-3 (measured 2.4e-4 at 0.6 MPa), and the same sliding force
    fixed = section_pullout(setup(), 0.6, squeeze_result=sq)
    free = section_pullout(setup(ends="free"), 0.6, squeeze_result=sq)
    assert fixed.initial_stiffness_n_per_mm2 == pytest.approx(
        free.initial_stiffness_n_per_mm2, rel=1e-9)
    assert np.allclose(fixed.force_n_per_mm, free.force_n_per_mm, rtol=1e-3, atol=0.0)
    assert fixed.sliding_force_n_per_mm == pytest.approx(free.sliding_force_n_per_mm, rel=1e-12)


@pytest.mark.parametrize("mu_wall", [0.1, 0.02])
def test_held_tube_sliding_on_the_wall_is_held_by_its_fittings_to_the_wires_capacity(
        sq, mu_wall):
    # mu_wall S_wall < mu_wire S_wire: the tube slides on the wall first, and the fittings
    # (a rod spring on the wall's slip) hold it until the wire arc slides on its whole
    # length: the section's plateau is mu_wire S_wire + mu_ww N (the squeeze's integrals,
    # 1e-6), reached at a finite slip; the force never exceeds it (before, the rod's foundation
    # went on as a spring past the computed path: 83.8 N at 5 mm against a capacity of 77.1 N)
    s = section_pullout(setup(mu_wall=mu_wall), 0.6, squeeze_result=sq)
    cap = (0.3 * sq.contact.wire_pressure_integral_n_per_mm[-1]
           + 0.2 * sq.squeeze_force_n_per_mm[-1])
    assert math.isfinite(s.slip_displacement_mm)
    assert s.stick_fraction_wire[-1] == 0.0 and np.nanmin(s.stick_fraction_wall) == 0.0
    assert s.force_n_per_mm[-1] == pytest.approx(cap, rel=1e-6)
    assert np.all(s.force_n_per_mm <= cap * (1 + 1e-9))
    assert np.all(np.diff(s.force_n_per_mm) >= -1e-12)
    r = pullout(setup(mu_wall=mu_wall), 0.6, displacement_mm=10.0, cycles=0, squeeze_result=sq)
    L = BASE.length_mm
    assert np.all(r.force_n <= L * cap * (1 + 1e-6))
    assert r.force_n[-1] == pytest.approx(L * cap, rel=1e-6)


def test_tangent_woodbury_solves_match_a_direct_solve():
    # the friction solver's tangent solves a stick set near its factorised one by the
    # Sherman-Morrison-Woodbury identity: against numpy's dense solve of the same matrix, for
    # random stick sets 0-12 nodes away (beyond 8 it refactorises), within 1e-9 relative
    from exofric.simulate._antiplane import _NodeLaws, _Tangent

    rng = np.random.default_rng(7)
    n = 40
    A = rng.normal(size=(n, n))
    K = A @ A.T / n + np.eye(n)
    sec = CondensedSection(K, rng.random(n) < 0.4, rng.random(n), 0.1 + rng.random(n),
                           np.where(rng.random(n) < 0.3, 0.5, 0.0))
    law = _NodeLaws(sec, 1e3)
    tangent = _Tangent(K, law)
    st = rng.random(n) < 0.5
    for k in [0, 1, 3, 8, 12, 2, 5]:
        flip = rng.choice(n, size=k, replace=False)
        st2 = st.copy()
        st2[flip] = ~st2[flip]
        b = rng.normal(size=n)
        want = np.linalg.solve(K + np.diag(law.stiffness(st2)), b)
        got = tangent.solve(st2, b)
        assert np.abs(got - want).max() < 1e-9 * np.abs(want).max(), k
