"""Option values converted without pydantic where the conversion is plain (start-up time).

typer (>= 0.2x) converts every option's value, defaults included, through a pydantic
``TypeAdapter``: importing pydantic and building one adapter per option costs about 0.1 s of
every command, though exofric's options are plain ``float``, ``int``, ``str``, ``bool``,
``Path`` and ``list[str]``. :func:`install` gives each option of a built click command tree a
converter that returns, for the plain cases only, what typer's own adapter returns (checked
in ``tests/test_cli_lazy.py`` against typer's adapter on many inputs):

* ``None`` (an option not given), handled by typer before any converter;
* ``float``: a float, an int (not a bool) or a decimal literal (``-1.5``, ``2e-3``, ``.5``);
* ``int``: an int (not a bool) or a string of at most 18 decimal digits with a sign;
* ``str``: a str; ``list[str]``: a list or tuple of str;
* ``Path``: a str, made a ``Path`` as pydantic makes it, then typer's own path checks.

Everything else (a malformed number, ``inf``, ``1_000``, an empty path, a bool from a string)
goes to typer's own pydantic converter, built then and kept for that option: the error
messages of bad input are typer's. If typer's internals differ from what this module expects
(another typer version), nothing is installed and typer converts as before.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

#: a decimal float literal: what Python's ``float`` and pydantic parse alike (no inf/nan,
#: no underscores, no surrounding blanks)
_FLOAT = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d{1,3})?")
_INT = re.compile(r"[+-]?\d{1,18}")

try:  # typer's runtime conversion layer (typer >= 0.2x); absent: nothing is installed
    from typer._coercion import RuntimeParam, build_runtime_param
    from typer._param_types import coerce_cli_path
except ImportError:  # pragma: no cover - another typer
    RuntimeParam = None  # type: ignore[assignment,misc]


def _plain(annotation: Any, value: Any) -> tuple[bool, Any]:
    """``(True, converted)`` where the conversion is plain, else ``(False, None)``."""
    if annotation is float:
        if isinstance(value, float):
            return True, value
        if isinstance(value, int) and not isinstance(value, bool):
            return True, float(value)
        if isinstance(value, str) and _FLOAT.fullmatch(value):
            out = float(value)
            if out - out == 0.0:   # finite (1e999 is inf: typer's path)
                return True, out
    elif annotation is int:
        if isinstance(value, int) and not isinstance(value, bool):
            return True, value
        if isinstance(value, str) and _INT.fullmatch(value):
            return True, int(value)
    elif annotation is str:
        if isinstance(value, str):
            return True, value
    elif annotation == list[str]:
        if isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
            return True, list(value)
    return False, None


if RuntimeParam is not None:

    @dataclass(frozen=True)
    class _PlainParam(RuntimeParam):
        """typer's converter contract; plain values converted here, others by typer."""

        descriptor: Any = None

        def _coerce_value(self, value: Any, param: Any, ctx: Any) -> Any:
            ok, out = _plain(self.annotation, value)
            if ok:
                return out
            if (self.annotation is Path and self.parameter_info.path_type is None
                    and isinstance(value, str) and value):
                # pydantic's Path from a str is Path(str); typer checks exists, dir_okay, ...
                return coerce_cli_path(Path(value), self.parameter_info, path_type=Path,
                                       param=param, ctx=ctx)
            typer_own = build_runtime_param(self.descriptor)   # imports pydantic
            param._runtime_param = typer_own                   # kept for this option
            return typer_own._coerce_value(value, param=param, ctx=ctx)


def install(command: Any) -> int:
    """Give every option of ``command`` (a click command tree) the plain converter.

    Returns the number of options given it (0 if typer's internals are not as expected).
    """
    if RuntimeParam is None:
        return 0
    n = 0
    for sub in getattr(command, "commands", {}).values():
        n += install(sub)
    for p in [*getattr(command, "params", ()), _help_option(command)]:
        desc = getattr(p, "type_descriptor", None)
        if desc is None or getattr(p, "_runtime_param", 0) is not None:
            continue
        info = desc.parameter_info
        if (desc.file_annotation is not None or info.parser is not None
                or info.min is not None or info.max is not None):
            continue
        p._runtime_param = _PlainParam(parameter_info=info, annotation=desc.annotation,
                                       descriptor=desc)
        n += 1
    return n


def _help_option(command: Any) -> Any:
    """The ``--help`` option of ``command``: click makes it on first use and keeps it."""
    try:
        ctx = command.context_class(command, **command.context_settings)
        return command.get_help_option(ctx)
    except Exception:  # pragma: no cover - another click/typer: typer converts it
        return None
