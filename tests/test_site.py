"""The website (results/site, ``snakemake --cores all site``) opened in headless Chromium as a reader would.

Every page of the site is served over http://127.0.0.1 by a thread of this
process and opened once in Debian's ``chromium`` through ``chromedriver``
(selenium); the tests then read what the browser recorded:

* the console: no message of level SEVERE (a script error, a resource that
  failed to load);
* the network (Chrome's performance log, the DevTools protocol's ``Network``
  events): no request failed or answered with status 400 or above, and none
  went to a host other than the local server. Chromium is also told to resolve
  no host but 127.0.0.1, so a request to another host could not reach the
  network while the test runs, and would fail loudly if one were made;
* every ``<img>`` loaded (``naturalWidth > 0``);
* every link to the site itself answers 200, and its ``#fragment``, if any,
  names an element of the target page;
* mathematics: every element Sphinx marks as math holds MathJax's output
  (``mjx-container``), the pages that carry math have some, and no TeX
  delimiter (``$...$``, ``$$``, ``\\(``, ``\\[``) is left in the text outside code;
* code: at the window's 1280 px no ``pre`` of a page (a notebook's cells,
  input and output, and the other pages' code) is wider than its box, so none
  is clipped or scrolls sideways (book/_static/code.css wraps long lines),
  and what a reader copies from each is its text as written;
* the search page, asked for "Algorithm 1", lists the tutorial's notebook 01,
  the notebook that states Algorithm 1;
* one way to search on each page at 1280 px and at 600 px: the sidebar's field
  on a wide window, the header's icon on a narrow one, the search page's own
  form on that page.

A screenshot of each page goes to ``results/site-check/<page>.png``.

Marked slow: it needs the site, which needs the executed notebooks. Without
``results/site`` the tests skip, saying how to build it (in CI, where
``.ci/run`` builds it first, they fail instead). Without ``chromium`` or
``chromedriver`` they skip with that reason (``.ci/run`` installs both with
apt-get when it runs as root).
"""

import html.parser
import json
import os
import re
import shutil
import threading
import urllib.error
import urllib.parse
import urllib.request
from functools import partial
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import NamedTuple

import pytest
from conftest import ROOT

pytestmark = pytest.mark.slow

SITE = ROOT / "results" / "site"
CHECK = ROOT / "results" / "site-check"
#: Folders of the site that hold assets, not pages (the theme's two HTML macro files live in _static).
ASSET_FOLDERS = ("_static", "_sources", "_images", "_downloads")
#: Seconds a page may take to load and typeset (MathJax on the longest notebook takes about 1 s here).
PAGE_TIMEOUT = 30
#: TeX left as text: $...$ on one line, $$, \( or \[.
RAW_TEX = re.compile(r"\$\$|\$[^\s$][^$\n]*\$|\\\(|\\\[")

# Run in the page after it has loaded: wait for MathJax (when the page loads it),
# scroll through the page (no image is left unloaded below the fold), then report.
INSPECT = r"""
const done = arguments[arguments.length - 1];
const typeset = (window.MathJax && MathJax.startup && MathJax.startup.promise) || Promise.resolve();
typeset.then(async () => {
  for (let y = 0; y < document.body.scrollHeight; y += window.innerHeight) {
    window.scrollTo(0, y);
    await new Promise(r => setTimeout(r, 20));
  }
  window.scrollTo(0, 0);
  const images = Array.from(document.images);
  await Promise.all(images.map(i => i.complete ? null : new Promise(r => { i.onload = i.onerror = r; })));
  const text = document.body.cloneNode(true);
  text.querySelectorAll("pre, code, script, style, textarea, mjx-container").forEach(e => e.remove());
  const math = Array.from(document.querySelectorAll(".math"));
  const code = Array.from(document.querySelectorAll(".bd-article pre"));
  const selection = window.getSelection();
  const copied = code.map(pre => {
    const range = document.createRange();
    range.selectNodeContents(pre);
    selection.removeAllRanges();
    selection.addRange(range);
    return selection.toString();
  });
  selection.removeAllRanges();
  done({
    images: images.map(i => [i.currentSrc || i.src, i.naturalWidth]),
    links: Array.from(document.querySelectorAll("a[href]")).map(a => a.href),
    math: math.length,
    untypeset: math.filter(e => !e.querySelector("mjx-container")).map(e => e.textContent.slice(0, 80)),
    rendered: document.querySelectorAll("mjx-container").length,
    text: text.textContent,
    mathjax: Boolean(window.MathJax && MathJax.startup),
    width: window.innerWidth,
    cells: document.querySelectorAll("div.cell pre").length,
    clipped: code.filter(p => p.scrollWidth > p.clientWidth).map(p => p.textContent.split("\n")[0].slice(0, 60)),
    miscopied: code.filter((p, i) => copied[i] !== p.textContent.replace(/\n$/, "")).map(p => p.textContent.slice(0, 60)),
  });
}).catch(e => done({error: String(e)}));
"""


