"""Hostile option values for every command: exit 0, 2 or 3, one error line, never a traceback.

Commands are discovered from the CLI itself (``sweep`` and ``design`` are covered by their own
tests). Each command starts from a cheap valid invocation (small meshes, the paper's tables,
no FE where the command allows it); each of its options in turn gets every hostile value
(negative, zero, NaN, inf, 1e300, a huge integer, an empty string, a missing path, a
directory). Runs are in-process (``exofric.cli.run``, which builds the click command tree once:
a failing run costs milliseconds) so the whole sweep of ~900 runs stays in seconds; an exception
escaping ``run`` is what a user would see as a traceback. Options read only in another mode of a
command (``material --fit``'s tensile-specimen options, ``calibrate --tensile``'s) are attacked
again from a base in that mode (``EXTRA_BASES``), so their own checks are reached.
"""

from __future__ import annotations

import contextlib
import io
import traceback
from pathlib import Path

import numpy as np
import pytest
import typer

from exofric.cli import app, run

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
PAPER_DATA = Path(__file__).resolve().parents[1] / "src" / "exofric" / "paper" / "data"
SQUEEZE = str(EXAMPLES / "friction-squeeze-eq8.csv")
FRICTION = str(EXAMPLES / "friction-synthetic-eq8.csv")
SKIP = {"sweep", "design"}  # tests/test_sweep*.py, tests/test_design.py

MISSING = "/nonexistent-exofric/x.csv"
HOSTILE = ["-1", "0", "nan", "inf", "-inf", "1e300", "99999999999999999999999", "", MISSING,
           "{dir}"]
#: reproduce runs the whole paper for any --out directory it accepts: only values it refuses
HOSTILE_BY_OPTION = {
    ("reproduce", "--out"): ["/dev/null/x", "{file}"],
    ("reproduce", "--notes-dir"): [MISSING, "{file}"],
}

#: --plot of any command: a number is a file name (``-1`` -> ``-1.png``, drawn and written, a
#: second or more each); one such name, then the values refused before any work (the shared
#: checks of ``plot_path``: tests/test_cli_hostile.py::test_reported_attacks...)
HOSTILE_BY_FLAG = {"--plot": ["-1", "", MISSING, "{dir}"]}

#: commands whose every accepted value runs a fit or a simulation: the five values that reach
#: each kind of check (sign, NaN, overflow, empty, a directory), to keep the suite's time
HOSTILE_BY_COMMAND = {c: ["-1", "nan", "1e300", "", "{dir}"]
                      for c in ("fit-pullout", "gait", "pullout", "stiffness")}


