"""README.md as a newcomer meets it (issue 34): its headline is the registry's and the ledger's
counts as they stand, and its first example prints what the README says it prints."""

import re
import subprocess
import sys

from harp_analysis.foundation import paths
from harp_analysis.reporting import gallery

README = paths.ROOT / "README.md"


def test_the_headline_is_generated_from_the_registry_and_the_ledger():
    start, end = gallery.README_MARKERS
    text = README.read_text()
    assert text.index(start) < text.index("## Two commands"), "the headline comes first"
    written = text.split(start, 1)[1].split(end, 1)[0].strip()
    assert written == gallery.readme_headline(), "run `make figures` to rewrite it"


def _first_example() -> tuple[str, str]:
    section = README.read_text().split("## A first example", 1)[1].split("\n## ", 1)[0]
    code, printed = re.findall(r"```(?:python|text)\n(.*?)```", section, re.S)[:2]
    return code, printed


def test_the_first_example_prints_what_the_readme_says():
    code, printed = _first_example()
    run = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=600, check=True
    )
    assert run.stdout == printed
    assert "HighDragWarning: MKS beta = 0.275 > 0.25" in run.stderr  # the warning it names
