"""The figure lint: every saved figure is 6.5 in wide, and save_figure refuses a figure with
labels over one another or over a curve, data clipped silently or ink off the page
or markers cut by the axes' edge (plotting.figure_defects). Each defect is drawn here once, to
see the lint catch it; the
notebooks' own figures are linted as they are saved (every `make test` and `make figures`),
and the committed files' sizes are read back from figures/."""

import re

import numpy as np
import pytest
from PIL import Image

from harp_analysis.foundation import paths
from harp_analysis.reporting import plotting, registry

DRAWN = [e for e in registry.load_registry() if e.file.endswith(".png")]


@pytest.fixture
def figures_dir(tmp_path, monkeypatch):
    monkeypatch.setattr(paths, "FIGURES_DIR", tmp_path)
    return tmp_path


def _clean_figure():
    fig, ax = plotting.new_figure(figsize=(plotting.FULL_WIDTH_IN, 3.0), layout="constrained")
    x = np.linspace(0.0, 10.0, 50)
    ax.plot(x, np.sin(x), label="a curve", **plotting.style("3DOF"))
    ax.set_xlabel("range (km)")
    ax.set_ylabel("a long label for the altitude axis (km)")
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0))
    return fig, ax


def test_a_clean_figure_has_no_defect_and_is_saved_full_width(figures_dir):
    fig, _ = _clean_figure()
    assert plotting.figure_defects(fig) == []
    png = plotting.save_figure(fig, "2.1")
    with Image.open(png) as image:
        width, height = image.size
    assert width == round(plotting.FULL_WIDTH_IN * plotting.DPI)
    assert height == round(3.0 * plotting.DPI)
    assert _pdf_width_in(png.with_suffix(".pdf")) == pytest.approx(plotting.FULL_WIDTH_IN)


def _pdf_width_in(path) -> float:
    box = re.search(rb"/MediaBox \[\s*([\d.]+) ([\d.]+) ([\d.]+) ([\d.]+)", path.read_bytes())
    assert box, f"{path.name}: no MediaBox"
    return (float(box[3]) - float(box[1])) / 72.0


def test_a_figure_of_another_width_is_refused(figures_dir):
    fig, _ = _clean_figure()
    fig.set_size_inches(plotting.COLUMN_WIDTH_IN, 3.0)
    with pytest.raises(ValueError, match=r"figure 2.1 is not fit to print: .*3.4 in wide"):
        plotting.save_figure(fig, "2.1")
    assert not list(figures_dir.iterdir())


def test_a_note_that_pushes_past_the_page_is_caught():
    """The old way of Figs 3.1 and 4.1-4.4: a note under the axes, wider than the page."""
    fig, ax = _clean_figure()
    note = ax.annotate("a note " * 20, (0, 0), xycoords="axes fraction", xytext=(0, -36),
                       textcoords="offset points", va="top")  # fmt: skip
    note.set_in_layout(False)  # as under a tight bounding box, which the page no longer is
    assert any("runs off the page" in d for d in plotting.figure_defects(fig))


def test_a_y_label_taller_than_the_axes_is_caught():
    """The old way of Fig 4.7: a two-line y label longer than the axes are tall, centred on
    them, runs off the page: constrained layout makes room beside the axes, not along them."""
    fig, ax = _clean_figure()
    ax.set_ylabel("floating-point operations\n(simulations: per trajectory to impact; "
                  "MKS: per apogee)")  # fmt: skip
    (defect,) = plotting.figure_defects(fig)
    assert defect == (
        "axes 'floating-point operations (simulations: per trajectory to impact; MKS: per "
        "apogee)': y label 'floating-point operations (simulations: per trajectory to impact; "
        "MKS: per apogee)' runs off the page"
    )


def test_a_tick_label_and_a_title_off_the_page_are_caught():
    """Texts no label list holds: a tick label past the page's edge (a figure laid out by hand
    with no room for it) and a title pushed above the page."""
    fig, ax = plotting.new_figure(figsize=(plotting.FULL_WIDTH_IN, 3.0))
    fig.subplots_adjust(left=0.0, right=1.0, bottom=0.2, top=0.8)
    ax.set_xticks([0.5])
    ax.set_yticks([0.0, 0.5, 1.0], ["nought", "a half", "one"])
    ax.set_title("a title", pad=80)
    defects = plotting.figure_defects(fig)
    assert defects == [
        "axes 'a title': y tick label 'nought' runs off the page",
        "axes 'a title': y tick label 'a half' runs off the page",
        "axes 'a title': y tick label 'one' runs off the page",
        "axes 'a title': title 'a title' runs off the page",
    ]


def test_a_marker_on_the_axes_edge_is_caught():
    """The old way of Figs X.1 and X.2: the outer row and column of a grid of markers on the
    axes' limits, each cut in half; margins take them in."""
    fig, ax = plotting.new_figure(figsize=(plotting.FULL_WIDTH_IN, 3.0), layout="constrained")
    x, y = np.meshgrid(np.arange(4.0), np.arange(3.0))
    ax.plot(x.ravel(), y.ravel(), "s", markersize=6, label="grid")
    ax.set_xlim(0.0, 3.0)  # the first and last columns on the edges
    ax.set_ylim(-0.5, 2.5)
    assert plotting.figure_defects(fig) == [
        "axes 0: Line2D 'grid': 6 of its markers cut by the axes' edge, the first at (0, 0) "
        "(the axes need margins)"
    ]
    ax.set_xlim(-0.5, 3.5)
    assert plotting.figure_defects(fig) == []


