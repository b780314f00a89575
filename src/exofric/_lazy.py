"""Lazy package facades (PEP 562): one implementation behind every subpackage's ``__init__``.

``import exofric`` and each stage's package stay cheap (the CLI and every sweep worker import
them); a public name is imported from its one home module on first use and then cached in the
package's namespace.
"""

from __future__ import annotations

import contextlib
import importlib
import sys
from collections.abc import Callable, Mapping, Sequence
from types import FunctionType, ModuleType
from typing import Any

__all__ = ["defer_numpy_extras", "export_checked", "facade", "install_scipy_hook"]

#: NumPy submodules that importing SciPy loads without using them: SciPy's array-API layer
#: copies every attribute of ``numpy`` (``array_api_compat.clone_module``), and NumPy imports
#: its submodules on attribute access (f2py compiles ~100 regular expressions, testing imports
#: unittest): about 40 % of ``import scipy.sparse``. :func:`defer_numpy_extras` makes them
#: load on their first real use instead.
NUMPY_EXTRAS = ("numpy.f2py", "numpy.testing", "numpy.ma", "numpy.polynomial",
                "numpy.ctypeslib", "numpy.rec", "numpy.char", "numpy.strings")


def facade(
    package: str, homes: Mapping[str, str], public: Sequence[str]
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``(__getattr__, __dir__)`` for a package whose names load from their modules on first use.

    A public function is exported checked (:func:`exofric._validate.checked`): an argument of
    the wrong kind raises :class:`~exofric.errors.InputError` naming the parameter.

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
        if isinstance(value, FunctionType):   # its arguments' kinds checked (exofric._validate)
            from exofric._validate import checked

            value = checked(value, package, name)
        setattr(sys.modules[package], name, value)
        return value

    def __dir__() -> list[str]:
        # the public names and the loaded subpackages: not the machinery of this file
        # (``annotations``, ``TYPE_CHECKING``, ``lazy_package``)
        mods = {n for n, v in vars(sys.modules[package]).items()
                if isinstance(v, ModuleType) and not n.startswith("_")}
        return sorted(set(public) | mods)

    return __getattr__, __dir__


def type_checking_homes(init_file: str) -> dict[str, str]:
    """Each name imported under ``if TYPE_CHECKING:`` in ``init_file`` -> its module (absolute).

    The one list of a package's public names: its ``TYPE_CHECKING`` block, which type checkers
    and IDEs read eagerly, is parsed here (once, at the package's import: about 0.3 ms) for
    the lazy facade and ``__all__``, in the order written.

    Parameters
    ----------
    init_file : str
        The package's ``__init__.py`` (its ``__file__``).

    Returns
    -------
    dict of str to str
        Name (its ``as`` alias where there is one) -> absolute module path.

    Examples
    --------
    >>> import exofric.control as c
    >>> type_checking_homes(c.__file__)["Controller"]
    'exofric.control._pid'
    """
    import ast
    from pathlib import Path

    tree = ast.parse(Path(init_file).read_text(encoding="utf-8"))
    homes: dict[str, str] = {}
    for node in tree.body:
        if not (isinstance(node, ast.If) and isinstance(node.test, ast.Name)
                and node.test.id == "TYPE_CHECKING"):
            continue
        for stmt in node.body:
            if isinstance(stmt, ast.ImportFrom) and stmt.module and stmt.level == 0:
                for alias in stmt.names:
                    homes[alias.asname or alias.name] = stmt.module
    return homes


def lazy_package(
    package: str, init_file: str, extra: Sequence[str] = ()
) -> tuple[Callable[[str], Any], Callable[[], list[str]], list[str]]:
    """``(__getattr__, __dir__, __all__)`` of a package from its ``TYPE_CHECKING`` imports.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    init_file : str
        Its ``__file__``.
    extra : sequence of str
        Public names defined in the ``__init__`` itself (e.g. ``__version__``), appended to
        ``__all__``.

    Returns
    -------
    tuple
        ``__getattr__``, ``__dir__`` and ``__all__`` for the package.

    Examples
    --------
    >>> import exofric.control as c
    >>> _, _, names = lazy_package(c.__name__, c.__file__)
    >>> "Controller" in names and names == c.__all__
    True
    """
    homes = type_checking_homes(init_file)
    public = [*homes, *extra]
    getattr_, dir_ = facade(package, homes, public)
    return getattr_, dir_, public


def export_checked(package: str) -> None:
    """Replace each public function of an eagerly imported ``package`` by its checked wrapper.

    The eager counterpart of :func:`facade`'s wrapping: call it as the last line of a stage's
    ``__init__`` that imports its names eagerly; its ``__all__`` functions then raise
    :class:`~exofric.errors.InputError` naming the parameter for an argument of the wrong kind
    (:func:`exofric._validate.checked`).

    Parameters
    ----------
    package : str
        The package's ``__name__`` (its ``__all__`` lists the public names).

    Examples
    --------
    >>> import exofric.material as m
    >>> export_checked(m.__name__)   # done already by its __init__: a no-op
    >>> m.shore_to_modulus("62")
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: shore must be a number, got '62' (str) in shore_to_modulus()
    """
    from exofric._validate import checked

    mod = sys.modules[package]
    for name in getattr(mod, "__all__", ()):
        value = getattr(mod, name, None)
        if isinstance(value, FunctionType):
            setattr(mod, name, checked(value, package, name))


def defer_numpy_extras(names: Sequence[str] = NUMPY_EXTRAS) -> list[str]:
    """Register NumPy submodules not imported yet as lazy modules (loaded on first use).

    Each becomes an :class:`importlib.util.LazyLoader` module in ``sys.modules`` and an
    attribute of ``numpy``: ``numpy.testing`` (``hasattr``, ``dir``) does not import it,
    ``numpy.testing.assert_allclose`` or ``from numpy.testing import ...`` does, and from then
    on the module is the ordinary one. Imports NumPy.

    Parameters
    ----------
    names : sequence of str
        Submodules of ``numpy`` (default :data:`NUMPY_EXTRAS`); those already imported or not
        found are left alone.

    Returns
    -------
    list of str
        The names made lazy.

    Examples
    --------
    >>> import numpy.testing
    >>> defer_numpy_extras(["numpy.testing"])   # imported already: left alone
    []
    """
    import importlib.util

    import numpy

    done: list[str] = []
    for name in names:
        if name in sys.modules:
            continue
        spec = importlib.util.find_spec(name)
        if spec is None or spec.loader is None:
            continue
        spec.loader = importlib.util.LazyLoader(spec.loader)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)   # lazy: runs on the first attribute access
        setattr(numpy, name.rpartition(".")[2], module)
        done.append(name)
    return done


class _BeforeScipy:
    """A ``sys.meta_path`` entry that calls :func:`defer_numpy_extras` once, just before the
    first import of SciPy, then removes itself (it never finds a module)."""

    def find_spec(self, name: str, path: Any = None, target: Any = None) -> None:
        if name == "scipy" or name.startswith("scipy."):
            with contextlib.suppress(ValueError):
                sys.meta_path.remove(self)
            with contextlib.suppress(Exception):   # never in the way of the import itself
                defer_numpy_extras()
        return None


def install_scipy_hook() -> None:
    """Defer :data:`NUMPY_EXTRAS` when SciPy is first imported (``import exofric`` calls it).

    Costs nothing until then (NumPy is not imported); a no-op if SciPy is imported already.

    Examples
    --------
    >>> install_scipy_hook()   # idempotent
    """
    if "scipy" in sys.modules or any(isinstance(f, _BeforeScipy) for f in sys.meta_path):
        return
    sys.meta_path.insert(0, _BeforeScipy())