class Visit(NamedTuple):
    """What the browser recorded on one page."""

    page: str
    console: list[dict]
    requests: list[str]
    failures: list[str]
    report: dict


def site_pages() -> list[str]:
    """Every HTML page of the built site, relative to its root (assets excluded)."""
    pages = (p.relative_to(SITE).as_posix() for p in SITE.rglob("*.html"))
    return sorted(p for p in pages if not p.startswith(ASSET_FOLDERS))


@pytest.fixture(scope="module")
def site() -> Path:
    """The built site, or a skip (a failure in CI) saying how to build it."""
    if not (SITE / "index.html").is_file():
        message = f"{SITE.relative_to(ROOT)} is not built: run `snakemake --cores all site` first"
        if os.environ.get("CI"):
            pytest.fail(message)
        pytest.skip(message)
    return SITE


@pytest.fixture(scope="module")
def server(site):
    """An HTTP server for the site on 127.0.0.1, a free port, in a thread; yields its base URL."""

    class Quiet(SimpleHTTPRequestHandler):
        def log_message(self, *args) -> None:  # the test reads the browser's log, not the server's
            pass

    httpd = ThreadingHTTPServer(("127.0.0.1", 0), partial(Quiet, directory=str(site)))
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}/"
    httpd.shutdown()
    httpd.server_close()


@pytest.fixture(scope="module")
def browser():
    """Headless Chromium with its console and network logged; skipped with the reason when absent."""
    webdriver = pytest.importorskip("selenium.webdriver", reason="selenium is not installed (environment-pip.txt)")
    binary = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_path = shutil.which("chromedriver")
    if binary is None or driver_path is None:
        missing = " and ".join(n for n, p in (("chromium", binary), ("chromedriver", driver_path)) if p is None)
        pytest.skip(f"{missing} not found: `apt-get install chromium chromium-driver` (.ci/run does, as root)")
    options = webdriver.ChromeOptions()
    options.binary_location = binary
    for flag in CHROMIUM_FLAGS:
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL", "performance": "ALL"})
    # An explicit driver path: selenium's driver manager, which could download one, is never consulted.
    driver = webdriver.Chrome(options=options, service=webdriver.ChromeService(executable_path=driver_path))
    driver.set_page_load_timeout(PAGE_TIMEOUT)
    driver.set_script_timeout(PAGE_TIMEOUT)
    yield driver
    driver.quit()


#: Headless, as root in CI (no sandbox), a fixed window, and nothing of Chromium's own traffic:
#: every host but the local server resolves to nothing.
CHROMIUM_FLAGS = (
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-dev-shm-usage",
    "--window-size=1280,900",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-default-apps",
    "--disable-sync",
    "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1",
)


def network(driver) -> tuple[list[str], list[str]]:
    """The URLs the page requested and its failures, from the performance log since the last read."""
    urls, failures, by_id = [], [], {}
    for entry in driver.get_log("performance"):
        message = json.loads(entry["message"])["message"]
        method, params = message["method"], message.get("params", {})
        if method == "Network.requestWillBeSent":
            by_id[params["requestId"]] = params["request"]["url"]
            urls.append(params["request"]["url"])
        elif method == "Network.loadingFailed":
            failures.append(f"{by_id.get(params['requestId'], '?')}: {params.get('errorText')}")
        elif method == "Network.responseReceived" and params["response"]["status"] >= 400:
            failures.append(f"{params['response']['url']}: status {params['response']['status']}")
    return urls, failures


def visit(driver, base: str, page: str) -> Visit:
    """Open ``page``, let it typeset and load its images, save its screenshot; return what was seen."""
    driver.get_log("browser"), driver.get_log("performance")  # drop what an earlier page left
    driver.get(base + page)
    report = driver.execute_async_script(INSPECT)
    CHECK.mkdir(parents=True, exist_ok=True)
    driver.save_screenshot(str(CHECK / (page.removesuffix(".html").replace("/", "__") + ".png")))
    urls, failures = network(driver)
    return Visit(page, driver.get_log("browser"), urls, failures, report)


@pytest.fixture(scope="module")
def visits(site, server, browser) -> dict[str, Visit]:
    """Every page of the site, visited once: page -> what the browser recorded."""
    return {page: visit(browser, server, page) for page in site_pages()}


