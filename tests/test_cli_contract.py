"""The CLI contract across all commands: --json everywhere; bad input -> one line, exit 2.

How fast bad input is rejected (before any solve or sweep) is measured by
benchmarks/bench_calibrate.py, not asserted here (no wall-clock asserts in tests).
"""

from __future__ import annotations

import pytest

from exofric.cli import run

COMMANDS = ["material", "paper", "inflate", "squeeze", "calibrate", "fit-friction", "predict",
            "invert", "rig", "control", "control compare", "control identify", "sweep", "design",
            "reproduce"]


@pytest.mark.parametrize("cmd", COMMANDS)
def test_every_command_offers_json(cmd, capsys):
    assert run([*cmd.split(), "--help"]) == 0
    assert "--json" in capsys.readouterr().out


@pytest.mark.parametrize(
    "args,needle",
    [
        (["calibrate", "--data", "nope.csv", "--tube-od", "8.3"], "nope.csv"),
        (["sweep", "nope.toml", "--out", "/tmp/exofric-x"], "nope.toml"),
        (["control", "--controller", "xyz", "--target-friction", "54.4"], "--controller"),
        (["invert", "--gamma", "0.7168", "--cubic", "1,2", "--target-friction", "54.4"], "--cubic"),
        (["design", "--target-torque", "-4"], "--target-torque"),
        (["design", "--objective", "foo"], "--objective"),
        (["reproduce", "--out", "/dev/null/x"], "--out"),
        (["predict", "--gamma", "-1", "--paper"], "gamma"),
        (["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
          "--shore", "62.5", "--length", "-5"], "--length"),
        (["inflate", "--shore", "62.5", "--tube-od", "8.3", "--tube-id", "4.97", "--pressures",
          "0.1,nan"], "--pressures"),
    ],
)
def test_bad_input_is_one_line_exit_2(args, needle, capsys):
    code = run(args)
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and needle in lines[0] and "Traceback" not in err


def test_non_convergence_says_what_to_try(cli) -> None:
    """A squeeze past the thin tube's limit pressure: exit 3, one line that says what to try
    (issue 20)."""
    r = cli(["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "7.9", "--wire", "1.6",
             "--shore", "62.5", "--pressures", "0.3,0.6,1.5"])
    assert r.code == 3
    lines = [ln for ln in r.err.splitlines() if ln.strip()]
    assert len(lines) == 1 and "To try" in lines[0] and "finer mesh" in lines[0]
