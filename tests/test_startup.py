"""Start-up stays light: what ``import exofric``, ``exofric --help`` and the light commands import.

Each case runs in a fresh interpreter (``python -c``) and inspects ``sys.modules`` after the
import or after the CLI's :func:`exofric.cli.run` returned; no timing is asserted (the times
are in ``benchmarks/bench_startup.py``). The stage packages are lazy facades (PEP 562): their
``TYPE_CHECKING`` imports and their ``_MODULES`` map must name the same things.
"""

from __future__ import annotations

import ast
import importlib
import importlib.metadata
import inspect
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import exofric

SRC = Path(exofric.__file__).resolve().parent

#: never needed to start the CLI, print help or compute a material
HEAVY = ("pandas", "pyarrow", "matplotlib", "dask", "distributed", "statsmodels",
         "scipy.optimize", "scipy.integrate", "scipy.special", "scipy.stats", "meshio",
         "control")

_PROBE = """
import json, sys
{body}
print("\\n@@MODULES@@" + json.dumps(sorted(sys.modules)))
"""


def _modules(body: str) -> set[str]:
    """``sys.modules`` of a fresh interpreter after running ``body``."""
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    env.pop("MPLBACKEND", None)
    r = subprocess.run([sys.executable, "-c", _PROBE.format(body=body)], capture_output=True,
                       text=True, env=env, timeout=120)
    assert r.returncode == 0, r.stderr[-3000:]
    return set(json.loads(r.stdout.rsplit("@@MODULES@@", 1)[1]))


def _cli_modules(args: list[str]) -> set[str]:
    """Modules loaded after ``exofric ARGS`` ran (exit code 0) through the CLI's entry."""
    return _modules(f"from exofric.cli import run\nassert run({args!r}) == 0")


def _loaded(mods: set[str], names: tuple[str, ...]) -> list[str]:
    return [n for n in names if n in mods]


def test_import_exofric_is_light() -> None:
    mods = _modules("import exofric")
    assert not _loaded(mods, (*HEAVY, "numpy", "scipy", "importlib.metadata"))
    # no stage: only the version and the facade mechanism itself
    assert not [m for m in mods
                if m.startswith("exofric.") and m not in ("exofric._version", "exofric._lazy")]


@pytest.mark.parametrize("args", [["--help"], ["material", "--help"], ["squeeze", "--help"],
                                  ["--version"]], ids=" ".join)
def test_help_imports_no_computing_code(args: list[str]) -> None:
    """Help and version need typer/click/rich and the option definitions only: no NumPy even."""
    mods = _cli_modules(args)
    assert not _loaded(mods, (*HEAVY, "numpy", "scipy")), "imported by exofric " + " ".join(args)
    computing = sorted(m for m in mods if m.startswith("exofric.")
                       and not m.startswith("exofric.cli")
                       and m not in ("exofric._version", "exofric._lazy", "exofric.defaults"))
    assert not computing, computing


def test_material_command_imports_no_scipy() -> None:
    mods = _cli_modules(["material", "--shore", "62.5"])
    assert "exofric.material" in mods
    assert not _loaded(mods, (*HEAVY, "scipy")), "scipy.special was only used for erfinv"


def test_squeeze_command_imports_only_the_solver() -> None:
    """A squeeze without --plot/--vtu loads the FE solver, not plotting, tables or Dask.

    (scipy.optimize, and scipy.special that it imports, are not checked here:
    ``exofric.simulate`` brackets the contact onset with ``brentq``.)
    """
    mods = _cli_modules(["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97",
                         "--wire", "1.6", "--shore", "62.5", "--n-radial", "1", "--n-circ", "12",
                         "--pressures", "0.3", "--json"])
    assert "exofric.fe" in mods and "scipy.sparse" in mods
    heavy = tuple(n for n in HEAVY if n not in ("scipy.optimize", "scipy.special"))
    assert not _loaded(mods, heavy)
    assert not [m for m in mods if m.startswith(("exofric.simulate._analytic",
                                                 "exofric.simulate._inflate",
                                                 "exofric.io._store", "exofric.io._vtu",
                                                 "exofric.design"))]


