"""Coulomb friction in the squeeze's contacts (issue 15): kernel, path, limits, outputs.

Independent references: finite differences of the force (the tangent), the frictionless solver
(mu = 0 through the frictional code path), the number of load steps and the penalty (convergence
studies), the sign of the dissipated work (second law), a hand integral of a uniform pressure on
a known arc. The CalculiX frictional reference is in ``test_friction_reference.py``.
"""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from exofric import defaults
from exofric.errors import InputError, PlausibilityWarning
from exofric.fe import (
    MeshSpec,
    NewtonSettings,
    RigidCircle,
    SqueezeProblem,
    evaluate_contact,
    evaluate_friction,
    solve_path,
)
from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.simulate import squeeze

MAT = MooneyRivlin.from_shore(62.5)
P12 = np.round(np.arange(1, 13) * 0.05, 2)
MESH = MeshSpec(**defaults.SQUEEZE_MESH)


@pytest.mark.parametrize("circle", [RigidCircle((0.0, 0.0), 5.0, True),
                                    RigidCircle((0.0, 4.0), 0.7, False)])
@pytest.mark.parametrize("bound", [False, True])
def test_friction_tangent_matches_finite_differences(circle: RigidCircle, bound: bool) -> None:
    """The blocks are d(-force)/dx of normal + friction force (central differences, h = 1e-8
    mm: truncation ~h^2 x third derivative, round-off ~1e-16 x force / h: 1e-6 relative covers
    both). Nodes mix stick and slip; ``bound`` freezes the slip bound (then the coupled blocks
    are compared with the frozen-bound force's derivative plus the dF_n term evaluated
    separately, so only the unfrozen case is the full check)."""
    rng = np.random.default_rng(1)
    m = 8
    if circle.inside:
        ang, rad = rng.uniform(-2, -1, m), 5.0 + rng.uniform(-0.002, 0.01, m)
    else:
        ang, rad = rng.uniform(-2.5, -0.6, m), 0.7 + rng.uniform(-0.01, 0.002, m)
    x = np.column_stack([np.cos(ang) * rad, np.sin(ang) * rad]) + np.asarray(circle.center)
    w = rng.uniform(0.1, 0.3, m)
    anchor = ang + rng.uniform(-2e-3, 2e-3, m)
    eps = 1e4
    b0 = None
    if bound:
        b0 = 0.3 * np.linalg.norm(evaluate_contact(x, w, circle, eps).force, axis=1)

    def force(xx: np.ndarray) -> tuple[np.ndarray, object]:
        n = evaluate_contact(xx, w, circle, eps)
        f = evaluate_friction(xx, w, circle, eps, eps, 0.3, anchor, n, True, b0, coupled=False)
        return n.force + f.force, (n, f)

    _, (n0, f0) = force(x)
    assert f0.stick.any() and (~f0.stick & n0.active).any()   # both regimes present
    blocks = n0.blocks + f0.blocks
    h = 1e-8
    for i in range(m):
        for j in range(2):
            xp, xm = x.copy(), x.copy()
            xp[i, j] += h
            xm[i, j] -= h
            col = -(force(xp)[0][i] - force(xm)[0][i]) / (2 * h)
            scale = max(1.0, float(np.max(np.abs(blocks[i]))))
            assert np.max(np.abs(col - blocks[i][:, j])) < 1e-6 * scale
    if not bound:
        # the coupled tangent (the solver's) equals the unfrozen force's derivative too
        f1 = evaluate_friction(x, w, circle, eps, eps, 0.3, anchor, n0, True,
                               0.3 * np.linalg.norm(n0.force, axis=1), coupled=True)
        np.testing.assert_allclose(f1.blocks, f0.blocks, rtol=1e-12, atol=1e-9)


def test_mu_zero_through_the_frictional_path_is_todays_solver() -> None:
    """mu = 0 with the frictional machinery on (anchors, bounds, commits) reproduces the
    frictionless N to 1e-9 relative (both converge Newton to tol_r = 1e-9)."""
    out = []
    for frictional in (False, True):
        prob = SqueezeProblem(BASE, MAT, MESH, 1e5, 1.1e-9, "none", 1.0, frictional=frictional)
        pts = solve_path(prob, P12, NewtonSettings(**defaults.SQUEEZE_NEWTON))
        out.append(np.array([prob.resultants(pt.u)[0][1] for pt in pts]))
    assert out[1][-1] > 1.0
    np.testing.assert_allclose(out[1], out[0], rtol=1e-9, atol=1e-12)


