"""Fixtures shared by the test modules."""

import os

import pytest

from harp_analysis.foundation import paths

#: The dissertation's text, in ../shared beside the checkout (as CI's checkout has it).
DISSERTATION = paths.ROOT.parent / "shared" / "dissertation" / "000_5344a0ab06f4edea.txt"


@pytest.fixture(scope="session")
def dissertation_text() -> str:
    """The dissertation's full text. Where it is missing the tests that read it are skipped,
    unless HARP_ANALYSIS_REQUIRE_TEXT=1 (CI, .ci/run), which makes that a failure."""
    if DISSERTATION.exists():
        return DISSERTATION.read_text()
    reason = f"the dissertation's text is not beside the checkout ({DISSERTATION})"
    if os.environ.get("HARP_ANALYSIS_REQUIRE_TEXT") == "1":
        pytest.fail(f"{reason}, and HARP_ANALYSIS_REQUIRE_TEXT=1 forbids skipping")
    pytest.skip(reason)
