"""CLI: `exofric control`, `control compare`, `control identify` (JSON contract, errors)."""

from __future__ import annotations

import json
import tomllib
from importlib.resources import files

import control as ct
import numpy as np
import pytest

from exofric import paper
from exofric.cli import run
from exofric.control import PlantParams
from exofric.reproduction import ControlSetup, run_case

CASE_KEYS = {"settling_time_s", "rise_time_s", "overshoot_pct", "steady_state_error_n",
             "final_friction_n", "final_pressure_mpa", "gains", "controller", "feedforward"}


def test_default_action_json_contract(cli):
    r = cli(["control", "--controller", "pd", "--feedforward", "--target-friction", "54.4",
             "--json"])
    assert r.code == 0, r.err
    d = json.loads(r.out)                      # exactly one JSON object
    assert CASE_KEYS <= set(d)
    assert d["controller"] == "pd" and d["feedforward"] is True
    assert set(d["gains"]) == {"kp_mpa_per_n", "ki_mpa_per_n_s", "kd_mpa_s_per_n"}
    assert d["gains"]["ki_mpa_per_n_s"] == 0.0
    assert abs(d["steady_state_error_n"]) < 0.005 * 54.4
    # PD + model feedforward ends at P_ff = the root of 0.7168 x Eq 8 = 54.4 N (np.roots,
    # independent of exofric's inverse); the residual error (< 0.27 N) moves it < 1e-3 MPa.
    c = 0.7168 * np.array(paper.eq8()) - np.array([0.0, 0.0, 0.0, 54.4])
    p_ff = [r.real for r in np.roots(c) if abs(r.imag) < 1e-12 and 0.2 <= r.real <= 0.6]
    assert len(p_ff) == 1 and d["final_pressure_mpa"] == pytest.approx(p_ff[0], abs=1e-3)
    # Settling time against python-control's step_info on the same trajectory (the CLI's
    # default setup re-simulated in process: same gains, deterministic loop): 2 % band,
    # y_final = the target; within one sample time (0.01 s).
    case = run_case(ControlSetup.default(target_n=54.4), "pd", feedforward=True)
    assert case.to_dict()["gains"] == d["gains"]
    sim = case.simulation
    info = ct.step_info(sim.friction_n, sim.time_s, yfinal=54.4, SettlingTimeThreshold=0.02)
    assert d["settling_time_s"] == pytest.approx(info["SettlingTime"], abs=0.01)


def test_compare_json_contract_and_plot(cli, tmp_path):
    png = tmp_path / "fig12.png"
    r = cli(["control", "compare", "--mismatch", "0.1", "--plot", str(png), "--json"])
    assert r.code == 0, r.err
    d = json.loads(r.out)
    cases = d["cases"]
    assert len(cases) == 6
    assert {(c["controller"], c["feedforward"]) for c in cases} == {
        (k, f) for k in ("pd", "pi", "pid") for f in (False, True)}
    for c in cases:
        assert CASE_KEYS <= set(c)
    assert d["mismatch"] == 0.1 and set(d["settling_reduction_pct"]) == {"pi", "pid"}
    assert d["paper_settling_reduction_pct"] == {"pi": 26.0, "pid": 29.0}
    assert png.stat().st_size > 10_000 and png.read_bytes()[:4] == b"\x89PNG"