@pytest.fixture(scope="module")
def steps() -> dict[float, tuple[np.ndarray, list[float]]]:
    """N (N/mm) at mu = 0.3 on both interfaces for 6, 12, 24 and 48 load steps to 0.6 MPa."""
    out = {}
    for ms in (0.1, 0.05, 0.025, 0.0125):
        prob = SqueezeProblem(BASE, MAT, MESH, 1e5, 1.1e-9, "none", 1.0, mu_wall=0.3,
                              mu_wire=0.3)
        pts = solve_path(prob, P12, NewtonSettings(**{**defaults.SQUEEZE_NEWTON,
                                                      "max_step": ms}))
        out[ms] = (np.array([prob.resultants(pt.u)[0][1] for pt in pts]),
                   list(prob.dissipation))
    return out


def test_load_step_convergence(steps: dict[float, tuple[np.ndarray, list[float]]]) -> None:
    """Path-dependent friction converges in the number of load steps: from 0.2 MPa N of 24 and
    48 steps agree to 0.05 %, and 6 steps are within 0.5 % of 48 (measured: ~1e-4 for all)."""
    n48 = steps[0.0125][0][3:]
    assert np.max(np.abs(steps[0.025][0][3:] / n48 - 1)) < 5e-4
    assert np.max(np.abs(steps[0.1][0][3:] / n48 - 1)) < 5e-3
    # and friction matters: several % at 0.6 MPa, against the frictionless 2.07 N/mm
    assert 0.85 < n48[-1] / 2.0726 < 0.97


def test_dissipation_is_never_negative(steps: dict[float, tuple[np.ndarray, list[float]]]
                                       ) -> None:
    """The frictional work of every committed step is >= 0 (second law; the return map makes
    each slip increment point along its traction). Round-off allowance 1e-12 N mm/mm."""
    for _, diss in steps.values():
        assert len(diss) > 6
        assert min(diss) >= -1e-12
        assert max(diss) > 0.0


def test_large_mu_approaches_full_stick_smoothly() -> None:
    """N falls monotonically with mu and levels off once everything sticks (mu >= 1.5 on the
    base group): N(1.5) and N(2.0) within 0.3 %, stick fractions 1. (At these mu the answer at
    the default 0.025 MPa load step carries a path error of ~0.3 %: N(0.6) at mu 1.5 is
    1.7967, 1.7994, 1.8007, 1.8024 N/mm at steps of 0.025, 0.0125, 0.00625, 0.003125 MPa, and
    cut-backs change the path; N(1.5) and N(2.0) agree to 0.01 % at the finest step. Issue 37
    changed the cut-backs: 0.207 % here, 0.15-0.2 % before.)"""
    n = []
    for mu in (0.3, 1.0, 1.5, 2.0):
        with pytest.warns(PlausibilityWarning) if mu > 1.5 else _nullcontext():
            r = squeeze(BASE, MAT, [0.4, 0.6], mesh=MESH, mu_wall=mu, mu_wire=mu)
        n.append(r.squeeze_force_n_per_mm[-1])
        if mu >= 1.5:
            c = r.contact
            assert c.stick_fraction_wire[-1] == 1.0 and c.stick_fraction_wall[-1] == 1.0
    assert n[0] > n[1] > n[2] - 1e-3
    assert abs(n[3] / n[2] - 1) < 3e-3


def test_penalty_convergence() -> None:
    """Normal and tangential penalties 1e4 -> 1e5 -> 1e6 N/mm^3 change N(0.6) by < 2e-4
    (measured 8e-5 and 6e-5): the penalty regularisation is converged at the default 1e5."""
    n = [squeeze(BASE, MAT, [0.6], mesh=MESH, penalty=e, mu_wall=0.3,
                 mu_wire=0.3).squeeze_force_n_per_mm[0] for e in (1e4, 1e5, 1e6)]
    assert abs(n[0] / n[2] - 1) < 5e-4
    assert abs(n[1] / n[2] - 1) < 2e-4