def test_the_site_has_every_page_the_pipeline_made(site):
    """A page per executed notebook, per figure and per guide page (book/guide/), with the index, article and README."""
    pages = set(site_pages())
    notebooks = {f"tutorial/{p.stem}.html" for p in (ROOT / "results" / "notebooks").glob("*.ipynb")}
    figures = {f"figures/{p.stem}.html" for p in (ROOT / "figures").glob("*.png")}
    guide = {f"guide/{p.stem}.html" for p in (ROOT / "book" / "guide").glob("*.md")}
    assert notebooks and figures and guide
    missing = (notebooks | figures | guide | {"index.html", "article.html", "readme.html", "search.html"}) - pages
    assert missing == set()


def test_the_tutorial_is_listed_in_order(site):
    """The home page links the notebooks in their numbered order."""
    index = (site / "index.html").read_text(encoding="utf-8")
    listed = list(dict.fromkeys(re.findall(r'href="tutorial/(\d\d)_[^"#]+\.html"', index)))
    expected = sorted(p.stem[:2] for p in (ROOT / "results" / "notebooks").glob("*.ipynb"))
    assert listed == expected


def test_no_console_errors(visits):
    """No SEVERE message in the console of any page."""
    errors = {v.page: [e["message"] for e in v.console if e["level"] == "SEVERE"] for v in visits.values()}
    assert {p: e for p, e in errors.items() if e} == {}


def test_no_failed_request_and_none_to_another_host(visits, server):
    """Every request of every page went to the local server and succeeded."""
    outside = {v.page: [u for u in v.requests if not u.startswith((server, "data:"))] for v in visits.values()}
    assert {p: u for p, u in outside.items() if u} == {}
    assert {v.page: v.failures for v in visits.values() if v.failures} == {}
    assert all(v.requests for v in visits.values()), "the performance log recorded no request"


def test_every_image_loaded(visits):
    """Each ``<img>`` of each page has a natural width above 0; the figure pages have one at least."""
    broken = {v.page: [src for src, width in v.report["images"] if width <= 0] for v in visits.values()}
    assert {p: b for p, b in broken.items() if b} == {}
    for page, v in visits.items():
        if page.startswith(("figures/fig", "figures/ext")):
            assert any(src.endswith(".png") for src, _ in v.report["images"]), page


def test_every_internal_link_resolves(visits, server):
    """Each link to the site answers 200; a ``#fragment`` names an element of the page it points to."""
    links = {link for v in visits.values() for link in v.report["links"] if link.startswith(server)}
    assert links
    ids, broken = {}, []
    for link in sorted(links):
        url, _, fragment = link.partition("#")
        if url not in ids:
            ids[url] = fetch_ids(url)
        if ids[url] is None:
            broken.append(f"{link}: not found")
        elif fragment and urllib.parse.unquote(fragment) not in ids[url]:
            broken.append(f"{link}: no element with id {fragment!r}")
    assert broken == []


class _Ids(html.parser.HTMLParser):
    """The ``id`` (and ``name``) attributes of an HTML document."""

    def __init__(self) -> None:
        super().__init__()
        self.ids: set[str] = set()

    def handle_starttag(self, tag, attrs) -> None:
        self.ids.update(value for name, value in attrs if name in ("id", "name") and value)


def fetch_ids(url: str) -> set[str] | None:
    """The ids of the document at ``url`` (empty for a file that is not HTML), None if it is not found."""
    try:
        with urllib.request.urlopen(url, timeout=PAGE_TIMEOUT) as response:
            body, kind = response.read(), response.headers.get_content_type()
    except urllib.error.HTTPError:
        return None
    if kind != "text/html":
        return set()
    parser = _Ids()
    parser.feed(body.decode("utf-8"))
    return parser.ids


def test_mathematics_is_rendered(visits):
    """Every math element holds MathJax's output, no TeX is left as text, and the notebooks carry math."""
    errors = {v.page: v.report["error"] for v in visits.values() if "error" in v.report}
    assert errors == {}
    untypeset = {v.page: v.report["untypeset"] for v in visits.values() if v.report["untypeset"]}
    assert untypeset == {}
    raw = {v.page: RAW_TEX.findall(v.report["text"]) for v in visits.values()}
    assert {p: r for p, r in raw.items() if r} == {}
    for page in ("tutorial/01_governing_equations.html", "tutorial/02_sgn_zero_failure.html"):
        assert visits[page].report["mathjax"], f"{page}: MathJax did not load"
        assert visits[page].report["rendered"] >= visits[page].report["math"] > 0, page


