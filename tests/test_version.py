"""One version (issue 28): pyproject.toml's, which the installed package reports as
``harp_analysis.__version__``, the documentation site shows (docs/conf.py reads it), and
CITATION.cff and the changelog's latest entry state."""

import re
import tomllib

import harp_analysis
from harp_analysis.foundation import paths


def _pyproject_version() -> str:
    with open(paths.ROOT / "pyproject.toml", "rb") as handle:
        return tomllib.load(handle)["project"]["version"]


def test_the_package_reports_pyproject_s_version():
    assert harp_analysis.__version__ == _pyproject_version()


def test_citation_cff_states_the_same_version():
    text = (paths.ROOT / "CITATION.cff").read_text()
    found = re.findall(r"^version:\s*['\"]?([^'\"\s]+)", text, re.M)
    assert found == [harp_analysis.__version__]


def test_the_changelog_s_latest_entry_is_this_version():
    text = (paths.ROOT / "CHANGELOG.md").read_text()
    entries = re.findall(r"^## \[([^\]]+)\]", text, re.M)
    assert entries and entries[0] == harp_analysis.__version__, entries[:3]


def test_the_site_reports_the_package_s_version():
    text = (paths.ROOT / "docs" / "conf.py").read_text()
    assert re.search(r"^version = release = harp_analysis\.__version__$", text, re.M)