def test_arc_integral_of_a_uniform_pressure() -> None:
    """Hand calculation: a uniform pressure p on the arc |phi| <= a of a circle of radius r has
    the arc integral S = 2 a r p and the resultant N = 2 r p sin a, so S / N = a / sin(a).
    Nodes on that arc, equally penetrated, with their tributary lengths: S from the nodal
    forces' magnitudes, N from their vector sum (the squeeze's definitions), to 1e-5 (the
    nodal quadrature of cos phi with 401 nodes)."""
    r, a, eps, pen = 0.8, np.radians(50.0), 1e5, 1e-5
    wire = RigidCircle((0.0, 0.0), r, inside=False)
    phi = np.linspace(-a, a, 401)
    x = (r - pen) * np.column_stack([np.sin(phi), -np.cos(phi)])
    w = np.full(len(phi), r * (2 * a) / (len(phi) - 1))
    w[[0, -1]] *= 0.5
    st = evaluate_contact(x, w, wire, eps)
    s = np.linalg.norm(st.force, axis=1).sum()
    n = np.linalg.norm(st.force.sum(axis=0))
    p = eps * pen
    assert abs(s / (2 * a * r * p) - 1) < 1e-5
    assert abs((s / n) / (a / np.sin(a)) - 1) < 1e-5


def test_arc_integral_bounds_the_resultant_frictionless() -> None:
    """Without friction S_wire >= N at every pressure (|sum| <= sum of magnitudes), equal at
    first contact (a point contact: one node)."""
    r = squeeze(BASE, MAT, P12, mesh=MESH)
    s, n = r.contact.wire_pressure_integral_n_per_mm, r.squeeze_force_n_per_mm
    assert np.all(s >= n * (1 - 1e-12))
    assert s[-1] / n[-1] > 1.03
    first = np.flatnonzero(n > 0)[0]
    assert len(r.contact.profiles[first]["wire"]["pressure_mpa"]) <= 2 or s[first] / n[first] < 1.01


def test_contact_profiles_integrate_to_the_arc_integral() -> None:
    """The pressure profile along the wire's arc (true pressure, MPa, vs arc, mm) integrates
    (trapezoid, x2 for the half model) to S_wire within 10 %: S_wire is the nodal quadrature,
    whose last active node's tributary length reaches half an element past the trapezoid's end
    (measured -5 % on 5-7 active nodes; a lost factor 2 or a reference-length pressure would
    show). The
    tangential traction never exceeds mu times the pressure (Coulomb, 1e-9)."""
    r = squeeze(BASE, MAT, [0.6], mesh=MESH, mu_wall=0.3, mu_wire=0.3)
    prof = r.contact.profiles[0]["wire"]
    arc, pr = np.array(prof["arc_mm"]), np.array(prof["pressure_mpa"])
    integ = 2.0 * np.trapezoid(pr, arc)
    assert abs(integ / r.contact.wire_pressure_integral_n_per_mm[0] - 1) < 0.10
    sh = np.abs(np.array(prof["shear_mpa"]))
    assert np.all(sh <= 0.3 * pr * (1 + 1e-9) + 1e-12)
    d = r.to_dict()
    for k in ("wire_pressure_integral_n_per_mm", "wall_pressure_integral_n_per_mm",
              "wire_tangential_force_n_per_mm", "stick_fraction_wire", "stick_fraction_wall"):
        assert len(d[k]) == 1


@pytest.mark.parametrize("value", [-0.1, float("nan"), 2.5])
def test_bad_friction_coefficients(value: float) -> None:
    with pytest.raises(InputError, match="mu_wall"):
        squeeze(BASE, MAT, [0.3], mesh=MeshSpec(2, 12), mu_wall=value)


