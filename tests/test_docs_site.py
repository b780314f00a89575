"""The built documentation site (``make docs`` -> docs/_build/html), checked as a reader sees it.

The site takes minutes to build (it executes every example), so it is built by ``make docs``
and this file checks the built tree: CI runs ``make docs`` and then this file with
``EXOFRIC_DOCS_REQUIRED=1`` (.ci/run), where a missing site is a failure. Elsewhere the tests are
skipped, with the reason, when no site has been built (or when Chromium or Playwright is
missing, for the browser test only).

* Every internal link of every page (``href`` and ``src``, with its ``#fragment``) points to a
  file of the site and to an id in it: no 404, no dead anchor.
* Every name in every stage's ``__all__`` has its entry on its stage's API page (an element
  with id ``exofric.<stage>.<name>``), and every name of ``exofric.__all__`` links to one.
* Every command of ``exofric`` (sub-commands included) has its ``--help`` on the CLI page.
* Every example that draws (it imports :mod:`exofric.plots` or matplotlib) shows at least one
  figure on its gallery page, and every example page shows its printed output.
* In headless Chromium (Playwright, as tests/test_report_browser.py): the entry page, every API
  page and every gallery page load with every image decoded (naturalWidth > 0), no console
  error, and no request that fails; nothing is fetched from the network.
"""

from __future__ import annotations

import importlib
import os
import re
import shutil
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "docs" / "_build" / "html"
EXAMPLES = ROOT / "examples"
REQUIRED = os.environ.get("EXOFRIC_DOCS_REQUIRED") == "1"
CHROMIUM = next((p for p in ("/usr/bin/chromium", shutil.which("chromium") or "")
                 if p and Path(p).is_file()), None)
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run"]
#: The stage packages with an API page each (docs/api/<stage>.rst).
STAGES = ("paper", "material", "geometry", "fe", "simulate", "calibration", "friction",
          "control", "design", "reproduction", "hardware", "report", "io", "plots", "errors",
          "defaults")


class _Page(HTMLParser):
    """The ids, links and images of one HTML page."""

    def __init__(self) -> None:
        super().__init__()
        self.ids: set[str] = set()
        self.links: list[str] = []
        self.images: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = dict(attrs)
        if a.get("id"):
            self.ids.add(str(a["id"]))
        if tag == "a" and a.get("name"):
            self.ids.add(str(a["name"]))
        for key in ("href", "src"):
            value = a.get(key)
            if value and not (tag == "link" and key == "href" and a.get("rel") in (
                    "preconnect", "dns-prefetch")):
                self.links.append(str(value))
        if tag == "img" and a.get("src"):
            self.images.append(str(a["src"]))


def _parse(path: Path) -> _Page:
    page = _Page()
    page.feed(path.read_text(encoding="utf-8"))
    return page


@pytest.fixture(scope="module")
def site() -> dict[Path, _Page]:
    if not (SITE / "index.html").is_file():
        if REQUIRED:
            pytest.fail(f"no documentation site at {SITE}: `make docs` did not build it")
        pytest.skip(f"no documentation site built at {SITE} (`make docs` builds it)")
    return {p: _parse(p) for p in sorted(SITE.rglob("*.html"))}


def test_no_broken_internal_links(site: dict[Path, _Page]) -> None:
    broken: list[str] = []
    for path, page in site.items():
        for link in page.links:
            parts = urlsplit(link)
            if parts.scheme or parts.netloc or link.startswith(("mailto:", "data:")):
                continue
            target = (path.parent / unquote(parts.path)).resolve() if parts.path else path
            if target.is_dir():
                target = target / "index.html"
            rel = path.relative_to(SITE)
            if not target.is_file():
                broken.append(f"{rel}: {link} (no file)")
            elif parts.fragment and target.suffix == ".html":
                ids = (site.get(target) or _parse(target)).ids
                if unquote(parts.fragment) not in ids:
                    broken.append(f"{rel}: {link} (no id {parts.fragment!r})")
    assert broken == [], f"{len(broken)} broken internal links, e.g. {broken[:10]}"


def test_every_public_name_has_its_entry(site: dict[Path, _Page]) -> None:
    missing: list[str] = []
    for stage in STAGES:
        page = site.get(SITE / "api" / f"{stage}.html")
        assert page is not None, f"no API page for exofric.{stage}"
        module = importlib.import_module(f"exofric.{stage}")
        missing += [f"exofric.{stage}.{name}" for name in module.__all__
                    if f"exofric.{stage}.{name}" not in page.ids]
    assert missing == [], f"public names without an entry on their stage's page: {missing}"
    # the facade's names link to their homes
    import exofric

    index = (SITE / "api" / "index.html").read_text(encoding="utf-8")
    unlinked = [n for n in exofric.__all__ if n != "__version__"
                and not re.search(rf'href="[a-z]+\.html#exofric\.[a-z]+\.{re.escape(n)}"', index)]
    assert unlinked == [], f"exofric.{unlinked} not linked to its home from api/index.html"


