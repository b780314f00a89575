"""Sphinx helpers for exofric's documentation site (loaded by docs/conf.py).

* The ``exofric-stage`` directive writes one stage's API page from its package's ``__all__``:
  the package docstring (the stage's story) on top, a summary table, then every public name
  (classes with their documented members, functions, constants with their ``#:`` comment).
  Nothing is listed by hand, so a name added to a stage's ``__all__`` appears on its page.
* :func:`public_home_modules` gives every public class and function its public import path as
  ``__module__`` (``exofric.fe._inflation.MeshSpec`` -> ``exofric.fe.MeshSpec``) for the docs
  build only, so the signatures' type hints link to the documented names.
* :class:`WrittenImages` is a sphinx-gallery image scraper for the examples, which write their
  figures with :func:`exofric.plots.save` (and close them): the PNGs an example wrote into
  ``examples/`` are moved into the gallery's image folder and shown on its page.

A public name without documentation (a constant without a ``#:`` comment, a class or function
without a docstring) is a build warning, so ``-W`` fails on it.
"""

from __future__ import annotations

import importlib
import inspect
import re
import shutil
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.application import Sphinx
from sphinx.pycode import ModuleAnalyzer
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

logger = logging.getLogger(__name__)

#: The stages in pipeline order (the layers of pyproject.toml's import contract, bottom-up for
#: the computing stages, then the helpers every stage uses). One API page each.
STAGES: tuple[str, ...] = (
    "exofric.paper",
    "exofric.material",
    "exofric.geometry",
    "exofric.fe",
    "exofric.simulate",
    "exofric.calibration",
    "exofric.friction",
    "exofric.control",
    "exofric.design",
    "exofric.reproduction",
    "exofric.hardware",
    "exofric.report",
    "exofric.io",
    "exofric.plots",
    "exofric.errors",
    "exofric.defaults",
)

#: Names that are documented but have no docstring or ``#:`` comment of their own yet (the
#: build warns about any other undocumented public name). Filled from conf.py.
UNDOCUMENTED_OK: set[str] = set()


def _unwrap(obj: Any) -> Any:
    return getattr(obj, "__wrapped__", obj) if not inspect.isclass(obj) else obj


def _kind(obj: Any) -> str:
    if inspect.isclass(obj):
        return "class"
    if inspect.isroutine(_unwrap(obj)) or inspect.isfunction(_unwrap(obj)):
        return "function"
    return "data"


def _home_module(package: Any, name: str) -> str:
    """The module that assigns ``name`` (for a constant's ``#:`` comment)."""
    from exofric._lazy import type_checking_homes

    if hasattr(package, "__path__"):
        homes = type_checking_homes(package.__file__)
        if name in homes:
            return homes[name]
        import pkgutil

        for info in pkgutil.iter_modules(package.__path__):
            sub = importlib.import_module(f"{package.__name__}.{info.name}")
            if name in vars(sub):
                try:
                    if ("", name) in ModuleAnalyzer.for_module(sub.__name__).find_attr_docs():
                        return sub.__name__
                except Exception:  # pragma: no cover - analyzer cannot read the source
                    continue
    return package.__name__


def constant_doc(package: Any, name: str) -> list[str]:
    """The ``#:`` comment (or docstring after the assignment) of a public constant."""
    home = _home_module(package, name)
    try:
        docs = ModuleAnalyzer.for_module(home).find_attr_docs()
    except Exception:  # pragma: no cover
        return []
    return [line for line in docs.get(("", name), []) if line is not None]


def _summary(lines: list[str]) -> str:
    para: list[str] = []
    for line in lines:
        if not line.strip():
            if para:
                break
            continue
        para.append(line.strip())
    return " ".join(para)


def _value_repr(obj: Any) -> str | None:
    text = repr(obj)
    if "\n" in text or len(text) > 90:
        return None
    return text


def _iter_public(mod: Any) -> Iterator[tuple[str, Any]]:
    for name in mod.__all__:
        yield name, getattr(mod, name)


def public_home_modules() -> None:
    """Set ``__module__`` of every stage's public classes and functions to the stage package.

    For the documentation build only: autodoc then shows and links ``exofric.fe.MeshSpec``
    (where it is documented) instead of its private home ``exofric.fe._inflation``.
    """
    for stage in STAGES:
        mod = importlib.import_module(stage)
        for _, obj in _iter_public(mod):
            target = _unwrap(obj)
            module = getattr(target, "__module__", None)
            if (isinstance(module, str) and module.startswith(stage + ".")
                    and _kind(obj) != "data"):
                try:
                    target.__module__ = stage
                    if target is not obj:
                        obj.__module__ = stage
                except (AttributeError, TypeError):  # pragma: no cover - builtins
                    pass


