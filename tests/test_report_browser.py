"""report.html in a real headless browser (Debian's chromium through Playwright).

Checks that every figure loaded (naturalWidth > 0), every table has rows, the console shows
no errors, nothing is fetched from the network, and the page does not overflow sideways at
phone width. On a 1400 px wide page no figure is shown below 80 % of its natural width and
its smallest text is shown at >= 9 pt (the report sizes figures for the page); no difference
cell of the paper-beside-ours tables shows a percentage above 1000 % (differences are shown
only where they mean something). Screenshots (desktop and phone) are written next to the
report for a look. Skipped only when no browser executable (or Playwright) is available.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from test_reproduce import fast_report_dir

CHROMIUM = next((p for p in ("/usr/bin/chromium", shutil.which("chromium") or "")
                 if p and Path(p).is_file()), None)
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run"]


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = fast_report_dir(tmp_path_factory)
    cli = json.loads((out / "cli.json").read_text())
    assert cli["code"] == 0, cli["stderr"]
    return out


def test_report_in_headless_chromium(report: Path) -> None:
    if CHROMIUM is None:
        pytest.skip("no chromium executable (/usr/bin/chromium); `make browser` installs it")
    sync_api = pytest.importorskip("playwright.sync_api",
                                   reason="Playwright's Python package is not installed")
    figures = json.loads((report / "results.json").read_text())["figures"]
    url = (report / "report.html").resolve().as_uri()
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        try:
            for name, vp in (("desktop", {"width": 1400, "height": 900}),
                             ("phone", {"width": 390, "height": 844})):
                page = browser.new_page(viewport=vp)
                errors: list[str] = []
                requests: list[str] = []
                page.on("console", lambda m, e=errors: e.append(m.text) if m.type == "error"
                        else None)
                page.on("pageerror", lambda exc, e=errors: e.append(str(exc)))
                page.on("request", lambda r, q=requests: q.append(r.url))
                page.goto(url, wait_until="load")
                imgs = page.evaluate("""() => [...document.images].map(i => ({
                    alt: i.alt, complete: i.complete, w: i.naturalWidth, h: i.naturalHeight,
                    shown: i.getBoundingClientRect().width}))""")
                assert len(imgs) == len(figures)
                bad = [i["alt"] for i in imgs if not (i["complete"] and i["w"] > 0 and i["h"] > 0)]
                assert bad == [], f"figures not loaded: {bad}"
                if name == "desktop":   # sized for the page: shown at >= 80 % of natural width
                    small = [(i["alt"], i["w"], round(i["shown"])) for i in imgs
                             if i["shown"] < 0.8 * i["w"]]
                    assert small == [], f"figures shrunk by more than 20 %: {small}"
                    # text as shown: min font (pt at the PNG's dpi) x dpi/96 x shown/natural
                    tiny = [(f["key"], round(f["min_font_pt"] * f["dpi"] / 96 * i["shown"]
                                             / i["w"], 1))
                            for f, i in zip(figures, imgs, strict=True)
                            if f["min_font_pt"] is not None
                            and f["min_font_pt"] * f["dpi"] / 96 * i["shown"] / i["w"] < 9.0]
                    assert tiny == [], f"figure text shown below 9 pt: {tiny}"
                # differences: a percentage in a difference cell stays <= 1000 % (none for
                # p-values, percentage points for quantities already in %)
                pcts = page.evaluate(r"""() => [...document.querySelectorAll('td.diff')].flatMap(
                    td => {
                        const th = td.closest('table').querySelectorAll('thead th')[td.cellIndex];
                        const inPct = th && th.textContent.includes('%');
                        const t = td.textContent;
                        if (/pp/.test(t)) return [];
                        const re = inPct ? /[-+]?\d+(\.\d+)?/g : /[-+]?\d+(\.\d+)?(?= %)/g;
                        return (t.match(re) || []).map(Number);
                    })""")
                assert pcts, "no difference cells found"
                assert max(abs(x) for x in pcts) <= 1000, sorted(pcts)[-3:]
                rows = page.evaluate("""() => [...document.querySelectorAll('table')].map(
                    t => t.querySelectorAll('tbody tr').length)""")
                assert len(rows) >= 15 and min(rows) >= 1, rows
                assert errors == [], errors
                dead = page.evaluate("""() => [...document.querySelectorAll('a[href^="#"]')]
                    .map(a => a.getAttribute('href').slice(1))
                    .filter(id => !document.getElementById(decodeURIComponent(id)))""")
                assert dead == [], f"in-page links without a target: {dead}"
                # self-contained: only the page itself and data: URIs
                assert [u for u in requests if not u.startswith(("file:", "data:"))] == []
                width = page.evaluate("document.documentElement.scrollWidth")
                assert width <= vp["width"] + 1, f"{name}: page is {width}px wide"
                assert page.locator("text=SYNTHETIC").count() > 5
                page.screenshot(path=str(report / f"screenshot-{name}.png"), full_page=True)
                page.close()
        finally:
            browser.close()
    assert (report / "screenshot-phone.png").stat().st_size > 10_000
