"""The figure registry lists every figure and table, and figures/ holds exactly what it says."""

import json
import re

import pytest

from harp_analysis.foundation import paths
from harp_analysis.reporting import gallery, registry

ENTRIES = registry.load_registry()
EXTENSIONS = [entry for entry in ENTRIES if entry.extension]
REPOSITORY_FIGURES = paths.COMMITTED_FIGURES_DIR


def test_every_figure_and_table_is_registered():
    expected = {
        f"{chapter}.{n}"
        for chapter, count in ((1, 3), (2, 10), (3, 4), (4, 18), (5, 11), (6, 11))
        for n in range(1, count + 1)
    }
    expected.add("Table 4.1")
    assert {entry.number for entry in ENTRIES if not entry.extension} == expected


def test_registry_titles_are_the_captions(dissertation_text):
    text = dissertation_text
    for entry in ENTRIES:
        if entry.kind == "figure" and not entry.extension:
            first_words = " ".join(entry.title.split()[:4])
            assert re.search(
                rf"^Figure {re.escape(entry.number)} {re.escape(first_words)}", text, re.M
            ), entry.number


@pytest.mark.parametrize(
    "entry",
    [e for e in ENTRIES if e.status in registry.DRAWN],
    ids=lambda e: e.number,
)
def test_reproduced_figures_have_their_file_and_notebook(entry):
    assert (REPOSITORY_FIGURES / entry.file).is_file(), f"{entry.label}: no figures/{entry.file}"
    notebook = paths.NOTEBOOKS_DIR / entry.notebook
    assert notebook.is_file(), f"{entry.label}: no notebooks/{entry.notebook}"
    # The notebook names this figure (it saves it through save_figure or save_table).
    code = "".join(
        "".join(cell["source"])
        for cell in json.loads(notebook.read_text())["cells"]
        if cell["cell_type"] == "code"
    )
    assert f'"{entry.number}"' in code and ("save_figure" in code or "save_table" in code)


def test_every_file_in_figures_is_registered():
    registered = {entry.file for entry in ENTRIES if entry.file} | set(registry.INDEX_FILES)
    registered |= {f[:-4] + ".pdf" for f in registered if f.endswith(".png")}
    stray = sorted(p.name for p in REPOSITORY_FIGURES.iterdir() if p.name not in registered)
    assert not stray, f"files in figures/ that the registry does not list: {stray}"


def test_malformed_registry_entry_is_named(tmp_path):
    path = tmp_path / "figures.toml"
    path.write_text(
        '[[item]]\nnumber = "9.9"\nkind = "figure"\ntitle = "t"\nclass = "data"\n'
        'notebook = ""\nfile = ""\nstatus = "pending"\nreason = ""\n'
    )
    with pytest.raises(ValueError, match=r"entry 1 \(9.9\).*needs a reason"):
        registry.load_registry(path)


def test_unknown_figure_number_is_named():
    with pytest.raises(ValueError, match="'7.7'"):
        registry.figure_file("7.7")


def test_gallery_lists_every_entry(tmp_path):
    text = gallery.render_gallery(tmp_path / "README.md").read_text()
    for entry in ENTRIES:
        assert f"| {entry.label} |" in text


@pytest.mark.parametrize(
    "notebook", sorted(paths.NOTEBOOKS_DIR.glob("*.ipynb")), ids=lambda p: p.name
)
def test_notebooks_are_committed_without_outputs(notebook):
    cells = json.loads(notebook.read_text())["cells"]
    assert not any(
        c.get("outputs") or c.get("execution_count") for c in cells if c["cell_type"] == "code"
    )


def test_statuses_agree_with_the_ledger():
    """ "reproduced" only when every ledger row about the figure reproduces; "deviates" only
    when one does not."""
    assert gallery.status_problems() == []


def _figure(no_number=""):
    return registry.RegistryEntry(
        "9.9", "figure", "t", "data", "n.ipynb", "f.png", "reproduced", "", no_number=no_number
    )


