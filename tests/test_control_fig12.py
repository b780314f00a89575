"""Acceptance: the qualitative findings of paper §5 / Fig 12 on the default plant and gains.

Paper (54.40 N, test-5 structure): PD without the model keeps a steady-state error, with it
none (4.41 s); PI 5.73 -> 4.20 s (-26 %); PID 6.17 -> 4.39 s (-29 %). The plant and gains are
exofric's documented defaults (docs/paper-notes.md), not fitted to these numbers
except where that note says so.
"""

from __future__ import annotations

import pytest

from exofric.control import PlantParams
from exofric.reproduce import ControlSetup, compare

TARGET = 54.40


@pytest.fixture(scope="module")
def nominal():
    return compare(ControlSetup.default())


@pytest.fixture(scope="module")
def mismatched():
    return compare(ControlSetup.default(plant=PlantParams(mismatch=0.1)))


def _case(res, kind, ff):
    return next(c for c in res.cases if c.controller == kind and c.feedforward == ff)


def test_pd_steady_state_error_without_and_with_model(nominal):
    pd = _case(nominal, "pd", False).metrics
    assert abs(pd.steady_state_error) > 0.02 * TARGET
    assert pd.settling_time_s is None
    pdm = _case(nominal, "pd", True).metrics
    assert abs(pdm.steady_state_error) < 0.005 * TARGET
    assert pdm.settling_time_s is not None


@pytest.mark.parametrize("kind", ["pi", "pid"])
def test_model_shortens_settling_by_at_least_20pct(nominal, kind):
    t0 = _case(nominal, kind, False).metrics.settling_time_s
    t1 = _case(nominal, kind, True).metrics.settling_time_s
    assert t0 is not None and t1 is not None
    assert t1 <= 0.8 * t0
    assert nominal.reduction_pct(kind) == pytest.approx(100 * (t0 - t1) / t0)
    for ff in (False, True):                 # integral action: no steady-state error
        assert abs(_case(nominal, kind, ff).metrics.steady_state_error) < 0.005 * TARGET


@pytest.mark.parametrize("kind", ["pi", "pid"])
def test_with_10pct_mismatch_integral_action_removes_the_error(mismatched, kind):
    # The feedforward benefit under mismatch is *reported*, whatever its value: it must be a
    # number in the JSON, and is documented in docs/paper-notes.md (about -37 % /
    # -34 % for +10 %; the value is not asserted).
    d = mismatched.to_dict()
    assert d["mismatch"] == 0.1
    assert isinstance(d["settling_reduction_pct"][kind], float)
    for ff in (False, True):
        m = _case(mismatched, kind, ff).metrics
        assert abs(m.steady_state_error) < 0.005 * TARGET


def test_pd_with_model_keeps_an_error_under_mismatch(mismatched):
    # Without integral action a gamma error shows: the true friction map is 10 % steeper,
    # so PD + model ends above the target (sign: error = target - final < 0).
    m = _case(mismatched, "pd", True).metrics
    assert m.steady_state_error < -0.02 * TARGET


def test_static_feedforward_overshoots_documented_finding():
    # Documented finding (not a paper claim): adding P_ff to a PI's output without telling
    # the feedback what to expect double-counts during the supply lag; on Eq 9's steep map
    # (dlnF/dlnP = 2.5 at 54.4 N) the PI overshoots by > 20 % and gains < 20 % settling.
    res = compare(ControlSetup.default(ff_mode="static"))
    pi = _case(res, "pi", True).metrics
    assert pi.overshoot_pct > 20.0
    red = res.reduction_pct("pi")
    assert red is None or red < 20.0


def test_tight_tuning_reverses_the_benefit_documented_finding():
    # With SIMC's tight setting (tau_c = theta) the feedback alone settles faster than the
    # supply's open-loop response, so the (2-DOF) model feedforward slows PI down.
    res = compare(ControlSetup.default(tau_c_s=0.2))
    red = res.reduction_pct("pi")
    assert red is not None and red < 0.0
