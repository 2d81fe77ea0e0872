"""The documentation site in a browser (issue 28): the built site (`make docs`) is served on a
free loopback port and Debian's headless Chromium opens it through selenium, as a reader would.
From the landing page it follows the gallery to a dissertation figure's page, from there a
ledger row about the figure, and from the row the API entry of the function that computes it,
whose docstring cites the dissertation's equation; it checks that the figure and the other
images render, that the ledger filters and sorts, that the search finds a function, that the
site reports the package's version and that MathJax, served by the site itself, typesets.

In the 1400 px window (issue 34) it checks what a reader sees: every ledger row's explanation
within the window's width, beneath its row, after filtering and sorting too; no chapter showing
an object's repr, a path of the build machine or a raw warning (a validity warning is a
sentence); a figure's page showing the figure at the page's width, linked to its full size,
with the text's caption; the gallery's thumbnail and coloured status badge of each figure;
the navigation and the API pages' headings never breaking a module's name mid-word; and
Parameters and Returns on the public entry points. A screenshot of each step goes to
$HARP_ANALYSIS_SCREENSHOT_DIR, else to the test's temporary folder.

Runs only where HARP_ANALYSIS_DOCS_SITE names the built site (`make check-docs` sets it after
building); skipped without chromium and chromium-driver unless HARP_ANALYSIS_REQUIRE_BROWSER=1,
which makes that a failure."""

import functools
import http.server
import inspect
import os
import re
import threading
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select, WebDriverWait

import harp_analysis
from harp_analysis.foundation import paths
from harp_analysis.reporting import ledger, registry, site
from harp_analysis.reporting.site import CHAPTER_NOTEBOOKS, EXPLORER_NOTEBOOK

pytestmark = [pytest.mark.browser, pytest.mark.docs]

WAIT_S = 30.0  # a bound on waiting for a page, never an asserted time
#: "eq 3.30", "eqs 4.4-4.7", "(eq 6.4)": how the docstrings cite the dissertation's equations
EQUATION = re.compile(r"\beqs?\.? ?\d+\.\d+")


@pytest.fixture(scope="module")
def built_site() -> Path:
    folder = os.environ.get("HARP_ANALYSIS_DOCS_SITE")
    if not folder:
        pytest.skip("no built site: HARP_ANALYSIS_DOCS_SITE is unset (make check-docs sets it)")
    site = Path(folder)
    assert (site / "index.html").is_file(), f"{site} holds no built site: run make docs"
    return site