@pytest.mark.parametrize(
    "no_number, rows, problem",
    [
        ("", [], "no ledger row speaks about it"),
        ("the text states no number about it", [], None),
        ("the text states no number about it", ["a row"], "no_number is stale"),
    ],
)
def test_a_reproduced_figure_without_rows_says_the_text_states_no_number(
    monkeypatch, no_number, rows, problem
):
    """A figure is "reproduced" without any row only where the registry says why: the text
    states no number about it. A row about it makes that stale."""

    class Reproduces:  # a ledger result that reproduces
        class claim:
            verdict = "reproduces"
            exempt: dict = {}

    monkeypatch.setattr(gallery, "load_registry", lambda: (_figure(no_number),))
    monkeypatch.setattr(gallery, "claims_by_figure", lambda: {"9.9": [Reproduces] * len(rows)})
    problems = gallery.status_problems()
    assert (problems == []) if problem is None else any(problem in p for p in problems)


# --- the project's own figures, beyond the dissertation -------------------------------------------
def test_extensions_are_numbered_outside_the_dissertation():
    assert EXTENSIONS, "the registry lists no extension"
    for position, entry in enumerate(EXTENSIONS, start=1):
        assert entry.number == f"X.{position}" and entry.label == f"Figure X.{position}"
        assert entry.status == "extension" and entry.caption and entry.reason
        assert registry.figure_file(entry.number).name == f"fig_x_{position}.png"
    # the dissertation's figures come first, the extensions after them
    flags = [entry.extension for entry in ENTRIES]
    assert flags == sorted(flags)


def test_gallery_lists_extensions_in_their_own_section(tmp_path):
    text = gallery.render_gallery(tmp_path / "README.md").read_text()
    dissertation, beyond = text.split("# Beyond the dissertation")
    for entry in EXTENSIONS:
        assert f"| {entry.label} |" not in dissertation
        assert f"| {entry.label} | {entry.title} | data | drawn, extension |" in beyond
        assert f"## {entry.label}: {entry.title}" in beyond and f"*{entry.caption}*" in beyond
    assert "extension" not in dissertation.split("|")[0]  # not among the dissertation's counts


_EXTENSION = (
    '[[item]]\nnumber = "{number}"\nkind = "figure"\ntitle = "t"\nclass = "data"\n'
    'notebook = "07_fire_control.ipynb"\nfile = "{file}"\nstatus = "{status}"\n'
    'reason = "held by tests"\n{extra}'
)


@pytest.mark.parametrize(
    "number, file, status, extra, message",
    [
        ("X.1", "fig_x_1.png", "reproduced", "extension = true\ncaption = 'c'\n",
         "nothing in the dissertation to reproduce"),
        ("7.1", "fig_7_1.png", "extension", "extension = true\ncaption = 'c'\n",
         "numbered X.1"),
        ("X.1", "fig_7_1.png", "extension", "extension = true\ncaption = 'c'\n",
         "file is 'fig_x_1.png'"),
        ("X.1", "fig_x_1.png", "extension", "extension = true\n", "needs its caption"),
        ("X.1", "fig_x_1.png", "extension", "caption = 'c'\n", "extension = true entries only"),
        ("X.1", "fig_x_1.png", "extension", "extension = 'yes'\ncaption = 'c'\n",
         "true or false"),
    ],
)  # fmt: skip
def test_malformed_extension_is_named(tmp_path, number, file, status, extra, message):
    path = tmp_path / "figures.toml"
    path.write_text(_EXTENSION.format(number=number, file=file, status=status, extra=extra))
    with pytest.raises(ValueError, match=message):
        registry.load_registry(path)


def test_a_wellformed_extension_loads(tmp_path):
    path = tmp_path / "figures.toml"
    path.write_text(
        _EXTENSION.format(
            number="X.3",
            file="fig_x_3.png",
            status="extension",
            extra="extension = true\ncaption = 'c'\n",
        )
    )
    (entry,) = registry.load_registry(path)
    assert entry.extension and entry.status == "extension" and entry.label == "Figure X.3"