def test_a_marker_of_a_curve_at_the_axes_corner_is_caught():
    """Markers every few points along a curve starting at the axes' origin: the first one cut;
    markevery's own subsampling decides which are drawn."""
    fig, ax = _clean_figure()
    x = np.linspace(0.0, 10.0, 101)
    ax.plot(x, 0.1 * x, marker="o", markevery=10, label="markers on a curve")
    ax.set_xlim(0.0, 11.0)
    ax.set_ylim(0.0, 1.2)
    (defect,) = [d for d in plotting.figure_defects(fig) if "markers" in d]
    assert defect.endswith("Line2D 'markers on a curve': 1 of its markers cut by the axes' edge, "
                           "the first at (0, 0) (the axes need margins)")  # fmt: skip
    ax.lines[-1].set_markevery((5, 10))  # from the sixth point on: none near an edge
    assert not [d for d in plotting.figure_defects(fig) if "markers" in d]


def test_a_curve_leaving_the_axes_keeps_its_markers_whole():
    """The old way of Fig 2.7's detail panel: a curve marked every few points leaves the axes
    with a marker on the edge; keep_markers_whole leaves that one out, and only that one."""
    fig, ax = _clean_figure()
    x = np.linspace(0.0, 10.0, 101)
    (line,) = ax.plot(x, 0.3 * x, marker="o", markevery=(10, 20), label="leaving")
    ax.set_ylim(-1.2, 2.7)  # the marker at x = 9 on the top edge
    (defect,) = plotting.figure_defects(fig)
    assert defect.endswith("Line2D 'leaving': 1 of its markers cut by the axes' edge, the first "
                           "at (9, 2.7) (the axes need margins)")  # fmt: skip
    plotting.keep_markers_whole(fig, [line])
    assert line.get_markevery() == [10, 30, 50, 70]
    assert plotting.figure_defects(fig) == []
    (points,) = ax.plot([1.0, 2.0], [0.0, 0.5], "o", label="points")
    with pytest.raises(ValueError, match="'points' is markers only"):
        plotting.keep_markers_whole(fig, [points])


def test_two_labels_over_one_another_are_caught():
    fig, ax = _clean_figure()
    ax.annotate("30 deg", (5.0, 0.0))
    ax.annotate("45 deg", (5.05, 0.02))
    assert plotting.figure_defects(fig) == ["axes 'a long label for the altitude axis (km)': "
                                            "'30 deg' overlaps '45 deg'"]  # fmt: skip


def test_two_panels_labels_over_one_another_are_caught():
    """As in a pair of panels laid out by hand, each x label wider than its panel (the figure
    tall enough for the labels to stay on the page, which matplotlib's default margins keep
    only from 4 in up)."""
    fig, (left, right) = plotting.new_figure(1, 2, figsize=(plotting.FULL_WIDTH_IN, 4.0))
    for ax in (left, right):
        ax.set_xlabel("distance from the nominal 3DOF flight (km)")
    (defect,) = plotting.figure_defects(fig)
    assert defect == ("'distance from the nominal 3DOF flight (km)' overlaps "
                      "'distance from the nominal 3DOF flight (km)'")  # fmt: skip


def test_a_label_over_a_curve_is_caught():
    """The old way of Fig 4.15: the off-scale note written across the curve it names."""
    fig, ax = _clean_figure()
    ax.annotate("off scale: max 6.8 km", (np.pi / 2, 1.0), ha="center", va="center")
    (defect,) = plotting.figure_defects(fig)
    assert "'off scale: max 6.8 km' sits over Line2D 'a curve'" in defect


def test_a_point_clipped_silently_is_caught():
    """The old way of Fig 4.9: one marker of a series beyond the y limit, not said."""
    fig, ax = _clean_figure()
    ax.plot([1.0, 2.0, 9.0], [0.2, 0.3, 1.5], "o", label="points")
    ax.set_ylim(-1.2, 1.2)
    assert plotting.figure_defects(fig)[-1].endswith(
        "Line2D 'points': 1 of its points outside the axes' limits"
    )
    ax.set_ylim(-1.2, 1.6)
    assert plotting.figure_defects(fig) == []


def test_a_curve_wholly_outside_the_axes_is_caught():
    fig, ax = _clean_figure()
    ax.plot([20.0, 30.0], [0.0, 0.5], label="elsewhere")
    ax.set_xlim(0.0, 10.0)
    assert plotting.figure_defects(fig)[-1].endswith(
        "Line2D 'elsewhere' lies wholly outside the axes' limits"
    )


@pytest.mark.parametrize("entry", DRAWN, ids=lambda e: e.number)
def test_every_committed_figure_is_full_width(entry):
    """figures/ as `make figures` wrote it: the PNG's pixels at 300 dpi and the PDF's page."""
    png = paths.COMMITTED_FIGURES_DIR / entry.file
    with Image.open(png) as image:
        width_px = image.size[0]
        dpi = image.info.get("dpi", (plotting.DPI,))[0]
    assert width_px == round(plotting.FULL_WIDTH_IN * plotting.DPI), (
        f"{entry.label}: {width_px / plotting.DPI:.3f} in wide at {plotting.DPI} dpi"
    )
    assert round(dpi) == plotting.DPI
    assert _pdf_width_in(png.with_suffix(".pdf")) == pytest.approx(plotting.FULL_WIDTH_IN)