@pytest.fixture(scope="module")
def served(built_site):
    """The built site over HTTP on a free loopback port, as a static host would serve it."""

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    handler = functools.partial(Quiet, directory=str(built_site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()


@pytest.fixture()
def shoot(tmp_path):
    folder = Path(os.environ.get("HARP_ANALYSIS_SCREENSHOT_DIR") or tmp_path)
    folder.mkdir(parents=True, exist_ok=True)

    def take(driver, name: str) -> None:
        path = folder / f"docs-{name}.png"
        assert driver.save_screenshot(str(path))
        print(f"docs screenshot: {path}")

    return take


def wait(driver, condition, message: str):
    return WebDriverWait(driver, WAIT_S, poll_frequency=0.2).until(condition, message=message)


def click(driver, element) -> None:
    """Click ``element`` as a reader would, once it is scrolled clear of the sticky header."""
    driver.execute_script(
        "arguments[0].scrollIntoView({block: 'center', inline: 'center'});", element
    )
    element.click()


def images_rendered(driver) -> list[str]:
    """The sources of the page's images that did not render (none loaded, or empty)."""
    return driver.execute_script(
        "return [...document.querySelectorAll('article img, main img')]"
        ".filter(img => !(img.complete && img.naturalWidth > 0)).map(img => img.src);"
    )


def the_figure_and_its_row():
    """A drawn figure of the dissertation and a ledger row about it whose function's docstring
    cites an equation: the reader's path the test follows, chosen from the registry and the
    ledger themselves."""
    claims = ledger.load_claims()
    for entry in registry.load_registry():
        if entry.extension or entry.status not in registry.DRAWN or not entry.file.endswith("png"):
            continue
        for claim in claims:
            if entry.number not in claim.figures:
                continue
            module, _, function = claim.compute.partition(":")
            doc = inspect.getdoc(getattr(__import__(module, fromlist=[function]), function)) or ""
            if EQUATION.search(doc):
                return entry, claim
    pytest.fail("no drawn figure has a ledger row whose function cites an equation")


def test_a_reader_goes_from_a_figure_to_its_rows_the_function_and_its_equation(
    browser_installed, browser, served, shoot
):
    entry, claim = the_figure_and_its_row()
    module, _, function = claim.compute.partition(":")

    browser.get(served)
    wait(browser, lambda d: d.find_elements(By.CSS_SELECTOR, ".navbar-brand"), "no landing page")
    brand = browser.find_element(By.CSS_SELECTOR, ".navbar-brand").text
    assert harp_analysis.__version__ in brand, brand  # the site's version is the package's
    assert images_rendered(browser) == []

    # the gallery, then the figure's page
    click(browser, browser.find_element(By.XPATH, "//nav//a[normalize-space()='Gallery']"))
    wait(browser, lambda d: "gallery" in d.current_url, "the Gallery link led nowhere")
    click(
        browser, browser.find_element(By.XPATH, f"//article//a[normalize-space()='{entry.label}']")
    )
    wait(browser, lambda d: d.find_elements(By.CSS_SELECTOR, ".figure-pair"), "no figure page")
    page = browser.find_element(By.TAG_NAME, "article").text
    assert " ".join(entry.title.split()) in " ".join(page.split())  # the text's caption
    wait(browser, lambda d: not images_rendered(d), "the figure did not render")
    figure = browser.find_element(By.CSS_SELECTOR, ".project-side img")
    assert entry.file in figure.get_attribute("src")
    assert f"make figures FIG={entry.number}" in page
    shoot(browser, "figure")

    # the row about it: its verdict on the figure page, then its line of the ledger
    row_link = browser.find_element(By.XPATH, f"//table//a[normalize-space()='{claim.id}']")
    figure_row = row_link.find_element(By.XPATH, "./ancestor::tr")
    assert claim.verdict in figure_row.text
    click(browser, row_link)
    wait(browser, lambda d: d.find_elements(By.CSS_SELECTOR, "tr.ledger-target"), "no row shown")
    target = browser.find_element(By.CSS_SELECTOR, "tr.ledger-target")
    assert claim.id in target.text and claim.verdict in target.text
    assert target.is_displayed()
    shoot(browser, "ledger-row")

    # the function that computes it, and the equation its docstring cites
    click(browser, target.find_element(By.XPATH, f".//a[normalize-space()='{function}']"))
    anchor = f"{module}.{function}"
    wait(browser, lambda d: unquote(urlsplit(d.current_url).fragment) == anchor, "no API entry")
    entry_text = browser.execute_script(
        "const dt = document.getElementById(arguments[0]); "
        "return dt ? dt.parentElement.innerText : null;",
        anchor,
    )
    assert entry_text and function in entry_text, anchor
    assert EQUATION.search(entry_text), f"{anchor}'s entry cites no equation:\n{entry_text}"
    shoot(browser, "api-entry")


@pytest.mark.parametrize(
    ("module", "function"),
    [
        ("harp_analysis.engines.threedof", "simulate_3dof"),
        ("harp_analysis.engines.mks", "for_launch"),
    ],
)
def test_the_public_entry_points_show_parameters_and_returns(
    browser_installed, browser, served, module, function
):
    browser.get(served + f"api/{module}.html")
    text = browser.execute_script(
        "return document.getElementById(arguments[0]).parentElement.innerText;",
        f"{module}.{function}",
    )
    assert "Parameters" in text and "Returns" in text and "launch" in text


def test_the_ledger_filters_by_chapter_and_verdict_and_sorts(browser_installed, browser, served):
    claims = ledger.load_claims()
    browser.get(served + "ledger.html")
    count = wait(browser, lambda d: d.find_element(By.ID, "ledger-count"), "no ledger controls")
    assert count.text == f"{len(claims)} of {len(claims)} rows"

    Select(browser.find_element(By.ID, "ledger-filter-verdict")).select_by_value("close")
    expected = sum(claim.verdict == "close" for claim in claims)
    assert count.text == f"{expected} of {len(claims)} rows"
    shown = visible_rows(browser)
    assert len(shown) == expected and all(row[8] == "close" for row in shown)

    Select(browser.find_element(By.ID, "ledger-filter-chapter")).select_by_value("Chapter 4")
    shown = visible_rows(browser)
    assert shown and all(row[1] == "Chapter 4" and row[8] == "close" for row in shown)

    Select(browser.find_element(By.ID, "ledger-filter-verdict")).select_by_value("")
    Select(browser.find_element(By.ID, "ledger-filter-chapter")).select_by_value("")
    assert len(visible_rows(browser)) == len(claims)
    computed = browser.find_element(
        By.XPATH, "//table[contains(@class,'ledger-table')]//th[normalize-space()='computed']"
    )
    click(browser, computed)  # numbers sort as numbers: 1e-05 before 0.1 before 10
    values = [leading_number(row[5]) for row in visible_rows(browser)]
    assert values == sorted(values), values[:20]
    click(browser, computed)
    assert [leading_number(row[5]) for row in visible_rows(browser)] == values[::-1]


def leading_number(text: str) -> float:
    found = re.match(r"[<>]?\s*([-+]?\d*\.?\d+(?:e[-+]?\d+)?)", text, re.I)
    return float(found.group(1)) if found else float("inf")


def visible_rows(driver) -> list[list[str]]:
    """The cells of the ledger's rows shown, each without the explanation beneath it."""
    return driver.execute_script(
        "return [...document.querySelectorAll('table.ledger-table tbody tr')]"
        ".filter(row => !row.hidden && !row.classList.contains('ledger-explanation'))"
        ".map(row => [...row.cells].map(cell => cell.textContent.trim()));"
    )


def test_the_search_finds_a_function(browser_installed, browser, served):
    browser.get(served + "search.html?q=simulate_3dof")
    wanted = "harp_analysis.engines.threedof.simulate_3dof"
    wait(
        browser,
        lambda d: any(
            wanted in (a.get_attribute("href") or "")
            for a in d.find_elements(By.CSS_SELECTOR, "#search-results a")
        ),
        "the search found no simulate_3dof",
    )


def test_the_chapters_render_their_figures_and_math(browser_installed, browser, served, shoot):
    browser.get(served + "chapters/03_modified_kepler.html")
    wait(browser, lambda d: d.find_elements(By.TAG_NAME, "article"), "no chapter page")
    outputs = browser.find_elements(By.CSS_SELECTOR, "article .cell_output img")
    if os.environ.get("HARP_ANALYSIS_DOCS_EXECUTE") != "0":
        assert outputs, "the chapter shows no figure: were its notebooks run?"
    wait(browser, lambda d: not images_rendered(d), "an image of the chapter did not render")
    if browser.find_elements(By.CSS_SELECTOR, "article .math"):
        wait(
            browser,
            lambda d: d.find_elements(By.CSS_SELECTOR, "mjx-container"),
            "MathJax typeset nothing (it must be served by the site itself)",
        )
    browser.get(served + "explorer.html")
    wait(browser, lambda d: not images_rendered(d), "the explorer's screenshot did not render")
    assert browser.find_elements(By.CSS_SELECTOR, "article img")
    shoot(browser, "explorer-page")


# --- the site at 1400 px (issue 34) -------------------------------------------------------------


def test_the_ledger_shows_every_row_s_explanation_in_the_window(
    browser_installed, browser, served, shoot
):
    """Each row's explanation, the reason behind its verdict, lies within the window's width,
    beneath its row, and stays with it when the rows are filtered and sorted; nothing on the
    page scrolls sideways."""
    claims = ledger.load_claims()
    browser.get(served + "ledger.html")
    wait(browser, lambda d: d.find_elements(By.ID, "ledger-count"), "no ledger controls")
    assert browser.execute_script("return window.innerWidth") == 1400

    def explanations() -> list[dict]:
        return browser.execute_script(
            "const width = document.documentElement.clientWidth;"
            "return [...document.querySelectorAll('table.ledger-table tbody tr')]"
            ".filter(row => !row.hidden && !row.classList.contains('ledger-explanation'))"
            ".map(row => { const below = row.nextElementSibling;"
            "  const cell = below && below.classList.contains('ledger-explanation')"
            "    && !below.hidden ? below.cells[0] : null;"
            "  const box = cell ? cell.getBoundingClientRect() : null;"
            "  return {id: row.cells[0].textContent.trim(), text: cell ? cell.innerText : '',"
            "    inside: !!box && box.left >= 0 && box.right <= width && box.width > width / 2};"
            "});"
        )

    shown = explanations()
    assert len(shown) == len(claims)
    assert [row["id"] for row in shown if not row["inside"]] == []
    explained = {claim.id for claim in claims if claim.verdict in ("close", "does not reproduce")}
    assert all(row["text"].strip() for row in shown if row["id"] in explained)
    sideways = browser.execute_script(
        "const box = document.querySelector('table.ledger-table')"
        ".closest('.pst-scrollable-table-container');"
        "return [document.documentElement.scrollWidth - document.documentElement.clientWidth,"
        " box.scrollWidth - box.clientWidth];"
    )
    assert sideways == [0, 0]
    first = browser.find_element(By.CSS_SELECTOR, "tr.ledger-explanation")
    click(browser, first)
    shoot(browser, "ledger-explanations")

    Select(browser.find_element(By.ID, "ledger-filter-verdict")).select_by_value("close")
    click(browser, browser.find_element(By.XPATH, "//th[normalize-space()='computed']"))
    after = explanations()
    assert len(after) == sum(claim.verdict == "close" for claim in claims)
    assert all(row["inside"] and row["text"].strip() for row in after)
    before = {row["id"]: row["text"] for row in shown}
    assert all(before[row["id"]] == row["text"] for row in after)  # each with its own row


#: Text of the machine a notebook ran on, or of Python's raw display of a warning or an object.
MACHINE_TEXT = re.compile(
    rf"PosixPath\(|{re.escape(str(paths.ROOT))}|/work/|/tmp/|Warning:|Traceback|\.py:\d+"
)


def test_the_chapters_show_no_paths_reprs_or_raw_warnings(browser_installed, browser, served):
    """A figure saved shows the figure, never the path it was saved to; a validity warning is
    a sentence, never the build machine's file and line (notebook 03 gives two)."""
    for notebook in sorted(paths.NOTEBOOKS_DIR.glob(CHAPTER_NOTEBOOKS)):
        if notebook.name == EXPLORER_NOTEBOOK:
            continue
        browser.get(served + f"chapters/{notebook.stem}.html")
        text = wait(browser, lambda d: d.find_element(By.TAG_NAME, "article"), "no page").text
        assert not MACHINE_TEXT.findall(text), (notebook.name, MACHINE_TEXT.findall(text))
        if notebook.name.startswith("03") and os.environ.get("HARP_ANALYSIS_DOCS_EXECUTE") != "0":
            said = [e.text for e in browser.find_elements(By.CSS_SELECTOR, ".output.stderr")]
            assert said and all(line.startswith("Model validity: ") for line in said), said
            assert all(
                e.size["width"] > 300
                for e in browser.find_elements(By.CSS_SELECTOR, ".output.stderr pre")
            )


def test_a_figure_page_shows_the_figure_at_the_page_s_width_and_the_text_s_caption(
    browser_installed, browser, served, shoot
):
    entry, _ = the_figure_and_its_row()
    browser.get(served + f"gallery/{site._slug(entry.number)}.html")
    wait(browser, lambda d: not images_rendered(d), "the figure did not render")
    measured = browser.execute_script(
        "const img = document.querySelector('.project-side img');"
        "const article = document.querySelector('article');"
        "const style = getComputedStyle(article);"
        "const content = article.clientWidth - parseFloat(style.paddingLeft)"
        "  - parseFloat(style.paddingRight);"
        "const caption = document.querySelector('.text-caption');"
        "return {image: img.getBoundingClientRect().width, content: content,"
        "  natural: img.naturalWidth, caption: caption.getBoundingClientRect().width,"
        "  font: parseFloat(getComputedStyle(caption).fontSize)};"
    )
    assert measured["content"] > 800, measured  # no contents column beside it at 1400 px
    assert measured["image"] >= 0.95 * measured["content"], measured
    assert measured["caption"] >= 0.5 * measured["content"] and measured["font"] >= 14, measured
    full_size = browser.find_element(By.CSS_SELECTOR, ".project-side a:has(> img)")
    assert unquote(full_size.get_attribute("href")).endswith(entry.file)
    shoot(browser, "figure-page")
    click(browser, full_size)
    width = browser.execute_script("return document.images[0].naturalWidth")
    assert width == measured["natural"] > measured["image"]


def test_the_gallery_shows_a_thumbnail_and_a_status_badge_of_each_figure(
    browser_installed, browser, served, shoot
):
    browser.get(served + "gallery/index.html")
    wait(browser, lambda d: not images_rendered(d), "a thumbnail did not render")
    rows = browser.execute_script(
        "return [...document.querySelectorAll('table.gallery-table tbody tr')].map(row => {"
        "  const img = row.querySelector('img'), badge = row.querySelector('.status-badge');"
        "  return {label: row.cells[0].innerText.trim().split('\\n').pop(),"
        "    img: img ? {src: img.src, natural: img.naturalWidth, shown: img.width,"
        "      link: img.closest('a') ? img.closest('a').href : null} : null,"
        "    badge: badge ? badge.innerText.trim() : null,"
        "    colour: badge ? getComputedStyle(badge).borderTopColor : null};"
        "});"
    )
    plain = browser.execute_script(  # a badge's colour without a status
        "const span = document.createElement('span'); span.className = 'status-badge';"
        "document.body.append(span); const colour = getComputedStyle(span).borderTopColor;"
        "span.remove(); return colour;"
    )
    by_label = {row["label"]: row for row in rows}
    entries = list(registry.load_registry())
    assert len(rows) == len(entries)
    colours = {}
    for entry in entries:
        row = by_label[entry.label]
        assert row["badge"] == site.SHOWN[entry.status], row
        colours.setdefault(entry.status, set()).add(row["colour"])
        if entry.status in registry.DRAWN and entry.file.endswith(".png"):
            image = row["img"]
            assert image and 0 < image["shown"] <= image["natural"], row
            assert image["natural"] == site.THUMBNAIL_WIDTH_PX, row  # a small copy, not 300 dpi
            assert image["link"].endswith(f"{site._slug(entry.number)}.html"), row
    assert all(len(found) == 1 for found in colours.values())  # one colour per status
    distinct = {colour for found in colours.values() for colour in found}
    assert len(distinct) == len(colours) and plain not in distinct, (colours, plain)
    shoot(browser, "gallery")


def test_the_navigation_never_breaks_a_name_mid_word(browser_installed, browser, served, shoot):
    """An API page of a deep module: each entry of the navigation on one line, and the
    heading's dotted name broken only after a dot."""
    module = "harp_analysis.reporting.figures.reference_trajectories"
    browser.get(served + f"api/{module}.html")
    wait(browser, lambda d: d.find_elements(By.CSS_SELECTOR, "nav.bd-docs-nav a"), "no navigation")
    lines = browser.execute_script(
        "const lines = node => { const range = document.createRange();"
        "  range.selectNodeContents(node);"
        "  return new Set([...range.getClientRects()].map(r => Math.round(r.top))).size; };"
        "const texts = element => { const walk = document.createTreeWalker(element, 4);"
        "  const found = []; while (walk.nextNode()) if (walk.currentNode.textContent.trim())"
        "  found.push(walk.currentNode); return found; };"
        "const heading = document.querySelector('article h1');"
        "return {nav: [...document.querySelectorAll('nav.bd-docs-nav a')]"
        "    .filter(a => a.offsetParent && !/\\s/.test(a.textContent.trim()))"
        "    .map(a => [a.textContent.trim(), lines(a)]),"
        "  heading: heading.textContent.replace('#', '').trim(),"
        "  overflow: heading.scrollWidth - heading.clientWidth,"
        "  parts: texts(heading).map(node => [node.textContent, lines(node)])};"
    )
    assert len(lines["nav"]) > 10
    assert [name for name, count in lines["nav"] if count != 1] == []
    assert lines["heading"] == module and lines["overflow"] <= 0
    assert [part for part, count in lines["parts"] if count != 1] == []
    shoot(browser, "api-navigation")
