"""The package's architecture, beyond what import-linter's contracts in pyproject.toml check
(the layers as folders, the independent engines and wings, matplotlib only in reporting):
every module in a layer's folder, no import circle inside a layer, no module reading another's
private names, and each module saying what it offers in ``__all__``."""

import ast
from pathlib import Path

import grimp
import pytest

import harp_analysis

PACKAGE = Path(harp_analysis.__file__).parent
LAYERS = ("foundation", "models", "engines", "analyses", "reporting")
MODULES = sorted(p for p in PACKAGE.rglob("*.py") if p.name != "__init__.py")


def _name(path: Path) -> str:
    return ".".join(("harp_analysis", *path.relative_to(PACKAGE).with_suffix("").parts))


def test_every_module_lives_in_a_layer_s_folder():
    assert {p.relative_to(PACKAGE).parts[0] for p in MODULES} == set(LAYERS)
    for folder in {p.parent for p in MODULES}:
        init = folder / "__init__.py"
        assert init.is_file() and ast.get_docstring(ast.parse(init.read_text())), (
            f"{folder.relative_to(PACKAGE)} needs an __init__.py saying what it holds"
        )


def _package_modules_bound(tree: ast.Module, module: str) -> set[str]:
    """The local names under which ``module``'s file binds other modules of the package
    (``from ..engines import mks``, ``from . import firing as f``)."""
    bound = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (
            node.level or (node.module or "").startswith("harp_analysis")
        ):
            base = node.module or ""
            if node.level:
                parts = module.split(".")[: -node.level]
                base = ".".join([*parts, base] if base else parts)
            for alias in node.names:
                try:
                    __import__(f"{base}.{alias.name}")
                except ImportError:
                    continue  # a function or constant, not a module
                bound.add(alias.asname or alias.name)
    return bound


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PACKAGE)))
def test_no_module_reads_another_module_s_private_names(path):
    """A name with a leading underscore is its module's own: another module that needs it
    needs a public name for it (the engines' compiled building blocks are public so)."""
    tree = ast.parse(path.read_text())
    modules = _package_modules_bound(tree, _name(path))
    private = sorted(
        f"{node.value.id}.{node.attr} (line {node.lineno})"
        for node in ast.walk(tree)
        if isinstance(node, ast.Attribute)
        and isinstance(node.value, ast.Name)
        and node.value.id in modules
        and node.attr.startswith("_")
        and not node.attr.startswith("__")
    )
    assert not private, f"{path.relative_to(PACKAGE)} reads {private}"


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PACKAGE)))
def test_every_module_lists_what_it_offers(path):
    targets = [
        target
        for node in ast.parse(path.read_text()).body
        if isinstance(node, ast.Assign | ast.AnnAssign)
        for target in (node.targets if isinstance(node, ast.Assign) else [node.target])
    ]
    assert any(getattr(target, "id", None) == "__all__" for target in targets), (
        f"{path.relative_to(PACKAGE)} has no __all__"
    )


def test_the_import_graph_has_no_circle():
    """import-linter forbids arrows up the layers; within a layer a circle would still tie
    modules together that should stand apart."""
    graph = grimp.build_graph("harp_analysis")
    modules = sorted(m for m in graph.modules if m.startswith("harp_analysis."))
    imports = {m: graph.find_modules_directly_imported_by(m) & set(modules) for m in modules}
    circles = []
    for module in modules:
        reached, frontier = set(), set(imports[module])
        while frontier:
            reached |= frontier
            frontier = {n for m in frontier for n in imports[m]} - reached
        if module in reached:
            circles.append(module)
    assert not circles, f"in an import circle: {circles}"


def test_fire_control_s_method_imports_none_of_its_studies():
    """analyses.fire_control.studies holds studies of the method (its costs, first guesses,
    models compared), which build on it: the method runs without them."""
    graph = grimp.build_graph("harp_analysis")
    package = "harp_analysis.analyses.fire_control"
    studies = {f"{package}.studies", *graph.find_descendants(f"{package}.studies")}
    method = {package, *graph.find_descendants(package)} - studies
    reading = sorted(m for m in method if graph.find_modules_directly_imported_by(m) & studies)
    assert not reading, f"modules of the method importing a study: {reading}"
