"""The documentation site's generator and checker (harp_analysis.reporting.site, issue 28),
without Sphinx: the pages it writes from the registry and the ledger (with made-up computed
values, so no trajectory is flown), the links they make, the check of a built site's links and
resources (harp_analysis.reporting.link_check), and the cache keys. `make docs` builds the real
site; `make check-docs` opens it in a browser (tests/browser/test_docs_site.py)."""

import ast
import importlib
import inspect
import json
import re
import typing

import pytest

import harp_analysis
from harp_analysis.foundation import paths
from harp_analysis.reporting import ledger, link_check, registry, site


def _rows() -> list[site.LedgerRow]:
    """Every ledger row as the site shows it, its computed value made up (the text's, or 1 for
    an extension result, which has none)."""
    rows = []
    for row in (*ledger.load_claims(), *ledger.load_measurements()):
        module, _, function = row.compute.partition(":")
        scored = isinstance(row, ledger.Claim)
        rows.append(
            site.LedgerRow(
                id=row.id,
                chapter=site.chapter_of(row.source),
                source=row.source,
                statement=row.statement,
                text=f"{row.text_value:g}" if scored else "",
                computed=f"{row.text_value:g}" if scored else "1",
                unit=row.unit,
                tolerance=f"{row.tolerance:g}" if scored else "",
                verdict=row.verdict if scored else site.EXTENSION_RESULT,
                explanation=row.explanation,
                figures=row.figures,
                module=module,
                function=function,
                kind="claim" if scored else "extension",
            )
        )
    return rows


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    target = tmp_path_factory.mktemp("source")
    chapters = {
        path.name: f"/chapters/{path.stem}" for path in paths.NOTEBOOKS_DIR.glob("0[1-9]_*.ipynb")
    }
    site.write_pages(target, _rows(), chapters, None)
    return target


@pytest.mark.parametrize(
    ("source", "chapter"),
    [
        ("Ch. 4 B, eq 4.8", "Chapter 4"),
        ("Ch. 3 (introduction)", "Chapter 3"),
        ("Table 4.1", "Chapter 4"),
        ("Appendix E", "Appendices"),
        ("Ch. 6 C-D", "Chapter 6"),
    ],
)
def test_a_row_s_chapter_is_the_one_its_source_cites(source, chapter):
    assert site.chapter_of(source) == chapter


def test_every_ledger_row_has_a_chapter():
    assert all(site.chapter_of(claim.source) != "Other" for claim in ledger.load_claims())


@pytest.mark.parametrize(
    "text", ["|r| - R, *starred*, `code`, [link](x), <tag>, $math$, a_b_c", "-", "1. first"]
)
def test_markdown_text_is_escaped_whole(text):
    escaped = site._md(text)
    assert re.sub(r"\\(.)", r"\1", escaped) == text  # every character kept
    assert not re.search(r"(?<!\\)[|*`\[\]<>$-]", escaped)  # no markup left unescaped
    assert not re.match(r"\d+[.)]", escaped)  # nor a list's number


def test_every_registry_entry_has_its_page_with_the_text_s_caption(pages):
    for entry in registry.load_registry():
        page = (pages / "gallery" / f"{site._slug(entry.number)}.md").read_text()
        assert site._md(entry.title) in page
        assert f"Status: {site._badge(entry.status)}" in page
        if entry.status in registry.DRAWN and entry.file.endswith(".png"):
            assert f"../figures/{entry.file}\n" in page and ":width: 100%" in page  # linked
            assert f"FIG={entry.number}" in page  # the command that regenerates it


def test_the_gallery_shows_a_thumbnail_of_each_drawn_figure_and_a_badge_of_each_status(pages):
    rows = (pages / "gallery" / "index.md").read_text().split("\n* - ")
    for entry in registry.load_registry():
        slug = site._slug(entry.number)
        (row,) = [row for row in rows if f"{{doc}}`{entry.label} <{slug}>`" in row]
        assert site._badge(entry.status) in row
        if entry.status in registry.DRAWN and entry.file.endswith(".png"):
            thumbnail = site._thumbnail_name(entry.file)
            assert f"[![{entry.label}](thumbnails/{thumbnail})]({slug}.md)" in row


def test_a_thumbnail_is_small_and_made_once(tmp_path):
    from PIL import Image

    figure = next(paths.COMMITTED_FIGURES_DIR.glob("*.png"))
    thumbnail = site._thumbnail(figure, tmp_path)
    with Image.open(thumbnail) as image:
        assert image.width == site.THUMBNAIL_WIDTH_PX
    assert thumbnail.stat().st_size < figure.stat().st_size / 5
    made = thumbnail.stat().st_mtime_ns
    assert site._thumbnail(figure, tmp_path) == thumbnail
    assert thumbnail.stat().st_mtime_ns == made and len(list(tmp_path.iterdir())) == 1


def test_a_figure_page_links_each_of_its_rows_and_the_function_computing_it(pages):
    for row in _rows():
        for number in row.figures:
            page = (pages / "gallery" / f"{site._slug(number)}.md").read_text()
            assert f"{{ref}}`{row.id} <claim-{row.id}>`" in page
            assert f"<{row.module}.{row.function}>`" in page