def test_no_code_is_clipped_at_1280_px(visits):
    """No ``pre`` of any page (notebook cells, input and output, and the other pages' code) overflows its box.

    A ``pre`` whose text is wider than its box (``scrollWidth > clientWidth``)
    is clipped and scrolls sideways; at 1280 px the notebooks' cells had 220
    such blocks before book/_static/code.css wrapped long lines.
    """
    assert {v.report["width"] for v in visits.values()} == {1280}
    notebooks = [v for page, v in visits.items() if page.startswith("tutorial/")]
    assert notebooks and all(v.report["cells"] > 0 for v in notebooks), "no code cell found on a notebook page"
    clipped = {v.page: v.report["clipped"] for v in visits.values() if v.report["clipped"]}
    print(f"pre clipped at 1280 px: {sum(map(len, clipped.values()))} on {len(clipped)} pages")
    assert clipped == {}


def test_code_copies_as_written(visits):
    """Selecting a whole ``pre`` gives its text as written: the wrapping adds no line break and drops none."""
    assert {v.page: v.report["miscopied"] for v in visits.values() if v.report["miscopied"]} == {}


#: A control that searches: the sidebar's field and the header's icon (buttons that open the
#: search dialog), or a search form in the page (the search page's own).
SEARCH_CONTROLS = """
return Array.from(document.querySelectorAll(".search-button__button, form.bd-search"))
  .filter(e => e.checkVisibility({checkOpacity: true, checkVisibilityCSS: true}))
  .filter(e => { const r = e.getBoundingClientRect(); return r.width > 0 && r.height > 0 && r.right > 0 && r.left < innerWidth; })
  .map(e => e.matches("form") ? "form" : e.closest(".bd-sidebar-primary") ? "sidebar field" : "header icon");
"""


@pytest.mark.parametrize("width", [1280, 600])
@pytest.mark.parametrize("page", ["index.html", "tutorial/01_governing_equations.html", "search.html?q=spring"])
def test_one_way_to_search(browser, server, page, width):
    """Each page shows exactly one search control at a wide and at a narrow window (a screenshot of each is saved)."""
    size = browser.get_window_size()
    try:
        browser.set_window_size(width, size["height"])
        browser.get(server + page)
        assert browser.execute_script("return window.innerWidth") == width
        controls = browser.execute_script(SEARCH_CONTROLS)
        CHECK.mkdir(parents=True, exist_ok=True)
        name = page.partition(".html")[0].replace("/", "__")
        browser.save_screenshot(str(CHECK / f"search_controls_{width}px_{name}.png"))
    finally:
        browser.set_window_size(size["width"], size["height"])
    print(f"{page} at {width} px: {controls}")
    assert len(controls) == 1, controls


def test_search_finds_algorithm_1(browser, server):
    """The search page, asked for "Algorithm 1", lists notebook 01 (which states Algorithm 1), math typeset.

    The results arrive after MathJax has typeset the page; the site's
    search-math.js typesets them in turn, so the listing (notebook 02's title
    has a formula) must end with no TeX left as text.
    """
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    browser.get(server + "search.html?q=" + urllib.parse.quote("Algorithm 1"))
    wait = WebDriverWait(browser, PAGE_TIMEOUT)
    wait.until(lambda d: "Search finished" in d.find_element(By.CSS_SELECTOR, "#search-results .search-summary").text)
    hrefs = [a.get_attribute("href") for a in browser.find_elements(By.CSS_SELECTOR, "#search-results ul.search a")]
    assert any(h.endswith("tutorial/01_governing_equations.html") for h in hrefs), hrefs
    assert "Algorithm 1" in browser.find_element(By.ID, "search-results").text
    try:  # MathJax typesets the results a moment after the last one is shown
        wait.until(lambda d: not RAW_TEX.search(results_text(d)) and d.find_elements(By.CSS_SELECTOR, "mjx-container"))
    finally:
        CHECK.mkdir(parents=True, exist_ok=True)
        browser.save_screenshot(str(CHECK / "search_Algorithm_1.png"))
    assert RAW_TEX.findall(results_text(browser)) == []


def results_text(driver) -> str:
    """The text of the search results, MathJax's output left out."""
    return driver.execute_script(
        "const r = document.getElementById('search-results').cloneNode(true);"
        "r.querySelectorAll('mjx-container').forEach(e => e.remove());"
        "return r.textContent;"
    )


def test_a_screenshot_of_every_page(visits):
    """``results/site-check/<page>.png`` exists for every page, a PNG of the browser's window."""
    shots = {page: CHECK / (page.removesuffix(".html").replace("/", "__") + ".png") for page in visits}
    assert [p for p, shot in shots.items() if not shot.read_bytes().startswith(b"\x89PNG")] == []