class StageDirective(SphinxDirective):
    """``.. exofric-stage:: exofric.fe`` -- the API page of one stage, from its ``__all__``."""

    required_arguments = 1
    has_content = False

    def _lines(self, package: str) -> list[str]:
        mod = importlib.import_module(package)
        out = [f".. automodule:: {package}", "   :no-members:", ""]
        out += ["Public names", "------------", "",
                f"Everything in ``{package}.__all__``, in the package's order.", "",
                ".. list-table::", "   :header-rows: 1", "   :widths: 35 65",
                "   :class: exofric-api-summary", "",
                "   * - name", "     - what it is"]
        entries: list[str] = []
        for name, obj in _iter_public(mod):
            kind = _kind(obj)
            full = f"{package}.{name}"
            if kind == "data":
                doc = constant_doc(mod, name)
            else:
                raw = inspect.getdoc(_unwrap(obj)) or ""
                doc = raw.splitlines()
            if not any(line.strip() for line in doc) and full not in UNDOCUMENTED_OK:
                logger.warning("exofric API: public name %s has no documentation "
                               "(a docstring, or a '#:' comment for a constant)", full,
                               location=(self.env.docname, self.lineno))
            summary = _escape_bars(_summary(doc)) or "(not documented yet)"
            role = {"class": "class", "function": "func", "data": "data"}[kind]
            out += [f"   * - :py:{role}:`~{full}`", f"     - {summary}"]
            if kind == "class":
                entries += [f".. autoclass:: {full}", "   :members:", ""]
            elif kind == "function":
                entries += [f".. autofunction:: {full}", ""]
            else:
                entries += [f".. py:data:: {name}", f"   :module: {package}"]
                value = _value_repr(obj)
                if value is not None:
                    entries.append(f"   :value: {value}")
                else:
                    entries.append(f"   :type: {type(obj).__module__}.{type(obj).__qualname__}"
                                   if type(obj).__module__ != "builtins"
                                   else f"   :type: {type(obj).__qualname__}")
                entries.append("")
                doc = list(doc)
                escape_absolute_values(None, "data", full, obj, None, doc)  # type: ignore[arg-type]
                entries += [f"   {line}" for line in doc] + [""]
        out += ["", "Reference", "---------", "", *entries]
        return out

    def run(self) -> list[nodes.Node]:
        package = self.arguments[0]
        content = StringList(self._lines(package), source=f"<exofric-stage {package}>")
        node = nodes.section()
        node.document = self.state.document
        nested_parse_with_titles(self.state, content, node)
        return node.children


