"""The browser tests open the explorer's web page in Debian's headless Chromium."""


def pytest_configure(config):
    config.addinivalue_line(
        "markers",
        "browser: drives Debian's chromium through chromium-driver (skipped when they are "
        "missing, unless HARP_ANALYSIS_REQUIRE_BROWSER=1)",
    )