def test_structure_json_and_identify_csv(cli, tmp_path):
    # A squeeze curve sampled from Eq 8 gives nearly the test5 result (PCHIP vs the cubic).
    p = np.linspace(0.2, 0.6, 17)
    sq = tmp_path / "squeeze.json"
    sq.write_text(json.dumps({"pressure_mpa": p.tolist(),
                              "squeeze_force_n": np.polyval(paper.eq8(), p).tolist()}))
    # A planted step response (tau 0.6 s, theta 0.15 s) to identify the supply from.
    t = np.arange(-0.2, 5.0, 0.01)
    pr = 0.3 * (1 - np.exp(-np.clip(t - 0.15, 0, None) / 0.6))
    pr += np.random.default_rng(5).normal(0, 0.002, t.size)
    t, pr = t[t >= 0], np.clip(pr[t >= 0], 0, None)            # rig files start at 0 s
    csv = tmp_path / "step.csv"
    csv.write_text("time_s,pressure_mpa\n" + "\n".join(f"{a:.3f},{b:.5f}" for a, b in
                                                         zip(t, pr, strict=True)))
    r = cli(["control", "identify", str(csv), "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert d["plant"]["time_constant_s"] == pytest.approx(0.6, rel=0.05)
    assert d["plant"]["delay_s"] == pytest.approx(0.15, rel=0.05)
    assert set(d["tuning"]) == {"pd", "pi", "pid"}
    r = cli(["control", "--controller", "pi", "--feedforward", "--structure", str(sq),
             "--step-csv", str(csv), "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert abs(d["steady_state_error_n"]) < 0.005 * 54.4
    assert d["tuning"]["time_constant_s"] == pytest.approx(0.6, rel=0.05)


def test_shipped_plant_file_equals_code_defaults(tmp_path, capsys):
    path = files("exofric") / "data" / "examples" / "plant-default.toml"
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    assert PlantParams.from_mapping(data["plant"]) == PlantParams()
    code = run(["control", "--plant", str(path), "--json"])
    assert code == 0
    assert json.loads(capsys.readouterr().out)["controller"] == "pid"


def _bad_files(tmp_path):
    bad_key = tmp_path / "bad.toml"
    bad_key.write_text("[plant]\ntau = 1.0\n")
    bad_toml = tmp_path / "broken.toml"
    bad_toml.write_text("[plant\n")
    bad_struct = tmp_path / "s.json"
    bad_struct.write_text(json.dumps({"pressure_mpa": [0.1, 0.2]}))
    return bad_key, bad_toml, bad_struct


@pytest.mark.parametrize(
    "args,needle",
    [
        (["control", "--controller", "pdq"], "--controller"),
        (["control", "--target-friction", "-5"], "target"),
        (["control", "--target-friction", "300", "--feedforward"], "300"),
        (["control", "--mismatch", "20"], "mismatch"),
        (["control", "--controller", "pd", "--ki", "0.1"], "--ki"),
        (["control", "--kp", "-1"], "kp"),
        (["control", "--tuning", "magic"], "--tuning"),
        (["control", "--ff-mode", "x"], "--ff-mode"),
        (["control", "--dt", "0"], "dt"),
        (["control", "--band", "0"], "band"),
        (["control", "--plant", "missing.toml"], "missing.toml"),
        (["control", "--plant", "BADKEY"], "tau"),
        (["control", "--plant", "BROKEN"], "TOML"),
        (["control", "--structure", "BADSTRUCT"], "squeeze_force_n"),
        (["control", "--structure", "nofile.json"], "--structure"),
        (["control", "--mismatch", "0.1", "compare"], "compare"),
        (["control", "compare", "--target-friction", "abc"], "target-friction"),
        (["control", "identify", "nofile.csv"], "nofile.csv"),
    ],
)
def test_bad_options_exit_2_with_one_line(args, needle, tmp_path, capsys):
    bad_key, bad_toml, bad_struct = _bad_files(tmp_path)
    swap = {"BADKEY": str(bad_key), "BROKEN": str(bad_toml), "BADSTRUCT": str(bad_struct)}
    code = run([swap.get(a, a) for a in args])
    out, err = capsys.readouterr()
    assert code == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0] and "Traceback" not in err


def test_itae_tuning_and_pwm_plant_in_process(tmp_path, capsys):
    code = run(["control", "--controller", "pi", "--tuning", "itae", "--duration", "6", "--json"])
    d = json.loads(capsys.readouterr().out)
    assert code == 0 and d["tuning"]["method"] == "itae"
    rule = run(["control", "--controller", "pi", "--duration", "6", "--json"])
    r = json.loads(capsys.readouterr().out)
    assert rule == 0 and d["tuning"]["itae_n_s2"] > 0
    assert d["gains"] != r["gains"]
    pwm = tmp_path / "pwm.toml"
    pwm.write_text("[plant]\npwm_period_s = 0.02\nnoise_n = 0.3\nseed = 4\n")
    code = run(["control", "--plant", str(pwm), "--feedforward", "--controller", "pi", "--json"])
    d = json.loads(capsys.readouterr().out)
    assert code == 0 and abs(d["steady_state_error_n"]) < 0.005 * 54.4
    code = run(["control", "--plant", str(pwm), "--dt", "0.01"])
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and "pwm_period_s" in err and len(err.strip().splitlines()) == 1


def test_pd_without_the_model_says_why_it_ends_at_zero_friction(cli) -> None:
    """`control --controller pd` never reaches contact onset (issue 20): the output says so."""
    r = cli(["control", "--controller", "pd", "--duration", "6", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert d["final_friction_n"] < 0.5
    assert any("below contact onset" in n for n in d["notes"])


def test_identify_reads_other_headers_through_columns(cli, tmp_path):
    """`control identify --columns` (issue 31: every command that reads a file maps headers):
    a step logged as t (s) and P1 (kPa), planted as 400 kPa x (1 - exp(-(t - 0.1)/0.4)): the
    fit returns the planted lag 0.4 s, dead time 0.1 s and a 0.4 MPa step (1 kPa = 1e-3 MPa),
    to 1e-3 relative (the sampling is 0.01 s; the identification fits the exact ZOH form)."""
    t = np.arange(0.0, 5.0, 0.01)
    p = np.where(t > 0.1, 400.0 * (1.0 - np.exp(-(t - 0.1) / 0.4)), 0.0)
    f = tmp_path / "step.csv"
    f.write_text("t,P1\n" + "".join(f"{a:.3f},{b:.6f}\n" for a, b in zip(t, p, strict=True)))
    r = cli(["control", "identify", str(f), "--columns", "time_s=t,pressure_kpa=P1", "--json"])
    assert r.code == 0, r.err
    d = json.loads(r.out)["plant"]
    assert d["time_constant_s"] == pytest.approx(0.4, rel=1e-3)
    assert d["delay_s"] == pytest.approx(0.1, rel=1e-3)
    assert d["step_mpa"] == pytest.approx(0.4, rel=1e-3)


def test_compare_says_the_feedforward_does_the_work(capsys) -> None:
    """Issue 34: PD, PI and PID with the model settle alike on an exact model; the output says
    why (the 2-DOF feedforward gives 100 % of the final pressure: P_ff / P_final, both from the
    same map, so exactly 100 up to the settled tail's 0.05 % ripple) and which rows are the
    feedback-only comparison."""
    assert run(["control", "compare", "--duration", "8", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    shares = [c["feedforward_share_pct"] for c in d["cases"] if c["feedforward"]]
    assert all(abs(s - 100.0) < 0.1 for s in shares)
    assert all(c["feedforward_share_pct"] is None for c in d["cases"] if not c["feedforward"])
    assert any("settle alike" in n and "feedforward" in n for n in d["notes"])


def test_control_run_takes_target_friction_and_the_old_target_flag(capsys) -> None:
    """One flag name for the set-point in `control` and `control run` (--target-friction);
    the old --target still works, hidden, with a deprecation warning."""
    base = ["control", "run", "--device", "sim://?speed=0", "--duration", "0.5", "--json"]
    assert run([*base, "--target-friction", "20"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["target_n"] == 20.0 and not any("deprecated" in w for w in d["warnings"])
    assert run([*base, "--target", "20"]) == 0
    captured = capsys.readouterr()
    d = json.loads(captured.out)
    assert d["target_n"] == 20.0 and any("--target is deprecated" in w for w in d["warnings"])


def test_fig12_titles_read_as_sentences(tmp_path) -> None:
    """The Fig 12 panel title of a loop that never settles reads 'never settles' (it read
    'exofric without not settled')."""
    from matplotlib.figure import Figure

    from exofric.plots import plot_control_cases

    setup = ControlSetup.default(duration_s=4.0)
    cases = [run_case(setup, "pd", feedforward=ff) for ff in (False, True)]
    title = plot_control_cases(cases, Figure()).axes[0].get_title()
    assert title.startswith("PD, exofric: without model never settles, with ")
    assert "not settled" not in title
