"""Notebooks are driven from one parameters cell, and every engine flies the launch built there.

nbmake executes every notebook as committed (``make test``); here notebook 04 runs with changed
parameters, and a last cell checks that the 3DOF, 6DOF, MLT and MKS all flew the changed launch
and that the headings name it. No notebook silences the models' validity warnings, draws,
defines a function of its own, or shows the path it saved a figure to.
"""

import ast
import os
import re
import warnings
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

from harp_analysis.foundation import paths
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models.trajectory import TruncatedFlightWarning
from harp_analysis.reporting import build, notebook

NOTEBOOKS = sorted(paths.NOTEBOOKS_DIR.glob("*.ipynb"))
CHANGED = """projectile = "LP"
elevation_deg = 60.0
speed_m_s = 2100.0
cross_wind_m_s = -3.0
baseline_elevations_deg = (45.0,)
"""
CHECK = """
import numpy as np
from harp_analysis.models.projectiles import LP

assert launch.projectile == LP and launch.elevation_deg == 60.0
assert launch.speed_m_s == 2100.0 and launch.cross_wind_m_s == -3.0
for table in (flight3, flight6, flight_mlt, mks_table):
    assert table.attrs["launch"] == launch, table.attrs["engine"]
assert {t.attrs["engine"] for t in (flight3, flight6, flight_mlt, mks_table)} == {
    "3DOF", "6DOF", "MLT", "MKS"}
assert np.isclose(hp_mks.speed_m_s.item(), 2100.0) and np.isclose(
    np.degrees(hp_mks.elevation_rad.item()), 60.0)
assert abs(flight3.attrs["cross_range_m"]) > 1.0  # the changed wind blew the 3DOF aside
"""


def _parameter_cells(notebook):
    return [c for c in notebook.cells if "parameters" in c.metadata.get("tags", [])]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_each_notebook_opens_with_one_parameters_cell(path):
    notebook = nbformat.read(path, as_version=4)
    cells = _parameter_cells(notebook)
    code = [c for c in notebook.cells if c.cell_type == "code"]
    assert len(cells) == 1 and code[0] is cells[0]


def test_notebook_04_flies_every_engine_on_the_changed_launch(tmp_path):
    notebook = nbformat.read(paths.NOTEBOOKS_DIR / "04_mks_vs_simulation.ipynb", as_version=4)
    _parameter_cells(notebook)[0].source = CHANGED
    # run through Fig 4.6, the figures every engine draws, then check what they flew
    last = next(i for i, c in enumerate(notebook.cells) if 'save_figure(fig, "4.6")' in c.source)
    notebook.cells = [*notebook.cells[: last + 1], nbformat.v4.new_code_cell(CHECK)]
    client = NotebookClient(
        notebook,
        timeout=600,
        kernel_name="python3",
        resources={"metadata": {"path": str(paths.NOTEBOOKS_DIR)}},
    )
    client.execute(env={**os.environ, "HARP_ANALYSIS_FIGURES_DIR": str(tmp_path)})
    assert (tmp_path / "fig_4_1.png").is_file()
    shown = [
        output.data["text/markdown"]
        for cell in notebook.cells
        for output in cell.get("outputs", [])
        if "text/markdown" in output.get("data", {})
    ]
    headings = [line for text in shown for line in text.splitlines() if line.startswith("## ")]
    assert headings == [
        "## Figures 4.1 to 4.4: LP at 60 deg",
        "## Figure 4.5: the geometry of the total position error, drawn from LP at apogee",
        "## Figure 4.6: total position error of LP against the 3DOF, 1 to 5 series terms",
    ]
    assert any("in the -3 m/s cross wind" in text for text in shown)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_no_notebook_silences_warnings(path):
    """A model used outside its validity warns, and the reader sees it (issue 25)."""
    silencing = re.compile(r"(simplefilter|filterwarnings)\(\s*[\"']ignore")
    for cell in nbformat.read(path, as_version=4).cells:
        assert cell.cell_type != "code" or not silencing.search(cell.source), cell.source


@pytest.mark.parametrize("path", [p for p in NOTEBOOKS if p.name != "00_explorer.ipynb"], ids=str)
def test_each_chapter_shows_validity_warnings_as_sentences(path):
    calls = [
        cell
        for cell in nbformat.read(path, as_version=4).cells
        if cell.cell_type == "code" and re.search(r"^show_validity_warnings\(\)", cell.source, re.M)
    ]
    assert len(calls) == 1


