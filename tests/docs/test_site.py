"""The documentation site as a reader's browser shows it (``make docs-check``, after ``make docs``).

The site is served from a local ``http.server`` on 127.0.0.1 and every page is opened in
Debian's headless Chromium (``/usr/bin/chromium``), driven by Playwright's Python package
(Playwright's own browsers are never downloaded), with a new, empty profile. Every
request the browser makes is routed through :func:`browser`: one to any other host is
refused and recorded, as is every failed or 4xx/5xx request. On every page its math
must be typeset by MathJax (every math element holds MathJax's output, no MathJax
error, no TeX left as text, nor a docstring's reST markup), every image must load
(``naturalWidth > 0``), every link to a page of the site must reach an existing file
and, when it has one, an existing anchor, no request may leave 127.0.0.1 or fail, and
no script may fail. The front page and the paper's derivation are kept as screenshots
in ``out/docs-check/``.

Not part of ``make test`` (marker ``docs``, deselected by default).
"""

from __future__ import annotations

import functools
import http.server
import os
import re
import threading
from dataclasses import dataclass, field
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

pytestmark = pytest.mark.docs

ROOT = Path(__file__).resolve().parents[2]
SITE = Path(os.environ.get("SYMCTL_DOCS_SITE", ROOT / "docs" / "_build" / "html"))
"""The built site (``make docs`` writes it)."""
ARTEFACTS = Path(os.environ.get("SYMCTL_DOCS_CHECK_OUT", ROOT / "out" / "docs-check"))
"""Where the screenshots go."""
CHROMIUM = os.environ.get("SYMCTL_CHROMIUM", "/usr/bin/chromium")
"""Debian's Chromium (``apt-get install chromium``)."""
CHROMIUM_ARGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-default-apps",
    "--disable-extensions",
    "--no-first-run",
    "--no-default-browser-check",
)
"""Chromium quiet: nothing of its own goes to the network."""
VIEWPORT = {"width": 1280, "height": 900}


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format, *args):
        pass


class _Server(http.server.ThreadingHTTPServer):
    """A browser that drops a connection it no longer needs is not an error."""

    def handle_error(self, request, client_address):
        import sys

        if not isinstance(sys.exc_info()[1], ConnectionError):
            super().handle_error(request, client_address)


@dataclass
class Traffic:
    """What the browser asked for that it should not have, or did not get."""

    outside: list[str] = field(default_factory=list)
    failed: list[str] = field(default_factory=list)

    def take(self) -> list[str]:
        """The problems seen since the last call, then forgotten."""
        seen = [f"request to outside: {u}" for u in self.outside] + self.failed
        self.outside.clear()
        self.failed.clear()
        return seen


@pytest.fixture(scope="session")
def site() -> Path:
    if not (SITE / "index.html").is_file():
        pytest.fail(f"no built site at {SITE}: run `make docs` first")
    return SITE


@pytest.fixture(scope="session")
def server(site):
    """The site's base URL on 127.0.0.1 (a free port), served until the session ends."""
    handler = functools.partial(_Quiet, directory=str(site))
    httpd = _Server(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}/"
    httpd.shutdown()
    httpd.server_close()


@pytest.fixture(scope="session")
def browser(server, tmp_path_factory):
    """``(context, traffic)``: a Chromium context with a new, empty profile whose every request
    is checked (see :class:`Traffic`)."""
    if not Path(CHROMIUM).is_file():
        pytest.fail(f"no Chromium at {CHROMIUM} (Debian: apt-get install chromium)")
    from playwright.sync_api import sync_playwright

    local = urlsplit(server).netloc
    traffic = Traffic()

    def guard(route):
        url = route.request.url
        if urlsplit(url).scheme in ("data", "blob") or urlsplit(url).netloc == local:
            route.continue_()
        else:
            traffic.outside.append(url)
            route.abort()

    def on_response(response):
        if response.status >= 400:
            traffic.failed.append(f"HTTP {response.status}: {response.url}")

    def on_failed(request):
        if urlsplit(request.url).netloc == local:
            traffic.failed.append(f"request failed ({request.failure}): {request.url}")

    with sync_playwright() as playwright:
        context = playwright.chromium.launch_persistent_context(
            str(tmp_path_factory.mktemp("chromium-profile")),
            executable_path=CHROMIUM,
            headless=True,
            args=list(CHROMIUM_ARGS),
            viewport=VIEWPORT,
            service_workers="block",
        )
        context.route("**/*", guard)
        context.on("response", on_response)
        context.on("requestfailed", on_failed)
        try:
            yield context, traffic
        finally:
            context.close()


