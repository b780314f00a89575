"""Capstan transmission over the knee arc (issue 15): T = F R exp(+-mu_arc theta).

Reference: the capstan ODE dT/dtheta = +-mu T integrated numerically with scipy's
``solve_ivp`` (independent of the closed form in the code), and T = F R at no wrap (the paper's
180.49 N x 0.10 m = 18.05 Nm). The CLI ``exofric torque`` is checked for --json, one-line
errors (exit 2) under hostile values, and its squeeze-file mode.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from exofric.cli import run
from exofric.errors import InputError, PlausibilityWarning
from exofric.friction import TorqueCheck, capstan_factor, torque

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _ode_ratio(mu: float, wrap_deg: float, sign: float) -> float:
    """T(theta)/T(0) of dT/dtheta = sign mu T, integrated from the block end over the wrap."""
    sol = solve_ivp(lambda th, t: sign * mu * t, (0.0, math.radians(wrap_deg)), [1.0],
                    rtol=1e-11, atol=1e-13)
    return float(sol.y[0, -1])


@pytest.mark.parametrize("mu,wrap", [(0.15, 90.0), (0.3, 180.0), (0.05, 30.0), (1.0, 400.0)])
def test_capstan_factor_matches_the_integrated_ode(mu: float, wrap: float) -> None:
    # locking: the wire slides toward the joint, tension grows from the block (F) to the anchor
    assert capstan_factor(wrap, mu, "locking") == pytest.approx(_ode_ratio(mu, wrap, +1.0),
                                                                rel=1e-8)
    # buffering: it slides toward the block, tension falls from F to the anchor
    assert capstan_factor(wrap, mu, "buffering") == pytest.approx(_ode_ratio(mu, wrap, -1.0),
                                                                  rel=1e-8)
    t = torque(180.49, 0.10, wrap_deg=wrap, mu_arc=mu)
    assert t.torque_nm == pytest.approx(180.49 * 0.10 * _ode_ratio(mu, wrap, +1.0), rel=1e-8)
    assert t.to_dict()["torque_no_wrap_nm"] == pytest.approx(18.049)


def test_no_wrap_is_the_papers_t_equals_f_r() -> None:
    # the paper: 180.49 N x 0.10 m = 18.05 Nm; 300 N x 0.10 m = 30 Nm; old results unchanged
    assert torque(180.49).torque_nm == pytest.approx(18.049, rel=1e-15)
    assert torque(300.0).torque_nm == 30.0
    old = TorqueCheck(300.0, 0.1, 30.0, 0.0, 40.0)
    assert torque(300.0) == old                      # defaults: no wrap, factor 1
    for k in ("friction_n", "arm_radius_m", "torque_nm", "required_min_nm", "required_max_nm",
              "meets_max", "coverage_pct"):
        assert torque(300.0).to_dict()[k] == old.to_dict()[k]
    # a wrap without friction, or friction without a wrap, changes nothing
    assert torque(300.0, wrap_deg=120.0).torque_nm == 30.0
    assert torque(300.0, mu_arc=0.3, direction="buffering").torque_nm == 30.0


def test_locking_and_buffering_are_reciprocal() -> None:
    up, down = capstan_factor(135.0, 0.2, "locking"), capstan_factor(135.0, 0.2, "buffering")
    assert up > 1 > down and up * down == pytest.approx(1.0, rel=1e-14)


@pytest.mark.parametrize("kw,field", [
    ({"mu_arc": -0.1}, "mu_arc"), ({"mu_arc": float("nan")}, "mu_arc"),
    ({"mu_arc": 2.5}, "mu_arc"), ({"wrap_deg": -5.0}, "wrap_deg"),
    ({"wrap_deg": 1000.0}, "wrap_deg"), ({"wrap_deg": float("nan")}, "wrap_deg"),
    ({"direction": "up"}, "direction"),
])
def test_bad_arc_inputs_name_the_field(kw: dict, field: str) -> None:
    with pytest.raises(InputError) as exc:
        torque(180.0, **kw)
    assert exc.value.param == field and "\n" not in str(exc.value)


def test_arc_coefficient_above_1_5_warns() -> None:
    with pytest.warns(PlausibilityWarning, match="mu_arc = 1.8 is above 1.5"):
        torque(180.0, wrap_deg=30.0, mu_arc=1.8)


# -- CLI ---------------------------------------------------------------------------------------


def _cli(*args: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = run(list(args))
    return code, out.getvalue(), err.getvalue()


def test_cli_torque_json() -> None:
    code, out, err = _cli("torque", "--friction", "180.49", "--arm-radius", "0.1", "--wrap-deg",
                          "90", "--mu-arc", "0.15", "--direction", "locking", "--required-max",
                          "40", "--json")
    assert code == 0, err
    d = json.loads(out)
    assert d["torque_nm"] == pytest.approx(18.049 * _ode_ratio(0.15, 90.0, 1.0), rel=1e-8)
    assert d["direction"] == "locking" and d["meets_max"] is False and d["warnings"] == []
    lo, hi = d["torque_band_nm"]
    assert lo == pytest.approx(18.049 * _ode_ratio(0.15, 90.0, -1.0), rel=1e-8)
    assert hi == pytest.approx(d["torque_nm"])
    code, out, _ = _cli("torque", "--friction", "180.49", "--wrap-deg", "90", "--mu-arc",
                        "0.15", "--direction", "buffering", "--json")
    assert code == 0 and json.loads(out)["torque_nm"] == pytest.approx(lo)
    code, out, _ = _cli("torque", "--friction", "180.49")           # text view
    assert code == 0 and "18.049" in out


def test_cli_torque_from_a_squeeze_curve() -> None:
    # gamma on the example squeeze CSV: T = gamma N(P) R at the curve's pressures
    code, out, err = _cli("torque", "--squeeze", str(EXAMPLES / "friction-squeeze-eq8.csv"),
                          "--gamma", "0.7168", "--pressures", "0.3,0.6", "--json")
    assert code == 0, err
    d = json.loads(out)
    assert d["torque_nm"] == pytest.approx([0.1 * f for f in d["friction_n"]])
    assert d["friction_n"] == pytest.approx([0.7168 * n for n in d["squeeze_force_n"]])


def test_cli_torque_interfaces_needs_the_wire_integral(tmp_path: Path) -> None:
    old = tmp_path / "old.json"
    old.write_text(json.dumps({"pressure_mpa": [0.2, 0.6], "squeeze_force_n": [20.0, 240.0]}))
    code, out, err = _cli("torque", "--squeeze", str(old), "--mu-tube", "0.4", "--mu-wall",
                          "0.2")
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert code == 2 and out == "" and len(lines) == 1
    assert "wire_pressure_integral_n_per_mm" in lines[0] and "exofric squeeze" in lines[0]
    new = tmp_path / "new.json"
    new.write_text(json.dumps({"pressure_mpa": [0.2, 0.6], "squeeze_force_n": [20.0, 240.0],
                               "wire_pressure_integral_n_per_mm": [22.0 / 116, 264.0 / 116],
                               "length_mm": 116.0}))
    code, out, err = _cli("torque", "--squeeze", str(new), "--mu-tube", "0.4", "--mu-wall",
                          "0.2", "--pressures", "0.6", "--json")
    assert code == 0, err
    assert json.loads(out)["friction_n"] == pytest.approx([0.4 * 264.0 + 0.2 * 240.0])


@pytest.mark.parametrize("args,needle", [
    (["--friction", "180", "--mu-arc", "-0.1"], "--mu-arc"),
    (["--friction", "180", "--mu-arc", "nan"], "--mu-arc"),
    (["--friction", "180", "--mu-arc", "3"], "--mu-arc"),
    (["--friction", "180", "--wrap-deg", "-1"], "--wrap-deg"),
    (["--friction", "180", "--direction", "sideways"], "--direction"),
    (["--friction", "nan"], "--friction"),
    ([], "--friction"),
    (["--friction", "180", "--gamma", "0.7"], "--squeeze"),
])
def test_cli_torque_bad_input_is_one_line(args: list[str], needle: str) -> None:
    code, out, err = _cli("torque", *args)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert code == 2 and out == "" and len(lines) == 1 and needle in lines[0], err


HOSTILE = ["-1", "0", "nan", "inf", "-inf", "1e300", "99999999999999999999999", "",
           "/nonexistent-exofric/x.csv", "{dir}"]


def test_cli_torque_hostile_values(tmp_path: Path) -> None:
    """Every option of `torque` with every hostile value (as tests/test_cli_hostile.py does for
    the other commands): exit 0, 2 or 3 with one error line, never a traceback."""
    import typer

    from exofric.cli import app

    cmd = typer.main.get_command(app).commands["torque"]  # type: ignore[attr-defined]
    opts = [p.opts[0] for p in cmd.params
            if not getattr(p, "is_flag", False) and p.opts[0] != "--help"]
    (tmp_path / "adir").mkdir()
    base = ["--friction", "180.49", "--wrap-deg", "45", "--mu-arc", "0.1"]
    assert _cli("torque", *base, "--json")[0] == 0
    for opt in opts:
        for value in HOSTILE:
            value = value.format(dir=tmp_path / "adir")
            rest = list(base)
            if opt in rest:
                i = rest.index(opt)
                del rest[i:i + 2]
            code, _, err = _cli("torque", *rest, opt, value, "--json")
            assert "Traceback" not in err and code in (0, 2, 3), (opt, value, err)
            if code:
                lines = [ln for ln in err.splitlines()
                         if ln.strip() and not ln.startswith("exofric: warning:")]
                assert len(lines) == 1, (opt, value, err)


def test_torque_command_offers_json() -> None:
    code, out, _ = _cli("torque", "--help")
    assert code == 0 and "--json" in out
    assert np.isfinite(capstan_factor(720.0, 2.0))
