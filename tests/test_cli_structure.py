"""The CLI's layout (issue 32): one module per command, no command module imports another,
short ``register()`` functions, option groups that keep every flag as declared.

Source checks by :mod:`ast` (no command runs), plus the option-group decorator
(:func:`exofric.cli._options.grouped`) on a throw-away typer app: what typer shows must be the
group's fields with their declared flags, help and defaults, and the command gets the group.
"""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Any, ClassVar

import pytest
import typer
from typer.testing import CliRunner

import exofric.cli
from exofric.cli._options import (
    MaterialOptions,
    OptionGroup,
    OutputOptions,
    StructureOptions,
    grouped,
)

CLI = Path(exofric.cli.__file__).parent
#: Command modules (a module not starting with "_"), the control group's included.
COMMAND_MODULES = sorted(p for p in CLI.rglob("*.py")
                         if not p.name.startswith("_") and "__pycache__" not in p.parts)


def _module_name(path: Path) -> str:
    return ".".join(("exofric", *path.relative_to(CLI.parent).with_suffix("").parts))


@pytest.mark.parametrize("path", COMMAND_MODULES, ids=lambda p: p.stem)
def test_no_command_module_imports_another(path: Path) -> None:
    """Shared code lives in the private modules (``cli/_*.py``), never in a command module."""
    commands = {_module_name(p) for p in COMMAND_MODULES}
    own = _module_name(path)
    for node in ast.walk(ast.parse(path.read_text())):
        names: list[str] = []
        if isinstance(node, ast.ImportFrom) and node.module:
            names = [node.module, *(f"{node.module}.{a.name}" for a in node.names)]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        for n in names:
            assert n == own or n not in commands, f"{own} imports the command module {n}"


@pytest.mark.parametrize("path", COMMAND_MODULES, ids=lambda p: p.stem)
def test_register_is_short(path: Path) -> None:
    """``register(app)`` only adds commands (their code lives at module level): <= 100 lines."""
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, ast.FunctionDef) and node.name == "register":
            lines = node.body[-1].end_lineno - node.body[0].lineno + 1  # type: ignore[operator]
            assert lines <= 100, f"{path.name}: register() body is {lines} lines"


def test_the_friction_commands_have_one_module_each() -> None:
    for name in ("fit_friction", "predict", "invert", "rig"):
        tree = ast.parse((CLI / f"{name}.py").read_text())
        added = [c.args[0].value for c in ast.walk(tree)
                 if isinstance(c, ast.Call) and isinstance(c.func, ast.Attribute)
                 and c.func.attr == "command" and c.args
                 and isinstance(c.args[0], ast.Constant)]
        assert added == [name.replace("_", "-")], (name, added)
    assert not (CLI / "friction.py").exists()


# --- the option-group decorator on a throw-away app -------------------------------------------


class _Pair(OptionGroup):
    first: int
    second: str
    OPTIONS: ClassVar[dict[str, Any]] = {
        "first": typer.Option(3, "--first", help="First (count)."),
        "second": typer.Option("b", "--second", help="Second (label)."),
    }


def _app() -> typer.Typer:
    app = typer.Typer()

    @grouped
    def cmd(
        head: int = typer.Option(0, help="Before the groups."),
        structure: StructureOptions = StructureOptions.options(),
        material: MaterialOptions = MaterialOptions.options(),
        pair: _Pair = _Pair.options(second=typer.Option("z", "--second", help="Own help.")),
        out: OutputOptions = OutputOptions.options(plot=typer.Option(None, help="PNG here.")),
    ) -> None:
        """A command taking four groups."""
        print(repr((head, structure, material, pair, out)))

    app.command("cmd")(cmd)
    app.command("other")(lambda: None)
    return app


def test_groups_show_their_fields_in_place_with_their_options() -> None:
    cmd = typer.main.get_command(_app()).commands["cmd"]  # type: ignore[attr-defined]
    opts = [(p.name, p.opts[0], p.default, p.required) for p in cmd.params]
    assert opts == [
        ("head", "--head", 0, False),
        ("hole", "--hole", None, True), ("tube_od", "--tube-od", None, True),
        ("tube_id", "--tube-id", None, True), ("wire", "--wire", None, True),
        ("shore", "--shore", None, False), ("c10", "--c10", None, False),
        ("c01", "--c01", None, False), ("d", "--d", None, False),
        ("model", "--model", None, False), ("params", "--params", None, False),
        ("first", "--first", 3, False), ("second", "--second", "z", False),
        ("plot", "--plot", None, False), ("as_json", "--json", False, False),
    ]
    helps = {p.name: p.help for p in cmd.params}
    assert helps["second"] == "Own help." and helps["first"] == "First (count)."
    assert helps["hole"] == "Hole diameter D (mm)." and helps["plot"] == "PNG here."


def test_the_command_gets_the_groups() -> None:
    r = CliRunner().invoke(_app(), ["cmd", "--hole", "10", "--tube-od", "8.3", "--tube-id",
                                    "4.97", "--wire", "1.6", "--shore", "62.5", "--first", "7",
                                    "--json"])
    assert r.exit_code == 0, r.output
    assert r.output.strip() == repr((
        0, StructureOptions(10.0, 8.3, 4.97, 1.6),
        MaterialOptions(62.5, None, None, None, None, None), _Pair(7, "z"),
        OutputOptions(None, True)))


def test_a_group_is_a_frozen_record() -> None:
    st = StructureOptions(10.0, 8.3, tube_id=4.97, wire=1.6)
    assert st.to_dict() == {"hole": 10.0, "tube_od": 8.3, "tube_id": 4.97, "wire": 1.6}
    assert st == StructureOptions(10.0, 8.3, 4.97, 1.6) != StructureOptions(10.0, 8.3, 4.9, 1.6)
    assert repr(st) == "StructureOptions(hole=10.0, tube_od=8.3, tube_id=4.97, wire=1.6)"
    with pytest.raises(AttributeError, match="frozen"):
        st.hole = 11.0  # type: ignore[misc]
    with pytest.raises(TypeError, match="missing: \\['wire'\\]"):
        StructureOptions(10.0, 8.3, 4.97)
    assert _Pair.FIELDS == ("first", "second")


def test_a_group_misdeclared_fails_at_import_not_at_run_time() -> None:
    with pytest.raises(TypeError, match="no field bogus"):
        StructureOptions.options(bogus=typer.Option(1))
    with pytest.raises(TypeError, match="OutputOptions.plot: no option declared"):
        def f(out: OutputOptions = OutputOptions.options()) -> None: ...
        grouped(f)
    with pytest.raises(TypeError, match="hole given twice"):
        def g(hole: float = typer.Option(1.0),
              st: StructureOptions = StructureOptions.options()) -> None: ...
        grouped(g)


def test_help_lists_the_commands_in_pipeline_order() -> None:
    # issue 34: `exofric --help` listed commands in module-name order; now the pipeline's
    import typer

    from exofric.cli import app

    names = list(typer.main.get_command(app).commands)   # type: ignore[attr-defined]
    pipeline = ["paper", "material", "inflate", "calibrate", "squeeze", "pullout", "reduce",
                "fit-friction", "predict", "torque", "gait", "sweep", "reproduce", "control"]
    assert [n for n in names if n in pipeline] == pipeline