def test_cli_squeeze_friction_json() -> None:
    g = ["--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
         "--shore", "62.5", "--pressures", "0.3,0.6", "--n-radial", "2", "--n-circ", "16"]
    run = subprocess.run([sys.executable, "-m", "exofric", "squeeze", *g, "--mu-wall", "0.3",
                          "--mu-wire", "0.3", "--json"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    d = json.loads(run.stdout)
    assert d["mu_wall"] == 0.3 and len(d["wire_pressure_integral_n_per_mm"]) == 2
    assert 0.0 <= d["stick_fraction_wire"][1] <= 1.0
    bad = subprocess.run([sys.executable, "-m", "exofric", "squeeze", *g, "--mu-wire", "-1"],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "--mu-wire" in bad.stderr and "Traceback" not in bad.stderr
    assert len(bad.stderr.strip().splitlines()) == 1


class _nullcontext:
    def __enter__(self) -> None:
        return None

    def __exit__(self, *a: object) -> None:
        return None


def test_vtu_point_data_and_contact_plot(tmp_path) -> None:
    """--vtu carries the contact pressures as point data (the same values as the profiles) and
    --contact-plot draws pressure vs arc position for both interfaces."""
    import meshio

    g = ["--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
         "--shore", "62.5", "--pressures", "0.6", "--n-radial", "2", "--n-circ", "16"]
    vtu, png = tmp_path / "s.vtu", tmp_path / "c.png"
    run = subprocess.run([sys.executable, "-m", "exofric", "squeeze", *g, "--mu-wall", "0.3",
                          "--vtu", str(vtu), "--contact-plot", str(png), "--json"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    d = json.loads(run.stdout)
    m = meshio.read(vtu)
    wire = d["contact"][0]["wire"]
    got = m.point_data["contact_pressure_wire_mpa"][np.asarray(wire["node"])]
    np.testing.assert_allclose(got, wire["pressure_mpa"], rtol=1e-12)
    assert m.point_data["contact_pressure_wall_mpa"].max() > 0.1
    assert png.stat().st_size > 10_000


def test_plot_contact_pressure_draws_both_arcs() -> None:
    from matplotlib.figure import Figure

    from exofric.plots import plot_contact_pressure

    r = squeeze(BASE, MAT, [0.6], mesh=MeshSpec(2, 16), mu_wall=0.3, mu_wire=0.3)
    ax = plot_contact_pressure(r, Figure().add_subplot())
    labels = [line.get_label() for line in ax.get_lines()]
    assert "wire: pressure" in labels and "wall: friction traction" in labels


def test_full_model_with_friction_is_the_rotated_half_model() -> None:
    """An off-centre wire (20 deg) with friction on both interfaces: the problem is the a = 0
    one turned about the hole's centre (symmetric about the line of the centres, friction
    included), so N, S_wire and the direction of N (20 deg) match the half model to 1e-6
    (measured 1e-9: the same mesh turned)."""
    m = MeshSpec(2, 24, grading=6.0)
    half = squeeze(BASE, MAT, [0.3, 0.6], mesh=m, mu_wall=0.3, mu_wire=0.3)
    off = squeeze(BASE, MAT, [0.3, 0.6], mesh=m, mu_wall=0.3, mu_wire=0.3, wire_angle_deg=20.0)
    np.testing.assert_allclose(off.squeeze_force_n_per_mm, half.squeeze_force_n_per_mm,
                               rtol=1e-6)
    np.testing.assert_allclose(off.contact.wire_pressure_integral_n_per_mm,
                               half.contact.wire_pressure_integral_n_per_mm, rtol=1e-6)
    np.testing.assert_allclose(off.squeeze_force_direction_deg, 20.0, atol=1e-6)


@pytest.mark.parametrize("index", range(7))
def test_paper_structures_converge_with_friction(index: int) -> None:
    """Robustness: every structure of the paper's Table 3 converges with mu 0.3 on both
    interfaces (sweep mesh 2 x 24) and friction lowers N(0.6 MPa) by 2-15 % (physical range:
    the wall friction resists the tube's spreading along the wall)."""
    from exofric.friction import paper_structures

    st = paper_structures()[index]
    fr = squeeze(st, MAT, [0.3, 0.6], mesh=MESH, mu_wall=0.3, mu_wire=0.3, keep_fields=False)
    free = squeeze(st, MAT, [0.3, 0.6], mesh=MESH, keep_fields=False)
    drop = 1 - fr.squeeze_force_n_per_mm[-1] / free.squeeze_force_n_per_mm[-1]
    assert 0.02 < drop < 0.15, drop
