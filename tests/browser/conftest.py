"""The browser tests serve the explorer with Voila on a free loopback port, with the settings
of `make explore` (serve/voila.py), and open it in Debian's headless Chromium.

The load test (marked ``load``) is left out unless HARP_ANALYSIS_EXPLORER_LOAD=1, as
`make check-browser` sets: it takes about a minute, beyond `make test`'s budget. The
documentation site's test (marked ``docs``) is left out unless HARP_ANALYSIS_DOCS_SITE names a
built site, as `make check-docs` sets after building it."""

import os
import socket
import subprocess
import sys
import time
from contextlib import contextmanager
from pathlib import Path

import pytest
from selenium import webdriver
from selenium.webdriver.chrome.service import Service

CHECKOUT = Path(__file__).resolve().parents[2]
NOTEBOOK = CHECKOUT / "notebooks" / "00_explorer.ipynb"
CHROMIUM = Path("/usr/bin/chromium")
CHROMEDRIVER = Path("/usr/bin/chromedriver")

# Bounds on waiting, never asserted times: a fresh kernel imports the package and loads the
# engines' cached kernels before the explorer first draws; `make test` shares two cores.
SERVER_START_S = 60.0
FIRST_DRAW_S = 120.0


def pytest_configure(config):
    config.addinivalue_line(
        "markers",
        "browser: drives Debian's chromium through chromium-driver (skipped when they are "
        "missing, unless HARP_ANALYSIS_REQUIRE_BROWSER=1)",
    )
    config.addinivalue_line(
        "markers", "load: the served explorer under load (HARP_ANALYSIS_EXPLORER_LOAD=1 only)"
    )
    config.addinivalue_line(
        "markers", "docs: the built documentation site (HARP_ANALYSIS_DOCS_SITE set only)"
    )


def pytest_collection_modifyitems(config, items):
    left_out = []
    if os.environ.get("HARP_ANALYSIS_EXPLORER_LOAD") != "1":
        left_out += [item for item in items if item.get_closest_marker("load")]
    if not os.environ.get("HARP_ANALYSIS_DOCS_SITE"):
        left_out += [item for item in items if item.get_closest_marker("docs")]
    if left_out:
        config.hook.pytest_deselected(items=left_out)
        items[:] = [item for item in items if item not in left_out]


def require_browser() -> None:
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


def _wait_until_listening(port: int, server: subprocess.Popen, log: Path) -> None:
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


@contextmanager
def served_explorer(folder: Path, *settings: str, environment: dict | None = None):
    """Voila serving the explorer as `make explore` does (plus ``settings``) on a free
    loopback port: yields its URL and its process."""
    port = free_loopback_port()
    log = folder / "voila.log"
    command = [
        sys.executable, "-m", "voila", str(NOTEBOOK), "--no-browser", f"--port={port}",
        "--Voila.ip=127.0.0.1", "--Voila.port_retries=0", "--Voila.config_file_paths=serve",
        *settings,
    ]  # fmt: skip
    environment = {
        **os.environ,
        "JUPYTER_RUNTIME_DIR": str(folder / "runtime"),
        **(environment or {}),
    }
    with log.open("w") as output:
        server = subprocess.Popen(
            command, cwd=CHECKOUT, env=environment, stdout=output, stderr=subprocess.STDOUT
        )
    try:
        _wait_until_listening(port, server, log)
        yield f"http://127.0.0.1:{port}/", server
    finally:
        server.terminate()  # voila shuts its kernels down on SIGTERM
        try:
            server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()


@contextmanager
def headless_chromium():
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


@pytest.fixture(scope="session")
def browser_installed():
    require_browser()


@pytest.fixture(scope="session")
def serve_explorer():
    """:func:`served_explorer`, for fixtures that serve the explorer with settings of their own."""
    return served_explorer


@pytest.fixture(scope="module")
def browser(browser_installed):
    with headless_chromium() as driver:
        yield driver
