"""The CLI shows a library message's Python parameter names as flags, and nothing else (issues
32, 38).

Library messages name Python parameters (``columns``, ``width_mm``, ``tube_id``); the CLI's
error handler (:func:`exofric.cli._with_flags`) maps a name to a flag only when it is an option
of the command that ran and the message names it as a parameter: its opening words, or a clause
``name:``. A file's header (``# width_mm:``), a quoted column and a Python name inside a sentence
stay as written.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import typer

from exofric.cli import _running_command, _with_flags, app
from exofric.errors import InputError

CURVE = str(Path(__file__).resolve().parents[1] / "examples" / "friction-squeeze-eq8.csv")


def _shown(argv: list[str], exc: InputError) -> str:
    return _with_flags(exc, _running_command(typer.main.get_command(app), argv))


@pytest.mark.parametrize("argv,message,param,expected", [
    # the opening parameter, with or without its unit suffix, of the command that ran
    (["material"], "width_mm must be > 0, got -1", None, "--width must be > 0, got -1"),
    (["ring"], "width must be > 0 mm, got -1", None, "--width must be > 0 mm, got -1"),
    (["design"], "pmax_mpa must be > 0 MPa, got -1", None, "--pmax must be > 0 MPa, got -1"),
    # a list of parameters opening the message
    (["rig"], "mu_tube and mu_wall are required with --law interfaces", "mu_tube",
     "--mu-tube and --mu-wall are required with --law interfaces"),
    # a clause opened by the parameter
    (["fit-friction"], "columns: unknown column in 'x=y' (keys: test)", "columns",
     "--columns: unknown column in 'x=y' (keys: test)"),
    (["reduce"], "log.csv: column 'P1' (columns: named by pressure_kpa=P1) is not in the file",
     "columns", "log.csv: column 'P1' (--columns: named by pressure_kpa=P1) is not in the file"),
    # a file's header is the user's file, not an option: '# width_mm:' never becomes a flag
    (["material"], "t.csv: '# width_mm:' line must be > 0, got '-1'", "width_mm",
     "t.csv: '# width_mm:' line must be > 0, got '-1'"),
    (["ring"], "ring.csv: # width_mm: must be > 0 mm", "width",
     "ring.csv: # width_mm: must be > 0 mm"),
    (["calibrate"], "r.csv: # width_mm: 5 contradicts the ring width", "ring_width",
     "r.csv: # width_mm: 5 contradicts the ring width"),
    # a quoted column of the user's file
    (["fit-friction"], "f.csv: 'friction_n' column missing; pressure_sd: none", "pressure_sd",
     "f.csv: 'friction_n' column missing; --pressure-sd: none"),
    # a Python name of an API object inside a sentence stays Python
    (["squeeze"], "structure: tube_id must be < tube_od (a wall)", "tube_id",
     "structure: tube_id must be < tube_od (a wall)"),
    # only the running command's options: sweep has no --tube-id, invert no --target
    (["sweep"], "tube_id must be < tube_od_mm in design 3", None,
     "tube_id must be < tube_od_mm in design 3"),
    (["invert"], "target friction 8 N is outside the curve's range [16, 205] N", None,
     "target friction 8 N is outside the curve's range [16, 205] N"),
    (["control", "run"], "target must be > 0 N", None, "--target-friction must be > 0 N"),
    # a file name that starts like an option is a file name
    (["calibrate"], "data.csv: file not found", "data", "data.csv: file not found"),
    # no parameter: never rewritten
    (["material"], "give --shore, or all of --c10, --c01 and --d", None,
     "give --shore, or all of --c10, --c01 and --d"),
])
def test_only_parameters_of_the_running_command_become_flags(argv, message, param, expected):
    assert _shown(argv, InputError(message, param=param)) == expected


def test_the_columns_message_end_to_end(cli, tmp_path):
    """A bad --columns: the library says ``columns:``, the CLI ``--columns:``, one line."""
    (tmp_path / "f.csv").write_text("P,F\n0.2,10\n0.4,20\n")
    r = cli(["fit-friction", "--squeeze", CURVE, "--friction",
             str(tmp_path / "f.csv"), "--columns", "bogus=P"])
    assert r.code == 2 and r.out == ""
    lines = r.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("exofric: error: --columns: unknown column "
                                                   "in 'bogus=P'"), r.err


def test_a_name_of_another_command_is_not_a_flag_end_to_end(cli):
    """``target`` is an option of `control run`, not of `invert`: the message stays as the
    library wrote it (it once read ``--target friction 8 N``)."""
    r = cli(["invert", "--gamma", "0.7168", "--squeeze", CURVE,
             "--target-friction", "8"])
    assert r.code == 2 and r.out == ""
    assert r.err.startswith("exofric: error: target friction 8 N is outside"), r.err


@pytest.mark.parametrize("argv,message,param,expected", [
    # a message about the user's file: its columns and keys stay as the file names them,
    # even where a name plus unit suffix is also an option (pullout's --pressure)
    (["pullout"], "s.json: pressure_mpa must be >= 0", "pressure_mpa",
     "s.json: pressure_mpa must be >= 0"),
    (["fit-pullout"], "/data/run 3.csv: gap in time_s from 1 s to 9 s", "time_s",
     "/data/run 3.csv: gap in time_s from 1 s to 9 s"),
    (["reduce"], "log.csv: columns: unknown column 'x'", "columns",
     "log.csv: --columns: unknown column 'x'"),
    # the Python API's kind errors (exofric._validate): the parameter opens the message,
    # the function's Python name stays Python
    (["squeeze"], "mu_wall must be a number, got '0.2' (str) in squeeze()", "mu_wall",
     "--mu-wall must be a number, got '0.2' (str) in squeeze()"),
    (["squeeze"], "material is required by squeeze() (missing argument)", "material",
     "material is required by squeeze() (missing argument)"),
])
def test_file_messages_and_kind_errors(argv, message, param, expected):
    assert _shown(argv, InputError(message, param=param)) == expected