def test_the_ledger_page_has_a_target_per_row_and_its_filters_columns(pages):
    text = (pages / "ledger.md").read_text()
    rows = _rows()
    assert text.count("(claim-") == len(rows) == len({row.id for row in rows})
    assert f"{len([r for r in rows if r.kind == 'claim'])} rows: " in text
    assert ":class: ledger-table" in text
    for heading in ("chapter", "verdict", "computed by", "explanation"):
        assert f"  - {heading}\n" in text
    widths = [width for _, width in site.LEDGER_COLUMNS]
    assert f":widths: {' '.join(map(str, widths))}\n" in text and sum(widths) == 100


def test_extension_results_stand_apart_from_the_scored_rows(pages):
    """Issue 34: the project's own measurements are listed beneath the ledger, unscored."""
    text = (pages / "ledger.md").read_text()
    scored, extensions = text.split("## Extension results: measured, not scored")
    for measurement in ledger.load_measurements():
        assert f"(claim-{measurement.id})=" in extensions
        assert f"(claim-{measurement.id})=" not in scored
    assert ":class: extension-table" in extensions


def test_reasons_and_captions_quote_the_ledger_s_numbers(pages):
    """A registry reason may quote a ledger row (<<row|name:format>>); no page shows the
    quote itself."""
    quoted = [e for e in registry.load_registry() if "<<" in e.reason + e.caption]
    assert quoted, "no reason quotes the ledger"
    for e in quoted:
        page = (pages / "gallery" / f"{site._slug(e.number)}.md").read_text()
        assert "<<" not in page and ">>" not in page


def test_the_landing_summary_counts_every_figure(pages):
    summary = (pages / "_generated" / "summary.md").read_text()
    drawn = [e for e in registry.load_registry() if not e.extension]
    assert f"Of the dissertation's {len(drawn)} figures and tables" in summary


def test_the_curated_names_page_lists_each_public_name(pages):
    text = (pages / "api" / "curated.md").read_text()
    for name in harp_analysis.__all__:
        assert name in text


def test_the_provenance_page_is_the_data_s_readme_with_its_files(pages):
    text = (pages / "provenance" / "index.md").read_text()
    assert text.startswith((paths.ROOT / "data" / "harp" / "README.md").read_text()[:200])
    assert (pages / "provenance" / "data" / "appendix_d_barbados.tsv").is_file()
    assert "](radar.md)" in text


class _Usage(ast.NodeVisitor):
    """What a README example calls of the package, in the order it is written: each name it
    imports, and what each name it assigns holds (a class stands for its instances, and a call
    of a function for what the function is annotated to return), so that ``launch.but(...)``
    and ``solution.apogee_altitude()`` are found as Launch.but and
    ModifiedKeplerSolution.apogee_altitude."""

    def __init__(self) -> None:
        self.names: dict[str, object] = {}
        self.called: list[object] = []

    def visit_ImportFrom(self, node: ast.ImportFrom) -> None:
        for alias in node.names:
            module = importlib.import_module(node.module)
            value = getattr(module, alias.name, None)
            if value is None:
                value = importlib.import_module(f"{node.module}.{alias.name}")
            self.names[alias.asname or alias.name] = value

    def value(self, node: ast.expr) -> object:
        if isinstance(node, ast.Name):
            return self.names.get(node.id)
        if isinstance(node, ast.Attribute):
            return getattr(self.value(node.value), node.attr, None)
        if isinstance(node, ast.Call):
            called = self.value(node.func)
            if inspect.isclass(called):
                return called
            try:
                return typing.get_type_hints(inspect.unwrap(called)).get("return")
            except TypeError:  # not a function of the package
                return None
        return None

    def visit_Assign(self, node: ast.Assign) -> None:
        self.generic_visit(node)
        for target in node.targets:
            if isinstance(target, ast.Name):
                self.names[target.id] = self.value(node.value)

    def visit_Call(self, node: ast.Call) -> None:
        self.generic_visit(node)
        self.called.append(self.value(node.func))


def _entry_points() -> dict[str, object]:
    """The package's public entry points: the functions and classes of ``harp_analysis.__all__``
    and every function, method and class README's "Using the package" calls, by full name."""
    readme = (paths.ROOT / "README.md").read_text()
    section = readme.split("\n## Using the package\n")[1].split("\n## ")[0]
    usage = _Usage()
    for block in re.findall(r"```python\n(.*?)```", section, re.S):
        usage.visit(ast.parse(block))
    curated = [getattr(harp_analysis, name) for name in harp_analysis.__all__[1:]]
    found = {}
    for value in [*curated, *usage.called]:
        value = inspect.unwrap(getattr(value, "__func__", value))
        if not (inspect.isfunction(value) or inspect.isclass(value)):
            continue  # a constant of the curated names (HP), or a call of another package
        warning = inspect.isclass(value) and issubclass(value, Warning)
        if value.__module__.startswith("harp_analysis") and not warning:
            found[f"{value.__module__}.{value.__qualname__}"] = value
    return found


