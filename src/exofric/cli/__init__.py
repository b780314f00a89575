"""The ``exofric`` command line: thin presentation over the computing modules.

Each sub-command lives in its own module in this package and exposes
``register(app)``; modules are discovered automatically (names starting with
``_`` are helpers). ``exofric.cli.app``, the typer app with every command, is built on first
use; :func:`run` imports and builds only the command it runs. Every command takes ``--json``
and then prints exactly one JSON object on stdout. Bad input prints one line on stderr and
exits 2; a solver that does not converge exits 3.
"""

from __future__ import annotations

import importlib
import os
import pkgutil
import re
import sys
import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import typer

from exofric._lazy import install_scipy_hook
from exofric._version import __version__
from exofric.cli._common import WARNINGS, record_warning
from exofric.cli._options import tidy_help

if TYPE_CHECKING:
    from exofric.errors import InputError

# Start-up: module level imports typer and the shared option helpers only; a command's module
# (its option definitions) is imported when that command runs, and everything a command
# computes with is imported inside the command function, so that ``exofric --help`` and the
# light commands start fast (tests/test_startup.py, benchmarks/bench_startup.py).
_APP_SETTINGS: dict[str, Any] = dict(
    name="exofric",
    help="Friction modelling, prediction and control for friction-based variable-stiffness "
    "exosuits (Ma et al. 2021). Units: mm, N, MPa, s, Nm.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"exofric {__version__}")
        raise typer.Exit()


def _root(
    version: bool = typer.Option(
        False, "--version", callback=_version, is_eager=True, help="Print the version and exit."
    ),
) -> None:
    """exofric: model, predict and control friction in variable-stiffness exosuits."""


#: The order of the commands in ``exofric --help``: the pipeline (issue 34): the paper, the
#: material and its calibration, the FE problems, friction from rig data and its predictions,
#: the lock at the knee, control, design sweeps, the whole paper. A module not listed follows
#: them, by name; command groups (control) come last in typer's listing anyway.
_ORDER = ("paper", "material", "inflate", "calibrate", "ring", "squeeze", "pullout", "stiffness",
          "reduce", "fit_friction", "rig", "predict", "invert", "torque", "fit_pullout", "gait",
          "sweep", "design", "reproduce", "control")

#: Commands registered by a module of another name (``sweep.py`` also registers ``design``).
_ALSO_IN = {"design": "sweep"}


def _listed(name: str) -> tuple[int, str]:
    return (_ORDER.index(name) if name in _ORDER else len(_ORDER), name)


def _command_modules() -> list[str]:
    """The command modules of this package, in help order (``_`` names are helpers)."""
    return sorted((m.name for m in pkgutil.iter_modules(__path__)
                   if not m.name.startswith("_")), key=_listed)


def _new_app(modules: Sequence[str]) -> typer.Typer:
    """A typer app with the root options and the commands of ``modules`` registered."""
    new = typer.Typer(**_APP_SETTINGS)
    new.callback()(_root)
    for mod in modules:
        importlib.import_module(f"{__name__}.{mod}").register(new)
    return new


_OWN: list[typer.Typer] = []   # the full app, once built by __getattr__


def __getattr__(name: str) -> Any:
    """``app``: the typer app with every command, built (every command module imported) on
    first use; :func:`run` builds only the command it runs."""
    if name == "app":
        full = _new_app(_command_modules())
        _OWN[:] = [full]
        globals()["app"] = full
        return full
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _only_module(args: Sequence[str]) -> str | None:
    """The module of the command ``args`` runs, if it alone is needed (not for root options,
    help listings or an unknown name: those build every command)."""
    first = args[0] if args else ""
    mod = _ALSO_IN.get(first, first.replace("-", "_"))
    if not first or first.startswith(("-", "_")) or mod not in _command_modules():
        return None
    return mod


def _click_classes(name: str) -> tuple[type[Exception], ...]:
    """Exception class ``name`` from click and from typer's vendored click (typer >= 0.20).

    Only from the one(s) already imported (``import typer`` imports the click it uses): a class
    of a module nobody imported cannot be raised, and importing click itself would cost
    start-up time for nothing.
    """
    found: list[type[Exception]] = []
    for mod in ("click.exceptions", "typer._click.exceptions"):
        cls = getattr(sys.modules.get(mod), name, None)
        if isinstance(cls, type) and issubclass(cls, Exception):
            found.append(cls)
    return tuple(found)


_EXIT: tuple[type[Exception], ...] = (typer.Exit, *_click_classes("Exit"))
_ABORT: tuple[type[Exception], ...] = (typer.Abort, *_click_classes("Abort"))
_USAGE: tuple[type[Exception], ...] = _click_classes("ClickException")


_UNIT_SUFFIXES = ("_mpa", "_mm", "_nm", "_n", "_m", "_s", "_pct")


def _running_command(cmd: Any, args: Sequence[str]) -> Any:
    """The (sub)command ``args`` run: ``control compare ...`` -> the ``compare`` command."""
    for a in args:
        sub = getattr(cmd, "commands", {}).get(a)
        if sub is None:
            break
        cmd = sub
    return cmd


def _option_flags(cmd: Any) -> dict[str, str]:
    """Python parameter name -> first long flag, of the options of ``cmd`` (one command)."""
    flags: dict[str, str] = {}
    for p in getattr(cmd, "params", []):
        longs = [o for o in getattr(p, "opts", []) if o.startswith("--")]
        if p.name and longs:
            flags.setdefault(p.name, longs[0])
    return flags


#: A parameter name where a message names one: at the start of the message, or opening a clause
#: (after "; ", ": ", ", " or "(") as ``name:``. Never after "# " or a quote (a file's header
#: such as ``# width_mm:`` or 'friction_n' is the user's file, not an option).
_SUBJECT = re.compile(r"^(?P<names>[a-z][a-z0-9_]*(?:(?:, | and | or )[a-z][a-z0-9_]*)*)"
                      r"(?=[ ,]|:(?:\s|$)|$)")
_CLAUSE = re.compile(r"(?:(?<=; )|(?<=: )|(?<=, )|(?<=\())(?P<name>[a-z][a-z0-9_]*)"
                     r"(?=:(?:\s|$))")
#: A parameter with a unit suffix in a sentence (``needs tube_id_mm (mm)``, ``< tube_od_mm``):
#: an option's name plus its unit is a parameter, never prose; not after "#", a quote, "=" or
#: a word character, not before a quote (a header ``# width_mm:`` or 'width_mm' is the file's).
_UNIT_NAME = re.compile(r"(?<![#'\"=\w])(?<!# )(?P<name>[a-z][a-z0-9]*(?:_[a-z0-9]+)*?"
                        r"(?:_mpa|_mm|_nm|_n|_m|_s|_pct))(?![\w'\"])")

#: A message about a file the user gave (``log.csv: ...``, ``/data/run 3.tdms: ...``): past
#: its ``name:`` clauses (``columns:``), its words are the file's columns and header keys.
_FILE_FIRST = re.compile(r"^[^:;,()]*\.[A-Za-z0-9]{1,6}: ")


def _with_flags(exc: InputError, cmd: Any) -> str:
    """The core's message with Python parameter names (``pmax_mpa``) shown as CLI flags.

    ``cmd`` is the command that ran. Only messages about a parameter (:attr:`InputError.param`
    set) are rewritten, and only names of that command's options (or of an option plus a unit
    suffix: ``pmax_mpa`` -> ``--pmax``) where the message names a parameter: its opening words
    (``mu_tube and mu_wall are required``), a clause opened by ``name:``, and an option's name
    with its unit suffix in a sentence (``needs tube_id_mm``). Other words stay as written: a
    file's header (``# width_mm:``), a quoted column ('friction_n'), a Python name in a sentence,
    and every word of a message about a file (``s.json: pressure_mpa must be >= 0``).
    """
    msg = str(exc)
    if not exc.param:
        return msg
    flags = _option_flags(cmd)

    def flag_for(name: str) -> str | None:
        if name in flags:
            return flags[name]
        for suf in _UNIT_SUFFIXES:
            if name.endswith(suf) and name[: -len(suf)] in flags:
                return flags[name[: -len(suf)]]
        return None

    def one(m: re.Match[str]) -> str:
        return flag_for(m.group(0)) or m.group(0)

    def subject(m: re.Match[str]) -> str:
        names = re.split(r"(, | and | or )", m.group("names"))
        if not all(flag_for(n) for n in names[::2]):   # a sentence, not a list of parameters
            return re.sub(r"^[a-z][a-z0-9_]*", one, m.group("names"))
        return "".join(flag_for(n) or n for n in names)

    msg = _CLAUSE.sub(one, msg)
    if _FILE_FIRST.match(msg):   # about the user's file: its words are its columns and keys
        return msg
    msg = _SUBJECT.sub(subject, msg, count=1)
    return _UNIT_NAME.sub(one, msg)


_BUILT: list[Any] = [None, None]   # [the app (or the one command's name), its click tree]


def _command(args: Sequence[str] = ()) -> Any:
    """The click command tree that runs ``args``, built once per app object (or command).

    With exofric's own app, only the module of the command ``args`` names is imported and
    built (a root option, a help listing or an unknown name builds every command); an app set
    from outside (``exofric.cli.app = ...``) is used whole. Building a tree (typer's
    ``get_command``, :func:`tidy_help`: flags without ``<bool>``, help that wraps; and
    :func:`exofric.cli._coerce.install`: option values converted without pydantic) costs
    about 25 ms for every command; in-process callers (the tests, a script) run many commands.
    A click command keeps no state between invocations: each makes its own context.
    """
    full = globals().get("app")
    mod = _only_module(args) if full is None or (_OWN and full is _OWN[0]) else None
    key: Any = (f"only:{args[0]}" if mod is not None
                else full if full is not None else __getattr__("app"))
    if not (_BUILT[0] is key or (isinstance(key, str) and _BUILT[0] == key)):
        from exofric.cli._coerce import install

        target = _new_app([mod]) if mod is not None else key
        if mod is not None and not _registers(target, args[0]):
            return _command(("--help",))   # not a command of its module: the full listing
        tree = tidy_help(typer.main.get_command(target))
        install(tree)
        _BUILT[:] = [key, tree]
    return _BUILT[1]


def _registers(app_: typer.Typer, name: str) -> bool:
    """True if ``app_`` has a command or group called ``name``."""
    names = [c.name for c in app_.registered_commands]
    names += [g.name for g in app_.registered_groups]
    return name in names


def run(argv: Sequence[str] | None = None) -> int:
    """Run the CLI with ``argv`` (default ``sys.argv[1:]``) and return the exit code."""
    warnings.showwarning = record_warning
    WARNINGS.clear()
    # figures are only ever written to files: a non-interactive backend, chosen once here
    # (before anything imports matplotlib; a user's MPLBACKEND wins)
    os.environ.setdefault("MPLBACKEND", "Agg")
    # the CLI's process is ours: NumPy's submodules that SciPy's import touches but no command
    # uses load on first use (exofric._lazy); a Python user's process is left as it is
    install_scipy_hook()
    args = list(sys.argv[1:] if argv is None else argv)
    cmd: Any = None
    try:
        cmd = _command(args)   # inside: a failing import is reported like any other error
        rv = cmd.main(
            args=args,
            prog_name="exofric",
            standalone_mode=False,
        )
    except _EXIT as exc:
        code = int(getattr(exc, "exit_code", 0))
        if code == 130:    # Ctrl-C (a running control loop has vented its device already)
            print("exofric: interrupted", file=sys.stderr)
        return code
    except _ABORT:
        print("exofric: aborted", file=sys.stderr)
        return 130
    except _USAGE as exc:
        msg = " ".join(str(exc.format_message()).split())  # type: ignore[attr-defined]
        if not msg:  # bare `exofric` (or a bare command group): the help was the answer
            return 0
        print(f"exofric: error: {msg}", file=sys.stderr)
        return 2
    except OSError as exc:  # files the user named: missing, unwritable, not a directory...
        where = f" {exc.filename}:" if getattr(exc, "filename", None) else ""
        why = " ".join(str(exc.strerror or exc).split())
        print(f"exofric: error:{where} {why}", file=sys.stderr)
        return 2
    except Exception as exc:
        # exofric's own errors (neither is an OSError), imported only now: --help and typer's
        # own errors never load exofric.errors (and NumPy with it)
        from exofric.errors import ConvergenceError, InputError

        if isinstance(exc, InputError):
            ran = _running_command(cmd, args)
            print(f"exofric: error: {_with_flags(exc, ran)}", file=sys.stderr)
            return 2
        if isinstance(exc, ConvergenceError):
            hint = ("" if "To try" in str(exc) else " To try: a finer mesh (--accuracy fine), "
                    "smaller pressure steps (more --pressures points), or a thicker wall.")
            print(f"exofric: did not converge: {' '.join(str(exc).split())}"
                  + (hint if _is_fe(args) else ""),
                  file=sys.stderr)
            return 3
        loop = sys.modules.get("exofric.hardware._loop")   # only if a loop ran
        if loop is not None and isinstance(exc, loop.LoopFault):
            head = "stopped" if getattr(exc, "vent_confirmed", True) else "VENT NOT CONFIRMED"
            print(f"exofric: {head}: {' '.join(str(exc).split())}", file=sys.stderr)
            return int(getattr(exc, "exit_code", 4))
        missing = str(getattr(exc, "name", "") or "") if isinstance(exc, ModuleNotFoundError) \
            else ""
        extra = _EXTRA_OF.get(missing.split(".")[0])
        if extra is not None:   # an optional dependency, not a bug: name what installs it
            print(f"exofric: error: this needs the optional package {missing!r} (not installed "
                  f"by `make demo`): pip install 'exofric[{extra}]', or `make test`, which "
                  "installs every extra", file=sys.stderr)
            return 2
        if os.environ.get("EXOFRIC_DEBUG"):
            raise
        # A bug, not the user's input: one line, never a traceback (EXOFRIC_DEBUG=1 shows it).
        what = " ".join(f"{type(exc).__name__}: {exc}".split())
        print(f"exofric: internal error: {what} (a bug in exofric: please report it with the "
              "command line; EXOFRIC_DEBUG=1 prints the traceback)", file=sys.stderr)
        return 1
    code = int(rv) if isinstance(rv, int) else 0
    if code == 130:        # typer turns Ctrl-C into exit code 130 (a control loop vented first)
        print("exofric: interrupted", file=sys.stderr)
    return code


#: Optional packages -> the extra of pyproject.toml that installs them (``make demo`` installs
#: the runtime dependencies only; ``make test`` every extra).
_EXTRA_OF = {"pyarrow": "dask", "dask": "dask", "distributed": "dask", "nptdms": "tdms",
             "openpyxl": "xlsx", "pymodbus": "hardware", "serial": "hardware",
             "playwright": "report", "felupe": "bench", "tensortrax": "bench"}


def _is_fe(args: list[str]) -> bool:
    """True when the command that failed solves the FE (its hint names mesh and steps)."""
    return bool(args) and args[0] in ("squeeze", "inflate", "calibrate", "predict", "sweep",
                                       "design", "reproduce")


def main() -> None:
    """Console entry point."""
    exit_process(run())


def exit_process(code: int) -> None:
    """End the process with ``code``, past pyarrow's intermittent abort at interpreter exit.

    pyarrow's native thread pools can abort the process while Python finalizes ("terminate
    called without an active exception", exit -6 after the command's work and output are done;
    apache/arrow#34314). When pyarrow was loaded, the outputs are flushed and the process ends
    without finalization; otherwise it exits normally.
    """
    if "pyarrow" in sys.modules:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        os._exit(code)
    raise SystemExit(code)
