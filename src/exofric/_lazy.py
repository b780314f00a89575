"""Lazy package facades (PEP 562): one implementation behind every subpackage's ``__init__``.

``import exofric`` and each stage's package stay cheap (the CLI and every sweep worker import
them); a public name is imported from its one home module on first use and then cached in the
package's namespace.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping, Sequence
from typing import Any

__all__ = ["facade"]


def facade(
    package: str, homes: Mapping[str, str], public: Sequence[str]
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``(__getattr__, __dir__)`` for a package whose names load from their modules on first use.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    homes : mapping of str to str
        Each public name to its home module: a submodule of the package (``"_api"``) or an
        absolute module path (``"exofric.fe"``).
    public : sequence of str
        The package's ``__all__`` (listed by ``dir()`` before they are loaded).

    Returns
    -------
    tuple of callables
        Assign them to the package's ``__getattr__`` and ``__dir__``.

    Examples
    --------
    >>> getattr_, dir_ = facade("exofric", {"InputError": "exofric.errors"}, ["InputError"])
    >>> getattr_("InputError").__name__
    'InputError'
    """

    def __getattr__(name: str) -> Any:
        home = homes.get(name)
        if home is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        path = home if "." in home else f"{package}.{home}"
        value = getattr(importlib.import_module(path), name)
        setattr(sys.modules[package], name, value)
        return value

    def __dir__() -> list[str]:
        return sorted(set(vars(sys.modules[package])) | set(public))

    return __getattr__, __dir__