ENTRY_POINTS = _entry_points()


@pytest.mark.parametrize(("name", "entry"), ENTRY_POINTS.items(), ids=list(ENTRY_POINTS))
def test_each_public_entry_point_documents_its_parameters_and_returns(name, entry):
    """Every parameter under Parameters (numpy style, names grouped "a, b : float" or not), and
    Returns unless it returns nothing; a class documents its constructor's parameters."""
    doc = inspect.getdoc(entry) or ""
    signature = inspect.signature(entry)
    parameters = [p for p in signature.parameters.values() if p.name not in ("self", "cls")]
    if parameters:
        assert "Parameters\n----------" in doc, name
    returns = signature.return_annotation not in ("None", None)
    if inspect.isfunction(entry) and returns:
        assert "Returns\n-------" in doc, name
    documented = re.findall(r"^(\**\w+(?:, \**\w+)*)(?: :|$)", doc, re.M)
    listed = {word for line in documented for word in line.split(", ")}
    for parameter in parameters:
        shown = f"**{parameter.name}" if parameter.kind is parameter.VAR_KEYWORD else parameter.name
        assert shown in listed, (name, parameter.name)


# --- the check of a built site ----------------------------------------------------------------


def _write(root, name, text):
    path = root / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


def test_a_sound_site_passes(tmp_path):
    _write(tmp_path, "index.html", '<a href="page.html#here">x</a><img src="img/a.png">')
    page = '<p id="here"></p><a href="index.html">back</a><a href="https://example.org/">out</a>'
    _write(tmp_path, "page.html", page + '<link rel="stylesheet" href="s.css">')
    _write(tmp_path, "img/a.png", "png")
    _write(tmp_path, "s.css", "body { background: url('img/a.png'); }")
    assert link_check.check_site(tmp_path) == []


def test_broken_links_missing_images_and_outside_resources_are_reported(tmp_path):
    _write(tmp_path, "index.html", '<a href="gone.html">a</a><a href="page.html#nowhere">b</a>'
           '<img src="missing.png"><script src="https://cdn.example/x.js"></script>'
           '<link rel="stylesheet" href="s.css">')  # fmt: skip
    _write(tmp_path, "page.html", "<p id='here'></p>")
    _write(tmp_path, "s.css", "@import 'https://fonts.example/f.css'; a { b: url(none.woff2) }")
    problems = "\n".join(link_check.check_site(tmp_path))
    for expected in (
        "'gone.html' reaches no file",
        "no element id='nowhere'",
        "'missing.png' is missing",
        "loads 'https://cdn.example/x.js' from outside",
        "loads 'https://fonts.example/f.css' from outside",
        "'none.woff2' is missing",
    ):
        assert expected in problems


def test_an_anchor_s_name_a_srcset_s_candidates_and_the_theme_s_static_templates(tmp_path):
    """An anchor's name is a link's target; each candidate of a srcset must be there; the
    theme's templates Sphinx copies into _static are no pages, never checked."""
    _write(tmp_path, "index.html", '<a name="top"></a><a href="#top">up</a>'
           '<img srcset="a.png 1x, b.png 2x">')  # fmt: skip
    _write(tmp_path, "a.png", "png")
    _write(tmp_path, "_static/macros.html", '<a href="nowhere.html">x</a>')
    assert link_check.check_site(tmp_path) == ["index.html: <img> 'b.png' is missing"]


def test_the_check_command_fails_on_a_problem(tmp_path, capsys):
    _write(tmp_path, "index.html", '<a href="gone.html">a</a>')
    assert site.main(["check", str(tmp_path)]) == 1
    assert capsys.readouterr().out.endswith("1 pages checked: 1 problems\n")
    _write(tmp_path, "gone.html", "<p></p>")
    assert site.main(["check", str(tmp_path)]) == 0


def test_the_page_templates_are_never_pages_of_the_site():
    """The generated pages' templates live in docs/_templates, which the assembled source tree
    Sphinx reads leaves out."""
    assert sorted((paths.ROOT / site.TEMPLATES).glob("*.md.j2"))
    assert site.TEMPLATES.parts[:2] == ("docs", "_templates")
    assert "_templates" in site._CONFIGURATION


def test_the_cache_key_follows_the_files_it_depends_on(tmp_path):
    notebook = tmp_path / "n.ipynb"
    notebook.write_text("{}")
    before = site.digest(notebook)
    assert site.digest(notebook) == before
    notebook.write_text('{"cells": []}')
    assert site.digest(notebook) != before


def test_a_cached_value_is_computed_once_per_key(tmp_path):
    calls = []

    def compute():
        calls.append(1)
        return {"value": len(calls)}

    assert site._cached_json(tmp_path, "thing", "a", compute) == {"value": 1}
    assert site._cached_json(tmp_path, "thing", "a", compute) == {"value": 1}
    assert site._cached_json(tmp_path, "thing", "b", compute) == {"value": 2}
    assert [p.name for p in tmp_path.glob("thing-*.json")] == ["thing-b.json"]  # stale gone
    assert json.loads((tmp_path / "thing-b.json").read_text()) == {"value": 2}