def _base(tmp: Path) -> dict[str, list[str]]:
    """A cheap valid invocation of every command (files made in ``tmp``)."""
    t = np.linspace(0.0, 5.0, 101)
    step = tmp / "step.csv"
    step.write_text("time_s,pressure_mpa\n" + "".join(
        f"{a:.3f},{0.5 * (1 - np.exp(-max(a - 0.1, 0.0) / 0.4)):.5f}\n" for a in t))
    from exofric.friction import RawRigConfig, simulate_raw_log
    from exofric.io import write_raw_log

    raw = tmp / "raw.csv"
    cfg = RawRigConfig(sample_rate_hz=50.0, replicates=1, pull_mm=4.0)
    log = simulate_raw_log([0.2, 0.4], [80.0, 160.0], 0.7, config=cfg, seed=1)
    write_raw_log(raw, log.to_frame())
    pulls = tmp / "pulls.csv"   # forces this structure can give (raw.csv's cannot: 0.7 x 160 N)
    write_raw_log(pulls, simulate_raw_log([0.2, 0.4], [18.8, 98.5], 0.5, config=cfg,
                                          seed=1).to_frame())
    one = tmp / "one.toml"
    one.write_text('[[structure]]\nname = "a"\nhole_mm = 10.0\ntube_od_mm = 8.3\n'
                   "wire_mm = 1.6\n")
    return {
        "calibrate": ["--data", str(PAPER_DATA / "table1_test.csv"), "--tube-od", "8.3",
                      "--tube-id", "4.97", "--model", "paper-table1"],
        "fit-friction": ["--squeeze", SQUEEZE, "--friction", FRICTION],
        "predict": ["--gamma", "0.7168", "--structures", str(one), "--pressures", "0.3"],
        "invert": ["--gamma", "0.7", "--target-friction", "4", "--cubic", "1,2,3,4"],
        "rig": ["--squeeze", SQUEEZE, "--gamma-true", "0.7", "--out", str(tmp / "rig.csv")],
        "inflate": ["--tube-od", "8.3", "--tube-id", "4.97", "--shore", "62.5", "--pressures",
                    "0.1", "--n-radial", "1", "--n-circ", "2"],
        "material": ["--shore", "62.5"],
        "ring": ["--od", "8.3", "--id", "4.97", "--width", "5", "--pin", "3", "--shore", "62.5",
                 "--max-displacement", "0.5", "--steps", "1", "--n-radial", "1", "--n-circ", "4"],
        "torque": ["--friction", "180.49"],
        "paper": [],
        "reproduce": ["--out", str(tmp / "never-written")],
        "squeeze": ["--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
                    "--shore", "62.5", "--pressures", "0.3", "--n-radial", "1", "--n-circ",
                    "8"],
        "control": ["--duration", "2"],
        "control compare": ["--duration", "2"],
        "control identify": [str(step)],
        "reduce": [str(raw)],
        "control run": ["--device", "sim://?speed=0", "--duration", "1"],
        "pullout": ["--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
                    "--pressure", "0.3", "--mu-wire", "0.3", "--mu-wall", "0.5",
                    "--mu-wire-wall", "0.2", "--shore", "62.5", "--accuracy", "draft",
                    "--section"],
        "fit-pullout": [str(pulls), "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97",
                        "--wire", "1.6", "--shore", "62.5", "--accuracy", "draft", "--mu-wall",
                        "0.5", "--mu-wire-wall", "0.2", "--n-z", "8", "--n-path", "10",
                        "--max-evaluations", "5"],
        "gait": ["--strides", "1", "--controller", "ff"],
        "stiffness": ["--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
                      "--pressures", "0.3", "--radius", "0.1", "--mu-wire", "0.3", "--mu-wall",
                      "0.5", "--mu-wire-wall", "0.2", "--shore", "62.5", "--accuracy", "draft"],
    }


MATERIAL_DATA = Path(__file__).resolve().parents[1] / "src" / "exofric" / "material" / "data"
DS20 = str(MATERIAL_DATA / "srmd_dragonskin20_uniaxial.csv")

#: A second valid invocation where a command's options mean something else (fits instead of
#: the default path): every option of the command is attacked again from this base, so that
#: an option read only in that mode (--gauge-length, --stress-kind, --residuals...) has its
#: own value checked, not just refused as out of place.
EXTRA_BASES: dict[str, tuple[str, list[str], list[str]]] = {
    "material --fit": ("material", ["--fit", DS20, "--model", "neo-hookean"], [
        "--fit", "--fit-biaxial", "--fit-planar", "--stress-kind", "--strain-kind",
        "--gauge-length", "--area", "--width", "--thickness", "--columns", "--stability-range",
        "--residuals", "--terms", "--model"]),
    "calibrate --tensile": ("calibrate", ["--tensile", DS20, "--model", "neo-hookean"], [
        "--tensile", "--tensile-biaxial", "--tensile-planar", "--stress-kind", "--strain-kind",
        "--gauge-length", "--area", "--width", "--thickness", "--tensile-noise"]),
}
#: calibrate fits the material for every value it accepts: the five values of each kind
HOSTILE_BY_COMMAND["calibrate --tensile"] = ["-1", "nan", "1e300", "", "{dir}"]


def _commands() -> dict[str, list[tuple[str, bool]]]:
    """``{"control identify": [(option or "ARG", is_argument), ...]}`` from the CLI."""
    out: dict[str, list[tuple[str, bool]]] = {}

    def walk(cmd, path: list[str]) -> None:
        subs = getattr(cmd, "commands", None) or {}
        if path and path[0] not in SKIP:
            opts = []
            for p in cmd.params:
                if p.param_type_name == "argument":
                    opts.append((p.name, True))
                elif not getattr(p, "is_flag", False) and p.opts[0] not in ("--help",):
                    opts.append((p.opts[0], False))
            out[" ".join(path)] = opts
        for name, sub in subs.items():
            walk(sub, [*path, name])

    walk(typer.main.get_command(app), [])
    return out


COMMANDS = _commands()


def test_every_command_has_a_cheap_base(tmp_path):
    assert set(_base(tmp_path)) == set(COMMANDS)