FACADE_CASES = [
    ("from exofric.simulate import squeeze", ("scipy.integrate", "scipy.optimize",
                                              "exofric.simulate._analytic")),
    ("from exofric.simulate import InflationResult", ("scipy.integrate", "scipy.optimize")),
    ("from exofric.plots import save, plot_squeeze, plot_design_map", ("matplotlib", "pandas")),
    ("from exofric.io import jsonable, read_toml, write_json", ("pandas", "pyarrow", "meshio")),
    ("from exofric.friction import FrictionModel, CubicFit", ("scipy", "pandas")),
    ("from exofric.calibration import CalibrationResult, InflationData", ("scipy", "pandas")),
    ("from exofric.control import PIDGains", ("scipy", "pandas")),
    ("from exofric.report import fmt", ("matplotlib", "pandas", "scipy", "exofric.reproduction")),
    ("from exofric.reproduction import Comparison", ("exofric.simulate", "exofric.fe")),
    ("from exofric.material import MooneyRivlin", ("scipy",)),
]


@pytest.mark.parametrize("stmt,absent", FACADE_CASES, ids=[c[0] for c in FACADE_CASES])
def test_stage_facades_load_only_what_is_asked(stmt: str, absent: tuple[str, ...]) -> None:
    mods = _modules(stmt)
    assert not _loaded(mods, absent), f"{stmt!r} loaded {_loaded(mods, absent)}"


def _facades() -> list[Path]:
    return sorted(p for p in SRC.glob("*/__init__.py")
                  if "_MODULES" in (t := p.read_text()) or "lazy_package(" in t)


def test_there_are_facades() -> None:
    names = {p.parent.name for p in _facades()}
    assert {"simulate", "plots", "io", "friction", "calibration"} <= names


@pytest.mark.parametrize("init", _facades(), ids=lambda p: p.parent.name)
def test_facade_map_matches_its_type_checking_imports(init: Path) -> None:
    """The names a type checker sees are the names ``__getattr__`` loads, from the same module,
    and ``__all__`` lists exactly them."""
    tree = ast.parse(init.read_text())
    pkg = f"exofric.{init.parent.name}"
    typed: dict[str, str] = {}
    for node in tree.body:
        if isinstance(node, ast.If) and getattr(node.test, "id", "") == "TYPE_CHECKING":
            for imp in node.body:
                assert isinstance(imp, ast.ImportFrom) and imp.module, ast.dump(imp)
                assert imp.module.startswith(pkg + "._"), imp.module
                for a in imp.names:
                    typed[a.asname or a.name] = imp.module.rsplit(".", 1)[1]
    mod = importlib.import_module(pkg)
    if hasattr(mod, "_HOME"):      # a hand-written map (packages not yet on lazy_package)
        assert typed == mod._HOME
    assert set(mod.__all__) == set(typed)
    for name, home in typed.items():
        # a function is exported checked (exofric._validate): its wrapper wraps the home's
        home_obj = getattr(importlib.import_module(f"{pkg}.{home}"), name)
        obj = getattr(mod, name)
        assert obj is home_obj or (inspect.isfunction(obj) and obj.__wrapped__ is home_obj)
    assert set(mod.__all__) <= set(dir(mod))
    with pytest.raises(AttributeError):
        mod.no_such_name  # noqa: B018


def test_version_is_the_installed_metadata() -> None:
    """``exofric/_version.py`` is the single source (pyproject reads it); the installed metadata
    agrees (after a version bump: ``pip install -e .`` again)."""
    assert exofric.__version__ == importlib.metadata.version("exofric")
    from exofric.cli import run

    assert run(["--version"]) == 0
