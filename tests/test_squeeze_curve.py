"""SqueezeCurve against closed forms (convergence, inverse, monotonicity) and check_series."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from exofric.control import CurveFrictionMap
from exofric.errors import InputError, PlausibilityWarning, check_series
from exofric.friction import SqueezeCurve, match_squeeze

# Closed form: no force before contact onset P0, then N = A (P - P0)^2 (N, MPa).
A, P0, PMAX = 1500.0, 0.15, 0.6


def exact(p: np.ndarray) -> np.ndarray:
    return A * np.clip(p - P0, 0.0, None) ** 2


def exact_inverse(n: np.ndarray) -> np.ndarray:
    return P0 + np.sqrt(n / A)


def curve_with(m: int) -> SqueezeCurve:
    p = np.linspace(0.0, PMAX, m + 1)          # P0 = 0.15 MPa is a node for m % 4 == 0
    return SqueezeCurve(p, exact(p))


def _orders(errors: list[float]) -> np.ndarray:
    return np.log2(np.asarray(errors[:-1]) / np.asarray(errors[1:]))


def test_interpolation_converges_to_the_closed_form() -> None:
    # Off-node points (midpoints and 30 % into each interval). Observed: the maximum error
    # halves its order near the onset, where the PCHIP harmonic-mean slope at P0 + h is
    # 1.5 A h against the true 2 A h -> O(h^2) overall (measured order 2.000); away from the
    # onset (P > 0.3 MPa) the interpolant is O(h^3) (measured 3.01-3.14). The slope is O(h).
    ms = [16, 32, 64, 128, 256]
    err, err_far, err_slope = [], [], []
    for m in ms:
        c = curve_with(m)
        p = np.asarray(c.pressure_mpa)
        h = p[1] - p[0]
        x = np.concatenate([p[:-1] + 0.5 * h, p[:-1] + 0.3 * h])
        err.append(float(np.max(np.abs(c(x) - exact(x)))))
        far = x[x > 0.3]
        err_far.append(float(np.max(np.abs(c(far) - exact(far)))))
        err_slope.append(float(np.max(np.abs(c.slope(x) - 2 * A * np.clip(x - P0, 0, None)))))
    np.testing.assert_allclose(_orders(err), 2.0, atol=0.05)
    assert np.all(_orders(err_far) > 2.9)
    np.testing.assert_allclose(_orders(err_slope), 1.0, atol=0.05)
    assert err[-1] < 1e-3                     # N up to 304 N: 3e-6 relative at 257 nodes


def test_nodes_are_reproduced_and_shapes_follow_the_input() -> None:
    c = curve_with(24)
    p, n = np.asarray(c.pressure_mpa), np.asarray(c.squeeze_force_n)
    np.testing.assert_allclose(c(p), n, rtol=1e-14, atol=1e-12)
    assert isinstance(c(0.3), float) and c(p.reshape(5, 5)).shape == (5, 5)
    assert c(np.array(0.3)) == c(0.3)


def test_inverse_round_trips_and_matches_the_closed_form() -> None:
    targets = np.linspace(1.0, float(exact(np.array(PMAX))), 37)
    prev = None
    for m in (32, 64, 128):
        c = curve_with(m)
        got = np.array([c.pressure(v) for v in targets])
        # round trip on the interpolant itself (Brent to 1e-12 MPa, slope <= 1350 N/MPa)
        back = c(got)
        np.testing.assert_allclose(back, targets, rtol=1e-10, atol=2e-9)
        e = float(np.max(np.abs(got - exact_inverse(targets))))
        if prev is not None:
            assert e < prev / 4                # at least second order
        prev = e
    assert prev is not None and prev < 1e-6    # 7e-7 MPa at 129 nodes
    c = curve_with(32)
    assert c.pressure(0.0) == pytest.approx(P0, abs=1e-15)       # the contact onset node
    assert c.pressure(c.squeeze_force_n[-1]) == pytest.approx(PMAX, abs=1e-12)


def test_inverse_range_and_errors() -> None:
    c = SqueezeCurve([0.2, 0.3, 0.4], [10.0, 40.0, 90.0])
    assert c.force_range_n == (10.0, 90.0) and c.pressure_range_mpa == (0.2, 0.4)
    assert c.pressure(10.0) == 0.2 and c.pressure(40.0) == 0.3
    with pytest.raises(InputError, match=r"squeeze_force_n must be in .*\[10, 90\] N, got 95"):
        c.pressure(95.0)
    with pytest.raises(InputError, match="reachable range"):
        c.pressure(5.0)
    with pytest.raises(InputError, match="squeeze_force_n"):
        c.pressure(float("nan"))
    with pytest.raises(InputError, match="stays at 0 N"):
        SqueezeCurve([0.1, 0.2], [0.0, 0.0]).pressure(0.0)


def test_first_crossing_on_a_non_monotone_curve() -> None:
    # N rises, dips, rises again: the least pressure reaching 30 N is in the first rise.
    with pytest.warns(PlausibilityWarning, match="falls from 40 to 20 N"):
        c = SqueezeCurve([0.0, 0.1, 0.2, 0.3, 0.4], [0.0, 40.0, 20.0, 60.0, 80.0])
    p = c.pressure(30.0)
    assert 0.0 < p < 0.1 and c(p) == pytest.approx(30.0, abs=1e-9)


def test_pchip_is_monotone_without_overshoot() -> None:
    # A plateau then a jump: a cubic spline overshoots both ends of the jump; PCHIP stays
    # inside each interval's data range and is non-decreasing (it is monotone per interval).
    p = np.array([0.0, 0.1, 0.2, 0.3, 0.4, 0.5])
    n = np.array([0.0, 0.0, 0.0, 50.0, 51.0, 51.5])
    x = np.linspace(0.0, 0.5, 2001)
    spline = CubicSpline(p, n)(x)
    assert spline.min() < -1.0 and spline.max() > 51.5     # the reference does overshoot
    y = SqueezeCurve(p, n)(x)
    assert np.all(np.diff(y) >= 0.0)
    assert y.min() == 0.0 and y.max() <= 51.5 + 1e-12
    assert np.all(y[x <= 0.2] == 0.0)                      # no force before contact
    k = np.clip(np.searchsorted(p, x, side="right") - 1, 0, p.size - 2)
    assert np.all((y >= n[k] - 1e-12) & (y <= n[k + 1] + 1e-12))


@pytest.mark.parametrize(
    ("p", "n", "field"),
    [
        ([0.1, np.nan, 0.3], [1.0, 2.0, 3.0], "pressure_mpa must be finite"),
        ([0.1, 0.2, 0.3], [1.0, np.inf, 3.0], "squeeze_force_n must be finite"),
        ([0.3, 0.2, 0.1], [1.0, 2.0, 3.0], "pressure_mpa must be strictly increasing"),
        ([0.1, 0.1, 0.3], [1.0, 2.0, 3.0], "pressure_mpa must be strictly increasing"),
        ([0.1, 0.2, 0.3], [1.0, 2.0], "pressure_mpa and squeeze_force_n must have the same"),
        ([0.1], [1.0], "pressure_mpa needs at least 2 values, got 1"),
        ([-0.1, 0.2], [1.0, 2.0], "pressure_mpa must be >= 0 MPa"),
        ([0.1, 0.2], [-1.0, 2.0], "squeeze_force_n must be >= 0 N"),
        (["a", "b"], [1.0, 2.0], "pressure_mpa must be a list of numbers"),
    ],
)
def test_bad_curves_raise_naming_the_field(p: list, n: list, field: str) -> None:
    with pytest.raises(InputError, match=field) as info:
        SqueezeCurve(p, n)
    msg = str(info.value)
    assert msg.startswith("squeeze curve: ") and "\n" not in msg
    assert info.value.param in ("pressure_mpa", "squeeze_force_n")


def test_evaluation_range_and_edge_tolerance() -> None:
    c = SqueezeCurve([0.2, 0.4, 0.6], [10.0, 50.0, 90.0])
    with pytest.raises(InputError, match=r"pressure_mpa must be in .*\[0.2, 0.6\] MPa, got 0.7"):
        c([0.3, 0.7])
    with pytest.raises(InputError, match="pressure_mpa"):
        c.slope(0.1)
    assert c(0.6004, edge_tol_mpa=0.005) == pytest.approx(90.08, abs=1e-9)   # linear data
    with pytest.raises(InputError, match="edge_tol_mpa"):
        c(0.3, edge_tol_mpa=-1.0)
    assert c.slope(0.5) == pytest.approx(200.0)


def test_dict_round_trip_origin_and_from_result() -> None:
    c = SqueezeCurve(np.array([0.2, 0.4]), np.array([1.0, 3.0]))
    assert c.to_dict() == {"pressure_mpa": [0.2, 0.4], "squeeze_force_n": [1.0, 3.0]}
    assert SqueezeCurve.from_dict(c.to_dict()) == c
    with pytest.raises(InputError, match="missing key 'squeeze_force_n'"):
        SqueezeCurve.from_dict({"pressure_mpa": [0.2, 0.4]})
    o = c.with_origin()
    assert o.pressure_mpa == (0.0, 0.2, 0.4) and o.squeeze_force_n == (0.0, 1.0, 3.0)
    assert o.with_origin() is o
    res = SimpleNamespace(pressure_mpa=np.array([0.0, 0.5]), squeeze_force_n=np.array([0, 2]))
    assert SqueezeCurve.from_result(res) == SqueezeCurve([0.0, 0.5], [0.0, 2.0])  # type: ignore[arg-type]


def test_users_share_the_interpolant() -> None:
    c = curve_with(12)
    p, n = c.pressure_mpa, c.squeeze_force_n
    x = np.linspace(0.0, PMAX, 61)
    got, inside = match_squeeze(p, n, x)
    assert inside.all() and np.array_equal(got, c(x))
    fmap = CurveFrictionMap(p, n, 0.7)
    np.testing.assert_array_equal(fmap(x), 0.7 * c(x))
    # above the last pressure the map continues with the interpolant's end slope (C1)
    assert fmap(0.7) == pytest.approx(0.7 * (c(PMAX) + 0.1 * c.slope(PMAX)), rel=1e-12)
    # the map's inverse is the curve's: one inverse, exact on the same interpolant
    for f in (0.7 * c(P0 + 0.01), 0.7 * c(0.33), 0.7 * c(PMAX)):
        assert fmap.inverse(f) == c.pressure(f / 0.7)


# ---------------------------------------------------------------------------- check_series


def test_check_series_returns_flat_float_arrays() -> None:
    x, y = check_series("time_s", [[0.0, 1.0, 2.5]], "friction_n", (1, 2, 3))
    assert x.tolist() == [0.0, 1.0, 2.5] and y.tolist() == [1.0, 2.0, 3.0]
    x1, none = check_series("pressures_mpa", [0.3], min_points=1)
    assert x1.tolist() == [0.3] and none is None
    x2, _ = check_series("value", [3.0, 1.0, 3.0], increasing=False)
    assert x2.tolist() == [3.0, 1.0, 3.0]


@pytest.mark.parametrize(
    ("kwargs", "message", "param"),
    [
        ({"x": [0.0, 0.2, 0.1], "x_unit": "s"},
         "time_s must be strictly increasing (s), got 0.2 then 0.1 at index 2", "time_s"),
        ({"x": [0.0, 0.1], "y": [1.0], "x_unit": "s"},
         "time_s and response_n must have the same length, got 2 and 1", "time_s"),
        ({"x": [0.0, float("nan")], "x_unit": "s"},
         "time_s must be finite numbers (s), got nan at index 1", "time_s"),
        ({"x": [0.0, 1.0], "y": [1.0, float("inf")], "y_unit": "N"},
         "response_n must be finite numbers (N), got inf at index 1", "response_n"),
        ({"x": [0.0], "min_points": 2}, "time_s needs at least 2 values, got 1", "time_s"),
        ({"x": [], "min_points": 1}, "time_s needs at least 1 value, got 0", "time_s"),
        ({"x": [0.0, 1.0], "y": [1.0, -2.0], "y_min": 0.0, "y_unit": "N"},
         "response_n must be >= 0 N, got -2 at index 1", "response_n"),
        ({"x": [0.0, 1.0], "where": "step response"},
         None, None),
        ({"x": [1.0, 0.5], "where": "step response"},
         "step response: time_s must be strictly increasing, got 1 then 0.5 at index 1",
         "time_s"),
    ],
)
def test_check_series_messages(kwargs: dict, message: str | None, param: str | None) -> None:
    x = kwargs.pop("x")
    y = kwargs.pop("y", None)
    args = ("time_s", x) if y is None else ("time_s", x, "response_n", y)
    if message is None:
        check_series(*args, **kwargs)
        return
    with pytest.raises(InputError) as info:
        check_series(*args, **kwargs)
    assert str(info.value) == message
    assert info.value.param == param
