"""The explorer as a web page (issue 18): Voila serves notebooks/00_explorer.ipynb on a free
loopback port, Debian's headless Chromium opens it through selenium, the elevation slider is
moved from the keyboard as a reader would, and the trajectories' plot and the summary's numbers
must both change. A screenshot goes to $HARP_ANALYSIS_SCREENSHOT_DIR, else to tmp_path.

Skipped when Debian's chromium or chromium-driver is missing, unless
HARP_ANALYSIS_REQUIRE_BROWSER=1 (CI, `make check-browser`), which makes that a failure."""

import os
import re
import socket
import subprocess
import sys
import time
from pathlib import Path
from typing import NamedTuple

import pytest
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support.ui import WebDriverWait

CHECKOUT = Path(__file__).resolve().parents[2]
NOTEBOOK = CHECKOUT / "notebooks" / "00_explorer.ipynb"
CHROMIUM = Path("/usr/bin/chromium")
CHROMEDRIVER = Path("/usr/bin/chromedriver")

# Bounds on waiting, never asserted times: a fresh kernel imports the package and loads the
# engines' cached kernels before the explorer first draws; `make test` shares two cores.
SERVER_START_S = 60.0
FIRST_DRAW_S = 120.0
REDRAW_S = 60.0
ARROW_PRESSES = 4

NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?")

# The dask cluster's tests start worker processes; the page is not loaded beside them.
pytestmark = [pytest.mark.browser, pytest.mark.xdist_group("dask_cluster")]


@pytest.fixture
def browser_installed():
    missing = [str(path) for path in (CHROMIUM, CHROMEDRIVER) if not path.is_file()]
    if missing:
        reason = (
            f"needs Debian's chromium and chromium-driver; missing {', '.join(missing)} "
            "(apt-get install chromium chromium-driver)"
        )
        if os.environ.get("HARP_ANALYSIS_REQUIRE_BROWSER") == "1":
            pytest.fail(f"{reason}, and HARP_ANALYSIS_REQUIRE_BROWSER=1 forbids skipping")
        pytest.skip(reason)


def free_loopback_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def wait_until_listening(port: int, server: subprocess.Popen, log: Path) -> None:
    deadline = time.monotonic() + SERVER_START_S
    while time.monotonic() < deadline:
        if server.poll() is not None:
            pytest.fail(f"voila exited with {server.returncode}:\n{log.read_text()}")
        try:
            socket.create_connection(("127.0.0.1", port), timeout=1.0).close()
            return
        except OSError:
            time.sleep(0.2)
    pytest.fail(
        f"voila did not listen on port {port} within {SERVER_START_S} s:\n{log.read_text()}"
    )


@pytest.fixture
def explorer_url(browser_installed, tmp_path):
    port = free_loopback_port()
    log = tmp_path / "voila.log"
    command = [
        sys.executable, "-m", "voila", str(NOTEBOOK), "--no-browser", f"--port={port}",
        "--Voila.ip=127.0.0.1", "--Voila.port_retries=0",
        "--VoilaConfiguration.show_tracebacks=True",
    ]  # fmt: skip
    environment = {**os.environ, "JUPYTER_RUNTIME_DIR": str(tmp_path / "runtime")}
    with log.open("w") as output:
        server = subprocess.Popen(
            command, cwd=CHECKOUT, env=environment, stdout=output, stderr=subprocess.STDOUT
        )
    try:
        wait_until_listening(port, server, log)
        yield f"http://127.0.0.1:{port}/"
    finally:
        server.terminate()  # voila shuts its kernel down on SIGTERM
        try:
            server.wait(timeout=20)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()


@pytest.fixture
def browser(browser_installed):
    options = webdriver.ChromeOptions()
    options.binary_location = str(CHROMIUM)
    for argument in (
        "--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1400,1000",
        # only loopback traffic: no name resolves, and no background fetches are started
        "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1",
        "--disable-background-networking", "--disable-component-update", "--no-first-run",
        "--disable-default-apps",
    ):  # fmt: skip
        options.add_argument(argument)
    driver = webdriver.Chrome(service=Service(str(CHROMEDRIVER)), options=options)
    driver.set_page_load_timeout(FIRST_DRAW_S)
    try:
        yield driver
    finally:
        driver.quit()


