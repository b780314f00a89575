"""The package layout reads as the pipeline: one subpackage per stage, one public home per name.

These are structural checks of the code base itself (no numbers): the layer contracts of
import-linter (pyproject.toml), no stage-prefixed modules at the top level, curated ``__all__``
in every stage package, no public name in two homes, and no reaching into another package's
private modules.
"""

from __future__ import annotations

import importlib
import pkgutil
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import exofric

SRC = Path(exofric.__file__).resolve().parent
STAGES = ("paper", "material", "fe", "simulate", "calibration", "friction", "control", "design",
          "reproduction", "hardware", "io", "plots", "report")
#: single-module homes at the top level (no stage prefix, no split)
TOP_MODULES = ("errors", "defaults", "geometry")


def test_top_level_holds_only_stage_packages_and_single_modules() -> None:
    mods = sorted(m.name for m in pkgutil.iter_modules([str(SRC)]))
    allowed = {*STAGES, *TOP_MODULES, "cli", "_version", "_json", "_lazy", "_lsq", "_display",
               "_validate", "_roots", "__main__"}
    assert set(mods) <= allowed, f"unexpected top-level modules: {set(mods) - allowed}"
    for name in mods:
        for stage in (*STAGES, "sweep", "report"):
            assert not name.startswith(stage + "_"), f"stage-prefixed module {name}"


@pytest.mark.parametrize("pkg", STAGES)
def test_stage_package_has_curated_all(pkg: str) -> None:
    mod = importlib.import_module(f"exofric.{pkg}")
    assert mod.__doc__ and "Examples" in mod.__doc__, f"exofric.{pkg}: docstring with Examples"
    names = getattr(mod, "__all__", None)
    assert names, f"exofric.{pkg} has no __all__"
    assert len(names) == len(set(names)), f"duplicate names in exofric.{pkg}.__all__"
    for n in names:
        assert hasattr(mod, n), f"exofric.{pkg}.__all__ names missing {n}"
    # implementation modules are private: the __init__ is the only public path
    for m in pkgutil.iter_modules(mod.__path__):
        assert m.name.startswith("_"), f"exofric.{pkg}.{m.name} should be private (_{m.name})"


def _homes() -> dict[str, list[str]]:
    homes: dict[str, list[str]] = {}
    for pkg in (*STAGES, *TOP_MODULES):
        mod = importlib.import_module(f"exofric.{pkg}")
        for n in getattr(mod, "__all__", ()):
            homes.setdefault(n, []).append(pkg)
    return homes


def test_no_name_is_public_in_two_places() -> None:
    twice = {n: p for n, p in _homes().items() if len(p) > 1}
    assert not twice, f"names public in more than one package: {twice}"


def test_top_level_names_are_their_homes_objects() -> None:
    homes = _homes()
    for n in exofric.__all__:
        if n == "__version__":
            continue
        assert n in homes, f"exofric.{n} has no home subpackage"
        home = importlib.import_module(f"exofric.{homes[n][0]}")
        assert getattr(exofric, n) is getattr(home, n), f"exofric.{n} is not its home's {n}"


def test_import_exofric_is_lazy() -> None:
    # the CLI and every Dask worker import exofric: it must not pull in the FE, pandas or scipy
    code = ("import sys, exofric; "
            "print(sorted(m for m in ('exofric.fe', 'pandas', 'scipy', 'matplotlib') "
            "if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


_PRIVATE = re.compile(r"^\s*from exofric\.(\w+)\.(_\w+) import", re.M)


def test_no_package_imports_another_packages_private_modules() -> None:
    bad = []
    for f in SRC.rglob("*.py"):
        rel = f.relative_to(SRC).parts
        for m in _PRIVATE.finditer(f.read_text(encoding="utf-8")):
            if rel[0] != m.group(1):
                bad.append(f"{'/'.join(rel)}: exofric.{m.group(1)}.{m.group(2)}")
    assert not bad, "import public names instead:\n" + "\n".join(bad)


def test_layer_contracts_hold() -> None:
    exe = shutil.which("lint-imports", path=str(Path(sys.executable).parent))
    if exe is None:
        pytest.skip("import-linter not installed (pip install -e '.[dev]')")
    root = SRC.parents[1]
    r = subprocess.run([exe, "--no-cache"], cwd=root, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-2000:]


@pytest.mark.parametrize("name", ["exofric", "exofric.simulate", "exofric.friction",
                                  "exofric.control", "exofric.io", "exofric.design"])
def test_dir_lists_the_api_not_the_machinery(name: str) -> None:
    # issue 34: dir(ef) in a notebook showed `annotations`, `TYPE_CHECKING`, `lazy_package`
    mod = importlib.import_module(name)
    listed = set(dir(mod))
    assert not listed & {"annotations", "TYPE_CHECKING", "lazy_package", "facade"}
    assert set(mod.__all__) <= listed