class FacadeDirective(SphinxDirective):
    """``.. exofric-facade::`` -- the names importable from ``exofric`` and their homes."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        import exofric

        lines = [".. list-table::", "   :header-rows: 1", "   :widths: 30 70", "",
                 "   * - ``exofric.``\\ name", "     - its home (documented there)"]
        for name in exofric.__all__:
            if name == "__version__":
                lines += ["   * - ``__version__``", "     - the package version (str)"]
                continue
            obj = getattr(exofric, name)
            target = _unwrap(obj)
            home = next((s for s in STAGES
                         if name in getattr(importlib.import_module(s), "__all__", ())
                         and getattr(importlib.import_module(s), name) is obj), None)
            if home is None:
                logger.warning("exofric API: exofric.%s is in no stage's __all__", name,
                               location=(self.env.docname, self.lineno))
                continue
            role = {"class": "class", "function": "func", "data": "data"}[_kind(target)]
            lines += [f"   * - ``{name}``", f"     - :py:{role}:`{home}.{name}`"]
        content = StringList(lines, source="<exofric-facade>")
        node = nodes.section()
        node.document = self.state.document
        nested_parse_with_titles(self.state, content, node)
        return node.children


class CliDirective(SphinxDirective):
    """``.. exofric-cli::`` -- every command's ``--help``, as the terminal shows it."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        import os

        import typer.main
        from typer.testing import CliRunner

        from exofric.cli import app

        os.environ.setdefault("TERMINAL_WIDTH", "80")
        env = {"TERMINAL_WIDTH": "80", "NO_COLOR": "1", "COLUMNS": "80"}
        runner = CliRunner()

        def walk(group: Any, path: list[str]) -> Iterator[list[str]]:
            # duck-typed: typer ships its own copy of click's classes
            yield path
            if hasattr(group, "list_commands"):
                ctx = group.context_class(group, info_name=path[-1] if path else "exofric")
                for name in group.list_commands(ctx):
                    sub = group.get_command(ctx, name)
                    if sub is not None and not getattr(sub, "hidden", False):
                        yield from walk(sub, [*path, name])

        import typer.testing

        from exofric.cli._options import tidy_help

        # the pages as `exofric ... --help` prints them: flags without <bool>, prose wrapped
        # by the width (exofric.cli.run builds its command tree the same way)
        cmd = tidy_help(typer.main.get_command(app))
        lines: list[str] = []
        get = typer.testing._get_command
        typer.testing._get_command = lambda _app: cmd
        try:
            pages = [(path, runner.invoke(app, [*path, "--help"], env=env))
                     for path in walk(cmd, [])]
        finally:
            typer.testing._get_command = get
        for path, result in pages:
            if result.exit_code != 0:
                logger.warning("exofric CLI: 'exofric %s --help' exited %d",
                               " ".join(path), result.exit_code,
                               location=(self.env.docname, self.lineno))
            title = "exofric " + " ".join(path) if path else "exofric"
            anchor = "cli-" + ("-".join(path) if path else "exofric")
            lines += [f".. _{anchor}:", "", f"``{title}``", "-" * (len(title) + 4), "",
                      "::", ""]
            lines += [f"   {line.rstrip()}" for line in result.output.splitlines()
                      if line.strip()]
            lines.append("")
        content = StringList(lines, source="<exofric-cli>")
        node = nodes.section()
        node.document = self.state.document
        nested_parse_with_titles(self.state, content, node)
        return node.children


# ---------------------------------------------------------------------------------------------
# sphinx-gallery: the figures an example writes with exofric.plots.save


_EXAMPLE_START: dict[str, float] = {}


def mark_example_start(gallery_conf: dict[str, Any], fname: str, when: str = "before") -> None:
    """sphinx-gallery ``reset_modules`` hook: note when each example starts."""
    if when == "before":
        _EXAMPLE_START["t"] = time.time() - 1.0


class WrittenImages:
    """sphinx-gallery image scraper: show the PNG/SVG files an example wrote next to itself.

    The examples draw with exofric's plot functions and write the figure with
    :func:`exofric.plots.save` (which closes it), as a user running them would. Files written
    into the example's folder since the example started are moved into the gallery's image
    folder (so the source tree stays clean) and shown in the page.
    """

    def __repr__(self) -> str:  # sphinx-gallery embeds the repr in its config cache key
        return "WrittenImages()"

    def __call__(self, block: Any, block_vars: dict[str, Any], gallery_conf: dict[str, Any]
                 ) -> str:
        from sphinx_gallery.scrapers import figure_rst

        src_dir = Path(block_vars["src_file"]).parent
        start = _EXAMPLE_START.get("t", 0.0)
        written = sorted((p for p in src_dir.iterdir()
                          if p.suffix in (".png", ".svg") and p.stat().st_mtime >= start),
                         key=lambda p: p.stat().st_mtime)
        images = []
        for path, target in zip(written, block_vars["image_path_iterator"], strict=False):
            target = Path(target).with_suffix(path.suffix)
            shutil.move(str(path), str(target))
            images.append(str(target))
        return figure_rst(images, gallery_conf["src_dir"])


WRITTEN_IMAGES = WrittenImages()

#: The gallery in pipeline order (material -> FE -> friction -> control -> design); examples
#: not listed here follow, by file name.
EXAMPLE_ORDER: tuple[str, ...] = (
    "treloar_fit.py",
    "silicone_fit.py",
    "inflate_tube.py",
    "tube_ends.py",
    "squeeze_base_group.py",
    "tolerance_bands.py",
    "pullout_knee.py",
    "pullout_calibration.py",
    "fit_gamma.py",
    "reduce_rig_log.py",
    "predict_structures.py",
    "pi_loop.py",
    "hardware_loop_sim.py",
    "gait_knee.py",
    "small_sweep.py",
)


class PipelineOrder:
    """sphinx-gallery ``within_subsection_order``: the examples in pipeline order."""

    def __init__(self, src_dir: str) -> None:
        self.src_dir = src_dir

    def __repr__(self) -> str:
        return "<PipelineOrder>"

    def __call__(self, filename: str) -> tuple[int, str]:
        name = Path(filename).name
        rank = EXAMPLE_ORDER.index(name) if name in EXAMPLE_ORDER else len(EXAMPLE_ORDER)
        return rank, name


