"""The CLI's start-up shortcuts give what typer itself gives (issue 37).

* :mod:`exofric.cli._coerce` converts plain option values without pydantic: every value is
  compared with typer's own pydantic converter (the reference) on the same option.
* :func:`exofric.cli.run` builds only the command it runs: the command-name -> module map
  covers every registered command, and a command built alone has the same options as in the
  full app.
* What a light command imports (fresh interpreters; no times asserted: those are in
  ``benchmarks/bench_startup.py``).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest
import typer

import exofric.cli as cli
from exofric.cli import _coerce

FLOATS = ["1", "-0.3", "1e3", "1E-3", ".5", "5.", "007", "+3", "0.6", "123456789.123456789",
          "2.5e-308", "1e308", 0, 5, 0.05, -1.5]
ODD_FLOATS = [" 1", "1_000", "inf", "nan", "-inf", "1e400", "0x10", "abc", "", True]
INTS = ["0", "12", "-3", "+7", "007", 3, -2]
ODD_INTS = ["1.0", " 4", "1_000", "1e3", "9" * 19, "x", True]
STRS = ["abc", "", " padded ", "0.1,0.2", "--x", "ä"]


def _param(annotation: object) -> typer.core.TyperOption:
    """The one option of a throw-away command taking ``annotation``, as typer builds it."""
    app = typer.Typer()

    if annotation is float:
        def cmd(x: float = typer.Option(0.0)) -> None: ...
    elif annotation is int:
        def cmd(x: int = typer.Option(0)) -> None: ...
    elif annotation is str:
        def cmd(x: str = typer.Option("")) -> None: ...
    elif annotation is Path:
        def cmd(x: Path = typer.Option(None)) -> None: ...   # noqa: B008
    elif annotation == "existing":
        def cmd(x: Path = typer.Option(None, exists=True, dir_okay=False)) -> None: ...  # noqa: B008
    else:
        def cmd(x: list[str] = typer.Option(None)) -> None: ...   # noqa: B008
    app.command("cmd")(cmd)
    app.command("other")(lambda: None)
    group = typer.main.get_command(app)
    return group.commands["cmd"].params[0]  # type: ignore[attr-defined]


def _typer_value(p: typer.core.TyperOption, value: object) -> object:
    """typer's own conversion (pydantic) of ``value``, or the error's class."""
    from typer._coercion import build_runtime_param

    try:
        return build_runtime_param(p.type_descriptor)._coerce_value(value, param=p, ctx=None)
    except Exception as exc:
        return type(exc)


def _plain_value(p: typer.core.TyperOption, value: object) -> object:
    q = _param(p.type_descriptor.annotation if p.type_descriptor.parameter_info.exists is None
               or not p.type_descriptor.parameter_info.exists else "existing")
    assert _coerce.install(_Holder(q)) == 1
    try:
        return q._runtime_param._coerce_value(value, param=q, ctx=None)
    except Exception as exc:
        return type(exc)


class _Holder:
    """A stand-in command holding one option (install walks ``params``)."""

    def __init__(self, p: typer.core.TyperOption) -> None:
        self.params = [p]


def _same(a: object, b: object) -> bool:
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a):
        return math.isnan(b)
    return type(a) is type(b) and a == b


@pytest.mark.parametrize("annotation,values", [
    (float, FLOATS + ODD_FLOATS), (int, INTS + ODD_INTS), (str, STRS),
    (list[str], [("a", "b"), ["c"], ()]),
    (Path, ["a/b", "", "/tmp/", "~/x", " x ", Path("y")]),
    ("existing", [__file__, str(Path(__file__).parent), "/no/such/file"])],
    ids=["float", "int", "str", "list", "path", "existing path"])
def test_plain_conversion_equals_typers(annotation: object, values: list[object]) -> None:
    """Exact equality (type and value) with typer's converter, or the same error class."""
    p = _param(annotation)
    for v in values:
        ours, theirs = _plain_value(p, v), _typer_value(p, v)
        assert _same(ours, theirs), (annotation, v, ours, theirs)


