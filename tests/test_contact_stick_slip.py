"""The frictional Newton of issue 37: the semismooth stick/slip direction and the patched refresh.

Independent references: the return map itself evaluated at the stepped position (the exact
Coulomb force the linear model with the predicted classes must reproduce to second order in
the step), a fresh evaluation of the whole problem (what the patched one must equal), and the
converged state of the plain active set (what the semismooth direction must reach: the
direction changes, never the residual).
"""

from __future__ import annotations

import numpy as np
import pytest

from exofric import defaults
from exofric.fe import (
    MeshSpec,
    NewtonSettings,
    RigidCircle,
    SqueezeProblem,
    evaluate_contact,
    evaluate_friction,
    solve_path,
)
from exofric.fe._contact import StickSlipModel
from exofric.fe._solver import _newton
from exofric.geometry import BASE
from exofric.material import MooneyRivlin

MAT = MooneyRivlin.from_shore(62.5)
MESH = MeshSpec(**defaults.SQUEEZE_MESH)
HOLE = RigidCircle((0.0, 0.0), 5.0, True)
EPS, EPS_T, MU, W = 1e5, 1e5, 0.3, 0.2
PEN = 0.005  # mm into the wall: F_n = eps w pen = 100 N/mm, bound mu F_n = 30 N/mm


def _node(offset: float) -> tuple[np.ndarray, np.ndarray]:
    """One node PEN into the hole's wall at the bottom, its anchor ``offset`` mm of arc back
    (trial force eps_t w offset), and its contact state."""
    x = np.array([[0.0, -(5.0 + PEN)]])
    return x, np.array([-0.5 * np.pi - offset / 5.0])


def _force(x: np.ndarray, anchor: np.ndarray) -> np.ndarray:
    """Coulomb friction force on the node at x (N/mm): the return map with bound mu F_n(x)."""
    n = evaluate_contact(x, np.full(1, W), HOLE, EPS)
    return evaluate_friction(x, np.full(1, W), HOLE, EPS, EPS_T, MU, anchor, n).force[0]


@pytest.mark.parametrize("case", ["stick->slip", "slip->stick", "slip reverses"])
def test_predicted_class_reproduces_the_return_map(case: str) -> None:
    """A node whose class the step changes: the linear model in the predicted class (tangent
    at x plus :meth:`StickSlipModel.correction`) gives the return map's force at x + d to
    second order: the force changes by at most 2 B over the step while its direction turns by
    |d| / r (a ~1e-3 mm step on the 5 mm wall), so the model is within 2 B |d| / r (~0.02
    N/mm against a 30 N/mm bound B), while the model of the class at x is off by a share of
    the bound."""
    b = MU * EPS * W * PEN
    # trial force at x as a share of the bound, and the step's tangential length (mm)
    share, step = {"stick->slip": (0.9, 0.2), "slip->stick": (1.5, -0.8),
                   "slip reverses": (1.2, -1.6)}[case]
    x, anchor = _node(share * b / (EPS_T * W))
    d = np.array([[step * b / (EPS_T * W), 0.0]])  # along +x: theta grows at the bottom
    n = evaluate_contact(x, np.full(1, W), HOLE, EPS)
    f0 = evaluate_friction(x, np.full(1, W), HOLE, EPS, EPS_T, MU, anchor, n)
    model = StickSlipModel(x, np.full(1, W), HOLE, EPS, EPS_T, MU, anchor, n.active,
                           np.array([b]))
    cls = model.classify(d)
    assert (model.cls0[0], cls[0]) == {"stick->slip": (2, 1), "slip->stick": (1, 2),
                                       "slip reverses": (1, 2)}[case]
    blocks, shift = model.correction(cls)
    exact = -_force(x + d, anchor)  # the residual's friction part at x + d
    plain = -f0.force[0] + f0.blocks[0] @ d[0]
    switched = -f0.force[0] + shift[0] + (f0.blocks[0] + blocks[0]) @ d[0]
    assert np.max(np.abs(switched - exact)) < 2.0 * b * abs(d[0, 0]) / 5.0
    assert np.max(np.abs(plain - exact)) > 0.05 * b


@pytest.mark.parametrize("ends", ["plane-strain", "open"])
def test_patched_refresh_equals_a_fresh_evaluation(ends: str) -> None:
    """After a refresh of the slip bounds, the held evaluation patched by the friction terms
    (and the cap with open ends) is the problem evaluated afresh: energy, residual and tangent
    to round-off (1e-9 relative to their largest entries)."""
    prob = SqueezeProblem(BASE, MAT, MESH, 1e5, 1.1e-9, "none", 1.0, mu_wall=0.3,
                          mu_wire=0.3, ends=ends)
    pts = solve_path(prob, [0.3, 0.35], NewtonSettings(**defaults.SQUEEZE_NEWTON))
    u0, u1 = pts[0].u, pts[1].u
    prob.refresh(u0)
    held = prob.evaluate(u1, 0.35, True)
    assert held is not None
    assert prob.refresh(u1) > 1e-3  # the bounds moved (N/mm)
    patched = prob.patch_refreshed(held)
    fresh = prob.evaluate(u1, 0.35, True)
    assert patched is not None and fresh is not None
    assert patched[2] is not None and fresh[2] is not None
    assert patched[0] == pytest.approx(fresh[0], rel=1e-12, abs=1e-12)
    scale = np.max(np.abs(fresh[1]))
    np.testing.assert_allclose(patched[1], fresh[1], rtol=0, atol=1e-9 * scale)
    kf, kp = fresh[2].toarray(), patched[2].toarray()
    np.testing.assert_allclose(kp, kf, rtol=0, atol=1e-9 * np.max(np.abs(kf)))
    assert not np.allclose(held[1], fresh[1], rtol=0, atol=1e-9 * scale)  # not trivial


def test_semismooth_direction_reaches_the_plain_state() -> None:
    """From the same state and anchors, Newton with and without the stick/slip classes in the
    direction converges to the same state at each next load (both stop at a residual below
    1e-9 of P x B: N within 1e-8 relative), the semismooth one in fewer iterations overall."""
    s = NewtonSettings(**defaults.SQUEEZE_NEWTON)
    prob = SqueezeProblem(BASE, MAT, MESH, 1e5, 1.1e-9, "none", 1.0, mu_wall=0.3,
                          mu_wire=0.3)
    loads = [0.45, 0.475, 0.5, 0.525, 0.55]
    pts = solve_path(prob, loads[:1], s)
    u, state = pts[0].u, prob.friction_state()
    iters = {False: 0, True: 0}
    for load in loads[1:]:
        n = {}
        for switches in (False, True):
            prob.set_friction_state(state)
            prob.stick_slip_switches = switches
            out = _newton(prob, u, load, s)
            assert out is not None
            n[switches] = prob.resultants(out[0])[0][1]
            iters[switches] += out[1]
            if switches:
                u_next = out[0]
        assert n[True] == pytest.approx(n[False], rel=1e-8)
        prob.set_friction_state(state)
        prob.commit(u_next)
        u, state = u_next, prob.friction_state()
    assert iters[True] < iters[False]
