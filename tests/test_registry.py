"""The figure registry lists every figure and table, and figures/ holds exactly what it says."""

import json
import re

import pytest

from harp_analysis import gallery, paths, registry

ENTRIES = registry.load_registry()
REPOSITORY_FIGURES = paths.COMMITTED_FIGURES_DIR
DISSERTATION = paths.ROOT.parent / "shared" / "dissertation" / "000_5344a0ab06f4edea.txt"


def test_every_figure_and_table_is_registered():
    expected = {
        f"{chapter}.{n}"
        for chapter, count in ((1, 3), (2, 10), (3, 4), (4, 18), (5, 11), (6, 11))
        for n in range(1, count + 1)
    }
    expected.add("Table 4.1")
    assert {entry.number for entry in ENTRIES} == expected


@pytest.mark.skipif(not DISSERTATION.exists(), reason="shared/dissertation not beside the repo")
def test_registry_titles_are_the_captions():
    text = DISSERTATION.read_text()
    for entry in ENTRIES:
        if entry.kind == "figure":
            first_words = " ".join(entry.title.split()[:4])
            assert re.search(
                rf"^Figure {re.escape(entry.number)} {re.escape(first_words)}", text, re.M
            ), entry.number


@pytest.mark.parametrize(
    "entry",
    [e for e in ENTRIES if e.status in ("reproduced", "deviates", "partial")],
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