def test_plain_path_skips_pydantic_and_odd_values_go_to_typer() -> None:
    p = _param(float)
    assert _coerce.install(_Holder(p)) == 1
    assert _coerce._plain(float, "0.25") == (True, 0.25)
    for odd in ODD_FLOATS:
        assert _coerce._plain(float, odd)[0] is False, odd
    # an odd value hands the option back to typer's own converter for good
    assert p._runtime_param._coerce_value("1_000", param=p, ctx=None) == 1000.0
    assert type(p._runtime_param).__name__ != "_PlainParam"


def test_every_command_maps_to_its_module() -> None:
    """The name -> module rule of :func:`exofric.cli._only_module` covers every command."""
    for name in cli.app.registered_commands + cli.app.registered_groups:
        mod = cli._only_module([name.name])
        assert mod is not None, name.name
        alone = cli._new_app([mod])
        assert cli._registers(alone, name.name), (name.name, mod)
    assert cli._only_module(["--help"]) is None and cli._only_module([]) is None
    assert cli._only_module(["no-such-command"]) is None


@pytest.mark.parametrize("name", ["material", "squeeze", "design", "control", "fit-friction"])
def test_a_command_built_alone_equals_the_full_apps(name: str) -> None:
    full = typer.main.get_command(cli.app).commands[name]  # type: ignore[attr-defined]
    alone = cli._command([name]).commands[name]

    def shape(cmd: object) -> object:
        subs = getattr(cmd, "commands", {})
        return ([(p.name, tuple(p.opts), p.default) for p in cmd.params],  # type: ignore[attr-defined]
                {k: shape(v) for k, v in subs.items()})

    assert shape(alone) == shape(full)


def _modules_after(args: list[str]) -> set[str]:
    code = (f"import json, sys\nfrom exofric.cli import run\nassert run({args!r}) == 0\n"
            "print('@@' + json.dumps(sorted(sys.modules)))")
    env = dict(os.environ, OMP_NUM_THREADS="1")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                       timeout=120, cwd=Path(cli.__file__).parent)
    assert r.returncode == 0, r.stderr[-2000:]
    return set(json.loads(r.stdout.rsplit("@@", 1)[1]))


def test_light_commands_load_neither_pydantic_nor_numpy_nor_other_commands() -> None:
    mods = _modules_after(["material", "--shore", "62.5", "--json"])
    assert not {"pydantic", "numpy", "scipy"} & mods
    assert not [m for m in mods if m.startswith("exofric.cli.") and m.split(".")[2] not in
                ("material", "_common", "_options", "_coerce")]


def test_squeeze_and_inflate_do_not_load_scipy_optimize() -> None:
    mods = _modules_after(["inflate", "--tube-od", "8.3", "--tube-id", "4.97", "--shore", "62.5",
                           "--pressures", "0.3", "--n-radial", "1", "--n-circ", "4", "--json"])
    assert "exofric.fe" in mods
    assert not {"pydantic", "scipy.optimize"} & mods


def test_numpy_extras_load_on_first_use_after_scipy() -> None:
    """The CLI (its ``run``) defers NumPy's unused submodules past SciPy's import; they still
    work (the reference: NumPy's own results, independent of the deferral). ``import exofric``
    alone leaves a Python user's process as it is."""
    code = """
import sys, exofric, exofric._lazy
assert not [f for f in sys.meta_path if type(f).__name__ == '_BeforeScipy']
exofric._lazy.install_scipy_hook()   # what exofric.cli.run does first
import scipy.sparse, numpy as np
lazy = [n for n in exofric._lazy.NUMPY_EXTRAS if type(sys.modules[n]).__name__ == '_LazyModule']
assert 'numpy.testing' in lazy and 'numpy.f2py' in lazy, lazy
np.testing.assert_allclose(np.polynomial.Polynomial([1.0, 2.0])(2.0), 5.0)
from numpy.testing import assert_array_equal
assert_array_equal(np.ma.masked_array([1, 2], mask=[0, 1]).filled(0), [1, 0])
assert type(np.testing).__name__ == 'module' and callable(np.f2py.run_main)
assert not [f for f in sys.meta_path if type(f).__name__ == '_BeforeScipy']
print('ok')
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=120, env=dict(os.environ, OMP_NUM_THREADS="1"))
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr[-2000:]