SKIPPED = ("_static", "_sources", "_downloads", "_images")
"""Folders of the site that hold files, not pages."""
PAGES = sorted(
    p.relative_to(SITE).as_posix()
    for p in SITE.rglob("*.html")
    if p.relative_to(SITE).parts[0] not in SKIPPED
) or ["index.html"]  # no site: the one test fails, saying `make docs`
DERIVATION = "generated/derivation_paper.html"
"""The page of the paper's derivation (T = 2), kept as a screenshot."""

INSPECT = r"""
async () => {
  const report = {math: 0, unrendered: [], mathErrors: [], rawTex: [], rawMarkup: [], images: [], links: []};
  if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
    await MathJax.startup.promise;
  }
  for (const el of document.querySelectorAll(".math")) {
    report.math += 1;
    if (!el.querySelector("mjx-container")) report.unrendered.push(el.textContent.trim().slice(0, 100));
  }
  for (const el of document.querySelectorAll("mjx-merror, [data-mjx-error]")) {
    report.mathErrors.push((el.getAttribute("data-mjx-error") || el.textContent).slice(0, 100));
  }
  // TeX left as text (delimiters, or a TeX command) outside code and MathJax's output.
  const skip = "pre, code, script, style, textarea, kbd, samp, mjx-container, .highlight";
  const commands = "frac|begin|end|left|right|mathrm|operatorname|epsilon|tilde|bar|hat|sum|cdot|"
    + "displaystyle|text|tag";
  const tex = new RegExp("\\\\\\(|\\\\\\[|\\$\\$|\\$[^$\\s][^$\\n]*\\$|\\\\(" + commands + ")\\b");
  // reST left as text (a docstring numpydoc did not parse): ``literal`` or a :role:`target`.
  const markup = /``|:(func|class|meth|attr|data|mod|obj|exc|math|ref|doc):`/;
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  for (let node = walker.nextNode(); node; node = walker.nextNode()) {
    const parent = node.parentElement;
    if (!parent || parent.closest(skip)) continue;
    for (const [pattern, found] of [[tex, report.rawTex], [markup, report.rawMarkup]]) {
      const match = node.textContent.match(pattern);
      if (match) {
        const at = Math.max(0, match.index - 40);
        found.push(node.textContent.slice(at, match.index + 60).replace(/\s+/g, " "));
      }
    }
  }
  // Images: lazy ones asked for now, then each one waited for.
  const images = Array.from(document.images);
  for (const img of images) img.loading = "eager";
  await Promise.all(images.map(img => img.complete ? null : new Promise(done => {
    img.addEventListener("load", done, {once: true});
    img.addEventListener("error", done, {once: true});
    setTimeout(done, 15000);
  })));
  for (const img of images) {
    report.images.push({src: img.currentSrc || img.src, ok: img.complete && img.naturalWidth > 0});
  }
  for (const a of document.querySelectorAll("a[href], area[href], link[href]")) report.links.push(a.href);
  return report;
}
"""


