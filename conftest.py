"""Repo-root pytest configuration: the names the doctests of ``src/exofric`` may use.

``pytest tests src/exofric --doctest-modules`` runs every docstring example. Examples that need a
whole reproduction use ``fast_result``: one ``reproduce(ReproduceConfig.for_mode(fast=True))``
per session (~3 s), computed only when a collected example names it. Examples that write files
write into ``tmp_dir``, a fresh temporary directory (``pathlib.Path``) per example. Every example
runs with the repository root as working directory, so it can name ``examples/...`` files.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parent


@pytest.fixture(scope="session")
def fast_result() -> Any:
    """The fast-mode :class:`exofric.reproduction.ReproduceResult`, computed once per session."""
    from exofric.reproduction import ReproduceConfig, reproduce

    return reproduce(ReproduceConfig.for_mode(fast=True))


@pytest.fixture(autouse=True)
def _doctest_names(request: pytest.FixtureRequest, doctest_namespace: dict[str, Any]) -> None:
    """For doctest items only: provide ``fast_result`` and ``tmp_dir``; cwd = repo root."""
    dtest = getattr(request.node, "dtest", None)
    if dtest is None:                       # an ordinary test: nothing to do
        return
    source = "".join(ex.source for ex in dtest.examples)
    if "fast_result" in source:
        doctest_namespace["fast_result"] = request.getfixturevalue("fast_result")
    if "tmp_dir" in source:
        doctest_namespace["tmp_dir"] = request.getfixturevalue("tmp_path")
    request.getfixturevalue("monkeypatch").chdir(ROOT)


def _resolve(dotted: str) -> Any:
    """The object named ``dotted`` (a module, then attributes), or None."""
    import importlib

    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj: Any = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for name in parts[i:]:
            obj = getattr(obj, name, None)
        return obj
    return None


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Each doctest runs once, from its home module: a public function's checked wrapper
    (``exofric._validate.checked``) names its package as ``__module__`` (so it pickles by its
    public path), which makes doctest find its examples a second time in the package's
    ``__init__``, without the home module's names; those copies are deselected."""
    keep, dropped = [], []
    for item in items:
        dtest = getattr(item, "dtest", None)
        if (dtest is not None and item.path.name == "__init__.py"
                and hasattr(_resolve(dtest.name), "__wrapped__")):
            dropped.append(item)
        else:
            keep.append(item)
    if dropped:
        config.hook.pytest_deselected(items=dropped)
        items[:] = keep