def _run(args: list[str]) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        try:
            code = run(args)
        except BaseException:  # what the user would see: a traceback
            return -1, err.getvalue() + traceback.format_exc()
    return code, err.getvalue()


def _check(args: list[str], code: int, err: str) -> None:
    assert "Traceback" not in err, (args, err)
    assert code in (0, 2, 3), (args, code, err)
    if code:
        lines = [ln for ln in err.splitlines()
                 if ln.strip() and not ln.startswith("exofric: warning:")]
        assert len(lines) == 1, (args, err)


@pytest.mark.parametrize("case", sorted(COMMANDS) + sorted(EXTRA_BASES))
def test_hostile_values(case, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    if case in EXTRA_BASES:
        command, base, attacked = EXTRA_BASES[case]
    else:
        command, base, attacked = case, _base(tmp_path)[case], None
    if command != "reproduce":  # its only valid run is the whole paper (tests/test_reproduce.py)
        code, err = _run([*command.split(), *base, "--json"])
        assert code == 0, err  # the base itself is valid
    (tmp_path / "adir").mkdir()
    (tmp_path / "afile").write_text("x\n")
    options = [(o, a) for o, a in COMMANDS[command] if attacked is None or o in attacked]
    assert attacked is None or len(options) == len(attacked), (case, options)
    for opt, is_arg in options:
        values = HOSTILE_BY_OPTION.get((command, opt)) or HOSTILE_BY_FLAG.get(opt) or \
            HOSTILE_BY_COMMAND.get(case, HOSTILE)
        for value in values:
            value = value.format(dir=tmp_path / "adir", file=tmp_path / "afile")
            if is_arg:
                args = [*command.split(), value, "--json"]
            else:
                rest = list(base)
                if opt in rest:  # replace the base's value of this option
                    i = rest.index(opt)
                    del rest[i:i + 2]
                args = [*command.split(), *rest, opt, value, "--json"]
            _check(args, *_run(args))


@pytest.mark.parametrize("args,needle", [
    (["rig", "--squeeze", SQUEEZE, "--gamma-true", "0.7", "--out", "r.csv", "--seed", "-1"],
     "--seed"),
    (["fit-friction", "--squeeze", SQUEEZE, "--friction", FRICTION, "--ci", "bootstrap",
      "--seed", "-1"], "--seed"),
    (["squeeze", "--hole", "1e300", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
      "--shore", "62.5"], "--hole"),
    (["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
      "--shore", "62.5", "--n-circ", "100000"], "GiB"),
    (["inflate", "--tube-od", "1e300", "--tube-id", "4.97", "--shore", "62.5"], "--tube-od"),
    (["fit-friction", "--squeeze", SQUEEZE, "--friction", FRICTION, "--plot", "adir"], "--plot"),
    (["fit-friction", "--squeeze", SQUEEZE, "--friction", FRICTION, "--plot", "a.xyz"],
     "--plot"),
])
def test_reported_attacks_are_one_line_exit_2(args, needle, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "adir").mkdir()
    code, err = _run(args)
    assert code == 2 and "Traceback" not in err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and needle in lines[0], err


def test_plot_without_suffix_reports_the_file_written(tmp_path, monkeypatch):
    import json

    monkeypatch.chdir(tmp_path)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = run(["fit-friction", "--squeeze", SQUEEZE, "--friction", FRICTION, "--plot",
                    "out", "--json"])
    assert code == 0
    assert json.loads(out.getvalue())["plot"] == "out.png"
    assert (tmp_path / "out.png").is_file() and not (tmp_path / "out").exists()


def test_full_disk_names_the_file_and_leaves_no_partial_png(tmp_path):
    """A write that fails (file-size limit: EFBIG, as on a full disk) -> one line, no file."""
    resource = pytest.importorskip("resource")
    import subprocess
    import sys

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_FSIZE, (20_000, 20_000))

    proc = subprocess.run(
        [sys.executable, "-m", "exofric", "fit-friction", "--squeeze", SQUEEZE, "--friction",
         FRICTION, "--plot", "big.png"], cwd=tmp_path, capture_output=True, text=True,
        preexec_fn=limit, timeout=120)
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert proc.returncode == 2 and len(lines) == 1, proc.stderr
    assert "big.png" in lines[0] and "too large" in lines[0].lower()
    assert list(tmp_path.iterdir()) == []
