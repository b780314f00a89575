"""Newton's direction, the banded solve's ordering and the solver statistics (issue 22).

Independent references:

* the banded solve against SciPy's SuperLU (``spsolve``) on the same matrices, and its band
  against SciPy's reverse Cuthill-McKee ordering;
* the active-set direction against its defining property: it minimises the piecewise-
  quadratic model of the energy along the step, m(d) = R.d + d.K.d / 2 +
  sum eps w / 2 <-(g + grad g . d)>^2 over the nodes outside contact (checked by random
  perturbations, which a minimiser of this convex model cannot improve on);
* the converged states, which must not depend on the direction Newton took (the residual
  tolerance bounds the difference).
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.csgraph import reverse_cuthill_mckee
from scipy.sparse.linalg import spsolve

from exofric import defaults
from exofric.fe import (
    InflationProblem,
    MeshSpec,
    NewtonSettings,
    SqueezeProblem,
    collect_stats,
    solve_path,
)
from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.simulate import squeeze

MAT = MooneyRivlin.from_shore(62.5)
SETTINGS = NewtonSettings(**defaults.SQUEEZE_NEWTON)


def _problem(nr: int, nc: int) -> SqueezeProblem:
    return SqueezeProblem(BASE, MAT, MeshSpec(nr, nc), defaults.CONTACT_PENALTY_N_PER_MM3,
                          defaults.SILICONE_DENSITY_T_PER_MM3, gravity="none")


@pytest.mark.parametrize(("nr", "nc"), [(2, 24), (4, 48), (8, 128)])
def test_band_is_no_wider_than_rcm_and_the_solve_matches_superlu(nr: int, nc: int) -> None:
    """The chosen ordering's band <= SciPy's RCM band; solutions agree with SuperLU to 1e-9.

    1e-9 relative: both are direct solves of a system whose condition number is ~1e7
    (penalty contact against the soft floating mode), so agreement to ~1e-16 x 1e7 is expected.
    """
    prob = _problem(nr, nc)
    asm = prob.assembler
    [pt] = solve_path(prob, [0.3], SETTINGS)
    _, _, K = prob.evaluate(pt.u, 0.3, True)
    assert K is not None
    perm = reverse_cuthill_mckee(sp.csr_matrix(K), symmetric_mode=True)
    iperm = np.empty_like(perm)
    iperm[perm] = np.arange(len(perm))
    Kc = K.tocoo()
    rcm_band = int(np.max(np.abs(iperm[Kc.row] - iperm[Kc.col])))
    assert asm.band <= rcm_band
    if (nr, nc) == (8, 128):  # the line-by-line order: 4 (2 n_radial + 1) + 5 = 73 dofs
        assert asm.band < 0.7 * rcm_band
    b = np.random.default_rng(1).standard_normal(asm.nf)
    x = asm.solve(K, b)
    ref = spsolve(K.tocsc(), b)
    assert np.max(np.abs(x - ref)) <= 1e-9 * np.max(np.abs(ref))


def _contact_model(prob: SqueezeProblem, u: np.ndarray, K: sp.csc_matrix, R: np.ndarray):
    """m(d) over the free dofs: the Newton quadratic plus the penalty of nodes now outside."""
    xo = (prob.X + u).reshape(-1, 2)[prob.outer]
    lin = []
    for c in (prob.hole, prob.wire):
        vec = xo - np.asarray(c.center)
        dist = np.linalg.norm(vec, axis=1)
        n = vec / dist[:, None]
        g, grad = (c.radius - dist, -n) if c.inside else (dist - c.radius, n)
        lin.append((g, grad))
    kw = prob.penalty * prob.w_outer
    free = prob.free

    def m(d: np.ndarray) -> float:
        step = np.zeros(prob.n_dofs)
        step[free] = d
        dn = step[prob.contact_dofs]
        val = float(R[free] @ d + 0.5 * d @ (K @ d))
        for g, grad in lin:
            gl = g + np.sum(grad * dn, axis=1)
            outside = g > 0.0
            val += 0.5 * float(np.sum((kw * np.minimum(gl, 0.0) ** 2)[outside]))
        return val

    def entering(d: np.ndarray) -> int:
        step = np.zeros(prob.n_dofs)
        step[free] = d
        dn = step[prob.contact_dofs]
        return sum(int(np.sum((g > 0) & (g + np.sum(grad * dn, axis=1) < 0))) for g, grad in lin)

    return m, entering


def test_active_set_direction_minimises_the_piecewise_contact_model() -> None:
    """From the state at 0.3 MPa loaded to 0.35 MPa, the plain Newton step runs nodes into the
    obstacles; the refined direction is the minimiser of the model with those contacts."""
    prob = _problem(4, 48)
    [pt] = solve_path(prob, [0.3], SETTINGS)
    u, load = pt.u, 0.35
    _, R, K = prob.evaluate(u, load, True)
    assert K is not None
    rhs = -R[prob.free]
    plain = prob.assembler.solve(K, rhs)
    d = prob.refine_direction(u, K, rhs, plain, prob.assembler.solve, 3)
    m, entering = _contact_model(prob, u, K, R)
    assert entering(plain) > 0  # the case the refinement is for
    assert not np.array_equal(d, plain)
    assert m(d) < m(plain)
    rng = np.random.default_rng(7)
    scale = float(np.max(np.abs(d)))
    m0 = m(d)
    for eps in (1e-3, 1e-5):
        for _ in range(10):
            v = rng.standard_normal(d.size)
            v *= eps * scale / np.max(np.abs(v))
            # a minimiser: no perturbation lowers m (beyond round-off of m's size)
            assert m(d + v) >= m0 - 1e-12 * abs(m0)


def test_converged_squeeze_does_not_depend_on_the_direction() -> None:
    """Plain Newton (no active-set re-solves, no early cut-back) and the default reach the same
    N to 1e-7 relative: both stop at a residual below 1e-9 of P x B (N/mm) and the contact
    stiffness maps that to N changes orders of magnitude below 1e-7."""
    p = np.array([0.1, 0.3, 0.6])
    mesh = MeshSpec(4, 48)
    plain = NewtonSettings(**{**defaults.SQUEEZE_NEWTON, "active_set_iterations": 0,
                              "stagnation_ratio": 0.0})
    a = squeeze(BASE, MAT, p, mesh=mesh, settings=plain, keep_fields=False)
    b = squeeze(BASE, MAT, p, mesh=mesh, keep_fields=False)
    assert np.allclose(a.squeeze_force_n, b.squeeze_force_n, rtol=1e-7, atol=0.0)
    assert b.solver_stats.iterations < a.solver_stats.iterations  # the point of it


def test_stats_count_attempts_and_failed_time() -> None:
    """A 0.6 MPa inflation in one step with 3 Newton iterations allowed must cut back: the
    failed attempts are counted and their time is part of the total; collectors nest."""
    prob = InflationProblem(8.3, 4.97, MAT, MeshSpec())
    # chord_step 0: a factorisation at every iteration (chord steps would solve without one)
    s = NewtonSettings(max_step=0.6, max_iter=3, extrapolate=False, chord_step=0.0)
    with collect_stats() as outer:
        with collect_stats() as inner:
            solve_path(prob, [0.6], s)
        first = inner.stats
        solve_path(prob, [0.2], NewtonSettings())
    st = outer.stats
    assert first.failed_attempts >= 1
    assert 0.0 < first.failed_time_s <= first.time_s
    assert first.iterations >= 3 * first.failed_attempts  # each failed one used its 3
    assert first.linear_solves >= first.iterations
    assert st.attempts > first.attempts
    assert st.failed_attempts == first.failed_attempts
    assert st.to_dict()["failed_time_pct"] == pytest.approx(
        100.0 * st.failed_time_s / st.time_s)


def test_squeeze_reports_its_solver_stats() -> None:
    r = squeeze(BASE, MAT, [0.3, 0.6], mesh=MeshSpec(2, 24), keep_fields=False)
    d = r.to_dict()["solver_stats"]
    assert d["attempts"] >= 2 and d["iterations"] >= d["attempts"] - d["failed_attempts"]
    assert 0.0 < d["time_s"] <= r.solve_time_s


def test_factorization_reuse_matches_superlu_for_several_right_hand_sides() -> None:
    """One factorisation (banded Cholesky for the SPD tangent, banded LU for a non-symmetric
    perturbation of it) serves several right-hand sides, each within 1e-9 of SciPy's SuperLU
    (``spsolve``, an independent direct solver; 1e-9 for the condition number ~1e7 as above)."""
    prob = _problem(2, 24)
    asm = prob.assembler
    [pt] = solve_path(prob, [0.3], SETTINGS)
    _, _, K = prob.evaluate(pt.u, 0.3, True)
    assert K is not None
    rng = np.random.default_rng(3)
    skew = K.copy()
    skew.data = skew.data + 1e-3 * np.abs(skew.data).max() * rng.standard_normal(skew.nnz)
    for A in (K, skew):
        f = asm.factorize(A)
        for _ in range(3):
            b = rng.standard_normal(asm.nf)
            x, ref = f.solve(b), spsolve(A.tocsc(), b)
            assert np.max(np.abs(x - ref)) <= 1e-9 * np.max(np.abs(ref))
        B = rng.standard_normal((asm.nf, 4))  # several columns in one sweep (Woodbury updates)
        X, ref = f.solve(B), spsolve(A.tocsc(), B)
        assert X.shape == B.shape
        assert np.max(np.abs(X - ref)) <= 1e-9 * np.max(np.abs(ref))


def _residual_log(prob: InflationProblem) -> list[tuple[float, float, bool]]:
    """Wrap ``prob.evaluate`` to log (load MPa, |R|_inf / force scale, tangent asked)."""
    log: list[tuple[float, float, bool]] = []
    evaluate = prob.evaluate

    def logged(u: np.ndarray, load: float, tangent: bool):  # type: ignore[no-untyped-def]
        out = evaluate(u, load, tangent)
        if out is not None:
            log.append((load, float(np.max(np.abs(out[1][prob.free]))) / prob.scales(load)[0],
                        tangent))
        return out

    prob.evaluate = logged  # type: ignore[method-assign]
    return log


def test_chord_steps_reach_the_full_newton_state_and_newton_stays_quadratic() -> None:
    """Issue 37: the residual-only trials and the reuse of the last factorisation (chord steps)
    save tangents and factorisations but not accuracy.

    * Free inflation to 0.3 MPa: with ``chord_step`` 0 (a tangent at every iterate) the
      convergence is quadratic, r_{k+1} <= 1e3 r_k^2 (relative residuals) wherever r_k < 1e-3
      and r_{k+1} is above round-off (1e-12); the default reaches the same state to 1e-9 of
      the displacement scale (both stop at a residual of 1e-9 of P x B, the stiffness maps it
      to displacements of that order), with fewer factorisations and some evaluations without
      a tangent.
    * Squeeze (contact, 2 x 24 mesh): N at 0.1, 0.3, 0.6 MPa the same to 1e-7 (as above).
    """
    runs = {}
    for cs in (0.0, defaults.NEWTON["chord_step"]):
        prob = InflationProblem(8.3, 4.97, MAT, MeshSpec(2, 6))
        log = _residual_log(prob)
        with collect_stats() as st:
            [pt] = solve_path(prob, [0.3], NewtonSettings(**{**defaults.NEWTON,
                                                             "chord_step": cs}))
        runs[cs] = (pt.u, log, st.stats)
    u0, log0, st0 = runs[0.0]
    u1, log1, st1 = runs[defaults.NEWTON["chord_step"]]
    assert all(t for _, r, t in log0 if r > 0.0)  # every iterate had its tangent
    pairs = [(a[1], b[1]) for a, b in zip(log0[:-1], log0[1:], strict=True)
             if a[0] == b[0] and a[1] < 1e-3 and b[1] > 1e-12]
    assert pairs and all(r1 <= 1e3 * r0**2 for r0, r1 in pairs)
    assert np.max(np.abs(u1 - u0)) <= 1e-9 * 4.15
    assert st1.linear_solves < st0.linear_solves
    assert sum(not t for _, _, t in log1) > sum(not t for _, _, t in log0)
    p = np.array([0.1, 0.3, 0.6])
    full = NewtonSettings(**{**defaults.SQUEEZE_NEWTON, "chord_step": 0.0})
    a = squeeze(BASE, MAT, p, mesh=MeshSpec(2, 24), settings=full, keep_fields=False)
    b = squeeze(BASE, MAT, p, mesh=MeshSpec(2, 24), keep_fields=False)
    assert np.allclose(a.squeeze_force_n, b.squeeze_force_n, rtol=1e-7, atol=0.0)
    assert b.solver_stats.linear_solves < a.solver_stats.linear_solves


def test_angle_wrap_matches_the_complex_exponential() -> None:
    """The slip angle's wrap to (-pi, pi] (issue 37: without a complex exponential) equals
    ``np.angle(np.exp(1j a))`` to 1e-15 rad (round-off of the remainder) away from the branch
    cut, and gives +pi on it."""
    from exofric.fe._contact import _wrap

    a = np.random.default_rng(5).uniform(-40.0, 40.0, 10_000)
    assert np.max(np.abs(_wrap(a) - np.angle(np.exp(1j * a)))) <= 1e-15 * 40.0
    assert _wrap(np.array([-np.pi, np.pi]))[0] == np.pi


@pytest.mark.parametrize("max_step", [0.015, 0.00625])
def test_each_output_takes_the_fewest_full_steps(max_step: float) -> None:
    """Outputs every 0.05 MPa (np.linspace, not exact in binary): each takes ceil(0.05 /
    max_step) sub-steps, the last one landing on the output exactly. Before issue 37 a step
    shortened to reach an output shrank the next (max_step 0.015: 4, 5, 7, 4, 5, 7, ...), and a
    round-off sliver short of an output was a sub-step of its own that shrank the step to
    ~1e-15 MPa (friction with open ends then failed at 0.55 MPa after thousands of them)."""
    prob = InflationProblem(8.3, 4.97, MAT, MeshSpec())
    loads = np.linspace(0.05, 0.6, 12)
    pts = solve_path(prob, loads, NewtonSettings(max_step=max_step))
    assert [pt.steps for pt in pts] == [int(np.ceil(0.05 / max_step - 1e-9))] * 12
    assert [pt.load for pt in pts] == loads.tolist()


class _FarPredictor:
    """An inflation problem whose load-step predictor is thrown 30 times too far (as a
    secant predictor past a contact's edge on a fine mesh): every attempt from it fails."""

    def __init__(self) -> None:
        self.inner = InflationProblem(8.3, 4.97, MAT, MeshSpec())
        self.n_dofs, self.free = self.inner.n_dofs, self.inner.free
        self.predicted = 0

    def evaluate(self, u: np.ndarray, load: float, tangent: bool):  # type: ignore[no-untyped-def]
        return self.inner.evaluate(u, load, tangent)

    def scales(self, load: float) -> tuple[float, float]:
        return self.inner.scales(load)

    def limit_predictor(self, u: np.ndarray, guess: np.ndarray) -> np.ndarray:
        self.predicted += 1
        return u + 30.0 * (guess - u)


def test_a_failed_predictor_is_retried_from_the_last_state_and_then_left_off() -> None:
    """Issue 37: an attempt from the predictor takes full Newton steps only, and after one
    has failed the rest of the path starts from the last converged state. Reference: the
    same path solved without any predictor (``extrapolate=False``), to the solver's
    tolerance; the far predictor is asked for once and fails once (before, it failed at
    every sub-step, each failure running to the stagnation test)."""
    loads = np.linspace(0.1, 0.6, 6)
    s = NewtonSettings(max_step=0.05)
    far = _FarPredictor()
    with collect_stats() as st:
        got = solve_path(far, loads, s)  # type: ignore[arg-type]
    ref = solve_path(InflationProblem(8.3, 4.97, MAT, MeshSpec()), loads,
                     NewtonSettings(max_step=0.05, extrapolate=False))
    assert far.predicted == 1
    assert st.stats.failed_attempts == 1
    for a, b in zip(got, ref, strict=True):
        assert np.max(np.abs(a.u - b.u)) <= 1e-8 * max(1.0, np.max(np.abs(b.u)))


@pytest.mark.parametrize("n_changed", [1, 6, 7, 20])
def test_active_set_resolve_by_low_rank_update_matches_superlu(n_changed: int) -> None:
    """Issue 37: an active-set matrix that differs from the factorised tangent in a few
    nodes' dofs (a node entering contact adds a 2 x 2 stiffness block) is solved by the
    Woodbury identity on the tangent's factors, without a factorisation, and matches SciPy's
    SuperLU on the changed matrix within 1e-9 (as above). More than 14 changed dofs
    (7 nodes) are factorised instead (counted)."""
    from exofric.fe._solver import _Linear

    prob = _problem(2, 24)
    [pt] = solve_path(prob, [0.3], SETTINGS)
    _, _, K = prob.evaluate(pt.u, 0.3, True)
    assert K is not None
    counter = [0, 0]
    lin = _Linear(prob, counter)
    lin.set_tangent(K)
    rng = np.random.default_rng(7)
    diag_nodes = rng.choice(K.shape[0] // 2, n_changed, replace=False)
    dofs = np.concatenate([2 * diag_nodes, 2 * diag_nodes + 1])
    bump = sp.coo_matrix((np.full(dofs.size, 1e3), (dofs, dofs)), shape=K.shape)
    A = (K + bump).tocsc()
    A.sort_indices()
    same_pattern = A.nnz == K.nnz and np.array_equal(A.indices, K.indices)
    b = rng.standard_normal(K.shape[0])
    x = lin.solve(A, b)
    ref = spsolve(A, b)
    assert np.max(np.abs(x - ref)) <= 1e-9 * np.max(np.abs(ref))
    factorised = counter[1] - 1
    assert same_pattern
    assert factorised == (0 if 2 * n_changed <= 14 else 1)