# The page's text if it shows a traceback, else the plot's image source and the summary table,
# read in one step: the HTML widget replaces its table on every redraw, so elements found one
# call earlier may be gone by the next.
READ_PAGE = """
const text = document.body.innerText;
if (text.includes("Traceback")) return {traceback: text};
const plot = document.querySelector("img.harp-plot, .harp-plot img");
const table = document.querySelector(".harp-summary table");
if (!plot || !plot.src || !table) return null;
const texts = cells => [...cells].map(cell => cell.textContent.trim());
return {plot: plot.src, header: texts(table.querySelectorAll("th")),
        rows: [...table.rows].filter(row => row.querySelector("td")).map(row => texts(row.cells))};
"""


class Shown(NamedTuple):
    plot_source: str
    apogee_km: dict[str, float]  # by engine, from the summary's "apogee" column
    numbers: tuple[float, ...]  # every number in the summary


def shown(driver) -> Shown | None:
    """What the explorer shows, once it has drawn a plot and a summary with numbers."""
    page = driver.execute_script(READ_PAGE)
    if page is None:
        return None
    assert "traceback" not in page, f"the page shows a traceback:\n{page.get('traceback')}"
    apogee = [i for i, name in enumerate(page["header"]) if name.startswith("apogee")]
    assert apogee, f"the summary has no apogee column: {page['header']}"
    rows = page["rows"]
    flown = [row for row in rows if all(NUMBER.fullmatch(cell) for cell in row[1:])]
    numbers = tuple(float(cell) for row in rows for cell in row[1:] if NUMBER.fullmatch(cell))
    if not flown:
        return None
    return Shown(page["plot"], {row[0]: float(row[apogee[0]]) for row in flown}, numbers)


def redrawn(driver, before: Shown) -> Shown:
    """What the page shows once its plot and its numbers both differ from `before`."""

    def changed(driver):
        now = shown(driver)
        moved = now and now.plot_source != before.plot_source and now.numbers != before.numbers
        return now if moved else False

    return WebDriverWait(driver, REDRAW_S, poll_frequency=0.2).until(
        changed, message=f"the plot and the numbers did not both change from {before.numbers}"
    )


def screenshot_path(tmp_path: Path) -> Path:
    folder = Path(os.environ.get("HARP_ANALYSIS_SCREENSHOT_DIR") or tmp_path)
    folder.mkdir(parents=True, exist_ok=True)
    return folder / "explorer.png"


def test_moving_the_elevation_slider_redraws_the_plot_and_the_numbers(
    explorer_url, browser, tmp_path
):
    browser.get(explorer_url)
    first = WebDriverWait(browser, FIRST_DRAW_S, poll_frequency=0.5).until(
        shown, message="the explorer drew no plot and no summary numbers"
    )
    assert browser.find_elements(By.CSS_SELECTOR, ".harp-explorer .harp-messages")
    assert {"MKS", "3DOF"} <= first.apogee_km.keys()

    # The slider's handle takes the keyboard focus; each arrow key moves it one step and the
    # explorer flies the launch again. Each redraw is awaited before the next key, so the last
    # one seen is the final elevation's.
    handle = browser.find_element(By.CSS_SELECTOR, ".harp-elevation .noUi-handle")
    start_deg = float(handle.get_attribute("aria-valuenow"))
    room_above = float(handle.get_attribute("aria-valuemax")) - start_deg
    room_below = start_deg - float(handle.get_attribute("aria-valuemin"))
    raise_it = room_above >= room_below
    now = first
    for _ in range(ARROW_PRESSES):
        handle.send_keys(Keys.ARROW_RIGHT if raise_it else Keys.ARROW_LEFT)
        now = redrawn(browser, now)
    end_deg = float(handle.get_attribute("aria-valuenow"))
    assert (end_deg > start_deg) if raise_it else (end_deg < start_deg)

    # Below the vertical a steeper gun climbs higher, in every engine, with or without drag.
    for engine, apogee_km in first.apogee_km.items():
        rose = now.apogee_km[engine] > apogee_km
        assert rose == raise_it, (engine, apogee_km, now.apogee_km[engine], start_deg, end_deg)

    path = screenshot_path(tmp_path)
    assert browser.save_screenshot(str(path))
    print(f"explorer screenshot: {path}")