def test_every_command_has_its_help(site: dict[Path, _Page]) -> None:
    import typer.main

    from exofric.cli import app

    def walk(cmd: object, path: list[str]) -> list[str]:
        out = ["-".join(path) or "exofric"]
        if hasattr(cmd, "list_commands"):
            ctx = cmd.context_class(cmd, info_name="exofric")  # type: ignore[attr-defined]
            for name in cmd.list_commands(ctx):
                out += walk(cmd.get_command(ctx, name), [*path, name])  # type: ignore[attr-defined]
        return out

    commands = walk(typer.main.get_command(app), [])
    assert len(commands) > 15 and "control-run" in commands
    ids = site[SITE / "api" / "cli.html"].ids
    assert [c for c in commands if f"cli-{c}" not in ids] == []


def _draws(script: Path) -> bool:
    text = script.read_text(encoding="utf-8")
    return bool(re.search(r"^\s*(from exofric\.plots import|import matplotlib|from matplotlib)",
                          text, re.MULTILINE)) or ".plot(" in text


def test_every_example_page_shows_its_figures_and_output(site: dict[Path, _Page]) -> None:
    scripts = sorted(EXAMPLES.glob("*.py"))
    assert len(scripts) >= 9
    problems: list[str] = []
    for script in scripts:
        html = SITE / "auto_examples" / f"{script.stem}.html"
        if html not in site:
            problems.append(f"{script.name}: no gallery page")
            continue
        figures = [src for src in site[html].images if "sphx_glr_" in src
                   and "thumb" not in src]
        if _draws(script) and not figures:
            problems.append(f"{script.name}: draws, but its page shows no figure")
        text = html.read_text(encoding="utf-8")
        if "sphx-glr-script-out" not in text:
            problems.append(f"{script.name}: no printed output on its page")
    assert problems == [], problems


def test_site_in_headless_chromium(site: dict[Path, _Page], tmp_path: Path) -> None:
    if CHROMIUM is None:
        pytest.skip("no chromium executable (/usr/bin/chromium); `make browser` installs it")
    sync_api = pytest.importorskip("playwright.sync_api",
                                   reason="Playwright's Python package is not installed")
    pages = [SITE / "index.html", *sorted((SITE / "api").glob("*.html")),
             *sorted((SITE / "auto_examples").glob("*.html")),
             *sorted((SITE / "guide").glob("*.html"))]
    problems: list[str] = []
    shown = 0
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        try:
            page = browser.new_page(viewport={"width": 1280, "height": 900})
            errors: list[str] = []
            outside: list[str] = []
            failed: list[str] = []
            page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
            page.on("pageerror", lambda exc: errors.append(str(exc)))
            page.on("requestfailed", lambda r: failed.append(r.url))
            # nothing from the network: such a request is recorded and refused
            page.route(re.compile(r"^(https?|wss?)://"),
                       lambda route: (outside.append(route.request.url), route.abort()))
            for path in pages:
                errors.clear(), outside.clear(), failed.clear()
                page.goto(path.as_uri(), wait_until="load")
                rel = path.relative_to(SITE)
                imgs = page.evaluate("""() => [...document.images].map(i => ({
                    src: i.getAttribute('src'), ok: i.complete && i.naturalWidth > 0}))""")
                shown += sum(i["ok"] for i in imgs)
                problems += [f"{rel}: image not shown: {i['src']}" for i in imgs if not i["ok"]]
                problems += [f"{rel}: console error: {e}" for e in errors]
                problems += [f"{rel}: fetched from the network: {u}" for u in outside]
                problems += [f"{rel}: request failed: {u}" for u in failed
                             if not u.startswith(("http:", "https:"))]
                text = page.inner_text("article") if page.locator("article").count() else ""
                if len(text.strip()) < 200:
                    problems.append(f"{rel}: almost empty ({len(text.strip())} characters)")
            page.goto((SITE / "auto_examples" / "index.html").as_uri(), wait_until="load")
            page.screenshot(path=str(tmp_path / "gallery.png"), full_page=False)
        finally:
            browser.close()
    assert problems == [], problems
    assert shown >= 10, f"only {shown} images shown on {len(pages)} pages"