def test_a_validity_warning_is_shown_once_as_a_sentence(capsys):
    """Without a path or a line of code, however often it is given and whatever filters the
    engines change in between; other warnings as Python shows them."""

    def warn(message, category=ModelValidityWarning):
        warnings.warn(message, category, stacklevel=2)

    with warnings.catch_warnings(record=True) as others:
        notebook.show_validity_warnings()
        for _ in range(2):
            warn("MKS beta = 0.3 > 0.25: the text finds\n it inaccurate")
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ModelValidityWarning)
                warn("kept quiet by an engine")
        warn("the 3DOF flight did not return to the ground.", TruncatedFlightWarning)
        notebook.show_validity_warnings()  # again: the same display, the count afresh
        warn("the MKS ignores the wind")
        warn("the MKS ignores the wind")
        warn("something else", UserWarning)
    assert capsys.readouterr().err.splitlines() == [
        "Model validity: MKS beta = 0.3 > 0.25: the text finds it inaccurate.",
        "Model validity: the 3DOF flight did not return to the ground.",
        "Model validity: the MKS ignores the wind.",
    ]
    assert [str(w.message) for w in others] == ["something else"]


#: What drawing looks like in a cell: matplotlib itself, or an axes' or the house style's calls.
DRAWING = re.compile(
    r"\bmatplotlib\b|\bplt\.|\bnew_figure\(|"
    r"\.(plot|semilogy|loglog|bar|fill|axhline|axvline|annotate|set_[xy]label|set_[xy]lim|legend)\("
)
#: A function, class or named lambda of the notebook's own.
DEFINING = re.compile(r"^\s*(def|class)\s|^\w+\s*=\s*lambda\b", re.MULTILINE)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_no_notebook_draws_or_defines_functions(path):
    """Physics and drawing live in the package: a notebook calls a figure function of
    harp_analysis.reporting.figures and saves what it returns, and defines no helper of its own
    (issue 27)."""
    for cell in nbformat.read(path, as_version=4).cells:
        if cell.cell_type == "code":
            assert not DRAWING.search(cell.source), cell.source
            assert not DEFINING.search(cell.source), cell.source


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_no_cell_shows_the_path_it_saved_to(path):
    """A cell that ends by saving a figure or a table ends with ";": its page shows the figure,
    not the returned path of the file on the machine that ran it."""
    for cell in nbformat.read(path, as_version=4).cells:
        if cell.cell_type != "code" or not cell.source.strip():
            continue
        last = ast.parse(cell.source).body[-1]
        saving = (
            isinstance(last, ast.Expr)
            and isinstance(last.value, ast.Call)
            and getattr(last.value.func, "id", None) in ("save_figure", "save_table")
        )
        assert not saving or cell.source.rstrip().endswith(";"), cell.source


def test_figures_go_to_a_scratch_folder_unless_asked(monkeypatch):
    monkeypatch.delenv("HARP_ANALYSIS_FIGURES_DIR", raising=False)
    assert paths.FIGURES_DIR != paths.COMMITTED_FIGURES_DIR
    monkeypatch.setenv("HARP_ANALYSIS_FIGURES_DIR", str(paths.COMMITTED_FIGURES_DIR))
    assert paths.FIGURES_DIR == paths.COMMITTED_FIGURES_DIR


def test_a_relative_figures_folder_is_the_caller_s_not_the_notebook_s(tmp_path, monkeypatch):
    """`make docs` names its scratch folder relative to the checkout, while the kernel runs from
    the notebook's folder: the figures go to the folder named, never to one under notebooks/."""
    folder = tmp_path / "notebooks"
    folder.mkdir()
    saving = "from harp_analysis.foundation import paths\n(paths.FIGURES_DIR / 'saved').touch()"
    notebook = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(saving)])
    nbformat.write(notebook, folder / "n.ipynb")
    (tmp_path / "scratch").mkdir()
    monkeypatch.chdir(tmp_path)
    build.execute_notebook(folder / "n.ipynb", Path("scratch"))
    assert (tmp_path / "scratch" / "saved").is_file()
    assert not (folder / "scratch").exists()
