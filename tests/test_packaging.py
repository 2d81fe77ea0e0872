"""Every package the code imports is declared in pyproject.toml (issue 37, item 6): what the
package imports at module level among its dependencies, what it imports inside a function
(an optional part: the explorer, the cluster, the site) among its dependencies or an optional
group, and what the tests, benchmarks, server and site configuration import among either."""

import ast
import re
import sys
import tomllib
from importlib.metadata import packages_distributions
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def _normalised(requirement: str) -> str:
    """A requirement's distribution name as PEP 503 compares them."""
    name = re.match(r"[A-Za-z0-9._-]+", requirement).group(0)
    return re.sub(r"[-_.]+", "-", name).lower()


CORE = {_normalised(r) for r in PROJECT["dependencies"]}
ANY = CORE | {_normalised(r) for group in PROJECT["optional-dependencies"].values() for r in group}
DISTRIBUTIONS = packages_distributions()


def _imports(path: Path) -> list[tuple[str, bool]]:
    """The top-level names ``path`` imports, each with whether it is imported at module level
    (relative imports and the standard library left out)."""
    tree = ast.parse(path.read_text(), str(path))
    at_module_level = {id(node) for node in tree.body}
    for node in tree.body:  # an import under `if` or `try` at module level is still one
        if isinstance(node, ast.If | ast.Try):
            at_module_level |= {id(child) for child in ast.walk(node)}
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
            names = [node.module]
        else:
            continue
        for name in names:
            top = name.split(".")[0]
            if top not in sys.stdlib_module_names and top != "harp_analysis":
                found.append((top, id(node) in at_module_level))
    return found


def _declared(path: Path, top: str, declared: set[str]) -> str | None:
    """Why ``top``, imported by ``path``, is not declared among ``declared``, or None."""
    distributions = DISTRIBUTIONS.get(top)
    if distributions is None:  # a module beside the script that imports it
        if (path.parent / f"{top}.py").exists() or (path.parent / top).is_dir():
            return None
        return f"{path.relative_to(ROOT)} imports {top}, which no installed distribution provides"
    if any(_normalised(d) in declared for d in distributions):
        return None
    return f"{path.relative_to(ROOT)} imports {top} ({', '.join(distributions)}), not declared"


def test_the_package_declares_what_it_imports():
    problems = [
        _declared(path, top, CORE if module_level else ANY)
        for path in sorted((ROOT / "src" / "harp_analysis").rglob("*.py"))
        for top, module_level in _imports(path)
    ]
    assert [p for p in problems if p] == []


@pytest.mark.parametrize("folder", ["tests", "benchmarks", "serve", "docs"])
def test_the_tests_benchmarks_server_and_site_declare_what_they_import(folder):
    problems = [
        _declared(path, top, ANY)
        for path in sorted((ROOT / folder).rglob("*.py"))
        for top, _ in _imports(path)
    ]
    assert [p for p in problems if p] == []