# ---------------------------------------------------------------------------------------------
# Docstrings: plain-text absolute values, and the facade's names


# ``|x|`` (an absolute value in plain-text maths) outside inline literals and roles; ``||`` and
# table bars (``a | b``) are left alone.
_BARS = re.compile(r"(``.*?``|`[^`\n]*`)|(?<![\\|\w])\|(?=[^\s|])([^|`\n]*?[^\s|\\])\|(?![|\w])")


def _escape_bars(line: str) -> str:
    return _BARS.sub(lambda m: m.group(1) or f"\\|{m.group(2)}\\|", line)


def escape_absolute_values(app: Sphinx, what: str, name: str, obj: Any, options: Any,
                           lines: list[str]) -> None:
    """``autodoc-process-docstring``: show ``|N - N_coarse|`` as written.

    exofric's docstrings write absolute values as ``|x|`` (they read as plain text in
    ``help()``); reStructuredText would take them for substitution references. Literal blocks
    (after ``::``), doctest lines and inline literals are left as they are.
    """
    in_literal = False
    literal_indent = 0  # the indentation of the paragraph that ended with "::"
    for i, line in enumerate(lines):
        stripped = line.strip()
        indent = len(line) - len(line.lstrip())
        if in_literal:
            if not stripped or indent > literal_indent:
                continue
            in_literal = False
        if not stripped or stripped.startswith(">>>") or stripped.startswith("..."):
            continue
        if "|" in line and not stripped.startswith(".. "):
            lines[i] = _escape_bars(line)
        if stripped.endswith("::") or (stripped.startswith(".. ") and "::" in stripped):
            in_literal, literal_indent = True, indent  # a literal block or a directive's body


def resolve_facade(app: Sphinx, env: Any, node: Any, contnode: Any) -> Any:
    """``missing-reference``: ``exofric.fit_gamma`` -> its home ``exofric.friction.fit_gamma``.

    The names importable from ``exofric`` itself are documented once, in their stage; a
    reference through the facade resolves there. Any other missing reference stays missing.
    """
    target = node.get("reftarget", "")
    if node.get("refdomain") != "py" or not target.startswith("exofric."):
        return None
    head, _, rest = target[len("exofric."):].partition(".")
    import exofric

    if head not in exofric.__all__ or head == "__version__":
        return None
    obj = getattr(exofric, head)
    home = next((s for s in STAGES if getattr(importlib.import_module(s), head, None) is obj
                 and head in importlib.import_module(s).__all__), None)
    if home is None:
        return None
    new_target = f"{home}.{head}" + (f".{rest}" if rest else "")
    domain = env.domains["py"]
    return domain.resolve_xref(env, node.get("refdoc", ""), app.builder, node["reftype"],
                               new_target, node, contnode)


def title_examples(app: Sphinx, docname: str, source: list[str]) -> None:
    """``source-read``: the first line of an example's docstring becomes its page title.

    The examples' docstrings open with a one-line summary (as ``help()`` shows it), not a
    reStructuredText heading; sphinx-gallery uses that line as the title of the thumbnail, and
    here it gets its underline so that the page has the same title.
    """
    if not docname.startswith("auto_examples/") or docname == "auto_examples/index":
        return
    lines = source[0].split("\n")
    label = next((i for i, line in enumerate(lines) if line.startswith(".. _sphx_glr_")), None)
    if label is None:
        return
    i = label + 1
    while i < len(lines) and not lines[i].strip():
        i += 1
    heading = i + 1 < len(lines) and re.fullmatch(r"([=\-~^\"'`#*+])\1{2,}",
                                                  lines[i + 1].strip())
    if not heading:
        if i + 1 < len(lines) and lines[i + 1].strip():
            logger.warning("exofric gallery: %s: the docstring's first paragraph is longer "
                           "than one line; the title is its first line", docname)
        title = lines[i].strip()
        lines[i] = title + "\n" + "=" * len(title) + "\n"
    escape_absolute_values(app, "example", docname, None, None, lines)
    source[0] = "\n".join(lines)


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_directive("exofric-stage", StageDirective)
    app.add_directive("exofric-facade", FacadeDirective)
    app.add_directive("exofric-cli", CliDirective)
    app.connect("source-read", title_examples)
    app.connect("autodoc-process-docstring", escape_absolute_values)
    app.connect("missing-reference", resolve_facade)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