class _Anchors(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.ids: set[str] = set()

    def handle_starttag(self, tag, attrs):
        for key, value in attrs:
            if key in ("id", "name") and value:
                self.ids.add(value)


@functools.cache
def anchors(path: Path) -> frozenset[str]:
    """The ids (and names) of the elements of an HTML file."""
    parser = _Anchors()
    parser.feed(path.read_text(encoding="utf-8"))
    return frozenset(parser.ids)


def broken_link(href: str, base: str) -> str | None:
    """Why ``href`` (absolute) does not reach a file or anchor of the site, or None if it does
    (or if it leads off the site: such links are not followed)."""
    url = urlsplit(href)
    if url.scheme not in ("http", "https") or f"{url.scheme}://{url.netloc}/" != base:
        return None
    target = SITE / unquote(url.path).lstrip("/")
    if url.path.endswith("/"):
        target = target / "index.html"
    if not target.is_file():
        return f"no such file: {href}"
    if url.fragment and target.suffix == ".html" and unquote(url.fragment) not in anchors(target):
        return f"no anchor #{url.fragment} in {target.relative_to(SITE)}: {href}"
    return None


def open_page(browser, server, page_path: str):
    """``(page, problems)``: the page loaded, with its script errors and bad requests so far."""
    context, traffic = browser
    traffic.take()
    page = context.new_page()
    problems: list[str] = []
    page.on("pageerror", lambda err: problems.append(f"script error: {err}"))
    page.on(
        "console",
        lambda msg: problems.append(f"console error: {msg.text}") if msg.type == "error" else None,
    )
    page.goto(server + page_path, wait_until="load", timeout=60_000)
    return page, problems


@pytest.mark.parametrize("page_path", PAGES)
def test_page_renders_math_images_and_links(browser, server, page_path):
    page, problems = open_page(browser, server, page_path)
    try:
        report = page.evaluate(INSPECT)
    finally:
        page.close()
    problems += [f"math not typeset: {t!r}" for t in report["unrendered"]]
    problems += [f"MathJax error: {t!r}" for t in sorted(set(report["mathErrors"]))]
    problems += [f"TeX left as text: {t!r}" for t in report["rawTex"]]
    problems += [f"reST markup left as text: {t!r}" for t in report["rawMarkup"]]
    problems += [f"image not loaded: {i['src']}" for i in report["images"] if not i["ok"]]
    problems += sorted({b for h in report["links"] if (b := broken_link(h, server))})
    problems += browser[1].take()
    assert not problems, f"{page_path}:\n" + "\n".join(problems)


def test_derivation_pages_have_typeset_math(browser, server, site):
    """The derivations are the math-heaviest pages: each has its displays, all typeset."""
    pages = sorted(
        p.relative_to(site).as_posix() for p in (site / "generated").glob("derivation_*.html")
    )
    assert pages, "no derivation page was built"
    for page_path in pages:
        page, problems = open_page(browser, server, page_path)
        try:
            report = page.evaluate(INSPECT)
            typeset = page.locator("mjx-container[display='true']").count()
        finally:
            page.close()
        assert report["math"] >= 20 and typeset >= 10, (page_path, report["math"], typeset)
        assert not problems and not report["unrendered"], (page_path, problems)


_EXTERNAL = re.compile(
    r"<(script|link|img|iframe|source|video|audio|embed|object)\b[^>]*?\b(src|href|data|srcset)"
    r"\s*=\s*[\"']?\s*(https?:|//)",
    re.IGNORECASE,
)
_CSS_EXTERNAL = re.compile(
    r"(url\(\s*[\"']?\s*(https?:|//)|@import\s+[\"']?(https?:|//))", re.IGNORECASE
)


def test_no_page_refers_to_a_resource_outside_the_site(site):
    """Scripts, styles, images and fonts all come from the site (the site works offline)."""
    found = []
    for path in sorted(site.rglob("*.html")):
        found += [
            f"{path.relative_to(site)}: {m.group(0)}"
            for m in _EXTERNAL.finditer(path.read_text("utf-8"))
        ]
    for path in sorted(site.rglob("*.css")):
        found += [
            f"{path.relative_to(site)}: {m.group(0)}"
            for m in _CSS_EXTERNAL.finditer(path.read_text("utf-8"))
        ]
    assert not found, "\n".join(found)


def _screenshot(browser, server, page_path: str, name: str, scroll_to: str | None = None):
    page, problems = open_page(browser, server, page_path)
    try:
        page.evaluate(INSPECT)  # waits for MathJax and the images
        if scroll_to:
            heading = page.get_by_role("heading", name=re.compile(scroll_to)).first
            heading.evaluate("el => el.scrollIntoView({block: 'start'})")
            page.evaluate("window.scrollBy(0, -120)")  # the heading below the theme's top bar
        visible = page.evaluate(
            """() => Array.from(document.querySelectorAll("mjx-container")).filter(el => {
                const r = el.getBoundingClientRect();
                return r.bottom > 0 && r.top < window.innerHeight && r.width > 0; }).length"""
        )
        ARTEFACTS.mkdir(parents=True, exist_ok=True)
        path = ARTEFACTS / name
        page.screenshot(path=str(path))
    finally:
        page.close()
    assert not problems, problems
    return path, visible


def test_screenshots_of_the_front_page_and_the_derivation(browser, server, site):
    front, _ = _screenshot(browser, server, "index.html", "front.png")
    derivation, math = _screenshot(
        browser, server, DERIVATION, "derivation.png", scroll_to=r"^The controller"
    )
    assert front.stat().st_size > 10_000 and derivation.stat().st_size > 10_000
    assert math >= 2, f"the derivation's screenshot shows {math} typeset formulas"
