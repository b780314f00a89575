"""Acceptance: the qualitative findings of paper §5 / Fig 12 on the default plant and gains.

Paper (54.40 N, test-5 structure): PD without the model keeps a steady-state error, with it
none (4.41 s); PI 5.73 -> 4.20 s (-26 %); PID 6.17 -> 4.39 s (-29 %). The plant and gains are
exofric's documented defaults (docs/paper-notes.md), not fitted to these numbers
except where that note says so.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from exofric import paper
from exofric.control import PlantParams
from exofric.reproduction import CompareResult, ControlSetup, compare

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
    assert nominal.reduction_pct(kind) >= 20.0      # its definition: test_reduction_is_...
    for ff in (False, True):                 # integral action: no steady-state error
        assert abs(_case(nominal, kind, ff).metrics.steady_state_error) < 0.005 * TARGET


def test_reduction_is_the_papers_percentage_of_the_time_without_model(nominal):
    # Independent reference: the paper's printed settling times (5.73 -> 4.20 s for PI,
    # 6.17 -> 4.39 s for PID) and its printed reductions "26 %" and "29 %" (26.7 % and 28.8 %
    # by hand: the paper truncated one and rounded the other, so within 1 %-point).
    s = paper.scalar
    times = {("pi", False): s("settling_pi_s"), ("pi", True): s("settling_pi_model_s"),
             ("pid", False): s("settling_pid_s"), ("pid", True): s("settling_pid_model_s")}
    # the four cases with the paper's settling times (real CaseResults: the class checks
    # its fields' kinds, issue 38)
    cases = tuple(replace(c, metrics=replace(c.metrics, settling_time_s=times[key]))
                  for c in nominal.cases if (key := (c.controller, c.feedforward)) in times)
    res = CompareResult(cases, TARGET, 0.0, "2dof")
    assert res.reduction_pct("pi") == pytest.approx(s("settling_reduction_pi_pct"), abs=1.0)
    assert res.reduction_pct("pid") == pytest.approx(s("settling_reduction_pid_pct"), abs=1.0)
    assert res.reduction_pct("pd") is None                  # no PD pair in these cases


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


# --- the one-call closed loop (issue 34) ----------------------------------------------------

def _linear_map(slope_n_per_mpa: float):
    """F = slope x P exactly (a straight N(P) is interpolated exactly by the map's PCHIP)."""
    import numpy as np

    from exofric.control import CurveFrictionMap

    p = np.linspace(0.0, 1.0, 11)
    return CurveFrictionMap(tuple(p), tuple(2.0 * slope_n_per_mpa * p), 0.5)


def test_closed_loop_pi_matches_python_control_on_a_linear_plant():
    """Independent reference: python-control's continuous step response of the PI loop
    C(s) G(s) / (1 + C G), G = K/(tau s + 1), with the gains closed_loop chose. Our loop is
    discrete (dt 2 ms): the trajectories agree to 0.05 % of the 60 N step (measured 0.034 %,
    the discretisation), the 2 % settling time to one sample of python-control's 10 ms grid
    (its step_info)."""
    import control as ct
    import numpy as np

    from exofric.control import PlantParams, closed_loop

    k, tau = 300.0, 0.8
    plant = PlantParams(time_constant_s=tau, delay_s=0.0, p_max_mpa=1.0)
    r = closed_loop(_linear_map(k), 60.0, "pi", None, plant=plant, duration_s=5.0, dt_s=0.002)
    g = r.tuning.gains
    s = ct.tf("s")
    loop = ct.feedback((g.kp + g.ki / s) * k / (tau * s + 1), 1)
    t = r.simulation.time_s[::5]                     # python-control on a 10 ms grid
    _, y = ct.step_response(60.0 * loop, T=t)
    assert np.max(np.abs(y - r.simulation.friction_n[::5])) < 0.0005 * 60.0
    info = ct.step_info(60.0 * loop, T=t, SettlingTimeThreshold=0.02)
    assert abs(info["SettlingTime"] - r.settling_time_s) <= 0.01   # one sample of its grid
    assert r.to_dict()["controller"] == "pi" and r.feedforward is None


def test_closed_loop_2dof_with_an_exact_model_follows_the_plant_step_closed_form():
    """With an exact linear model the 2-DOF loop's friction is the model's own FOPDT response,
    F(t) = F* (1 - exp(-(t - theta)/tau)) for t > theta (closed form; the feedback has nothing
    to correct), so it settles at theta + tau ln(50) for a 2 % band. Tolerance: 1e-9 N
    (round-off; measured 1e-12) and one sample (2 ms)."""
    import numpy as np

    from exofric.control import PlantParams, closed_loop

    tau, theta = 0.8, 0.2
    plant = PlantParams(time_constant_s=tau, delay_s=theta, p_max_mpa=1.0)
    r = closed_loop(_linear_map(300.0), 60.0, "pid", "2dof", plant=plant, duration_s=5.0,
                    dt_s=0.002)
    t = r.simulation.time_s
    ref = np.where(t > theta, 60.0 * (1.0 - np.exp(-(t - theta) / tau)), 0.0)
    assert np.max(np.abs(ref - r.simulation.friction_n)) < 1e-9
    assert abs(r.settling_time_s - (theta + tau * np.log(50.0))) <= 0.002


def test_closed_loop_takes_a_squeeze_curve_and_plots(tmp_path):
    """The natural objects: a squeeze result (here a SqueezeCurve of Eq 9's N) and gamma; bad
    arguments are InputErrors naming the parameter."""
    import numpy as np
    from matplotlib.figure import Figure

    from exofric.control import closed_loop
    from exofric.errors import InputError
    from exofric.friction import SqueezeCurve

    p = np.linspace(0.05, 0.6, 12)
    curve = SqueezeCurve(p, 400.0 * p**2)
    r = closed_loop(curve, 40.0, gamma=0.5, duration_s=6.0)
    assert abs(r.feedforward_pressure_mpa - np.sqrt(40.0 / 200.0)) < 1e-3   # F = 200 P^2
    ax = r.plot(Figure().subplots())
    assert "settles in" in ax.get_title()
    with pytest.raises(InputError, match="controller"):
        closed_loop(curve, 40.0, "pii")
    with pytest.raises(InputError, match="feedforward"):
        closed_loop(curve, 40.0, feedforward="dynamic")  # type: ignore[arg-type]
